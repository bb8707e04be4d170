/* profile.c: profile-likelihood intervals for fitted parameters
 * (doc/methods.md §3), with inner fits as thorough as the fit itself.
 *
 * [1] Y. Pawitan, "In All Likelihood", OUP 2001, §2.6 and §9.2 (profile
 *     likelihood intervals; Wilks' theorem).
 * [2] GSL manual, "One Dimensional Root-Finding" (Brent-Dekker,
 *     gsl_root_fsolver_brent).
 * [3] GSL manual, "One Dimensional Minimization" (Brent,
 *     gsl_min_fminimizer_brent).
 *
 * Equations (Gaussian errors of unknown variance, n configurations):
 *   -2 ln Lambda(theta_j) = n ln(S_p(theta_j) / S_min)       [1] §9.2
 *   interval: { theta_j : n ln(S_p / S_min) <= chi2_1(level) }  (3.841 at
 *   95%), S_p(theta_j) = min over the other free parameters of S.
 *
 * The inner fit S_p(theta): with theta held, the nuisance parameters get
 * at least what the fit itself does -- their whole grid, then the exact
 * refinement, here from each of the grid's lowest local minima -- and,
 * besides, the refinement from the last point's nuisance optimum; the
 * lowest counts. Because that
 * grid fit costs a grid of model curves per point, it is done where the
 * interval's end is bracketed -- at an outward step whose warm-started
 * criterion lies above the threshold (below it, a lower S_p could only
 * put the point further inside: the step is inside either way) -- and at
 * the end found; the root finder in between uses the warm-started
 * refinement alone, on the criterion's signed root (signed_root: the same
 * root, about linear in theta), from the bracket's two ends as the walk
 * found them. If the grid fit at an outward step finds the point
 * inside after all, the walk goes on; if the grid fit at the end found
 * finds a lower S_p than the warm one did (the warm start followed a
 * local minimum, so the end was too early), the search goes on from
 * there. The result is the end of the true profile wherever the nuisance
 * grid resolves its minima.
 *
 * A specular model or composite (SPEC §9; varpro.c): at every point its
 * free scales are solved exactly (NNLS; a held scale joins the fixed part
 * of the columns) and the other free parameters refined by
 * bf__varpro_refine; the thorough fit refines them from the optimum's
 * values as well (no stored grid). Its domains have no grid step: the
 * first outward step is 5 % of the estimate; on dense data (more than
 * BF__DENSE_K configurations, where that step lies far outside) it is
 * predicted by Gauss-Newton at the estimate, and the bracket found is
 * narrowed by predicted points before the root finder (gauss_newton_steps,
 * narrow): the same roots, in a third of the inner fits.
 */
#include <float.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Absolute tolerance of the interval ends (parameter units). */
#define CI_TOL 1e-7
/* The root finder also stops at a point whose criterion is within CI_CRIT
 * of 0: the end is then within CI_CRIT / |dc/dtheta| of the root, about
 * 2.5e-6 standard errors at 95 % (dc/dtheta ~ 2 z / se). */
#define CI_CRIT 1e-5
/* The inner fits' Levenberg-Marquardt (a specular model's, varpro.c)
 * stops at an iteration that lowers S by less than CI_STALL_CRIT / n of it
 * (n the weights' sum), so that the criterion n ln(S_p / S_min) is off by
 * about CI_STALL_CRIT, a tenth of CI_CRIT, per iteration left (a flat
 * valley can crawl at ~1e-9 of S for the 200 allowed); on dense data not
 * below CI_STALL_MIN of S, the stop before 2026-12-05 for all data (at
 * 72,000 configurations the criterion is then off by 7e-6 per iteration
 * left). */
#define CI_STALL_CRIT 1e-6
#define CI_STALL_MIN 1e-10
/* Iteration limit of the root finder and of the outward bracketing. */
#define CI_MAXITER 200
/* How often the end found is re-checked by a grid fit and the search
 * resumed (each resumption moves the end outwards). */
#define CI_VERIFY 8
/* The grid fit is better than the warm one when lower by this relative
 * amount (rounding of S is far below it). */
#define CI_BETTER 1e-12
/* The local minima of the nuisance grid refined at a grid fit. */
#define CI_STARTS 4
/* Points of the scan for regions below the threshold apart from the
 * optimum's (scan_side), evenly spaced over the search range. */
#define SCAN_N 13
/* Points per side at which the region found from the optimum is checked
 * for a ridge the outward walk stepped over (ridge). */
#define RIDGE_N 8
/* The scan's grid fits take every s-th point of a nuisance grid, at most
 * this many (FC's 501 values of m: every 8th), then refine from its
 * lowest local minima as every grid fit does: a region is found wherever
 * the nuisance's basin is wider than s steps. */
#define SCAN_GRID 64
/* A dip's minimisation stops at a bracket this share of its width. */
#define SCAN_TOL 1e-3
/* A second minimum of the profile (a scan's dip, or its last point where
 * the criterion still falls there: a basin at the range's bound) competes
 * with the estimate's when its criterion is at most SCAN_COMPETE times
 * the threshold: within twice the interval's half-width in the normal
 * approximation (D = z^2), where a simulated measurement's optimum can
 * fall into it (look-elsewhere; bf__profile_ci_thr's open bit 8). */
#define SCAN_COMPETE 4.0
/* Dense data (more than BF__DENSE_K configurations): the bracket is
 * narrowed by at most CI_NARROW predicted points while its outside end's
 * -2 ln Lambda exceeds CI_NARROW_Q times the threshold; each predicted
 * point lies CI_BEYOND (of its distance from the estimate) past the
 * predicted end, so that it usually becomes the new outside end; not
 * below CI_NARROW_TOL times the root's tolerance, which the root finder
 * reaches in a few bisections (data without noise: the criterion jumps
 * at rounding level, no quadratic predicts it). */
