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
 *   - bf__grid precomputes the normalised model curves of every grid point
 *     once per geometry and reuses them for every sample (the study path).
 *     Model curves do not depend on the sample, so the study's cost falls
 *     from samples x grid x K model evaluations to grid x K. bf_study_run
 *     does the same without storing them (bf__stream_fast in kernels.c:
 *     8 grid points at a time, scored at once, same kernels and sums,
 *     same bits); models without a kernel go through bf__grid.
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

#include "fit/engine.h"

struct bf_fit_workspace {
    size_t n;          /* capacity in configurations */
    double *curve;     /* model curve at one parameter vector */
    void *work;        /* a model's eval workspace (the largest of the
                          registry's), or NULL */
    size_t work_bytes;
};

/* The largest eval workspace of the registry's models. */
static size_t registry_work_bytes(void)
{
    size_t i;
    size_t most = 0;
    for (i = 0; i < bf_model_count(); i++) {
        size_t b = bf_model_get(i)->work_size;
        most = b > most ? b : most;
    }
    return most;
}

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
    w->work_bytes = registry_work_bytes();
    if (w->work_bytes > 0) {
        w->work = bf__alloc_lines(w->work_bytes);
    }
    if (w->curve == NULL || (w->work_bytes > 0 && w->work == NULL)) {
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
    free(w->work);
    free(w);
}

/* w's eval workspace for type, or a new one in *own (freed by the caller)
 * for a type made outside the library that needs more; NULL with *own
 * NULL when none is needed. BF_ENOMEM. */
static int eval_work(bf_fit_workspace *w, const bf_model_type *type,
                     void **work, void **own)
{
    *own = NULL;
    *work = w->work;
    if (type->work_size > w->work_bytes) {
        *own = bf__alloc_lines(type->work_size);
        *work = *own;
        if (*own == NULL) {
            return BF_ENOMEM;
        }
    }
    return BF_OK;
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

int bf_fit_lse(const bf_model_type *type, const double *param, size_t n,
               const bf_geom *geom, const double *data, bf_fit_workspace *w,
               double *lse)
{
    void *work;
    void *own;
    bf__prep pm;
    int rc;
    if (type == NULL || (param == NULL && type->p > 0) || geom == NULL ||
        data == NULL || w == NULL || lse == NULL || n == 0 || n > w->n) {
        return BF_EINVAL;
    }
    rc = eval_work(w, type, &work, &own);
    if (rc == BF_OK) {
        rc = bf_model_eval_work(type, param, n, geom, w->curve, work);
    }
    if (rc == BF_OK) {
        rc = bf_normalise(n, w->curve, w->curve);
    }
    if (rc == BF_OK) {
        *lse = bf__sum_sq_diff(n, w->curve, data);
    }
    (void)pm;
    free(own);
    return rc;
}

/* ==== the grid layout and enumerator ===================================== */

int bf__grid_layout(const bf_model_type *type, const double *fixed,
                    unsigned free_mask, bf__grid_layout_t *g)
{
    double lo[BF_MAX_PARAMS] = {0};
    double hi[BF_MAX_PARAMS] = {0};
    size_t j;
    if (type == NULL || type->p > BF_MAX_PARAMS) {
        memset(g, 0, sizeof *g);
        return BF_EINVAL;
    }
    if (free_mask == 0) {
        for (j = 0; j < type->p; j++) {
            if (type->param[j].fitted) {
                free_mask |= 1u << j;
            }
        }
    }
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        lo[j] = pj->grid_lo;
        hi[j] = pj->grid_lo + pj->grid_step * (double)(pj->grid_n - 1);
        if (pj->grid_n == 0 && ((free_mask >> j) & 1u)) {
            memset(g, 0, sizeof *g);
            return BF_EINVAL;
        }
    }
    return bf__grid_layout_range(type, fixed, free_mask, lo, hi, g);
}

int bf__grid_layout_range(const bf_model_type *type, const double *fixed,
                          unsigned mask, const double *lo, const double *hi,
                          bf__grid_layout_t *g)
{
    size_t j;
    memset(g, 0, sizeof *g);
    if (type == NULL || (type->p > 0 && fixed == NULL) ||
        type->p > BF_MAX_PARAMS || (mask >> type->p) != 0) {
        return BF_EINVAL;
    }
    g->points = 1;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        g->base[j] = fixed[j];
        if ((mask >> j) & 1u) {
            size_t i = g->n_free;
            double span = hi[j] - lo[j];
            if (pj->grid_n == 0 || !(pj->grid_step > 0.0) ||
                !(span >= 0.0) || !(lo[j] >= pj->min) ||
                !(hi[j] <= pj->max)) {
                return BF_EINVAL;
            }
            g->free[i] = j;
            g->lo[i] = lo[j];
            g->step[i] = pj->grid_step;
            /* points lo + step t <= hi; 1e-9 absorbs the rounding of the
             * span, so the paper's ranges give grid_n points */
            g->count[i] = (size_t)floor(span / pj->grid_step + 1e-9) + 1;
            if (g->count[i] > SIZE_MAX / g->points) {
                return BF_ENOMEM;
            }
            g->points *= g->count[i];
            g->n_free++;
        } else if (!isfinite(fixed[j]) || fixed[j] < pj->min ||
                   fixed[j] > pj->max) {
            return BF_EINVAL;
        }
    }
    g->mask = mask;
    return BF_OK;
}

