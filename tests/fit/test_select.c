/* test_select.c: objectives (doc/methods.md §1), information criteria
 * (§4), cross-validation folds and error (§5) and model variants (§6). */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define PI 3.14159265358979323846

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(select, .init = setup);

/* Three configurations with theta_i = 0, pi/3, 0.7313: LAMBERT's
 * normalised curve is L = (1, 1/2, cos 0.7313 = 0.74430684239126980). */
static const bf_geom tiny_geom[3] = {
    {0.0, PI, 0.3, 1.0}, {PI / 3.0, PI, 0.5, 2.0}, {0.7313, PI, 0.9, -1.0}};

static double objective(bf_objective obj, const double *data)
{
    bf_problem pb;
    double work[6];
    double v = NAN;
    cr_assert_eq(bf_problem_init(&pb, bf_model_lambert, NULL, 3, tiny_geom,
                                 data), BF_OK);
    pb.objective = obj;
    cr_assert_eq(bf_problem_value(&pb, NULL, work, &v), BF_OK);
    return v;
}

Test(select, objectives_match_hand_computed_values)
{
    const double d[3] = {0.9, 0.6, 0.7};
    const double d_log[3] = {0.9, -0.01, 0.0005};
    /* max: 0.1^2 + 0.1^2 + (0.7443068423912698 - 0.7)^2 */
    bf_assert_rel(objective(BF_OBJ_MAX, d), 0.021963096282684814, TOL2);
    /* scale: s* = (0.9 + 0.3 + 0.52101479) / (1 + 0.25 + 0.55399268)
     * = 0.9540032024090261, S = sum (s* L - D)^2 */
    bf_assert_rel(objective(BF_OBJ_SCALE, d), 0.018146379257813386, TOL2);
    /* cosw: weights cos theta_i = 1, 0.5, 0.74430684 */
    bf_assert_rel(objective(BF_OBJ_COSW, d), 0.01646114599547517, TOL2);
    /* log with the floor 1e-3 for -0.01 and 0.0005:
     * ln(1/0.9)^2 + ln(0.5/1e-3)^2 + ln(0.74430684/1e-3)^2 */
    bf_assert_rel(objective(BF_OBJ_LOG, d_log), 82.3569942571233, TOL2);
}

Test(select, objective_names_round_trip)
{
    bf_objective o;
    cr_assert_str_eq(bf_objective_name(BF_OBJ_MAX), "max");
    cr_assert_str_eq(bf_objective_name(BF_OBJ_LOG), "log");
    cr_assert_null(bf_objective_name((bf_objective)17));
    cr_assert_eq(bf_objective_find("cosw", &o), BF_OK);
    cr_assert_eq(o, BF_OBJ_COSW);
    cr_assert_eq(bf_objective_find("scale", &o), BF_OK);
    cr_assert_eq(o, BF_OBJ_SCALE);
    cr_assert_eq(bf_objective_find("Max", &o), BF_ENOTFOUND);
}

Test(select, aic_and_bic_match_hand_computed_values)
{
    /* rss = 0.5, n = 10, k = 2: 10 ln 0.05 = -29.95732273553991;
     * AIC = -29.957... + 4; BIC = -29.957... + 2 ln 10 (4.605170185988091) */
    bf_assert_rel(bf_criterion_aic(0.5, 10, 2), -25.95732273553991, TOL1);
    bf_assert_rel(bf_criterion_bic(0.5, 10, 2), -25.35215254955182, TOL1);
    /* k = 0: both are n ln(rss/n) */
    bf_assert_rel(bf_criterion_aic(0.5, 10, 0), bf_criterion_bic(0.5, 10, 0),
                  TOL0);
}

Test(select, parameter_count_includes_the_scale_only_when_fitted)
{
    bf_problem pb;
    const double d[3] = {0.9, 0.6, 0.7};
    cr_assert_eq(bf_problem_init(&pb, bf_model_fc_e, NULL, 3, tiny_geom, d),
                 BF_OK);
    cr_assert_eq(bf_problem_nparams(&pb), 1u); /* m; n is an input */
    pb.objective = BF_OBJ_SCALE;
    cr_assert_eq(bf_problem_nparams(&pb), 2u);
    pb.objective = BF_OBJ_LOG;
    cr_assert_eq(bf_problem_nparams(&pb), 1u);
}

Test(select, cv_folds_are_deterministic_balanced_and_seed_dependent)
{
    size_t a[198];
    size_t b[198];
    size_t c[198];
    size_t count[10] = {0};
    size_t k;
    cr_assert_eq(bf_fit_cv_folds(198, 10, 7, a), BF_OK);
    cr_assert_eq(bf_fit_cv_folds(198, 10, 7, b), BF_OK);
    cr_assert_eq(bf_fit_cv_folds(198, 10, 8, c), BF_OK);
    cr_assert_arr_eq(a, b, sizeof a);
    cr_assert(memcmp(a, c, sizeof a) != 0);
    for (k = 0; k < 198; k++) {
        cr_assert_lt(a[k], 10u);
        count[a[k]]++;
    }
    for (k = 0; k < 10; k++) { /* 198 = 8 x 20 + 2 x 19 */
        cr_assert(count[k] == 20 || count[k] == 19, "fold %zu: %zu", k,
                  count[k]);
    }
    cr_assert_eq(bf_fit_cv_folds(198, 1, 7, a), BF_EINVAL);
    cr_assert_eq(bf_fit_cv_folds(5, 6, 7, a), BF_EINVAL);
}

