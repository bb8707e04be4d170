/* report_html.c: report.html (report_html.h) -- tables, figures,
 * conventions (SPEC §1.4, §2, §4, §7) and provenance in one page that opens
 * from disk. */
#include "report_html.h"
#include "texttable.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define DEG (M_PI / 180.0)

/* Writes s with HTML's special characters escaped. */
static void put_text(FILE *fp, const char *s)
{
    for (; *s != '\0'; s++) {
        switch (*s) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp); break;
        }
    }
}

/* Writes an argument as a POSIX shell word (quoted when needed). */
static void put_shell_word(FILE *fp, const char *s)
{
    const char *safe = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                       "0123456789-_./,=:+%@";
    if (s[0] != '\0' && strspn(s, safe) == strlen(s)) {
        put_text(fp, s);
        return;
    }
    fputc('\'', fp);
    for (; *s != '\0'; s++) {
        if (*s == '\'') {
            fputs("'\\''", fp);
        } else {
            char c[2] = {*s, '\0'};
            put_text(fp, c);
        }
    }
    fputc('\'', fp);
}

/* ==== provenance ========================================================== */

static int add_input(bf_report_meta *meta, const char *role, const char *path)
{
    bf_report_input *in;
    struct stat sb;
    if (meta->n_inputs >= BF_REPORT_MAX_INPUTS) {
        return BF_EXIT_SOFTWARE;
    }
    in = &meta->inputs[meta->n_inputs];
    in->role = role;
    snprintf(in->path, sizeof in->path, "%s", path);
    if (stat(path, &sb) != 0 || bf_sha256_file(path, in->sha256) != BF_OK) {
        bf_cli_err("%s: cannot read to compute its checksum", path);
        return BF_EXIT_NOINPUT;
    }
    in->size = (long long)sb.st_size;
    meta->n_inputs++;
    return BF_EXIT_OK;
}

int bf_report_checksums(const bf_cli_study *st, bf_report_meta *meta)
{
    int rc;
    size_t i;
    meta->n_inputs = 0;
    if (st->in.curet) {
        rc = add_input(meta, "configuration table", st->in.table_path);
        if (rc == BF_EXIT_OK) {
            rc = add_input(meta, "BRDF values", st->in.brdf_path);
        }
        if (rc == BF_EXIT_OK && st->in.names_path[0] != '\0') {
            rc = add_input(meta, "sample names", st->in.names_path);
        }
    } else {
        rc = BF_EXIT_OK;
        for (i = 0; rc == BF_EXIT_OK && i < st->opts.src.n_inputs; i++) {
            rc = add_input(meta, "measurements", st->opts.src.inputs[i]);
        }
        if (rc == BF_EXIT_OK && st->in.configs_path[0] != '\0' &&
            strcmp(st->in.configs_path, "all") != 0) {
            rc = add_input(meta, "MERL sampling configurations",
                           st->in.configs_path);
        }
    }
    if (rc == BF_EXIT_OK && st->opts.on_file != NULL) {
        rc = add_input(meta, "Oren-Nayar parameters", st->opts.on_file);
    }
    if (rc == BF_EXIT_OK && st->opts.n_file != NULL) {
        rc = add_input(meta, "refractive indices", st->opts.n_file);
    }
    return rc;
}

/* ==== page parts ========================================================== */

static const char *style =
    "body{font-family:sans-serif;max-width:1250px;margin:1em auto;"
    "padding:0 1em;color:#111;line-height:1.4}"
    "table{border-collapse:collapse;margin:.5em 0 1.5em;font-size:90%}"
    "th,td{border:1px solid #bbb;padding:2px 6px}"
    "td.n{text-align:right;font-variant-numeric:tabular-nums}"
    "td.best{font-weight:bold;background:#e6f0fa}"
    "figure{margin:1em 0 2em}img{max-width:100%;height:auto;"
    "border:1px solid #ddd}figcaption{font-size:90%;color:#333}"
    "code,pre{background:#f4f4f4}pre{padding:.5em;overflow-x:auto}"
    "nav a{margin-right:1em}";

/* Shown at the end of loading: whether every image loaded (read by
 * `make screenshot` through the DOM). */
static const char *script =
    "window.addEventListener('load',function(){var im=document.images,"
    "ok=0,i;for(i=0;i<im.length;i++){if(im[i].complete&&"
    "im[i].naturalWidth>0){ok++;}}document.body.setAttribute("
    "'data-images',ok+'/'+im.length);document.body.setAttribute("
    "'data-images-ok',ok===im.length?'yes':'no');});";

