/* varpro.c: the fit of the specular models (SPEC §9.3) and the composites
 * D+S (SPEC §9.4) under the objectives that keep the scale (SPEC §10), as
 * separable least squares: the scales enter linearly, so for every value
 * of the other parameters they are solved exactly (variable projection).
 *
 * [1] G. H. Golub, V. Pereyra, "The differentiation of pseudo-inverses and
 *     nonlinear least squares problems whose variables separate", SIAM J.
 *     Numer. Anal. 10(2), 1973 (variable projection).
 * [2] C. L. Lawson, R. J. Hanson, "Solving Least Squares Problems", 1974,
 *     ch. 23 (non-negative least squares: the optimum is the
 *     unconstrained one on its active set).
 * [3] GSL manual, "Multidimensional Minimization" (nmsimplex2).
 *
 * Equations (rho = BRDF cos ti measured, w weights, theta the scales):
 *   rho_hat = c_0 + sum_j theta_j c_j,   c_0 = rho_hat at theta = 0,
 *             c_j = rho_hat at theta = e_j minus c_0      (affine in theta;
 *             the kernel's columns evaluate each part once: a lobe
 *             rho_s f has c_0 = 0, a composite's c_rho_d is D's alone)
 *   theta = argmin_{theta >= 0} sum_k w_k (rho_hat_k - rho_k)^2
 *     (NNLS, two columns at most: the unconstrained solution of the
 *      normal equations when it is >= 0, else the better of the two
 *      one-column solutions clamped at 0 -- the four active sets)
 *   ngan: S = sum w (rho_hat - rho)^2, reported E = sqrt(S / K) (SPEC §10)
 *   joint (--channel joint, SPEC §9.4; Ngan et al. 2005): C channels'
 *     rho^(c) on the same K configurations, one shape, the scales
 *     theta^(c) solved per channel on the shared columns c_j,
 *     S = sum_c sum_k w (rho_hat^(c) - rho^(c))^2, E = sqrt(S / (K C))
 * The other free parameters: a product grid over their domains (log-spaced
 * where the domain is positive and spans a factor 50 or more: alpha in
 * [1e-3, 2], the exponents), then Levenberg-Marquardt from the grid's
 * best local minima in the same coordinates (ln x where the grid is
 * log-spaced), Nelder-Mead where it ends on a bound short of a KKT point,
 * the scales re-solved at every trial point; every trial point clamped
 * into the domain; a cross-validation fold's descents stop where they
 * join, within half a grid step, a minimum an earlier one reached. Dense
 * data: the grid and those descents on a regular
 * subsample, one descent on all (doc/methods.md). cuberoot, log1p: the
 * ngan solution starts Nelder-Mead over every free parameter, scales
 * included.
 */
#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

#define MAX_LIN 2
#define STARTS 6
/* A fold's descent merges into a known minimum within MERGE_NEAR of a
 * grid step of it on every axis (space_t.known_u): in the grid cell
 * around it, where the grid tells no two minima apart. */
#define MERGE_NEAR 0.5
#define NM_ITER 300
/* Nelder-Mead stops on a plateau: NM_FLAT (m + 1) trial values in a row
 * exactly equal (a lobe whose scale solves to 0 there: its other
 * parameters move nothing; or trial points all clamped into one corner of
 * the domain), where no vertex leads anywhere. */
#define NM_FLAT 10
#define NM_SIZE 1e-7
/* The one-sided step of the bound test, a fraction of the span. */
#define KKT_STEP 1e-6
#define UNDEFINED 1e300
/* Levenberg-Marquardt's iterations and tolerances (xtol, gtol, ftol). */
#define LM_ITER 200
#define LM_TOL 1e-14

/* Grid points per parameter by the number of gridded parameters (log-
 * spaced, linear). */
static const size_t grid_log[] = {0, 200, 48, 24, 14, 8, 6, 5, 4};
static const size_t grid_lin[] = {0, 101, 7, 7, 6, 5, 4, 4, 3};

/* ==== the scales solved exactly ========================================== */

static double weight_of(const bf_problem *pb, size_t k)
{
    return pb->weight != NULL ? pb->weight[k] : 1.0;
}

/* sum w (c0 + t1 c1 + t2 c2 - R)^2 (c2 NULL: one column). */
static double sse(const bf_problem *pb, const double *c0, const double *c1,
                  const double *c2, double t1, double t2)
{
    double sum = 0.0;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double r = c0[k] + t1 * c1[k] - pb->data[k];
        if (c2 != NULL) {
            r += t2 * c2[k];
        }
        sum += weight_of(pb, k) * r * r;
    }
    return sum;
}

/* The normal equations of the scales: g11 = <c1, c1>, g12, g22, b1 =
 * <c1, R - c0>, b2 (weighted). */
typedef struct {
    double g11, g12, g22, b1, b2;
} normal_t;

/* NNLS from the normal equations ne (two columns when two): 1 with t the
 * unconstrained optimum when it is inside [0, hi]; else 0 with t the two
 * one-column optima clamped into [0, hi] (one column: always 1). */
static int nnls_solve(const normal_t *ne, int two, const double *hi,
                      double *t)
{
    t[0] = ne->g11 > 0.0 && ne->b1 > 0.0 ? fmin(ne->b1 / ne->g11, hi[0])
                                         : 0.0;
    if (!two) {
        return 1;
    }
    t[1] = ne->g22 > 0.0 && ne->b2 > 0.0 ? fmin(ne->b2 / ne->g22, hi[1])
                                         : 0.0;
    {
        double det = ne->g11 * ne->g22 - ne->g12 * ne->g12;
        if (det > 1e-14 * ne->g11 * ne->g22 && det > 0.0) {
            double u1 = (ne->b1 * ne->g22 - ne->b2 * ne->g12) / det;
            double u2 = (ne->b2 * ne->g11 - ne->b1 * ne->g12) / det;
            if (u1 >= 0.0 && u2 >= 0.0 && u1 <= hi[0] && u2 <= hi[1]) {
                t[0] = u1; /* both active: the unconstrained optimum */
                t[1] = u2;
                return 1;
            }
        }
    }
    return 0;
}

/* The NNLS scales of one or two columns c1, c2 for the target R - c0,
 * each clamped into [0, hi]. */
