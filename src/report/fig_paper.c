/* fig_paper.c: the figures of the paper's protocol (fig_internal.h) --
 * Figure 2(b) (each model's Table 3 value, the LSE under the paper's
 * objective, against the samples sorted by fitted FC-E slope), Figures
 * 3-6 (predicted against measured normalised radiance) and the count of
 * samples each model fits best.
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann
 *       Model": Figure 2(b), Figures 3-6. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fig_internal.h"
#include "model_style.h"

/* Scatter axes: [0, 1] with room so that markers at 0 and 1 are whole. */
#define SCATTER_LO (-0.05)
#define SCATTER_HI 1.05
#define SCATTER_MARKER 0.62 /* marker size factor: 198 points a panel */
/* Figure 2(b)'s shape (axes height / width). */
#define LSE_ASPECT 0.42

/* ==== Figure 2(b) ======================================================== */

typedef struct {
    double key;
    int sample;
    size_t s;
} sort_item;

static int cmp_item(const void *a, const void *b)
{
    const sort_item *x = a;
    const sort_item *y = b;
    if (x->key != y->key) {
        return x->key < y->key ? -1 : 1;
    }
    return (x->sample > y->sample) - (x->sample < y->sample);
}

/* Sample indices sorted by increasing fitted FC-E slope; by sample number
 * when FC-E is not in the run (or not fitted for every sample). Returns
 * 1 when sorted by slope, 0 by number, -1 when out of memory. */
static int order_by_slope(const bf_rep_study *st, size_t *order)
{
    long fc = -1;
    int jm = -1;
    sort_item *it = malloc(st->n_samples * sizeof *it + 1);
    size_t s;
    size_t m;
    int by_slope;
    for (m = 0; m < st->n_models; m++) {
        if (strcmp(st->models[m]->name, "FC-E") == 0) {
            fc = (long)m;
            jm = bf_model_param_index(st->models[m], "m");
        }
    }
    if (it == NULL) {
        return -1;
    }
    by_slope = jm >= 0;
    for (s = 0; s < st->n_samples && by_slope; s++) {
        by_slope = bf_fig_row(st, s, (size_t)fc)->status == BF_OK;
    }
    for (s = 0; s < st->n_samples; s++) {
        it[s].sample = st->samples[s];
        it[s].s = s;
        it[s].key = by_slope ? bf_fig_row(st, s, (size_t)fc)->fit.param[jm]
                             : (double)st->samples[s];
    }
    qsort(it, st->n_samples, sizeof *it, cmp_item);
    for (s = 0; s < st->n_samples; s++) {
        order[s] = it[s].s;
    }
    free(it);
    return by_slope;
}

/* The upper end of an axis from 0 showing hi, with headroom frac. */
static double axis_top(double hi, double frac)
{
    double top = hi * (1.0 + frac);
    double mag = pow(10.0, floor(log10(top)));
    return ceil(top / mag * 2.0) / 2.0 * mag;
}

