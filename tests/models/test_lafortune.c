/* test_lafortune.c: tests of the Lafortune diffuse lobe LFTG (SPEC §6).
 * References: the closed form (P7) evaluated through exp/log (a different
 * route from pow), n_d = 0 giving the constant 1/pi, literal value from
 * tests/ref/models_ref.py. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

static double zenith(int i, int n)
{
    return (i >= n) ? PI_2 : (PI_2 * i / n);
}

static double lftg1(double n_d, double ti, double ts, double ps)
{
    double out;
    bf_geom g;
    int rc;
    g.theta_i = ti;
    g.phi_i = PI;
    g.theta_s = ts;
    g.phi_s = ps;
    rc = bf_model_eval(bf_model_lftg, &n_d, 1, &g, &out);
    cr_assert_eq(rc, BF_OK);
    return out;
}

Test(lafortune, matches_the_closed_form)
{
    /* (n_d + 2)/(2 pi) exp(n_d (ln cos ti + ln cos ts)); n_d 1.3917,
     * ti 0.7313, ts 1.0219: 3.3917/(2 pi) = 0.539808...,
     * cos ti cos ts = 0.744276 * 0.521665 = 0.388263, ^1.3917 = 0.268104,
     * product 0.144725 (tests/ref/models_ref.py: 0.1447247169325997). */
    double n_d = 1.3917;
    double ti = 0.7313;
    double ts = 1.0219;
    double expect =
        (n_d + 2.0) / (2.0 * PI) * exp(n_d * (log(cos(ti)) + log(cos(ts))));
    bf_assert_rel(lftg1(n_d, ti, ts, 2.2619), expect, TOL2);
    bf_assert_rel(lftg1(n_d, ti, ts, 2.2619), 0.1447247169325997, TOL2);
}

Test(lafortune, is_constant_when_the_exponent_is_zero)
{
    int u;
    int v;
    for (u = 0; u <= 20; u++) {
        for (v = 0; v <= 20; v++) {
            /* 2/(2 pi) = 1/pi everywhere, grazing included (pow(0, 0) = 1) */
            bf_assert_rel(lftg1(0.0, zenith(u, 20), zenith(v, 20), 0.3512),
                          1.0 / PI, TOL0);
        }
    }
}

Test(lafortune, is_reciprocal_and_independent_of_azimuth)
{
    double a = lftg1(2.7311, 0.7313, 1.0219, 2.2619);
    bf_assert_rel(lftg1(2.7311, 1.0219, 0.7313, 2.2619), a, TOL0);
    bf_assert_rel(lftg1(2.7311, 0.7313, 1.0219, -0.3512), a, TOL0);
}

Test(lafortune, vanishes_at_grazing_for_a_positive_exponent)
{
    bf_assert_abs(lftg1(0.1, PI_2, 0.7313, 0.0), 0.0, 0.0);
    bf_assert_abs(lftg1(20.1, 0.7313, PI_2, 0.0), 0.0, 0.0);
}

Test(lafortune, is_finite_and_non_negative_across_its_domain)
{
    static const double n_d[] = {0.0, 0.1, 1.3917, 20.1, 100.0};
    size_t a;
    int u;
    int v;
    for (a = 0; a < sizeof n_d / sizeof n_d[0]; a++) {
        for (u = 0; u <= 40; u++) {
            for (v = 0; v <= 40; v++) {
                double l = lftg1(n_d[a], zenith(u, 40), zenith(v, 40), 1.0);
                cr_assert(isfinite(l) && l >= 0.0);
            }
        }
    }
}

Test(lafortune, exponent_grid_is_the_papers)
{
    const bf_param *p = &bf_model_lftg->param[0];
    /* SPEC §7.4: n_d = 0.1 + 0.04 i, i = 0..500, last point 20.1 */
    cr_assert_str_eq(p->name, "n_d");
    bf_assert_rel(p->grid_lo, 0.1, TOL0);
    bf_assert_rel(p->grid_step, 0.04, TOL0);
    cr_assert_eq(p->grid_n, (size_t)501);
    bf_assert_rel(p->grid_lo + (p->grid_step * 500.0), 20.1, TOL1);
    cr_assert(p->fitted);
}
