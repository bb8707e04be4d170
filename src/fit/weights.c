/* weights.c: many weight vectors against one grid's stored curves -- the
 * sums S_b(g) = sum_k w_bk c_k (L_kg - D_k)^2 of bootstrap replicates and
 * cross-validation folds (doc/methods.md §3, §5, §9), and their grid
 * optima, from one pass over the curves.
 *
 * [1] SPEC §7.3 (the LSE as a sum), §7.4 (grid, ties keep the first
 *     point); doc/methods.md §1 (objectives), §3 (bootstrap weights).
 *
 * Every sum is formed alone, in index order, one fma per term (the
 * engine's objective, bf__sum_weighted): vectorised across grid points,
 * never across the sum over configurations, so a sum has the same bits
 * whichever kernel forms it. Built like src/fit/kernels.c (-O3, one clone
 * per ISA, no contraction).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* ==== the tile kernel ===================================================== */

/* Grid columns whose squared residuals are formed at once (in L2); a tile
 * is WTILE weight vectors x WLANES columns, its WTILE x WLANES sums in
 * registers (AVX2: 12 of 16, so that the FMA latency is hidden). */
#define WSUPER 128
#define WLANES 8
#define WTILE 6
/* Configurations between two tests of a tile against its rows' bounds. */
#define WCHUNK 16

/* The sums of one tile: out[q * WLANES + j] = sum_k w[q][k] rho[k *
 * WSUPER + j], one fma per term in index order (the engine's objective,
 * bf__sum_weighted: the same bits). Early stop: after every WCHUNK
 * configurations, when every sum of a candidate column (cand[j] != 0)
 * exceeds its row's bound[q], returns 0 with the sums unfinished. With
 * weights and factors >= 0 every term is >= 0 and a rounded fma of a
 * non-negative term never lowers a sum, so a partial sum past the bound
 * ends past it: no column of the tile is then an optimum of any of its
 * rows. A NaN bound never stops. Else 1. */
static int tile_c(size_t n, const double *restrict rho,
                  const double *const *w, const double *restrict bound,
                  const int *restrict cand, double *restrict out)
{
    double acc[WTILE][WLANES];
    size_t k;
    size_t j;
    size_t q;
    for (q = 0; q < WTILE; q++) {
        for (j = 0; j < WLANES; j++) {
            acc[q][j] = 0.0;
        }
    }
    for (k = 0; k < n; k++) {
        const double *restrict rk = rho + (k * WSUPER);
        for (q = 0; q < WTILE; q++) {
            double wq = w[q][k];
            for (j = 0; j < WLANES; j++) {
                acc[q][j] = fma(wq, rk[j], acc[q][j]);
            }
        }
        if ((k + 1) % WCHUNK == 0 && k + 1 < n) {
            int past = 1;
            for (q = 0; q < WTILE; q++) {
                for (j = 0; j < WLANES; j++) {
                    past &= (acc[q][j] > bound[q]) | (cand[j] == 0);
                }
            }
            if (past) {
                return 0;
            }
        }
    }
    for (q = 0; q < WTILE; q++) {
        for (j = 0; j < WLANES; j++) {
            out[(q * WLANES) + j] = acc[q][j];
        }
    }
    return 1;
}

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define TILE_AVX2 1

/* tile_c with AVX2 and FMA, written out so that the 12 sums stay in
 * registers (the compiler spills the C version's): the same fma of the
 * same terms in the same order, so the same bits. */
