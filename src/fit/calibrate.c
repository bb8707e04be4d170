/* calibrate.c: the intervals of a fit checked on simulated measurements
 * of the fitted model (doc/methods.md §3, `brdffit calibrate`).
 *
 * [1] SPEC §2 (measured data normalised by their maximum).
 * [2] src/fit/noise.c: the noise model, var e_k = sigma^2 max(L_k, f)^p.
 *
 * Each simulation: D_k = L_k(truth) + sigma max(L_k, f)^(p/2) eps_k,
 * eps_k ~ N(0, 1), divided by max_k D_k [1] (so the value that sets the
 * scale is as noisy as a measurement's); the fit under pb's objective
 * (grid optimum on stored curves, refinement) and its intervals
 * (bf__intervals; with n_neyman, the Neyman construction's where the
 * analysis makes it, neyman.c) and, with n_boot, its bootstrap interval
 * (bf__bootstrap); the truth inside or not. Coverage is the share of
 * simulations whose interval holds the truth; bias and sd are those of
 * the objective's estimates and of the maximum-likelihood ones.
 */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* One simulated data set into d (n values): false when not normalisable.
 * m > 0: a specular model's (SPEC §9), curve = rho_hat / m, the data
 * m (L + sigma max(L, f)^(p/2) eps) kept in sr^-1 (noise.c), never
 * normalised. */
int bf__simulate(const bf_problem *pb, const double *curve, double m,
                    double p, double sigma, gsl_rng *rng, double *d)
{
    double top = -HUGE_VAL;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double l = curve[k] > BF_LOG_FLOOR ? curve[k] : BF_LOG_FLOOR;
        d[k] = curve[k] + sigma * pow(l, 0.5 * p) * gsl_ran_gaussian(rng, 1.0);
        top = d[k] > top ? d[k] : top;
    }
    if (m > 0.0) {
        for (k = 0; k < pb->n; k++) {
            d[k] *= m;
        }
        return 1;
    }
    if (!(top > 0.0)) {
        return 0;
    }
    for (k = 0; k < pb->n; k++) {
        d[k] /= top; /* [1] */
    }
    return 1;
}

typedef struct {
    double *est;   /* n_sim x BF_MAX_PARAMS, parameter-major */
    double *ml;
    double *width;
    double *boot_width; /* NULL without the bootstrap */
    double *f_width;    /* the profile threshold's, before the construction */
    size_t *cover; /* BF_MAX_PARAMS */
    size_t *flag;
    size_t *boot_cover;
    size_t *f_cover;
    size_t *competing;
} tally_t;

static void summarise(const bf_problem *pb, const tally_t *t, size_t m,
                      size_t n_sim, bf_calibration *out)
{
    size_t j;
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        double *e = t->est + j * n_sim;
        double *q = t->ml + j * n_sim;
        double *w = t->width + j * n_sim;
        if (j >= pb->type->p || !((pb->free_mask >> j) & 1u) || m < 2) {
            continue;
        }
        out->coverage[j] = (double)t->cover[j] / (double)m;
        out->not_identified[j] = (double)t->flag[j] / (double)m;
        out->bias[j] = gsl_stats_mean(e, 1, m) - out->truth[j];
        out->sd[j] = gsl_stats_sd(e, 1, m);
        out->ml_bias[j] = gsl_stats_mean(q, 1, m) - out->truth[j];
        out->ml_sd[j] = gsl_stats_sd(q, 1, m);
        gsl_sort(w, 1, m);
        out->width[j] = gsl_stats_median_from_sorted_data(w, 1, m);
        if (t->boot_width != NULL) {
            double *bw = t->boot_width + j * n_sim;
            out->boot_coverage[j] = (double)t->boot_cover[j] / (double)m;
            gsl_sort(bw, 1, m);
            out->boot_width[j] = gsl_stats_median_from_sorted_data(bw, 1, m);
        }
        {
            double *fw = t->f_width + j * n_sim;
            out->f_coverage[j] = (double)t->f_cover[j] / (double)m;
            out->competing[j] = (double)t->competing[j] / (double)m;
            gsl_sort(fw, 1, m);
            out->f_width[j] = gsl_stats_median_from_sorted_data(fw, 1, m);
        }
    }
}