static void nnls(const bf_problem *pb, const double *c0, const double *c1,
                 const double *c2, const double *hi, double *t)
{
    normal_t ne = {0.0, 0.0, 0.0, 0.0, 0.0};
    double a[MAX_LIN];
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double w = weight_of(pb, k);
        double r = pb->data[k] - c0[k];
        ne.g11 += w * c1[k] * c1[k];
        ne.b1 += w * c1[k] * r;
        if (c2 != NULL) {
            ne.g12 += w * c1[k] * c2[k];
            ne.g22 += w * c2[k] * c2[k];
            ne.b2 += w * c2[k] * r;
        }
    }
    if (nnls_solve(&ne, c2 != NULL, hi, t)) {
        return;
    }
    a[0] = t[0];
    a[1] = t[1];
    /* one scale at 0: the better of the two one-column optima */
    if (sse(pb, c0, c1, c2, a[0], 0.0) <= sse(pb, c0, c1, c2, 0.0, a[1])) {
        t[0] = a[0];
        t[1] = 0.0;
    } else {
        t[0] = 0.0;
        t[1] = a[1];
    }
}

int bf__varpro_value(bf__fitctx *fc, const double *param, double *value)
{
    const bf_problem *pb = fc->pb;
    const size_t n = fc->pm->n;
    double *col[MAX_LIN + 1];
    double hi[MAX_LIN];
    size_t lj[MAX_LIN];
    size_t n_l = 0;
    size_t j;
    size_t q;
    size_t b;
    double t[MAX_LIN] = {0.0, 0.0};
    int rc;
    for (j = 0; j < pb->type->p; j++) {
        if ((fc->lin_mask >> j) & 1u) {
            if (n_l == MAX_LIN || fc->cols == NULL) {
                return BF_EINVAL;
            }
            hi[n_l] = pb->hi[j];
            lj[n_l++] = j;
        }
    }
    for (q = 0; q <= n_l; q++) {
        col[q] = fc->cols + q * n;
    }
    /* c_0 and the c_j, each part of the model evaluated once (the
     * kernel's columns), then as bf__curve: rho = values cos ti; kept
     * from the last evaluation when it was at the same point */
    fc->n_eval++;
    if (!fc->cols_ok || fc->cols_lin != fc->lin_mask ||
        memcmp(fc->cols_at, param, pb->type->p * sizeof *param) != 0) {
        fc->cols_ok = 0;
        rc = (fc->pm->kr->columns != NULL ? fc->pm->kr->columns
                                          : bf__columns_values)(
            fc->pm, param, fc->lin_mask, fc->work, col[0], col + 1);
        if (rc != BF_OK) {
            return BF_EDOM;
        }
        for (q = 0; q <= n_l; q++) {
            const double *cti = fc->pm->cs->cti;
            size_t k;
            for (k = 0; k < n; k++) {
                col[q][k] *= cti[k];
                if (!isfinite(col[q][k])) {
                    return BF_EDOM;
                }
            }
        }
        memcpy(fc->cols_at, param, pb->type->p * sizeof *param);
        fc->cols_lin = fc->lin_mask;
        fc->cols_ok = 1;
    }
    /* per block (a joint fit's channel, SPEC §9.4; one block otherwise):
     * its scales by NNLS on the shared columns, its curve, its S; the
     * blocks' S summed */
    *value = 0.0;
    for (b = 0; b < fc->blocks; b++) {
        bf_problem sub = *pb;
        double *curve = fc->curve + b * n;
        size_t k;
        sub.data = pb->data + b * n;
        nnls(&sub, col[0], col[1], n_l > 1 ? col[2] : NULL, hi, t);
        for (k = 0; k < n; k++) { /* the curve at the solved scales */
            double v = col[0][k];
            for (q = 0; q < n_l; q++) {
                v += t[q] * col[q + 1][k];
            }
            curve[k] = v;
        }
        for (q = 0; q < n_l; q++) {
            fc->block_lin[b * BF_MAX_PARAMS + lj[q]] = t[q];
            if (b == 0) {
                fc->lin[lj[q]] = t[q];
            }
        }
        *value += bf__objective(&sub, fc->pm->cs->cti, NULL, curve,
                                fc->scratch);
    }
    return isfinite(*value) ? BF_OK : BF_EDOM;
}

/* ==== coordinates, the grid ============================================== */

/* What moves in a search: parameter idx[i] over [lo_i, hi_i], in ln x when
 * lg[i] (lo > 0). */
typedef struct {
    bf__fitctx *fc;
    double base[BF_MAX_PARAMS];
    size_t m;
    size_t idx[BF_MAX_PARAMS];
    int lg[BF_MAX_PARAMS];
    double lo[BF_MAX_PARAMS];
    double hi[BF_MAX_PARAMS];
    size_t count[BF_MAX_PARAMS]; /* grid points */
    double zero_first[BF_MAX_PARAMS]; /* 1: grid point 0 is x = 0 */
    const double *sw; /* sqrt of the weights (levenberg), NULL: 1 */
    double flat_f;  /* Nelder-Mead's last trial value */
    size_t flat_n;  /* trial values in a row equal to it */
    /* A fold's fit (bf__varpro_fit_grid): the minima its descents have
     * reached (search coordinates, values), n_known of them; a descent
     * that comes within near (per axis) of one at no lower value stops
     * there, merged (its basin's minimum is known). */
    int merge;
    size_t n_known;
    double known_u[STARTS][BF_MAX_PARAMS];
    double known_f[STARTS];
    double near[BF_MAX_PARAMS];
    int merged;
} space_t;

/* A domain [lo, hi] searched on a log scale: positive lo, a factor 50. */
static int log_scaled(double lo, double hi)
{
    return (lo > 0.0 && hi / lo >= 50.0) || (lo == 0.0 && hi >= 50.0);
}

static void space_init(space_t *sp, bf__fitctx *fc, unsigned mask)
{
    const bf_problem *pb = fc->pb;
    size_t j;
    memset(sp, 0, sizeof *sp);
    sp->fc = fc;
    memcpy(sp->base, pb->fixed, sizeof sp->base);
    for (j = 0; j < pb->type->p; j++) {
        if ((mask >> j) & 1u) {
            size_t i = sp->m++;
            sp->idx[i] = j;
            sp->lo[i] = pb->lo[j];
            sp->hi[i] = pb->hi[j];
            sp->lg[i] = log_scaled(pb->lo[j], pb->hi[j]);
            if (sp->lg[i] && !(sp->lo[i] > 0.0)) {
                /* [0, hi]: 0 and a log grid from hi 1e-6 */
                sp->zero_first[i] = 1.0;
                sp->lo[i] = pb->hi[j] * 1e-6;
            }
        }
    }
    for (j = 0; j < sp->m; j++) {
        size_t d = sp->m < 8 ? sp->m : 8;
        sp->count[j] = sp->lg[j] ? grid_log[d] : grid_lin[d];
    }
}

