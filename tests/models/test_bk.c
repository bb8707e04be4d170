/* test_bk.c: tests of the Beckmann-Kirchhoff family BK-G, BK-E, VH-G, VH-E,
 * FC-G, FC-E (SPEC §3, §4.2).
 *
 * Independent references: the scattering vector formed from unit vectors
 * (Beckmann's wave vectors) instead of SPEC §3's trigonometric components;
 * the printed (P2) shape of the E form; the textbook Fresnel rs, rp; closed
 * forms at the specular direction and in the plane of incidence (derived in
 * the comments); literal values from tests/ref/models_ref.py. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846
#define PI_2 1.57079632679489661923

/* Sweep steps of the peak tests. */
#define SWEEP_NT 900 /* theta_s steps over [0, pi/2] */
#define SWEEP_NP 360 /* phi_s steps over (-pi, pi] */
#define STEP_T (PI_2 / SWEEP_NT)
#define STEP_P (2.0 * PI / SWEEP_NP)

/* Zenith angle i of n equal steps over [0, pi/2], exactly pi/2 at i = n
 * (n * (pi/2 / n) can round above pi/2, which bf_model_eval rejects). */
static double zenith(int i, int n)
{
    return (i >= n) ? PI_2 : (PI_2 * i / n);
}

static const bf_model_type *family(size_t i)
{
    const bf_model_type *t[6];
    t[0] = bf_model_bk_g;
    t[1] = bf_model_bk_e;
    t[2] = bf_model_vh_g;
    t[3] = bf_model_vh_e;
    t[4] = bf_model_fc_g;
    t[5] = bf_model_fc_e;
    return t[i];
}

/* Evaluates type at one configuration through the checked entry point. */
static double eval1(const bf_model_type *type, double m, double n, double ti,
                    double ts, double ps, int *rc)
{
    double p[2];
    double out;
    bf_geom g;
    int status;
    p[0] = m;
    p[1] = n;
    g.theta_i = ti;
    g.phi_i = PI;
    g.theta_s = ts;
    g.phi_s = ps;
    status = bf_model_eval(type, p, 1, &g, &out);
    if (rc != NULL) {
        *rc = status;
    } else {
        cr_assert_eq(status, BF_OK, "%s(%g, %g; %.17g, %.17g, %.17g): %d",
                     type->name, m, n, ti, ts, ps, status);
    }
    return out;
}

/* Textbook Fresnel reflectance (Born & Wolf §1.5), independent of
 * src/fresnel.c. */
static double fresnel_rs_rp(double a, double r)
{
    double st = sin(a) / r;
    double ci = cos(a);
    double ct = sqrt(1.0 - (st * st));
    double rs = (ci - (r * ct)) / (ci + (r * ct));
    double rp = (ct - (r * ci)) / (ct + (r * ci));
    return 0.5 * ((rs * rs) + (rp * rp));
}

/* The six models by the vector route: v = k1 - ks with k1 = -w_i (w_i the
 * unit vector towards the source at azimuth pi) and ks = w_s; F_BK's
 * numerator 1 + w_i.w_s; (P2) in its printed shape. out[0..5] in registry
 * order. */
static void family_by_vectors(double ti, double ts, double ps, double m,
                              double n, double out[6])
{
    double wi[3] = {sin(ti) * cos(PI), sin(ti) * sin(PI), cos(ti)};
    double ws[3] = {sin(ts) * cos(ps), sin(ts) * sin(ps), cos(ts)};
    double v[3];
    double dot = 0.0;
    double vxy2;
    double vz2;
    double f2[3];
    double g;
    double e;
    int i;
    for (i = 0; i < 3; i++) {
        v[i] = -wi[i] - ws[i];
        dot += wi[i] * ws[i];
    }
    vxy2 = (v[0] * v[0]) + (v[1] * v[1]);
    vz2 = v[2] * v[2];
    f2[0] = pow((1.0 + dot) / (wi[2] * (wi[2] + ws[2])), 2.0);
    f2[1] = wi[2];
    f2[2] = (1.0 - fresnel_rs_rp(ti, n))
            * (1.0 - fresnel_rs_rp(asin(sin(ts) / n), 1.0 / n)) * wi[2];
    g = 1.0 / (m * m) / vz2 * exp(-vxy2 / (4.0 * m * m * vz2));
    e = 2.0 / (m * m) / vz2 * pow(1.0 + (vxy2 / (m * m * vz2)), -1.5);
    for (i = 0; i < 3; i++) {
        out[2 * i] = f2[i] * g;
        out[(2 * i) + 1] = f2[i] * e;
    }
}

