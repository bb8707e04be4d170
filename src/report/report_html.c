/* report_html.c: report.html (report_html.h) -- the page: contents, the
 * data it was given, tables, figures with captions, the analysis, the
 * per-sample figures in collapsible sections, conventions (SPEC §1.4, §2,
 * §4, §7) and provenance, in one page that opens from disk. */
#include "calibration.h"
#include "energy.h"
#include "report_html.h"
#include "texttable.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define DEG (M_PI / 180.0)
/* Figures are shown at twice their size in points, in CSS pixels (a
 * double-column figure 1008 pixels wide): 1.5 times print size. */
#define CSS_PX_PER_PT 2

/* Writes an argument as a POSIX shell word (quoted when needed). */
static void put_shell_word(FILE *fp, const char *s)
{
    const char *safe = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                       "0123456789-_./,=:+%@";
    if (s[0] != '\0' && strspn(s, safe) == strlen(s)) {
        bf_tt_html_text(fp, s);
        return;
    }
    fputc('\'', fp);
    for (; *s != '\0'; s++) {
        if (*s == '\'') {
            fputs("'\\''", fp);
        } else {
            char c[2] = {*s, '\0'};
            bf_tt_html_text(fp, c);
        }
    }
    fputc('\'', fp);
}

/* Set when a part of the page could not be formed for want of memory:
 * bf_report_html then fails (the page would be incomplete). */
static int page_oom;

/* ==== provenance ========================================================= */

static int add_input(bf_report_meta *meta, const char *role, const char *path)
{
    bf_report_input *in;
    struct stat sb;
    if (meta->n_inputs >= BF_REPORT_MAX_INPUTS) {
        return BF_REPORT_SOFTWARE;
    }
    in = &meta->inputs[meta->n_inputs];
    in->role = role;
    snprintf(in->path, sizeof in->path, "%s", path);
    if (stat(path, &sb) != 0) {
        bf_rep_err("%s: cannot read to compute its checksum", path);
        return BF_REPORT_NOINPUT;
    }
    switch (bf_sha256_file(path, in->sha256)) {
    case BF_OK:
        break;
    case BF_ENOMEM:
        bf_rep_err("%s: cannot compute its checksum: out of memory", path);
        return BF_REPORT_SOFTWARE;
    default:
        bf_rep_err("%s: cannot read to compute its checksum", path);
        return BF_REPORT_NOINPUT;
    }
    in->size = (long long)sb.st_size;
    meta->n_inputs++;
    return BF_REPORT_OK;
}

int bf_report_checksums(const bf_rep_study *st, bf_report_meta *meta)
{
    int rc = BF_REPORT_OK;
    size_t i;
    meta->n_inputs = 0;
    if (st->in.curet) {
        rc = add_input(meta, "configuration table", st->in.table_path);
        if (rc == BF_REPORT_OK) {
            rc = add_input(meta, "BRDF values", st->in.brdf_path);
        }
        if (rc == BF_REPORT_OK && st->in.names_path[0] != '\0') {
            rc = add_input(meta, "sample names", st->in.names_path);
        }
    } else {
        for (i = 0; rc == BF_REPORT_OK && i < st->in.n_files; i++) {
            rc = add_input(meta, "measurements", st->in.files[i]);
        }
        if (rc == BF_REPORT_OK && st->in.configs_path[0] != '\0' &&
            strcmp(st->in.configs_path, "all") != 0) {
            rc = add_input(meta, "MERL sampling configurations",
                           st->in.configs_path);
        }
    }
    if (rc == BF_REPORT_OK && st->opts.on_file != NULL) {
        rc = add_input(meta, "Oren-Nayar parameters", st->opts.on_file);
    }
    if (rc == BF_REPORT_OK && st->opts.n_file != NULL) {
        rc = add_input(meta, "refractive indices", st->opts.n_file);
    }
    return rc;
}