static void sample_cells(FILE *fp, const bf_cli_study *st, size_t s)
{
    char title[512];
    bf_cli_sample_title(st, s, title, sizeof title);
    fprintf(fp, "<td class=\"n\">%d</td><td>", st->samples[s]);
    put_text(fp, title);
    fputs("</td>", fp);
}

/* Table 2: fitted parameters ('*' on a grid bound). */
static void table2(FILE *fp, const bf_cli_study *st)
{
    size_t s;
    size_t m;
    size_t j;
    fputs("<table id=\"table2\"><tr><th>No.</th><th>Sample</th>", fp);
    for (m = 0; m < st->n_models; m++) {
        const bf_model_type *t = st->models[m];
        for (j = 0; j < t->p; j++) {
            if (bf_cli_shows_param(t, j)) {
                fputs("<th>", fp);
                put_text(fp, t->name);
                fputs(" ", fp);
                put_text(fp, t->param[j].label);
                fputs("</th>", fp);
            }
        }
    }
    fputs("</tr>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        fputs("<tr>", fp);
        sample_cells(fp, st, s);
        for (m = 0; m < st->n_models; m++) {
            const bf_study_row *r = &st->rows[s * st->n_models + m];
            for (j = 0; j < r->type->p; j++) {
                if (!bf_cli_shows_param(r->type, j)) {
                    continue;
                }
                if (r->status != BF_OK) {
                    fputs("<td class=\"n\">-</td>", fp);
                } else {
                    fprintf(fp, "<td class=\"n\">%.2f%s</td>", r->fit.param[j],
                            (r->fit.bound_hit & (1u << j)) ? "*" : "");
                }
            }
        }
        fputs("</tr>\n", fp);
    }
    fputs("</table>\n", fp);
}

/* Table 3: LSE, the lowest of each sample highlighted. */
static void table3(FILE *fp, const bf_cli_study *st)
{
    size_t s;
    size_t m;
    fputs("<table id=\"table3\"><tr><th>No.</th><th>Sample</th>", fp);
    for (m = 0; m < st->n_models; m++) {
        fputs("<th>", fp);
        put_text(fp, st->models[m]->name);
        fputs("</th>", fp);
    }
    fputs("</tr>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        const bf_study_row *row = &st->rows[s * st->n_models];
        double best = HUGE_VAL;
        for (m = 0; m < st->n_models; m++) {
            if (row[m].status == BF_OK && row[m].fit.lse < best) {
                best = row[m].fit.lse;
            }
        }
        fputs("<tr>", fp);
        sample_cells(fp, st, s);
        for (m = 0; m < st->n_models; m++) {
            if (row[m].status != BF_OK) {
                fputs("<td class=\"n\">-</td>", fp);
            } else {
                fprintf(fp, "<td class=\"n%s\">%.2f</td>",
                        row[m].fit.lse == best ? " best" : "",
                        row[m].fit.lse);
            }
        }
        fputs("</tr>\n", fp);
    }
    fputs("</table>\n", fp);
}

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
    fprintf(fp, "<figure id=\"%s\">", e->base);
    if (show >= 0) {
        fprintf(fp, "<img src=\"%s/%s.%s\" width=\"%u\" height=\"%u\" alt=\"",
                BF_FIG_DIR, e->base, bf_plot_format_ext((bf_plot_format)show),
                e->width, e->height);
        put_text(fp, e->title);
        fputs("\">", fp);
    }
    fputs("<figcaption><b>", fp);
    put_text(fp, e->title);
    fputs(".</b> ", fp);
    put_text(fp, e->caption);
    fputs(" Files:", fp);
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        const char *ext = bf_plot_format_ext((bf_plot_format)f);
        if (figs->formats & (1u << f)) {
            fprintf(fp, " <a href=\"%s/%s.%s\">%s</a>", BF_FIG_DIR, e->base,
                    ext, ext);
        }
    }
    fputs("</figcaption></figure>\n", fp);
}

static void figures_of(FILE *fp, const bf_fig_set *figs, bf_fig_kind kind,
                       int sample)
{
    size_t i;
    for (i = 0; i < figs->n; i++) {
        if (figs->fig[i].kind == kind && figs->fig[i].sample == sample) {
            figure(fp, figs, &figs->fig[i]);
        }
    }
}

/* Model selection (with --stats or --fit exact): the summary over samples
 * by AIC, BIC and CV and the per-sample BIC table, as `brdffit rank`
 * writes them (doc/methods.md §4-5). */