#define CI_NARROW 4
#define CI_NARROW_Q 1.5
#define CI_BEYOND 0.02
#define CI_NARROW_TOL 100.0

/* The profile of parameter j: the problem with j held at theta. */
typedef struct {
    bf__fitctx *fc;
    bf_problem sub;              /* the problem with j fixed */
    double start[BF_MAX_PARAMS]; /* nuisance optimum of the last point */
    double anchor[BF_MAX_PARAMS]; /* the root finder's start: the nuisance
                                    optimum at the bracket's inside end */
    double est[BF_MAX_PARAMS];   /* the optimum */
    size_t j;
    double s_min;                /* objective at the optimum */
    double n_w;                  /* sum of the weights */
    double chi2;                 /* the threshold: chi2_1(level), or the
                                    likelihood's F form (intervals.c) */
    int status;                  /* first failure, BF_OK if none */
    double last_x;               /* the root finder's last point */
    double last_c;               /* and its criterion */
    /* the bracket's ends and their criteria, known from the outward
     * steps, which the root finder's first two evaluations then do not
     * repeat */
    double known_x[2];
    double known_c[2];
    size_t n_known;
    int coarse;                  /* the scan's grid fits (scan_side): at
                                    most SCAN_GRID points per nuisance */
} profile_t;

/* The grid fit of the nuisance parameters at sub's fixed values: their
 * whole grid, then the refinement from each of its CI_STARTS lowest local
 * minima (the fit itself refines its grid optimum only; a profile's inner
 * minimum can lie in a basin whose grid points are not the lowest --
 * between two grid points a deeper minimum than the best grid point's).
 * The lowest refined result goes to r. */
static int grid_fit(profile_t *p, bf_fit_result *r)
{
    bf__grid_layout_t lay;
    bf_fit_result g[CI_STARTS];
    size_t n_min = 0;
    size_t i;
    bf__grid *gr;
    int found = 0;
    int rc = bf__grid_layout_range(p->sub.type, p->sub.fixed,
                                   p->sub.free_mask, p->sub.lo, p->sub.hi,
                                   &lay);
    if (rc != BF_OK) {
        return rc;
    }
    if (p->coarse) {
        bf__grid_layout_coarsen(&lay, SCAN_GRID);
    }
    gr = bf__grid_make(p->fc->pm, &lay, &rc);
    if (gr == NULL) {
        return rc;
    }
    rc = bf__grid_minima(gr, &p->sub, p->fc->pm->cs->cti, CI_STARTS, g,
                         &n_min);
    bf__grid_free(gr);
    for (i = 0; rc == BF_OK && i < n_min; i++) {
        bf_fit_result ri;
        int st = bf__refine(p->fc, &g[i], &ri);
        if (st == BF_ENOMEM) {
            return st;
        }
        if ((st == BF_OK || st == BF_ENOCONV) && (!found || ri.lse < r->lse)) {
            *r = ri;
            found = 1;
        }
    }
    if (rc != BF_OK) {
        return rc;
    }
    return found ? BF_OK : BF_EDOM;
}

/* The warm-started refinement of the nuisance parameters from the last
 * point's optimum. A specular model (SPEC §9): its scales solved exactly
 * (NNLS) at every point, the other free parameters refined (varpro.c). */
static int warm_fit(profile_t *p, bf_fit_result *warm)
{
    bf_fit_result start;
    int rc;
    if (p->sub.type->kind == BF_MODEL_SPECULAR) {
        return bf__varpro_refine(p->fc, p->start, warm);
    }
    memset(&start, 0, sizeof start);
    memcpy(start.param, p->start, sizeof start.param);
    rc = bf__fit_value(p->fc, start.param, &start.lse);
    if (rc != BF_OK) {
        start.lse = HUGE_VAL; /* the refinement keeps a defined point */
    }
    rc = bf__refine(p->fc, &start, warm);
    return rc == BF_ENOCONV ? BF_OK : rc;
}

/* The thorough fit: the grid fit; a specular model's refinement from the
 * optimum's values (its grid is the fit's own, made for the whole domain;
 * with the scales solved at most two parameters are left, and the two
 * starts, this and the warm one, find the basins its grid would). */
static int thorough_fit(profile_t *p, bf_fit_result *g)
{
    if (p->sub.type->kind == BF_MODEL_SPECULAR) {
        return bf__varpro_refine(p->fc, p->est, g);
    }
    return grid_fit(p, g);
}

/* 1 when the thorough fit would repeat the warm one: a specular model's
 * (a refinement from p->est) where the warm start holds the same free
 * values -- each side's first outward step, which starts from the
 * optimum. */
static int thorough_is_warm(const profile_t *p)
{
    size_t j;
    if (p->sub.type->kind != BF_MODEL_SPECULAR) {
        return 0; /* the thorough fit is a grid fit */
    }
    for (j = 0; j < p->sub.type->p; j++) {
        if (((p->sub.free_mask >> j) & 1u) && p->start[j] != p->est[j]) {
            return 0;
        }
    }
    return 1;
}

/* inner's thorough: FIT_WARM, the warm-started refinement alone;
 * FIT_THOROUGH, the thorough fit too; FIT_OUTWARD (an outward step), the
 * thorough fit only where the warm one puts theta outside the interval
 * or fails (inside, a lower S_p could only put it further inside). */
enum { FIT_WARM = 0, FIT_THOROUGH, FIT_OUTWARD };

/* n ln(S / S_min) - chi2: negative inside the interval. */
static double crit_of(const profile_t *p, double s)
{
    return p->n_w * log(s / p->s_min) - p->chi2;
}

