/* figures.c: the report's figures (figures.h) -- computes the normalised
 * measured and predicted radiances of a finished study (SPEC §2) and
 * describes Figure 2(b), Figures 3-6, the plane-of-incidence views and the
 * model-wins chart for src/report/plot.c to draw.
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann
 *       Model": Figure 2(b) (LSE against samples sorted by FC-E slope),
 *       Figures 3-6 (predicted against measured radiance). */
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define DEG (M_PI / 180.0)

/* Figures 3-6 hold six samples each, as in the paper. */
#define SAMPLES_PER_FIGURE 6
/* The paper's scatter-plot models, in its order (Figures 3-6). */
static const char *const paper_scatter[] = {"ON", "LFTG", "VH-E", "FC-E"};

/* A measured configuration is "in the plane of incidence" when its viewing
 * direction lies within PLANE_TOL of that plane and its theta_i within
 * PLANE_TOL of the panel's incidence angle (CURET's in-plane
 * configurations lie exactly in it, at multiples of 11.25 degrees). */
#define PLANE_TOL (1.0 * DEG)
/* Model curves: points over theta_s in [-90, 90] degrees (1-degree steps). */
#define CURVE_POINTS 181
/* Plane-of-incidence axes: at least [0, 1], at most [0, PLANE_YMAX_CAP];
 * model peaks above it (the specular peak of a smooth surface, whose
 * configurations the fit leaves out) are clipped. */
#define PLANE_YMAX_CAP 1.6
/* Most models in one plane-of-incidence panel. */
#define MAX_MODELS 16

/* Figure sizes, pixels (PNG) or points (SVG, PDF). */
#define LSE_W 1400u
#define LSE_H 650u
#define PANEL 330u /* one scatter panel */
#define PLANE_W 1400u
#define PLANE_H 900u
#define POLAR_H 760u
#define WINS_W 800u
#define WINS_H 500u

/* ==== radiances =========================================================== */

/* Normalised measured and predicted radiance of one sample on the K used
 * configurations: data[k], pred[m * K + k], and scale[m], the maximum of
 * model m's raw curve over the K configurations (which normalises any
 * other curve of that model the same way, SPEC §2). ok[m] is 0 for a model
 * not evaluated for this sample. */
typedef struct {
    size_t K;
    size_t n_models;
    bf_geom *geom; /* the K used configurations (Beckmann's frame) */
    double *data;
    double *pred;
    double *scale;
    int *ok;
} radiances;

static void radiances_free(radiances *r)
{
    free(r->geom);
    free(r->data);
    free(r->pred);
    free(r->scale);
    free(r->ok);
    memset(r, 0, sizeof *r);
}

/* Fills r for sample index s of st: its used configurations and data as
 * the study fitted them. Returns BF_OK or a BF_E* code. */
static int radiances_compute(const bf_cli_study *st, size_t s, radiances *r)
{
    size_t nconf = bf_dataset_nconf(st->in.ds, st->targets[s].material);
    const bf_geom *all = bf_dataset_geom(st->in.ds, st->targets[s].material);
    size_t *sel = malloc((nconf + 1) * sizeof *sel);
    size_t K = 0;
    size_t k;
    size_t m;
    int rc;

    memset(r, 0, sizeof *r);
    r->n_models = st->n_models;
    r->geom = malloc((nconf + 1) * sizeof *r->geom);
    r->data = malloc((nconf + 1) * sizeof *r->data);
    r->pred = malloc((nconf * st->n_models + 1) * sizeof *r->pred);
    r->scale = calloc(st->n_models + 1, sizeof *r->scale);
    r->ok = calloc(st->n_models + 1, sizeof *r->ok);
    if (sel == NULL || r->geom == NULL || r->data == NULL ||
        r->pred == NULL || r->scale == NULL || r->ok == NULL) {
        free(sel);
        return BF_ENOMEM;
    }
    rc = bf_cli_target_data(st, s, sel, &K, r->data);
    for (k = 0; rc == BF_OK && k < K; k++) {
        r->geom[k] = all[sel[k]];
    }
    free(sel);
    r->K = K;
    if (rc != BF_OK) {
        return rc;
    }
    for (m = 0; m < st->n_models; m++) {
        const bf_study_row *row_m = &st->rows[s * st->n_models + m];
        double *p = &r->pred[m * K];
        double mx = -HUGE_VAL;
        if (row_m->status != BF_OK) {
            continue;
        }
        rc = bf_model_eval(row_m->type, row_m->fit.param, K, r->geom, p);
        if (rc != BF_OK) {
            return rc;
        }
        for (k = 0; k < K; k++) {
            mx = fmax(mx, p[k]);
        }
        if (!(mx > 0.0)) {
            return BF_EDOM;
        }
        for (k = 0; k < K; k++) {
            p[k] /= mx; /* SPEC §2: normalise by the max over K */
        }
        r->scale[m] = mx;
        r->ok[m] = 1;
    }
    return BF_OK;
}