/* ====================================================================== */
/* values                                                                 */
/* ====================================================================== */

Test(bk, every_variant_matches_the_vector_route_at_high_entropy_geometry)
{
    static const double ps[] = {2.2619, 0.3512, -1.1937};
    /* tests/ref/models_ref.py, ti 0.7313, ts 1.0219, m 0.6173, n 1.7 */
    static const double lit[2][6] = {
        {2.5986908229827836, 1.3572048763733493, 0.55989153003408276,
         0.29241166670615776, 0.4588863925895928, 0.23966023361298358},
        {1.2868230014188331, 2.1217713750228651, 1.1678612882214616,
         1.925621976459458, 0.95717764039823572, 1.5782373457496881}};
    size_t j;
    size_t i;
    for (j = 0; j < sizeof ps / sizeof ps[0]; j++) {
        double ref[6];
        family_by_vectors(0.7313, 1.0219, ps[j], 0.6173, 1.7, ref);
        for (i = 0; i < 6; i++) {
            double val =
                eval1(family(i), 0.6173, 1.7, 0.7313, 1.0219, ps[j], NULL);
            bf_assert_rel(val, ref[i], TOL2);
            if (j < 2) {
                bf_assert_rel(val, lit[j][i], TOL2);
            }
        }
    }
}

Test(bk, specular_values_have_closed_forms)
{
    /* At ts = ti, ps = 0: vx = vy = 0, vz = -2 ci, and F_BK = (1 + ci^2 -
     * si^2)/(ci 2 ci) = 1. So G: F^2/(4 m^2 ci^2), E: F^2/(2 m^2 ci^2), with
     * F^2 = 1 (BK), ci (VH), T^2 ci (FC; T = 1 - f(ti, n), using the
     * reciprocity of SPEC §4.2 for the outgoing factor). */
    double ti = 0.7313;
    double m = 0.4127;
    double n = 1.7;
    double ci = cos(ti);
    double t = 1.0 - fresnel_rs_rp(ti, n);
    double m2 = m * m;
    bf_assert_rel(eval1(bf_model_bk_g, m, n, ti, ti, 0.0, NULL),
                  1.0 / (4.0 * m2 * ci * ci), TOL1);
    bf_assert_rel(eval1(bf_model_bk_e, m, n, ti, ti, 0.0, NULL),
                  1.0 / (2.0 * m2 * ci * ci), TOL1);
    bf_assert_rel(eval1(bf_model_vh_g, m, n, ti, ti, 0.0, NULL),
                  1.0 / (4.0 * m2 * ci), TOL1);
    bf_assert_rel(eval1(bf_model_vh_e, m, n, ti, ti, 0.0, NULL),
                  1.0 / (2.0 * m2 * ci), TOL1);
    bf_assert_rel(eval1(bf_model_fc_g, m, n, ti, ti, 0.0, NULL),
                  t * t / (4.0 * m2 * ci), TOL2);
    bf_assert_rel(eval1(bf_model_fc_e, m, n, ti, ti, 0.0, NULL),
                  t * t / (2.0 * m2 * ci), TOL2);
}

Test(bk, beckmann_factor_in_the_plane_of_incidence_has_a_closed_form)
{
    /* For ps = 0 and D = ti - ts, S = ti + ts: 1 + ci cs - si ss = 1 + cos S
     * = 2 cos^2(S/2), ci + cs = 2 cos(S/2) cos(D/2), so F_BK/|vz| =
     * 1/(2 ci cos^2(D/2)) and F_BK^2/vz^2 = (1 + t)^2/(4 ci^2) with
     * t = tan^2(D/2) = vx^2/vz^2 ((sin a - sin b)/(cos a + cos b) =
     * tan((a - b)/2)). Hence
     *   BK-G = (1 + t)^2 exp(-t/(4 m^2)) / (4 m^2 ci^2)
     *   BK-E = 2 (1 + t)^2 (1 + t/m^2)^(-3/2) / (4 m^2 ci^2). */
    static const double ts[] = {0.0, 0.2113, 0.7313, 1.1939, PI_2};
    double ti = 0.7313;
    double m = 0.5381;
    double ci = cos(ti);
    size_t j;
    for (j = 0; j < sizeof ts / sizeof ts[0]; j++) {
        double h = tan(0.5 * (ti - ts[j]));
        double t = h * h;
        double q = (1.0 + t) * (1.0 + t) / (4.0 * m * m * ci * ci);
        bf_assert_rel(eval1(bf_model_bk_g, m, 1.7, ti, ts[j], 0.0, NULL),
                      q * exp(-t / (4.0 * m * m)), TOL2);
        bf_assert_rel(eval1(bf_model_bk_e, m, 1.7, ti, ts[j], 0.0, NULL),
                      2.0 * q * pow(1.0 + (t / (m * m)), -1.5), TOL2);
    }
}