/* S_p(theta): the warm-started refinement, and as thorough says the
 * thorough fit (never where it would repeat the warm one); *improved = 1
 * when that was lower. */
static int inner(profile_t *p, double theta, int thorough, double *s,
                 int *improved)
{
    bf_fit_result warm;
    int rc;
    int same;
    *improved = 0;
    p->sub.fixed[p->j] = theta;
    p->start[p->j] = theta;
    if (p->sub.free_mask == 0) {
        return bf__fit_value(p->fc, p->sub.fixed, s);
    }
    same = thorough != FIT_WARM && thorough_is_warm(p);
    thorough = same ? FIT_WARM : thorough; /* keeps FIT_OUTWARD */
    rc = warm_fit(p, &warm);
    if (rc == BF_OK && thorough == FIT_OUTWARD &&
        crit_of(p, warm.lse) <= 0.0) {
        thorough = FIT_WARM;
    }
    if (rc != BF_OK) {
        if (same && rc != BF_ENOMEM) {
            return BF_EDOM; /* as the thorough fit's failure would be */
        }
        if (!thorough || rc == BF_ENOMEM) {
            return rc;
        }
        warm.lse = HUGE_VAL;
    }
    if (thorough) {
        bf_fit_result g;
        rc = thorough_fit(p, &g);
        if (rc == BF_ENOMEM) {
            return rc;
        }
        if (rc == BF_OK && g.lse < warm.lse * (1.0 - CI_BETTER)) {
            warm = g;
            *improved = 1;
        }
    }
    if (!(warm.lse < HUGE_VAL)) {
        return BF_EDOM;
    }
    memcpy(p->start, warm.param, sizeof p->start);
    *s = warm.lse;
    return BF_OK;
}

/* n ln(S_p(theta) / S_min) - chi2: negative inside the interval (inner,
 * thorough as there). */
static double crit_at(profile_t *p, double theta, int thorough,
                      int *improved)
{
    double s = HUGE_VAL;
    int rc = inner(p, theta, thorough, &s, improved);
    if (rc != BF_OK) {
        if (p->status == BF_OK) {
            p->status = rc;
        }
        return GSL_POSINF;
    }
    return crit_of(p, s);
}

/* The signed root of a criterion c: sqrt(n ln(S_p / S_min)) -
 * sqrt(chi2), of c's sign and 0 where c is. Where the profile is
 * quadratic about the estimate (Wilks' asymptotics [1] §9.2), n ln(S_p /
 * S_min) = c + chi2 grows as (theta - theta_hat)^2, so this is linear in
 * theta and an interpolating root finder lands on its root in a step or
 * two. */
static double signed_root(const profile_t *p, double c)
{
    double q = c + p->chi2;
    return sqrt(q > 0.0 ? q : 0.0) - sqrt(p->chi2);
}

/* The root finder's function: the signed root of the criterion (same root,
 * fewer steps), every point refined from the same start, the bracket's
 * inside end's nuisance optimum, so that the function it sees is one
 * basin's, continuous, whatever order it evaluates in (a start carried
 * from point to point can hop to another basin between the two ends of
 * the bracket). */
static double crit_warm(double theta, void *arg)
{
    profile_t *p = arg;
    int improved;
    size_t i;
    p->last_x = theta;
    for (i = 0; i < p->n_known; i++) {
        if (theta == p->known_x[i]) {
            p->last_c = p->known_c[i];
            return signed_root(p, p->last_c);
        }
    }
    memcpy(p->start, p->anchor, sizeof p->start);
    p->last_c = crit_at(p, theta, FIT_WARM, &improved);
    return signed_root(p, p->last_c);
}

/* Root of the warm criterion in [in, out] (crit(in) <= 0 < crit(out)). */
static int root(profile_t *p, double in, double out, double *x)
{
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_function fn;
    double lo = in < out ? in : out;
    double hi = in < out ? out : in;
    int status;
    size_t iter = 0;
    if (s == NULL) {
        return BF_ENOMEM;
    }
    fn.function = crit_warm;
    fn.params = p;
    status = gsl_root_fsolver_set(s, &fn, lo, hi);
    while (status == GSL_SUCCESS && iter++ < CI_MAXITER) {
        status = gsl_root_fsolver_iterate(s);
        if (status != GSL_SUCCESS) {
            break;
        }
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                        gsl_root_fsolver_x_upper(s), CI_TOL,
                                        0.0);
        if (status == GSL_SUCCESS ||
            (gsl_root_fsolver_root(s) == p->last_x &&
             fabs(p->last_c) <= CI_CRIT)) {
            status = GSL_SUCCESS;
            break;
        }
        status = GSL_SUCCESS;
    }
    *x = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    return status == GSL_SUCCESS ? BF_OK : BF_ENOCONV;
}

/* The end predicted in the bracket [x, out] (criteria cx <= 0 < co): the
 * zero of the signed root (linear in theta on a profile quadratic about
 * theta_hat, as on dense data) interpolated linearly between the two,
 * then moved CI_BEYOND of its distance from theta_hat outwards. */
static double predict(const profile_t *p, double theta_hat, double x,
                      double cx, double out, double co)
{
    double gx = signed_root(p, cx);
    double go = signed_root(p, co);
    double e = x + (out - x) * -gx / (go - gx);
    return e + CI_BEYOND * (e - theta_hat);
}

/* Dense data: the bracket [*x, *out] (criteria *cx <= 0 < *co; inside the
 * nuisance optimum at *x) narrowed by predicted points, each judged by the
 * thorough criterion as the outward steps are; the root finder then needs
 * a few points of the warm criterion instead of some twenty (the first
 * step, 5 % of the estimate, lies far outside a dense table's interval). */
