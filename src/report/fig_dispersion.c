/* fig_dispersion.c: one material's refractive index against wavelength
 * (issue 17 item 7; doc/methods.md "Dispersion"): the points of
 * bf_dispersion_points of its fits, n per spectral channel with its 95%
 * profile interval as an error bar; a joint fit's one n as a horizontal
 * line across the channels' wavelengths with its interval as a band. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fig_internal.h"
#include "model_style.h"

#define DISP_ASPECT 0.62
#define SERIES 6
#define VALUES(n) (5 * (n) + 8)

/* The study's dispersion points (malloc'ed; NULL when none or out of
 * memory), their number in *n. */
static bf_dispersion_point *all_points(const bf_rep_study *st, size_t *n)
{
    bf_dispersion_point *pt;
    *n = bf_dispersion_points(&st->spec, st->rows, st->stats, NULL);
    if (*n == 0 || (pt = malloc(*n * sizeof *pt)) == NULL) {
        return NULL;
    }
    (void)bf_dispersion_points(&st->spec, st->rows, st->stats, pt);
    return pt;
}

/* The material of point p. */
static size_t material_of(const bf_rep_study *st,
                          const bf_dispersion_point *p)
{
    return st->targets[p->row / st->n_models].material;
}

size_t bf_fig_dispersion_first(const bf_rep_study *st, size_t s)
{
    size_t n;
    size_t i;
    size_t first = SIZE_MAX;
    bf_dispersion_point *pt;
    if (s > 0 && st->targets[s - 1].material == st->targets[s].material) {
        return SIZE_MAX; /* one figure a material, at its first target */
    }
    pt = all_points(st, &n);
    for (i = 0; i < n && first == SIZE_MAX; i++) {
        if (material_of(st, &pt[i]) == st->targets[s].material) {
            first = i;
        }
    }
    free(pt);
    return first;
}

/* Fills the series of model m's points of the material into ser (up to
 * SERIES: error bars, the fit's values, the intervals' estimates; joint:
 * line, band's two edges); returns their number. v: room for VALUES(n). Widens [*x0, *x1] x [*y0, *y1]. */
static size_t model_series(const bf_dispersion_point *pt, size_t n,
                           const bf_model_type *t, double *v,
                           bf_plot_series *ser, double *x0, double *x1,
                           double *y0, double *y1)
{
    double *x = v;
    double *y = x + n;
    double *lo = y + n;
    double *hi = lo + n;
    double *ml = hi + n;
    size_t k = 0;
    size_t i;
    size_t ns = 0;
    const bf_dispersion_point *joint = NULL;
    for (i = 0; i < n; i++) {
        if (strcmp(pt[i].model, t->name) != 0) {
            continue;
        }
        if (pt[i].joint) {
            joint = &pt[i];
        } else {
            x[k] = pt[i].wavelength;
            y[k] = pt[i].n;
            lo[k] = pt[i].ci_low;
            hi[k] = pt[i].ci_high;
            ml[k] = pt[i].n_ml;
            k++;
        }
        *x0 = fmin(*x0, pt[i].lambda_lo);
        *x1 = fmax(*x1, pt[i].lambda_hi);
        *y0 = fmin(*y0, isfinite(pt[i].ci_low) ? fmin(pt[i].ci_low, pt[i].n)
                                               : pt[i].n);
        *y1 = fmax(*y1, isfinite(pt[i].ci_high)
                            ? fmax(pt[i].ci_high, pt[i].n)
                            : pt[i].n);
    }
    memset(ser, 0, SERIES * sizeof *ser);
    if (k > 0) {
        ser[0].kind = BF_SERIES_ERRORBARS;
        ser[0].x = x;
        ser[0].y = lo;
        ser[0].y2 = hi;
        ser[0].n = k;
        ser[0].style = bf_report_model_style(t);
        ser[0].dash = BF_DASH_SOLID;
        ser[1].kind = BF_SERIES_POINTS;
        ser[1].x = x;
        ser[1].y = y;
        ser[1].n = k;
        ser[1].style = ser[0].style;
        ser[1].label = t->name;
        ser[2] = ser[1];
        ser[2].y = ml;
        ser[2].style = BF_PLOT_INK;
        ser[2].label = BF_FIG_ML_LABEL;
        ns = 3;
    }
    if (joint != NULL) {
        double *jx = ml + n; /* the joint line: 2 x, 2 y, band edges */
        double *jy = jx + 2;
        double *jl = jy + 2;
        double *jh = jl + 2;
        jx[0] = joint->lambda_lo;
        jx[1] = joint->lambda_hi;
        jy[0] = jy[1] = joint->n;
        jl[0] = jl[1] = joint->ci_low;
        jh[0] = jh[1] = joint->ci_high;
        ser[ns].kind = BF_SERIES_LINE;
        ser[ns].x = jx;
        ser[ns].y = jy;
        ser[ns].n = 2;
        ser[ns].style = bf_report_model_style(t);
        ser[ns].dash = BF_DASH_SOLID;
        ser[ns].label = t->name;
        ser[ns + 1] = ser[ns];
        ser[ns + 1].y = jl;
        ser[ns + 1].dash = BF_DASH_DOTTED;
        ser[ns + 1].label = NULL;
        ser[ns + 2] = ser[ns + 1];
        ser[ns + 2].y = jh;
        ns += 3;
    }
    return ns;
}

