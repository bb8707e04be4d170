/* test_cmd_report.c: `brdffit report` on the CURET data -- every figure
 * in every format is a valid file, of the size the page declares, without
 * title or date metadata, and on the page; the analysis figures appear
 * exactly when the analysis ran; the page is valid HTML (html5lib's strict
 * parser) with its tables as HTML tables of the right number of rows;
 * nothing is fetched from the network; the outputs are the same for 1 and
 * 2 drawing processes and between runs; bad options and a failed run leave
 * no output. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "formats.h"
#include "support.h"

#define EXIT_BADVALUE 63
#define EXIT_CANTCREAT 73
/* The page shows a figure of w x h points as 2w x 2h CSS pixels; its PNG
 * has 150 pixels per inch. */
#define CSS_PER_PT 2
#define PNG_DPI 150

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

/* A copy of the page (bf_test_slurp's buffer is reused). */
static char *page_of(const char *dir)
{
    const char *html = bf_test_slurp(bf_test_join(dir, "report.html"), NULL);
    char *page;
    cr_assert_not_null(html, "no report.html in %s", dir);
    page = strdup(html);
    cr_assert_not_null(page);
    return page;
}

/* Every src="..." and href="..." of the page: a local file that exists in
 * dir, or an anchor in the page; nothing from the network. */
static void check_references(const char *dir, const char *html)
{
    static const char *const attrs[2] = {" src=\"", " href=\""};
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
            cr_expect(bf_test_exists(bf_test_join(dir, ref)),
                      "report.html refers to a missing file: %s", ref);
        }
    }
}

/* The <img> of figure base on the page: its declared size, CSS pixels. */
static void img_size(const char *page, const char *base, const char *ext,
                     unsigned *w, unsigned *h)
{
    char src[256];
    const char *p;
    snprintf(src, sizeof src, "<img src=\"figures/%s.%s\" width=\"", base,
             ext);
    p = strstr(page, src);
    cr_assert_not_null(p, "%s.%s is not shown on the page", base, ext);
    cr_assert_eq(sscanf(p + strlen(src), "%u\" height=\"%u\"", w, h), 2);
}

/* Checks every file of figures/ -- valid in its format at the size the
 * page declares, no metadata title, on the page, no temporary left -- and
 * returns their number. */
static size_t check_figures(const char *dir, const char *page)
{
    DIR *d = opendir(bf_test_join(dir, "figures"));
    struct dirent *de;
    size_t n = 0;
    cr_assert_not_null(d);
    while ((de = readdir(d)) != NULL) {
        char ref[600];
        char base[256];
        const char *ext = strrchr(de->d_name, '.');
        unsigned w;
        unsigned h;
        if (de->d_name[0] == '.' && (strcmp(de->d_name, ".") == 0 ||
                                     strcmp(de->d_name, "..") == 0)) {
            continue;
        }
        cr_expect(de->d_name[0] != '.', "temporary file left: %s",
                  de->d_name);
        snprintf(ref, sizeof ref, "\"figures/%s\"", de->d_name);
        cr_expect_not_null(strstr(page, ref), "%s is not on the page", ref);
        cr_assert_not_null(ext);
        snprintf(base, sizeof base, "%.*s", (int)(ext - de->d_name),
                 de->d_name);
        /* the page shows the PNG (or the SVG without PNG) */
        img_size(page, base,
                 bf_test_exists(bf_test_join(dir, "figures/fig2b.png"))
                     ? "png"
                     : "svg",
                 &w, &h);
        w /= CSS_PER_PT;
        h /= CSS_PER_PT;
        snprintf(ref, sizeof ref, "figures/%s", de->d_name);
        if (strcmp(ext, ".png") == 0) {
            fmt_check_png(bf_test_join(dir, ref), (w * PNG_DPI + 36) / 72,
                          (h * PNG_DPI + 36) / 72);
            fmt_check_png_plain(bf_test_join(dir, ref));
        } else if (strcmp(ext, ".svg") == 0) {
            fmt_check_svg(bf_test_join(dir, ref), w, h);
            fmt_check_svg_plain(bf_test_join(dir, ref));
        } else {
            cr_assert_str_eq(ext, ".pdf");
            fmt_check_pdf(bf_test_join(dir, ref), w, h);
            fmt_check_pdf_plain(bf_test_join(dir, ref));
        }
        n++;
    }
    closedir(d);
    return n;
}