static int narrow(profile_t *p, double theta_hat, double *x, double *cx,
                  double *inside, double *out, double *co)
{
    size_t i;
    for (i = 0; i < CI_NARROW && *co + p->chi2 > CI_NARROW_Q * p->chi2 &&
                fabs(*out - *x) > CI_NARROW_TOL * CI_TOL;
         i++) {
        double t = predict(p, theta_hat, *x, *cx, *out, *co);
        double c;
        int improved;
        if (!((t - *x) * (*out - t) > 0.0)) {
            break; /* not strictly inside the bracket */
        }
        c = crit_at(p, t, FIT_THOROUGH, &improved);
        if (p->status != BF_OK) {
            return p->status;
        }
        if (c > 0.0) {
            *out = t;
            *co = c;
        } else {
            *x = t;
            *cx = c;
            memcpy(inside, p->start, BF_MAX_PARAMS * sizeof *inside);
        }
    }
    return BF_OK;
}

/* One end of the interval: walks from x0 (the optimum, or a point the
 * scan found inside; its criterion c0, p->start its nuisance optimum)
 * towards limit in steps that double until the criterion (grid fits)
 * turns positive, on dense data narrows that bracket (narrow), finds the
 * root, and re-checks it with a grid fit (see the file comment).
 * *at_limit is set when the interval reaches limit. */
static int one_side(profile_t *p, double theta_hat, double x0, double c0,
                    double limit, double d0, double *end, int *at_limit)
{
    double x = x0;
    double cx = c0;  /* the criterion at x */
    double co = 0.0; /* and at out */
    double d = d0;
    double nuisance[BF_MAX_PARAMS];
    double inside[BF_MAX_PARAMS]; /* the nuisance optimum at x */
    double out = limit;
    double edge = limit; /* the walk's bound: limit, or where not defined */
    size_t iter;
    size_t verify;
    int improved;
    int rc = BF_OK;
    memcpy(nuisance, p->start, sizeof nuisance);
    memcpy(inside, p->start, sizeof inside);
    *at_limit = 0;
    if (x0 == limit) { /* the start is on the search range's bound */
        *end = limit;
        *at_limit = 1;
        return BF_OK;
    }
    for (iter = 0; iter < CI_MAXITER; iter++) {
        double next = limit > theta_hat ? x + d : x - d;
        double c;
        if (edge != limit && fabs(edge - x) <= CI_TOL) {
            /* within CI_TOL of where the model is not defined (below),
             * the profile below the threshold: an open end (not
             * identified) */
            *end = x;
            *at_limit = 1;
            memcpy(p->start, nuisance, sizeof nuisance);
            return BF_OK;
        }
        if ((limit > theta_hat && next >= edge) ||
            (limit < theta_hat && next <= edge)) {
            next = edge == limit ? limit : 0.5 * (x + edge);
        }
        c = crit_at(p, next, FIT_OUTWARD, &improved);
        if (p->status == BF_EDOM) {
            /* not defined at next (with theta there the model overflows
             * from every start the inner fits take: a lobe's power beyond
             * the largest double): the walk stays inside next, halving
             * the way to it; where it comes within CI_TOL (above) the
             * profile is below the threshold as far as it is defined */
            p->status = BF_OK;
            edge = next;
            d = 0.5 * fabs(next - x);
            continue;
        }
        if (p->status != BF_OK) {
            return p->status;
        }
        if (c > 0.0) {
            out = next;
            co = c;
            break;
        }
        if (next == limit) {
            *end = limit;
            *at_limit = 1;
            memcpy(p->start, nuisance, sizeof nuisance);
            return BF_OK;
        }
        x = next;
        cx = c;
        memcpy(inside, p->start, sizeof inside);
        d *= 2.0;
    }
    if (iter == CI_MAXITER) {
        return BF_ENOCONV;
    }
    if (p->fc->pb->n > BF__DENSE_K) {
        rc = narrow(p, theta_hat, &x, &cx, inside, &out, &co);
        if (rc != BF_OK) {
            return rc;
        }
    }
    for (verify = 0; verify < CI_VERIFY; verify++) {
        double c;
        /* the warm starts begin at the bracket's inside point, whose
         * criterion is known; so is the outside point's, found by the walk
         * from the same start -- but not once a grid fit has moved the
         * inside point to a lower basin, from whose optimum the root
         * finder evaluates it again */
        memcpy(p->anchor, inside, sizeof inside);
        p->known_x[0] = x;
        p->known_c[0] = cx;
        p->known_x[1] = out;
        p->known_c[1] = co;
        p->n_known = verify == 0 ? 2 : 1;
        rc = root(p, x, out, end);
        p->n_known = 0;
        if (rc != BF_OK || p->status != BF_OK) {
            break;
        }
        c = crit_at(p, *end, FIT_THOROUGH, &improved);
        if (p->status != BF_OK || !improved || c > 0.0) {
            break; /* the grid fit agrees: the end stands */
        }
        x = *end; /* a lower nuisance minimum: the end lies further out */
        cx = c;
        memcpy(inside, p->start, sizeof inside);
    }
    memcpy(p->start, nuisance, sizeof nuisance);
    return p->status != BF_OK ? p->status : rc;
}

/* Dense data, a specular model: the first outward steps from the
 * Gauss-Newton approximation at the estimate, every free parameter's from
 * one Jacobian. With J the residuals' finite-difference Jacobian over the
 * free parameters (scales included) and H = J' W J, S(theta) ~ S_min +
 * d' H d, so the profile of theta_j rises as S_p - S_min ~ d_j^2 /
 * [H^-1]_jj and n ln(S_p / S_min) reaches thr at d_j = sqrt(thr S_min
 * [H^-1]_jj / n) [1] §9.2; the step is CI_BEYOND past it, and at least the
 * ends' tolerance CI_TOL (data without noise: S_min at rounding level,
 * d_j ~ 1e-15, where the criterion is rounding noise and doubling steps
 * would take some thirty inner fits to leave it). d0[j] is left as it is
 * when H is not positive definite or a residual is not defined. fc->pb is
 * the problem. */
