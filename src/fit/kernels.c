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
 *   - exp is the kernels' own (exp_nonpos below, within 1 ulp of glibc's),
 *     so that it vectorises inline and gives the same bits on every ISA.
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

#include "fit/engine.h"



/* Grid points per curve block: one AVX-512 register of doubles (two of
 * AVX2's); a block of curves (8 x K doubles: 12.7 KB at K = 198) and the
 * next one fit a 32 KB L1 together. The bits do not depend on it: every
 * grid point's sums are formed alone, in index order. */
#define CURVE_LANES 8
/* Samples scored together (each loaded curve value is used this often). */
#define TILE_SAMPLES 4

/* ==== exp of a non-positive argument, vectorisable ======================= */

/* ln 2 as the double nearest it and the rest (the reduction x - k ln 2 is
 * taken with fma, which forms k ln2_hi exactly); 1/ln 2; 1.5 * 2^52, which
 * rounds a double below 2^51 in magnitude to an integer in its low
 * bits. */
#define EXP_LN2_HI 0x1.62e42fefa39efp-1
#define EXP_LN2_LO 0x1.abc9e3b39803fp-56
#define EXP_INV_LN2 0x1.71547652b82fep0
#define EXP_SHIFTER 0x1.8p52
/* Below this argument e^x < 2^-1021 (near DBL_MIN): the result is 0. */
#define EXP_MIN_ARG (-708.0)

/* e^x for x <= 0, the only arguments of the kernels (x = b/m^2 with b <= 0,
 * x = n_d ln(cos ti cos ts) with the base <= 1). Straight-line code the
 * compiler vectorises: x = k ln 2 + r with |r| <= ln(2)/2 (Cody-Waite,
 * fma), e^r by its Taylor polynomial of degree 13 (truncation below
 * 2^-57), times 2^k built in the exponent bits. Within 1 ulp of glibc's
 * exp on [-708, 0] (tests/fit/test_grid.c); 0 below -708 (where glibc
 * gives a subnormal or 0), for -inf and for NaN. The same bits on every
 * ISA: every operation is correctly rounded (no contraction, explicit
 * fma). */
static inline double exp_nonpos(double x)
{
    double xc = (x >= EXP_MIN_ARG) ? x : EXP_MIN_ARG;
    double t = fma(xc, EXP_INV_LN2, EXP_SHIFTER); /* k in the low bits */
    double kd = t - EXP_SHIFTER;                    /* k = round(x/ln 2) */
    double r = fma(-kd, EXP_LN2_HI, xc);
    double p;
    double scale;
    uint64_t bits;
    r = fma(-kd, EXP_LN2_LO, r);
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
    return (x >= EXP_MIN_ARG) ? p * scale : 0.0;
}

double bf__exp_nonpos(double x)
{
    return exp_nonpos(x);
}

/* ==== geometry terms, once per configuration set ======================== */

/* The BK family's terms (src/fit/engine.h, BF__BK_NTERMS rows of n, then
 * one extra: 1 when some slope gives a curve). Every factor that does not
 * depend on the configuration (1/m^2 of (P1), 2m of (P2)) is dropped: it
 * cancels in the normalisation (SPEC §2). */
enum {
    T_SI = 0, T_CI, T_SS, T_CS, /* sines and cosines, for FC's F^2 */
    T_VZ2,                      /* vz^2 (SPEC §3) */
    T_VXY2,                     /* vxy^2 */
    T_AVZ,                      /* |vz| */
    T_A,                        /* G: F^2/vz^2   E: F^2 |vz| (not FC) */
    T_B,                        /* G: -vxy^2/(4 vz^2)   E: vz^2 */
    T_C,                        /* E: vxy^2 */
    T_F2                        /* F^2 of BK, VH (not FC) */
};

/* The slope-independent parts of (P1)/(P2) from F^2 = f2 at one
 * configuration, exactly as the grid has always formed them. Where vz = 0
 * (theta_i = theta_s = pi/2) the model's limit is 0 (SPEC §3.3): a = 0 and
 * a harmless denominator. Returns 0 when a term is not finite. */
