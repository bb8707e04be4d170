/* test_cmd_report.c: `brdffit report` on the CURET data -- every figure in
 * every format is a valid file of the documented size (README.md), the
 * page references only files that exist (and every figure), nothing is
 * fetched from the network, the outputs are reproducible, and a failed
 * run leaves no partial output. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "formats.h"
#include "support.h"

/* Figure sizes documented in README.md (pixels for PNG, points for SVG
 * and PDF): one scatter panel is 330 x 330. */
#define PANEL 330
#define LSE_W 1400
#define LSE_H 650
#define PLANE_W 1400
#define PLANE_H 900
#define POLAR_H 760
#define WINS_W 800
#define WINS_H 500

#define EXIT_BADVALUE 63
#define EXIT_CANTCREAT 73

static const char *join(const char *dir, const char *name)
{
    static char path[2][1024];
    static int k;
    k = !k;
    snprintf(path[k], sizeof path[k], "%s/%s", dir, name);
    return path[k];
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* Runs report on the given samples into dir with extra arguments. */
static int run_report(const char *dir, const char *samples,
                      const char *const *extra, const char **err)
{
    const char *argv[32] = {"report", "--data", BF_CURET_DIR, "--on-params",
                            BF_REFERENCE_DIR "/oren_nayar_params.tsv",
                            "--samples", samples, "--out", dir, "-q"};
    size_t n = 10;
    for (; extra != NULL && *extra != NULL; extra++) {
        argv[n++] = *extra;
    }
    argv[n] = NULL;
    return bf_test_run_cli(argv, NULL, err);
}

/* Asserts the figure base exists in the three formats with size w x h. */
static void check_figure(const char *dir, const char *base, unsigned w,
                         unsigned h)
{
    char name[256];
    snprintf(name, sizeof name, "figures/%s.png", base);
    fmt_check_png(join(dir, name), w, h);
    snprintf(name, sizeof name, "figures/%s.svg", base);
    fmt_check_svg(join(dir, name), w, h);
    snprintf(name, sizeof name, "figures/%s.pdf", base);
    fmt_check_pdf(join(dir, name), w, h);
}

/* Every src="..." and href="..." of the page: a local file that exists in
 * dir, or an anchor in the page; nothing from the network. Returns the
 * number of local references; counts each figure file referenced in
 * *figs. */
static size_t check_references(const char *dir, const char *html)
{
    static const char *const attrs[2] = {" src=\"", " href=\""};
    size_t local = 0;
    int a;
    for (a = 0; a < 2; a++) {
        const char *p = html;
        while ((p = strstr(p, attrs[a])) != NULL) {
            char ref[512];
            size_t n;
            p += strlen(attrs[a]);
            n = strcspn(p, "\"");
            cr_assert_lt(n, sizeof ref);
            memcpy(ref, p, n);
            ref[n] = '\0';
            p += n;
            if (ref[0] == '#') {
                char id[600];
                snprintf(id, sizeof id, " id=\"%s\"", ref + 1);
                cr_expect_not_null(strstr(html, id), "anchor %s has no target",
                                   ref);
                continue;
            }
            cr_expect(strstr(ref, "://") == NULL && strncmp(ref, "//", 2) &&
                          ref[0] != '/',
                      "report.html refers outside its folder: %s", ref);
            cr_expect(exists(join(dir, ref)),
                      "report.html refers to a missing file: %s", ref);
            local++;
        }
    }
    return local;
}

Test(report, writes_every_figure_valid_in_three_formats_and_a_page_that_links_only_existing_files,
     .timeout = 600)
{
    static const char *const extra[] = {"--per-sample", NULL};
    static const int samples[4] = {1, 9, 34, 44};
    const char *dir = bf_test_tmpdir();
    const char *err = NULL;
    const char *html;
    char *page;
    size_t len;
    size_t i;
    DIR *d;
    struct dirent *de;
    size_t n_files = 0;
    char cmd[1200];
    char sum[65] = "";
    FILE *p;

    cr_assert_eq(run_report(dir, "1,9,34,44", extra, &err), 0, "stderr:\n%s",
                 err);
    cr_expect_str_empty(err, "stderr is not a terminal: no progress line");

    /* the figures, at the documented sizes */
    check_figure(dir, "fig2b", LSE_W, LSE_H);
    check_figure(dir, "wins", WINS_W, WINS_H);
    /* 4 samples x the paper's 4 scatter models (ON, LFTG, VH-E, FC-E) */
    check_figure(dir, "scatter1", 4 * PANEL, 4 * PANEL);
    cr_expect(!exists(join(dir, "figures/scatter2.png")));
    for (i = 0; i < 4; i++) {
        char base[64];
        snprintf(base, sizeof base, "scatter_sample%d", samples[i]);
        check_figure(dir, base, 4 * PANEL, PANEL);
        snprintf(base, sizeof base, "plane_sample%d", samples[i]);
        check_figure(dir, base, PLANE_W, PLANE_H);
        snprintf(base, sizeof base, "polar_sample%d", samples[i]);
        check_figure(dir, base, PLANE_W, POLAR_H);
    }
    /* the tables, as compare writes them */
    cr_expect(exists(join(dir, "fits.csv")));
    cr_expect(exists(join(dir, "table2.md")));
    cr_expect(exists(join(dir, "table3.md")));

    /* the page: well-formed enough, local references only */
    html = bf_test_slurp(join(dir, "report.html"), &len);
    cr_assert_not_null(html, "no report.html");
    page = strdup(html);
    cr_assert_not_null(page);
    cr_expect(strncmp(page, "<!DOCTYPE html>", 15) == 0);
    cr_expect_not_null(strstr(page, "</html>"));
    check_references(dir, page);
    /* every figure file is on the page; no temporary file is left */
    d = opendir(join(dir, "figures"));
    cr_assert_not_null(d);
    while ((de = readdir(d)) != NULL) {
        char ref[600];
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) {
            continue;
        }
        cr_expect(de->d_name[0] != '.', "temporary file left: %s",
                  de->d_name);
        snprintf(ref, sizeof ref, "\"figures/%s\"", de->d_name);
        cr_expect_not_null(strstr(page, ref), "%s is not on the page", ref);
        n_files++;
    }
    closedir(d);
    /* fig2b, wins, scatter1, and 3 per sample, in 3 formats */
    cr_expect_eq(n_files, (3 + 3 * 4) * 3);

    /* provenance: version, the command and the data checksum, computed
     * here by the system's sha256sum */
    cr_expect_not_null(strstr(page, "brdffit " BF_VERSION_STRING));
    cr_expect_not_null(strstr(page, "--samples 1,9,34,44"));
    snprintf(cmd, sizeof cmd, "sha256sum '%s/abrdf.dat'", BF_CURET_DIR);
    p = popen(cmd, "r");
    cr_assert_not_null(p);
    cr_assert_eq(fscanf(p, "%64s", sum), 1);
    pclose(p);
    cr_expect_not_null(strstr(page, sum), "abrdf.dat's SHA-256 %s missing",
                       sum);
    /* conventions */
    cr_expect_not_null(strstr(page, "K = 198"));
    cr_expect_not_null(strstr(page, "54, 97, 131, 161, 183, 196, 202"));
    free(page);
}

