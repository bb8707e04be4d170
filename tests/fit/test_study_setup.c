/* test_study_setup.c: the study setup every caller shares (bf_study_models,
 * bf_study_variants, bf_study_rows_check): the model list's defaults,
 * "all" and its errors; the variants' exact-fit freeing, ranges and their
 * errors; the first failed row; the analysis options' check. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "support.h"

#define CAP 64

Test(study_models, defaults_all_and_a_list)
{
    const bf_model_type *m[CAP];
    size_t n = 0;
    size_t i;
    bf_error err;
    cr_assert_eq(bf_study_models(NULL, BF_MODELS_PAPER, BF_OBJ_MAX, 0, 0, m,
                                 CAP, &n, &err), BF_OK);
    cr_assert_eq(n, 6);
    cr_assert_str_eq(m[0]->name, "VH-G");
    cr_assert_str_eq(m[5]->name, "LFTG");
    cr_assert_eq(bf_study_models(NULL, BF_MODELS_RANKING, BF_OBJ_MAX, 0, 0,
                                 m, CAP, &n, &err), BF_OK);
    cr_assert_eq(n, 9);
    cr_assert_eq(bf_study_models("all", BF_MODELS_PAPER, BF_OBJ_MAX, 0, 0, m,
                                 CAP, &n, &err), BF_OK);
    cr_assert_gt(n, 6);
    for (i = 0; i < n; i++) {
        cr_assert_eq(m[i]->kind, BF_MODEL_DIFFUSE, "%s", m[i]->name);
    }
    cr_assert_eq(bf_study_models("fc-e,ON", BF_MODELS_PAPER, BF_OBJ_MAX, 0,
                                 0, m, CAP, &n, &err), BF_OK);
    cr_assert_eq(n, 2);
    cr_assert_eq(m[0], bf_model_find("FC-E"));
    cr_assert_eq(bf_study_models("GGX", BF_MODELS_PAPER, BF_OBJ_NGAN, 0, 0, m,
                                 CAP, &n, &err), BF_OK);
    cr_assert_eq(n, 1);
}

Test(study_models, all_under_the_objectives_that_keep_the_scale_is_complete)
{
    /* the complete glossy comparison: every diffuse model, then LAMBERT+S
     * for every specular model S of SPEC §9.3, AS alone (its own diffuse
     * term); the paper's objectives keep the diffuse models only */
    static const bf_objective keep[3] = {BF_OBJ_NGAN, BF_OBJ_CUBEROOT,
                                         BF_OBJ_LOG1P};
    const bf_model_type *m[CAP];
    const bf_model_type *diffuse[CAP];
    size_t nd = 0;
    size_t n = 0;
    size_t o;
    size_t i;
    bf_error err;
    cr_assert_eq(bf_study_models("all", BF_MODELS_PAPER, BF_OBJ_MAX, 0, 0,
                                 diffuse, CAP, &nd, &err), BF_OK);
    for (o = 0; o < 3; o++) {
        size_t composites = 0;
        size_t alone = 0;
        cr_assert_eq(bf_study_models("all", BF_MODELS_PAPER, keep[o], 0, 0,
                                     m, CAP, &n, &err), BF_OK, "%s",
                     err.msg);
        cr_assert_eq(n, 21, "%s", bf_objective_name(keep[o]));
        cr_assert_eq(n, bf_model_count(), "bf_model_count() + 1 is enough");
        for (i = 0; i < nd; i++) {
            cr_assert_eq(m[i], diffuse[i], "%s", m[i]->name);
        }
        for (i = nd; i < n; i++) {
            size_t first;
            const bf_model_type *s = bf_model_specular_part(m[i], &first);
            cr_assert_eq(m[i]->kind, BF_MODEL_SPECULAR, "%s", m[i]->name);
            cr_assert_not_null(s, "%s", m[i]->name);
            if (first == 0) { /* alone: a model with its diffuse term */
                cr_assert_str_eq(m[i]->name, "AS");
                cr_assert(m[i]->own_diffuse);
                alone++;
            } else {
                char want[64];
                snprintf(want, sizeof want, "LAMBERT+%s", s->name);
                cr_assert_str_eq(m[i]->name, want);
                cr_assert_not(s->own_diffuse, "%s", s->name);
                composites++;
            }
        }
        cr_assert_eq(composites, 9);
        cr_assert_eq(alone, 1);
        cr_assert_str_eq(m[nd]->name, "LAMBERT+GGX");
    }
}

