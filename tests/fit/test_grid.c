/* test_grid.c: normalisation (SPEC §2), the LSE (SPEC §7.3), the paper's
 * grid search (SPEC §7.4), round trips on the 198 CURET configurations and
 * the agreement of the precomputed (study) path with the plain one. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "support.h"

/* Noise level of the noisy round trip: 1% of the normalised maximum. */
#define NOISE_SD 0.01
/* A noisy fit recovers the parameter to within this many grid steps. */
#define NOISY_STEPS 3

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(grid, .init = setup);

/* The 198 non-specular CURET configurations in Beckmann's frame. */
static size_t curet_geometry(bf_geom *geom)
{
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    size_t k;
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    bf_table_free(t);
    return n;
}

static void defaults(const bf_model_type *type, double *param)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        param[j] = type->param[j].value;
    }
}

Test(grid, normalise_divides_by_the_maximum)
{
    const double in[4] = {0.5, 2.0, -0.25, 1.0};
    double out[4];
    cr_assert_eq(bf_normalise(4, in, out), BF_OK);
    bf_assert_rel(out[0], 0.25, TOL0);
    bf_assert_rel(out[1], 1.0, TOL0);
    bf_assert_rel(out[2], -0.125, TOL0);
    bf_assert_rel(out[3], 0.5, TOL0);
}

Test(grid, normalise_rejects_a_non_positive_maximum_and_non_finite_values)
{
    const double zero[3] = {0.0, -1.0, 0.0};
    const double nan_in[3] = {1.0, NAN, 0.5};
    const double inf_in[2] = {1.0, INFINITY};
    double out[3];
    cr_assert_eq(bf_normalise(3, zero, out), BF_EDOM);
    cr_assert_eq(bf_normalise(3, nan_in, out), BF_EDOM);
    cr_assert_eq(bf_normalise(2, inf_in, out), BF_EDOM);
    cr_assert_eq(bf_normalise(0, zero, out), BF_EINVAL);
}

Test(grid, data_radiance_is_brdf_times_cos_theta_i_over_its_maximum)
{
    /* SPEC §2 by hand on three configurations of a made-up table. */
    FILE *fp = bf_test_memfile("1 0.3 0 0.2 0\n"
                               "2 0.5 1 0.9 2\n"
                               "3 0.7 2 1.3 3\n");
    bf_table *t = NULL;
    bf_error err;
    const double v[3] = {2.0, 1.0, 4.0};
    const size_t sel[3] = {0, 1, 2};
    double out[3];
    double l0 = 2.0 * cos(0.2);
    double l1 = 1.0 * cos(0.9);
    double l2 = 4.0 * cos(1.3);
    double max = fmax(l0, fmax(l1, l2));
    cr_assert_eq(bf_table_read(fp, "mem", &t, &err), BF_OK);
    fclose(fp);
    cr_assert_eq(bf_data_radiance(t, v, 3, sel, out), BF_OK);
    bf_assert_rel(out[0], l0 / max, TOL1);
    bf_assert_rel(out[1], l1 / max, TOL1);
    bf_assert_rel(out[2], l2 / max, TOL1);
    bf_table_free(t);
}

Test(grid, lse_is_the_sum_of_squared_differences_of_normalised_curves)
{
    /* LAMBERT normalised is cos(theta_i) / max cos(theta_i): compute the
     * residual sum by hand against arbitrary data. */
    const bf_geom g[3] = {{0.3, M_PI, 0.1, 0.0},
                          {0.7313, M_PI, 0.4, 1.0},
                          {1.2, M_PI, 0.9, 2.0}};
    const double data[3] = {0.9, 0.5, 0.2};
    bf_fit_workspace *w = bf_fit_alloc(3);
    double lse = -1.0;
    double c0 = cos(0.3);
    double expect = 0.0;
    size_t k;
    for (k = 0; k < 3; k++) {
        double r = cos(g[k].theta_i) / c0 - data[k];
        expect += r * r;
    }
    cr_assert_eq(bf_fit_lse(bf_model_lambert, NULL, 3, g, data, w, &lse),
                 BF_OK);
    bf_assert_rel(lse, expect, TOL1);
    bf_fit_free(w);
}