static void provenance(FILE *fp, const bf_report_meta *meta)
{
    size_t i;
    int a;
    fputs("<h2 id=\"provenance\">Provenance</h2>\n<ul>\n", fp);
    fprintf(fp, "<li>brdffit %s</li>\n", bf_version());
    if (meta->argc == 0) { /* not from the command line */
        fputs("<li>Written by <code>bf_report_write</code></li>\n", fp);
    } else {
        fputs("<li>Command: <code>brdffit", fp);
        for (a = 0; a < meta->argc; a++) {
            fputc(' ', fp);
            put_shell_word(fp, meta->argv[a]);
        }
        fputs("</code></li>\n", fp);
    }
    fputs("</ul>\n<table id=\"inputs\">\n<thead><tr>"
          "<th>Input</th><th>File</th><th>Bytes</th><th>SHA-256</th></tr>"
          "</thead>\n<tbody>\n",
          fp);
    for (i = 0; i < meta->n_inputs; i++) {
        const bf_report_input *in = &meta->inputs[i];
        fputs("<tr><td>", fp);
        bf_tt_html_text(fp, in->role);
        fputs("</td><td><code>", fp);
        bf_tt_html_text(fp, in->path);
        fprintf(fp, "</code></td><td class=\"n\">%lld</td><td><code>%s"
                    "</code></td></tr>\n",
                in->size, in->sha256);
    }
    fputs("</tbody>\n</table>\n", fp);
}

/* ==== page parts ========================================================= */

static const char *style =
    "body{font-family:sans-serif;max-width:1100px;margin:1em auto;"
    "padding:0 1em;color:#111;line-height:1.4}"
    /* a table wider than the page scrolls in its own box */
    "table{border-collapse:collapse;margin:.5em 0 1.5em;font-size:90%;"
    "display:block;max-width:100%;overflow-x:auto}"
    "th,td{border:1px solid #bbb;padding:2px 6px}th{background:#f2f2f2}"
    "td.n{text-align:right;font-variant-numeric:tabular-nums}"
    "td.best{font-weight:bold;background:#e6f0fa}"
    "figure{margin:1em 0 2em}img{max-width:100%;height:auto}"
    "figcaption{font-size:90%;color:#333;max-width:60em}"
    "code,pre{background:#f4f4f4}pre{padding:.5em;overflow-x:auto}"
    "details{margin:.3em 0;border:1px solid #ddd;padding:.2em .6em}"
    "summary{cursor:pointer;font-weight:bold}"
    "nav ol{margin-top:0}";

/* Sets, once every image has loaded, whether all did (read by `make
 * screenshot` through the DOM). */
static const char *script =
    "window.addEventListener('load',function(){var im=document.images,"
    "ok=0,i;for(i=0;i<im.length;i++){if(im[i].complete&&"
    "im[i].naturalWidth>0){ok++;}}document.body.setAttribute("
    "'data-images',ok+'/'+im.length);document.body.setAttribute("
    "'data-images-ok',ok===im.length?'yes':'no');});";

/* The format shown inline: PNG, else SVG; -1 when only PDF was drawn. */
static int inline_format(unsigned formats)
{
    if (formats & (1u << BF_PLOT_PNG)) {
        return BF_PLOT_PNG;
    }
    if (formats & (1u << BF_PLOT_SVG)) {
        return BF_PLOT_SVG;
    }
    return -1;
}

static void figure(FILE *fp, const bf_fig_set *figs, const bf_fig_entry *e)
{
    int show = inline_format(figs->formats);
    int f;
    fprintf(fp, "<figure id=\"%s\">\n", e->base);
    if (show >= 0) {
        fprintf(fp, "<img src=\"%s/%s.%s\" width=\"%u\" height=\"%u\" alt=\"",
                BF_FIG_DIR, e->base, bf_plot_format_ext((bf_plot_format)show),
                e->width * CSS_PX_PER_PT, e->height * CSS_PX_PER_PT);
        bf_tt_html_text(fp, e->alt);
        fputs("\">\n", fp);
    }
    fputs("<figcaption><b>", fp);
    bf_tt_html_text(fp, e->title);
    fputs(".</b> ", fp);
    bf_tt_html_text(fp, e->caption);
    fputs(" Files:", fp);
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        const char *ext = bf_plot_format_ext((bf_plot_format)f);
        if (figs->formats & (1u << f)) {
            fprintf(fp, " <a href=\"%s/%s.%s\">%s</a>", BF_FIG_DIR, e->base,
                    ext, ext);
        }
    }
    fprintf(fp, " (%u \xc3\x97 %u pt).</figcaption>\n</figure>\n", e->width,
            e->height);
}

