/* kernels.c: the study path's vectorised inner loops -- normalised model
 * curves of a block of grid points at once by the model's block kernel
 * (bf_kernel.block, src/fit/block.h), and the residual sums of squares
 * (SPEC §7.3) of a block of grid points against several samples at once.
 * No model lives here: each model's file has its block kernel (the BK
 * family's in src/models/bk.c, LFTG's in src/models/lafortune.c); this
 * file drives any of them.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model";
 *     SPEC §2 (the normalisation), §7.3-7.4 (LSE, grid).
 *
 * Layout: curves are stored transposed, curves[k * stride + g] for
 * configuration k and grid point g, so a vector register holds one
 * configuration of consecutive grid points. Vectorising across grid
 * points, never across the sum over configurations, keeps every LSE a
 * sum in index order, as bf__sum_sq_diff forms it.
 *
 * A block kernel may rearrange the math against its model's plain path
 * (eval, bf_normalise), algebraically exactly, to take divisions and pow
 * out of the inner loop (factors constant over the configurations
 * dropped, exp by the kernels' own bf__vexp_nonpos: see the models'
 * files); here the normalisation multiplies by 1/max instead of dividing
 * by max, and each LSE term is added with one fma (one rounding instead
 * of two). The normalised curves therefore differ from the plain path's
 * by a few units in the last place (absolute, the curves peak at 1), and
 * each LSE by a few ulp times sqrt(K LSE). tests/fit/test_grid.c bounds
 * the difference and checks that every optimum is the same grid point on
 * all 61 CURET samples and every model (the plain path stays the
 * reference). No -ffast-math: the library is built with -ffp-contract=off,
 * so the only fused multiply-adds are the explicit fma() calls, in every
 * ISA.
 *
 * Dispatch: the kernels are compiled for x86-64-v4 (AVX-512), x86-64-v3
 * (AVX2 + FMA) and the baseline, and the loader picks one at run time
 * (GCC's target_clones); the default build never uses -march=native. A
 * model's block kernel is called through its function pointers once per
 * block of BF__BLOCK_LANES grid points (its inner loops stay inlined in
 * its own file).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/block.h"
#include "fit/engine.h"

#define CURVE_LANES BF__BLOCK_LANES
/* Samples scored together (each loaded curve value is used this often). */
#define TILE_SAMPLES 4

/* The kernels' exp (src/fit/block.h), exposed for the tests. */
double bf__exp_nonpos(double x)
{
    return bf__vexp_nonpos(x);
}

/* ==== curve kernels ====================================================== */

/* The normalisation of a block (SPEC §2) -- every value finite, maximum
 * positive -- by one reciprocal per lane: r[j] = 1 / mx[j] and ok[j]. The
 * normalised value is v * r[j] (gen_block stores it; the streaming scorer
 * forms it as it reads v). nf[j] is the sum of v - v over the lane's
 * values: 0 when all are finite, NaN otherwise. */
static inline void block_recip(const double *mx, const double *nf,
                               double *r, unsigned char *ok)
{
    size_t j;
    for (j = 0; j < CURVE_LANES; j++) {
        r[j] = 1.0 / mx[j];
        ok[j] = (unsigned char)((nf[j] == 0.0) && (mx[j] > 0.0));
    }
}

static void block_state_release(bf__block *blk)
{
    free(blk->state);
    blk->state = NULL;
}

void *bf__block_state(bf__block *blk, size_t head, size_t n_doubles,
                      double **arrays)
{
    size_t off = bf__line_bytes(head);
    size_t len = off + bf__line_bytes(n_doubles * sizeof(double));
    unsigned char *mem;
    memset(blk, 0, sizeof *blk);
    if (n_doubles > (SIZE_MAX - 128 - off) / sizeof(double)) {
        return NULL;
    }
    mem = aligned_alloc(64, len);
    if (mem == NULL) {
        return NULL;
    }
    *arrays = (double *)(void *)(mem + off);
    blk->state = mem;
    blk->release = block_state_release;
    return mem;
}

/* A curve generator: a model's block kernel on one grid of a single free
 * parameter (the paper's protocol), its points lo + step i, i < points. */
typedef struct {
    bf__block blk;
    double lo;
    double step;
    size_t points;
} gen_t;

/* Sets up g for pm on lay by the model's block kernel; returns 1, 0 when
 * none applies (no kernel, several free parameters, or the model's own
 * conditions), or -BF_ENOMEM. */