int bf_fig_lse(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
               int full)
{
    const bf_rep_study *st = D->st;
    size_t N = st->n_samples;
    size_t M = st->n_models;
    size_t *order = bf_fig_alloc(d, N * sizeof *order);
    double *x = bf_fig_alloc(d, N * sizeof *x);
    double *y = bf_fig_alloc(d, N * M * sizeof *y);
    char (*num)[16] = bf_fig_alloc(d, N * sizeof *num);
    const char **ticks = bf_fig_alloc(d, N * sizeof *ticks);
    bf_plot_series *ser = bf_fig_alloc(d, M * sizeof *ser);
    bf_plot_panel *p = bf_fig_alloc(d, sizeof *p);
    char *ylabel = bf_fig_alloc(d, 32);
    char models[512];
    char ktext[48];
    char each[48];
    double lo = HUGE_VAL;
    double hi = 0.0;
    size_t i;
    size_t m;
    int by_slope;

    (void)full;
    if (order == NULL || x == NULL || y == NULL || num == NULL ||
        ticks == NULL || ser == NULL || p == NULL || ylabel == NULL ||
        (by_slope = order_by_slope(st, order)) < 0) {
        return BF_ENOMEM;
    }
    for (i = 0; i < N; i++) {
        x[i] = (double)(i + 1);
        snprintf(num[i], sizeof num[i], "%d", st->samples[order[i]]);
        ticks[i] = num[i];
    }
    for (m = 0; m < M; m++) {
        for (i = 0; i < N; i++) {
            const bf_study_row *r = bf_fig_row(st, order[i], m);
            double v = r->status == BF_OK ? r->fit.lse : NAN;
            y[m * N + i] = v;
            if (isfinite(v) && v > 0.0) {
                lo = fmin(lo, v);
                hi = fmax(hi, v);
            }
        }
        ser[m].kind = BF_SERIES_LINE;
        ser[m].x = x;
        ser[m].y = &y[m * N];
        ser[m].n = N;
        ser[m].style = bf_report_model_style(st->models[m]);
        ser[m].mark_every = 1;
        /* a model no sample has (ON without tabulated parameters) is
         * left out of the legend: it draws nothing */
        ser[m].label =
            bf_fig_evaluated_anywhere(st, m) ? st->models[m]->name : NULL;
    }
    if (!(hi > 0.0)) {
        lo = 0.1;
        hi = 1.0;
    }
    p->xmin = 0.5;
    p->xmax = (double)N + 0.5;
    p->logy = D->o->log_lse;
    p->ymin = p->logy ? pow(10.0, floor(log10(lo))) : 0.0;
    p->ymax = p->logy ? pow(10.0, ceil(log10(hi))) : axis_top(hi, 0.05);
    if (p->logy && !(p->ymax > p->ymin)) { /* every value one power of 10 */
        p->ymax = 10.0 * p->ymin;
    }
    p->xtick_labels = ticks;
    p->n_xticks = N;
    p->series = ser;
    p->n_series = M;
    d->fig.width = D->o->width;
    d->fig.aspect = LSE_ASPECT;
    d->fig.nx = d->fig.ny = 1;
    d->fig.xlabel = by_slope ? "sample (by increasing fitted FC-E slope)"
                             : "sample";
    snprintf(ylabel, 32, "%s%s", bf_fig_value_name(st->opts.objective),
             p->logy ? " (log scale)" : "");
    d->fig.ylabel = ylabel;
    d->fig.legend = BF_LEGEND_TOP;
    d->fig.panels = p;
    d->fig.n_panels = 1;

    models[0] = '\0';
    for (m = 0; m < M; m++) {
        size_t used = strlen(models);
        snprintf(models + used, sizeof models - used, "%s%s", m ? ", " : "",
                 st->models[m]->name);
    }
    snprintf(e->base, sizeof e->base, "fig2b");
    snprintf(e->title, sizeof e->title, "Figure 2(b): %s of each model, "
             "samples %s", bf_fig_value_name(st->opts.objective),
             by_slope ? "sorted by fitted FC-E slope" : "by number");
    if (bf_objective_keeps_scale(st->opts.objective)) {
        snprintf(e->caption, sizeof e->caption,
                 "%s of the %s objective (SPEC §10: over each sample's used "
                 "configurations with \xce\xb8i, \xce\xb8o \xe2\x89\xa4 "
                 "80\xc2\xb0, \xcf\x81 = BRDF cos \xce\xb8i as measured, "
                 "nothing normalised) of %s for %s; the "
                 "x axis lists the sample numbers %s%s.",
                 st->opts.objective == BF_OBJ_NGAN
                     ? "E = \xe2\x88\x9a(\xce\xa3 (\xcf\x81 \xe2\x88\x92 "
                       "\xcf\x81\xcc\x82)\xc2\xb2 / K)"
                     : "The sum S",
                 bf_objective_name(st->opts.objective), models,
                 bf_fig_each_sample(N, each, sizeof each),
                 by_slope ? "in order of increasing fitted FC-E slope m"
                          : "in increasing order (FC-E is not in the run)",
                 p->logy ? "; logarithmic axis" : "");
    } else if (st->opts.objective != BF_OBJ_MAX) {
        snprintf(e->caption, sizeof e->caption,
                 "The sum S of the %s objective (doc/methods.md §1) over the "
                 "%s used configurations, data and models normalised as "
                 "that objective asks (SPEC §2, §7), of %s for %s; the x "
                 "axis lists the sample numbers %s%s.",
                 bf_objective_name(st->opts.objective),
                 bf_fig_k_text(st, ktext, sizeof ktext), models,
                 bf_fig_each_sample(N, each, sizeof each),
                 by_slope ? "in order of increasing fitted FC-E slope m"
                          : "in increasing order (FC-E is not in the run)",
                 p->logy ? "; logarithmic axis" : "");
    } else {
    snprintf(e->caption, sizeof e->caption,
             "LSE (the sum over the %s used configurations of the "
             "squared difference between the model's and the measured "
             "radiance, each divided by its maximum over those "
             "configurations) of %s for %s; the x axis "
             "lists the sample numbers %s%s.",
             bf_fig_k_text(st, ktext, sizeof ktext), models,
             bf_fig_each_sample(N, each, sizeof each),
             by_slope ? "in order of increasing fitted FC-E slope m, as in "
                        "the paper's Figure 2(b)"
                      : "in increasing order (FC-E is not in the run)",
             p->logy ? "; logarithmic LSE axis" : "");
    }
    snprintf(e->alt, sizeof e->alt,
             "Line chart: %s of %zu model%s (%.400s) for %zu sample%s%s.",
             bf_fig_value_name(st->opts.objective), M, M == 1 ? "" : "s",
             models, N, N == 1 ? "" : "s",
             by_slope ? " sorted by FC-E slope" : "");
    return BF_OK;
}

