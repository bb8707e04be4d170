/* oren_nayar.c: Oren-Nayar's rough diffuse model with interreflections, in
 * radiance form (SPEC §5).
 *
 * References:
 *   [1] M. Oren, S. K. Nayar, "Generalization of the Lambertian model and
 *       implications for machine vision", IJCV 14(3), 1995 (the full model
 *       with the interreflection term L2).
 *   [2] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (ON is evaluated at CURET's tabulated rho, sigma; Table 2).
 *
 * Equations (alpha = max(ti, ts), beta = min(ti, ts), sigma in radians,
 * cos dphi = -cos phi_s in Beckmann's frame):          SPEC §1.2, §5
 *   C1 = 1 - 0.5 s2 / (s2 + 0.33)                       SPEC §5
 *   C2 = 0.45 s2 / (s2 + 0.09) sin alpha           if cos dphi >= 0
 *        0.45 s2 / (s2 + 0.09) (sin alpha - (2 beta/pi)^3)  otherwise
 *   C3 = 0.125 s2 / (s2 + 0.09) (4 alpha beta / pi^2)^2
 *   L1 = rho/pi cos ti [C1 + cos dphi C2 tan beta
 *                       + (1 - |cos dphi|) C3 tan((alpha + beta)/2)]
 *   L2 = 0.17 rho^2/pi cos ti s2/(s2 + 0.13) [1 - cos dphi (2 beta/pi)^2]
 *   L  = L1 + L2                                        SPEC §5
 *
 * Limits: at theta_i = pi/2 the value is 0 (the cos ti factor; SPEC §5).
 * Otherwise beta <= theta_i < pi/2 and (alpha + beta)/2 < pi/2, so both
 * tangents are finite and no special case is needed. (Note: near the corner
 * theta_i, theta_s -> pi/2 the products cos ti tan beta and
 * cos ti tan((alpha+beta)/2) stay bounded, by 1 and 2, but do not all tend to
 * 0; returning 0 exactly at theta_i = pi/2 is SPEC §5's convention.)
 * Where theta_i or theta_s is 0 (azimuth undefined) beta = 0 removes every
 * term that depends on phi_s, so the value is finite and phi-independent.
 *
 * Departure from SPEC §5: the value is clamped at 0. For very rough
 * surfaces the qualitative model goes slightly negative in the forward
 * grazing corner, where cos dphi C2 tan(beta) < 0 outweighs C1 (e.g. rho
 * 0.05, sigma 1, theta_i 1.43117, theta_s pi/2, phi_s 0 gives -1.7e-4). A
 * radiance cannot be negative; the term is Oren & Nayar's fit to their
 * numerical model, not physics, and their exact model is non-negative, so
 * 0 is the physically meaningful value there. The clamp never acts at the
 * study's tabulated values: CURET's zeniths stop at 1.464 and its samples'
 * sigma at 0.978, where the formula is positive, so Tables 2 and 3 are
 * unchanged (checked by test_oren_nayar and test_reproduction). Where ON
 * is fitted it can (sigma = 1.57 on samples 7, 19, 61: three
 * configurations); the kernel counts where (on_kclamped) and the analysis
 * flags those fits (doc/methods.md §8).
 */
#include <math.h>

#include <string.h>

#include "fit/engine.h"

/* Geometry-only terms of Oren-Nayar (SPEC §5) at one configuration. */
typedef struct {
    double ci;        /* cos theta_i (0: the value is 0, nothing else set) */
    double cos_dphi;  /* cos of the sample-frame azimuth difference */
    double sin_alpha; /* sin alpha */
    double b3;        /* (2 beta / pi)^3 */
    double q2;        /* (2 beta / pi)^2 */
    double r2;        /* (4 alpha beta / pi^2)^2 */
    double tan_beta;  /* tan beta */
    double tan_mean;  /* tan((alpha + beta) / 2) */
} on_terms_t;

/* Coefficients of SPEC §5 that depend on (rho, sigma) only. */
typedef struct {
    double c1;
    double c2_scale;
    double c3_scale;
    double l2_scale;
    double rho_pi;
} on_coef_t;

/* The geometry-only terms of SPEC §5 at one configuration: everything but
 * rho and sigma. The study path computes them once per configuration and
 * evaluates every sample's (rho, sigma) with on_value; eval_on does the
 * same per call, so both give the same bits. */
