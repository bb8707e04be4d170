/* albedo.c: the directional albedo of a specular model (SPEC §9; issue 17,
 * the energy check), by adaptive quadrature.
 *
 * References:
 *   [1] GSL manual, "Numerical Integration": QAG (adaptive Gauss-Kronrod,
 *       21 points), one per interval between break points.
 *
 * Equations:
 *   a(theta_i) = int_0^{pi/2} int_{-pi}^{pi} f(ti, to, phi_s) cos to sin to
 *                d phi_s d to
 *              = 2 int_0^{pi/2} int_0^{pi} ... (the models see cos phi_s
 *                and sin^2(phi_s / 2) only: symmetric in phi_s).
 * The lobe of a specular model is as narrow as alpha = 1e-3 (SPEC §9.3)
 * around the mirror direction (to = ti, phi_s = 0; SPEC §1.2), so both
 * integrals get break points at geometric distances from it, ti +- w 4^k
 * and w0 4^k, and adapt between them: every width from w to the
 * hemisphere is resolved by some interval. w is the lobe's own scale
 * (lobe_width: a quarter of the first of 1e-5 4^k at which f moves by a
 * thousandth of its value at the mirror direction, not below 1e-5), so a
 * wide lobe is not cut into intervals far finer than anything in it, and
 * a narrow one keeps w = 1e-5. The lobes are functions of the
 * angle g between o and the mirror direction r (or of the half vector's,
 * which follows it), and
 *   1 - cos g = (1 - cos(to - ti)) + sin to sin ti (1 - cos phi_s),
 * so at a zenith to the inner integrand changes with phi_s on no finer
 * scale than the phi_s where the second term reaches a sixteenth of the
 * first: phi_1 = sqrt((1 - cos(to - ti)) / (8 sin to sin ti)), about
 * |to - ti| / (4 sqrt(sin to sin ti)). The inner break points start at
 * w0 = max(w, phi_1 / 4) (none at normal incidence, where nothing
 * depends on phi_s): the outer nodes away from ti skip the finest
 * intervals, which there would each cost 21 evaluations to integrate a
 * constant.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#include "internal.h"

#define ALB_W 1e-5        /* the narrowest width resolved (radians) */
#define ALB_FLAT 1e-3     /* lobe_width(): a relative change it resolves */
#define ALB_LIMIT 1000    /* subintervals per quadrature */
#define ALB_MAXPTS 40
#define ALB_EPSREL_IN 1e-9
#define ALB_EPSABS_IN 1e-11
#define ALB_EPSREL_OUT 1e-8
#define ALB_EPSABS_OUT 1e-10
#define ALB_ACCEPT_IN 1e-7  /* accepted() relative error bounds */
#define ALB_ACCEPT_OUT 1e-6

typedef struct {
    const bf_model_type *type;
    const double *param;
    void *work;
    double theta_i;
    double w;         /* the narrowest width resolved (lobe_width) */
    double theta_o;
    double cos_sin_o; /* cos to sin to, once per to */
    gsl_integration_workspace *inner;
    double pts_in[ALB_MAXPTS];
    size_t n_in;
    int failed;
} alb_t;

/* Break points a, a + w0 4^k (k = 0, 1, ...) below hi, and hi, after lo
 * when lo < a: sorted, into pts (capacity ALB_MAXPTS), with those below a
 * mirrored (a - w0 4^k above lo). Returns the count. */
static size_t breaks(double lo, double a, double hi, double w0, double *pts)
{
    double below[ALB_MAXPTS / 2];
    size_t nb = 0;
    size_t n = 0;
    double d;
    for (d = w0; (a - d > lo) && (nb < ALB_MAXPTS / 2 - 2); d *= 4.0) {
        below[nb++] = a - d;
    }
    pts[n++] = lo;
    while (nb > 0) {
        pts[n++] = below[--nb];
    }
    if (a > lo && a < hi) {
        pts[n++] = a;
    }
    for (d = w0; (a + d < hi) && (n < ALB_MAXPTS - 1); d *= 4.0) {
        pts[n++] = a + d;
    }
    pts[n++] = hi;
    return n;
}