/* Rows of the body of the table with the given id. */
static size_t table_rows(const char *page, const char *id)
{
    char open[128];
    const char *t;
    const char *body;
    const char *end;
    size_t n = 0;
    snprintf(open, sizeof open, "<table id=\"%s\">", id);
    t = strstr(page, open);
    cr_assert_not_null(t, "no table %s", id);
    body = strstr(t, "<tbody>");
    end = strstr(t, "</table>");
    cr_assert(body != NULL && end != NULL && body < end, "table %s has no "
                                                         "body", id);
    for (; (body = strstr(body, "<tr>")) != NULL && body < end; body += 4) {
        n++;
    }
    return n;
}

/* The page through html5lib's strict parser (python3-html5lib): any parse
 * error fails. */
static void check_valid_html(const char *dir)
{
    char cmd[2048];
    const char *out = NULL;
    int rc;
    snprintf(cmd, sizeof cmd,
             "/usr/bin/python3 -c 'import sys, html5lib; "
             "html5lib.HTMLParser(strict=True).parse(open(sys.argv[1], "
             "\"rb\"))' '%s/report.html'",
             dir);
    rc = bf_test_run_sh(cmd, &out);
    cr_assert_eq(rc, 0,
                 "report.html is not valid HTML (or python3-html5lib is "
                 "missing: scripts/install-deps.sh installs it):\n%s",
                 out);
}

/* Rows of fits.csv whose ci_low column is filled: one per sample, model
 * and fitted parameter of the analysis. */
static size_t csv_interval_rows(const char *dir)
{
    const char *csv = bf_test_slurp(bf_test_join(dir, "fits.csv"), NULL);
    const char *line;
    size_t col = 0;
    size_t n = 0;
    size_t c;
    cr_assert_not_null(csv);
    for (line = csv; strncmp(line, "ci_low,", 7) != 0; line++) {
        cr_assert(*line != '\n', "fits.csv has no ci_low column");
        col += *line == ',';
    }
    for (line = strchr(csv, '\n'); line != NULL && line[1] != '\0';
         line = strchr(line + 1, '\n')) {
        const char *f = line + 1;
        for (c = 0; c < col; c++) {
            f = strchr(f, ',') + 1;
        }
        n += *f != ',';
    }
    return n;
}

Test(report, writes_every_figure_valid_and_sized_as_the_page_says,
     .timeout = 600)
{
    static const char *const extra[] = {"--per-sample", "--format",
                                        "png,svg,pdf", NULL};
    static const int samples[4] = {1, 9, 34, 44};
    const char *dir = bf_test_tmpdir();
    const char *err = NULL;
    char cmd[1200];
    char sum[65] = "";
    char *page;
    size_t i;
    FILE *p;

    cr_assert_eq(run_report(dir, "1,9,34,44", extra, &err), 0, "stderr:\n%s",
                 err);
    cr_expect_str_empty(err, "stderr is not a terminal: no progress line");
    page = page_of(dir);
    check_valid_html(dir);
    check_references(dir, page);
    /* fig2b, wins, scatter1, and 3 per sample (scatter, plane, polar); no
     * analysis figure without the analysis; in 3 formats */
    cr_expect_eq(check_figures(dir, page), (3 + 3 * 4) * 3);
    for (i = 0; i < 4; i++) {
        char base[64];
        snprintf(base, sizeof base, "figures/plane_sample%d.png", samples[i]);
        cr_expect(bf_test_exists(bf_test_join(dir, base)), "%s", base);
    }
    cr_expect(!bf_test_exists(bf_test_join(dir, "figures/delta_bic.png")));
    /* the tables, as HTML tables with a row per sample */
    cr_expect_eq(table_rows(page, "table2"), 4u);
    cr_expect_eq(table_rows(page, "table3"), 4u);
    cr_expect_not_null(strstr(page, "Not computed: run with "
                                    "<code>--stats</code>"));
    /* the page describes the data it was given */
    cr_expect_not_null(strstr(page, "Format: CURET"));
    cr_expect_not_null(strstr(page, "K = 198 of 205"));
    cr_expect_not_null(strstr(page, "54, 97, 131, 161, 183, 196, 202"));
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
    free(page);
}

