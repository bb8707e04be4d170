/* test_policy.c: the exact fit's policy in the library (doc/methods.md
 * §6) -- which parameters bf_model_variant_exact frees and over which
 * grid, for every registry model, with the refractive index kept when the
 * user gives it; and a user's search range (bf_model_variant_range). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "support.h"

Test(policy, the_exact_fit_frees_exactly_the_inputs_with_a_free_range)
{
    size_t i;
    size_t n_freed_total = 0;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *base = bf_model_get(i);
        unsigned keeps[2] = {0u, 1u << BF_INPUT_INDEX};
        size_t q;
        for (q = 0; q < 2; q++) {
            bf_model_variant v;
            size_t expect = 0;
            size_t j;
            bf_model_variant_init(&v, base);
            for (j = 0; j < base->p; j++) {
                const bf_param *b = &base->param[j];
                expect += !b->fitted && b->free_lo < b->free_hi &&
                          !((keeps[q] >> b->input) & 1u);
            }
            cr_assert_eq(bf_model_variant_exact(&v, keeps[q]), expect, "%s",
                         base->name);
            n_freed_total += expect;
            for (j = 0; j < base->p; j++) {
                const bf_param *b = &base->param[j];
                const bf_param *p = &v.type.param[j];
                int freed = !b->fitted && p->fitted;
                cr_assert(b->fitted ? p->fitted : 1);
                if (b->fitted) { /* the paper's grid stays */
                    cr_assert_eq(p->grid_n, b->grid_n);
                    continue;
                }
                cr_assert_eq(freed, b->free_lo < b->free_hi &&
                                        !((keeps[q] >> b->input) & 1u),
                             "%s %s", base->name, b->name);
                if (freed) {
                    cr_assert_float_eq(p->grid_lo, b->free_lo, 0.0);
                    cr_assert_float_eq(p->grid_step, b->free_step, 0.0);
                    cr_assert_float_eq(p->grid_lo + p->grid_step *
                                                        (double)(p->grid_n -
                                                                 1),
                                       b->free_hi, 1e-12);
                }
            }
        }
    }
    cr_assert_gt(n_freed_total, 0);
    /* the values methods.md §6 states */
    {
        bf_model_variant v;
        bf_model_variant_init(&v, bf_model_find("FC-E"));
        cr_assert_eq(bf_model_variant_exact(&v, 0), 1);
        cr_assert(v.type.param[bf_model_param_index(&v.type, "n")].fitted);
        bf_model_variant_init(&v, bf_model_find("FC-E"));
        cr_assert_eq(bf_model_variant_exact(&v, 1u << BF_INPUT_INDEX), 0);
        bf_model_variant_init(&v, bf_model_find("ON"));
        cr_assert_eq(bf_model_variant_exact(&v, 1u << BF_INPUT_INDEX), 2);
        cr_assert_float_eq(v.type.param[0].grid_lo, 0.05, 0.0);
        cr_assert_float_eq(v.type.param[1].grid_lo + v.type.param[1].grid_step *
                                                       (double)(v.type.param[1].grid_n - 1),
                           1.57, 1e-12);
    }
}

Test(policy, a_search_range_keeps_the_grid_step)
{
    bf_model_variant v;
    const bf_param *m;
    bf_model_variant_init(&v, bf_model_find("VH-E"));
    m = &v.type.param[bf_model_param_index(&v.type, "m")];
    cr_assert_eq(bf_model_variant_range(&v, "m", 0.05, 10.0), BF_OK);
    cr_assert_float_eq(m->grid_lo, 0.05, 0.0);
    cr_assert_float_eq(m->grid_step,
                       bf_model_find("VH-E")->param[0].grid_step, 0.0);
    cr_assert_eq(bf_model_variant_range(&v, "zz", 0.1, 1.0), BF_ENOTFOUND);
    cr_assert_eq(bf_model_variant_range(&v, "m", 1.0, 0.5), BF_EINVAL);
    cr_assert_eq(bf_model_variant_range(&v, "m", m->min - 1.0, 1.0),
                 BF_EINVAL);
    /* a parameter without a grid (ON's rho): 100 intervals */
    bf_model_variant_init(&v, bf_model_find("ON"));
    cr_assert_eq(bf_model_variant_range(&v, "rho", 0.2, 0.8), BF_OK);
    cr_assert(v.type.param[0].fitted);
    cr_assert_eq(v.type.param[0].grid_n, 101);
    cr_assert_float_eq(v.type.param[0].grid_step, 0.006, 1e-15);
}