/* Every figure of the kind; with index != SIZE_MAX only the one of that
 * index (the sample of per-sample kinds, the model of forest plots). */
static void figures_of(FILE *fp, const bf_fig_set *figs, bf_fig_kind kind,
                       size_t index)
{
    size_t i;
    for (i = 0; i < figs->n; i++) {
        if (figs->fig[i].kind == kind &&
            (index == SIZE_MAX || figs->fig[i].index == index)) {
            figure(fp, figs, &figs->fig[i]);
        }
    }
}

/* The configurations target s does not use, as "54, 97, ...", or
 * "none". */
static void left_out(FILE *fp, const bf_rep_study *st, size_t s)
{
    size_t mat = st->targets[s].material;
    size_t nconf = bf_dataset_nconf(st->in.ds, mat);
    size_t *sel = malloc((nconf + 1) * sizeof *sel);
    double *data = malloc((nconf + 1) * sizeof *data);
    size_t K = 0;
    size_t j = 0;
    size_t k;
    int first = 1;
    if (sel == NULL || data == NULL) {
        page_oom = 1;
    }
    if (sel != NULL && data != NULL &&
        bf_rep_target_data(st, s, sel, &K, data) == BF_OK) {
        for (k = 0; k < nconf; k++) {
            if (j < K && sel[j] == k) {
                j++;
                continue;
            }
            fprintf(fp, "%s%zu", first ? "" : ", ", k + 1);
            first = 0;
        }
    }
    if (first) {
        fputs("none", fp);
    }
    free(sel);
    free(data);
}

/* Whether every target uses the same configurations of the same list. */
static int one_selection(const bf_rep_study *st)
{
    size_t s;
    for (s = 1; s < st->n_samples; s++) {
        if (bf_dataset_set(st->in.ds, st->targets[s].material) !=
                bf_dataset_set(st->in.ds, st->targets[0].material) ||
            st->k[s] != st->k[0]) {
            return 0;
        }
    }
    return st->n_samples > 0;
}

/* What the run was given: the data (format, files, names), the samples,
 * the models, the configurations used and left out. */