static int gen_init(gen_t *g, const bf__prep *pm, const bf__grid_layout_t *lay)
{
    int rc;
    memset(g, 0, sizeof *g);
    if (pm->kr->block == NULL || lay->n_free != 1) {
        return 0;
    }
    rc = pm->kr->block(pm, lay, &g->blk);
    if (rc <= 0) {
        return rc;
    }
    g->lo = lay->lo[0];
    g->step = lay->step[0];
    g->points = lay->points;
    return 1;
}

static void gen_free(gen_t *g)
{
    if (g->blk.release != NULL) {
        g->blk.release(&g->blk);
    }
}

/* The grid values of the block at g0 (padding lanes, grid indices >=
 * points, repeat the last grid point). */
static void gen_x(const gen_t *g, size_t g0, double *x)
{
    size_t j;
    for (j = 0; j < CURVE_LANES; j++) {
        size_t i = g0 + j < g->points ? g0 + j : g->points - 1;
        x[j] = g->lo + g->step * (double)i; /* SPEC §7.4 */
    }
}

/* ok of the block at g0: padding lanes and undefined grids are not. */
static void gen_ok(const gen_t *g, size_t g0, unsigned char *ok)
{
    size_t j;
    for (j = 0; j < CURVE_LANES; j++) {
        if (g0 + j >= g->points || !g->blk.defined) {
            ok[j] = 0;
        }
    }
}

/* The raw values (before the normalisation) of the block at g0 into c,
 * with the reciprocals r[j] of the lanes' maxima and their flags ok[j]:
 * the normalised curve is c[k * stride + j] * r[j] (the streaming scorer
 * forms it as it reads c). One call of the model's kernel per block. */
static void gen_block_raw(const gen_t *g, size_t n, size_t g0, size_t stride,
                          double *c, double *r, unsigned char *ok)
{
    double x[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    gen_x(g, g0, x);
    g->blk.raw(&g->blk, n, x, stride, c, mx, nf);
    block_recip(mx, nf, r, ok);
    gen_ok(g, g0, ok);
}

/* The normalised curves of grid points g0 .. g0 + CURVE_LANES - 1 into
 * c[k * stride + j] and their flags ok[j]. */
static void gen_block(const gen_t *g, size_t n, size_t g0, size_t stride,
                      double *c, unsigned char *ok)
{
    double r[CURVE_LANES];
    size_t j;
    size_t k;
    gen_block_raw(g, n, g0, stride, c, r, ok);
    for (k = 0; k < n; k++) { /* SPEC §2 */
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            ck[j] = ck[j] * r[j];
        }
    }
}

/* Fills the transposed normalised curves of every grid point with the
 * model's block kernel when one applies (see gen_init). Returns 1 when
 * done, 0 when none does (the caller uses the plain evaluation), or
 * -BF_ENOMEM. */
int bf__curves_fast(const bf__prep *pm, const bf__grid_layout_t *lay,
                    size_t cols, size_t stride, double *curves,
                    unsigned char *ok)
{
    gen_t g;
    size_t g0;
    int rc;

    if (cols % CURVE_LANES != 0 || lay->points > cols) {
        return 0;
    }
    rc = gen_init(&g, pm, lay);
    if (rc <= 0) {
        return rc;
    }
    for (g0 = 0; g0 < cols; g0 += CURVE_LANES) {
        gen_block(&g, pm->n, g0, stride, curves + g0, ok + g0);
    }
    gen_free(&g);
    return 1;
}

/* ==== scoring ============================================================ */

/* LSE of BF__SCORE_LANES consecutive grid points (curves c, transposed with
 * stride) against TILE_SAMPLES samples d[s]: per lane the sum of
 * bf__sum_sq_diff, s = fma(r, r, s) over k in index order. */
BF__CLONES
static void score_tile(size_t n, size_t stride, const double *restrict c,
                       const double *const *d, double *restrict lse,
                       size_t lse_stride)
{
    double a0[BF__SCORE_LANES] = {0.0};
    double a1[BF__SCORE_LANES] = {0.0};
    double a2[BF__SCORE_LANES] = {0.0};
    double a3[BF__SCORE_LANES] = {0.0};
    const double *restrict d0 = d[0];
    const double *restrict d1 = d[1];
    const double *restrict d2 = d[2];
    const double *restrict d3 = d[3];
    size_t j;
    size_t k;
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * stride);
        double x0 = d0[k];
        double x1 = d1[k];
        double x2 = d2[k];
        double x3 = d3[k];
