/* table.c: CURET's configuration table (table.txt), rows
 * "index theta_v phi_v theta_i phi_i" in the sample's frame (SPEC §1.3).
 *
 * [1] K. J. Dana et al., ACM TOG 18(1), 1999 (CURET); layout in
 *     shared/data/curet/SOURCES.md.
 *
 * Checks: exactly 5 numbers per row; indices run 1..N in order; angles are
 * finite decimal numbers; zeniths lie in [0, pi/2] and azimuths in
 * [-2 pi, 2 pi], each up to BF__ANGLE_TOL. A zenith within the tolerance
 * outside [0, pi/2] is clamped onto it, so a pi/2 printed with rounding
 * (1.5707963268 > pi/2) still passes bf_model_eval's closed-hemisphere check. */
#include "data/curet.h"
#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

/* Number of numbers per row: index and four angles. */
#define NCOL 5

struct bf_table {
    size_t n;    /* number of configurations */
    double *raw; /* n rows of theta_v, phi_v, theta_i, phi_i */
};

static const char *const col_name[NCOL] = {"index", "theta_v", "phi_v",
                                           "theta_i", "phi_i"};

/* Grows t->raw to hold at least need rows. */
static int reserve(bf_table *t, size_t *cap, size_t need)
{
    double *raw;
    size_t c;
    if (need <= *cap) {
        return BF_OK;
    }
    c = (*cap == 0) ? 256 : 2 * (*cap);
    raw = realloc(t->raw, c * 4 * sizeof *raw);
    if (raw == NULL) {
        return BF_ENOMEM;
    }
    t->raw = raw;
    *cap = c;
    return BF_OK;
}

/* Checks angle a of column c (1..4) and clamps zeniths within tolerance
 * (bf__angle_ok). */
static int check_angle(const bf__lines *r, size_t c, double *a, bf_error *err)
{
    int zenith = (c == 1) || (c == 3);
    if (!bf__angle_ok(a, zenith)) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "field %zu (%s) = %g outside [%s]", c + 1,
                             col_name[c], *a,
                             zenith ? "0, pi/2" : "-2 pi, 2 pi");
    }
    return BF_OK;
}

int bf_table_read(FILE *fp, const char *name, bf_table **out, bf_error *err)
{
    bf__lines r;
    bf_table *t = NULL;
    size_t cap = 0;
    int have = 0;
    int rc;

    bf__error_clear(err, name);
    bf__lines_init(&r, fp);
    if (out != NULL) {
        *out = NULL;
    }
    if (out == NULL || fp == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    t = calloc(1, sizeof *t);
    if (t == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    for (;;) {
        long index = 0;
        double *row;
        size_t c;
        rc = bf__lines_next(&r, &have, err);
        if (rc != BF_OK || !have) {
            break;
        }
        rc = bf__lines_split_ws(&r, err);
        if (rc != BF_OK) {
            goto done;
        }
        if (r.nfield != NCOL) {
            rc = bf__error_set(err, BF_EPARSE, r.line,
                               "expected %d numbers, found %zu", NCOL,
                               r.nfield);
            goto done;
        }
        rc = bf__field_long(&r, 0, col_name[0], 1, LONG_MAX, &index, err);
        if (rc != BF_OK) {
            goto done;
        }
        if ((size_t)index != t->n + 1) {
            rc = bf__error_set(err, BF_EPARSE, r.line,
                               "index %ld out of order: expected %zu "
                               "(indices must run 1, 2, 3, ...)",
                               index, t->n + 1);
            goto done;
        }
        if (reserve(t, &cap, t->n + 1) != BF_OK) {
            rc = bf__error_set(err, BF_ENOMEM, r.line, "out of memory");
            goto done;
        }
        row = t->raw + 4 * t->n;
        for (c = 1; c < NCOL; c++) {
            rc = bf__field_double(&r, c, col_name[c], &row[c - 1], err);
            if (rc != BF_OK) {
                goto done;
            }
            rc = check_angle(&r, c, &row[c - 1], err);
            if (rc != BF_OK) {
                goto done;
            }
        }
        t->n++;
    }
    if (rc != BF_OK) {
        goto done;
    }
    if (t->n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0, "empty file");
        goto done;
    }
    *out = t;
    t = NULL;
done:
    bf__lines_free(&r);
    bf_table_free(t);
    return rc;
}

int bf_table_load(const char *path, bf_table **out, bf_error *err)
{
    FILE *fp = NULL;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_table_read(fp, path, out, err);
    fclose(fp);
    return rc;
}

void bf_table_free(bf_table *t)
{
    if (t == NULL) {
        return;
    }
    free(t->raw);
    free(t);
}

size_t bf_table_size(const bf_table *t)
{
    return t == NULL ? 0 : t->n;
}

bf_geom bf_table_geom(const bf_table *t, size_t k)
{
    const double *row;
    if ((t == NULL) || (k >= t->n)) {
        bf_geom bad = {NAN, NAN, NAN, NAN};
        return bad;
    }
    row = t->raw + 4 * k;
    return bf_geom_from_curet(row[0], row[1], row[2], row[3]);
}

void bf_table_raw(const bf_table *t, size_t k, double raw[4])
{
    size_t c;
    for (c = 0; c < 4; c++) {
        raw[c] = ((t == NULL) || (k >= t->n)) ? NAN : t->raw[4 * k + c];
    }
}

size_t bf_table_select(const bf_table *t, double max_theta, size_t *sel)
{
    size_t n = 0;
    size_t k;
    if ((t == NULL) || (sel == NULL)) {
        return 0;
    }
    for (k = 0; k < t->n; k++) {
        const double *row = t->raw + 4 * k;
        bf_geom g = bf_table_geom(t, k);
        if (bf_geom_is_specular(&g)) {
            continue;
        }
        if ((row[0] <= max_theta) && (row[2] <= max_theta)) {
            sel[n++] = k;
        }
    }
    return n;
}
