/* test_cli_inputs.c: the study on data other than CURET, through the CLI
 * (--input, --exclude-specular, --channel, info, convert; SPEC §1.5, §1.6,
 * §8): the five real Cornell .brdf files through compare, report and rank;
 * several inputs numbered in input order; the same measurements as .brdf,
 * as tidy CSV (brdffit convert) and as ASTM (written here, independently of
 * the library) give identical fits; what info counts on a file whose counts
 * are derived by hand. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_NOVALUE 61
#define EXIT_BADVALUE 63
#define EXIT_NOINPUT 66
#define EXIT_CANTCREAT 73

#define CORNELL_DIR BF_CORNELL_DIR
#define PATH_LEN 1024

static const char *const cornell[5] = {"acryl_blue", "cayman", "garnet_red",
                                       "krylon_blue", "mystique"};

/* Path of a Cornell file; fails loudly (never skips) when it is missing. */
static const char *cornell_path(const char *name)
{
    static char path[PATH_LEN];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s.brdf", CORNELL_DIR, name);
    cr_assert_eq(stat(path, &sb), 0,
                 "%s is missing: the tests need ../shared/data", path);
    return path;
}

/* ==== CSV of the outputs ================================================= */

#define MAX_FIELDS 48
#define MAX_ROWS 4096

typedef struct {
    char *text;
    char *field[MAX_ROWS][MAX_FIELDS];
    size_t n_rows; /* the header is row 0 */
    size_t n_cols;
} csv_t;

/* Splits CSV text (RFC 4180 quoting, as brdffit writes it) in place. */
static void csv_parse(csv_t *c, const char *text)
{
    char *p;
    c->text = strdup(text);
    cr_assert_not_null(c->text);
    c->n_rows = 0;
    p = c->text;
    while (*p != '\0') {
        size_t nf = 0;
        cr_assert_lt(c->n_rows, MAX_ROWS);
        for (;;) {
            char *out = p;
            cr_assert_lt(nf, MAX_FIELDS);
            c->field[c->n_rows][nf++] = p;
            if (*p == '"') { /* quoted: "" is a quote */
                p++;
                while (*p != '\0' && !(p[0] == '"' && p[1] != '"')) {
                    *out++ = *p;
                    p += (p[0] == '"') ? 2 : 1;
                }
                p += (*p == '"');
                *out = '\0'; /* the unquoted text, in place */
            } else {
                while (*p != ',' && *p != '\n' && *p != '\0') {
                    p++;
                }
            }
            if (*p == ',') {
                *p++ = '\0';
                continue;
            }
            if (*p == '\n') {
                *p++ = '\0';
            }
            break;
        }
        if (c->n_rows == 0) {
            c->n_cols = nf;
        }
        cr_assert_eq(nf, c->n_cols, "CSV row %zu has %zu fields, not %zu",
                     c->n_rows, nf, c->n_cols);
        c->n_rows++;
    }
}

static size_t csv_col(const csv_t *c, const char *name)
{
    size_t j;
    for (j = 0; j < c->n_cols; j++) {
        if (strcmp(c->field[0][j], name) == 0) {
            return j;
        }
    }
    cr_assert_fail("no column '%s'", name);
    return 0;
}

static void load_out_csv(csv_t *c, const char *dir, const char *name)
{
    char path[PATH_LEN];
    const char *text;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    text = bf_test_slurp(path, NULL);
    cr_assert_not_null(text, "%s was not written", path);
    csv_parse(c, text);
}

/* Asserts that column `name` of every data row holds a finite number. */
static void expect_finite(const csv_t *c, const char *name)
{
    size_t j = csv_col(c, name);
    size_t r;
    for (r = 1; r < c->n_rows; r++) {
        char *end = NULL;
        double x = strtod(c->field[r][j], &end);
        cr_assert(end != c->field[r][j] && *end == '\0' && isfinite(x),
                  "row %zu: %s = '%s' is not a finite number", r, name,
                  c->field[r][j]);
    }
}

/* ==== the Cornell files through every command ========================== */

/* The files the next test runs: all five, and under ASan the first two --
 * the same code at under half the cost (the five took 150 s of
 * test_cli_inputs' 267 s there). */
#define N_EVERY (BF_TEST_SANITIZED ? 2 : 5)