int bf_fig_dispersion(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                      int full)
{
    const bf_rep_study *st = D->st;
    size_t mat = st->targets[e->index].material;
    size_t n_all;
    bf_dispersion_point *all = all_points(st, &n_all);
    bf_dispersion_point *pt;
    bf_plot_panel *panel = bf_fig_alloc(d, sizeof *panel);
    bf_plot_series *ser =
        bf_fig_alloc(d, SERIES * (st->n_models + 1) * sizeof *ser);
    double *v;
    double x0 = HUGE_VAL;
    double x1 = -HUGE_VAL;
    double y0 = HUGE_VAL;
    double y1 = -HUGE_VAL;
    size_t n = 0;
    size_t ns = 0;
    size_t m;
    size_t i;
    int joint = 0;
    char label[160];
    (void)full;
    pt = bf_fig_alloc(d, (n_all + 1) * sizeof *pt);
    v = bf_fig_alloc(d, VALUES(n_all) * st->n_models * sizeof *v + 1);
    if (all == NULL || pt == NULL || v == NULL || panel == NULL ||
        ser == NULL) {
        int none = all == NULL && n_all == 0;
        free(all);
        return none ? BF_EINVAL : BF_ENOMEM;
    }
    for (i = 0; i < n_all; i++) { /* this material's points */
        if (material_of(st, &all[i]) == mat) {
            joint |= all[i].joint;
            pt[n++] = all[i];
        }
    }
    free(all);
    for (m = 0; m < st->n_models; m++) {
        ns += model_series(pt, n, st->models[m],
                           &v[VALUES(n_all) * m], &ser[ns], &x0, &x1,
                           &y0, &y1);
    }
    if (!(x1 > x0)) {
        x0 -= 10.0;
        x1 += 10.0;
    }
    if (!(y1 > y0)) {
        y0 -= 0.01;
        y1 += 0.01;
    }
    panel->xmin = x0 - 0.04 * (x1 - x0);
    panel->xmax = x1 + 0.04 * (x1 - x0);
    panel->ymin = y0 - 0.06 * (y1 - y0);
    panel->ymax = y1 + 0.06 * (y1 - y0);
    panel->series = ser;
    panel->n_series = ns;
    d->fig.width = D->o->width;
    d->fig.aspect = DISP_ASPECT;
    d->fig.nx = d->fig.ny = 1;
    d->fig.xlabel = "wavelength (nm)";
    d->fig.ylabel = "refractive index n";
    d->fig.legend = BF_LEGEND_TOP;
    d->fig.panels = panel;
    d->fig.n_panels = 1;
    bf_rep_material_label(st->spec.data, mat, label, sizeof label);
    snprintf(e->base, sizeof e->base, "dispersion_sample%d", e->sample);
    snprintf(e->title, sizeof e->title,
             "%s: refractive index against wavelength", label);
    snprintf(e->caption, sizeof e->caption,
             "The refractive index n of the dielectric Fresnel factor "
             "(--fresnel dielectric, SPEC §4.1, §9.2) %s, for each model "
             "that has it. Bars: the 95%% profile interval (doc/methods.md "
             "§3) under the fitted noise model, about the noise-weighted "
             "estimate (black dots), which can differ from the fit's value "
             "under the objective (the model's markers). n is identified only through the angular shape of "
             "the Fresnel factor beside the scale rho_s: read it as the "
             "index of the outermost interface (doc/methods.md "
             "\"Dispersion\").",
             joint ? "shared by every channel (--channel joint): one "
                     "horizontal line over the channels' wavelengths, "
                     "dotted lines at its interval's ends where the fit has one"
                   : "fitted on each spectral channel (points at the "
                     "channel's wavelength)");
    snprintf(e->alt, sizeof e->alt,
             "Refractive index n against wavelength in nm for %s, %zu "
             "points with error bars.",
             label, n);
    return BF_OK;
}
