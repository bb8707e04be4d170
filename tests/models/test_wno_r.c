/* test_wno_r.c: WNO-R, the rough-surface Wolff-Nayar-Oren model -- a
 * V-cavity surface of WNO facets evaluated by quadrature
 * (src/models/wolff_nayar_oren.c, doc/methods.md §7).
 *
 * Independent values: the facet integral is computed here a second way,
 * with GSL's adaptive quadrature (QAG in phi_a inside QAG in theta_a) of
 * the integrand written from its references, the Fresnel reflectance in its
 * textbook sin/tan form (Born & Wolf §1.5) rather than the library's
 * rearranged one. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

static double wnor(double ti, double ts, double ps, double sigma, double n)
{
    bf_geom g = {ti, PI, ts, ps};
    double p[2] = {sigma, n};
    double out = NAN;
    cr_assert_eq(bf_model_eval(bf_model_wno_r, p, 1, &g, &out), BF_OK);
    return out;
}

static double wno(double ti, double ts, double ps, double n)
{
    bf_geom g = {ti, PI, ts, ps};
    double out = NAN;
    cr_assert_eq(bf_model_eval(bf_model_wno, &n, 1, &g, &out), BF_OK);
    return out;
}

/* ---- the reference integral ------------------------------------------- */

/* Unpolarised Fresnel reflectance from air into index n at incidence x
 * (cos x = c > 0), textbook form: 1/2 [sin^2(x - t)/sin^2(x + t)
 * + tan^2(x - t)/tan^2(x + t)], sin t = sin x / n. */
static double ref_fresnel(double c, double n)
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
    double sigma, n;
    double theta;   /* current theta_a of the outer integral */
    gsl_integration_workspace *inner;
} ref_ctx;

