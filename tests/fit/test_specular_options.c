/* test_specular_options.c: the options of the specular models (SPEC §9.2,
 * issue 17 item 4) on the fitting commands: --fresnel dielectric and
 * --smith separable recover synthetic composites exactly through tidy CSV
 * under --objective ngan --fit exact, fits.csv names the variant fitted,
 * the separable and height-correlated fits of the same data differ, and
 * bad input gets a clear error and a non-zero exit. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(specular_options, .init = setup);

typedef struct {
    const char *name;     /* the material's */
    const char *model;    /* --models */
    const char *fresnel;  /* --fresnel, or NULL */
    const char *smith;    /* --smith, or NULL */
    bf_fresnel_kind f;
    bf_smith_kind s;
    double param[BF_MAX_PARAMS];
} truth_t;

/* Inside every parameter's domain, off its bounds. */
static const truth_t truths[] = {
    {"ggx-dielectric", "LAMBERT+GGX", "dielectric", NULL,
     BF_FRESNEL_DIELECTRIC, BF_SMITH_DEFAULT, {0.3, 0.8, 0.15, 1.5}},
    {"beckmann-separable", "LAMBERT+BECKMANN", NULL, "separable",
     BF_FRESNEL_DEFAULT, BF_SMITH_SEPARABLE, {0.2, 0.5, 0.5, 0.08}},
    {"ggx-none-separable", "LAMBERT+GGX", "none", "separable",
     BF_FRESNEL_NONE, BF_SMITH_SEPARABLE, {0.25, 0.05, 0.2}},
    {"ct-dielectric", "CT", "dielectric", NULL, BF_FRESNEL_DIELECTRIC,
     BF_SMITH_DEFAULT, {0.6, 0.25, 2.2}},
};
#define N_TRUTHS (sizeof truths / sizeof truths[0])

static const bf_model_type *variant(const truth_t *tr)
{
    const char *why = NULL;
    const bf_model_type *t = bf_model_specular_variant(
        bf_model_find(tr->model), tr->f, tr->s, &why);
    cr_assert_not_null(t, "%s: %s", tr->name, why);
    return t;
}

/* The synthetic materials' CSV in a fresh folder (static buffer). */
static const char *synthetic_csv(void)
{
    static char csv[512];
    bf_test_material mat[N_TRUTHS];
    size_t i;
    snprintf(csv, sizeof csv, "%s/synthetic.csv", bf_test_tmpdir());
    for (i = 0; i < N_TRUTHS; i++) {
        mat[i].name = truths[i].name;
        mat[i].type = variant(&truths[i]);
        mat[i].param = truths[i].param;
    }
    bf_test_write_glossy_csv(csv, N_TRUTHS, mat);
    return csv;
}

/* A composite's variants (bf_model_specular_variant on D+S): named as the
 * composite, parameters rho_d, D's, then S's variant's, value rho_d d + S's
 * variant (SPEC §9.4), and back to the registry's composite. */
Test(specular_options, composite_variants)
{
    static const bf_geom g[3] = {{0.2, 3.14159265358979, 0.25, 0.1},
                                 {0.7, 3.14159265358979, 0.5, 2.0},
                                 {1.1, 3.14159265358979, 1.0, 0.3}};
    static const double p[4] = {0.3, 0.8, 0.25, 1.6};
    const bf_model_type *c = bf_model_find("LAMBERT+GGX");
    const bf_model_type *s = bf_model_specular_variant(
        bf_model_find("GGX"), BF_FRESNEL_DIELECTRIC, BF_SMITH_SEPARABLE,
        NULL);
    const bf_model_type *v = bf_model_specular_variant(
        c, BF_FRESNEL_DIELECTRIC, BF_SMITH_SEPARABLE, NULL);
    const bf_model_type *on = bf_model_specular_variant(
        bf_model_find("ON+BECKMANN"), BF_FRESNEL_NONE, 0, NULL);
    double vv[3];
    double sv[3];
    size_t k;
    cr_assert(s != NULL && v != NULL && on != NULL);
    cr_assert_str_eq(v->name, "LAMBERT+GGX");
    cr_assert_eq(v->p, 4);
    cr_assert_str_eq(v->param[3].name, "n");
    cr_assert_str_eq(v->masking, s->masking);
    cr_assert_eq(bf_model_specular_part(v, NULL), s);
    cr_assert_eq(on->p, 5); /* rho_d, rho, sigma, rho_s, alpha */
    cr_assert_str_eq(on->param[4].name, "alpha");
    cr_assert_eq(bf_model_specular_variant(v, BF_FRESNEL_SCHLICK,
                                           BF_SMITH_HEIGHT, NULL), c);
    cr_assert_eq(bf_model_eval(v, p, 3, g, vv), BF_OK);
    cr_assert_eq(bf_model_eval(s, p + 1, 3, g, sv), BF_OK);
    for (k = 0; k < 3; k++) {
        bf_assert_rel(vv[k], p[0] / 3.14159265358979323846 + sv[k], 1e-14);
    }
}

