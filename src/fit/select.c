/* select.c: model selection -- information criteria and k-fold
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

double bf_aic(double rss, size_t n, size_t k)
{
    double dn = (double)n;
    return dn * log(rss / dn) + 2.0 * (double)k; /* [1] */
}

double bf_bic(double rss, size_t n, size_t k)
{
    double dn = (double)n;
    return dn * log(rss / dn) + (double)k * log(dn); /* [2] */
}

int bf_cv_folds(size_t n, size_t folds, unsigned long seed, size_t *fold)
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

int bf__cv(bf__fitctx *fc, const bf_grid *gr, size_t folds,
           unsigned long seed, double *cv)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    size_t *fold = malloc(n * sizeof *fold);
    double *w = malloc(folds * n * sizeof *w);
    const double **wp = malloc(folds * sizeof *wp);
    bf_fit_result *g = malloc(folds * sizeof *g);
    double *resid = malloc(n * sizeof *resid);
    double sum = 0.0;
    size_t f;
    size_t k;
    int rc;

    if (fold == NULL || w == NULL || wp == NULL || g == NULL ||
        resid == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    rc = bf_cv_folds(n, folds, seed, fold);
    for (f = 0; rc == BF_OK && f < folds; f++) {
        for (k = 0; k < n; k++) {
            w[f * n + k] = fold[k] == f ? 0.0 : 1.0; /* the other folds */
        }
        wp[f] = w + f * n;
    }
    if (rc == BF_OK) { /* every fold's grid optimum from the same curves */
        rc = bf__grid_optima(gr, pb, fc->pm->cs->cti, folds, wp, g);
    }
    for (f = 0; rc == BF_OK && f < folds; f++) {
        bf_problem train = *pb;
        bf_fit_result r;
        train.weight = wp[f];
        bf__fitctx_use(fc, &train);
        rc = isfinite(g[f].lse) ? bf__refine(fc, &g[f], &r) : BF_EDOM;
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
    free(fold);
    free(w);
    free(wp);
    free(g);
    free(resid);
    return rc;
}

int bf_fit_cv(const bf_problem *pb, const bf_curves *curves, size_t folds,
              unsigned long seed, double *cv)
{
    bf__solo so;
    int rc;
    if (bf__curves_check(curves, pb) != BF_OK || cv == NULL ||
        pb->weight != NULL || folds < 2 || folds > pb->n) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__cv(&so.fc, bf__curves_grid(curves), folds, seed, cv);
    bf__solo_free(&so);
    return rc;
}
