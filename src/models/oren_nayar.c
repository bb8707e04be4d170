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

/* Evaluates ON at param = {rho, sigma}; both checked by bf_model_eval. */
static int eval_on(const double *param, size_t count, const bf_geom *geom,
                   double *out)
{
    double rho = param[0];
    double sigma = param[1];
    double s2 = sigma * sigma;
    double c1 = 1.0 - (0.5 * s2 / (s2 + 0.33));  /* C1, SPEC §5 */
    double c2_scale = 0.45 * s2 / (s2 + 0.09);   /* C2 without its angles */
    double c3_scale = 0.125 * s2 / (s2 + 0.09);  /* C3 without its angles */
    double l2_scale = 0.17 * (rho * rho) / BF__PI * (s2 / (s2 + 0.13));
    double rho_pi = rho / BF__PI;
    size_t k;
    for (k = 0; k < count; k++) {
        double ti = geom[k].theta_i;
        double ts = geom[k].theta_s;
        double ci;
        double si;
        double alpha;
        double beta;
        double cos_dphi;
        double c2;
        double c3;
        double q;
        double b3;
        double l1;
        double l2;
        bf__zenith_sincos(ti, &si, &ci);
        if (ci == 0.0) {
            out[k] = 0.0; /* theta_i = pi/2: cos ti = 0, SPEC §5 */
            continue;
        }
        alpha = (ti > ts) ? ti : ts;
        beta = (ti > ts) ? ts : ti;
        cos_dphi = -cos(geom[k].phi_s); /* sample frame, SPEC §1.2, §5 */
        q = 2.0 * beta / BF__PI;        /* 2 beta / pi */
        b3 = q * q * q;
        if (cos_dphi >= 0.0) {
            c2 = c2_scale * sin(alpha); /* C2, SPEC §5 */
        } else {
            c2 = c2_scale * (sin(alpha) - b3); /* C2, SPEC §5 */
        }
        {
            double r = 4.0 * alpha * beta / (BF__PI * BF__PI);
            c3 = c3_scale * (r * r); /* C3, SPEC §5 */
        }
        l1 = rho_pi * ci
             * (c1 + (cos_dphi * c2 * tan(beta))
                + ((1.0 - fabs(cos_dphi)) * c3 * tan(0.5 * (alpha + beta))));
        l2 = l2_scale * ci * (1.0 - (cos_dphi * (q * q))); /* L2, SPEC §5 */
        /* L, SPEC §5, clamped at 0 (see the departure noted above) */
        out[k] = fmax(0.0, l1 + l2);
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
