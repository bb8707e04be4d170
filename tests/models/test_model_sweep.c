/* test_model_sweep.c: numerical edge cases of every model of the registry
 * (so a model added later is swept too) and of the Fresnel terms: a dense
 * sweep of the closed hemisphere, theta = 0 and theta = pi/2 included and
 * all azimuths, across each parameter's whole domain [min, max]:
 *   - every value is finite and >= 0, except where brdffit.h documents a
 *     domain error (BK-G, BK-E at theta_i = pi/2: NaN and BF_EDOM);
 *   - the values on the boundary of the hemisphere (theta = 0, where the
 *     azimuth is undefined, and theta = pi/2, where the models take limits)
 *     are the limits from inside, and the models are continuous in their
 *     parameters, wherever the physics is continuous (not at the grazing
 *     corner theta_i = theta_s = pi/2, where VH and ON have no limit:
 *     test_bk.c and test_oren_nayar.c);
 *   - curves that cannot be normalised (zero or undefined on every used
 *     configuration, SPEC §2) are reported as BF_EDOM by every fitting
 *     entry point, never as NaN.
 * Heavy (about 8 million evaluations): valgrind skips it (tests/valgrind.sh),
 * ASan+UBSan runs it. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define PI 3.14159265358979323846
/* The double nearest pi/2, what asin(1) returns: exactly grazing. */
#define PI_2 1.57079632679489661923

/* Zenith sweep: 0, steps of 2.5 degrees, then pi/2 - 1e-6, pi/2 - 1e-12
 * and pi/2 itself. Azimuth sweep: steps of 10 degrees over [-pi, pi]. */
#define N_STEP 36
#define N_ZEN (N_STEP + 3)
#define N_AZI 37
#define N_GEOM (N_ZEN * N_ZEN * N_AZI)

/* Offset from a boundary for the limit checks, and their tolerance
 * relative to the larger of the two values compared and the curve's
 * largest value away from grazing: a jump at the boundary would be of the
 * order of the curve's values (and values near 0 compare absolutely). */
#define DELTA 1e-9
#define TOL_LIMIT 1e-6

/* Zenith limit below which grazing viewing or incidence is "away from the
 * corner" theta_i = theta_s = pi/2 (radians). */
#define AWAY_FROM_CORNER 1.4

static double zenith(int u)
{
    if (u <= N_STEP - 1) {
        return u * (PI_2 / N_STEP);
    }
    if (u == N_STEP) {
        return PI_2 - 1e-6;
    }
    if (u == N_STEP + 1) {
        return PI_2 - 1e-12;
    }
    return PI_2;
}

static double azimuth(int w)
{
    return (w == N_AZI - 1) ? PI : -PI + w * (2.0 * PI / (N_AZI - 1));
}

static bf_geom *hemisphere(void)
{
    bf_geom *g = malloc(N_GEOM * sizeof *g);
    int u;
    int v;
    int w;
    size_t k = 0;
    cr_assert_not_null(g);
    for (u = 0; u < N_ZEN; u++) {
        for (v = 0; v < N_ZEN; v++) {
            for (w = 0; w < N_AZI; w++) {
                g[k].theta_i = zenith(u);
                g[k].phi_i = PI;
                g[k].theta_s = zenith(v);
                g[k].phi_s = azimuth(w);
                k++;
            }
        }
    }
    return g;
}

/* BK-G and BK-E: undefined at theta_i = pi/2 (SPEC §3.3, brdffit.h). */
static int undefined_at_grazing_incidence(const bf_model_type *t)
{
    return t == bf_model_bk_g || t == bf_model_bk_e;
}

static int named(const bf_model_type *t, const char *name)
{
    return strcmp(t->name, name) == 0;
}

/* The specular models undefined somewhere (brdffit.h): WARD and WARD-DUER
 * diverge at a grazing zenith; LAFORTUNE where max(0, base)^n exceeds the
 * largest double (base up to 2 at the domain's ends, n up to 1e4). */
static int specular_undefined_somewhere(const bf_model_type *t)
{
    return named(t, "WARD") || named(t, "WARD-DUER") || named(t, "LAFORTUNE");
}