static void on_terms(const bf_geom *g, on_terms_t *t)
{
    double ti = g->theta_i;
    double ts = g->theta_s;
    double si;
    double alpha;
    double beta;
    double q;
    double r;
    bf__zenith_sincos(ti, &si, &t->ci);
    if (t->ci == 0.0) {
        return; /* theta_i = pi/2: L = 0 (SPEC §5); nothing else is used */
    }
    alpha = (ti > ts) ? ti : ts;
    beta = (ti > ts) ? ts : ti;
    t->cos_dphi = -cos(g->phi_s); /* sample frame, SPEC §1.2, §5 */
    q = 2.0 * beta / BF__PI;      /* 2 beta / pi */
    t->q2 = q * q;
    t->b3 = q * q * q;
    t->sin_alpha = sin(alpha);
    r = 4.0 * alpha * beta / (BF__PI * BF__PI);
    t->r2 = r * r;
    t->tan_beta = tan(beta);
    t->tan_mean = tan(0.5 * (alpha + beta));
}

/* L1 + L2 of SPEC §5, unclamped, from one configuration's terms (theta_i
 * < pi/2) and the coefficients of one (rho, sigma). Inline and branch-free
 * so that the engine's loop vectorises; on_value and the kernel both
 * use it, so they give the same bits. */
static inline double on_formula(double ci, double cos_dphi, double sin_alpha,
                                double b3, double q2, double r2,
                                double tan_beta, double tan_mean,
                                const on_coef_t *c)
{
    /* C2, SPEC §5: the backward half-plane subtracts (2 beta / pi)^3 */
    double c2 = (cos_dphi >= 0.0) ? c->c2_scale * sin_alpha
                                  : c->c2_scale * (sin_alpha - b3);
    double c3 = c->c3_scale * r2; /* C3, SPEC §5 */
    double l1 = c->rho_pi * ci
                * (c->c1 + (cos_dphi * c2 * tan_beta)
                   + ((1.0 - fabs(cos_dphi)) * c3 * tan_mean));
    double l2 = c->l2_scale * ci * (1.0 - (cos_dphi * q2)); /* L2 */
    return l1 + l2;
}

/* L of SPEC §5 from the terms of one configuration and the coefficients
 * of one (rho, sigma) (on_coef), clamped at 0 (doc/methods.md §8). */
static double on_value(const on_terms_t *t, const on_coef_t *c)
{
    if (t->ci == 0.0) {
        return 0.0; /* theta_i = pi/2: cos ti = 0, SPEC §5 */
    }
    return fmax(0.0, on_formula(t->ci, t->cos_dphi, t->sin_alpha, t->b3,
                                t->q2, t->r2, t->tan_beta, t->tan_mean, c));
}

/* The coefficients of SPEC §5 that depend on rho and sigma only. */
static void on_coef(double rho, double sigma, on_coef_t *c)
{
    double s2 = sigma * sigma;
    c->c1 = 1.0 - (0.5 * s2 / (s2 + 0.33));  /* C1, SPEC §5 */
    c->c2_scale = 0.45 * s2 / (s2 + 0.09);   /* C2 without its angles */
    c->c3_scale = 0.125 * s2 / (s2 + 0.09);  /* C3 without its angles */
    c->l2_scale = 0.17 * (rho * rho) / BF__PI * (s2 / (s2 + 0.13));
    c->rho_pi = rho / BF__PI;
}

/* Evaluates ON at param = {rho, sigma}; both checked by bf_model_eval. */
static int eval_on(const double *param, size_t count, const bf_geom *geom,
                   double *out, void *work)
{
    on_coef_t c;
    size_t k;
    (void)work;
    on_coef(param[0], param[1], &c);
    for (k = 0; k < count; k++) {
        on_terms_t t;
        on_terms(&geom[k], &t);
        out[k] = on_value(&t, &c);
    }
    return BF_OK;
}

/* ==== the engine's kernel ================================================ */

/* The terms of on_terms as 8 rows of n (SoA); at theta_i = pi/2 only
 * ci = 0 matters and the others are 0 so the loop stays finite. */
enum { ON_CI = 0, ON_CDPHI, ON_SA, ON_B3, ON_Q2, ON_R2, ON_TB, ON_TM, ON_NT };