/* With --stats: the analysis figures (delta BIC, a forest plot per model
 * with fitted parameters, a profile per sample) and tables (samples won
 * per criterion, BIC per sample, the intervals with a row per fitted
 * parameter of fits.csv), the per-sample figures in collapsed sections. */
Test(report, stats_add_the_analysis_figures_and_tables, .timeout = 600)
{
    static const char *const stats[] = {"--stats", NULL};
    static const char *const fitted[] = {"VH-G", "VH-E", "FC-G", "FC-E",
                                         "LFTG"};
    const char *dir = bf_test_tmpdir();
    const char *err = NULL;
    char *page;
    size_t i;
    cr_assert_eq(run_report(dir, "9,34,44", stats, &err), 0, "%s", err);
    page = page_of(dir);
    check_valid_html(dir);
    check_references(dir, page);
    /* 2 + 1 scatter + delta BIC + 5 forests + 3 x (plane, polar, profile),
     * PNG and PDF (the default formats) */
    cr_expect_eq(check_figures(dir, page), (2 + 1 + 1 + 5 + 3 * 3) * 2);
    cr_expect(bf_test_exists(bf_test_join(dir, "figures/delta_bic.pdf")));
    for (i = 0; i < 5; i++) {
        char f[64];
        snprintf(f, sizeof f, "figures/forest_%s.png", fitted[i]);
        cr_expect(bf_test_exists(bf_test_join(dir, f)), "%s", f);
    }
    cr_expect(!bf_test_exists(bf_test_join(dir, "figures/forest_ON.png")),
              "ON fits nothing under the paper's protocol");
    cr_expect(
        bf_test_exists(bf_test_join(dir, "figures/profile_sample34.png")));
    cr_expect_eq(table_rows(page, "wins-table"), 3u, "AIC, BIC, CV");
    cr_expect_eq(table_rows(page, "bic-table"), 3u);
    cr_expect_eq(table_rows(page, "intervals"), csv_interval_rows(dir));
    cr_expect_eq(csv_interval_rows(dir), 3u * 5u);
    cr_expect_not_null(strstr(page, "<details id=\"sample44\">"));
    cr_expect_null(strstr(page, "Not computed"));
    /* the profiles drawn are the noise model's likelihood's, whose
     * threshold the reported intervals (the default, profile-lik) take,
     * not the objective's */
    cr_expect_not_null(strstr(page, "profiles of the likelihood"));
    cr_expect_not_null(strstr(page, "ci_method profile-lik"));
    cr_expect_null(strstr(page, "profiles of the objective"));
    free(page);
}

/* Removes the line that starts with "<li>Command:" (the command line,
 * which names the output folder and --threads) from the text. */
static void drop_command(char *s, size_t *len)
{
    char *c = strstr(s, "<li>Command:");
    char *e = c != NULL ? strchr(c, '\n') : NULL;
    if (e != NULL) {
        memmove(c, e + 1, strlen(e + 1) + 1);
        *len = strlen(s);
    }
}

/* Every file of a's figures/ and the tables and page (but for its command
 * line) are the same bytes in b. */