static int gauss_newton_steps(bf__fitctx *fc, const double *est, double thr,
                              double *d0)
{
    const bf_problem *pb = fc->pb;
    const size_t n = pb->n;
    size_t idx[BF_MAX_PARAMS];
    size_t m = 0;
    size_t a;
    size_t b;
    size_t k;
    double s_min;
    double *r;
    gsl_matrix *h;
    int rc = bf__fit_value(fc, est, &s_min);
    if (rc != BF_OK) {
        return BF_OK; /* no prediction: the default steps */
    }
    s_min = s_min > DBL_MIN ? s_min : DBL_MIN; /* as the profiles' */
    for (a = 0; a < pb->type->p; a++) {
        if ((pb->free_mask >> a) & 1u) {
            idx[m++] = a;
        }
    }
    r = malloc((m + 1) * n * sizeof *r);
    h = gsl_matrix_calloc(m, m);
    if (r == NULL || h == NULL) {
        free(r);
        gsl_matrix_free(h);
        return BF_ENOMEM;
    }
    for (a = 0; a <= m && rc == BF_OK; a++) {
        double x[BF_MAX_PARAMS];
        memcpy(x, est, sizeof x);
        if (a > 0) { /* forward difference, backward at the upper bound */
            size_t q = idx[a - 1];
            double step = 1e-6 * fmax(fabs(est[q]), 1e-3);
            x[q] = est[q] + step <= pb->hi[q] ? est[q] + step
                                               : est[q] - step;
        }
        rc = bf__fit_residuals(fc, x, r + a * n);
        for (k = 0; rc == BF_OK && a > 0 && k < n; k++) {
            r[a * n + k] = (r[a * n + k] - r[k]) / (x[idx[a - 1]] -
                                                    est[idx[a - 1]]);
        }
    }
    for (a = 0; rc == BF_OK && a < m; a++) {
        for (b = 0; b <= a; b++) {
            double sum = 0.0;
            for (k = 0; k < n; k++) {
                double w = pb->weight != NULL ? pb->weight[k] : 1.0;
                sum += w * r[(a + 1) * n + k] * r[(b + 1) * n + k];
            }
            gsl_matrix_set(h, a, b, sum);
            gsl_matrix_set(h, b, a, sum);
        }
    }
    free(r);
    if (rc == BF_OK && gsl_linalg_cholesky_decomp1(h) == GSL_SUCCESS &&
        gsl_linalg_cholesky_invert(h) == GSL_SUCCESS) {
        double n_w = bf__weight_sum(pb);
        for (a = 0; a < m; a++) {
            double d = sqrt(thr * s_min * gsl_matrix_get(h, a, a) / n_w);
            if (d > 0.0 && isfinite(d)) {
                d0[idx[a]] = fmax((1.0 + CI_BEYOND) * d, CI_TOL);
            }
        }
    }
    gsl_matrix_free(h);
    return rc == BF_ENOMEM ? rc : BF_OK;
}

double bf__profile_step(const bf_problem *pb, size_t j, double est)
{
    const bf_param *pj = &pb->type->param[j];
    if (pb->type->kind == BF_MODEL_SPECULAR) {
        /* domains without a grid, the scales' up to 1e6 (SPEC §9.3): 5 %
         * of the estimate (1e-3 of the domain, at most 1e-3, from 0) */
        return est > 0.0 ? 0.05 * est : 1e-3 * fmin(pb->hi[j] - pb->lo[j],
                                                     1.0);
    }
    return pj->grid_n > 0 ? pj->grid_step : (pb->hi[j] - pb->lo[j]) / 100.0;
}

int bf__profile_steps(bf__fitctx *fc, const bf_fit_result *best, double thr,
                      double *d0)
{
    const bf_problem *pb = fc->pb;
    size_t j;
    for (j = 0; j < pb->type->p; j++) {
        d0[j] = bf__profile_step(pb, j, best->param[j]);
    }
    if (pb->n > BF__DENSE_K && pb->type->kind == BF_MODEL_SPECULAR) {
        return gauss_newton_steps(fc, best->param, thr, d0);
    }
    return BF_OK;
}

double bf__weight_sum(const bf_problem *pb)
{
    double s = 0.0;
    size_t k;
    if (pb->weight == NULL) {
        return (double)pb->n;
    }
    for (k = 0; k < pb->n; k++) {
        s += pb->weight[k];
    }
    return s;
}

int bf__profile_ci(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                   double level, double *low, double *high, unsigned *open)
{
    /* Wilks: chi2_1(level), 3.841 at 95% [1] §2.6 */
    double thr = gsl_cdf_chisq_Pinv(level, 1.0);
    double d0[BF_MAX_PARAMS];
    int rc = bf__profile_steps(fc, best, thr, d0);
    return rc != BF_OK ? rc
                       : bf__profile_ci_thr(fc, best, j, thr, d0[j], low,
                                            high, open, NULL);
}

/* The profile of fc->pb's parameter j about best under the threshold
 * thr: p set up, fc switched to p->sub with the inner fits' stall stop
 * (undone by profile_end). BF_OK, or bf__fit_value's failure at best. */
