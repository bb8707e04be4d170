/* test_registry.c: tests of the model registry and the checked entry point
 * bf_model_eval (SPEC §3-6, §7.4 grids). */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

/* The first eleven models keep their indices (the API's order); a model
 * added later comes after them. */
Test(registry, lists_the_first_eleven_models_in_order)
{
    static const char *names[] = {"BK-G", "BK-E",    "VH-G", "VH-E",
                                  "FC-G", "FC-E",    "ON",   "LFTG",
                                  "LAMBERT", "WNO", "WNO-R"};
    size_t i;
    cr_assert_geq(bf_model_count(), (size_t)11);
    for (i = 0; i < 11; i++) {
        cr_assert_str_eq(bf_model_get(i)->name, names[i]);
    }
    for (i = 0; i < bf_model_count(); i++) {
        cr_assert_not_null(bf_model_get(i));
    }
    cr_assert_null(bf_model_get(bf_model_count()));
    cr_assert_eq(bf_model_get(9), bf_model_wno);
    cr_assert_eq(bf_model_get(10), bf_model_wno_r);
    cr_assert_eq(bf_model_get(0), bf_model_bk_g);
    cr_assert_eq(bf_model_get(5), bf_model_fc_e);
    cr_assert_eq(bf_model_get(8), bf_model_lambert);
}

Test(registry, finds_models_by_name_ignoring_case)
{
    cr_assert_eq(bf_model_find("FC-E"), bf_model_fc_e);
    cr_assert_eq(bf_model_find("fc-e"), bf_model_fc_e);
    cr_assert_eq(bf_model_find("Vh-G"), bf_model_vh_g);
    cr_assert_eq(bf_model_find("lambert"), bf_model_lambert);
    cr_assert_eq(bf_model_find("on"), bf_model_on);
}

Test(registry, returns_null_for_unknown_names)
{
    cr_assert_null(bf_model_find("FC-X"));
    cr_assert_null(bf_model_find("FC-E "));
    cr_assert_null(bf_model_find("FC"));
    cr_assert_null(bf_model_find(""));
    cr_assert_null(bf_model_find(NULL));
}

Test(registry, finds_parameters_by_name)
{
    cr_assert_eq(bf_model_param_index(bf_model_fc_e, "m"), 0);
    cr_assert_eq(bf_model_param_index(bf_model_fc_e, "n"), 1);
    cr_assert_eq(bf_model_param_index(bf_model_on, "rho"), 0);
    cr_assert_eq(bf_model_param_index(bf_model_on, "sigma"), 1);
    cr_assert_eq(bf_model_param_index(bf_model_lftg, "n_d"), 0);
    cr_assert_eq(bf_model_param_index(bf_model_vh_g, "n"), -1);
    cr_assert_eq(bf_model_param_index(bf_model_lambert, "m"), -1);
    cr_assert_eq(bf_model_param_index(NULL, "m"), -1);
    cr_assert_eq(bf_model_param_index(bf_model_bk_g, NULL), -1);
}

Test(registry, every_model_describes_itself_consistently)
{
    size_t i;
    size_t j;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        cr_assert(t->p <= BF_MAX_PARAMS);
        cr_assert_not_null(t->eval);
        cr_assert(strlen(t->title) > 0);
        cr_assert_not_null(strstr(t->reference, "SPEC §"), "%s", t->name);
        for (j = 0; j < t->p; j++) {
            const bf_param *p = &t->param[j];
            cr_assert(p->min <= p->value && p->value <= p->max, "%s.%s",
                      t->name, p->name);
            if (p->grid_n > 0) {
                double last = p->grid_lo + (p->grid_step * (p->grid_n - 1));
                cr_assert(p->grid_lo >= p->min && last <= p->max);
            }
        }
    }
}

