/* test_intervals.c: the default intervals under their noise model
 * (doc/methods.md §3, issue 18) -- coverage of the paper's models on data
 * normalised by their own noisy maximum, as measured data are, under
 * relative and absolute noise and the objectives max, scale and log;
 * the residual bootstrap on the same kind of data, and its bad input;
 * bf_fit_calibrate on a synthetic material whose answer is known; the
 * not-identified flag on constructed flat profiles; bad input.
 *
 * Acceptance band: R = 200 simulations, a correct 95% interval covers the
 * truth Binomial(200, 0.95) times: sd 0.0154, band [0.90, 0.99] (-3.2 sd,
 * +2.6 sd; the seeds are fixed). The intervals before issue 18 (the
 * objective's S, the scale fixed by the noisy maximum: BF_NOISE_OBJECTIVE)
 * fail it: FC-E's n under max and 5% relative noise covers about half
 * (0.46; checked below, so the test can tell the two apart). Width: the median
 * width over 2 z sd of the estimates the intervals are about within
 * [1/1.3, 1.3] (issue 18's contract) where the parameter is identified.
 * The truths: 37 % of each search range, FC-E's n at 15 % (off the fold
 * of its profile, bf_test_truth_at). */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <string.h>

#include "fit/engine.h"
#include "support.h"

#define LEVEL 0.95
#define SEED 20261202ul
#if !BF_TEST_SANITIZED
#define REPS 200
#define COVER_LO 0.90
#define COVER_HI 0.99
#define WIDTH_TOL 1.3
#else
/* The sanitizer build runs the same code on 20 simulations, no band. */
#define REPS 20
#define COVER_LO 0.0
#define COVER_HI 1.0
#define WIDTH_TOL HUGE_VAL
#endif
#define STRIDE 2 /* every second CURET configuration: K = 99 */

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(intervals, .init = setup);


/* pb for the exact fit's variant of base on geom, truth at 37% of each
 * search range (n at 15 %, bf_test_truth_at). */
static void problem(bf_model_variant *v, const bf_model_type *base,
                    size_t n, const bf_geom *geom, bf_objective obj,
                    bf_problem *pb, double *truth)
{
    size_t j;
    bf_model_variant_init(v, base);
    bf_model_variant_exact(v, 0);
    cr_assert_eq(bf_problem_init(pb, &v->type, NULL, n, geom, NULL), BF_OK);
    pb->objective = obj;
    for (j = 0; j < v->type.p; j++) {
        truth[j] = pb->fixed[j];
        if ((pb->free_mask >> j) & 1u) {
            truth[j] = bf_test_truth_at(pb, j);
        }
        pb->fixed[j] = truth[j];
    }
}

/* REPS simulations of base at CURET's geometry (every STRIDE-th
 * configuration) under noise power p (sd sd at the maximum), fitted under
 * obj, with n_boot bootstrap replicates each (0: none), into *cal; *v and
 * *pb the problem simulated. Nearly all simulations must fit. */
