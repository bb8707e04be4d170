/* wnor_ref.h: WNO-R's facet integral by GSL's adaptive quadrature, written
 * from the model's references (src/models/wno_r.c [1]-[4]) independently
 * of the library's rule: nested qagp (theta_a outside, phi_a inside) with
 * the kinks of the integrand as break points, the Fresnel reflectance in
 * its textbook sin/tan form (Born & Wolf §1.5) rather than the library's
 * rearranged one. Shared by tests/models/test_wno_r.c and
 * bench/bench_wnor.c (static functions: one copy per program). */
#ifndef BF_TESTS_WNOR_REF_H
#define BF_TESTS_WNOR_REF_H

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#define WREF_PI 3.14159265358979323846
#define WREF_PI_2 1.57079632679489661923
#define WREF_LIMIT 2000

/* Unpolarised Fresnel reflectance from air into index n at incidence x
 * (cos x = c > 0), textbook form: 1/2 [sin^2(x - t)/sin^2(x + t)
 * + tan^2(x - t)/tan^2(x + t)], sin t = sin x / n. */
static double wref_fresnel(double c, double n)
{
    double x = acos(c);
    double t;
    double a;
    double b;
    if (n == 1.0) {
        return 0.0;
    }
    if (x < 1e-8) {
        return ((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0));
    }
    t = asin(sin(x) / n);
    a = sin(x - t) / sin(x + t);
    b = tan(x - t) / tan(x + t);
    return 0.5 * ((a * a) + (b * b));
}

typedef struct {
    double l[3], v[3];
    double m[5][3]; /* the kink circles' poles */
    double sigma, n;
    double theta; /* current theta_a of the outer integral */
    double epsrel_in;
    int worst;    /* the worst inner status: GSL_SUCCESS, or the last other */
    double worst_err; /* the largest inner error estimate */
    double max_r;     /* the largest inner value */
    gsl_integration_workspace *inner;
} wref_ctx;

/* Integrand in phi_a: P is applied by the outer integral. */
static double wref_phi(double ph, void *arg)
{
    const wref_ctx *c = arg;
    double a[3] = {sin(c->theta) * cos(ph), sin(c->theta) * sin(ph),
                   cos(c->theta)};
    double al = a[0] * c->l[0] + a[1] * c->l[1] + a[2] * c->l[2];
    double av = a[0] * c->v[0] + a[1] * c->v[1] + a[2] * c->v[2];
    double g;
    double lf;
    if (al <= 0.0 || av <= 0.0) {
        return 0.0;
    }
    /* Torrance-Sparrow V-cavity masking and shadowing; at grazing view
     * the limit of <a,v> G / <v,n> is 2 <a,n> */
    if (c->v[2] <= 0.0) {
        lf = al * (1.0 - wref_fresnel(al, c->n)) *
             (1.0 - wref_fresnel(av, c->n));
        return lf * 2.0;
    }
    g = fmin(1.0, fmin(2.0 * a[2] * c->v[2] / av, 2.0 * a[2] * c->l[2] / al));
    lf = al * (1.0 - wref_fresnel(al, c->n)) * (1.0 - wref_fresnel(av, c->n));
    /* projected radiance L_f <a,v> G / (<a,n> <v,n>) */
    return lf * av * g / (a[2] * c->v[2]);
}

static int wref_cmp(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorts pts[0..np) and drops points within 1e-12 of the one before (qagp
 * fails on an empty interval): the count left. */
static size_t wref_sort_unique(double *pts, size_t np)
{
    size_t kept = 1;
    size_t i;
    qsort(pts, np, sizeof *pts, wref_cmp);
    for (i = 1; i < np; i++) {
        if (pts[i] - pts[kept - 1] > 1e-12) {
            pts[kept++] = pts[i];
        }
    }
    pts[kept - 1] = pts[np - 1]; /* the last point stays the end */
    return kept;
}

/* The azimuths in [0, 2 pi] where the ring of facets at tilt th crosses a
 * kink of the integrand, with 0 and 2 pi, sorted (the points of GSL's
 * qagp). The kinks lie on great circles <a,m> = 0: m = l, v (a facet
 * turns unlit or unseen), 2 <v,n> n - v and 2 <l,n> n - l (a masking or
 * shadowing term of G reaches 1), <v,n> l - <l,n> v (the two terms
 * cross). Without them an adaptive rule can miss a lit and visible
 * interval of the ring altogether: at theta_i = 1.358, theta_s = 1.150,
 * phi_s = 0.475, n = 1.2 and tilt 0.85, qags on [0, 2 pi] reports success
 * with an error estimate of 4e-15 and is 1.3e-4 off. */
static size_t wref_ring_kinks(const wref_ctx *c, double th, double *pts)
{
    size_t np = 0;
    size_t i;
    pts[np++] = 0.0;
    pts[np++] = 2.0 * WREF_PI;
    for (i = 0; i < 5; i++) {
        /* sin th (mx cos ph + my sin ph) + cos th mz = 0 */
        const double *m = c->m[i];
        double r = hypot(m[0], m[1]);
        double q = r > 0.0 ? -cos(th) * m[2] / (sin(th) * r) : 2.0;
        if (fabs(q) < 1.0) {
            double psi = atan2(m[1], m[0]);
            pts[np++] = fmod(psi + acos(q) + 4.0 * WREF_PI, 2.0 * WREF_PI);
            pts[np++] = fmod(psi - acos(q) + 4.0 * WREF_PI, 2.0 * WREF_PI);
        }
    }
    return wref_sort_unique(pts, np);
}

static double wref_theta(double th, void *arg)
{
    wref_ctx *c = arg;
    gsl_function f = {wref_phi, c};
    double r;
    double e;
    int st;
    double pts[12];
    size_t np = wref_ring_kinks(c, th, pts);
    c->theta = th;
    st = gsl_integration_qagp(&f, pts, np, 0.0, c->epsrel_in, WREF_LIMIT,
                              c->inner, &r, &e);
    if (st != GSL_SUCCESS) {
        c->worst = st;
    }
    c->worst_err = fmax(c->worst_err, e);
    c->max_r = fmax(c->max_r, fabs(r));
    return exp(-(th * th) / (2.0 * c->sigma * c->sigma)) * sin(th) * r;
}

static double wref_norm(double th, void *arg)
{
    const wref_ctx *c = arg;
    return exp(-(th * th) / (2.0 * c->sigma * c->sigma)) * sin(th) * 2.0 *
           WREF_PI;
}

/* The tilts where the theta_a integrand is not smooth, inside (0, top),
 * with 0 and top, sorted: where a kink circle touches the ring (pi/2 -
 * theta_i, pi/2 - theta_s) and where two of them cross. */
static size_t wref_theta_points(const wref_ctx *c, double top, double *pts)
{
    double cand[16];
    size_t nc = 0;
    size_t np = 0;
    size_t i;
    size_t j;
    cand[nc++] = asin(c->l[2]);
    cand[nc++] = asin(c->v[2]);
    for (i = 0; i < 5; i++) {
        for (j = i + 1; j < 5; j++) {
            const double *a = c->m[i];
            const double *b = c->m[j];
            double x[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]};
            double h = hypot(x[0], x[1]);
            if (hypot(h, x[2]) > 1e-12) {
                cand[nc++] = atan2(h, fabs(x[2]));
            }
        }
    }
    pts[np++] = 0.0;
    for (i = 0; i < nc; i++) {
        if (cand[i] > 1e-9 && cand[i] < top - 1e-9) {
            pts[np++] = cand[i];
        }
    }
    pts[np++] = top;
    return wref_sort_unique(pts, np);
}