/* Synthesises each fitted model on the CURET configurations at a grid value
 * and checks the grid search returns exactly that value with LSE 0. */
Test(grid, round_trip_recovers_every_model_exactly_at_grid_values)
{
    bf_geom geom[BF_CURET_NCONF];
    size_t n = curet_geometry(geom);
    bf_fit_workspace *w = bf_fit_alloc(n);
    /* grid indices; taken modulo each grid's size (WNO's n grid has 131,
     * WNO-R's 32 and 14 points; none of the picks lands on a bound) */
    static const size_t picks[3] = {7, 137, 388};
    size_t i;
    int fitted_models = 0;

    cr_assert_eq(n, 198u);
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *type = bf_model_get(i);
        size_t n_grid = 1;
        size_t j;
        size_t q;
        for (j = 0; j < type->p; j++) {
            n_grid *= type->param[j].fitted ? type->param[j].grid_n : 1;
        }
        if (n_grid == 1 || type->kind != BF_MODEL_DIFFUSE) {
            continue; /* nothing fitted (ON, LAMBERT); SPEC §9's models
                         are fitted under SPEC §10, not on grids */
        }
        fitted_models++;
        /* WNO-R's plain grid is its quadrature rule at 448 points:
         * one pick */
        for (q = 0; q < (type == bf_model_wno_r ? 1u : 3u); q++) {
            double param[BF_MAX_PARAMS];
            double data[BF_CURET_NCONF];
            bf_fit_result res;
            defaults(type, param);
            for (j = 0; j < type->p; j++) {
                const bf_param *pj = &type->param[j];
                if (pj->fitted) {
                    param[j] = pj->grid_lo +
                               pj->grid_step * (double)(picks[q] % pj->grid_n);
                }
            }
            cr_assert_eq(bf_model_eval(type, param, n, geom, data), BF_OK);
            cr_assert_eq(bf_normalise(n, data, data), BF_OK);
            cr_assert_eq(bf_fit_grid(type, param, 0, n, geom, data, w, &res),
                         BF_OK, "%s", type->name);
            for (j = 0; j < type->p; j++) {
                cr_assert_eq(res.param[j], param[j],
                             "%s: %s synthesised at %.17g, recovered %.17g",
                             type->name, type->param[j].name, param[j],
                             res.param[j]);
            }
            cr_assert_eq(res.lse, 0.0, "%s: LSE %g", type->name, res.lse);
            cr_assert_eq(res.bound_hit, 0u);
            cr_assert_eq(res.n_eval, n_grid);
        }
    }
    cr_assert_eq(fitted_models, 9, "BK-G..FC-E, LFTG, WNO and WNO-R have "
                                   "fitted parameters");
    bf_fit_free(w);
}

/* With 1% Gaussian noise (fixed seed), the optimum stays within a few grid
 * steps of the truth and the LSE is close to the noise energy n sd^2. */
