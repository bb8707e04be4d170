/* test_spec_intervals.c: the intervals of the specular models and the
 * composites D+S (SPEC §9, doc/methods.md §3; issue 17 item 6, issue 18
 * items 2 and 4) -- coverage of the profile intervals under relative and
 * absolute noise at the Cornell geometry and at random geometry, objective
 * ngan (LAMBERT+GGX, LAMBERT+WARD, AS); the not-identified flag on a
 * constructed flat profile (F0 without effect); finite intervals holding
 * the estimate, bootstrap and CV on the real Cornell file; `brdffit
 * calibrate` on a composite, and its note on a noise power at its bound.
 *
 * Acceptance band as tests/fit/test_intervals.c: R = 200 simulations, a
 * correct 95% interval covers the truth Binomial(200, 0.95) times: sd
 * 0.0154, band [0.90, 0.99] (-3.2 sd, +2.6 sd; fixed seeds); the median
 * width over 2 z sd of the estimates the intervals are about within
 * [1/1.3, 1.3] (issue 18's contract). */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <string.h>

#include "cli_run.h"
#include "fit/engine.h"
#include "support.h"

#define LEVEL 0.95
#define SEED 20261203ul
#if !BF_TEST_SANITIZED
#define REPS 200
#define COVER_LO 0.90
#define COVER_HI 0.99
#define WIDTH_TOL 1.3
#define WRONG_LO 0.80
#else
/* The sanitizer build runs the same code on 10 simulations, no band. */
#define REPS 10
#define COVER_LO 0.0
#define COVER_HI 1.0
#define WIDTH_TOL HUGE_VAL
#define WRONG_LO 0.0
#endif
/* Every CORNELL_STRIDE-th of krylon_blue's 1439 configurations with
 * theta_i, theta_o <= 80 deg (SPEC §10): K = 360, the suite's size. */
#define CORNELL_STRIDE 4
#define MAX_CONF 1500
/* Random geometry: half uniform up to 80 deg, half within 10 deg of the
 * mirror direction (where a lobe is measured). */
#define N_RANDOM 300

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(spec_intervals, .init = setup);

/* krylon_blue's configurations with theta_i, theta_o <= 80 deg, every
 * stride-th (Beckmann's frame). */
static size_t cornell_geom(size_t stride, bf_geom *geom)
{
    bf_dataset *ds = NULL;
    bf_error err;
    bf_selection s;
    static size_t sel[MAX_CONF];
    size_t n = 0;
    size_t k;
    size_t out = 0;
    cr_assert_eq(bf_dataset_load(bf_test_cornell_path("krylon_blue.brdf"),
                                 NULL, &ds, &err),
                 BF_OK, "cannot load krylon_blue.brdf: %s", err.msg);
    cr_assert(bf_dataset_nconf(ds, 0) <= MAX_CONF);
    bf_selection_init(&s);
    s.max_theta = BF_KEEP_SCALE_THETA;
    cr_assert_eq(bf_dataset_select(ds, 0, BF_CHANNEL_MEAN, &s, sel, &n, NULL),
                 BF_OK);
    cr_assert_eq(n, 1439); /* SPEC §10's K for the Cornell files */
    for (k = 0; k < n; k += stride) {
        geom[out++] = bf_dataset_geom(ds, 0)[sel[k]];
    }
    bf_dataset_free(ds);
    return out;
}

static size_t random_geom(bf_geom *geom)
{
    bf_test_random_geometry(geom, N_RANDOM, 11, 1);
    return N_RANDOM;
}

/* Coverage of every parameter of model at truth through bf_calibrate
 * (noise power p, sd sigma of the maximum) under the noise model noise,
 * objective ngan: at least lo, at most COVER_HI; with width, the width
 * over the spread within WIDTH_TOL. */
static void coverage_under(const char *model, const double *truth, size_t n,
                           const bf_geom *geom, double p, double sigma,
                           bf_noise noise, double lo, int width,
                           const char *what)
{
    const bf_model_type *t = bf_model_find(model);
    bf_problem pb;
    bf_calibration cal;
    size_t j;
    cr_assert_not_null(t, "%s", model);
    cr_assert_eq(bf_problem_init(&pb, t, truth, n, geom, NULL), BF_OK);
    pb.objective = BF_OBJ_NGAN;
    cr_assert_eq(bf_fit_calibrate(&pb, truth, p, sigma, noise, REPS, 0, 0,
                                  0, SEED, LEVEL, &cal),
                 BF_OK, "%s %s", model, what);
    cr_assert_geq(cal.n_sim, REPS - REPS / 20, "%s %s: %zu of %d fitted",
                  model, what, cal.n_sim, REPS);
    for (j = 0; j < t->p; j++) {
        double ratio = cal.width[j] / (2.0 * 1.959964 * cal.ml_sd[j]);
        cr_log_info("%s %s %s: covered %.3f, width/spread %.2f", model, what,
                    t->param[j].name, cal.coverage[j], ratio);
        cr_expect(cal.coverage[j] >= lo && cal.coverage[j] <= COVER_HI,
                  "%s %s %s: coverage %.3f outside [%.2f, %.2f]", model, what,
                  t->param[j].name, cal.coverage[j], lo, COVER_HI);
        cr_expect(!width || (ratio <= WIDTH_TOL && ratio >= 1.0 / WIDTH_TOL),
                  "%s %s %s: width %.3g over spread %.3g = %.2f", model,
                  what, t->param[j].name, cal.width[j],
                  2.0 * 1.959964 * cal.ml_sd[j], ratio);
    }
}