/* A model with nothing to fit predicts the held-out configurations as it
 * predicts all of them, so its CV error is its LSE. A fitted model's CV
 * error exceeds its in-sample LSE (it is judged on data it did not see). */
Test(select, cv_error_of_a_model_without_parameters_is_its_lse)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *br = bf_test_load_abrdf();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, PI, sel);
    bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    double work[2 * BF_CURET_NCONF];
    bf_problem pb;
    bf_curves *c;
    bf_fit_result g;
    bf_fit_result r;
    double lse;
    double cv;
    size_t k;
    int st;
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    cr_assert_eq(bf_data_radiance(t, bf_brdf_values(br, 11), n, sel, data),
                 BF_OK); /* sample 12 */
    cr_assert_eq(bf_problem_init(&pb, bf_model_lambert, NULL, n, geom, data),
                 BF_OK);
    c = bf_curves_alloc(&pb, &st);
    cr_assert_eq(bf_problem_value(&pb, NULL, work, &lse), BF_OK);
    cr_assert_eq(bf_fit_cv(&pb, c, 10, 1, &cv), BF_OK);
    bf_assert_rel(cv, lse, TOL3);
    bf_curves_free(c);

    cr_assert_eq(bf_problem_init(&pb, bf_model_vh_e, NULL, n, geom, data),
                 BF_OK);
    c = bf_curves_alloc(&pb, &st);
    cr_assert_eq(bf_curves_best(c, &pb, &g), BF_OK);
    cr_assert_eq(bf_fit_refine(&pb, &g, &r), BF_OK);
    cr_assert_eq(bf_fit_cv(&pb, c, 10, 1, &cv), BF_OK);
    cr_assert_gt(cv, r.lse);
    bf_curves_free(c);
    bf_table_free(t);
    bf_brdf_free(br);
}

Test(select, variants_free_parameters_within_their_domain_only)
{
    bf_model_variant v;
    bf_model_variant_init(&v, bf_model_fc_g);
    cr_assert_str_eq(v.type.name, "FC-G");
    cr_assert_not(v.type.param[1].fitted);
    cr_assert_eq(bf_model_variant_fit(&v, "n", 0.9, 2.0, 0.1), BF_EINVAL);
    cr_assert_eq(bf_model_variant_fit(&v, "n", 1.5, 1.5, 0.1), BF_EINVAL);
    cr_assert_eq(bf_model_variant_fit(&v, "n", 1.2, 2.0, 0.0), BF_EINVAL);
    cr_assert_eq(bf_model_variant_fit(&v, "k", 1.2, 2.0, 0.1), BF_ENOTFOUND);
    cr_assert_eq(bf_model_variant_fit(&v, "m", 0.001, 100.0, 1e-4),
                 BF_EINVAL); /* a million points */
    cr_assert_eq(bf_model_variant_fit(&v, "n", 1.2, 2.5, 0.05), BF_OK);
    cr_assert(v.type.param[1].fitted);
    cr_assert_eq(v.type.param[1].grid_n, 27u); /* 1.20, 1.25, ..., 2.50 */
    /* the base type is untouched */
    cr_assert_not(bf_model_fc_g->param[1].fitted);
}

/* The refinement never leaves the search range, and flags an optimum on
 * it: LAMBERT-like data pull VH-G's slope to the top of a narrow range. */
Test(select, refinement_stays_in_the_search_range_and_flags_its_bound)
{
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, PI, sel);
    bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    bf_model_variant v;
    bf_problem pb;
    bf_curves *c;
    bf_fit_result g;
    bf_fit_result r;
    size_t k;
    int st;
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    cr_assert_eq(bf_model_eval(bf_model_vh_g, (double[]){3.0}, n, geom,
                               data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    bf_model_variant_init(&v, bf_model_vh_g);
    cr_assert_eq(bf_model_variant_fit(&v, "m", 0.5, 1.0, 0.01), BF_OK);
    cr_assert_eq(bf_problem_init(&pb, &v.type, NULL, n, geom, data), BF_OK);
    c = bf_curves_alloc(&pb, &st);
    cr_assert_eq(bf_curves_best(c, &pb, &g), BF_OK);
    cr_assert_eq(g.bound_hit, 1u);
    cr_assert_eq(bf_fit_refine(&pb, &g, &r), BF_OK);
    cr_assert_eq(r.param[0], 1.0);
    cr_assert_eq(r.bound_hit, 1u);
    bf_curves_free(c);
    bf_table_free(t);
}
