/* neyman.c: intervals whose threshold is calibrated by simulation at each
 * value they test -- the Neyman construction with the likelihood-ratio
 * ordering (doc/methods.md §3, ci_method "neyman").
 *
 * [1] G. J. Feldman, R. D. Cousins, "Unified approach to the classical
 *     statistical analysis of small signals", Phys. Rev. D 57 (1998)
 *     3873-3889 (the likelihood-ratio ordering; intervals that cover at
 *     a boundary).
 * [2] K. Cranmer, "Statistical challenges for searches for new physics at
 *     the LHC", PHYSTAT 2005, §4 (the profile construction: nuisance
 *     parameters held at their constrained estimates).
 * [3] src/fit/intervals.c: the likelihood, its profile criterion
 *     D(theta_j) = n ln(S_p(theta_j) / S_min) and its F threshold.
 *
 * Equations: theta_j is inside when D(theta_j) <= c(theta_j), c the
 * level-quantile of D*_r(theta_j) over R measurements simulated at
 * (theta_j, the other parameters' constrained estimate at theta_j) under
 * the fitted noise model (power p, sigma) [2] and refitted as the data
 * were (grid optimum, refinement, maximum likelihood at p); the same R
 * normal deviates at every theta_j (common random numbers, so that c is
 * smooth in theta_j). Where the likelihood is regular c is the F
 * threshold [3] up to simulation error; at a fold of the model (the
 * Fresnel index n near 1.7, where two values give one shape and D is
 * half chi2_0, half chi2_1) it is lower, and where two basins compete
 * (look-elsewhere) higher [1]. Each end of the interval is the fixed point
 * of end -> the profile interval's end under the threshold c(end),
 * started from the F threshold's end.
 */
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Passes of (threshold at the end, end under that threshold) per end. */
#define NY_PASSES 4
/* An end has converged when it moves less than this share of the
 * parameter's range. */
#define NY_TOL 1e-3

typedef struct {
    bf__fitctx *fc;
    const bf_problem *pb;   /* the objective's problem (measured data) */
    bf_problem lik;         /* the likelihood at the fitted power */
    bf_problem sim;         /* pb on the simulated data */
    bf_problem sim_lik;     /* lik on the simulated data */
    const bf_interval *iv;
    const bf__grid *gr;     /* pb's grid: the simulations' first fits */
    gsl_rng *rng;
    double *curve;          /* n: the constrained fit's curve */
    double *d;              /* n: a simulated measurement */
    double *lr;             /* n_sim: the simulations' D* */
    size_t n_sim;
    size_t j;               /* the parameter whose interval is built */
    unsigned long seed;
    double level;
} neyman_t;

/* c(theta): the level-quantile of D*(theta) over the m simulations at
 * theta's constrained estimate -- the order statistic of rank
 * ceil(level (m + 1)), at most m, whose expected distribution function is
 * level (ceil(level m) is biased low: the 95th of 100 has expectation
 * 95/101 = 0.941) -- and *dev the measured D(theta). */
static int threshold_at(neyman_t *t, double theta, double *c, double *dev)
{
    bf__fitctx *fc = t->fc;
    double param[BF_MAX_PARAMS];
    size_t m = 0;
    size_t r;
    int rc;
    bf__fitctx_use(fc, &t->lik);
    rc = bf__profile_point(fc, &t->iv->ml, t->j, theta, dev, param);
    if (rc == BF_OK) {
        rc = bf__curve(fc->pm, param, fc->work, t->curve);
    }
    gsl_rng_set(t->rng, t->seed); /* common random numbers */
    for (r = 0; rc == BF_OK && r < t->n_sim; r++) {
        bf_fit_result best;
        bf_fit_result ml;
        double d_r;
        int st;
        if (!bf__simulate(&t->sim, t->curve, 0.0, t->iv->noise_power,
                          t->iv->sigma, t->rng, t->d)) {
            continue;
        }
        bf__fitctx_use(fc, &t->sim);
        st = bf__grid_refine(fc, t->gr, &best);
        if (st == BF_OK || st == BF_ENOCONV) {
            bf__fitctx_use(fc, &t->sim_lik);
            st = bf__ml_fit(fc, best.param, &ml);
        }
        if (st == BF_OK) {
            st = bf__profile_point(fc, &ml, t->j, theta, &d_r, NULL);
        }
        if (st == BF_ENOMEM) {
            rc = st;
        } else if (st == BF_OK) {
            t->lr[m++] = d_r;
        }
    }
    bf__fitctx_use(fc, t->pb);
    if (rc == BF_OK && m < 2) {
        rc = BF_EDOM;
    }
    if (rc == BF_OK) {
        size_t k = (size_t)ceil(t->level * (double)(m + 1));
        gsl_sort(t->lr, 1, m);
        *c = t->lr[(k < m ? k : m) - 1];
    }
    return rc;
}