#pragma omp simd
        for (j = 0; j < BF__SCORE_LANES; j++) {
            double cj = ck[j];
            double r0 = cj - x0; /* SPEC §7.3 */
            double r1 = cj - x1;
            double r2 = cj - x2;
            double r3 = cj - x3;
            a0[j] = fma(r0, r0, a0[j]);
            a1[j] = fma(r1, r1, a1[j]);
            a2[j] = fma(r2, r2, a2[j]);
            a3[j] = fma(r3, r3, a3[j]);
        }
    }
    for (j = 0; j < BF__SCORE_LANES; j++) {
        lse[j] = a0[j];
        lse[lse_stride + j] = a1[j];
        lse[(2 * lse_stride) + j] = a2[j];
        lse[(3 * lse_stride) + j] = a3[j];
    }
}

/* The same for one sample (bf__grid_fit): four independent sums per lane
 * group keep the pipeline busy without a second sample. */
BF__CLONES
static void score_one(size_t n, size_t stride, const double *restrict c,
                      const double *restrict d, double *restrict lse)
{
    double a[BF__SCORE_LANES] = {0.0};
    size_t j;
    size_t k;
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * stride);
        double x = d[k];
#pragma omp simd
        for (j = 0; j < BF__SCORE_LANES; j++) {
            double r = ck[j] - x; /* SPEC §7.3 */
            a[j] = fma(r, r, a[j]);
        }
    }
    for (j = 0; j < BF__SCORE_LANES; j++) {
        lse[j] = a[j];
    }
}

/* LSE of every grid point (cols columns of the transposed curves) against
 * each of n_samples samples: lse[s * cols + g]. Tiles of TILE_SAMPLES
 * samples x BF__SCORE_LANES grid points. */
void bf__score_all(size_t n, size_t cols, size_t stride,
                   const double *curves, size_t n_samples,
                   const double *const *data, double *lse)
{
    long n_blocks = (long)(cols / BF__SCORE_LANES);
    long b;
    if (n_samples == 1) {
        for (b = 0; b < n_blocks; b++) {
            size_t g0 = (size_t)b * BF__SCORE_LANES;
            score_one(n, stride, curves + g0, data[0], lse + g0);
        }
        return;
    }
    for (b = 0; b < n_blocks; b++) {
        size_t g0 = (size_t)b * BF__SCORE_LANES;
        size_t s;
        for (s = 0; s < n_samples; s += TILE_SAMPLES) {
            const double *d[TILE_SAMPLES];
            double tmp[TILE_SAMPLES * BF__SCORE_LANES];
            size_t q;
            size_t left = n_samples - s;
            for (q = 0; q < TILE_SAMPLES; q++) {
                d[q] = data[s + (q < left ? q : left - 1)];
            }
            if (left >= TILE_SAMPLES) {
                score_tile(n, stride, curves + g0, d, lse + (s * cols) + g0,
                           cols);
            } else { /* last, partial tile: repeat a sample, keep `left` */
                score_tile(n, stride, curves + g0, d, tmp, BF__SCORE_LANES);
                for (q = 0; q < left; q++) {
                    memcpy(lse + ((s + q) * cols) + g0,
                           tmp + (q * BF__SCORE_LANES), sizeof(double) *
                                                             BF__SCORE_LANES);
                }
            }
        }
    }
}

/* ==== the objective's sum (src/fit/objective.c) ========================= */

/* sum_k w_k f_k (c_k - d_k)^2 in index order, each rounded square added by
 * one fma (w NULL: one add; f NULL: 1) -- the weights kernel's sum, so a
 * grid point's S is the same number either way. Here, not in objective.c,
 * so that fma is one instruction in the ISA clones. */
BF__CLONES
double bf__sum_weighted(size_t n, const double *c, const double *d,
                        const double *w, const double *f)
{
    double sum = 0.0;
    size_t k;
    for (k = 0; k < n; k++) {
        double r = c[k] - d[k]; /* SPEC §7.3 */
        double rho = (f != NULL ? f[k] : 1.0) * (r * r);
        sum = w != NULL ? fma(w[k], rho, sum) : sum + rho;
    }
    return sum;
}

/* ==== evaluate-and-normalise (src/fit/engine.c) ========================= */

/* Division by the maximum through its reciprocal, as the grid kernels
 * normalise a block (block_recip): BF_EDOM when a value is not finite
 * or the maximum is not positive. Vectorised: the sum of v - v is +0 when
 * every value is finite and NaN otherwise in any order, and the maximum
 * of finite values does not depend on the order, so the decision and the
 * bits are those of the loop in index order. */
