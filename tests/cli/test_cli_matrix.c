/* test_cli_matrix.c: every combination a user may ask for works -- the
 * commands report, compare and rank x one, two and all samples x the
 * default models, --models all and one model x without and with --stats
 * x CURET, one Cornell file, the five Cornell files, a tidy CSV (three
 * CURET materials through brdffit convert) and a MERL table (written here
 * from an analytic model: no MERL file exists here). Each run exits 0;
 * fits.csv (ranking.csv for rank) has a header and rows of its width;
 * every file report.html references (img src, href) exists; every figure
 * is at most BF_PLOT_MAX_TALL times as tall as wide (read from the PNGs).
 * Glossy reports (--fit exact --objective ngan on Cornell files: --models
 * all, --channel each on the five files, --channel joint, --size single)
 * pass the same checks and write their figures per model family and in
 * pages (glossy_case).
 *
 * Cost: figures in PNG only, two threads, the 61 CURET samples' analyses
 * without the Neyman construction (cost_of_the_construction). Data with one sample have no
 * "two samples" case and their "all" is their "one"; rank always runs the
 * analysis, so rank --stats is rank and is not run twice. Left out
 * (costly(), repeated()):
 *  - report --stats --models all but on one CURET sample (the profile
 *    figures trace the objective along every parameter of every model,
 *    WNO-R's quadrature included: ~20 s of CPU a sample);
 *  - the analysis (--stats, rank) of --models all on more than one sample
 *    of data other than CURET (WNO-R's refinement on 1379 configurations
 *    a sample);
 *  - on the five Cornell files, two samples (CURET and the CSV have them)
 *    and report --stats but with one model;
 *  - report --stats on all 61 CURET samples (61 profile figures) and
 *    report on all 61 but with --models all (make report-all's figures,
 *    over a hundred of them).
 * Under ASan only a diagonal of each data set's combinations runs
 * (diagonal()). */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "report/plot.h"
#include "support.h"

#define PATH_LEN 1024

/* The data sets. */
typedef enum { CURET, CORNELL1, CORNELL5, CSV, MERL, NDATA } data_t;
static const char *const data_name[NDATA] = {"CURET", "one Cornell file",
                                             "five Cornell files",
                                             "tidy CSV", "MERL table"};

enum { REPORT, COMPARE, RANK, NCMD };
static const char *const cmd_name[NCMD] = {"report", "compare", "rank"};

enum { ONE, TWO, ALL, NSAMPLES };
static const char *const samples_arg[NSAMPLES] = {"1", "1,2", "all"};

enum { DEFAULT_MODELS, ALL_MODELS, ONE_MODEL, NMODELS };
static const char *const models_arg[NMODELS] = {NULL, "all", "FC-E"};

/* ==== inputs ============================================================= */

/* A MERL table (SPEC §8) from an analytic model: a Lambertian floor and a
 * Gaussian lobe in the half angle, f = 0.05 + 0.4 exp(-(theta_h/0.25)^2),
 * theta_h = (i / 90)^2 pi/2 at index i (the table's square-root spacing);
 * every channel holds f / scale_c. Returns its path. */
static const char *write_merl(const char *dir)
{
    static const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0,
                                    1.66 / 1500.0};
    static const unsigned char dims[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    static char path[PATH_LEN];
    size_t per_i = 90u * 180u;
    unsigned char *b = malloc(8 * per_i);
    FILE *fp;
    size_t c;
    size_t i;
    size_t n;
    cr_assert_not_null(b);
    snprintf(path, sizeof path, "%s/lobe.binary", dir);
    fp = fopen(path, "wb");
    cr_assert_not_null(fp, "%s", path);
    cr_assert_eq(fwrite(dims, 1, sizeof dims, fp), sizeof dims);
    for (c = 0; c < 3; c++) {
        for (i = 0; i < 90; i++) {
            double th = (double)i / 90.0 * (double)i / 90.0 * M_PI / 2;
            double f = 0.05 + 0.4 * exp(-(th / 0.25) * (th / 0.25));
            double raw = f / scale[c];
            uint64_t u;
            size_t k;
            memcpy(&u, &raw, 8);
            for (n = 0; n < per_i; n++) { /* little-endian doubles */
                for (k = 0; k < 8; k++) {
                    b[8 * n + k] = (unsigned char)(u >> (8 * k));
                }
            }
            cr_assert_eq(fwrite(b, 8, per_i, fp), per_i);
        }
    }
    cr_assert_eq(fclose(fp), 0);
    free(b);
    return path;
}

