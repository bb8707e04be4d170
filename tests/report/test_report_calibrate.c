/* test_report_calibrate.c: `brdffit report --calibrate N` (doc/methods.md
 * §3) on synthetic materials whose answer is known -- VH-E at m = 0.3 and
 * FC-E at m = 0.6, n = 1.5 under 5% relative noise: the intervals of the
 * default noise model cover the value simulated within the binomial band
 * (computed here) and are as wide as the estimates spread;
 * calibrate.csv is `brdffit calibrate`'s, byte for byte, and the same for
 * 1 and 2 threads; the page's table holds calibrate.csv's numbers; the
 * figure exists, fits a page and is on the page, and a sample with more
 * panels than a page holds gets several; and the bad values of
 * --calibrate are refused before any work. (The verdicts low and high:
 * tests/fit/test_calibration_summary.c.) */
#include <criterion/criterion.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "formats.h"
#include "plot.h"
#include "support.h"

#define DEG (M_PI / 180.0)
#define EXIT_CONFLICT 62
#define EXIT_BADVALUE 63
/* The configurations: theta_i x theta_o x phi_o. */
#define NTI 5
#define NTO 6
#define NPHI 4
#define K (NTI * NTO * NPHI)
/* Simulations of the coverage check: its band at 200 is about [0.91,
 * 0.985]. */
#define N_SIM 200

static const double vh_truth[1] = {0.3};
static const double fc_truth[2] = {0.6, 1.5};

/* Writes VH-E (material 1) and FC-E (material 2) with 5% relative noise
 * to dir/synth.csv; returns its path (static). */
static const char *write_materials(const char *dir)
{
    static char path[512];
    static double at[4 * K];
    bf_test_material mat[2];
    size_t n = 0;
    int a;
    int b;
    int c;
    for (a = 0; a < NTI; a++) {
        for (b = 0; b < NTO; b++) {
            for (c = 0; c < NPHI; c++) {
                at[4 * n + 0] = (10.0 + 15.0 * a) * DEG;
                at[4 * n + 1] = 0.0;
                at[4 * n + 2] = (5.0 + 15.0 * b) * DEG;
                at[4 * n + 3] = (45.0 + 90.0 * c) * DEG;
                n++;
            }
        }
    }
    mat[0].name = "vh";
    mat[0].type = bf_model_find("VH-E");
    mat[0].param = vh_truth;
    mat[1].name = "fc";
    mat[1].type = bf_model_find("FC-E");
    mat[1].param = fc_truth;
    cr_assert(mat[0].type != NULL && mat[1].type != NULL);
    snprintf(path, sizeof path, "%s/synth.csv", dir);
    bf_test_write_noisy_csv(path, K, at, 2, mat, 0.05, 11);
    return path;
}

/* Runs cmd ("report" or "calibrate") on input with the given extra
 * arguments into out; returns the exit status, stderr in *err. */
static int run(const char *cmd, const char *input, const char *out,
               const char *const *extra, const char **err)
{
    const char *argv[40] = {cmd, "--input", input, "--fit", "exact",
                            "--folds", "0", "--out", out, "-q"};
    size_t n = 10;
    for (; extra != NULL && *extra != NULL; extra++) {
        argv[n++] = *extra;
    }
    argv[n] = NULL;
    return bf_test_run_cli(argv, NULL, err);
}

static void same_file(const char *a, const char *b)
{
    size_t la;
    size_t lb;
    char *x = bf_test_copy(a, &la);
    char *y = bf_test_copy(b, &lb);
    cr_expect(la == lb && memcmp(x, y, la) == 0, "%s and %s differ", a, b);
    free(x);
    free(y);
}

/* The counts x of N simulations whose tails under Binomial(N, 0.95) are
 * both at least 0.005, as shares: computed here from GSL's binomial
 * distribution, not by the program. */
static void band(size_t N, double *lo, double *hi)
{
    size_t x;
    *lo = *hi = NAN;
    for (x = 0; x <= N; x++) {
        double below = gsl_cdf_binomial_P((unsigned)x, 0.95, (unsigned)N);
        double above = x == 0 ? 1.0
                              : gsl_cdf_binomial_Q((unsigned)x - 1, 0.95,
                                                   (unsigned)N);
        if (below >= 0.005 && above >= 0.005) {
            *lo = isnan(*lo) ? (double)x / (double)N : *lo;
            *hi = (double)x / (double)N;
        }
    }
}

/* The cells of the page's calibration table, row by row (at most 16 rows
 * of 13 cells), tags stripped; returns the number of rows. */