/* The acceptance of issue 10: every Cornell file runs through compare,
 * report and rank with --exclude-specular 15 and gives finite fits; each
 * keeps K = its configurations minus those within 15 deg of the mirror
 * direction, and is named from its description header (pbrt's comment,
 * SOURCES.md). */
Test(inputs, every_cornell_file_runs_through_compare_report_and_rank)
{
    const char *dir = bf_test_tmpdir();
    char out[PATH_LEN];
    char paths[5][PATH_LEN];
    const char *argv[32];
    const char *err = NULL;
    char last[8]; /* the last file's sample number */
    size_t a = 0;
    size_t i;
    csv_t c;

    snprintf(last, sizeof last, "%d", N_EVERY);
    argv[a++] = "compare";
    for (i = 0; i < N_EVERY; i++) {
        snprintf(paths[i], sizeof paths[i], "%s", cornell_path(cornell[i]));
        argv[a++] = "--input";
        argv[a++] = paths[i];
    }
    argv[a++] = "--exclude-specular";
    argv[a++] = "15";
    argv[a++] = "--out";
    snprintf(out, sizeof out, "%s/compare", dir);
    argv[a++] = out;
    argv[a++] = "-q";
    argv[a] = NULL;
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    load_out_csv(&c, out, "fits.csv");
    /* 5 materials x (VH-G, VH-E, FC-G, FC-E, LFTG); ON has no parameters
     * for these data and is noted, not fitted */
    cr_assert_eq(c.n_rows, 1 + N_EVERY * 5, "%zu rows", c.n_rows);
    expect_finite(&c, "value");
    expect_finite(&c, "lse");
    for (i = 1; i < c.n_rows; i++) {
        long k = strtol(c.field[i][csv_col(&c, "k")], NULL, 10);
        cr_assert(k > 1000 && k < 1439, "K = %ld", k);
        cr_assert_str_eq(c.field[i][csv_col(&c, "channel")], "mean");
    }
    cr_assert_str_eq(c.field[1][csv_col(&c, "sample")], "1");
    cr_assert_str_eq(c.field[c.n_rows - 1][csv_col(&c, "sample")], last);
    cr_assert_str_eq(c.field[6][csv_col(&c, "name")],
                     "Cayman Metallic, High-gloss Paint");
    free(c.text);

    /* report and rank: the same inputs, fewer models (the speed of rank is
     * the benchmark's business) */
    argv[0] = "report";
    snprintf(out, sizeof out, "%s/report", dir);
    argv[a - 2] = out;
    argv[a] = "--models";
    argv[a + 1] = "VH-E,FC-E,LFTG,LAMBERT";
    argv[a + 2] = "--format";
    argv[a + 3] = "png";
    argv[a + 4] = "--stats"; /* the analysis' figures too: the materials'
                                long names must fit their axes */
    argv[a + 5] = NULL;
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    {
        char fig[PATH_LEN + 32];
        snprintf(fig, sizeof fig, "%s/figures/delta_bic.png", out);
        cr_assert_not_null(bf_test_slurp(fig, NULL), "%s", fig);
        snprintf(fig, sizeof fig, "%s/figures/forest_FC-E.png", out);
        cr_assert_not_null(bf_test_slurp(fig, NULL), "%s", fig);
    }
    {
        /* Cornell measures the plane of incidence at theta_i = 10, 20, ...,
         * 80 degrees: the figures take four of the eight, spread evenly
         * (bf_geom_plane_incidences), not CURET's multiples of 11.25 */
        const char *page = bf_test_slurp(strcat(out, "/report.html"), NULL);
        cr_assert_not_null(page);
        cr_assert(strstr(page, "incidence angles 10.00\xc2\xb0, "
                               "30.00\xc2\xb0, 60.00\xc2\xb0, "
                               "80.00\xc2\xb0 (chosen from the data") !=
                  NULL);
    }
    argv[0] = "rank";
    snprintf(out, sizeof out, "%s/rank", dir);
    argv[a + 2] = NULL;
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    load_out_csv(&c, out, "ranking.csv");
    cr_assert_eq(c.n_rows, 1 + N_EVERY * 4, "%zu rows", c.n_rows);
    expect_finite(&c, "objective_value");
    expect_finite(&c, "bic");
    free(c.text);
}