/* A tidy CSV of the first three CURET materials (brdffit convert, then the
 * header and the rows of three material names). Returns its path. */
static const char *write_csv(const char *dir)
{
    static char path[PATH_LEN];
    char cmd[4 * PATH_LEN];
    const char *out;
    snprintf(path, sizeof path, "%s/three.csv", dir);
    snprintf(cmd, sizeof cmd,
             "'%s' convert '%s' --to csv - | awk -F, 'NR == 1 { print; "
             "next } !($1 in seen) { seen[$1] = 1; n++ } n <= 3' > '%s'",
             BF_CLI_PATH, bf_test_curet_path(""), path);
    cr_assert_eq(bf_test_run_sh(cmd, &out), 0, "%s", out);
    return path;
}

/* ==== checks ============================================================= */

/* Every record of dir/name has as many comma-separated fields as the
 * header (RFC 4180: a quoted field may hold commas, "" is a quote), and
 * there is at least one row. */
static void check_csv(const char *dir, const char *name, const char *what)
{
    char path[PATH_LEN];
    size_t len;
    const char *t;
    size_t fields = 0;
    size_t lines = 0;
    size_t here = 1;
    int quoted = 0;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    t = bf_test_slurp(path, &len);
    cr_assert_not_null(t, "%s: no %s", what, name);
    cr_assert(len > 0 && t[len - 1] == '\n', "%s: %s does not end a line",
              what, name);
    for (; *t != '\0'; t++) {
        if (*t == '"') {
            quoted = !quoted; /* "" toggles twice */
        } else if (quoted) {
            continue;
        } else if (*t == ',') {
            here++;
        } else if (*t == '\n') {
            if (lines == 0) {
                fields = here;
            }
            cr_assert_eq(here, fields, "%s: %s line %zu has %zu fields, "
                         "the header %zu", what, name, lines + 1, here,
                         fields);
            lines++;
            here = 1;
        }
    }
    cr_assert(!quoted, "%s: %s ends inside a quoted field", what, name);
    cr_assert_geq(lines, 2, "%s: %s has no row", what, name);
}

/* Every src="..." and href="..." of dir/report.html that is not an
 * anchor or a web address names a file that exists. */
static void check_page(const char *dir, const char *what)
{
    static const char *const attr[2] = {"src=\"", "href=\""};
    char path[PATH_LEN];
    size_t len;
    const char *page;
    char *copy;
    size_t a;
    size_t refs = 0;
    snprintf(path, sizeof path, "%s/report.html", dir);
    page = bf_test_slurp(path, &len);
    cr_assert_not_null(page, "%s: no report.html", what);
    copy = strdup(page);
    cr_assert_not_null(copy);
    for (a = 0; a < 2; a++) {
        const char *p = copy;
        while ((p = strstr(p, attr[a])) != NULL) {
            const char *v = p + strlen(attr[a]);
            size_t n = strcspn(v, "\"#?");
            char file[PATH_LEN];
            struct stat sb;
            p = v;
            if (v[0] == '#' || strncmp(v, "http", 4) == 0 ||
                strncmp(v, "mailto:", 7) == 0 || strncmp(v, "data:", 5) == 0) {
                continue;
            }
            cr_assert_lt(n, 512);
            snprintf(file, sizeof file, "%s/%.*s", dir, (int)n, v);
            cr_expect_eq(stat(file, &sb), 0, "%s: report.html names %.*s, "
                         "which is missing", what, (int)n, v);
            refs++;
        }
    }
    free(copy);
    cr_assert_gt(refs, 0, "%s: report.html references no file", what);
}

