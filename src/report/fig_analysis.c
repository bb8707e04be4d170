/* fig_analysis.c: the figures of the analysis beyond the paper
 * (fig_internal.h, doc/methods.md §3-4), drawn when it ran -- per model,
 * each sample's fitted parameter with its profile and bootstrap intervals
 * (a forest plot); per sample, the profile of the objective along each
 * fitted parameter with the 95% threshold; and the samples x models
 * overview of delta BIC.
 *
 * References:
 *   [1] R. E. Kass, A. E. Raftery, "Bayes Factors", JASA 90:773-795
 *       (1995), §3.2: evidence categories of 2 ln B (0-2, 2-6, 6-10, > 10),
 *       which delta BIC approximates. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fig_internal.h"
#include "ranking.h"
#include "model_style.h"

/* chi2_1(0.95): the profile interval's threshold (doc/methods.md §3). */
#define CHI2_95 3.841458820694124
/* Height of one sample's row in the forest plots and the overview. */
#define ROW_PT 10.5
/* Room of the legend, the x numbers and labels of those figures. */
#define FRAME_PT 64.0
/* Room of the longest model names written upwards (composites). */
#define NAMES_PT 110.0
/* Forest plots: room of the sample names beside the panels, the narrowest
 * panels in one row, the room of a row's x numbers and label. */
#define FOREST_NAMES_PT 150.0
#define FOREST_MIN_AXES 50.0
#define XLABEL_PT 34.0
/* Profile panels: points per curve (over the window bf_study_profiles
 * chooses), panels per row and their shape. */
#define PROFILE_POINTS 41
/* A panel's values beside its curve: the interval (4), the threshold's x
 * and the optimum's y (3), the threshold's y (2). */
#define PROFILE_EXTRA 10
#define PROFILE_COLS 5
#define PROFILE_YMAX 12.0
#define PROFILE_ASPECT 0.75
/* The bootstrap interval sits this far below the profile interval. */
#define BOOT_OFFSET 0.3

/* Sets the width of d's figure of a row per sample (the forest plots and
 * the overview): the width it wants, widened up to cap points until it
 * lays out -- at most BF_PLOT_MAX_TALL times as tall as wide (many
 * samples) and with room for the names and the legend (few models, long
 * names). */
static void rows_width(bf_fig_desc *d, double want, unsigned cap)
{
    double w = fmax(want, ceil((double)d->fig.height / BF_PLOT_MAX_TALL));
    d->fig.width = (unsigned)fmin((double)cap, w);
    while (d->fig.width < cap && !bf_plot_fits(&d->fig, 0.0)) {
        d->fig.width = (unsigned)fmin((double)cap,
                                      ceil(1.2 * (double)d->fig.width));
    }
}

/* Makes d's figure of rows taller, up to BF_PLOT_MAX_TALL times its
 * width, until it lays out: names written upwards below many columns. */
static void rows_height(bf_fig_desc *d)
{
    double cap = BF_PLOT_MAX_TALL * (double)d->fig.width;
    while (!bf_plot_fits(&d->fig, 0.0) && (double)d->fig.height + 1 < cap) {
        d->fig.height = (unsigned)fmin(cap, d->fig.height + 2.0 * ROW_PT);
    }
}

/* e's file name: prefix and name, on the further pages of its n rows
 * (bf_fig_rows_per_page) followed by _2, _3, ... */
static void page_name(bf_fig_entry *e, size_t n, const char *prefix,
                      const char *name)
{
    if (e->first == 0) {
        snprintf(e->base, sizeof e->base, "%s%s", prefix, name);
    } else {
        snprintf(e->base, sizeof e->base, "%s%s_%zu", prefix, name,
                 e->first / ((n + e->parts - 1) / e->parts) + 1);
    }
}

size_t bf_fig_rows_per_page(const bf_fig_data *D)
{
    /* a page's height less the frame and the model names upwards */
    double room = BF_PLOT_MAX_TALL * (double)D->o->width - FRAME_PT
                  - NAMES_PT;
    return room > ROW_PT ? (size_t)(room / ROW_PT) : 1;
}

