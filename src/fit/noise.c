/* noise.c: the statistical model behind the intervals (doc/methods.md §3)
 * -- the likelihood of normalised data under a power-law noise model, with
 * the scale and the noise level profiled in closed form, and the noise
 * power estimated from the residuals.
 *
 * [1] Y. Pawitan, "In All Likelihood", OUP 2001, §6.8 (Gaussian
 *     likelihood with a variance function), §10.6 (profile likelihood of
 *     nuisance parameters).
 * [2] R. J. Carroll, D. Ruppert, "Transformation and Weighting in
 *     Regression", Chapman & Hall 1988, §3.2 (power-of-the-mean variance
 *     functions, var = sigma^2 mu^p, and the estimation of p).
 *
 * Model: D_k = s L_k(theta) + e_k, e_k ~ N(0, sigma^2 v_k) independent,
 * v_k = max(L_k, f)^p (f = BF_LOG_FLOOR; var proportional to (s L)^p, the
 * factor s^p absorbed by sigma^2). The data's normalisation by their own
 * maximum is one factor on every D_k: s absorbs it, so no configuration is
 * special. With w_k the weights and n = sum w:
 *   s*(theta) = sum w L D / v / sum w L^2 / v                 (weighted LS)
 *   RSS_v     = sum w (D - s* L)^2 / v,   sigma^2* = RSS_v / n
 *   -2 ln L(theta, s*, sigma^2*) = n ln(RSS_v / n) + sum w ln v + n
 *                                = n ln S + const,   S = g RSS_v,
 *   g = exp(sum w ln v / n)                                       [1] §6.8
 * so the likelihood-ratio criterion is n ln(S_p / S_min) as for a
 * constant-variance fit, with this S. p = 0 is the scale objective.
 */
#include <math.h>
#include <string.h>

#include "fit/engine.h"

/* Noise powers of the first pass of bf__noise_power: 0, 0.1, ... PMAX. */
#define P_STEPS 30
/* Golden-section tolerance of p. */
#define P_TOL 1e-4

static double weight_of(const bf_problem *pb, size_t k)
{
    return pb->weight != NULL ? pb->weight[k] : 1.0;
}

/* One pass: v_k = max(L_k, f)^p into v, s* of the weighted least squares
 * with variances v into *scale, and g = exp(sum w ln v / sum w). */
static void variances(const bf_problem *pb, const double *curve, double p,
                      double *v, double *scale, double *g)
{
    size_t k;
    double sl = 0.0;
    double sw = 0.0;
    double num = 0.0;
    double den = 0.0;
    for (k = 0; k < pb->n; k++) {
        double c = curve[k];
        double l = c > BF_LOG_FLOOR ? c : BF_LOG_FLOOR;
        double w = weight_of(pb, k);
        double lv = p == 0.0 || p == 2.0 ? 0.0 : p * log(l);
        double vk = p == 0.0 ? 1.0 : (p == 2.0 ? l * l : exp(lv));
        double iv = w / vk;
        v[k] = vk;
        sl += p == 2.0 ? w * 2.0 * log(l) : w * lv;
        sw += w;
        num += iv * c * pb->data[k];
        den += iv * c * c;
    }
    *scale = den > 0.0 ? num / den : 0.0;
    *g = sw > 0.0 ? exp(sl / sw) : 1.0;
}

/* S at noise power p (v: n doubles of scratch; want_resid: v gets r_k
 * with S = sum w r_k^2), each squared residual divided by 1 - h_k where
 * lev (the leverages h, or NULL) is given. */
static double value_at(const bf_problem *pb, const double *curve, double p,
                       const double *lev, double *v, int want_resid)
{
    double s;
    double g;
    double sum = 0.0;
    size_t k;
    variances(pb, curve, p, v, &s, &g);
    for (k = 0; k < pb->n; k++) {
        double e = s * curve[k] - pb->data[k];
        double q = weight_of(pb, k) * e * e / v[k];
        if (lev != NULL) {
            q /= 1.0 - (lev[k] < BF__LEV_MAX ? lev[k] : BF__LEV_MAX);
        }
        if (want_resid) {
            v[k] = sqrt(g / v[k]) * e;
        }
        sum += q;
    }
    return g * sum;
}

double bf__lik_value(const bf_problem *pb, const double *curve,
                     double *scratch)
{
    return value_at(pb, curve, pb->noise_power, NULL, scratch, 0);
}

void bf__lik_residuals(const bf_problem *pb, const double *curve,
                       double *resid)
{
    value_at(pb, curve, pb->noise_power, NULL, resid, 1);
}