Test(study_models, errors_say_what)
{
    static const struct {
        const char *list;
        bf_objective obj;
        int code;
        const char *msg;
    } bad[] = {
        {"VH-G,XX", BF_OBJ_MAX, BF_ENOTFOUND, "unknown model 'XX'"},
        {"ON,ON", BF_OBJ_MAX, BF_EINVAL, "'ON' listed twice"},
        {"ON,", BF_OBJ_MAX, BF_EINVAL, "trailing comma"},
        {",ON", BF_OBJ_MAX, BF_EINVAL, "bad list"},
        {"", BF_OBJ_MAX, BF_EINVAL, "bad list"},
        {"GGX", BF_OBJ_MAX, BF_EDOM, "GGX gives absolute BRDF values"},
        {"FOO+GGX", BF_OBJ_NGAN, BF_ENOTFOUND, "'FOO+GGX': "},
        {"VH-G,VH-E", BF_OBJ_MAX, BF_EINVAL, "too many"}, /* cap 1 */
    };
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const bf_model_type *m[CAP];
        size_t n = 0;
        bf_error err;
        size_t cap = strcmp(bad[i].msg, "too many") == 0 ? 1 : CAP;
        cr_assert_eq(bf_study_models(bad[i].list, BF_MODELS_PAPER,
                                     bad[i].obj, 0, 0, m, cap, &n, &err),
                     bad[i].code, "%s", bad[i].list);
        cr_assert_not_null(strstr(err.msg, bad[i].msg), "%s: %s",
                           bad[i].list, err.msg);
    }
}

/* The names of type's parameters, comma-separated, into buf. */
static const char *param_names(const bf_model_type *t, char *buf, size_t len)
{
    size_t j;
    size_t at = 0;
    buf[0] = '\0';
    for (j = 0; j < t->p && at < len; j++) {
        at += (size_t)snprintf(buf + at, len - at, "%s%s", j ? "," : "",
                               t->param[j].name);
    }
    return buf;
}

