/* plane.c: fitted models where a figure draws them -- a model's curve at
 * any configurations, normalised as in the fit (SPEC §2) or in absolute
 * units under the objectives that keep the scale (SPEC §10), the rule of
 * a figure's log radiance axis, and the plane of
 * incidence (SPEC §1.2: Beckmann's frame, phi_i = pi, the forward or
 * specular side at phi_s = 0).
 *
 * [1] SPEC §1.2 (frame), §2 (normalisation by the maximum over the used
 *     configurations). */
#include <math.h>
#include <stdlib.h>

#include "internal.h"

int bf_fit_curve(const bf_model_type *type, const double *param,
                 size_t n_used, const bf_geom *used, size_t n,
                 const bf_geom *at, double *work, double *out)
{
    double mx = -HUGE_VAL;
    size_t k;
    int rc;
    if (type == NULL || param == NULL || n_used == 0 || used == NULL ||
        work == NULL || (n > 0 && (at == NULL || out == NULL))) {
        return BF_EINVAL;
    }
    rc = bf_model_eval(type, param, n_used, used, work);
    if (rc != BF_OK) {
        return rc;
    }
    for (k = 0; k < n_used; k++) {
        mx = fmax(mx, work[k]);
    }
    if (!(mx > 0.0) || !isfinite(mx)) {
        return BF_EDOM; /* SPEC §2: the curve cannot be normalised */
    }
    if (n == 0) {
        return BF_OK;
    }
    /* BF_EDOM here leaves NaN where the model is undefined (BK at grazing
     * incidence): the curve breaks there, which is what a figure shows */
    rc = bf_model_eval(type, param, n, at, out);
    if (rc != BF_OK && rc != BF_EDOM) {
        return rc;
    }
    for (k = 0; k < n; k++) {
        out[k] /= mx; /* SPEC §2 */
    }
    return BF_OK;
}

int bf_fit_rho_curve(const bf_problem *pb, const double *param, size_t n,
                     const bf_geom *at, double *out)
{
    static const bf_geom normal = {0.0, M_PI, 0.0, 0.0};
    double vn = 1.0;
    double rho_d = 1.0;
    double f = 1.0; /* the diffuse model's scale over its value */
    int specular;
    size_t k;
    int rc;
    if (pb == NULL || pb->type == NULL || param == NULL ||
        !bf_objective_keeps_scale(pb->objective) ||
        (n > 0 && (at == NULL || out == NULL))) {
        return BF_EINVAL;
    }
    specular = pb->type->kind == BF_MODEL_SPECULAR;
    if (!specular) { /* SPEC §9.4: rho_d v / (pi v(normal)) */
        rc = bf_fit_scale(pb, param, &rho_d);
        if (rc == BF_OK) {
            rc = bf_model_eval(pb->type, param, 1, &normal, &vn);
        }
        if (rc != BF_OK) {
            return rc;
        }
        f = rho_d / (M_PI * vn);
    }
    if (n == 0) {
        return BF_OK;
    }
    rc = bf_model_eval(pb->type, param, n, at, out);
    if (rc != BF_OK && rc != BF_EDOM) {
        return rc; /* BF_EDOM: NaN where undefined, as bf_fit_curve */
    }
    for (k = 0; k < n; k++) {
        /* SPEC §10: a specular model's value is the BRDF, rho_hat = BRDF
         * cos ti; a diffuse model's is already radiance (cos ti in it) */
        out[k] *= specular ? f * cos(at[k].theta_i) : f;
    }
    return BF_OK;
}

int bf_fit_log_axis(size_t n, const double *v)
{
    double lo = HUGE_VAL;
    double hi = 0.0;
    size_t k;
    for (k = 0; k < n; k++) {
        if (v[k] > 0.0 && isfinite(v[k])) {
            lo = fmin(lo, v[k]);
            hi = fmax(hi, v[k]);
        }
    }
    return hi > 0.0 && log10(hi / lo) > BF_LOG_AXIS_DECADES;
}

bf_geom bf_geom_in_plane(double theta_i, double t)
{
    bf_geom g;
    g.theta_i = theta_i;
    g.phi_i = M_PI;                       /* SPEC §1.2 */
    g.theta_s = fmin(fabs(t), M_PI / 2);
    g.phi_s = t >= 0.0 ? 0.0 : M_PI;      /* forward: phi_s = 0 */
    return g;
}

double bf_geom_plane_angle(const bf_geom *g, double *off_plane)
{
    /* the viewing direction (sin ts cos ps, sin ts sin ps, cos ts) is
     * off the plane phi = 0, pi by asin(|sin ts sin ps|) */
    if (off_plane != NULL) {
        *off_plane =
            asin(fmin(1.0, fabs(sin(g->theta_s) * sin(g->phi_s))));
    }
    return cos(g->phi_s) >= 0.0 ? g->theta_s : -g->theta_s;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

int bf_geom_plane_incidences(size_t K, const bf_geom *g, double tol,
                             size_t max, double *theta_i, size_t *n)
{
    double *v;
    size_t *start;
    size_t *count;
    size_t nv = 0;
    size_t nc = 0;
    size_t most = 0;
    size_t ncand = 0;
    size_t i;
    size_t k;
    if ((K > 0 && g == NULL) || n == NULL || (max > 0 && theta_i == NULL) ||
        !(tol >= 0.0)) {
        return BF_EINVAL;
    }
    *n = 0;
    v = malloc((K + 1) * sizeof *v);
    start = malloc((K + 1) * sizeof *start);
    count = malloc((K + 1) * sizeof *count);
    if (v == NULL || start == NULL || count == NULL) {
        free(v);
        free(start);
        free(count);
        return BF_ENOMEM;
    }
    for (k = 0; k < K; k++) {
        double off;
        bf_geom_plane_angle(&g[k], &off);
        if (off <= tol && isfinite(g[k].theta_i)) {
            v[nv++] = g[k].theta_i;
        }
    }
    qsort(v, nv, sizeof *v, cmp_double);
    /* clusters of incidence angles within tol of their first */
    for (i = 0; i < nv; i = start[nc] + count[nc], nc++) {
        start[nc] = i;
        count[nc] = 1;
        while (i + count[nc] < nv && v[i + count[nc]] - v[i] <= tol) {
            count[nc]++;
        }
    }
    for (i = 0; i < nc; i++) {
        most = count[i] > most ? count[i] : most;
    }
    /* the candidates, groups of more than half the largest group's views:
     * their angles (each group's median member: a measured value), in
     * increasing order, into v's front */
    for (i = 0; i < nc; i++) {
        if (2 * count[i] > most) {
            v[ncand++] = v[start[i] + count[i] / 2];
        }
    }
    if (ncand <= max) {
        for (i = 0; i < ncand; i++) {
            theta_i[i] = v[i];
        }
        *n = ncand;
    } else if (max == 1) {
        theta_i[0] = v[0];
        *n = 1;
    } else if (max > 1) { /* spread over the range: first, last, between */
        for (i = 0; i < max; i++) {
            theta_i[i] = v[(i * (ncand - 1) + (max - 1) / 2) / (max - 1)];
        }
        *n = max;
    }
    free(v);
    free(start);
    free(count);
    return BF_OK;
}