static void calibrated(const bf_model_type *base, double p, double sd,
                       bf_objective obj, size_t n_boot, bf_model_variant *v,
                       bf_problem *pb, bf_calibration *cal)
{
    static bf_geom geom[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    double truth[BF_MAX_PARAMS];
    problem(v, base, n, geom, obj, pb, truth);
    cr_assert_eq(bf_fit_calibrate(pb, truth, p, sd, BF_NOISE_AUTO, REPS, n_boot,
                                  0, 0, SEED, LEVEL, cal),
                 BF_OK);
    cr_assert_geq(cal->n_sim, REPS - REPS / 50, "%s: %zu fitted", base->name,
                  cal->n_sim);
}

/* Coverage and width of the default intervals of base under noise power
 * p (sd sd at the maximum) and objective obj. */
static void check(const bf_model_type *base, double p, double sd,
                  bf_objective obj)
{
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    size_t j;
    calibrated(base, p, sd, obj, 0, &v, &pb, &cal);
    for (j = 0; j < v.type.p; j++) {
        double ratio;
        if (!((pb.free_mask >> j) & 1u)) {
            continue;
        }
        ratio = cal.width[j] / (2.0 * 1.959964 * cal.ml_sd[j]);
        cr_log_info("%s %s p=%g %s: coverage %.3f width/spread %.2f",
                    base->name, v.type.param[j].name, p,
                    bf_objective_name(obj), cal.coverage[j], ratio);
        cr_expect(cal.coverage[j] >= COVER_LO && cal.coverage[j] <= COVER_HI,
                  "%s %s (p = %g, %s): coverage %.3f", base->name,
                  v.type.param[j].name, p, bf_objective_name(obj),
                  cal.coverage[j]);
        /* the width where the parameter is identified: off the fold of
         * the Fresnel index (bf_test_truth_at) the estimates fall on two
         * branches, about half the intervals span both (flagged), and
         * the estimates' sd is the branches' distance, no interval's
         * width (doc/methods.md §3, "Split sets") */
        cr_log_info("%s %s: not identified in %.3f", base->name,
                    v.type.param[j].name, cal.not_identified[j]);
        cr_expect(cal.not_identified[j] >= 0.05 ||
                      (ratio <= WIDTH_TOL && ratio >= 1.0 / WIDTH_TOL),
                  "%s %s (p = %g, %s): width / spread %.2f", base->name,
                  v.type.param[j].name, p, bf_objective_name(obj), ratio);
    }
}

Test(intervals, cover_under_relative_noise_and_the_max_objective,
     .timeout = 300)
{
    check(bf_model_bk_e, 2.0, 0.05, BF_OBJ_MAX);
    check(bf_model_vh_e, 2.0, 0.05, BF_OBJ_MAX);
    check(bf_model_fc_e, 2.0, 0.05, BF_OBJ_MAX);
}

Test(intervals, cover_under_absolute_noise_and_the_max_objective,
     .timeout = 300)
{
    check(bf_model_fc_e, 0.0, 0.02, BF_OBJ_MAX);
}

/* The scale and log objectives score their grids one curve at a time
 * (src/fit/curves.c), so they run on the one-parameter models here;
 * bench_coverage runs every model under every objective. */
Test(intervals, cover_under_absolute_noise_and_the_scale_objective,
     .timeout = 300)
{
    check(bf_model_bk_g, 0.0, 0.02, BF_OBJ_SCALE);
}

Test(intervals, cover_under_relative_noise_and_the_log_objective,
     .timeout = 300)
{
    check(bf_model_vh_e, 2.0, 0.05, BF_OBJ_LOG);
}

/* The intervals before issue 18 (scale from the noisy maximum, constant
 * variance) on the same data: far below 95% -- the failure the default
 * intervals fix, and proof that the band above can fail. */
Test(intervals, the_objectives_own_profile_undercovers_under_max,
     .timeout = 300)
{
    static bf_geom geom[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    double truth[BF_MAX_PARAMS];
    problem(&v, bf_model_fc_e, n, geom, BF_OBJ_MAX, &pb, truth);
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_OBJECTIVE,
                                  REPS, 0, 0, 0, SEED, LEVEL, &cal),
                 BF_OK);
    cr_log_info("FC-E old profile: m %.3f n %.3f", cal.coverage[0],
                cal.coverage[1]);
    if (REPS >= 200) {
        cr_expect_lt(cal.coverage[1], 0.7, "n: %.3f", cal.coverage[1]);
    }
}

/* ==== the residual bootstrap ============================================= */

/* Replicates of each bootstrap interval (the percentile's quantiles are
 * those of 99 refits). */
#define BOOT_B 199

/* Coverage of the bootstrap's intervals (bf_fit_bootstrap,
 * src/fit/bootstrap.c) through bf_fit_calibrate: data simulated at the truth
 * with noise of power p, normalised by the noisy maximum, fitted under
 * obj, the noise model's intervals and each simulation's bootstrap. The
 * resampling of configurations it replaced covered 16-19 of 40 under max
 * (issue 18): the value that sets the scale is not resampled. FC-E (two
 * parameters, 200 x 199 refits) is measured by bench_coverage, not here
 * (about 30 s; bench/RESULTS.md). */
