/* curves.c: normalised model curves at every grid point of a problem, so
 * that grid optima under any objective, weights or data -- one per sample,
 * per bootstrap replicate, per cross-validation fold -- cost no model
 * evaluation (doc/methods.md §2).
 *
 * [1] SPEC §7.4: grid x = lo + step * i; with the paper's ranges the points
 *     and curves are those of bf_fit_grid, bit for bit.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

struct bf_curves {
    const bf_model_type *type;
    unsigned mask;                  /* free parameters */
    double base[BF_MAX_PARAMS];     /* fixed values */
    size_t free[BF_MAX_PARAMS];     /* free parameter indices */
    size_t n_free;
    double lo[BF_MAX_PARAMS];       /* grid of free parameter i: */
    double step[BF_MAX_PARAMS];     /*   lo + step * t, t < count */
    size_t count[BF_MAX_PARAMS];
    size_t points;
    size_t n;                       /* configurations */
    double *curves;                 /* points x n, row-major */
    unsigned char *ok;              /* 1 where the curve is defined */
};

/* Parameter vector of point idx (first free parameter slowest, as
 * bf__grid_point) and its grid-bound flags. */
static unsigned point(const bf_curves *c, size_t idx, double *param)
{
    unsigned bound = 0;
    size_t f = c->n_free;
    memcpy(param, c->base, sizeof c->base);
    while (f-- > 0) {
        size_t t = idx % c->count[f];
        idx /= c->count[f];
        param[c->free[f]] = c->lo[f] + c->step[f] * (double)t; /* SPEC §7.4 */
        if (t == 0 || t + 1 == c->count[f]) {
            bound |= 1u << c->free[f];
        }
    }
    return bound;
}

bf_curves *bf_curves_alloc(const bf_problem *pb, int *status)
{
    bf_curves *c = NULL;
    double param[BF_MAX_PARAMS];
    size_t j;
    size_t idx;
    int rc = BF_OK;

    if (pb == NULL || pb->type == NULL || pb->geom == NULL || pb->n == 0 ||
        pb->type->p > BF_MAX_PARAMS) {
        rc = BF_EINVAL;
        goto fail;
    }
    c = calloc(1, sizeof *c);
    if (c == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    c->type = pb->type;
    c->mask = pb->free_mask;
    c->n = pb->n;
    c->points = 1;
    memcpy(c->base, pb->fixed, sizeof c->base);
    for (j = 0; j < pb->type->p; j++) {
        const bf_param *pj = &pb->type->param[j];
        double span;
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        span = pb->hi[j] - pb->lo[j];
        if (pj->grid_n == 0 || !(pj->grid_step > 0.0) || !(span >= 0.0) ||
            pb->lo[j] < pj->min || pb->hi[j] > pj->max) {
            rc = BF_EINVAL;
            goto fail;
        }
        c->free[c->n_free] = j;
        c->lo[c->n_free] = pb->lo[j];
        c->step[c->n_free] = pj->grid_step;
        /* points lo + step t <= hi (1e-9 absorbs the rounding of span) */
        c->count[c->n_free] = (size_t)floor(span / pj->grid_step + 1e-9) + 1;
        if (c->count[c->n_free] > SIZE_MAX / c->points) {
            rc = BF_ENOMEM;
            goto fail;
        }
        c->points *= c->count[c->n_free];
        c->n_free++;
    }
    if (c->points > SIZE_MAX / sizeof(double) / c->n) {
        rc = BF_ENOMEM;
        goto fail;
    }
    c->curves = malloc(c->points * c->n * sizeof *c->curves);
    c->ok = malloc(c->points);
    if (c->curves == NULL || c->ok == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    for (idx = 0; idx < c->points; idx++) {
        point(c, idx, param);
        c->ok[idx] = bf__model_curve(c->type, param, c->n, pb->geom,
                                     c->curves + idx * c->n) == BF_OK;
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
    free(c->curves);
    free(c->ok);
    free(c);
}

size_t bf_curves_points(const bf_curves *c)
{
    return c->points;
}

int bf_curves_best(const bf_curves *c, const bf_problem *pb,
                   bf_fit_result *result)
{
    double *scratch;
    double best_value = INFINITY;
    size_t best = SIZE_MAX;
    size_t idx;

    if (c == NULL || pb == NULL || result == NULL || pb->data == NULL ||
        pb->type != c->type || pb->n != c->n || pb->free_mask != c->mask) {
        return BF_EINVAL;
    }
    scratch = malloc(c->n * sizeof *scratch);
    if (scratch == NULL) {
        return BF_ENOMEM;
    }
    memset(result, 0, sizeof *result);
    for (idx = 0; idx < c->points; idx++) {
        double v;
        if (!c->ok[idx]) {
            continue;
        }
        v = bf__objective_curve(pb, c->curves + idx * c->n, scratch);
        if (v < best_value) { /* strict: ties keep the first point */
            best_value = v;
            best = idx;
        }
    }
    free(scratch);
    result->n_eval = c->points;
    if (best == SIZE_MAX) {
        return BF_EDOM;
    }
    result->bound_hit = point(c, best, result->param);
    result->lse = best_value;
    return BF_OK;
}