void bf_fig_param_label(const bf_param *p, char *buf, size_t len)
{
    static const char *const from[] = {"sigma", "rho", "theta", "n_d"};
    static const char *const to[] = {"\xcf\x83", "\xcf\x81", "\xce\xb8",
                                     "n_{d}"};
    char tmp[64];
    const char *s = p->label;
    size_t j = 0;
    while (*s != '\0' && j + 8 < sizeof tmp) {
        size_t k;
        for (k = 0; k < sizeof from / sizeof *from; k++) {
            size_t n = strlen(from[k]);
            if (strncmp(s, from[k], n) == 0) {
                j += (size_t)snprintf(tmp + j, sizeof tmp - j, "%s", to[k]);
                s += n;
                break;
            }
        }
        if (k == sizeof from / sizeof *from) {
            tmp[j++] = *s++;
        }
    }
    tmp[j] = '\0';
    if (strcmp(p->unit, "1") == 0) {
        snprintf(buf, len, "%s", tmp);
    } else {
        snprintf(buf, len, "%s (%s)", tmp, p->unit);
    }
}

/* Free parameters of model m analysed for some sample. */
static unsigned free_params(const bf_rep_study *st, size_t m)
{
    unsigned mask = 0;
    size_t s;
    for (s = 0; s < st->n_samples; s++) {
        const bf_fit_stats *f = &st->stats[s * st->n_models + m];
        if (f->done) {
            mask |= f->free_mask;
        }
    }
    return mask;
}

static size_t popcount(unsigned v)
{
    size_t n = 0;
    for (; v != 0; v &= v - 1) {
        n++;
    }
    return n;
}

/* Sample names of the rows, top to bottom in study order, at y = N - s. */
static const char **sample_names(const bf_rep_study *st, bf_fig_desc *d)
{
    size_t N = st->n_samples;
    char (*buf)[128] = bf_fig_alloc(d, N * sizeof *buf);
    const char **names = bf_fig_alloc(d, N * sizeof *names);
    size_t s;
    if (buf == NULL || names == NULL) {
        return NULL;
    }
    for (s = 0; s < N; s++) {
        bf_fig_sample_tick(st, s, buf[s], sizeof buf[s]);
        names[N - 1 - s] = buf[s];
    }
    return names;
}

/* ==== forest plots ======================================================= */

/* Columns of a forest plot of nj parameter panels at D's width: all in
 * one row, or fewer (rows of panels, each with the sample names) where
 * the axes beside the names would be narrower than FOREST_MIN_AXES. */
static size_t forest_cols(const bf_fig_data *D, size_t nj)
{
    size_t cols = nj > 0 ? nj : 1;
    while (cols > 1 && ((double)D->o->width - FOREST_NAMES_PT) /
                               (double)cols < FOREST_MIN_AXES) {
        cols--;
    }
    return cols;
}

size_t bf_fig_forest_rows(const bf_fig_data *D, size_t m)
{
    size_t nj = popcount(free_params(D->st, m));
    size_t cols = forest_cols(D, nj);
    size_t grid = nj > 0 ? (nj + cols - 1) / cols : 1;
    double room = BF_PLOT_MAX_TALL * (double)D->o->width - FRAME_PT -
                  (double)(grid - 1) * XLABEL_PT;
    double rows = room / (ROW_PT * (double)grid);
    return rows >= 1.0 ? (size_t)rows : 1;
}


