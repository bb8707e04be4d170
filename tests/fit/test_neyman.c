/* test_neyman.c: the Neyman construction (src/fit/neyman.c,
 * doc/methods.md §3, ci_method "neyman") -- the coverage of the default
 * intervals (the construction where a second minimum of the profile
 * competes, bf_analysis_opts_init) where the F threshold's falls short,
 * the policy of which parameters are constructed, the construction's
 * agreement with the F threshold where the likelihood is regular, and its
 * bad input.
 *
 * The case that needs it: WNO's Fresnel index n at 15 % of its range at
 * CURET's 198 configurations under 5 % relative noise. WNO's normalised
 * shape folds over n (two values either side of about 1.7 give nearly the
 * same shape), so the likelihood has two basins and the deviance at the
 * truth is larger than chi2_1 says (the look-elsewhere effect): the F
 * threshold's intervals covered 0.900-0.915 of 400 simulations as hulls
 * (bench/RESULTS.md); as two segments where the set is split, 0.875 of
 * the 200 here (the default, which constructs where the profile's second
 * minimum competes -- nearly every simulation here -- 0.935; every
 * parameter's construction, --neyman 100, the same: WNO has n alone free,
 * and it competes in 99.5 % of these simulations, so that case is not run
 * twice). R = 200 simulations: a correct
 * 95 % interval covers Binomial(200, 0.95) times, sd 0.0154; the band
 * [0.92, 0.99] (-1.9 sd, +2.6 sd; the seeds are fixed) is issue 18's
 * 95 % +- 3 % and excludes 0.90. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <string.h>

#include "fit/engine.h"
#include "support.h"

#define LEVEL 0.95
#define SEED 20261206ul
#if !BF_TEST_SANITIZED
#define REPS 200
#define NY_REGULAR 200
#define COVER_LO 0.92
#define COVER_HI 0.99
#else
/* The sanitizer build runs the same code on 10 simulations, no band. */
#define REPS 10
#define NY_REGULAR 200 /* the same check: one fit, 8 s plain */
#define COVER_LO 0.0
#define COVER_HI 1.0
#endif

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(neyman, .init = setup);

/* pb: the exact fit's variant of base at CURET's geometry (every stride-th
 * configuration), truth at bf_test_truth_at (n at 15 % of its range, the
 * others at 37 %). */
static void problem(bf_model_variant *v, const bf_model_type *base,
                    size_t stride, bf_problem *pb, double *truth)
{
    static bf_geom geom[BF_CURET_NCONF];
    size_t n = bf_test_curet_geometry(geom, stride);
    size_t j;
    bf_model_variant_init(v, base);
    bf_model_variant_exact(v, 0);
    cr_assert_eq(bf_problem_init(pb, &v->type, NULL, n, geom, NULL), BF_OK);
    for (j = 0; j < v->type.p; j++) {
        truth[j] = pb->fixed[j];
        if ((pb->free_mask >> j) & 1u) {
            truth[j] = bf_test_truth_at(pb, j);
        }
        pb->fixed[j] = truth[j];
    }
}

Test(neyman, the_default_intervals_cover_where_the_F_threshold_falls_short,
     .timeout = 900)
{
    bf_model_variant v;
    bf_problem pb;
    bf_calibration cal;
    bf_analysis_opts o;
    double truth[BF_MAX_PARAMS];
    size_t n;
    bf_analysis_opts_init(&o); /* the default: where a minimum competes */
    problem(&v, bf_model_wno, 1, &pb, truth);
    n = (size_t)bf_model_param_index(&v.type, "n");
    cr_assert((pb.free_mask >> n) & 1u);
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_AUTO, REPS,
                                  0, o.n_neyman, o.neyman_every, SEED, LEVEL,
                                  &cal),
                 BF_OK);
    cr_assert_geq(cal.n_sim, REPS - REPS / 50, "%zu fitted", cal.n_sim);
    cr_log_info("WNO n = %.4f: F threshold %.3f, default %.3f (width %.4f "
                "against %.4f; %.3f competing)",
                truth[n], cal.f_coverage[n], cal.coverage[n], cal.width[n],
                cal.f_width[n], cal.competing[n]);
    cr_assert(cal.coverage[n] >= COVER_LO && cal.coverage[n] <= COVER_HI,
              "WNO n: the default intervals covered %.3f", cal.coverage[n]);
