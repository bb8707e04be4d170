/* brdf.c: BRDF files with rows "sample v1 ... vN" -- CURET's abrdf.dat and
 * its per-channel rbrdf/gbrdf/bbrdf.dat (SPEC §2).
 *
 * [1] K. J. Dana et al., ACM TOG 18(1), 1999 (CURET); layout in
 *     shared/data/curet/SOURCES.md.
 *
 * Every row has the sample number and exactly n_conf finite decimal values.
 * Values may be slightly negative (CURET has 29 such entries) and are kept
 * as measured. Rows may come in any order but the sample numbers must be
 * 1, 2, ..., count, each exactly once; the rows are stored sorted, so
 * row r holds sample r + 1. */
#include "data/curet.h"
#include "internal.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct bf_brdf {
    size_t n;      /* number of samples (rows) */
    size_t n_conf; /* values per row */
    int *sample;   /* n sample numbers, 1..n after sorting */
    double *v;     /* n * n_conf values, row-major */
    long *line;    /* n line numbers of the rows in the file */
};

/* A row as read: its sample number, position in the file and line. */
typedef struct {
    int sample;
    size_t pos;
    long line;
} row_info;

/* Orders rows by sample number, then by position in the file. */
static int cmp_rows(const void *a, const void *b)
{
    const row_info *x = a;
    const row_info *y = b;
    if (x->sample != y->sample) {
        return (x->sample < y->sample) ? -1 : 1;
    }
    return (x->pos < y->pos) ? -1 : (x->pos > y->pos);
}

/* Grows the row arrays to hold at least need rows. */
static int reserve(double **v, row_info **info, size_t n_conf, size_t *cap,
                   size_t need)
{
    size_t c;
    double *nv;
    row_info *ni;
    if (need <= *cap) {
        return BF_OK;
    }
    c = (*cap == 0) ? 64 : 2 * (*cap);
    if (c > SIZE_MAX / sizeof(double) / n_conf) {
        return BF_ENOMEM;
    }
    nv = realloc(*v, c * n_conf * sizeof *nv);
    if (nv == NULL) {
        return BF_ENOMEM;
    }
    *v = nv;
    ni = realloc(*info, c * sizeof *ni);
    if (ni == NULL) {
        return BF_ENOMEM;
    }
    *info = ni;
    *cap = c;
    return BF_OK;
}

/* Checks that the sorted rows hold samples 1..n exactly once. */
static int check_samples(const row_info *sorted, size_t n, bf_error *err)
{
    size_t k;
    const row_info *dup = NULL;
    const row_info *first = NULL;
    /* Report the duplicate whose second occurrence comes first in the file. */
    for (k = 1; k < n; k++) {
        if ((sorted[k].sample == sorted[k - 1].sample) &&
            ((dup == NULL) || (sorted[k].pos < dup->pos))) {
            dup = &sorted[k];
            first = &sorted[k - 1];
            while ((first > sorted) && (first[-1].sample == dup->sample)) {
                first--;
            }
        }
    }
    if (dup != NULL) {
        return bf__error_set(err, BF_EPARSE, dup->line,
                             "sample %d appears twice, first at line %ld",
                             dup->sample, first->line);
    }
    for (k = 0; k < n; k++) {
        if ((size_t)sorted[k].sample != k + 1) {
            return bf__error_set(err, BF_EPARSE, 0,
                                 "sample %zu is missing (sample numbers "
                                 "must be 1, 2, 3, ... without gaps)",
                                 k + 1);
        }
    }
    return BF_OK;
}