/* ==== samples won ======================================================== */

/* A step for integer counts up to hi giving at most 6 ticks. */
static double count_step(double hi)
{
    static const double steps[] = {1, 2, 5, 10, 20, 25, 50, 100, 200, 500};
    size_t i;
    for (i = 0; i < sizeof steps / sizeof *steps; i++) {
        if (hi / steps[i] <= 6.0) {
            return steps[i];
        }
    }
    return 1000.0;
}

int bf_fig_wins(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                int full)
{
    const bf_rep_study *st = D->st;
    size_t M = st->n_models;
    double *x = bf_fig_alloc(d, M * sizeof *x);
    double *y = bf_fig_alloc(d, M * sizeof *y);
    const char **names = bf_fig_alloc(d, M * sizeof *names);
    bf_plot_series *ser = bf_fig_alloc(d, M * sizeof *ser);
    bf_plot_panel *p = bf_fig_alloc(d, sizeof *p);
    double hi = 1.0;
    size_t s;
    size_t m;

    (void)full;
    if (x == NULL || y == NULL || names == NULL || ser == NULL || p == NULL) {
        return BF_ENOMEM;
    }
    for (s = 0; s < st->n_samples; s++) {
        double best = HUGE_VAL;
        for (m = 0; m < M; m++) {
            const bf_study_row *r = bf_fig_row(st, s, m);
            if (r->status == BF_OK && r->fit.lse < best) {
                best = r->fit.lse;
            }
        }
        for (m = 0; m < M; m++) {
            const bf_study_row *r = bf_fig_row(st, s, m);
            if (r->status == BF_OK && r->fit.lse == best) {
                y[m] += 1.0; /* ties count for every tied model */
            }
        }
    }
    for (m = 0; m < M; m++) {
        x[m] = (double)(m + 1);
        names[m] = st->models[m]->name;
        hi = fmax(hi, y[m]);
        ser[m].kind = BF_SERIES_BARS;
        ser[m].x = &x[m];
        ser[m].y = &y[m];
        ser[m].n = 1;
        ser[m].style = bf_report_model_style(st->models[m]);
    }
    p->xmin = 0.4;
    p->xmax = (double)M + 0.6;
    p->ymin = 0.0;
    p->ytick = count_step(hi);
    p->ymax = ceil(hi * 1.18 / p->ytick) * p->ytick; /* room for the counts */
    p->xtick_labels = names;
    p->n_xticks = M;
    p->series = ser;
    p->n_series = M;
    /* a bar a model: no wider than it needs */
    d->fig.width = (unsigned)fmin((double)D->o->width, 90.0 + 42.0 * (double)M);
    d->fig.aspect = 0.6;
    d->fig.nx = d->fig.ny = 1;
    d->fig.ylabel = "samples fitted best";
    d->fig.panels = p;
    d->fig.n_panels = 1;
    snprintf(e->base, sizeof e->base, "wins");
    snprintf(e->title, sizeof e->title, "Samples fitted best by each model");
    snprintf(e->caption, sizeof e->caption,
             "For each model, the number of samples (of %zu) on which it "
             "has the lowest %s (Table 3) among the models evaluated for "
             "that sample (a tie counts for every tied model).",
             st->n_samples, bf_fig_value_name(st->opts.objective));
    snprintf(e->alt, sizeof e->alt,
             "Bar chart: the number of samples each of %zu model%s fits "
             "with the lowest %s.",
             M, M == 1 ? "" : "s", bf_fig_value_name(st->opts.objective));
    return BF_OK;
}