/* Whether t at param is documented undefined at g (NaN, BF_EDOM). */
static int undefined_at(const bf_model_type *t, const double *param,
                        const bf_geom *g)
{
    if (undefined_at_grazing_incidence(t)) {
        return g->theta_i == PI_2;
    }
    if (named(t, "WARD") || named(t, "WARD-DUER")) {
        return g->theta_i == PI_2 || g->theta_s == PI_2;
    }
    if (named(t, "LAFORTUNE")) {
        /* SPEC §9.3: Cxy (ix ox + iy oy) + Cz iz oz, in the test's own
         * terms (grazing: cos = 0) */
        double ci = g->theta_i == PI_2 ? 0.0 : cos(g->theta_i);
        double cs = g->theta_s == PI_2 ? 0.0 : cos(g->theta_s);
        double base = param[0] * -(sin(g->theta_i) * sin(g->theta_s) *
                                   cos(g->phi_s)) +
                      param[1] * ci * cs;
        return base > 1.0 && param[2] * log(base) > log(DBL_MAX);
    }
    return 0;
}

/* The values of parameter j swept for the finite/non-negative check: both
 * ends of the domain, the default, both ends of the paper's grid, and the
 * geometric (or, from 0, arithmetic) middle of the domain. */
static size_t sweep_values(const bf_param *p, double *x)
{
    size_t n = 0;
    x[n++] = p->min;
    x[n++] = p->max;
    x[n++] = p->value;
    if (p->grid_n > 0) {
        x[n++] = p->grid_lo;
        x[n++] = p->grid_lo + p->grid_step * (double)(p->grid_n - 1);
    }
    x[n++] = p->min > 0.0 ? sqrt(p->min * p->max) : 0.5 * (p->min + p->max);
    return n;
}

/* The values for the continuity checks: inside the domain, at the paper's
 * grid ends and the defaults, away from the extremes where a lobe is
 * narrower than the checks' offsets resolve (m = 1e-3) or a power law
 * tends to its limit slower than they can see (n_d < 1). */
static size_t smooth_values(const bf_param *p, double *x)
{
    size_t n = 0;
    if (p->grid_n > 0) {
        double hi = p->grid_lo + p->grid_step * (double)(p->grid_n - 1);
        x[n++] = p->grid_lo > 1.0 || strcmp(p->name, "n_d") != 0 ? p->grid_lo
                                                                 : 1.0;
        x[n++] = 0.5 * (p->grid_lo + hi);
        x[n++] = hi;
    } else if (p->linear) {
        /* a scale (SPEC §9.3): the value is linear in it, and at the far
         * end of its domain (1e6) the other parameters' derivatives grow
         * with it while the curve's largest value need not (AS at Rs = 1
         * has no diffuse term), beyond what the offsets can compare */
        x[n++] = p->min;
        x[n++] = p->value;
    } else {
        x[n++] = p->min;
        x[n++] = 0.5 * (p->min + p->max);
        x[n++] = p->max;
    }
    return n;
}

/* Calls fn for every combination of the parameter values of type (values
 * from pick), with the parameter vector. */
static void for_each_param(const bf_model_type *t,
                           size_t (*pick)(const bf_param *, double *),
                           void (*fn)(const bf_model_type *, const double *,
                                      const bf_geom *, double *),
                           const bf_geom *geom, double *out)
{
    double x[BF_MAX_PARAMS][8];
    size_t nx[BF_MAX_PARAMS];
    size_t idx[BF_MAX_PARAMS] = {0};
    double param[BF_MAX_PARAMS];
    size_t j;
    for (j = 0; j < t->p; j++) {
        nx[j] = pick(&t->param[j], x[j]);
    }
    for (;;) {
        for (j = 0; j < t->p; j++) {
            param[j] = x[j][idx[j]];
        }
        fn(t, param, geom, out);
        for (j = 0; j < t->p; j++) {
            if (++idx[j] < nx[j]) {
                break;
            }
            idx[j] = 0;
        }
        if (j == t->p) {
            return;
        }
    }
}

/* Calls for_each_param for every model of the registry on the hemisphere
 * sweep. */
static void for_each_model(size_t (*pick)(const bf_param *, double *),
                           void (*fn)(const bf_model_type *, const double *,
                                      const bf_geom *, double *))
{
    bf_geom *geom = hemisphere();
    double *out = malloc(N_GEOM * sizeof *out);
    size_t i;
    cr_assert_not_null(out);
    for (i = 0; i < bf_model_count(); i++) {
        if (bf_model_get(i) == bf_model_wno_r) {
            continue; /* its quadrature rule, about 150 us a value: swept
                         on a coarser hemisphere in test_wno_r.c */
        }
        for_each_param(bf_model_get(i), pick, fn, geom, out);
    }
    free(out);
    free(geom);
}

