/* test_block.c: a model made here, outside the library, with its own block
 * kernel (bf_kernel.block, src/fit/block.h) -- the hooks a new model fills
 * to get the study path's grid kernels, nothing in src/fit changed. The
 * streaming path (bf__stream_fast) and the stored grids (bf__grid_build)
 * must use it and give, bit for bit, what the model's own values() and
 * bf__curve give point by point, with and without the interleaved rows of
 * its streaming scorer, and at a grid the kernel declines, the
 * point-by-point path. */
#include <criterion/criterion.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/block.h"
#include "fit/engine.h"
#include "support.h"

#define SAMPLES 6 /* more than one narrow tile of samples */
#define K 203     /* not a multiple of anything */

/* The test model: L_k = 1 / (1 + a^2 u_k), u_k = sin^2 theta_i (a
 * division per value, as the models whose scorers interleave rows). */
static int toy_eval(const double *param, size_t n, const bf_geom *geom,
                    double *out, void *work)
{
    size_t k;
    (void)work;
    for (k = 0; k < n; k++) {
        double s = sin(geom[k].theta_i);
        out[k] = 1.0 / fma(param[0] * param[0], s * s, 1.0);
    }
    return BF_OK;
}

static void toy_terms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t k;
    (void)kr;
    for (k = 0; k < cs->n; k++) {
        terms[k] = cs->trig[k].si * cs->trig[k].si; /* u_k */
    }
}

static int toy_values(const bf__prep *pm, const double *param, void *work,
                      double *out)
{
    size_t k;
    (void)work;
    for (k = 0; k < pm->n; k++) {
        out[k] = 1.0 / fma(param[0] * param[0], pm->terms[k], 1.0);
    }
    return BF_OK;
}

/* Row k of a block, the same operations as toy_values. */
static inline void toy_row(const void *state, size_t k, const double *x,
                           double *out, double *mx, double *nf)
{
    const double *u = state;
    size_t j;
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        double v = 1.0 / fma(x[j] * x[j], u[k], 1.0);
        out[j] = v;
        nf[j] += v - v;
        mx[j] = v > mx[j] ? v : mx[j];
    }
}

static void toy_raw(const bf__block *blk, size_t n, const double *x,
                    size_t stride, double *c, double *mx, double *nf)
{
    size_t j;
    size_t k;
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        toy_row(blk->state, k, x, c + k * stride, mx, nf);
    }
}

static void toy_score_wide(size_t n, const double *c, const double *rs,
                           const double *const *d, double *lse,
                           bf__rows_t *e)
{
    bf__stream_score(BF__STREAM_SAMPLES, n, c, rs, d, lse, e, toy_row);
}

static void toy_score_narrow(size_t n, const double *c, const double *rs,
                             const double *const *d, double *lse,
                             bf__rows_t *e)
{
    bf__stream_score(BF__STREAM_SAMPLES_NARROW, n, c, rs, d, lse, e,
                     toy_row);
}

static int blocks_made; /* calls of toy_block that set a kernel up */

/* The block kernel: u copied (pm may be freed first); declines grids
 * reaching below a = 0.2, to test the fallback. */
static int toy_block(const bf__prep *pm, const bf__grid_layout_t *lay,
                     bf__block *blk, int piped)
{
    double *u;
    if (lay->lo[0] < 0.2) {
        return 0;
    }
    if (bf__block_state(blk, 0, pm->n, &u) == NULL) {
        return -BF_ENOMEM;
    }
    memcpy(u, pm->terms, pm->n * sizeof *u);
    blk->defined = 1;
    blk->raw = toy_raw;
    if (piped) {
        blk->score[0] = toy_score_wide;
        blk->score[1] = toy_score_narrow;
    }
    blocks_made++;
    return 1;
}

static int toy_block_plain(const bf__prep *pm, const bf__grid_layout_t *lay,
                           bf__block *blk)
{
    return toy_block(pm, lay, blk, 0);
}