__attribute__((target("avx2,fma"))) static int
tile_avx2(size_t n, const double *restrict rho, const double *const *w,
          const double *restrict bound, const int *restrict cand,
          double *restrict out)
{
    __m256d a00 = _mm256_setzero_pd();
    __m256d a01 = a00, a10 = a00, a11 = a00, a20 = a00, a21 = a00;
    __m256d a30 = a00, a31 = a00, a40 = a00, a41 = a00, a50 = a00;
    __m256d a51 = a00;
    /* all-ones lanes where a column is no candidate: always past */
    __m256d dead0 = _mm256_castsi256_pd(_mm256_set_epi64x(
        -(long long)!cand[3], -(long long)!cand[2], -(long long)!cand[1],
        -(long long)!cand[0]));
    __m256d dead1 = _mm256_castsi256_pd(_mm256_set_epi64x(
        -(long long)!cand[7], -(long long)!cand[6], -(long long)!cand[5],
        -(long long)!cand[4]));
    const double *w0 = w[0], *w1 = w[1], *w2 = w[2];
    const double *w3 = w[3], *w4 = w[4], *w5 = w[5];
    size_t k = 0;
    while (k < n) {
        size_t end = n - k > WCHUNK ? k + WCHUNK : n;
        __m256d m;
        __m256d b;
        for (; k < end; k++) {
            const double *rk = rho + (k * WSUPER);
            __m256d r0 = _mm256_loadu_pd(rk);
            __m256d r1 = _mm256_loadu_pd(rk + 4);
            b = _mm256_broadcast_sd(w0 + k);
            a00 = _mm256_fmadd_pd(b, r0, a00);
            a01 = _mm256_fmadd_pd(b, r1, a01);
            b = _mm256_broadcast_sd(w1 + k);
            a10 = _mm256_fmadd_pd(b, r0, a10);
            a11 = _mm256_fmadd_pd(b, r1, a11);
            b = _mm256_broadcast_sd(w2 + k);
            a20 = _mm256_fmadd_pd(b, r0, a20);
            a21 = _mm256_fmadd_pd(b, r1, a21);
            b = _mm256_broadcast_sd(w3 + k);
            a30 = _mm256_fmadd_pd(b, r0, a30);
            a31 = _mm256_fmadd_pd(b, r1, a31);
            b = _mm256_broadcast_sd(w4 + k);
            a40 = _mm256_fmadd_pd(b, r0, a40);
            a41 = _mm256_fmadd_pd(b, r1, a41);
            b = _mm256_broadcast_sd(w5 + k);
            a50 = _mm256_fmadd_pd(b, r0, a50);
            a51 = _mm256_fmadd_pd(b, r1, a51);
        }
        if (k == n) {
            break;
        }
#define PAST(m, acc0, acc1, q)                                               \
    b = _mm256_broadcast_sd(bound + (q));                                    \
    m = _mm256_and_pd(                                                       \
        m, _mm256_and_pd(                                                    \
               _mm256_or_pd(_mm256_cmp_pd(acc0, b, _CMP_GT_OQ), dead0),      \
               _mm256_or_pd(_mm256_cmp_pd(acc1, b, _CMP_GT_OQ), dead1)))
        m = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        PAST(m, a00, a01, 0);
        PAST(m, a10, a11, 1);
        PAST(m, a20, a21, 2);
        PAST(m, a30, a31, 3);
        PAST(m, a40, a41, 4);
        PAST(m, a50, a51, 5);
#undef PAST
        if (_mm256_movemask_pd(m) == 0xf) {
            return 0;
        }
    }
    _mm256_storeu_pd(out + 0, a00);
    _mm256_storeu_pd(out + 4, a01);
    _mm256_storeu_pd(out + 8, a10);
    _mm256_storeu_pd(out + 12, a11);
    _mm256_storeu_pd(out + 16, a20);
    _mm256_storeu_pd(out + 20, a21);
    _mm256_storeu_pd(out + 24, a30);
    _mm256_storeu_pd(out + 28, a31);
    _mm256_storeu_pd(out + 32, a40);
    _mm256_storeu_pd(out + 36, a41);
    _mm256_storeu_pd(out + 40, a50);
    _mm256_storeu_pd(out + 44, a51);
    return 1;
}
#endif

int bf__weights_tile(int generic, size_t n, const double *rho,
                     const double *const *w, const double *bound,
                     const int *cand, double *out)
{
#ifdef TILE_AVX2
    if (!generic && __builtin_cpu_supports("avx2") &&
        __builtin_cpu_supports("fma")) {
        return tile_avx2(n, rho, w, bound, cand, out);
    }
#endif
    (void)generic;
    return tile_c(n, rho, w, bound, cand, out);
}

/* ==== squared residuals and tiles of weight vectors ====================== */

/* rho[k * WSUPER + j] = cw_k (c[k][g0 + j] - d_k)^2, j < WSUPER. */
BF__CLONES
static void squared_residuals(size_t n, size_t stride,
                              const double *restrict c,
                              const double *restrict d,
                              const double *restrict cw,
                              double *restrict rho)
{
    size_t j;
    size_t k;
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * stride);
        double dk = d[k];
        double f = cw != NULL ? cw[k] : 1.0;
#pragma omp simd
        for (j = 0; j < WSUPER; j++) {
            double r = ck[j] - dk;
            rho[(k * WSUPER) + j] = f * (r * r);
        }
    }
}

/* rho for the super-block of columns g0 .. g0 + width (a padded copy when
 * width < WSUPER: the columns past the grid score 0 - d_k). */