/* coverage_under the default noise model (auto), in the band. */
static void coverage(const char *model, const double *truth, size_t n,
                     const bf_geom *geom, double p, double sigma,
                     const char *what)
{
    coverage_under(model, truth, n, geom, p, sigma, BF_NOISE_AUTO, COVER_LO,
                   1, what);
}

/* LAMBERT+GGX: krylon_blue's ngan fit, rounded (rho_d, rho_s, alpha,
 * F0); LAMBERT+WARD: a broader lobe than krylon_blue's (alpha 0.019),
 * which random directions would rarely meet. */
static const double ggx_truth[4] = {0.077, 0.76, 0.113, 0.059};
static const double ward_truth[3] = {0.1, 0.05, 0.08};

Test(spec_intervals, lambert_ggx_covers_at_the_cornell_geometry,
     .timeout = 600)
{
    static bf_geom geom[MAX_CONF];
    size_t n = cornell_geom(CORNELL_STRIDE, geom);
    coverage("LAMBERT+GGX", ggx_truth, n, geom, 2.0, 0.05, "Cornell rel 5%");
    coverage("LAMBERT+GGX", ggx_truth, n, geom, 0.0, 0.02, "Cornell abs 2%");
}

Test(spec_intervals, lambert_ggx_and_ward_cover_at_random_geometry,
     .timeout = 600)
{
    static bf_geom geom[N_RANDOM];
    size_t n = random_geom(geom);
    coverage("LAMBERT+GGX", ggx_truth, n, geom, 2.0, 0.05, "random rel 5%");
    coverage("LAMBERT+WARD", ward_truth, n, geom, 0.0, 0.02,
             "random abs 2%");
}

/* The robust factor (doc/methods.md §3, src/fit/sandwich.c): data with 5 %
 * relative noise fitted under --noise absolute, a constant variance the
 * gloss peak's residuals contradict. The likelihood's intervals alone
 * cover the lobe's parameters in a third to a half of these simulations
 * (rho_s 0.350, alpha 0.315, F0 0.505, measured with every factor set to
 * 1); widened by their robust factors, at least WRONG_LO (measured: 0.910,
 * 0.880, 0.830; rho_d 0.985 both ways). Not calibrated -- rho_s's sandwich
 * rests on about four configurations' worth of residuals at the peak, and
 * the widths are not checked -- but no longer intervals that miss most of
 * the time. */
Test(spec_intervals, the_robust_factor_mends_a_wrong_noise_model,
     .timeout = 600)
{
    static bf_geom geom[N_RANDOM];
    size_t n = random_geom(geom);
    coverage_under("LAMBERT+GGX", ggx_truth, n, geom, 2.0, 0.05,
                   BF_NOISE_ABSOLUTE, WRONG_LO, 0, "random rel 5%, absolute");
}

/* The robust factor against its definition (doc/methods.md §3): with
 * alpha and F0 held, LAMBERT+GGX is linear in its scales, rho = rho_d a_k
 * + rho_s b_k, so the derivatives bf_fit_intervals takes are exact and the
 * sandwich can be written out here with GSL: under --noise absolute (p =
 * 0, every weight 1) X = [a b], A = X'X, h_k = x_k A^-1 x_k', V_model =
 * s^2 A^-1 with s^2 = sum e^2 / (K - 2), V_robust = A^-1 (sum e_k^2 / (1 -
 * h_k) x_k x_k') A^-1 at the least-squares fit, and c_j = max(1,
 * V_robust,jj / V_model,jj). Noise sd proportional to rho^q: q = 1 (the
 * peak noisiest) gives the lobe's scale a factor well above 1; q = -1/2
 * (the dim configurations noisiest) a ratio below 1 for it, which is
 * taken as 1. */
