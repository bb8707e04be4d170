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
 *     from samples x grid x K model evaluations to grid x K. bf_study_run
 *     does the same without storing them (bf__stream_fast in kernels.c:
 *     16 grid points at a time, scored at once, same kernels and sums,
 *     same bits); models without a kernel go through bf_grid.
 * Both form LSE = sum_k (L_k / max L - D_k)^2 in index order. The plain
 * path is the reference; the study path's vector kernels
 * (src/fit/kernels.c) rearrange the math without divisions in the inner
 * loop and agree with it to a few ulp (bound tested), with the same optima
 * (tested on all 61 CURET samples). The study path stores the curves
 * transposed (configuration-major, grid points padded to a multiple of
 * BF__SCORE_LANES). Models without a kernel (ON, LAMBERT, other free
 * masks) fill the study path's curves by the plain evaluation.
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
 * index order (SPEC §7.3: a sum, not a mean). */
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
 * Returns BF_OK, BF_ENOMEM (WNO-R's quadrature table), or BF_EDOM when the
 * model is undefined or its maximum is not positive. Parameters are assumed
 * valid (checked by the callers). */
int bf__model_curve(const bf_model_type *type, const double *param, size_t n,
                    const bf_geom *geom, double *curve)
{
    int rc = type->eval(param, n, geom, curve);
    if (rc != BF_OK) {
        return (rc == BF_ENOMEM) ? BF_ENOMEM : BF_EDOM;
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
    size_t cols;       /* grid points padded to a multiple of the lanes */
    size_t stride;     /* row pitch of curves: cols plus one cache line, so
                          that rows do not all fall in one cache set */
    double *curves;    /* n x stride normalised curves, transposed */
    unsigned char *ok; /* cols flags: 1 where the curve is defined */
};

/* Fills gr's curves with the plain evaluation, one grid point at a time
 * (models without a vector kernel: ON, LAMBERT, other free masks). */
static int curves_plain(bf_grid *gr, const bf_geom *geom)
{
    double param[BF_MAX_PARAMS];
    double *curve = malloc(gr->n * sizeof *curve);
    size_t idx;
    size_t k;
    if (curve == NULL) {
        return BF_ENOMEM;
    }
    for (idx = 0; idx < gr->layout.points; idx++) {
        bf__grid_point(gr->type, &gr->layout, idx, param);
        gr->ok[idx] = bf__model_curve(gr->type, param, gr->n, geom, curve) ==
                      BF_OK;
        for (k = 0; k < gr->n; k++) {
            gr->curves[(k * gr->stride) + idx] = curve[k];
        }
    }
    free(curve);
    return BF_OK;
}

bf_grid *bf__grid_build(const bf_model_type *type, const double *fixed,
                        unsigned free_mask, size_t n, const bf_geom *geom,
                        int *status)
{
    bf_grid *gr = NULL;
    size_t bytes;
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
    gr->cols = (gr->layout.points + BF__SCORE_LANES - 1) / BF__SCORE_LANES *
               BF__SCORE_LANES;
    gr->stride = gr->cols + BF__ROW_PAD;
    if (gr->cols < gr->layout.points ||
        gr->stride > SIZE_MAX / sizeof(double) / n) {
        rc = BF_ENOMEM;
        goto fail;
    }
    bytes = gr->stride * n * sizeof *gr->curves; /* a multiple of 64 */
    gr->curves = aligned_alloc(64, bytes);
    gr->ok = calloc(gr->cols, 1);
    if (gr->curves == NULL || gr->ok == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    rc = bf__curves_fast(type, &gr->layout, n, geom, gr->cols, gr->stride,
                         gr->curves, gr->ok);
    if (rc < 0) {
        rc = -rc;
        goto fail;
    }
    if (rc == 0) {
        memset(gr->curves, 0, bytes); /* padding lanes stay defined */
        rc = curves_plain(gr, geom);
        if (rc != BF_OK) {
            goto fail;
        }
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

bf_grid *bf_grid_alloc(const bf_model_type *type, const double *fixed,
                       unsigned free_mask, size_t n, const bf_geom *geom,
                       int *status)
{
    return bf__grid_build(type, fixed, free_mask, n, geom, status);
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

size_t bf__grid_cols(const bf_grid *gr)
{
    return gr->cols;
}

void bf__grid_score(const bf_grid *gr, size_t n_samples,
                    const double *const *data, double *lse)
{
    bf__score_all(gr->n, gr->cols, gr->stride, gr->curves, n_samples, data,
                  lse);
}

int bf__grid_result(const bf_model_type *type, const bf__grid_layout_t *g,
                    size_t best, double best_lse, bf_fit_result *result)
{
    memset(result, 0, sizeof *result);
    result->n_eval = g->points;
    if (best == SIZE_MAX) {
        return BF_EDOM;
    }
    result->bound_hit = bf__grid_point(type, g, best, result->param);
    result->lse = best_lse;
    return BF_OK;
}

int bf__grid_best(const bf_grid *gr, const double *lse,
                  bf_fit_result *result)
{
    size_t best;
    double best_lse = bf__argmin(gr->layout.points, lse, gr->ok, &best);
    return bf__grid_result(gr->type, &gr->layout, best, best_lse, result);
}

int bf_grid_fit(const bf_grid *gr, const double *data, bf_fit_result *result)
{
    double *lse;
    int rc;

    if (gr == NULL || data == NULL || result == NULL) {
        return BF_EINVAL;
    }
    lse = malloc(gr->cols * sizeof *lse);
    if (lse == NULL) {
        return BF_ENOMEM;
    }
    bf__grid_score(gr, 1, &data, lse);
    rc = bf__grid_best(gr, lse, result);
    free(lse);
    return rc;
}

/* ==== models with nothing to fit (the study path for ON, LAMBERT) ======= */

/* A model evaluated once per sample at that sample's fixed inputs (SPEC
 * §7.5: ON at the tabulated rho, sigma). The geometry-only terms of ON are
 * computed once for all samples; the value, the normalisation and the LSE
 * are the plain path's, operation for operation, so the results are bit
 * for bit those of bf_fit_grid. */
struct bf__fixed_model {
    const bf_model_type *type;
    size_t n;
    const bf_geom *geom;   /* borrowed from the caller */
    bf__on_terms_t *on;    /* ON's terms, or NULL: plain evaluation */
    double *curve;
};

int bf__fits_nothing(const bf_model_type *type)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        if (type->param[j].fitted) {
            return 0;
        }
    }
    return 1;
}

bf__fixed_model *bf__fixed_alloc(const bf_model_type *type, size_t n,
                                 const bf_geom *geom)
{
    bf__fixed_model *fm = calloc(1, sizeof *fm);
    size_t k;
    if (fm == NULL) {
        return NULL;
    }
    fm->type = type;
    fm->n = n;
    fm->geom = geom;
    fm->curve = malloc(n * sizeof *fm->curve);
    if (fm->curve == NULL) {
        bf__fixed_free(fm);
        return NULL;
    }
    if (bf__is_on(type)) {
        fm->on = malloc(n * sizeof *fm->on);
        if (fm->on == NULL) {
            bf__fixed_free(fm);
            return NULL;
        }
        for (k = 0; k < n; k++) {
            bf__on_terms(&geom[k], &fm->on[k]);
        }
    }
    return fm;
}

int bf__fixed_fit(const bf__fixed_model *fm, const double *fixed,
                  const double *data, bf_fit_result *result)
{
    bf__grid_layout_t g;
    int rc = bf__grid_layout(fm->type, fixed, 0, &g);
    memset(result, 0, sizeof *result);
    if (rc != BF_OK) {
        return rc;
    }
    if (fm->on != NULL) {
        bf__on_coef_t c;
        size_t k;
        bf__on_coef(fixed[0], fixed[1], &c); /* rho, sigma: SPEC §5 */
        for (k = 0; k < fm->n; k++) {
            fm->curve[k] = bf__on_value(&fm->on[k], &c);
        }
        rc = bf_normalise(fm->n, fm->curve, fm->curve);
    } else {
        rc = bf__model_curve(fm->type, g.base, fm->n, fm->geom, fm->curve);
    }
    result->n_eval = 1;
    if (rc != BF_OK) {
        return BF_EDOM; /* as bf_fit_grid: no defined grid point */
    }
    result->bound_hit = bf__grid_point(fm->type, &g, 0, result->param);
    result->lse = bf__sum_sq_diff(fm->n, fm->curve, data);
    return BF_OK;
}

void bf__fixed_free(bf__fixed_model *fm)
{
    if (fm == NULL) {
        return;
    }
    free(fm->on);
    free(fm->curve);
    free(fm);
}