static void data_section(FILE *fp, const bf_rep_study *st)
{
    const bf_report_inputs *in = &st->in;
    const bf_dataset *ds = in->ds;
    char cone[512];
    size_t m;
    size_t s;
    fputs("<h2 id=\"data\">Data</h2>\n<ul>\n", fp);
    if (in->curet) {
        fputs("<li>Format: CURET (the Columbia-Utrecht Reflectance and "
              "Texture database; K. J. Dana et al., ACM TOG 18(1), 1999): "
              "<code>",
              fp);
        bf_tt_html_text(fp, in->table_path);
        fprintf(fp, "</code> (%zu illumination and viewing configurations) "
                    "and <code>",
                bf_dataset_nconf(ds, 0));
        bf_tt_html_text(fp, in->brdf_path);
        fprintf(fp, "</code> (BRDF values of %zu samples); names %s.</li>\n",
                bf_dataset_count(ds),
                in->names_path[0] != '\0'
                    ? "from samples.tsv"
                    : "by number (no samples.tsv in the data folder)");
    } else {
        fprintf(fp, "<li>%zu material%s from %zu file%s:<ul>\n",
                bf_dataset_count(ds), bf_dataset_count(ds) == 1 ? "" : "s",
                st->in.n_files, st->in.n_files == 1 ? "" : "s");
        for (m = 0; m < bf_dataset_count(ds); m++) {
            size_t nc = bf_dataset_nchannels(ds, m);
            char who[256];
            bf_rep_material_label(ds, m, who, sizeof who);
            fputs("<li>", fp);
            bf_tt_html_text(fp, who);
            fprintf(fp, ": format %s, <code>",
                    bf_format_name(bf_dataset_format(ds, m)));
            bf_tt_html_text(fp, bf_dataset_source(ds, m));
            fprintf(fp, "</code>, %zu configurations, %zu channel%s",
                    bf_dataset_nconf(ds, m), nc, nc == 1 ? "" : "s");
            if (nc > 1) {
                fputs(" (", fp);
                bf_tt_html_text(fp, bf_dataset_channel(ds, m, 0));
                fputs(" … ", fp);
                bf_tt_html_text(fp, bf_dataset_channel(ds, m, nc - 1));
                fputs(")", fp);
            }
            fputs("</li>\n", fp);
        }
        fputs("</ul></li>\n", fp);
    }
    fprintf(fp, "<li>Fitted: %zu sample%s (channel: ", st->n_samples,
            st->n_samples == 1 ? "" : "s");
    bf_tt_html_text(fp, st->opts.channel != NULL ? st->opts.channel
                                                 : "mean of the channels");
    fprintf(fp, "), %zu model%s (", st->n_models,
            st->n_models == 1 ? "" : "s");
    for (m = 0; m < st->n_models; m++) {
        fputs(m ? ", " : "", fp);
        bf_tt_html_text(fp, st->models[m]->name);
    }
    fputs(").</li>\n", fp);
    bf_rep_describe_cone(st, cone, sizeof cone);
    fputs("<li>Specular exclusion: ", fp);
    bf_tt_html_text(fp, cone);
    fputs(".</li>\n", fp);
    if (one_selection(st)) {
        size_t nconf = bf_dataset_nconf(ds, st->targets[0].material);
        fprintf(fp, "<li>Configurations used: K = %zu of %zu; left out "
                    "(specular, <code>--exclude</code>, "
                    "<code>--max-theta</code>, invalid values): ",
                st->k[0], nconf);
        left_out(fp, st, 0);
        fputs(".</li>\n", fp);
    } else {
        size_t lo = SIZE_MAX;
        size_t hi = 0;
        for (s = 0; s < st->n_samples; s++) {
            lo = st->k[s] < lo ? st->k[s] : lo;
            hi = st->k[s] > hi ? st->k[s] : hi;
        }
        if (lo == hi) { /* different configurations, as many of each */
            fprintf(fp, "<li>Configurations used: K = %zu for every "
                        "sample", lo);
        } else {
            fprintf(fp, "<li>Configurations used: K from %zu to %zu per "
                        "sample", lo, hi);
        }
        fputs(" (each sample's list is in the run's description, under "
              "Conventions).</li>\n", fp);
    }
    fputs("</ul>\n", fp);
}

/* The conventions' Fresnel and Oren-Nayar lines, each only when a model
 * of the run has such an input. */
static void input_conventions(FILE *fp, const bf_rep_study *st)
{
    unsigned n_use = bf_rep_input_use(st, BF_INPUT_INDEX);
    unsigned on_use = bf_rep_input_use(st, BF_INPUT_ON);
    const char *sep = "";
    if (n_use != 0) {
        fputs("<li>Fresnel reflectance with the factor ½ (SPEC §4.1): ", fp);
    }
    if ((n_use & BF_REP_INPUT_HELD) && st->opts.n_file != NULL) {
        fputs("refractive index per sample from <code>", fp);
        bf_tt_html_text(fp, st->opts.n_file);
        fputs("</code>", fp);
        sep = "; ";
    } else if (n_use & BF_REP_INPUT_HELD) {
        fprintf(fp, "refractive index n = %g for every sample (SPEC §4.2)",
                st->opts.n);
        sep = "; ";
    }
    if (n_use & BF_REP_INPUT_FREED) {
        fprintf(fp, "%sFC's refractive index n fitted per sample (the exact "
                    "fit frees it, doc/methods.md §6: its range under \"Free "
                    "parameters\" in the run's description)",
                sep);
        sep = "; ";
    }
    if (n_use & BF_REP_INPUT_OWN) {
        fprintf(fp, "%sthe refractive index a model has as its own "
                    "parameter (a specular model's n under --fresnel "
                    "dielectric, ABC's ior, WNO's n) fitted per sample",
                sep);
    }
    if (n_use != 0) {
        fputs(".</li>\n", fp);
    }
    if (on_use & BF_REP_INPUT_FREED) {
        fputs("<li>Oren–Nayar (ON): ρ and σ fitted per sample (the exact "
              "fit frees them, doc/methods.md §6), not taken from a "
              "table.</li>\n",
              fp);
    } else if (on_use != 0) {
        fputs("<li>Oren–Nayar (ON) is evaluated, not fitted, at tabulated "
              "ρ, σ (SPEC §5)",
              fp);
        if (st->opts.on_file != NULL) {
            fputs(" from <code>", fp);
            bf_tt_html_text(fp, st->opts.on_file);
            fputs("</code>", fp);
        }
        fputs(".</li>\n", fp);
    }
}

