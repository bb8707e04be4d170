/* test_dispersion.c: n(lambda) under --fresnel dielectric (issue 17 item
 * 7; doc/methods.md "Dispersion"): a synthetic spectral paint whose index
 * follows Cauchy's law n = A + B / lambda^2, measured with 1% relative
 * noise on three wavelengths, comes back per channel within its profile
 * intervals through tidy CSV, the CLI and dispersion.csv; --channel joint
 * gives one n; a model without n gives no points (bf_dispersion_points);
 * the real krylon_blue's mean index is a binder's. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(dispersion, .init = setup);

#define N_CONF BF_TEST_GLOSSY_NCONF
#define N_CH 3
#define NOISE 0.01

static const double lambda_nm[N_CH] = {450.0, 550.0, 650.0};
static const char *const ch_name[N_CH] = {"450", "550", "650"};

/* Cauchy's law (Born & Wolf, Principles of Optics, §2.3 eq. (39)):
 * n = A + B / lambda^2, lambda in micrometres; B larger than a real
 * binder's so the three channels differ by more than their intervals. */
static double cauchy(double nm)
{
    double um = nm / 1000.0;
    return 1.50 + 0.03 / (um * um);
}

/* LAMBERT+GGX under --fresnel dielectric: rho_d, rho_s, alpha, n. */
static const bf_model_type *dielectric_type(void)
{
    const bf_model_type *t = bf_model_specular_variant(
        bf_model_find("LAMBERT+GGX"), BF_FRESNEL_DIELECTRIC,
        BF_SMITH_DEFAULT, NULL);
    cr_assert_not_null(t);
    cr_assert_eq(bf_model_param_index(t, "n"), 3);
    return t;
}

static const char *const paint[1] = {"paint"};

/* Writes the paint (channel c: LAMBERT+GGX with n = cauchy(lambda_c),
 * each value times 1 + NOISE eps) as tidy CSV to path. */
static void write_paint(const char *path)
{
    static double at[4 * N_CONF];
    static bf_geom geom[N_CONF];
    static double value[N_CONF * N_CH];
    const bf_model_type *t = dielectric_type();
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double v[N_CONF];
    size_t c;
    size_t k;
    cr_assert_not_null(rng);
    gsl_rng_set(rng, 17);
    bf_test_glossy_configs(at);
    for (k = 0; k < N_CONF; k++) {
        geom[k] = bf_geom_from_measurement(at[4 * k], at[4 * k + 1],
                                           at[4 * k + 2], at[4 * k + 3]);
    }
    for (c = 0; c < N_CH; c++) {
        double p[4] = {0.2, 0.5, 0.12, 0.0};
        p[3] = cauchy(lambda_nm[c]);
        cr_assert_eq(bf_model_eval(t, p, N_CONF, geom, v), BF_OK);
        for (k = 0; k < N_CONF; k++) {
            value[k * N_CH + c] =
                v[k] * (1.0 + NOISE * gsl_ran_gaussian(rng, 1.0));
        }
    }
    bf_test_write_channels_csv(path, N_CONF, at, 1, paint, N_CH, ch_name,
                               lambda_nm, value);
    gsl_rng_free(rng);
}

/* brdffit compare on the paint with channel and fresnel; returns the
 * lines of dispersion.csv (loaded; 0 when the file is absent). */
static size_t run(const char *channel, const char *fresnel, const char *out)
{
    const char *dir = bf_test_tmpdir();
    char csv[512];
    char path[600];
    const char *err = NULL;
    const char *argv[] = {"compare",  "--input",     csv,   "--models",
                          "LAMBERT+GGX", "--channel", channel, "--fresnel",
                          fresnel,   "--fit",       "exact", "--objective",
                          "ngan",    "--out",       out,   "--quiet",
                          "--folds", "0",           NULL};
    FILE *fp;
    snprintf(csv, sizeof csv, "%s/paint.csv", dir);
    write_paint(csv);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "compare: %s", err);
    snprintf(path, sizeof path, "%s/dispersion.csv", out);
    fp = fopen(path, "r");
    if (fp == NULL) {
        return 0;
    }
    fclose(fp);
    return bf_test_csv_load(out, "dispersion.csv");
}