BF__CLONES
int bf__normalise_recip(size_t n, double *curve)
{
    double mx = -INFINITY;
    double nf = 0.0;
    double r;
    size_t k;
#pragma omp simd reduction(max : mx) reduction(+ : nf)
    for (k = 0; k < n; k++) {
        double v = curve[k];
        nf += v - v; /* NaN once a value is not finite */
        mx = v > mx ? v : mx;
    }
    if (!(nf == 0.0 && mx > 0.0)) {
        return BF_EDOM;
    }
    r = 1.0 / mx;
#pragma omp simd
    for (k = 0; k < n; k++) {
        curve[k] = curve[k] * r; /* SPEC §2 */
    }
    return BF_OK;
}

/* ==== streaming: curves of one block, scored at once (the study) ======== */

/* The generic streaming scorers (no rows of the next block: that block is
 * made by the model's raw() between the blocks), the sample count a
 * constant (its sums in registers). */
BF__CLONES
static void score_stream_wide(size_t n, const double *restrict c,
                              const double *restrict rs,
                              const double *const *d, double *restrict lse,
                              bf__rows_t *restrict e)
{
    (void)e;
    bf__stream_score(BF__STREAM_SAMPLES, n, c, rs, d, lse, NULL, NULL);
}

BF__CLONES
static void score_stream_narrow(size_t n, const double *restrict c,
                                const double *restrict rs,
                                const double *const *d,
                                double *restrict lse, bf__rows_t *restrict e)
{
    (void)e;
    bf__stream_score(BF__STREAM_SAMPLES_NARROW, n, c, rs, d, lse, NULL,
                     NULL);
}

/* Samples per pass on this processor: BF__STREAM_SAMPLES with AVX-512's
 * 32 vector registers, BF__STREAM_SAMPLES_NARROW otherwise. */
static size_t stream_samples(void)
{
#if defined(__GNUC__) && defined(__x86_64__)
    return __builtin_cpu_supports("avx512f") ? BF__STREAM_SAMPLES
                                             : BF__STREAM_SAMPLES_NARROW;
#else
    return BF__STREAM_SAMPLES;
#endif
}

/* 1 when some defined value v[j] + pen[j] (pen 0 where defined, +inf
 * elsewhere) is below best; NaN never is. */
static inline int block_beats(const double *restrict v,
                              const double *restrict pen, double best)
{
    int any = 0;
    size_t j;
#pragma omp simd reduction(| : any)
    for (j = 0; j < CURVE_LANES; j++) {
        any |= (v[j] + pen[j]) < best;
    }
    return any;
}