int bf_brdf_read(FILE *fp, const char *name, size_t n_conf, bf_brdf **out,
                 bf_error *err)
{
    bf__lines r;
    bf_brdf *b = NULL;
    double *v = NULL;
    row_info *info = NULL;
    size_t n = 0;
    size_t cap = 0;
    size_t k;
    int have = 0;
    int rc;

    bf__error_clear(err, name);
    bf__lines_init(&r, fp);
    if (out != NULL) {
        *out = NULL;
    }
    if ((out == NULL) || (fp == NULL)) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    for (;;) {
        long sample = 0;
        double *row;
        rc = bf__lines_next(&r, &have, err);
        if ((rc != BF_OK) || !have) {
            break;
        }
        rc = bf__lines_split_ws(&r, err);
        if (rc != BF_OK) {
            goto done;
        }
        if (n_conf == 0 && r.nfield > 1) { /* the first row sets the count */
            n_conf = r.nfield - 1;
        }
        if (n_conf == 0) {
            rc = bf__error_set(err, BF_EPARSE, r.line,
                               "a sample number without values");
            goto done;
        }
        if (r.nfield != n_conf + 1) {
            rc = bf__error_set(err, BF_EPARSE, r.line,
                               "expected %zu values after the sample "
                               "number, found %zu",
                               n_conf, r.nfield == 0 ? 0 : r.nfield - 1);
            goto done;
        }
        rc = bf__field_long(&r, 0, "sample", 1, INT_MAX, &sample, err);
        if (rc != BF_OK) {
            goto done;
        }
        if (reserve(&v, &info, n_conf, &cap, n + 1) != BF_OK) {
            rc = bf__error_set(err, BF_ENOMEM, r.line, "out of memory");
            goto done;
        }
        row = v + n * n_conf;
        for (k = 0; k < n_conf; k++) {
            int st = bf__parse_double(r.field[k + 1], &row[k]);
            if (st != BF__NUM_OK) {
                char what[48];
                snprintf(what, sizeof what, "value %zu", k + 1);
                rc = bf__field_error(&r, k + 1, what, st, 1, 0, err);
                goto done;
            }
        }
        info[n].sample = (int)sample;
        info[n].pos = n;
        info[n].line = r.line;
        n++;
    }
    if (rc != BF_OK) {
        goto done;
    }
    if (n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0, "empty file");
        goto done;
    }
    qsort(info, n, sizeof *info, cmp_rows);
    rc = check_samples(info, n, err);
    if (rc != BF_OK) {
        goto done;
    }
    b = calloc(1, sizeof *b);
    if (b == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    b->n = n;
    b->n_conf = n_conf;
    b->sample = malloc(n * sizeof *b->sample);
    b->v = malloc(n * n_conf * sizeof *b->v);
    b->line = malloc(n * sizeof *b->line);
    if ((b->sample == NULL) || (b->v == NULL) || (b->line == NULL)) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    for (k = 0; k < n; k++) {
        b->sample[k] = info[k].sample;
        b->line[k] = info[k].line;
        memcpy(b->v + k * n_conf, v + info[k].pos * n_conf,
               n_conf * sizeof *b->v);
    }
    *out = b;
    b = NULL;
done:
    bf__lines_free(&r);
    free(v);
    free(info);
    bf_brdf_free(b);
    return rc;
}

int bf_brdf_load(const char *path, size_t n_conf, bf_brdf **out,
                 bf_error *err)
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
    rc = bf_brdf_read(fp, path, n_conf, out, err);
    fclose(fp);
    return rc;
}

void bf_brdf_free(bf_brdf *b)
{
    if (b == NULL) {
        return;
    }
    free(b->sample);
    free(b->v);
    free(b->line);
    free(b);
}

size_t bf_brdf_count(const bf_brdf *b)
{
    return (b == NULL) ? 0 : b->n;
}

size_t bf_brdf_nconf(const bf_brdf *b)
{
    return (b == NULL) ? 0 : b->n_conf;
}

int bf_brdf_sample(const bf_brdf *b, size_t row)
{
    return ((b == NULL) || (row >= b->n)) ? -1 : b->sample[row];
}

long bf_brdf_line(const bf_brdf *b, size_t row)
{
    return ((b == NULL) || (row >= b->n)) ? 0 : b->line[row];
}

const double *bf_brdf_values(const bf_brdf *b, size_t row)
{
    return ((b == NULL) || (row >= b->n)) ? NULL : b->v + row * b->n_conf;
}

long bf_brdf_find(const bf_brdf *b, int sample)
{
    /* Rows are sorted and complete: sample s sits in row s - 1. */
    if ((b == NULL) || (sample < 1) || ((size_t)sample > b->n)) {
        return -1;
    }
    return (long)sample - 1;
}