#if !BF_TEST_SANITIZED
    /* the case is one: the F threshold alone falls short, and a second
     * minimum competes in most simulations */
    cr_assert_lt(cal.f_coverage[n], COVER_LO, "F threshold %.3f",
                 cal.f_coverage[n]);
    cr_assert_gt(cal.competing[n], 0.5, "%.3f competing", cal.competing[n]);
#endif
}

/* Where the likelihood is regular (FC-E's roughness m, well inside its
 * range, on one simulated measurement) the simulated threshold is the F
 * threshold up to simulation error: at 200 simulations its 95 % quantile
 * has an sd of about 0.5 against 3.9, which moves an end by about 6 % of
 * the half-width; the ends agree within a quarter of it. A threshold from
 * the wrong quantile, the wrong noise or a refit that misses the optimum
 * moves them further. */
Test(neyman, agrees_with_the_F_threshold_where_the_likelihood_is_regular,
     .timeout = 600)
{
    bf_model_variant v;
    bf_problem pb;
    bf_interval iv;
    bf_fit_result best;
    double truth[BF_MAX_PARAMS];
    double curve[BF_CURET_NCONF];
    double d[BF_CURET_NCONF];
    bf_interval ny;
    size_t m = (size_t)bf_model_param_index(bf_model_fc_e, "m");
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    bf__solo so;
    double half;
    problem(&v, bf_model_fc_e, 2, &pb, truth);
    cr_assert_eq(bf__solo_init(&so, &pb), BF_OK);
    cr_assert_eq(bf__curve(&so.pm, truth, so.fc.work, curve), BF_OK);
    bf__solo_free(&so);
    gsl_rng_set(rng, SEED);
    cr_assert(bf__simulate(&pb, curve, 0.0, 2.0, 0.05, rng, d));
    gsl_rng_free(rng);
    pb.data = d;
    cr_assert_eq(bf_fit_minimise(&pb, truth, &best), BF_OK);
    cr_assert_eq(bf_fit_intervals(&pb, &best, BF_NOISE_AUTO, LEVEL, &iv),
                 BF_OK);
    cr_assert_eq(bf_fit_neyman(&pb, &iv, pb.free_mask, NY_REGULAR, SEED, LEVEL, &ny),
                 BF_OK);
    half = 0.5 * (iv.high[m] - iv.low[m]);
    cr_log_info("FC-E m: F [%.4f, %.4f], Neyman [%.4f, %.4f]", iv.low[m],
                iv.high[m], ny.low[m], ny.high[m]);
    cr_assert_eq(ny.method, BF_CI_NEYMAN);
    cr_assert_eq(ny.open & (3u << (2 * m)), 0u, "m is inside its range");
    cr_assert(isnan(ny.gap_low[m]) && isnan(ny.gap_high[m]), "one region");
    cr_assert(half > 0.0);
    cr_assert_leq(fabs(ny.low[m] - iv.low[m]), 0.25 * half,
                  "low %.4f vs %.4f", ny.low[m], iv.low[m]);
    cr_assert_leq(fabs(ny.high[m] - iv.high[m]), 0.25 * half,
                  "high %.4f vs %.4f", ny.high[m], iv.high[m]);
    cr_assert(ny.low[m] < iv.ml.param[m] && iv.ml.param[m] < ny.high[m]);
}