static void sandwich_case(double q, double *ratio, double *factor)
{
    static bf_geom geom[N_RANDOM];
    static double rho[N_RANDOM];
    static double a[N_RANDOM];
    static double b[N_RANDOM];
    const bf_model_type *t = bf_model_find("LAMBERT+GGX");
    const double truth[4] = {0.3, 0.6, 0.3, 0.2};
    double unit[4] = {1.0, 0.0, 0.3, 0.2};
    double xtx[4] = {0.0};
    double m[4];
    double mid[4] = {0.0};
    double fit[2] = {0.0, 0.0};
    double rss = 0.0;
    double mean = 0.0;
    size_t n = random_geom(geom);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_matrix_view xv = gsl_matrix_view_array(xtx, 2, 2);
    gsl_matrix_view mv = gsl_matrix_view_array(m, 2, 2);
    bf_problem pb;
    bf_fit_result best;
    bf_interval iv;
    bf__solo so;
    size_t j;
    size_t k;
    cr_assert_eq(bf_model_eval(t, unit, n, geom, a), BF_OK);
    unit[0] = 0.0;
    unit[1] = 1.0;
    cr_assert_eq(bf_model_eval(t, unit, n, geom, b), BF_OK);
    for (k = 0; k < n; k++) {
        a[k] *= cos(geom[k].theta_i); /* rho = BRDF cos theta_i (SPEC §10) */
        b[k] *= cos(geom[k].theta_i);
        mean += (truth[0] * a[k] + truth[1] * b[k]) / (double)n;
    }
    gsl_rng_set(rng, 5);
    for (k = 0; k < n; k++) {
        double mu = truth[0] * a[k] + truth[1] * b[k];
        rho[k] = mu + 0.05 * mean * pow(mu / mean, q) *
                          gsl_ran_gaussian(rng, 1.0);
        xtx[0] += a[k] * a[k];
        xtx[1] += a[k] * b[k];
        xtx[3] += b[k] * b[k];
    }
    xtx[2] = xtx[1];
    gsl_rng_free(rng);
    cr_assert_eq(bf_problem_init(&pb, t, truth, n, geom, rho), BF_OK);
    pb.objective = BF_OBJ_NGAN;
    pb.free_mask = 3u; /* rho_d, rho_s; alpha and F0 held at the truth */
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &best, NULL), BF_OK);
    bf__solo_free(&so);
    cr_assert_eq(bf_fit_intervals(&pb, &best, BF_NOISE_ABSOLUTE, LEVEL, &iv),
                 BF_OK);
    cr_assert(isnan(iv.robust[2]) && isnan(iv.robust[3]), "held: none");
    /* the least-squares fit, A^-1 and the middle of the sandwich */
    cr_assert_eq(gsl_linalg_cholesky_decomp1(&xv.matrix), GSL_SUCCESS);
    memcpy(m, xtx, sizeof m);
    cr_assert_eq(gsl_linalg_cholesky_invert(&mv.matrix), GSL_SUCCESS);
    for (k = 0; k < n; k++) {
        fit[0] += (m[0] * a[k] + m[1] * b[k]) * rho[k];
        fit[1] += (m[2] * a[k] + m[3] * b[k]) * rho[k];
    }
    bf_assert_rel(iv.ml.param[0], fit[0], 1e-6);
    bf_assert_rel(iv.ml.param[1], fit[1], 1e-6);
    for (k = 0; k < n; k++) {
        double e = rho[k] - fit[0] * a[k] - fit[1] * b[k];
        double h = a[k] * (m[0] * a[k] + m[1] * b[k]) +
                   b[k] * (m[2] * a[k] + m[3] * b[k]);
        double w = e * e / (1.0 - fmin(h, 0.99));
        rss += e * e;
        mid[0] += w * a[k] * a[k];
        mid[1] += w * a[k] * b[k];
        mid[3] += w * b[k] * b[k];
    }
    mid[2] = mid[1];
    for (j = 0; j < 2; j++) {
        double vr = 0.0; /* (A^-1 M A^-1)_jj */
        double vm = rss / (double)(n - 2) * m[j * 2 + j];
        size_t u;
        size_t v;
        for (u = 0; u < 2; u++) {
            for (v = 0; v < 2; v++) {
                vr += m[j * 2 + u] * mid[u * 2 + v] * m[v * 2 + j];
            }
        }
        cr_log_info("q = %g, %s: V_robust / V_model = %g, factor %g", q,
                    t->param[j].name, vr / vm, iv.robust[j]);
        bf_assert_rel(iv.robust[j], fmax(1.0, vr / vm), 1e-5);
        ratio[j] = vr / vm;
        factor[j] = iv.robust[j];
    }
}

Test(spec_intervals, the_robust_factor_is_the_sandwich_ratio)
{
    double ratio[2];
    double factor[2];
    sandwich_case(1.0, ratio, factor);
    cr_assert_gt(factor[1], 3.0, "rho_s, the peak noisiest: %g", factor[1]);
    sandwich_case(-0.5, ratio, factor);
    cr_assert_lt(ratio[1], 0.8, "rho_s, the peak quietest: %g", ratio[1]);
    cr_assert_eq(factor[1], 1.0, "widening only: %g", factor[1]);
}

