/* report_tables.c: the tables of report.html (report_html.h) -- Table 2
 * (fitted parameters), Table 3 (each fit's objective value) and, with the
 * analysis, the model selection (samples won per criterion, BIC per
 * sample; doc/methods.md §4-5) and the fitted parameters with their 95%
 * intervals (§3), each as an HTML table. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report_html.h"
#include "texttable.h"

/* The number and name (with its channel) of target s. */
static void sample_cells(FILE *fp, const bf_rep_study *st, size_t s)
{
    char title[512];
    bf_rep_sample_title(st, s, title, sizeof title);
    fprintf(fp, "<td class=\"n\">%d</td><td>", st->samples[s]);
    bf_tt_html_text(fp, title);
    fputs("</td>", fp);
}

void bf_report_table2(FILE *fp, const bf_rep_study *st)
{
    size_t s;
    size_t m;
    size_t j;
    fputs("<table id=\"table2\">\n<thead><tr><th>No.</th><th>Sample</th>",
          fp);
    for (m = 0; m < st->n_models; m++) {
        const bf_model_type *t = st->models[m];
        for (j = 0; j < t->p; j++) {
            if (bf_rep_shows_param(t, j)) {
                fputs("<th>", fp);
                bf_tt_html_text(fp, t->name);
                fputs(" ", fp);
                bf_tt_html_text(fp, t->param[j].label);
                fputs("</th>", fp);
            }
        }
    }
    fputs("</tr></thead>\n<tbody>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        fputs("<tr>", fp);
        sample_cells(fp, st, s);
        for (m = 0; m < st->n_models; m++) {
            const bf_study_row *r = &st->rows[s * st->n_models + m];
            for (j = 0; j < r->type->p; j++) {
                if (!bf_rep_shows_param(r->type, j)) {
                    continue;
                }
                if (r->status != BF_OK) {
                    fputs("<td class=\"n\">-</td>", fp);
                } else {
                    fprintf(fp, "<td class=\"n\">%.*f%s</td>",
                            st->opts.exact ? 4 : 2, r->fit.param[j],
                            (r->fit.bound_hit & (1u << j)) ? "*" : "");
                }
            }
        }
        fputs("</tr>\n", fp);
    }
    fputs("</tbody>\n</table>\n", fp);
}

void bf_report_table3(FILE *fp, const bf_rep_study *st)
{
    size_t s;
    size_t m;
    fputs("<table id=\"table3\">\n<thead><tr><th>No.</th><th>Sample</th>",
          fp);
    for (m = 0; m < st->n_models; m++) {
        fputs("<th>", fp);
        bf_tt_html_text(fp, st->models[m]->name);
        fputs("</th>", fp);
    }
    fputs("</tr></thead>\n<tbody>\n", fp);
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
                fprintf(fp, "<td class=\"n%s\">%.*f</td>",
                        row[m].fit.lse == best ? " best" : "",
                        st->opts.exact ? 4 : 2, row[m].fit.lse);
            }
        }
        fputs("</tr>\n", fp);
    }
    fputs("</tbody>\n</table>\n", fp);
}

/* Samples won by each model under each criterion (the best of each
 * sample, bf_rep_rank_best), and the text summary beside it. */
static void wins_table(FILE *fp, const bf_rep_study *st)
{
    size_t m;
    size_t s;
    int c;
    fputs("<table id=\"wins-table\">\n<thead><tr><th>Criterion</th>", fp);
    for (m = 0; m < st->n_models; m++) {
        fputs("<th>", fp);
        bf_tt_html_text(fp, st->models[m]->name);
        fputs("</th>", fp);
    }
    fputs("</tr></thead>\n<tbody>\n", fp);
    for (c = 0; c < BF_REP_NCRIT; c++) {
        fprintf(fp, "<tr><td>%s</td>", bf_rep_crit_names[c]);
        for (m = 0; m < st->n_models; m++) {
            size_t n = 0;
            for (s = 0; s < st->n_samples; s++) {
                n += bf_rep_rank_best(st, s, c) == m;
            }
            fprintf(fp, "<td class=\"n\">%zu</td>", n);
        }
        fputs("</tr>\n", fp);
    }
    fputs("</tbody>\n</table>\n", fp);
}