/* ==== selections ========================================================== */

/* Index of model name in the study, or -1. */
static long model_index(const bf_cli_study *st, const char *name)
{
    size_t m;
    for (m = 0; m < st->n_models; m++) {
        if (strcmp(st->models[m]->name, name) == 0) {
            return (long)m;
        }
    }
    return -1;
}

/* The models of the scatter and plane figures: those of --models when it
 * was given, else the paper's ON, LFTG, VH-E, FC-E that the run has. */
static size_t scatter_models(const bf_cli_study *st, size_t *idx)
{
    size_t n = 0;
    size_t i;
    if (st->opts.models != NULL) {
        for (i = 0; i < st->n_models; i++) {
            idx[n++] = i;
        }
        return n;
    }
    for (i = 0; i < sizeof paper_scatter / sizeof *paper_scatter; i++) {
        long m = model_index(st, paper_scatter[i]);
        if (m >= 0) {
            idx[n++] = (size_t)m;
        }
    }
    return n;
}

/* Colour of a model (plot.h palette), the same in every figure and run:
 * the paper's models get the strongest colours. */
static const struct {
    const char *name;
    unsigned color;
} model_colors[] = {{"FC-E", 0}, {"VH-E", 1}, {"ON", 2},      {"LFTG", 3},
                    {"VH-G", 4}, {"FC-G", 5}, {"BK-G", 6},    {"BK-E", 7},
                    {"LAMBERT", 8}};
#define COLOR_MEASURED 9 /* black */

static unsigned model_color(const bf_model_type *type)
{
    size_t i;
    for (i = 0; i < sizeof model_colors / sizeof *model_colors; i++) {
        if (strcmp(model_colors[i].name, type->name) == 0) {
            return model_colors[i].color;
        }
    }
    return 8;
}

/* Sample indices sorted by increasing fitted FC-E slope (Figure 2(b));
 * by sample number when FC-E is not in the run. Returns 1 when sorted by
 * slope. */
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

static int order_by_slope(const bf_cli_study *st, size_t *order)
{
    long fc = model_index(st, "FC-E");
    int jm = fc >= 0 ? bf_model_param_index(st->models[fc], "m") : -1;
    sort_item *it = malloc(st->n_samples * sizeof *it);
    size_t s;
    int by_slope = jm >= 0;
    if (it == NULL) {
        return -1;
    }
    for (s = 0; s < st->n_samples && by_slope; s++) {
        by_slope = st->rows[s * st->n_models + (size_t)fc].status == BF_OK;
    }
    for (s = 0; s < st->n_samples; s++) {
        it[s].sample = st->samples[s];
        it[s].s = s;
        it[s].key =
            by_slope
                ? st->rows[s * st->n_models + (size_t)fc].fit.param[jm]
                : (double)st->samples[s];
    }
    qsort(it, st->n_samples, sizeof *it, cmp_item);
    for (s = 0; s < st->n_samples; s++) {
        order[s] = it[s].s;
    }
    free(it);
    return by_slope;
}

/* ==== temporary files ===================================================== */

static int make_dir(const char *dir)
{
    return bf_cli_make_outdir(dir);
}

/* Creates an empty temporary file for fig in format fmt. */
static int make_tmp(const bf_fig_set *set, bf_fig_entry *fig,
                    bf_plot_format fmt)
{
    int fd;
    int len = snprintf(fig->tmp[fmt], sizeof fig->tmp[fmt], "%s/.%s.%s.XXXXXX",
                       set->dir, fig->base, bf_plot_format_ext(fmt));
    if (len < 0 || (size_t)len >= sizeof fig->tmp[fmt]) {
        bf_cli_err("%s: output path too long", set->dir);
        fig->tmp[fmt][0] = '\0';
        return BF_EXIT_CANTCREAT;
    }
    fd = mkstemp(fig->tmp[fmt]);
    if (fd < 0) {
        bf_cli_err("%s/%s.%s: cannot create: %s", set->dir, fig->base,
                   bf_plot_format_ext(fmt), strerror(errno));
        fig->tmp[fmt][0] = '\0';
        return BF_EXIT_CANTCREAT;
    }
    (void)fchmod(fd, 0644);
    close(fd);
    return BF_EXIT_OK;
}