/* AS alone (SPEC §9.3), a complete model: only Rd is a scale solved
 * linearly; Rs, the Fresnel reflectance, is non-linear and enters both
 * the lobe and the diffuse term's (1 - Rs), so the profiles re-optimise
 * it with n. Truth: krylon_blue's ngan fit, rounded (Rd, Rs, n; as
 * bench/bench_coverage.c). */
Test(spec_intervals, as_covers_at_the_cornell_geometry, .timeout = 600)
{
    static bf_geom geom[MAX_CONF];
    static const double as_truth[3] = {0.095, 0.043, 107.0};
    size_t n = cornell_geom(CORNELL_STRIDE, geom);
    coverage("AS", as_truth, n, geom, 2.0, 0.05, "Cornell rel 5%");
}

/* ==== not identified ====================================================== */

/* Near normal incidence and view (theta_i, theta_o <= 12 deg) cos theta_d
 * >= cos 12 deg, so Schlick's (1 - cos theta_d)^5 <= 1.1e-6: F = F0 to
 * that, and rho_s F0 is all the data say (SPEC §9.2). F0's profile stays
 * below the threshold to its bound 1 (rho_s making up for it): open, and
 * flagged; alpha, which the lobe's shape fixes, is not. */
Test(spec_intervals, f0_without_effect_is_flagged_not_identified)
{
    const bf_model_type *t = bf_model_find("LAMBERT+GGX");
    enum { N = 240 };
    static bf_geom geom[N];
    static double data[N];
    const double truth[4] = {0.2, 0.5, 0.08, 0.3};
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    bf__solo so;
    bf_problem pb;
    bf_fit_result fit;
    bf_interval iv;
    size_t k;
    gsl_rng_set(rng, 5);
    for (k = 0; k < N; k++) {
        geom[k].theta_i = 12.0 * M_PI / 180.0 * gsl_rng_uniform(rng);
        geom[k].phi_i = M_PI;
        geom[k].theta_s = 12.0 * M_PI / 180.0 * gsl_rng_uniform(rng);
        geom[k].phi_s = M_PI * (2.0 * gsl_rng_uniform(rng) - 1.0);
    }
    cr_assert_eq(bf_problem_init(&pb, t, truth, N, geom, data), BF_OK);
    pb.objective = BF_OBJ_NGAN;
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__curve(&so.pm, truth, so.fc.work, so.fc.curve), BF_OK);
    for (k = 0; k < N; k++) { /* 2% relative noise */
        data[k] = so.fc.curve[k] * (1.0 + 0.02 * gsl_ran_gaussian(rng, 1.0));
    }
    bf__fitctx_use(&so.fc, &pb);
    cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &fit, NULL), BF_OK);
    cr_assert_eq(bf__intervals(&so.fc, &fit, BF_NOISE_RELATIVE, LEVEL, &iv),
                 BF_OK);
    cr_assert(iv.not_identified & (1u << 3), "F0 [%g, %g] open %u flags %u",
              iv.low[3], iv.high[3], iv.open, iv.not_identified);
    cr_assert(iv.open & (2u << (2 * 3)), "F0's interval reaches 1: %g",
              iv.high[3]);
    cr_assert_eq(iv.high[3], pb.hi[3]);
    cr_assert(!(iv.not_identified & (1u << 2)), "alpha [%g, %g]", iv.low[2],
              iv.high[2]);
    cr_assert(iv.low[2] <= truth[2] * 1.2 && iv.high[2] >= truth[2] * 0.8);
    bf__solo_free(&so);
    gsl_rng_free(rng);
}

/* ==== dense data: the profile's narrowed bracket (profile.c) ============= */

/* theta_i on 30 and theta_s on 40 zeniths below 80 deg, 60 azimuths: K =
 * 72,000, above BF__DENSE_K, so each profile end is searched from a
 * predicted first step (Gauss-Newton at the estimate) and a bracket
 * narrowed by prediction (profile.c). Each end must still be a root of
 * the profile on all the data: LAMBERT+GGX refitted there, the parameter
 * held at the end, by the separable fit itself (its own grid and descent,
 * no profile code), gives n ln(S_p / S_min) = chi2_1(0.95) = 3.841 -- a
 * predicted point taken for the end would be off by about 0.15-0.3
 * (CI_BEYOND: 2 % of the distance); the root finder's own tolerance is
 * 1e-5, the inner fits' stall n 1e-10 per iteration (7e-6). */
#define DENSE_TI 30
#define DENSE_TS 40
#define DENSE_PHI 60
#define DENSE_N (DENSE_TI * DENSE_TS * DENSE_PHI)
#define DENSE_CRIT_TOL 0.01

