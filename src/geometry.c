/* geometry.c: angle wrapping, CURET -> Beckmann frame conversion and the
 * specular test (SPEC §1).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (Beckmann's frame, SPEC §1.2).
 *   [2] K. J. Dana et al., "Reflectance and Texture of Real-World Surfaces",
 *       ACM TOG 18(1), 1999 (CURET's table.txt, SPEC §1.3).
 *
 * Equations:
 *   wrap(a) in (-pi, pi]                                    SPEC §1.3
 *   theta_s = theta_v, phi_s = wrap(phi_v - phi_i - pi)     SPEC §1.3
 *   |theta_s - theta_i| < 1e-3 and |phi_s| < 1e-3           SPEC §1.4
 */
#include <math.h>

#include "internal.h"

#define TWO_PI (2.0 * BF__PI)

/* Wraps a to (-pi, pi]. fmod is exact, so the only rounding is the one
 * addition of 2 pi. Non-finite input gives NaN. */
double bf_wrap_angle(double a)
{
    double r = fmod(a, TWO_PI); /* (-2 pi, 2 pi), sign of a */
    if (r > BF__PI) {
        r -= TWO_PI;
    } else if (r <= -BF__PI) {
        r += TWO_PI; /* -pi itself maps to +pi */
    }
    return r;
}

/* SPEC §1.3: CURET's sample frame has the specular direction at
 * phi_v = phi_i + pi; Beckmann's has it at phi_s = 0 with phi_i = pi. */
bf_geom bf_geom_from_curet(double theta_v, double phi_v, double theta_i,
                           double phi_i)
{
    bf_geom g;
    g.theta_i = theta_i;
    g.phi_i = BF__PI;
    g.theta_s = theta_v;
    g.phi_s = bf_wrap_angle(phi_v - phi_i - BF__PI); /* SPEC §1.3 */
    return g;
}

/* SPEC §1.4. phi_s is wrapped first so that 2 pi counts as 0. The test is
 * exactly the SPEC's: at theta_i = theta_s = 0 (azimuth undefined) it still
 * asks for |phi_s| < tol; CURET has no such configuration. */
int bf_geom_is_specular(const bf_geom *g)
{
    if (g == NULL) {
        return 0;
    }
    return (fabs(g->theta_s - g->theta_i) < BF_SPECULAR_TOL)
           && (fabs(bf_wrap_angle(g->phi_s)) < BF_SPECULAR_TOL);
}