Test(grid, round_trip_with_fixed_seed_noise_recovers_within_three_steps)
{
    bf_geom geom[BF_CURET_NCONF];
    size_t n = curet_geometry(geom);
    bf_fit_workspace *w = bf_fit_alloc(n);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    static const char *const names[] = {"VH-G", "VH-E", "FC-G", "FC-E",
                                        "LFTG"};
    size_t i;

    gsl_rng_set(rng, 20261122);
    for (i = 0; i < sizeof names / sizeof *names; i++) {
        const bf_model_type *type = bf_model_find(names[i]);
        int jm = bf_model_param_index(type, strcmp(names[i], "LFTG") == 0
                                                ? "n_d"
                                                : "m");
        const bf_param *pj = &type->param[jm];
        double param[BF_MAX_PARAMS];
        double data[BF_CURET_NCONF];
        bf_fit_result res;
        size_t k;
        defaults(type, param);
        param[jm] = pj->grid_lo + pj->grid_step * 73.0;
        cr_assert_eq(bf_model_eval(type, param, n, geom, data), BF_OK);
        cr_assert_eq(bf_normalise(n, data, data), BF_OK);
        for (k = 0; k < n; k++) {
            data[k] += gsl_ran_gaussian(rng, NOISE_SD);
        }
        cr_assert_eq(bf_fit_grid(type, param, 0, n, geom, data, w, &res),
                     BF_OK);
        cr_assert_leq(fabs(res.param[jm] - param[jm]),
                      NOISY_STEPS * pj->grid_step + 1e-12,
                      "%s: truth %g, recovered %g", names[i], param[jm],
                      res.param[jm]);
        /* E[LSE] ~ n sd^2 = 0.0198; allow the chi-square spread and the
         * small bias of re-normalising a noisy maximum. */
        cr_assert(res.lse > 0.5 * (double)n * NOISE_SD * NOISE_SD &&
                      res.lse < 2.0 * (double)n * NOISE_SD * NOISE_SD,
                  "%s: LSE %g", names[i], res.lse);
    }
    gsl_rng_free(rng);
    bf_fit_free(w);
}