Test(registry, slope_grids_are_the_papers)
{
    /* SPEC §7.4: m = 0.1 + 0.01 i, i = 0..500, i.e. [0.1, 5.1] */
    size_t i;
    for (i = 0; i < 6; i++) {
        const bf_param *p = &bf_model_get(i)->param[0];
        cr_assert_str_eq(p->name, "m");
        cr_assert(p->fitted);
        bf_assert_rel(p->grid_lo, 0.1, TOL0);
        bf_assert_rel(p->grid_step, 0.01, TOL0);
        cr_assert_eq(p->grid_n, (size_t)501);
    }
    /* n of FC is a fixed input defaulting to 1.7 (SPEC §4.2) */
    cr_assert_not(bf_model_fc_g->param[1].fitted);
    bf_assert_rel(bf_model_fc_e->param[1].value, BF_DEFAULT_N, TOL0);
    /* ON's rho and sigma are fixed inputs (SPEC §5) */
    cr_assert_not(bf_model_on->param[0].fitted);
    cr_assert_not(bf_model_on->param[1].fitted);
    cr_assert_str_eq(bf_model_on->param[1].unit, "rad");
}

/* Evaluates type at g with parameters p and expects rc; when rc is not
 * BF_OK the output must be NaN. */
static void expect_eval(const bf_model_type *type, const double *p, bf_geom g,
                        int rc)
{
    double out = 42.0;
    int got = bf_model_eval(type, p, 1, &g, &out);
    cr_assert_eq(got, rc, "%s: got %d, expected %d", type->name, got, rc);
    if (rc != BF_OK) {
        cr_assert(isnan(out));
    } else {
        cr_assert(isfinite(out));
    }
}

Test(registry, eval_rejects_parameters_outside_their_domain)
{
    bf_geom g = {0.7313, PI, 1.0219, 2.2619};
    double bad_m[] = {0.0, 9e-4, 100.5, -1.0, NAN, INFINITY};
    size_t i;
    size_t j;
    for (i = 0; i < 6; i++) {
        for (j = 0; j < sizeof bad_m / sizeof bad_m[0]; j++) {
            double p[2] = {bad_m[j], 1.7};
            expect_eval(bf_model_get(i), p, g, BF_EINVAL);
        }
    }
    {
        double p[2] = {0.5, 0.99}; /* n < 1 */
        expect_eval(bf_model_fc_g, p, g, BF_EINVAL);
        p[1] = 10.5;
        expect_eval(bf_model_fc_e, p, g, BF_EINVAL);
        p[1] = 1.0; /* the bound itself is valid */
        expect_eval(bf_model_fc_e, p, g, BF_OK);
    }
    {
        double p[2] = {1.1, 0.3}; /* rho > 1 */
        expect_eval(bf_model_on, p, g, BF_EINVAL);
        p[0] = 0.4;
        p[1] = -0.1; /* sigma < 0 */
        expect_eval(bf_model_on, p, g, BF_EINVAL);
        p[1] = PI_2 + 1e-9;
        expect_eval(bf_model_on, p, g, BF_EINVAL);
        p[1] = PI_2;
        expect_eval(bf_model_on, p, g, BF_OK);
    }
    {
        double p[1] = {-0.01};
        expect_eval(bf_model_lftg, p, g, BF_EINVAL);
        p[0] = 100.1;
        expect_eval(bf_model_lftg, p, g, BF_EINVAL);
    }
    {
        double p[1] = {0.1}; /* grid bounds are valid */
        expect_eval(bf_model_vh_e, p, g, BF_OK);
        p[0] = 5.1;
        expect_eval(bf_model_vh_e, p, g, BF_OK);
    }
}

