/* plane.c: fitted models where a figure draws them -- a model's curve at
 * any configurations, normalised as in the fit (SPEC §2), and the plane of
 * incidence (SPEC §1.2: Beckmann's frame, phi_i = pi, the forward or
 * specular side at phi_s = 0).
 *
 * [1] SPEC §1.2 (frame), §2 (normalisation by the maximum over the used
 *     configurations). */
#include <math.h>

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