Test(bk, fresnel_correction_with_unit_index_reduces_to_vernold_harvey)
{
    int i;
    int j;
    int k;
    for (i = 0; i <= 10; i++) {
        for (j = 0; j <= 10; j++) {
            for (k = -6; k <= 6; k++) {
                double ti = 0.1517 * i;
                double ts = 0.1433 * j;
                double ps = 0.5171 * k;
                bf_assert_rel(
                    eval1(bf_model_fc_g, 0.7313, 1.0, ti, ts, ps, NULL),
                    eval1(bf_model_vh_g, 0.7313, 1.0, ti, ts, ps, NULL), TOL0);
                bf_assert_rel(
                    eval1(bf_model_fc_e, 0.7313, 1.0, ti, ts, ps, NULL),
                    eval1(bf_model_vh_e, 0.7313, 1.0, ti, ts, ps, NULL), TOL0);
            }
        }
    }
}

/* ====================================================================== */
/* symmetries                                                             */
/* ====================================================================== */

Test(bk, every_variant_is_isotropic_in_phi)
{
    size_t i;
    int a;
    int b;
    for (i = 0; i < 6; i++) {
        for (a = 0; a <= 8; a++) {
            for (b = 1; b <= 12; b++) {
                double ti = 0.1713 * a;
                double ts = 1.0219;
                double ps = 0.2617 * b;
                double l1 = eval1(family(i), 0.6173, 1.7, ti, ts, ps, NULL);
                double l2 = eval1(family(i), 0.6173, 1.7, ti, ts, -ps, NULL);
                bf_assert_rel(l2, l1, TOL0);
            }
        }
    }
}

Test(bk, the_scattering_kernel_is_reciprocal)
{
    /* vxy^2 = si^2 + ss^2 - 2 si ss cos ps and vz are symmetric under
     * i <-> s, so L / F^2 is reciprocal: L(i,s)/F^2(i,s) = L(s,i)/F^2(s,i),
     * with F_BK^2 ~ 1/(ci^2 (ci + cs)^2) (symmetric numerator), VH: ci,
     * FC: T(ti) T(ts) ci. So BK: L ci^2, VH and FC: L / ci are symmetric. */
    static const double cfg[][3] = {{0.7313, 1.0219, 2.2619},
                                    {0.2113, 1.3391, 0.3512},
                                    {1.4107, 0.5119, -2.9001},
                                    {0.0, 0.9137, 1.0}};
    size_t j;
    for (j = 0; j < sizeof cfg / sizeof cfg[0]; j++) {
        double ti = cfg[j][0];
        double ts = cfg[j][1];
        double ps = cfg[j][2];
        double ci = cos(ti);
        double cs = cos(ts);
        double m = 0.4931;
        bf_assert_rel(eval1(bf_model_bk_g, m, 1.7, ti, ts, ps, NULL) * ci * ci,
                      eval1(bf_model_bk_g, m, 1.7, ts, ti, ps, NULL) * cs * cs,
                      TOL2);
        bf_assert_rel(eval1(bf_model_bk_e, m, 1.7, ti, ts, ps, NULL) * ci * ci,
                      eval1(bf_model_bk_e, m, 1.7, ts, ti, ps, NULL) * cs * cs,
                      TOL2);
        bf_assert_rel(eval1(bf_model_vh_g, m, 1.7, ti, ts, ps, NULL) / ci,
                      eval1(bf_model_vh_g, m, 1.7, ts, ti, ps, NULL) / cs,
                      TOL2);
        bf_assert_rel(eval1(bf_model_vh_e, m, 1.7, ti, ts, ps, NULL) / ci,
                      eval1(bf_model_vh_e, m, 1.7, ts, ti, ps, NULL) / cs,
                      TOL2);
        bf_assert_rel(eval1(bf_model_fc_g, m, 1.7, ti, ts, ps, NULL) / ci,
                      eval1(bf_model_fc_g, m, 1.7, ts, ti, ps, NULL) / cs,
                      TOL2);
        bf_assert_rel(eval1(bf_model_fc_e, m, 1.7, ti, ts, ps, NULL) / ci,
                      eval1(bf_model_fc_e, m, 1.7, ts, ti, ps, NULL) / cs,
                      TOL2);
    }
}

