/* test_joint.c: --channel joint (SPEC §9.4; Ngan, Durand, Matusik 2005):
 * one shape for every channel, each channel's scales; exact recovery of a
 * synthetic three-channel material through tidy CSV (bf_csv_write) and
 * the CLI, fits.csv's layout (the shape on channel "joint", the scales on
 * the channels' names), the reported E over all K C values recomputed
 * from the written parameters, and the errors where joint cannot apply. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(joint, .init = setup);

#define N_CONF BF_TEST_GLOSSY_NCONF
#define N_CH 3

static const char *const ch_name[N_CH] = {"R", "G", "B"};

/* LAMBERT+GGX (rho_d, rho_s, alpha, F0) per channel: one alpha and F0,
 * the scales differ. */
static const double truth[N_CH][4] = {{0.3, 0.8, 0.15, 0.05},
                                      {0.2, 0.6, 0.15, 0.05},
                                      {0.1, 0.4, 0.15, 0.05}};

static double at[4 * N_CONF];
static bf_geom geom[N_CONF];
static double value[N_CONF * N_CH]; /* row-major, configuration x channel */

/* Writes one material whose channel c is LAMBERT+GGX at p[c] (BRDF,
 * sr^-1) through the library's tidy CSV writer. */
static void write_csv(const char *path, const double (*p)[4])
{
    static const char *const name[1] = {"paint"};
    const bf_model_type *t = bf_model_find("LAMBERT+GGX");
    double v[N_CONF];
    size_t c;
    size_t k;
    cr_assert_not_null(t);
    bf_test_glossy_configs(at);
    for (k = 0; k < N_CONF; k++) {
        geom[k] = bf_geom_from_measurement(at[4 * k], at[4 * k + 1],
                                           at[4 * k + 2], at[4 * k + 3]);
    }
    for (c = 0; c < N_CH; c++) {
        cr_assert_eq(bf_model_eval(t, p[c], N_CONF, geom, v), BF_OK);
        for (k = 0; k < N_CONF; k++) {
            value[k * N_CH + c] = v[k];
        }
    }
    bf_test_write_channels_csv(path, N_CONF, at, 1, name, N_CH, ch_name,
                               NULL, value);
}

/* brdffit compare --channel joint on path with extra arguments; the exit
 * status, err the message. */
static int compare_joint(const char *csv, const char *out,
                         const char *objective, const char *model,
                         const char **err)
{
    const char *argv[] = {"compare",   "--input",   csv,       "--models",
                          model,       "--channel", "joint",   "--fit",
                          "exact",     "--objective", objective, "--out",
                          out,         "--quiet",   NULL};
    return bf_test_run_cli(argv, NULL, err);
}

/* Writes p's material and fits it jointly with LAMBERT+GGX under ngan;
 * returns the lines of its fits.csv (loaded). */
static size_t fit_joint(const double (*p)[4])
{
    const char *dir = bf_test_tmpdir();
    char csv[512];
    char out[512];
    const char *err = NULL;
    snprintf(csv, sizeof csv, "%s/joint.csv", dir);
    snprintf(out, sizeof out, "%s/out", dir);
    write_csv(csv, p);
    cr_assert_eq(compare_joint(csv, out, "ngan", "LAMBERT+GGX", &err), 0,
                 "brdffit compare --channel joint: %s", err);
    return bf_test_csv_load(out, "fits.csv");
}

/* The row of fits.csv (loaded) with channel ch and parameter param. */
static size_t row_of(const char *ch, const char *param, size_t lines)
{
    size_t r;
    for (r = 1; r < lines; r++) {
        if (strcmp(bf_test_csv_cell(r, "channel"), ch) == 0 &&
            strcmp(bf_test_csv_cell(r, "parameter"), param) == 0) {
            return r;
        }
    }
    cr_assert_fail("no row for channel %s, %s", ch, param);
    return 0;
}

