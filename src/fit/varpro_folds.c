/* varpro_folds.c: the grid values of every cross-validation fold of a
 * separable fit (SPEC §9.3, §10; doc/methods.md §5): at each grid point
 * the model once, every fold's scales and S from sums over the
 * configurations (the whole's minus the fold's), so that a fold's fit
 * (bf__varpro_fit_grid) starts from its own grid without evaluating the
 * model there again.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/varpro.h"

/* The grid of the separable fit of fc->pb: its points (0 where it has
 * none: dense data, a joint fit, not such a model). */
static size_t grid_points(bf__fitctx *fc, unsigned lin)
{
    const bf_problem *pb = fc->pb;
    bf__vp_space sp;
    size_t points = 1;
    size_t a;
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        pb->n > BF__DENSE_K || fc->blocks > 1) {
        return 0;
    }
    bf__vp_grid_init(&sp, fc, pb->free_mask & ~lin);
    for (a = 0; a < sp.m; a++) {
        points *= sp.count[a];
    }
    return points;
}

/* A fold's S from the whole's sums minus the fold's, in the normal
 * equations' form S = <R', R'> - 2 t.b + t'G t, has the rounding of its
 * terms taken at the whole's size (Cauchy-Schwarz bounds of the mixed
 * sums: |<c1, R'>| <= sqrt(<c1, c1> <R', R'>)); below FOLD_DIGITS of that
 * size the fold's S is summed directly instead (a lobe whose values run
 * to 1e139 at a grid point: one held-out configuration's term is nearly
 * the whole's, and the training sums cancel to nothing). */
#define FOLD_DIGITS 1e-4

/* S = <R', R'> - 2 t.b + t'G t of the scales t (R' = R - c0) from the
 * training normal equations ne and rr = <R', R'>; NAN when it is below
 * FOLD_DIGITS of its terms' size in the whole's sums all (g11 g12 g22 b1
 * b2 rr). */
static double sse_normal(const bf__vp_normal *ne, double rr, const double *t,
                         const double *all)
{
    double s1 = sqrt(all[0] * all[5]);
    double s2 = sqrt(all[2] * all[5]);
    double size = all[5] + 2.0 * (fabs(t[0]) * s1 + fabs(t[1]) * s2) +
                  t[0] * t[0] * all[0] +
                  2.0 * fabs(t[0] * t[1]) * sqrt(all[0] * all[2]) +
                  t[1] * t[1] * all[2];
    double v = rr - 2.0 * (t[0] * ne->b1 + t[1] * ne->b2) +
               t[0] * t[0] * ne->g11 + 2.0 * t[0] * t[1] * ne->g12 +
               t[1] * t[1] * ne->g22;
    return v >= FOLD_DIGITS * size && isfinite(size) ? v : NAN;
}

/* Every fold's ngan value at the point whose curve parts fc holds (the
 * columns c0, c1, c2 of n_l scales, or with none the curve as c0; with hg
 * a homogeneous lobe's, c0 one more scaled column: bf__vp_grid_value): the
 * fold's training configurations (weight 1 off the fold, 0 on it) in the
 * normal equations and S, from one pass's sums per held-out fold (the
 * training sums: the whole's minus the fold's; mom: 6 (folds + 1)
 * doubles); into out[f * stride], NAN where S cancels (sse_normal). */
static void fold_values(const bf__fitctx *fc, size_t n_l, const double *hi,
                        int hg, const size_t *fold, size_t folds,
                        double *mom, double *out, size_t stride)
{
    const size_t n = fc->pm->n;
    const double *data = fc->pb->data;
    const double *c0 = n_l > 0 ? fc->cols : fc->curve;
    const double *c1 = fc->cols + n;
    const double *c2 = fc->cols + 2 * n;
    double *all = mom + 6 * folds;
    size_t f;
    size_t k;
    size_t q;
    if (hg) { /* the lobe c0 scaled too: columns (c1, c0) or (c0) */
        c2 = n_l > 0 ? fc->cols : NULL;
        c1 = n_l > 0 ? c1 : fc->cols;
        c0 = NULL;
        n_l++;
    }
    memset(mom, 0, 6 * (folds + 1) * sizeof *mom);
    for (k = 0; k < n; k++) { /* g11 g12 g22 b1 b2 rr of each fold */
        double *m = mom + 6 * fold[k];
        double r = data[k] - (c0 != NULL ? c0[k] : 0.0);
        if (n_l > 0) {
            m[0] += c1[k] * c1[k];
            m[3] += c1[k] * r;
        }
        if (n_l > 1) {
            m[1] += c1[k] * c2[k];
            m[2] += c2[k] * c2[k];
            m[4] += c2[k] * r;
        }
        m[5] += r * r;
    }
    for (f = 0; f < folds; f++) {
        for (q = 0; q < 6; q++) {
            all[q] += mom[6 * f + q];
        }
    }
    for (f = 0; f < folds; f++) {
        const double *m = mom + 6 * f;
        bf__vp_normal ne;
        double t[BF__VP_MAX_LIN] = {0.0, 0.0};
        double v;
        ne.g11 = all[0] - m[0];
        ne.g12 = all[1] - m[1];
        ne.g22 = all[2] - m[2];
        ne.b1 = all[3] - m[3];
        ne.b2 = all[4] - m[4];
        if (n_l > 0 && !bf__vp_nnls_solve(&ne, n_l > 1, hi, t)) {
            /* one scale at 0: the better of the two one-column optima */
            double t1[BF__VP_MAX_LIN] = {t[0], 0.0};
            double t2[BF__VP_MAX_LIN] = {0.0, t[1]};
            double v1 = sse_normal(&ne, all[5] - m[5], t1, all);
            double v2 = sse_normal(&ne, all[5] - m[5], t2, all);
            v = isnan(v1) || isnan(v2) ? NAN : fmin(v1, v2);
        } else {
            v = sse_normal(&ne, all[5] - m[5], t, all);
        }
        out[f * stride] = v;
    }
}