/* Every PNG of dir/figures is at most BF_PLOT_MAX_TALL times as tall as
 * wide (pixel sizes from the IHDR chunk); returns how many there are. */
static size_t check_figures(const char *dir, const char *what)
{
    char path[PATH_LEN];
    DIR *d;
    struct dirent *e;
    size_t n = 0;
    snprintf(path, sizeof path, "%s/figures", dir);
    d = opendir(path);
    cr_assert_not_null(d, "%s: no figures folder", what);
    while ((e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        unsigned char h[24];
        FILE *fp;
        unsigned long w;
        unsigned long ht;
        if (l < 4 || strcmp(e->d_name + l - 4, ".png") != 0) {
            continue;
        }
        snprintf(path, sizeof path, "%s/figures/%s", dir, e->d_name);
        fp = fopen(path, "rb");
        cr_assert_not_null(fp, "%s", path);
        cr_assert_eq(fread(h, 1, sizeof h, fp), sizeof h, "%s", path);
        fclose(fp);
        w = (unsigned long)h[16] << 24 | (unsigned long)h[17] << 16 |
            (unsigned long)h[18] << 8 | h[19];
        ht = (unsigned long)h[20] << 24 | (unsigned long)h[21] << 16 |
             (unsigned long)h[22] << 8 | h[23];
        /* one pixel of rounding from points */
        cr_expect_leq((double)ht, BF_PLOT_MAX_TALL * (double)w + 1.0,
                      "%s: %s is %lu x %lu pixels, taller than a page", what,
                      e->d_name, w, ht);
        n++;
    }
    closedir(d);
    cr_assert_gt(n, 0, "%s: no figure", what);
    return n;
}

/* ==== the matrix ========================================================= */

/* The combinations left out for their cost (see the top of the file). */
static int costly(data_t data, int cmd, int smp, int models, int stats)
{
    int analysis = stats || cmd == RANK;
    if (cmd == RANK && stats) {
        return 1; /* rank always analyses: the same run as without */
    }
    if (analysis && models == ALL_MODELS && smp != ONE && data != CURET) {
        return 1; /* every model analysed on 1379 configurations */
    }
    if (data == CORNELL5 && (smp == TWO || (cmd == REPORT && stats &&
                                            models != ONE_MODEL))) {
        return 1; /* five times 1379 configurations */
    }
    if (cmd != REPORT || !stats) {
        return 0;
    }
    return (models == ALL_MODELS && (data != CURET || smp != ONE)) ||
           (data == CURET && smp == ALL);
}

/* Left out as well: report on all 61 CURET samples but with --models all
 * (make report-all; each draws over a hundred figures, and the default
 * and one-model grids of 61 samples are those of the paper's runs). */
static int repeated(data_t data, int cmd, int smp, int models)
{
    return data == CURET && cmd == REPORT && smp == ALL &&
           models != ALL_MODELS;
}

/* Under ASan: a diagonal of each command's combinations -- every sample
 * set once, each with another model set (a Latin square over the
 * commands: all samples with all models in compare, the cheapest), --stats
 * on every other one; no report on all 61 CURET samples (over a hundred
 * figures; the plain build draws them), no rank of all 61 CURET samples
 * (60 s under ASan; the plain build and CI's `make rank` run it, and
 * rank's code runs here on one sample with every model), and rank on one
 * sample only of the 1379-configuration data, once: rank --samples 1 of
 * the five files is the one file's run again (24 s under ASan), so only
 * one_cornell_file runs it. */
static int diagonal(data_t data, int cmd, int smp, int models, int stats)
{
    return models == (smp + 2 * cmd) % NMODELS &&
           stats == (cmd + smp) % 2 &&
           !(data == CURET && cmd != COMPARE && smp == ALL) &&
           !(data != CURET && cmd == RANK && smp != ONE) &&
           !(data == CORNELL5 && cmd == RANK);
}

/* cost_of_the_construction: the analyses of all 61 CURET samples run
 * with --neyman off. By default a diffuse model's interval is the Neyman
 * construction's where a second minimum of its profile competes -- WNO's
 * and WNO-R's n on most of the 61 samples, about 1 s of CPU each -- which
 * would take this file from about 150 s to 460 s. The default runs on one
 * and two samples of every data set here, and the construction's results
 * are tested in test_neyman, test_cli_analysis and the Python suite. */

/* Ends argv at a: the figures in PNG only (png), --out out, two threads,
 * quiet, NULL. */
static void end_args(const char **argv, size_t a, const char *out, int png)
{
    if (png) {
        argv[a++] = "--format";
        argv[a++] = "png";
    }
    argv[a++] = "--out";
    argv[a++] = out;
    argv[a++] = "--threads";
    argv[a++] = "2";
    argv[a++] = "-q";
    argv[a] = NULL;
}

static void run_one(data_t data, const char *const *inputs, size_t n_inputs,
                    int cmd, int smp, int models, int stats)
{
    const char *argv[96];
    char what[256];
    const char *out = bf_test_tmpdir();
    const char *err;
    size_t a = 0;
    size_t i;
    int rc;
    argv[a++] = cmd_name[cmd];
    argv[a++] = "--data";
    argv[a++] = bf_test_curet_path(""); /* MERL: CURET's configurations */
    for (i = 0; i < n_inputs; i++) {
        argv[a++] = "--input";
        argv[a++] = inputs[i];
    }
    argv[a++] = "--samples";
    argv[a++] = samples_arg[smp];
    if (models_arg[models] != NULL) {
        argv[a++] = "--models";
        argv[a++] = models_arg[models];
    }
    if (stats) {
        argv[a++] = "--stats";
    }
    if (smp == ALL && data == CURET) { /* see cost_of_the_construction */
        argv[a++] = "--neyman";
        argv[a++] = "off";
    }
    end_args(argv, a, out, cmd == REPORT);
    snprintf(what, sizeof what, "%s, %s, --samples %s, --models %s%s",
             cmd_name[cmd], data_name[data], samples_arg[smp],
             models_arg[models] != NULL ? models_arg[models] : "(default)",
             stats ? ", --stats" : "");
    rc = bf_test_run_cli(argv, NULL, &err);
    cr_assert_eq(rc, 0, "%s: exit %d: %s", what, rc, err);
    if (cmd == RANK) {
        check_csv(out, "ranking.csv", what);
        return;
    }
    check_csv(out, "fits.csv", what);
    if (cmd == REPORT) {
        check_page(out, what);
        check_figures(out, what);
    }
}

/* Runs every combination on one data set (n_samples: how many it has). */
static void run_matrix(data_t data, const char *const *inputs,
                       size_t n_inputs, size_t n_samples)
{
    int cmd;
    int smp;
    int models;
    int stats;
    size_t runs = 0;
    for (cmd = 0; cmd < NCMD; cmd++) {
        for (smp = 0; smp < NSAMPLES; smp++) {
            if ((smp == TWO && n_samples < 2) ||
                (smp == ALL && n_samples == 1)) {
                continue; /* no second sample; all is the one */
            }
            for (models = 0; models < NMODELS; models++) {
                for (stats = 0; stats < 2; stats++) {
                    if (costly(data, cmd, smp, models, stats) ||
                        repeated(data, cmd, smp, models) ||
                        (BF_TEST_SANITIZED &&
                         !diagonal(data, cmd, smp, models, stats))) {
                        continue;
                    }
                    run_one(data, inputs, n_inputs, cmd, smp, models, stats);
                    runs++;
                }
            }
        }
    }
    cr_assert_gt(runs, 0);
}

Test(matrix, curet)
{
    run_matrix(CURET, NULL, 0, 61);
}

Test(matrix, one_cornell_file)
{
    static char path[PATH_LEN]; /* the path's buffer is reused */
    const char *in[1];
    snprintf(path, sizeof path, "%s",
             bf_test_cornell_path(bf_test_cornell[2]));
    in[0] = path;
    run_matrix(CORNELL1, in, 1, 1);
}

Test(matrix, five_cornell_files)
{
    static char paths[BF_TEST_NCORNELL][PATH_LEN];
    const char *in[BF_TEST_NCORNELL];
    size_t i;
    for (i = 0; i < BF_TEST_NCORNELL; i++) {
        snprintf(paths[i], sizeof paths[i], "%s",
                 bf_test_cornell_path(bf_test_cornell[i]));
        in[i] = paths[i];
    }
    run_matrix(CORNELL5, in, BF_TEST_NCORNELL, BF_TEST_NCORNELL);
}

Test(matrix, tidy_csv)
{
    const char *in[1];
    in[0] = write_csv(bf_test_tmpdir());
    run_matrix(CSV, in, 1, 3);
}

Test(matrix, merl_table)
{
    const char *in[1];
    in[0] = write_merl(bf_test_tmpdir());
    run_matrix(MERL, in, 1, 1);
}

/* Six samples of the paper's four (here three: ON lacks its parameters)
 * scatter models keep the paper's grid: a column per sample, a row per
 * model, in one figure. */
Test(matrix, six_samples_keep_the_papers_scatter_grid)
{
    const char *out = bf_test_tmpdir();
    const char *argv[] = {"report", "--data", "DATA", "--samples", "1-6",
                          "--format", "png", "--out", out, "--threads",
                          "2", "-q", NULL};
    char path[PATH_LEN];
    const char *page;
    const char *fig;
    int rc = bf_test_run_curet(argv);
    cr_assert_eq(rc, 0, "exit %d", rc);
    snprintf(path, sizeof path, "%s/report.html", out);
    page = bf_test_slurp(path, NULL);
    cr_assert_not_null(page);
    fig = strstr(page, "part 1 of 1: predicted against measured");
    cr_assert_not_null(fig, "one scatter figure for six samples");
    cr_expect_not_null(strstr(fig, "one column per sample, one row per "
                                   "model"));
    snprintf(path, sizeof path, "%s/figures/scatter2.png", out);
    cr_expect_null(bf_test_slurp(path, NULL));
}

/* ==== glossy reports (SPEC §9, §10) ====================================== */

/* brdffit report under --objective ngan --fit exact on Cornell files
 * (files[0..n_files) of bf_test_cornell) with the options extra: exits 0,
 * fits.csv, a page whose every reference exists, figures that fit a page
 * (run_one's checks) and each figure of want (names without .png). The
 * runs leave out all but the first k configurations of 1439 (a fifth of
 * those under ASan): the point is the figures' layout, not the fits. */
static void run_glossy(const char *what, const int *files, size_t n_files,
                       size_t k, const char *const *extra,
                       const char *const *want)
{
    char exclude[32];
    static char paths[BF_TEST_NCORNELL][PATH_LEN];
    const char *argv[64];
    const char *out = bf_test_tmpdir();
    const char *err;
    char path[PATH_LEN];
    struct stat sb;
    size_t a = 0;
    size_t i;
    int rc;
    argv[a++] = "report";
    for (i = 0; i < n_files; i++) {
        snprintf(paths[i], sizeof paths[i], "%s",
                 bf_test_cornell_path(bf_test_cornell[files[i]]));
        argv[a++] = "--input";
        argv[a++] = paths[i];
    }
    for (i = 0; extra[i] != NULL; i++) {
        argv[a++] = extra[i];
    }
    /* the first k configurations (a fifth of them under ASan) */
    snprintf(exclude, sizeof exclude, "%zu-1439",
             (BF_TEST_SANITIZED ? k / 5 : k) + 1);
    argv[a++] = "--exclude";
    argv[a++] = exclude;
    argv[a++] = "--fit";
    argv[a++] = "exact";
    argv[a++] = "--objective";
    argv[a++] = "ngan";
    end_args(argv, a, out, 1);
    rc = bf_test_run_cli(argv, NULL, &err);
    cr_assert_eq(rc, 0, "%s: exit %d: %s", what, rc, err);
    check_csv(out, "fits.csv", what);
    check_page(out, what);
    check_figures(out, what);
    for (i = 0; want[i] != NULL; i++) {
        snprintf(path, sizeof path, "%s/figures/%s.png", out, want[i]);
        cr_expect_eq(stat(path, &sb), 0, "%s: no %s.png", what, want[i]);
    }
}

/* The glossy runs: what, the files (indices into bf_test_cornell, -1
 * ends), the options and the figures each must write. */
typedef struct {
    const char *what;
    int files[BF_TEST_NCORNELL + 1];
    size_t k; /* configurations used (run_glossy) */
    const char *extra[12];
    const char *want[16];
} glossy_case;

static const glossy_case glossy[] = {
    /* --models all under ngan: the complete glossy comparison, 11
     * diffuse models and 10 specular ones, drawn per family with at most
     * six curves a figure; the one run of --models all */
    {"report --models all, one Cornell file",
     {3, -1},
     300,
     {"--models", "all", NULL},
     {"plane_sample1", "plane_sample1_diffuse2", "plane_sample1_specular",
      "plane_sample1_specular2", "polar_sample1", "polar_sample1_diffuse2",
      "polar_sample1_specular", "polar_sample1_specular2", "profile_sample1",
      "profile_sample1_specular", "delta_bic", "wins",
      "forest_LAMBERT+WARD-DUER", NULL}},
    /* --channel each on the five files: 155 targets of 31 channels, the
     * delta BIC overview in pages of rows (LAMBERT: a scale only, cheap) */
    {"report --channel each, five Cornell files",
     {0, 1, 2, 3, 4, -1},
     100,
     {"--models", "LAMBERT", "--channel", "each", NULL},
     {"delta_bic", "delta_bic_2", "plane_sample5_700", NULL}},
    /* --channel joint: one shape for the 31 channels, a figure each */
    {"report --channel joint, one Cornell file",
     {1, -1},
     300,
     {"--models", "LAMBERT+GGX,AS", "--channel", "joint", NULL},
     {"plane_sample1_400", "polar_sample1_700", NULL}},
    /* --size single: 31 channels' rows over two pages of the overview and
     * of the forest plot at single-column width */
    {"report --size single --channel each, one Cornell file",
     {4, -1},
     300,
     {"--models", "LAMBERT,LAMBERT+GGX", "--channel", "each", "--size",
      "single", NULL},
     {"delta_bic_2", "forest_LAMBERT+GGX_2", "plane_sample1_400_specular",
      NULL}},
};

static void run_glossy_case(size_t i)
{
    size_t n = 0;
    while (glossy[i].files[n] >= 0) {
        n++;
    }
    run_glossy(glossy[i].what, glossy[i].files, n, glossy[i].k,
               glossy[i].extra, glossy[i].want);
}

Test(glossy, one_file_every_model_by_family, .timeout = 600)
{
    run_glossy_case(0);
}

Test(glossy, five_files_every_channel_page_the_overview, .timeout = 600)
{
    run_glossy_case(1);
}

Test(glossy, one_file_joint_channels, .timeout = 600)
{
    run_glossy_case(2);
}

Test(glossy, single_column_every_channel, .timeout = 600)
{
    run_glossy_case(3);
}