Test(joint, recovery_through_csv_and_cli, .timeout = 300)
{
    size_t lines = fit_joint(truth);
    size_t r;
    size_t c;
    /* the shape once on "joint", the two scales on each channel */
    cr_assert_eq(lines, 1 + 2 + 2 * N_CH);
    bf_assert_rel(bf_test_csv_num(row_of("joint", "alpha", lines), "value"),
                  truth[0][2], 1e-5);
    bf_assert_rel(bf_test_csv_num(row_of("joint", "F0", lines), "value"),
                  truth[0][3], 1e-5);
    for (c = 0; c < N_CH; c++) {
        bf_assert_rel(bf_test_csv_num(row_of(ch_name[c], "rho_d", lines),
                                      "value"),
                      truth[c][0], 1e-5);
        bf_assert_rel(bf_test_csv_num(row_of(ch_name[c], "rho_s", lines),
                                      "value"),
                      truth[c][1], 1e-5);
    }
    for (r = 1; r < lines; r++) {
        cr_assert_str_eq(bf_test_csv_cell(r, "model"), "LAMBERT+GGX");
        cr_assert_str_eq(bf_test_csv_cell(r, "objective"), "ngan");
        cr_assert_eq((size_t)bf_test_csv_num(r, "k"), N_CONF);
        /* the shape's 2 and every channel's 2 scales */
        cr_assert_eq((size_t)bf_test_csv_num(r, "n_params"), 2 + 2 * N_CH);
        cr_assert(bf_test_csv_num(r, "lse") < 1e-9, "E %g",
                  bf_test_csv_num(r, "lse"));
    }
}

Test(joint, fits_csv_layout, .timeout = 300)
{
    /* target-major: the first channel's row carries the shape (channel
     * "joint", in the model's parameter order), then each channel's
     * scales */
    static const char *const expect[][2] = {
        {"R", "rho_d"},     {"R", "rho_s"}, {"joint", "alpha"},
        {"joint", "F0"},    {"G", "rho_d"}, {"G", "rho_s"},
        {"B", "rho_d"},     {"B", "rho_s"}};
    size_t lines = fit_joint(truth);
    size_t r;
    cr_assert_eq(lines, 1 + sizeof expect / sizeof expect[0]);
    for (r = 1; r < lines; r++) {
        cr_assert_str_eq(bf_test_csv_cell(r, "channel"), expect[r - 1][0],
                         "line %zu", r);
        cr_assert_str_eq(bf_test_csv_cell(r, "parameter"), expect[r - 1][1],
                         "line %zu", r);
        cr_assert_str_eq(bf_test_csv_cell(r, "name"), "paint");
    }
}

Test(joint, reported_e_is_over_every_channel_value, .timeout = 300)
{
    /* channel B's lobe is wider: no shared shape fits exactly. E must be
     * sqrt(sum_c sum_k (rho_hat - rho)^2 / (K C)) at the written
     * parameters (SPEC §10 over the K C values, nothing rescaled) */
    static const double p[N_CH][4] = {{0.3, 0.8, 0.15, 0.05},
                                      {0.2, 0.6, 0.15, 0.05},
                                      {0.1, 0.4, 0.25, 0.05}};
    const bf_model_type *t = bf_model_find("LAMBERT+GGX");
    double fit[4];
    double v[N_CONF];
    double sum = 0.0;
    double e;
    size_t lines = fit_joint(p);
    size_t c;
    size_t k;
    fit[2] = bf_test_csv_num(row_of("joint", "alpha", lines), "value");
    fit[3] = bf_test_csv_num(row_of("joint", "F0", lines), "value");
    e = bf_test_csv_num(row_of("joint", "alpha", lines), "lse");
    for (c = 0; c < N_CH; c++) {
        fit[0] = bf_test_csv_num(row_of(ch_name[c], "rho_d", lines), "value");
        fit[1] = bf_test_csv_num(row_of(ch_name[c], "rho_s", lines), "value");
        cr_assert_eq(bf_test_csv_num(row_of(ch_name[c], "rho_d", lines),
                                     "lse"),
                     e, "one E for the joint fit");
        cr_assert_eq(bf_model_eval(t, fit, N_CONF, geom, v), BF_OK);
        for (k = 0; k < N_CONF; k++) {
            double ci = cos(geom[k].theta_i);
            double d = (v[k] - value[k * N_CH + c]) * ci;
            sum += d * d;
        }
    }
    cr_assert(e > 1e-4, "the channels disagree: E %g", e);
    /* the parameters are written with 10 digits */
    bf_assert_rel(e, sqrt(sum / (N_CONF * N_CH)), 1e-6);
    /* AIC on the K C values with the shape's 2 and every channel's 2
     * scales: n ln(S / n) + 2 k, S / n = E^2 */
    bf_assert_rel(bf_test_csv_num(row_of("B", "rho_s", lines), "aic"),
                  N_CONF * N_CH * log(e * e) + 2.0 * (2 + 2 * N_CH), 1e-8);
}