static void clear(bf_calibration *out, const double *truth, size_t p)
{
    size_t j;
    memset(out, 0, sizeof *out);
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        out->truth[j] = j < p ? truth[j] : NAN;
        out->coverage[j] = out->bias[j] = out->sd[j] = NAN;
        out->ml_bias[j] = out->ml_sd[j] = out->width[j] = NAN;
        out->not_identified[j] = NAN;
        out->boot_coverage[j] = out->boot_width[j] = NAN;
        out->f_coverage[j] = out->f_width[j] = out->competing[j] = NAN;
    }
}

/* Copies the maximum-likelihood estimates of the m simulations fitted
 * into ml_est (n_sim x BF_MAX_PARAMS, parameter-major; NaN for the
 * simulations not fitted and the parameters not free). */
static void keep_estimates(const bf_problem *pb, const tally_t *t, size_t m,
                           size_t n_sim, double *ml_est)
{
    size_t j;
    size_t r;
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        int fitted = j < pb->type->p && ((pb->free_mask >> j) & 1u);
        for (r = 0; r < n_sim; r++) {
            ml_est[j * n_sim + r] = fitted && r < m ? t->ml[j * n_sim + r]
                                                  : NAN;
        }
    }
}

int bf_fit_calibrate(const bf_problem *pb, const double *truth,
                     double noise_power, double sigma, bf_noise noise,
                     size_t n_sim, size_t n_boot, size_t n_neyman,
                     int neyman_every, unsigned long seed, double level,
                     bf_calibration *out)
{
    return bf__fit_calibrate(pb, truth, noise_power, sigma, noise, n_sim,
                             n_boot, n_neyman, neyman_every, seed, level,
                             NULL, NULL, out);
}