Test(study_models, fresnel_and_smith_options)
{
    const bf_model_type *m[CAP];
    size_t n = 0;
    bf_error err;
    char names[128];
    cr_assert_eq(bf_study_models("LAMBERT+GGX,ON,CT", BF_MODELS_PAPER,
                                 BF_OBJ_NGAN, BF_FRESNEL_DIELECTRIC, 0, m,
                                 CAP, &n, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(n, 3);
    cr_assert_str_eq(m[0]->name, "LAMBERT+GGX");
    cr_assert_str_eq(param_names(m[0], names, sizeof names),
                     "rho_d,rho_s,alpha,n");
    cr_assert_eq(m[1], bf_model_find("ON")); /* diffuse: unaffected */
    cr_assert_str_eq(param_names(m[2], names, sizeof names), "rho_s,alpha,n");
    cr_assert_neq(m[0], bf_model_find("LAMBERT+GGX"));
    cr_assert_str_eq(m[0]->fresnel_term, m[2]->fresnel_term);
    cr_assert_str_neq(m[0]->fresnel_term,
                      bf_model_find("LAMBERT+GGX")->fresnel_term);
    /* the composite's S part is GGX's variant */
    cr_assert_eq(bf_model_specular_part(m[0], NULL),
                 bf_model_specular_variant(bf_model_find("GGX"),
                                           BF_FRESNEL_DIELECTRIC, 0, NULL));

    cr_assert_eq(bf_study_models("BECKMANN,ON+BECKMANN", BF_MODELS_PAPER,
                                 BF_OBJ_NGAN, BF_FRESNEL_NONE,
                                 BF_SMITH_SEPARABLE, m, CAP, &n, &err),
                 BF_OK, "%s", err.msg);
    cr_assert_str_eq(param_names(m[0], names, sizeof names), "rho_s,alpha");
    cr_assert_str_eq(param_names(m[1], names, sizeof names),
                     "rho_d,rho,sigma,rho_s,alpha");
    cr_assert_str_eq(m[1]->masking, m[0]->masking);
    cr_assert_str_neq(m[0]->masking, bf_model_find("BECKMANN")->masking);

    /* the options given explicitly as the defaults: the registry's */
    cr_assert_eq(bf_study_models("GGX", BF_MODELS_PAPER, BF_OBJ_NGAN,
                                 BF_FRESNEL_SCHLICK, BF_SMITH_HEIGHT, m, CAP,
                                 &n, &err), BF_OK);
    cr_assert_eq(m[0], bf_model_find("GGX"));
}

Test(study_models, option_errors_say_what)
{
    static const struct {
        const char *list;
        bf_objective obj;
        bf_fresnel_kind f;
        bf_smith_kind s;
        int code;
        const char *msg;
    } bad[] = {
        {"GGX,WARD", BF_OBJ_NGAN, BF_FRESNEL_DIELECTRIC, 0, BF_EDOM,
         "WARD has no Fresnel term"},
        {"LAMBERT+WARD", BF_OBJ_NGAN, BF_FRESNEL_NONE, 0, BF_EDOM,
         "LAMBERT+WARD has no Fresnel term"},
        {"ABC", BF_OBJ_NGAN, BF_FRESNEL_SCHLICK, 0, BF_EDOM,
         "ABC has its own Fresnel term"},
        {"CT", BF_OBJ_NGAN, 0, BF_SMITH_SEPARABLE, BF_EDOM,
         "CT has no Smith masking"},
        {"VH-G,ON", BF_OBJ_NGAN, BF_FRESNEL_DIELECTRIC, 0, BF_EDOM,
         "no selected model takes --fresnel or --smith"},
        {NULL, BF_OBJ_MAX, 0, BF_SMITH_SEPARABLE, BF_EDOM,
         "--fresnel and --smith apply to the specular models"},
        {"GGX", BF_OBJ_NGAN, (bf_fresnel_kind)9, 0, BF_EINVAL,
         "unknown --fresnel or --smith value"},
    };
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const bf_model_type *m[CAP];
        size_t n = 0;
        bf_error err;
        cr_assert_eq(bf_study_models(bad[i].list, BF_MODELS_PAPER,
                                     bad[i].obj, bad[i].f, bad[i].s, m, CAP,
                                     &n, &err),
                     bad[i].code, "%zu", i);
        cr_assert_not_null(strstr(err.msg, bad[i].msg), "%zu: %s", i,
                           err.msg);
    }
}

Test(study_variants, none_exact_and_ranges)
{
    const bf_model_type *base[2];
    const bf_model_type *out[2];
    bf_model_variant v[2];
    bf_param_range r = {"m", 0.01, 1.0};
    size_t br = 99;
    size_t bm = 99;
    int j;
    base[0] = bf_model_find("FC-E");
    base[1] = bf_model_find("ON");
    cr_assert_eq(bf_study_variants(base, 2, 0, 0, NULL, 0, NULL, out, &br,
                                   &bm), BF_OK);
    cr_assert(out[0] == base[0] && out[1] == base[1]);
    /* exact: FC-E's n freed, unless kept */
    cr_assert_eq(bf_study_variants(base, 2, 1, 0, NULL, 0, v, out, &br, &bm),
                 BF_OK);
    cr_assert_eq(out[0], &v[0].type);
    cr_assert_eq(out[1], &v[1].type);
    j = bf_model_param_index(out[0], "n");
    cr_assert(j >= 0 && out[0]->param[j].fitted);
    cr_assert(!base[0]->param[j].fitted);
    cr_assert_eq(bf_study_variants(base, 2, 1, 1u << BF_INPUT_INDEX, NULL, 0,
                                   v, out, &br, &bm), BF_OK);
    cr_assert(!out[0]->param[j].fitted);
    /* a range applies to the model that has the parameter */
    cr_assert_eq(bf_study_variants(base, 2, 0, 0, &r, 1, v, out, &br, &bm),
                 BF_OK);
    j = bf_model_param_index(out[0], "m");
    cr_assert_float_eq(out[0]->param[j].grid_lo, 0.01, 1e-12);
    cr_assert_gt(out[0]->param[j].grid_n, 1);
    cr_assert_float_eq(out[0]->param[j].grid_lo +
                           out[0]->param[j].grid_step *
                               (double)(out[0]->param[j].grid_n - 1),
                       1.0, 1e-9);
    cr_assert_eq(memcmp(out[1]->param, base[1]->param,
                        base[1]->p * sizeof *base[1]->param), 0); /* no m */
    /* no model has q; m outside its limits */
    r.name = "q";
    cr_assert_eq(bf_study_variants(base, 2, 0, 0, &r, 1, v, out, &br, &bm),
                 BF_ENOTFOUND);
    cr_assert_eq(br, 0);
    r.name = "m";
    r.hi = 1e9;
    cr_assert_eq(bf_study_variants(base, 2, 0, 0, &r, 1, v, out, &br, &bm),
                 BF_EINVAL);
    cr_assert(br == 0 && bm == 0);
}

Test(study_rows_check, the_first_failed_row)
{
    bf_study_row rows[4];
    size_t bad = 99;
    memset(rows, 0, sizeof rows);
    rows[1].status = BF_ENOTFOUND; /* a gap, not a failure */
    cr_assert_eq(bf_study_rows_check(rows, 4, &bad), BF_OK);
    cr_assert_eq(bad, 99);
    rows[2].status = BF_EDOM;
    rows[3].status = BF_ENOMEM;
    cr_assert_eq(bf_study_rows_check(rows, 4, &bad), BF_EDOM);
    cr_assert_eq(bad, 2);
    cr_assert_eq(bf_study_rows_check(rows, 2, &bad), BF_OK);
}

/* bf_analysis_opts_check: the defaults pass; each wrong field is refused
 * with BF_EINVAL and a message naming it. */
Test(analysis_opts_check, the_defaults_pass_each_wrong_field_is_named)
{
    bf_analysis_opts o;
    bf_error err;
    bf_analysis_opts_init(&o);
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_OK);
    o.no_intervals = 1;
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_OK);
    o.n_boot = 10;
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_EINVAL);
    cr_expect_not_null(strstr(err.msg, "bootstrap"), "%s", err.msg);
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_EINVAL);
    bf_analysis_opts_init(&o);
    o.level = 1.0;
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_EINVAL);
    cr_expect_not_null(strstr(err.msg, "level"), "%s", err.msg);
    bf_analysis_opts_init(&o);
    o.objective = (bf_objective)99;
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_EINVAL);
    cr_expect_not_null(strstr(err.msg, "objective"), "%s", err.msg);
    bf_analysis_opts_init(&o);
    o.noise = (bf_noise)99;
    cr_assert_eq(bf_analysis_opts_check(&o, &err), BF_EINVAL);
    cr_expect_not_null(strstr(err.msg, "noise"), "%s", err.msg);
    cr_assert_eq(bf_analysis_opts_check(NULL, &err), BF_EINVAL);
}