/* ==== Figures 3-6: predicted against measured ============================ */

/* Narrowest scatter axes of a group's grid (the paper's six columns of a
 * double-column figure are 59 points) and of one sample's re-flowed
 * panels, points. */
#define SCATTER_GRID_MIN 50.0
#define SCATTER_FLOW_MIN 100.0

/* How a scatter figure's panels are arranged. */
typedef enum {
    GRID_PAPER,      /* a column per sample, a row per model (the paper) */
    GRID_TRANSPOSED, /* a column per model, a row per sample */
    GRID_FLOW        /* one sample: its model panels in rows, each named
                        by its note (bf_plot_flow chooses the grid) */
} scatter_grid;

/* What a scatter figure's description points into. */
typedef struct {
    bf_plot_panel *panel;
    bf_plot_series *ser;
    char (*notes)[48];
    char (*slabel)[256];
    const char **slabels; /* the sample labels */
    const char **mlabels; /* the model names */
} scatter_mem;

static int scatter_alloc(const bf_fig_data *D, size_t ns, bf_fig_desc *d,
                         scatter_mem *w)
{
    size_t n = ns * D->nm;
    w->panel = bf_fig_alloc(d, n * sizeof *w->panel);
    w->ser = bf_fig_alloc(d, n * sizeof *w->ser);
    w->notes = bf_fig_alloc(d, n * sizeof *w->notes);
    w->slabel = bf_fig_alloc(d, ns * sizeof *w->slabel);
    w->slabels = bf_fig_alloc(d, ns * sizeof *w->slabels);
    w->mlabels = bf_fig_alloc(d, D->nm * sizeof *w->mlabels);
    return w->panel != NULL && w->ser != NULL && w->notes != NULL &&
                   w->slabel != NULL && w->slabels != NULL &&
                   w->mlabels != NULL
               ? BF_OK
               : BF_ENOMEM;
}

/* Describes the scatter panels of samples [s0, s0 + ns) in d->fig, in
 * grid g. */