/* Grid coordinate i of axis a. */
static double grid_x(const space_t *sp, size_t a, size_t i)
{
    size_t c = sp->count[a];
    double f;
    if (sp->zero_first[a] != 0.0) {
        if (i == 0) {
            return 0.0;
        }
        i--;
        c--;
    }
    f = c > 1 ? (double)i / (double)(c - 1) : 0.0;
    if (sp->lg[a]) {
        return exp(log(sp->lo[a]) + f * (log(sp->hi[a]) - log(sp->lo[a])));
    }
    return sp->lo[a] + f * (sp->hi[a] - sp->lo[a]);
}

/* x from the search coordinate u (clamped into the domain). */
static double from_u(const space_t *sp, size_t a, double u)
{
    double x = sp->lg[a] ? exp(u) : u;
    double lo = sp->zero_first[a] != 0.0 ? 0.0 : sp->lo[a];
    if (sp->lg[a] && sp->zero_first[a] != 0.0 && x <= sp->lo[a]) {
        x = 0.0; /* below the log grid's first point: the bound 0 */
    }
    return x < lo ? lo : (x > sp->hi[a] ? sp->hi[a] : x);
}

static double to_u(const space_t *sp, size_t a, double x)
{
    if (!sp->lg[a]) {
        return x;
    }
    return log(x > sp->lo[a] ? x : sp->lo[a]);
}

/* The objective at x (full vector; the scales solved when the context
 * says so), UNDEFINED where not defined. */
static double value_at(bf__fitctx *fc, const double *x)
{
    double v;
    if (bf__fit_value(fc, x, &v) != BF_OK || !isfinite(v)) {
        return UNDEFINED;
    }
    return v;
}

/* ==== Nelder-Mead in the search coordinates ============================== */

static double f_nm(const gsl_vector *u, void *arg)
{
    space_t *sp = arg;
    double x[BF_MAX_PARAMS];
    double v;
    size_t a;
    memcpy(x, sp->base, sizeof x);
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] = from_u(sp, a, gsl_vector_get(u, a));
    }
    v = value_at(sp->fc, x);
    if (v == sp->flat_f) {
        sp->flat_n++;
    } else {
        sp->flat_f = v;
        sp->flat_n = 1;
    }
    return v;
}

/* Minimises from x (in place; *f its value on return) with initial steps
 * step (search coordinates). */
static int nelder_mead(space_t *sp, double *x, const double *step, double *f)
{
    gsl_multimin_fminimizer *mn;
    gsl_multimin_function fn;
    gsl_vector *u;
    gsl_vector *ss;
    size_t a;
    size_t it;
    int status = GSL_CONTINUE;
    if (sp->m == 0) {
        *f = value_at(sp->fc, x);
        return BF_OK;
    }
    mn = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2,
                                       sp->m);
    u = gsl_vector_alloc(sp->m);
    ss = gsl_vector_alloc(sp->m);
    if (mn == NULL || u == NULL || ss == NULL) {
        gsl_multimin_fminimizer_free(mn);
        gsl_vector_free(u);
        gsl_vector_free(ss);
        return BF_ENOMEM;
    }
    memcpy(sp->base, x, sizeof sp->base);
    for (a = 0; a < sp->m; a++) {
        gsl_vector_set(u, a, to_u(sp, a, x[sp->idx[a]]));
        gsl_vector_set(ss, a, step[a]);
    }
    fn.n = sp->m;
    fn.f = f_nm;
    fn.params = sp;
    sp->flat_f = NAN;
    sp->flat_n = 0;
    gsl_multimin_fminimizer_set(mn, &fn, u, ss);
    for (it = 0; it < NM_ITER && status == GSL_CONTINUE &&
                 sp->flat_n < NM_FLAT * (sp->m + 1);
         it++) {
        if (gsl_multimin_fminimizer_iterate(mn) != GSL_SUCCESS) {
            break;
        }
        status = gsl_multimin_test_size(gsl_multimin_fminimizer_size(mn),
                                        NM_SIZE);
    }
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] =
            from_u(sp, a, gsl_vector_get(gsl_multimin_fminimizer_x(mn), a));
    }
    *f = gsl_multimin_fminimizer_minimum(mn);
    gsl_multimin_fminimizer_free(mn);
    gsl_vector_free(u);
    gsl_vector_free(ss);
    return BF_OK;
}

/* ==== Levenberg-Marquardt on the projected residuals ===================== */

/* r_k = sqrt(w_k) (rho_hat_k - rho_k) at u, the scales solved (ngan). */
static int f_lm(const gsl_vector *u, void *arg, gsl_vector *f)
{
    const space_t *sp = arg;
    const bf_problem *pb = sp->fc->pb;
    double x[BF_MAX_PARAMS];
    double v;
    size_t a;
    size_t k;
    memcpy(x, sp->base, sizeof x);
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] = from_u(sp, a, gsl_vector_get(u, a));
    }
    if (bf__fit_value(sp->fc, x, &v) != BF_OK || !isfinite(v)) {
        return GSL_EDOM;
    }
    for (k = 0; k < pb->n * sp->fc->blocks; k++) { /* every block's */
        double w = sp->sw != NULL ? sp->sw[k % pb->n] : 1.0;
        f->data[k * f->stride] = w * (sp->fc->curve[k] - pb->data[k]);
    }
    return GSL_SUCCESS;
}

/* 1 when LM's iterate (cost c) lies within sp->near of a known minimum
 * whose value is no higher than c (space_t.known_u). */
static int joins_known(const space_t *sp, gsl_multifit_nlinear_workspace *w)
{
    const gsl_vector *u = gsl_multifit_nlinear_position(w);
    double c;
    size_t e;
    gsl_blas_ddot(gsl_multifit_nlinear_residual(w),
                  gsl_multifit_nlinear_residual(w), &c);
    for (e = 0; e < sp->n_known; e++) {
        size_t a;
        int in = c >= sp->known_f[e];
        for (a = 0; in && a < sp->m; a++) {
            /* the iterate's coordinate clamped into the domain */
            double ua = to_u(sp, a, from_u(sp, a, gsl_vector_get(u, a)));
            in = fabs(ua - sp->known_u[e][a]) <= sp->near[a];
        }
        if (in) {
            return 1;
        }
    }
    return 0;
}

/* The loop of GSL's gsl_multifit_nlinear_driver (LM_ITER iterations,
 * tolerances LM_TOL; the same iterates and status), and with stall > 0 a
 * stop at the first iteration that lowers the cost by less than stall of
 * it (fitctx.stall); with sp->merge a stop, sp->merged, at the first
 * iterate that joins a known minimum (joins_known). */
