/* test_oren_nayar.c: tests of the Oren-Nayar model ON (SPEC §5).
 *
 * Independent references: cos(dphi) from the tangential projections of the
 * unit vectors (not from -cos phi_s), closed forms at dphi = +-pi/2 and at
 * sigma = 0, literal values from tests/ref/models_ref.py. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

static double zenith(int i, int n)
{
    return (i >= n) ? PI_2 : (PI_2 * i / n);
}

static double on1(double rho, double sigma, double ti, double ts, double ps)
{
    double p[2];
    double out;
    bf_geom g;
    int rc;
    p[0] = rho;
    p[1] = sigma;
    g.theta_i = ti;
    g.phi_i = PI;
    g.theta_s = ts;
    g.phi_s = ps;
    rc = bf_model_eval(bf_model_on, p, 1, &g, &out);
    cr_assert_eq(rc, BF_OK, "ON(%g, %g; %.17g %.17g %.17g): %d", rho, sigma, ti,
                 ts, ps, rc);
    return out;
}

/* SPEC §5 written out with cos(dphi) from the unit vectors: w_i towards the
 * source (azimuth pi), w_s towards the viewer, cos dphi = (w_i,xy . w_s,xy) /
 * (sin ti sin ts). */
static double on_by_vectors(double rho, double sigma, double ti, double ts,
                            double ps)
{
    double wi[2] = {sin(ti) * cos(PI), sin(ti) * sin(PI)};
    double ws[2] = {sin(ts) * cos(ps), sin(ts) * sin(ps)};
    double cdp = ((wi[0] * ws[0]) + (wi[1] * ws[1])) / (sin(ti) * sin(ts));
    double a = fmax(ti, ts);
    double b = fmin(ti, ts);
    double s2 = sigma * sigma;
    double c1 = 1.0 - (0.5 * s2 / (s2 + 0.33));
    double c2 = 0.45 * s2 / (s2 + 0.09)
                * ((cdp >= 0.0) ? sin(a) : (sin(a) - pow(2.0 * b / PI, 3.0)));
    double c3 = 0.125 * s2 / (s2 + 0.09) * pow(4.0 * a * b / (PI * PI), 2.0);
    double l1 = rho / PI * cos(ti)
                * (c1 + (cdp * c2 * tan(b))
                   + ((1.0 - fabs(cdp)) * c3 * tan((a + b) / 2.0)));
    double l2 = 0.17 * rho * rho / PI * cos(ti) * s2 / (s2 + 0.13)
                * (1.0 - (cdp * pow(2.0 * b / PI, 2.0)));
    return l1 + l2;
}

Test(oren_nayar, reduces_to_lambert_when_sigma_is_zero)
{
    int u;
    int v;
    int w;
    for (u = 0; u <= 30; u++) {
        for (v = 0; v <= 30; v++) {
            for (w = -12; w <= 12; w++) {
                double ti = zenith(u, 30);
                double ts = zenith(v, 30);
                double ps = w * (PI / 12.0);
                double lambert = 0.4127 / PI * ((u == 30) ? 0.0 : cos(ti));
                bf_assert_rel(on1(0.4127, 0.0, ti, ts, ps), lambert, TOL0);
            }
        }
    }
}

Test(oren_nayar, matches_an_independent_evaluation_at_high_entropy_geometry)
{
    /* rho 0.4127, sigma 0.5119, ti 0.7313, ts 1.0219; literals from
     * tests/ref/models_ref.py */
    double rho = 0.4127;
    double sigma = 0.5119;
    bf_assert_rel(on1(rho, sigma, 0.7313, 1.0219, 2.2619), 0.09643285466540942,
                  TOL2);
    bf_assert_rel(on1(rho, sigma, 0.7313, 1.0219, 0.3512), 0.060963253659883372,
                  TOL2);
    bf_assert_rel(on1(rho, sigma, 1.0219, 0.7313, 2.2619), 0.06759773462683405,
                  TOL2);
    bf_assert_rel(on1(rho, sigma, 0.7313, 1.0219, -1.9137),
                  on_by_vectors(rho, sigma, 0.7313, 1.0219, -1.9137), TOL2);
    bf_assert_rel(on1(rho, sigma, 1.3391, 0.2113, 0.1234),
                  on_by_vectors(rho, sigma, 1.3391, 0.2113, 0.1234), TOL2);
}

