/* grid.c: the paper's exhaustive grid search (SPEC §7.3-7.4) and the LSE of
 * one parameter vector.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model", §5: the
 *     slope sigma/T runs over [0.1, 5.1] and n_d over [0.1, 20.1]; SPEC §7.4
 *     fixes the 501-point grids x = lo + step * i, i = 0..500.
 *
 * Two paths compute the same numbers:
 *   - bf_fit_grid evaluates the model at every grid point for one sample
 *     (the plain path, no allocation beyond the workspace);
 *   - bf_grid precomputes the normalised model curves of every grid point
 *     once per geometry and reuses them for every sample (the study path).
 *     Model curves do not depend on the sample, so the study's cost falls
 *     from samples x grid x K model evaluations to grid x K.
 * Both form LSE = sum_k (L_k / max L - D_k)^2 in the same order, so their
 * results are bit-for-bit identical (tested).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

struct bf_fit_workspace {
    size_t n;       /* capacity in configurations */
    double *curve;  /* model curve at one parameter vector */
};

bf_fit_workspace *bf_fit_alloc(size_t n)
{
    bf_fit_workspace *w;
    if (n == 0) {
        return NULL;
    }
    w = calloc(1, sizeof *w);
    if (w == NULL) {
        return NULL;
    }
    w->n = n;
    w->curve = malloc(n * sizeof *w->curve);
    if (w->curve == NULL) {
        bf_fit_free(w);
        return NULL;
    }
    return w;
}

void bf_fit_free(bf_fit_workspace *w)
{
    if (w == NULL) {
        return;
    }
    free(w->curve);
    free(w);
}

/* Sum of squared differences between a normalised curve and the data, in
 * index order (SPEC §7.3: a sum, not a mean). Shared by both paths. */
double bf__sum_sq_diff(size_t n, const double *curve, const double *data)
{
    double s = 0.0;
    size_t k;
    for (k = 0; k < n; k++) {
        double r = curve[k] - data[k];
        s += r * r;
    }
    return s;
}

/* Evaluates type at param on the n configurations and normalises in place.
 * Returns BF_OK, or BF_EDOM when the model is undefined or its maximum is
 * not positive. Parameters are assumed valid (checked by the callers). */
int bf__model_curve(const bf_model_type *type, const double *param, size_t n,
                    const bf_geom *geom, double *curve)
{
    int rc = type->eval(param, n, geom, curve);
    if (rc != BF_OK) {
        return BF_EDOM;
    }
    return bf_normalise(n, curve, curve);
}

int bf_fit_lse(const bf_model_type *type, const double *param, size_t n,
               const bf_geom *geom, const double *data, bf_fit_workspace *w,
               double *lse)
{
    int rc;
    if (type == NULL || (param == NULL && type->p > 0) || geom == NULL ||
        data == NULL || w == NULL || lse == NULL || n == 0 || n > w->n) {
        return BF_EINVAL;
    }
    rc = bf_model_eval(type, param, n, geom, w->curve);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_normalise(n, w->curve, w->curve);
    if (rc != BF_OK) {
        return rc;
    }
    *lse = bf__sum_sq_diff(n, w->curve, data);
    return BF_OK;
}

/* ==== grid enumeration ================================================== */

/* Fills g with the free parameters of type (bit j of mask, or the ones the
 * paper fits when mask is 0) and checks that each has a grid and fixed[]
 * holds valid values for the others. */
int bf__grid_layout(const bf_model_type *type, const double *fixed,
                    unsigned free_mask, bf__grid_layout_t *g)
{
    size_t j;
    memset(g, 0, sizeof *g);
    if (type == NULL || (type->p > 0 && fixed == NULL) ||
        type->p > BF_MAX_PARAMS) {
        return BF_EINVAL;
    }
    if (free_mask == 0) {
        for (j = 0; j < type->p; j++) {
            if (type->param[j].fitted) {
                free_mask |= 1u << j;
            }
        }
    }
    if ((free_mask >> type->p) != 0) {
        return BF_EINVAL;
    }
    g->points = 1;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        g->base[j] = fixed[j];
        if (free_mask & (1u << j)) {
            double hi = pj->grid_lo + pj->grid_step * (double)(pj->grid_n - 1);
            if (pj->grid_n == 0 || pj->grid_lo < pj->min || hi > pj->max) {
                return BF_EINVAL;
            }
            g->free[g->n_free++] = j;
            g->points *= pj->grid_n;
        } else if (!isfinite(fixed[j]) || fixed[j] < pj->min ||
                   fixed[j] > pj->max) {
            return BF_EINVAL;
        }
    }
    g->mask = free_mask;
    return BF_OK;
}

/* Parameter vector of grid point idx (mixed radix, first free parameter
 * varying slowest) and the bound flags of that point. */
