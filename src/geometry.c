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
 *   theta_s = theta_o, phi_s = wrap(phi_o - phi_i - pi)     SPEC §1.5
 *   delta = angle(omega_o, mirror of omega_i)               SPEC §1.6
 */
#include <math.h>

#include "internal.h"

#define TWO_PI (2.0 * BF__PI)

/* Wraps a to (-pi, pi]. fmod is exact, so the only rounding is the one
 * addition of 2 pi. Non-finite input gives NaN. */
double bf_geom_wrap_angle(double a)
{
    double r = fmod(a, TWO_PI); /* (-2 pi, 2 pi), sign of a */
    if (r > BF__PI) {
        r -= TWO_PI;
    } else if (r <= -BF__PI) {
        r += TWO_PI; /* -pi itself maps to +pi */
    }
    return r;
}

/* SPEC §1.5: the measurement frame has the mirror direction of (theta_i,
 * phi_i) at (theta_i, phi_i + pi); Beckmann's has it at phi_s = 0 with
 * phi_i = pi. */
bf_geom bf_geom_from_measurement(double theta_i, double phi_i,
                                 double theta_o, double phi_o)
{
    bf_geom g;
    g.theta_i = theta_i;
    g.phi_i = BF__PI;
    g.theta_s = theta_o;
    /* SPEC §1.3, §1.5 */
    g.phi_s = bf_geom_wrap_angle(phi_o - phi_i - BF__PI);
    return g;
}

/* SPEC §1.3: CURET's sample frame is the measurement frame with the view
 * direction v = o. */
bf_geom bf_geom_from_curet(double theta_v, double phi_v, double theta_i,
                           double phi_i)
{
    return bf_geom_from_measurement(theta_i, phi_i, theta_v, phi_v);
}

/* SPEC §1.6: delta = angle between omega_o and the mirror image
 * (-x, -y, z) of omega_i, as atan2(|m x o|, m . o), which keeps its
 * precision near 0 where acos does not. Rotations about the normal change
 * neither vector's angle, so either frame gives the same delta. */
double bf_geom_mirror_angle(const bf_geom *g)
{
    double si;
    double ci;
    double so;
    double co;
    double m[3];
    double o[3];
    double x[3];
    bf__zenith_sincos(g->theta_i, &si, &ci);
    bf__zenith_sincos(g->theta_s, &so, &co);
    m[0] = -si * cos(g->phi_i); /* mirror of omega_i */
    m[1] = -si * sin(g->phi_i);
    m[2] = ci;
    o[0] = so * cos(g->phi_s);
    o[1] = so * sin(g->phi_s);
    o[2] = co;
    x[0] = m[1] * o[2] - m[2] * o[1];
    x[1] = m[2] * o[0] - m[0] * o[2];
    x[2] = m[0] * o[1] - m[1] * o[0];
    return atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]),
                 m[0] * o[0] + m[1] * o[1] + m[2] * o[2]);
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
           && (fabs(bf_geom_wrap_angle(g->phi_s)) < BF_SPECULAR_TOL);
}

void bf__geom_trig(const bf_geom *g, bf__trig_t *tr)
{
    tr->sp = sin(g->phi_s);
    tr->cp = cos(g->phi_s);
    bf__zenith_sincos(g->theta_i, &tr->si, &tr->ci);
    bf__zenith_sincos(g->theta_s, &tr->ss, &tr->cs);
}