Test(oren_nayar, has_a_closed_form_perpendicular_to_the_plane_of_incidence)
{
    /* phi_s = pi/2: cos dphi = 0 (to 6e-17), so C2 drops out and
     * L = rho/pi ci [C1 + C3 tan((a + b)/2)] + 0.17 rho^2/pi ci s2/(s2+0.13).
     * ti 0.7313, ts 1.0219, sigma 0.5119: a = 1.0219, b = 0.7313. */
    double rho = 0.4127;
    double s2 = 0.5119 * 0.5119;
    double a = 1.0219;
    double b = 0.7313;
    double ci = cos(0.7313);
    double c1 = 1.0 - (0.5 * s2 / (s2 + 0.33));
    double r = 4.0 * a * b / (PI * PI);
    double c3 = 0.125 * s2 / (s2 + 0.09) * r * r;
    double expect = (rho / PI * ci * (c1 + (c3 * tan(0.5 * (a + b)))))
                    + (0.17 * rho * rho / PI * ci * s2 / (s2 + 0.13));
    bf_assert_rel(on1(rho, 0.5119, 0.7313, 1.0219, PI_2), expect, 1e-15);
}

Test(oren_nayar, backscatter_is_brighter_than_forward_for_rough_surfaces)
{
    /* Beckmann's phi_s = pi looks back along the light: cos dphi = +1 in the
     * sample frame (SPEC §5). Getting the sign of cos dphi wrong swaps the
     * two. The CURET conversion of row 20 gives that geometry. */
    bf_geom g = bf_geom_from_curet(0.7313, 3.141593, 0.7313, 3.141593);
    double back = on1(0.4127, 0.5119, g.theta_i, g.theta_s, g.phi_s);
    double fwd = on1(0.4127, 0.5119, 0.7313, 0.7313, 0.0);
    double lambert = 0.4127 / PI * cos(0.7313);
    cr_assert(back > fwd, "back %g, forward %g", back, fwd);
    cr_assert(back > lambert, "back %g, Lambert %g", back, lambert);
}

Test(oren_nayar, vanishes_at_grazing_incidence)
{
    int v;
    int w;
    for (v = 0; v <= 20; v++) {
        for (w = -6; w <= 6; w++) {
            bf_assert_abs(
                on1(0.4127, 0.5119, PI_2, zenith(v, 20), w * (PI / 6.0)), 0.0,
                0.0);
        }
    }
}

Test(oren_nayar, stays_finite_as_both_directions_graze)
{
    /* beta -> pi/2 needs ti -> pi/2 too; cos ti tan(beta) <= sin ti and
     * cos ti tan((a + b)/2) <= 2, so the value stays bounded by
     * rho/pi (C1 + C2 + 2 C3) + L2 < 1 for rho <= 1. (The products do not all
     * tend to 0, so the value at ti = pi/2 exactly, 0, is SPEC §5's
     * convention rather than a limit along every path.) */
    static const double ps[] = {0.0, 0.7313, PI_2, PI};
    int k;
    size_t j;
    for (j = 0; j < sizeof ps / sizeof ps[0]; j++) {
        for (k = 1; k <= 15; k++) {
            double th = PI_2 - pow(10.0, -k);
            double l1 = on1(1.0, PI_2, th, PI_2, ps[j]);
            double l2 = on1(1.0, PI_2, PI_2, th, ps[j]);
            double l3 = on1(1.0, PI_2, th, th, ps[j]);
            cr_assert(isfinite(l1) && fabs(l1) < 1.0, "%g", l1);
            cr_assert(isfinite(l2) && fabs(l2) < 1.0, "%g", l2);
            cr_assert(isfinite(l3) && fabs(l3) < 1.0, "%g", l3);
        }
    }
}

Test(oren_nayar, azimuth_does_not_matter_at_normal_incidence_or_viewing)
{
    int w;
    double at_i = on1(0.4127, 0.5119, 0.0, 1.0219, 0.0);
    double at_s = on1(0.4127, 0.5119, 0.7313, 0.0, 0.0);
    for (w = -12; w <= 12; w++) {
        double ps = w * (PI / 12.0);
        cr_assert(isfinite(at_i) && isfinite(at_s));
        bf_assert_rel(on1(0.4127, 0.5119, 0.0, 1.0219, ps), at_i, TOL0);
        bf_assert_rel(on1(0.4127, 0.5119, 0.7313, 0.0, ps), at_s, TOL0);
    }
}

Test(oren_nayar, is_isotropic_in_phi)
{
    int w;
    for (w = 1; w <= 12; w++) {
        double ps = w * 0.2617;
        bf_assert_rel(on1(0.4127, 0.5119, 0.7313, 1.0219, -ps),
                      on1(0.4127, 0.5119, 0.7313, 1.0219, ps), TOL0);
    }
}