static int drive(space_t *sp, gsl_multifit_nlinear_workspace *w, int *info)
{
    double stall = sp->fc->stall;
    double c0 = 0.0;
    size_t iter = 0;
    int st;
    if (stall > 0.0) {
        gsl_blas_ddot(gsl_multifit_nlinear_residual(w),
                      gsl_multifit_nlinear_residual(w), &c0);
    }
    do {
        st = gsl_multifit_nlinear_iterate(w);
        if (st == GSL_ENOPROG && iter == 0) {
            *info = st;
            return GSL_EMAXITER;
        }
        iter++;
        st = gsl_multifit_nlinear_test(LM_TOL, LM_TOL, LM_TOL, info, w);
        if (st == GSL_CONTINUE && stall > 0.0) {
            double c;
            gsl_blas_ddot(gsl_multifit_nlinear_residual(w),
                          gsl_multifit_nlinear_residual(w), &c);
            if (c0 - c < stall * c) {
                return GSL_SUCCESS;
            }
            c0 = c;
        }
        if (st == GSL_CONTINUE && sp->merge && joins_known(sp, w)) {
            sp->merged = 1;
            return GSL_SUCCESS;
        }
    } while (st == GSL_CONTINUE && iter < LM_ITER);
    if (st == GSL_ETOLF || st == GSL_ETOLX || st == GSL_ETOLG) {
        *info = st; /* converged to rounding */
        return GSL_SUCCESS;
    }
    return iter >= LM_ITER && st != GSL_SUCCESS ? GSL_EMAXITER : st;
}

/* GSL's workspace for n residuals and p parameters (default parameters)
 * and n doubles for the weights' square roots, kept in fc between runs;
 * NULL when out of memory. */
static gsl_multifit_nlinear_workspace *lm_workspace(bf__fitctx *fc,
                                                    size_t n, size_t p)
{
    if (fc->lm == NULL || fc->lm_n != n || fc->lm_p != p) {
        gsl_multifit_nlinear_parameters prm =
            gsl_multifit_nlinear_default_parameters();
        bf__varpro_free(fc);
        fc->lm = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust,
                                            &prm, n, p);
        fc->lm_sw = malloc(n * sizeof *fc->lm_sw);
        if (fc->lm == NULL || fc->lm_sw == NULL) {
            bf__varpro_free(fc);
            return NULL;
        }
        fc->lm_n = n;
        fc->lm_p = p;
    }
    return fc->lm;
}

void bf__varpro_free(bf__fitctx *fc)
{
    gsl_multifit_nlinear_free(fc->lm);
    free(fc->lm_sw);
    fc->lm = NULL;
    fc->lm_sw = NULL;
    fc->lm_n = 0;
    fc->lm_p = 0;
}

/* Levenberg-Marquardt (GSL's trust region, finite-difference Jacobian)
 * from x in the search coordinates; x is replaced when it ends lower.
 * *done (when not NULL): 1 when the driver met its tolerances. */
static int levenberg(space_t *sp, double *x, double *f, int *done)
{
    gsl_multifit_nlinear_workspace *w;
    gsl_multifit_nlinear_fdf fdf;
    gsl_vector *u;
    double *sw;
    double y[BF_MAX_PARAMS];
    double fy;
    int info;
    size_t a;
    size_t n_res = sp->fc->pb->n * sp->fc->blocks;
    if (done != NULL) {
        *done = 0;
    }
    if (sp->m == 0 || n_res <= sp->m) {
        return BF_OK;
    }
    w = lm_workspace(sp->fc, n_res, sp->m);
    u = gsl_vector_alloc(sp->m);
    if (w == NULL || u == NULL) {
        gsl_vector_free(u);
        return BF_ENOMEM;
    }
    sw = sp->fc->pb->weight != NULL ? sp->fc->lm_sw : NULL;
    for (a = 0; sw != NULL && a < sp->fc->pb->n; a++) {
        sw[a] = sqrt(sp->fc->pb->weight[a]); /* once, not per residual */
    }
    sp->sw = sw;
    memcpy(sp->base, x, sizeof sp->base);
    for (a = 0; a < sp->m; a++) {
        /* a start on a bound moves a hundredth of the domain inside: the
         * clamp's derivative is 0 there */
        double ua = to_u(sp, a, x[sp->idx[a]]);
        double lo = to_u(sp, a, sp->lo[a]);
        double hi = to_u(sp, a, sp->hi[a]);
        double in = 0.01 * (hi - lo);
        ua = ua < lo + in ? lo + in : (ua > hi - in ? hi - in : ua);
        gsl_vector_set(u, a, ua);
    }
    memset(&fdf, 0, sizeof fdf);
    fdf.f = f_lm;
    fdf.n = n_res;
    fdf.p = sp->m;
    fdf.params = sp;
    if (gsl_multifit_nlinear_init(u, &fdf, w) == GSL_SUCCESS) {
        int st = drive(sp, w, &info);
        if (done != NULL) {
            *done = st == GSL_SUCCESS;
        }
        memcpy(y, x, sizeof y);
        for (a = 0; a < sp->m; a++) {
            y[sp->idx[a]] =
                from_u(sp, a, gsl_vector_get(gsl_multifit_nlinear_position(w),
                                             a));
        }
        fy = value_at(sp->fc, y);
        if (fy < *f) {
            memcpy(x, y, sizeof y);
            *f = fy;
        }
    }
    gsl_vector_free(u);
    sp->sw = NULL;
    return BF_OK;
}

/* Nelder-Mead twice (the second restarted at a tenth of the steps, so a
 * collapsed simplex does not stop it early), keeping x when no better. */
static int polish(space_t *sp, double *x, const double *step, double *f)
{
    double s2[BF_MAX_PARAMS];
    double y[BF_MAX_PARAMS];
    double fy;
    size_t a;
    int pass;
    int rc = BF_OK;
    *f = value_at(sp->fc, x);
    for (pass = 0; pass < 2 && rc == BF_OK; pass++) {
        for (a = 0; a < sp->m; a++) {
            s2[a] = pass == 0 ? step[a] : 0.1 * step[a];
        }
        memcpy(y, x, sizeof y);
        rc = nelder_mead(sp, y, s2, &fy);
        fy = value_at(sp->fc, y); /* the clamped point's own value */
        if (rc == BF_OK && fy < *f) {
            memcpy(x, y, sizeof y);
            *f = fy;
        }
    }
    return rc;
}

/* ==== the grid search ===================================================== */

