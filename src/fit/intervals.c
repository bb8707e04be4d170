/* intervals.c: the intervals of a fit under its noise model
 * (doc/methods.md §3) -- the noise power estimated from the residuals,
 * the maximum-likelihood fit with the scale and the noise level profiled
 * (src/fit/noise.c), and each free parameter's profile-likelihood
 * interval with an F threshold; open ends and not-identified parameters
 * said.
 *
 * [1] Y. Pawitan, "In All Likelihood", OUP 2001, §9.2 (profile likelihood
 *     intervals), §10.6 (nuisance parameters).
 * [2] D. M. Bates, D. G. Watts, "Nonlinear Regression Analysis and Its
 *     Applications", Wiley 1988, §6.1.2 (profile t: the likelihood-ratio
 *     interval with sigma^2 estimated, calibrated by F(1, n - k)).
 *
 * Equations: theta_j is inside when
 *   n ln(S_p(theta_j) / S_min) <= n ln(1 + F_{1,nu}(level) / nu)      [2]
 * with S the likelihood objective (noise.c; -2 ln L = n ln S + const),
 * S_p minimised over the other free parameters and the scale, nu = n - k,
 * k = free parameters + the scale + the noise power when estimated. As
 * nu grows the threshold tends to Wilks' chi2_1(level) [1] §9.2; at small
 * n it is the exact interval of a linear model with unknown variance. A
 * specular model's threshold of theta_j is multiplied by its robust
 * factor c_j >= 1 (src/fit/sandwich.c, Stafford's adjustment).
 */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Passes of (noise power at the estimate, estimate at that power). */
#define NOISE_PASSES 4
/* The noise power has converged when it moves less than this. */
#define NOISE_TOL 1e-3
/* Passes of (leverages at the noise power, noise power from the residuals
 * they standardise). */
#define LEV_PASSES 3

double bf__lik_dof(const bf_problem *pb, bf_noise noise)
{
    /* a diffuse model's free scale; the noise power under auto */
    double k = (double)bf_problem_nfree(pb) +
               (pb->type->kind == BF_MODEL_SPECULAR ? 0.0 : 1.0) +
               (noise == BF_NOISE_AUTO ? 1.0 : 0.0);
    return bf__weight_sum(pb) - k;
}

double bf__lik_threshold(double n, double nu, double level)
{
    /* F_{1,nu}(level) = t_nu((1 + level) / 2)^2: GSL's F quantile is NaN
     * for nu above about 2e5 (dense data), its t quantile is not */
    double t = gsl_cdf_tdist_Pinv(0.5 * (1.0 + level), nu);
    return n * log1p(t * t / nu);
}

/* The optimum of fc->pb (the likelihood): the lower of the refinement
 * from start (the objective's optimum, or the last pass's estimate) and a
 * minimisation over the whole search range from it (refine.c,
 * bf__minimise: one parameter sampled across its range first). The
 * likelihood's variances follow the curve, so its S has local minima a
 * grid step apart, and the objective's optimum can lie steps from the
 * likelihood's: on CURET's 24 paper samples (`make run`) the refinement
 * alone left 75 of the 144 estimates in a higher basin (44 more than 2 %
 * away; VH-E on sample 1 at m = 3.00, its interval [1.17, 3.05] reaching
 * down to the lower basin at 1.77); in 74 the old interval held the
 * lower basin's estimate (doc/methods.md §3). */
int bf__ml_fit(bf__fitctx *fc, const double *start, bf_fit_result *out)
{
    bf_fit_result s0;
    bf_fit_result whole;
    int rc;
    memset(&s0, 0, sizeof s0);
    memcpy(s0.param, start, sizeof s0.param);
    rc = bf__fit_value(fc, s0.param, &s0.lse);
    if (rc == BF_OK) {
        rc = bf__refine(fc, &s0, out);
        rc = rc == BF_ENOCONV ? BF_OK : rc; /* the best point found */
    }
    if (rc == BF_OK) {
        int rw = bf__minimise(fc, start, &whole);
        if ((rw == BF_OK || rw == BF_ENOCONV) && whole.lse < out->lse) {
            whole.n_eval += out->n_eval;
            *out = whole;
        }
        rc = rw == BF_ENOMEM ? rw : rc;
    }
    return rc;
}

/* The noise power of the fit at param whose normalised curve is in
 * fc->curve, under fc->pb's weights: the likelihood's estimate from the
 * residuals standardised by their leverages (doc/methods.md §3; a narrow
 * lobe's few configurations are nearly interpolated, and their raw
 * residuals understate their variance), the leverages taken at the power
 * they give (LEV_PASSES). buf: (BF_MAX_PARAMS + 4) n doubles. */
