/* fig_plane.c: one sample's fitted models and measurements in the plane
 * of incidence (fig_internal.h), as curves over the signed viewing angle
 * (Cartesian) or as a polar half-disc, one panel per incidence angle.
 * Curves are drawn as in the fit, so points and curves compare directly:
 * under the paper's objectives normalised (SPEC §2, bf_fit_curve); under
 * those that keep the scale (SPEC §10) in absolute units, the measured
 * rho = BRDF cos ti and each model's rho_hat with its fitted scales
 * (bf_study_fit_data, bf_fit_rho_curve), on a logarithmic radiance axis
 * when the measured points drawn span more than BF_LOG_AXIS_DECADES
 * decades (bf_fit_log_axis: the gloss peak and the diffuse floor both
 * visible). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fig_internal.h"
#include "model_style.h"

/* Model curves: theta_s over [-90, 90] degrees in 1-degree steps, with a
 * marker every 30 degrees. */
#define CURVE_POINTS 181
#define MARK_EVERY 30
/* The radiance axis: at least [0, 1] (Cartesian; the polar panels each
 * fit their own maximum), at most [0, YMAX_CAP]; model peaks above it
 * (the specular peak of a smooth surface, or grazing directions, where no
 * configuration is used) are cut. */
#define YMAX_CAP 1.3
#define MAX_POINTS 64
/* Axes height / width of the Cartesian panels. */
#define PLANE_ASPECT 0.62

/* The points and curves of one panel. */
typedef struct {
    double px[MAX_POINTS];  /* measured: signed theta_s, radians */
    double pxd[MAX_POINTS]; /* the same in degrees */
    double py[MAX_POINTS];  /* measured: normalised radiance */
    size_t np;
    double cx[CURVE_POINTS];  /* curve abscissae, radians */
    double cxd[CURVE_POINTS]; /* the same in degrees */
    double cy[BF_FIG_MAX_MODELS][CURVE_POINTS];
    char note[48];
} plane_data;

/* What the panels draw from: the used configurations and measured data of
 * the fit (normalised, or rho under the scale-keeping objectives: abs),
 * and with abs each model's problem (bf_fit_rho_curve's pb). */
typedef struct {
    size_t K;
    const bf_geom *geom;
    const double *data;
    int abs;
    bf_problem pb[BF_FIG_MAX_MODELS];
} plane_src;

int bf_fig_fit_data(const bf_fig_data *D, size_t s, bf_fig_desc *d,
                    size_t *K, const bf_geom **geom, const double **data,
                    int *abs)
{
    const bf_rep_study *st = D->st;
    const bf_fig_sample *r = &D->smp[s];
    bf_objective obj = st->opts.objective;
    size_t mat = st->targets[s].material;
    size_t nconf = bf_dataset_nconf(st->in.ds, mat);
    const bf_geom *all = bf_dataset_geom(st->in.ds, mat);
    size_t *sel;
    bf_geom *g;
    double *v;
    bf_error err;
    size_t k;
    int rc;
    *K = r->K;
    *geom = r->geom;
    *data = r->data;
    *abs = 0;
    if (!bf_objective_keeps_scale(obj)) {
        return BF_OK;
    }
    *abs = 1;
    sel = bf_fig_alloc(d, (nconf + 1) * sizeof *sel);
    g = bf_fig_alloc(d, (nconf + 1) * sizeof *g);
    v = bf_fig_alloc(d, (nconf + 1) * sizeof *v);
    if (sel == NULL || g == NULL || v == NULL) {
        return BF_ENOMEM;
    }
    rc = bf_study_fit_data(&st->spec, obj, s, sel, K, v, &err);
    for (k = 0; rc == BF_OK && k < *K; k++) {
        g[k] = all[sel[k]];
    }
    *geom = g;
    *data = v;
    return rc;
}

/* ps for sample index s: the figure data's (bf_fig_sample) under the
 * paper's objectives, the fit's rho (SPEC §10) under the others. */