static const char *describe(const bf_model_type *t, const double *param)
{
    static char buf[256];
    size_t j;
    size_t len = (size_t)snprintf(buf, sizeof buf, "%s(", t->name);
    for (j = 0; j < t->p && len < sizeof buf; j++) {
        len += (size_t)snprintf(buf + len, sizeof buf - len, "%s%s=%.17g",
                                j ? ", " : "", t->param[j].name, param[j]);
    }
    if (len < sizeof buf) {
        snprintf(buf + len, sizeof buf - len, ")");
    }
    return buf;
}

/* ==== finite and non-negative ============================================ */

static void check_finite(const bf_model_type *t, const double *param,
                         const bf_geom *geom, double *out)
{
    size_t k;
    int rc = bf_model_eval(t, param, N_GEOM, geom, out);
    int undefined = 0;
    for (k = 0; k < N_GEOM; k++) {
        const bf_geom *g = &geom[k];
        if (undefined_at(t, param, g)) {
            cr_assert(isnan(out[k]), "%s at (%.17g, %.17g, %.17g): %g",
                      describe(t, param), g->theta_i, g->theta_s, g->phi_s,
                      out[k]);
            undefined = 1;
            continue;
        }
        cr_assert(isfinite(out[k]) && out[k] >= 0.0,
                  "%s at (%.17g, %.17g, %.17g) = %g", describe(t, param),
                  g->theta_i, g->theta_s, g->phi_s, out[k]);
    }
    cr_assert_eq(rc, undefined ? BF_EDOM : BF_OK, "%s: status %d",
                 describe(t, param), rc);
}

Test(sweep, every_model_is_finite_and_non_negative_over_hemisphere_and_domain)
{
    for_each_model(sweep_values, check_finite);
}

/* ==== limits at the boundary and continuity in the parameters ============ */

/* One model value; NaN when undefined. */
static double eval1(const bf_model_type *t, const double *param, double ti,
                    double ts, double ps)
{
    bf_geom g = {ti, PI, ts, ps};
    double out = NAN;
    (void)bf_model_eval(t, param, 1, &g, &out);
    return out;
}

static void expect_close(double a, double b, double scale, const char *what,
                         const bf_model_type *t, const double *param,
                         double ti, double ts, double ps)
{
    double tol = TOL_LIMIT * fmax(fmax(fabs(a), fabs(b)), scale);
    if ((!isfinite(a) || !isfinite(b)) && specular_undefined_somewhere(t)) {
        return; /* a divergence check_finite has checked is documented */
    }
    if (!(fabs(a - b) <= tol)) {
        cr_expect_fail("%s: %s at (%.17g, %.17g, %.17g): %.17g vs %.17g "
                       "(tolerance %g)",
                       what, describe(t, param), ti, ts, ps, a, b, tol);
    }
}