/* The first inner break point's width at zenith to (file comment): w0 =
 * max(w, phi_1 / 4); HUGE_VAL where nothing depends on phi_s. */
static double inner_w0(double w, double theta_i, double theta_o)
{
    double s = sin(theta_o) * sin(theta_i);
    double c = 1.0 - cos(theta_o - theta_i);
    double phi_1;
    if (!(s > 0.0)) {
        return HUGE_VAL;
    }
    phi_1 = sqrt(c / (8.0 * s));
    return phi_1 / 4.0 > w ? phi_1 / 4.0 : w;
}

/* f at (ti, to, phi_s); NaN where not defined. */
static double f_at(const alb_t *a, double theta_o, double phi_s)
{
    bf_geom g;
    double v = NAN;
    g.theta_i = a->theta_i;
    g.phi_i = BF__PI;
    g.theta_s = theta_o;
    g.phi_s = phi_s;
    if (a->type->eval(a->param, 1, &g, &v, a->work) != BF_OK) {
        return NAN;
    }
    return v;
}

/* The narrowest width both integrals resolve (file comment): a quarter
 * of the first of d = ALB_W 4^k (k = 0, 1, ...) at which f, from the
 * mirror direction to to = ti + d (ti - d where that passes the horizon)
 * in the plane, changes by more than ALB_FLAT of its value -- where the
 * lobe's curvature shows -- and not below ALB_W; ALB_W where f at the
 * mirror direction is not positive. The angle from the mirror direction
 * changes fastest along to (by d; along phi_s, by sqrt(sin to sin ti)
 * d), so the lobe is flat to ALB_FLAT within d / 4 every way. */
static double lobe_width(const alb_t *a)
{
    double v0 = f_at(a, a->theta_i, 0.0);
    double d;
    if (!(v0 > 0.0) || !isfinite(v0)) {
        return ALB_W;
    }
    for (d = ALB_W; d < 0.25; d *= 4.0) {
        double to = a->theta_i + d < BF__PI_2 ? a->theta_i + d
                                               : a->theta_i - d;
        double v = f_at(a, to, 0.0);
        if (!isfinite(v) || fabs(v - v0) > ALB_FLAT * v0) {
            break;
        }
    }
    return d / 4.0 > ALB_W ? d / 4.0 : ALB_W;
}

/* A quadrature's result r with error estimate err and GSL status st is
 * accepted when it converged, or when GSL stopped short of the requested
 * tolerance (round-off detected, subdivision limit: a lobe of 1e-3 rad
 * against a hemisphere) with an estimated error still within the relative
 * bound acc -- far below what the energy check (an albedo against 1) can
 * see. Any other failure (an undefined integrand) is not. */
static int accepted(int st, double r, double err, double acc)
{
    if (st == GSL_SUCCESS) {
        return 1;
    }
    return (st == GSL_EROUND || st == GSL_EMAXITER || st == GSL_ESING ||
            st == GSL_EDIVERGE) &&
           isfinite(r) && isfinite(err) && err <= acc * fabs(r) + 1e-12;
}

/* int fn over [pts[0], pts[n - 1]]: QAG (Gauss-Kronrod 21 points, no
 * extrapolation) on every interval between break points, each to the
 * relative tolerance epsrel and its share of epsabs; *r and *err the
 * sums, the status the first failure's (GSL_SUCCESS when none). Not
 * QAGP, whose extrapolation (the epsilon algorithm, made for integrable
 * singularities at the break points) ran over kinks of the lobes'
 * masking (ABC's V-groove min() at one phi_s of each theta_o) to results
 * 1e-7 off with error estimates of 1e-11, and the outer integral, fed
 * those, to 5e-5 off (doc/methods.md §11). */
