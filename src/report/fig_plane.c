/* fig_plane.c: one sample's fitted models and measurements in the plane
 * of incidence (fig_internal.h), as curves over the signed viewing angle
 * (Cartesian) or as a polar half-disc, one panel per incidence angle.
 * Curves are normalised as in the fit (SPEC §2, bf_fit_curve), so points
 * and curves compare directly. */
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

/* Fills pd for incidence theta_i of sample index s. Returns the largest
 * value drawn, or -1 on error (*rc set). */
static double plane_compute(const bf_fig_data *D, size_t s, double theta_i,
                            plane_data *pd, int *rc)
{
    const bf_rep_study *st = D->st;
    const bf_fig_sample *r = &D->smp[s];
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
        int e = r->ok[m] ? bf_fit_curve(row->type, row->fit.param, r->K,
                                        r->geom, CURVE_POINTS, cg, work, y)
                         : BF_ENOTFOUND;
        for (k = 0; k < CURVE_POINTS; k++) {
            if (e != BF_OK) {
                y[k] = NAN; /* not evaluated for this sample */
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

int bf_fig_plane(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                 int full)
{
    const bf_rep_study *st = D->st;
    int polar = e->kind == BF_FIG_POLAR;
    size_t s = e->index;
    size_t na = D->o->n_incidence;
    size_t nm = D->nm;
    plane_data *pd = bf_fig_alloc(d, na * sizeof *pd);
    bf_plot_panel *panel = bf_fig_alloc(d, na * sizeof *panel);
    bf_plot_series *ser = bf_fig_alloc(d, na * (nm + 1) * sizeof *ser);
    char (*labels)[64] = bf_fig_alloc(d, nm * sizeof *labels);
    char who[256];
    char key[64];
    char models[256];
    double top = 1.0;
    double ptop[BF_FIG_MAX_INCIDENCE];
    double ymax;
    size_t a;
    size_t b;
    int rc = BF_OK;

    (void)full; /* the curves set the radiance axis, named in the caption */
    if (pd == NULL || panel == NULL || ser == NULL || labels == NULL ||
        nm > BF_FIG_MAX_MODELS) {
        return BF_ENOMEM;
    }
    bf_fig_sample_label(st, e->index, who, sizeof who);
    for (a = 0; a < na; a++) {
        double t = plane_compute(D, s, D->o->incidence[a], &pd[a], &rc);
        if (t < 0.0) {
            return rc;
        }
        top = fmax(top, t);
        ptop[a] = fmin(ceil(t * 1.05 * 10.0) / 10.0, YMAX_CAP);
    }
    ymax = fmin(ceil(top * 1.05 * 10.0) / 10.0, YMAX_CAP);
    for (b = 0; b < nm; b++) {
        const bf_study_row *row = bf_fig_row(st, s, D->idx[b]);
        if (row->status == BF_OK) {
            snprintf(labels[b], sizeof labels[b], "%s (LSE %.2f)",
                     row->type->name, row->fit.lse);
        } else {
            snprintf(labels[b], sizeof labels[b], "%s (not evaluated)",
                     row->type->name);
        }
    }
    for (a = 0; a < na; a++) {
        bf_plot_panel *p = &panel[a];
        bf_plot_series *q = &ser[a * (nm + 1)];
        for (b = 0; b < nm; b++) {
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
        p->ymin = 0.0;
        p->ymax = polar && ptop[a] > 0.0 ? ptop[a] : ymax;
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
    if (polar) {
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
    snprintf(e->base, sizeof e->base, "%s_%s", polar ? "polar" : "plane",
             bf_fig_target_key(st, s, key, sizeof key));
    snprintf(e->title, sizeof e->title, "%.160s: plane of incidence%s", who,
             polar ? " (polar)" : "");
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
    snprintf(e->alt, sizeof e->alt,
             "%s plots of the models %.200s and the measurements of %.160s in the "
             "plane of incidence, %zu incidence angle%s.",
             polar ? "Polar" : "Line", models, who, na, na == 1 ? "" : "s");
    return BF_OK;
}
