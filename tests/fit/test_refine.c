/* test_refine.c: exact refinement of grid optima (doc/methods.md §2), the
 * objectives (§1), the curve cache and model variants (§6). */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

/* A refined optimum is a local minimum: moving any free parameter by this
 * much (100 times BF_REFINE_TOL) does not lower the objective. */
#define PROBE 1e-4
/* Relative slack of that comparison: rounding of a sum of 198 squares. */
#define PROBE_SLACK 1e-12

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(refine, .init = setup);

/* The 198 non-specular CURET configurations and the normalised data of
 * the 24 study samples (24 x 198, sample-major). */
static size_t study_data(bf_geom *geom, double *data)
{
    bf_table *t = bf_test_load_table();
    bf_brdf *b = bf_test_load_abrdf();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    size_t k;
    size_t s;
    for (k = 0; k < n; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    for (s = 0; s < BF_STUDY_NSAMPLES; s++) {
        long row = bf_brdf_find(b, bf_study_samples[s]);
        cr_assert_geq(row, 0);
        cr_assert_eq(bf_data_radiance(t, bf_brdf_values(b, (size_t)row), n,
                                      sel, data + s * n),
                     BF_OK);
    }
    bf_table_free(t);
    bf_brdf_free(b);
    return n;
}

/* Every model that fits something: the registry's (paper grids; FC at
 * n = 1.7) plus FC with n free and ON with rho and sigma fitted, the
 * variants of --fit exact. */
static size_t fitted_models(bf_model_variant *v, const bf_model_type **out)
{
    size_t i;
    size_t count = 0;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        if (t->p > 0 && t->param[0].fitted &&
            t->kind == BF_MODEL_DIFFUSE) { /* the study's models */
            out[count++] = t;
        }
    }
    bf_model_variant_init(&v[0], bf_model_fc_g);
    bf_model_variant_init(&v[1], bf_model_fc_e);
    bf_model_variant_init(&v[2], bf_model_on);
    cr_assert_eq(bf_model_variant_fit(&v[0], "n", BF_FREE_N_LO, BF_FREE_N_HI,
                                      BF_FREE_N_STEP), BF_OK);
    cr_assert_eq(bf_model_variant_fit(&v[1], "n", BF_FREE_N_LO, BF_FREE_N_HI,
                                      BF_FREE_N_STEP), BF_OK);
    cr_assert_eq(bf_model_variant_fit(&v[2], "rho", 0.05, 1.0, 0.05), BF_OK);
    cr_assert_eq(bf_model_variant_fit(&v[2], "sigma", 0.0, 1.57, 0.01),
                 BF_OK);
    out[count++] = &v[0].type;
    out[count++] = &v[1].type;
    out[count++] = &v[2].type;
    return count;
}

/* The acceptance test: over the 24 study samples and every fitted
 * model, the refined optimum lies within one grid step of the grid optimum
 * (in every free parameter), its LSE is not above the grid LSE, and it is
 * a local minimum. Under the sanitizers every fourth sample (the same
 * code for each; 44 s of CPU under ASan for all 24). */
Test(refine, refined_optima_are_within_one_grid_step_and_no_worse_than_the_grid)
{
    static bf_geom geom[BF_CURET_NCONF];
    static double data[BF_STUDY_NSAMPLES * BF_CURET_NCONF];
    bf_model_variant v[3];
    const bf_model_type *models[16];
    size_t n = study_data(geom, data);
    size_t n_models = fitted_models(v, models);
    double *work = malloc(2 * n * sizeof *work);
    size_t m;
    size_t s;
    size_t improved = 0;
    size_t total = 0;

    cr_assert_eq(n_models, 12u);
    for (m = 0; m < n_models; m++) {
        bf_problem pb;
        bf_curves *c;
        int st;
        cr_assert_eq(bf_problem_init(&pb, models[m], NULL, n, geom, data),
                     BF_OK);
        c = bf_curves_alloc(&pb, &st);
        cr_assert_not_null(c, "%s: %d", models[m]->name, st);
        for (s = 0; s < BF_STUDY_NSAMPLES; s += BF_TEST_SANITIZED ? 4 : 1) {
            bf_fit_result g;
            bf_fit_result r;
            size_t j;
            int rc;
            pb.data = data + s * n;
            cr_assert_eq(bf_curves_best(c, &pb, &g), BF_OK);
            rc = bf_fit_refine(&pb, &g, &r);
            cr_assert_eq(rc, BF_OK, "%s sample %d: %d", models[m]->name,
                         bf_study_samples[s], rc);
            cr_assert_leq(r.lse, g.lse, "%s sample %d: refined %.17g > grid "
                          "%.17g", models[m]->name, bf_study_samples[s],
                          r.lse, g.lse);
            total++;
            /* strictly better, unless the optimum lies on the search range
             * (a grid bound: VH's slope 5.10 of the paper) */
            improved += r.lse < g.lse || r.bound_hit != 0;
            for (j = 0; j < models[m]->p; j++) {
                const bf_param *pj = &models[m]->param[j];
                double p2[BF_MAX_PARAMS];
                double v2;
                int d;
                if (!((pb.free_mask >> j) & 1u)) {
                    cr_assert_eq(r.param[j], pb.fixed[j]);
                    continue;
                }
                cr_assert_leq(fabs(r.param[j] - g.param[j]),
                              pj->grid_step * (1.0 + 1e-12),
                              "%s sample %d %s: grid %.6f refined %.6f",
                              models[m]->name, bf_study_samples[s], pj->name,
                              g.param[j], r.param[j]);
                cr_assert(r.param[j] >= pj->min && r.param[j] <= pj->max);
                for (d = -1; d <= 1; d += 2) {
                    memcpy(p2, r.param, sizeof p2);
                    p2[j] += d * PROBE;
                    if (p2[j] < pb.lo[j] || p2[j] > pb.hi[j] ||
                        fabs(p2[j] - g.param[j]) > pj->grid_step) {
                        continue; /* outside the refinement box */
                    }
                    cr_assert_eq(bf_problem_value(&pb, p2, work, &v2), BF_OK);
                    cr_assert_geq(v2, r.lse * (1.0 - PROBE_SLACK),
                                  "%s sample %d %s: f(x%+g) = %.17g < "
                                  "f(x) = %.17g", models[m]->name,
                                  bf_study_samples[s], pj->name, d * PROBE,
                                  v2, r.lse);
                }
            }
        }
        bf_curves_free(c);
    }
    /* off the range bounds the grid is never exactly optimal */
    cr_assert_eq(improved, total, "improved %zu of %zu", improved, total);
    free(work);
}
