/* leverage.c: the leverages of a fit under its noise model (doc/methods.md
 * §3) -- the share of each configuration's own value in its fitted value,
 * used to standardise residuals (the bootstrap's modified residuals, the
 * noise power's estimate).
 *
 * [1] A. C. Davison, D. V. Hinkley, "Bootstrap Methods and their
 *     Application", CUP 1997, §6.3 (nonlinear and weighted regression:
 *     leverages of the linearised fit, residuals standardised by the
 *     variance function).
 * [2] src/fit/noise.c: D_k = s L_k(theta) + e_k, var e_k = sigma^2 v_k,
 *     v_k = max(L_k / top, f)^p.
 *
 * Equations: z_k the derivatives of the mean s L_k(theta) over the free
 * parameters and s (a specular model: its own scales are parameters, no s)
 * times sqrt(w_k / v_k); h_k = z_k (Z'Z)^-1 z_k' [1] §6.3, sum h_k = the
 * number of columns q.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

#include "fit/engine.h"

/* Relative step of the derivatives (of the search range): central
 * differences, error O(step^2). */
#define LEV_STEP 1e-4

int bf__leverages(bf__fitctx *fc, const double *param, double scale,
                  double p, const double *fit, double top, double *z,
                  double *t0, double *t1, double *h)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    /* a specular model (SPEC §9): no scale beside its own parameters */
    int spec = pb->type->kind == BF_MODEL_SPECULAR;
    size_t q = spec ? 0 : 1;
    double a[(BF_MAX_PARAMS + 1) * (BF_MAX_PARAMS + 1)] = {0};
    double x[BF_MAX_PARAMS + 1];
    gsl_matrix_view av;
    gsl_vector_view xv;
    size_t i;
    size_t j;
    size_t k;
    int rc = BF_OK;
    for (k = 0; k < n; k++) {
        double l = fit[k] / top;
        double w = pb->weight != NULL ? pb->weight[k] : 1.0;
        l = l > BF_LOG_FLOOR ? l : BF_LOG_FLOOR;
        h[k] = sqrt(w) * pow(l, -0.5 * p); /* sqrt(w_k / v_k) */
        z[k * (BF_MAX_PARAMS + 1)] = fit[k] * h[k];
    }
    for (j = 0; rc == BF_OK && j < pb->type->p; j++) {
        double p0[BF_MAX_PARAMS];
        double p1[BF_MAX_PARAMS];
        double dx = LEV_STEP * (pb->hi[j] - pb->lo[j]);
        if (spec) { /* domains up to 1e6 wide: relative to the value */
            dx = LEV_STEP * fmax(fabs(param[j]), dx * LEV_STEP);
        }
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        memcpy(p0, param, sizeof p0);
        memcpy(p1, param, sizeof p1);
        p0[j] = p0[j] - dx < pb->lo[j] ? pb->lo[j] : p0[j] - dx;
        p1[j] = p1[j] + dx > pb->hi[j] ? pb->hi[j] : p1[j] + dx;
        rc = bf__curve(fc->pm, p0, fc->work, t0);
        if (rc == BF_OK) {
            rc = bf__curve(fc->pm, p1, fc->work, t1);
        }
        for (k = 0; rc == BF_OK && k < n; k++) {
            z[k * (BF_MAX_PARAMS + 1) + q] =
                scale * (t1[k] - t0[k]) / (p1[j] - p0[j]) * h[k];
        }
        q++;
    }
    if (rc != BF_OK) {
        return rc;
    }
    for (k = 0; k < n; k++) {
        for (i = 0; i < q; i++) {
            for (j = 0; j < q; j++) {
                a[i * q + j] += z[k * (BF_MAX_PARAMS + 1) + i] *
                                z[k * (BF_MAX_PARAMS + 1) + j];
            }
        }
    }
    av = gsl_matrix_view_array(a, q, q);
    xv = gsl_vector_view_array(x, q);
    if (gsl_linalg_cholesky_decomp1(&av.matrix) != GSL_SUCCESS) {
        for (k = 0; k < n; k++) { /* a parameter without effect */
            h[k] = (double)q / (double)n;
        }
        return BF_OK;
    }
    for (k = 0; k < n; k++) {
        gsl_vector_const_view zk =
            gsl_vector_const_view_array(z + k * (BF_MAX_PARAMS + 1), q);
        double hk = 0.0;
        gsl_linalg_cholesky_solve(&av.matrix, &zk.vector, &xv.vector);
        for (i = 0; i < q; i++) {
            hk += zk.vector.data[i] * x[i];
        }
        h[k] = hk;
    }
    return BF_OK;
}