/* ====================================================================== */
/* where the peak is                                                      */
/* ====================================================================== */

/* Sweeps theta_s in [0, pi/2] and phi_s in (-pi, pi]; returns the arg max. */
static void sweep_max(const bf_model_type *type, double m, double ti,
                      double *ts_max, double *ps_max)
{
    double best = -1.0;
    int i;
    int j;
    for (i = 0; i <= SWEEP_NT; i++) {
        for (j = 1; j <= SWEEP_NP; j++) {
            double ts = zenith(i, SWEEP_NT);
            double ps = -PI + (STEP_P * j);
            double v = eval1(type, m, 1.7, ti, ts, ps, NULL);
            if (v > best) {
                best = v;
                *ts_max = ts;
                *ps_max = ps;
            }
        }
    }
}

/* For BK the in-plane closed form above gives the peak exactly: with
 * t = tan^2((ti - ts)/2), d ln L/dt = 2/(1 + t) - 1/(4 m^2) (G) and
 * 2/(1 + t) - 3/(2 (m^2 + t)) (E, t <= 1 in the hemisphere). Both are < 0 for
 * all t >= 0 iff m < 1/sqrt(8) = 0.354 (G), resp. m < 1/sqrt(2) = 0.707 (E):
 * then the forward-plane maximum is exactly specular, for every ti (F_BK^2
 * cancels the 1/vz^2 tilt). The hemisphere sweep confirms it is the global
 * maximum. For rougher surfaces F_BK^2 (~1/ci^2 at grazing backscatter) wins
 * and the maximum leaves the specular direction (next test). */
Test(bk, original_beckmann_peaks_at_specular_below_the_slope_threshold)
{
    static const double ti[] = {0.3, 0.7313, 1.1};
    static const double m_g[] = {0.1, 0.2, 0.3};
    static const double m_e[] = {0.1, 0.3, 0.5};
    size_t a;
    size_t b;
    for (a = 0; a < sizeof ti / sizeof ti[0]; a++) {
        for (b = 0; b < 3; b++) {
            double ts;
            double ps;
            sweep_max(bf_model_bk_g, m_g[b], ti[a], &ts, &ps);
            cr_assert(fabs(ts - ti[a]) <= STEP_T && fabs(ps) <= STEP_P,
                      "BK-G m %g ti %g: max at ts %g ps %g", m_g[b], ti[a], ts,
                      ps);
            sweep_max(bf_model_bk_e, m_e[b], ti[a], &ts, &ps);
            cr_assert(fabs(ts - ti[a]) <= STEP_T && fabs(ps) <= STEP_P,
                      "BK-E m %g ti %g: max at ts %g ps %g", m_e[b], ti[a], ts,
                      ps);
        }
    }
}

Test(bk, original_beckmann_specular_stops_being_the_maximum_above_threshold)
{
    /* m = 0.4 > 1/sqrt(8): specular is a local minimum in t for BK-G. */
    double ti = 0.7313;
    double spec = eval1(bf_model_bk_g, 0.4, 1.7, ti, ti, 0.0, NULL);
    cr_assert(eval1(bf_model_bk_g, 0.4, 1.7, ti, ti + 0.05, 0.0, NULL) > spec);
    /* m = 0.3 < 1/sqrt(8): it is the maximum */
    spec = eval1(bf_model_bk_g, 0.3, 1.7, ti, ti, 0.0, NULL);
    cr_assert(eval1(bf_model_bk_g, 0.3, 1.7, ti, ti + 0.05, 0.0, NULL) < spec);
}

/* VH and FC do not peak at specular: their factor (cos ti, F_FC^2) does not
 * depend on theta_s (VH) or falls slowly (FC), so the 1/vz^2 = 1/(ci + cs)^2
 * prefactor tilts the lobe towards grazing -- the well-known off-specular
 * peak. What the physics does guarantee, and what is asserted:
 *   (1) at fixed ti, ts the value decreases with vxy^2 = si^2 + ss^2 -
 *       2 si ss cos ps, so the maximum is in the forward plane ps = 0;
 *   (2) in that plane the peak lies at or beyond specular, ts >= ti;
 *   (3) for a narrow lobe the shift matches the asymptote of the next
 *       test. */