Test(spec_intervals, dense_profile_ends_are_roots_on_all_the_data,
     .timeout = 600)
{
    const bf_model_type *t = bf_model_find("LAMBERT+GGX");
    const double truth[4] = {0.3, 0.8, 0.15, 0.05};
    const double chi2 = 3.841458820694124; /* chi2_1(0.95) */
    bf_geom *geom = malloc(DENSE_N * sizeof *geom);
    double *data = malloc(DENSE_N * sizeof *data);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    bf__solo so;
    bf_problem pb;
    bf_fit_result fit;
    size_t n = 0;
    size_t j;
    int a;
    int b;
    int c;
    cr_assert(geom != NULL && data != NULL && rng != NULL);
    gsl_rng_set(rng, 17);
    for (a = 0; a < DENSE_TI; a++) {
        for (b = 0; b < DENSE_TS; b++) {
            for (c = 0; c < DENSE_PHI; c++) {
                geom[n].theta_i = (1.0 + 78.0 * a / (DENSE_TI - 1)) * M_PI /
                                  180.0;
                geom[n].phi_i = M_PI;
                geom[n].theta_s = (1.0 + 78.0 * b / (DENSE_TS - 1)) * M_PI /
                                  180.0;
                geom[n].phi_s = (0.5 + 360.0 * c / DENSE_PHI) * M_PI / 180.0;
                n++;
            }
        }
    }
    cr_assert_eq(bf_problem_init(&pb, t, truth, DENSE_N, geom, data), BF_OK);
    pb.objective = BF_OBJ_NGAN;
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__curve(&so.pm, truth, so.fc.work, so.fc.curve), BF_OK);
    for (n = 0; n < DENSE_N; n++) { /* 3% relative noise */
        data[n] = so.fc.curve[n] * (1.0 + 0.03 * gsl_ran_gaussian(rng, 1.0));
    }
    bf__fitctx_use(&so.fc, &pb);
    cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &fit, NULL), BF_OK);
    for (j = 0; j < 4; j++) {
        double end[2];
        unsigned open = 7;
        size_t e;
        cr_assert_eq(bf__profile_ci(&so.fc, &fit, j, LEVEL, &end[0], &end[1],
                                    &open),
                     BF_OK, "parameter %zu", j);
        cr_assert_eq(open, 0u, "parameter %zu [%g, %g]", j, end[0], end[1]);
        cr_assert(end[0] < fit.param[j] && fit.param[j] < end[1],
                  "parameter %zu: %g not inside [%g, %g]", j, fit.param[j],
                  end[0], end[1]);
        for (e = 0; e < 2; e++) { /* S_p at the end, fitted afresh */
            bf_problem held = pb;
            bf_fit_result r;
            double crit;
            held.free_mask &= ~(1u << j);
            held.fixed[j] = end[e];
            bf__fitctx_use(&so.fc, &held);
            cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &r, NULL), BF_OK);
            bf__fitctx_use(&so.fc, &pb);
            crit = (double)DENSE_N * log(r.lse / fit.lse);
            cr_assert(fabs(crit - chi2) < DENSE_CRIT_TOL,
                      "parameter %zu's %s end %.10g: n ln(S_p / S_min) = "
                      "%.6g, not %.6g",
                      j, e == 0 ? "lower" : "upper", end[e], crit, chi2);
        }
    }
    bf__solo_free(&so);
    gsl_rng_free(rng);
    free(geom);
    free(data);
}

/* ==== the real file ======================================================== */

/* krylon_blue, LAMBERT+GGX through the CLI with --stats: under --noise
 * absolute the likelihood is the ngan objective (p = 0, every weight 1),
 * so each interval holds the reported estimate; under auto (relative-like
 * noise on the paint) they hold the maximum-likelihood estimate instead
 * (doc/methods.md §3). Constant variance is the wrong noise model for a
 * gloss peak whose noise grows with its value: the residuals at the peak
 * are many times larger than it says, and the robust factor (ci_robust)
 * widens the lobe's intervals by more than 3 (a threshold 10 times the
 * likelihood's) where the diffuse term's, set by the dim configurations,
 * is widened less. Bootstrap and CV finite. */