Test(registry, eval_rejects_geometry_outside_the_closed_hemisphere)
{
    bf_geom ok = {0.7313, PI, 1.0219, 2.2619};
    bf_geom g;
    size_t i;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        /* WNO's only parameter is n >= 1; WNO-R's are sigma, n; the
         * specular models (SPEC §9.3) at their defaults */
        double q[BF_MAX_PARAMS] = {(t == bf_model_on) ? 0.4
                                          : (t == bf_model_wno ? 1.6173 : 0.6173),
                       (t == bf_model_on) ? 0.5 : 1.7};
        size_t j;
        for (j = 0; t->kind == BF_MODEL_SPECULAR && j < t->p; j++) {
            q[j] = t->param[j].value;
        }
        g = ok;
        g.theta_i = NAN;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok;
        g.theta_s = -1e-3;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok;
        g.theta_s = PI_2 + 1e-9;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok;
        g.theta_i = 2.0;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok;
        g.phi_s = INFINITY;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok;
        g.phi_i = NAN;
        expect_eval(t, q, g, BF_EINVAL);
        g = ok; /* pi/2 itself (asin(1)) is inside for the viewing angle;
                   WARD and WARD-DUER diverge there (brdffit.h) */
        g.theta_s = asin(1.0);
        expect_eval(t, q, g,
                    (strcmp(t->name, "WARD") == 0 ||
                     strcmp(t->name, "WARD-DUER") == 0) ? BF_EDOM : BF_OK);
    }
}

Test(registry, eval_rejects_missing_arrays_and_accepts_empty_input)
{
    double p[1] = {0.5};
    bf_geom g = {0.7313, PI, 1.0219, 2.2619};
    double out;
    cr_assert_eq(bf_model_eval(NULL, p, 1, &g, &out), BF_EINVAL);
    cr_assert_eq(bf_model_eval(bf_model_vh_g, NULL, 1, &g, &out), BF_EINVAL);
    cr_assert_eq(bf_model_eval(bf_model_vh_g, p, 1, NULL, &out), BF_EINVAL);
    cr_assert_eq(bf_model_eval(bf_model_vh_g, p, 1, &g, NULL), BF_EINVAL);
    cr_assert_eq(bf_model_eval(bf_model_vh_g, p, 0, NULL, NULL), BF_OK);
}

Test(registry, eval_reports_a_domain_error_and_still_fills_the_rest)
{
    double p[1] = {0.5};
    bf_geom g[2] = {{PI_2, PI, 0.3, 0.0}, {0.7313, PI, 0.7313, 0.0}};
    double out[2];
    cr_assert_eq(bf_model_eval(bf_model_bk_g, p, 2, g, out), BF_EDOM);
    cr_assert(isnan(out[0]));
    /* specular closed form 1/(4 m^2 ci^2), see test_bk.c */
    bf_assert_rel(out[1], 1.0 / (4.0 * 0.25 * cos(0.7313) * cos(0.7313)), TOL1);
}

/* The default model sets name registry models, each once: the paper's six
 * (its Tables 2-3), and for a ranking those six first, then the
 * baselines. */
Test(registry, default_model_sets_name_registry_models)
{
    static const char *const paper[] = {"VH-G", "VH-E", "FC-G",
                                        "FC-E", "ON",   "LFTG"};
    const bf_model_set sets[] = {BF_MODELS_PAPER, BF_MODELS_RANKING};
    size_t i;
    for (i = 0; i < 2; i++) {
        char buf[256];
        char *save = NULL;
        char *tok;
        size_t n = 0;
        const char *list = bf_model_set_names(sets[i]);
        cr_assert_not_null(list);
        cr_assert_lt(strlen(list), sizeof buf);
        strcpy(buf, list);
        for (tok = strtok_r(buf, ",", &save); tok != NULL;
             tok = strtok_r(NULL, ",", &save), n++) {
            cr_assert_not_null(bf_model_find(tok), "%s", tok);
            cr_assert(strstr(list, tok) == list + (tok - buf),
                      "%s listed twice", tok); /* its first occurrence */
            if (n < 6) {
                cr_assert_str_eq(tok, paper[n]);
            }
        }
        cr_assert_eq(n, i == 0 ? 6u : 9u, "%zu models", n);
    }
    cr_assert_null(bf_model_set_names((bf_model_set)7));
}
