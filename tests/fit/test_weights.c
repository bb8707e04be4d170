/* test_weights.c: the sums of many weight vectors against stored curves
 * (src/fit/weights.c) -- the bootstrap's grid optima -- against sums and
 * an argmin written out here in the plainest way (doc/methods.md §9: one
 * fma per term in index order; SPEC §7.4: ties keep the first point).
 *
 * The grid optima stop summing a tile of points early once every partial
 * sum exceeds its row's best so far; that must never change an optimum or
 * its value, whichever kernel (the processor's or the portable one) runs,
 * including ties between points and rows whose optimum is not near the
 * start the pass seeds every row with. */
#include <criterion/criterion.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* The tile kernel's shape (src/fit/weights.c). */
#define ROWS 6
#define LANES 8
#define SUPER 128

/* sum_k w_k rho_k, one fma per term in index order (w NULL: ones). */
static double plain_sum(size_t n, const double *w, const double *rho,
                        size_t stride)
{
    double s = 0.0;
    size_t k;
    for (k = 0; k < n; k++) {
        s = fma(w != NULL ? w[k] : 1.0, rho[k * stride], s);
    }
    return s;
}

static void fill_tile(gsl_rng *rng, size_t n, double *rho, double *w,
                      const double **wp)
{
    size_t k;
    size_t q;
    for (k = 0; k < n * SUPER; k++) {
        rho[k] = gsl_rng_uniform(rng) * gsl_rng_uniform(rng);
    }
    for (q = 0; q < ROWS; q++) {
        for (k = 0; k < n; k++) {
            w[q * n + k] = (double)gsl_rng_uniform_int(rng, 4);
        }
        wp[q] = w + q * n;
    }
}

Test(weights, both_tile_kernels_give_the_plain_sums_bit_for_bit)
{
    static const size_t sizes[] = {1, 15, 16, 17, 37, 198, 513};
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double *rho = malloc(513 * SUPER * sizeof *rho);
    double *w = malloc(ROWS * 513 * sizeof *w);
    const double *wp[ROWS];
    double bound[ROWS];
    int cand[LANES];
    size_t s;
    size_t q;
    size_t j;
    for (q = 0; q < ROWS; q++) {
        bound[q] = NAN; /* never stops */
    }
    for (j = 0; j < LANES; j++) {
        cand[j] = 1;
    }
    for (s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        int generic;
        fill_tile(rng, n, rho, w, wp);
        for (generic = 0; generic <= 1; generic++) {
            double out[ROWS * LANES];
            cr_assert_eq(bf__weights_tile(generic, n, rho, wp, bound, cand,
                                          out),
                         1);
            for (q = 0; q < ROWS; q++) {
                for (j = 0; j < LANES; j++) {
                    double ref = plain_sum(n, wp[q], rho + j, SUPER);
                    cr_assert(memcmp(&out[q * LANES + j], &ref,
                                     sizeof ref) == 0,
                              "n %zu kernel %d row %zu col %zu: %.17g, "
                              "plain %.17g",
                              n, generic, q, j, out[q * LANES + j], ref);
                }
            }
        }
    }
    gsl_rng_free(rng);
    free(rho);
    free(w);
}

Test(weights, a_tile_stops_only_when_every_candidate_is_past_its_bound)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t n = 198;
    double *rho = malloc(n * SUPER * sizeof *rho);
    double *w = malloc(ROWS * n * sizeof *w);
    const double *wp[ROWS];
    double bound[ROWS];
    int cand[LANES];
    double out[ROWS * LANES];
    size_t q;
    size_t j;
    size_t k;
    int generic;
    fill_tile(rng, n, rho, w, wp);
    /* column 3 scores nothing: its sums stay 0 */
    for (k = 0; k < n; k++) {
        rho[k * SUPER + 3] = 0.0;
    }
    for (generic = 0; generic <= 1; generic++) {
        for (j = 0; j < LANES; j++) {
            cand[j] = 1;
        }
        for (q = 0; q < ROWS; q++) {
            bound[q] = 1e-3; /* every other sum passes it soon */
        }
        cr_expect_eq(bf__weights_tile(generic, n, rho, wp, bound, cand, out),
                     1, "column 3 stays below: no stop (kernel %d)", generic);
        cand[3] = 0; /* not a candidate: it cannot keep the tile going */
        cr_expect_eq(bf__weights_tile(generic, n, rho, wp, bound, cand, out),
                     0, "every candidate past: stop (kernel %d)", generic);
        bound[5] = INFINITY; /* one row that nothing passes */
        cr_expect_eq(bf__weights_tile(generic, n, rho, wp, bound, cand, out),
                     1, "row 5 below its bound: no stop (kernel %d)",
                     generic);
    }
    gsl_rng_free(rng);
    free(rho);
    free(w);
}

/* The plain argmin of row w over the defined points: strict < in index
 * order (SPEC §7.4), NaN and +inf never win. */
