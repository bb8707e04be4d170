/* test_wno_r.c: WNO-R, the rough-surface Wolff-Nayar-Oren model -- a
 * V-cavity surface of WNO facets evaluated by quadrature
 * (src/models/wolff_nayar_oren.c, doc/methods.md §7).
 *
 * Independent values: the facet integral is computed here a second way,
 * with GSL's adaptive quadrature (tests/models/wnor_ref.h: nested qagp
 * with the integrand's kinks as break points) of the integrand written
 * from its references, the Fresnel reflectance in its textbook sin/tan
 * form (Born & Wolf §1.5) rather than the library's rearranged one. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#include "fit/engine.h"
#include "internal.h"
#include "models/wno_r_rule.h"
#include "support.h"
#include "wnor_ref.h"

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

/* The WNO-R integral by GSL's nested qagp (tests/models/wnor_ref.h): the
 * outer and inner relative tolerances 1e-12 and 1e-13. GSL may report
 * that roundoff limits the last digits of a ring (the rings of a few
 * facets near a visibility edge); its error estimates must stay 100 times
 * below the 1e-8 the tests check. */
static double reference(double ti, double ts, double ps, double sigma,
                        double n)
{
    int st;
    double e;
    double r = wref_value(ti, ts, ps, sigma, n, 1e-12, 1e-13, &st, &e);
    cr_assert(isfinite(r) && e <= 1e-10,
              "reference at (%g, %g, %g, %g, %g): %s, error %g", ti, ts, ps,
              sigma, n, gsl_strerror(st), e);
    return r;
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

Test(wno_r, matches_gsls_adaptive_quadrature_to_1e_8_of_the_value)
{
    /* The rule (bf_model_eval) against GSL's nested qagp, relative to the
     * value itself, at CURET configurations (theta_i, theta_s, phi_s as
     * table.txt gives them) chosen for their kinks -- the plane of
     * incidence (every kink circle through one point of the horizon), a
     * view 1e-6 rad off the normal (a tangency 1e-6 below pi/2), grazing
     * (83.9 degrees, CURET's largest), theta_i and theta_s equal to 6
     * digits (two tangencies 1e-6 apart), normal incidence -- at the fit
     * grid's extremes of sigma (0.05 and 1.55; pi/2, the model's bound)
     * and of n (1.2, 2.5), a narrow distribution (0.004) and values
     * between the grid's. Measured: within 2e-9 on all 198 of CURET's used
     * configurations (bench/RESULTS.md); the former rule (12 theta-panels
     * x 4 points x 48 azimuths) is 7e-3 off, this rule with half its
     * points (6 per piece) 9e-6: both fail here. */
    static const double geo[][3] = {
        {1.178098, 0.785399, 3.1415926535897931}, /* plane of incidence */
        {0.392699, 1e-6, 3.4641020674186507e-07}, /* view 1e-6 off normal */
        {1.4640, 1.4640, 0.0000},                 /* grazing, specular */
        {1.4640, 0.4363, 2.6180},
        {0.589048, 0.589049, 1.5708},             /* tangencies 1e-6 apart */
        {0.0, 0.9817, 0.0},                       /* normal incidence */
        {0.9817, 1.2763, 1.0000},
    };
    static const double par[][2] = {
        {0.05, 1.2}, {1.55, 2.5}, {0.004, 1.6}, {0.3, 1.85},
        {0.9, 1.2}, {1.5707963267948966, 1.35}, {0.125, 2.5},
    };
    size_t i;
    size_t j;
    for (i = 0; i < sizeof geo / sizeof geo[0]; i++) {
        for (j = 0; j < sizeof par / sizeof par[0]; j++) {
            const double *g = geo[i];
            const double *p = par[j];
            double ref = reference(g[0], g[1], g[2], p[0], p[1]);
            double got = wnor(g[0], g[1], g[2], p[0], p[1]);
            cr_assert(fabs(got - ref) <= 1e-8 * ref,
                      "(%g, %g, %g) sigma %g n %g: WNO-R %.12g, adaptive "
                      "quadrature %.12g, relative %.2e",
                      g[0], g[1], g[2], p[0], p[1], got, ref,
                      (got - ref) / ref);
        }
    }
}

Test(wno_r, resolves_narrow_slope_distributions_near_the_normal)
{
    /* sigma = 2e-4: the weight lies within 3e-3 rad of the normal, where
     * the rule's geometric panels (widths doubling from pi/2^14) resolve
     * it: within 1e-10 of GSL's adaptive quadrature. */
    double ref = reference(0.7, 0.9, 1.0, 2e-4, 1.6);
    double got = wnor(0.7, 0.9, 1.0, 2e-4, 1.6);
    cr_assert(fabs(got - ref) <= 1e-10 * ref,
              "WNO-R %.14f, adaptive quadrature %.14f", got, ref);
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

Test(wno_r, is_finite_and_non_negative_over_the_hemisphere_and_domain)
{
    /* test_model_sweep.c's sweep on a coarser hemisphere (its rule costs
     * about 150 us a value): zeniths 0, steps of 15 degrees, pi/2 - 1e-6,
     * pi/2 - 1e-12, pi/2; azimuths in steps of 45 degrees; sigma and n at
     * their bounds, the grid's ends and inside */
    static const double sig[] = {0.0, 1e-9, 0.05, 0.6, 1.55,
                                 1.5707963267948966};
    static const double nn[] = {1.0, 1.2, 2.5, 10.0};
    double zen[16];
    size_t nz = 0;
    size_t a;
    size_t b;
    size_t c;
    size_t i;
    size_t j;
    for (i = 0; i * 15 < 90; i++) {
        zen[nz++] = (double)i * 15.0 * PI / 180.0;
    }
    zen[nz++] = PI_2 - 1e-6;
    zen[nz++] = PI_2 - 1e-12;
    zen[nz++] = PI_2;
    for (i = 0; i < sizeof sig / sizeof sig[0]; i++) {
        for (j = 0; j < sizeof nn / sizeof nn[0]; j++) {
            for (a = 0; a < nz; a++) {
                for (b = 0; b < nz; b++) {
                    for (c = 0; c <= 8; c++) {
                        double ps = -PI + (double)c * PI / 4.0;
                        double v = wnor(zen[a], zen[b], ps, sig[i], nn[j]);
                        cr_assert(isfinite(v) && v >= 0.0,
                                  "(%.17g, %.17g, %g) sigma %g n %g: %g",
                                  zen[a], zen[b], ps, sig[i], nn[j], v);
                    }
                }
            }
        }
    }
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
     * WNO-R's rule (bf_model_eval) at (sigma, n) = (0.42, 1.63),
     * normalised (SPEC §2); the engine's grid (step 0.05, 0.1; its
     * tables) then GSL's refinement recover both parameters. */
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
    bf_curves *curves;
    int status = BF_OK;
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    cr_assert_eq(bf_model_eval(bf_model_wno_r, truth, n, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    cr_assert_eq(bf_problem_init(&pb, bf_model_wno_r, NULL, n, geom, data),
                 BF_OK);
    /* the engine's grid and refinement (its tables, not the rule) */
    curves = bf_curves_alloc(&pb, &status);
    cr_assert_not_null(curves, "status %d", status);
    cr_assert_eq(bf_curves_best(curves, &pb, &grid), BF_OK);
    cr_assert_eq(bf_fit_refine(&pb, &grid, &fit), BF_OK);
    bf_assert_abs(fit.param[0], truth[0], 1e-4);
    bf_assert_abs(fit.param[1], truth[1], 1e-4);
    cr_assert(fit.lse < 1e-10, "LSE at the optimum %g", fit.lse);
    bf_curves_free(curves);
    bf_table_free(t);
}

Test(wno_r, uses_gsls_gauss_legendre_rule_bit_for_bit)
{
    /* the rule's 12-point Gauss-Legendre table is GSL's (no allocation per
     * evaluation, the same nodes) */
    gsl_integration_glfixed_table *t =
        gsl_integration_glfixed_table_alloc(WNOR_Q);
    const double *x;
    const double *w;
    size_t i;
    cr_assert_not_null(t);
    bf__wnor_gl(&x, &w);
    for (i = 0; i < WNOR_Q / 2; i++) { /* GSL holds the positive half */
        cr_assert_eq(x[WNOR_Q / 2 + i], t->x[i]);
        cr_assert_eq(x[WNOR_Q / 2 - 1 - i], -t->x[i]);
        cr_assert_eq(w[WNOR_Q / 2 + i], t->w[i]);
        cr_assert_eq(w[WNOR_Q / 2 - 1 - i], t->w[i]);
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

Test(wno_r, the_engines_tables_interpolate_the_rule_to_2e_10)
{
    /* The engine interpolates each configuration's value in (sigma, n)
     * from Chebyshev tables of the rule's values (src/models/wno_r.c):
     * on CURET's 198 configurations its normalised curves equal those of
     * the rule itself (bf_model_eval) to 2e-10 relative to each value
     * (measured 9e-11 over the fit's grids and their midpoints) at 40
     * random (sigma, n): sigma over (0, 1.5), a quarter of them below
     * 0.01 (the panel in sigma^2), n over both n-panels (1.15 to 4.15)
     * and below them (1.05: the rule itself). */
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    bf_geom g[BF_CURET_NCONF];
    double a[BF_CURET_NCONF];
    double b[BF_CURET_NCONF];
    size_t n = bf_table_select(t, PI, sel);
    bf__cset cs;
    bf__prep pm;
    void *work;
    size_t k;
    int r;
    unsigned seed = 20240611u;
    for (k = 0; k < n; k++) {
        g[k] = bf_table_geom(t, sel[k]);
    }
    bf_table_free(t);
    cr_assert_eq(bf__cset_init(&cs, n, g), BF_OK);
    cr_assert_eq(bf__prep_init(&pm, bf_model_wno_r, &cs), BF_OK);
    work = bf__work_alloc(&pm);
    cr_assert_not_null(work);
    for (r = 0; r < 40; r++) {
        double p[2];
        seed = seed * 1103515245u + 12345u;
        p[0] = (r % 4 == 0 ? 0.01 : 1.5) * (double)(seed >> 8) / 16777216.0;
        seed = seed * 1103515245u + 12345u;
        p[1] = r == 0 ? 1.05 : 1.15 + 3.0 * (double)(seed >> 8) / 16777216.0;
        cr_assert_eq(bf__curve(&pm, p, work, a), BF_OK);
        cr_assert_eq(bf_model_eval(bf_model_wno_r, p, n, g, b), BF_OK);
        cr_assert_eq(bf_normalise(n, b, b), BF_OK);
        for (k = 0; k < n; k++) {
            cr_assert(fabs(a[k] - b[k]) <= 2e-10 * b[k],
                      "sigma %g n %g configuration %zu: engine %.15g, rule "
                      "%.15g", p[0], p[1], k, a[k], b[k]);
        }
    }
    free(work);
    bf__prep_free(&pm);
    bf__cset_free(&cs);
}