static int toy_block_piped(const bf__prep *pm, const bf__grid_layout_t *lay,
                           bf__block *blk)
{
    return toy_block(pm, lay, blk, 1);
}

static const bf_kernel kr_plain = {
    .n_terms = 1,
    .terms = toy_terms,
    .values = toy_values,
    .normalise = bf__normalise_recip,
    .block = toy_block_plain,
    .cheap = -1,
};

static const bf_kernel kr_piped = {
    .n_terms = 1,
    .terms = toy_terms,
    .values = toy_values,
    .normalise = bf__normalise_recip,
    .block = toy_block_piped,
    .cheap = -1,
};

/* 43 grid points: five blocks and a partial one */
static const bf_param toy_param[1] = {
    {.name = "a", .label = "a", .unit = "1", .min = 0.0, .max = 10.0,
     .value = 1.0, .fitted = 1, .grid_lo = 0.25, .grid_step = 0.07,
     .grid_n = 43, .input = BF_INPUT_DEFAULT},
};

static const bf_model_type toy_plain = {
    .name = "TOY", .title = "test model", .reference = "tests",
    .p = 1, .param = toy_param, .eval = toy_eval, .kernel = &kr_plain,
};

static const bf_model_type toy_piped = {
    .name = "TOY", .title = "test model", .reference = "tests",
    .p = 1, .param = toy_param, .eval = toy_eval, .kernel = &kr_piped,
};

/* K random configurations, SAMPLES noisy data vectors of the model (d[q]
 * points at vector q) and their configuration set. */
static void make_set(bf_geom *geom, double *data, const double **d,
                     bf__cset *cs)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t k;
    size_t q;
    for (k = 0; k < K; k++) {
        geom[k].theta_i = gsl_rng_uniform(rng) * 1.5;
        geom[k].phi_i = BF__PI;
        geom[k].theta_s = gsl_rng_uniform(rng) * 1.5;
        geom[k].phi_s = gsl_rng_uniform(rng);
    }
    for (q = 0; q < SAMPLES; q++) {
        double a = 0.3 + 0.4 * (double)q; /* optima spread over the grid */
        for (k = 0; k < K; k++) {
            double s = sin(geom[k].theta_i);
            data[q * K + k] = (1.0 / (1.0 + a * a * s * s)) *
                              (0.95 + 0.1 * gsl_rng_uniform(rng));
        }
        d[q] = data + q * K;
    }
    gsl_rng_free(rng);
    cr_assert_eq(bf__cset_init(cs, K, geom), BF_OK);
}

/* The point-by-point reference: bf__curve (the model's values, its
 * normalisation) and the streaming sum (fma per term in index order). */
static void reference(const bf_model_type *type, const bf__cset *cs,
                      const bf__grid_layout_t *lay, const double *data,
                      double *best_lse, size_t *best)
{
    bf__prep pm;
    double curve[K];
    void *work;
    size_t g;
    size_t q;
    cr_assert_eq(bf__prep_init(&pm, type, cs), BF_OK);
    work = bf__work_alloc(&pm);
    for (q = 0; q < SAMPLES; q++) {
        best_lse[q] = INFINITY;
        best[q] = SIZE_MAX;
    }
    for (g = 0; g < lay->points; g++) {
        double param[BF_MAX_PARAMS];
        bf__grid_point(lay, g, param);
        cr_assert_eq(bf__curve(&pm, param, work, curve), BF_OK);
        for (q = 0; q < SAMPLES; q++) {
            double s = 0.0;
            size_t k;
            for (k = 0; k < K; k++) {
                double r = curve[k] - data[q * K + k];
                s = fma(r, r, s);
            }
            if (s < best_lse[q]) {
                best_lse[q] = s;
                best[q] = g;
            }
        }
    }
    free(work);
    bf__prep_free(&pm);
}