Test(spec_intervals, cornell_intervals_are_finite_and_hold_the_estimate,
     .timeout = 300)
{
    static const char *const param[4] = {"rho_d", "rho_s", "alpha", "F0"};
    const char *dir = bf_test_tmpdir();
    char out[512];
    const char *err = NULL;
    double robust[4];
    size_t j;
    int rc;
    snprintf(out, sizeof out, "%s/abs", dir);
    {
        const char *argv[] = {"compare", "--models", "LAMBERT+GGX", "--fit",
                              "exact", "--objective", "ngan", "--stats",
                              "--noise", "absolute", "--bootstrap", "19",
                              "--quiet", "--out", out,
                              bf_test_cornell_path("krylon_blue.brdf"),
                              NULL};
        rc = bf_test_run_cli(argv, NULL, &err);
    }
    cr_assert_eq(rc, 0, "brdffit compare: %s", err);
    bf_test_csv_load(out, "fits.csv");
    for (j = 0; j < 4; j++) {
        size_t r = bf_test_csv_find("1", "LAMBERT+GGX", param[j]);
        double v = bf_test_csv_num(r, "value");
        double lo = bf_test_csv_num(r, "ci_low");
        double hi = bf_test_csv_num(r, "ci_high");
        cr_assert(isfinite(lo) && isfinite(hi) && lo < hi, "%s [%g, %g]",
                  param[j], lo, hi);
        cr_assert(lo <= v && v <= hi, "%s %g outside [%g, %g]", param[j], v,
                  lo, hi);
        robust[j] = bf_test_csv_num(r, "ci_robust");
        cr_assert(robust[j] >= 1.0, "%s: robust factor %g", param[j],
                  robust[j]);
        cr_assert(j == 0 || robust[j] > 10.0, "%s: robust factor %g",
                  param[j], robust[j]);
        cr_assert_str_eq(bf_test_csv_cell(r, "ci_method"), "profile-lik");
        cr_assert(isfinite(bf_test_csv_num(r, "boot_low")) &&
                  isfinite(bf_test_csv_num(r, "boot_high")));
        cr_assert(isfinite(bf_test_csv_num(r, "cv")) &&
                  bf_test_csv_num(r, "cv") > 0.0);
        cr_assert(strstr(bf_test_csv_cell(r, "flags"), "not_identified") ==
                  NULL);
    }
}

/* The Cornell file's rho (SPEC §10) at its configurations with theta_i,
 * theta_o <= 80 deg, as model's ngan problem pb. */
static void paint_problem(const char *file, const char *model, bf_geom *geom,
                          double *rho, bf_problem *pb)
{
    const bf_model_type *t = bf_model_find(model);
    bf_dataset *ds = NULL;
    bf_error err;
    bf_selection s;
    static size_t sel[MAX_CONF];
    size_t n = 0;
    size_t k;
    cr_assert_not_null(t, "%s", model);
    cr_assert_eq(bf_dataset_load(bf_test_cornell_path(file), NULL, &ds, &err),
                 BF_OK, "cannot load %s: %s", file, err.msg);
    bf_selection_init(&s);
    s.max_theta = BF_KEEP_SCALE_THETA;
    cr_assert_eq(bf_dataset_select(ds, 0, BF_CHANNEL_MEAN, &s, sel, &n, NULL),
                 BF_OK);
    cr_assert(n <= MAX_CONF);
    for (k = 0; k < n; k++) {
        geom[k] = bf_dataset_geom(ds, 0)[sel[k]];
    }
    cr_assert_eq(bf__dataset_rho(ds, 0, BF_CHANNEL_MEAN, n, sel, rho), BF_OK);
    cr_assert_eq(bf_problem_init(pb, t, NULL, n, geom, rho), BF_OK);
    pb->objective = BF_OBJ_NGAN;
    bf_dataset_free(ds);
}

/* model's ngan fit to the Cornell file and its intervals (noise model
 * auto) into so, pb (its data in buffers of this function) and iv: every
 * free parameter's interval finite, not a point, and holding the
 * maximum-likelihood estimate. */
static void paint_intervals(const char *file, const char *model,
                            bf__solo *so, bf_problem *pb, bf_interval *iv)
{
    static bf_geom geom[MAX_CONF];
    static double rho[MAX_CONF];
    bf_fit_result fit;
    size_t j;
    paint_problem(file, model, geom, rho, pb);
    cr_assert_eq(bf__solo_init(so, pb), BF_OK);
    cr_assert_eq(bf__varpro_fit(&so->fc, NULL, &fit, NULL), BF_OK);
    cr_assert_eq(bf__intervals(&so->fc, &fit, BF_NOISE_AUTO, LEVEL, iv),
                 BF_OK, "%s on %s", model, file);
    for (j = 0; j < pb->type->p; j++) {
        cr_assert(isfinite(iv->low[j]) && isfinite(iv->high[j]) &&
                      iv->low[j] < iv->high[j],
                  "%s [%g, %g]", pb->type->param[j].name, iv->low[j],
                  iv->high[j]);
        cr_assert(iv->low[j] <= iv->ml.param[j] &&
                      iv->ml.param[j] <= iv->high[j],
                  "%s ML %g outside [%g, %g]", pb->type->param[j].name,
                  iv->ml.param[j], iv->low[j], iv->high[j]);
    }
}