static void conventions(FILE *fp, const bf_rep_study *st,
                        const bf_report_meta *meta)
{
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    size_t a;

    fputs("<h2 id=\"conventions\">Conventions</h2>\n<ul>\n", fp);
    if (bf_objective_keeps_scale(st->opts.objective)) {
        fprintf(fp, "<li>Objective %s (SPEC §10): the measured ρ = BRDF × "
                "cos θ<sub>i</sub> as measured on the configurations with "
                "θ<sub>i</sub>, θ<sub>o</sub> ≤ 80°, nothing normalised; "
                "each model's ρ̂ carries its fitted scales. The plane and "
                "polar figures show ρ and ρ̂ in these absolute units; the "
                "predicted-against-measured figures (Figures 3–6) show "
                "radiance divided by its maximum over the K used "
                "configurations (SPEC §2).</li>\n",
                bf_objective_name(st->opts.objective));
    } else {
        fputs("<li>Measured radiance = BRDF × cos θ<sub>i</sub>, divided by "
              "its maximum over the K used configurations; every model "
              "curve is divided by its own maximum over the same "
              "configurations, so the models' scale constants cancel (SPEC "
              "§2). Every figure shows radiance normalised this way.</li>\n",
              fp);
    }
    if (st->opts.objective == BF_OBJ_NGAN) {
        fputs("<li>E = √(Σ<sub>k</sub> (ρ<sub>k</sub> − ρ̂<sub>k</sub>)² / "
              "K), over each sample's K used configurations (SPEC §10); "
              "Table 3 and the figures give each fit's E.</li>\n",
              fp);
    } else if (st->opts.objective != BF_OBJ_MAX) {
        fprintf(fp, "<li>S, the sum of the %s objective over the K used "
                    "configurations (doc/methods.md §1); Table 3 and the "
                    "figures give each fit's S.</li>\n",
                bf_objective_name(st->opts.objective));
    } else {
        fputs("<li>LSE = Σ<sub>k</sub> (L<sub>model,k</sub> − "
              "L<sub>data,k</sub>)², a sum over the K configurations (SPEC "
              "§7.3).</li>\n",
              fp);
    }
    if (bf_rep_n_specular(st) < st->n_models) { /* a gridded model */
        fprintf(fp, "<li>Exhaustive grids (SPEC §7.4): slope m = σ/T = 0.1 "
                    "+ 0.01 i, Lafortune exponent n<sub>d</sub> = 0.1 + 0.04 "
                    "i, i = 0…500; ties keep the smaller value; %s. The "
                    "slopes of the Gaussian (G) and exponential (E) forms "
                    "are different quantities.</li>\n",
                st->opts.exact ? "the exact fit refines each grid optimum, "
                                 "and * in Table 2 marks an optimum on a "
                                 "bound of the search range"
                               : "* in Table 2 marks an optimum on a grid "
                                 "bound");
    }
    input_conventions(fp, st);
    if (meta->fig->n_incidence == 0) {
        fputs("<li>Plane-of-incidence figures: none, no measured "
              "configuration lies in its plane of incidence.</li>\n", fp);
    } else {
        fputs("<li>Plane-of-incidence figures: incidence angles", fp);
        for (a = 0; a < meta->fig->n_incidence; a++) {
            fprintf(fp, "%s %.2f°", a ? "," : "",
                    meta->fig->incidence[a] / DEG);
        }
        if (meta->fig->incidence_chosen) {
            fputs(" (chosen from the data: those with the most measured "
                  "configurations in their plane of incidence, spread over "
                  "their range)", fp);
        }
        fputs("; θ<sub>s</sub> &gt; 0 on the forward (specular) side, "
              "Beckmann's frame (SPEC §1.2).</li>\n", fp);
    }
    fprintf(fp, "<li>Figures are drawn at print size, %s column (%u pt = "
                "%.1f in wide), with %g-point text; PNG at %d pixels per "
                "inch, PDF%s vector.</li>\n</ul>\n",
            meta->fig->width == BF_PLOT_SINGLE_COLUMN ? "single" : "double",
            meta->fig->width, meta->fig->width / 72.0, BF_PLOT_FONT,
            BF_PLOT_PNG_DPI,
            (meta->fig->formats & (1u << BF_PLOT_SVG)) ? " and SVG" : "");
    if (mem == NULL || bf_rep_study_describe(st, mem) != BF_REPORT_OK ||
        ferror(mem)) {
        page_oom = 1;
    }
    /* glibc's memstream may lose the buffered text to a failed final
     * flush and still close: the description is never empty */
    if (mem != NULL && (fclose(mem) != 0 || text == NULL || len == 0)) {
        page_oom = 1;
    }
    if (!page_oom) {
        fputs("<p>The run, as printed by brdffit:</p>\n<pre>", fp);
        bf_tt_html_text(fp, text);
        fputs("</pre>\n", fp);
    }
    free(text);
}

