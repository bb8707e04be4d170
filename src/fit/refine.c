/* refine.c: exact optima -- GSL minimisers started from the grid optimum
 * (doc/methods.md §2).
 *
 * [1] GSL manual, "One Dimensional Minimization" (Brent's method,
 *     gsl_min_fminimizer_brent) and "Multidimensional Minimization"
 *     (Nelder-Mead simplex, gsl_multimin_fminimizer_nmsimplex2).
 * [2] R. P. Brent, "Algorithms for Minimization without Derivatives", 1973.
 *
 * One free parameter: Brent on a bracket [a, b] around the best of a few
 * sampled points, to an interval narrower than BF_REFINE_TOL. Two or more:
 * Nelder-Mead on u in R^p with x_j = a_j + (b_j - a_j)(1 + sin u_j)/2, so
 * every trial point lies in the box [a, b] and the model's domain (the
 * box lies inside [lo, hi], which lies inside [min, max]); it stops when
 * the simplex is smaller than BF_REFINE_TOL in parameter units.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_multimin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Objective value given to GSL where the model is undefined: such points
 * are never minima (GSL rejects non-finite function values). */
#define UNDEFINED_VALUE 1e300
/* Points sampled over the whole range before Brent (bf_fit_minimise). */
#define SCAN_POINTS 17
/* Points sampled over the inner box of a nested search: the objective's
 * max-normalisation (SPEC §2) puts kinks in it, where the brightest
 * configuration changes, and so local minima a grid step apart; these
 * samples pick the lowest basin before Brent, at the cost of cheap
 * evaluations. */
#define NEST_SAMPLES 9
/* A refined parameter this close to an inner edge of its box is on it. */
#define EDGE_TOL (10.0 * BF_REFINE_TOL)
/* Initial simplex step in the mapped coordinates u (radians). */
#define SIMPLEX_STEP 0.5
/* A parameter is flat where moving it across its whole box changes S by
 * less than this, relative: rounding of S is near 1e-16 relative, while
 * the weakest dependence a fit resolves (ON's rho at sigma = 1e-3: 1e-6
 * relative) is far above. */
#define FLAT_REL 1e-13

/* The state shared with the GSL callbacks. */
typedef struct {
    const bf_problem *pb;
    bf__fitctx *fc;              /* the engine, pointed at pb */
    double param[BF_MAX_PARAMS]; /* current full parameter vector */
    size_t free[BF_MAX_PARAMS];  /* indices of the moving parameters */
    size_t n_free;
    double a[BF_MAX_PARAMS];     /* box of each moving parameter */
    double b[BF_MAX_PARAMS];
    size_t n_eval;
} ctx_t;

/* Objective at the current parameter vector. */
static double value_at(ctx_t *c)
{
    double v;
    c->n_eval++;
    if (bf__fit_value(c->fc, c->param, &v) != BF_OK || !isfinite(v)) {
        return UNDEFINED_VALUE;
    }
    return v;
}

/* ==== one free parameter: Brent ========================================== */

/* One parameter of the context moving: the function Brent minimises. */
typedef struct {
    ctx_t *c;
    size_t j; /* the parameter's index */
} axis_t;

static double f_axis(double x, void *arg)
{
    axis_t *ax = arg;
    ax->c->param[ax->j] = x;
    return value_at(ax->c);
}

/* Brent on [lo, hi] from mid (f(mid) < f(lo), f(hi)) for fn. Sets *x to
 * the minimiser. */
static int brent(gsl_function *fn, double lo, double mid, double hi,
                 double f_lo, double f_mid, double f_hi, double *x)
{
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    int status;
    size_t iter = 0;
    if (s == NULL) {
        return BF_ENOMEM;
    }
    status = gsl_min_fminimizer_set_with_values(s, fn, mid, f_mid, lo, f_lo,
                                                hi, f_hi);
    while (status == GSL_SUCCESS && iter++ < BF_REFINE_MAXITER) {
        status = gsl_min_fminimizer_iterate(s);
        if (status != GSL_SUCCESS) {
            break;
        }
        status = gsl_min_test_interval(gsl_min_fminimizer_x_lower(s),
                                       gsl_min_fminimizer_x_upper(s),
                                       BF_REFINE_TOL, 0.0);
        if (status == GSL_SUCCESS) {
            break;
        }
        status = GSL_SUCCESS; /* GSL_CONTINUE: iterate on */
    }
    *x = gsl_min_fminimizer_x_minimum(s);
    gsl_min_fminimizer_free(s);
    if (status != GSL_SUCCESS) {
        return iter > BF_REFINE_MAXITER ? BF_ENOCONV : BF_EDOM;
    }
    return BF_OK;
}