static void boot_check(const bf_model_type *base, double p, double sd,
                       bf_objective obj)
{
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    size_t j;
    calibrated(base, p, sd, obj, BOOT_B, &v, &pb, &cal);
    for (j = 0; j < v.type.p; j++) {
        if (!((pb.free_mask >> j) & 1u)) {
            cr_assert(isnan(cal.boot_coverage[j]));
            continue;
        }
        cr_log_info("%s %s p=%g %s: bootstrap coverage %.3f width %.3g "
                    "(profile %.3f, %.3g)", base->name, v.type.param[j].name,
                    p, bf_objective_name(obj), cal.boot_coverage[j],
                    cal.boot_width[j], cal.coverage[j], cal.width[j]);
        cr_assert_gt(cal.boot_width[j], 0.0);
        cr_expect(cal.boot_coverage[j] >= COVER_LO &&
                      cal.boot_coverage[j] <= COVER_HI,
                  "%s %s (p = %g, %s): bootstrap coverage %.3f", base->name,
                  v.type.param[j].name, p, bf_objective_name(obj),
                  cal.boot_coverage[j]);
    }
}

Test(intervals, the_bootstrap_covers_under_absolute_noise_and_max,
     .timeout = 300)
{
    boot_check(bf_model_vh_e, 0.0, 0.02, BF_OBJ_MAX);
}

Test(intervals, the_bootstrap_needs_the_noise_model)
{
    static bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    bf_model_variant v;
    bf_problem pb;
    bf_interval iv;
    double truth[BF_MAX_PARAMS];
    double lo[BF_MAX_PARAMS];
    double hi[BF_MAX_PARAMS];
    problem(&v, bf_model_vh_e, n, geom, BF_OBJ_MAX, &pb, truth);
    cr_assert_eq(bf_model_eval(&v.type, truth, n, geom, data), BF_OK);
    pb.data = data;
    memset(&iv, 0, sizeof iv);
    iv.method = BF_CI_PROFILE; /* the objective's own: no noise model */
    cr_assert_eq(bf_fit_bootstrap(&pb, &iv, 20, SEED, LEVEL, lo, hi),
                 BF_EDOM);
    cr_assert(isnan(lo[0]) && isnan(hi[0]));
    cr_assert_eq(bf_fit_bootstrap(&pb, &iv, 1, SEED, LEVEL, lo, hi),
                 BF_EINVAL);
    cr_assert_str_eq(bf_ci_method_name(BF_CI_RESIDUAL_BOOTSTRAP),
                     "residual-bootstrap");
}

/* ==== calibrate on a known answer ======================================== */

/* The calibration's truth and bias: simulations at the truth give
 * estimates whose mean is the truth within 4 standard errors, and the
 * bias of the max objective's estimates is what is reported. */
Test(intervals, calibrate_reports_coverage_and_bias_of_a_known_material)
{
    static bf_geom geom[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    double truth[BF_MAX_PARAMS];
    size_t reps = REPS < 100 ? REPS : 100;
    problem(&v, bf_model_bk_e, n, geom, BF_OBJ_SCALE, &pb, truth);
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 0.0, 0.02, BF_NOISE_ABSOLUTE,
                                  reps, 0, 0, 0, SEED, LEVEL, &cal),
                 BF_OK);
    cr_assert_eq(cal.n_sim + cal.n_failed, reps);
    cr_assert_float_eq(cal.truth[0], truth[0], 0.0);
    cr_assert_lt(fabs(cal.bias[0]), 4.0 * cal.sd[0] / sqrt((double)reps),
                 "bias %.3g sd %.3g", cal.bias[0], cal.sd[0]);
    cr_assert_gt(cal.sd[0], 0.0);
    cr_assert_gt(cal.width[0], 0.0);
    cr_assert(cal.coverage[0] >= 0.0 && cal.coverage[0] <= 1.0);
    cr_assert(isnan(cal.coverage[1]), "not a parameter: NaN");
}