Test(bk, vernold_harvey_and_fresnel_variants_peak_in_the_forward_plane)
{
    static const double ti[] = {0.3, 0.7313, 1.1};
    static const double m[] = {0.05, 0.3, 1.0, 5.0};
    size_t i;
    size_t a;
    size_t b;
    for (i = 2; i < 6; i++) {
        for (a = 0; a < sizeof ti / sizeof ti[0]; a++) {
            for (b = 0; b < sizeof m / sizeof m[0]; b++) {
                double ts;
                double ps;
                sweep_max(family(i), m[b], ti[a], &ts, &ps);
                cr_assert(fabs(ps) <= STEP_P / 2, "%s m %g ti %g: max at ps %g",
                          family(i)->name, m[b], ti[a], ps);
                cr_assert(ts >= ti[a] - STEP_T,
                          "%s m %g ti %g: max at ts %g before specular",
                          family(i)->name, m[b], ti[a], ts);
            }
        }
    }
}

Test(bk, vernold_harvey_gaussian_peak_shift_follows_its_asymptote)
{
    /* In the plane, with ts = ti + d: ln L = -2 ln(ci + cs) - (si - ss)^2 /
     * (4 m^2 (ci + cs)^2) + const ~ tan(ti) d - d^2/(16 m^2), maximal at
     * d = 8 m^2 tan ti (+ O(m^4)). m = 0.02, ti = 0.7313: d = 2.87e-3. */
    double ti = 0.7313;
    double m = 0.02;
    double d_pred = 8.0 * m * m * tan(ti);
    double best = -1.0;
    double d_best = 0.0;
    int i;
    for (i = 0; i <= 20000; i++) {
        double d = -0.005 + (1e-6 * i);
        double v = eval1(bf_model_vh_g, m, 1.7, ti, ti + d, 0.0, NULL);
        if (v > best) {
            best = v;
            d_best = d;
        }
    }
    bf_assert_rel(d_best, d_pred, 0.05);
}

/* ====================================================================== */
/* limits and domains                                                     */
/* ====================================================================== */

Test(bk, original_beckmann_is_a_domain_error_at_grazing_incidence)
{
    bf_geom g[3] = {{0.7313, PI, 1.0219, 2.2619},
                    {PI_2, PI, 1.0219, 2.2619},
                    {0.3, PI, PI_2, 0.0}};
    double p[1] = {0.6173};
    double out[3];
    cr_assert_eq(bf_model_eval(bf_model_bk_g, p, 3, g, out), BF_EDOM);
    cr_assert(isfinite(out[0]) && isnan(out[1]) && isfinite(out[2]));
    cr_assert_eq(bf_model_eval(bf_model_bk_e, p, 3, g, out), BF_EDOM);
    cr_assert(isfinite(out[0]) && isnan(out[1]) && isfinite(out[2]));
    /* no Inf just below grazing either: F_BK^2 ~ 1/ci^4 stays finite */
    cr_assert(isfinite(
        eval1(bf_model_bk_g, 1e-3, 1.7, PI_2 - 1e-15, PI_2, PI, NULL)));
}

Test(bk, vernold_harvey_and_fresnel_vanish_as_both_directions_graze)
{
    static const double ps_vh[] = {0.5, 2.2619, PI};
    static const double ps_fc[] = {0.0, 0.5, PI};
    int k;
    size_t j;
    for (j = 0; j < 3; j++) {
        for (k = 1; k <= 8; k++) {
            double th = PI_2 - pow(10.0, -k);
            double vg =
                eval1(bf_model_vh_g, 0.7313, 1.7, th, th, ps_vh[j], NULL);
            double ve =
                eval1(bf_model_vh_e, 0.7313, 1.7, th, th, ps_vh[j], NULL);
            double fg =
                eval1(bf_model_fc_g, 0.7313, 1.7, th, th, ps_fc[j], NULL);
            double fe =
                eval1(bf_model_fc_e, 0.7313, 1.7, th, th, ps_fc[j], NULL);
            cr_assert(isfinite(vg) && isfinite(ve) && isfinite(fg)
                      && isfinite(fe));
            if (k == 8) {
                cr_assert(vg < 1e-6 && ve < 1e-6 && fg < 1e-6 && fe < 1e-6,
                          "at 1e-8 from grazing: %g %g %g %g", vg, ve, fg, fe);
            }
        }
        bf_assert_abs(
            eval1(bf_model_vh_g, 0.7313, 1.7, PI_2, PI_2, ps_vh[j], NULL), 0.0,
            0.0);
        bf_assert_abs(
            eval1(bf_model_vh_e, 0.7313, 1.7, PI_2, PI_2, ps_vh[j], NULL), 0.0,
            0.0);
        bf_assert_abs(
            eval1(bf_model_fc_g, 0.7313, 1.7, PI_2, PI_2, ps_fc[j], NULL), 0.0,
            0.0);
        bf_assert_abs(
            eval1(bf_model_fc_e, 0.7313, 1.7, PI_2, PI_2, ps_fc[j], NULL), 0.0,
            0.0);
    }
}