void bf_report_selection(FILE *fp, const bf_rep_study *st)
{
    bf_tt *t;
    fputs("<p>Samples won by each model: the model with the lowest AIC, "
          "BIC (Gaussian errors) or cross-validated error of each sample "
          "(doc/methods.md §4–5; among exact ties the one with fewer "
          "parameters).</p>\n",
          fp);
    wins_table(fp, st);
    t = bf_rep_rank_table(st, BF_REP_BIC);
    if (t != NULL) {
        fputs("<details>\n<summary id=\"bic\">BIC per sample (lower is "
              "better; * marks the best, the last columns the best by each "
              "criterion)</summary>\n",
              fp);
        bf_tt_print_html(t, "bic-table", fp);
        fputs("</details>\n", fp);
    }
    bf_tt_free(t);
}

/* A cell of the interval (bf_rep_interval_format: " (bound)" after an
 * end at the search range's bound, a split one as two segments), then
 * note (" (Neyman)": the construction's, or ""); "–" when not computed. */
static void interval(FILE *fp, double lo, double hi, unsigned open,
                     double gl, double gh, const char *note)
{
    char text[160];
    if (!isfinite(lo) || !isfinite(hi)) {
        fputs("<td class=\"n\">\xe2\x80\x93</td>", fp);
        return;
    }
    bf_rep_interval_format(text, sizeof text, lo, hi, gl, gh, open);
    fprintf(fp, "<td class=\"n\">%s%s</td>", text, note);
}

void bf_report_intervals(FILE *fp, const bf_rep_study *st)
{
    size_t s;
    size_t m;
    size_t j;
    int boot = st->opts.n_boot >= 2;
    fputs("<table id=\"intervals\">\n<thead><tr><th>No.</th><th>Sample</th>"
          "<th>Model</th><th>Parameter</th><th>Grid optimum</th>"
          "<th>Exact optimum</th><th>Its interval's estimate (ML)</th>"
          "<th>Profile 95% interval</th>",
          fp);
    if (boot) {
        fputs("<th>Bootstrap 95% interval</th>", fp);
    }
    fputs("</tr></thead>\n<tbody>\n", fp);
    for (s = 0; s < st->n_samples; s++) {
        for (m = 0; m < st->n_models; m++) {
            const bf_fit_stats *f = &st->stats[s * st->n_models + m];
            const bf_model_type *t = st->rows[s * st->n_models + m].type;
            if (!f->done) {
                continue;
            }
            for (j = 0; j < t->p; j++) {
                if (!((f->free_mask >> j) & 1u)) {
                    continue;
                }
                fputs("<tr>", fp);
                sample_cells(fp, st, s);
                fputs("<td>", fp);
                bf_tt_html_text(fp, t->name);
                fputs("</td><td>", fp);
                bf_tt_html_text(fp, t->param[j].label);
                fprintf(fp, "</td><td class=\"n\">%.4g</td><td class=\"n\">"
                            "%.6g</td><td class=\"n\">%.6g</td>",
                        f->grid.param[j], f->refined.param[j],
                        f->ml_param[j]);
                interval(fp, f->ci_low[j], f->ci_high[j],
                         (f->ci_open >> (2 * j)) & 3u, f->ci_gap_low[j],
                         f->ci_gap_high[j],
                         bf_fit_stats_ci_method(f, j) == BF_CI_NEYMAN
                             ? " (Neyman)"
                             : "");
                if (boot) {
                    interval(fp, f->boot_low[j], f->boot_high[j], 0, NAN,
                             NAN, "");
                }
                fputs("</tr>\n", fp);
            }
        }
    }
    fputs("</tbody>\n</table>\n", fp);
}