/* ==== drawing ============================================================= */

/* Shared state of one render. */
typedef struct {
    const bf_cli_study *st;
    const bf_fig_opts *o;
    bf_fig_set *set;
    size_t done;   /* files drawn */
    size_t total;  /* files to draw */
} render_ctx;

static size_t n_formats(unsigned formats)
{
    size_t n = 0;
    int f;
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        n += (formats >> f) & 1u;
    }
    return n;
}

/* Appends a figure entry; returns it, or NULL when out of memory. */
static bf_fig_entry *add_entry(bf_fig_set *set, bf_fig_kind kind, int sample)
{
    bf_fig_entry *f = realloc(set->fig, (set->n + 1) * sizeof *f);
    if (f == NULL) {
        return NULL;
    }
    set->fig = f;
    f = &set->fig[set->n++];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->sample = sample;
    return f;
}

/* Draws the figure description in every requested format. */
static int draw(render_ctx *c, bf_fig_entry *e, const bf_plot_figure *fig)
{
    int f;
    e->width = fig->width;
    e->height = fig->height;
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        int rc;
        if (!((c->set->formats >> f) & 1u)) {
            continue;
        }
        rc = make_tmp(c->set, e, (bf_plot_format)f);
        if (rc != BF_EXIT_OK) {
            return rc;
        }
        rc = bf_plot_write(fig, (bf_plot_format)f, e->tmp[f]);
        if (rc != BF_OK) {
            bf_cli_err("%s/%s.%s: cannot draw the figure: %s", c->set->dir,
                       e->base, bf_plot_format_ext((bf_plot_format)f),
                       bf_strerror(rc));
            return rc == BF_EIO ? BF_EXIT_IOERR : BF_EXIT_SOFTWARE;
        }
        c->done++;
        if (c->o->progress) {
            fprintf(stderr, "\rbrdffit report: drawing figures %zu/%zu",
                    c->done, c->total);
            fflush(stderr);
        }
    }
    return BF_EXIT_OK;
}

/* "Leather (16)", "Leather [R] (16)" or "sample 16" for target s. */
static const char *sample_label(const bf_cli_study *st, size_t s, char *buf,
                                size_t len)
{
    char title[96]; /* long names are cut: the label is a panel title */
    bf_cli_sample_title(st, s, title, sizeof title);
    if (title[0] != '\0') {
        snprintf(buf, len, "%.95s (%d)", title, st->samples[s]);
    } else {
        snprintf(buf, len, "sample %d", st->samples[s]);
    }
    return buf;
}

/* Describes a figure of one panel. */
static void one_panel(bf_plot_figure *fig, const bf_plot_panel *panel,
                      unsigned width, unsigned height)
{
    memset(fig, 0, sizeof *fig);
    fig->width = width;
    fig->height = height;
    fig->nx = fig->ny = 1;
    fig->text_scale = 1.0;
    fig->panels = panel;
    fig->n_panels = 1;
}

/* ---- Figure 2(b) -------------------------------------------------------- */