/* Minimises fn from the sorted samples xs[0..m) (which include the box
 * ends). */
static int minimise_1d(gsl_function *fn, const double *xs, size_t m,
                       double *x)
{
    double fs[SCAN_POINTS + 2];
    size_t i;
    size_t best = 0;
    for (i = 0; i < m; i++) {
        fs[i] = fn->function(xs[i], fn->params);
        if (fs[i] < fs[best]) {
            best = i;
        }
    }
    if (best > 0 && best + 1 < m) {
        if (fs[best] < fs[best - 1] && fs[best] < fs[best + 1]) {
            return brent(fn, xs[best - 1], xs[best], xs[best + 1],
                         fs[best - 1], fs[best], fs[best + 1], x);
        }
        *x = xs[best]; /* flat: ties with a neighbour */
        return BF_OK;
    }
    {
        /* the best sample is an end of the box: a minimum on the bound,
         * or one between the end and its neighbour */
        size_t nb = best == 0 ? 1 : m - 2;
        double end = xs[best];
        double delta = (xs[nb] - end) * 1e-3;
        double probe = end + delta;
        double f_probe = fn->function(probe, fn->params);
        if (!(f_probe < fs[best]) || !(f_probe < fs[nb])) {
            *x = end; /* minimum on the bound of the box */
            return BF_OK;
        }
        if (best == 0) {
            return brent(fn, end, probe, xs[nb], fs[best], f_probe, fs[nb], x);
        }
        return brent(fn, xs[nb], probe, end, fs[nb], f_probe, fs[best], x);
    }
}

/* The samples of a box [lo, hi] for minimise_1d: scan points, or its ends
 * with the start between them. Returns their number. */
static size_t box_samples(double lo, double hi, double start, size_t pts,
                          double *xs)
{
    size_t m = 0;
    size_t i;
    for (i = 0; i < pts; i++) {
        double xi = lo + (hi - lo) * (double)i / (double)(pts - 1);
        if (m > 0 && xs[m - 1] < start && start < xi) {
            xs[m++] = start;
        }
        xs[m++] = i + 1 == pts ? hi : xi;
    }
    return m;
}

/* ==== two, one cheap given the other: nested Brent ======================== */

/* The outer function of the nested search: at outer value x, the minimum
 * over the inner parameter (Brent from the last inner minimiser). */
typedef struct {
    ctx_t *c;
    size_t o, i;   /* parameter indices: outer, inner */
    double ai, bi; /* the inner box */
    double xi;     /* the last inner minimiser */
    int status;
} nest_t;

static double f_outer(double x, void *arg)
{
    nest_t *t = arg;
    axis_t inner = {t->c, t->i};
    gsl_function fn = {f_axis, &inner};
    double xs[NEST_SAMPLES + 2];
    double xin;
    size_t m;
    int rc;
    t->c->param[t->o] = x;
    m = box_samples(t->ai, t->bi, t->xi, NEST_SAMPLES, xs);
    rc = minimise_1d(&fn, xs, m, &xin);
    if (rc != BF_OK && t->status == BF_OK) {
        t->status = rc;
    }
    t->xi = xin;
    return f_axis(xin, &inner);
}

/* Minimises over the two moving parameters, the cheap one (kernel's
 * cheap) inside: the outer Brent calls the expensive model terms once per
 * value (FC's Fresnel factor, WNO-R's ring sums), every inner step only the
 * cheap rest. Same box, same tolerances as the simplex. */
static int minimise_nested(ctx_t *c, const double *x0, size_t cheap)
{
    size_t slot_i = c->free[0] == cheap ? 0 : 1;
    size_t slot_o = 1 - slot_i;
    nest_t t = {c, c->free[slot_o], c->free[slot_i], c->a[slot_i],
                c->b[slot_i], x0[cheap], BF_OK};
    gsl_function fn = {f_outer, &t};
    double xs[3];
    double xo;
    size_t m = box_samples(c->a[slot_o], c->b[slot_o], x0[t.o], 2, xs);
    int rc = minimise_1d(&fn, xs, m, &xo);
    (void)f_outer(xo, &t); /* the minimiser's inner parameter */
    return rc != BF_OK ? rc : t.status;
}