static inline int bk_abc(int corr, double f2, double vz2, double vxy2,
                         double abs_vz, double *a, double *b, double *c)
{
    if (vz2 == 0.0) {
        *a = 0.0; /* the limit 0, SPEC §3.3 */
        *b = 0.0;
        *c = 1.0;
    } else if (corr == BF__BK_CORR_GAUSS) {
        /* (P1): L m^2 = F^2/vz^2 exp(-vxy^2/(4 vz^2) / m^2) */
        *a = f2 / vz2;
        *b = -vxy2 / (4.0 * vz2);
        *c = 0.0;
    } else {
        /* (P2) as in bk.c: L / (2m) = F^2 |vz| / (m^2 vz^2 + vxy^2)^1.5 */
        *a = f2 * abs_vz;
        *b = vz2;
        *c = vxy2;
    }
    return isfinite(*a) && isfinite(*b);
}

void bf__bk_kterms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t n = cs->n;
    size_t k;
    int ok = 1;
    for (k = 0; k < n; k++) {
        bf__bk_terms_t bt = {0.0, 0.0, 0.0, 0.0};
        const bf__trig_t *tr = &cs->trig[k];
        double a;
        double b;
        double c;
        /* FC's F^2 depends on n: formed per n in the workspace */
        int fc = kr->factor == BF__BK_FACTOR_FC;
        if (bf__bk_terms_trig(fc ? BF__BK_FACTOR_VH : kr->factor, 1.0, tr,
                              &bt) != BF_OK) {
            ok = 0; /* BK at theta_i = pi/2: no slope works (SPEC §3.3) */
        }
        terms[T_SI * n + k] = tr->si;
        terms[T_CI * n + k] = tr->ci;
        terms[T_SS * n + k] = tr->ss;
        terms[T_CS * n + k] = tr->cs;
        terms[T_VZ2 * n + k] = bt.vz2;
        terms[T_VXY2 * n + k] = bt.vxy2;
        terms[T_AVZ * n + k] = bt.abs_vz;
        terms[T_F2 * n + k] = bt.f2;
        ok &= bk_abc(kr->corr, bt.f2, bt.vz2, bt.vxy2, bt.abs_vz, &a, &b, &c);
        terms[T_A * n + k] = a;
        terms[T_B * n + k] = b;
        terms[T_C * n + k] = c;
    }
    terms[BF__BK_NTERMS * n] = ok;
}

/* FC's workspace: the a-terms of the last FC_SLOTS indices n (the grid of
 * n is 27 values: a fit, a grid of n or a profile over it finds them
 * here after their first use), replaced round-robin. A slot's content is
 * a function of its n alone, so hits and misses give the same bits. */
#define FC_SLOTS 32
typedef struct {
    double n[FC_SLOTS];
    int used[FC_SLOTS]; /* 1 once the slot holds n[slot]'s terms */
    int ok[FC_SLOTS];   /* every a finite */
    size_t next;        /* the slot to replace */
    double a[];         /* FC_SLOTS x n values */
} fc_work;

size_t bf__bk_kwork(const bf_kernel *kr, size_t n)
{
    return kr->factor == BF__BK_FACTOR_FC
               ? sizeof(fc_work) + FC_SLOTS * n * sizeof(double)
               : 0;
}

/* bk_abc's a-terms in place of f2 = F_FC^2 (as[k]), vectorised: the same
 * operations per configuration, so the same bits. Its b-terms depend on
 * the geometry alone, checked once in the terms (bf__bk_kterms's flag, which
 * every use of these terms is combined with). Returns 1 when every a is
 * finite (a - a == 0). */
BF__CLONES
static int fc_a_terms(size_t n, int gauss, const double *restrict vz2,
                      const double *restrict abs_vz, double *restrict as)
{
    int ok = 1;
    size_t k;
#pragma omp simd reduction(& : ok)
    for (k = 0; k < n; k++) {
        double f2 = as[k];
        double a = gauss ? f2 / vz2[k] : f2 * abs_vz[k]; /* (P1), (P2) */
        a = vz2[k] == 0.0 ? 0.0 : a; /* the limit 0, SPEC §3.3 */
        as[k] = a;
        ok &= (a - a) == 0.0;
    }
    return ok;
}