int bf_fig_forest(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                  int full)
{
    const bf_rep_study *st = D->st;
    size_t s0 = e->count > 0 ? e->first : 0; /* this page's rows */
    size_t N = e->count > 0 ? e->count : st->n_samples;
    size_t m = e->index;
    const bf_model_type *t = st->models[m];
    unsigned mask = free_params(st, m);
    size_t nj = popcount(mask);
    const char **names = sample_names(st, d);
    bf_plot_panel *panel = bf_fig_alloc(d, nj * sizeof *panel);
    bf_plot_series *ser = bf_fig_alloc(d, 4 * nj * sizeof *ser);
    double *v = bf_fig_alloc(d, 10 * N * nj * sizeof *v);
    unsigned *open = bf_fig_alloc(d, N * nj * sizeof *open);
    char (*xl)[128] = bf_fig_alloc(d, nj * sizeof *xl);
    char each[48];
    int boot = st->opts.n_boot >= 2;
    size_t j;
    size_t q = 0;
    size_t s;

    (void)full;
    if (names == NULL || panel == NULL || ser == NULL || v == NULL ||
        open == NULL || xl == NULL || nj == 0) {
        return nj == 0 ? BF_EINVAL : BF_ENOMEM;
    }
    for (j = 0; j < t->p; j++) {
        double *est = &v[10 * N * q];
        double *lo = est + N;
        double *hi = lo + N;
        double *blo = hi + N;
        double *bhi = blo + N;
        double *y = bhi + N;
        double *yb = y + N;
        double *ml = yb + N; /* the estimate the interval is about */
        double *gl = ml + N; /* a split interval's gap */
        double *gh = gl + N;
        double xmin = HUGE_VAL;
        double xmax = -HUGE_VAL;
        bf_plot_series *sq = &ser[4 * q];
        if (!((mask >> j) & 1u)) {
            continue;
        }
        for (s = 0; s < N; s++) {
            const bf_fit_stats *f = &st->stats[(s0 + s) * st->n_models + m];
            int ok = f->done && ((f->free_mask >> j) & 1u);
            est[s] = ok ? f->refined.param[j] : NAN;
            lo[s] = ok ? f->ci_low[j] : NAN;
            hi[s] = ok ? f->ci_high[j] : NAN;
            ml[s] = ok ? f->ml_param[j] : NAN;
            gl[s] = ok ? f->ci_gap_low[j] : NAN;
            gh[s] = ok ? f->ci_gap_high[j] : NAN;
            blo[s] = ok ? f->boot_low[j] : NAN;
            bhi[s] = ok ? f->boot_high[j] : NAN;
            y[s] = (double)(N - s);
            yb[s] = y[s] - BOOT_OFFSET;
            open[q * N + s] = ok ? (f->ci_open >> (2 * j)) & 3u : 0u;
            if (ok) {
                xmin = fmin(xmin, fmin(est[s], isfinite(lo[s]) ? lo[s]
                                                               : est[s]));
                xmax = fmax(xmax, fmax(est[s], isfinite(hi[s]) ? hi[s]
                                                               : est[s]));
                if (boot && isfinite(blo[s]) && isfinite(bhi[s])) {
                    xmin = fmin(xmin, blo[s]);
                    xmax = fmax(xmax, bhi[s]);
                }
            }
        }
        if (!(xmax > xmin)) { /* one value: a window around it */
            double w = isfinite(xmin) ? fmax(0.05 * fabs(xmin), 0.01) : 1.0;
            xmin = isfinite(xmin) ? xmin - w : 0.0;
            xmax = xmin + 2 * w;
        }
        sq[0].kind = BF_SERIES_INTERVALS;
        sq[0].x = lo;
        sq[0].x2 = hi;
        sq[0].y = y;
        sq[0].open = &open[q * N];
        sq[0].gap_lo = gl;
        sq[0].gap_hi = gh;
        sq[0].n = N;
        sq[0].style = bf_report_model_style(t);
        sq[0].dash = BF_DASH_SOLID;
        sq[0].weight = 1.3;
        sq[0].label = bf_rep_neyman_scope(st) == BF_REP_NEYMAN_EVERY &&
                              t->kind != BF_MODEL_SPECULAR
                          ? "profile 95% interval (Neyman construction)"
                          : "profile 95% interval";
        sq[1] = sq[0];
        sq[1].x = blo;
        sq[1].x2 = bhi;
        sq[1].y = yb;
        sq[1].open = NULL;
        sq[1].gap_lo = sq[1].gap_hi = NULL;
        sq[1].n = boot ? N : 0;
        sq[1].dash = BF_DASH_DOTTED;
        sq[1].weight = 0.9;
        sq[1].label = boot ? "bootstrap 95% interval" : NULL;
        sq[2].kind = BF_SERIES_POINTS;
        sq[2].x = est;
        sq[2].y = y;
        sq[2].n = N;
        sq[2].style = sq[0].style;
        sq[2].label = "exact optimum";
        /* the noise model's estimate, the interval's centre: it differs
         * from the optimum where the noise model weights the residuals;
         * drawn first, so the optimum's marker covers it where equal */
        sq[3] = sq[2];
        sq[2].x = ml;
        sq[2].style = BF_PLOT_INK;
        sq[2].label = BF_FIG_ML_LABEL;
        bf_fig_param_label(&t->param[j], xl[q], sizeof xl[q]);
        panel[q].xmin = xmin - 0.04 * (xmax - xmin);
        panel[q].xmax = xmax + 0.04 * (xmax - xmin);
        panel[q].ymin = 0.3;
        panel[q].ymax = (double)N + 0.7;
        panel[q].ytick_labels = names + (st->n_samples - s0 - N);
        panel[q].n_yticks = N;
        panel[q].xlabel = xl[q];
        panel[q].series = sq;
        panel[q].n_series = 4;
        q++;
    }
    /* the sample names, then at most 200 points a parameter */
    d->fig.nx = forest_cols(D, nj);
    d->fig.ny = (nj + d->fig.nx - 1) / d->fig.nx;
    d->fig.height = (unsigned)ceil((double)(d->fig.ny * N) * ROW_PT +
                                   FRAME_PT +
                                   (double)(d->fig.ny - 1) * XLABEL_PT);
    d->fig.share_y = 1;
    d->fig.legend = BF_LEGEND_TOP;
    d->fig.panels = panel;
    d->fig.n_panels = nj;
    rows_width(d, 160.0 + 200.0 * (double)d->fig.nx, D->o->width);
    rows_height(d);
    page_name(e, st->n_samples, "forest_", t->name);
    snprintf(e->title, sizeof e->title,
             "%s: fitted parameters and their 95%% intervals", t->name);
    snprintf(e->caption, sizeof e->caption,
             "For %s, %s's exact optimum (points; the "
             "objective \"%s\" minimised by refinement of the grid optimum, "
             "doc/methods.md §2) and its 95%% profile interval (solid: the "
             "noise model's likelihood profile%s, doc/methods.md §3), which "
             "is about the noise model's maximum-likelihood estimate "
             "(black dots, fits.csv's ml_value): where the noise model "
             "weights the residuals that estimate can differ from the "
             "optimum, and the interval need not hold the optimum%s. An "
             "interval that reaches the search range is cut there and drawn "
             "without an end tick; one in two regions apart is drawn as its "
             "two segments (fits.csv ci_gap_low, ci_gap_high).",
             bf_fig_each_sample(N, each, sizeof each), t->name,
             bf_objective_name(st->opts.objective),
             bf_rep_neyman_scope(st) == BF_REP_NEYMAN_NONE ||
                     t->kind == BF_MODEL_SPECULAR
                 ? ""
             : bf_rep_neyman_scope(st) == BF_REP_NEYMAN_EVERY
                 ? ", each end's threshold calibrated by simulation (the "
                   "Neyman construction)"
                 : "; where a second minimum of the profile competes "
                   "with the estimate's (flag competing), each end's "
                   "threshold calibrated by simulation (the Neyman "
                   "construction, ci_method neyman)",
             boot ? "; dotted below it, the residual bootstrap's "
                    "percentile interval (residuals resampled under the "
                    "noise model and refitted, doc/methods.md §3)"
                  : "");
    snprintf(e->alt, sizeof e->alt,
             "Forest plot: %s's fitted parameter%s with 95%% intervals for "
             "%zu sample%s.",
             t->name, nj == 1 ? "" : "s", N, N == 1 ? "" : "s");
    return BF_OK;
}

