/* fresnel.c: unpolarised Fresnel reflectance and the Fresnel correction
 * factor F_FC^2 of the FC models (SPEC §4).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (equations (P4)-(P6)).
 *   [2] L. B. Wolff, "Diffuse-reflectance model for smooth dielectric
 *       surfaces", JOSA A 11(11), 1994 (the Fresnel-corrected diffuse term).
 *   [3] M. Born, E. Wolf, "Principles of Optics", §1.5 (Fresnel formulae).
 *
 * Equations:
 *   alpha_t = asin(sin alpha_i / r)                          (P5), SPEC §4.1
 *   f = 1/2 sin^2(ai-at)/sin^2(ai+at) [1 + cos^2(ai+at)/cos^2(ai-at)]
 *                                                           (P4), SPEC §4.1
 *   F_FC^2 = [1 - f(ti, n)] [1 - f(asin(sin ts / n), 1/n)] cos ti
 *                                                           (P6), SPEC §4.2
 *
 * Departure from the paper: (P4) is printed without the factor 1/2; SPEC
 * §4.1 restores it (0 <= f <= 1). (P4) is evaluated in an algebraically
 * equivalent form without the 0/0 at alpha_i = 0 (see bf__fresnel_sc).
 */
#include <math.h>

#include "internal.h"

/* f(alpha_i, r) of SPEC §4.1 from s = sin alpha_i, c = cos alpha_i and
 * ct = cos alpha_t: bf__fresnel_s2ct (src/internal.h) with s^2. */
static double fresnel_sct(double s, double c, double ct, double r)
{
    return bf__fresnel_s2ct(s * s, c, ct, r);
}

/* f(alpha_i, r) from s = sin alpha_i and c = cos alpha_i (see
 * fresnel_sct). */
double bf__fresnel_sc(double s, double c, double r)
{
    double st = s / r; /* Snell (P5): sin alpha_t */
    if (r == 1.0) {
        return 0.0; /* no interface: no reflection at any angle */
    }
    if (st >= 1.0) {
        return 1.0; /* at or beyond the critical angle (r < 1): TIR */
    }
    /* cos alpha_t; (1 - st)(1 + st) is accurate when st is near 1 */
    return fresnel_sct(s, c, sqrt((1.0 - st) * (1.0 + st)), r);
}

/* Public entry point of SPEC §4.1. Returns NaN for r <= 0, non-finite
 * arguments or alpha_i outside [0, pi/2]. */
double bf_fresnel(double alpha_i, double r)
{
    double s;
    double c;
    if (!(r > 0.0) || !isfinite(r) || !(alpha_i >= 0.0)
        || !(alpha_i <= BF__PI_2)) {
        return NAN;
    }
    bf__zenith_sincos(alpha_i, &s, &c);
    return bf__fresnel_sc(s, c, r);
}

/* F_FC^2 of (P6), SPEC §4.2, from sines and cosines. The internal angle
 * asin(sin theta_s / n) is never formed: its sine is sin theta_s / n and its
 * cosine sqrt(1 - sin^2 theta_s / n^2) (well conditioned: the sine is at most
 * 1/n). Its refracted angle in air is theta_s itself (Snell), so the exact
 * cos theta_s is used as cos alpha_t instead of recomputing it as
 * sqrt(1 - (n sin(internal))^2), which loses up to half the digits near
 * grazing (1 - st ~ cos^2 theta_s / 2). */
double bf__fresnel_fc2_sc(double si, double ci, double ss, double cs,
                          double n)
{
    return bf__fc2_inline(si, ci, ss, cs, n); /* (P6), SPEC §4.2 */
}

/* F_FC^2 of (P6), SPEC §4.2, for n configurations at once: the models'
 * kernels (FC's workspace, WNO's and WNO-R's terms). */
BF__CLONES
void bf__fc2_values(size_t n, const double *si, const double *ci,
                    const double *ss, const double *cs, double n_index,
                    double *out)
{
    size_t k;
#pragma omp simd
    for (k = 0; k < n; k++) {
        out[k] = bf__fc2_inline(si[k], ci[k], ss[k], cs[k], n_index);
    }
}

/* Public entry point of SPEC §4.2. Returns NaN for n < 1, non-finite
 * arguments or angles outside [0, pi/2]. */
double bf_fresnel_fc2(double theta_i, double theta_s, double n)
{
    double si;
    double ci;
    double ss;
    double cs;
    if (!(n >= 1.0) || !isfinite(n) || !(theta_i >= 0.0)
        || !(theta_i <= BF__PI_2) || !(theta_s >= 0.0)
        || !(theta_s <= BF__PI_2)) {
        return NAN;
    }
    bf__zenith_sincos(theta_i, &si, &ci);
    bf__zenith_sincos(theta_s, &ss, &cs);
    return bf__fresnel_fc2_sc(si, ci, ss, cs, n);
}
