/* test_lambert.c: tests of the Lambert baseline LAMBERT (SPEC §6a). */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

Test(lambert, is_the_cosine_of_incidence_and_has_no_parameter)
{
    /* cos 0.7313 = 0.74427... ; cos(pi/3) = 1/2 closed form */
    bf_geom g[4] = {{0.7313, PI, 1.0219, 2.2619},
                    {PI / 3.0, PI, 0.2, -1.0},
                    {0.0, PI, 0.5, 0.0},
                    {PI_2, PI, 0.0, 0.0}};
    double out[4];
    cr_assert_eq(bf_model_lambert->p, (size_t)0);
    cr_assert_eq(bf_model_eval(bf_model_lambert, NULL, 4, g, out), BF_OK);
    bf_assert_rel(out[0], cos(0.7313), TOL0);
    bf_assert_rel(out[1], 0.5, TOL1);
    bf_assert_rel(out[2], 1.0, TOL0);
    bf_assert_abs(out[3], 0.0, 0.0);
}