/* --calibrate: the table, then each sample's figures (collapsed when
 * there are several samples). */
static void calibration(FILE *fp, const bf_rep_study *st,
                        const bf_fig_set *figs)
{
    size_t s;
    size_t i;
    fputs("<h3 id=\"calibration-section\">Are the intervals calibrated? "
          "Simulated measurements</h3>\n", fp);
    if (bf_report_calibration(fp, st) != 0) {
        page_oom = 1;
    }
    for (s = 0; s < st->n_samples; s++) {
        char who[256];
        for (i = 0; i < figs->n && (figs->fig[i].kind != BF_FIG_CALIBRATION ||
                                    figs->fig[i].index != s);
             i++) {
        }
        if (i == figs->n) {
            continue; /* nothing calibrated */
        }
        if (st->n_samples > 1) {
            fputs("<details>\n<summary>", fp);
            bf_tt_html_text(fp, bf_fig_sample_label(st, s, who, sizeof who));
            fputs(": simulated estimates against the interval</summary>\n",
                  fp);
        }
        figures_of(fp, figs, BF_FIG_CALIBRATION, s);
        fputs(st->n_samples > 1 ? "</details>\n" : "", fp);
    }
}

/* The energy table (energy.h) when some fit is specular. */
static void energy_table(FILE *fp, const bf_rep_study *st)
{
    size_t n;
    size_t over;
    bf_tt *t = bf_rep_energy_table(&st->spec, st->rows, &n, &over);
    if (t == NULL) {
        return;
    }
    fputs("<h3 id=\"energy\">", fp);
    bf_tt_html_text(fp, BF_REP_ENERGY_TITLE);
    fprintf(fp, "</h3>\n<p>%zu of %zu specular fits exceed 1 somewhere: "
                "the albedo a(theta_i) = ∫ f cos theta_o dω of the fitted "
                "specular model (a composite's diffuse part left out; AS "
                "with its own diffuse term, SPEC §9.3), by quadrature "
                "(fits.csv's albedo columns).</p>\n",
            over, n);
    bf_tt_print_html(t, "energy-table", fp);
    bf_tt_free(t);
}

/* n against wavelength (--fresnel dielectric on spectral channels), when
 * some material has it. */