/* The a-terms of FC at index n_index (F_FC^2 of (P6), SPEC §4.2), as
 * bf__bk_terms_trig and the grid form them, from w's slots or into one;
 * *a points at them. Returns 0 when a term is not finite. */
static int fc_terms(const bf__prep *pm, double n_index, fc_work *w,
                    const double **a)
{
    size_t n = pm->n;
    const double *t = pm->terms;
    size_t slot;
    double *as;
    for (slot = 0; slot < FC_SLOTS; slot++) {
        if (w->used[slot] && w->n[slot] == n_index) {
            *a = w->a + slot * n;
            return w->ok[slot];
        }
    }
    slot = w->next;
    w->next = (w->next + 1) % FC_SLOTS;
    as = w->a + slot * n;
    bf__fc2_values(n, t + T_SI * n, t + T_CI * n, t + T_SS * n, t + T_CS * n,
                   n_index, as);
    w->ok[slot] = fc_a_terms(n, pm->kr->corr == BF__BK_CORR_GAUSS,
                             t + T_VZ2 * n, t + T_AVZ * n, as);
    w->used[slot] = 1;
    w->n[slot] = n_index;
    *a = as;
    return w->ok[slot];
}

/* The BK family at one slope m (and FC's n): the grid kernels' operations
 * for one lane, vectorised across the configurations instead, so a value
 * has the bits of the same grid value's (before normalisation). */
BF__CLONES
int bf__bk_kvalues(const bf__prep *pm, const double *param, void *work,
                   double *out)
{
    size_t n = pm->n;
    const double *t = pm->terms;
    const double *fa = t + T_A * n;
    const double *restrict a;
    const double *restrict b = t + T_B * n;
    const double *restrict c = t + T_C * n;
    double m = param[0];
    size_t k;
    int ok = t[BF__BK_NTERMS * n] != 0.0;
    if (pm->kr->factor == BF__BK_FACTOR_FC) {
        ok &= fc_terms(pm, param[1], work, &fa);
    }
    a = fa;
    if (!ok) {
        for (k = 0; k < n; k++) {
            out[k] = NAN; /* BK at theta_i = pi/2 (SPEC §3.3) */
        }
        return BF_EDOM;
    }
    if (pm->kr->corr == BF__BK_CORR_GAUSS) {
        double inv_m2 = 1.0 / (m * m);
#pragma omp simd
        for (k = 0; k < n; k++) {
            out[k] = a[k] * exp_nonpos(b[k] * inv_m2); /* (P1), SPEC §3.1 */
        }
    } else {
        double m2 = m * m;
#pragma omp simd
        for (k = 0; k < n; k++) {
            double d = fma(m2, b[k], c[k]); /* (P2), SPEC §3.2 */
            out[k] = a[k] / (d * sqrt(d));
        }
    }
    return BF_OK;
}

/* LFTG (P7), SPEC §6, at one n_d: (cos ti cos ts)^n_d = exp(n_d ln(cos ti
 * cos ts)) with the kernels' exp; the constant (n_d + 2)/(2 pi) cancels
 * (SPEC §2). At grazing the base is 0: the value 0 for n_d > 0, 1 for
 * n_d = 0 (pow(0, 0) = 1, as eval_lftg). */
BF__CLONES
int bf__lftg_kvalues(const bf__prep *pm, const double *param, void *work,
                     double *out)
{
    const double *restrict lnb = pm->terms;
    double n_d = param[0];
    size_t k;
    (void)work;
#pragma omp simd
    for (k = 0; k < pm->n; k++) {
        double x = lnb[k];
        double e = exp_nonpos(n_d * x); /* (P7), SPEC §6 */
        out[k] = (n_d == 0.0) ? 1.0 : e;
    }
    return BF_OK;
}

BF__CLONES
void bf__fc2_values(size_t n, const double *si, const double *ci,
                    const double *ss, const double *cs, double n_index,
                    double *out)
{
    size_t k;
#pragma omp simd
    for (k = 0; k < n; k++) {
        out[k] = bf__fc2_inline(si[k], ci[k], ss[k], cs[k], n_index);
    }
}