static int profile_begin(profile_t *p, bf__fitctx *fc,
                         const bf_fit_result *best, size_t j, double thr)
{
    const bf_problem *pb = fc->pb;
    int rc;
    memset(p, 0, sizeof *p);
    p->fc = fc;
    p->sub = *pb;
    p->sub.free_mask &= ~(1u << j);
    memcpy(p->sub.fixed, best->param, sizeof p->sub.fixed);
    memcpy(p->start, best->param, sizeof p->start);
    memcpy(p->est, best->param, sizeof p->est);
    p->j = j;
    p->n_w = bf__weight_sum(pb);
    p->chi2 = thr;
    rc = bf__fit_value(fc, best->param, &p->s_min);
    if (rc == BF_OK) {
        if (!(p->s_min > DBL_MIN)) {
            p->s_min = DBL_MIN; /* an exact fit: the interval is a point */
        }
        bf__fitctx_use(fc, &p->sub);
        fc->stall = fmax(CI_STALL_CRIT / p->n_w, CI_STALL_MIN);
    }
    return rc;
}

static void profile_end(bf__fitctx *fc, const bf_problem *pb)
{
    bf__fitctx_use(fc, pb);
    fc->stall = 0.0;
}

int bf__profile_curve(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                      size_t n, const double *theta, double *dev)
{
    const bf_problem *pb = fc->pb;
    profile_t p;
    size_t mid = 0;
    size_t k;
    int side;
    int rc = profile_begin(&p, fc, best, j, 0.0); /* crit_at: D itself */
    for (k = 0; k < n; k++) {
        dev[k] = NAN;
    }
    while (mid < n && theta[mid] < best->param[j]) {
        mid++;
    }
    /* outward from the optimum, each point warm-started from its inner
     * neighbour (the nuisance optimum moves smoothly with theta) */
    for (side = 0; side < 2 && rc == BF_OK; side++) {
        memcpy(p.start, best->param, sizeof p.start);
        for (k = 0; (side == 0 ? k < n - mid : k < mid) && rc == BF_OK;
             k++) {
            size_t at = side == 0 ? mid + k : mid - 1 - k;
            int improved;
            /* the thorough fit at every point: a curve drawn inside the
             * interval too, where a warm chain can follow a local
             * minimum of the nuisance (FC-G's n) */
            double c = crit_at(&p, theta[at], FIT_THOROUGH, &improved);
            if (p.status == BF_ENOMEM) {
                rc = BF_ENOMEM;
            } else if (p.status != BF_OK) {
                p.status = BF_OK; /* not defined there: left NaN */
                memcpy(p.start, best->param, sizeof p.start);
            } else { /* S_p >= S_min up to the inner fits' tolerance */
                dev[at] = fmax(c, 0.0);
            }
        }
    }
    profile_end(fc, pb);
    return rc;
}

int bf__profile_point(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                      double theta, double *dev, double *param)
{
    const bf_problem *pb = fc->pb;
    profile_t p;
    int improved;
    int rc = profile_begin(&p, fc, best, j, 0.0); /* crit_at: D itself */
    if (rc == BF_OK) {
        double c = crit_at(&p, theta, FIT_THOROUGH, &improved);
        rc = p.status;
        *dev = fmax(c, 0.0); /* S_p >= S_min up to the fits' tolerance */
        if (param != NULL) {
            memcpy(param, p.start, BF_MAX_PARAMS * sizeof *param);
        }
        profile_end(fc, pb);
    }
    return rc;
}

/* The least criterion between the scan's points a < b (their middle
 * point m lower than both, cm > 0, p->anchor m's nuisance optimum):
 * Brent's minimiser [3] on the warm criterion's signed root (the same
 * order), until a point is inside or the bracket is SCAN_TOL of it.
 * *x, *c get the lowest point found and its criterion, p->start its
 * nuisance optimum. */
static int dip(profile_t *p, double a, double m, double b, double ca,
               double cm, double cb, double *x, double *c)
{
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    gsl_function fn;
    double start[BF_MAX_PARAMS];
    size_t iter = 0;
    int status;
    if (s == NULL) {
        return BF_ENOMEM;
    }
    *x = m;
    *c = cm;
    memcpy(start, p->anchor, sizeof start);
    fn.function = crit_warm;
    fn.params = p;
    p->n_known = 0;
    status = gsl_min_fminimizer_set_with_values(
        s, &fn, m, signed_root(p, cm), a, signed_root(p, ca), b,
        signed_root(p, cb));
    while (status == GSL_SUCCESS && iter++ < CI_MAXITER && *c > 0.0 &&
           p->status == BF_OK) {
        status = gsl_min_fminimizer_iterate(s);
        if (p->last_c < *c) {
            *x = p->last_x;
            *c = p->last_c;
            memcpy(start, p->start, sizeof start);
        }
        if (gsl_min_fminimizer_x_upper(s) - gsl_min_fminimizer_x_lower(s) <
            SCAN_TOL * (b - a)) {
            break;
        }
    }
    gsl_min_fminimizer_free(s);
    memcpy(p->start, start, sizeof start);
    if (p->status == BF_ENOMEM) {
        return BF_ENOMEM;
    }
    p->status = BF_OK; /* a point not defined: the dip is outside */
    return BF_OK;
}

/* A ridge inside the region the walk found from the optimum to its end
 * (a profile that rises above the threshold and comes back below between
 * two of the walk's doubling steps, as at a kink where the normalising
 * maximum moves to another configuration): the criterion (outward fits,
 * warm-started from point to point) at RIDGE_N - 1 points evenly spaced
 * strictly between theta_hat and end. Where it rises above the threshold
 * and comes back below once, *gap_a, *gap_b get the ridge's two roots
 * (root, each from its inside neighbour's nuisance; nearer theta_hat
 * first); left as they are when there is no ridge, more than one, or a
 * root is not found (the region stands whole). p->start is the optimum's
 * nuisance on return. */