static void dispersion(FILE *fp, const bf_fig_set *figs)
{
    size_t i;
    for (i = 0; i < figs->n && figs->fig[i].kind != BF_FIG_DISPERSION; i++) {
    }
    if (i == figs->n) {
        return;
    }
    fputs("<h3 id=\"dispersion-section\">Dispersion: n against "
          "wavelength</h3>\n<p>The refractive index of the dielectric "
          "Fresnel factor (n under --fresnel dielectric, ABC's ior) fitted "
          "on each spectral channel, with its 95% "
          "interval; the values are in <a href=\"dispersion.csv\">"
          "dispersion.csv</a>. It is the index of a smooth outermost "
          "interface seen through one specular lobe: read "
          "doc/methods.md “Dispersion” before reading it as the binder's.</p>"
          "\n",
          fp);
    figures_of(fp, figs, BF_FIG_DISPERSION, SIZE_MAX);
}

/* The analysis beyond the paper: model selection and intervals. */
static void analysis(FILE *fp, const bf_rep_study *st, const bf_fig_set *figs)
{
    size_t m;
    fputs("<h2 id=\"analysis\">Analysis beyond the paper</h2>\n", fp);
    if (st->stats == NULL) {
        fputs("<p>Not computed: run with <code>--stats</code> (or "
              "<code>brdffit rank</code>) for refined optima, 95% intervals, "
              "AIC, BIC and cross-validation.</p>\n",
              fp);
        return;
    }
    fputs("<h3 id=\"selection\">Model selection</h3>\n", fp);
    figures_of(fp, figs, BF_FIG_DELTA_BIC, SIZE_MAX);
    bf_report_selection(fp, st);
    fputs("<h3 id=\"intervals-section\">Fitted parameters and their "
          "intervals</h3>\n",
          fp);
    for (m = 0; m < st->n_models; m++) {
        figures_of(fp, figs, BF_FIG_FOREST, m);
    }
    fputs("<details>\n<summary>The same as a table: each sample's grid and "
          "exact optima with their 95% intervals (\"(Neyman)\": the Neyman "
          "construction's, each end's threshold simulated; by default where "
          "two minima of the profile compete; fits.csv ci_method "
          "neyman)</summary>\n",
          fp);
    bf_report_intervals(fp, st);
    fputs("</details>\n", fp);
    dispersion(fp, figs);
    if (st->opts.calibrate > 0) {
        calibration(fp, st, figs);
    }
}

/* One collapsible section per sample with its figures. */
static void per_sample(FILE *fp, const bf_rep_study *st,
                       const bf_fig_set *figs)
{
    size_t s;
    fputs("<h2 id=\"samples\">Per sample</h2>\n<p>Each sample's figures "
          "(open a section to see them): the fitted models in the plane of "
          "incidence, Cartesian and polar",
          fp);
    fputs(st->stats != NULL ? ", and the profiles behind the intervals" : "",
          fp);
    fputs(".</p>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        char key[64];
        char who[256];
        fprintf(fp, "<details id=\"%s\">\n<summary>",
                bf_fig_target_key(st, s, key, sizeof key));
        bf_tt_html_text(fp, bf_fig_sample_label(st, s, who, sizeof who));
        fputs("</summary>\n", fp);
        figures_of(fp, figs, BF_FIG_SAMPLE, s);
        figures_of(fp, figs, BF_FIG_PLANE, s);
        figures_of(fp, figs, BF_FIG_POLAR, s);
        figures_of(fp, figs, BF_FIG_PROFILE, s);
        fputs("</details>\n", fp);
    }
}

static void contents(FILE *fp, const bf_rep_study *st)
{
    fputs("<nav aria-label=\"Contents\">\n<h2>Contents</h2>\n<ol>\n"
          "<li><a href=\"#data\">Data</a></li>\n"
          "<li><a href=\"#tables\">Tables 2 and 3</a></li>\n"
          "<li><a href=\"#figures\">Figures</a>: <a href=\"#fig2b\">Figure "
          "2(b)</a>, <a href=\"#wins\">samples fitted best</a>, <a href=\""
          "#scatter\">Figures 3–6</a></li>\n"
          "<li><a href=\"#analysis\">Analysis beyond the paper</a>",
          fp);
    if (st->stats != NULL) {
        fputs(": <a href=\"#selection\">model selection</a>, <a href=\""
              "#intervals-section\">fitted parameters and intervals</a>",
              fp);
        fputs(st->opts.calibrate > 0 ? ", <a href=\"#calibration-section\">"
                                       "calibration</a>"
                                     : "",
              fp);
    }
    fputs("</li>\n<li><a href=\"#samples\">Per sample</a></li>\n"
          "<li><a href=\"#conventions\">Conventions</a></li>\n"
          "<li><a href=\"#provenance\">Provenance</a></li>\n</ol>\n</nav>\n",
          fp);
}

