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
 * 0 is the physically meaningful value there. The clamp never acts on the
 * study: CURET's zeniths stop at 1.464 and its samples' sigma at 0.978,
 * where the formula is positive, so Tables 2 and 3 are unchanged (checked
 * by test_oren_nayar and test_reproduction).
 */
#include <math.h>

#include "internal.h"

/* The geometry-only terms of SPEC §5 at one configuration: everything but
 * rho and sigma. The study path computes them once per configuration and
 * evaluates every sample's (rho, sigma) with bf__on_value; eval_on does the
 * same per call, so both give the same bits. */
void bf__on_terms(const bf_geom *g, bf__on_terms_t *t)
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

/* L of SPEC §5 from the terms of one configuration and the coefficients
 * of one (rho, sigma) (bf__on_coef). */
double bf__on_value(const bf__on_terms_t *t, const bf__on_coef_t *c)
{
    double c2;
    double c3;
    double l1;
    double l2;
    if (t->ci == 0.0) {
        return 0.0; /* theta_i = pi/2: cos ti = 0, SPEC §5 */
    }
    if (t->cos_dphi >= 0.0) {
        c2 = c->c2_scale * t->sin_alpha; /* C2, SPEC §5 */
    } else {
        c2 = c->c2_scale * (t->sin_alpha - t->b3); /* C2, SPEC §5 */
    }
    c3 = c->c3_scale * t->r2; /* C3, SPEC §5 */
    l1 = c->rho_pi * t->ci
         * (c->c1 + (t->cos_dphi * c2 * t->tan_beta)
            + ((1.0 - fabs(t->cos_dphi)) * c3 * t->tan_mean));
    l2 = c->l2_scale * t->ci * (1.0 - (t->cos_dphi * t->q2)); /* L2 */
    /* L, SPEC §5, clamped at 0 (see the departure noted above) */
    return fmax(0.0, l1 + l2);
}

/* The coefficients of SPEC §5 that depend on rho and sigma only. */
void bf__on_coef(double rho, double sigma, bf__on_coef_t *c)
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
                   double *out)
{
    bf__on_coef_t c;
    size_t k;
    bf__on_coef(param[0], param[1], &c);
    for (k = 0; k < count; k++) {
        bf__on_terms_t t;
        bf__on_terms(&geom[k], &t);
        out[k] = bf__on_value(&t, &c);
    }
    return BF_OK;
}

/* rho and sigma are fixed inputs of the study (CURET's op.dat, the paper's
 * Table 2), not fitted: no grid. Defaults give Lambert (sigma = 0). */
static const bf_param param_on[2] = {
    {"rho", "albedo rho", "1", 0.0, 1.0, 1.0, 0, 0.0, 0.0, 0},
    {"sigma", "facet slope sigma", "rad", 0.0, BF__PI_2, 0.0, 0, 0.0, 0.0, 0},
};

static const bf_model_type on_type = {
    "ON", "Oren-Nayar with interreflections",
    "Oren & Nayar IJCV 1995 (full model), SPEC §5", 2, param_on, eval_on};

const bf_model_type *const bf_model_on = &on_type;

/* 1 when type is ON (or a copy of it), recognised by its eval function;
 * used by the study path to reuse the geometry terms across samples. */
int bf__is_on(const bf_model_type *type)
{
    return type->eval == eval_on;
}