static size_t plain_argmin(size_t n, size_t points, size_t stride,
                           const double *curves, const unsigned char *ok,
                           const double *data, const double *w, double *best)
{
    size_t g;
    size_t k;
    size_t at = SIZE_MAX;
    *best = INFINITY;
    for (g = 0; g < points; g++) {
        double s = 0.0;
        if (!ok[g]) {
            continue;
        }
        for (k = 0; k < n; k++) {
            double r = curves[k * stride + g] - data[k];
            s = fma(w != NULL ? w[k] : 1.0, r * r, s);
        }
        if (s < *best) {
            *best = s;
            at = g;
        }
    }
    return at;
}

/* bf__weights_argmin of the n_w rows w equals plain_argmin for every row,
 * index and value bit for bit; best gets the indices. */
static void check_optima(size_t n, size_t points, size_t cols,
                         const double *curves, const unsigned char *ok,
                         const double *data, size_t n_w,
                         const double *const *w, size_t *best)
{
    double *best_lse = malloc(n_w * sizeof *best_lse);
    size_t b;
    cr_assert_eq(bf__weights_argmin(n, cols, cols, curves, ok, points, data,
                                    NULL, n_w, w, best_lse, best),
                 BF_OK);
    for (b = 0; b < n_w; b++) {
        double ref;
        size_t at = plain_argmin(n, points, cols, curves, ok, data, w[b], &ref);
        cr_assert_eq(best[b], at, "row %zu: point %zu, plain %zu", b, best[b],
                     at);
        cr_assert(memcmp(&best_lse[b], &ref, sizeof ref) == 0,
                  "row %zu: %.17g, plain %.17g", b, best_lse[b], ref);
    }
    free(best_lse);
}

Test(weights, pruned_grid_optima_equal_the_plain_argmin_ties_included)
{
    enum { N = 150, POINTS = 300, COLS = 320, ROWS_W = 41 };
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double *curves = malloc(N * COLS * sizeof *curves);
    double *data = malloc(N * sizeof *data);
    double *w = calloc(ROWS_W * N, sizeof *w);
    unsigned char ok[COLS];
    const double *wp[ROWS_W];
    size_t best[ROWS_W];
    size_t b;
    size_t g;
    size_t k;
    for (k = 0; k < N; k++) {
        data[k] = gsl_rng_uniform(rng);
    }
    /* a smooth valley of points (most far from the data, as on a grid),
     * its bottom at 200 for the data and elsewhere for resamples */
    for (g = 0; g < COLS; g++) {
        double d = ((double)g - 200.0) / 60.0;
        ok[g] = g < POINTS && g % 37 != 11; /* some undefined points */
        for (k = 0; k < N; k++) {
            curves[k * COLS + g] =
                data[k] + d * d * (0.5 + gsl_rng_uniform(rng)) +
                0.05 * gsl_rng_uniform(rng);
        }
    }
    /* the data's optimum: point 200, a small residual everywhere */
    for (k = 0; k < N; k++) {
        curves[k * COLS + 200] = data[k] + 1e-9 * (double)(k % 3 + 1);
    }
    /* ties: 120 repeats 60, which fits exactly but at configuration 8;
     * 30 is 200 but at configuration 7 */
    for (k = 0; k < N; k++) {
        curves[k * COLS + 60] = data[k] + (k == 8 ? 1.0 : 0.0);
        curves[k * COLS + 120] = curves[k * COLS + 60];
        curves[k * COLS + 30] = curves[k * COLS + 200] + (k == 7 ? 50.0 : 0.0);
    }
    for (b = 0; b < ROWS_W; b++) {
        double *wb = w + b * N;
        wp[b] = wb;
        for (k = 0; k < N; k++) {
            wb[gsl_rng_uniform_int(rng, N)] += 1.0; /* a resample */
        }
    }
    wp[3] = NULL; /* ones */
    /* row 5 leaves configuration 8 out: 60 and 120 tie at 0 */
    for (k = 0; k < N; k++) {
        w[5 * N + k] = k == 8 ? 0.0 : 1.0;
    }
    /* row 9 leaves configuration 7 out: 30 and 200 tie, and 30 comes
     * first although the pass starts every row at the data's 200 */
    w[9 * N + 7] = 0.0;
    w[9 * N + 8] = 1.0;
    check_optima(N, POINTS, COLS, curves, ok, data, ROWS_W, wp, best);
    cr_expect_eq(best[5], 60, "a tie keeps the first point");
    cr_expect_eq(best[9], 30, "a tie before the start keeps the first point");
    /* negative weights: no early stop, the same plain answer */
    w[11 * N + 2] = -3.0;
    check_optima(N, POINTS, COLS, curves, ok, data, ROWS_W, wp, best);
    gsl_rng_free(rng);
    free(curves);
    free(data);
    free(w);
}
