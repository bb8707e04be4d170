/* block.h: what a model's block kernel (bf_kernel.block, src/fit/engine.h)
 * is made of -- the raw values of BF__BLOCK_LANES consecutive grid points
 * at once for the study/grid path (src/fit/kernels.c drives it, scores
 * and normalises), the exp the kernels share, and the streaming scorer a
 * model may instantiate with its own row (to interleave the next block's
 * values with the scoring of the current one). No model lives here: each
 * model's file fills its own bf__block (src/models/bk.c,
 * src/models/lafortune.c). Included by the kernels, never installed. */
#ifndef BF_FIT_BLOCK_H
#define BF_FIT_BLOCK_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* Grid points per block: one AVX-512 register of doubles (two of AVX2's);
 * a block of curves (8 x K doubles: 12.7 KB at K = 198) and the next one
 * fit a 32 KB L1 together. The bits do not depend on it: every grid
 * point's sums are formed alone, in index order. */
#define BF__BLOCK_LANES 8

/* Samples the streaming scorer scores together against one block: their
 * BF__STREAM_SAMPLES x BF__BLOCK_LANES sums take 8 of AVX-512's 32
 * registers; with AVX2's (or the baseline's) 16, BF__STREAM_SAMPLES_NARROW
 * leave room for the curve values (measured on Zen 3: 4 is fastest). The
 * sums, and so the bits, do not depend on how many samples share a pass. */
#define BF__STREAM_SAMPLES 8
#define BF__STREAM_SAMPLES_NARROW 4

/* ==== exp of a non-positive argument, vectorisable ======================= */

/* ln 2 as the double nearest it and the rest (the reduction x - k ln 2 is
 * taken with fma, which forms k ln2_hi exactly); 1/ln 2; 1.5 * 2^52, which
 * rounds a double below 2^51 in magnitude to an integer in its low
 * bits. */
#define BF__EXP_LN2_HI 0x1.62e42fefa39efp-1
#define BF__EXP_LN2_LO 0x1.abc9e3b39803fp-56
#define BF__EXP_INV_LN2 0x1.71547652b82fep0
#define BF__EXP_SHIFTER 0x1.8p52
/* Below this argument e^x < 2^-1021 (near DBL_MIN): the result is 0. */
#define BF__EXP_MIN_ARG (-708.0)

/* e^x for x <= 0 (the block kernels' arguments are exponents of decaying
 * lobes). Straight-line code the compiler vectorises: x = k ln 2 + r with
 * |r| <= ln(2)/2 (Cody-Waite, fma), e^r by its Taylor polynomial of degree
 * 13 (truncation below 2^-57), times 2^k built in the exponent bits.
 * Within 1 ulp of glibc's exp on [-708, 0] (tests/fit/test_grid.c through
 * bf__exp_nonpos); 0 below -708 (where glibc gives a subnormal or 0), for
 * -inf and for NaN. The same bits on every ISA: every operation is
 * correctly rounded (no contraction, explicit fma). */
static inline double bf__vexp_nonpos(double x)
{
    double xc = (x >= BF__EXP_MIN_ARG) ? x : BF__EXP_MIN_ARG;
    double t = fma(xc, BF__EXP_INV_LN2, BF__EXP_SHIFTER); /* k, low bits */
    double kd = t - BF__EXP_SHIFTER; /* k = round(x/ln 2) */
    double r = fma(-kd, BF__EXP_LN2_HI, xc);
    double p;
    double scale;
    uint64_t bits;
    r = fma(-kd, BF__EXP_LN2_LO, r);
    p = 1.0 / 6227020800.0; /* 1/13! ... 1/0!, Horner */
    p = fma(p, r, 1.0 / 479001600.0);
    p = fma(p, r, 1.0 / 39916800.0);
    p = fma(p, r, 1.0 / 3628800.0);
    p = fma(p, r, 1.0 / 362880.0);
    p = fma(p, r, 1.0 / 40320.0);
    p = fma(p, r, 1.0 / 5040.0);
    p = fma(p, r, 1.0 / 720.0);
    p = fma(p, r, 1.0 / 120.0);
    p = fma(p, r, 1.0 / 24.0);
    p = fma(p, r, 1.0 / 6.0);
    p = fma(p, r, 0.5);
    p = fma(p, r, 1.0);
    p = fma(p, r, 1.0);
    memcpy(&bits, &t, sizeof bits);
    /* 2^k, k in [-1021, 0]: k + 1023 into the exponent field; unsigned
     * arithmetic drops the shifter's high bits (wraps, as defined) */
    bits = (bits + 1023u) << 52;
    memcpy(&scale, &bits, sizeof scale);
    return (x >= BF__EXP_MIN_ARG) ? p * scale : 0.0;
}

/* ==== a model's block kernel ============================================= */

/* The rows of the next block a streaming scorer computes while it scores
 * the current one (see bf__stream_score): the next block's parameter
 * values, its running maxima and finiteness sums (as a raw() call forms
 * them), its n x BF__BLOCK_LANES raw values (contiguous), and which rows
 * this call computes (first, first + every, ...). */
typedef struct {
    const void *state; /* the block kernel's state (bf__block.state) */
    double x[BF__BLOCK_LANES];
    double mx[BF__BLOCK_LANES];
    double nf[BF__BLOCK_LANES];
    double *out;
    size_t first;
    size_t every;
} bf__rows_t;