/* ==== not identified ====================================================== */

/* A model of two parameters where a sets the shape, cos(theta_i)^a, and b
 * almost nothing: (1 + EPS_B b sin theta_s) -- a profile in b that is flat
 * to every bound. EPS_B 0: b has no effect at all. */
static double eps_b;

static int flat_eval(const double *param, size_t n, const bf_geom *geom,
                     double *out, void *work)
{
    size_t k;
    (void)work;
    for (k = 0; k < n; k++) {
        out[k] = pow(cos(geom[k].theta_i), param[0]) *
                 (1.0 + eps_b * param[1] * sin(geom[k].theta_s));
    }
    return BF_OK;
}

static const bf_param flat_params[2] = {
    {.name = "a", .label = "a", .unit = "1", .min = 0.0, .max = 10.0,
     .value = 1.0, .fitted = 1, .grid_lo = 0.5, .grid_step = 0.05,
     .grid_n = 51, .input = BF_INPUT_DEFAULT},
    {.name = "b", .label = "b", .unit = "1", .min = 0.0, .max = 1.0,
     .value = 0.5, .fitted = 1, .grid_lo = 0.0, .grid_step = 0.05,
     .grid_n = 21, .input = BF_INPUT_DEFAULT},
};

static const bf_model_type flat_type = {
    .name = "FLAT", .title = "test: b without effect", .reference = "test",
    .p = 2, .param = flat_params, .eval = flat_eval,
};