/* ==== two or more: Nelder-Mead on the sine-mapped box ===================== */

static void unmap(const ctx_t *c, const gsl_vector *u, double *param)
{
    size_t i;
    for (i = 0; i < c->n_free; i++) {
        size_t j = c->free[i];
        double t = 0.5 * (1.0 + sin(gsl_vector_get(u, i)));
        param[j] = c->a[i] + (c->b[i] - c->a[i]) * t;
    }
}

static double f_nd(const gsl_vector *u, void *arg)
{
    ctx_t *c = arg;
    unmap(c, u, c->param);
    return value_at(c);
}

static int minimise_nd(ctx_t *c, const double *x0)
{
    const gsl_multimin_fminimizer_type *T =
        gsl_multimin_fminimizer_nmsimplex2;
    gsl_multimin_fminimizer *s = NULL;
    gsl_vector *u = gsl_vector_alloc(c->n_free);
    gsl_vector *step = gsl_vector_alloc(c->n_free);
    gsl_multimin_function fn;
    double half = 0.0;
    size_t i;
    size_t iter = 0;
    int status;
    int rc = BF_OK;

    s = gsl_multimin_fminimizer_alloc(T, c->n_free);
    if (u == NULL || step == NULL || s == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    for (i = 0; i < c->n_free; i++) {
        double w = c->b[i] - c->a[i];
        double t = 2.0 * (x0[c->free[i]] - c->a[i]) / w - 1.0;
        t = t < -1.0 ? -1.0 : (t > 1.0 ? 1.0 : t);
        gsl_vector_set(u, i, asin(t));
        gsl_vector_set(step, i, SIMPLEX_STEP);
        if (0.5 * w > half) {
            half = 0.5 * w;
        }
    }
    fn.n = c->n_free;
    fn.f = f_nd;
    fn.params = c;
    status = gsl_multimin_fminimizer_set(s, &fn, u, step);
    while (status == GSL_SUCCESS && iter++ < BF_REFINE_MAXITER) {
        status = gsl_multimin_fminimizer_iterate(s);
        if (status != GSL_SUCCESS) {
            break;
        }
        /* |dx| <= half-width * |du|: the simplex is below the tolerance
         * in parameter units */
        status = gsl_multimin_test_size(gsl_multimin_fminimizer_size(s),
                                        BF_REFINE_TOL / half);
        if (status == GSL_SUCCESS) {
            break;
        }
        status = GSL_SUCCESS;
    }
    unmap(c, gsl_multimin_fminimizer_x(s), c->param);
    if (status != GSL_SUCCESS) {
        rc = iter > BF_REFINE_MAXITER ? BF_ENOCONV : BF_EDOM;
    }
done:
    gsl_multimin_fminimizer_free(s);
    gsl_vector_free(u);
    gsl_vector_free(step);
    return rc;
}

/* ==== flat directions ===================================================== */

/* Drops from the moving set every parameter on which the objective does
 * not depend at the start: S at both ends of its box equals S at the start
 * to FLAT_REL (ON's rho at sigma = 0, where the model is LAMBERT whatever
 * rho is; the simplex cannot converge along such a line). The parameter
 * keeps its start value. Two evaluations per moving parameter; returns the
 * bits (parameter indices) of the ones dropped. */
static unsigned hold_flat(ctx_t *c, double f0)
{
    unsigned flat = 0;
    size_t i;
    size_t kept = 0;
    if (!(f0 < UNDEFINED_VALUE)) {
        return 0;
    }
    for (i = 0; i < c->n_free; i++) {
        size_t j = c->free[i];
        double x = c->param[j];
        double fa;
        double fb;
        c->param[j] = c->a[i];
        fa = value_at(c);
        c->param[j] = c->b[i];
        fb = value_at(c);
        c->param[j] = x;
        if (fabs(fa - f0) <= FLAT_REL * f0 && fabs(fb - f0) <= FLAT_REL * f0) {
            flat |= 1u << j;
            continue;
        }
        c->free[kept] = j;
        c->a[kept] = c->a[i];
        c->b[kept] = c->b[i];
        kept++;
    }
    c->n_free = kept;
    return flat;
}

/* ==== drivers ============================================================= */

/* Minimises over c's moving parameters from x0 (in the box): Brent for
 * one (after SCAN_POINTS samples of the box when scan, else its ends and
 * x0), the mapped simplex for more, nothing for none. Leaves the minimiser
 * in c->param. */
static int search(ctx_t *c, const double *x0, int scan)
{
    int rc = BF_OK;
    int cheap = c->fc->pm->kr->cheap;
    if (c->n_free == 1) {
        axis_t ax = {c, c->free[0]};
        gsl_function fn = {f_axis, &ax};
        double xs[SCAN_POINTS + 2];
        double x;
        size_t m = box_samples(c->a[0], c->b[0], x0[c->free[0]],
                               scan ? SCAN_POINTS : 2, xs);
        rc = minimise_1d(&fn, xs, m, &x);
        c->param[c->free[0]] = x;
    } else if (c->n_free == 2 && cheap >= 0 && !scan &&
               (c->free[0] == (size_t)cheap || c->free[1] == (size_t)cheap)) {
        rc = minimise_nested(c, x0, (size_t)cheap);
    } else if (c->n_free > 1) {
        rc = minimise_nd(c, x0);
    }
    return rc;
}

/* Minimises pb from x0 over the box [a, b] of its free parameters. scan:
 * sample the 1-D box at SCAN_POINTS points first (else only a, x0, b). */
static int minimise_box(bf__fitctx *fc, const double *x0, const double *a,
                        const double *b, int scan, bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    ctx_t c;
    ctx_t whole; /* the moving set before hold_flat */
    double f0;
    double f1;
    int rc = BF_OK;
    size_t j;

    memset(&c, 0, sizeof c);
    memset(result, 0, sizeof *result);
    c.pb = pb;
    c.fc = fc;
    memcpy(c.param, pb->fixed, sizeof c.param);
    for (j = 0; j < pb->type->p; j++) {
        if ((pb->free_mask >> j) & 1u) {
            if (!(x0[j] >= a[j] && x0[j] <= b[j])) {
                rc = BF_EINVAL;
                goto done;
            }
            c.param[j] = x0[j];
            if (b[j] > a[j]) {
                c.a[c.n_free] = a[j];
                c.b[c.n_free] = b[j];
                c.free[c.n_free++] = j;
            }
        }
    }
    f0 = value_at(&c);
    memcpy(result->param, c.param, sizeof c.param);
    whole = c;
    if (c.n_free > 1) {
        result->flat = hold_flat(&c, f0);
    }
    rc = search(&c, x0, scan);
    f1 = value_at(&c);
    if (result->flat != 0 && f1 < f0) {
        /* moved off the start: a held parameter may matter here */
        double x1[BF_MAX_PARAMS];
        unsigned flat;
        memcpy(x1, c.param, sizeof x1);
        memcpy(c.free, whole.free, sizeof c.free);
        memcpy(c.a, whole.a, sizeof c.a);
        memcpy(c.b, whole.b, sizeof c.b);
        c.n_free = whole.n_free;
        flat = hold_flat(&c, f1);
        if (flat != result->flat) {
            result->flat = flat;
            rc = search(&c, x1, 0);
            f1 = value_at(&c);
        }
    }
    if (f1 <= f0) { /* keep the better of start and minimiser */
        memcpy(result->param, c.param, sizeof c.param);
        result->lse = f1;
    } else {
        result->lse = f0;
    }
    if (result->lse >= UNDEFINED_VALUE) {
        rc = BF_EDOM;
    }
    for (j = 0; j < pb->type->p; j++) {
        if (((pb->free_mask >> j) & 1u) &&
            (result->param[j] <= pb->lo[j] + BF_REFINE_TOL ||
             result->param[j] >= pb->hi[j] - BF_REFINE_TOL)) {
            result->bound_hit |= 1u << j;
        }
    }
    result->n_eval = c.n_eval;
done:
    return rc;
}

/* Checks pb's search ranges against the model's domain. */
static int check_problem(const bf_problem *pb)
{
    size_t j;
    if (pb == NULL || pb->type == NULL || pb->data == NULL ||
        pb->geom == NULL || pb->n == 0 || pb->type->p > BF_MAX_PARAMS) {
        return BF_EINVAL;
    }
    for (j = 0; j < pb->type->p; j++) {
        const bf_param *pj = &pb->type->param[j];
        if (((pb->free_mask >> j) & 1u) &&
            !(pb->lo[j] >= pj->min && pb->hi[j] <= pj->max &&
              pb->lo[j] <= pb->hi[j])) {
            return BF_EINVAL;
        }
    }
    return BF_OK;
}

/* 1 when a free parameter of r ends on an edge of the box [a, b] that is
 * not a bound of pb's search range: the minimum lies beyond the box. */
static int on_inner_edge(const bf_problem *pb, const bf_fit_result *r,
                         const double *a, const double *b)
{
    size_t j;
    for (j = 0; j < pb->type->p; j++) {
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        if ((a[j] > pb->lo[j] && r->param[j] <= a[j] + EDGE_TOL) ||
            (b[j] < pb->hi[j] && r->param[j] >= b[j] - EDGE_TOL)) {
            return 1;
        }
    }
    return 0;
}

int bf__refine(bf__fitctx *fc, const bf_fit_result *start,
               bf_fit_result *result)
{
    const bf_problem *pb = fc->pb;
    double a[BF_MAX_PARAMS] = {0};
    double b[BF_MAX_PARAMS] = {0};
    bf_fit_result from;
    size_t n_eval = 0;
    size_t walk;
    size_t j;
    int rc = BF_OK;
    from = *start;
    for (walk = 0; walk <= BF_REFINE_WALKS; walk++) {
        for (j = 0; j < pb->type->p; j++) {
            const bf_param *pj = &pb->type->param[j];
            double step =
                pj->grid_n > 0 ? pj->grid_step : pb->hi[j] - pb->lo[j];
            double x = from.param[j];
            a[j] = x - step > pb->lo[j] ? x - step : pb->lo[j];
            b[j] = x + step < pb->hi[j] ? x + step : pb->hi[j];
        }
        rc = minimise_box(fc, from.param, a, b, 0, result);
        n_eval += result->n_eval;
        if ((rc != BF_OK && rc != BF_ENOCONV) || !on_inner_edge(pb, result, a, b)
            || !(result->lse < from.lse)) {
            break; /* interior minimum, a failure, or no progress */
        }
        from = *result; /* the minimum lies beyond the box: move it */
    }
    result->n_eval = n_eval;
    return rc;
}

int bf__grid_refine(bf__fitctx *fc, const bf__grid *gr,
                    bf_fit_result *result)
{
    const double *w[1] = {NULL};
    bf_fit_result g;
    int rc = bf__grid_optima(gr, fc->pb, fc->pm->cs->cti, 1, w, &g);
    if (rc != BF_OK) {
        return rc;
    }
    return isfinite(g.lse) ? bf__refine(fc, &g, result) : BF_EDOM;
}

int bf__minimise(bf__fitctx *fc, const double *start, bf_fit_result *result)
{
    return minimise_box(fc, start, fc->pb->lo, fc->pb->hi, 1, result);
}

/* The public entry points: pb checked, then its own engine for the call.
 * start: the start as a fit result (refine) or NULL (minimise from x0). */
static int solo_fit(const bf_problem *pb, const bf_fit_result *start,
                    const double *x0, bf_fit_result *result)
{
    bf__solo so;
    int rc = check_problem(pb);
    if (rc != BF_OK || (start == NULL && x0 == NULL) || result == NULL) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = start != NULL ? bf__refine(&so.fc, start, result)
                       : bf__minimise(&so.fc, x0, result);
    bf__solo_free(&so);
    return rc;
}

int bf_fit_refine(const bf_problem *pb, const bf_fit_result *start,
                  bf_fit_result *result)
{
    return start != NULL ? solo_fit(pb, start, NULL, result) : BF_EINVAL;
}

int bf_fit_minimise(const bf_problem *pb, const double *start,
                    bf_fit_result *result)
{
    return start != NULL ? solo_fit(pb, NULL, start, result) : BF_EINVAL;
}