static int src_init(const bf_fig_data *D, size_t s, bf_fig_desc *d,
                    plane_src *ps)
{
    const bf_rep_study *st = D->st;
    size_t b;
    int rc;

    memset(ps, 0, sizeof *ps);
    rc = bf_fig_fit_data(D, s, d, &ps->K, &ps->geom, &ps->data, &ps->abs);
    for (b = 0; rc == BF_OK && ps->abs && b < D->nm; b++) {
        const bf_study_row *row = bf_fig_row(st, s, D->idx[b]);
        rc = bf_problem_init(&ps->pb[b], row->type, row->fit.param, ps->K,
                             ps->geom, ps->data);
        ps->pb[b].objective = st->opts.objective;
    }
    return rc;
}

/* 1 when a fitted curve y[0..n) is zero (or undefined) everywhere: a fit
 * whose scales are all zero (SPEC §10), not drawn. */
static int curve_zero(const double *y, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++) {
        if (isfinite(y[k]) && y[k] != 0.0) {
            return 0;
        }
    }
    return 1;
}

/* Fills pd for incidence theta_i of sample index s. Returns the largest
 * value drawn, or -1 on error (*rc set). */
static double plane_compute(const bf_fig_data *D, size_t s,
                            const plane_src *r, double theta_i,
                            plane_data *pd, int *rc)
{
    const bf_rep_study *st = D->st;
    bf_geom cg[CURVE_POINTS];
    double *work = malloc(r->K * sizeof *work + 1);
    double top = 0.0;
    size_t k;
    size_t b;

    if (work == NULL) {
        *rc = BF_ENOMEM;
        return -1.0;
    }
    pd->np = 0;
    for (k = 0; k < r->K && pd->np < MAX_POINTS; k++) {
        double off;
        double t = bf_geom_plane_angle(&r->geom[k], &off);
        if (fabs(r->geom[k].theta_i - theta_i) <= BF_FIG_PLANE_TOL &&
            off <= BF_FIG_PLANE_TOL) {
            pd->px[pd->np] = t;
            pd->pxd[pd->np] = t / BF_FIG_DEG;
            pd->py[pd->np] = r->data[k];
            top = fmax(top, r->data[k]);
            pd->np++;
        }
    }
    for (k = 0; k < CURVE_POINTS; k++) {
        double t = -M_PI / 2 + M_PI * (double)k / (CURVE_POINTS - 1);
        pd->cx[k] = t;
        pd->cxd[k] = -90.0 + (double)k;
        cg[k] = bf_geom_in_plane(theta_i, t);
    }
    for (b = 0; b < D->nm; b++) {
        size_t m = D->idx[b];
        const bf_study_row *row = bf_fig_row(st, s, m);
        double *y = pd->cy[b];
        int e = !D->smp[s].ok[m] ? BF_ENOTFOUND
                : r->abs ? bf_fit_rho_curve(&r->pb[b], row->fit.param,
                                            CURVE_POINTS, cg, y)
                         : bf_fit_curve(row->type, row->fit.param, r->K,
                                        r->geom, CURVE_POINTS, cg, work, y);
        if (e == BF_OK && r->abs && curve_zero(y, CURVE_POINTS)) {
            e = BF_EDOM; /* zero scales: not drawn (a line on 0) */
        }
        for (k = 0; k < CURVE_POINTS; k++) {
            if (e != BF_OK) {
                y[k] = NAN; /* not evaluated, or zero, for this sample */
            } else if (isfinite(y[k])) {
                top = fmax(top, y[k]);
            }
        }
    }
    free(work);
    snprintf(pd->note, sizeof pd->note, "\xce\xb8_{i} = %.2f\xc2\xb0",
             theta_i / BF_FIG_DEG);
    return top;
}


/* ==== the axes ============================================================ */

/* The radiance axis of the absolute figures (SPEC §10) beyond the
 * measured maximum: model peaks up to ABS_CAP_LIN (linear axis) or
 * ABS_CAP_LOG (log axis) times it are drawn, higher ones cut. */
#define ABS_CAP_LIN 1.3
#define ABS_CAP_LOG 10.0

