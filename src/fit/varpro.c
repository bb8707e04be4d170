/* varpro.c: the fit of the specular models (SPEC §9.3) and the composites
 * D+S (SPEC §9.4) under the objectives that keep the scale (SPEC §10), as
 * separable least squares: the scales enter linearly, so for every value
 * of the other parameters they are solved exactly (variable projection;
 * varpro_scales.c), and this file searches the other parameters (the
 * cross-validation folds' grid values: varpro_folds.c).
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
 * [1e-3, 2], the exponents), then Levenberg-Marquardt (lmq.c: turning to
 * quasi-Newton steps near a large-residual minimum) from the grid's
 * best local minima in the same coordinates (ln x where the grid is
 * log-spaced), Nelder-Mead where it ends on a bound short of a KKT point,
 * the scales re-solved at every trial point; every trial point clamped
 * into the domain; a cross-validation fold's descents stop where they
 * join, within half a grid step, a minimum an earlier one reached. A
 * homogeneous lobe (LAFORTUNE, bf_param.homog; varpro_homog.c): the grid
 * and the descents from its minima with the lobe's size solved exactly,
 * then a descent over every parameter from where each ends. Dense
 * data: the grid and those descents on a regular
 * subsample, one descent on all (doc/methods.md). cuberoot, log1p: the
 * ngan solution starts Nelder-Mead over every free parameter, scales
 * included.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/lmq.h"
#include "fit/varpro.h"

/* A fold's descent merges into a known minimum within MERGE_NEAR of a
 * grid step of it on every axis (bf__vp_space.known_u): in the grid cell
 * around it, where the grid tells no two minima apart. */
#define MERGE_NEAR 0.5
#define NM_ITER 300
/* Nelder-Mead stops on a plateau: NM_FLAT (m + 1) trial values in a row
 * exactly equal (a lobe whose scale solves to 0 there: its other
 * parameters move nothing; or trial points all clamped into one corner of
 * the domain), where no vertex leads anywhere. */
#define NM_FLAT 10
#define NM_SIZE 1e-7
/* Under a stall stop (fitctx.stall: the profiles' inner fits, whose LM
 * then finishes to the criterion's tolerance from where Nelder-Mead
 * ends), Nelder-Mead's one job is to leave the bound: one pass, to
 * NM_SIZE_STALL. On the ten specular models' Cornell profiles a
 * 15 % cut of their evaluations, every interval end the same to 2e-8 of
 * its width. */
#define NM_SIZE_STALL 1e-4
/* The one-sided step of the bound test, a fraction of the span. */
#define KKT_STEP 1e-6
/* Levenberg-Marquardt's iterations and tolerances (xtol, gtol, ftol). */
#define LM_ITER 200
#define LM_TOL 1e-14
/* A fold's descents from the whole's minima (warm_descents) stop at an
 * iteration that lowers S by less than WARM_STALL of it (fitctx.stall):
 * S to twelve digits. Run to LM_TOL they crawl on for tens of iterations
 * below that (the finite-difference gradient's noise); on the ten
 * specular models x five Cornell files every fold's S stays within 1e-9
 * of the crawl's end, CV within 4.2e-7, at a sixth fewer of the folds'
 * model evaluations. */
#define WARM_STALL 1e-12

/* Grid points per parameter by the number of gridded parameters (log-
 * spaced, linear). */
static const size_t grid_log[] = {0, 200, 48, 24, 14, 8, 6, 5, 4};
static const size_t grid_lin[] = {0, 101, 7, 7, 6, 5, 4, 4, 3};

/* ==== coordinates, the grid ============================================== */

/* A domain [lo, hi] searched on a log scale: positive lo, a factor 50. */
static int log_scaled(double lo, double hi)
{
    return (lo > 0.0 && hi / lo >= 50.0) || (lo == 0.0 && hi >= 50.0);
}