void bf__grid_layout_coarsen(bf__grid_layout_t *g, size_t max)
{
    size_t i;
    for (i = 0; i < g->n_free; i++) {
        size_t s = (g->count[i] + max - 1) / max;
        g->points /= g->count[i];
        g->step[i] *= (double)s;
        g->count[i] = (g->count[i] - 1) / s + 1;
        g->points *= g->count[i];
    }
}

unsigned bf__grid_point(const bf__grid_layout_t *g, size_t idx,
                        double *param)
{
    unsigned bound = 0;
    size_t f = g->n_free;
    memcpy(param, g->base, sizeof g->base);
    while (f-- > 0) {
        size_t j = g->free[f];
        size_t i = idx % g->count[f];
        idx /= g->count[f];
        param[j] = g->lo[f] + g->step[f] * (double)i; /* SPEC §7.4 */
        if (i == 0 || i == g->count[f] - 1) {
            bound |= 1u << j;
        }
    }
    return bound;
}

/* ==== the plain path: the paper's search, one point at a time =========== */

int bf_fit_grid(const bf_model_type *type, const double *fixed,
                unsigned free_mask, size_t n, const bf_geom *geom,
                const double *data, bf_fit_workspace *w,
                bf_fit_result *result)
{
    bf__grid_layout_t g;
    bf__prep pm;
    double param[BF_MAX_PARAMS];
    double *lse = NULL;
    unsigned char *ok = NULL;
    void *work;
    void *own = NULL;
    size_t idx;
    size_t best;
    double best_lse;
    int rc;

    if (geom == NULL || data == NULL || w == NULL || result == NULL ||
        n == 0 || n > w->n) {
        return BF_EINVAL;
    }
    rc = bf__grid_layout(type, fixed, free_mask, &g);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__prep_plain(&pm, type, n, geom);
    if (rc == BF_OK) {
        rc = eval_work(w, type, &work, &own);
    }
    lse = malloc(g.points * sizeof *lse);
    ok = malloc(g.points);
    if (rc == BF_OK && (lse == NULL || ok == NULL)) {
        rc = BF_ENOMEM;
    }
    for (idx = 0; rc == BF_OK && idx < g.points; idx++) {
        bf__grid_point(&g, idx, param);
        /* undefined here: not a candidate */
        ok[idx] = bf__curve(&pm, param, work, w->curve) == BF_OK;
        lse[idx] = ok[idx] ? bf__sum_sq_diff(n, w->curve, data) : 0.0;
    }
    if (rc == BF_OK) {
        best_lse = bf__argmin(g.points, lse, ok, &best);
        rc = bf__grid_result(&g, best, best_lse, result);
    }
    free(lse);
    free(ok);
    free(own);
    return rc;
}

/* ==== precomputed grid (the study path) ================================= */

struct bf__grid {
    bf__grid_layout_t layout;
    size_t n;          /* configurations */
    size_t cols;       /* grid points padded to a multiple of the lanes */
    size_t stride;     /* row pitch of curves: cols plus one cache line, so
                          that rows do not all fall in one cache set */
    double *curves;    /* n x stride normalised curves, transposed */
    unsigned char *ok; /* cols flags: 1 where the curve is defined */
};

/* Fills gr's curves one grid point at a time through the engine (models
 * without a block kernel: ON, LAMBERT, WNO, WNO-R, other free masks),
 * BF__GRID_BLOCK points into buf before they are stored. */
static int curves_by_point(bf__grid *gr, const bf__prep *pm)
{
    double param[BF_MAX_PARAMS];
    double *buf = malloc(BF__GRID_BLOCK * gr->n * sizeof *buf);
    void *work = bf__work_alloc(pm);
    size_t idx0;
    if (buf == NULL || work == NULL) {
        free(buf);
        free(work);
        return BF_ENOMEM;
    }
    for (idx0 = 0; idx0 < gr->layout.points; idx0 += BF__GRID_BLOCK) {
        size_t nb = gr->layout.points - idx0;
        size_t b;
        size_t k;
        nb = nb < BF__GRID_BLOCK ? nb : BF__GRID_BLOCK;
        for (b = 0; b < nb; b++) {
            bf__grid_point(&gr->layout, idx0 + b, param);
            gr->ok[idx0 + b] =
                bf__curve(pm, param, work, buf + (b * gr->n)) == BF_OK;
        }
        for (k = 0; k < gr->n; k++) {
            double *row = gr->curves + (k * gr->stride) + idx0;
            for (b = 0; b < nb; b++) {
                row[b] = buf[(b * gr->n) + k];
            }
        }
    }
    free(buf);
    free(work);
    return BF_OK;
}