double bf__noise_power(const bf_problem *pb, const double *curve,
                       const double *lev, double *scratch)
{
    const double phi = 0.5 * (sqrt(5.0) - 1.0);
    double best = HUGE_VAL;
    double p_best = 0.0;
    double a;
    double b;
    double c;
    double d;
    double fc;
    double fd;
    int i;
    /* -2 ln L(p) = n ln S(p) + const: minimise S over p [2] §3.2 */
    for (i = 0; i <= P_STEPS; i++) {
        double p = BF_NOISE_PMAX * i / P_STEPS;
        double f = value_at(pb, curve, p, lev, scratch, 0);
        if (f < best) {
            best = f;
            p_best = p;
        }
    }
    a = p_best - BF_NOISE_PMAX / P_STEPS;
    b = p_best + BF_NOISE_PMAX / P_STEPS;
    a = a < 0.0 ? 0.0 : a;
    b = b > BF_NOISE_PMAX ? BF_NOISE_PMAX : b;
    c = b - phi * (b - a);
    d = a + phi * (b - a);
    fc = value_at(pb, curve, c, lev, scratch, 0);
    fd = value_at(pb, curve, d, lev, scratch, 0);
    while (b - a > P_TOL) {
        if (fc < fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - phi * (b - a);
            fc = value_at(pb, curve, c, lev, scratch, 0);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + phi * (b - a);
            fd = value_at(pb, curve, d, lev, scratch, 0);
        }
    }
    c = 0.5 * (a + b);
    return value_at(pb, curve, c, lev, scratch, 0) < best ? c : p_best;
}

void bf__lik_scale(const bf_problem *pb, const double *curve, double dof,
                   double *scratch, double *scale, double *sigma2)
{
    double g;
    double rss = 0.0;
    size_t k;
    variances(pb, curve, pb->noise_power, scratch, scale, &g);
    for (k = 0; k < pb->n; k++) {
        double r = *scale * curve[k] - pb->data[k];
        rss += weight_of(pb, k) * r * r / scratch[k];
    }
    *sigma2 = dof > 0.0 ? rss / dof : NAN;
}

/* ==== the specular models (SPEC §9): weights of the likelihood ========== */

/* For a model whose scales are parameters (rho_hat = BRDF cos ti in sr^-1,
 * the scales solved by NNLS, varpro.c) the noise model is the same with
 * the mean's shape L_k = rho_hat_k / M (M its maximum): var e_k =
 * sigma^2 M^2 max(L_k, f)^p. Its variances are held at the fit (Carroll &
 * Ruppert [2] §2.1, generalised least squares with estimated weights:
 * fit, weights from the fit, refit), so the likelihood is a weighted sum
 * of squares whose scales NNLS solves exactly, and -2 ln L = n ln S +
 * const as above. */
int bf__spec_weights(bf__fitctx *fc, const double *param, double p,
                     double *w, double *m)
{
    const bf_problem *pb = fc->pb;
    double top = 0.0;
    double sw = 0.0;
    double sv = 0.0;
    size_t k;
    int rc = bf__curve(fc->pm, param, fc->work, fc->curve);
    if (rc != BF_OK) {
        return BF_EDOM;
    }
    for (k = 0; k < pb->n; k++) {
        top = fc->curve[k] > top ? fc->curve[k] : top;
    }
    if (!(top > 0.0) || !isfinite(top)) {
        return BF_EDOM;
    }
    for (k = 0; k < pb->n; k++) {
        double l = fc->curve[k] / top;
        double w0 = weight_of(pb, k);
        w[k] = w0 / pow(l > BF_LOG_FLOOR ? l : BF_LOG_FLOOR, p);
        sw += w0;
        sv += w[k];
    }
    for (k = 0; k < pb->n; k++) {
        w[k] *= sw / sv; /* sum w = sum w0: n of the criterion */
    }
    if (m != NULL) {
        *m = top;
    }
    return BF_OK;
}

/* ==== names ============================================================== */

static const char *const noise_names[] = {"auto", "absolute", "relative",
                                          "objective"};

#define N_NOISE (sizeof noise_names / sizeof noise_names[0])

static const char *const noise_variances[N_NOISE] = {
    "variance ~ value^p, p fitted per fit", "constant variance",
    "variance ~ value^2", "the objective's own S"};

const char *bf_noise_name(bf_noise noise)
{
    return (unsigned)noise < N_NOISE ? noise_names[noise] : NULL;
}

const char *bf_noise_variance(bf_noise noise)
{
    return (unsigned)noise < N_NOISE ? noise_variances[noise] : NULL;
}

int bf_noise_find(const char *name, bf_noise *noise)
{
    size_t i;
    if (name == NULL || noise == NULL) {
        return BF_EINVAL;
    }
    for (i = 0; i < N_NOISE; i++) {
        if (strcmp(name, noise_names[i]) == 0) {
            *noise = (bf_noise)i;
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}

const char *bf_ci_method_name(bf_ci_method m)
{
    static const char *const names[] = {"", "profile", "profile-lik",
                                        "residual-bootstrap", "neyman"};
    return (unsigned)m < sizeof names / sizeof names[0] ? names[m] : NULL;
}

bf_ci_method bf_fit_stats_ci_method(const bf_fit_stats *st, size_t j)
{
    return j < BF_MAX_PARAMS && ((st->ci_neyman >> j) & 1u) ? BF_CI_NEYMAN
                                                            : st->ci_method;
}