Test(block, a_model_made_outside_src_fit_streams_by_its_own_block_kernel)
{
    static bf_geom geom[K];
    static double data[SAMPLES * K];
    const bf_model_type *types[] = {&toy_plain, &toy_piped};
    const double *d[SAMPLES];
    double fixed[BF_MAX_PARAMS] = {1.0};
    bf__grid_layout_t lay;
    bf__cset cs;
    size_t t;
    size_t q;
    make_set(geom, data, d, &cs);
    cr_assert_eq(bf__grid_layout(&toy_plain, fixed, 1u, &lay), BF_OK);
    for (t = 0; t < 2; t++) {
        double ref_lse[SAMPLES];
        size_t ref[SAMPLES];
        double best_lse[SAMPLES];
        size_t best[SAMPLES];
        int made = blocks_made;
        reference(types[t], &cs, &lay, data, ref_lse, ref);
        cr_assert_eq(bf__stream_fast(types[t], &lay, &cs, SAMPLES, d,
                                     best_lse, best),
                     1, "the model's block kernel applies");
        cr_assert_eq(blocks_made, made + 1, "and was used");
        for (q = 0; q < SAMPLES; q++) {
            cr_assert_eq(best[q], ref[q], "%s, sample %zu: point %zu, %zu",
                         t ? "piped" : "plain", q, best[q], ref[q]);
            cr_assert(memcmp(&best_lse[q], &ref_lse[q], sizeof(double)) == 0,
                      "%s, sample %zu: LSE %.17g, point by point %.17g",
                      t ? "piped" : "plain", q, best_lse[q], ref_lse[q]);
        }
        cr_assert(ref[0] != ref[SAMPLES - 1], "optima spread");
    }
    bf__cset_free(&cs);
}

Test(block, stored_grids_use_the_block_kernel_and_fall_back_where_it_declines)
{
    static bf_geom geom[K];
    static double data[SAMPLES * K];
    double curve[K];
    double lo[1];
    double hi[1];
    double fixed[BF_MAX_PARAMS] = {1.0};
    double best_lse[SAMPLES];
    size_t best[SAMPLES];
    const double *d[SAMPLES];
    bf__grid_layout_t lay;
    bf__cset cs;
    bf__prep pm;
    int pass;
    make_set(geom, data, d, &cs);
    cr_assert_eq(bf__prep_init(&pm, &toy_piped, &cs), BF_OK);
    for (pass = 0; pass < 2; pass++) {
        /* the paper grid (kernel), then one from 0.1 (declined) */
        int made = blocks_made;
        bf__grid *gr;
        void *work = bf__work_alloc(&pm);
        size_t g;
        int status;
        lo[0] = pass == 0 ? 0.25 : 0.1;
        hi[0] = lo[0] + 0.07 * 42.0;
        cr_assert_eq(bf__grid_layout_range(&toy_piped, fixed, 1u, lo, hi,
                                           &lay),
                     BF_OK);
        gr = bf__grid_make(&pm, &lay, &status);
        cr_assert_not_null(gr);
        cr_assert_eq(blocks_made, made + (pass == 0 ? 1 : 0),
                     "pass %d: the block kernel %s", pass,
                     pass == 0 ? "applies" : "declines");
        for (g = 0; g < lay.points; g++) {
            double param[BF_MAX_PARAMS];
            double stored[K];
            bf__grid_point(&lay, g, param);
            cr_assert_eq(bf__curve(&pm, param, work, curve), BF_OK);
            bf__grid_curves(gr, g, 1, stored);
            cr_assert(memcmp(stored, curve, sizeof curve) == 0,
                      "pass %d, point %zu: the stored curve is bf__curve's",
                      pass, g);
        }
        cr_assert_eq(bf__stream_fast(&toy_piped, &lay, &cs, SAMPLES, d,
                                     best_lse, best),
                     pass == 0 ? 1 : 0);
        bf__grid_free(gr);
        free(work);
    }
    bf__prep_free(&pm);
    bf__cset_free(&cs);
}