/* --channel each fits every wavelength in turn, named by its wavelength. */
Test(inputs, channel_each_gives_one_set_of_rows_per_wavelength)
{
    const char *dir = bf_test_tmpdir();
    char out[PATH_LEN];
    const char *err = NULL;
    const char *argv[] = {"compare", "--input", cornell_path("garnet_red"),
                          "--exclude-specular", "20", "--channel", "each",
                          "--models", "LFTG", "--out", out, "-q", NULL};
    csv_t c;
    size_t i;
    snprintf(out, sizeof out, "%s/each", dir);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    load_out_csv(&c, out, "fits.csv");
    cr_assert_eq(c.n_rows, 1 + 31, "%zu rows", c.n_rows);
    for (i = 0; i < 31; i++) { /* 400, 410, ..., 700 nm (SOURCES.md) */
        char nm[16];
        snprintf(nm, sizeof nm, "%zu", 400 + 10 * i);
        cr_assert_str_eq(c.field[1 + i][csv_col(&c, "channel")], nm);
    }
    expect_finite(&c, "value");
    free(c.text);
}

Test(inputs, a_channel_the_data_lack_and_paper_samples_are_usage_errors)
{
    const char *err = NULL;
    const char *argv1[] = {"compare", "--input", cornell_path("cayman"),
                           "--channel", "R", "--out", bf_test_tmpdir(),
                           NULL};
    const char *argv2[] = {"compare", "--input", cornell_path("cayman"),
                           "--samples", "paper", "--out", bf_test_tmpdir(),
                           NULL};
    cr_assert_eq(bf_test_run_cli(argv1, NULL, &err), EXIT_BADVALUE, "%s",
                 err);
    cr_assert(strstr(err, "has no channel 'R'") != NULL, "%s", err);
    cr_assert_eq(bf_test_run_cli(argv2, NULL, &err), EXIT_BADVALUE, "%s",
                 err);
    cr_assert(strstr(err, "CURET samples") != NULL, "%s", err);
}

/* ==== the same measurements in three formats ============================ */

/* Reads a pbrt-v2 .brdf file as SPEC §8 describes it -- '#' comment
 * lines, then a stream of numbers: W, W wavelengths, records of four
 * angles and W values -- with the C library alone (strtod), and writes it
 * as ASTM E1392 (SPEC §8: KEY value lines, NUM_POINTS, VARS, then comma
 * rows, radians) with %.17g, so every number reads back exactly. */
static void write_astm_from_pbrt(const char *brdf, const char *astm,
                                 const char *name)
{
    FILE *in = fopen(brdf, "r");
    FILE *out = fopen(astm, "w");
    static double num[60000];
    size_t n = 0;
    size_t w;
    size_t rec;
    size_t r;
    size_t j;
    char line[8192];
    cr_assert_not_null(in);
    cr_assert_not_null(out);
    while (fgets(line, sizeof line, in) != NULL) {
        char *p = line;
        char *end;
        if (line[0] == '#') {
            continue;
        }
        for (;;) {
            double x = strtod(p, &end);
            if (end == p) {
                break;
            }
            cr_assert_lt(n, sizeof num / sizeof *num);
            num[n++] = x;
            p = end;
        }
    }
    fclose(in);
    w = (size_t)num[0];
    cr_assert_eq((n - 1 - w) % (4 + w), 0u, "SPEC §8's count rule");
    rec = (n - 1 - w) / (4 + w);
    fprintf(out, "SOURCE test_cli_inputs.c\nSAMPLE_NAME \"%s\"\n"
                 "NUM_POINTS %zu\nVARS theta_i,phi_i,theta_s,phi_s",
            name, rec);
    for (j = 0; j < w; j++) {
        fprintf(out, ",%.17g", num[1 + j]);
    }
    fputc('\n', out);
    for (r = 0; r < rec; r++) {
        const double *x = num + 1 + w + r * (4 + w);
        for (j = 0; j < 4 + w; j++) {
            fprintf(out, "%s%.17g", j == 0 ? "" : ",", x[j]);
        }
        fputc('\n', out);
    }
    cr_assert_eq(fclose(out), 0);
}