unsigned bf__grid_point(const bf_model_type *type, const bf__grid_layout_t *g,
                        size_t idx, double *param)
{
    unsigned bound = 0;
    size_t f = g->n_free;
    memcpy(param, g->base, sizeof g->base);
    while (f-- > 0) {
        size_t j = g->free[f];
        const bf_param *pj = &type->param[j];
        size_t i = idx % pj->grid_n;
        idx /= pj->grid_n;
        param[j] = pj->grid_lo + pj->grid_step * (double)i; /* SPEC §7.4 */
        if (i == 0 || i == pj->grid_n - 1) {
            bound |= 1u << j;
        }
    }
    return bound;
}

int bf_fit_grid(const bf_model_type *type, const double *fixed,
                unsigned free_mask, size_t n, const bf_geom *geom,
                const double *data, bf_fit_workspace *w,
                bf_fit_result *result)
{
    bf__grid_layout_t g;
    double param[BF_MAX_PARAMS];
    size_t idx;
    size_t best = SIZE_MAX;
    double best_lse = INFINITY;
    int rc;

    if (geom == NULL || data == NULL || w == NULL || result == NULL ||
        n == 0 || n > w->n) {
        return BF_EINVAL;
    }
    rc = bf__grid_layout(type, fixed, free_mask, &g);
    if (rc != BF_OK) {
        return rc;
    }
    memset(result, 0, sizeof *result);
    for (idx = 0; idx < g.points; idx++) {
        double lse;
        bf__grid_point(type, &g, idx, param);
        result->n_eval++;
        if (bf__model_curve(type, param, n, geom, w->curve) != BF_OK) {
            continue; /* undefined here: not a candidate */
        }
        lse = bf__sum_sq_diff(n, w->curve, data);
        if (lse < best_lse) { /* strict: ties keep the first grid point */
            best_lse = lse;
            best = idx;
        }
    }
    if (best == SIZE_MAX) {
        return BF_EDOM;
    }
    result->bound_hit = bf__grid_point(type, &g, best, result->param);
    result->lse = best_lse;
    return BF_OK;
}

/* ==== precomputed grid (the study path) ================================= */

struct bf_grid {
    const bf_model_type *type;
    bf__grid_layout_t layout;
    size_t n;          /* configurations */
    double *curves;    /* points x n normalised curves, row-major */
    unsigned char *ok; /* 1 where the curve is defined */
};

bf_grid *bf_grid_alloc(const bf_model_type *type, const double *fixed,
                       unsigned free_mask, size_t n, const bf_geom *geom,
                       int *status)
{
    bf_grid *gr = NULL;
    double param[BF_MAX_PARAMS];
    size_t idx;
    int rc;

    if (geom == NULL || n == 0) {
        rc = BF_EINVAL;
        goto fail;
    }
    gr = calloc(1, sizeof *gr);
    if (gr == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    rc = bf__grid_layout(type, fixed, free_mask, &gr->layout);
    if (rc != BF_OK) {
        goto fail;
    }
    gr->type = type;
    gr->n = n;
    if (gr->layout.points > SIZE_MAX / sizeof(double) / n) {
        rc = BF_ENOMEM;
        goto fail;
    }
    gr->curves = malloc(gr->layout.points * n * sizeof *gr->curves);
    gr->ok = malloc(gr->layout.points);
    if (gr->curves == NULL || gr->ok == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    for (idx = 0; idx < gr->layout.points; idx++) {
        bf__grid_point(type, &gr->layout, idx, param);
        gr->ok[idx] = bf__model_curve(type, param, n, geom,
                                      gr->curves + idx * n) == BF_OK;
    }
    if (status != NULL) {
        *status = BF_OK;
    }
    return gr;

fail:
    bf_grid_free(gr);
    if (status != NULL) {
        *status = rc;
    }
    return NULL;
}

void bf_grid_free(bf_grid *gr)
{
    if (gr == NULL) {
        return;
    }
    free(gr->curves);
    free(gr->ok);
    free(gr);
}

size_t bf_grid_points(const bf_grid *gr)
{
    return gr->layout.points;
}

int bf_grid_fit(const bf_grid *gr, const double *data, bf_fit_result *result)
{
    size_t idx;
    size_t best = SIZE_MAX;
    double best_lse = INFINITY;

    if (gr == NULL || data == NULL || result == NULL) {
        return BF_EINVAL;
    }
    memset(result, 0, sizeof *result);
    for (idx = 0; idx < gr->layout.points; idx++) {
        double lse;
        if (!gr->ok[idx]) {
            continue;
        }
        lse = bf__sum_sq_diff(gr->n, gr->curves + idx * gr->n, data);
        if (lse < best_lse) { /* strict: ties keep the first grid point */
            best_lse = lse;
            best = idx;
        }
    }
    result->n_eval = gr->layout.points;
    if (best == SIZE_MAX) {
        return BF_EDOM;
    }
    result->bound_hit = bf__grid_point(gr->type, &gr->layout, best,
                                       result->param);
    result->lse = best_lse;
    return BF_OK;
}
