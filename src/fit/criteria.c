/* criteria.c: model selection -- information criteria and k-fold
 * cross-validation over configurations (doc/methods.md §4, §5).
 *
 * [1] H. Akaike, "A new look at the statistical model identification",
 *     IEEE TAC 19(6), 1974.
 * [2] G. Schwarz, "Estimating the dimension of a model", Ann. Stat. 6(2),
 *     1978.
 * [3] T. Hastie, R. Tibshirani, J. Friedman, "The Elements of Statistical
 *     Learning", 2nd ed., §7.10 (k-fold cross-validation).
 *
 * Equations (Gaussian errors of unknown variance, maximised likelihood;
 * the constant n (1 + ln 2 pi) common to all models is dropped):
 *   AIC = n ln(RSS/n) + 2k                                      [1]
 *   BIC = n ln(RSS/n) + k ln n                                  [2]
 *   CV  = sum over folds f, over k in f, of r_k(theta_-f)^2      [3]
 */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

double bf_criterion_aic(double rss, size_t n, size_t k)
{
    double dn = (double)n;
    return dn * log(rss / dn) + 2.0 * (double)k; /* [1] */
}

double bf_criterion_bic(double rss, size_t n, size_t k)
{
    double dn = (double)n;
    return dn * log(rss / dn) + (double)k * log(dn); /* [2] */
}

int bf_fit_cv_folds(size_t n, size_t folds, unsigned long seed, size_t *fold)
{
    gsl_rng *rng;
    size_t *perm;
    size_t p;
    if (fold == NULL || folds < 2 || folds > n) {
        return BF_EINVAL;
    }
    rng = gsl_rng_alloc(gsl_rng_mt19937);
    perm = malloc(n * sizeof *perm);
    if (rng == NULL || perm == NULL) {
        gsl_rng_free(rng);
        free(perm);
        return BF_ENOMEM;
    }
    gsl_rng_set(rng, seed);
    for (p = 0; p < n; p++) {
        perm[p] = p;
    }
    gsl_ran_shuffle(rng, perm, n, sizeof *perm);
    for (p = 0; p < n; p++) {
        fold[perm[p]] = p % folds;
    }
    gsl_rng_free(rng);
    free(perm);
    return BF_OK;
}

int bf__cv(bf__fitctx *fc, const bf__grid *gr, const size_t *fold,
           size_t folds, const bf_fit_result *fold_grid,
           const bf__vp_whole *whole, double *cv)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    double *w = malloc(n * sizeof *w);
    /* a specular model (SPEC §9): each fold fitted by its own separable
     * fit (varpro.c: grid, refinement) on the grid values the folds
     * share (bf__varpro_fold_grids), no stored grid */
    int spec = pb->type->kind == BF_MODEL_SPECULAR;
    bf_fit_result *g = fold_grid == NULL && !spec
                           ? malloc((folds + 1) * sizeof *g)
                           : NULL;
    double *resid = malloc(n * sizeof *resid);
    double *vals = NULL;         /* the folds' grid values computed here */
    const double *grid_vals = NULL; /* those, or the whole fit's */
    size_t points = 0;
    double sum = 0.0;
    size_t f;
    size_t k;
    int rc = BF_OK;

    if (w == NULL || resid == NULL ||
        (fold_grid == NULL && g == NULL && !spec)) {
        rc = BF_ENOMEM;
        goto done;
    }
    if (spec && whole != NULL && whole->vals != NULL) {
        grid_vals = whole->vals; /* from the whole fit's grid pass */
        points = whole->points;
    } else if (spec) {
        rc = bf__varpro_fold_grids(fc, fold, folds, &vals, &points);
        if (rc == BF_EINVAL) {
            rc = BF_OK; /* no grid to share: each fold its own fit */
        }
        grid_vals = vals;
    }
    if (fold_grid == NULL && !spec) { /* every fold's grid optimum */
        rc = bf__grid_optima_folds(gr, pb, fc->pm->cs->cti, fold, folds, g);
        fold_grid = g + 1;
    }
    for (f = 0; rc == BF_OK && f < folds; f++) {
        bf_problem train = *pb;
        bf_fit_result r;
        for (k = 0; k < n; k++) {
            w[k] = fold[k] == f ? 0.0 : 1.0; /* fit to the other folds */
        }
        train.weight = w;
        bf__fitctx_use(fc, &train);
        if (spec) {
            rc = grid_vals != NULL
                     ? bf__varpro_fit_grid(
                           fc, grid_vals + f * points,
                           whole != NULL ? &whole->minima : NULL, &r)
                     : bf__varpro_fit(fc, NULL, &r, NULL);
        } else {
            rc = isfinite(fold_grid[f].lse)
                     ? bf__refine(fc, &fold_grid[f], &r)
                     : BF_EDOM;
        }
        rc = rc == BF_ENOCONV ? BF_OK : rc;
        if (rc == BF_OK) {
            /* residuals under the training fit (its scale, for scale) */
            rc = bf__fit_residuals(fc, r.param, resid);
        }
        for (k = 0; rc == BF_OK && k < n; k++) {
            if (fold[k] == f) {
                sum += resid[k] * resid[k]; /* held out [3] */
            }
        }
    }
    bf__fitctx_use(fc, pb);
    *cv = rc == BF_OK ? sum : NAN;
done:
    free(w);
    free(g);
    free(resid);
    free(vals);
    return rc;
}

int bf_fit_cv(const bf_problem *pb, const bf_curves *curves, size_t folds,
              unsigned long seed, double *cv)
{
    bf__solo so;
    size_t *fold;
    int rc;
    if (bf__curves_check(curves, pb) != BF_OK || cv == NULL ||
        pb->weight != NULL || folds < 2 || folds > pb->n) {
        return BF_EINVAL;
    }
    fold = malloc(pb->n * sizeof *fold);
    if (fold == NULL) {
        return BF_ENOMEM;
    }
    rc = bf_fit_cv_folds(pb->n, folds, seed, fold);
    if (rc == BF_OK) {
        rc = bf__solo_init(&so, pb);
        if (rc == BF_OK) {
            rc = bf__cv(&so.fc, bf__curves_grid(curves), fold, folds, NULL,
                        NULL, cv);
            bf__solo_free(&so);
        }
    }
    free(fold);
    return rc;
}
