/* test_fresnel.c: tests of bf_fresnel and bf_fresnel_fc2 (SPEC §4).
 *
 * Reference values come from independent routes: the textbook amplitude
 * coefficients rs, rp (Born & Wolf §1.5), the printed trigonometric form
 * (P4) with the 1/2, closed forms at normal incidence, Brewster's angle and
 * grazing, and tests/ref/models_ref.py for literal values. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI_2 1.57079632679489661923

/* Textbook unpolarised reflectance 1/2 (Rs + Rp) from the amplitude
 * coefficients (Born & Wolf §1.5), n1 = 1, n2 = r; written independently of
 * src/fresnel.c. */
static double fresnel_rs_rp(double a, double r)
{
    double st = sin(a) / r;
    double ci = cos(a);
    double ct = sqrt(1.0 - (st * st));
    double rs = (ci - (r * ct)) / (ci + (r * ct));
    double rp = (ct - (r * ci)) / (ct + (r * ci));
    return 0.5 * ((rs * rs) + (rp * rp));
}

/* SPEC §4.1 as printed (P4, with the 1/2), valid for 0 < a, below the
 * critical angle. */
static double fresnel_p4(double a, double r)
{
    double t = asin(sin(a) / r);
    double sm = sin(a - t);
    double sp = sin(a + t);
    double cp = cos(a + t);
    double cm = cos(a - t);
    return 0.5 * (sm * sm) / (sp * sp) * (1.0 + ((cp * cp) / (cm * cm)));
}

static const double indices[] = {1.7, 1.3317, 2.4191, 1.0 / 1.7, 0.6127};
#define N_INDICES (sizeof indices / sizeof indices[0])

Test(fresnel, normal_incidence_gives_the_squared_ratio_of_index_differences)
{
    size_t j;
    for (j = 0; j < N_INDICES; j++) {
        double r = indices[j];
        double q = (r - 1.0) / (r + 1.0);
        bf_assert_rel(bf_fresnel(0.0, r), q * q, TOL1);
    }
    /* 1.7: (0.7 / 2.7)^2 = 0.067215363511659807 (by hand: 0.49 / 7.29). */
    bf_assert_rel(bf_fresnel(0.0, 1.7), 0.49 / 7.29, TOL1);
}

Test(fresnel, is_continuous_as_the_angle_tends_to_zero)
{
    /* f(a) = f(0) (1 + O(a^2)): for a <= 1e-8 the change is below 1e-16
     * relative, so the values must agree with the limit to rounding. */
    static const double small[] = {1e-8, 1e-10, 1e-100, 5e-324};
    size_t j;
    size_t i;
    for (j = 0; j < N_INDICES; j++) {
        double f0 = bf_fresnel(0.0, indices[j]);
        for (i = 0; i < sizeof small / sizeof small[0]; i++) {
            bf_assert_rel(bf_fresnel(small[i], indices[j]), f0, TOL2);
        }
        /* and matches the textbook form at a small but resolvable angle */
        bf_assert_rel(bf_fresnel(1e-3, indices[j]),
                      fresnel_rs_rp(1e-3, indices[j]), TOL2);
    }
}

Test(fresnel, reaches_one_at_grazing_incidence_on_the_air_side)
{
    static const double n[] = {1.0001, 1.3317, 1.7, 4.0, 10.0};
    size_t j;
    for (j = 0; j < sizeof n / sizeof n[0]; j++) {
        double near = bf_fresnel(PI_2 - 1e-9, n[j]);
        bf_assert_rel(bf_fresnel(PI_2, n[j]), 1.0, TOL0);
        cr_assert(near < 1.0 && near > 1.0 - 1e-6, "f(pi/2 - 1e-9, %g) = %.17g",
                  n[j], near);
    }
}

Test(fresnel, lies_between_zero_and_one_on_a_sweep)
{
    static const double r[] = {0.3, 1.0 / 1.7, 0.9, 1.0, 1.1, 1.7, 2.5, 10.0};
    size_t j;
    int i;
    for (j = 0; j < sizeof r / sizeof r[0]; j++) {
        for (i = 0; i <= 2000; i++) {
            double a = PI_2 * i / 2000.0;
            double f = bf_fresnel(a, r[j]);
            cr_assert(f >= 0.0 && f <= 1.0, "f(%.17g, %g) = %.17g", a, r[j], f);
        }
    }
}

Test(fresnel, agrees_with_the_textbook_rs_rp_form_at_high_entropy_angles)
{
    static const double a[] = {0.7313, 0.1234, 1.3391, 1.5607};
    static const double n[] = {1.7, 1.4521, 2.2137};
    size_t i;
    size_t j;
    for (j = 0; j < sizeof n / sizeof n[0]; j++) {
        for (i = 0; i < sizeof a / sizeof a[0]; i++) {
            bf_assert_rel(bf_fresnel(a[i], n[j]), fresnel_rs_rp(a[i], n[j]),
                          TOL2);
            bf_assert_rel(bf_fresnel(a[i], n[j]), fresnel_p4(a[i], n[j]), TOL2);
        }
        /* dielectric -> air below the critical angle asin(1/n) */
        bf_assert_rel(bf_fresnel(0.1234, 1.0 / n[j]),
                      fresnel_rs_rp(0.1234, 1.0 / n[j]), TOL2);
        bf_assert_rel(bf_fresnel(0.4321, 1.0 / n[j]),
                      fresnel_p4(0.4321, 1.0 / n[j]), TOL2);
    }
    /* literal values, tests/ref/models_ref.py */
    bf_assert_rel(bf_fresnel(0.7313, 1.7), 0.075501446609670453, TOL2);
    bf_assert_rel(bf_fresnel(1.3391, 1.7), 0.32010064630764745, TOL2);
    bf_assert_rel(bf_fresnel(0.1234, 1.0 / 1.7), 0.0672558828639154, TOL2);
}