static void same_outputs(const char *a, const char *b)
{
    static const char *const files[] = {"fits.csv", "table2.md", "table3.md",
                                        "report.html"};
    DIR *d = opendir(bf_test_join(a, "figures"));
    struct dirent *de;
    size_t n = 0;
    size_t i;
    cr_assert_not_null(d);
    for (i = 0; i < 4 + 1000; i++) {
        char name[600];
        size_t la;
        size_t lb;
        char *x;
        char *y;
        if (i < 4) {
            snprintf(name, sizeof name, "%s", files[i]);
        } else {
            while ((de = readdir(d)) != NULL && de->d_name[0] == '.') {
            }
            if (de == NULL) {
                break;
            }
            snprintf(name, sizeof name, "figures/%s", de->d_name);
            n++;
        }
        x = bf_test_copy(bf_test_join(a, name), &la);
        y = bf_test_copy(bf_test_join(b, name), &lb);
        if (i == 3) {
            drop_command(x, &la);
            drop_command(y, &lb);
        }
        cr_expect(la == lb && memcmp(x, y, la) == 0, "%s differs", name);
        free(x);
        free(y);
    }
    closedir(d);
    cr_expect_gt(n, 10u, "figures compared");
}

Test(report, gives_the_same_files_for_one_and_two_drawing_processes,
     .timeout = 600)
{
    static const char *const one[] = {"--stats", "--format", "png,svg,pdf",
                                      "--threads", "1", NULL};
    static const char *const two[] = {"--stats", "--format", "png,svg,pdf",
                                      "--threads", "2", NULL};
    char *a = strdup(bf_test_tmpdir());
    char *b = strdup(bf_test_tmpdir());
    const char *err = NULL;
    cr_assert_eq(run_report(a, "1,44", one, &err), 0, "%s", err);
    cr_assert_eq(run_report(b, "1,44", two, &err), 0, "%s", err);
    same_outputs(a, b);
    free(a);
    free(b);
}

Test(report, gives_byte_identical_outputs_when_run_twice, .timeout = 600)
{
    static const char *const extra[] = {"--models", "VH-E,FC-E", "--format",
                                        "png,svg,pdf", "--log", NULL};
    char *a = strdup(bf_test_tmpdir());
    char *b = strdup(bf_test_tmpdir());
    cr_assert_eq(run_report(a, "44", extra, NULL), 0);
    cr_assert_eq(run_report(b, "44", extra, NULL), 0);
    same_outputs(a, b);
    free(a);
    free(b);
}

/* --size single draws every figure 3.5 in wide; --format svg alone
 * shows the SVGs on the page. */
Test(report, draws_single_column_figures_on_request)
{
    static const char *const extra[] = {"--size", "single", "--format", "svg",
                                        "--models", "FC-E,ON", NULL};
    const char *dir = bf_test_tmpdir();
    char *page;
    unsigned w;
    unsigned h;
    cr_assert_eq(run_report(dir, "44", extra, NULL), 0);
    page = page_of(dir);
    img_size(page, "fig2b", "svg", &w, &h);
    cr_expect_eq(w, 252u * CSS_PER_PT);
    img_size(page, "plane_sample44", "svg", &w, &h);
    cr_expect_eq(w, 252u * CSS_PER_PT);
    cr_expect(!bf_test_exists(bf_test_join(dir, "figures/fig2b.png")));
    check_figures(dir, page);
    free(page);
}

/* The page's conventions and the run's description under them (as
 * brdffit prints it) say what the run held and what it fitted, and only
 * of the models it ran (and the page counts one sample as one): the
 * paper's protocol holds n = 1.7 and evaluates ON at tabulated rho,
 * sigma; --fit exact frees both (bf_model_variant_exact), and with --n
 * given n stays fixed; a specular model alone has no grid, FC or ON
 * line, and under --fresnel dielectric its own n is fitted. */