/* x rounded up to two significant digits (x > 0). */
static double nice_up(double x)
{
    double e = pow(10.0, floor(log10(x)));
    return ceil(x / e * 10.0 - 1e-9) / 10.0 * e;
}

/* The largest and smallest positive measured value of pd[0..na-1] (0 and
 * HUGE_VAL when none), the largest finite curve value (0 when none). */
static void abs_range(const plane_data *pd, size_t na, size_t nm,
                      double *mhi, double *mlo, double *chi)
{
    size_t a;
    size_t k;
    size_t b;
    *mhi = 0.0;
    *mlo = HUGE_VAL;
    *chi = 0.0;
    for (a = 0; a < na; a++) {
        for (k = 0; k < pd[a].np; k++) {
            if (pd[a].py[k] > 0.0 && isfinite(pd[a].py[k])) {
                *mhi = fmax(*mhi, pd[a].py[k]);
                *mlo = fmin(*mlo, pd[a].py[k]);
            }
        }
        for (b = 0; b < nm; b++) {
            for (k = 0; k < CURVE_POINTS; k++) {
                if (isfinite(pd[a].cy[b][k])) {
                    *chi = fmax(*chi, pd[a].cy[b][k]);
                }
            }
        }
    }
}

/* The upper end of an absolute axis: the measured maximum mhi and the
 * curves' chi up to cap x mhi (linear: rounded up; log: to a decade). */
static double abs_top(double mhi, double chi, double cap, int logy)
{
    double t = mhi > 0.0 ? fmax(mhi, fmin(chi, cap * mhi)) : chi;
    if (!(t > 0.0)) {
        return 1.0;
    }
    t *= 1.05;
    return logy ? pow(10.0, ceil(log10(t))) : nice_up(t);
}

/* 1 when the measured points drawn in pd[0..na-1] call for a log axis
 * (bf_fit_log_axis). */
static int abs_logy(const plane_data *pd, size_t na)
{
    double v[BF_FIG_MAX_INCIDENCE * MAX_POINTS];
    size_t n = 0;
    size_t a;
    size_t k;
    for (a = 0; a < na; a++) {
        for (k = 0; k < pd[a].np; k++) {
            v[n++] = pd[a].py[k];
        }
    }
    return bf_fit_log_axis(n, v);
}

/* Polar panels on a log axis: radius log10(v / lo), at least 0. */
static void polar_log(double *v, size_t n, double lo)
{
    size_t k;
    for (k = 0; k < n; k++) {
        if (isfinite(v[k])) {
            v[k] = v[k] > lo ? log10(v[k] / lo) : 0.0;
        }
    }
}

static int plane_describe(const bf_fig_data *D, const char *suffix,
                          bf_fig_entry *e, bf_fig_desc *d, int full);

/* 1 when curve b is drawn in none of pd[0..na) (plane_compute). */
static int zero_everywhere(const plane_data *pd, size_t na, size_t b)
{
    size_t a;
    for (a = 0; a < na; a++) {
        if (!curve_zero(pd[a].cy[b], CURVE_POINTS)) {
            return 0;
        }
    }
    return 1;
}

/* Curves far beyond the axis range [lo, hi] (log: logy) held a factor
 * CLIP_FAR beyond it: still cut at the axes, never extreme numbers to
 * draw. */
#define CLIP_FAR 1e3
static void clip_far(double *y, size_t n, double lo, double hi, int logy)
{
    double top = logy ? hi * CLIP_FAR : hi + CLIP_FAR * (hi - lo);
    double bot = logy ? lo / CLIP_FAR : lo - CLIP_FAR * (hi - lo);
    size_t k;
    for (k = 0; k < n; k++) {
        if (isfinite(y[k])) {
            y[k] = fmin(fmax(y[k], bot), top);
        }
    }
}

const char *bf_fig_value_name(bf_objective obj)
{
    return obj == BF_OBJ_MAX ? "LSE" : obj == BF_OBJ_NGAN ? "E" : "S";
}