static int adjusted_power(bf__fitctx *fc, const double *param, double *buf,
                          double *p)
{
    size_t n = fc->pb->n;
    double *z = buf;
    double *t0 = buf + (BF_MAX_PARAMS + 1) * n;
    double *h = t0 + 2 * n;
    size_t pass;
    int rc = BF_OK;
    *p = bf__noise_power(fc->pb, fc->curve, NULL, fc->scratch);
    for (pass = 0; pass < LEV_PASSES; pass++) {
        double q;
        /* the columns' scale leaves the leverages as they are: 1 */
        rc = bf__leverages(fc, param, 1.0, *p, fc->curve, 1.0, z, t0,
                           t0 + n, h);
        if (rc != BF_OK) {
            break;
        }
        q = bf__noise_power(fc->pb, fc->curve, h, fc->scratch);
        if (fabs(q - *p) < NOISE_TOL) {
            *p = q;
            break;
        }
        *p = q;
    }
    return rc;
}

/* The noise power at param under lik (fc->pb). */
static int power_at(bf__fitctx *fc, const double *param, double *buf,
                    double *p)
{
    int rc = bf__curve(fc->pm, param, fc->work, fc->curve);
    if (rc == BF_OK) {
        rc = adjusted_power(fc, param, buf, p);
    }
    return rc;
}

static void clear(bf_interval *out, bf_noise noise)
{
    size_t j;
    memset(out, 0, sizeof *out);
    out->noise = noise;
    out->noise_power = NAN;
    out->sigma = NAN;
    out->scale = NAN;
    out->ml.lse = NAN; /* no estimate until the noise model has one */
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        out->low[j] = NAN;
        out->high[j] = NAN;
        out->robust[j] = NAN;
        out->gap_low[j] = NAN;
        out->gap_high[j] = NAN;
        out->ml.param[j] = NAN;
    }
}

/* Each free parameter j's interval around out->ml under fc->pb with the
 * criterion n ln(S_p / S_min) <= thr times its robust factor (1 without
 * one). */
static int profiles(bf__fitctx *fc, double thr, bf_interval *out)
{
    const bf_problem *pb = fc->pb;
    double d0[BF_MAX_PARAMS];
    size_t j;
    int rc = bf__profile_steps(fc, &out->ml, thr, d0); /* one for all */
    if (rc != BF_OK) {
        return rc;
    }
    for (j = 0; j < pb->type->p; j++) {
        unsigned open = 0;
        double gap[2];
        double c; /* the robust factor */
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        c = isfinite(out->robust[j]) ? out->robust[j] : 1.0;
        rc = bf__profile_ci_thr(fc, &out->ml, j, c * thr, d0[j], &out->low[j],
                                &out->high[j], &open, gap);
        if (rc != BF_OK) {
            out->low[j] = NAN;
            out->high[j] = NAN;
            return rc;
        }
        out->open |= (open & 3u) << (2 * j);
        out->gap_low[j] = gap[0];
        out->gap_high[j] = gap[1];
        /* open where the estimate is not on the bound: the profile stays
         * below the threshold all the way there; or split: below it in a
         * region apart from the estimate's too (the interval their hull) */
        if (((open & 1u) && out->ml.param[j] > pb->lo[j]) ||
            ((open & 2u) && out->ml.param[j] < pb->hi[j]) || (open & 4u)) {
            out->not_identified |= 1u << j;
        }
        if (open & 8u) {
            out->competing |= 1u << j;
        }
    }
    return BF_OK;
}

/* ==== the specular models (SPEC §9) ====================================== */

/* The noise power at param of a specular model under fc->pb (its data and
 * weights): bf__noise_power on the mean's shape rho_hat / max. */
static int spec_power(bf__fitctx *fc, const double *param, double *buf,
                      double *p)
{
    double top = 0.0;
    size_t k;
    int rc = bf__curve(fc->pm, param, fc->work, fc->curve);
    for (k = 0; rc == BF_OK && k < fc->pb->n; k++) {
        top = fc->curve[k] > top ? fc->curve[k] : top;
    }
    if (rc != BF_OK || !(top > 0.0) || !isfinite(top)) {
        return BF_EDOM;
    }
    for (k = 0; k < fc->pb->n; k++) {
        fc->curve[k] /= top;
    }
    return adjusted_power(fc, param, buf, p);
}