Test(grid, optimum_on_the_grid_bound_is_flagged)
{
    /* Data from VH-G at m = 7 lie beyond the grid's upper end 5.1: the best
     * grid value is the bound and is flagged; m = 0.05 gives the lower
     * bound 0.1. */
    bf_geom geom[BF_CURET_NCONF];
    size_t n = curet_geometry(geom);
    bf_fit_workspace *w = bf_fit_alloc(n);
    const bf_model_type *type = bf_model_vh_g;
    double data[BF_CURET_NCONF];
    double param[BF_MAX_PARAMS];
    bf_fit_result res;

    defaults(type, param);
    param[0] = 7.0;
    cr_assert_eq(bf_model_eval(type, param, n, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    cr_assert_eq(bf_fit_grid(type, param, 0, n, geom, data, w, &res), BF_OK);
    bf_assert_rel(res.param[0], 5.1, TOL1);
    cr_assert_eq(res.bound_hit, 1u);

    param[0] = 0.05;
    cr_assert_eq(bf_model_eval(type, param, n, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    cr_assert_eq(bf_fit_grid(type, param, 0, n, geom, data, w, &res), BF_OK);
    bf_assert_rel(res.param[0], 0.1, TOL1);
    cr_assert_eq(res.bound_hit, 1u);
    bf_fit_free(w);
}

Test(grid, model_without_free_parameters_is_evaluated_once)
{
    bf_geom geom[BF_CURET_NCONF];
    size_t n = curet_geometry(geom);
    bf_fit_workspace *w = bf_fit_alloc(n);
    double data[BF_CURET_NCONF];
    const double on[2] = {0.387, 0.415}; /* Felt, reference/ */
    bf_fit_result res;
    cr_assert_eq(bf_model_eval(bf_model_on, on, n, geom, data), BF_OK);
    cr_assert_eq(bf_normalise(n, data, data), BF_OK);
    cr_assert_eq(bf_fit_grid(bf_model_on, on, 0, n, geom, data, w, &res),
                 BF_OK);
    cr_assert_eq(res.n_eval, 1u);
    cr_assert_eq(res.lse, 0.0);
    cr_assert_eq(res.param[0], on[0]);
    cr_assert_eq(res.param[1], on[1]);
    bf_fit_free(w);
}

Test(grid, invalid_fixed_inputs_and_masks_are_rejected)
{
    bf_geom geom[BF_CURET_NCONF];
    size_t n = curet_geometry(geom);
    bf_fit_workspace *w = bf_fit_alloc(n);
    double data[BF_CURET_NCONF];
    double param[BF_MAX_PARAMS];
    bf_fit_result res;
    size_t k;
    for (k = 0; k < n; k++) {
        data[k] = 0.5;
    }
    defaults(bf_model_fc_e, param);
    param[bf_model_param_index(bf_model_fc_e, "n")] = 0.5; /* n < 1 */
    cr_assert_eq(bf_fit_grid(bf_model_fc_e, param, 0, n, geom, data, w, &res),
                 BF_EINVAL);
    defaults(bf_model_fc_e, param);
    cr_assert_eq(bf_fit_grid(bf_model_fc_e, param, 1u << 3, n, geom, data, w,
                             &res),
                 BF_EINVAL); /* no parameter 3 */
    cr_assert_eq(bf_fit_grid(bf_model_fc_e, param, 0, n + 1, geom, data, w,
                             &res),
                 BF_EINVAL); /* larger than the workspace */
    bf_fit_free(w);
}

/* The kernels' exp (src/fit/kernels.c) is within EXP_ULPS of glibc's exp
 * on [-708, 0] -- checked at 200001 points spread over the range and
 * dense near 0, where the study's arguments lie -- and 0 below -708 and at
 * -inf; exactly 1 at 0. */
#define EXP_ULPS 1.0

Test(grid, kernel_exp_is_within_one_ulp_of_exp_on_its_range)
{
    const size_t n = 200001;
    double worst = 0.0;
    double at = 0.0;
    size_t i;
    for (i = 0; i < n; i++) {
        double u = (double)i / (double)(n - 1);
        /* half the points uniform on [-708, 0], half within [-1, 0] */
        double x = (i % 2 == 0) ? -708.0 * u : -u * 0.7313;
        double e = exp(x);
        double ulp = nextafter(e, INFINITY) - e;
        double d = fabs(bf__exp_nonpos(x) - e) / ulp;
        if (d > worst) {
            worst = d;
            at = x;
        }
    }
    cr_assert_leq(worst, EXP_ULPS, "%.3g ulp at x = %.17g", worst, at);
    cr_assert_eq(bf__exp_nonpos(0.0), 1.0);
    cr_assert_eq(bf__exp_nonpos(-708.5), 0.0);
    cr_assert_eq(bf__exp_nonpos(-INFINITY), 0.0);
}

/* Bound on |LSE_study - LSE_plain| (src/fit/kernels.c). The study path's
 * normalised curves C' differ from the plain path's C by at most
 * CURVE_DELTA (absolute; both peak at 1): each has about a dozen roundings,
 * the kernels' exp adds at most 1 ulp (tested below), a rounding of x
 * becomes a relative error |x| eps of exp(x), where the normalised value
 * is not negligible only for |x| below about 16 (values ~ e^-16 of the
 * peak contribute below eps), so |C' - C| <= (12 + 1 + 2 * 16) eps < 64 eps.
 * With residuals r_k: |sum (r_k + d_k)^2 - sum r_k^2| <= 2 sum |r_k| |d_k| +
 * sum d_k^2 <= 2 CURVE_DELTA sqrt(K LSE) + K CURVE_DELTA^2 (Cauchy-Schwarz),
 * plus the rounding of the two sums of K terms, at most K eps LSE each. */
#define CURVE_DELTA (64.0 * DBL_EPSILON)

static double study_lse_bound(size_t k, double lse)
{
    double kd = (double)k;
    return (2.0 * CURVE_DELTA * sqrt(kd * lse)) +
           (kd * CURVE_DELTA * CURVE_DELTA) + (2.0 * kd * DBL_EPSILON * lse);
}

/* The same for WNO-R, whose study path interpolates the plain path's
 * rule in tables (src/models/wno_r.c): each value within 2e-10 of it
 * relative (tests/models/test_wno_r.c), so a normalised curve within
 * 4e-10 absolute (the value and the maximum). */
static double wnor_lse_bound(size_t k, double lse)
{
    double kd = (double)k;
    double delta = 4e-10;
    return (2.0 * delta * sqrt(kd * lse)) + (kd * delta * delta) +
           (2.0 * kd * DBL_EPSILON * lse);
}

/* A study of all 61 samples against every model with a grid, plus LAMBERT
 * and ON (Felt's tabulated rho, sigma for every sample), on n_threads. */
static bf_study_row *study_all(const bf_table *t, const bf_brdf *b,
                               const size_t *sel, size_t n,
                               const bf_model_type **models,
                               size_t *n_models, int *samples,
                               size_t *n_samples, bf_sample_table *on,
                               int n_threads)
{
    bf_study_spec spec;
    bf_error err;
    bf_study_row *rows;
    size_t i;

    *n_models = 0;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *type = bf_model_get(i);
        if (type->p > 0 && type->param[0].fitted &&
            type->kind == BF_MODEL_DIFFUSE) { /* the study's models */
            models[(*n_models)++] = type;
        }
    }
    models[(*n_models)++] = bf_model_lambert;
    models[(*n_models)++] = bf_model_on;
    bf_dataset *ds = NULL;
    static bf_target targets[64];
    cr_assert_eq(bf_curet_dataset(t, b, NULL, "abrdf.dat", "mean", &ds, &err),
                 BF_OK);
    *n_samples = bf_brdf_count(b);
    for (i = 0; i < *n_samples; i++) {
        samples[i] = bf_brdf_sample(b, i);
        targets[i].material = i;
        targets[i].channel = BF_CHANNEL_MEAN;
    }
    (void)sel;
    (void)n; /* the dataset's default selection is sel (SPEC §1.4) */
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_select_init(&spec.select);
    spec.targets = targets;
    spec.n_targets = *n_samples;
    spec.models = models;
    spec.n_models = *n_models;
    spec.n_default = BF_DEFAULT_N;
    spec.on_params = on;
    spec.n_threads = n_threads;
    rows = calloc(*n_samples * *n_models, sizeof *rows);
    cr_assert_eq(bf_study_run(&spec, rows, &err), BF_OK, "%s", err.msg);
    for (i = 0; i < *n_samples * *n_models; i++) {
        cr_assert_eq(rows[i].k, n, "K of row %zu", i);
    }
    bf_dataset_free(ds);
    return rows;
}

/* ON's inputs for every sample: Felt's (reference/) rho, sigma. */
static bf_sample_table *on_for_all(const bf_brdf *b)
{
    char text[64 * 32];
    size_t len = 0;
    size_t s;
    bf_sample_table *on = NULL;
    bf_error err;
    FILE *fp;
    for (s = 0; s < bf_brdf_count(b); s++) {
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "%d 0.387 0.415\n", bf_brdf_sample(b, s));
    }
    fp = bf_test_memfile(text);
    cr_assert_eq(bf_on_params_read(fp, "mem", &on, &err), BF_OK);
    fclose(fp);
    return on;
}

/* The study's precomputed grids and vector kernels find the plain grid
 * search's optimum -- the same grid point, the same bound flags -- on every
 * one of CURET's 61 samples and every model, with the LSE within the
 * derived bound; ON and LAMBERT (no kernel) agree bit for bit. */
Test(grid, study_path_finds_the_plain_optimum_on_all_61_samples)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *b = bf_test_load_abrdf();
    bf_sample_table *on = on_for_all(b);
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    bf_geom geom[BF_CURET_NCONF];
    const bf_model_type *models[16];
    size_t n_models;
    int samples[64];
    size_t n_samples;
    bf_study_row *rows;
    bf_fit_workspace *w = bf_fit_alloc(n);
    size_t i;
    size_t s;
    double worst = 0.0;

    for (i = 0; i < n; i++) {
        geom[i] = bf_table_geom(t, sel[i]);
    }
    rows = study_all(t, b, sel, n, models, &n_models, samples, &n_samples,
                     on, 1);
    for (s = 0; s < n_samples; s++) {
        double data[BF_CURET_NCONF];
        cr_assert_eq(bf_data_radiance(t, bf_brdf_values(b, s), n, sel, data),
                     BF_OK);
        for (i = 0; i < n_models; i++) {
            const bf_study_row *r = &rows[s * n_models + i];
            double param[BF_MAX_PARAMS];
            bf_fit_result plain;
            double bound;
            if (models[i] == bf_model_wno_r &&
                s % (BF_TEST_SANITIZED ? 60 : 30) != 0) {
                /* WNO-R's plain path is its quadrature rule (about 6 400
                 * facets a value, 448 grid points): samples 1, 31 and 61
                 * (1 and 61 in the sanitizer build) */
                continue;
            }
            defaults(models[i], param);
            if (models[i] == bf_model_on) {
                param[0] = 0.387;
                param[1] = 0.415;
            }
            cr_assert_eq(r->status, BF_OK);
            cr_assert_eq(bf_fit_grid(models[i], param, 0, n, geom, data, w,
                                     &plain),
                         BF_OK);
            cr_assert_eq(memcmp(r->fit.param, plain.param,
                                sizeof plain.param),
                         0, "sample %d %s: optimum %.17g, plain %.17g",
                         r->sample, models[i]->name, r->fit.param[0],
                         plain.param[0]);
            cr_assert_eq(r->fit.bound_hit, plain.bound_hit);
            cr_assert_eq(r->fit.n_eval, plain.n_eval);
            cr_assert(isfinite(r->fit.lse));
            if (bf__fits_nothing(models[i])) {
                cr_assert_eq(r->fit.lse, plain.lse, "sample %d %s",
                             r->sample, models[i]->name);
                continue;
            }
            bound = models[i] == bf_model_wno_r
                        ? wnor_lse_bound(n, plain.lse)
                        : study_lse_bound(n, plain.lse);
            bf_assert_abs(r->fit.lse, plain.lse, bound);
            if (fabs(r->fit.lse - plain.lse) / bound > worst) {
                worst = fabs(r->fit.lse - plain.lse) / bound;
            }
        }
    }
    cr_log_info("largest LSE difference: %.3g of the bound", worst);
    free(rows);
    bf_fit_free(w);
    bf_sample_table_free(on);
    bf_brdf_free(b);
    bf_table_free(t);
}

/* OpenMP threads share grid blocks, never a sum: the rows are identical
 * bit for bit whatever the thread count. */
Test(grid, study_results_do_not_depend_on_the_thread_count)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *b = bf_test_load_abrdf();
    bf_sample_table *on = on_for_all(b);
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    const bf_model_type *models[16];
    size_t n_models;
    int samples[64];
    size_t n_samples;
    bf_study_row *one = study_all(t, b, sel, n, models, &n_models, samples,
                                  &n_samples, on, 1);
    static const int threads[] = {2, 3};
    size_t q;
    for (q = 0; q < sizeof threads / sizeof threads[0]; q++) {
        bf_study_row *many = study_all(t, b, sel, n, models, &n_models,
                                       samples, &n_samples, on, threads[q]);
        size_t i;
        for (i = 0; i < n_samples * n_models; i++) {
            cr_assert_eq(many[i].status, one[i].status);
            cr_assert_eq(memcmp(&many[i].fit, &one[i].fit, sizeof one[i].fit),
                         0, "%d threads: sample %d %s differs", threads[q],
                         one[i].sample, one[i].type->name);
        }
        free(many);
    }
    free(one);
    bf_sample_table_free(on);
    bf_brdf_free(b);
    bf_table_free(t);
}