static size_t table_cells(const char *page, char cells[16][13][64])
{
    const char *t = strstr(page, "<table id=\"calibration\">");
    const char *end = t != NULL ? strstr(t, "</table>") : NULL;
    const char *row;
    size_t n = 0;
    cr_assert(t != NULL && end != NULL, "no calibration table on the page");
    row = strstr(t, "<tbody>");
    while ((row = strstr(row, "<tr>")) != NULL && row < end && n < 16) {
        const char *p = row;
        size_t c;
        for (c = 0; c < 13; c++) {
            const char *q;
            size_t len;
            p = strstr(p, "<td");
            cr_assert(p != NULL && p < end);
            p = strchr(p, '>') + 1;
            q = strstr(p, "</td>");
            len = (size_t)(q - p) < 63 ? (size_t)(q - p) : 63;
            memcpy(cells[n][c], p, len);
            cells[n][c][len] = '\0';
            p = q;
        }
        n++;
        row = p;
    }
    return n;
}

/* Asserts that the PNG at path fits a page (BF_PLOT_MAX_TALL). */
static void fits_a_page(const char *path)
{
    size_t len;
    unsigned char *png = (unsigned char *)bf_test_copy(path, &len);
    unsigned long w;
    unsigned long h;
    cr_assert_gt(len, 24u);
    w = fmt_be32(png + 16);
    h = fmt_be32(png + 20);
    cr_expect(w > 0 && (double)h <= BF_PLOT_MAX_TALL * (double)w + 1.0,
              "%s: %lu x %lu pixels", path, w, h);
    free(png);
}

Test(report_calibrate, covers_a_known_material_as_calibrate_says,
     .timeout = 300)
{
    static const char *const rep[] = {"--models", "VH-E", "--samples", "1",
                                      "--format", "png", "--seed", "7",
                                      "--calibrate", "200", NULL};
    static const char *const cal[] = {"--models", "VH-E", "--samples", "1",
                                      "--seed", "7", "--sims", "200", NULL};
    char *a = strdup(bf_test_tmpdir());
    char *b = strdup(bf_test_tmpdir());
    const char *input = write_materials(a);
    const char *err = NULL;
    char cells[16][13][64];
    char want[64];
    char ml[64];
    char *page;
    size_t len;
    double lo;
    double hi;
    double cov;
    size_t r;

    cr_assert_eq(run("report", input, bf_test_join(a, "rep"), rep, &err), 0,
                 "%s", err);
    cr_assert_eq(run("calibrate", input, b, cal, &err), 0, "%s", err);
    /* the same numbers from the same data, models, seed and options */
    same_file(bf_test_join(a, "rep/calibrate.csv"),
              bf_test_join(b, "calibrate.csv"));

    cr_assert_eq(bf_test_csv_load(bf_test_join(a, "rep"), "calibrate.csv"),
                 2u);
    r = bf_test_csv_find("1", "VH-E", "m");
    cr_expect_geq(bf_test_csv_num(r, "n_sim"), N_SIM - 4.0);
    cov = bf_test_csv_num(r, "coverage");
    band((size_t)bf_test_csv_num(r, "n_sim"), &lo, &hi);
    cr_expect(cov >= lo && cov <= hi, "coverage %g outside [%g, %g]", cov,
              lo, hi);
    /* the value simulated is the fit's: fits.csv's exact optimum; the
     * page's ML estimate, the one the interval is about, its ml_value */
    strcpy(want, bf_test_csv_cell(r, "value"));
    bf_test_csv_load(bf_test_join(a, "rep"), "fits.csv");
    cr_expect_str_eq(bf_test_csv_cell(bf_test_csv_find("1", "VH-E", "m"),
                                      "value"),
                     want);
    snprintf(ml, sizeof ml, "%.4g",
             bf_test_csv_num(bf_test_csv_find("1", "VH-E", "m"), "ml_value"));
    bf_test_csv_load(bf_test_join(a, "rep"), "calibrate.csv");

    /* the page's table: calibrate.csv's numbers, the band and verdict */
    page = bf_test_copy(bf_test_join(a, "rep/report.html"), &len);
    cr_assert_eq(table_cells(page, cells), 1u);
    cr_expect_str_eq(cells[0][0], "1");
    cr_expect_str_eq(cells[0][1], "VH-E");
    cr_expect_str_eq(cells[0][2], "m");
    snprintf(want, sizeof want, "%.4g", bf_test_csv_num(r, "value"));
    cr_expect_str_eq(cells[0][3], want);
    cr_expect_str_eq(cells[0][4], ml);
    snprintf(want, sizeof want, "%.0f", bf_test_csv_num(r, "n_sim"));
    cr_expect_str_eq(cells[0][6], want);
    snprintf(want, sizeof want, "%.3f \xc2\xb1 %.3f", cov,
             sqrt(0.95 * 0.05 / bf_test_csv_num(r, "n_sim")));
    cr_expect_str_eq(cells[0][7], want);
    snprintf(want, sizeof want, "[%.3f, %.3f]", lo, hi);
    cr_expect_str_eq(cells[0][8], want);
    cr_expect_str_eq(cells[0][9], "ok");
    snprintf(want, sizeof want, "%+.2f",
             bf_test_csv_num(r, "ml_bias") / bf_test_csv_num(r, "ml_sd"));
    cr_expect_str_eq(cells[0][10], want);
    snprintf(want, sizeof want, "%.2f",
             bf_test_csv_num(r, "width") /
                 (2.0 * 1.959963984540054 * bf_test_csv_num(r, "ml_sd")));
    cr_expect_str_eq(cells[0][11], want);
    /* issue 18: the median width within 1.3x of the spread */
    cr_expect(strtod(want, NULL) > 1.0 / 1.3 && strtod(want, NULL) < 1.3,
              "width/spread %s", want);

    /* the figure: on the page, a PNG that fits a page */
    cr_expect_not_null(strstr(page, "<img src=\"figures/calibration_sample1"
                                    ".png\""));
    cr_expect_not_null(strstr(page, "<a href=\"calibrate.csv\">"));
    fits_a_page(bf_test_join(a, "rep/figures/calibration_sample1.png"));
    free(page);
    free(a);
    free(b);
}