static int fig_lse(render_ctx *c)
{
    const bf_cli_study *st = c->st;
    size_t N = st->n_samples;
    size_t M = st->n_models;
    size_t *order = malloc(N * sizeof *order);
    double *x = malloc(N * sizeof *x);
    double *y = malloc(N * M * sizeof *y);
    char (*ticks)[16] = malloc(N * sizeof *ticks);
    const char **tick_ptr = malloc(N * sizeof *tick_ptr);
    bf_plot_series *ser = calloc(M, sizeof *ser);
    bf_plot_panel panel;
    bf_plot_figure fig;
    bf_fig_entry *e;
    double lo = HUGE_VAL;
    double hi = 0.0;
    size_t i;
    size_t m;
    int by_slope;
    int rc = BF_EXIT_SOFTWARE;

    if (order == NULL || x == NULL || y == NULL || ticks == NULL ||
        tick_ptr == NULL || ser == NULL ||
        (by_slope = order_by_slope(st, order)) < 0 ||
        (e = add_entry(c->set, BF_FIG_LSE, 0)) == NULL) {
        bf_cli_err("out of memory");
        goto done;
    }
    for (i = 0; i < N; i++) {
        x[i] = (double)(i + 1);
        snprintf(ticks[i], sizeof ticks[i], "%d", st->samples[order[i]]);
        tick_ptr[i] = ticks[i];
    }
    for (m = 0; m < M; m++) {
        for (i = 0; i < N; i++) {
            const bf_study_row *r = &st->rows[order[i] * M + m];
            y[m * N + i] = r->status == BF_OK ? r->fit.lse : NAN;
            if (r->status == BF_OK) {
                hi = fmax(hi, r->fit.lse);
                if (r->fit.lse > 0.0) {
                    lo = fmin(lo, r->fit.lse);
                }
            }
        }
        ser[m].x = x;
        ser[m].y = &y[m * N];
        ser[m].n = N;
        ser[m].style = BF_SERIES_LINEPOINTS;
        ser[m].color = model_color(st->models[m]);
        ser[m].marker = (unsigned)m;
        ser[m].label = st->models[m]->name;
    }
    if (!(hi > 0.0)) {
        hi = 1.0;
    }
    if (!(lo < HUGE_VAL)) {
        lo = hi / 10.0;
    }
    memset(&panel, 0, sizeof panel);
    panel.title = c->o->log_lse ? "Figure 2(b): LSE of each model "
                                  "(logarithmic axis)"
                                : "Figure 2(b): LSE of each model";
    panel.xlabel = by_slope ? "sample number, sorted by increasing "
                              "fitted FC-E slope σ/T"
                            : "sample number (FC-E not fitted: in "
                              "numerical order)";
    panel.ylabel = "LSE = Σ (L_model − L_data)² (dimensionless)";
    panel.xmin = 0.5;
    panel.xmax = (double)N + 0.5;
    panel.logy = c->o->log_lse;
    panel.ymin = panel.logy ? lo / 1.5 : 0.0;
    panel.ymax = panel.logy ? hi * 1.5 : hi * 1.08;
    panel.xtick_labels = tick_ptr;
    panel.n_xticks = N;
    panel.legend = 4;
    panel.series = ser;
    panel.n_series = M;
    one_panel(&fig, &panel, LSE_W, LSE_H);
    snprintf(e->base, sizeof e->base, "fig2b");
    snprintf(e->title, sizeof e->title,
             "Figure 2(b): LSE against the samples sorted by FC-E slope");
    snprintf(e->caption, sizeof e->caption,
             "Least-squared error (sum over the K = %zu used configurations) "
             "of each model for each sample; samples on the x-axis %s%s.",
             st->n_sel,
             by_slope ? "in order of increasing fitted FC-E slope σ/T, as in "
                        "the paper's Figure 2(b)"
                      : "in numerical order (FC-E was not fitted)",
             panel.logy ? "; logarithmic LSE axis" : "");
    rc = draw(c, e, &fig);
done:
    free(order);
    free(x);
    free(y);
    free(ticks);
    free(tick_ptr);
    free(ser);
    return rc;
}

/* ---- Figures 3-6: predicted against measured ---------------------------- */

/* Scatter panels for samples order[0..ns) (rows) and models idx[0..nm)
 * (columns). titles/ser are caller storage of ns * nm entries. */
static void scatter_panels(const bf_cli_study *st, const size_t *samples,
                           size_t ns, const size_t *idx, size_t nm,
                           const radiances *rad, bf_plot_panel *panel,
                           bf_plot_series *ser, char (*titles)[160])
{
    size_t a;
    size_t b;
    for (a = 0; a < ns; a++) {
        const radiances *r = &rad[a];
        for (b = 0; b < nm; b++) {
            size_t m = idx[b];
            size_t p = a * nm + b;
            const bf_study_row *row = &st->rows[samples[a] * st->n_models + m];
            char who[128];
            sample_label(st, samples[a], who, sizeof who);
            if (row->status == BF_OK) {
                snprintf(titles[p], sizeof titles[p], "%s: %s, LSE %.2f", who,
                         row->type->name, row->fit.lse);
            } else {
                snprintf(titles[p], sizeof titles[p], "%s: %s not evaluated",
                         who, row->type->name);
            }
            memset(&ser[p], 0, sizeof ser[p]);
            ser[p].x = r->data;
            ser[p].y = &r->pred[m * r->K];
            ser[p].n = r->ok[m] ? r->K : 0;
            ser[p].style = BF_SERIES_POINTS;
            ser[p].color = model_color(row->type);
            ser[p].marker = 0;
            memset(&panel[p], 0, sizeof panel[p]);
            panel[p].title = titles[p];
            panel[p].xlabel = "measured L/L_max (dimensionless)";
            panel[p].ylabel = "predicted L/L_max (dimensionless)";
            panel[p].xmin = panel[p].ymin = 0.0;
            panel[p].xmax = panel[p].ymax = 1.0;
            panel[p].square = 1;
            panel[p].diagonal = 1;
            panel[p].series = &ser[p];
            panel[p].n_series = 1;
        }
    }
}

