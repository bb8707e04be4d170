/* curves.c: grid optima of a fitting problem under any objective and any
 * number of weight vectors against stored normalised curves -- one per
 * sample, per bootstrap replicate, per cross-validation fold -- at no model
 * evaluation (doc/methods.md §2), and the public bf_curves built on them.
 *
 * [1] SPEC §7.4: grid x = lo + step * i; with the paper's ranges the points
 *     are those of bf_fit_grid.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

struct bf_curves {
    bf__cset cs;
    bf__prep pm;
    bf__grid *gr;
    unsigned mask; /* free parameters */
};

/* The objective of pb (weights w) at every grid point, the slow way: one
 * curve at a time through bf__objective (the scale and log objectives),
 * read BF__GRID_BLOCK curves at a time. */
static int optima_by_point(const bf__grid *gr, const bf_problem *pb,
                           const double *cti, size_t n_w,
                           const double *const *w, double *lse)
{
    const bf__grid_layout_t *lay = bf__grid_lay(gr);
    size_t cols = bf__grid_cols(gr);
    double *curves =
        malloc((BF__GRID_BLOCK + 2) * pb->n * sizeof *curves);
    double *scratch;
    double *log_d;
    size_t g0;
    if (curves == NULL) {
        return BF_ENOMEM;
    }
    scratch = curves + (BF__GRID_BLOCK * pb->n);
    log_d = scratch + pb->n;
    bf__data_transform(pb, log_d);
    for (g0 = 0; g0 < lay->points; g0 += BF__GRID_BLOCK) {
        size_t nb = lay->points - g0;
        size_t g;
        size_t b;
        nb = nb < BF__GRID_BLOCK ? nb : BF__GRID_BLOCK;
        bf__grid_curves(gr, g0, nb, curves);
        for (g = 0; g < nb; g++) {
            for (b = 0; b < n_w; b++) {
                bf_problem q = *pb;
                q.weight = w[b];
                lse[(b * cols) + g0 + g] = bf__objective(
                    &q, cti, log_d, curves + (g * pb->n), scratch);
            }
        }
    }
    free(curves);
    return BF_OK;
}

int bf__grid_optima(const bf__grid *gr, const bf_problem *pb,
                    const double *cti, size_t n_w, const double *const *w,
                    bf_fit_result *results)
{
    const bf__grid_layout_t *lay = bf__grid_lay(gr);
    size_t cols = bf__grid_cols(gr);
    double *lse;
    size_t b;
    int rc = BF_OK;
    if (n_w == 0) {
        return BF_OK;
    }
    if (pb->objective == BF_OBJ_MAX || pb->objective == BF_OBJ_COSW) {
        /* the sums' optima without storing them: one pass for all */
        return bf__grid_weights_argmin(
            gr, pb->data, pb->objective == BF_OBJ_COSW ? cti : NULL, n_w, w,
            results);
    }
    if (cols > SIZE_MAX / sizeof(double) / n_w) {
        return BF_ENOMEM;
    }
    lse = malloc(n_w * cols * sizeof *lse);
    if (lse == NULL) {
        return BF_ENOMEM;
    }
    rc = optima_by_point(gr, pb, cti, n_w, w, lse); /* scale, log */
    for (b = 0; rc == BF_OK && b < n_w; b++) {
        int r = bf__grid_best(gr, lse + b * cols, &results[b]);
        if (r != BF_OK) {
            memset(&results[b], 0, sizeof results[b]);
            results[b].lse = NAN; /* no defined point: BF_EDOM's result */
            results[b].n_eval = lay->points;
        }
    }
    free(lse);
    return rc;
}

int bf__grid_optima_folds(const bf__grid *gr, const bf_problem *pb,
                          const double *cti, const size_t *fold,
                          size_t folds, bf_fit_result *results)
{
    const bf__grid_layout_t *lay = bf__grid_lay(gr);
    size_t cols = bf__grid_cols(gr);
    double *lse;
    size_t b;
    if (pb->objective != BF_OBJ_MAX && pb->objective != BF_OBJ_COSW) {
        /* the slow way: explicit 0/1 weights */
        double *w = malloc((folds + 1) * pb->n * sizeof *w);
        const double **wp = malloc((folds + 1) * sizeof *wp);
        size_t k;
        int rc = BF_ENOMEM;
        if (w != NULL && wp != NULL) {
            wp[0] = NULL;
            for (b = 0; b < folds; b++) {
                for (k = 0; k < pb->n; k++) {
                    w[b * pb->n + k] = fold[k] == b ? 0.0 : 1.0;
                }
                wp[b + 1] = w + b * pb->n;
            }
            rc = bf__grid_optima(gr, pb, cti, folds + 1, wp, results);
        }
        free(w);
        free(wp);
        return rc;
    }
    if (cols > SIZE_MAX / sizeof(double) / (folds + 1)) {
        return BF_ENOMEM;
    }
    lse = malloc((folds + 1) * cols * sizeof *lse);
    if (lse == NULL) {
        return BF_ENOMEM;
    }
    bf__grid_score_folds(gr, pb->data,
                         pb->objective == BF_OBJ_COSW ? cti : NULL, fold,
                         folds, lse);
    for (b = 0; b <= folds; b++) {
        if (bf__grid_best(gr, lse + b * cols, &results[b]) != BF_OK) {
            memset(&results[b], 0, sizeof results[b]);
            results[b].lse = NAN;
            results[b].n_eval = lay->points;
        }
    }
    free(lse);
    return BF_OK;
}