/* The side of the estimate theta a gap g (its two ends) lies on: 1 above,
 * 0 below. A gap never holds the estimate, whose D is 0. */
static int gap_side(const double g[2], double theta)
{
    return g[0] > theta;
}

/* One end (side 0 low, 1 high) of parameter j's interval: from the F
 * threshold's end x, x -> the profile interval's end under c(x). gap (2
 * doubles, NaN: none) gets the gap of a split set on this side from the
 * last profile under c(x): its two regions' ends, each thresholded at the
 * outer end's c (not at the gap's own). */
static int one_end(neyman_t *t, int side, double d0, double *x,
                   unsigned *open, double *gap)
{
    const bf_problem *pb = t->pb;
    double bound = side ? pb->hi[t->j] : pb->lo[t->j];
    size_t pass;
    int rc = BF_OK;
    if (*x == bound && t->iv->ml.param[t->j] == bound) {
        return BF_OK; /* the estimate's D = 0 is inside whatever c is */
    }
    for (pass = 0; rc == BF_OK && pass < NY_PASSES; pass++) {
        double c;
        double dev;
        double lo;
        double hi;
        double g[2];
        unsigned op = 0;
        double x_new;
        rc = threshold_at(t, *x, &c, &dev);
        if (rc != BF_OK) {
            break;
        }
        if (*x == bound && dev <= c) {
            break; /* open: inside at the bound */
        }
        bf__fitctx_use(t->fc, &t->lik);
        rc = bf__profile_ci_thr(t->fc, &t->iv->ml, t->j, c, d0, &lo, &hi,
                                &op, g);
        bf__fitctx_use(t->fc, pb);
        if (rc != BF_OK) {
            break;
        }
        if (isfinite(g[0]) && gap_side(g, t->iv->ml.param[t->j]) == side) {
            gap[0] = g[0];
            gap[1] = g[1];
        } else {
            gap[0] = gap[1] = NAN;
        }
        x_new = side ? hi : lo;
        if (fabs(x_new - *x) < NY_TOL * (pb->hi[t->j] - pb->lo[t->j])) {
            *x = x_new;
            break;
        }
        if (pass + 1 == NY_PASSES) { /* not settled: the outer of the two */
            x_new = side ? fmax(x_new, *x) : fmin(x_new, *x);
        }
        *x = x_new;
    }
    if (rc == BF_OK) { /* the end kept is the range's, or not */
        *open = *x == bound ? (side ? 2u : 1u) : 0u;
    }
    return rc;
}

/* Parameter t->j's two ends and gap into out (from iv's; d0: its
 * profile's first step); on failure they are iv's again. */
static int one_param(neyman_t *t, double d0, bf_interval *out)
{
    const bf_interval *iv = t->iv;
    size_t j = t->j;
    double theta = iv->ml.param[j];
    unsigned op_lo = (iv->open >> (2 * j)) & 1u;
    unsigned op_hi = (iv->open >> (2 * j)) & 2u;
    /* iv's gap, on the side it lies */
    double g_lo[2] = {NAN, NAN};
    double g_hi[2] = {NAN, NAN};
    double g_iv[2] = {iv->gap_low[j], iv->gap_high[j]};
    double *g = gap_side(g_iv, theta) ? g_hi : g_lo;
    int rc = isfinite(iv->low[j]) && isfinite(iv->high[j]) ? BF_OK
                                                           : BF_EDOM;
    if (isfinite(g_iv[0])) {
        g[0] = g_iv[0];
        g[1] = g_iv[1];
    }
    if (rc == BF_OK) {
        rc = one_end(t, 0, d0, &out->low[j], &op_lo, g_lo);
    }
    if (rc == BF_OK) {
        rc = one_end(t, 1, d0, &out->high[j], &op_hi, g_hi);
    }
    if (rc != BF_OK) {
        out->low[j] = iv->low[j];
        out->high[j] = iv->high[j];
        return rc;
    }
    out->open = (out->open & ~(3u << (2 * j))) | ((op_lo | op_hi) << (2 * j));
    /* one gap inside the ends, or none (the hull) */
    g = isfinite(g_lo[0]) == isfinite(g_hi[0]) ? NULL
        : isfinite(g_lo[0])                    ? g_lo
                                               : g_hi;
    out->gap_low[j] = out->gap_high[j] = NAN;
    if (g != NULL && g[0] > out->low[j] && g[1] < out->high[j]) {
        out->gap_low[j] = g[0];
        out->gap_high[j] = g[1];
    }
    return BF_OK;
}