static void scatter_fill(const bf_fig_data *D, size_t s0, size_t ns,
                         scatter_grid g, scatter_mem *w, bf_fig_desc *d)
{
    const bf_rep_study *st = D->st;
    size_t nm = D->nm;
    size_t a;
    size_t b;
    memset(&d->fig, 0, sizeof d->fig);
    for (a = 0; a < ns; a++) {
        size_t s = s0 + a;
        const bf_fig_sample *r = &D->smp[s];
        w->slabels[a] = bf_fig_sample_tick(st, s, w->slabel[a],
                                           sizeof w->slabel[a]);
        for (b = 0; b < nm; b++) {
            size_t m = D->idx[b];
            size_t p = g == GRID_PAPER ? b * ns + a : a * nm + b;
            const bf_study_row *row = bf_fig_row(st, s, m);
            const char *name = g == GRID_FLOW ? st->models[m]->name : "";
            const char *sep = g == GRID_FLOW ? ": " : "";
            bf_plot_series *ser = &w->ser[p];
            bf_plot_panel *pan = &w->panel[p];
            if (row->status == BF_OK &&
                bf_objective_keeps_scale(st->opts.objective)) {
                snprintf(w->notes[p], sizeof w->notes[p], "%.24s%s%s %.3g",
                         name, sep, bf_fig_value_name(st->opts.objective),
                         row->fit.lse);
            } else if (row->status == BF_OK) {
                snprintf(w->notes[p], sizeof w->notes[p], "%.24s%s%s %.2f",
                         name, sep, bf_fig_value_name(st->opts.objective),
                         row->fit.lse);
            } else {
                snprintf(w->notes[p], sizeof w->notes[p],
                         "%.24s%snot evaluated", name, sep);
            }
            memset(ser, 0, sizeof *ser);
            memset(pan, 0, sizeof *pan);
            ser->kind = BF_SERIES_POINTS;
            ser->x = r->data;
            ser->y = &r->pred[m * r->K];
            ser->n = r->ok[m] ? r->K : 0;
            ser->style = bf_report_model_style(st->models[m]);
            ser->weight = SCATTER_MARKER;
            pan->xmin = pan->ymin = SCATTER_LO;
            pan->xmax = pan->ymax = SCATTER_HI;
            pan->xtick = pan->ytick = 0.5;
            pan->diagonal = 1;
            pan->note = w->notes[p];
            pan->series = ser;
            pan->n_series = 1;
        }
    }
    for (b = 0; b < nm; b++) {
        w->mlabels[b] = st->models[D->idx[b]]->name;
    }
    d->fig.width = D->o->width;
    d->fig.aspect = 1.0;
    d->fig.share_x = d->fig.share_y = 1;
    d->fig.xlabel = "measured L/L_{max}";
    d->fig.ylabel = "predicted L/L_{max}";
    d->fig.panels = w->panel;
    d->fig.n_panels = ns * nm;
    if (g == GRID_PAPER) {
        d->fig.nx = ns;
        d->fig.ny = nm;
        d->fig.col_labels = w->slabels;
        d->fig.row_labels = w->mlabels;
    } else if (g == GRID_TRANSPOSED) {
        d->fig.nx = nm;
        d->fig.ny = ns;
        d->fig.col_labels = w->mlabels;
        d->fig.row_labels = w->slabels;
    } else {
        d->fig.nx = nm;
        d->fig.ny = 1;
    }
}

/* Describes the group of samples [s0, s0 + ns) (ns >= 2) in the paper's
 * grid, or transposed when that does not fit; *g is the grid, GRID_FLOW
 * when neither fits. */
static int scatter_grid_of(const bf_fig_data *D, size_t s0, size_t ns,
                           scatter_mem *w, bf_fig_desc *d, scatter_grid *g)
{
    static const scatter_grid tries[2] = {GRID_PAPER, GRID_TRANSPOSED};
    size_t t;
    for (t = 0; t < 2; t++) {
        scatter_fill(D, s0, ns, tries[t], w, d);
        if (bf_plot_fits(&d->fig, SCATTER_GRID_MIN)) {
            *g = tries[t];
            return BF_OK;
        }
    }
    *g = GRID_FLOW;
    return BF_OK;
}