/* 1 when point idx of lay is a local minimum of lse: no lower value at any
 * neighbour along a free parameter (lattice neighbours), and no equal one
 * before it (a plateau counts once, at its first point). */
static int local_min(const bf__grid_layout_t *lay, const double *lse,
                     const unsigned char *ok, size_t idx)
{
    size_t stride = 1;
    size_t f = lay->n_free;
    if (!ok[idx] || !isfinite(lse[idx])) {
        return 0;
    }
    while (f-- > 0) { /* the last free parameter varies fastest */
        size_t i = (idx / stride) % lay->count[f];
        if (i > 0 && ok[idx - stride] && !(lse[idx] < lse[idx - stride])) {
            return 0;
        }
        if (i + 1 < lay->count[f] && ok[idx + stride] &&
            lse[idx + stride] < lse[idx]) {
            return 0;
        }
        stride *= lay->count[f];
    }
    return 1;
}

int bf__grid_minima(const bf__grid *gr, const bf_problem *pb,
                    const double *cti, size_t max, bf_fit_result *results,
                    size_t *count)
{
    const bf__grid_layout_t *lay = bf__grid_lay(gr);
    const unsigned char *ok = bf__grid_ok(gr);
    size_t cols = bf__grid_cols(gr);
    const double *w[1];
    double *lse = malloc(cols * sizeof *lse);
    size_t *idx = malloc((max + 1) * sizeof *idx);
    size_t g;
    size_t i;
    int rc = BF_OK;
    *count = 0;
    if (lse == NULL || idx == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    w[0] = pb->weight;
    switch (pb->objective) {
    case BF_OBJ_MAX:
        bf__grid_score_weights(gr, pb->data, NULL, 1, w, lse);
        break;
    case BF_OBJ_COSW:
        bf__grid_score_weights(gr, pb->data, cti, 1, w, lse);
        break;
    default:
        rc = optima_by_point(gr, pb, cti, 1, w, lse);
        break;
    }
    for (g = 0; rc == BF_OK && g < lay->points; g++) {
        if (!local_min(lay, lse, ok, g)) {
            continue;
        }
        /* keep the max lowest, in increasing value (ties: grid order) */
        for (i = *count; i > 0 && lse[g] < lse[idx[i - 1]]; i--) {
            if (i < max) {
                idx[i] = idx[i - 1];
            }
        }
        if (i < max) {
            idx[i] = g;
            *count += *count < max;
        }
    }
    for (i = 0; rc == BF_OK && i < *count; i++) {
        bf__grid_result(lay, idx[i], lse[idx[i]], &results[i]);
    }
done:
    free(lse);
    free(idx);
    return rc;
}

/* ==== the public bf_curves =============================================== */

bf_curves *bf_curves_alloc(const bf_problem *pb, int *status)
{
    bf_curves *c = NULL;
    bf__grid_layout_t lay;
    int rc;

    if (pb == NULL || pb->type == NULL || pb->geom == NULL || pb->n == 0 ||
        pb->type->p > BF_MAX_PARAMS) {
        rc = BF_EINVAL;
        goto fail;
    }
    rc = bf__grid_layout_range(pb->type, pb->fixed, pb->free_mask, pb->lo,
                               pb->hi, &lay);
    if (rc != BF_OK) {
        goto fail;
    }
    rc = bf__geom_check(pb->n, pb->geom);
    if (rc != BF_OK) {
        goto fail;
    }
    c = calloc(1, sizeof *c);
    if (c == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    c->mask = pb->free_mask;
    rc = bf__cset_init(&c->cs, pb->n, pb->geom);
    if (rc == BF_OK) {
        rc = bf__prep_init(&c->pm, pb->type, &c->cs);
    }
    if (rc == BF_OK) {
        c->gr = bf__grid_make(&c->pm, &lay, &rc);
    }
    if (rc != BF_OK) {
        goto fail;
    }
    if (status != NULL) {
        *status = BF_OK;
    }
    return c;

fail:
    bf_curves_free(c);
    if (status != NULL) {
        *status = rc;
    }
    return NULL;
}

void bf_curves_free(bf_curves *c)
{
    if (c == NULL) {
        return;
    }
    bf__grid_free(c->gr);
    bf__prep_free(&c->pm);
    bf__cset_free(&c->cs);
    free(c);
}

size_t bf_curves_points(const bf_curves *c)
{
    return bf__grid_points(c->gr);
}

const bf__grid *bf__curves_grid(const bf_curves *c)
{
    return c->gr;
}

int bf__curves_check(const bf_curves *c, const bf_problem *pb)
{
    return (c != NULL && pb != NULL && pb->data != NULL &&
            pb->type == c->pm.type && pb->n == c->pm.n &&
            pb->free_mask == c->mask)
               ? BF_OK
               : BF_EINVAL;
}

int bf_curves_best(const bf_curves *c, const bf_problem *pb,
                   bf_fit_result *result)
{
    const double *w[1];
    int rc;
    if (result == NULL || bf__curves_check(c, pb) != BF_OK) {
        return BF_EINVAL;
    }
    w[0] = pb->weight;
    rc = bf__grid_optima(c->gr, pb, c->cs.cti, 1, w, result);
    if (rc == BF_OK && !isfinite(result->lse)) {
        rc = BF_EDOM;
    }
    return rc;
}
