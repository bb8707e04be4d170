/* sample_table.c: per-sample tables of numbers, rows "sample x1 ... xk" --
 * the Oren-Nayar parameter file (SPEC §5) and the refractive index file
 * (SPEC §4.2).
 *
 * Fields are separated by spaces and/or tabs. The first line is a header
 * when its first field is not a number (oren_nayar_params.tsv has
 * "sample rho sigma"). Every row has the same number k of values, with
 * min_cols <= k <= max_cols; values are finite decimal numbers; sample
 * numbers are positive and unique, in any order, gaps allowed. */
#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest refractive index accepted by bf_n_file_read: far above any
 * dielectric (SPEC §4.2: typical values lie in [1.4, 2.0]), so only typos
 * and misplaced columns are rejected. */
#define BF__N_MAX 10.0

struct bf_sample_table {
    size_t n;    /* number of rows */
    size_t k;    /* values per row */
    int *sample; /* n sample numbers, file order */
    long *line;  /* n line numbers */
    double *v;   /* n * k values, row-major */
};

/* Row of sample s, or -1. */
static long find(const bf_sample_table *st, int sample)
{
    size_t r;
    for (r = 0; r < st->n; r++) {
        if (st->sample[r] == sample) {
            return (long)r;
        }
    }
    return -1;
}

/* Grows st's arrays to hold at least need rows of max_cols values. */
static int reserve(bf_sample_table *st, size_t max_cols, size_t *cap,
                   size_t need)
{
    size_t c;
    void *p;
    if (need <= *cap) {
        return BF_OK;
    }
    c = (*cap == 0) ? 64 : 2 * (*cap);
    p = realloc(st->sample, c * sizeof *st->sample);
    if (p == NULL) {
        return BF_ENOMEM;
    }
    st->sample = p;
    p = realloc(st->line, c * sizeof *st->line);
    if (p == NULL) {
        return BF_ENOMEM;
    }
    st->line = p;
    p = realloc(st->v, c * max_cols * sizeof *st->v);
    if (p == NULL) {
        return BF_ENOMEM;
    }
    st->v = p;
    *cap = c;
    return BF_OK;
}

/* Parses the current line of r as a row of st. */
static int add_row(bf_sample_table *st, size_t min_cols, size_t max_cols,
                   size_t *cap, const bf__lines *r, bf_error *err)
{
    long sample = 0;
    long dup;
    size_t k = r->nfield - 1; /* nfield >= 1 for a non-blank line */
    size_t c;
    int rc;
    rc = bf__field_long(r, 0, "sample", 1, INT_MAX, &sample, err);
    if (rc != BF_OK) {
        return rc;
    }
    if ((k < min_cols) || (k > max_cols)) {
        if (min_cols == max_cols) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "expected %zu number%s after the sample "
                                 "number, found %zu",
                                 min_cols, (min_cols == 1) ? "" : "s", k);
        }
        return bf__error_set(err, BF_EPARSE, r->line,
                             "expected %zu to %zu numbers after the sample "
                             "number, found %zu",
                             min_cols, max_cols, k);
    }
    if ((st->n > 0) && (k != st->k)) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "found %zu numbers after the sample number, "
                             "but line %ld has %zu",
                             k, st->line[0], st->k);
    }
    dup = find(st, (int)sample);
    if (dup >= 0) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "sample %ld appears twice, first at line %ld",
                             sample, st->line[dup]);
    }
    if (reserve(st, max_cols, cap, st->n + 1) != BF_OK) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    for (c = 0; c < k; c++) {
        char what[32];
        double *x = st->v + st->n * max_cols + c;
        int status = bf__parse_double(r->field[c + 1], x);
        if (status != BF__NUM_OK) {
            snprintf(what, sizeof what, "column %zu", c + 1);
            return bf__field_error(r, c + 1, what, status, 1, 0, err);
        }
    }
    st->k = k;
    st->sample[st->n] = (int)sample;
    st->line[st->n] = r->line;
    st->n++;
    return BF_OK;
}

/* Packs the rows (stored max_cols apart) to k values each. */
static void pack(bf_sample_table *st, size_t max_cols)
{
    size_t r;
    if (st->k == max_cols) {
        return;
    }
    for (r = 1; r < st->n; r++) {
        memmove(st->v + r * st->k, st->v + r * max_cols,
                st->k * sizeof *st->v);
    }
}