static void check_limits(const bf_model_type *t, const double *param,
                         const bf_geom *geom, double *out)
{
    double scale = 0.0;
    size_t k;
    int bk = undefined_at_grazing_incidence(t);
    int u;
    int w;
    (void)bf_model_eval(t, param, N_GEOM, geom, out);
    for (k = 0; k < N_GEOM; k++) {
        if (geom[k].theta_i <= AWAY_FROM_CORNER &&
            geom[k].theta_s <= AWAY_FROM_CORNER && out[k] > scale) {
            scale = out[k];
        }
    }
    if (scale == 0.0) {
        scale = 1.0; /* the zero curve (ON, rho = 0): compare absolutely */
    }
    for (u = 0; u < N_ZEN; u++) {
        double th = zenith(u);
        for (w = 0; w < N_AZI; w++) {
            double ps = azimuth(w);
            double param2[BF_MAX_PARAMS];
            size_t j;
            /* theta = 0: the limit from inside, whatever the azimuth */
            if (!bk || th < PI_2) {
                expect_close(eval1(t, param, 0.0, th, ps),
                             eval1(t, param, DELTA, th, ps), scale,
                             "theta_i -> 0", t, param, 0.0, th, ps);
                expect_close(eval1(t, param, 0.0, th, ps),
                             eval1(t, param, 0.0, th, 0.0), scale,
                             "azimuth at theta_i = 0", t, param, 0.0, th, ps);
            }
            if (!bk || th < PI_2) {
                expect_close(eval1(t, param, th, 0.0, ps),
                             eval1(t, param, th, DELTA, ps), scale,
                             "theta_s -> 0", t, param, th, 0.0, ps);
            }
            /* theta = pi/2 away from the grazing corner */
            if (th <= AWAY_FROM_CORNER) {
                if (!bk) {
                    expect_close(eval1(t, param, PI_2, th, ps),
                                 eval1(t, param, PI_2 - DELTA, th, ps), scale,
                                 "theta_i -> pi/2", t, param, PI_2, th, ps);
                }
                expect_close(eval1(t, param, th, PI_2, ps),
                             eval1(t, param, th, PI_2 - DELTA, ps), scale,
                             "theta_s -> pi/2", t, param, th, PI_2, ps);
            }
            /* the azimuth wraps: -pi and pi are one direction */
            if (!bk || th < PI_2) {
                expect_close(eval1(t, param, th, 0.7313, -PI),
                             eval1(t, param, th, 0.7313, PI), scale,
                             "phi_s = -pi vs pi", t, param, th, 0.7313, PI);
            }
            /* continuity in every parameter, within its domain, away from
             * grazing incidence: there FC's Fresnel factor tends to its
             * n -> 1 limit non-uniformly (f(theta, n) rises to 1 over
             * cos theta ~ sqrt(n^2 - 1), so near theta = pi/2 it moves by
             * O(1) between n = 1 and n = 1 + 1e-9: continuous, but steeper
             * than this check's offset resolves) */
            for (j = 0; j < t->p && th <= AWAY_FROM_CORNER; j++) {
                memcpy(param2, param, t->p * sizeof *param);
                param2[j] = param[j] + ((param[j] < t->param[j].max)
                                            ? DELTA : -DELTA) *
                                           fmax(1.0, fabs(param[j]));
                expect_close(eval1(t, param, th, 1.0219, ps),
                             eval1(t, param2, th, 1.0219, ps), scale,
                             t->param[j].name, t, param, th, 1.0219, ps);
            }
        }
    }
}

Test(sweep, boundary_values_are_the_limits_and_models_are_continuous)
{
    for_each_model(smooth_values, check_limits);
}

/* ==== Fresnel terms ======================================================= */

Test(sweep, fresnel_terms_lie_in_their_ranges_and_meet_their_limits)
{
    /* f(alpha, r) in [0, 1] for r on both sides of 1 (r < 1: inside the
     * dielectric, total internal reflection past asin(r)); at alpha = 0 the
     * limit ((r - 1)/(r + 1))^2 and at grazing on the air side 1 (SPEC
     * §4.1), reached continuously. F_FC^2 in [0, cos theta_i] for n in
     * [1, 10] (two transmittances times cos theta_i, SPEC §4.2), and
     * continuous as n -> 1, where it is cos theta_i (away from grazing). */
    static const double r[] = {1e-3, 0.5, 1.0 / 1.7, 0.999, 1.0,
                               1.001, 1.7, 10.0, 100.0};
    static const double n[] = {1.0, 1.0 + 1e-9, 1.4, 1.7, 2.0, 10.0};
    size_t a;
    int u;
    int v;
    for (a = 0; a < sizeof r / sizeof r[0]; a++) {
        double f0 = ((r[a] - 1.0) / (r[a] + 1.0)) * ((r[a] - 1.0) / (r[a] + 1.0));
        bf_assert_abs(bf_fresnel(0.0, r[a]), f0, TOL2);
        bf_assert_abs(bf_fresnel(DELTA, r[a]), f0, TOL_LIMIT);
        if (r[a] > 1.0) {
            bf_assert_abs(bf_fresnel(PI_2, r[a]), 1.0, TOL0);
            bf_assert_abs(bf_fresnel(PI_2 - DELTA, r[a]), 1.0,
                          TOL_LIMIT * r[a]);
        }
        for (u = 0; u < N_ZEN; u++) {
            double f = bf_fresnel(zenith(u), r[a]);
            cr_assert(isfinite(f) && f >= 0.0 && f <= 1.0,
                      "f(%.17g, %g) = %g", zenith(u), r[a], f);
        }
    }
    for (a = 0; a < sizeof n / sizeof n[0]; a++) {
        for (u = 0; u < N_ZEN; u++) {
            for (v = 0; v < N_ZEN; v++) {
                double ci = cos(zenith(u));
                double f2 = bf_fresnel_fc2(zenith(u), zenith(v), n[a]);
                cr_assert(isfinite(f2) && f2 >= 0.0 &&
                              f2 <= ci * (1.0 + TOL1),
                          "F_FC^2(%.17g, %.17g, %g) = %g", zenith(u),
                          zenith(v), n[a], f2);
                /* n -> 1: cos theta_i, away from grazing (the
                 * transmittances tend to 1 non-uniformly there, see
                 * check_limits) */
                if (n[a] < 1.0 + 2e-9 && zenith(u) <= AWAY_FROM_CORNER &&
                    zenith(v) <= AWAY_FROM_CORNER) {
                    bf_assert_abs(f2, ci, TOL_LIMIT);
                }
            }
        }
    }
}

