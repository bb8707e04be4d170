/* cmd_report.c: `brdffit report` -- runs the study of SPEC §7 like
 * `compare` and writes, into the output folder, its tables (fits.csv,
 * table2.md, table3.md), every figure (figures/: Figure 2(b), Figures 3-6,
 * the model-wins chart, per-sample plane-of-incidence views and, with the
 * analysis, forest plots, profiles and the delta-BIC overview) in PNG and
 * PDF (SVG on request), and report.html, one page that gathers them with
 * the conventions and provenance of the run. */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "figures.h"
#include "report_html.h"
#include "tables.h"

#define DEG (M_PI / 180.0)

/* Largest incidence angle accepted by --incidence, degrees (the original
 * BK models diverge at grazing incidence, SPEC §3.3). */
#define MAX_INCIDENCE_DEG 89.0
/* Most processes drawing figures at once. */
#define MAX_JOBS 64

enum { O_FORMAT = 512, O_LOG, O_PER_SAMPLE, O_INCIDENCE, O_SIZE };

static const struct option report_opts[] = {
    {"format", required_argument, NULL, O_FORMAT},
    {"size", required_argument, NULL, O_SIZE},
    {"log", no_argument, NULL, O_LOG},
    {"per-sample", no_argument, NULL, O_PER_SAMPLE},
    {"incidence", required_argument, NULL, O_INCIDENCE},
    {NULL, 0, NULL, 0}};

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit report [OPTIONS] [FILE...]\n"
"\n"
"Run the study of 'brdffit compare' and write into the output folder its\n"
"tables (fits.csv, table2.md, table3.md), report.html (one page with the\n"
"tables, the figures with their captions, the conventions and the\n"
"provenance; it opens from disk) and every figure in figures/. Figures\n"
"carry no title (the captions are on the page):\n"
"  fig2b           LSE of each model against the samples sorted by\n"
"                  fitted FC-E slope (the paper's Figure 2(b))\n"
"  wins            samples fitted best (lowest LSE) by each model\n"
"  scatterN        predicted against measured normalised radiance, a\n"
"                  column per sample (six per figure), a row per model\n"
"                  (the paper's Figures 3-6); fewer samples a figure,\n"
"                  transposed or one sample's panels in rows where that\n"
"                  grid would not fit a page (at most 1.5 times as tall\n"
"                  as wide)\n"
"  plane_sampleN   fitted model curves and the measurements in the plane\n"
"  polar_sampleN   of incidence, Cartesian and polar, per incidence angle\n"
"  scatter_sampleN one sample's scatter panels (--per-sample)\n"
"With the analysis (--stats, --fit exact, --bootstrap):\n"
"  delta_bic       samples x models, BIC minus each sample's best\n"
"  forest_MODEL    each sample's fitted parameters with their 95%\n"
"                  profile (and bootstrap) intervals\n"
"  profile_sampleN the profile n ln(S/S_min) along each fitted parameter\n"
"                  with the 95% threshold 3.84\n"
"Every curve and measurement is divided by its maximum over the used\n"
"configurations (SPEC §2). Figures are drawn at print size (--size) with\n"
"8-point text; PNG at 150 pixels per inch.\n"
"\n"
"Options:\n",
        fp);
    bf_cli_opts_usage(fp);
    fputs(
"  --format LIST     figure formats among png,svg,pdf (default png,pdf)\n"
"  --size SIZE       figure width: double (7 in, default) or single\n"
"                    (3.5 in), the journal column widths\n"
"  --log             Figure 2(b) on a logarithmic LSE axis\n"
"  --per-sample      also one scatter figure per sample (scatter_sampleN)\n"
"  --incidence LIST  incidence angles of the plane-of-incidence figures,\n"
"                    degrees, at most 4 (default: chosen from the data, the\n"
"                    incidence angles with the most in-plane measurements,\n"
"                    spread over their range; 11.25,33.75,56.25,78.75 on\n"
"                    CURET)\n"
"\n"
"--threads N also draws the figures in N processes (the same files for\n"
"every N). A progress line is printed on stderr when it is a terminal.\n",
        fp);
    bf_cli_exit_usage(fp);
}

static int parse_formats(const char *arg, unsigned *formats)
{
    const char *p = arg;
    *formats = 0;
    while (*p != '\0') {
        size_t len = strcspn(p, ",");
        int f;
        int found = 0;
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            const char *ext = bf_plot_format_ext((bf_plot_format)f);
            if (len == strlen(ext) && strncmp(p, ext, len) == 0) {
                *formats |= 1u << f;
                found = 1;
            }
        }
        if (!found) {
            return -1;
        }
        p += len;
        if (*p == ',' && *++p == '\0') {
            return -1;
        }
    }
    return *formats != 0 ? 0 : -1;
}

static int parse_incidence(const char *arg, bf_fig_opts *o)
{
    const char *p = arg;
    o->n_incidence = 0;
    while (*p != '\0') {
        char word[64];
        size_t len = strcspn(p, ",");
        double deg;
        if (len == 0 || len >= sizeof word ||
            o->n_incidence == BF_FIG_MAX_INCIDENCE) {
            return -1;
        }
        memcpy(word, p, len);
        word[len] = '\0';
        if (bf_cli_parse_double(word, &deg) != 0 || deg < 0.0 ||
            deg > MAX_INCIDENCE_DEG) {
            return -1;
        }
        o->incidence[o->n_incidence++] = deg * DEG;
        p += len;
        if (*p == ',' && *++p == '\0') {
            return -1;
        }
    }
    return o->n_incidence > 0 ? 0 : -1;
}