/* Copies a file's bytes (bf_test_slurp's buffer is reused). */
static char *copy_of(const char *path, size_t *len)
{
    const char *s = bf_test_slurp(path, len);
    char *c;
    cr_assert_not_null(s, "%s missing", path);
    c = malloc(*len + 1);
    cr_assert_not_null(c);
    memcpy(c, s, *len + 1);
    return c;
}

Test(report, gives_byte_identical_tables_page_and_png_svg_figures_when_run_twice,
     .timeout = 600)
{
    static const char *const extra[] = {"--models", "VH-E,FC-E", "--format",
                                        "png,svg", "--log", NULL};
    static const char *const files[] = {
        "fits.csv", "table2.md", "table3.md", "report.html",
        "figures/fig2b.png", "figures/fig2b.svg", "figures/scatter1.png",
        "figures/scatter1.svg", "figures/plane_sample44.png",
        "figures/polar_sample44.svg", "figures/wins.png"};
    const char *dir = bf_test_tmpdir();
    char *first[sizeof files / sizeof *files];
    size_t len[sizeof files / sizeof *files];
    size_t i;

    cr_assert_eq(run_report(dir, "44", extra, NULL), 0);
    for (i = 0; i < sizeof files / sizeof *files; i++) {
        first[i] = copy_of(join(dir, files[i]), &len[i]);
    }
    cr_expect(!exists(join(dir, "figures/fig2b.pdf")), "--format: no pdf");
    cr_assert_eq(run_report(dir, "44", extra, NULL), 0);
    for (i = 0; i < sizeof files / sizeof *files; i++) {
        size_t n;
        char *again = copy_of(join(dir, files[i]), &n);
        cr_expect(n == len[i] && memcmp(first[i], again, n) == 0,
                  "%s differs between two identical runs", files[i]);
        free(again);
        free(first[i]);
    }
}

