/* kernels.c: the study path's vectorised inner loops -- normalised model
 * curves of a block of grid points at once from geometry terms computed
 * once per configuration, and the residual sums of squares (SPEC §7.3) of
 * a block of grid points against several samples at once.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model",
 *     (P1), (P2), (P7); SPEC §3.1, §3.2, §6 (the formulas), §2 (the
 *     normalisation), §7.3-7.4 (LSE, grid).
 *
 * Layout: curves are stored transposed, curves[k * stride + g] for
 * configuration k and grid point g, so a vector register holds one
 * configuration of consecutive grid points. Vectorising across grid
 * points, never across the sum over configurations, keeps every LSE a
 * sum in index order, as bf__sum_sq_diff forms it.
 *
 * The math is rearranged against the plain path (bk.c, lafortune.c,
 * bf_normalise), algebraically exactly, to take divisions and pow out of
 * the inner loop:
 *   - factors that do not depend on the configuration are dropped, since
 *     they cancel in the normalisation (SPEC §2): 1/m^2 of (P1), 2m of
 *     (P2), (n_d + 2)/(2 pi) of (P7);
 *   - G:  l = (F^2/vz^2) exp((-vxy^2/(4 vz^2)) / m^2), both brackets once
 *         per configuration, 1/m^2 once per grid point;
 *   - E:  l = F^2 |vz| / (d sqrt d), d = fma(m^2, vz^2, vxy^2), as bk.c;
 *   - LFTG: (cos ti cos ts)^n_d = exp(n_d ln(cos ti cos ts)), the log once
 *         per configuration;
 *   - normalisation multiplies by 1/max instead of dividing by max;
 *   - each LSE term is added with one fma (one rounding instead of two);
 *   - exp comes from glibc's vector math library libmvec (at most 4 ulp)
 *     when BF_VECTOR_MATH is defined (the default build).
 * The normalised curves therefore differ from the plain path's by a few
 * units in the last place (absolute, the curves peak at 1), and each LSE
 * by a few ulp times sqrt(K LSE). tests/fit/test_grid.c bounds the
 * difference and checks that every optimum is the same grid point on all
 * 61 CURET samples and every model (the plain path stays the reference).
 * No -ffast-math: the library is built with -ffp-contract=off, so the only
 * fused multiply-adds are the explicit fma() calls, in every ISA.
 *
 * Dispatch: the kernels are compiled for x86-64-v4 (AVX-512), x86-64-v3
 * (AVX2 + FMA) and the baseline, and the loader picks one at run time
 * (GCC's target_clones); the default build never uses -march=native.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#if defined(BF_VECTOR_MATH)
/* glibc declares its vector variants (libmvec) only under -ffast-math;
 * declare exp's here so that the simd loops below call _ZGV*_exp. */
#pragma omp declare simd notinbranch
extern double exp(double x);
#endif

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&   \
    defined(__has_attribute)
#if __has_attribute(target_clones)
#define BF__CLONES                                                         \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3",     \
                                 "default")))
#endif
#endif
#ifndef BF__CLONES
#define BF__CLONES
#endif

/* Grid points per curve block: one AVX-512 register of doubles. */
#define CURVE_LANES 8
/* Samples scored together (each loaded curve value is used this often). */
#define TILE_SAMPLES 4

/* ==== geometry terms, once per configuration ============================= */

/* Structure of arrays of the per-configuration terms, 64-byte aligned.
 * Every factor that does not depend on the configuration (1/m^2 of (P1),
 * 2m of (P2), (n_d + 2)/(2 pi) of (P7)) is dropped: it cancels in the
 * normalisation (SPEC §2). */
typedef struct {
    double *a;   /* G: F^2/vz^2   E: F^2 |vz|   LFTG: ln(cos ti cos ts) */
    double *b;   /* G: -vxy^2/(4 vz^2)   E: vz^2 */
    double *c;   /* E: vxy^2 */
    double *mem;
} terms_t;

static int terms_alloc(terms_t *t, size_t n)
{
    size_t len = (3 * n * sizeof(double) + 63) / 64 * 64;
    t->mem = aligned_alloc(64, len);
    if (t->mem == NULL) {
        return BF_ENOMEM;
    }
    t->a = t->mem;
    t->b = t->a + n;
    t->c = t->b + n;
    return BF_OK;
}