static void super_rho(size_t n, size_t stride, const double *curves,
                      const double *data, const double *cw, size_t g0,
                      size_t width, double *rho)
{
    size_t k;
    size_t j;
    if (width == WSUPER) {
        squared_residuals(n, stride, curves + g0, data, cw, rho);
        return;
    }
    for (k = 0; k < n; k++) {
        for (j = 0; j < WSUPER; j++) {
            double r = (j < width ? curves[k * stride + g0 + j] : 0.0) -
                       data[k];
            rho[k * WSUPER + j] = (cw != NULL ? cw[k] : 1.0) * (r * r);
        }
    }
}

/* The WTILE weight rows of tile b (the last repeated past n_w; NULL rows
 * are ones); returns how many are real. */
static size_t tile_rows(size_t n_w, const double *const *w, size_t b,
                        const double *ones, const double **wt)
{
    size_t left = n_w - b < WTILE ? n_w - b : WTILE;
    size_t q;
    for (q = 0; q < WTILE; q++) {
        const double *row = w[b + (q < left ? q : left - 1)];
        wt[q] = row != NULL ? row : ones;
    }
    return left;
}

/* What a pass over the curves works with. */
typedef struct {
    size_t n, cols, stride;
    const double *curves;
    const unsigned char *ok; /* NULL: every column a candidate */
    size_t points;           /* columns scored: < points */
    const double *data;
    const double *cw;
    int prune;     /* tiles may stop at their rows' bounds */
    double *rho;   /* n x WSUPER */
    double *ones;  /* n */
} wpass;

static int wpass_init(wpass *p, size_t n, size_t cols, size_t stride,
                      const double *curves, const double *data,
                      const double *cw)
{
    size_t k;
    memset(p, 0, sizeof *p);
    p->n = n;
    p->cols = cols;
    p->stride = stride;
    p->curves = curves;
    p->points = cols;
    p->data = data;
    p->cw = cw;
    p->rho = aligned_alloc(64, n * WSUPER * sizeof *p->rho);
    p->ones = malloc(n * sizeof *p->ones);
    if (p->rho == NULL || p->ones == NULL) {
        free(p->rho);
        free(p->ones);
        return 0;
    }
    for (k = 0; k < n; k++) {
        p->ones[k] = 1.0;
    }
    return 1;
}

static void wpass_free(wpass *p)
{
    free(p->rho);
    free(p->ones);
}

/* What a pass does with the finished sums of a tile: tmp[q * WLANES + j]
 * of weight vector b + q (q < left) at column g0 + j (cand[j] != 0). */
typedef void (*wsink)(void *ctx, size_t b, size_t left, size_t g0,
                      const int *cand, const double *tmp);

/* The one pass over the curves for n_w weight vectors: each super-block's
 * squared residuals once, every tile of weight vectors against them.
 * bound (pruning passes): the rows' best values so far. */
static void weights_pass(const wpass *p, size_t n_w, const double *const *w,
                         const double *best, wsink sink, void *ctx)
{
    double tmp[WTILE * WLANES];
    double bound[WTILE];
    int cand[WLANES];
    size_t g0;
    for (g0 = 0; g0 < p->points; g0 += WSUPER) {
        size_t width = p->cols - g0 < WSUPER ? p->cols - g0 : WSUPER;
        size_t b;
        super_rho(p->n, p->stride, p->curves, p->data, p->cw, g0, width,
                  p->rho);
        for (b = 0; b < n_w; b += WTILE) {
            const double *wt[WTILE];
            size_t left = tile_rows(n_w, w, b, p->ones, wt);
            size_t j0;
            size_t q;
            for (j0 = 0; j0 < width && g0 + j0 < p->points; j0 += WLANES) {
                size_t j;
                int any = 0;
                for (j = 0; j < WLANES; j++) {
                    size_t g = g0 + j0 + j;
                    cand[j] = g < p->points && (p->ok == NULL || p->ok[g]);
                    any |= cand[j];
                }
                if (!any) {
                    continue; /* no defined point here */
                }
                for (q = 0; q < WTILE; q++) {
                    bound[q] = p->prune ? best[b + (q < left ? q : left - 1)]
                                        : NAN;
                }
                if (bf__weights_tile(0, p->n, p->rho + j0, wt, bound, cand,
                                     tmp)) {
                    sink(ctx, b, left, g0 + j0, cand, tmp);
                }
            }
        }
    }
}

/* ==== all sums ============================================================ */

typedef struct {
    double *lse;
    size_t cols;
} store_ctx;