/* ==== delta BIC overview ================================================= */

/* The evidence class of delta BIC [1]: 0 the best model, then (0, 2],
 * (2, 6], (6, 10], > 10; -1 when not computed. */
static int bic_class(double delta)
{
    if (!isfinite(delta)) {
        return -1;
    }
    if (delta <= 0.0) {
        return 0;
    }
    return delta <= 2.0 ? 1 : delta <= 6.0 ? 2 : delta <= 10.0 ? 3 : 4;
}

int bf_fig_delta_bic(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                     int full)
{
    static const char *const classes[BF_PLOT_NCLASSES] = {
        "\xce\x94" "BIC = 0 (best)", "\xe2\x89\xa4 2", "2\xe2\x80\x93" "6",
        "6\xe2\x80\x93" "10", "> 10"};
    const bf_rep_study *st = D->st;
    size_t N0 = e->count > 0 ? e->first : 0; /* this page's rows */
    size_t N = e->count > 0 ? e->count : st->n_samples;
    size_t M = st->n_models;
    const char **names = sample_names(st, d);
    const char **models = bf_fig_alloc(d, M * sizeof *models);
    int *cls = bf_fig_alloc(d, N * M * sizeof *cls);
    const char **text = bf_fig_alloc(d, N * M * sizeof *text);
    char (*buf)[16] = bf_fig_alloc(d, N * M * sizeof *buf);
    bf_plot_cells *cells = bf_fig_alloc(d, sizeof *cells);
    bf_plot_panel *p = bf_fig_alloc(d, sizeof *p);
    double want = 110.0 + 52.0 * (double)M; /* names, then cells */
    size_t s;
    size_t m;

    (void)full;
    if (names == NULL || models == NULL || cls == NULL || text == NULL ||
        buf == NULL || cells == NULL || p == NULL) {
        return BF_ENOMEM;
    }
    for (m = 0; m < M; m++) {
        models[m] = st->models[m]->name;
    }
    for (s = 0; s < N; s++) {
        double best = HUGE_VAL;
        size_t r = N - 1 - s; /* the first sample on top */
        size_t row = N0 + s;
        for (m = 0; m < M; m++) {
            double b = bf_rep_rank_value(st, row * M + m, BF_REP_BIC);
            best = isfinite(b) ? fmin(best, b) : best;
        }
        for (m = 0; m < M; m++) {
            double b = bf_rep_rank_value(st, row * M + m, BF_REP_BIC);
            double delta = b - best;
            size_t c = r * M + m;
            cls[c] = bic_class(delta);
            if (!isfinite(delta)) {
                snprintf(buf[c], sizeof buf[c], "\xe2\x80\x93");
            } else if (delta == 0.0) {
                snprintf(buf[c], sizeof buf[c], "0");
            } else if (delta < 9.95) {
                snprintf(buf[c], sizeof buf[c], "%.1f", delta);
            } else if (delta < 999.5) {
                snprintf(buf[c], sizeof buf[c], "%.0f", delta);
            } else { /* four digits and more, in thousands: "15k" */
                snprintf(buf[c], sizeof buf[c], "%.0fk", fmin(delta / 1e3,
                                                             999.0));
            }
            text[c] = buf[c];
        }
    }
    cells->nx = M;
    cells->ny = N;
    cells->cls = cls;
    cells->text = text;
    cells->n_classes = BF_PLOT_NCLASSES;
    cells->class_label = classes;
    p->xmin = 0.5;
    p->xmax = (double)M + 0.5;
    p->ymin = 0.5;
    p->ymax = (double)N + 0.5;
    p->xtick_labels = models;
    p->n_xticks = M;
    p->ytick_labels = names + (st->n_samples - N0 - N); /* bottom up */
    p->n_yticks = N;
    p->cells = cells;
    d->fig.height = (unsigned)ceil((double)N * ROW_PT + FRAME_PT);
    d->fig.nx = d->fig.ny = 1;
    d->fig.legend = BF_LEGEND_TOP;
    d->fig.panels = p;
    d->fig.n_panels = 1;
    rows_width(d, want, D->o->width);
    rows_height(d);
    page_name(e, st->n_samples, "delta_bic", "");
    snprintf(e->title, sizeof e->title,
             "Model selection at a glance: \xce\x94" "BIC per sample");
    snprintf(e->caption, sizeof e->caption,
             "For each sample (rows) and model (columns), BIC minus the "
             "lowest BIC of that sample (Gaussian errors, the refined "
             "optimum of the objective \"%s\"; doc/methods.md §4): 0 marks "
             "the best model, and the shades follow Kass and Raftery's "
             "evidence against a model (\xe2\x89\xa4 2 barely worth a "
             "mention, 2\xe2\x80\x93" "6 positive, 6\xe2\x80\x93" "10 "
             "strong, > 10 very strong); \xe2\x80\x93: not evaluated.",
             bf_objective_name(st->opts.objective));
    snprintf(e->alt, sizeof e->alt,
             "Heat map: delta BIC of %zu model%s for %zu sample%s, darker "
             "for models closer to the best.",
             M, M == 1 ? "" : "s", N, N == 1 ? "" : "s");
    return BF_OK;
}