/* Fills t for the BK family member (factor, corr) with FC's index n_index
 * (SPEC §3): per configuration the slope-independent parts of (P1)/(P2).
 * Where vz = 0 (theta_i = theta_s = pi/2) the model's limit is 0 (SPEC
 * §3.3): a = 0 and a harmless denominator. Returns 0 when some
 * configuration is outside the model's domain (BK at theta_i = pi/2) or a
 * term is not finite: then no slope gives a curve. */
static int terms_bk(int factor, int corr, double n_index, size_t n,
                    const bf_geom *geom, terms_t *t)
{
    size_t k;
    int ok = 1;
    for (k = 0; k < n; k++) {
        bf__bk_terms_t bt = {0.0, 0.0, 0.0, 0.0};
        if (bf__bk_terms(factor, n_index, &geom[k], &bt) != BF_OK) {
            ok = 0; /* BK at theta_i = pi/2: no slope works */
        }
        if (bt.vz2 == 0.0) {
            t->a[k] = 0.0; /* the limit 0, SPEC §3.3 */
            t->b[k] = 0.0;
            t->c[k] = 1.0;
        } else if (corr == BF__BK_CORR_GAUSS) {
            /* (P1): L m^2 = F^2/vz^2 exp(-vxy^2/(4 vz^2) / m^2) */
            t->a[k] = bt.f2 / bt.vz2;
            t->b[k] = -bt.vxy2 / (4.0 * bt.vz2);
            t->c[k] = 0.0;
        } else {
            /* (P2) as in bk.c: L / (2m) = F^2 |vz| / (m^2 vz^2 + vxy^2)^1.5 */
            t->a[k] = bt.f2 * bt.abs_vz;
            t->b[k] = bt.vz2;
            t->c[k] = bt.vxy2;
        }
        if (!isfinite(t->a[k]) || !isfinite(t->b[k])) {
            ok = 0;
        }
    }
    return ok;
}

/* ==== curve kernels ====================================================== */

/* Normalises a block (SPEC §2) -- every value finite, maximum positive --
 * by one reciprocal per lane, and sets ok per lane. nf[j] is the sum of
 * v - v over the lane's values: 0 when all are finite, NaN otherwise. */
static inline void normalise_block(size_t n, size_t stride,
                                   double *restrict c, const double *mx,
                                   const double *nf, unsigned char *ok)
{
    double r[CURVE_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < CURVE_LANES; j++) {
        r[j] = 1.0 / mx[j];
        ok[j] = (unsigned char)((nf[j] == 0.0) && (mx[j] > 0.0));
    }
    for (k = 0; k < n; k++) {
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            ck[j] = ck[j] * r[j]; /* SPEC §2 */
        }
    }
}

/* Gaussian correlation (P1), SPEC §3.1, for CURVE_LANES slopes m[]:
 * l = a exp(b / m^2), one multiply, one exp and one multiply per value. */