Test(report_calibrate, the_same_for_one_and_two_threads, .timeout = 300)
{
    static const char *const one[] = {"--models", "VH-E", "--format", "png",
                                      "--calibrate", "20", "--threads", "1",
                                      NULL};
    static const char *const two[] = {"--models", "VH-E", "--format", "png",
                                      "--calibrate", "20", "--threads", "2",
                                      NULL};
    const char *dir = bf_test_tmpdir();
    const char *input = write_materials(dir);
    const char *err = NULL;
    cr_assert_eq(run("report", input, bf_test_join(dir, "one"), one, &err),
                 0, "%s", err);
    cr_assert_eq(run("report", input, bf_test_join(dir, "two"), two, &err),
                 0, "%s", err);
    cr_assert_eq(bf_test_csv_load(bf_test_join(dir, "one"), "calibrate.csv"),
                 3u, "both materials' VH-E m");
    same_file(bf_test_join(dir, "one/calibrate.csv"),
              bf_test_join(dir, "two/calibrate.csv"));
    same_file(bf_test_join(dir, "one/figures/calibration_sample2.png"),
              bf_test_join(dir, "two/figures/calibration_sample2.png"));
}

Test(report_calibrate, many_panels_are_split_into_figures_that_fit_a_page)
{
    /* six panels (--fit exact frees FC's n: FC-G and FC-E m, n, VH-E m,
     * LFTG n_d) at the single column width: more than one figure holds */
    static const char *const rep[] = {"--models", "FC-G,FC-E,VH-E,LFTG",
                                      "--samples", "2", "--size", "single",
                                      "--format", "png", "--calibrate",
                                      "10", NULL};
    const char *dir = bf_test_tmpdir();
    const char *input = write_materials(dir);
    const char *err = NULL;
    char *page;
    size_t len;
    cr_assert_eq(run("report", input, bf_test_join(dir, "rep"), rep, &err),
                 0, "%s", err);
    page = bf_test_copy(bf_test_join(dir, "rep/report.html"), &len);
    fits_a_page(bf_test_join(dir, "rep/figures/calibration_sample2.png"));
    fits_a_page(bf_test_join(dir, "rep/figures/calibration_sample2_2.png"));
    cr_expect_not_null(strstr(page, "figures/calibration_sample2.png"));
    cr_expect_not_null(strstr(page, "figures/calibration_sample2_2.png"));
    cr_expect_not_null(strstr(page, "(part 2 of "));
    free(page);
}

Test(report_calibrate, bad_values_are_refused_before_any_work)
{
    static const char *const five[] = {"--calibrate", "5", NULL};
    static const char *const word[] = {"--calibrate", "abc", NULL};
    static const char *const joint[] = {"--calibrate", "10", "--channel",
                                        "joint", "--objective", "ngan",
                                        NULL};
    const char *dir = bf_test_tmpdir();
    const char *input = write_materials(dir);
    const char *err = NULL;
    cr_assert_eq(run("report", input, bf_test_join(dir, "a"), five, &err),
                 EXIT_BADVALUE);
    cr_expect_not_null(strstr(err, "--calibrate: 5 simulations: at least "
                                   "10 are needed"),
                       "%s", err);
    cr_assert_eq(run("report", input, bf_test_join(dir, "b"), word, &err),
                 EXIT_BADVALUE);
    cr_expect_not_null(strstr(err, "--calibrate: 'abc' is not a number"),
                       "%s", err);
    cr_assert_eq(run("report", input, bf_test_join(dir, "c"), joint, &err),
                 EXIT_CONFLICT);
    cr_expect_not_null(strstr(err, "--channel joint"), "%s", err);
    cr_expect(!bf_test_exists(bf_test_join(dir, "a")) &&
                  !bf_test_exists(bf_test_join(dir, "b")) &&
                  !bf_test_exists(bf_test_join(dir, "c")),
              "no output");
}