Test(inputs, cornell_as_brdf_csv_and_astm_gives_identical_fits)
{
    const char *dir = bf_test_tmpdir();
    char csv[PATH_LEN];
    char astm[PATH_LEN];
    char out[3][PATH_LEN];
    char text[3][1 << 14];
    char brdf[PATH_LEN];
    const char *src[3];
    const char *err = NULL;
    const char *conv[] = {"convert", cornell_path("cayman"), "--to", "csv",
                          csv, NULL};
    size_t f;

    snprintf(csv, sizeof csv, "%s/cayman.csv", dir);
    snprintf(astm, sizeof astm, "%s/cayman.astm", dir);
    cr_assert_eq(bf_test_run_cli(conv, NULL, &err), 0, "%s", err);
    write_astm_from_pbrt(cornell_path("cayman"), astm,
                         "Cayman Metallic, High-gloss Paint");
    snprintf(brdf, sizeof brdf, "%s", cornell_path("cayman"));
    src[0] = brdf;
    src[1] = csv;
    src[2] = astm;
    for (f = 0; f < 3; f++) {
        const char *argv[] = {"compare", "--input", src[f],
                              "--exclude-specular", "15", "--models",
                              "VH-E,FC-E,LFTG,LAMBERT", "--stats",
                              "--folds", "0", "--out", out[f], "-q", NULL};
        const char *t;
        snprintf(out[f], sizeof out[f], "%s/out%zu", dir, f);
        cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s: %s", src[f],
                     err);
        {
            char path[PATH_LEN + 16];
            snprintf(path, sizeof path, "%s/fits.csv", out[f]);
            t = bf_test_slurp(path, NULL);
            cr_assert_not_null(t);
            cr_assert_lt(strlen(t), sizeof text[f]);
            strcpy(text[f], t);
        }
    }
    /* byte for byte: the same configurations, values, name and channels */
    cr_assert_str_eq(text[1], text[0], "CSV vs .brdf");
    cr_assert_str_eq(text[2], text[0], "ASTM vs .brdf");
}

/* ==== several inputs and info =========================================== */

/* A tidy CSV (README "Tidy CSV") with three configurations whose angles to
 * the mirror direction are known by hand (SPEC §1.6): the first is the
 * mirror direction itself (phi_o = phi_i + 180), the second lies 3 deg
 * from it in the plane of incidence (theta_o 33 instead of 30), the third
 * is backscatter, 2 x 30 = 60 deg away. One value is negative, one empty
 * (invalid). */
static const char hand_csv[] =
    "# three configurations, two materials\n"
    "material,theta_i,phi_i,theta_o,phi_o,R,G\n"
    "flat,30,20,30,200,0.5,0.4\n"
    "flat,30,20,33,200,0.3,-0.01\n"
    "flat,30,20,30,20,0.2,\n"
    "bumpy,30,20,30,200,0.6,0.5\n"
    "bumpy,30,20,33,200,0.5,0.4\n"
    "bumpy,30,20,30,20,0.4,0.3\n";

static void write_text(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    fputs(text, fp);
    cr_assert_eq(fclose(fp), 0);
}

Test(inputs, info_counts_configurations_near_the_mirror_and_bad_values)
{
    char path[PATH_LEN];
    const char *out = NULL;
    const char *err = NULL;
    const char *argv[] = {"info", path, NULL};
    snprintf(path, sizeof path, "%s/hand.csv", bf_test_tmpdir());
    write_text(path, hand_csv);
    cr_assert_eq(bf_test_run_cli(argv, &out, &err), 0, "%s", err);
    cr_assert(strstr(out, "csv, 2 materials") != NULL, "%s", out);
    cr_assert(strstr(out, "Configurations: 3 (shared by 2 materials)") !=
                  NULL,
              "%s", out);
    cr_assert(strstr(out, "within 1 deg: 1, within 5 deg: 2, within 10 deg: "
                          "2, within 15 deg: 2, within 25 deg: 2") != NULL,
              "%s", out);
    cr_assert(strstr(out, "theta_o 30.00 to 33.00 deg") != NULL, "%s", out);
    /* flat: 1 negative, 1 invalid; bumpy: none */
    cr_assert(strstr(out, "2 (R ... G)") != NULL, "%s", out);
    cr_assert(strstr(out, "|        1 |    0 | 1 (in 1 configurations) |") !=
                  NULL,
              "%s", out);
}

/* Two files: the CSV's two materials are 1 and 2, the Cornell file 3; the
 * specular cone of 2 deg leaves 1 of the CSV's 3 configurations out, and
 * the mean over R, G leaves out the one with an invalid G. */