Test(bk, vernold_harvey_diverges_along_the_grazing_specular_path)
{
    /* At specular VH-G = 1/(4 m^2 ci), VH-E = 1/(2 m^2 ci) (closed forms
     * above): unbounded as ti -> pi/2. The corner ti = ts = pi/2, ps = 0 has
     * no limit (0 along the grazing boundary); SPEC §3.3 sets it to 0, for
     * VH and for FC with n = 1, which is VH. FC with n > 1 tends to 0. */
    static const double th[] = {1.5, 1.57, PI_2 - 1e-9};
    double m = 0.7313;
    size_t j;
    int rc;
    for (j = 0; j < 3; j++) {
        double ci = cos(th[j]);
        bf_assert_rel(eval1(bf_model_vh_g, m, 1.7, th[j], th[j], 0.0, NULL),
                      1.0 / (4.0 * m * m * ci), TOL2);
        bf_assert_rel(eval1(bf_model_vh_e, m, 1.7, th[j], th[j], 0.0, NULL),
                      1.0 / (2.0 * m * m * ci), TOL2);
    }
    cr_assert_eq(eval1(bf_model_vh_g, m, 1.7, PI_2, PI_2, 0.0, &rc), 0.0);
    cr_assert_eq(rc, BF_OK);
    cr_assert_eq(eval1(bf_model_vh_e, m, 1.7, PI_2, PI_2, 0.0, &rc), 0.0);
    cr_assert_eq(rc, BF_OK);
    cr_assert_eq(eval1(bf_model_fc_e, m, 1.0, PI_2, PI_2, 0.0, &rc), 0.0);
    cr_assert_eq(rc, BF_OK);
}

Test(bk, every_variant_is_finite_and_non_negative_on_the_closed_hemisphere)
{
    static const double m[] = {1e-3, 0.1, 0.7313, 5.1, 100.0};
    static const double n[] = {1.0, 1.7, 10.0};
    size_t i;
    size_t a;
    size_t b;
    int u;
    int v;
    int w;
    for (i = 0; i < 6; i++) {
        for (a = 0; a < sizeof m / sizeof m[0]; a++) {
            for (b = 0; b < sizeof n / sizeof n[0]; b++) {
                for (u = 0; u <= 40; u++) {
                    for (v = 0; v <= 40; v++) {
                        for (w = -36; w <= 36; w++) {
                            double ti = zenith(u, 40);
                            double ts = zenith(v, 40);
                            double ps = w * (PI / 36.0);
                            int rc;
                            double val =
                                eval1(family(i), m[a], n[b], ti, ts, ps, &rc);
                            int is_bk = (i < 2);
                            if (is_bk && u == 40) {
                                cr_assert_eq(rc, BF_EDOM);
                                cr_assert(isnan(val));
                            } else {
                                cr_assert_eq(rc, BF_OK);
                                cr_assert(isfinite(val) && val >= 0.0,
                                          "%s(m %g n %g; %g %g %g) = %g",
                                          family(i)->name, m[a], n[b], ti, ts,
                                          ps, val);
                            }
                        }
                    }
                }
            }
        }
    }
}

Test(bk, slope_labels_distinguish_gaussian_from_exponential)
{
    cr_assert_str_eq(bf_model_bk_g->param[0].label, "sigma/T (G)");
    cr_assert_str_eq(bf_model_vh_g->param[0].label, "sigma/T (G)");
    cr_assert_str_eq(bf_model_fc_g->param[0].label, "sigma/T (G)");
    cr_assert_str_eq(bf_model_bk_e->param[0].label, "sigma/T (E)");
    cr_assert_str_eq(bf_model_vh_e->param[0].label, "sigma/T (E)");
    cr_assert_str_eq(bf_model_fc_e->param[0].label, "sigma/T (E)");
}