size_t bf_fig_scatter_group(const bf_fig_data *D, size_t s0)
{
    size_t left = D->st->n_samples - s0;
    size_t ns = left < BF_FIG_SCATTER_SAMPLES ? left
                                              : BF_FIG_SCATTER_SAMPLES;
    for (; ns > 1; ns--) {
        bf_fig_desc d;
        scatter_mem w;
        scatter_grid g = GRID_FLOW;
        memset(&d, 0, sizeof d);
        if (scatter_alloc(D, ns, &d, &w) == BF_OK) {
            (void)scatter_grid_of(D, s0, ns, &w, &d, &g);
        }
        bf_fig_desc_free(&d);
        if (g != GRID_FLOW) {
            break;
        }
    }
    return ns;
}

int bf_fig_scatter(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                   int full)
{
    const bf_rep_study *st = D->st;
    int one = e->kind == BF_FIG_SAMPLE;
    size_t s0 = one ? e->index : e->first;
    size_t ns = one ? 1 : e->count;
    size_t nm = D->nm;
    scatter_grid g = GRID_FLOW;
    scatter_mem w;
    char models[256];
    char key[64];
    char ktext[48];
    char where[256];
    int rc;

    (void)full;
    rc = scatter_alloc(D, ns, d, &w);
    if (rc == BF_OK && ns > 1) {
        rc = scatter_grid_of(D, s0, ns, &w, d, &g);
    }
    if (rc == BF_OK && g == GRID_FLOW) {
        if (ns != 1) {
            return BF_EINVAL; /* groups are chosen to fit */
        }
        scatter_fill(D, s0, ns, GRID_FLOW, &w, d);
        rc = bf_plot_flow(&d->fig, SCATTER_FLOW_MIN);
    }
    if (rc != BF_OK) {
        return rc;
    }

    bf_fig_model_list(st, D->idx, nm, models, sizeof models);
    snprintf(where, sizeof where, " of %.200s", w.slabel[0]);
    if (one) {
        where[0] = '\0'; /* the title names the sample */
    }
    if (ns == 1) {
        snprintf(ktext, sizeof ktext, "K = %zu", D->smp[s0].K);
    } else {
        bf_fig_k_text(st, ktext, sizeof ktext);
    }
    if (one) {
        snprintf(e->base, sizeof e->base, "scatter_%s",
                 bf_fig_target_key(st, s0, key, sizeof key));
        snprintf(e->title, sizeof e->title, "%s: predicted against measured",
                 w.slabel[0]);
    } else {
        snprintf(e->base, sizeof e->base, "scatter%zu", e->index + 1);
        snprintf(e->title, sizeof e->title,
                 "Figures 3–6, part %zu of %zu: predicted against measured",
                 e->index + 1, e->parts);
    }
    snprintf(e->caption, sizeof e->caption,
             "Predicted against measured radiance on the %s used "
             "configurations%s, %s (%s); measured and "
             "predicted radiance are each divided by their maximum over the "
             "K configurations (SPEC §2), the models at their fitted "
             "parameters; the grey diagonal is perfect agreement, and each "
             "panel gives the model's %s.",
             ktext,
             g == GRID_PAPER        ? ", one column per sample"
             : g == GRID_TRANSPOSED ? ", one row per sample"
                                    : where,
             g == GRID_PAPER        ? "one row per model"
             : g == GRID_TRANSPOSED ? "one column per model"
                                    : "one panel per model",
             models, bf_fig_value_name(st->opts.objective));
    snprintf(e->alt, sizeof e->alt,
             "Grid of %zu scatter plots: predicted against measured "
             "normalised radiance of %zu sample%s for the models %s.",
             ns * nm, ns, ns == 1 ? "" : "s", models);
    return BF_OK;
}