Test(inputs, several_inputs_are_numbered_in_input_order)
{
    char path[PATH_LEN];
    char out[PATH_LEN];
    const char *err = NULL;
    const char *argv[] = {"compare", "--input", path, "--input",
                          cornell_path("mystique"), "--exclude-specular",
                          "2", "--models", "LAMBERT", "--out", out, "-q",
                          NULL};
    csv_t c;
    snprintf(path, sizeof path, "%s/hand.csv", bf_test_tmpdir());
    snprintf(out, sizeof out, "%s/out", bf_test_tmpdir());
    write_text(path, hand_csv);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
    load_out_csv(&c, out, "fits.csv");
    cr_assert_eq(c.n_rows, 4u);
    cr_assert_str_eq(c.field[1][csv_col(&c, "name")], "flat");
    cr_assert_str_eq(c.field[1][csv_col(&c, "k")], "1");
    cr_assert_str_eq(c.field[2][csv_col(&c, "name")], "bumpy");
    cr_assert_str_eq(c.field[2][csv_col(&c, "k")], "2");
    cr_assert_str_eq(c.field[3][csv_col(&c, "sample")], "3");
    cr_assert_str_eq(c.field[3][csv_col(&c, "name")],
                     "Ford Mystic lacquer (BASF, 2-2-95)");
    free(c.text);
}

/* Files after the options are inputs too, after any --input, in order;
 * a missing one is named. */
Test(inputs, files_after_the_options_are_inputs_in_order)
{
    char path[PATH_LEN];
    char out[2][PATH_LEN];
    char gone[PATH_LEN];
    char *text[2];
    const char *err = NULL;
    const char *flag[] = {"compare", "--input", path, "--input",
                          cornell_path("mystique"), "--models", "LAMBERT",
                          "--out", out[0], "-q", NULL};
    const char *pos[] = {"compare", "--models", "LAMBERT", "--input", path,
                         "--out", out[1], "-q", cornell_path("mystique"),
                         NULL};
    const char *missing[] = {"compare", "--models", "LAMBERT", "-q", gone,
                             NULL};
    size_t f;
    snprintf(path, sizeof path, "%s/hand.csv", bf_test_tmpdir());
    snprintf(gone, sizeof gone, "%s/no-such-file.brdf", bf_test_tmpdir());
    write_text(path, hand_csv);
    for (f = 0; f < 2; f++) {
        char fits[PATH_LEN + 16];
        const char *t;
        snprintf(out[f], sizeof out[f], "%.900s/out%zu", bf_test_tmpdir(), f);
        cr_assert_eq(bf_test_run_cli(f == 0 ? flag : pos, NULL, &err), 0,
                     "%s", err);
        snprintf(fits, sizeof fits, "%.900s/fits.csv", out[f]);
        t = bf_test_slurp(fits, NULL);
        cr_assert_not_null(t);
        text[f] = strdup(t);
        cr_assert_not_null(text[f]);
    }
    cr_assert_str_eq(text[1], text[0]);
    cr_assert(strstr(text[0], "\n3,\"Ford Mystic lacquer") != NULL);
    free(text[0]);
    free(text[1]);
    cr_assert_eq(bf_test_run_cli(missing, NULL, &err), EXIT_NOINPUT, "%s",
                 err);
    cr_assert(strstr(err, "no-such-file.brdf") != NULL, "%s", err);
}

Test(inputs, convert_reports_missing_input_and_output_folders)
{
    const char *err = NULL;
    char bad_out[PATH_LEN];
    const char *missing[] = {"convert", "/nonexistent-brdffit/a.brdf", "--to",
                             "csv", "x.csv", NULL};
    const char *no_dir[] = {"convert", cornell_path("cayman"), "--to", "csv",
                            bad_out, NULL};
    const char *no_to[] = {"convert", cornell_path("cayman"), "x.csv", NULL};
    snprintf(bad_out, sizeof bad_out, "%s/no/such/dir/x.csv",
             bf_test_tmpdir());
    cr_assert_eq(bf_test_run_cli(missing, NULL, &err), EXIT_NOINPUT, "%s",
                 err);
    cr_assert(strstr(err, "/nonexistent-brdffit/a.brdf") != NULL, "%s", err);
    cr_assert_eq(bf_test_run_cli(no_dir, NULL, &err), EXIT_CANTCREAT, "%s",
                 err);
    cr_assert_eq(bf_test_run_cli(no_to, NULL, &err), EXIT_NOVALUE, "%s",
                 err);
}
