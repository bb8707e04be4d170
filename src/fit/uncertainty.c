/* uncertainty.c: 95% (or any level) intervals for fitted parameters -- the
 * profile of the objective and a percentile bootstrap over configurations
 * (doc/methods.md §3).
 *
 * [1] Y. Pawitan, "In All Likelihood", OUP 2001, §2.6 and §9.2 (profile
 *     likelihood intervals; Wilks' theorem).
 * [2] B. Efron, R. J. Tibshirani, "An Introduction to the Bootstrap",
 *     Chapman & Hall 1993, ch. 9 (bootstrapping regression by resampling
 *     pairs) and ch. 13 (percentile intervals).
 *
 * Equations (Gaussian errors of unknown variance, n configurations):
 *   -2 ln Lambda(theta_j) = n ln(S_p(theta_j) / S_min)       [1] §9.2
 *   interval: { theta_j : n ln(S_p / S_min) <= chi2_1(level) }  (3.841 at
 *   95%), S_p(theta_j) = min over the other free parameters of S.
 *   bootstrap: quantiles (1 - level)/2 and (1 + level)/2 of the estimates
 *   fitted to B resamples of the configurations.                [2]
 */
#include <float.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* Absolute tolerance of the interval ends (parameter units). */
#define CI_TOL 1e-7
/* Iteration limit of the root finder and of the outward bracketing. */
#define CI_MAXITER 200

/* The profile of parameter j: pb with j held at theta, the others (if any
 * are free) minimised from the last nuisance optimum. */
typedef struct {
    bf_problem sub;              /* pb with j fixed */
    double start[BF_MAX_PARAMS]; /* warm start of the nuisance parameters */
    size_t j;
    double s_min;                /* objective at the optimum */
    double n_w;                  /* sum of the weights */
    double chi2;                 /* chi2_1(level) */
    double *work;                /* 2 n doubles */
    int status;                  /* first failure, BF_OK if none */
} profile_t;

/* n ln(S_p(theta) / S_min) - chi2: negative inside the interval. */
static double profile_crit(double theta, void *arg)
{
    profile_t *p = arg;
    double s;
    p->sub.fixed[p->j] = theta;
    p->start[p->j] = theta;
    if (p->sub.free_mask == 0) {
        if (bf_problem_value(&p->sub, p->sub.fixed, p->work, &s) != BF_OK) {
            p->status = BF_EDOM;
            return GSL_POSINF;
        }
    } else {
        bf_fit_result r;
        int rc = bf_fit_minimise(&p->sub, p->start, &r);
        if (rc != BF_OK && rc != BF_ENOCONV) {
            p->status = rc;
            return GSL_POSINF;
        }
        memcpy(p->start, r.param, sizeof p->start);
        s = r.lse;
    }
    return p->n_w * log(s / p->s_min) - p->chi2;
}

/* Root of profile_crit in [in, out] (crit(in) <= 0 < crit(out)). */
static int root(profile_t *p, double in, double out, double *x)
{
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_function fn;
    double lo = in < out ? in : out;
    double hi = in < out ? out : in;
    int status;
    size_t iter = 0;
    if (s == NULL) {
        return BF_ENOMEM;
    }
    fn.function = profile_crit;
    fn.params = p;
    status = gsl_root_fsolver_set(s, &fn, lo, hi);
    while (status == GSL_SUCCESS && iter++ < CI_MAXITER) {
        status = gsl_root_fsolver_iterate(s);
        if (status != GSL_SUCCESS) {
            break;
        }
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                        gsl_root_fsolver_x_upper(s), CI_TOL,
                                        0.0);
        if (status == GSL_SUCCESS) {
            break;
        }
        status = GSL_SUCCESS;
    }
    *x = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    return status == GSL_SUCCESS ? BF_OK : BF_ENOCONV;
}

/* One end of the interval: walks from the optimum towards limit in steps
 * that double until the criterion turns positive, then finds the root.
 * *at_limit is set when the interval reaches limit. */
static int one_side(profile_t *p, double theta_hat, double limit, double d0,
                    double *end, int *at_limit)
{
    double x = theta_hat;
    double d = d0;
    size_t iter;
    double nuisance[BF_MAX_PARAMS];
    memcpy(nuisance, p->start, sizeof nuisance);
    *at_limit = 0;
    if (theta_hat == limit) { /* the optimum is on the search range */
        *end = limit;
        *at_limit = 1;
        return BF_OK;
    }
    for (iter = 0; iter < CI_MAXITER; iter++) {
        double next = limit > theta_hat ? x + d : x - d;
        double c;
        if ((limit > theta_hat && next >= limit) ||
            (limit < theta_hat && next <= limit)) {
            next = limit;
        }
        c = profile_crit(next, p);
        if (p->status != BF_OK) {
            return p->status;
        }
        if (c > 0.0) {
            int rc = root(p, x, next, end);
            memcpy(p->start, nuisance, sizeof nuisance);
            return p->status != BF_OK ? p->status : rc;
        }
        if (next == limit) {
            *end = limit;
            *at_limit = 1;
            memcpy(p->start, nuisance, sizeof nuisance);
            return BF_OK;
        }
        x = next;
        d *= 2.0;
    }
    return BF_ENOCONV;
}