Test(joint, errors_where_joint_cannot_apply, .timeout = 120)
{
    static const struct {
        const char *objective;
        const char *model;
        const char *why;
    } bad[] = {
        {"cuberoot", "LAMBERT+GGX", "--objective ngan"},
        {"ngan", "ON", "no scale parameter"},
        {"ngan", "LAFORTUNE", "no scale parameter"},
    };
    const char *dir = bf_test_tmpdir();
    char csv[512];
    char out[512];
    size_t i;
    snprintf(csv, sizeof csv, "%s/joint.csv", dir);
    write_csv(csv, truth);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *err = NULL;
        snprintf(out, sizeof out, "%s/bad%zu", dir, i);
        cr_assert_neq(compare_joint(csv, out, bad[i].objective, bad[i].model,
                                    &err),
                      0, "%s", bad[i].model);
        cr_assert_not_null(err);
        cr_assert(strstr(err, bad[i].why) != NULL, "%s: %s", bad[i].model,
                  err);
        {
            char fits[600];
            snprintf(fits, sizeof fits, "%s/fits.csv", out);
            cr_assert_null(bf_test_slurp(fits, NULL), "no partial output");
        }
    }
    {
        /* the paper's protocol max-normalises the scales away */
        const char *argv[] = {"compare", "--input", csv, "--models", "ON",
                              "--channel", "joint", "--out", out, "--quiet",
                              NULL};
        const char *err = NULL;
        snprintf(out, sizeof out, "%s/bad_paper", dir);
        cr_assert_neq(bf_test_run_cli(argv, NULL, &err), 0);
        cr_assert(err != NULL && strstr(err, "--fit exact") != NULL, "%s",
                  err);
    }
}

Test(joint, report_draws_every_channel_from_the_shared_shape, .timeout = 300)
{
    /* the report's figures of a joint fit: one plane-of-incidence figure
     * per channel (its curve the shared shape with its scales), fits.csv
     * with the shape on "joint"; no profile figure (a joint fit has no
     * profile interval, and one channel's profile is not its profile: it
     * was drawn flat at 0) */
    static const char *const fig[] = {"plane_sample1_R.png",
                                      "plane_sample1_G.png",
                                      "plane_sample1_B.png"};
    const char *dir = bf_test_tmpdir();
    char csv[512];
    char out[512];
    char path[700];
    const char *err = NULL;
    size_t lines;
    size_t i;
    snprintf(csv, sizeof csv, "%s/joint.csv", dir);
    snprintf(out, sizeof out, "%s/report", dir);
    write_csv(csv, truth);
    {
        const char *argv[] = {"report",    "--input",     csv,
                              "--models",  "LAMBERT+GGX", "--channel",
                              "joint",     "--fit",       "exact",
                              "--objective", "ngan",      "--format",
                              "png",       "--out",       out,
                              "--quiet",   NULL};
        cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    }
    for (i = 0; i < sizeof fig / sizeof fig[0]; i++) {
        size_t len = 0;
        snprintf(path, sizeof path, "%s/figures/%s", out, fig[i]);
        cr_assert_not_null(bf_test_slurp(path, &len), "%s", fig[i]);
        cr_assert(len > 1000, "%s: %zu bytes", fig[i], len);
        snprintf(path, sizeof path, "%s/figures/profile_sample1_%c.png", out,
                 "RGB"[i]);
        cr_expect(!bf_test_exists(path), "%s", path);
    }
    lines = bf_test_csv_load(out, "fits.csv");
    bf_assert_rel(bf_test_csv_num(row_of("joint", "alpha", lines), "value"),
                  truth[0][2], 1e-5);
    snprintf(path, sizeof path, "%s/report.html", out);
    cr_assert(bf_test_slurp(path, NULL) != NULL &&
                  strstr(bf_test_slurp(path, NULL), "joint") != NULL,
              "the page names the joint fit");
}