/* Grids of sizes that are not multiples of the kernels' lanes (padding),
 * through the public bf_grid API: the same optimum as bf_fit_grid for a
 * VH-E and an LFTG with shortened grids (recognised as the same models),
 * and for ON and LAMBERT, whose curves bf_grid evaluates plainly. */
Test(grid, grids_of_any_size_find_the_plain_optimum)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *b = bf_test_load_abrdf();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    bf_geom geom[BF_CURET_NCONF];
    bf_fit_workspace *w = bf_fit_alloc(n);
    static const size_t sizes[] = {1, 7, 37, 70, 501};
    const bf_model_type *bases[4];
    size_t i;
    size_t q;
    size_t m;

    bases[0] = bf_model_vh_e;
    bases[1] = bf_model_lftg;
    bases[2] = bf_model_on;
    bases[3] = bf_model_lambert;
    for (i = 0; i < n; i++) {
        geom[i] = bf_table_geom(t, sel[i]);
    }
    for (m = 0; m < 4; m++) {
        for (q = 0; q < sizeof sizes / sizeof sizes[0]; q++) {
            bf_param par[BF_MAX_PARAMS];
            bf_model_type type = *bases[m];
            double param[BF_MAX_PARAMS];
            double data[BF_CURET_NCONF];
            bf_fit_result plain;
            bf_fit_result fast;
            bf_grid *gr;
            int st = -1;
            size_t s = (q * 17 + m * 5) % bf_brdf_count(b); /* a sample */
            if (type.p > 0) {
                memcpy(par, type.param, type.p * sizeof par[0]);
                if (par[0].fitted) {
                    par[0].grid_n = sizes[q];
                }
                type.param = par;
            }
            defaults(&type, param);
            cr_assert_eq(bf_data_radiance(t, bf_brdf_values(b, s), n, sel,
                                          data),
                         BF_OK);
            gr = bf_grid_alloc(&type, param, 0, n, geom, &st);
            cr_assert_not_null(gr, "%s: status %d", type.name, st);
            cr_assert_eq(bf_grid_fit(gr, data, &fast), BF_OK);
            cr_assert_eq(bf_fit_grid(&type, param, 0, n, geom, data, w,
                                     &plain),
                         BF_OK);
            cr_assert_eq(memcmp(fast.param, plain.param, sizeof plain.param),
                         0, "%s, %zu points", type.name, sizes[q]);
            cr_assert_eq(fast.bound_hit, plain.bound_hit);
            cr_assert_eq(fast.n_eval, plain.n_eval);
            bf_assert_abs(fast.lse, plain.lse, study_lse_bound(n, plain.lse));
            bf_grid_free(gr);
        }
    }
    bf_fit_free(w);
    bf_brdf_free(b);
    bf_table_free(t);
}