Test(report, refuses_a_bad_format_or_incidence_before_writing_anything)
{
    static const char *const bad[][3] = {{"--format", "png,gif", NULL},
                                         {"--format", "", NULL},
                                         {"--format", "png,", NULL},
                                         {"--incidence", "95", NULL},
                                         {"--incidence", "10,20,30,40,50",
                                          NULL}};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof *bad; i++) {
        const char *dir = bf_test_tmpdir();
        const char *out = join(dir, "out");
        const char *err = NULL;
        cr_expect_eq(run_report(out, "44", bad[i], &err), EXIT_BADVALUE,
                     "%s %s", bad[i][0], bad[i][1]);
        cr_expect_not_null(strstr(err, bad[i][0]), "message names %s: %s",
                           bad[i][0], err);
        cr_expect(!exists(out), "%s %s created the output folder", bad[i][0],
                  bad[i][1]);
    }
}

Test(report, leaves_no_partial_output_when_the_figures_cannot_be_written,
     .timeout = 600)
{
    static const char *const extra[] = {"--models", "FC-E", NULL};
    const char *dir = bf_test_tmpdir();
    const char *err = NULL;
    DIR *d;
    struct dirent *de;
    FILE *fp = fopen(join(dir, "figures"), "w"); /* a file, not a folder */
    cr_assert_not_null(fp);
    fclose(fp);
    cr_assert_eq(run_report(dir, "44", extra, &err), EXIT_CANTCREAT);
    cr_expect_not_null(strstr(err, "figures"), "message: %s", err);
    d = opendir(dir);
    cr_assert_not_null(d);
    while ((de = readdir(d)) != NULL) {
        cr_expect(strcmp(de->d_name, ".") == 0 ||
                      strcmp(de->d_name, "..") == 0 ||
                      strcmp(de->d_name, "figures") == 0,
                  "a failed run left %s", de->d_name);
    }
    closedir(d);
}

/* With --stats the page carries the model selection of `brdffit rank`: the
 * summary line of each criterion, whose counts add up to the samples, and
 * the per-sample BIC table; without it, a note says how to get it. */
Test(report, stats_add_a_model_selection_section)
{
    static const char *const stats[] = {"--stats", "--format", "png", NULL};
    static const char *const plain[] = {"--format", "png", NULL};
    static const char *const crit[] = {"AIC:", "BIC:", "CV:"};
    char with[512];
    char without[512];
    const char *err = NULL;
    char *page;
    size_t i;
    snprintf(with, sizeof with, "%s/out", bf_test_tmpdir());
    snprintf(without, sizeof without, "%s/out", bf_test_tmpdir());
    cr_assert_eq(run_report(with, "9,34,44", stats, &err), 0, "%s", err);
    page = strdup(bf_test_slurp(join(with, "report.html"), NULL));
    for (i = 0; i < 3; i++) {
        const char *li = strstr(page, crit[i]);
        int counted = 0;
        int n;
        const char *p;
        cr_assert_not_null(li, "no %s summary", crit[i]);
        /* "BIC: FC-E best for 2 of 3 samples, VH-E 1" */
        cr_assert_eq(sscanf(strstr(li, "best for"), "best for %d", &n), 1);
        counted += n;
        for (p = strstr(li, "samples"); *p != '<'; p++) {
            if (*p == ' ' && p[1] >= '0' && p[1] <= '9') {
                counted += atoi(p + 1);
            }
        }
        cr_assert_eq(counted, 3, "%s counts %d of 3 samples", crit[i],
                     counted);
    }
    cr_assert_not_null(strstr(page, "<h3>BIC per sample</h3>"));
    free(page);
    cr_assert_eq(run_report(without, "44", plain, &err), 0, "%s", err);
    cr_assert_not_null(strstr(bf_test_slurp(join(without, "report.html"),
                                            NULL),
                              "Not computed: run with <code>--stats</code>"));
}