static int handle(int val, const char *arg, void *ctx)
{
    bf_fig_opts *o = ctx;
    switch (val) {
    case O_FORMAT:
        if (parse_formats(arg, &o->formats) != 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, "report ", "--format: '%s' is not a "
                                      "list of png, svg, pdf", arg);
        }
        return 0;
    case O_SIZE:
        if (strcmp(arg, "double") == 0) {
            o->width = BF_PLOT_DOUBLE_COLUMN;
        } else if (strcmp(arg, "single") == 0) {
            o->width = BF_PLOT_SINGLE_COLUMN;
        } else {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, "report ",
                                     "--size: '%s' is not single or double",
                                     arg);
        }
        return 0;
    case O_LOG: o->log_lse = 1; return 0;
    case O_PER_SAMPLE: o->per_sample = 1; return 0;
    case O_INCIDENCE:
        if (parse_incidence(arg, o) != 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, "report ", "--incidence: '%s' is not a "
                                      "list of 1 to %d angles in [0, %g] "
                                      "degrees",
                                      arg, BF_FIG_MAX_INCIDENCE,
                                      MAX_INCIDENCE_DEG);
        }
        return 0;
    default: return BF_EXIT_SOFTWARE;
    }
}

/* Writes report.html into the output folder's temporary file o. */
static int write_page(const bf_cli_study *st, const bf_fig_set *figs,
                      const bf_report_meta *meta, bf_out *o)
{
    int rc = bf_out_open(o, st->opts.out_dir, "report.html");
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    if (bf_report_html(st, figs, meta, o->fp) != 0) {
        bf_cli_err("%s: write failed", o->path);
        bf_out_abort(o);
        return BF_EXIT_IOERR;
    }
    return BF_EXIT_OK;
}

int bf_cmd_report(int argc, char **argv)
{
    bf_cli_study st;
    bf_fig_opts fo;
    bf_fig_set figs;
    bf_report_meta meta;
    bf_cli_extra extra;
    bf_out page;
    int page_open = 0;
    int started = 0;
    int rc;

    memset(&st, 0, sizeof st);
    memset(&fo, 0, sizeof fo);
    memset(&figs, 0, sizeof figs);
    memset(&meta, 0, sizeof meta);
    fo.formats = (1u << BF_PLOT_PNG) | (1u << BF_PLOT_PDF);
    fo.width = BF_PLOT_DOUBLE_COLUMN;
    fo.progress = isatty(STDERR_FILENO);
    extra.longopts = report_opts;
    extra.handle = handle;
    extra.ctx = &fo;
    st.cmd = "report";
    rc = bf_cli_opts_parse(st.cmd, argc, argv, usage, &extra, &st.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    meta.argc = argc;
    meta.argv = argv;
    meta.fig = &fo;

    rc = bf_cli_study_prepare(&st);
    if (rc == BF_EXIT_OK && fo.n_incidence == 0) {
        rc = bf_figures_choose_incidence(&st, &fo);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_report_checksums(&st, &meta);
    }
    if (rc == BF_EXIT_OK) {
        if (fo.progress) {
            fprintf(stderr, "brdffit report: fitting %zu models to %zu "
                            "samples...\n",
                    st.n_models, st.n_samples);
        }
        rc = bf_cli_study_run_protocol(&st);
    }
    /* Everything is drawn and written to temporary files first, then
     * renamed into place: a failure leaves no partial output. The paper's
     * figures are drawn while the analysis runs (with --fit exact the
     * analysis is the study: the figures wait for it). */
    fo.jobs = st.spec.n_threads > 1 ? st.spec.n_threads : 1;
    fo.jobs = fo.jobs > MAX_JOBS ? MAX_JOBS : fo.jobs;
    if (rc == BF_EXIT_OK && !st.opts.exact) {
        rc = bf_figures_start(&st, &fo, st.opts.out_dir, &figs, 0);
        started = rc == BF_EXIT_OK;
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_study_run_analysis(&st);
    }
    if (rc == BF_EXIT_OK && !started) {
        rc = bf_figures_start(&st, &fo, st.opts.out_dir, &figs, 1);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_figures_finish(&st, &figs);
    }
    if (rc == BF_EXIT_OK) {
        rc = write_page(&st, &figs, &meta, &page);
        page_open = rc == BF_EXIT_OK;
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_study_write_tables(&st);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_figures_commit(&figs);
    }
    if (rc == BF_EXIT_OK) {
        page_open = 0;
        rc = bf_out_commit(&page);
    }
    if (page_open) {
        bf_out_abort(&page);
    }
    if (rc == BF_EXIT_OK && !st.opts.quiet) {
        printf("Written: %s/report.html and %zu figures in %s/%s\n",
               st.opts.out_dir, figs.n, st.opts.out_dir, BF_FIG_DIR);
    }
    bf_figures_free(&figs);
    bf_cli_study_free(&st);
    return rc;
}