int bf__neyman(bf__fitctx *fc, const bf_interval *iv, const bf__grid *gr,
               unsigned which, size_t n_sim, unsigned long seed,
               double level, bf_interval *out, unsigned *failed)
{
    const bf_problem *pb = fc->pb;
    neyman_t t;
    bf__grid *own = NULL;
    double d0[BF_MAX_PARAMS];
    double n_w = bf__weight_sum(pb);
    double thr = bf__lik_threshold(n_w, bf__lik_dof(pb, iv->noise), level);
    int first = BF_OK; /* the first parameter's failure */
    size_t j;
    int rc = BF_OK;

    *out = *iv;
    which &= pb->free_mask;
    *failed = which;
    if (which == 0) {
        return BF_OK;
    }
    if (iv->method != BF_CI_PROFILE_LIK ||
        pb->type->kind == BF_MODEL_SPECULAR) {
        return BF_EDOM;
    }
    memset(&t, 0, sizeof t);
    t.fc = fc;
    t.pb = pb;
    t.iv = iv;
    t.gr = gr;
    t.n_sim = n_sim;
    t.seed = seed;
    t.level = level;
    t.lik = *pb;
    t.lik.objective = BF__OBJ_LIK;
    t.lik.noise_power = iv->noise_power;
    t.curve = malloc((2 * pb->n + n_sim) * sizeof *t.curve);
    t.rng = gsl_rng_alloc(gsl_rng_mt19937);
    rc = t.curve == NULL || t.rng == NULL ? BF_ENOMEM : BF_OK;
    if (rc == BF_OK) {
        t.d = t.curve + pb->n;
        t.lr = t.d + pb->n;
        t.sim = *pb;
        t.sim.data = t.d;
        t.sim_lik = t.lik;
        t.sim_lik.data = t.d;
    }
    if (rc == BF_OK && gr == NULL) {
        bf__grid_layout_t lay;
        rc = bf__grid_layout_range(pb->type, pb->fixed, pb->free_mask,
                                   pb->lo, pb->hi, &lay);
        if (rc == BF_OK) {
            t.gr = own = bf__grid_make(fc->pm, &lay, &rc);
        }
    }
    if (rc == BF_OK) {
        bf__fitctx_use(fc, &t.lik);
        rc = bf__profile_steps(fc, &iv->ml, thr, d0); /* one for all */
        bf__fitctx_use(fc, pb);
    }
    if (rc == BF_OK) {
        *failed = 0;
    }
    for (j = 0; rc == BF_OK && j < pb->type->p; j++) {
        int st;
        if (!((which >> j) & 1u)) {
            continue;
        }
        t.j = j;
        st = one_param(&t, d0[j], out);
        if (st == BF_ENOMEM) {
            rc = st;
        } else if (st != BF_OK) {
            *failed |= 1u << j;
            first = first == BF_OK ? st : first;
        } else {
            out->neyman |= 1u << j;
        }
    }
    if (rc == BF_OK && out->neyman == pb->free_mask) {
        out->method = BF_CI_NEYMAN;
    }
    bf__grid_free(own);
    gsl_rng_free(t.rng);
    free(t.curve);
    return rc != BF_OK ? rc : first;
}

unsigned bf__neyman_which(const bf_problem *pb, const bf_interval *iv,
                          size_t n_neyman, int every)
{
    if (n_neyman == 0 || pb->type->kind == BF_MODEL_SPECULAR ||
        iv->method != BF_CI_PROFILE_LIK) {
        return 0;
    }
    return every ? pb->free_mask : iv->competing & pb->free_mask;
}

int bf_fit_neyman(const bf_problem *pb, const bf_interval *iv, unsigned which,
                  size_t n_sim, unsigned long seed, double level,
                  bf_interval *out)
{
    bf__solo so;
    unsigned failed = 0;
    int rc;
    if (pb == NULL || iv == NULL || out == NULL || pb->type == NULL ||
        pb->data == NULL || pb->weight != NULL ||
        n_sim < BF_NEYMAN_MIN_SIM || !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    *out = *iv;
    rc = bf__solo_init(&so, pb);
    if (rc == BF_OK) {
        rc = bf__neyman(&so.fc, iv, NULL, which, n_sim, seed, level, out,
                        &failed);
        bf__solo_free(&so);
    }
    return rc;
}