int bf_fig_plane(const bf_fig_data *D0, bf_fig_entry *e, bf_fig_desc *d,
                 int full)
{
    bf_fig_data *D = bf_fig_alloc(d, sizeof *D);
    size_t pos[BF_FIG_MAX_MODELS];
    size_t nf;
    size_t j;
    char suffix[32];
    if (D == NULL) {
        return BF_ENOMEM;
    }
    /* the entry's models: those of its family, [first, first + count) */
    *D = *D0;
    nf = e->family != 0 ? bf_fig_family(D0, e->family, pos) : D0->nm;
    D->nm = 0;
    for (j = e->first; j < nf && (e->count == 0 || j < e->first + e->count);
         j++) {
        D->idx[D->nm++] = D0->idx[e->family != 0 ? pos[j] : j];
    }
    bf_fig_family_suffix(e->family,
                         bf_fig_family(D0, BF_FIG_DIFFUSE, pos) > 0,
                         e->first / BF_FIG_PLANE_CURVES + 1, suffix,
                         sizeof suffix);
    return plane_describe(D, suffix, e, d, full);
}

/* bf_fig_plane for the models of D, the file name ending in suffix. */
static int plane_describe(const bf_fig_data *D, const char *suffix,
                          bf_fig_entry *e, bf_fig_desc *d, int full)
{
    const bf_rep_study *st = D->st;
    int polar = e->kind == BF_FIG_POLAR;
    size_t s = e->index;
    size_t na = D->o->n_incidence;
    size_t nm = D->nm;
    plane_data *pd = bf_fig_alloc(d, na * sizeof *pd);
    plane_src *src = bf_fig_alloc(d, sizeof *src);
    bf_plot_panel *panel = bf_fig_alloc(d, na * sizeof *panel);
    bf_plot_series *ser = bf_fig_alloc(d, na * (nm + 1) * sizeof *ser);
    char (*labels)[64] = bf_fig_alloc(d, nm * sizeof *labels);
    char *axis = bf_fig_alloc(d, 160);
    char who[256];
    char key[64];
    char models[256];
    char scale[800];
    double top = 1.0;
    double ptop[BF_FIG_MAX_INCIDENCE];
    double ymax;
    double ymin = 0.0;
    double mhi = 0.0;
    double mlo = HUGE_VAL;
    double chi = 0.0;
    int logy = 0;
    size_t a;
    size_t b;
    int rc = BF_OK;

    (void)full; /* the curves set the radiance axis, named in the caption */
    if (pd == NULL || src == NULL || panel == NULL || ser == NULL ||
        labels == NULL || axis == NULL || nm > BF_FIG_MAX_MODELS) {
        return BF_ENOMEM;
    }
    rc = src_init(D, s, d, src);
    if (rc != BF_OK) {
        return rc;
    }
    bf_fig_sample_label(st, e->index, who, sizeof who);
    for (a = 0; a < na; a++) {
        double t =
            plane_compute(D, s, src, D->o->incidence[a], &pd[a], &rc);
        if (t < 0.0) {
            return rc;
        }
        top = fmax(top, t);
        ptop[a] = fmin(ceil(t * 1.05 * 10.0) / 10.0, YMAX_CAP);
    }
    ymax = fmin(ceil(top * 1.05 * 10.0) / 10.0, YMAX_CAP);
    if (src->abs) { /* SPEC §10: absolute units, no cap at 1 */
        abs_range(pd, na, nm, &mhi, &mlo, &chi);
        logy = abs_logy(pd, na);
        ymin = logy ? pow(10.0, floor(log10(mlo))) : 0.0;
        ymax = abs_top(mhi, chi, logy ? ABS_CAP_LOG : ABS_CAP_LIN, logy);
        for (a = 0; a < na; a++) {
            double phi;
            double plo;
            double pch;
            abs_range(&pd[a], 1, nm, &phi, &plo, &pch);
            ptop[a] = logy ? log10(ymax / ymin)
                           : abs_top(phi, pch, ABS_CAP_LIN, 0);
            if (polar && logy) {
                polar_log(pd[a].py, pd[a].np, ymin);
                for (b = 0; b < nm; b++) {
                    polar_log(pd[a].cy[b], CURVE_POINTS, ymin);
                }
            }
        }
    }
    for (b = 0; b < nm; b++) {
        const bf_study_row *row = bf_fig_row(st, s, D->idx[b]);
        if (row->status == BF_OK && src->abs && zero_everywhere(pd, na, b)) {
            snprintf(labels[b], sizeof labels[b], "%s (zero scale, not drawn)",
                     row->type->name);
        } else if (row->status == BF_OK && src->abs) {
            snprintf(labels[b], sizeof labels[b], "%s (%s %.3g)",
                     row->type->name, bf_fig_value_name(st->opts.objective),
                     row->fit.lse);
        } else if (row->status == BF_OK) {
            snprintf(labels[b], sizeof labels[b], "%s (%s %.2f)",
                     row->type->name, bf_fig_value_name(st->opts.objective),
                     row->fit.lse);
        } else {
            snprintf(labels[b], sizeof labels[b], "%s (not evaluated)",
                     row->type->name);
        }
    }
    for (a = 0; a < na; a++) {
        bf_plot_panel *p = &panel[a];
        bf_plot_series *q = &ser[a * (nm + 1)];
        for (b = 0; b < nm; b++) {
            if (!polar) {
                clip_far(pd[a].cy[b], CURVE_POINTS, ymin, ymax, logy);
            }
            q[b].kind = BF_SERIES_LINE;
            q[b].x = polar ? pd[a].cx : pd[a].cxd;
            q[b].y = pd[a].cy[b];
            q[b].n = CURVE_POINTS;
            q[b].style = bf_report_model_style(st->models[D->idx[b]]);
            q[b].mark_every = MARK_EVERY;
            q[b].label = labels[b];
        }
        q[nm].kind = BF_SERIES_POINTS;
        q[nm].x = polar ? pd[a].px : pd[a].pxd;
        q[nm].y = pd[a].py;
        q[nm].n = pd[a].np;
        q[nm].style = BF_PLOT_INK;
        q[nm].label = "measured";
        p->polar = polar;
        p->ymin = polar ? 0.0 : ymin;
        p->ymax = polar && ptop[a] > 0.0 ? ptop[a] : ymax;
        p->logy = !polar && logy;
        p->note = pd[a].note;
        p->series = q;
        p->n_series = nm + 1;
        if (!polar) {
            p->xmin = -90.0;
            p->xmax = 90.0;
            p->xtick = 30.0;
        }
    }
    d->fig.width = D->o->width;
    d->fig.aspect = PLANE_ASPECT;
    d->fig.nx = na > 1 ? 2 : 1;
    d->fig.ny = (na + 1) / 2;
    d->fig.share_x = d->fig.share_y = 1;
    d->fig.legend = BF_LEGEND_TOP;
    if (src->abs && polar) {
        if (logy) {
            snprintf(axis, 160, "angle: \xce\xb8_{s} from the surface normal "
                     "(> 0 forward); radius: log_{10}(\xcf\x81/%.3g sr^{-1})",
                     ymin);
        } else {
            snprintf(axis, 160, "angle: \xce\xb8_{s} from the surface normal "
                     "(> 0 forward); radius: \xcf\x81 = BRDF cos \xce\xb8_{i} "
                     "(sr^{-1})");
        }
        d->fig.xlabel = axis;
    } else if (src->abs) {
        snprintf(axis, 160, "\xcf\x81 = BRDF cos \xce\xb8_{i} (sr^{-1}%s)",
                 logy ? ", log scale" : "");
        d->fig.xlabel = "\xce\xb8_{s} in the plane of incidence "
                        "(\xc2\xb0, > 0 forward)";
        d->fig.ylabel = axis;
    } else if (polar) {
        d->fig.xlabel = "angle: \xce\xb8_{s} from the surface normal "
                        "(> 0 forward); radius: L/L_{max}";
    } else {
        d->fig.xlabel = "\xce\xb8_{s} in the plane of incidence "
                        "(\xc2\xb0, > 0 forward)";
        d->fig.ylabel = "L/L_{max}";
    }
    d->fig.panels = panel;
    d->fig.n_panels = na;

    bf_fig_model_list(st, D->idx, nm, models, sizeof models);
    snprintf(e->base, sizeof e->base, "%s_%s%s", polar ? "polar" : "plane",
             bf_fig_target_key(st, s, key, sizeof key), suffix);
    snprintf(e->title, sizeof e->title, "%.160s: plane of incidence%s", who,
             polar ? " (polar)" : "");
    if (src->abs) {
        snprintf(scale, sizeof scale,
                 "Points and curves are in absolute units as fitted under "
                 "the %s objective (SPEC §10): the measured \xcf\x81 = BRDF "
                 "cos \xce\xb8i on the K = %zu used configurations with "
                 "\xce\xb8i, \xce\xb8o \xe2\x89\xa4 80\xc2\xb0 and each "
                 "model's \xcf\x81\xcc\x82 with its fitted scales, never "
                 "normalised; the legend gives each fit's %s. The radiance "
                 "axis is %s (the rule: logarithmic when the measured points "
                 "drawn span more than %.0f decades), from %.3g to %.3g "
                 "sr\xe2\x81\xbb\xc2\xb9"
                 "%s; model peaks above %.0f\xc3\x97 the measured maximum "
                 "are cut.",
                 bf_objective_name(st->opts.objective), src->K,
                 st->opts.objective == BF_OBJ_NGAN
                     ? "E = \xe2\x88\x9a(\xce\xa3 (\xcf\x81 \xe2\x88\x92 "
                       "\xcf\x81\xcc\x82)\xc2\xb2 / K)"
                     : "objective S",
                 logy ? "logarithmic" : "linear", BF_LOG_AXIS_DECADES, ymin,
                 ymax,
                 polar ? (logy ? " (radius: decades above the lower end)"
                               : " (each panel's radius fits its largest "
                                 "value)")
                       : "",
                 logy ? ABS_CAP_LOG : ABS_CAP_LIN);
        snprintf(e->caption, sizeof e->caption,
                 "The fitted models (%s; lines, with markers every 30\xc2\xb0 "
                 "to tell them apart) over \xce\xb8s from \xe2\x88\x92"
                 "90\xc2\xb0 to 90\xc2\xb0 in the plane of incidence "
                 "(\xce\xb8s > 0: forward, the specular side)%s, and the "
                 "used measured configurations within %.0f\xc2\xb0 of that "
                 "plane (black points), one panel per incidence angle "
                 "\xce\xb8i. %s",
                 models, polar ? " as a polar plot" : "",
                 BF_FIG_PLANE_TOL / BF_FIG_DEG, scale);
    } else {
        snprintf(e->caption, sizeof e->caption,
             "The fitted models (%s; lines, with markers every 30\xc2\xb0 to "
             "tell them apart) over \xce\xb8s from \xe2\x88\x92" "90\xc2\xb0 to "
             "90\xc2\xb0 in the plane of incidence (\xce\xb8s > 0: forward, "
             "the specular side)%s, and the used measured configurations "
             "within %.0f\xc2\xb0 of that plane (black points), one panel per "
             "incidence angle \xce\xb8i. Each model curve is divided by the "
             "model's maximum over the K = %zu used configurations and the "
             "measurements by theirs, as in the fit (SPEC §2), so points and "
             "curves compare directly; %s %.2f (higher peaks, where no "
             "configuration is used, are cut).",
             models,
             polar ? " as a polar plot: angle \xce\xb8s from the surface "
                     "normal, radius L/L_max"
                   : "",
             BF_FIG_PLANE_TOL / BF_FIG_DEG, D->smp[s].K,
             polar ? "each panel's radius fits its largest value, at most"
                   : "the radiance axis ends at",
             polar ? YMAX_CAP : ymax);
    }
    snprintf(e->alt, sizeof e->alt,
             "%s plots of the models %.200s and the measurements of %.160s in the "
             "plane of incidence, %zu incidence angle%s.",
             polar ? "Polar" : "Line", models, who, na, na == 1 ? "" : "s");
    return BF_OK;
}
