/* test_stream.c: the streaming study path (bf__stream_fast, src/fit/
 * kernels.c) at a K whose blocks leave the caches, against the stored
 * grids (bf__grid_build, bf__grid_score). The streaming path stores each
 * block's raw values and normalises them as it scores them (the value
 * times the lane's 1/max); the stored grids normalise first. Both must
 * give the same normalised curves and the same sums: the same optimum
 * and the same LSE bit for bit, for the BK models' G and E forms (FC's
 * a-terms included; the 61 CURET samples check K = 198, test_grid.c). */
#include <criterion/criterion.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"
#include "support.h"

#define SAMPLES 5 /* more than one tile of samples */

/* n random configurations (zeniths up to 80 degrees) and SAMPLES data
 * vectors in [0, 1] that peak at 1. */
static void make_set(gsl_rng *rng, size_t n, bf_geom *geom, double *data)
{
    size_t k;
    size_t q;
    for (k = 0; k < n; k++) {
        geom[k].theta_i = gsl_rng_uniform(rng) * 1.4;
        geom[k].phi_i = BF__PI;
        geom[k].theta_s = gsl_rng_uniform(rng) * 1.4;
        geom[k].phi_s = (2.0 * gsl_rng_uniform(rng) - 1.0) * BF__PI;
    }
    for (q = 0; q < SAMPLES; q++) {
        for (k = 0; k < n; k++) {
            data[q * n + k] = gsl_rng_uniform(rng);
        }
        data[q * n + (q * 7) % n] = 1.0;
    }
}

static void check_model(const bf_model_type *type, size_t n,
                        const bf_geom *geom, const double *data)
{
    double fixed[BF_MAX_PARAMS] = {0};
    const double *d[SAMPLES];
    double best_lse[SAMPLES];
    size_t best[SAMPLES];
    bf__grid_layout_t lay;
    bf__cset cs;
    bf__grid *gr;
    double *lse;
    size_t cols;
    size_t q;
    size_t j;
    int status;
    for (j = 0; j < type->p; j++) {
        fixed[j] = type->param[j].value;
    }
    for (q = 0; q < SAMPLES; q++) {
        d[q] = data + q * n;
    }
    cr_assert_eq(bf__cset_init(&cs, n, geom), BF_OK);
    cr_assert_eq(bf__grid_layout(type, fixed, 1u, &lay), BF_OK);
    cr_assert_eq(bf__stream_fast(type, &lay, &cs, SAMPLES, d, best_lse, best),
                 1, "%s: the streaming path applies", type->name);
    gr = bf__grid_build(type, fixed, 1u, &cs, &status);
    cr_assert_not_null(gr, "%s: grid", type->name);
    cols = bf__grid_cols(gr);
    lse = malloc(SAMPLES * cols * sizeof *lse);
    bf__grid_score(gr, SAMPLES, d, lse);
    for (q = 0; q < SAMPLES; q++) {
        size_t at;
        double v = bf__argmin(lay.points, lse + q * cols, bf__grid_ok(gr),
                              &at);
        cr_assert_eq(best[q], at,
                     "%s, K %zu, sample %zu: point %zu, stored %zu",
                     type->name, n, q, best[q], at);
        cr_assert(memcmp(&best_lse[q], &v, sizeof v) == 0,
                  "%s, K %zu, sample %zu: LSE %.17g, stored %.17g",
                  type->name, n, q, best_lse[q], v);
    }
    free(lse);
    bf__grid_free(gr);
    bf__cset_free(&cs);
}

Test(stream, large_k_streamed_blocks_give_the_stored_grids_bits)
{
    /* a block of 8 x K doubles: 1 MB, past the L2 (the sanitised build:
     * a smaller K, the same code) */
#if BF_TEST_SANITIZED
    static const size_t sizes[] = {4099};
#else
    static const size_t sizes[] = {16411};
#endif
    /* G and E forms, FC's a-terms (every BK member shares the kernels) */
    const bf_model_type *models[] = {bf_model_bk_g, bf_model_vh_e,
                                     bf_model_fc_g, bf_model_fc_e};
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t s;
    size_t m;
    for (s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        bf_geom *geom = malloc(n * sizeof *geom);
        double *data = malloc(SAMPLES * n * sizeof *data);
        make_set(rng, n, geom, data);
        for (m = 0; m < sizeof models / sizeof models[0]; m++) {
            check_model(models[m], n, geom, data);
        }
        free(geom);
        free(data);
    }
    gsl_rng_free(rng);
}