/* brdffit compare of sample (1-based) of csv with model under the options
 * (NULL: not given), fits.csv loaded; fails the test on an error. Returns
 * fits.csv's number of lines. */
static size_t fit(const char *csv, size_t sample, const char *model,
                const char *fresnel, const char *smith)
{
    const char *argv[24];
    const char *err = NULL;
    char out[512];
    char number[32];
    size_t a = 0;
    int rc;
    snprintf(out, sizeof out, "%s/out", bf_test_tmpdir());
    snprintf(number, sizeof number, "%zu", sample);
    argv[a++] = "compare";
    argv[a++] = "--input";
    argv[a++] = csv;
    argv[a++] = "--samples";
    argv[a++] = number;
    argv[a++] = "--models";
    argv[a++] = model;
    argv[a++] = "--fit";
    argv[a++] = "exact";
    argv[a++] = "--objective";
    argv[a++] = "ngan";
    if (fresnel != NULL) {
        argv[a++] = "--fresnel";
        argv[a++] = fresnel;
    }
    if (smith != NULL) {
        argv[a++] = "--smith";
        argv[a++] = smith;
    }
    argv[a++] = "--out";
    argv[a++] = out;
    argv[a++] = "--quiet";
    argv[a] = NULL;
    rc = bf_test_run_cli(argv, NULL, &err);
    cr_assert_eq(rc, 0, "brdffit compare %s: %s", model, err);
    return bf_test_csv_load(out, "fits.csv");
}

Test(specular_options, recovery_ngan_through_csv_and_cli, .timeout = 300)
{
    const char *csv = synthetic_csv();
    size_t i;
    for (i = 0; i < N_TRUTHS; i++) {
        const truth_t *tr = &truths[i];
        const bf_model_type *type = variant(tr);
        const bf_model_type *sp = bf_model_specular_part(type, NULL);
        char sample[32];
        size_t j;
        snprintf(sample, sizeof sample, "%zu", i + 1);
        /* the header and one line per parameter of the variant */
        cr_assert_eq(fit(csv, i + 1, tr->model, tr->fresnel, tr->smith),
                     1 + type->p, "%s", tr->name);
        for (j = 0; j < type->p; j++) {
            size_t q = bf_test_csv_find(sample, tr->model,
                                        type->param[j].name);
            cr_assert_str_eq(bf_test_csv_cell(q, "objective"), "ngan");
            cr_assert_str_eq(bf_test_csv_cell(q, "ndf"), sp->ndf);
            cr_assert_str_eq(bf_test_csv_cell(q, "masking"), sp->masking);
            cr_assert_str_eq(bf_test_csv_cell(q, "fresnel"),
                             sp->fresnel_term);
            /* noise-free: E at rounding level */
            cr_assert(bf_test_csv_num(q, "lse") < 1e-9, "%s: E %g",
                      tr->name, bf_test_csv_num(q, "lse"));
            bf_assert_rel(bf_test_csv_num(q, "value"), tr->param[j], 1e-5);
        }
    }
}

/* fits.csv's lines of (sample, model), the registry's parameter names in
 * them: F0 under Schlick only, n under dielectric only. */
Test(specular_options, fits_csv_has_the_variants_parameters, .timeout = 120)
{
    const char *csv = synthetic_csv();
    const char *ggx_schlick = bf_model_find("GGX")->fresnel_term;
    const char *ggx_height = bf_model_find("GGX")->masking;
    size_t q;
    fit(csv, 1, "LAMBERT+GGX", "dielectric", NULL);
    q = bf_test_csv_find("1", "LAMBERT+GGX", "n");
    cr_assert_str_neq(bf_test_csv_cell(q, "fresnel"), ggx_schlick);
    cr_assert_str_eq(bf_test_csv_cell(q, "masking"), ggx_height);
    fit(csv, 3, "LAMBERT+GGX", "none", "separable");
    q = bf_test_csv_find("3", "LAMBERT+GGX", "alpha");
    cr_assert_str_neq(bf_test_csv_cell(q, "masking"), ggx_height);
    fit(csv, 1, "LAMBERT+GGX", NULL, NULL); /* Schlick: F0, no n */
    q = bf_test_csv_find("1", "LAMBERT+GGX", "F0");
    cr_assert_str_eq(bf_test_csv_cell(q, "fresnel"), ggx_schlick);
}

/* The same data (BECKMANN, separable masking) fitted with either masking
 * form: the separable fit is exact, the height-correlated one is not --
 * its E is far above rounding and its alpha differs. */