Test(spec_intervals, the_library_intervals_hold_the_ml_estimate_on_cornell,
     .timeout = 300)
{
    bf__solo so;
    bf_problem pb;
    bf_interval iv;
    paint_intervals("krylon_blue.brdf", "LAMBERT+GGX", &so, &pb, &iv);
    cr_assert(iv.noise_power > 1.0 && iv.noise_power <= BF_NOISE_PMAX,
              "p %g", iv.noise_power);
    cr_assert_eq(iv.not_identified, 0u);
    bf__solo_free(&so);
}

/* mystique under LAMBERT+LAFORTUNE: the ngan fit's lobe is at n's bound
 * (1e4). A profile of Cxy under a wide threshold (a robust factor of some
 * 3000 times chi2_1, as the likelihood's had when its fit stopped short of
 * its minimum) walks out to where the lobe (|Cxy| sin^2 + Cz cos^2)^n
 * overflows a double from every start the inner fits take (Cxy = 2,
 * 1.52, ... 1.11). The walk stays inside such points and finds the end
 * short of them, open (not identified), instead of failing: before
 * profile.c bounded its walk there, the profile returned BF_EDOM and
 * fits.csv had no interval for Cxy, Cz or n. */
Test(spec_intervals, a_profile_stays_inside_where_the_model_overflows,
     .timeout = 300)
{
    static bf_geom geom[MAX_CONF];
    static double rho[MAX_CONF];
    bf__solo so;
    bf_problem pb;
    bf_fit_result fit;
    double x[BF_MAX_PARAMS];
    double lo, hi, v;
    unsigned open;
    paint_problem("mystique.brdf", "LAMBERT+LAFORTUNE", geom, rho, &pb);
    pb.free_mask &= ~(1u << 3); /* n held at its bound */
    pb.fixed[3] = pb.hi[3];
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &fit, NULL), BF_OK);
    cr_assert_eq(bf__profile_ci_thr(&so.fc, &fit, 1, 1e6,
                                    bf__profile_step(&pb, 1, fit.param[1]),
                                    &lo, &hi, &open, NULL),
                 BF_OK);
    /* Cxy's upper end short of its bound 2, where the lobe is still a
     * double, and open */
    cr_assert(lo <= fit.param[1] && fit.param[1] < hi, "[%g, %g]", lo, hi);
    cr_assert(hi < pb.hi[1], "Cxy's end %g", hi);
    cr_assert(open & 2u, "Cxy's upper end open");
    memcpy(x, fit.param, sizeof x);
    x[1] = hi;
    cr_assert_eq(bf__fit_value(&so.fc, x, &v), BF_OK,
                 "the lobe at the end is defined");
    bf__solo_free(&so);
}

/* The curve a profile figure draws (bf_fit_interval_curve) is the one the
 * intervals threshold: on krylon_blue's LAMBERT+GGX it is 0 at the
 * maximum-likelihood estimate and crosses its threshold n ln(1 +
 * F_{1,nu}(0.95) / nu), nu = K - 4 free - the noise power, times the
 * parameter's robust factor (>= 1, the one bf_fit_intervals used), at each
 * interval end bf_fit_intervals reports. The objective's own profile
 * (bf_fit_profile_curve) does not: its value at those ends is off. */
Test(spec_intervals, the_interval_curve_crosses_its_threshold_at_the_ends,
     .timeout = 300)
{
    static bf_geom geom[MAX_CONF];
    static double rho[MAX_CONF];
    bf_problem pb;
    bf_fit_result fit;
    bf_interval iv;
    bf__solo so;
    double nu;
    size_t off = 0; /* ends where the objective's profile is off */
    size_t j;
    paint_problem("krylon_blue.brdf", "LAMBERT+GGX", geom, rho, &pb);
    nu = (double)pb.n - 5.0;
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__varpro_fit(&so.fc, NULL, &fit, NULL), BF_OK);
    bf__solo_free(&so);
    cr_assert_eq(bf_fit_intervals(&pb, &fit, BF_NOISE_AUTO, LEVEL, &iv),
                 BF_OK);
    for (j = 0; j < 4; j++) {
        double ends[3] = {iv.low[j], iv.ml.param[j], iv.high[j]};
        double dev[3];
        double obj[3];
        double thr = NAN;
        bf_interval own;
        cr_assert_eq(bf_fit_interval_curve(&pb, &fit, BF_NOISE_AUTO, LEVEL, j,
                                           3, ends, dev, &thr, &own),
                     BF_OK, "%s", pb.type->param[j].name);
        cr_assert(iv.robust[j] >= 1.0, "%s: %g", pb.type->param[j].name,
                  iv.robust[j]);
        cr_expect_eq(own.robust[j], iv.robust[j]);
        bf_assert_rel(thr,
                      (double)pb.n *
                          log1p(gsl_cdf_fdist_Pinv(LEVEL, 1.0, nu) / nu) *
                          iv.robust[j],
                      1e-12);
        cr_expect_eq(own.noise_power, iv.noise_power);
        bf_assert_abs(dev[1], 0.0, 1e-3);
        bf_assert_abs(dev[0], thr, 1e-3);
        bf_assert_abs(dev[2], thr, 1e-3);
        ends[1] = iv.high[j];
        cr_assert_eq(bf_fit_profile_curve(&pb, &fit, j, 2, ends, obj), BF_OK);
        cr_log_info("%s: objective's profile %g, %g at the ends",
                    pb.type->param[j].name, obj[0], obj[1]);
        off += !(fabs(obj[0] - thr) <= 0.1);
        off += !(fabs(obj[1] - thr) <= 0.1);
    }
    cr_expect_eq(off, 8u, "the objective's profile is another curve");
}

