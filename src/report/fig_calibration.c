/* fig_calibration.c: one sample's calibration figure (fig_internal.h,
 * `brdffit report --calibrate N`, doc/methods.md §3) -- for each fitted
 * parameter of each model calibrated, a panel with the maximum-likelihood
 * estimates of the N simulated measurements (a strip of points), the
 * range holding their central share at the intervals' level, the fit's
 * interval on the data (a bar) and the fitted value the simulations were
 * drawn from (a dashed line). When the intervals mean what they say, the
 * two bars are about as long, and the strip is centred on the line. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fig_internal.h"

/* The strip: points at y = 1 +- STRIP_HALF (a fixed jitter), the
 * estimates' central range at RANGE_Y, the fit's interval at BAR_Y; the
 * y axis from 0.4 to YMAX, its two rows named. */
#define STRIP_HALF 0.3
#define RANGE_Y 1.55
#define BAR_Y 2.0
#define YMAX 2.45
/* Style slots: the estimates and their range (open orange circles), the
 * fit's interval (black). */
#define SIM_STYLE 5u
/* Axes at least this wide (points), and the aspects tried (height over
 * width) until the panels fit a page. */
#define MIN_AXES 130.0
static const double aspects[] = {0.42, 0.3, 0.2};
/* Most panels a figure holds (the rest go to the sample's next part). */
#define MAX_PANELS 15
/* Series per panel. */
#define SERIES 5