Test(grid, study_reports_a_missing_sample_and_missing_on_parameters)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *b = bf_test_load_abrdf();
    bf_dataset *ds = NULL;
    const bf_model_type *models[1] = {bf_model_on};
    bf_target targets[1] = {{61, BF_CHANNEL_MEAN, 0}}; /* 61 materials: 0-60 */
    bf_study_row rows[1];
    bf_study_spec spec;
    bf_error err;

    cr_assert_eq(bf_curet_dataset(t, b, NULL, "abrdf.dat", "mean", &ds, &err),
                 BF_OK);
    cr_assert_eq(bf_dataset_find(ds, 62), -1);
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_select_init(&spec.select);
    spec.targets = targets;
    spec.n_targets = 1;
    spec.models = models;
    spec.n_models = 1;
    spec.n_default = BF_DEFAULT_N;
    cr_assert_eq(bf_study_run(&spec, rows, &err), BF_EINVAL);

    targets[0].material = 2; /* no ON parameters given: the row says so */
    cr_assert_eq(bf_study_run(&spec, rows, &err), BF_OK);
    cr_assert_eq(rows[0].status, BF_ENOTFOUND);
    cr_assert_eq(rows[0].sample, 3);
    cr_assert_eq(rows[0].k, 198);
    bf_dataset_free(ds);
    bf_brdf_free(b);
    bf_table_free(t);
}