/* The block kernels' terms (structure of arrays, 64-byte aligned), copied
 * from a prepared model's terms for one grid. */
typedef struct {
    double *a;   /* G: F^2/vz^2   E: F^2 |vz|   LFTG: ln(cos ti cos ts) */
    double *b;   /* G: -vxy^2/(4 vz^2)   E: vz^2   LFTG: scratch */
    double *c;   /* E: vxy^2 */
    double *p;   /* LFTG: n x CURVE_LANES, exp(j step ln(cos ti cos ts)) */
    double *mem;
} terms_t;

static int terms_alloc(terms_t *t, size_t n)
{
    size_t len = ((3 + CURVE_LANES) * n * sizeof(double) + 63) / 64 * 64;
    t->mem = aligned_alloc(64, len);
    if (t->mem == NULL) {
        return BF_ENOMEM;
    }
    t->a = t->mem;
    t->b = t->a + n;
    t->c = t->b + n;
    t->p = t->c + n;
    return BF_OK;
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

/* Gaussian correlation (P1), SPEC §3.1, for CURVE_LANES slopes m[]:
 * l = a exp(b / m^2), one multiply, one exp and one multiply per value. */
BF__CLONES
static void block_gauss(size_t n, const terms_t *t, const double *m,
                        size_t stride, double *restrict c, double *mx_out,
                        double *nf_out)
{
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    double inv_m2[CURVE_LANES];
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
            double v = a * exp_nonpos(b * inv_m2[j]); /* (P1), SPEC §3.1 */
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* Exponential correlation (P2), SPEC §3.2, in bk.c's form:
 * l = a / (d sqrt d), d = m^2 vz^2 + vxy^2 (one fma, sqrt, multiply,
 * division per value). */
BF__CLONES
static void block_exp(size_t n, const terms_t *t, const double *m,
                      size_t stride, double *restrict c, double *mx_out,
                      double *nf_out)
{
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    double m2[CURVE_LANES];
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
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* LFTG (P7), SPEC §6: l = (cos ti cos ts)^n_d = exp(n_d L), L = ln(cos ti
 * cos ts) taken once per configuration (0 at grazing gives exp(-inf) = 0,
 * the value of pow for n_d > 0). The lanes' exponents n_d = n_0 + j step
 * are an arithmetic progression, so exp(n_d L) = exp(n_0 L) exp(j step L):
 * one exp per configuration and block (e0, vectorised across
 * configurations) times a factor computed once per grid (t->p), instead of
 * one exp per value. The rounding of n_d and of the two factors moves a
 * normalised value v by at most a few v |n_d L| eps <= a few eps / e. */
BF__CLONES
static void block_lftg(size_t n, const terms_t *t, const double *n_d,
                       size_t stride, double *restrict c, double *mx_out,
                       double *nf_out)
{
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    double *restrict e0 = t->b; /* scratch */
    const double *restrict ln_base = t->a;
    double n0 = n_d[0];
    size_t j;
    size_t k;
    for (j = 0; j < CURVE_LANES; j++) {
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
#pragma omp simd
    for (k = 0; k < n; k++) {
        e0[k] = exp_nonpos(n0 * ln_base[k]); /* (P7), SPEC §6 */
    }
    for (k = 0; k < n; k++) {
        double e = e0[k];
        const double *restrict pk = t->p + (k * CURVE_LANES);
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            double v = e * pk[j];
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* The factors exp(j step L_k) of block_lftg for j < CURVE_LANES. */
BF__CLONES
static void lftg_factors(size_t n, double step, const double *ln_base,
                         double *restrict p)
{
    size_t j;
    size_t k;
    for (k = 0; k < n; k++) {
        double l = ln_base[k];
#pragma omp simd simdlen(CURVE_LANES)
        for (j = 0; j < CURVE_LANES; j++) {
            /* j = 0: exp(0 L) = 1; at grazing 0 (-inf) = NaN gives 0,
             * harmless: e0 is 0 there */
            p[(k * CURVE_LANES) + j] = exp_nonpos(((double)j * step) * l);
        }
    }
}

/* A curve generator: the block kernel and terms of one model on one grid
 * (BK family with the slope m free, or LFTG with n_d free on a grid of
 * positive values: a single free parameter, the paper's protocol). The
 * terms come from the model's prepared terms (bf__bk_kterms; LFTG's
 * ln(cos ti cos ts)); FC's a-terms are formed here for the grid's n. */
typedef struct {
    int is_lftg;
    int corr;
    int defined; /* 0: no grid point gives a curve (domain, see bk_abc) */
    double lo;   /* the grid: lo + step i, i < points */
    double step;
    size_t points;
    terms_t t;
} gen_t;

/* Sets up g for pm on lay; returns 1, 0 when no block kernel applies, or
 * -BF_ENOMEM. */
static int gen_init(gen_t *g, const bf__prep *pm, const bf__grid_layout_t *lay)
{
    const bf_kernel *kr = pm->kr;
    size_t n = pm->n;
    size_t k;

    memset(g, 0, sizeof *g);
    g->is_lftg = kr->block == BF__BLOCK_LFTG;
    g->corr = kr->corr;
    g->defined = 1;
    if (kr->block == BF__BLOCK_NONE || lay->n_free != 1 ||
        lay->free[0] != 0 || (g->is_lftg && !(lay->lo[0] > 0.0))) {
        return 0;
    }
    g->lo = lay->lo[0];
    g->step = lay->step[0];
    g->points = lay->points;
    if (terms_alloc(&g->t, n) != BF_OK) {
        return -BF_ENOMEM;
    }
    if (g->is_lftg) {
        /* ln(cos ti cos ts), -inf at grazing (the LFTG kernel's terms) */
        memcpy(g->t.a, pm->terms, n * sizeof *g->t.a);
        lftg_factors(n, g->step, g->t.a, g->t.p);
    } else {
        const double *tm = pm->terms;
        memcpy(g->t.b, tm + T_B * n, n * sizeof *g->t.b);
        memcpy(g->t.c, tm + T_C * n, n * sizeof *g->t.c);
        g->defined = tm[BF__BK_NTERMS * n] != 0.0;
        if (kr->factor != BF__BK_FACTOR_FC) {
            memcpy(g->t.a, tm + T_A * n, n * sizeof *g->t.a);
        } else {
            /* FC's refractive index is parameter 1, fixed here (P6) */
            bf__fc2_values(n, tm + T_SI * n, tm + T_CI * n, tm + T_SS * n,
                           tm + T_CS * n, lay->base[1], g->t.a);
            for (k = 0; k < n; k++) {
                double b;
                double c;
                g->defined &= bk_abc(g->corr, g->t.a[k], tm[T_VZ2 * n + k],
                                     tm[T_VXY2 * n + k], tm[T_AVZ * n + k],
                                     &g->t.a[k], &b, &c);
            }
        }
    }
    return 1;
}

/* The normalised curves of grid points g0 .. g0 + CURVE_LANES - 1 into
 * c[k * stride + j] and their flags ok[j]. Padding lanes (grid indices >=
 * points) repeat the last grid point and are marked not ok. */
/* The grid values of the block at g0 (padding repeats the last). */
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
        if (g0 + j >= g->points || !g->defined) {
            ok[j] = 0;
        }
    }
}

/* The raw values (before the normalisation) of the block at g0 into c,
 * with the reciprocals r[j] of the lanes' maxima and their flags ok[j]:
 * the normalised curve is c[k * stride + j] * r[j] (the streaming scorer
 * forms it as it reads c). */
static void gen_block_raw(const gen_t *g, size_t n, size_t g0, size_t stride,
                          double *c, double *r, unsigned char *ok)
{
    double x[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    gen_x(g, g0, x);
    if (g->is_lftg) {
        block_lftg(n, &g->t, x, stride, c, mx, nf);
    } else if (g->corr == BF__BK_CORR_GAUSS) {
        block_gauss(n, &g->t, x, stride, c, mx, nf);
    } else {
        block_exp(n, &g->t, x, stride, c, mx, nf);
    }
    block_recip(mx, nf, r, ok);
    gen_ok(g, g0, ok);
}

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

/* Fills the transposed normalised curves of every grid point with a
 * vectorised kernel when one exists for type (see gen_t). Returns 1 when
 * done, 0 when type has no kernel (the caller uses the plain evaluation),
 * or -BF_ENOMEM. */
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
    free(g.t.mem);
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

/* Samples scored together against one block of streamed curves: their
 * STREAM_SAMPLES x CURVE_LANES sums take 8 of AVX-512's 32 registers; with
 * AVX2's (or the baseline's) 16, STREAM_SAMPLES_NARROW leave room for the
 * curve values (stream_samples; measured on Zen 3: 4 is fastest). The
 * sums, and so the bits, do not depend on how many samples share a pass. */
#define STREAM_SAMPLES 8
#define STREAM_SAMPLES_NARROW 4

/* The raw curves of the next block of an E model (P2), computed while the
 * current block is scored (interleaved): the divider's work (a division
 * and a square root per value) then overlaps the scoring's FMA work.
 * Exactly block_exp's operations, row by row. */
typedef struct {
    const terms_t *t;
    double m2[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    double *out;  /* n x CURVE_LANES, contiguous */
    size_t first; /* rows first, first + every, ... are this call's */
    size_t every;
} erows_t;

/* LSE of the CURVE_LANES grid points of one block (raw values c[k *
 * CURVE_LANES + j], contiguous, normalised as they are read: c * rs[j],
 * gen_block's product) against ns samples d[q]: lse[q * CURVE_LANES + j],
 * each the sum of bf__sum_sq_diff in index order with one fma per term,
 * as score_tile forms it. When e is not NULL, also the rows of e (see
 * erows_t). Scaling here instead of in a pass of its own saves a read and
 * a write of the block (which leaves the caches at large K). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void score_stream(size_t ns, size_t n,
                                const double *restrict c,
                                const double *restrict rs,
                                const double *const *d,
                                double *restrict lse, erows_t *restrict e)
{
    double a[STREAM_SAMPLES][CURVE_LANES];
    double m2[CURVE_LANES];
    double mx[CURVE_LANES];
    double nf[CURVE_LANES];
    size_t next_e = e != NULL ? e->first : SIZE_MAX;
    size_t j;
    size_t k;
    size_t q;
    for (q = 0; q < ns; q++) {
        for (j = 0; j < CURVE_LANES; j++) {
            a[q][j] = 0.0;
        }
    }
    if (e != NULL) {
        memcpy(m2, e->m2, sizeof m2);
        memcpy(mx, e->mx, sizeof mx);
        memcpy(nf, e->nf, sizeof nf);
    } else {
        memset(m2, 0, sizeof m2);
        memset(mx, 0, sizeof mx);
        memset(nf, 0, sizeof nf);
    }
    for (k = 0; k < n; k++) {
        const double *restrict ck = c + (k * CURVE_LANES);
        double x[STREAM_SAMPLES];
        for (q = 0; q < ns; q++) {
            x[q] = d[q][k];
        }
        for (q = 0; q < ns; q++) {
#pragma omp simd simdlen(CURVE_LANES)
            for (j = 0; j < CURVE_LANES; j++) {
                /* the normalised value, SPEC §2 (gen_block's) */
                double r = (ck[j] * rs[j]) - x[q]; /* SPEC §7.3 */
                a[q][j] = fma(r, r, a[q][j]);
            }
        }
        if (k == next_e) { /* block_exp's row k, SPEC §3.2 */
            double ea = e->t->a[k];
            double vz2 = e->t->b[k];
            double vxy2 = e->t->c[k];
            double *restrict ok_ = e->out + (k * CURVE_LANES);
#pragma omp simd simdlen(CURVE_LANES)
            for (j = 0; j < CURVE_LANES; j++) {
                double dd = fma(m2[j], vz2, vxy2); /* (P2) */
                double v = ea / (dd * sqrt(dd));
                ok_[j] = v;
                nf[j] += v - v;
                mx[j] = (v > mx[j]) ? v : mx[j];
            }
            next_e += e->every;
        }
    }
    for (q = 0; q < ns; q++) {
        for (j = 0; j < CURVE_LANES; j++) {
            lse[(q * CURVE_LANES) + j] = a[q][j];
        }
    }
    if (e != NULL) {
        memcpy(e->mx, mx, sizeof mx);
        memcpy(e->nf, nf, sizeof nf);
    }
}

/* score_stream with the sample count a constant (its sums in registers). */
BF__CLONES
static void score_stream_wide(size_t n, const double *restrict c,
                              const double *restrict rs,
                              const double *const *d, double *restrict lse,
                              erows_t *restrict e)
{
    score_stream(STREAM_SAMPLES, n, c, rs, d, lse, e);
}

BF__CLONES
static void score_stream_narrow(size_t n, const double *restrict c,
                                const double *restrict rs,
                                const double *const *d,
                                double *restrict lse, erows_t *restrict e)
{
    score_stream(STREAM_SAMPLES_NARROW, n, c, rs, d, lse, e);
}

/* Samples per pass on this processor: STREAM_SAMPLES with AVX-512's 32
 * vector registers, STREAM_SAMPLES_NARROW otherwise. */
static size_t stream_samples(void)
{
#if defined(__GNUC__) && defined(__x86_64__)
    return __builtin_cpu_supports("avx512f") ? STREAM_SAMPLES
                                             : STREAM_SAMPLES_NARROW;
#else
    return STREAM_SAMPLES;
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
    double lse[STREAM_SAMPLES * CURVE_LANES];
    double rs[CURVE_LANES]; /* the current block's reciprocal maxima */
    unsigned char ok[CURVE_LANES];
    double pen[CURVE_LANES];
    erows_t e;
    double *c;
    double *nxt;
    gen_t g;
    bf__prep pm;
    size_t n = cs->n;
    size_t ns = stream_samples();
    size_t n_tiles = (n_samples + ns - 1) / ns;
    size_t g0;
    size_t s;
    int pipe; /* E models: the next block's curves during the scoring */
    int rc;

    if (type->kernel == NULL || type->kernel->block == BF__BLOCK_NONE) {
        return 0; /* no block kernel: nothing to prepare */
    }
    rc = bf__prep_init(&pm, type, cs);
    if (rc != BF_OK) {
        bf__prep_free(&pm);
        return -rc;
    }
    rc = gen_init(&g, &pm, lay);
    bf__prep_free(&pm); /* gen copied what it needs */
    if (rc <= 0) {
        return rc;
    }
    pipe = !g.is_lftg && g.corr == BF__BK_CORR_EXP;
    c = aligned_alloc(64, 2 * n * CURVE_LANES * sizeof *c); /* 256 n B */
    if (c == NULL) {
        free(g.t.mem);
        return -BF_ENOMEM;
    }
    nxt = c + (n * CURVE_LANES);
    for (s = 0; s < n_samples; s++) {
        best_lse[s] = INFINITY;
        best[s] = SIZE_MAX;
    }
    gen_block_raw(&g, n, 0, CURVE_LANES, c, rs, ok);
    for (g0 = 0; g0 < g.points; g0 += CURVE_LANES) {
        int more = pipe && g0 + CURVE_LANES < g.points;
        for (s = 0; s < CURVE_LANES; s++) {
            pen[s] = ok[s] ? 0.0 : INFINITY;
        }
        if (more) { /* block_exp's set-up for the next block */
            double x[CURVE_LANES];
            gen_x(&g, g0 + CURVE_LANES, x);
            for (s = 0; s < CURVE_LANES; s++) {
                e.m2[s] = x[s] * x[s];
                e.mx[s] = -INFINITY;
                e.nf[s] = 0.0;
            }
            e.t = &g.t;
            e.out = nxt;
            e.every = n_tiles;
        }
        for (s = 0; s < n_samples; s += ns) {
            const double *d[STREAM_SAMPLES];
            size_t left = n_samples - s;
            size_t q;
            size_t j;
            for (q = 0; q < ns; q++) {
                d[q] = data[s + (q < left ? q : left - 1)];
            }
            e.first = s / ns; /* rows spread over the tiles */
            if (ns == STREAM_SAMPLES) {
                score_stream_wide(n, c, rs, d, lse, more ? &e : NULL);
            } else {
                score_stream_narrow(n, c, rs, d, lse, more ? &e : NULL);
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
    free(g.t.mem);
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