static void selection(FILE *fp, const bf_cli_study *st)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *mem;
    bf_tt *t;
    int c;
    fputs("<h2 id=\"selection\">Model selection</h2>\n", fp);
    if (st->stats == NULL) {
        fputs("<p>Not computed: run with <code>--stats</code> (or "
              "<code>brdffit rank</code>) for AIC, BIC and cross-validation."
              "</p>\n",
              fp);
        return;
    }
    fputs("<p>Per sample, "
          "the models ranked by AIC, BIC (Gaussian errors) and the "
          "cross-validated error (doc/methods.md §4–5); lower is better, * "
          "marks the best.</p>\n<ul>\n",
          fp);
    for (c = 0; c < BF_CLI_NCRIT; c++) {
        mem = open_memstream(&buf, &len);
        if (mem == NULL) {
            return;
        }
        bf_cli_rank_summary(st, c, mem);
        fclose(mem);
        buf[strcspn(buf, "\n")] = '\0';
        fputs("<li>", fp);
        put_text(fp, buf);
        fputs("</li>\n", fp);
        free(buf);
        buf = NULL;
    }
    fputs("</ul>\n", fp);
    t = bf_cli_rank_table(st, BF_CLI_BIC);
    mem = t != NULL ? open_memstream(&buf, &len) : NULL;
    if (mem != NULL) {
        bf_tt_print(t, mem);
        fclose(mem);
        fputs("<h3>BIC per sample</h3>\n<pre>", fp);
        put_text(fp, buf);
        fputs("</pre>\n", fp);
        free(buf);
    }
    bf_tt_free(t);
}

static void conventions(FILE *fp, const bf_cli_study *st,
                        const bf_report_meta *meta)
{
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    size_t a;

    fputs("<h2 id=\"conventions\">Conventions</h2>\n<ul>\n", fp);
    fputs("<li>Measured radiance = BRDF × cos θ<sub>i</sub>, divided by its "
          "maximum over the K used configurations; every model curve is "
          "divided by its own maximum over the same configurations, so the "
          "models' scale constants cancel (SPEC §2).</li>\n", fp);
    {
        char cone[256];
        bf_cli_describe_cone(st, cone, sizeof cone);
        fputs("<li>Specular exclusion: ", fp);
        put_text(fp, cone);
        fprintf(fp, "%s; the configurations used and left out are listed "
                    "below.</li>\n",
                (st->opts.exclude != NULL || st->opts.max_theta < 90.0)
                    ? ", and more by --exclude or --max-theta"
                    : "");
    }
    fputs("<li>LSE = Σ<sub>k</sub> (L<sub>model,k</sub> − L<sub>data,k"
          "</sub>)², a sum over the K configurations (SPEC §7.3).</li>\n"
          "<li>Exhaustive grids (SPEC §7.4): slope m = σ/T = 0.1 + 0.01 i, "
          "Lafortune exponent n<sub>d</sub> = 0.1 + 0.04 i, i = 0…500; ties "
          "keep the smaller value; * marks an optimum on a grid bound. The "
          "slopes of the Gaussian (G) and exponential (E) forms are different "
          "quantities.</li>\n"
          "<li>Fresnel reflectance with the factor ½ (SPEC §4.1); ", fp);
    if (st->opts.n_file != NULL) {
        fputs("refractive index per sample from <code>", fp);
        put_text(fp, st->opts.n_file);
        fputs("</code>.</li>\n", fp);
    } else {
        fprintf(fp, "refractive index n = %g for every sample (SPEC §4.2)."
                    "</li>\n",
                st->opts.n);
    }
    fputs("<li>Oren–Nayar (ON) is evaluated, not fitted, at tabulated ρ, σ "
          "(SPEC §5)", fp);
    if (st->opts.on_file != NULL) {
        fputs(" from <code>", fp);
        put_text(fp, st->opts.on_file);
        fputs("</code>", fp);
    }
    fputs(".</li>\n<li>Plane-of-incidence figures: incidence angles", fp);
    for (a = 0; a < meta->fig->n_incidence; a++) {
        fprintf(fp, "%s %.2f°", a ? "," : "", meta->fig->incidence[a] / DEG);
    }
    fputs("; θ<sub>s</sub> &gt; 0 on the forward (specular) side, Beckmann's "
          "frame (SPEC §1.2).</li>\n</ul>\n", fp);
    if (mem != NULL) {
        bf_cli_study_describe(st, mem);
        fclose(mem);
        fputs("<p>The run, as printed by brdffit:</p>\n<pre>", fp);
        put_text(fp, text != NULL ? text : "");
        fputs("</pre>\n", fp);
    }
    free(text);
}