bf__grid *bf__grid_make(const bf__prep *pm, const bf__grid_layout_t *lay,
                        int *status)
{
    bf__grid *gr = NULL;
    size_t bytes;
    size_t n = pm->n;
    int rc;

    gr = calloc(1, sizeof *gr);
    if (gr == NULL) {
        rc = BF_ENOMEM;
        goto fail;
    }
    gr->layout = *lay;
    gr->n = n;
    gr->cols = (lay->points + BF__SCORE_LANES - 1) / BF__SCORE_LANES *
               BF__SCORE_LANES;
    gr->stride = gr->cols + BF__ROW_PAD;
    if (gr->cols < lay->points ||
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
    rc = bf__curves_fast(pm, lay, gr->cols, gr->stride, gr->curves, gr->ok);
    if (rc < 0) {
        rc = -rc;
        goto fail;
    }
    if (rc == 0) {
        memset(gr->curves, 0, bytes); /* padding lanes stay defined */
        rc = curves_by_point(gr, pm);
        if (rc != BF_OK) {
            goto fail;
        }
    }
    if (status != NULL) {
        *status = BF_OK;
    }
    return gr;

fail:
    bf__grid_free(gr);
    if (status != NULL) {
        *status = rc;
    }
    return NULL;
}

bf__grid *bf__grid_build(const bf_model_type *type, const double *fixed,
                         unsigned free_mask, const bf__cset *cs, int *status)
{
    bf__grid_layout_t lay;
    bf__prep pm;
    bf__grid *gr = NULL;
    int rc = bf__grid_layout(type, fixed, free_mask, &lay);
    if (rc == BF_OK) {
        rc = bf__prep_init(&pm, type, cs);
        if (rc == BF_OK) {
            gr = bf__grid_make(&pm, &lay, &rc);
        }
        bf__prep_free(&pm);
    }
    if (status != NULL) {
        *status = rc;
    }
    return gr;
}

bf__grid *bf__grid_alloc(const bf_model_type *type, const double *fixed,
                         unsigned free_mask, size_t n, const bf_geom *geom,
                         int *status)
{
    bf__cset cs;
    bf__grid *gr = NULL;
    int rc = bf__geom_check(n, geom);
    if (rc == BF_OK) {
        rc = bf__cset_init(&cs, n, geom);
    }
    if (rc == BF_OK) {
        gr = bf__grid_build(type, fixed, free_mask, &cs, &rc);
        bf__cset_free(&cs);
    }
    if (status != NULL) {
        *status = rc;
    }
    return gr;
}

void bf__grid_free(bf__grid *gr)
{
    if (gr == NULL) {
        return;
    }
    free(gr->curves);
    free(gr->ok);
    free(gr);
}

size_t bf__grid_points(const bf__grid *gr)
{
    return gr->layout.points;
}

size_t bf__grid_cols(const bf__grid *gr)
{
    return gr->cols;
}

const bf__grid_layout_t *bf__grid_lay(const bf__grid *gr)
{
    return &gr->layout;
}

const unsigned char *bf__grid_ok(const bf__grid *gr)
{
    return gr->ok;
}

void bf__grid_score(const bf__grid *gr, size_t n_samples,
                    const double *const *data, double *lse)
{
    bf__score_all(gr->n, gr->cols, gr->stride, gr->curves, n_samples, data,
                  lse);
}

void bf__grid_score_weights(const bf__grid *gr, const double *data,
                            const double *cw, size_t n_w,
                            const double *const *w, double *lse)
{
    bf__score_weights(gr->n, gr->cols, gr->stride, gr->curves, data, cw,
                      n_w, w, lse);
}

int bf__grid_weights_argmin(const bf__grid *gr, const double *data,
                            const double *cw, size_t n_w,
                            const double *const *w, bf_fit_result *results)
{
    double *lse = malloc((n_w + 1) * sizeof *lse);
    size_t *best = malloc((n_w + 1) * sizeof *best);
    size_t b;
    int rc = BF_OK;
    if (lse == NULL || best == NULL) {
        free(lse);
        free(best);
        return BF_ENOMEM;
    }
    rc = bf__weights_argmin(gr->n, gr->cols, gr->stride, gr->curves, gr->ok,
                            gr->layout.points, data, cw, n_w, w, lse, best);
    for (b = 0; rc == BF_OK && b < n_w; b++) {
        if (bf__grid_result(&gr->layout, best[b], lse[b], &results[b]) !=
            BF_OK) {
            memset(&results[b], 0, sizeof results[b]);
            results[b].lse = NAN; /* no defined point: BF_EDOM's result */
            results[b].n_eval = gr->layout.points;
        }
    }
    free(lse);
    free(best);
    return rc;
}

void bf__grid_score_folds(const bf__grid *gr, const double *data,
                          const double *cw, const size_t *fold, size_t folds,
                          double *lse)
{
    bf__score_folds(gr->n, gr->cols, gr->stride, gr->curves, data, cw, fold,
                    folds, lse);
}

int bf__grid_folds_argmin(const bf__grid *gr, size_t n_data,
                          const double *const *data, const double *cw,
                          const size_t *fold, size_t folds,
                          bf_fit_result *results)
{
    size_t total = n_data * (folds + 1);
    double *lse = malloc((total + 1) * sizeof *lse);
    size_t *best = malloc((total + 1) * sizeof *best);
    size_t q;
    int rc = BF_OK;
    if (lse == NULL || best == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    rc = bf__folds_argmin(gr->n, gr->cols, gr->stride, gr->curves, gr->ok,
                          gr->layout.points, n_data, data, cw, fold, folds,
                          lse, best);
    if (rc != BF_OK) {
        goto done;
    }
    for (q = 0; q < total; q++) {
        if (bf__grid_result(&gr->layout, best[q], lse[q], &results[q]) !=
            BF_OK) {
            results[q].lse = NAN; /* no defined point */
        }
    }
done:
    free(lse);
    free(best);
    return rc;
}

const double *bf__grid_curve_row(const bf__grid *gr, size_t k,
                                 size_t *stride)
{
    *stride = gr->stride;
    return gr->curves + k * gr->stride;
}

void bf__grid_curves(const bf__grid *gr, size_t idx0, size_t nb,
                     double *curves)
{
    size_t k;
    size_t b;
    for (k = 0; k < gr->n; k++) {
        const double *row = gr->curves + (k * gr->stride) + idx0;
        for (b = 0; b < nb; b++) {
            curves[(b * gr->n) + k] = row[b];
        }
    }
}

int bf__grid_result(const bf__grid_layout_t *g, size_t best, double best_lse,
                    bf_fit_result *result)
{
    memset(result, 0, sizeof *result);
    result->n_eval = g->points;
    if (best == SIZE_MAX) {
        return BF_EDOM;
    }
    result->bound_hit = bf__grid_point(g, best, result->param);
    result->lse = best_lse;
    return BF_OK;
}

int bf__grid_best(const bf__grid *gr, const double *lse,
                  bf_fit_result *result)
{
    size_t best;
    double best_lse = bf__argmin(gr->layout.points, lse, gr->ok, &best);
    return bf__grid_result(&gr->layout, best, best_lse, result);
}

int bf__grid_fit(const bf__grid *gr, const double *data, bf_fit_result *result)
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
 * §7.5: ON at the tabulated rho, sigma) through the engine: the geometry
 * terms (ON's) once for all samples; the values, bf_normalise and the LSE
 * are the plain path's operations, so the results are bit for bit those of
 * bf_fit_grid. */
struct bf__fixed_model {
    bf__prep pm;
    void *work;
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

bf__fixed_model *bf__fixed_alloc(const bf_model_type *type,
                                 const bf__cset *cs)
{
    bf__fixed_model *fm = calloc(1, sizeof *fm);
    if (fm == NULL) {
        return NULL;
    }
    if (bf__prep_init(&fm->pm, type, cs) != BF_OK) {
        bf__fixed_free(fm);
        return NULL;
    }
    fm->work = bf__work_alloc(&fm->pm);
    fm->curve = malloc(cs->n * sizeof *fm->curve);
    if (fm->work == NULL || fm->curve == NULL) {
        bf__fixed_free(fm);
        return NULL;
    }
    return fm;
}

int bf__fixed_fit(const bf__fixed_model *fm, const double *fixed,
                  const double *data, bf_fit_result *result)
{
    bf__grid_layout_t g;
    int rc = bf__grid_layout(fm->pm.type, fixed, 0, &g);
    memset(result, 0, sizeof *result);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__curve(&fm->pm, g.base, fm->work, fm->curve);
    result->n_eval = 1;
    if (rc != BF_OK) {
        return BF_EDOM; /* as bf_fit_grid: no defined grid point */
    }
    result->bound_hit = bf__grid_point(&g, 0, result->param);
    result->lse = bf__sum_sq_diff(fm->pm.n, fm->curve, data);
    return BF_OK;
}

void bf__fixed_free(bf__fixed_model *fm)
{
    if (fm == NULL) {
        return;
    }
    bf__prep_free(&fm->pm);
    free(fm->work);
    free(fm->curve);
    free(fm);
}