size_t bf_fig_calibration_panels(const bf_rep_study *st, size_t s)
{
    size_t np = 0;
    size_t i;
    for (i = 0; i < st->cal.n; i++) {
        if (st->cal.pair[i] / st->n_models == s) {
            unsigned mask = st->stats[st->cal.pair[i]].free_mask;
            for (; mask != 0; mask &= mask - 1) {
                np++;
            }
        }
    }
    return np;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The sorted finite values of v[0..n) into out; returns how many. */
static size_t sorted(const double *v, size_t n, double *out)
{
    size_t m = 0;
    size_t r;
    for (r = 0; r < n; r++) {
        if (isfinite(v[r])) {
            out[m++] = v[r];
        }
    }
    qsort(out, m, sizeof *out, cmp_double);
    return m;
}

/* The q-quantile of the m sorted values (linear interpolation). */
static double quantile(const double *x, size_t m, double q)
{
    double h = q * (double)(m - 1);
    size_t lo = (size_t)floor(h);
    size_t hi = lo + 1 < m ? lo + 1 : lo;
    return x[lo] + (h - (double)lo) * (x[hi] - x[lo]);
}

/* A series of kind drawn solid in slot style (x2 only for intervals). */
static void series(bf_plot_series *s, bf_series_kind kind, const double *x,
                   const double *x2, const double *y, size_t n,
                   unsigned style, const char *label)
{
    memset(s, 0, sizeof *s);
    s->kind = kind;
    s->x = x;
    s->x2 = x2;
    s->y = y;
    s->n = n;
    s->style = style;
    s->dash = BF_DASH_SOLID;
    s->label = label;
}

/* What one panel points into. */
typedef struct {
    double *x;      /* n_sim estimates */
    double *y;      /* their jittered heights */
    double gap[2];  /* the interval's gap (NaN: none) */
    double v[12];   /* range low, high, y; interval low, high, y; truth x
                       twice, y twice; the interval's estimate */
    unsigned open;  /* the interval's open ends */
    char xl[128];
    char note[96];
} panel_data;

/* The series of a panel (ser[0..SERIES)) over q's n estimates. */
static void fill_series(bf_plot_series *ser, panel_data *q, size_t n)
{
    series(&ser[0], BF_SERIES_POINTS, q->x, NULL, q->y, n, SIM_STYLE,
           "simulated ML estimates");
    series(&ser[1], BF_SERIES_INTERVALS, &q->v[0], &q->v[1], &q->v[2], 1,
           SIM_STYLE, "their central 95%");
    series(&ser[2], BF_SERIES_INTERVALS, &q->v[3], &q->v[4], &q->v[5], 1,
           BF_PLOT_INK, "the fit's 95% interval");
    ser[2].open = &q->open;
    ser[2].gap_lo = &q->gap[0];
    ser[2].gap_hi = &q->gap[1];
    ser[2].weight = 1.6;
    series(&ser[3], BF_SERIES_LINE, &q->v[6], NULL, &q->v[8], 2, BF_PLOT_REF,
           "value simulated");
    ser[3].dash = BF_DASH_DASHED;
    series(&ser[4], BF_SERIES_POINTS, &q->v[10], NULL, &q->v[5], 1,
           BF_PLOT_INK, "its ML estimate");
}

/* Fills panel p (series ser[0..SERIES)) for parameter j of calibrated
 * pair i. */
static void fill(const bf_rep_study *st, size_t i, size_t j, panel_data *q,
                 double *work, bf_plot_panel *p, bf_plot_series *ser)
{
    static const char *const verdict[3] = {"low", "ok", "high"};
    const bf_calibration *c = &st->cal.cal[i];
    const bf_fit_stats *f = &st->stats[st->cal.pair[i]];
    const bf_model_type *t = st->rows[st->cal.pair[i]].type;
    size_t n = st->cal.n_sim;
    const double *est = st->cal.ml_est + (i * BF_MAX_PARAMS + j) * n;
    double level = st->analysis.level;
    double lo = HUGE_VAL;
    double hi = -HUGE_VAL;
    bf_calibration_summary s;
    size_t m;
    size_t r;
    int k;

    for (r = 0; r < n; r++) {
        q->x[r] = est[r];
        /* a fixed jitter: the fractional parts of r times the golden
         * ratio, spread evenly over the strip */
        q->y[r] = 1.0 + STRIP_HALF * (2.0 * fmod(0.6180339887498949 *
                                                     (double)r, 1.0) -
                                      1.0);
    }
    m = sorted(est, n, work);
    q->v[0] = m > 1 ? quantile(work, m, 0.5 * (1.0 - level)) : NAN;
    q->v[1] = m > 1 ? quantile(work, m, 0.5 * (1.0 + level)) : NAN;
    q->v[2] = RANGE_Y;
    q->v[3] = f->ci_low[j];
    q->v[4] = f->ci_high[j];
    q->gap[0] = f->ci_gap_low[j];
    q->gap[1] = f->ci_gap_high[j];
    q->v[5] = BAR_Y;
    q->v[6] = q->v[7] = c->truth[j];
    q->v[8] = 0.4;
    q->v[9] = YMAX;
    q->v[10] = f->ml_param[j];
    q->open = (f->ci_open >> (2 * j)) & 3u;
    if (m > 0) {
        lo = work[0];
        hi = work[m - 1];
    }
    for (k = 0; k < 4; k++) { /* the interval, its estimate, the truth */
        static const int at[4] = {3, 4, 6, 10};
        double x = q->v[at[k]];
        if (isfinite(x)) {
            lo = fmin(lo, x);
            hi = fmax(hi, x);
        }
    }
    if (!(hi > lo)) { /* one value: a window around it */
        double w = isfinite(lo) ? fmax(0.05 * fabs(lo), 0.01) : 1.0;
        lo = isfinite(lo) ? lo - w : 0.0;
        hi = lo + 2.0 * w;
    }
    if (bf_calibration_summarise(c, j, level, &s) == BF_OK) {
        snprintf(q->note, sizeof q->note, "%s %s: %.2f %s", t->name,
                 t->param[j].name, s.coverage, verdict[s.verdict + 1]);
    } else {
        snprintf(q->note, sizeof q->note, "%s %s", t->name,
                 t->param[j].name);
    }
    bf_fig_param_label(&t->param[j], q->xl, sizeof q->xl);

    fill_series(ser, q, n);
    p->xmin = lo - 0.05 * (hi - lo);
    p->xmax = hi + 0.05 * (hi - lo);
    p->ymin = 0.4;
    p->ymax = YMAX;
    p->note = q->note;
    p->xlabel = q->xl;
    p->series = ser;
    p->n_series = SERIES;
}

/* Lays out fig's panels (its width set) in the grid and aspect with the
 * widest axes, up to MIN_AXES wide, that fit a page. BF_OK, or BF_EINVAL
 * when none fits. */
static int lay_out(bf_plot_figure *fig)
{
    int rc = BF_EINVAL;
    size_t a;
    fig->share_y = 1;
    fig->legend = BF_LEGEND_TOP;
    for (a = 0; a < sizeof aspects / sizeof *aspects; a++) {
        fig->aspect = aspects[a];
        rc = bf_plot_flow(fig, MIN_AXES);
        if (rc == BF_OK && bf_plot_fits(fig, MIN_AXES)) {
            return BF_OK;
        }
    }
    return rc;
}

size_t bf_fig_calibration_per_figure(const bf_fig_data *D)
{
    static const char *const rows[2] = {"simulated", "data"};
    static const double x[2] = {0.0, 1.0};
    static const double y[2] = {1.0, 2.0};
    bf_plot_panel panel[MAX_PANELS];
    bf_plot_series ser[SERIES];
    panel_data q;
    bf_plot_figure fig;
    size_t k;
    size_t i;
    /* the series of a panel, with their legend labels */
    memset(&q, 0, sizeof q);
    fill_series(ser, &q, 1);
    for (i = 0; i < SERIES; i++) {
        ser[i].x = x;
        ser[i].x2 = x + 1;
        ser[i].y = y;
        ser[i].open = NULL;
    }
    memset(panel, 0, sizeof panel);
    for (i = 0; i < MAX_PANELS; i++) { /* a long name and label */
        panel[i].xmin = 0.0;
        panel[i].xmax = 1.0;
        panel[i].ymin = 0.4;
        panel[i].ymax = YMAX;
        panel[i].ytick_labels = rows;
        panel[i].n_yticks = 2;
        panel[i].note = "LAMBERT+GGX alpha: 0.95 high";
        panel[i].xlabel = "refractive index n";
        panel[i].series = ser;
        panel[i].n_series = SERIES;
    }
    for (k = 2; k <= MAX_PANELS; k++) {
        memset(&fig, 0, sizeof fig);
        fig.width = D->o->width;
        fig.panels = panel;
        fig.n_panels = k;
        if (lay_out(&fig) != BF_OK || !bf_plot_fits(&fig, MIN_AXES)) {
            break;
        }
    }
    return k - 1;
}

int bf_fig_calibration(const bf_fig_data *D, bf_fig_entry *e,
                       bf_fig_desc *d, int full)
{
    static const char *const rows[2] = {"simulated", "data"};
    const bf_rep_study *st = D->st;
    size_t s = e->index;
    size_t n = st->cal.n_sim;
    size_t np;
    size_t K = 0;
    size_t i;
    size_t j;
    size_t q = 0;
    size_t all = 0;
    size_t per;
    bf_plot_panel *panel;
    bf_plot_series *ser;
    panel_data *pd;
    double *xy;
    double *work;
    char who[256];
    char key[64];
    const char *k;
    char part[64] = "";
    int rc;

    (void)full;
    for (i = 0; i < st->cal.n; i++) {
        if (st->cal.pair[i] / st->n_models == s) {
            K = st->stats[st->cal.pair[i]].n;
        }
    }
    np = e->count;
    panel = bf_fig_alloc(d, (np + 1) * sizeof *panel);
    ser = bf_fig_alloc(d, SERIES * (np + 1) * sizeof *ser);
    pd = bf_fig_alloc(d, (np + 1) * sizeof *pd);
    xy = bf_fig_alloc(d, 2 * n * (np + 1) * sizeof *xy);
    work = bf_fig_alloc(d, (n + 1) * sizeof *work);
    if (panel == NULL || ser == NULL || pd == NULL || xy == NULL ||
        work == NULL) {
        return BF_ENOMEM;
    }
    for (i = 0; i < st->cal.n; i++) { /* the sample's panels, in order */
        const bf_fit_stats *f = &st->stats[st->cal.pair[i]];
        if (st->cal.pair[i] / st->n_models != s) {
            continue;
        }
        for (j = 0; j < BF_MAX_PARAMS; j++) {
            if (!((f->free_mask >> j) & 1u)) {
                continue;
            }
            if (all >= e->first && all < e->first + np) {
                pd[q].x = xy + 2 * n * q;
                pd[q].y = pd[q].x + n;
                fill(st, i, j, &pd[q], work, &panel[q], &ser[SERIES * q]);
                panel[q].ytick_labels = rows;
                panel[q].n_yticks = 2;
                q++;
            }
            all++;
        }
    }
    if (q == 0) {
        return BF_EINVAL; /* listed only with calibrated panels */
    }
    d->fig.width = D->o->width;
    d->fig.panels = panel;
    d->fig.n_panels = q;
    rc = lay_out(&d->fig);
    if (rc != BF_OK) {
        return rc;
    }
    bf_fig_sample_label(st, s, who, sizeof who);
    k = bf_fig_target_key(st, s, key, sizeof key);
    /* part k of e->parts, each but the last of per panels */
    per = (bf_fig_calibration_panels(st, s) + e->parts - 1) / e->parts;
    if (e->first == 0) {
        snprintf(e->base, sizeof e->base, "calibration_%s", k);
    } else { /* the sample's further parts: _2, _3, ... */
        snprintf(e->base, sizeof e->base, "calibration_%s_%zu", k,
                 e->first / per + 1);
    }
    if (e->parts > 1) {
        snprintf(part, sizeof part, " (part %zu of %zu)", e->first / per + 1,
                 e->parts);
    }
    snprintf(e->title, sizeof e->title,
             "%.160s: the intervals checked on simulated measurements%.30s",
             who, part);
    snprintf(e->caption, sizeof e->caption,
             "For each fitted parameter of each model (panels; above each, "
             "the share of the simulations' %.0f%% intervals that hold the "
             "value simulated, and the table's check), %zu measurements "
             "simulated at the sample's K = %zu configurations from the "
             "fitted parameters (dashed line) under the fitted noise model "
             "(--noise %s) and refitted: their maximum-likelihood "
             "estimates (points, spread vertically only to be seen), the "
             "range holding the central %.0f%% of them (thin bar), and the "
             "fit's %.0f%% interval on the data (thick bar; an end cut at "
             "the search range has no tick) with the maximum-likelihood "
             "estimate it is about (black point; under the objectives "
             "other than scale it may differ from the fitted value, "
             "doc/methods.md §3). When the intervals mean what "
             "they say, the two bars are about as long and the points "
             "centre on the line; a thick bar shorter than the thin one "
             "is an interval too narrow for these data (doc/methods.md "
             "§3).",
             100.0 * st->analysis.level, n, K,
             bf_noise_name(st->analysis.noise), 100.0 * st->analysis.level,
             100.0 * st->analysis.level);
    snprintf(e->alt, sizeof e->alt,
             "%zu strip plots: simulated estimates of each fitted parameter "
             "of %s against the fit's 95%% interval and the fitted value.",
             q, who);
    return BF_OK;
}
