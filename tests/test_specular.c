/* test_specular.c: the specular configurations of CURET's real table.txt
 * (SPEC §1.4; needs the CURET data and the table loader, src/data/table.c).
 * Reference: SPEC §1.4 and data/curet/SOURCES.md list exactly 7 specular
 * configurations, 54, 97, 131, 161, 183, 196, 202 (1-based), K = 198. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

Test(specular, curet_has_exactly_seven_specular_configurations)
{
    static const size_t expected[] = {54, 97, 131, 161, 183, 196, 202};
    bf_table *t = bf_test_load_table();
    size_t n = bf_table_size(t);
    size_t found = 0;
    size_t k;
    cr_assert_eq(n, (size_t)BF_CURET_NCONF);
    for (k = 0; k < n; k++) {
        double raw[4];
        bf_geom g;
        bf_table_raw(t, k, raw);
        /* columns: theta_v, phi_v, theta_i, phi_i (SPEC §1.3) */
        g = bf_geom_from_curet(raw[0], raw[1], raw[2], raw[3]);
        if (bf_geom_is_specular(&g)) {
            cr_assert(found < 7, "more than 7 specular configurations");
            cr_assert_eq(k + 1, expected[found],
                         "specular configuration %zu, expected %zu", k + 1,
                         expected[found]);
            found++;
        }
    }
    cr_assert_eq(found, (size_t)7);
    cr_assert_eq(n - found, (size_t)198, "K = %zu", n - found);
    bf_table_free(t);
}

Test(specular, table_geometry_agrees_with_the_curet_conversion)
{
    bf_table *t = bf_test_load_table();
    size_t k;
    for (k = 0; k < bf_table_size(t); k++) {
        double raw[4];
        bf_geom a;
        bf_geom b = bf_table_geom(t, k);
        bf_table_raw(t, k, raw);
        a = bf_geom_from_curet(raw[0], raw[1], raw[2], raw[3]);
        bf_assert_rel(b.theta_i, a.theta_i, TOL0);
        bf_assert_rel(b.theta_s, a.theta_s, TOL0);
        /* phi_s near +-pi may wrap either way: compare cosines and sines */
        bf_assert_abs(cos(b.phi_s), cos(a.phi_s), TOL1);
        bf_assert_abs(sin(b.phi_s), sin(a.phi_s), TOL1);
    }
    bf_table_free(t);
}