/* ==== profiles =========================================================== */

size_t bf_fig_profile_panels(const bf_rep_study *st, size_t s, int family)
{
    size_t M = st->n_models;
    size_t np = 0;
    size_t m;
    for (m = 0; m < M; m++) {
        const bf_fit_stats *f = &st->stats[s * M + m];
        if (bf_fig_in_family(st, m, family) && f->done) {
            np += popcount(f->free_mask);
        }
    }
    return np;
}

int bf_fig_profile(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                   int full)
{
    const bf_rep_study *st = D->st;
    size_t s = e->index;
    size_t M = st->n_models;
    size_t np = 0;
    size_t m;
    size_t j;
    size_t q = 0;
    bf_plot_panel *panel;
    bf_plot_series *ser;
    double *v;
    char (*xl)[128];
    unsigned *open;
    char who[256];
    char key[64];
    char part[32];
    size_t rows;
    size_t all = 0; /* the family's panels so far */
    /* the intervals' criterion: the noise model's likelihood, or with
     * --noise objective the objective's own S */
    int lik = st->analysis.noise != BF_NOISE_OBJECTIVE;
    np = bf_fig_profile_panels(st, s, e->family);
    panel = bf_fig_alloc(d, (np + 1) * sizeof *panel);
    ser = bf_fig_alloc(d, 4 * (np + 1) * sizeof *ser);
    v = bf_fig_alloc(d, (2 * PROFILE_POINTS + PROFILE_EXTRA) * (np + 1) *
                            sizeof *v);
    xl = bf_fig_alloc(d, (np + 1) * sizeof *xl);
    open = bf_fig_alloc(d, (np + 1) * sizeof *open);
    if (panel == NULL || ser == NULL || v == NULL || xl == NULL ||
        open == NULL) {
        return BF_ENOMEM;
    }
    bf_fig_sample_label(st, e->index, who, sizeof who);
    for (m = 0; m < M; m++) {
        const bf_fit_stats *f = &st->stats[s * M + m];
        const bf_model_type *t = bf_fig_row(st, s, m)->type;
        size_t nf = popcount(f->free_mask);
        size_t first = all; /* this model's first panel in the family */
        double *tm = NULL;  /* the library's profiles: theta, dev, thr */
        double *dm = NULL;
        double *thm = NULL;
        size_t qq = 0;
        if (!f->done || f->free_mask == 0 ||
            !bf_fig_in_family(st, m, e->family)) {
            continue;
        }
        all += nf;
        if (e->count > 0 && (first + nf <= e->first ||
                             first >= e->first + e->count)) {
            continue; /* every panel on another page of the family's */
        }
        {   /* the windows always (the layout's tick labels), the curves
             * when drawn */
            bf_error err;
            tm = bf_fig_alloc(d, 2 * PROFILE_POINTS * nf * sizeof *tm);
            thm = bf_fig_alloc(d, nf * sizeof *thm);
            if (tm == NULL || thm == NULL) {
                return BF_ENOMEM;
            }
            dm = tm + PROFILE_POINTS * nf;
            for (j = 0; j < 2 * PROFILE_POINTS * nf; j++) {
                tm[j] = NAN; /* what a failure leaves undrawn */
            }
            for (j = 0; j < nf; j++) {
                thm[j] = NAN;
            }
            if (bf_study_profiles(&st->spec, &st->analysis, st->rows,
                                  st->stats, s * M + m, PROFILE_POINTS, tm,
                                  full ? dm : NULL, thm,
                                  &err) == BF_ENOMEM) {
                return BF_ENOMEM;
            }
        }
        for (j = 0; j < t->p; j++) {
            double *theta = &v[(2 * PROFILE_POINTS + PROFILE_EXTRA) * q];
            double *dev = theta + PROFILE_POINTS;
            double *ci = dev + PROFILE_POINTS; /* low, high; y of both */
            double *thr_x = ci + 4;            /* x0, x1; the optimum's y */
            double *thr_y = thr_x + 3;         /* the threshold's y */
            double thr = CHI2_95;
            /* a specular model's robust factor: the curve and its
             * threshold divided by it (Stafford's adjusted profile), so
             * every panel's threshold is the same line */
            double c = isfinite(f->ci_robust[j]) ? f->ci_robust[j] : 1.0;
            size_t k;
            bf_plot_series *sq = &ser[4 * q];
            if (!((f->free_mask >> j) & 1u)) {
                continue;
            }
            qq++;
            if (e->count > 0 && (first + qq - 1 < e->first ||
                                 first + qq - 1 >= e->first + e->count)) {
                continue; /* on another page of the family's panels */
            }
            for (k = 0; k < PROFILE_POINTS; k++) {
                double x = tm[(qq - 1) * PROFILE_POINTS + k];
                theta[k] = isfinite(x) ? x : (double)k / (PROFILE_POINTS - 1);
                dev[k] = dm[(qq - 1) * PROFILE_POINTS + k] / c;
            }
            if (isfinite(thm[qq - 1])) {
                thr = thm[qq - 1] / c; /* else no noise fit, no curve */
            }
            ci[0] = f->ci_low[j];
            ci[1] = f->ci_high[j];
            ci[2] = ci[3] = thr;
            thr_y[0] = thr_y[1] = thr;
            thr_x[0] = theta[0];
            thr_x[1] = theta[PROFILE_POINTS - 1];
            sq[0].kind = BF_SERIES_LINE;  /* the threshold */
            sq[0].x = thr_x;
            sq[0].y = thr_y;
            sq[0].n = 2;
            sq[0].style = BF_PLOT_REF;
            sq[0].weight = 0.8;
            sq[0].label = lik ? "95% threshold, n ln(1 + F/\xce\xbd)"
                              : "95% threshold, \xcf\x87\xc2\xb2\xe2\x82\x81 = 3.84";
            sq[1].kind = BF_SERIES_LINE;  /* the profile */
            sq[1].x = theta;
            sq[1].y = dev;
            sq[1].n = PROFILE_POINTS;
            sq[1].style = bf_report_model_style(t);
            sq[1].dash = BF_DASH_SOLID;
            open[q] = (f->ci_open >> (2 * j)) & 3u;
            sq[2].kind = BF_SERIES_INTERVALS; /* the interval */
            sq[2].open = &open[q];
            sq[2].x = &ci[0];
            sq[2].x2 = &ci[1];
            sq[2].gap_lo = &f->ci_gap_low[j];
            sq[2].gap_hi = &f->ci_gap_high[j];
            sq[2].y = &ci[2];
            sq[2].n = 1;
            sq[2].style = sq[1].style;
            sq[2].dash = BF_DASH_SOLID;
            sq[2].weight = 2.0;
            sq[3].kind = BF_SERIES_POINTS; /* the estimate it is about */
            sq[3].x = &f->ml_param[j];
            sq[3].y = &thr_x[2];
            thr_x[2] = 0.0;
            sq[3].n = 1;
            sq[3].style = sq[1].style;
            bf_fig_param_label(&t->param[j], xl[q], sizeof xl[q]);
            panel[q].xmin = theta[0];
            panel[q].xmax = theta[PROFILE_POINTS - 1];
            panel[q].ymin = -0.8;
            panel[q].ymax = PROFILE_YMAX;
            panel[q].ytick = 4.0;
            panel[q].note = t->name;
            panel[q].xlabel = xl[q];
            panel[q].series = sq;
            panel[q].n_series = 4;
            q++;
        }
    }
    if (q == 0) { /* nothing fitted for this sample: an empty panel */
        panel[0].xmin = 0.0;
        panel[0].xmax = 1.0;
        panel[0].ymin = 0.0;
        panel[0].ymax = PROFILE_YMAX;
        panel[0].note = "no fitted parameter";
        q = 1;
    }
    d->fig.width = D->o->width;
    d->fig.aspect = PROFILE_ASPECT;
    rows = (q + PROFILE_COLS - 1) / PROFILE_COLS; /* balanced rows */
    d->fig.nx = (q + rows - 1) / rows;
    d->fig.ny = rows;
    d->fig.share_y = 1;
    d->fig.ylabel = "n ln(S/S_{min})";
    d->fig.legend = BF_LEGEND_TOP;
    d->fig.panels = panel;
    d->fig.n_panels = q;
    /* the specular models' profiles beside the diffuse ones', each in
     * pages of at most BF_FIG_PROFILE_PANELS panels */
    bf_fig_family_suffix(e->family, bf_fig_profile_panels(st, s,
                                                          BF_FIG_DIFFUSE) > 0,
                         e->parts > 1 ? e->first / ((np + e->parts - 1) /
                                                    e->parts) + 1
                                      : 1,
                         part, sizeof part);
    snprintf(e->base, sizeof e->base, "profile_%s%s",
             bf_fig_target_key(st, s, key, sizeof key), part);
    snprintf(e->title, sizeof e->title, "%.160s: profiles of the %s", who,
             lik ? "likelihood" : "objective");
    if (lik) {
        snprintf(e->caption, sizeof e->caption,
                 "For each fitted parameter of each model, the profile "
                 "n ln(S_p/S_min) of the noise model's likelihood (noise "
                 "'%s': %s; fits.csv noise; ci_method profile-lik, "
                 "doc/methods.md §3), S_p minimised "
                 "over the model's other free parameters%s, n = K = %zu "
                 "configurations, around the maximum-likelihood estimate "
                 "(point); a specular model's curve is divided by the "
                 "parameter's robust factor (fits.csv ci_robust, at least "
                 "1: its threshold widened where the residuals show more "
                 "variance than the noise model). The dashed line is the "
                 "95%% threshold n ln(1 + F_{1,nu}(0.95)/nu), nu = n minus "
                 "the estimated parameters (about 3.84); the thick segment, "
                 "where the curve lies below it, is the parameter's "
                 "reported 95%% interval (fits.csv ci_low, ci_high); where "
                 "the curve lies below it in two separate regions, two "
                 "segments, the ridge between them outside (fits.csv "
                 "ci_gap_low, ci_gap_high; flags not_identified; more than "
                 "two: one segment across them all).%s",
                 bf_noise_name(st->analysis.noise),
                 bf_noise_variance(st->analysis.noise),
                 bf_objective_keeps_scale(st->opts.objective)
                     ? ""
                     : " and the scale",
                 D->smp[s].K,
                 bf_rep_neyman_scope(st) == BF_REP_NEYMAN_NONE ? ""
                 : bf_rep_neyman_scope(st) == BF_REP_NEYMAN_EVERY
                     ? " With --neyman, a diffuse model's segment ends "
                       "where its curve reaches that end's simulated "
                       "threshold (the Neyman construction, ci_method "
                       "neyman), above or below the dashed line."
                     : " Where a diffuse model's curve has a second "
                       "minimum that competes with the estimate's (flag "
                       "competing), its segment ends where the curve "
                       "reaches that end's simulated threshold (the "
                       "Neyman construction, ci_method neyman), above or "
                       "below the dashed line.");
    } else {
        snprintf(e->caption, sizeof e->caption,
                 "For each fitted parameter of each model, the profile "
                 "n ln(S_p/S_min) of the objective \"%s\" (S_p minimised "
                 "over the model's other free parameters, n = K = %zu "
                 "configurations; doc/methods.md §3) around the exact "
                 "optimum (point); the 95%% profile interval is where the "
                 "curve lies below the dashed threshold 3.84 (thick "
                 "segment; two segments where it lies below in two "
                 "separate regions, flagged not_identified).",
                 bf_objective_name(st->opts.objective), D->smp[s].K);
    }
    snprintf(e->alt, sizeof e->alt,
             "%zu line plots: profile of the %s along each fitted "
             "parameter of %s, with the 95%% threshold.",
             q, lik ? "likelihood" : "objective", who);
    return BF_OK;
}