/* One scatter figure: samples[0..ns) x models idx[0..nm). */
static int fig_scatter(render_ctx *c, bf_fig_kind kind, const size_t *samples,
                       size_t ns, const size_t *idx, size_t nm,
                       const radiances *rad, size_t number, size_t count)
{
    const bf_cli_study *st = c->st;
    bf_plot_panel *panel = calloc(ns * nm, sizeof *panel);
    bf_plot_series *ser = calloc(ns * nm, sizeof *ser);
    char (*titles)[160] = calloc(ns * nm, sizeof *titles);
    bf_plot_figure fig;
    bf_fig_entry *e;
    char models[256] = "";
    size_t b;
    int rc = BF_EXIT_SOFTWARE;

    if (panel == NULL || ser == NULL || titles == NULL ||
        (e = add_entry(c->set, kind, kind == BF_FIG_SAMPLE
                                         ? st->samples[samples[0]]
                                         : 0)) == NULL) {
        bf_cli_err("out of memory");
        goto done;
    }
    for (b = 0; b < nm; b++) {
        size_t len = strlen(models);
        snprintf(models + len, sizeof models - len, "%s%s", b ? ", " : "",
                 st->models[idx[b]]->name);
    }
    scatter_panels(st, samples, ns, idx, nm, rad, panel, ser, titles);
    memset(&fig, 0, sizeof fig);
    fig.nx = nm;
    fig.ny = ns;
    fig.width = PANEL * (unsigned)nm;
    fig.height = PANEL * (unsigned)ns;
    fig.text_scale = 0.8;
    fig.panels = panel;
    fig.n_panels = ns * nm;
    if (kind == BF_FIG_SAMPLE) {
        char who[128];
        snprintf(e->base, sizeof e->base, "scatter_sample%d",
                 st->samples[samples[0]]);
        snprintf(e->title, sizeof e->title, "%s: predicted against measured",
                 sample_label(st, samples[0], who, sizeof who));
    } else {
        snprintf(e->base, sizeof e->base, "scatter%zu", number);
        snprintf(e->title, sizeof e->title,
                 "Figures 3-6, part %zu of %zu: predicted against measured",
                 number, count);
    }
    snprintf(e->caption, sizeof e->caption,
             "Predicted against measured normalised radiance on the K = %zu "
             "used configurations, one row per sample, one column per model "
             "(%s); each curve divided by its maximum over the K "
             "configurations (SPEC §2); grey line: perfect agreement.",
             st->n_sel, models);
    rc = draw(c, e, &fig);
done:
    free(panel);
    free(ser);
    free(titles);
    return rc;
}

/* ---- plane of incidence ------------------------------------------------- */

/* Signed viewing angle in the plane of incidence: theta_s on the forward
 * (specular) side, -theta_s on the backward side (Beckmann frame, SPEC
 * §1.2: forward is phi_s = 0). */
static double signed_theta(const bf_geom *g)
{
    return cos(g->phi_s) >= 0.0 ? g->theta_s : -g->theta_s;
}

/* The points and curves of one plane-of-incidence panel. */
typedef struct {
    double px[64];                  /* measured: signed theta_s (rad) */
    double pxd[64];                 /* the same in degrees */
    double py[64];                  /* measured: normalised radiance */
    size_t np;
    double cx[CURVE_POINTS];        /* curve abscissae (rad) */
    double cxd[CURVE_POINTS];       /* the same in degrees */
    double cy[MAX_MODELS][CURVE_POINTS]; /* one curve per model */
} plane_data;

/* Fills pd for incidence theta_i: the used configurations in the plane
 * (within PLANE_TOL) and each model's curve, normalised by its maximum
 * over the K used configurations so points and curves compare as in the
 * fit (SPEC §2). Returns the largest value drawn. */
