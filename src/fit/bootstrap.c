/* bootstrap.c: the residual bootstrap under a fit's noise model
 * (doc/methods.md §3): replicate data from the fitted curve plus
 * residuals drawn from the fit's standardised residuals, refitted by
 * maximum likelihood with the scale profiled, as the intervals'
 * likelihood is.
 *
 * [1] A. C. Davison, D. V. Hinkley, "Bootstrap Methods and their
 *     Application", CUP 1997, §6.2.3 and algorithm 6.3 (resampling
 *     modified residuals: e_k / sqrt(1 - h_k), centred), §6.3 (nonlinear
 *     and weighted regression: residuals standardised by the variance
 *     function), §5.2 (percentile intervals).
 * [2] src/fit/noise.c: D_k = s L_k(theta) + e_k, var e_k = sigma^2 v_k,
 *     v_k = max(L_k, f)^p.
 * [3] C. F. J. Wu, "Jackknife, bootstrap and other resampling methods in
 *     regression analysis", Ann. Statist. 14 (1986) 1261-1295 (the wild
 *     bootstrap, e*_k = e_k eta_k: measured here and not kept, below).
 *
 * Equations: with theta^ the maximum-likelihood estimate under the noise
 * model (bf_interval.ml, power p), s^ its profiled scale,
 * e_k = D_k - s^ L_k(theta^) the residuals and h_k the leverages of the
 * linearised weighted fit (leverage.c),
 *   u_k   = e_k / (sqrt(v_k) sqrt(1 - h_k)),  u_k -= mean(u)        [1]
 *   D*_bk = s^ L_k(theta^) + sqrt(v_k) u_J,   J uniform on 1..n     [1]
 * replicate b's estimate maximises the likelihood [2] of D*_b at the same
 * p with the scale profiled (refined from theta^); the interval is the
 * (1 -+ level)/2 quantiles [q_lo, q_hi] of the B estimates, the order
 * statistics of rank (B + 1)(1 -+ level)/2 [1] §5.2 (order_stat).
 * The value that sets the data's normalisation is as noisy in every
 * replicate as it is in the data (the scale is a parameter, no
 * configuration is special), which resampling configurations cannot give
 * (issue 18). Measured and not kept (doc/methods.md §3): the wild
 * bootstrap [3] (each residual with a random sign) estimates each
 * configuration's variance from its one residual, so its intervals vary
 * from one data set to the next and cover less (LFTG's n_d on 66
 * configurations 0.72, VH-E 0.90 of 200); the basic interval
 * 2 theta^ - [q_hi, q_lo] turns a bound's skew the wrong way (FC-E's n
 * 0.77 of 200).
 */
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* A gap between replicate estimates wider than this share of the interval
 * splits it (is_split). */
#define SPLIT_GAP 0.25

/* 1 when the sorted estimates e[0..m) fall into separate groups inside
 * the interval [low, high]: a gap wider than SPLIT_GAP of it with at least
 * the interval's tail share (1 - level)/2 of the replicates on either
 * side -- replicates whose optima lie in different basins of the
 * likelihood, so the percentile interval spans both (doc/methods.md §3). */
static int is_split(const double *e, size_t m, double low, double high,
                    double level)
{
    size_t tail = (size_t)ceil(0.5 * (1.0 - level) * (double)m);
    size_t i;
    for (i = 1; i < m; i++) {
        if (e[i - 1] >= low && e[i] <= high && i >= tail && m - i >= tail &&
            e[i] - e[i - 1] > SPLIT_GAP * (high - low)) {
            return 1;
        }
    }
    return 0;
}

/* The a-quantile of the sorted replicate estimates e[0..m): the order
 * statistic of rank (m + 1) a, interpolated between its neighbours when
 * the rank is not whole, within [1, m] [1] §5.2. The rule
 * (m - 1) a + 1 of sample quantiles puts the 2.5 % point of 99 replicates
 * at rank 3.45, where a normal sample's expected value is -1.87 sd, not
 * -1.96: intervals 5 % short; rank (m + 1) a is 2.5 there and exactly 5
 * for m = 199, 25 for 999. */
static double order_stat(const double *e, size_t m, double a)
{
    double r = (double)(m + 1) * a;
    size_t i;
    double f;
    r = r < 1.0 ? 1.0 : (r > (double)m ? (double)m : r);
    i = (size_t)floor(r);
    f = r - (double)i;
    return i >= m ? e[m - 1] : e[i - 1] + f * (e[i] - e[i - 1]);
}

/* The percentile interval of each free parameter from e (parameter-major,
 * used of n_boot per parameter; sorted on return). */
static void percentiles(const bf_problem *pb, double *e, size_t n_boot,
                        size_t used, double level, double *low, double *high,
                        unsigned *split)
{
    size_t j;
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        double *ej = e + j * n_boot;
        double qlo;
        double qhi;
        low[j] = NAN;
        high[j] = NAN;
        if (j >= pb->type->p || !((pb->free_mask >> j) & 1u) || used < 2) {
            continue;
        }
        gsl_sort(ej, 1, used);
        qlo = order_stat(ej, used, 0.5 * (1.0 - level));
        qhi = order_stat(ej, used, 0.5 * (1.0 + level));
        if (split != NULL && is_split(ej, used, qlo, qhi, level)) {
            *split |= 1u << j;
        }
        low[j] = qlo;
        high[j] = qhi;
    }
}