typedef struct {
    double f;
    size_t idx;
} cand_t;

/* The grid point's multi-index digits (the first axis slowest). */
static void digits(const space_t *sp, size_t idx, size_t *d)
{
    size_t a = sp->m;
    while (a-- > 0) {
        d[a] = idx % sp->count[a];
        idx /= sp->count[a];
    }
}

static size_t index_of(const space_t *sp, const size_t *d)
{
    size_t idx = 0;
    size_t a;
    for (a = 0; a < sp->m; a++) {
        idx = idx * sp->count[a] + d[a];
    }
    return idx;
}

static void point_of(const space_t *sp, size_t idx, double *x)
{
    size_t d[BF_MAX_PARAMS];
    size_t a;
    digits(sp, idx, d);
    memcpy(x, sp->base, sizeof sp->base);
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] = grid_x(sp, a, d[a]);
    }
}

/* 1 when no lattice neighbour of point idx has a lower value. */
static int local_min(const space_t *sp, const double *vals, size_t idx)
{
    size_t d[BF_MAX_PARAMS];
    size_t a;
    digits(sp, idx, d);
    for (a = 0; a < sp->m; a++) {
        int s;
        for (s = -1; s <= 1; s += 2) {
            size_t e[BF_MAX_PARAMS];
            if ((s < 0 && d[a] == 0) || (s > 0 && d[a] + 1 == sp->count[a])) {
                continue;
            }
            memcpy(e, d, sizeof e);
            e[a] = (size_t)((long)d[a] + s);
            if (vals[index_of(sp, e)] < vals[idx]) {
                return 0;
            }
        }
    }
    return 1;
}

/* The STARTS lowest local minima of the grid into best (n of them). */
static void pick_starts(const space_t *sp, const double *vals, size_t points,
                        cand_t *best, size_t *n)
{
    size_t g;
    *n = 0;
    for (g = 0; g < points; g++) {
        size_t q;
        if (!(vals[g] < UNDEFINED) || !local_min(sp, vals, g)) {
            continue;
        }
        if (*n == STARTS && !(vals[g] < best[STARTS - 1].f)) {
            continue;
        }
        q = *n < STARTS ? (*n)++ : STARTS - 1;
        while (q > 0 && best[q - 1].f > vals[g]) {
            best[q] = best[q - 1];
            q--;
        }
        best[q].f = vals[g];
        best[q].idx = g;
    }
}

/* The scales of x solved at x's other values (fc->lin_mask). */
static void fill_scales(bf__fitctx *fc, double *x)
{
    size_t j;
    (void)value_at(fc, x);
    for (j = 0; j < fc->pb->type->p; j++) {
        if ((fc->lin_mask >> j) & 1u) {
            x[j] = fc->lin[j];
        }
    }
}

/* The steps of Nelder-Mead: one grid step (search coordinates). */
static void grid_steps(const space_t *sp, double *step)
{
    size_t a;
    for (a = 0; a < sp->m; a++) {
        double c = (double)(sp->count[a] > 1 ? sp->count[a] - 1 : 1);
        step[a] = sp->lg[a] ? (log(sp->hi[a]) - log(sp->lo[a])) / c
                            : (sp->hi[a] - sp->lo[a]) / c;
        if (!(step[a] > 0.0)) {
            step[a] = 1e-3;
        }
    }
}

/* -1 (+1) when moving parameter a of x lies on the lower (upper) bound of
 * its domain (within 1e-6 of the search coordinate's span), else 0. */
static int bound_side(const space_t *sp, const double *x, size_t a)
{
    double u = to_u(sp, a, x[sp->idx[a]]);
    double lo = to_u(sp, a, sp->lo[a]);
    double hi = to_u(sp, a, sp->hi[a]);
    double tol = 1e-6 * (hi - lo);
    if (u <= lo + tol || x[sp->idx[a]] <= sp->lo[a]) {
        return -1;
    }
    return u >= hi - tol ? 1 : 0;
}

/* 1 when a moving parameter of x lies on a bound of its domain. */
static int on_bound(const space_t *sp, const double *x)
{
    size_t a;
    for (a = 0; a < sp->m; a++) {
        if (bound_side(sp, x, a) != 0) {
            return 1;
        }
    }
    return 0;
}

/* 1 when x (f its value) on a bound is a Karush-Kuhn-Tucker point as far
 * as one-sided differences tell: every coordinate on a bound, moved
 * KKT_STEP of its span into the domain, gives a value >= f (a converged
 * LM has minimised over the others: the clamp leaves them free), so
 * Nelder-Mead has nothing to take off the bound. */
static int bound_kkt(const space_t *sp, const double *x, double f)
{
    size_t a;
    for (a = 0; a < sp->m; a++) {
        int side = bound_side(sp, x, a);
        double lo = to_u(sp, a, sp->lo[a]);
        double hi = to_u(sp, a, sp->hi[a]);
        double y[BF_MAX_PARAMS];
        if (side == 0) {
            continue;
        }
        memcpy(y, x, sizeof y);
        y[sp->idx[a]] = from_u(sp, a, side < 0 ? lo + KKT_STEP * (hi - lo)
                                               : hi - KKT_STEP * (hi - lo));
        if (value_at(sp->fc, y) < f) {
            return 0;
        }
    }
    return 1;
}

/* From x (f its value; both replaced when it ends lower) to its basin's
 * minimum: Levenberg-Marquardt; where it ends on a bound (the clamped
 * coordinates' Jacobian vanishes there) and is not plainly the minimum
 * there, Nelder-Mead, without derivatives, takes it off, and LM
 * finishes. */
static int descend(space_t *sp, const double *step, double *x, double *f)
{
    double fl;
    int done;
    int rc;
    sp->merged = 0;
    rc = levenberg(sp, x, f, &done);
    fl = *f;
    if (sp->merged) {
        return rc; /* a known minimum's basin */
    }
    if (rc == BF_OK && on_bound(sp, x) && !(done && bound_kkt(sp, x, *f))) {
        rc = polish(sp, x, step, f);
    }
    if (rc == BF_OK && *f < fl) {
        rc = levenberg(sp, x, f, NULL);
    }
    return rc;
}

/* Adds x (value f; not merged) to the minima a fold's descents join. */
static void add_known(space_t *sp, const double *x, double f)
{
    size_t a;
    if (!sp->merge || sp->merged || sp->n_known == STARTS) {
        return;
    }
    for (a = 0; a < sp->m; a++) {
        sp->known_u[sp->n_known][a] = to_u(sp, a, x[sp->idx[a]]);
    }
    sp->known_f[sp->n_known++] = f;
}

