/* test_geometry.c: tests of bf_geom_wrap_angle, bf_geom_from_curet and
 * bf_geom_is_specular (SPEC §1). Hand examples use rows of CURET's
 * table.txt copied here, so this file needs no data; the real table is
 * checked in test_specular.c. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define TWO_PI (2.0 * PI)

Test(geometry, wrap_maps_into_the_half_open_interval_minus_pi_to_pi)
{
    bf_assert_abs(bf_geom_wrap_angle(0.0), 0.0, 0.0);
    bf_assert_rel(bf_geom_wrap_angle(PI), PI, TOL0);
    bf_assert_rel(bf_geom_wrap_angle(-PI), PI, TOL0); /* -pi is excluded */
    bf_assert_rel(bf_geom_wrap_angle(1.5 * PI), -0.5 * PI, TOL1);
    bf_assert_rel(bf_geom_wrap_angle(-1.5 * PI), 0.5 * PI, TOL1);
    /* 7.1234 - 2 pi = 0.83981469282041 (by hand) */
    bf_assert_rel(bf_geom_wrap_angle(7.1234), 7.1234 - TWO_PI, TOL1);
    /* -20.5 + 6 pi = -1.650444078461... (3 turns) */
    bf_assert_rel(bf_geom_wrap_angle(-20.5), -20.5 + (3.0 * TWO_PI), TOL2);
    cr_assert(isnan(bf_geom_wrap_angle(NAN)));
    cr_assert(isnan(bf_geom_wrap_angle(INFINITY)));
}

Test(geometry, wrap_differs_from_its_input_by_whole_turns)
{
    int i;
    for (i = -2000; i <= 2000; i++) {
        double a = 0.0173 * i;
        double w = bf_geom_wrap_angle(a);
        double turns = (a - w) / TWO_PI;
        cr_assert(w > -PI && w <= PI, "wrap(%.17g) = %.17g", a, w);
        bf_assert_abs(turns, nearbyint(turns), 1e-12);
    }
}

Test(geometry, curet_configuration_one_converts_by_hand)
{
    /* table.txt row 1: theta_v 1.389566, phi_v -1.970402, theta_i 1.374447,
     * phi_i -1.570796. phi_v - phi_i - pi = -0.399606 - 3.14159265358979
     * = -3.54119865358979, + 2 pi = 2.74198665358979. */
    bf_geom g = bf_geom_from_curet(1.389566, -1.970402, 1.374447, -1.570796);
    bf_assert_rel(g.theta_s, 1.389566, TOL0);
    bf_assert_rel(g.theta_i, 1.374447, TOL0);
    bf_assert_rel(g.phi_i, PI, TOL0);
    bf_assert_rel(g.phi_s, 2.74198665358979, 1e-13);
    cr_assert_not(bf_geom_is_specular(&g));
}

Test(geometry, viewing_along_the_light_is_backscatter)
{
    /* row 20: theta_v 1.374447, phi_v 3.141593 = phi_i: the camera sits at
     * the light's azimuth, Beckmann's phi_s = pi (SPEC §1.2). */
    bf_geom g = bf_geom_from_curet(1.374447, 3.141593, 0.981748, 3.141593);
    bf_assert_rel(g.phi_s, PI, TOL0);
    /* row 2: phi_v = phi_i = 0, same thing; wrap(-pi) = +pi */
    g = bf_geom_from_curet(0.981748, 0.0, 1.374447, 0.0);
    bf_assert_rel(g.phi_s, PI, TOL0);
}

Test(geometry, a_mirror_configuration_is_specular)
{
    /* row 54: theta_v 0.196350, phi_v 3.141593, theta_i 0.196349, phi_i 0:
     * |dtheta| = 1e-6, phi_s = 3.141593 - pi = 3.46e-7. */
    bf_geom g = bf_geom_from_curet(0.196350, 3.141593, 0.196349, 0.0);
    bf_assert_abs(g.phi_s, 3.141593 - PI, 1e-15);
    cr_assert(bf_geom_is_specular(&g));
}

Test(geometry, specular_test_uses_the_tolerance_of_spec_1_4)
{
    bf_geom g = {0.7313, PI, 0.7313 + 9e-4, -9e-4};
    cr_assert(bf_geom_is_specular(&g));
    g.theta_s = 0.7313 + 1.1e-3;
    cr_assert_not(bf_geom_is_specular(&g));
    g.theta_s = 0.7313;
    g.phi_s = 1.1e-3;
    cr_assert_not(bf_geom_is_specular(&g));
    g.phi_s = TWO_PI; /* a whole turn is specular */
    cr_assert(bf_geom_is_specular(&g));
    g.phi_s = PI; /* backscatter */
    cr_assert_not(bf_geom_is_specular(&g));
    cr_assert_not(bf_geom_is_specular(NULL));
}