/* Table 2 or 3 under its title, the text tables' (tables.h): Table 2
 * holds the optima alone, Table 3 the lowest of each sample in bold. */
static void titled_table(FILE *fp, const bf_rep_study *st, int which)
{
    char title[BF_REP_TITLE_LEN];
    if (which == 2) {
        bf_rep_table2_title(st, 0, title, sizeof title);
    } else {
        bf_rep_table3_title(st, 0, title, sizeof title);
    }
    fputs("<h3>", fp);
    bf_tt_html_text(fp, title);
    fputs("</h3>\n", fp);
    if (which == 2) {
        bf_report_table2(fp, st);
    } else {
        fputs("<p>The lowest of each sample is in bold.</p>\n", fp);
        bf_report_table3(fp, st);
    }
}

/* ==== the page =========================================================== */

int bf_report_html(const bf_rep_study *st, const bf_fig_set *figs,
                   const bf_report_meta *meta, FILE *fp)
{
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8"
          "\">\n<title>brdffit report</title>\n<style>",
          fp);
    fputs(style, fp);
    fputs("</style>\n<script>", fp);
    fputs(script, fp);
    fputs("</script>\n</head>\n<body>\n", fp);
    fprintf(fp, "<h1>brdffit report: %zu model%s fitted to %zu %s</h1>\n",
            st->n_models, st->n_models == 1 ? "" : "s", st->n_samples,
            st->n_samples == 1
                ? (st->in.curet ? "sample of the CURET database" : "sample")
                : (st->in.curet ? "samples of the CURET database"
                                : "samples"));
    if (bf_objective_keeps_scale(st->opts.objective)) {
        fprintf(fp, "<p>Reflectance models fitted to measured BRDF data in "
                    "absolute units under the %s objective (SPEC §10: "
                    "nothing normalised, each model's scales fitted), laid "
                    "out as in Ragheb &amp; Hancock, “Comparing Variants of "
                    "the Beckmann Model” (tables and figures numbered as in "
                    "that paper), and the analysis beyond it when it "
                    "ran.</p>\n",
                bf_objective_name(st->opts.objective));
    } else {
        fputs("<p>Rough-surface reflectance models fitted to measured BRDF "
              "data with the protocol of Ragheb &amp; Hancock, “Comparing "
              "Variants of the Beckmann Model” (tables and figures numbered "
              "as in the paper), and the analysis beyond it when it "
              "ran.</p>\n",
              fp);
    }
    contents(fp, st);
    data_section(fp, st);
    fputs("<h2 id=\"tables\">Tables 2 and 3</h2>\n", fp);
    titled_table(fp, st, 2);
    titled_table(fp, st, 3);
    energy_table(fp, st);
    fputs("<p>The same as files: <a href=\"fits.csv\">fits.csv</a>, <a href="
          "\"table2.md\">table2.md</a>, <a href=\"table3.md\">table3.md</a>."
          "</p>\n<h2 id=\"figures\">Figures</h2>\n",
          fp);
    figures_of(fp, figs, BF_FIG_LSE, SIZE_MAX);
    figures_of(fp, figs, BF_FIG_WINS, SIZE_MAX);
    fputs("<h3 id=\"scatter\">Figures 3–6: predicted against measured</h3>\n",
          fp);
    figures_of(fp, figs, BF_FIG_SCATTER, SIZE_MAX);
    analysis(fp, st, figs);
    per_sample(fp, st, figs);
    conventions(fp, st, meta);
    provenance(fp, meta);
    fputs("</body>\n</html>\n", fp);
    return page_oom ? -2 : ferror(fp) ? -1 : 0;
}
