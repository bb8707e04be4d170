/* sandwich.c: the robust check of an interval's noise model (doc/methods.md
 * §3) -- each free parameter's variance from the residuals themselves (the
 * sandwich) against the noise model's, and the factor by which its profile
 * threshold is widened where the residuals show more variance than the
 * model states.
 *
 * [1] H. White, "A heteroskedasticity-consistent covariance matrix
 *     estimator and a direct test for heteroskedasticity", Econometrica 48
 *     (1980) 817-838 (the sandwich A^-1 B A^-1).
 * [2] J. G. MacKinnon, H. White, "Some heteroskedasticity-consistent
 *     covariance matrix estimators with improved finite sample
 *     properties", J. Econometrics 29 (1985) 305-325 (HC2: each squared
 *     residual divided by 1 - h_k).
 * [3] J. E. Stafford, "A robust adjustment of the profile likelihood",
 *     Annals of Statistics 24 (1996) 336-352 (the profile likelihood ratio
 *     of a parameter divided by the ratio of its robust to its model
 *     variance is again chi^2_1).
 * [4] src/fit/noise.c: D_k = mu_k + e_k, var e_k = sigma^2 v_k,
 *     v_k = max(L_k / top, f)^p.
 *
 * Equations, at a specular model's estimate (its scales are parameters,
 * so the mean mu_k = rho_hat_k has no scale beside them): z_k the
 * derivatives of mu_k over the free parameters (bf__leverages) times
 * sqrt(w_k / v_k), u_k =
 * sqrt(w_k / v_k) (mu_k - D_k), h_k the leverages,
 *   A = sum z_k z_k',  g_k = A^-1 z_k,  sigma^2 = sum u_k^2 / nu
 *   V_model,jj  = sigma^2 (A^-1)_jj = sigma^2 sum g_kj^2
 *   V_robust,jj = (A^-1 [sum u_k^2 / (1 - h_k) z_k z_k'] A^-1)_jj
 *               = sum g_kj^2 u_k^2 / (1 - h_k)                       [1], [2]
 *   c_j = max(1, V_robust,jj / V_model,jj)                             [3]
 * and parameter j's interval is where n ln(S_p / S_min) <= c_j times the
 * threshold. Only widening: where the noise model holds, c_j scatters
 * about 1 with the residuals, and an interval narrowed by that scatter
 * covers less than it says (doc/methods.md §3 has the measurements).
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>

#include "fit/engine.h"

#define NCOL (BF_MAX_PARAMS + 1)

int bf__robust_factors(bf__fitctx *fc, const double *param, double p,
                       const double *fit, double top, double nu, double *buf,
                       double *c)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    double *z = buf;
    double *t0 = buf + NCOL * n;
    double *h = t0 + 2 * n;
    double a[NCOL * NCOL] = {0};
    double vr[NCOL] = {0};
    double g2[NCOL] = {0};
    double uu = 0.0;
    gsl_matrix_view av;
    size_t q = 0; /* the columns: the free parameters */
    size_t col;
    size_t i;
    size_t j;
    size_t k;
    int rc;
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        int fr = j < pb->type->p && ((pb->free_mask >> j) & 1u);
        c[j] = fr ? 1.0 : NAN;
        q += fr ? 1u : 0u;
    }
    rc = bf__leverages(fc, param, 1.0, p, fit, top, z, t0, t0 + n, h);
    if (rc != BF_OK) {
        return rc;
    }
    for (k = 0; k < n; k++) {
        const double *zk = z + k * NCOL;
        for (i = 0; i < q; i++) {
            for (j = 0; j < q; j++) {
                a[i * q + j] += zk[i] * zk[j];
            }
        }
    }
    av = gsl_matrix_view_array(a, q, q);
    if (gsl_linalg_cholesky_decomp1(&av.matrix) != GSL_SUCCESS ||
        gsl_linalg_cholesky_invert(&av.matrix) != GSL_SUCCESS) {
        return BF_OK; /* a parameter without effect: 1 */
    }
    for (k = 0; k < n; k++) {
        double l = fit[k] / top;
        double w = pb->weight != NULL ? pb->weight[k] : 1.0;
        double hk = h[k] < BF__LEV_MAX ? h[k] : BF__LEV_MAX;
        const double *zk = z + k * NCOL;
        double u;
        l = l > BF_LOG_FLOOR ? l : BF_LOG_FLOOR;
        u = sqrt(w) * pow(l, -0.5 * p) * (fit[k] - pb->data[k]);
        uu += u * u;
        for (i = 0; i < q; i++) { /* g = A^-1 z_k */
            double gi = 0.0;
            double gg;
            for (j = 0; j < q; j++) {
                gi += a[i * q + j] * zk[j];
            }
            gg = gi * gi;
            vr[i] += gg * u * u / (1.0 - hk);
            g2[i] += gg;
        }
    }
    if (!(uu > 0.0) || !(nu > 0.0)) {
        return BF_OK; /* an exact fit: 1 */
    }
    col = 0;
    for (j = 0; j < pb->type->p; j++) {
        double vm; /* V_model,jj = sigma^2 (A^-1)_jj = sigma^2 sum g_k^2 */
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        vm = uu / nu * g2[col];
        c[j] = vm > 0.0 && vr[col] > vm ? vr[col] / vm : 1.0; /* [3] */
        col++;
    }
    return BF_OK;
}