int bf__bootstrap(bf__fitctx *fc, const bf_interval *iv, size_t n_boot,
                  unsigned long seed, double level, double *est,
                  size_t *n_est, double *low, double *high, unsigned *split)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double *fit = malloc((8 + BF_MAX_PARAMS) * n * sizeof *fit);
    double *own = est == NULL ? malloc(n_boot * BF_MAX_PARAMS * sizeof *own)
                              : NULL;
    double *e = est != NULL ? est : own;
    double *resid = fit == NULL ? NULL : fit + n;
    double *d = fit == NULL ? NULL : fit + 2 * n;
    double *lev = fit == NULL ? NULL : fit + 3 * n;
    double *t1 = fit == NULL ? NULL : fit + 4 * n;
    double *sdv = fit == NULL ? NULL : fit + 5 * n;
    double *z = fit == NULL ? NULL : fit + 6 * n; /* n x (free + 1) */
    double *wlik = fit == NULL ? NULL : fit + (7 + BF_MAX_PARAMS) * n;
    int spec = pb->type->kind == BF_MODEL_SPECULAR;
    double top = 1.0; /* the mean's maximum (specular models) */
    double mean = 0.0;
    bf_problem rep = *pb;
    bf_fit_result start;
    size_t used = 0;
    size_t b;
    size_t i;
    int rc = BF_OK;

    if (split != NULL) {
        *split = 0;
    }
    for (i = 0; i < BF_MAX_PARAMS; i++) {
        low[i] = NAN;
        high[i] = NAN;
    }
    if (rng == NULL || fit == NULL || e == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    if (iv->method != BF_CI_PROFILE_LIK || !isfinite(iv->scale) ||
        !(n > bf_problem_nfree(pb) + 1)) {
        rc = BF_EDOM; /* no noise model fitted (bf__intervals) */
        goto done;
    }
    rep.objective = BF__OBJ_LIK; /* [4], at the fitted power */
    rep.noise_power = iv->noise_power;
    rep.data = d;
    if (spec) { /* its likelihood: weights held at the fit (noise.c) */
        rep.objective = BF_OBJ_NGAN;
        rep.weight = wlik;
        rc = bf__spec_weights(fc, iv->ml.param, iv->noise_power, wlik,
                              &top);
    }
    if (rc == BF_OK) {
        rc = bf__curve(fc->pm, iv->ml.param, fc->work, fit);
    }
    if (rc == BF_OK) {
        rc = bf__leverages(fc, iv->ml.param, iv->scale, iv->noise_power,
                           fit, top, z, d, t1, lev);
    }
    for (i = 0; rc == BF_OK && i < n; i++) { /* [1] alg. 6.3 */
        double l = fit[i] / top > BF_LOG_FLOOR ? fit[i] / top : BF_LOG_FLOOR;
        double r = pb->data[i] - iv->scale * fit[i];
        sdv[i] = pow(l, 0.5 * iv->noise_power); /* sqrt(v_i) */
        fit[i] *= iv->scale;
        resid[i] = (lev[i] < 1.0 ? r / sqrt(1.0 - lev[i]) : r) / sdv[i];
        mean += resid[i] / (double)n;
    }
    for (i = 0; rc == BF_OK && i < n; i++) {
        resid[i] -= mean; /* centred: E* e* = 0 */
    }
    gsl_rng_set(rng, seed);
    memset(&start, 0, sizeof start);
    memcpy(start.param, iv->ml.param, sizeof start.param);
    bf__fitctx_use(fc, &rep);
    for (b = 0; rc == BF_OK && b < n_boot; b++) {
        bf_fit_result r;
        int st;
        size_t j;
        for (i = 0; i < n; i++) { /* [1] alg. 6.3 */
            d[i] = fit[i] + sdv[i] * resid[gsl_rng_uniform_int(rng, n)];
        }
        if (spec) { /* the scales solved, the others refined */
            st = bf__varpro_refine(fc, start.param, &r);
        } else {
            st = bf__fit_value(fc, start.param, &start.lse);
            if (st == BF_OK) {
                st = bf__refine(fc, &start, &r);
                st = st == BF_ENOCONV ? BF_OK : st; /* the best point */
            }
        }
        if (st == BF_ENOMEM) {
            rc = st;
            break;
        }
        if (st != BF_OK) {
            continue; /* a replicate the model cannot fit: left out */
        }
        for (j = 0; j < BF_MAX_PARAMS; j++) {
            e[j * n_boot + used] = r.param[j];
        }
        used++;
    }
    bf__fitctx_use(fc, pb);
    if (rc == BF_OK) {
        percentiles(pb, e, n_boot, used, level, low, high, split);
        rc = used >= 2 ? BF_OK : BF_EDOM;
    }
    if (n_est != NULL) {
        *n_est = used;
    }
done:
    gsl_rng_free(rng);
    free(fit);
    free(own);
    return rc;
}

int bf_fit_bootstrap(const bf_problem *pb, const bf_interval *iv,
                     size_t n_boot, unsigned long seed, double level,
                     double *low, double *high)
{
    bf__solo so;
    int rc;
    if (pb == NULL || iv == NULL || low == NULL || high == NULL ||
        pb->type == NULL || pb->data == NULL || pb->weight != NULL ||
        n_boot < 2 || !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__bootstrap(&so.fc, iv, n_boot, seed, level, NULL, NULL, low,
                       high, NULL);
    bf__solo_free(&so);
    return rc;
}