static double weight_sum(const bf_problem *pb)
{
    double s = 0.0;
    size_t k;
    if (pb->weight == NULL) {
        return (double)pb->n;
    }
    for (k = 0; k < pb->n; k++) {
        s += pb->weight[k];
    }
    return s;
}

int bf_fit_profile_ci(const bf_problem *pb, const bf_fit_result *best,
                      size_t j, double level, double *low, double *high,
                      unsigned *open)
{
    profile_t p;
    const bf_param *pj;
    double theta_hat;
    double d0;
    int at_lo = 0;
    int at_hi = 0;
    int rc;

    if (pb == NULL || best == NULL || low == NULL || high == NULL ||
        open == NULL || pb->type == NULL || j >= pb->type->p ||
        !((pb->free_mask >> j) & 1u) || !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    memset(&p, 0, sizeof p);
    p.work = malloc(2 * pb->n * sizeof *p.work);
    if (p.work == NULL) {
        return BF_ENOMEM;
    }
    p.sub = *pb;
    p.sub.free_mask &= ~(1u << j);
    memcpy(p.sub.fixed, best->param, sizeof p.sub.fixed);
    memcpy(p.start, best->param, sizeof p.start);
    p.j = j;
    p.n_w = weight_sum(pb);
    p.chi2 = gsl_cdf_chisq_Pinv(level, 1.0); /* 3.841 at 95% */
    rc = bf_problem_value(pb, best->param, p.work, &p.s_min);
    if (rc != BF_OK) {
        goto done;
    }
    if (!(p.s_min > DBL_MIN)) {
        p.s_min = DBL_MIN; /* an exact fit: the interval shrinks to a point */
    }
    pj = &pb->type->param[j];
    theta_hat = best->param[j];
    d0 = pj->grid_n > 0 ? pj->grid_step : (pb->hi[j] - pb->lo[j]) / 100.0;
    rc = one_side(&p, theta_hat, pb->lo[j], d0, low, &at_lo);
    if (rc == BF_OK) {
        rc = one_side(&p, theta_hat, pb->hi[j], d0, high, &at_hi);
    }
    *open = (at_lo ? 1u : 0u) | (at_hi ? 2u : 0u);
done:
    free(p.work);
    return rc;
}

/* ==== bootstrap ============================================================ */

int bf_fit_bootstrap(const bf_problem *pb, const bf_curves *curves,
                     size_t n_boot, unsigned long seed, double level,
                     double *low, double *high)
{
    gsl_rng *rng = NULL;
    double *w = NULL;
    double *est = NULL;
    size_t used = 0;
    size_t b;
    size_t j;
    int rc = BF_OK;

    if (pb == NULL || curves == NULL || low == NULL || high == NULL ||
        pb->weight != NULL || n_boot < 2 || !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    rng = gsl_rng_alloc(gsl_rng_mt19937);
    w = malloc(pb->n * sizeof *w);
    est = malloc(n_boot * BF_MAX_PARAMS * sizeof *est);
    if (rng == NULL || w == NULL || est == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    gsl_rng_set(rng, seed);
    for (b = 0; b < n_boot; b++) {
        bf_problem rep = *pb;
        bf_fit_result g;
        bf_fit_result r;
        size_t k;
        memset(w, 0, pb->n * sizeof *w);
        for (k = 0; k < pb->n; k++) { /* resample configurations [2] */
            w[gsl_rng_uniform_int(rng, pb->n)] += 1.0;
        }
        rep.weight = w;
        rc = bf_curves_best(curves, &rep, &g);
        if (rc == BF_OK) {
            rc = bf_fit_refine(&rep, &g, &r);
            rc = rc == BF_ENOCONV ? BF_OK : rc; /* r: the best point found */
        }
        if (rc == BF_ENOMEM || rc == BF_EINVAL) {
            goto done;
        }
        if (rc != BF_OK) {
            rc = BF_OK;
            continue; /* a replicate the model cannot fit: left out */
        }
        for (j = 0; j < BF_MAX_PARAMS; j++) {
            est[j * n_boot + used] = r.param[j];
        }
        used++;
    }
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        double *e = est + j * n_boot;
        low[j] = NAN;
        high[j] = NAN;
        if (j >= pb->type->p || !((pb->free_mask >> j) & 1u) || used < 2) {
            continue;
        }
        gsl_sort(e, 1, used);
        low[j] = gsl_stats_quantile_from_sorted_data(e, 1, used,
                                                     0.5 * (1.0 - level));
        high[j] = gsl_stats_quantile_from_sorted_data(e, 1, used,
                                                      0.5 * (1.0 + level));
    }
    if (used < 2) {
        rc = BF_EDOM;
    }
done:
    gsl_rng_free(rng);
    free(w);
    free(est);
    return rc;
}