Test(specular_options, separable_and_height_fits_differ, .timeout = 120)
{
    const char *csv = synthetic_csv();
    double e[2];
    double alpha[2];
    int k;
    for (k = 0; k < 2; k++) {
        size_t q;
        fit(csv, 2, "LAMBERT+BECKMANN", NULL,
            k == 0 ? "separable" : "height");
        q = bf_test_csv_find("2", "LAMBERT+BECKMANN", "alpha");
        e[k] = bf_test_csv_num(q, "lse");
        alpha[k] = bf_test_csv_num(q, "value");
    }
    cr_assert(e[0] < 1e-9, "separable: E %g", e[0]);
    cr_assert(e[1] > 1e3 * e[0] && e[1] > 1e-6, "height: E %g", e[1]);
    cr_assert(fabs(alpha[1] - alpha[0]) > 1e-4, "alpha %g and %g", alpha[0],
              alpha[1]);
}

Test(specular_options, cli_refuses_bad_options, .timeout = 120)
{
    static const struct {
        const char *models;
        const char *option;
        const char *value;
        const char *objective;
        int status;
        const char *msg[2];
    } bad[] = {
        {"LAMBERT+GGX,LAMBERT+WARD", "--fresnel", "dielectric", "ngan", 63,
         {"LAMBERT+WARD has no Fresnel term", "--fresnel applies to GGX"}},
        {"WARD-DUER", "--fresnel", "none", "ngan", 63,
         {"WARD-DUER has no Fresnel term", "SPEC §9.3"}},
        {"AS", "--fresnel", "dielectric", "ngan", 63,
         {"AS has its own Fresnel term", "--fresnel applies to"}},
        {"LAMBERT+CT", "--smith", "separable", "ngan", 63,
         {"LAMBERT+CT has no Smith masking", "--smith applies to GGX"}},
        {"VH-G,ON", "--fresnel", "dielectric", "ngan", 63,
         {"no selected model takes --fresnel", "GGX, BECKMANN, CT"}},
        {"VH-G", "--smith", "height", "max", 63,
         {"--fresnel and --smith apply to the specular models",
          "--objective ngan"}},
        {"LAMBERT+GGX", "--fresnel", "glass", "ngan", 63,
         {"--fresnel: 'glass' is not schlick, dielectric or none", "--help"}},
        {"LAMBERT+GGX", "--smith", "uncorrelated", "ngan", 63,
         {"--smith: 'uncorrelated' is not height or separable", "--help"}},
    };
    const char *csv = synthetic_csv();
    char out[512];
    char fits[600];
    size_t i;
    snprintf(out, sizeof out, "%s/bad", bf_test_tmpdir());
    snprintf(fits, sizeof fits, "%s/fits.csv", out);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *err = NULL;
        const char *argv[] = {"compare",   "--input",     csv,
                              "--models",  bad[i].models, bad[i].option,
                              bad[i].value, "--fit",      "exact",
                              "--objective", bad[i].objective, "--out",
                              out,         "--quiet",     NULL};
        int rc = bf_test_run_cli(argv, NULL, &err);
        size_t m;
        cr_assert_eq(rc, bad[i].status, "%s %s: exit %d", bad[i].option,
                     bad[i].value, rc);
        for (m = 0; m < 2; m++) {
            cr_assert(strstr(err, bad[i].msg[m]) != NULL, "%s %s: %s",
                      bad[i].option, bad[i].value, err);
        }
        cr_assert_null(bf_test_slurp(fits, NULL), "%s written", fits);
    }
}

/* The run's description (printed, and the report page's) names each
 * specular model's NDF, masking and Fresnel term: the variant's. */
Test(specular_options, description_names_the_variant, .timeout = 120)
{
    const char *csv = synthetic_csv();
    const truth_t *tr = &truths[2]; /* GGX, none, separable */
    const bf_model_type *sp = bf_model_specular_part(variant(tr), NULL);
    const char *out = NULL;
    const char *err = NULL;
    char dir[512];
    char want[512];
    int rc;
    snprintf(dir, sizeof dir, "%s/described", bf_test_tmpdir());
    {
        const char *argv[] = {"compare",   "--input",   csv,
                              "--samples", "3",         "--models",
                              "LAMBERT,LAMBERT+GGX",    "--fresnel",
                              "none",      "--smith",   "separable",
                              "--fit",     "exact",     "--objective",
                              "ngan",      "--out",     dir,
                              NULL};
        rc = bf_test_run_cli(argv, &out, &err);
    }
    cr_assert_eq(rc, 0, "%s", err);
    snprintf(want, sizeof want,
             "Specular models (SPEC §9.2: NDF, masking, Fresnel): "
             "LAMBERT+GGX (%s, %s, %s)\n",
             sp->ndf, sp->masking, sp->fresnel_term);
    cr_assert_not_null(strstr(out, want), "%s", out);
    cr_assert_str_neq(sp->masking, bf_model_find("GGX")->masking);
    cr_assert_str_neq(sp->fresnel_term, bf_model_find("GGX")->fresnel_term);
}