static void on_kterms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t n = cs->n;
    size_t k;
    (void)kr;
    for (k = 0; k < n; k++) {
        on_terms_t t;
        memset(&t, 0, sizeof t);
        on_terms(&cs->geom[k], &t);
        terms[ON_CI * n + k] = t.ci;
        terms[ON_CDPHI * n + k] = t.cos_dphi;
        terms[ON_SA * n + k] = t.sin_alpha;
        terms[ON_B3 * n + k] = t.b3;
        terms[ON_Q2 * n + k] = t.q2;
        terms[ON_R2 * n + k] = t.r2;
        terms[ON_TB * n + k] = t.tan_beta;
        terms[ON_TM * n + k] = t.tan_mean;
    }
}

/* The unclamped formula at every configuration into out. */
static void on_unclamped(const bf__prep *pm, const double *param, double *out)
{
    const double *t = pm->terms;
    size_t n = pm->n;
    on_coef_t c;
    size_t k;
    on_coef(param[0], param[1], &c); /* rho, sigma: SPEC §5 */
#pragma omp simd
    for (k = 0; k < n; k++) {
        out[k] = on_formula(t[ON_CI * n + k], t[ON_CDPHI * n + k],
                            t[ON_SA * n + k], t[ON_B3 * n + k],
                            t[ON_Q2 * n + k], t[ON_R2 * n + k],
                            t[ON_TB * n + k], t[ON_TM * n + k], &c);
    }
}

static int on_kvalues(const bf__prep *pm, const double *param, void *work,
                      double *out)
{
    const double *ci = pm->terms + ON_CI * pm->n;
    size_t k;
    (void)work;
    on_unclamped(pm, param, out);
#pragma omp simd
    for (k = 0; k < pm->n; k++) {
        /* theta_i = pi/2: 0 (SPEC §5); the clamp at 0 (methods.md §8) */
        out[k] = (ci[k] == 0.0) ? 0.0 : fmax(0.0, out[k]);
    }
    return BF_OK;
}

/* Configurations where SPEC §5's formula is negative at param, so the
 * clamp acts (doc/methods.md §8). Allocation-free: one pass per config. */
static size_t on_kclamped(const bf__prep *pm, const double *param)
{
    const double *t = pm->terms;
    size_t n = pm->n;
    on_coef_t c;
    size_t k;
    size_t count = 0;
    on_coef(param[0], param[1], &c);
    for (k = 0; k < n; k++) {
        double v = on_formula(t[ON_CI * n + k], t[ON_CDPHI * n + k],
                              t[ON_SA * n + k], t[ON_B3 * n + k],
                              t[ON_Q2 * n + k], t[ON_R2 * n + k],
                              t[ON_TB * n + k], t[ON_TM * n + k], &c);
        count += (t[ON_CI * n + k] != 0.0) && (v < 0.0);
    }
    return count;
}

static const bf_kernel on_kernel = {
    .n_terms = ON_NT,
    .terms = on_kterms,
    .values = on_kvalues,
    .clamped = on_kclamped,
    .cheap = -1,
};

/* rho and sigma are fixed inputs of the study (CURET's op.dat, the paper's
 * Table 2), not fitted: no grid. Defaults give Lambert (sigma = 0). The
 * exact fit (doc/methods.md §6) frees both: rho over [0.05, 1] (rho = 0
 * gives no radiance to normalise), step 0.05; sigma over [0, 1.57] rad
 * (SPEC §5's domain is [0, pi/2]), step 0.01. */
static const bf_param param_on[2] = {
    {.name = "rho", .label = "albedo rho", .unit = "1", .min = 0.0,
     .max = 1.0, .value = 1.0, .fitted = 0, .input = BF_INPUT_ON,
     .input_col = 0, .free_lo = 0.05, .free_hi = 1.0, .free_step = 0.05},
    {.name = "sigma", .label = "facet slope sigma", .unit = "rad",
     .min = 0.0, .max = BF__PI_2, .value = 0.0, .fitted = 0,
     .input = BF_INPUT_ON, .input_col = 1, .free_lo = 0.0, .free_hi = 1.57,
     .free_step = 0.01},
};

/* At sigma = 0, C1 = 1 and C2 = C3 = L2 = 0: L = rho/pi cos ti, LAMBERT
 * after normalisation (SPEC §5, §6a). */
static const bf_model_type on_type = {
    .name = "ON",
    .title = "Oren-Nayar with interreflections",
    .reference = "Oren & Nayar IJCV 1995 (full model), SPEC §5",
    .p = 2,
    .param = param_on,
    .eval = eval_on,
    .kernel = &on_kernel,
    .style = 2,
    .reduces_to = "LAMBERT",
    .reduces_param = 1,
    .reduces_at = 0.0,
};

const bf_model_type *const bf_model_on = &on_type;