static int ridge(profile_t *p, double theta_hat, double end, double *gap_a,
                 double *gap_b)
{
    double in_x = theta_hat;  /* the last point inside */
    double in_nu[BF_MAX_PARAMS];
    double out_x = NAN;       /* the ridge's first and last points */
    double last_out = NAN;
    double back_x = NAN;      /* the first point inside beyond it */
    double back_nu[BF_MAX_PARAMS];
    double ra;
    double rb;
    int ridges = 0;
    size_t i;
    int rc;
    memcpy(p->start, p->est, sizeof p->start);
    memcpy(in_nu, p->est, sizeof in_nu);
    for (i = 1; i < RIDGE_N && ridges < 2; i++) {
        double x = theta_hat + (end - theta_hat) * (double)i / RIDGE_N;
        int improved;
        double c = crit_at(p, x, FIT_OUTWARD, &improved);
        if (p->status == BF_ENOMEM) {
            return BF_ENOMEM;
        }
        if (p->status != BF_OK) { /* not defined: no ridge to speak of */
            p->status = BF_OK;
            ridges = 2;
            break;
        }
        if (c > 0.0) {
            if (isnan(out_x)) {
                ridges++;
                out_x = x;
            } else if (!isnan(back_x)) {
                ridges++; /* a second ridge */
            }
            last_out = x;
        } else if (isnan(out_x)) {
            in_x = x;
            memcpy(in_nu, p->start, sizeof in_nu);
        } else if (isnan(back_x)) {
            back_x = x;
            memcpy(back_nu, p->start, sizeof back_nu);
        }
    }
    memcpy(p->start, p->est, sizeof p->start);
    if (ridges != 1 || isnan(back_x)) {
        return BF_OK; /* none, more than one, or open to the end */
    }
    memcpy(p->anchor, in_nu, sizeof in_nu);
    rc = root(p, in_x, out_x, &ra);
    if (rc == BF_OK && p->status == BF_OK) {
        memcpy(p->anchor, back_nu, sizeof back_nu);
        rc = root(p, back_x, last_out, &rb);
    }
    memcpy(p->start, p->est, sizeof p->start);
    if (rc == BF_ENOMEM || p->status == BF_ENOMEM) {
        return BF_ENOMEM;
    }
    p->status = BF_OK;
    if (rc == BF_OK && (ra - theta_hat) * (rb - ra) > 0.0) {
        *gap_a = ra;
        *gap_b = rb;
    }
    return BF_OK;
}

/* The gap between the region found from the optimum (its end near) and
 * the region apart from it that holds far_x (criterion far_c, p->start
 * its nuisance): the far region's inner end by one_side from far_x towards
 * near; *gap_a = near, *gap_b = that end, unless the walk reaches near,
 * fails (the hull stands; BF_ENOMEM returned), or one of the m scanned
 * points t (criterion c) strictly inside the gap is below the threshold. */
static int gap_of(profile_t *p, double far_x, double far_c, double near,
                  double d0, const double *t, const double *c, size_t m,
                  double *gap_a, double *gap_b)
{
    double inner = NAN;
    int reached = 0;
    size_t i;
    int rc = one_side(p, far_x, far_x, far_c, near, d0, &inner, &reached);
    if (rc == BF_ENOMEM || p->status == BF_ENOMEM) {
        return BF_ENOMEM;
    }
    p->status = BF_OK;
    if (rc != BF_OK || reached || !isfinite(inner)) {
        return BF_OK;
    }
    for (i = 1; i < m; i++) {
        if (c[i] <= 0.0 && (t[i] - near) * (t[i] - inner) < 0.0) {
            return BF_OK;
        }
    }
    *gap_a = near;
    *gap_b = inner;
    return BF_OK;
}

/* The scan beyond the end *end of the interval found from the optimum,
 * towards limit: the thorough criterion (its grid fit on a coarser grid,
 * SCAN_GRID) at the points of SCAN_N evenly spaced over the search range
 * that lie beyond it, from the nearest out,
 * and the least criterion between neighbours about each scanned point
 * lower than both (dip: a region narrower than the points' spacing).
 * Where a point is inside (a region below the threshold apart from the
 * optimum's: a profile with two minima, as the Fresnel index's of FC-E,
 * FC-G, WNO and WNO-R, whose normalised shapes fold over n), the end is
 * found again from the farthest (one_side) and *split set: the interval
 * is the hull of the regions, which holds the whole set. The far region's
 * inner end is found too (one_side from the far point back towards the
 * end found first): *gap_a, *gap_b get the gap between the two regions
 * (the end found first, that inner end), left as they are when the walk
 * back reaches the first end (one region after all), fails, or a scanned
 * point inside the gap is below the threshold (a third region: the hull
 * stands). p->start is the optimum's nuisance on return. */