Test(oren_nayar, is_finite_and_non_negative_everywhere_for_every_rho_and_sigma)
{
    /* Finite and >= 0 on the closed hemisphere for every rho, sigma of the
     * domain: SPEC §5's formula goes slightly negative in the forward
     * grazing corner for very rough surfaces, and the model clamps it at 0
     * (a departure, see oren_nayar.c and the next test). */
    static const double rho[] = {0.0, 0.05, 0.4127, 1.0};
    static const double sigma[] = {0.0, 0.2, 0.5, 1.0, PI_2};
    size_t a;
    size_t b;
    int u;
    int v;
    int w;
    for (a = 0; a < sizeof rho / sizeof rho[0]; a++) {
        for (b = 0; b < sizeof sigma / sizeof sigma[0]; b++) {
            for (u = 0; u <= 40; u++) {
                for (v = 0; v <= 40; v++) {
                    for (w = -18; w <= 18; w++) {
                        double l = on1(rho[a], sigma[b], zenith(u, 40),
                                       zenith(v, 40), w * (PI / 18.0));
                        cr_assert(isfinite(l) && l >= 0.0,
                                  "ON(%g, %g) = %g", rho[a], sigma[b], l);
                    }
                }
            }
        }
    }
}

Test(oren_nayar, is_clamped_at_zero_only_where_the_formula_goes_negative)
{
    /* rho 0.05, sigma 1, ti 1.43117, ts pi/2, phi_s 0 (forward, cos dphi =
     * -1, alpha = pi/2, beta = ti): C1 = 1 - 0.5/1.33 = 0.62406,
     * C2 = 0.45/1.09 (1 - (2 ti/pi)^3) = 0.10060, tan(ti) = 7.1154, so
     * C1 - C2 tan(ti) = -0.09172 < 0 and L1 = 0.05/pi cos(ti) (-0.09172) =
     * -2.03e-4, L2 = 0.17 0.0025/pi cos(ti) (1/1.13) (1 + (2 ti/pi)^2) =
     * 3.05e-5: L = -1.73e-4 (C3 drops out: 1 - |cos dphi| = 0). */
    double raw = on_by_vectors(0.05, 1.0, 1.43117, PI_2, 0.0);
    cr_assert(raw < -1.6e-4 && raw > -1.8e-4, "formula gives %g", raw);
    cr_assert_eq(on1(0.05, 1.0, 1.43117, PI_2, 0.0), 0.0);
    /* Where the formula is positive the model is the formula. */
    bf_assert_rel(on1(0.05, 1.0, 1.43117, 1.2, 0.0),
                  on_by_vectors(0.05, 1.0, 1.43117, 1.2, 0.0), TOL2);
}

Test(oren_nayar, clamp_never_acts_on_the_study_samples_and_configurations)
{
    /* SPEC §5's formula, evaluated independently (on_by_vectors) at every
     * CURET configuration for the rho, sigma of the 24 study samples, is
     * positive: the clamp leaves the study's ON results as SPEC gives them.
     * (cos dphi is irrelevant where a zenith is 0: beta = 0.) */
    bf_table *t = bf_test_load_table();
    bf_sample_table *on = NULL;
    bf_error err;
    size_t r;
    size_t k;
    cr_assert_eq(bf_on_params_load(
                     bf_test_reference_path("oren_nayar_params.tsv"), &on,
                     &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(bf_sample_table_count(on), 24u);
    for (r = 0; r < bf_sample_table_count(on); r++) {
        int s = bf_sample_table_sample(on, r);
        double rho = 0.0;
        double sigma = 0.0;
        cr_assert_eq(bf_sample_table_get(on, s, 0, &rho), BF_OK);
        cr_assert_eq(bf_sample_table_get(on, s, 1, &sigma), BF_OK);
        for (k = 0; k < bf_table_size(t); k++) {
            bf_geom g = bf_table_geom(t, k);
            double ts = (g.theta_s > 0.0) ? g.theta_s : 1e-300;
            double ti = (g.theta_i > 0.0) ? g.theta_i : 1e-300;
            double raw = on_by_vectors(rho, sigma, ti, ts, g.phi_s);
            cr_assert(raw > 0.0, "sample %d configuration %zu: %g", s, k + 1,
                      raw);
        }
    }
    bf_sample_table_free(on);
    bf_table_free(t);
}