int bf_sample_table_read(FILE *fp, const char *name, size_t min_cols,
                         size_t max_cols, bf_sample_table **out,
                         bf_error *err)
{
    bf__lines r;
    bf_sample_table *st = NULL;
    size_t cap = 0;
    int have = 0;
    int header = 0;
    int rc;

    bf__error_clear(err, name);
    bf__lines_init(&r, fp);
    if (out != NULL) {
        *out = NULL;
    }
    if ((out == NULL) || (fp == NULL) || (max_cols == 0) ||
        (min_cols > max_cols)) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "no stream, no output or bad column range");
    }
    st = calloc(1, sizeof *st);
    if (st == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    for (;;) {
        rc = bf__lines_next(&r, &have, err);
        if ((rc != BF_OK) || !have) {
            break;
        }
        rc = bf__lines_split_ws(&r, err);
        if (rc != BF_OK) {
            goto done;
        }
        if ((st->n == 0) && !header) {
            double x;
            if (bf__parse_double(r.field[0], &x) != BF__NUM_OK) {
                header = 1; /* the first line's first field is not a number */
                continue;
            }
        }
        rc = add_row(st, min_cols, max_cols, &cap, &r, err);
        if (rc != BF_OK) {
            goto done;
        }
    }
    if (rc != BF_OK) {
        goto done;
    }
    if (st->n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           header ? "header line but no rows" : "empty file");
        goto done;
    }
    pack(st, max_cols);
    *out = st;
    st = NULL;
done:
    bf__lines_free(&r);
    bf_sample_table_free(st);
    return rc;
}

int bf_sample_table_load(const char *path, size_t min_cols, size_t max_cols,
                         bf_sample_table **out, bf_error *err)
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
    rc = bf_sample_table_read(fp, path, min_cols, max_cols, out, err);
    fclose(fp);
    return rc;
}

void bf_sample_table_free(bf_sample_table *st)
{
    if (st == NULL) {
        return;
    }
    free(st->sample);
    free(st->line);
    free(st->v);
    free(st);
}

size_t bf_sample_table_count(const bf_sample_table *st)
{
    return (st == NULL) ? 0 : st->n;
}

size_t bf_sample_table_cols(const bf_sample_table *st)
{
    return (st == NULL) ? 0 : st->k;
}

int bf_sample_table_sample(const bf_sample_table *st, size_t row)
{
    return ((st == NULL) || (row >= st->n)) ? -1 : st->sample[row];
}

int bf_sample_table_get(const bf_sample_table *st, int sample, size_t col,
                        double *value)
{
    long r;
    if ((st == NULL) || (value == NULL) || (col >= st->k)) {
        return BF_EINVAL;
    }
    r = find(st, sample);
    if (r < 0) {
        return BF_ENOTFOUND;
    }
    *value = st->v[(size_t)r * st->k + col];
    return BF_OK;
}

/* ==== Oren-Nayar parameters and refractive indices ==== */

/* Checks column col of every row against [lo, hi], or (lo, hi] when lo_open
 * is set; range is the interval as printed in the message. On failure frees
 * *st, sets it to NULL and fills err (BF_EPARSE at the row's line). */
static int check_column(bf_sample_table **st, size_t col, const char *what,
                        double lo, int lo_open, double hi,
                        const char *range, bf_error *err)
{
    size_t r;
    const bf_sample_table *t = *st;
    for (r = 0; r < t->n; r++) {
        double x = t->v[r * t->k + col];
        if ((lo_open ? (x <= lo) : (x < lo)) || (x > hi)) {
            long line = t->line[r];
            int sample = t->sample[r];
            bf_sample_table_free(*st);
            *st = NULL;
            return bf__error_set(err, BF_EPARSE, line,
                                 "sample %d: %s = %g outside %s", sample,
                                 what, x, range);
        }
    }
    return BF_OK;
}

int bf_on_params_read(FILE *fp, const char *name, bf_sample_table **out,
                      bf_error *err)
{
    /* "sample rho sigma", or CURET op.dat "sample rho sigma kd" */
    int rc = bf_sample_table_read(fp, name, 2, 3, out, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = check_column(out, 0, "rho", 0.0, 0, 1.0, "[0, 1]", err);
    if (rc != BF_OK) {
        return rc;
    }
    return check_column(out, 1, "sigma", 0.0, 0, BF__PI_2,
                        "[0, pi/2] (radians)", err);
}

int bf_on_params_load(const char *path, bf_sample_table **out, bf_error *err)
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
    rc = bf_on_params_read(fp, path, out, err);
    fclose(fp);
    return rc;
}

int bf_n_file_read(FILE *fp, const char *name, bf_sample_table **out,
                   bf_error *err)
{
    int rc = bf_sample_table_read(fp, name, 1, 1, out, err);
    if (rc != BF_OK) {
        return rc;
    }
    return check_column(out, 0, "n", 1.0, 1, BF__N_MAX, "(1, 10]", err);
}

int bf_n_file_load(const char *path, bf_sample_table **out, bf_error *err)
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
    rc = bf_n_file_read(fp, path, out, err);
    fclose(fp);
    return rc;
}