/* `brdffit calibrate` on a composite: one row per parameter, coverage in
 * [0, 1] over the 10 simulations. */
Test(spec_intervals, calibrate_runs_on_a_composite, .timeout = 300)
{
    const char *dir = bf_test_tmpdir();
    char out[512];
    const char *err = NULL;
    static const char *const param[3] = {"rho_d", "rho_s", "alpha"};
    size_t j;
    int rc;
    snprintf(out, sizeof out, "%s/cal", dir);
    {
        const char *argv[] = {"calibrate", "--models", "LAMBERT+WARD",
                              "--objective", "ngan", "--sims", "10",
                              "--quiet", "--out", out,
                              bf_test_cornell_path("krylon_blue.brdf"),
                              NULL};
        rc = bf_test_run_cli(argv, NULL, &err);
    }
    cr_assert_eq(rc, 0, "brdffit calibrate: %s", err);
    bf_test_csv_load(out, "calibrate.csv");
    for (j = 0; j < 3; j++) {
        size_t r = bf_test_csv_find("1", "LAMBERT+WARD", param[j]);
        double c = bf_test_csv_num(r, "coverage");
        cr_assert(c >= 0.0 && c <= 1.0, "%s coverage %g", param[j], c);
        cr_assert_eq((int)bf_test_csv_num(r, "n_sim"), 10);
        cr_assert(bf_test_csv_num(r, "width") > 0.0);
    }
}

/* mystique's LAMBERT+GGX under ngan: the narrow lobe (alpha 0.005) rises
 * above 10^-3 of its maximum at only 4 of the 1439 configurations, and the
 * fitted noise power sits on its bound BF_NOISE_PMAX (doc/methods.md §3):
 * `brdffit calibrate` says so under its table, naming the pair; on
 * krylon_blue (p = 1.84) it does not, nor on mystique under --noise
 * relative (p = 2 held, not estimated: no bound reached). */
Test(spec_intervals, calibrate_says_when_the_noise_power_is_at_its_bound,
     .timeout = 300)
{
    static const char *const file[3] = {"mystique.brdf", "krylon_blue.brdf",
                                        "mystique.brdf"};
    static const char *const noise[3] = {"auto", "auto", "relative"};
    /* under the sanitizers mystique's run alone (the note's code; the
     * same calibrate on krylon_blue takes as long) */
    const int n_files = BF_TEST_SANITIZED ? 1 : 3;
    const char *dir = bf_test_tmpdir();
    char out[512];
    int i;
    for (i = 0; i < n_files; i++) {
        const char *text = NULL;
        const char *err = NULL;
        size_t r;
        int rc;
        snprintf(out, sizeof out, "%s/bound%d", dir, i);
        {
            const char *argv[] = {"calibrate", "--models", "LAMBERT+GGX",
                                  "--objective", "ngan", "--noise", noise[i],
                                  "--sims", "10",
                                  "--threads", "1", "--out", out,
                                  bf_test_cornell_path(file[i]), NULL};
            rc = bf_test_run_cli(argv, &text, &err);
        }
        cr_assert_eq(rc, 0, "brdffit calibrate %s: %s", file[i], err);
        bf_test_csv_load(out, "calibrate.csv");
        r = bf_test_csv_find("1", "LAMBERT+GGX", "alpha");
        if (i == 0) {
            cr_assert_eq(bf_test_csv_num(r, "noise_power"), BF_NOISE_PMAX);
            cr_assert_not_null(strstr(text, "Noise power at its bound: "
                                            "sample 1 LAMBERT+GGX: "),
                               "%s", text);
        } else {
            cr_assert(i == 2 ? bf_test_csv_num(r, "noise_power") == 2.0
                             : bf_test_csv_num(r, "noise_power") <
                                   BF_NOISE_PMAX);
            cr_assert_null(strstr(text, "Noise power at its bound"), "%s",
                           text);
        }
    }
}