int bf__vp_foldpass_init(bf__vp_foldpass *fp, bf__fitctx *fc,
                         const size_t *fold, size_t folds)
{
    const bf_problem *pb = fc->pb;
    unsigned lin = bf__varpro_lin(pb);
    size_t j;
    memset(fp, 0, sizeof *fp);
    fp->fold = fold;
    fp->folds = folds;
    fp->points = grid_points(fc, lin);
    for (j = 0; j < pb->type->p; j++) { /* the scales and their bounds */
        if ((lin >> j) & 1u) {
            if (fp->n_lin < BF__VP_MAX_LIN) {
                fp->hi[fp->n_lin] = pb->hi[j];
            }
            fp->n_lin++;
        }
    }
    if (fp->points == 0 || fp->n_lin > BF__VP_MAX_LIN ||
        !bf_objective_keeps_scale(pb->objective) || fold == NULL ||
        folds == 0) {
        return BF_EINVAL;
    }
    fp->vals = malloc(folds * fp->points * sizeof *fp->vals);
    fp->mom = malloc((6 * (folds + 1) + pb->n) * sizeof *fp->mom);
    if (fp->vals == NULL || fp->mom == NULL) {
        bf__vp_foldpass_free(fp);
        return BF_ENOMEM;
    }
    fp->whole = *pb;
    fp->whole.objective = BF_OBJ_NGAN;
    fp->whole.weight = NULL;
    return BF_OK;
}

void bf__vp_foldpass_point(bf__vp_foldpass *fp, bf__fitctx *fc,
                           const bf__vp_space *gs, size_t g,
                           const double *x, int defined)
{
    const bf_problem *keep = fc->pb;
    double hi[BF__VP_MAX_LIN + 1];
    double *w = fp->mom + 6 * (fp->folds + 1);
    size_t f;
    if (!defined) {
        for (f = 0; f < fp->folds; f++) {
            fp->vals[f * fp->points + g] = BF__VP_UNDEFINED;
        }
        return;
    }
    memcpy(hi, fp->hi, sizeof hi);
    if (gs->hg) {
        hi[fp->n_lin] = HUGE_VAL; /* the lobe's size (varpro_scales.c) */
    }
    fold_values(fc, fp->n_lin, hi, gs->hg, fp->fold, fp->folds, fp->mom,
                fp->vals + g, fp->points);
    for (f = 0; f < fp->folds; f++) {
        bf_problem train = fp->whole;
        size_t k;
        if (!isnan(fp->vals[f * fp->points + g])) {
            continue;
        }
        for (k = 0; k < train.n; k++) {
            w[k] = fp->fold[k] == f ? 0.0 : 1.0;
        }
        train.weight = w;
        bf__fitctx_use(fc, &train);
        fp->vals[f * fp->points + g] = bf__vp_grid_value(gs, x, NULL);
        bf__fitctx_use(fc, keep);
    }
}

void bf__vp_foldpass_free(bf__vp_foldpass *fp)
{
    free(fp->vals);
    free(fp->mom);
    fp->vals = NULL;
    fp->mom = NULL;
}

int bf__varpro_fold_grids(bf__fitctx *fc, const size_t *fold, size_t folds,
                          double **vals, size_t *n_points)
{
    const bf_problem *pb = fc->pb;
    bf__vp_foldpass fp;
    bf__vp_space sp;
    size_t g;
    int rc = bf__vp_foldpass_init(&fp, fc, fold, folds);
    *vals = NULL;
    *n_points = fp.points;
    if (rc != BF_OK) {
        return rc;
    }
    bf__fitctx_use(fc, &fp.whole);
    fc->lin_mask = bf__varpro_lin(pb);
    bf__vp_grid_init(&sp, fc, pb->free_mask & ~fc->lin_mask);
    /* point by point: the model once (its columns), every fold's scales
     * and S from sums over the configurations (fold_values), summed
     * directly where they cancel (bf__varpro_value keeps the columns) */
    for (g = 0; g < fp.points; g++) {
        double x[BF_MAX_PARAMS];
        bf__vp_point_of(&sp, g, x);
        bf__vp_foldpass_point(
            &fp, fc, &sp, g, x,
            bf__vp_grid_value(&sp, x, NULL) < BF__VP_UNDEFINED);
    }
    *vals = fp.vals;
    fp.vals = NULL;
    bf__vp_foldpass_free(&fp);
    bf__fitctx_use(fc, pb);
    fc->lin_mask = 0;
    return BF_OK;
}