/* The WNO-R integral at (theta_i, theta_s, phi_s) (Beckmann's frame: the
 * source at azimuth pi) by nested qagp, normalised by the integral of P
 * over the hemisphere; relative tolerances epsrel_out (theta_a) and
 * epsrel_in (phi_a). *status: the worst GSL status met (GSL_SUCCESS when
 * every integral converged), *err: the outer error estimate relative to
 * the value, or the largest inner one relative to the largest inner value
 * if larger. */
static double wref_value(double ti, double ts, double ps, double sigma,
                         double n, double epsrel_out, double epsrel_in,
                         int *status, double *err)
{
    wref_ctx c = {{-sin(ti), 0.0, cos(ti)},
                  {sin(ts) * cos(ps), sin(ts) * sin(ps), cos(ts)},
                  {{0.0}},
                  sigma, n, 0.0, epsrel_in, GSL_SUCCESS, 0.0, 0.0, NULL};
    gsl_integration_workspace *outer =
        gsl_integration_workspace_alloc(WREF_LIMIT);
    gsl_function f = {wref_theta, &c};
    gsl_function fn = {wref_norm, &c};
    /* P is below e^-72 of its peak beyond 12 sigma: the integrals stop
     * there, so that a narrow distribution is not missed */
    double top = fmin(WREF_PI_2, 12.0 * sigma);
    double pts[20];
    size_t np;
    double num = 0.0;
    double den = 1.0;
    double e = 0.0;
    double en = 0.0;
    int st;
    int stn;
    size_t i;
    const double *l = c.l;
    const double *v = c.v;
    double m[5][3] = {{l[0], l[1], l[2]},
                      {v[0], v[1], v[2]},
                      {-v[0], -v[1], v[2]},
                      {-l[0], -l[1], l[2]},
                      {v[2] * l[0] - l[2] * v[0], v[2] * l[1] - l[2] * v[1],
                       0.0}};
    for (i = 0; i < 5; i++) {
        c.m[i][0] = m[i][0];
        c.m[i][1] = m[i][1];
        c.m[i][2] = m[i][2];
    }
    gsl_set_error_handler_off(); /* statuses are returned */
    c.inner = gsl_integration_workspace_alloc(WREF_LIMIT);
    if (outer == NULL || c.inner == NULL) {
        *status = GSL_ENOMEM;
        *err = INFINITY;
        return NAN;
    }
    np = wref_theta_points(&c, top, pts);
    if (ti >= WREF_PI_2) {
        st = GSL_SUCCESS; /* no light: the value is 0 */
    } else {
        st = gsl_integration_qagp(&f, pts, np, 0.0, epsrel_out, WREF_LIMIT,
                                  outer, &num, &e);
    }
    stn = gsl_integration_qag(&fn, 0.0, top, 0.0, 1e-13, WREF_LIMIT,
                              GSL_INTEG_GAUSS21, outer, &den, &en);
    gsl_integration_workspace_free(c.inner);
    gsl_integration_workspace_free(outer);
    *status = st != GSL_SUCCESS ? st : (stn != GSL_SUCCESS ? stn : c.worst);
    *err = fmax(num != 0.0 ? e / fabs(num) : e,
                c.max_r > 0.0 ? c.worst_err / c.max_r : 0.0);
    return num / den;
}

#endif