static void store_sums(void *ctx, size_t b, size_t left, size_t g0,
                       const int *cand, const double *tmp)
{
    const store_ctx *c = ctx;
    size_t q;
    size_t j;
    for (q = 0; q < left; q++) {
        for (j = 0; j < WLANES; j++) {
            if (cand[j]) {
                c->lse[((b + q) * c->cols) + g0 + j] = tmp[(q * WLANES) + j];
            }
        }
    }
}

void bf__score_weights(size_t n, size_t cols, size_t stride,
                       const double *curves, const double *data,
                       const double *cw, size_t n_w, const double *const *w,
                       double *lse)
{
    store_ctx c = {lse, cols};
    wpass p;
    size_t g;
    if (!wpass_init(&p, n, cols, stride, curves, data, cw)) {
        for (g = 0; g < n_w * cols; g++) {
            lse[g] = NAN; /* never a grid optimum */
        }
        return;
    }
    weights_pass(&p, n_w, w, NULL, store_sums, &c);
    wpass_free(&p);
}

/* ==== grid optima, pruned ================================================= */

/* 1 when every weight and factor is >= 0 (bootstrap counts, fold masks,
 * cos theta_i): the sums then only grow and tiles may stop early. */
static int nonnegative(size_t n, const double *cw, size_t n_w,
                       const double *const *w)
{
    size_t b;
    size_t k;
    for (k = 0; cw != NULL && k < n; k++) {
        if (!(cw[k] >= 0.0)) {
            return 0;
        }
    }
    for (b = 0; b < n_w; b++) {
        for (k = 0; w[b] != NULL && k < n; k++) {
            if (!(w[b][k] >= 0.0)) {
                return 0;
            }
        }
    }
    return 1;
}

/* Row b's sum at column g is v: it becomes the row's optimum when it is
 * lower than the best so far, or equal to it at an earlier column -- the
 * smallest value over the candidates and its first column, whatever order
 * the columns come in (bf__argmin's choice: strict < in index order; NaN
 * and +inf never win). */
static void offer(double v, size_t g, double *best_lse, size_t *best)
{
    if (v < INFINITY && (v < *best_lse || (v == *best_lse && g < *best))) {
        *best_lse = v;
        *best = g;
    }
}

typedef struct {
    double *best_lse;
    size_t *best;
} argmin_ctx;

static void keep_best(void *ctx, size_t b, size_t left, size_t g0,
                      const int *cand, const double *tmp)
{
    const argmin_ctx *c = ctx;
    size_t q;
    size_t j;
    for (q = 0; q < left; q++) {
        for (j = 0; j < WLANES; j++) {
            if (cand[j]) {
                offer(tmp[(q * WLANES) + j], g0 + j, &c->best_lse[b + q],
                      &c->best[b + q]);
            }
        }
    }
}

/* Row wb's exact sum at column g (the tiles' terms in their order). */
static double column_sum(const wpass *p, const double *wb, size_t g)
{
    double s = 0.0;
    size_t k;
    for (k = 0; k < p->n; k++) {
        double r = p->curves[k * p->stride + g] - p->data[k];
        double rho = (p->cw != NULL ? p->cw[k] : 1.0) * (r * r);
        s = fma(wb != NULL ? wb[k] : 1.0, rho, s);
    }
    return s;
}

int bf__weights_argmin(size_t n, size_t cols, size_t stride,
                       const double *curves, const unsigned char *ok,
                       size_t points, const double *data, const double *cw,
                       size_t n_w, const double *const *w, double *best_lse,
                       size_t *best)
{
    argmin_ctx c = {best_lse, best};
    wpass p;
    size_t b;
    for (b = 0; b < n_w; b++) {
        best_lse[b] = INFINITY;
        best[b] = SIZE_MAX;
    }
    if (!wpass_init(&p, n, cols, stride, curves, data, cw)) {
        return BF_ENOMEM;
    }
    p.ok = ok;
    p.points = points;
    p.prune = nonnegative(n, cw, n_w, w);
    if (p.prune && n_w > 1) {
        /* a start for every row: its sum at the optimum under weights 1
         * (the full data's, near every replicate's), so that tiles stop
         * early from the first column on */
        const double *one[1] = {NULL};
        double s_lse = INFINITY;
        size_t s_best = SIZE_MAX;
        argmin_ctx sc = {&s_lse, &s_best};
        weights_pass(&p, 1, one, &s_lse, keep_best, &sc);
        for (b = 0; s_best != SIZE_MAX && b < n_w; b++) {
            offer(column_sum(&p, w[b], s_best), s_best, &best_lse[b],
                  &best[b]);
        }
    }
    weights_pass(&p, n_w, w, best_lse, keep_best, &c);
    wpass_free(&p);
    return BF_OK;
}