Test(dispersion, each_channel_within_its_interval, .timeout = 600)
{
    char out[512];
    size_t lines;
    size_t c;
    snprintf(out, sizeof out, "%s/each", bf_test_tmpdir());
    lines = run("each", "dielectric", out);
    cr_assert_eq(lines, 1 + N_CH);
    for (c = 0; c < N_CH; c++) {
        size_t r = c + 1;
        double truth = cauchy(lambda_nm[c]);
        double lo = bf_test_csv_num(r, "ci_low");
        double hi = bf_test_csv_num(r, "ci_high");
        cr_assert_str_eq(bf_test_csv_cell(r, "channel"), ch_name[c]);
        cr_assert_str_eq(bf_test_csv_cell(r, "model"), "LAMBERT+GGX");
        cr_assert_eq(bf_test_csv_num(r, "wavelength_nm"), lambda_nm[c]);
        cr_assert(lo <= truth && truth <= hi,
                  "%s: n = %.5f outside [%.5f, %.5f] (fit %.5f)", ch_name[c],
                  truth, lo, hi, bf_test_csv_num(r, "n"));
        /* an interval that says something: narrower than the gap
         * between the first and last channel's true n */
        cr_assert(hi - lo < cauchy(lambda_nm[0]) - cauchy(lambda_nm[2]),
                  "%s: interval [%g, %g] too wide", ch_name[c], lo, hi);
        cr_assert(fabs(bf_test_csv_num(r, "n") - truth) < 0.05,
                  "%s: n %g against %g", ch_name[c],
                  bf_test_csv_num(r, "n"), truth);
    }
}

Test(dispersion, joint_gives_one_value, .timeout = 600)
{
    char out[512];
    size_t lines;
    double n;
    snprintf(out, sizeof out, "%s/joint", bf_test_tmpdir());
    lines = run("joint", "dielectric", out);
    cr_assert_eq(lines, 2);
    cr_assert_str_eq(bf_test_csv_cell(1, "channel"), "joint");
    cr_assert(isnan(bf_test_csv_num(1, "wavelength_nm")));
    n = bf_test_csv_num(1, "n");
    /* one n for all three: between the channels' true values */
    cr_assert(n > cauchy(lambda_nm[2]) - 0.02 &&
                  n < cauchy(lambda_nm[0]) + 0.02,
              "joint n %g", n);
}

/* The paint at one configuration, 0.1 on every channel. */
static bf_dataset *one_point_paint(void)
{
    static const double at[4] = {0.3, 3.14159265358979323846, 0.3, 0.0};
    static const double value[N_CH] = {0.1, 0.1, 0.1};
    return bf_test_channels_dataset(1, at, 1, paint, N_CH, ch_name,
                                    lambda_nm, value);
}

/* A study of ds's target tg with the one model *t, and its fitted row on
 * channel 1 (sample 1, parameters 0). */
static void one_row(bf_dataset *ds, bf_target *tg, const bf_model_type **t,
                    bf_study_spec *spec, bf_study_row *row)
{
    memset(spec, 0, sizeof *spec);
    memset(row, 0, sizeof *row);
    spec->data = ds;
    spec->targets = tg;
    spec->n_targets = 1;
    spec->models = t;
    spec->n_models = 1;
    row->sample = 1;
    row->channel = 1;
    row->type = *t;
    row->status = BF_OK;
}