static void flat_case(double eps)
{
    static bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    double truth[2] = {1.3, 0.4};
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    size_t k;
    bf_problem pb;
    bf_curves *c;
    bf_fit_result g;
    bf_fit_result best;
    bf_interval iv;
    int st;
    eps_b = eps;
    cr_assert_eq(flat_eval(truth, n, geom, data, NULL), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    for (k = 0; k < n; k++) { /* a fixed, deterministic 2% "noise" */
        data[k] *= 1.0 + 0.02 * sin(12.9898 * (double)k);
    }
    cr_assert_eq(bf_problem_init(&pb, &flat_type, truth, n, geom, data),
                 BF_OK);
    cr_assert_eq(pb.free_mask, 3u);
    c = bf_curves_alloc(&pb, &st);
    cr_assert_not_null(c);
    cr_assert_eq(bf_curves_best(c, &pb, &g), BF_OK);
    st = bf_fit_refine(&pb, &g, &best);
    cr_assert(st == BF_OK || st == BF_ENOCONV);
    cr_assert_eq(bf_fit_intervals(&pb, &best, BF_NOISE_AUTO, LEVEL, &iv),
                 BF_OK);
    cr_assert_eq(iv.method, BF_CI_PROFILE_LIK);
    /* b: the bounds, both ends open, flagged */
    cr_expect_float_eq(iv.low[1], 0.0, 0.0, "b low %.9g", iv.low[1]);
    cr_expect_float_eq(iv.high[1], 1.0, 0.0, "b high %.9g", iv.high[1]);
    cr_expect_eq((iv.open >> 2) & 3u, 3u);
    cr_expect_eq((iv.not_identified >> 1) & 1u, 1u);
    /* a: identified, a closed interval around its estimate */
    cr_expect_eq(iv.open & 3u, 0u);
    cr_expect_eq(iv.not_identified & 1u, 0u);
    cr_expect(iv.low[0] < iv.ml.param[0] && iv.ml.param[0] < iv.high[0]);
    cr_expect_lt(iv.high[0] - iv.low[0], 0.5);
    bf_curves_free(c);
}

Test(intervals, a_parameter_without_effect_is_not_identified)
{
    flat_case(0.0);
}

Test(intervals, a_nearly_flat_profile_is_open_to_its_bounds)
{
    flat_case(1e-6);
}

/* ==== bad input ============================================================ */

/* ==== split sets ========================================================= */

/* One parameter a, L = cos(theta_i)^e(a). SPLIT_FOLD: e = 0.5 + (a - 2)^2,
 * so a and 4 - a give one shape (two regions apart, the fold at 2 between
 * them). SPLIT_RIDGE: e = 1 + 0.05 a + 0.3 max(0, 1 - |a - c| / 0.005), a
 * rise far narrower than the outward walk's steps from the estimate, at c
 * five eighths of the way from the estimate to the upper end the slope
 * alone gives (ridge_at, 0: no rise). */
enum { SPLIT_FOLD, SPLIT_RIDGE };
static int split_mode;
static double ridge_at;

static double split_exponent(double a)
{
    if (split_mode == SPLIT_FOLD) {
        return 0.5 + (a - 2.0) * (a - 2.0);
    }
    return 1.0 + 0.05 * a +
           (ridge_at > 0.0 ? 0.3 * fmax(0.0, 1.0 - fabs(a - ridge_at) / 0.005)
                           : 0.0);
}

static int split_eval(const double *param, size_t n, const bf_geom *geom,
                      double *out, void *work)
{
    double e = split_exponent(param[0]);
    size_t k;
    (void)work;
    for (k = 0; k < n; k++) {
        out[k] = pow(cos(geom[k].theta_i), e);
    }
    return BF_OK;
}

static const bf_param split_params[1] = {
    {.name = "a", .label = "a", .unit = "1", .min = 0.0, .max = 4.0,
     .value = 1.3, .fitted = 1, .grid_lo = 0.0, .grid_step = 0.05,
     .grid_n = 81, .input = BF_INPUT_DEFAULT},
};

static const bf_model_type split_type = {
    .name = "SPLIT", .title = "test: a split profile", .reference = "test",
    .p = 1, .param = split_params, .eval = split_eval,
};

/* The intervals of a (truth 1.3, a fixed deterministic 2% "noise") under
 * mode; the gap's ends on the threshold, its middle above it, the two
 * segments' insides below it (the criterion's curve). */
static void split_fit(int mode, bf_interval *iv, bf_problem *pb,
                      bf_fit_result *best, double *data, bf_geom *geom)
{
    double truth[1] = {1.3};
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    size_t k;
    bf_curves *c;
    bf_fit_result g;
    int st;
    split_mode = mode;
    cr_assert_eq(split_eval(truth, n, geom, data, NULL), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    for (k = 0; k < n; k++) {
        data[k] *= 1.0 + 0.02 * sin(12.9898 * (double)k);
    }
    cr_assert_eq(bf_problem_init(pb, &split_type, truth, n, geom, data),
                 BF_OK);
    c = bf_curves_alloc(pb, &st);
    cr_assert_not_null(c);
    cr_assert_eq(bf_curves_best(c, pb, &g), BF_OK);
    st = bf_fit_refine(pb, &g, best);
    cr_assert(st == BF_OK || st == BF_ENOCONV);
    bf_curves_free(c);
    cr_assert_eq(bf_fit_intervals(pb, best, BF_NOISE_AUTO, LEVEL, iv),
                 BF_OK);
}

static void split_case(int mode, bf_interval *iv)
{
    static bf_geom geom[BF_CURET_NCONF];
    static double data[BF_CURET_NCONF];
    bf_problem pb;
    bf_fit_result best;
    double theta[5];
    double dev[5];
    double thr;
    ridge_at = 0.0;
    if (mode == SPLIT_RIDGE) { /* where the end is without the rise */
        split_fit(mode, iv, &pb, &best, data, geom);
        cr_assert(isnan(iv->gap_low[0]), "no rise, no gap");
        ridge_at = iv->ml.param[0] + 0.625 * (iv->high[0] - iv->ml.param[0]);
    }
    split_fit(mode, iv, &pb, &best, data, geom);
    cr_log_info("a in [%.6f, %.6f], gap (%.6f, %.6f), estimate %.6f",
                iv->low[0], iv->high[0], iv->gap_low[0], iv->gap_high[0],
                iv->ml.param[0]);
    cr_assert(isfinite(iv->gap_low[0]) && isfinite(iv->gap_high[0]),
              "a split set has its gap");
    cr_assert(iv->low[0] < iv->gap_low[0] && iv->gap_low[0] < iv->gap_high[0]
              && iv->gap_high[0] < iv->high[0]);
    cr_expect_eq(iv->not_identified & 1u, 1u, "split: flagged");
    theta[0] = 0.5 * (iv->low[0] + iv->gap_low[0]);   /* inside */
    theta[1] = iv->gap_low[0];                         /* on it */
    theta[2] = 0.5 * (iv->gap_low[0] + iv->gap_high[0]); /* outside */
    theta[3] = iv->gap_high[0];
    theta[4] = 0.5 * (iv->gap_high[0] + iv->high[0]);
    cr_assert_eq(bf_fit_interval_curve(&pb, &best, BF_NOISE_AUTO, LEVEL, 0,
                                       5, theta, dev, &thr, NULL),
                 BF_OK);
    cr_expect_leq(dev[0], thr, "below segment: %g vs %g", dev[0], thr);
    cr_expect_leq(dev[4], thr, "above segment: %g vs %g", dev[4], thr);
    cr_expect_gt(dev[2], thr, "the gap: %g vs %g", dev[2], thr);
    cr_expect_float_eq(dev[1], thr, 1e-3 * thr, "gap low end: %g", dev[1]);
    cr_expect_float_eq(dev[3], thr, 1e-3 * thr, "gap high end: %g", dev[3]);
    /* what a caller asks of the set */
    cr_expect(bf_interval_holds(iv, 0, iv->ml.param[0]));
    cr_expect(bf_interval_holds(iv, 0, theta[0]));
    cr_expect(bf_interval_holds(iv, 0, theta[4]));
    cr_expect(!bf_interval_holds(iv, 0, theta[2]), "the gap is outside");
    cr_expect(!bf_interval_holds(iv, 0, iv->high[0] + 1e-3));
    cr_expect_float_eq(bf_interval_length(iv, 0),
                       (iv->high[0] - iv->low[0]) -
                           (iv->gap_high[0] - iv->gap_low[0]),
                       1e-12);
}

/* The profile's two branches (a, 4 - a) are reported as two segments, not
 * their hull across the fold. */
Test(intervals, a_set_in_two_regions_apart_is_two_segments)
{
    bf_interval iv;
    split_case(SPLIT_FOLD, &iv);
    cr_expect(bf_interval_holds(&iv, 0, 4.0 - iv.ml.param[0]),
              "the mirror branch is inside");
    cr_expect(!bf_interval_holds(&iv, 0, 2.0), "the fold is outside");
}

/* A narrow rise above the threshold between the estimate and its end, which
 * the outward walk steps over, splits the set too. */
Test(intervals, a_ridge_inside_the_interval_splits_it)
{
    bf_interval iv;
    split_case(SPLIT_RIDGE, &iv);
    cr_expect(!bf_interval_holds(&iv, 0, ridge_at), "the ridge is outside");
    cr_expect_lt(iv.gap_high[0] - iv.gap_low[0], 0.1, "a narrow gap");
}

/* A parameter without a split has no gap: its set is one segment. */
Test(intervals, one_region_has_no_gap)
{
    bf_interval iv;
    memset(&iv, 0, sizeof iv);
    iv.low[0] = 1.0;
    iv.high[0] = 2.0;
    iv.gap_low[0] = iv.gap_high[0] = NAN;
    cr_expect(bf_interval_holds(&iv, 0, 1.5));
    cr_expect(bf_interval_holds(&iv, 0, 1.0) && bf_interval_holds(&iv, 0, 2.0));
    cr_expect(!bf_interval_holds(&iv, 0, 2.5));
    cr_expect_float_eq(bf_interval_length(&iv, 0), 1.0, 1e-15);
    iv.low[0] = NAN;
    cr_expect(!bf_interval_holds(&iv, 0, 1.5), "no interval holds nothing");
    cr_expect(isnan(bf_interval_length(&iv, 0)));
}

Test(intervals, an_unknown_noise_word_is_not_found)
{
    bf_noise nz = BF_NOISE_RELATIVE;
    cr_assert_eq(bf_noise_find("gaussian", &nz), BF_ENOTFOUND);
    cr_assert_eq(nz, BF_NOISE_RELATIVE);
    cr_assert_eq(bf_noise_find("relative", &nz), BF_OK);
    cr_assert_eq(nz, BF_NOISE_RELATIVE);
    cr_assert_null(bf_noise_name((bf_noise)17));
    /* what each model states, for the captions */
    cr_assert_str_eq(bf_noise_variance(BF_NOISE_ABSOLUTE),
                     "constant variance");
    cr_assert_str_eq(bf_noise_variance(BF_NOISE_RELATIVE),
                     "variance ~ value^2");
    cr_assert_not_null(strstr(bf_noise_variance(BF_NOISE_AUTO), "fitted"));
    cr_assert_null(bf_noise_variance((bf_noise)17));
}

Test(intervals, calibrate_refuses_fewer_than_ten_simulations)
{
    static bf_geom geom[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, STRIDE);
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    double truth[BF_MAX_PARAMS];
    problem(&v, bf_model_bk_e, n, geom, BF_OBJ_MAX, &pb, truth);
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_AUTO, 9, 0,
                                  0, 0, SEED, LEVEL, &cal),
                 BF_EINVAL);
}