/* Integrand in phi_a: P is applied by the outer integral. */
static double ref_phi(double ph, void *arg)
{
    const ref_ctx *c = arg;
    double a[3] = {sin(c->theta) * cos(ph), sin(c->theta) * sin(ph),
                   cos(c->theta)};
    double al = a[0] * c->l[0] + a[1] * c->l[1] + a[2] * c->l[2];
    double av = a[0] * c->v[0] + a[1] * c->v[1] + a[2] * c->v[2];
    double g;
    double lf;
    if (al <= 0.0 || av <= 0.0) {
        return 0.0;
    }
    /* Torrance-Sparrow V-cavity masking and shadowing */
    g = fmin(1.0, fmin(2.0 * a[2] * c->v[2] / av, 2.0 * a[2] * c->l[2] / al));
    lf = al * (1.0 - ref_fresnel(al, c->n)) * (1.0 - ref_fresnel(av, c->n));
    /* projected radiance L_f <a,v> G / (<a,n> <v,n>) */
    return lf * av * g / (a[2] * c->v[2]);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
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
static size_t ring_kinks(const ref_ctx *c, double th, double *pts)
{
    const double *l = c->l;
    const double *v = c->v;
    double m[5][3] = {{l[0], l[1], l[2]},
                      {v[0], v[1], v[2]},
                      {-v[0], -v[1], v[2]},
                      {-l[0], -l[1], l[2]},
                      {v[2] * l[0] - l[2] * v[0], v[2] * l[1] - l[2] * v[1],
                       0.0}};
    size_t np = 0;
    size_t i;
    pts[np++] = 0.0;
    pts[np++] = 2.0 * PI;
    for (i = 0; i < 5; i++) {
        /* sin th (mx cos ph + my sin ph) + cos th mz = 0 */
        double r = hypot(m[i][0], m[i][1]);
        double q = r > 0.0 ? -cos(th) * m[i][2] / (sin(th) * r) : 2.0;
        if (fabs(q) < 1.0) {
            double psi = atan2(m[i][1], m[i][0]);
            pts[np++] = fmod(psi + acos(q) + 4.0 * PI, 2.0 * PI);
            pts[np++] = fmod(psi - acos(q) + 4.0 * PI, 2.0 * PI);
        }
    }
    qsort(pts, np, sizeof *pts, cmp_double);
    return np;
}

static double ref_theta(double th, void *arg)
{
    ref_ctx *c = arg;
    gsl_function f = {ref_phi, c};
    double r;
    double e;
    int st;
    double pts[12];
    size_t np = ring_kinks(c, th, pts);
    c->theta = th;
    /* GSL may report that roundoff limits the last digits; its error
     * estimate must stay 10 times below the 1e-3 the test checks */
    st = gsl_integration_qagp(&f, pts, np, 1e-12, 1e-7, 1000, c->inner, &r,
                              &e);
    cr_assert(st == GSL_SUCCESS ||
                  (st == GSL_EROUND && e <= 1e-4 * fabs(r) + 1e-12),
              "inner quadrature: %s, value %g, error %g", gsl_strerror(st),
              r, e);
    return exp(-(th * th) / (2.0 * c->sigma * c->sigma)) * sin(th) * r;
}

static double ref_norm(double th, void *arg)
{
    const ref_ctx *c = arg;
    return exp(-(th * th) / (2.0 * c->sigma * c->sigma)) * sin(th) * 2.0 * PI;
}

/* The WNO-R integral by nested adaptive quadrature, normalised by the
 * integral of P over the hemisphere. */
static double reference(double ti, double ts, double ps, double sigma,
                        double n)
{
    ref_ctx c = {{-sin(ti), 0.0, cos(ti)},
                 {sin(ts) * cos(ps), sin(ts) * sin(ps), cos(ts)},
                 sigma, n, 0.0, NULL};
    gsl_integration_workspace *outer = gsl_integration_workspace_alloc(1000);
    gsl_function f = {ref_theta, &c};
    gsl_function fn = {ref_norm, &c};
    /* P is below e^-72 of its peak beyond 12 sigma: the integrals stop
     * there, so that a narrow distribution is not missed by the first
     * Gauss-Kronrod panel */
    double top = fmin(PI_2, 12.0 * sigma);
    double num;
    double den;
    double e;
    int st;
    gsl_set_error_handler_off(); /* statuses are checked */
    c.inner = gsl_integration_workspace_alloc(1000);
    cr_assert(outer != NULL && c.inner != NULL);
    st = gsl_integration_qag(&f, 0.0, top, 1e-12, 1e-6, 1000,
                             GSL_INTEG_GAUSS21, outer, &num, &e);
    cr_assert(st == GSL_SUCCESS || (st == GSL_EROUND && e <= 1e-4 * num),
              "outer quadrature: %s, error %g", gsl_strerror(st), e);
    cr_assert_eq(gsl_integration_qag(&fn, 0.0, top, 1e-14, 1e-12, 1000,
                                     GSL_INTEG_GAUSS21, outer, &den, &e),
                 GSL_SUCCESS);
    gsl_integration_workspace_free(c.inner);
    gsl_integration_workspace_free(outer);
    return num / den;
}

/* ---- tests ---------------------------------------------------------------- */

Test(wno_r, is_wno_for_a_surface_of_level_facets)
{
    /* sigma = 0 is WNO exactly; a tiny sigma tends to it (the quadrature
     * normalises P by its own rule) */
    bf_assert_rel(wnor(0.7313, 1.0219, 0.4, 0.0, 1.6271),
                  wno(0.7313, 1.0219, 0.4, 1.6271), TOL0);
    bf_assert_rel(wnor(0.7313, 1.0219, 0.4, 1e-5, 1.6271),
                  wno(0.7313, 1.0219, 0.4, 1.6271), 1e-8);
    bf_assert_rel(wnor(0.2, 1.3, 2.5, 1e-5, 2.2), wno(0.2, 1.3, 2.5, 2.2),
                  1e-8);
}

Test(wno_r, matches_the_integral_computed_by_adaptive_quadrature)
{
    /* The library's fixed rule (48 rings x 48 facets) against GSL's
     * adaptive one: within 1e-3 of the surface's value at normal incidence
     * and view (the scale
     * of a normalised curve) over CURET's range of geometry (zeniths up to
     * 1.46 rad), smooth to very rough surfaces, light and dense bodies. */
    static const double cases[][5] = {
        /* theta_i, theta_s, phi_s, sigma, n */
        {0.3, 0.3, PI, 0.1, 1.5},    {0.8, 0.8, PI, 0.3, 1.5},
        {1.2, 1.2, PI, 0.6, 1.7},    {0.5, 1.0, 0.0, 0.3, 1.7},
        {1.0, 0.5, 0.0, 1.0, 1.3},   {0.7, 0.7, PI_2, 0.45, 2.2},
        {1.3, 0.2, 2.0, 0.8, 1.6},   {0.0, 1.0, 0.0, 0.25, 1.5},
        {1.46, 1.46, 0.3, 0.5, 1.9}, {1.1, 1.4, 2.8, 1.5, 1.4},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const double *c = cases[i];
        double ref = reference(c[0], c[1], c[2], c[3], c[4]);
        double got = wnor(c[0], c[1], c[2], c[3], c[4]);
        /* the scale: the same surface at normal incidence and view */
        double scale = reference(0.0, 0.0, 0.0, c[3], c[4]);
        cr_assert(fabs(got - ref) <= 1e-3 * scale,
                  "case %zu: WNO-R %.8f, adaptive quadrature %.8f, scale %.4f",
                  i, got, ref, scale);
    }
}

Test(wno_r, resolves_narrow_slope_distributions_near_the_normal)
{
    /* sigma = 0.004: the weight lies within 0.05 rad of the normal, where
     * the rule's panels are narrow (widths doubling from pi/2^13) and no
     * facet is masked or turned away, so the integrand is smooth and the
     * rule is far more accurate than at rough surfaces: within 1e-6 of
     * the normal-incidence value of GSL's adaptive quadrature (measured
     * 3e-9; the rule with half its theta panels, doubling from pi/2^7, is
     * 1.5e-5 off here and fails). */
    double ref = reference(0.7, 0.9, 1.0, 0.004, 1.6);
    double scale = reference(0.0, 0.0, 0.0, 0.004, 1.6);
    double got = wnor(0.7, 0.9, 1.0, 0.004, 1.6);
    cr_assert(fabs(got - ref) <= 1e-6 * scale,
              "WNO-R %.10f, adaptive quadrature %.10f, scale %.6f", got, ref,
              scale);
}

Test(wno_r, has_the_moments_of_the_slope_distribution_where_nothing_is_masked)
{
    /* Lambertian facets (n = 1), near-normal light and view and a smooth
     * surface: every facet of weight is lit, visible and unmasked (G = 1),
     * so the integral is linear in the moments of P:
     *   L = [(lx vx + ly vy) E(sin^2 t / cos t) / 2 + lz vz E(cos t)] / vz
     * with E over the Gaussian slope-area distribution (1-D integrals). */
    double sigma = 0.05;
    double ti = 0.2;
    double ts = 0.25;
    double ps = 1.1;
    double l[3] = {-sin(ti), 0.0, cos(ti)};
    double v[3] = {sin(ts) * cos(ps), sin(ts) * sin(ps), cos(ts)};
    double m_sc = 0.0;
    double m_c = 0.0;
    double w = 0.0;
    double h = 1e-5;
    double t;
    double expect;
    /* E(.) by the midpoint rule on a fine grid (the Gaussian is negligible
     * beyond 12 sigma) */
    for (t = 0.5 * h; t < 12.0 * sigma; t += h) {
        double p = exp(-(t * t) / (2.0 * sigma * sigma)) * sin(t);
        w += p;
        m_sc += p * sin(t) * sin(t) / cos(t);
        m_c += p * cos(t);
    }
    expect = ((l[0] * v[0] + l[1] * v[1]) * 0.5 * (m_sc / w)
              + l[2] * v[2] * (m_c / w))
             / v[2];
    bf_assert_rel(wnor(ti, ts, ps, sigma, 1.0), expect, 1e-6);
}

Test(wno_r, with_lambertian_facets_approaches_oren_nayar_direct_term)
{
    /* n = 1 makes the facets Lambertian: the surface of Oren & Nayar, whose
     * qualitative model (SPEC §5, L1 without the interreflection L2) is a
     * fit to this integral. Over CURET's range of geometry its error is a
     * few per cent of the normal-incidence value: rms <= 0.025, and the
     * backscatter rise and forward fall have the right sign. */
    static const double sig[] = {0.1, 0.2, 0.4, 0.7, 1.0};
    size_t s;
    for (s = 0; s < sizeof sig / sizeof sig[0]; s++) {
        double ss2 = sig[s] * sig[s];
        double c1 = 1.0 - 0.5 * ss2 / (ss2 + 0.33);
        double sum = 0.0;
        int count = 0;
        double ti;
        for (ti = 0.1; ti < 1.45; ti += 0.2) {
            double ts;
            for (ts = 0.1; ts < 1.45; ts += 0.2) {
                double ps;
                for (ps = 0.0; ps < 3.2; ps += 0.785) {
                    double a = fmax(ti, ts);
                    double b = fmin(ti, ts);
                    double cd = -cos(ps); /* SPEC §5: sample frame */
                    double c2 = 0.45 * ss2 / (ss2 + 0.09)
                                * (cd >= 0.0 ? sin(a)
                                             : sin(a) - pow(2.0 * b / PI, 3));
                    double c3 = 0.125 * ss2 / (ss2 + 0.09)
                                * pow(4.0 * a * b / (PI * PI), 2);
                    double l1 = cos(ti)
                                * (c1 + cd * c2 * tan(b)
                                   + (1.0 - fabs(cd)) * c3 * tan((a + b) / 2));
                    double d = wnor(ti, ts, ps, sig[s], 1.0) - l1;
                    sum += d * d;
                    count++;
                }
            }
        }
        cr_assert(sqrt(sum / count) <= 0.025, "sigma %.2f: rms %.4f", sig[s],
                  sqrt(sum / count));
    }
    /* rough: brighter towards the source than Lambert, darker forward */
    cr_assert(wnor(0.8, 0.8, PI, 0.5, 1.0) > cos(0.8));
    cr_assert(wnor(0.5, 1.0, 0.0, 0.5, 1.0) < cos(0.5));
}

Test(wno_r, obeys_reciprocity_and_isotropy)
{
    /* Helmholtz: L / cos(theta_i) is symmetric in light and view. The
     * integrand is, and the rule is turned to the geometry symmetrically
     * in l and v, so the swapped configuration is integrated on the same
     * nodes: equal to rounding. So is the mirror image phi_s -> -phi_s. */
    double a = wnor(0.7313, 1.0219, 0.4, 0.35, 1.6271) / cos(0.7313);
    double b = wnor(1.0219, 0.7313, 0.4, 0.35, 1.6271) / cos(1.0219);
    bf_assert_rel(a, b, TOL3);
    bf_assert_rel(wnor(0.3, 1.2, 3.0, 0.9, 1.4) / cos(0.3),
                  wnor(1.2, 0.3, 3.0, 0.9, 1.4) / cos(1.2), TOL3);
    bf_assert_rel(wnor(0.7313, 1.0219, 0.4, 0.35, 1.6271),
                  wnor(0.7313, 1.0219, -0.4, 0.35, 1.6271), TOL3);
}

Test(wno_r, darkens_at_grazing_view_less_than_the_smooth_surface_does)
{
    /* The smooth surface's view transmittance vanishes at grazing view;
     * tilted facets still see the viewer at a finite angle, so the rough
     * surface keeps a finite radiance there -- its grazing limit, taken
     * exactly (2 <a,n> for every visible facet), continuous with the
     * values just inside. */
    double edge = wnor(0.5, PI_2, 0.0, 0.4, 1.7);
    double inside = wnor(0.5, PI_2 - 1e-7, 0.0, 0.4, 1.7);
    cr_assert(wno(0.5, PI_2, 0.0, 1.7) < 1e-12);
    cr_assert(edge > 0.05, "grazing-view value %g", edge);
    bf_assert_rel(inside, edge, 1e-5);
    cr_assert(isfinite(edge));
}

Test(wno_r, vanishes_at_grazing_incidence)
{
    cr_assert_eq(wnor(PI_2, 0.3, 0.0, 0.5, 1.5), 0.0);
    cr_assert(wnor(PI_2 - 1e-6, 0.3, 0.0, 0.5, 1.5) < 1e-5);
}

Test(wno_r, rejects_parameters_outside_the_domain)
{
    bf_geom g = {0.3, PI, 0.4, 0.0};
    double out = 0.0;
    double p1[2] = {-0.01, 1.5};
    double p2[2] = {0.3, 0.99};
    double p3[2] = {1.6, 1.5};
    cr_assert_eq(bf_model_eval(bf_model_wno_r, p1, 1, &g, &out), BF_EINVAL);
    cr_assert(isnan(out));
    cr_assert_eq(bf_model_eval(bf_model_wno_r, p2, 1, &g, &out), BF_EINVAL);
    cr_assert_eq(bf_model_eval(bf_model_wno_r, p3, 1, &g, &out), BF_EINVAL);
}

Test(wno_r, fits_its_own_curve_back_to_the_parameters)
{
    /* Round trip on CURET's 198 configurations: data synthesised from
     * WNO-R at (sigma, n) = (0.42, 1.63), normalised (SPEC §2); the grid
     * (step 0.05, 0.1) then GSL's refinement recover both parameters. */
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    double truth[2] = {0.42, 1.63};
    size_t n = bf_table_select(t, 90.0, sel);
    size_t k;
    bf_problem pb;
    bf_fit_result grid;
    bf_fit_result fit;
    bf_fit_workspace *w = bf_fit_alloc(n);
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    cr_assert_eq(bf_model_eval(bf_model_wno_r, truth, n, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    cr_assert_eq(bf_fit_grid(bf_model_wno_r, truth, 0, n, geom, data, w,
                             &grid),
                 BF_OK); /* fitted parameters: truth[] is not used */
    cr_assert_eq(bf_problem_init(&pb, bf_model_wno_r, NULL, n, geom, data),
                 BF_OK);
    cr_assert_eq(bf_fit_refine(&pb, &grid, &fit), BF_OK);
    bf_assert_abs(fit.param[0], truth[0], 1e-4);
    bf_assert_abs(fit.param[1], truth[1], 1e-4);
    cr_assert(fit.lse < 1e-10, "LSE at the optimum %g", fit.lse);
    bf_fit_free(w);
    bf_table_free(t);
}

Test(wno_r, uses_gsls_gauss_legendre_rule_bit_for_bit)
{
    /* the rule's 4-point Gauss-Legendre table is GSL's (no allocation per
     * evaluation, the same nodes) */
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(4);
    const double *x;
    const double *w;
    size_t i;
    cr_assert_not_null(t);
    bf__wnor_gl4(&x, &w);
    for (i = 0; i < 2; i++) {
        cr_assert_eq(x[i], t->x[i]);
        cr_assert_eq(w[i], t->w[i]);
    }
    gsl_integration_glfixed_table_free(t);
}

Test(wno_r, is_smooth_in_sigma)
{
    /* The rule's nodes do not move with sigma: second differences of the
     * value in sigma at steps h follow the curvature (h^2 scaling), with no
     * jumps where a moving node would cross a masking edge (the former
     * sigma-scaled rule jumped by up to 1e-5 below sigma = pi/12). Grazing
     * geometry, where masking acts: the second difference at h = 1e-4,
     * scaled by 1/h^2, agrees with the one at h = 1e-3 to 1%. */
    static const double s0[] = {0.031, 0.097, 0.183, 0.241};
    size_t i;
    for (i = 0; i < sizeof s0 / sizeof s0[0]; i++) {
        double h1 = 1e-3;
        double h2 = 1e-4;
        double c1 = (wnor(1.35, 1.42, 0.4, s0[i] + h1, 1.6) -
                     2.0 * wnor(1.35, 1.42, 0.4, s0[i], 1.6) +
                     wnor(1.35, 1.42, 0.4, s0[i] - h1, 1.6)) / (h1 * h1);
        double c2 = (wnor(1.35, 1.42, 0.4, s0[i] + h2, 1.6) -
                     2.0 * wnor(1.35, 1.42, 0.4, s0[i], 1.6) +
                     wnor(1.35, 1.42, 0.4, s0[i] - h2, 1.6)) / (h2 * h2);
        cr_assert(fabs(c1 - c2) <= 0.01 * fabs(c1) + 1e-6,
                  "sigma %.3f: %g against %g", s0[i], c1, c2);
    }
}

Test(wno_r, the_engines_evaluation_is_the_quadrature_to_rounding)
{
    /* The engine evaluates the ring sums of the rule through their
     * Chebyshev series in n (src/models/wno_r.c): its normalised curves
     * on CURET's 198 configurations equal those of the reference path
     * (bf_model_eval: the sums themselves) to 4e-15 at 40 random (sigma,
     * n), n over the panels and below them (1.05: exact sums). */
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    bf_geom g[BF_CURET_NCONF];
    double zero[BF_CURET_NCONF] = {0.0};
    double a[BF_CURET_NCONF];
    double b[BF_CURET_NCONF];
    size_t n = bf_table_select(t, PI, sel);
    bf_problem pb;
    size_t k;
    int r;
    unsigned seed = 20240611u;
    for (k = 0; k < n; k++) {
        g[k] = bf_table_geom(t, sel[k]);
    }
    bf_table_free(t);
    cr_assert_eq(bf_problem_init(&pb, bf_model_wno_r, NULL, n, g, zero),
                 BF_OK);
    for (r = 0; r < 40; r++) {
        double p[2];
        seed = seed * 1103515245u + 12345u;
        p[0] = (r % 4 == 0 ? 0.01 : 1.5) * (double)(seed >> 8) / 16777216.0;
        seed = seed * 1103515245u + 12345u;
        p[1] = r == 0 ? 1.05 : 1.15 + 3.0 * (double)(seed >> 8) / 16777216.0;
        /* the engine: residuals against zero data are the curve */
        cr_assert_eq(bf_problem_residuals(&pb, p, NULL, a), BF_OK);
        cr_assert_eq(bf_model_eval(bf_model_wno_r, p, n, g, b), BF_OK);
        cr_assert_eq(bf_normalise(n, b, b), BF_OK);
        for (k = 0; k < n; k++) {
            bf_assert_abs(a[k], b[k], 4e-15);
        }
    }
}