static double plane_compute(const bf_cli_study *st, const radiances *r,
                            size_t s, const size_t *idx,
                            size_t nm, double theta_i, plane_data *pd)
{
    double top = 0.0;
    size_t k;
    size_t b;
    bf_geom cg[CURVE_POINTS];

    pd->np = 0;
    for (k = 0; k < r->K && pd->np < 64; k++) {
        const bf_geom *g = &r->geom[k];
        double off = asin(fmin(1.0, sin(g->theta_s) * fabs(sin(g->phi_s))));
        if (fabs(g->theta_i - theta_i) <= PLANE_TOL && off <= PLANE_TOL) {
            pd->px[pd->np] = signed_theta(g);
            pd->pxd[pd->np] = pd->px[pd->np] / DEG;
            pd->py[pd->np] = r->data[k];
            top = fmax(top, r->data[k]);
            pd->np++;
        }
    }
    for (k = 0; k < CURVE_POINTS; k++) {
        double t = -M_PI / 2 + M_PI * (double)k / (CURVE_POINTS - 1);
        pd->cx[k] = t;
        pd->cxd[k] = t / DEG;
        cg[k].theta_i = theta_i;
        cg[k].phi_i = M_PI;
        cg[k].theta_s = fmin(fabs(t), M_PI / 2);
        cg[k].phi_s = t >= 0.0 ? 0.0 : M_PI;
    }
    for (b = 0; b < nm; b++) {
        size_t m = idx[b];
        const bf_study_row *row = &st->rows[s * st->n_models + m];
        double *y = pd->cy[b];
        if (!r->ok[m]) {
            for (k = 0; k < CURVE_POINTS; k++) {
                y[k] = NAN;
            }
            continue;
        }
        /* BF_EDOM leaves NaN where undefined: the line breaks there */
        (void)bf_model_eval(row->type, row->fit.param, CURVE_POINTS, cg, y);
        for (k = 0; k < CURVE_POINTS; k++) {
            y[k] /= r->scale[m];
            if (isfinite(y[k])) {
                top = fmax(top, y[k]);
            }
        }
    }
    return top;
}

/* The plane-of-incidence figure of sample index s, Cartesian or polar. */
static int fig_plane(render_ctx *c, size_t s, const radiances *r, const size_t *idx, size_t nm,
                     int polar)
{
    const bf_cli_study *st = c->st;
    size_t na = c->o->n_incidence;
    plane_data *pd = calloc(na, sizeof *pd);
    bf_plot_panel panel[BF_FIG_MAX_INCIDENCE];
    bf_plot_series ser[BF_FIG_MAX_INCIDENCE][MAX_MODELS + 1];
    char titles[BF_FIG_MAX_INCIDENCE][192];
    char labels[MAX_MODELS][64];
    char who[128];
    char models[256] = "";
    bf_plot_figure fig;
    bf_fig_entry *e;
    double top = 1.0;
    double ymax;
    size_t a;
    size_t b;
    int rc = BF_EXIT_SOFTWARE;

    if (pd == NULL || nm > MAX_MODELS ||
        (e = add_entry(c->set, polar ? BF_FIG_POLAR : BF_FIG_PLANE,
                       st->samples[s])) == NULL) {
        bf_cli_err("out of memory");
        goto done;
    }
    sample_label(st, s, who, sizeof who);
    for (a = 0; a < na; a++) {
        top = fmax(top, plane_compute(st, r, s, idx, nm,
                                      c->o->incidence[a], &pd[a]));
    }
    ymax = fmin(1.05 * top, PLANE_YMAX_CAP);
    for (b = 0; b < nm; b++) {
        const bf_study_row *row = &st->rows[s * st->n_models + idx[b]];
        size_t len = strlen(models);
        if (row->status == BF_OK) {
            snprintf(labels[b], sizeof labels[b], "%s (LSE %.2f)",
                     row->type->name, row->fit.lse);
        } else {
            snprintf(labels[b], sizeof labels[b], "%s (not evaluated)",
                     row->type->name);
        }
        snprintf(models + len, sizeof models - len, "%s%s", b ? ", " : "",
                 row->type->name);
    }
    for (a = 0; a < na; a++) {
        bf_plot_panel *p = &panel[a];
        memset(p, 0, sizeof *p);
        snprintf(titles[a], sizeof titles[a], "%s, θi = %.2f°", who,
                 c->o->incidence[a] / DEG);
        for (b = 0; b < nm; b++) {
            bf_plot_series *q = &ser[a][b];
            memset(q, 0, sizeof *q);
            q->x = polar ? pd[a].cx : pd[a].cxd;
            q->y = pd[a].cy[b];
            q->n = CURVE_POINTS;
            q->style = BF_SERIES_LINE;
            q->color = model_color(st->models[idx[b]]);
            q->dashed = (int)(b % 2);
            q->label = labels[b];
        }
        memset(&ser[a][nm], 0, sizeof ser[a][nm]);
        ser[a][nm].x = polar ? pd[a].px : pd[a].pxd;
        ser[a][nm].y = pd[a].py;
        ser[a][nm].n = pd[a].np;
        ser[a][nm].style = BF_SERIES_POINTS;
        ser[a][nm].color = COLOR_MEASURED;
        ser[a][nm].marker = 0;
        ser[a][nm].label = "measured";
        p->title = titles[a];
        p->polar = polar;
        p->ymin = 0.0;
        p->ymax = ymax;
        p->series = ser[a];
        p->n_series = nm + 1;
        p->legend = 4;
        if (polar) {
            p->xlabel = "angle: θs (°, > 0 forward); radius: L/L_max "
                        "(dimensionless)";
        } else {
            p->xmin = -90.0;
            p->xmax = 90.0;
            p->xlabel = "θs in the plane of incidence (°; > 0 forward)";
            p->ylabel = "L/L_max (dimensionless)";
        }
    }
    memset(&fig, 0, sizeof fig);
    fig.nx = na > 1 ? 2 : 1;
    fig.ny = (na + 1) / 2;
    fig.width = PLANE_W;
    fig.height = polar ? POLAR_H : PLANE_H;
    if (na <= 2) {
        fig.height /= 2;
    }
    fig.text_scale = 0.8;
    fig.panels = panel;
    fig.n_panels = na;
    snprintf(e->base, sizeof e->base, "%s_sample%d", polar ? "polar" : "plane",
             st->samples[s]);
    snprintf(e->title, sizeof e->title, "%s: plane of incidence%s", who,
             polar ? " (polar)" : "");
    snprintf(e->caption, sizeof e->caption,
             "Model curves (%s, fitted parameters) over θs from −90° to 90° "
             "in the plane of incidence (θs > 0: forward, the specular side), "
             "and the used measured configurations within %.0f° of that plane "
             "(points), for each incidence angle. Curves are divided by the "
             "model's maximum over the K = %zu used configurations, as in the "
             "fit, so points and curves compare directly; the radiance axis "
             "ends at %.2f (higher peaks are clipped).",
             models, PLANE_TOL / DEG, st->n_sel, ymax);
    rc = draw(c, e, &fig);
done:
    free(pd);
    return rc;
}