/* K = 3 configurations for FC-E (m, n, the scale, the noise power): no
 * degree of freedom is left for the noise -- an error, never an interval. */
Test(intervals, the_noise_of_too_few_configurations_cannot_be_estimated)
{
    static bf_geom geom[BF_CURET_NCONF];
    double data[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, 40);
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    bf_fit_result best;
    bf_interval iv;
    double truth[BF_MAX_PARAMS];
    cr_assert_geq(n, 4u);
    problem(&v, bf_model_fc_e, 4, geom, BF_OBJ_MAX, &pb, truth);
    cr_assert_eq(bf_model_eval(&v.type, truth, 4, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(4, data, data), BF_OK);
    pb.data = data;
    memset(&best, 0, sizeof best);
    memcpy(best.param, truth, sizeof best.param);
    cr_assert_eq(bf_fit_intervals(&pb, &best, BF_NOISE_AUTO, LEVEL, &iv),
                 BF_EDOM);
    cr_assert(isnan(iv.low[0]) && isnan(iv.high[1]));
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_AUTO, 20, 0,
                                  0, 0, SEED, LEVEL, &cal),
                 BF_EDOM);
    /* with p fixed one degree of freedom is left: intervals exist */
    cr_assert_eq(bf_fit_intervals(&pb, &best, BF_NOISE_RELATIVE, LEVEL, &iv),
                 BF_OK);
}

/* The likelihood threshold n ln(1 + F_{1,nu}(0.95) / nu): GSL's F
 * quantile at small nu, and finite on dense data (a MERL table, nu ~ 9e5),
 * where GSL's F quantile is NaN and every interval would run to its
 * bounds; it tends to chi2_1's 3.841 (n = nu + 4 here). */
Test(intervals, the_threshold_is_the_f_form_and_finite_on_dense_data)
{
    static const double nus[] = {3.0, 194.0, 1435.0, 71995.0};
    size_t i;
    for (i = 0; i < sizeof nus / sizeof nus[0]; i++) {
        double nu = nus[i];
        bf_assert_rel(bf__lik_threshold(nu + 4.0, nu, 0.95),
                      (nu + 4.0) *
                          log1p(gsl_cdf_fdist_Pinv(0.95, 1.0, nu) / nu),
                      1e-10);
    }
    bf_assert_abs(bf__lik_threshold(909696.0, 909691.0, 0.95),
                  3.841458820694124, 1e-4);
    cr_assert(isfinite(bf__lik_threshold(1e9 + 4.0, 1e9, 0.95)));
}