/* A specular model's likelihood (the setup of its intervals): its scales
 * are parameters, solved by NNLS (varpro.c) in every evaluation, the
 * likelihood's variances held at the fit (noise.c, bf__spec_weights):
 * from the objective's fit, p there, the maximum-likelihood fit under the
 * weights of p, p again (NOISE_PASSES); the profiles are then taken under
 * the last weights, k = free parameters + [p estimated] (no scale beside
 * the model's own), each parameter's threshold times its robust factor
 * (sandwich.c: the peak's variance is extrapolated from p over the lobe's
 * decades, and a p a little off, or a wrong fixed noise model, makes the
 * intervals narrow). w: n doubles, the weights, borrowed by *lik. */
static int spec_problem(bf__fitctx *fc, const bf_fit_result *best,
                        bf_noise noise, double level, double *w,
                        double *buf, bf_interval *out, bf_problem *lik,
                        double *thr)
{
    const bf_problem *pb = fc->pb;
    double n_w = bf__weight_sum(pb);
    double nu = bf__lik_dof(pb, noise);
    double p = noise == BF_NOISE_RELATIVE ? 2.0 : 0.0;
    double top = 0.0;
    double rss = 0.0;
    size_t pass;
    size_t k;
    int rc = BF_OK;
    if (!(nu >= 1.0)) {
        return BF_EDOM; /* K <= estimated parameters: no noise estimate */
    }
    *lik = *pb;
    lik->objective = BF_OBJ_NGAN;
    lik->weight = w;
    out->ml = *best;
    if (noise == BF_NOISE_AUTO) {
        rc = spec_power(fc, best->param, buf, &p);
    }
    for (pass = 0; rc == BF_OK && pass < NOISE_PASSES; pass++) {
        double p_new;
        bf_fit_result ml;
        rc = bf__spec_weights(fc, out->ml.param, p, w, NULL);
        if (rc == BF_OK) {
            bf__fitctx_use(fc, lik);
            rc = bf__varpro_refine(fc, out->ml.param, &ml);
            bf__fitctx_use(fc, pb);
        }
        if (rc != BF_OK) {
            break;
        }
        out->ml = ml;
        if (noise != BF_NOISE_AUTO) {
            break;
        }
        rc = spec_power(fc, out->ml.param, buf, &p_new);
        if (rc != BF_OK || fabs(p_new - p) < NOISE_TOL ||
            pass + 1 == NOISE_PASSES) {
            break;
        }
        p = p_new;
    }
    if (rc == BF_OK) { /* sigma^2 = RSS_v / nu, relative to M */
        rc = bf__curve(fc->pm, out->ml.param, fc->work, fc->curve);
        for (k = 0; rc == BF_OK && k < pb->n; k++) {
            top = fc->curve[k] > top ? fc->curve[k] : top;
        }
        for (k = 0; rc == BF_OK && k < pb->n; k++) {
            double l = fc->curve[k] / top;
            double r = fc->curve[k] - pb->data[k];
            double wk = pb->weight != NULL ? pb->weight[k] : 1.0;
            rss += wk * r * r /
                   pow(l > BF_LOG_FLOOR ? l : BF_LOG_FLOOR, p);
        }
    }
    if (rc == BF_OK) {
        out->noise_power = p;
        out->scale = 1.0; /* the model's own scales */
        out->sigma = sqrt(rss / nu) / top;
        out->method = BF_CI_PROFILE_LIK;
        *thr = bf__lik_threshold(n_w, nu, level);
        /* 1 where the derivatives cannot be taken (sandwich.c) */
        (void)bf__robust_factors(fc, out->ml.param, p, fc->curve, top, nu,
                                 buf, out->robust);
    }
    return rc;
}

/* bf__interval_problem with buf: (BF_MAX_PARAMS + 4) n doubles of
 * scratch for the noise power's leverages (adjusted_power) and the
 * robust factors (bf__robust_factors). */
