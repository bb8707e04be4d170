/* test_wno.c: the Wolff-Nayar-Oren smooth dielectric model WNO
 * (src/models/wolff_nayar_oren.c, doc/methods.md §7). */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

static double wno(double ti, double ts, double ps, double n)
{
    bf_geom g = {ti, PI, ts, ps};
    double out = NAN;
    cr_assert_eq(bf_model_eval(bf_model_wno, &n, 1, &g, &out), BF_OK);
    return out;
}

Test(wno, matches_hand_values_at_normal_incidence_and_viewing)
{
    /* f(0, 1.5) = (0.5/2.5)^2 = 0.04 and f(0, 1/1.5) = ((-1/3)/(5/3))^2 =
     * 0.04, so L = cos 0 (1 - 0.04)(1 - 0.04) = 0.9216 */
    bf_assert_rel(wno(0.0, 0.0, 0.0, 1.5), 0.9216, TOL1);
    /* n = 2: f = (1/3)^2 both ways, L = (8/9)^2 = 64/81 */
    bf_assert_rel(wno(0.0, 0.0, 1.3, 2.0), 64.0 / 81.0, TOL1);
}

Test(wno, vanishes_at_grazing_incidence_and_grazing_view)
{
    /* incidence: cos theta_i = 0 and 1 - f(pi/2, n) = 0; view: light leaves
     * the body at the critical angle asin(1/n), where f(., 1/n) = 1 */
    bf_assert_abs(wno(PI_2, 0.3, 0.0, 1.6271), 0.0, 0.0);
    bf_assert_abs(wno(0.4, PI_2, 0.0, 1.6271), 0.0, TOL1);
    cr_assert(wno(0.4, 1.5, 0.0, 1.6271) > 0.0);
}

Test(wno, is_lambert_without_an_interface)
{
    /* n = 1: no Fresnel loss, L = cos theta_i */
    bf_assert_rel(wno(0.7313, 1.0219, 2.2619, 1.0), cos(0.7313), TOL1);
}

Test(wno, obeys_reciprocity_and_isotropy)
{
    /* BRDF = L / cos theta_i is symmetric in i and s (Fresnel reciprocity,
     * SPEC §4.2) and independent of azimuth */
    double a = wno(0.7313, 1.0219, 0.4, 1.6271) / cos(0.7313);
    double b = wno(1.0219, 0.7313, 0.4, 1.6271) / cos(1.0219);
    bf_assert_rel(a, b, TOL2);
    bf_assert_rel(wno(0.7313, 1.0219, 2.9, 1.6271),
                  wno(0.7313, 1.0219, -0.4, 1.6271), TOL0);
}

Test(wno, equals_the_fresnel_correction_factor)
{
    bf_assert_rel(wno(0.5113, 0.9127, 1.1, 1.83),
                  bf_fresnel_fc2(0.5113, 0.9127, 1.83), TOL0);
}

Test(wno, rejects_an_index_below_one)
{
    bf_geom g = {0.3, PI, 0.2, 0.0};
    double n = 0.99;
    double out;
    cr_assert_eq(bf_model_eval(bf_model_wno, &n, 1, &g, &out), BF_EINVAL);
    cr_assert(isnan(out));
}