static int scan_side(profile_t *p, double theta_hat, double limit, double d0,
                     double *end, int *at_limit, int *split, double *gap_a,
                     double *gap_b, double *second)
{
    const double lo = p->fc->pb->lo[p->j];
    const double hi = p->fc->pb->hi[p->j];
    double t[SCAN_N + 1];
    double c[SCAN_N + 1];
    double nu[SCAN_N + 1][BF_MAX_PARAMS];
    double far_x = NAN;
    double far_c = NAN;
    double far_start[BF_MAX_PARAMS];
    size_t m = 1;
    size_t i;
    int rc = BF_OK;
    if (*at_limit) {
        return BF_OK;
    }
    t[0] = *end; /* the end found: on the threshold */
    c[0] = 0.0;
    memcpy(nu[0], p->start, sizeof nu[0]);
    for (i = 0; i < SCAN_N; i++) {
        size_t at = limit > theta_hat ? i : SCAN_N - 1 - i;
        double x = lo + (hi - lo) * (double)at / (double)(SCAN_N - 1);
        int improved;
        if (!(limit > theta_hat ? x > *end + CI_TOL : x < *end - CI_TOL)) {
            continue;
        }
        p->coarse = 1;
        c[m] = crit_at(p, x, FIT_THOROUGH, &improved);
        p->coarse = 0;
        if (p->status == BF_ENOMEM) {
            return BF_ENOMEM;
        }
        if (p->status != BF_OK) { /* not defined there: outside */
            p->status = BF_OK;
            c[m] = HUGE_VAL;
        }
        t[m] = x;
        memcpy(nu[m], p->start, sizeof nu[m]);
        if (c[m] <= 0.0) {
            far_x = x;
            far_c = c[m];
            memcpy(far_start, p->start, sizeof far_start);
        }
        m++;
    }
    if (m >= 3 && c[m - 1] > 0.0 && c[m - 1] < c[m - 2] &&
        c[m - 1] + p->chi2 < *second) { /* still falling at the bound */
        *second = c[m - 1] + p->chi2;
    }
    for (i = m >= 2 ? m - 2 : 0; i >= 1; i--) { /* the farthest dip first */
        double x;
        double cx;
        if (!isnan(far_x) && (t[i] - far_x) * (limit - theta_hat) <= 0.0) {
            break; /* no farther than the farthest point inside */
        }
        if (!(c[i] > 0.0 && c[i] < c[i - 1] && c[i] < c[i + 1] &&
              isfinite(c[i + 1]))) {
            continue;
        }
        memcpy(p->anchor, nu[i], sizeof nu[i]);
        rc = dip(p, fmin(t[i - 1], t[i + 1]), t[i], fmax(t[i - 1], t[i + 1]),
                 t[i - 1] < t[i + 1] ? c[i - 1] : c[i + 1], c[i],
                 t[i - 1] < t[i + 1] ? c[i + 1] : c[i - 1], &x, &cx);
        if (rc != BF_OK) {
            return rc;
        }
        if (cx + p->chi2 < *second) {
            *second = cx + p->chi2;
        }
        if (cx <= 0.0) {
            far_x = x;
            far_c = cx;
            memcpy(far_start, p->start, sizeof far_start);
            break;
        }
    }
    if (!isnan(far_x)) {
        double near = *end;
        *split = 1;
        memcpy(p->start, far_start, sizeof far_start);
        rc = one_side(p, theta_hat, far_x, far_c, limit, d0, end, at_limit);
        if (rc == BF_OK) {
            memcpy(p->start, far_start, sizeof far_start);
            rc = gap_of(p, far_x, far_c, near, d0, t, c, m, gap_a, gap_b);
        }
    }
    memcpy(p->start, p->est, sizeof p->start);
    return rc;
}

int bf__profile_ci_thr(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                       double thr, double d0, double *low, double *high,
                       unsigned *open, double *gap)
{
    const bf_problem *pb = fc->pb;
    profile_t p;
    double theta_hat = best->param[j];
    /* the gaps: ridges below, above; regions apart below, above */
    double g[8] = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
    size_t k;
    size_t n_gaps = 0;
    int at_lo = 0;
    int at_hi = 0;
    int split = 0;
    double second = HUGE_VAL; /* the least D of a second minimum outside */
    int scan = pb->type->kind != BF_MODEL_SPECULAR;
    int rc = profile_begin(&p, fc, best, j, thr);
    if (rc == BF_OK) {
        rc = one_side(&p, theta_hat, theta_hat, -thr, pb->lo[j], d0, low,
                      &at_lo);
        if (rc == BF_OK) {
            rc = one_side(&p, theta_hat, theta_hat, -thr, pb->hi[j], d0,
                          high, &at_hi);
        }
        if (rc == BF_OK && scan) {
            rc = ridge(&p, theta_hat, *low, &g[1], &g[0]);
        }
        if (rc == BF_OK && scan) {
            rc = ridge(&p, theta_hat, *high, &g[2], &g[3]);
        }
        if (rc == BF_OK && scan) {
            rc = scan_side(&p, theta_hat, pb->lo[j], d0, low, &at_lo, &split,
                           &g[5], &g[4], &second);
        }
        if (rc == BF_OK && scan) {
            rc = scan_side(&p, theta_hat, pb->hi[j], d0, high, &at_hi,
                           &split, &g[6], &g[7], &second);
        }
        profile_end(fc, pb);
    }
    for (k = 0; k < 8; k += 2) {
        n_gaps += isfinite(g[k]);
    }
    split = split || n_gaps > 0;
    *open = (at_lo ? 1u : 0u) | (at_hi ? 2u : 0u) | (split ? 4u : 0u) |
            (split || second <= SCAN_COMPETE * thr ? 8u : 0u);
    if (gap != NULL) { /* one gap, or none: three regions keep the hull */
        gap[0] = gap[1] = NAN;
        for (k = 0; k < 8 && n_gaps == 1; k += 2) {
            if (isfinite(g[k])) {
                gap[0] = g[k];
                gap[1] = g[k + 1];
            }
        }
    }
    return rc;
}

int bf_fit_profile_ci(const bf_problem *pb, const bf_fit_result *best,
                      size_t j, double level, double *low, double *high,
                      unsigned *open)
{
    bf__solo so;
    int rc;
    if (pb == NULL || best == NULL || low == NULL || high == NULL ||
        open == NULL || pb->type == NULL || pb->data == NULL ||
        j >= pb->type->p || !((pb->free_mask >> j) & 1u) ||
        !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__profile_ci(&so.fc, best, j, level, low, high, open);
    bf__solo_free(&so);
    return rc;
}