/* ==== cross-validation folds ============================================== */

/* Lanes of the folds' blocks. */
#define FLANES 4

/* The full-data LSE and every fold's training LSE of one 16-lane block:
 * full[j] = sum_k rho_kj in index order (the weights kernel's sum for
 * weights 1, the same bits), held[f][j] = sum over the configurations of
 * fold f, so that fold f's training sum is full - held[f]. */
BF__CLONES
static void folds_block(size_t n, size_t stride, const double *restrict c,
                        const double *restrict d, const double *restrict cw,
                        const size_t *restrict fold, size_t folds,
                        double *restrict full, double *restrict held)
{
    double acc[FLANES];
    size_t f;
    size_t j;
    size_t k;
    for (j = 0; j < FLANES; j++) {
        acc[j] = 0.0;
    }
    for (f = 0; f < (folds > 0 ? folds : 1) * FLANES; f++) {
        held[f] = 0.0;
    }
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * stride);
        /* without folds the sums go to a scratch row nobody reads */
        double *restrict hk = held + ((folds > 0 ? fold[k] : 0) * FLANES);
        double dk = d[k];
        double fk = cw != NULL ? cw[k] : 1.0;
#pragma omp simd
        for (j = 0; j < FLANES; j++) {
            double r = ck[j] - dk;
            double rho = fk * (r * r);
            acc[j] = acc[j] + rho;
            hk[j] = hk[j] + rho;
        }
    }
    for (j = 0; j < FLANES; j++) {
        full[j] = acc[j];
    }
}

void bf__score_folds(size_t n, size_t cols, size_t stride,
                     const double *curves, const double *data,
                     const double *cw, const size_t *fold, size_t folds,
                     double *lse)
{
    double *held = malloc((folds + 1) * FLANES * sizeof *held);
    size_t g0;
    size_t f;
    size_t j;
    if (held == NULL) {
        for (g0 = 0; g0 < (folds + 1) * cols; g0++) {
            lse[g0] = NAN; /* never a grid optimum */
        }
        return;
    }
    for (g0 = 0; g0 < cols; g0 += FLANES) {
        folds_block(n, stride, curves + g0, data, cw, fold, folds,
                    lse + g0, held);
        for (f = 0; f < folds; f++) { /* training: all but the fold */
            for (j = 0; j < FLANES; j++) {
                lse[(f + 1) * cols + g0 + j] =
                    lse[g0 + j] - held[f * FLANES + j];
            }
        }
    }
    free(held);
}

/* Running grid optima of many data vectors and their folds: for each
 * 16-lane block of stored curves (in L1) every data vector's full and
 * training sums (folds_block), the smallest defined value of each and its
 * first index (strict <, in index order: bf__argmin's result). */
int bf__folds_argmin(size_t n, size_t cols, size_t stride,
                     const double *curves, const unsigned char *ok,
                     size_t points, size_t n_data, const double *const *data,
                     const double *cw, const size_t *fold, size_t folds,
                     double *best_lse, size_t *best)
{
    double *held = malloc((folds + 1) * FLANES * sizeof *held);
    double full[FLANES];
    size_t per = folds + 1;
    size_t g0;
    size_t q;
    size_t f;
    size_t j;
    (void)cols; /* >= points rounded up to FLANES: blocks read padding */
    for (q = 0; q < n_data * per; q++) {
        best_lse[q] = INFINITY;
        best[q] = SIZE_MAX;
    }
    if (held == NULL) {
        return BF_ENOMEM; /* no optimum */
    }
    for (g0 = 0; g0 < points; g0 += FLANES) {
        size_t width = points - g0 < FLANES ? points - g0 : FLANES;
        for (q = 0; q < n_data; q++) {
            double *bl = best_lse + q * per;
            size_t *bi = best + q * per;
            folds_block(n, stride, curves + g0, data[q], cw, fold, folds,
                        full, held);
            for (j = 0; j < width; j++) {
                if (!ok[g0 + j]) {
                    continue;
                }
                if (full[j] < bl[0]) {
                    bl[0] = full[j];
                    bi[0] = g0 + j;
                }
                for (f = 0; f < folds; f++) {
                    double v = full[j] - held[f * FLANES + j];
                    if (v < bl[1 + f]) {
                        bl[1 + f] = v;
                        bi[1 + f] = g0 + j;
                    }
                }
            }
        }
    }
    free(held);
    return BF_OK;
}