/* Scores the raw values c (n x BF__BLOCK_LANES, contiguous; normalised as
 * they are read, c * rs[j]) of one block against a fixed number of samples
 * d[q] into lse[q * BF__BLOCK_LANES + j], and computes e's rows of the
 * next block when e is not NULL. */
typedef void (*bf__stream_score_fn)(size_t n, const double *c,
                                    const double *rs, const double *const *d,
                                    double *lse, bf__rows_t *e);

/* A model's block kernel set up for one grid (by bf_kernel.block): its
 * state and what to call. One thread uses a bf__block (raw() may use
 * scratch memory of the state). */
typedef struct bf__block bf__block;
struct bf__block {
    void *state;  /* the model's; release() frees it */
    int defined;  /* 0: no grid point gives a curve (the model's domain) */
    /* Raw values (before the normalisation of SPEC §2; factors constant
     * over the configurations may be dropped) of the n configurations at
     * the free parameter's values x[j], j < BF__BLOCK_LANES, into c[k *
     * stride + j], with per lane the maximum mx[j] and nf[j], the sum of
     * v - v over the lane's values (0 when all are finite, else NaN). */
    void (*raw)(const bf__block *blk, size_t n, const double *x,
                size_t stride, double *c, double *mx, double *nf);
    /* Optional (NULL: the next block is made by raw() between the blocks):
     * streaming scorers of BF__STREAM_SAMPLES (score[0]) and
     * BF__STREAM_SAMPLES_NARROW (score[1]) samples that also compute the
     * next block's rows, the operations of raw() row by row (so the bits
     * are raw()'s); made by bf__stream_score with the model's row. Worth
     * it where the values use another unit than the scoring (divisions,
     * square roots). */
    bf__stream_score_fn score[2];
    void (*release)(bf__block *blk);
};

/* Clears blk and makes its state: head bytes (the model's struct) followed
 * by n_doubles doubles, 64-byte aligned, in one allocation (*arrays points
 * at the doubles); blk->release frees it (src/fit/kernels.c). Returns the
 * state, or NULL when out of memory (blk then holds nothing). */
void *bf__block_state(bf__block *blk, size_t head, size_t n_doubles,
                      double **arrays);

/* Row k of the next block at the lanes' parameter values x: the raw
 * values into out[j], the maxima mx[j] and finiteness sums nf[j] updated
 * (raw()'s operations for that row). */
typedef void (*bf__row_fn)(const void *state, size_t k, const double *x,
                           double *out, double *mx, double *nf);

#if defined(__GNUC__)
#define BF__ALWAYS_INLINE __attribute__((always_inline))
#else
#define BF__ALWAYS_INLINE
#endif

/* `omp simd` over the BF__BLOCK_LANES (8) lanes where OpenMP is on (the
 * library; a file built without it, a test, gets the plain loop, the same
 * values). */
#if defined(_OPENMP)
#define BF__SIMD_LANES _Pragma("omp simd simdlen(8)")
#else
#define BF__SIMD_LANES
#endif

/* The streaming scorer of ns samples (a constant where it is
 * instantiated: its sums stay in registers), row the model's (a constant
 * function, inlined; NULL only with e NULL): each LSE the sum of
 * bf__sum_sq_diff in index order with one fma per term, as score_tile
 * (src/fit/kernels.c) forms it. Scaling as the values are read instead of
 * in a pass of its own saves a read and a write of the block (which
 * leaves the caches at large K). */
static inline BF__ALWAYS_INLINE void
bf__stream_score(size_t ns, size_t n, const double *restrict c,
                 const double *restrict rs, const double *const *d,
                 double *restrict lse, bf__rows_t *restrict e,
                 bf__row_fn row)
{
    double a[BF__STREAM_SAMPLES][BF__BLOCK_LANES];
    double x[BF__BLOCK_LANES];
    double mx[BF__BLOCK_LANES];
    double nf[BF__BLOCK_LANES];
    size_t next_e = e != NULL ? e->first : SIZE_MAX;
    size_t j;
    size_t k;
    size_t q;
    for (q = 0; q < ns; q++) {
        for (j = 0; j < BF__BLOCK_LANES; j++) {
            a[q][j] = 0.0;
        }
    }
    if (e != NULL) {
        memcpy(x, e->x, sizeof x);
        memcpy(mx, e->mx, sizeof mx);
        memcpy(nf, e->nf, sizeof nf);
    } else {
        memset(x, 0, sizeof x);
        memset(mx, 0, sizeof mx);
        memset(nf, 0, sizeof nf);
    }
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * BF__BLOCK_LANES);
        double dk[BF__STREAM_SAMPLES];
        for (q = 0; q < ns; q++) {
            dk[q] = d[q][k];
        }
        for (q = 0; q < ns; q++) {
            BF__SIMD_LANES
            for (j = 0; j < BF__BLOCK_LANES; j++) {
                /* the normalised value, SPEC §2 */
                double r = (ck[j] * rs[j]) - dk[q]; /* SPEC §7.3 */
                a[q][j] = fma(r, r, a[q][j]);
            }
        }
        if (k == next_e) { /* the model's row k of the next block */
            row(e->state, k, x, e->out + (k * BF__BLOCK_LANES), mx, nf);
            next_e += e->every;
        }
    }
    for (q = 0; q < ns; q++) {
        for (j = 0; j < BF__BLOCK_LANES; j++) {
            lse[(q * BF__BLOCK_LANES) + j] = a[q][j];
        }
    }
    if (e != NULL) {
        memcpy(e->mx, mx, sizeof mx);
        memcpy(e->nf, nf, sizeof nf);
    }
}

#endif