/* The separable ngan fit on fc (fc->pb's objective ngan); pre (NULL:
 * computed here) the grid's values, as bf__varpro_fold_grids gives them:
 * a fold's fit, whose descents merge into the minima the earlier ones
 * reached (space_t.known_u). */
static int varpro_ngan(bf__fitctx *fc, unsigned lin, const double *pre,
                       bf_fit_result *grid, bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    space_t sp;
    double *vals;
    size_t points = 1;
    cand_t best[STARTS];
    size_t n_best;
    size_t g;
    size_t a;
    double step[BF_MAX_PARAMS];
    double xbest[BF_MAX_PARAMS];
    double fbest = UNDEFINED;
    int rc = BF_OK;
    fc->lin_mask = lin;
    space_init(&sp, fc, pb->free_mask & ~lin);
    for (a = 0; a < sp.m; a++) {
        points *= sp.count[a];
    }
    vals = malloc(points * sizeof *vals);
    if (vals == NULL) {
        fc->lin_mask = 0;
        return BF_ENOMEM;
    }
    for (g = 0; g < points; g++) {
        double x[BF_MAX_PARAMS];
        if (pre != NULL) {
            vals[g] = pre[g];
            continue;
        }
        point_of(&sp, g, x);
        vals[g] = value_at(fc, x);
    }
    pick_starts(&sp, vals, points, best, &n_best);
    free(vals);
    if (n_best == 0) {
        fc->lin_mask = 0;
        return BF_EDOM;
    }
    point_of(&sp, best[0].idx, xbest);
    fill_scales(fc, xbest);
    if (grid != NULL) {
        memset(grid, 0, sizeof *grid);
        memcpy(grid->param, xbest, sizeof xbest);
        grid->lse = best[0].f;
        grid->n_eval = points;
    }
    grid_steps(&sp, step);
    sp.merge = pre != NULL;
    for (a = 0; a < sp.m; a++) {
        sp.near[a] = MERGE_NEAR * step[a];
    }
    for (g = 0; g < n_best && rc == BF_OK; g++) {
        double x[BF_MAX_PARAMS];
        double f;
        point_of(&sp, best[g].idx, x);
        f = value_at(fc, x);
        rc = descend(&sp, step, x, &f);
        if (rc == BF_OK && f < fbest) {
            fbest = f;
            memcpy(xbest, x, sizeof x);
        }
        if (rc == BF_OK) {
            add_known(&sp, x, f);
        }
    }
    fill_scales(fc, xbest);
    memcpy(result->param, xbest, sizeof xbest);
    result->lse = fbest;
    fc->lin_mask = 0;
    return rc;
}

/* The free scales of pb (bf_param.linear) as a mask; *n_lin their number. */
static unsigned lin_of(const bf_problem *pb, size_t *n_lin)
{
    unsigned lin = 0;
    size_t j;
    *n_lin = 0;
    for (j = 0; j < pb->type->p; j++) {
        if (((pb->free_mask >> j) & 1u) && pb->type->param[j].linear) {
            lin |= 1u << j;
            (*n_lin)++;
        }
    }
    return lin;
}

unsigned bf__varpro_lin(const bf_problem *pb)
{
    size_t n_lin;
    return lin_of(pb, &n_lin);
}

int bf__varpro_refine(bf__fitctx *fc, const double *start,
                      bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    unsigned lin = bf__varpro_lin(pb);
    unsigned saved = fc->lin_mask;
    size_t eval0 = fc->n_eval;
    space_t sp;
    double x[BF_MAX_PARAMS];
    double step[BF_MAX_PARAMS];
    double f;
    size_t j;
    int rc;
    memset(result, 0, sizeof *result);
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        pb->objective != BF_OBJ_NGAN || fc->blocks > 1) {
        return BF_EINVAL; /* not a joint fit's channels (no intervals) */
    }
    fc->lin_mask = lin;
    space_init(&sp, fc, pb->free_mask & ~lin);
    memcpy(x, pb->fixed, sizeof x);
    for (j = 0; j < sp.m; j++) { /* the free values from start */
        x[sp.idx[j]] = start[sp.idx[j]];
    }
    f = value_at(fc, x);
    grid_steps(&sp, step);
    rc = f < UNDEFINED ? descend(&sp, step, x, &f) : BF_EDOM;
    if (rc == BF_OK) {
        fill_scales(fc, x);
        memcpy(result->param, x, sizeof x);
        result->lse = f;
    }
    result->n_eval = fc->n_eval - eval0;
    fc->lin_mask = saved;
    return rc;
}

int bf__varpro_scales(bf__fitctx *fc, const double *param, double *out)
{
    const bf_problem *pb = fc->pb;
    size_t n_lin;
    unsigned lin = lin_of(pb, &n_lin);
    unsigned keep = fc->lin_mask;
    size_t b;
    size_t j;
    double v;
    int rc;
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        n_lin > MAX_LIN || n_lin == 0) {
        return BF_EINVAL;
    }
    fc->lin_mask = lin;
    rc = bf__varpro_value(fc, param, &v);
    fc->lin_mask = keep;
    for (b = 0; rc == BF_OK && b < fc->blocks; b++) {
        for (j = 0; j < BF_MAX_PARAMS; j++) {
            out[b * BF_MAX_PARAMS + j] =
                j < pb->type->p && ((lin >> j) & 1u)
                    ? fc->block_lin[b * BF_MAX_PARAMS + j]
                    : param[j];
        }
    }
    return rc;
}

/* ==== dense data ========================================================= */

/* Above BF__DENSE_K configurations (every cell of a MERL table, issue 17
 * item 10) the grid and the descents from its minima run on about
 * DENSE_SUB of them, every s-th in index order, and only their best end
 * descends again on all of them: the grid and the starts only pick the
 * basin, which a regular subsample of dense data shows as well, at 1/s
 * of the cost. The grid's reported value is the full data's at its
 * point. */
#define DENSE_SUB 16384