void bf__vp_space_init(bf__vp_space *sp, bf__fitctx *fc, unsigned mask)
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
static double grid_x(const bf__vp_space *sp, size_t a, size_t i)
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
static double from_u(const bf__vp_space *sp, size_t a, double u)
{
    double x = sp->lg[a] ? exp(u) : u;
    double lo = sp->zero_first[a] != 0.0 ? 0.0 : sp->lo[a];
    if (sp->lg[a] && sp->zero_first[a] != 0.0 && x <= sp->lo[a]) {
        x = 0.0; /* below the log grid's first point: the bound 0 */
    }
    return x < lo ? lo : (x > sp->hi[a] ? sp->hi[a] : x);
}

static double to_u(const bf__vp_space *sp, size_t a, double x)
{
    if (!sp->lg[a]) {
        return x;
    }
    return log(x > sp->lo[a] ? x : sp->lo[a]);
}

/* The objective at x (full vector; the scales solved when the context
 * says so), BF__VP_UNDEFINED where not defined. */
double bf__vp_value_at(bf__fitctx *fc, const double *x)
{
    double v;
    if (bf__fit_value(fc, x, &v) != BF_OK || !isfinite(v)) {
        return BF__VP_UNDEFINED;
    }
    return v;
}

/* ==== Nelder-Mead in the search coordinates ============================== */