/* ---- wins ---------------------------------------------------------------- */

static int fig_wins(render_ctx *c)
{
    const bf_cli_study *st = c->st;
    size_t M = st->n_models;
    double *x = malloc(M * sizeof *x);
    double *y = calloc(M, sizeof *y);
    const char **names = malloc(M * sizeof *names);
    bf_plot_series ser;
    bf_plot_panel panel;
    bf_plot_figure fig;
    bf_fig_entry *e;
    double hi = 1.0;
    size_t s;
    size_t m;
    int rc = BF_EXIT_SOFTWARE;

    if (x == NULL || y == NULL || names == NULL ||
        (e = add_entry(c->set, BF_FIG_WINS, 0)) == NULL) {
        bf_cli_err("out of memory");
        goto done;
    }
    for (s = 0; s < st->n_samples; s++) {
        double best = HUGE_VAL;
        for (m = 0; m < M; m++) {
            const bf_study_row *r = &st->rows[s * M + m];
            if (r->status == BF_OK && r->fit.lse < best) {
                best = r->fit.lse;
            }
        }
        for (m = 0; m < M; m++) {
            const bf_study_row *r = &st->rows[s * M + m];
            if (r->status == BF_OK && r->fit.lse == best) {
                y[m] += 1.0; /* ties count for every tied model */
            }
        }
    }
    for (m = 0; m < M; m++) {
        x[m] = (double)(m + 1);
        names[m] = st->models[m]->name;
        hi = fmax(hi, y[m]);
    }
    memset(&ser, 0, sizeof ser);
    ser.x = x;
    ser.y = y;
    ser.n = M;
    ser.style = BF_SERIES_BARS;
    ser.color = 0;
    memset(&panel, 0, sizeof panel);
    panel.title = "Samples best fitted by each model (lowest LSE)";
    panel.xlabel = "model";
    panel.ylabel = "number of samples";
    panel.xmin = 0.4;
    panel.xmax = (double)M + 0.6;
    panel.ymin = 0.0;
    panel.ymax = ceil(hi * 1.15);
    panel.xtick_labels = names;
    panel.n_xticks = M;
    panel.series = &ser;
    panel.n_series = 1;
    one_panel(&fig, &panel, WINS_W, WINS_H);
    snprintf(e->base, sizeof e->base, "wins");
    snprintf(e->title, sizeof e->title, "Which model fits best");
    snprintf(e->caption, sizeof e->caption,
             "For each model, the number of the %zu samples on which it has "
             "the lowest LSE among the models evaluated for that sample "
             "(a tie counts for every tied model).",
             st->n_samples);
    rc = draw(c, e, &fig);
done:
    free(x);
    free(y);
    free(names);
    return rc;
}

/* ==== the render ========================================================== */