/* varpro_ngan of fc's problem on its configurations 0, s, 2s, ... */
static int ngan_subsample(bf__fitctx *fc, unsigned lin, bf_fit_result *grid,
                          bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    size_t stride = (pb->n + DENSE_SUB - 1) / DENSE_SUB;
    size_t n = (pb->n + stride - 1) / stride;
    bf_geom *geom = malloc(n * sizeof *geom);
    double *data = malloc(2 * n * sizeof *data);
    bf_problem sub = *pb;
    bf__cset cs;
    bf__prep pm;
    bf__fitctx sfc;
    size_t i;
    int rc = BF_ENOMEM;
    if (geom != NULL && data != NULL) {
        for (i = 0; i < n; i++) {
            geom[i] = pb->geom[i * stride];
            data[i] = pb->data[i * stride];
            data[n + i] = pb->weight != NULL ? pb->weight[i * stride] : 1.0;
        }
        sub.n = n;
        sub.geom = geom;
        sub.data = data;
        sub.weight = pb->weight != NULL ? data + n : NULL;
        rc = bf__cset_init(&cs, n, geom);
    }
    if (rc == BF_OK) {
        rc = bf__prep_init(&pm, pb->type, &cs);
        if (rc == BF_OK) {
            rc = bf__fitctx_init(&sfc, &pm);
            if (rc == BF_OK) {
                bf__fitctx_use(&sfc, &sub);
                rc = varpro_ngan(&sfc, lin, NULL, grid, result);
                fc->n_eval += sfc.n_eval;
                bf__fitctx_free(&sfc);
            }
            bf__prep_free(&pm);
        }
        bf__cset_free(&cs);
    }
    free(geom);
    free(data);
    return rc;
}

/* The separable ngan fit of dense data: the subsample's, then one descent
 * on every configuration. */
static int varpro_dense(bf__fitctx *fc, unsigned lin, bf_fit_result *grid,
                        bf_fit_result *result)
{
    space_t sp;
    double step[BF_MAX_PARAMS];
    double x[BF_MAX_PARAMS];
    double f;
    int rc = ngan_subsample(fc, lin, grid, result);
    if (rc != BF_OK) {
        return rc;
    }
    fc->lin_mask = lin;
    space_init(&sp, fc, fc->pb->free_mask & ~lin);
    grid_steps(&sp, step);
    if (grid != NULL) {
        fill_scales(fc, grid->param);
        grid->lse = value_at(fc, grid->param);
    }
    memcpy(x, result->param, sizeof x);
    f = value_at(fc, x);
    rc = descend(&sp, step, x, &f);
    fill_scales(fc, x);
    memcpy(result->param, x, sizeof x);
    result->lse = f;
    fc->lin_mask = 0;
    return rc;
}

/* bf__varpro_fit with the grid's ngan values pre (NULL: computed). */
static int varpro_fit_pre(bf__fitctx *fc, const double *pre,
                          bf_fit_result *grid, bf_fit_result *result);

int bf__varpro_fit(bf__fitctx *fc, bf_fit_result *grid,
                   bf_fit_result *result)
{
    return varpro_fit_pre(fc, NULL, grid, result);
}

int bf__varpro_fit_grid(bf__fitctx *fc, const double *vals,
                        bf_fit_result *result)
{
    return varpro_fit_pre(fc, vals, NULL, result);
}

/* The grid of the separable fit of fc->pb: its points (0 where it has
 * none: dense data, a joint fit, not such a model). */
static size_t grid_points(bf__fitctx *fc, unsigned lin)
{
    const bf_problem *pb = fc->pb;
    space_t sp;
    size_t points = 1;
    size_t a;
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        pb->n > BF__DENSE_K || fc->blocks > 1) {
        return 0;
    }
    space_init(&sp, fc, pb->free_mask & ~lin);
    for (a = 0; a < sp.m; a++) {
        points *= sp.count[a];
    }
    return points;
}

/* A fold's S from the whole's sums minus the fold's, in the normal
 * equations' form S = <R', R'> - 2 t.b + t'G t, has the rounding of its
 * terms taken at the whole's size (Cauchy-Schwarz bounds of the mixed
 * sums: |<c1, R'>| <= sqrt(<c1, c1> <R', R'>)); below FOLD_DIGITS of that
 * size the fold's S is summed directly instead (a lobe whose values run
 * to 1e139 at a grid point: one held-out configuration's term is nearly
 * the whole's, and the training sums cancel to nothing). */
#define FOLD_DIGITS 1e-4

/* S = <R', R'> - 2 t.b + t'G t of the scales t (R' = R - c0) from the
 * training normal equations ne and rr = <R', R'>; NAN when it is below
 * FOLD_DIGITS of its terms' size in the whole's sums all (g11 g12 g22 b1
 * b2 rr). */
static double sse_normal(const normal_t *ne, double rr, const double *t,
                         const double *all)
{
    double s1 = sqrt(all[0] * all[5]);
    double s2 = sqrt(all[2] * all[5]);
    double size = all[5] + 2.0 * (fabs(t[0]) * s1 + fabs(t[1]) * s2) +
                  t[0] * t[0] * all[0] +
                  2.0 * fabs(t[0] * t[1]) * sqrt(all[0] * all[2]) +
                  t[1] * t[1] * all[2];
    double v = rr - 2.0 * (t[0] * ne->b1 + t[1] * ne->b2) +
               t[0] * t[0] * ne->g11 + 2.0 * t[0] * t[1] * ne->g12 +
               t[1] * t[1] * ne->g22;
    return v >= FOLD_DIGITS * size && isfinite(size) ? v : NAN;
}

/* Every fold's ngan value at the point whose curve parts fc holds (the
 * columns c0, c1, c2 of n_l scales, or with none the curve as c0): the
 * fold's training configurations (weight 1 off the fold, 0 on it) in the
 * normal equations and S, from one pass's sums per held-out fold (the
 * training sums: the whole's minus the fold's; mom: 6 (folds + 1)
 * doubles); into out[f * stride], NAN where S cancels (sse_normal). */