static void provenance(FILE *fp, const bf_report_meta *meta)
{
    size_t i;
    int a;
    fputs("<h2 id=\"provenance\">Provenance</h2>\n<ul>\n", fp);
    fprintf(fp, "<li>brdffit %s</li>\n<li>Command: <code>brdffit",
            bf_version());
    for (a = 0; a < meta->argc; a++) {
        fputc(' ', fp);
        put_shell_word(fp, meta->argv[a]);
    }
    fputs("</code></li>\n</ul>\n<table id=\"inputs\"><tr><th>Input</th>"
          "<th>File</th><th>Bytes</th><th>SHA-256</th></tr>\n", fp);
    for (i = 0; i < meta->n_inputs; i++) {
        const bf_report_input *in = &meta->inputs[i];
        fputs("<tr><td>", fp);
        put_text(fp, in->role);
        fputs("</td><td><code>", fp);
        put_text(fp, in->path);
        fprintf(fp, "</code></td><td class=\"n\">%lld</td><td><code>%s</code>"
                    "</td></tr>\n",
                in->size, in->sha256);
    }
    fputs("</table>\n", fp);
}

/* ==== the page ============================================================ */

int bf_report_html(const bf_cli_study *st, const bf_fig_set *figs,
                   const bf_report_meta *meta, FILE *fp)
{
    size_t s;
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8"
          "\">\n<title>brdffit report</title>\n<style>",
          fp);
    fputs(style, fp);
    fputs("</style>\n<script>", fp);
    fputs(script, fp);
    fputs("</script>\n</head>\n<body>\n", fp);
    fprintf(fp, "<h1>brdffit report: %zu models fitted to %zu %s"
                "samples</h1>\n",
            st->n_models, st->n_samples, st->in.curet ? "CURET " : "");
    fputs("<p>Rough-surface reflectance models fitted to measured BRDF data "
          "with the protocol of Ragheb &amp; Hancock, “Comparing Variants of "
          "the Beckmann Model” (tables and figures numbered as in the "
          "paper).</p>\n<nav><a href=\"#tables\">Tables</a><a href=\"#fig2b"
          "\">Figure 2(b)</a><a href=\"#scatter\">Figures 3–6</a><a href=\""
          "#samples\">Per sample</a><a href=\"#selection\">Model selection</a>"
          "<a href=\"#conventions\">Conventions</a>"
          "<a href=\"#provenance\">Provenance</a></nav>\n",
          fp);
    fputs("<h2 id=\"tables\">Tables</h2>\n<h3>Table 2: fitted parameters "
          "(grid optima; * on a grid bound)</h3>\n",
          fp);
    table2(fp, st);
    fprintf(fp, "<h3>Table 3: LSE (sum over the K = %zu used configurations; "
                "lowest per sample highlighted)</h3>\n",
            st->n_sel);
    table3(fp, st);
    fputs("<p>The same as files: <a href=\"fits.csv\">fits.csv</a>, <a href="
          "\"table2.md\">table2.md</a>, <a href=\"table3.md\">table3.md</a>."
          "</p>\n<h2>Figures</h2>\n",
          fp);
    figures_of(fp, figs, BF_FIG_LSE, 0);
    figures_of(fp, figs, BF_FIG_WINS, 0);
    fputs("<h3 id=\"scatter\">Figures 3–6: predicted against measured</h3>\n",
          fp);
    figures_of(fp, figs, BF_FIG_SCATTER, 0);
    fputs("<h3 id=\"samples\">Per sample</h3>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        int sample = st->samples[s];
        char title[512];
        bf_cli_sample_title(st, s, title, sizeof title);
        fprintf(fp, "<h4 id=\"sample%d\">", sample);
        put_text(fp, title[0] != '\0' ? title : "sample");
        fprintf(fp, " (%d)</h4>\n", sample);
        figures_of(fp, figs, BF_FIG_SAMPLE, sample);
        figures_of(fp, figs, BF_FIG_PLANE, sample);
        figures_of(fp, figs, BF_FIG_POLAR, sample);
    }
    selection(fp, st);
    conventions(fp, st, meta);
    provenance(fp, meta);
    fputs("</body>\n</html>\n", fp);
    return ferror(fp) ? -1 : 0;
}