int bf_figures_render(const bf_cli_study *st, const bf_fig_opts *o,
                      const char *out_dir, bf_fig_set *set)
{
    render_ctx c;
    size_t idx[64];
    size_t nm;
    size_t N = st->n_samples;
    size_t n_fig;
    size_t s;
    size_t k;
    size_t g;
    size_t groups = (N + SAMPLES_PER_FIGURE - 1) / SAMPLES_PER_FIGURE;
    radiances *rad = calloc(N, sizeof *rad);
    size_t *all = malloc(N * sizeof *all);
    int rc;

    memset(set, 0, sizeof *set);
    set->formats = o->formats;
    snprintf(set->dir, sizeof set->dir, "%s/%s", out_dir, BF_FIG_DIR);
    if (rad == NULL || all == NULL) {
        bf_cli_err("out of memory");
        rc = BF_EXIT_SOFTWARE;
        goto done;
    }
    rc = make_dir(out_dir);
    if (rc == BF_EXIT_OK) {
        rc = make_dir(set->dir);
    }
    if (rc != BF_EXIT_OK) {
        goto done;
    }
    for (s = 0; s < N; s++) {
        int e = radiances_compute(st, s, &rad[s]);
        all[s] = s;
        if (e != BF_OK) {
            bf_cli_err("sample %d: cannot compute the radiances to plot: %s",
                       st->samples[s], bf_strerror(e));
            rc = e == BF_ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_DATAERR;
            goto done;
        }
    }
    nm = scatter_models(st, idx);
    if (nm == 0) { /* none of the paper's four: use every model */
        for (k = 0; k < st->n_models && k < 64; k++) {
            idx[nm++] = k;
        }
    }
    n_fig = 2 + groups + N * (2 + (o->per_sample ? 1 : 0));
    c.st = st;
    c.o = o;
    c.set = set;
    c.done = 0;
    c.total = n_fig * n_formats(o->formats);

    rc = fig_lse(&c);
    for (g = 0; g < groups && rc == BF_EXIT_OK; g++) {
        size_t ns = N - g * SAMPLES_PER_FIGURE;
        if (ns > SAMPLES_PER_FIGURE) {
            ns = SAMPLES_PER_FIGURE;
        }
        rc = fig_scatter(&c, BF_FIG_SCATTER, &all[g * SAMPLES_PER_FIGURE], ns,
                         idx, nm, &rad[g * SAMPLES_PER_FIGURE], g + 1, groups);
    }
    if (rc == BF_EXIT_OK) {
        rc = fig_wins(&c);
    }
    for (s = 0; s < N && rc == BF_EXIT_OK; s++) {
        if (o->per_sample) {
            rc = fig_scatter(&c, BF_FIG_SAMPLE, &all[s], 1, idx, nm, &rad[s],
                             0, 0);
        }
        if (rc == BF_EXIT_OK) {
            rc = fig_plane(&c, s, &rad[s], idx, nm, 0);
        }
        if (rc == BF_EXIT_OK) {
            rc = fig_plane(&c, s, &rad[s], idx, nm, 1);
        }
    }
    if (o->progress && c.done > 0) {
        fputc('\n', stderr);
    }
done:
    if (rad != NULL) {
        for (s = 0; s < N; s++) {
            radiances_free(&rad[s]);
        }
    }
    free(rad);
    free(all);
    if (rc != BF_EXIT_OK) {
        bf_figures_free(set);
        (void)rmdir(set->dir); /* only when empty: nothing else is lost */
    }
    return rc;
}

int bf_figures_commit(bf_fig_set *set)
{
    size_t i;
    int f;
    for (i = 0; i < set->n; i++) {
        bf_fig_entry *e = &set->fig[i];
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            char path[4200];
            if (e->tmp[f][0] == '\0') {
                continue;
            }
            snprintf(path, sizeof path, "%s/%s.%s", set->dir, e->base,
                     bf_plot_format_ext((bf_plot_format)f));
            if (rename(e->tmp[f], path) != 0) {
                bf_cli_err("%s: cannot rename into place: %s", path,
                           strerror(errno));
                return BF_EXIT_IOERR; /* bf_figures_free removes the rest */
            }
            e->tmp[f][0] = '\0';
        }
    }
    return BF_EXIT_OK;
}

void bf_figures_free(bf_fig_set *set)
{
    size_t i;
    int f;
    for (i = 0; i < set->n; i++) {
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            if (set->fig[i].tmp[f][0] != '\0') {
                unlink(set->fig[i].tmp[f]);
                set->fig[i].tmp[f][0] = '\0';
            }
        }
    }
    free(set->fig);
    set->fig = NULL;
    set->n = 0;
}
