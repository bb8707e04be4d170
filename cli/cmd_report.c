/* cmd_report.c: `brdffit report` -- parses the options of the study of
 * SPEC §7 (as `compare`) and of the figures, and calls the report
 * library's bf_report_write, which writes into the output folder the
 * tables (fits.csv, table2.md, table3.md), every figure (figures/: Figure
 * 2(b), Figures 3-6, the model-wins chart, per-sample plane-of-incidence
 * views and, with the analysis, forest plots, profiles and the delta-BIC
 * overview) in PNG and PDF (SVG on request), and report.html. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "setup.h"

#define DEG (M_PI / 180.0)

/* Largest incidence angle accepted by --incidence, degrees (the original
 * BK models diverge at grazing incidence, SPEC §3.3). */
#define MAX_INCIDENCE_DEG 89.0

enum {
    O_FORMAT = 512,
    O_LOG,
    O_PER_SAMPLE,
    O_INCIDENCE,
    O_SIZE,
    O_CALIBRATE
};

static const struct option report_opts[] = {
    {"format", required_argument, NULL, O_FORMAT},
    {"size", required_argument, NULL, O_SIZE},
    {"log", no_argument, NULL, O_LOG},
    {"per-sample", no_argument, NULL, O_PER_SAMPLE},
    {"incidence", required_argument, NULL, O_INCIDENCE},
    {"calibrate", required_argument, NULL, O_CALIBRATE},
    {NULL, 0, NULL, 0}};

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit report [OPTIONS] [FILE...]\n"
"\n"
"Run the study of 'brdffit compare' and write into the output folder its\n"
"tables (fits.csv, table2.md, table3.md, dispersion.csv when it has\n"
"one), report.html (one page with the\n"
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
"  polar_sampleN   of incidence, Cartesian and polar, per incidence angle;\n"
"                  at most six curves a figure: the diffuse models, then\n"
"                  _diffuse2, the specular ones in _specular, _specular2\n"
"  scatter_sampleN one sample's scatter panels (--per-sample)\n"
"With the analysis (--stats, --fit exact, --bootstrap, --calibrate):\n"
"  delta_bic       samples x models, BIC minus each sample's best\n"
"  forest_MODEL    each sample's fitted parameters with their 95%\n"
"                  profile (and bootstrap) intervals (both continued in\n"
"                  delta_bic_2, forest_MODEL_2, ... when rows fill a page)\n"
"  profile_sampleN the profile n ln(S/S_min) along each fitted parameter\n"
"                  with the 95% threshold 3.84 (specular models:\n"
"                  profile_sampleN_specular; 15 panels a figure)\n"
"  dispersion_sampleN  with dispersion.csv (--fresnel dielectric, or\n"
"                  ABC's ior, on spectral channels): n against\n"
"                  wavelength, the 95%\n"
"                  intervals as error bars (joint: one line)\n"
"With --calibrate N:\n"
"  calibration_sampleN  each fitted parameter's estimates from N simulated\n"
"                  measurements against the fit's 95% interval and the\n"
"                  fitted value simulated (more panels than a page holds:\n"
"                  continued in calibration_sampleN_2, ...)\n"
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
"  --calibrate N     check the intervals on N simulated measurements of\n"
"                    every fit (as 'brdffit calibrate --sims N', N >= 10;\n"
"                    0: off, the default): calibrate.csv, a table and a\n"
"                    figure per sample; runs the analysis (implies\n"
"                    --stats); costs N refits per (sample, model) pair,\n"
"                    on --threads threads\n"
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
        for (f = 0; f <= BF_REPORT_PDF; f++) {
            static const char *const exts[] = {"png", "svg", "pdf"};
            const char *ext = exts[f];
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

static int parse_incidence(const char *arg, bf_report_options *o)
{
    const char *p = arg;
    o->n_incidence = 0;
    while (*p != '\0') {
        char word[64];
        size_t len = strcspn(p, ",");
        double deg;
        if (len == 0 || len >= sizeof word ||
            o->n_incidence == BF_REPORT_MAX_INCIDENCE) {
            return -1;
        }
        memcpy(word, p, len);
        word[len] = '\0';
        if (bf_rep_parse_double(word, &deg) != 0 || deg < 0.0 ||
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
    bf_report_options *o = ctx;
    switch (val) {
    case O_FORMAT:
        if (parse_formats(arg, &o->formats) != 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, "report ", "--format: '%s' is not a "
                                      "list of png, svg, pdf", arg);
        }
        return 0;
    case O_SIZE:
        if (strcmp(arg, "double") == 0) {
            o->single_column = 0;
        } else if (strcmp(arg, "single") == 0) {
            o->single_column = 1;
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
                                      arg, BF_REPORT_MAX_INCIDENCE,
                                      MAX_INCIDENCE_DEG);
        }
        return 0;
    case O_CALIBRATE: {
        char *end = NULL;
        long v = strtol(arg, &end, 10);
        if (end == arg || *end != '\0' || v < 0 || v > 1000000) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, "report ",
                                     "--calibrate: '%s' is not a number of "
                                     "simulations from 0 to 1000000", arg);
        }
        o->calibrate = (size_t)v; /* the library refuses 1-9 */
        return 0;
    }
    default: return BF_EXIT_SOFTWARE;
    }
}

int bf_cmd_report(int argc, char **argv)
{
    static char hint[] = "report ";
    bf_report_options fig = BF_REPORT_OPTIONS_INIT; /* report's own */
    bf_report_options ro;
    bf_report_inputs in;
    bf_cli_extra extra;
    bf_cli_run r;
    size_t n_figures = 0;
    size_t i;
    int rc;

    memset(&r, 0, sizeof r);
    extra.longopts = report_opts;
    extra.handle = handle;
    extra.ctx = &fig;
    rc = bf_cli_opts_parse("report", argc, argv, usage, &extra, &r.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    bf_cli_report_options(&r, &ro, &in);
    ro.formats = fig.formats;
    ro.single_column = fig.single_column;
    ro.log_lse = fig.log_lse;
    ro.per_sample = fig.per_sample;
    ro.calibrate = fig.calibrate;
    ro.n_incidence = fig.n_incidence;
    for (i = 0; i < fig.n_incidence; i++) {
        ro.incidence[i] = fig.incidence[i];
    }
    ro.argc = argc;
    ro.argv = argv;
    ro.message = bf_cli_message;
    ro.message_ctx = hint;
    rc = bf_report_write(&in, &ro, r.opts.out_dir, &n_figures, NULL);
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        printf("Written: %s/report.html and %zu figures in %s/figures\n",
               r.opts.out_dir, n_figures, r.opts.out_dir);
    }
    bf_cli_run_free(&r);
    return rc;
}