static void fold_values(const bf__fitctx *fc, size_t n_l, const double *hi,
                        const size_t *fold, size_t folds, double *mom,
                        double *out, size_t stride)
{
    const size_t n = fc->pm->n;
    const double *data = fc->pb->data;
    const double *c0 = n_l > 0 ? fc->cols : fc->curve;
    const double *c1 = fc->cols + n;
    const double *c2 = fc->cols + 2 * n;
    double *all = mom + 6 * folds;
    size_t f;
    size_t k;
    size_t q;
    memset(mom, 0, 6 * (folds + 1) * sizeof *mom);
    for (k = 0; k < n; k++) { /* g11 g12 g22 b1 b2 rr of each fold */
        double *m = mom + 6 * fold[k];
        double r = data[k] - c0[k];
        if (n_l > 0) {
            m[0] += c1[k] * c1[k];
            m[3] += c1[k] * r;
        }
        if (n_l > 1) {
            m[1] += c1[k] * c2[k];
            m[2] += c2[k] * c2[k];
            m[4] += c2[k] * r;
        }
        m[5] += r * r;
    }
    for (f = 0; f < folds; f++) {
        for (q = 0; q < 6; q++) {
            all[q] += mom[6 * f + q];
        }
    }
    for (f = 0; f < folds; f++) {
        const double *m = mom + 6 * f;
        normal_t ne;
        double t[MAX_LIN] = {0.0, 0.0};
        double v;
        ne.g11 = all[0] - m[0];
        ne.g12 = all[1] - m[1];
        ne.g22 = all[2] - m[2];
        ne.b1 = all[3] - m[3];
        ne.b2 = all[4] - m[4];
        if (n_l > 0 && !nnls_solve(&ne, n_l > 1, hi, t)) {
            /* one scale at 0: the better of the two one-column optima */
            double t1[MAX_LIN] = {t[0], 0.0};
            double t2[MAX_LIN] = {0.0, t[1]};
            double v1 = sse_normal(&ne, all[5] - m[5], t1, all);
            double v2 = sse_normal(&ne, all[5] - m[5], t2, all);
            v = isnan(v1) || isnan(v2) ? NAN : fmin(v1, v2);
        } else {
            v = sse_normal(&ne, all[5] - m[5], t, all);
        }
        out[f * stride] = v;
    }
}

int bf__varpro_fold_grids(bf__fitctx *fc, const size_t *fold, size_t folds,
                          double **vals, size_t *n_points)
{
    const bf_problem *pb = fc->pb;
    bf_problem whole = *pb;
    size_t n_lin;
    unsigned lin = lin_of(pb, &n_lin);
    size_t points = grid_points(fc, lin);
    double hi[MAX_LIN] = {0.0, 0.0};
    double *mom;
    double *w;
    space_t sp;
    size_t g;
    size_t f;
    size_t j;
    *vals = NULL;
    *n_points = points;
    if (points == 0 || n_lin > MAX_LIN ||
        !bf_objective_keeps_scale(pb->objective)) {
        return BF_EINVAL;
    }
    *vals = malloc(folds * points * sizeof **vals);
    mom = malloc((6 * (folds + 1) + pb->n) * sizeof *mom);
    if (*vals == NULL || mom == NULL) {
        free(*vals);
        free(mom);
        *vals = NULL;
        return BF_ENOMEM;
    }
    w = mom + 6 * (folds + 1);
    for (j = 0, f = 0; j < pb->type->p; j++) { /* the scales' bounds */
        if ((lin >> j) & 1u) {
            hi[f++] = pb->hi[j];
        }
    }
    whole.objective = BF_OBJ_NGAN;
    whole.weight = NULL;
    bf__fitctx_use(fc, &whole);
    fc->lin_mask = lin;
    space_init(&sp, fc, pb->free_mask & ~lin);
    /* point by point: the model once (its columns), every fold's scales
     * and S from sums over the configurations (fold_values), summed
     * directly where they cancel (bf__varpro_value keeps the columns) */
    for (g = 0; g < points; g++) {
        double x[BF_MAX_PARAMS];
        point_of(&sp, g, x);
        if (value_at(fc, x) < UNDEFINED) {
            fold_values(fc, n_lin, hi, fold, folds, mom, *vals + g, points);
            for (f = 0; f < folds; f++) {
                bf_problem train = whole;
                size_t k;
                if (!isnan((*vals)[f * points + g])) {
                    continue;
                }
                for (k = 0; k < pb->n; k++) {
                    w[k] = fold[k] == f ? 0.0 : 1.0;
                }
                train.weight = w;
                bf__fitctx_use(fc, &train);
                (*vals)[f * points + g] = value_at(fc, x);
                bf__fitctx_use(fc, &whole);
            }
        } else {
            for (f = 0; f < folds; f++) {
                (*vals)[f * points + g] = UNDEFINED;
            }
        }
    }
    free(mom);
    bf__fitctx_use(fc, pb);
    fc->lin_mask = 0;
    return BF_OK;
}

static int varpro_fit_pre(bf__fitctx *fc, const double *pre,
                          bf_fit_result *grid, bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    bf_problem ngan;
    size_t n_lin;
    unsigned lin = lin_of(pb, &n_lin);
    size_t eval0 = fc->n_eval;
    size_t j;
    int rc;
    memset(result, 0, sizeof *result);
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        !bf_objective_keeps_scale(pb->objective)) {
        return BF_EINVAL;
    }
    if (n_lin > MAX_LIN ||
        (fc->blocks > 1 && (n_lin == 0 || pb->objective != BF_OBJ_NGAN))) {
        /* a joint fit solves each channel's scales by least squares */
        return BF_EINVAL;
    }
    ngan = *pb;
    ngan.objective = BF_OBJ_NGAN;
    bf__fitctx_use(fc, &ngan);
    /* dense data on a subsample; a joint fit's channels always whole
     * (the subsample holds one channel) */
    rc = pb->n > BF__DENSE_K && fc->blocks == 1
             ? varpro_dense(fc, lin, grid, result)
             : varpro_ngan(fc, lin, pre, grid, result);
    bf__fitctx_use(fc, pb);
    if (rc == BF_OK && pb->objective != BF_OBJ_NGAN) {
        /* SPEC §10's other objectives: every free parameter from there */
        space_t sp;
        double step[BF_MAX_PARAMS];
        double f;
        size_t a;
        space_init(&sp, fc, pb->free_mask);
        for (a = 0; a < sp.m; a++) {
            double x = result->param[sp.idx[a]];
            sp.lg[a] = sp.lg[a] && !pb->type->param[sp.idx[a]].linear;
            step[a] = sp.lg[a] ? 0.1 : 0.1 * (fabs(x) > 1e-3 ? fabs(x)
                                                              : 1e-3);
        }
        for (a = 0; a < sp.m; a++) { /* linear coordinates for the scales */
            if (!sp.lg[a]) {
                sp.zero_first[a] = 0.0;
                sp.lo[a] = pb->lo[sp.idx[a]];
            }
        }
        if (grid != NULL) {
            grid->lse = value_at(fc, grid->param);
        }
        rc = polish(&sp, result->param, step, &f);
        result->lse = f;
    }
    for (j = 0; j < pb->type->p; j++) {
        if (((pb->free_mask >> j) & 1u) &&
            (result->param[j] <= pb->lo[j] + BF_REFINE_TOL ||
             result->param[j] >= pb->hi[j] - BF_REFINE_TOL)) {
            result->bound_hit |= 1u << j;
        }
    }
    result->n_eval = fc->n_eval - eval0;
    if (rc == BF_OK && !(result->lse < UNDEFINED)) {
        rc = BF_EDOM;
    }
    return rc;
}