int bf__fit_calibrate(const bf_problem *pb, const double *truth,
                      double noise_power, double sigma, bf_noise noise,
                      size_t n_sim, size_t n_boot, size_t n_neyman,
                      int neyman_every, unsigned long seed, double level,
                      double *ml_est, const bf__tick *tick,
                      bf_calibration *out)
{
    bf__solo so;
    bf__grid_layout_t lay;
    bf__grid *gr = NULL;
    gsl_rng *rng = NULL;
    bf_problem sim;
    tally_t t;
    size_t cover[BF_MAX_PARAMS] = {0};
    size_t flag[BF_MAX_PARAMS] = {0};
    size_t boot_cover[BF_MAX_PARAMS] = {0};
    size_t f_cover[BF_MAX_PARAMS] = {0};
    size_t competing[BF_MAX_PARAMS] = {0};
    size_t n_arr = 4 + (n_boot >= 2);
    double *curve = NULL;
    double *d = NULL;
    double top = 0.0; /* a specular model's maximum (simulate) */
    int spec;
    size_t m = 0;
    size_t r;
    size_t j;
    int rc;

    if (pb == NULL || truth == NULL || out == NULL || pb->type == NULL ||
        pb->weight != NULL || n_sim < BF_CALIBRATE_MIN_SIM || !(sigma >= 0.0) ||
        !(noise_power >= 0.0 && noise_power <= BF_NOISE_PMAX) ||
        (n_neyman > 0 && n_neyman < BF_NEYMAN_MIN_SIM) ||
        (n_neyman > 0 && neyman_every &&
         (pb->type->kind == BF_MODEL_SPECULAR ||
          noise == BF_NOISE_OBJECTIVE)) ||
        bf_noise_name(noise) == NULL || !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    spec = pb->type->kind == BF_MODEL_SPECULAR;
    clear(out, truth, pb->type->p);
    if (!((double)pb->n > (double)bf_problem_nfree(pb) + 1.0 +
                             (noise == BF_NOISE_AUTO ? 1.0 : 0.0))) {
        return BF_EDOM; /* no noise estimate (bf_fit_intervals) */
    }
    memset(&t, 0, sizeof t);
    sim = *pb;
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    t.est = malloc(n_arr * n_sim * BF_MAX_PARAMS * sizeof *t.est);
    curve = malloc(2 * pb->n * sizeof *curve);
    rng = gsl_rng_alloc(gsl_rng_mt19937);
    rc = t.est == NULL || curve == NULL || rng == NULL ? BF_ENOMEM : BF_OK;
    if (rc == BF_OK) {
        t.ml = t.est + n_sim * BF_MAX_PARAMS;
        t.width = t.ml + n_sim * BF_MAX_PARAMS;
        t.boot_width = n_boot >= 2 ? t.width + n_sim * BF_MAX_PARAMS : NULL;
        t.f_width = t.est + (n_arr - 1) * n_sim * BF_MAX_PARAMS;
        t.f_cover = f_cover;
        t.competing = competing;
        t.cover = cover;
        t.flag = flag;
        t.boot_cover = boot_cover;
        d = curve + pb->n;
        sim.data = d;
        gsl_rng_set(rng, seed);
        rc = bf__curve(&so.pm, truth, so.fc.work, curve);
    }
    for (j = 0; rc == BF_OK && spec && j < pb->n; j++) {
        top = curve[j] > top ? curve[j] : top;
    }
    if (rc == BF_OK && spec) { /* its own search, no stored grid */
        for (j = 0; j < pb->n; j++) {
            curve[j] /= top;
        }
        rc = top > 0.0 && isfinite(top) ? BF_OK : BF_EDOM;
    } else if (rc == BF_OK) {
        rc = bf__grid_layout_range(pb->type, pb->fixed, pb->free_mask, pb->lo,
                                   pb->hi, &lay);
    }
    if (rc == BF_OK && !spec) {
        gr = bf__grid_make(&so.pm, &lay, &rc);
    }
    for (r = 0; rc == BF_OK && r < n_sim; r++) {
        bf_fit_result best;
        bf_interval iv;
        double blo[BF_MAX_PARAMS];
        double bhi[BF_MAX_PARAMS];
        bf_interval ny;
        const bf_interval *dflt = &iv; /* the analysis's intervals */
        unsigned which = 0;
        int st;
        if (r > 0 && tick != NULL) {
            tick->fn(tick->ctx); /* the previous simulation's */
        }
        if (!bf__simulate(&sim, curve, top, noise_power, sigma, rng, d)) {
            out->n_failed++;
            continue;
        }
        bf__fitctx_use(&so.fc, &sim);
        if (spec) { /* the separable fit (varpro.c) */
            st = bf__varpro_fit(&so.fc, NULL, &best, NULL);
        } else {
            st = bf__grid_refine(&so.fc, gr, &best);
        }
        if (st == BF_OK || st == BF_ENOCONV) {
            st = bf__intervals(&so.fc, &best, noise, level, &iv);
        }
        if (st == BF_OK) {
            which = bf__neyman_which(pb, &iv, n_neyman, neyman_every);
        }
        if (which != 0) { /* as the analysis's */
            unsigned failed;
            st = bf__neyman(&so.fc, &iv, gr, which, n_neyman,
                            seed + 1 + n_sim + r, level, &ny, &failed);
            dflt = &ny;
            if (st == BF_EDOM) { /* the analysis keeps the profile's */
                st = BF_OK;
            }
        }
        if (st == BF_OK && n_boot >= 2) {
            st = bf__bootstrap(&so.fc, &iv, n_boot, seed + 1 + r, level, NULL,
                               NULL, blo, bhi, NULL);
        }
        if (st == BF_ENOMEM) {
            rc = st;
            break;
        }
        if (st != BF_OK) {
            out->n_failed++;
            continue;
        }
        for (j = 0; j < pb->type->p; j++) {
            if (!((pb->free_mask >> j) & 1u)) {
                continue;
            }
            t.est[j * n_sim + m] = best.param[j];
            t.ml[j * n_sim + m] = iv.ml.param[j];
            t.f_width[j * n_sim + m] = bf_interval_length(&iv, j);
            f_cover[j] += bf_interval_holds(&iv, j, truth[j]);
            t.width[j * n_sim + m] = bf_interval_length(dflt, j);
            cover[j] += bf_interval_holds(dflt, j, truth[j]);
            flag[j] += (iv.not_identified >> j) & 1u;
            competing[j] += (iv.competing >> j) & 1u;
            if (t.boot_width != NULL) {
                t.boot_width[j * n_sim + m] = bhi[j] - blo[j];
                boot_cover[j] += blo[j] <= truth[j] && truth[j] <= bhi[j];
            }
        }
        m++;
    }
    if (rc == BF_OK && tick != NULL) {
        tick->fn(tick->ctx); /* the last simulation's */
    }
    if (rc == BF_OK && ml_est != NULL) {
        keep_estimates(pb, &t, m, n_sim, ml_est);
    }
    if (rc == BF_OK) {
        out->n_sim = m;
        summarise(pb, &t, m, n_sim, out);
        rc = m >= 2 ? BF_OK : BF_EDOM;
    }
    bf__grid_free(gr);
    gsl_rng_free(rng);
    free(t.est);
    free(curve);
    bf__solo_free(&so);
    return rc;
}