Test(neyman, refuses_what_it_cannot_do)
{
    bf_model_variant v;
    bf_problem pb;
    bf_interval iv;
    bf_analysis_opts o;
    bf_calibration cal;
    double truth[BF_MAX_PARAMS];
    bf_interval ny;
    static double d[BF_CURET_NCONF];
    size_t k;
    problem(&v, bf_model_fc_e, 2, &pb, truth);
    for (k = 0; k < pb.n; k++) {
        d[k] = 1.0;
    }
    pb.data = d;
    memset(&iv, 0, sizeof iv);
    iv.method = BF_CI_PROFILE_LIK;
    /* too few simulations for a 95 % quantile */
    cr_assert_eq(bf_fit_neyman(&pb, &iv, pb.free_mask, BF_NEYMAN_MIN_SIM - 1, SEED, LEVEL,
                               &ny),
                 BF_EINVAL);
    cr_assert_eq(bf_fit_neyman(&pb, NULL, pb.free_mask, BF_NEYMAN_MIN_SIM, SEED, LEVEL, &ny),
                 BF_EINVAL);
    cr_assert_eq(bf_fit_neyman(&pb, &iv, pb.free_mask, BF_NEYMAN_MIN_SIM, SEED, LEVEL, NULL),
                 BF_EINVAL);
    /* no noise model: nothing to simulate */
    iv.method = BF_CI_PROFILE;
    iv.low[0] = iv.low[1] = 0.0;
    iv.high[0] = iv.high[1] = 1.0;
    cr_assert_eq(bf_fit_neyman(&pb, &iv, pb.free_mask, BF_NEYMAN_MIN_SIM, SEED, LEVEL, &ny),
                 BF_EDOM);
    /* the analysis's options */
    bf_analysis_opts_init(&o);
    cr_assert_eq(o.n_neyman, (size_t)BF_NEYMAN_AUTO_SIM,
                 "the construction where a minimum competes by default");
    cr_assert_eq(o.neyman_every, 0);
    o.n_neyman = BF_NEYMAN_MIN_SIM - 1;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_EINVAL);
    o.n_neyman = BF_NEYMAN_MIN_SIM;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_OK);
    /* the default needs no intervals' noise model: it makes nothing */
    o.no_intervals = 1;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_OK);
    o.noise = BF_NOISE_OBJECTIVE;
    o.no_intervals = 0;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_OK);
    /* every parameter's does */
    o.neyman_every = 1;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_EINVAL);
    o.noise = BF_NOISE_AUTO;
    o.no_intervals = 1;
    cr_assert_eq(bf_analysis_opts_check(&o, NULL), BF_EINVAL);
    /* calibrate: too few, or with the objective's own noise model */
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_AUTO, 20,
                                  0, BF_NEYMAN_MIN_SIM - 1, 0, SEED, LEVEL,
                                  &cal),
                 BF_EINVAL);
    cr_assert_eq(bf_fit_calibrate(&pb, truth, 2.0, 0.05, BF_NOISE_OBJECTIVE,
                                  20, 0, BF_NEYMAN_MIN_SIM, 1, SEED, LEVEL,
                                  &cal),
                 BF_EINVAL);
    cr_assert_str_eq(bf_ci_method_name(BF_CI_NEYMAN), "neyman");
}

/* Which intervals the analysis constructs (bf__neyman_which, the one
 * policy of the analysis and the calibration): by default those whose
 * profile has a competing second minimum, and only those -- not a
 * profile open to a bound (ON's rho at CURET's geometry: the construction
 * there covered less than the F threshold, bench/RESULTS.md); every free
 * one on request; none with --neyman off, without the likelihood's
 * intervals, or for a parameter held fixed. */
Test(neyman, the_default_constructs_where_a_minimum_competes)
{
    bf_model_variant v;
    bf_problem pb;
    bf_interval iv;
    double truth[BF_MAX_PARAMS];
    size_t jm;
    unsigned m, n;
    problem(&v, bf_model_fc_e, 2, &pb, truth);
    jm = (size_t)bf_model_param_index(&v.type, "m");
    m = 1u << jm;
    n = 1u << bf_model_param_index(&v.type, "n");
    cr_assert_eq(pb.free_mask, m | n);
    memset(&iv, 0, sizeof iv);
    iv.method = BF_CI_PROFILE_LIK;
    memcpy(iv.ml.param, truth, sizeof truth);
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), 0u,
                 "a regular profile keeps the F threshold");
    iv.competing = n;
    iv.not_identified = n; /* split */
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), n,
                 "only the competing parameter");
    iv.competing = 0;
    iv.not_identified = m;
    iv.open = 2u << (2 * jm); /* m's profile open to its high bound */
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), 0u,
                 "an open profile keeps the F threshold");
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 1), m | n,
                 "every parameter on request");
    iv.competing = n;
    cr_assert_eq(bf__neyman_which(&pb, &iv, 0, 0), 0u, "--neyman off");
    cr_assert_eq(bf__neyman_which(&pb, &iv, 0, 1), 0u);
    iv.method = BF_CI_PROFILE;
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), 0u,
                 "no likelihood, no construction");
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 1), 0u);
    /* a parameter held fixed is never constructed */
    iv.method = BF_CI_PROFILE_LIK;
    pb.free_mask = m;
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), 0u);
    cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 1), m);
    /* a specular model keeps profile-lik: its domains have no grid */
    {
        bf_model_type spec = v.type;
        spec.kind = BF_MODEL_SPECULAR;
        pb.type = &spec;
        pb.free_mask = m | n;
        cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), 0u,
                     "a specular model is not constructed");
        cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 1), 0u);
        pb.type = &v.type;
        cr_assert_eq(bf__neyman_which(&pb, &iv, BF_NEYMAN_AUTO_SIM, 0), n);
    }
}