static double f_nm(const gsl_vector *u, void *arg)
{
    bf__vp_space *sp = arg;
    double x[BF_MAX_PARAMS];
    double v;
    size_t a;
    memcpy(x, sp->base, sizeof x);
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] = from_u(sp, a, gsl_vector_get(u, a));
    }
    v = bf__vp_grid_value(sp, x, NULL);
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
static int nelder_mead(bf__vp_space *sp, double *x, const double *step,
                       double *f)
{
    gsl_multimin_fminimizer *mn;
    gsl_multimin_function fn;
    gsl_vector *u;
    gsl_vector *ss;
    size_t a;
    size_t it;
    int status = GSL_CONTINUE;
    if (sp->m == 0) {
        *f = bf__vp_grid_value(sp, x, NULL);
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
        status = gsl_multimin_test_size(
            gsl_multimin_fminimizer_size(mn),
            sp->fc->stall > 0.0 ? NM_SIZE_STALL : NM_SIZE);
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

/* r_k = sqrt(w_k) (rho_hat_k - rho_k) at u, the scales solved (ngan);
 * nonzero where not defined. */
static int f_lm(const double *u, double *r, void *arg)
{
    const bf__vp_space *sp = arg;
    double x[BF_MAX_PARAMS];
    double v;
    size_t a;
    memcpy(x, sp->base, sizeof x);
    for (a = 0; a < sp->m; a++) {
        x[sp->idx[a]] = from_u(sp, a, u[a]);
    }
    v = bf__vp_grid_value(sp, x, NULL); /* fc->curve at x */
    if (!(v < BF__VP_UNDEFINED)) {
        return 1;
    }
    bf__vp_residuals(sp->fc, sp->sw, r);
    return 0;
}

/* 1 when the iterate u (cost c) lies within sp->near of a known minimum
 * whose value is no higher than c (bf__vp_space.known_u). */
static int joins_known(const double *u, double c, void *arg)
{
    const bf__vp_space *sp = arg;
    size_t e;
    for (e = 0; e < sp->n_known; e++) {
        size_t a;
        int in = c >= sp->known_f[e];
        for (a = 0; in && a < sp->m; a++) {
            /* the iterate's coordinate clamped into the domain */
            double ua = to_u(sp, a, from_u(sp, a, u[a]));
            in = fabs(ua - sp->known_u[e][a]) <= sp->near[a];
        }
        if (in) {
            return 1;
        }
    }
    return 0;
}

/* The least-squares workspace for n residuals and p parameters and n
 * doubles for the weights' square roots, kept in fc between runs; NULL
 * when out of memory. */
static bf__lmq *lm_workspace(bf__fitctx *fc, size_t n, size_t p)
{
    if (fc->lm == NULL || fc->lm_n != n || fc->lm_p != p) {
        bf__varpro_free(fc);
        fc->lm = bf__lmq_alloc(n, p);
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
    bf__lmq_free(fc->lm);
    free(fc->lm_sw);
    fc->lm = NULL;
    fc->lm_sw = NULL;
    fc->lm_n = 0;
    fc->lm_p = 0;
}

/* Levenberg-Marquardt with its quasi-Newton turn (lmq.c; LM_ITER
 * steps, tolerances LM_TOL, fitctx.stall; with sp->merge a stop,
 * sp->merged, at the first iterate that joins a known minimum) from x in
 * the search coordinates; x is replaced when it ends lower. *done (when
 * not NULL): 1 when the run met a tolerance or stopped as asked. */
static int levenberg(bf__vp_space *sp, double *x, double *f, int *done)
{
    bf__lmq *w;
    bf__lmq_opts o;
    double u[BF_MAX_PARAMS];
    double typ[BF_MAX_PARAMS];
    double y[BF_MAX_PARAMS];
    double *sw;
    double c;
    double fy;
    int st;
    size_t a;
    size_t n_res = sp->fc->pb->n * sp->fc->blocks;
    if (done != NULL) {
        *done = 0;
    }
    if (sp->m == 0 || n_res <= sp->m) {
        return BF_OK;
    }
    w = lm_workspace(sp->fc, n_res, sp->m);
    if (w == NULL) {
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
        u[a] = ua < lo + in ? lo + in : (ua > hi - in ? hi - in : ua);
        /* the finite differences' scale: ln x's unit, the domain */
        typ[a] = sp->lg[a] ? 1.0 : hi - lo;
    }
    memset(&o, 0, sizeof o);
    o.max_iter = LM_ITER;
    o.tol = LM_TOL;
    o.stall = sp->fc->stall;
    o.check = sp->merge ? joins_known : NULL;
    o.typ = typ;
    st = bf__lmq_run(w, u, &c, f_lm, sp, &o);
    if (st != BF__LMQ_UNDEFINED) {
        if (done != NULL) {
            *done = st == BF__LMQ_CONVERGED || st == BF__LMQ_JOINED;
        }
        sp->merged = st == BF__LMQ_JOINED;
        memcpy(y, x, sizeof y);
        for (a = 0; a < sp->m; a++) {
            y[sp->idx[a]] = from_u(sp, a, u[a]);
        }
        fy = bf__vp_grid_value(sp, y, NULL);
        if (fy < *f) {
            memcpy(x, y, sizeof y);
            *f = fy;
        }
    }
    sp->sw = NULL;
    return BF_OK;
}

/* Nelder-Mead twice (the second restarted at a tenth of the steps, so a
 * collapsed simplex does not stop it early; once under a stall stop,
 * NM_SIZE_STALL), keeping x when no better. */
static int polish(bf__vp_space *sp, double *x, const double *step, double *f)
{
    double s2[BF_MAX_PARAMS];
    double y[BF_MAX_PARAMS];
    double fy;
    size_t a;
    int pass;
    int passes = sp->fc->stall > 0.0 ? 1 : 2;
    int rc = BF_OK;
    *f = bf__vp_grid_value(sp, x, NULL);
    for (pass = 0; pass < passes && rc == BF_OK; pass++) {
        for (a = 0; a < sp->m; a++) {
            s2[a] = pass == 0 ? step[a] : 0.1 * step[a];
        }
        memcpy(y, x, sizeof y);
        rc = nelder_mead(sp, y, s2, &fy);
        fy = bf__vp_grid_value(sp, y, NULL); /* the clamped point's */
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
static void digits(const bf__vp_space *sp, size_t idx, size_t *d)
{
    size_t a = sp->m;
    while (a-- > 0) {
        d[a] = idx % sp->count[a];
        idx /= sp->count[a];
    }
}

static size_t index_of(const bf__vp_space *sp, const size_t *d)
{
    size_t idx = 0;
    size_t a;
    for (a = 0; a < sp->m; a++) {
        idx = idx * sp->count[a] + d[a];
    }
    return idx;
}

void bf__vp_point_of(const bf__vp_space *sp, size_t idx, double *x)
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
static int local_min(const bf__vp_space *sp, const double *vals, size_t idx)
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

/* The BF__VP_STARTS lowest local minima of the grid into best (n of them). */
static void pick_starts(const bf__vp_space *sp, const double *vals,
                        size_t points, cand_t *best, size_t *n)
{
    size_t g;
    *n = 0;
    for (g = 0; g < points; g++) {
        size_t q;
        if (!(vals[g] < BF__VP_UNDEFINED) || !local_min(sp, vals, g)) {
            continue;
        }
        if (*n == BF__VP_STARTS && !(vals[g] < best[BF__VP_STARTS - 1].f)) {
            continue;
        }
        q = *n < BF__VP_STARTS ? (*n)++ : BF__VP_STARTS - 1;
        while (q > 0 && best[q - 1].f > vals[g]) {
            best[q] = best[q - 1];
            q--;
        }
        best[q].f = vals[g];
        best[q].idx = g;
    }
}

/* The scales of x solved at x's other values (fc->lin_mask); the value
 * there (bf__vp_value_at: the scales' own values do not enter it). */
static double fill_scales(bf__fitctx *fc, double *x)
{
    size_t j;
    double v = bf__vp_value_at(fc, x);
    for (j = 0; j < fc->pb->type->p; j++) {
        if ((fc->lin_mask >> j) & 1u) {
            x[j] = fc->lin[j];
        }
    }
    return v;
}

/* The steps of Nelder-Mead: one grid step (search coordinates). */
static void grid_steps(const bf__vp_space *sp, double *step)
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
static int bound_side(const bf__vp_space *sp, const double *x, size_t a)
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
static int on_bound(const bf__vp_space *sp, const double *x)
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
static int bound_kkt(const bf__vp_space *sp, const double *x, double f)
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
        if (bf__vp_grid_value(sp, y, NULL) < f) {
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
static int descend(bf__vp_space *sp, const double *step, double *x, double *f)
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

/* The start of grid point idx of gs in x: the point, or where it stands
 * for (bf__vp_grid_value). */
static void start_of(const bf__vp_space *gs, size_t idx, double *x)
{
    double g[BF_MAX_PARAMS];
    bf__vp_point_of(gs, idx, g);
    if (!gs->hg || !(bf__vp_grid_value(gs, g, x) < BF__VP_UNDEFINED)) {
        memcpy(x, g, sizeof g);
    }
}

/* Adds x (value f; not merged) to the minima a fold's descents join. */
static void add_known(bf__vp_space *sp, const double *x, double f)
{
    size_t a;
    if (!sp->merge || sp->merged || sp->n_known == BF__VP_STARTS) {
        return;
    }
    for (a = 0; a < sp->m; a++) {
        sp->known_u[sp->n_known][a] = to_u(sp, a, x[sp->idx[a]]);
    }
    sp->known_f[sp->n_known++] = f;
}

/* Adds x to rec (not NULL) unless one of its minima lies within
 * MERGE_NEAR of a grid step of it (sp's coordinates, steps step) on every
 * axis: the same minimum. */
static void add_minimum(bf__vp_minima *rec, const bf__vp_space *sp,
                        const double *step, const double *x)
{
    size_t e;
    size_t a;
    if (rec == NULL || rec->n == BF__VP_MINIMA) {
        return;
    }
    for (e = 0; e < rec->n; e++) {
        int same = 1;
        for (a = 0; same && a < sp->m; a++) {
            double d = to_u(sp, a, x[sp->idx[a]]) -
                       to_u(sp, a, rec->x[e][sp->idx[a]]);
            same = fabs(d) <= MERGE_NEAR * step[a];
        }
        if (same) {
            return;
        }
    }
    memcpy(rec->x[rec->n++], x, sizeof rec->x[0]);
}

/* A fold's descents from the whole data's minima warm (doc/methods.md
 * §1, §5): Levenberg-Marquardt alone from each (its free values; the
 * fold's minimum mostly lies a small step away, and where the whole's
 * needed Nelder-Mead to leave a bound it started there), each stopped
 * once an iteration gains less than WARM_STALL. The lowest into xbest,
 * *fbest. Their ends are not known minima that the fold's descent from
 * its grid merges into: where the held-out configurations carry much of
 * S (a gloss peak), the fold's surface differs, and such an end is where
 * LM stopped, not a basin's minimum (cayman, LAMBERT+GGX: a fold's
 * descent from its grid that merged into one ended at S 13.95; on its
 * own, at 9.95). */
static int warm_descents(bf__fitctx *fc, bf__vp_space *sp,
                         const bf__vp_minima *warm, double *xbest,
                         double *fbest)
{
    double stall = fc->stall;
    size_t e;
    size_t a;
    int rc = BF_OK;
    for (e = 0; e < warm->n && rc == BF_OK; e++) {
        double x[BF_MAX_PARAMS];
        double f;
        memcpy(x, fc->pb->fixed, sizeof x);
        for (a = 0; a < sp->m; a++) {
            x[sp->idx[a]] = warm->x[e][sp->idx[a]];
        }
        f = bf__vp_value_at(fc, x);
        if (!(f < BF__VP_UNDEFINED)) {
            continue;
        }
        fc->stall = WARM_STALL;
        rc = levenberg(sp, x, &f, NULL);
        fc->stall = stall;
        if (rc == BF_OK && f < *fbest) {
            *fbest = f;
            memcpy(xbest, x, sizeof x);
        }
    }
    return rc;
}

/* The separable ngan fit on fc (fc->pb's objective ngan); pre (NULL:
 * computed here) the grid's values, as bf__varpro_fold_grids gives them:
 * a fold's fit, whose descents merge into the minima the earlier ones
 * reached (bf__vp_space.known_u), and with warm (not NULL, not empty) the
 * whole data's minima: their descents (warm_descents), then one from the
 * grid's lowest minimum. whole (not NULL) gets the distinct minima of the
 * descents and, with its folds set (and pre NULL), every fold's values
 * at the grid's points from the same pass (bf__vp_foldpass). */
static int varpro_ngan(bf__fitctx *fc, unsigned lin, const double *pre,
                       const bf__vp_minima *warm, bf__vp_whole *whole,
                       bf_fit_result *grid, bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    bf__vp_space sp;
    bf__vp_space gs;
    double *vals;
    size_t points = 1;
    cand_t best[BF__VP_STARTS];
    size_t n_best;
    size_t g;
    size_t a;
    double step[BF_MAX_PARAMS];
    double gstep[BF_MAX_PARAMS];
    double xbest[BF_MAX_PARAMS];
    double fgrid;
    double fbest = BF__VP_UNDEFINED;
    bf__vp_minima *rec = whole != NULL ? &whole->minima : NULL;
    bf__vp_foldpass fp;
    int pass = 0;
    int rc = BF_OK;
    fc->lin_mask = lin;
    bf__vp_space_init(&sp, fc, pb->free_mask & ~lin);
    bf__vp_grid_init(&gs, fc, pb->free_mask & ~lin);
    for (a = 0; a < gs.m; a++) {
        points *= gs.count[a];
    }
    if (pre == NULL && whole != NULL && whole->fold != NULL) {
        rc = bf__vp_foldpass_init(&fp, fc, whole->fold, whole->folds);
        if (rc == BF_ENOMEM) {
            fc->lin_mask = 0;
            return rc;
        }
        pass = rc == BF_OK && fp.points == points;
        if (rc == BF_OK && !pass) {
            bf__vp_foldpass_free(&fp);
        }
        rc = BF_OK;
    }
    vals = malloc(points * sizeof *vals);
    if (vals == NULL) {
        if (pass) {
            bf__vp_foldpass_free(&fp);
        }
        fc->lin_mask = 0;
        return BF_ENOMEM;
    }
    for (g = 0; g < points; g++) {
        double x[BF_MAX_PARAMS];
        if (pre != NULL) {
            vals[g] = pre[g];
            continue;
        }
        bf__vp_point_of(&gs, g, x);
        vals[g] = bf__vp_grid_value(&gs, x, NULL);
        if (pass) { /* the folds' values from the same columns */
            bf__vp_foldpass_point(&fp, fc, &gs, g, x,
                                  vals[g] < BF__VP_UNDEFINED);
        }
    }
    if (pass) {
        whole->vals = fp.vals;
        whole->points = points;
        fp.vals = NULL;
        bf__vp_foldpass_free(&fp);
    }
    pick_starts(&gs, vals, points, best, &n_best);
    free(vals);
    if (n_best == 0) {
        fc->lin_mask = 0;
        return BF_EDOM;
    }
    start_of(&gs, best[0].idx, xbest);
    fgrid = fill_scales(fc, xbest);
    if (grid != NULL) {
        memset(grid, 0, sizeof *grid);
        memcpy(grid->param, xbest, sizeof xbest);
        /* a homogeneous lobe's point clamped into its domain: its value */
        grid->lse = gs.hg ? fgrid : best[0].f;
        grid->n_eval = points;
    }
    grid_steps(&sp, step);
    grid_steps(&gs, gstep);
    /* a fold's descents merge in the grid's coordinates (gs: sp's own
     * without a homogeneous lobe) */
    gs.merge = pre != NULL;
    for (a = 0; a < gs.m; a++) {
        gs.near[a] = MERGE_NEAR * gstep[a];
    }
    if (rec != NULL) {
        rec->n = 0;
    }
    if (pre != NULL && warm != NULL && warm->n > 0) {
        rc = warm_descents(fc, &sp, warm, xbest, &fbest);
        n_best = 1;
    }
    for (g = 0; g < n_best && rc == BF_OK; g++) {
        double x[BF_MAX_PARAMS];
        double y[BF_MAX_PARAMS];
        double f;
        bf__vp_point_of(&gs, best[g].idx, x);
        if (gs.hg) {
            /* a homogeneous lobe: descends with its size solved exactly
             * (the stiff direction of Cxy, Cz taken out), then, where
             * what that stands for is not inside the domain, over every
             * parameter from there (bf__vp_grid_inside) */
            int inside;
            f = bf__vp_grid_value(&gs, x, NULL);
            rc = descend(&gs, gstep, x, &f);
            if (rc == BF_OK && !gs.merged) {
                add_known(&gs, x, f);
            }
            if (rc != BF_OK || gs.merged ||
                !(bf__vp_grid_value(&gs, x, y) < BF__VP_UNDEFINED)) {
                continue;
            }
            inside = bf__vp_grid_inside(&gs, x, y);
            memcpy(x, y, sizeof x);
            f = bf__vp_value_at(fc, x);
            if (!inside) {
                rc = descend(&sp, step, x, &f);
            }
        } else {
            f = bf__vp_value_at(fc, x);
            rc = descend(&gs, gstep, x, &f);
            if (rc == BF_OK) {
                add_known(&gs, x, f);
            }
        }
        if (rc == BF_OK) {
            add_minimum(rec, &sp, step, x);
        }
        if (rc == BF_OK && f < fbest) {
            fbest = f;
            memcpy(xbest, x, sizeof x);
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
    bf__vp_space sp;
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
    bf__vp_space_init(&sp, fc, pb->free_mask & ~lin);
    memcpy(x, pb->fixed, sizeof x);
    for (j = 0; j < sp.m; j++) { /* the free values from start */
        x[sp.idx[j]] = start[sp.idx[j]];
    }
    f = bf__vp_value_at(fc, x);
    grid_steps(&sp, step);
    rc = f < BF__VP_UNDEFINED ? descend(&sp, step, x, &f) : BF_EDOM;
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
        n_lin > BF__VP_MAX_LIN || n_lin == 0) {
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
                rc = varpro_ngan(&sfc, lin, NULL, NULL, NULL, grid,
                                 result);
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
    bf__vp_space sp;
    double step[BF_MAX_PARAMS];
    double x[BF_MAX_PARAMS];
    double f;
    int rc = ngan_subsample(fc, lin, grid, result);
    if (rc != BF_OK) {
        return rc;
    }
    fc->lin_mask = lin;
    bf__vp_space_init(&sp, fc, fc->pb->free_mask & ~lin);
    grid_steps(&sp, step);
    if (grid != NULL) {
        grid->lse = fill_scales(fc, grid->param);
    }
    memcpy(x, result->param, sizeof x);
    f = bf__vp_value_at(fc, x);
    rc = descend(&sp, step, x, &f);
    fill_scales(fc, x);
    memcpy(result->param, x, sizeof x);
    result->lse = f;
    fc->lin_mask = 0;
    return rc;
}

/* bf__varpro_fit with the grid's ngan values pre (NULL: computed), a
 * fold's warm starts warm, what the folds take into whole (varpro_ngan). */
static int varpro_fit_pre(bf__fitctx *fc, const double *pre,
                          const bf__vp_minima *warm, bf__vp_whole *whole,
                          bf_fit_result *grid, bf_fit_result *result);

int bf__varpro_fit(bf__fitctx *fc, bf_fit_result *grid,
                   bf_fit_result *result, bf__vp_whole *whole)
{
    return varpro_fit_pre(fc, NULL, NULL, whole, grid, result);
}

void bf__vp_whole_free(bf__vp_whole *wh)
{
    if (wh != NULL) {
        free(wh->vals);
        wh->vals = NULL;
        wh->points = 0;
    }
}

int bf__varpro_fit_grid(bf__fitctx *fc, const double *vals,
                        const bf__vp_minima *warm, bf_fit_result *result)
{
    return varpro_fit_pre(fc, vals, warm, NULL, NULL, result);
}

static int varpro_fit_pre(bf__fitctx *fc, const double *pre,
                          const bf__vp_minima *warm, bf__vp_whole *whole,
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
    if (whole != NULL) { /* dense data, a joint fit: none */
        whole->minima.n = 0;
        whole->vals = NULL;
        whole->points = 0;
    }
    if (pb->type->kind != BF_MODEL_SPECULAR || fc->cols == NULL ||
        !bf_objective_keeps_scale(pb->objective)) {
        return BF_EINVAL;
    }
    if (n_lin > BF__VP_MAX_LIN ||
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
             : varpro_ngan(fc, lin, pre, warm, whole, grid, result);
    bf__fitctx_use(fc, pb);
    if (rc == BF_OK && pb->objective != BF_OBJ_NGAN) {
        /* SPEC §10's other objectives: every free parameter from there */
        bf__vp_space sp;
        double step[BF_MAX_PARAMS];
        double f;
        size_t a;
        bf__vp_space_init(&sp, fc, pb->free_mask);
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
            grid->lse = bf__vp_value_at(fc, grid->param);
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
    if (rc == BF_OK && !(result->lse < BF__VP_UNDEFINED)) {
        rc = BF_EDOM;
    }
    return rc;
}
