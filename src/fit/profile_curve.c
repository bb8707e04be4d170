/* profile_curve.c: the profile of a fit's criterion along one parameter,
 * as a curve -- what a profile interval (profile.c, intervals.c,
 * doc/methods.md §3) thresholds, for drawing it: the objective's own, or
 * the noise model's likelihood that the reported intervals take.
 *
 * [1] Y. Pawitan, "In All Likelihood", OUP 2001, §9.2 (profile likelihood).
 * [2] D. M. Bates, D. G. Watts, "Nonlinear Regression Analysis and Its
 *     Applications", Wiley 1988, §6.1.2 (the F form of the threshold).
 *
 * Equation (doc/methods.md §3, Gaussian errors of unknown variance):
 *   D(theta_j) = n ln(S_p(theta_j) / S_min),  S_p(theta_j) = min over the
 *   other free parameters of S, n the sum of the weights;
 *   the 95% interval is { theta_j : D <= chi2_1(0.95) = 3.841 } under the
 *   objective [1], { theta_j : D <= n ln(1 + F_{1,nu}(0.95) / nu) } under
 *   the likelihood, nu = n - k [2].
 */
#include <math.h>
#include <stdlib.h>

#include "fit/engine.h"

/* The valid arguments of a profile curve of pb along j. */
static int curve_args(const bf_problem *pb, const bf_fit_result *best,
                      size_t j, size_t n, const double *theta,
                      const double *dev)
{
    size_t i;
    if (pb == NULL || best == NULL || pb->type == NULL || j >= pb->type->p ||
        !((pb->free_mask >> j) & 1u) || (n > 0 && (theta == NULL ||
                                                   dev == NULL))) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (!(theta[i] >= pb->lo[j] && theta[i] <= pb->hi[j]) ||
            (i > 0 && !(theta[i] > theta[i - 1]))) {
            return 0; /* outside the search range, or not increasing */
        }
    }
    return 1;
}

/* bf_fit_profile_curve for valid arguments: the intervals' inner fits
 * (bf__profile_curve, profile.c) on one engine for the whole curve. */
static int curve(const bf_problem *pb, const bf_fit_result *best, size_t j,
                 size_t n, const double *theta, double *dev)
{
    bf__solo so;
    int rc = bf__solo_init(&so, pb);
    if (rc == BF_OK) {
        rc = bf__profile_curve(&so.fc, best, j, n, theta, dev);
        bf__solo_free(&so);
    }
    return rc;
}

int bf_fit_profile_curve(const bf_problem *pb, const bf_fit_result *best,
                         size_t j, size_t n, const double *theta,
                         double *dev)
{
    return curve_args(pb, best, j, n, theta, dev)
               ? curve(pb, best, j, n, theta, dev)
               : BF_EINVAL;
}

int bf__interval_curves(const bf_problem *pb, const bf_fit_result *best,
                        bf_noise noise, double level, unsigned mask, size_t n,
                        const double *theta, double *dev, double *thr,
                        bf_interval *iv)
{
    bf__solo so;
    bf_problem lik;
    bf_interval own;
    double t = NAN;
    double *w = malloc((pb->n + 1) * sizeof *w);
    size_t j;
    size_t k;
    size_t q = 0;
    int engine = 0;
    int rc = BF_OK;
    for (j = 0; j < pb->type->p; j++) {
        if (!((mask >> j) & 1u)) {
            continue;
        }
        if (!curve_args(pb, best, j, n, theta + q * n, dev + q * n)) {
            rc = BF_EINVAL;
        }
        for (k = 0; k < n; k++) {
            dev[q * n + k] = NAN;
        }
        q++;
    }
    q = 0;
    if (iv == NULL) {
        iv = &own;
    }
    if (rc == BF_OK) {
        rc = w == NULL ? BF_ENOMEM : bf__solo_init(&so, pb);
        engine = rc == BF_OK;
    }
    if (rc == BF_OK) {
        rc = bf__interval_problem(&so.fc, best, noise, level, w, iv, &lik,
                                  &t);
    }
    if (rc == BF_OK) { /* one engine for every curve, as bf__intervals */
        bf__fitctx_use(&so.fc, &lik);
    }
    for (j = 0; j < pb->type->p; j++) {
        if (!((mask >> j) & 1u)) {
            continue;
        }
        /* the threshold parameter j's interval takes (intervals.c) */
        thr[q] = rc == BF_OK && isfinite(iv->robust[j]) ? t * iv->robust[j]
                                                         : t;
        if (rc == BF_OK) { /* around the estimate the intervals are about */
            rc = bf__profile_curve(&so.fc, &iv->ml, j, n, theta + q * n,
                                   dev + q * n);
        }
        q++;
    }
    if (engine) {
        bf__solo_free(&so);
    }
    free(w);
    return rc;
}

int bf_fit_interval_curve(const bf_problem *pb, const bf_fit_result *best,
                          bf_noise noise, double level, size_t j, size_t n,
                          const double *theta, double *dev, double *thr,
                          bf_interval *iv)
{
    if (!curve_args(pb, best, j, n, theta, dev) || pb->data == NULL ||
        thr == NULL || bf_noise_name(noise) == NULL ||
        !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    return bf__interval_curves(pb, best, noise, level, 1u << j, n, theta,
                               dev, thr, iv);
}