Test(fresnel, at_brewster_angle_only_the_s_polarisation_is_reflected)
{
    /* At a_B = atan(r): a_B + a_t = pi/2, so Rp = 0 and
     * Rs = sin^2(a_B - a_t) = cos^2(2 a_B) = ((1 - r^2)/(1 + r^2))^2;
     * f = Rs / 2. */
    static const double r[] = {1.7, 1.4521, 1.0 / 1.7};
    size_t j;
    for (j = 0; j < sizeof r / sizeof r[0]; j++) {
        double q = (1.0 - (r[j] * r[j])) / (1.0 + (r[j] * r[j]));
        bf_assert_rel(bf_fresnel(atan(r[j]), r[j]), 0.5 * q * q, TOL2);
    }
}

Test(fresnel, is_total_beyond_the_critical_angle_and_continuous_at_it)
{
    double r = 1.0 / 1.7;
    double crit = asin(r);
    bf_assert_rel(bf_fresnel(crit + 1e-6, r), 1.0, TOL0);
    bf_assert_rel(bf_fresnel(1.2345, r), 1.0, TOL0);
    bf_assert_rel(bf_fresnel(PI_2, r), 1.0, TOL0);
    /* just below: 1 - f ~ sqrt(distance), so within 1e-2 at 1e-6 rad */
    cr_assert(bf_fresnel(crit - 1e-6, r) > 0.99);
    cr_assert(bf_fresnel(crit - 1e-6, r) < 1.0);
}

Test(fresnel, vanishes_without_an_interface)
{
    int i;
    for (i = 0; i <= 100; i++) {
        bf_assert_abs(bf_fresnel(PI_2 * i / 100.0, 1.0), 0.0, 0.0);
    }
}

Test(fresnel, transmission_out_of_the_dielectric_equals_transmission_into_it)
{
    /* SPEC §4.2: 1 - f(asin(sin ts / n), 1/n) = 1 - f(ts, n). Evaluated
     * through the public bf_fresnel, the left side recomputes
     * cos(alpha_t) = sqrt(1 - (n sin(asin(sin ts / n)))^2), whose relative
     * error grows like eps / cos^2 ts; the angles stay where that is below
     * TOL2 (bf_fresnel_fc2 avoids the loss, next test). */
    static const double ts[] = {0.0, 0.3, 0.7313, 1.0219, 1.2};
    static const double n[] = {1.7, 1.33, 2.4};
    size_t i;
    size_t j;
    for (j = 0; j < sizeof n / sizeof n[0]; j++) {
        for (i = 0; i < sizeof ts / sizeof ts[0]; i++) {
            double out = 1.0 - bf_fresnel(asin(sin(ts[i]) / n[j]), 1.0 / n[j]);
            double in = 1.0 - bf_fresnel(ts[i], n[j]);
            bf_assert_rel(out, in, TOL2);
        }
    }
}

Test(fresnel, correction_factor_keeps_full_precision_near_grazing_view)
{
    /* ts = 1.5607 (1e-2 from grazing). Reference: 50-digit Decimal
     * evaluation of the textbook 1 - (Rs + Rp)/2 at the exact binary value
     * of 1.5607 (tests/ref/models_ref.py, --precise):
     * T(1.5607, 1.7) = 0.05517449679716192450726690264...
     * ti = 0: T(0, 1.7) = 1 - 0.49/7.29, cos 0 = 1. */
    double t_s = 0.055174496797161924507;
    double t_i = 1.0 - (0.49 / 7.29);
    bf_assert_rel(bf_fresnel_fc2(0.0, 1.5607, 1.7), t_i * t_s, TOL2);
}

Test(fresnel, correction_factor_is_the_product_of_transmittances_and_cosine)
{
    /* (P6) with the second factor replaced by the reciprocity identity. */
    double ti = 0.7313;
    double ts = 1.0219;
    double n = 1.7;
    double expect =
        (1.0 - fresnel_rs_rp(ti, n)) * (1.0 - fresnel_rs_rp(ts, n)) * cos(ti);
    bf_assert_rel(bf_fresnel_fc2(ti, ts, n), expect, TOL2);
    /* n = 1: no interface, F_FC^2 = cos ti exactly (FC reduces to VH) */
    bf_assert_rel(bf_fresnel_fc2(ti, ts, 1.0), cos(ti), TOL0);
    /* grazing on either side kills one transmittance */
    bf_assert_abs(bf_fresnel_fc2(PI_2, ts, n), 0.0, 0.0);
    bf_assert_abs(bf_fresnel_fc2(ti, PI_2, n), 0.0, 1e-300);
}

Test(fresnel, returns_nan_outside_its_domain)
{
    cr_assert(isnan(bf_fresnel(-0.1, 1.7)));
    cr_assert(isnan(bf_fresnel(PI_2 + 1e-9, 1.7)));
    cr_assert(isnan(bf_fresnel(0.3, 0.0)));
    cr_assert(isnan(bf_fresnel(0.3, -1.7)));
    cr_assert(isnan(bf_fresnel(0.3, NAN)));
    cr_assert(isnan(bf_fresnel(0.3, INFINITY)));
    cr_assert(isnan(bf_fresnel(NAN, 1.7)));
    cr_assert(isnan(bf_fresnel_fc2(0.3, 0.4, 0.9)));
    cr_assert(isnan(bf_fresnel_fc2(0.3, -0.4, 1.7)));
    cr_assert(isnan(bf_fresnel_fc2(NAN, 0.4, 1.7)));
}