static int interval_problem(bf__fitctx *fc, const bf_fit_result *best,
                            bf_noise noise, double level, double *w,
                            double *buf, bf_interval *out, bf_problem *lik,
                            double *thr)
{
    const bf_problem *pb = fc->pb;
    double n_w = bf__weight_sum(pb);
    double nu = bf__lik_dof(pb, noise);
    double p = noise == BF_NOISE_RELATIVE ? 2.0 : 0.0;
    double sigma2 = NAN;
    size_t pass;
    int rc = BF_OK;

    clear(out, noise);
    if (noise == BF_NOISE_OBJECTIVE) { /* the objective's own S */
        out->method = BF_CI_PROFILE;
        out->ml = *best;
        *lik = *pb;
        *thr = gsl_cdf_chisq_Pinv(level, 1.0); /* Wilks, 3.841 at 95% */
        return BF_OK;
    }
    if (pb->type->kind == BF_MODEL_SPECULAR) {
        return spec_problem(fc, best, noise, level, w, buf, out, lik,
                            thr);
    }
    if (!(nu >= 1.0)) {
        return BF_EDOM; /* K <= estimated parameters: no noise estimate */
    }
    *lik = *pb;
    lik->objective = BF__OBJ_LIK;
    lik->noise_power = p;
    bf__fitctx_use(fc, lik);
    out->ml = *best;
    if (noise == BF_NOISE_AUTO) {
        rc = power_at(fc, best->param, buf, &p);
    }
    for (pass = 0; rc == BF_OK && pass < NOISE_PASSES; pass++) {
        double p_new;
        lik->noise_power = p;
        rc = bf__ml_fit(fc, out->ml.param, &out->ml);
        if (rc != BF_OK || noise != BF_NOISE_AUTO) {
            break;
        }
        rc = power_at(fc, out->ml.param, buf, &p_new);
        if (rc != BF_OK || fabs(p_new - p) < NOISE_TOL ||
            pass + 1 == NOISE_PASSES) {
            break;
        }
        p = p_new;
    }
    if (rc == BF_OK) {
        rc = bf__curve(fc->pm, out->ml.param, fc->work, fc->curve);
    }
    if (rc == BF_OK) {
        bf__lik_scale(lik, fc->curve, nu, fc->scratch, &out->scale,
                      &sigma2);
        out->noise_power = p;
        out->sigma = sqrt(sigma2) / out->scale; /* of the fitted max */
        out->method = BF_CI_PROFILE_LIK;
        *thr = bf__lik_threshold(n_w, nu, level);
    }
    bf__fitctx_use(fc, pb);
    return rc;
}

int bf__interval_problem(bf__fitctx *fc, const bf_fit_result *best,
                         bf_noise noise, double level, double *w,
                         bf_interval *out, bf_problem *lik, double *thr)
{
    /* the noise power's leverages; a specular model's robust factors */
    int use = noise == BF_NOISE_AUTO ||
              (noise != BF_NOISE_OBJECTIVE &&
               fc->pb->type->kind == BF_MODEL_SPECULAR);
    double *buf = use ? malloc((BF_MAX_PARAMS + 4) * fc->pb->n * sizeof *buf)
                      : NULL;
    int rc = use && buf == NULL
                 ? BF_ENOMEM
                 : interval_problem(fc, best, noise, level, w, buf, out, lik,
                                    thr);
    free(buf);
    return rc;
}

int bf__intervals(bf__fitctx *fc, const bf_fit_result *best, bf_noise noise,
                  double level, bf_interval *out)
{
    const bf_problem *pb = fc->pb;
    bf_problem lik;
    double thr = NAN;
    double *w = malloc((pb->n + 1) * sizeof *w);
    int rc = w == NULL ? BF_ENOMEM
                       : bf__interval_problem(fc, best, noise, level, w, out,
                                              &lik, &thr);
    if (rc == BF_OK) {
        bf__fitctx_use(fc, &lik);
        rc = profiles(fc, thr, out);
        bf__fitctx_use(fc, pb);
    }
    free(w);
    return rc;
}

int bf_fit_intervals(const bf_problem *pb, const bf_fit_result *best,
                     bf_noise noise, double level, bf_interval *out)
{
    bf__solo so;
    int rc;
    if (pb == NULL || best == NULL || out == NULL || pb->type == NULL ||
        pb->data == NULL || bf_noise_name(noise) == NULL ||
        !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__intervals(&so.fc, best, noise, level, out);
    bf__solo_free(&so);
    return rc;
}

int bf_interval_holds(const bf_interval *iv, size_t j, double x)
{
    if (iv == NULL || j >= BF_MAX_PARAMS ||
        !(iv->low[j] <= x && x <= iv->high[j])) {
        return 0;
    }
    return !(iv->gap_low[j] < x && x < iv->gap_high[j]);
}

double bf_interval_length(const bf_interval *iv, size_t j)
{
    double len;
    if (iv == NULL || j >= BF_MAX_PARAMS) {
        return NAN;
    }
    len = iv->high[j] - iv->low[j];
    if (isfinite(iv->gap_low[j]) && isfinite(iv->gap_high[j])) {
        len -= iv->gap_high[j] - iv->gap_low[j];
    }
    return len;
}