Test(report, conventions_follow_the_models_and_their_freed_inputs)
{
    static const char *const paper[] = {"--models", "FC-E,ON", "--format",
                                        "svg", NULL};
    static const char *const exact[] = {"--models", "FC-E,ON", "--fit",
                                        "exact", "--format", "svg", NULL};
    static const char *const given[] = {"--models", "FC-E,ON", "--fit",
                                        "exact", "--n", "1.5", "--format",
                                        "svg", NULL};
    static const char *const glossy[] = {"--models", "LAMBERT+GGX", "--fit",
                                         "exact", "--objective", "ngan",
                                         "--format", "svg", NULL};
    static const char *const dielectric[] = {
        "--models", "LAMBERT+GGX", "--fit", "exact", "--objective", "ngan",
        "--fresnel", "dielectric", "--format", "svg", NULL};
    const char *const *runs[5] = {paper, exact, given, glossy, dielectric};
    const char *n_text[5] = {"refractive index n = 1.7 for every sample",
                             "refractive index n fitted per sample",
                             "refractive index n = 1.5 for every sample",
                             NULL, "as its own parameter"};
    /* ON's line: 0 none, 1 evaluated, 2 fitted */
    const int on_line[5] = {1, 2, 2, 0, 0};
    const int grids[5] = {1, 1, 1, 0, 0};
    int r;
    for (r = 0; r < 5; r++) {
        const char *dir = bf_test_tmpdir();
        char *page;
        char *conv;
        char *desc;
        cr_assert_eq(run_report(dir, "44", runs[r], NULL), 0, "run %d", r);
        page = page_of(dir);
        conv = strstr(page, "<h2 id=\"conventions\">");
        cr_assert_not_null(conv, "run %d", r);
        cr_expect_eq(strstr(conv, "<li>Fresnel reflectance") != NULL,
                     n_text[r] != NULL, "run %d", r);
        cr_expect(n_text[r] == NULL || strstr(conv, n_text[r]) != NULL,
                  "run %d", r);
        cr_expect_eq(strstr(conv, "Oren–Nayar (ON): ρ and σ fitted") != NULL,
                     on_line[r] == 2, "run %d", r);
        cr_expect_eq(strstr(conv, "Oren–Nayar (ON) is evaluated, not "
                                  "fitted") != NULL,
                     on_line[r] == 1, "run %d", r);
        cr_expect_eq(strstr(conv, "<li>Exhaustive grids") != NULL, grids[r],
                     "run %d", r);
        /* the description: the same lines */
        desc = strstr(conv, "<pre>");
        cr_assert_not_null(desc, "run %d", r);
        cr_expect_eq(strstr(desc, "Refractive index (FC): n = ") != NULL,
                     r == 0 || r == 2, "run %d", r);
        cr_expect_eq(strstr(desc, "Oren-Nayar: rho, sigma fitted") != NULL,
                     on_line[r] == 2, "run %d", r);
        cr_expect_eq(strstr(desc, "Oren-Nayar: rho, sigma from") != NULL,
                     on_line[r] == 1, "run %d", r);
        cr_expect_eq(strstr(desc, "grid optimum, then GSL Brent") != NULL ||
                         strstr(desc, "Fit: exhaustive") != NULL,
                     grids[r], "run %d", r);
        cr_expect_eq(strstr(desc, "Free parameters") != NULL,
                     r == 1 || r == 2, "run %d", r);
        /* one sample, one or two models: no "1 samples", "1 models" */
        cr_expect(strstr(page, " 1 samples") == NULL, "run %d", r);
        cr_expect(strstr(page, " 1 models") == NULL, "run %d", r);
        free(page);
    }
}

Test(report, refuses_a_bad_format_size_or_incidence_before_writing_anything)
{
    static const char *const bad[][3] = {{"--format", "png,gif", NULL},
                                         {"--format", "", NULL},
                                         {"--format", "png,", NULL},
                                         {"--size", "a4", NULL},
                                         {"--incidence", "95", NULL},
                                         {"--incidence", "10,20,30,40,50",
                                          NULL}};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof *bad; i++) {
        const char *dir = bf_test_tmpdir();
        const char *out = bf_test_join(dir, "out");
        const char *err = NULL;
        cr_expect_eq(run_report(out, "44", bad[i], &err), EXIT_BADVALUE,
                     "%s %s", bad[i][0], bad[i][1]);
        cr_expect_not_null(strstr(err, bad[i][0]), "message names %s: %s",
                           bad[i][0], err);
        cr_expect(!bf_test_exists(out), "%s %s created the output folder",
                  bad[i][0], bad[i][1]);
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
    /* a file, not a folder */
    FILE *fp = fopen(bf_test_join(dir, "figures"), "w");
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