/* ==== degenerate normalisations =========================================== */

/* n configurations with theta_s = pi/2 (LFTG is 0 on all of them) or
 * theta_i = pi/2 (Lambert and ON are 0, BK undefined). */
#define N_DEGEN 5

static void grazing(bf_geom *g, int incidence)
{
    size_t k;
    for (k = 0; k < N_DEGEN; k++) {
        double other = 0.2 + 0.25 * (double)k;
        g[k].theta_i = incidence ? PI_2 : other;
        g[k].phi_i = PI;
        g[k].theta_s = incidence ? other : PI_2;
        g[k].phi_s = 0.4 * (double)k;
    }
}

/* Every fitting entry point answers BF_EDOM for type at param on g, and
 * leaves no NaN in its results. */
static void expect_not_normalisable(const bf_model_type *t,
                                    const double *param, const bf_geom *g)
{
    static const double data[N_DEGEN] = {1.0, 0.8, 0.6, 0.4, 0.2};
    bf_fit_workspace *w = bf_fit_alloc(N_DEGEN);
    bf_fit_result res;
    bf_grid *gr;
    double lse = 42.0;
    int st = -1;
    cr_assert_not_null(w);
    cr_expect_eq(bf_fit_lse(t, param, N_DEGEN, g, data, w, &lse), BF_EDOM,
                 "%s: bf_fit_lse", t->name);
    cr_expect_eq(lse, 42.0, "%s: bf_fit_lse wrote %g", t->name, lse);
    cr_expect_eq(bf_fit_grid(t, param, 0, N_DEGEN, g, data, w, &res), BF_EDOM,
                 "%s: bf_fit_grid", t->name);
    cr_expect(!isnan(res.lse), "%s: bf_fit_grid left NaN", t->name);
    gr = bf_grid_alloc(t, param, 0, N_DEGEN, g, &st);
    cr_assert_not_null(gr, "%s: bf_grid_alloc %d", t->name, st);
    cr_expect_eq(bf_grid_fit(gr, data, &res), BF_EDOM, "%s: bf_grid_fit",
                 t->name);
    cr_expect(!isnan(res.lse), "%s: bf_grid_fit left NaN", t->name);
    bf_grid_free(gr);
    bf_fit_free(w);
}

Test(sweep, curves_that_cannot_be_normalised_are_domain_errors_never_nan)
{
    bf_geom view[N_DEGEN];
    bf_geom light[N_DEGEN];
    double lftg[1] = {2.3};
    double bk[1] = {0.7313};
    double on_dark[2] = {0.0, 0.4}; /* rho = 0: ON is 0 everywhere */
    double zeros[N_DEGEN] = {0.0};
    double negative[N_DEGEN] = {-0.1, -0.2, 0.0, -0.05, -0.3};
    double out[N_DEGEN];
    bf_geom normal[N_DEGEN];
    grazing(view, 0);
    grazing(light, 1);
    grazing(normal, 0);
    normal[0].theta_s = 0.3; /* one non-grazing view */
    expect_not_normalisable(bf_model_lftg, lftg, view);       /* all zero */
    expect_not_normalisable(bf_model_lambert, NULL, light);   /* all zero */
    expect_not_normalisable(bf_model_bk_g, bk, light);        /* undefined */
    expect_not_normalisable(bf_model_bk_e, bk, light);        /* undefined */
    expect_not_normalisable(bf_model_on, on_dark, normal);    /* all zero */
    /* data: all zero or no positive value (SPEC §2) */
    cr_expect_eq(bf_normalise(N_DEGEN, zeros, out), BF_EDOM);
    cr_expect_eq(bf_normalise(N_DEGEN, negative, out), BF_EDOM);
}