static int qag_pieces(gsl_function *fn, const double *pts, size_t n,
                      double epsabs, double epsrel,
                      gsl_integration_workspace *w, double *r, double *err)
{
    int st = GSL_SUCCESS;
    size_t i;
    *r = 0.0;
    *err = 0.0;
    for (i = 0; i + 1 < n; i++) {
        double ri = 0.0;
        double ei = 0.0;
        int si = gsl_integration_qag(fn, pts[i], pts[i + 1],
                                     epsabs / (double)(n - 1), epsrel,
                                     ALB_LIMIT, GSL_INTEG_GAUSS21, w, &ri,
                                     &ei);
        st = st == GSL_SUCCESS ? si : st;
        *r += ri;
        *err += ei;
    }
    return st;
}

/* f cos to sin to at (ti, to, phi_s). */
static double integrand(double phi_s, void *arg)
{
    alb_t *a = arg;
    double v = f_at(a, a->theta_o, phi_s);
    if (!isfinite(v)) {
        a->failed = 1;
        return 0.0;
    }
    return v * a->cos_sin_o;
}

/* 2 int_0^pi f cos to sin to d phi_s at to. */
static double over_phi(double theta_o, void *arg)
{
    alb_t *a = arg;
    gsl_function fn = {integrand, a};
    double r = 0.0;
    double err = 0.0;
    a->theta_o = theta_o;
    a->cos_sin_o = cos(theta_o) * sin(theta_o);
    /* the mirror: phi_s = 0 */
    a->n_in = breaks(0.0, 0.0, BF__PI, inner_w0(a->w, a->theta_i, theta_o),
                     a->pts_in);
    if (!accepted(qag_pieces(&fn, a->pts_in, a->n_in, ALB_EPSABS_IN,
                             ALB_EPSREL_IN, a->inner, &r, &err),
                  r, err, ALB_ACCEPT_IN)) {
        a->failed = 1;
    }
    return 2.0 * r;
}

static int params_ok(const bf_model_type *type, const double *param)
{
    size_t j;
    if ((type->p > 0) && (param == NULL)) {
        return 0;
    }
    for (j = 0; j < type->p; j++) {
        if (!isfinite(param[j]) || (param[j] < type->param[j].min)
            || (param[j] > type->param[j].max)) {
            return 0;
        }
    }
    return 1;
}

int bf_model_albedo(const bf_model_type *type, const double *param,
                    double theta_i, double *albedo)
{
    alb_t a;
    gsl_integration_workspace *outer;
    gsl_function fn;
    double pts_out[ALB_MAXPTS];
    size_t n_out;
    double err = 0.0;
    double r = 0.0;
    int st;
    if ((type == NULL) || (albedo == NULL) || (type->eval == NULL)
        || (type->kind != BF_MODEL_SPECULAR) || !params_ok(type, param)
        || !(theta_i >= 0.0) || !(theta_i < BF__PI_2)) {
        return BF_EINVAL;
    }
    a.type = type;
    a.param = param;
    a.theta_i = theta_i;
    a.theta_o = 0.0;
    a.failed = 0;
    a.work = (type->work_size > 0)
                 ? bf__alloc_lines(type->work_size)
                 : NULL;
    a.inner = gsl_integration_workspace_alloc(ALB_LIMIT);
    outer = gsl_integration_workspace_alloc(ALB_LIMIT);
    if ((a.inner == NULL) || (outer == NULL)
        || ((type->work_size > 0) && (a.work == NULL))) {
        gsl_integration_workspace_free(a.inner);
        gsl_integration_workspace_free(outer);
        free(a.work);
        return BF_ENOMEM;
    }
    a.w = lobe_width(&a);
    n_out = breaks(0.0, theta_i, BF__PI_2, a.w, pts_out); /* to = ti */
    fn.function = over_phi;
    fn.params = &a;
    st = accepted(qag_pieces(&fn, pts_out, n_out, ALB_EPSABS_OUT,
                             ALB_EPSREL_OUT, outer, &r, &err),
                  r, err, ALB_ACCEPT_OUT)
             ? GSL_SUCCESS
             : GSL_FAILURE;
    gsl_integration_workspace_free(a.inner);
    gsl_integration_workspace_free(outer);
    free(a.work);
    *albedo = r;
    return ((st != GSL_SUCCESS) || a.failed) ? BF_EDOM : BF_OK;
}