BF__CLONES
int bf__stream_fast(const bf_model_type *type, const bf__grid_layout_t *lay,
                    const bf__cset *cs, size_t n_samples,
                    const double *const *data, double *best_lse,
                    size_t *best)
{
    double lse[BF__STREAM_SAMPLES * CURVE_LANES];
    double rs[CURVE_LANES]; /* the current block's reciprocal maxima */
    unsigned char ok[CURVE_LANES];
    double pen[CURVE_LANES];
    bf__rows_t e;
    double *c;
    double *nxt;
    gen_t g;
    bf__prep pm;
    size_t n = cs->n;
    size_t ns = stream_samples();
    size_t wide = ns == BF__STREAM_SAMPLES ? 0 : 1; /* score[wide] */
    size_t n_tiles = (n_samples + ns - 1) / ns;
    size_t g0;
    size_t s;
    bf__stream_score_fn plain = wide == 0 ? score_stream_wide
                                          : score_stream_narrow;
    bf__stream_score_fn piped; /* the next block's rows while scoring */
    int rc;

    if (type->kernel == NULL || type->kernel->block == NULL) {
        return 0; /* no block kernel: nothing to prepare */
    }
    rc = bf__prep_init(&pm, type, cs);
    if (rc != BF_OK) {
        bf__prep_free(&pm);
        return -rc;
    }
    rc = gen_init(&g, &pm, lay);
    bf__prep_free(&pm); /* the block kernel copied what it needs */
    if (rc <= 0) {
        return rc;
    }
    piped = g.blk.score[wide];
    c = aligned_alloc(64, 2 * n * CURVE_LANES * sizeof *c); /* 128 n B */
    if (c == NULL) {
        gen_free(&g);
        return -BF_ENOMEM;
    }
    nxt = c + (n * CURVE_LANES);
    for (s = 0; s < n_samples; s++) {
        best_lse[s] = INFINITY;
        best[s] = SIZE_MAX;
    }
    memset(&e, 0, sizeof e);
    gen_block_raw(&g, n, 0, CURVE_LANES, c, rs, ok);
    for (g0 = 0; g0 < g.points; g0 += CURVE_LANES) {
        int more = piped != NULL && g0 + CURVE_LANES < g.points;
        for (s = 0; s < CURVE_LANES; s++) {
            pen[s] = ok[s] ? 0.0 : INFINITY;
        }
        if (more) { /* the next block's rows, set up as raw() would */
            gen_x(&g, g0 + CURVE_LANES, e.x);
            for (s = 0; s < CURVE_LANES; s++) {
                e.mx[s] = -INFINITY;
                e.nf[s] = 0.0;
            }
            e.state = g.blk.state;
            e.out = nxt;
            e.every = n_tiles;
        }
        for (s = 0; s < n_samples; s += ns) {
            const double *d[BF__STREAM_SAMPLES];
            size_t left = n_samples - s;
            size_t q;
            size_t j;
            for (q = 0; q < ns; q++) {
                d[q] = data[s + (q < left ? q : left - 1)];
            }
            if (more) {
                e.first = s / ns; /* rows spread over the tiles */
                piped(n, c, rs, d, lse, &e);
            } else {
                plain(n, c, rs, d, lse, NULL);
            }
            if (left > ns) {
                left = ns;
            }
            /* the running argmin: grid points in index order, strict <
             * (ties keep the first point, NaN never wins), defined points
             * only -- bf__argmin's result. A vector test first: only when
             * some point of the block beats the best so far, the scan. */
            for (q = 0; q < left; q++) {
                const double *lq = lse + (q * CURVE_LANES);
                if (!block_beats(lq, pen, best_lse[s + q])) {
                    continue; /* the usual case */
                }
                for (j = 0; j < CURVE_LANES; j++) {
                    if (ok[j] && lq[j] < best_lse[s + q]) {
                        best_lse[s + q] = lq[j];
                        best[s + q] = g0 + j;
                    }
                }
            }
        }
        if (more) { /* the next block is complete: normalise, swap */
            double *tmp = c;
            block_recip(e.mx, e.nf, rs, ok); /* scaled as it is read */
            gen_ok(&g, g0 + CURVE_LANES, ok);
            c = nxt;
            nxt = tmp;
        } else if (g0 + CURVE_LANES < g.points) {
            gen_block_raw(&g, n, g0 + CURVE_LANES, CURVE_LANES, c, rs, ok);
        }
    }
    free(c < nxt ? c : nxt);
    gen_free(&g);
    return 1;
}

/* Lanes of the argmin below. */
#define ARGMIN_LANES 8

/* The smallest LSE among the defined grid points (ok[g] != 0) of one row
 * and the first point where it occurs (ties keep the first grid point, as
 * bf_fit_grid's strict comparison does); *best = SIZE_MAX when no point is
 * defined or no LSE is finite. Each lane keeps its own minimum and the
 * first index reaching it; the first index among the lanes that hold the
 * overall minimum is the first occurrence overall. */
BF__CLONES
double bf__argmin(size_t points, const double *restrict lse,
                  const unsigned char *restrict ok, size_t *best)
{
    double mv[ARGMIN_LANES];
    size_t mi[ARGMIN_LANES];
    double min = INFINITY;
    size_t g0;
    size_t g;
    size_t j;
    for (j = 0; j < ARGMIN_LANES; j++) {
        mv[j] = INFINITY;
        mi[j] = SIZE_MAX;
    }
    for (g0 = 0; g0 + ARGMIN_LANES <= points; g0 += ARGMIN_LANES) {
#pragma omp simd
        for (j = 0; j < ARGMIN_LANES; j++) {
            double v = ok[g0 + j] ? lse[g0 + j] : INFINITY;
            int lt = v < mv[j]; /* NaN never wins, as in bf_fit_grid */
            mv[j] = lt ? v : mv[j];
            mi[j] = lt ? g0 + j : mi[j];
        }
    }
    for (g = g0; g < points; g++) {
        double v = ok[g] ? lse[g] : INFINITY;
        if (v < mv[g - g0]) {
            mv[g - g0] = v;
            mi[g - g0] = g;
        }
    }
    *best = SIZE_MAX;
    for (j = 0; j < ARGMIN_LANES; j++) {
        if (mv[j] < min || (mv[j] == min && mi[j] < *best)) {
            min = mv[j];
            *best = mi[j];
        }
    }
    return min;
}