Test(dispersion, no_n_no_points)
{
    /* Schlick's F0 instead of n: no dispersion point, no file */
    const bf_model_type *schlick = bf_model_find("LAMBERT+GGX");
    const bf_model_type *diel = dielectric_type();
    bf_dataset *ds = one_point_paint();
    bf_target tg = {0, 1, 0};
    bf_study_spec spec;
    bf_study_row row;
    bf_dispersion_point pt;
    cr_assert_eq(bf_model_param_index(schlick, "n"), -1);
    one_row(ds, &tg, &schlick, &spec, &row);
    cr_assert_eq(bf_dispersion_points(&spec, &row, NULL, NULL), 0);
    /* the same row with n: one point at 550 nm, n its value */
    row.type = diel;
    spec.models = &diel;
    row.fit.param[3] = 1.6;
    cr_assert_eq(bf_dispersion_points(&spec, &row, NULL, &pt), 1);
    cr_assert_eq(pt.wavelength, 550.0);
    cr_assert_eq(pt.n, 1.6);
    cr_assert(isnan(pt.ci_low));
    /* the mean channel has no wavelength */
    tg.channel = BF_CHANNEL_MEAN;
    cr_assert_eq(bf_dispersion_points(&spec, &row, NULL, NULL), 0);
    bf_dataset_free(ds);
}

/* Only a refractive index is one: AS's and LAMBERT+LAFORTUNE's fitted
 * exponents are named n too and give no point (an AS fit on a channel put
 * its exponent, 1549, into dispersion.csv as n); ABC's ior is an index
 * (its Fresnel factor is the dielectric one) and gives one. */
Test(dispersion, exponents_named_n_are_no_index)
{
    static const char *const names[3] = {"AS", "LAMBERT+LAFORTUNE",
                                         "LAMBERT+ABC"};
    static const int points[3] = {0, 0, 1};
    bf_dataset *ds = one_point_paint();
    bf_target tg = {0, 1, 0};
    size_t i;
    for (i = 0; i < 3; i++) {
        const bf_model_type *t = bf_model_find(names[i]);
        bf_study_spec spec;
        bf_study_row row;
        bf_dispersion_point pt;
        size_t j;
        cr_assert_not_null(t);
        one_row(ds, &tg, &t, &spec, &row);
        for (j = 0; j < t->p; j++) {
            row.fit.param[j] = 1.0 + (double)j;
        }
        cr_assert_eq(bf_dispersion_points(&spec, &row, NULL, &pt),
                     (size_t)points[i], "%s", names[i]);
        if (points[i]) {
            int k = bf_model_param_index(t, "ior");
            cr_assert_geq(k, 0);
            cr_assert_eq(pt.n, row.fit.param[k], "%s", names[i]);
            cr_assert_eq(pt.wavelength, 550.0);
        }
    }
    bf_dataset_free(ds);
}

/* The real krylon_blue (Cornell, spectral): the channel mean's dielectric
 * n lies in the range of paint binders and clear coats, 1.40 to 1.70
 * (doc/methods.md "Dispersion": about 1.54 with F(0) = 0.045; Schlick's
 * F0 = 0.059 of the same file would mean 1.64 under another Fresnel
 * form). The mean channel has no wavelength: no dispersion.csv. */
Test(dispersion, krylon_blue_mean_index_is_a_binders, .timeout = 600)
{
    char out[512];
    char path[600];
    const char *err = NULL;
    const char *argv[] = {"compare",     "--input",
                          BF_CORNELL_DIR "/krylon_blue.brdf",
                          "--models",    "LAMBERT+GGX",
                          "--fresnel",   "dielectric",
                          "--fit",       "exact",
                          "--objective", "ngan",
                          "--folds",     "0",
                          "--out",       out,
                          "--quiet",     NULL};
    size_t lines;
    size_t r;
    FILE *fp;
    snprintf(out, sizeof out, "%s/krylon", bf_test_tmpdir());
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "compare: %s", err);
    lines = bf_test_csv_load(out, "fits.csv");
    for (r = 1; r < lines; r++) {
        if (strcmp(bf_test_csv_cell(r, "parameter"), "n") == 0) {
            double n = bf_test_csv_num(r, "value");
            cr_assert(n >= 1.40 && n <= 1.70, "krylon_blue n = %g", n);
            break;
        }
    }
    cr_assert(r < lines, "no n in fits.csv");
    snprintf(path, sizeof path, "%s/dispersion.csv", out);
    fp = fopen(path, "r");
    cr_assert_null(fp, "dispersion.csv written for the mean channel");
}