BF__CLONES
static void block_gauss(size_t n, const terms_t *t, const double *m,
                        size_t stride, double *restrict c, unsigned char *ok)
{
    double inv_m2[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < CURVE_LANES; j++) {
        inv_m2[j] = 1.0 / (m[j] * m[j]);
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        double a = t->a[k];
        double b = t->b[k];
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            double v = a * exp(b * inv_m2[j]); /* (P1), SPEC §3.1 */
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    normalise_block(n, stride, c, mx, nf, ok);
}

/* Exponential correlation (P2), SPEC §3.2, in bk.c's form:
 * l = a / (d sqrt d), d = m^2 vz^2 + vxy^2 (one fma, sqrt, multiply,
 * division per value). */
BF__CLONES
static void block_exp(size_t n, const terms_t *t, const double *m,
                      size_t stride, double *restrict c, unsigned char *ok)
{
    double m2[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < CURVE_LANES; j++) {
        m2[j] = m[j] * m[j];
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        double a = t->a[k];
        double vz2 = t->b[k];
        double vxy2 = t->c[k];
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            double d = fma(m2[j], vz2, vxy2); /* (P2), SPEC §3.2 */
            double v = a / (d * sqrt(d));
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    normalise_block(n, stride, c, mx, nf, ok);
}

/* LFTG (P7), SPEC §6: l = (cos ti cos ts)^n_d = exp(n_d ln(cos ti cos ts)),
 * with the logarithm taken once per configuration (0 at grazing gives
 * exp(-inf) = 0, the value of pow for n_d > 0). */
BF__CLONES
static void block_lftg(size_t n, const terms_t *t, const double *n_d,
                       size_t stride, double *restrict c, unsigned char *ok)
{
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < CURVE_LANES; j++) {
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        double ln_base = t->a[k];
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            double v = exp(n_d[j] * ln_base); /* (P7), SPEC §6 */
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    normalise_block(n, stride, c, mx, nf, ok);
}

/* Fills the transposed normalised curves of every grid point with a
 * vectorised kernel when one exists for type: BK family with the slope m
 * free, or LFTG with n_d free on a grid of positive values (a single free
 * parameter, the paper's protocol). Returns 1 when done, 0 when type has
 * no kernel (the caller uses the plain evaluation), or -BF_ENOMEM. Padding
 * lanes (grid indices >= points, up to cols) repeat the last grid point
 * and are marked not ok. Blocks are shared among n_threads threads. */
int bf__curves_fast(const bf_model_type *type, const bf__grid_layout_t *lay,
                    size_t n, const bf_geom *geom, size_t cols,
                    size_t stride, double *curves, unsigned char *ok,
                    int n_threads)
{
    int factor = 0;
    int corr = 0;
    int is_bk = bf__bk_kind(type, &factor, &corr);
    int is_lftg = bf__is_lftg(type);
    const bf_param *pf;
    terms_t t;
    long n_blocks;
    long b;
    size_t k;
    int defined = 1;

    if ((!is_bk && !is_lftg) || lay->n_free != 1 || lay->free[0] != 0 ||
        cols % CURVE_LANES != 0 || lay->points > cols ||
        (is_lftg && !(type->param[0].grid_lo > 0.0))) {
        return 0;
    }
    pf = &type->param[0];
    if (n_threads < 1) {
        n_threads = 1;
    }
    if (terms_alloc(&t, n) != BF_OK) {
        return -BF_ENOMEM;
    }
    if (is_lftg) {
        for (k = 0; k < n; k++) {
            t.a[k] = log(bf__lftg_base(&geom[k])); /* -inf at grazing */
        }
    } else {
        /* FC's refractive index is parameter 1, fixed here */
        double n_index = (factor == BF__BK_FACTOR_FC) ? lay->base[1] : 1.0;
        defined = terms_bk(factor, corr, n_index, n, geom, &t);
    }
    n_blocks = (long)(cols / CURVE_LANES);
#pragma omp parallel for num_threads(n_threads) if (n_threads > 1)         \
    schedule(static)
    for (b = 0; b < n_blocks; b++) {
        size_t g0 = (size_t)b * CURVE_LANES;
        double x[CURVE_LANES];
        size_t j;
        for (j = 0; j < CURVE_LANES; j++) {
            size_t i = g0 + j < lay->points ? g0 + j : lay->points - 1;
            x[j] = pf->grid_lo + pf->grid_step * (double)i; /* SPEC §7.4 */
        }
        if (is_lftg) {
            block_lftg(n, &t, x, stride, curves + g0, ok + g0);
        } else if (corr == BF__BK_CORR_GAUSS) {
            block_gauss(n, &t, x, stride, curves + g0, ok + g0);
        } else {
            block_exp(n, &t, x, stride, curves + g0, ok + g0);
        }
        for (j = 0; j < CURVE_LANES; j++) {
            if (g0 + j >= lay->points || !defined) {
                ok[g0 + j] = 0;
            }
        }
    }
    free(t.mem);
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

/* The same for one sample (bf_grid_fit): four independent sums per lane
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
 * samples x BF__SCORE_LANES grid points; threads share the grid blocks. */
void bf__score_all(size_t n, size_t cols, size_t stride,
                   const double *curves, size_t n_samples,
                   const double *const *data, double *lse, int n_threads)
{
    long n_blocks = (long)(cols / BF__SCORE_LANES);
    long b;
    if (n_threads < 1) {
        n_threads = 1;
    }
    if (n_samples == 1) {
        for (b = 0; b < n_blocks; b++) {
            size_t g0 = (size_t)b * BF__SCORE_LANES;
            score_one(n, stride, curves + g0, data[0], lse + g0);
        }
        return;
    }
#pragma omp parallel for num_threads(n_threads) if (n_threads > 1)         \
    schedule(static)
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
