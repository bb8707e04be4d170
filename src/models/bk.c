/* bk.c: the Beckmann-Kirchhoff family -- BK-G, BK-E (Beckmann's original
 * geometric factor), VH-G, VH-E (Vernold-Harvey) and FC-G, FC-E (Fresnel
 * correction), for Gaussian (G) and exponential (E) surface correlation
 * (SPEC §3).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (equations (P1)-(P3), (P6) and Table 1).
 *   [2] P. Beckmann, A. Spizzichino, "The Scattering of Electromagnetic Waves
 *       from Rough Surfaces", Pergamon, 1963 (F_BK, the frame of SPEC §1.2).
 *   [3] C. L. Vernold, J. E. Harvey, "A modified Beckmann-Kirchhoff
 *       scattering theory for non-paraxial angles", Proc. SPIE 3426, 1998.
 *
 * Equations (k = 2 pi / lambda cancels, k = 1; m = sigma / T):
 *   vx = sin ti - sin ts cos ps,  vy = -sin ts sin ps,
 *   vz = -(cos ti + cos ts),  vxy^2 = vx^2 + vy^2              SPEC §3
 *   F_BK = (1 + cos ti cos ts - sin ti sin ts cos ps)
 *          / (cos ti (cos ti + cos ts))                   (P3), SPEC §3
 *   G:  L = (1/m^2) F^2 / vz^2 exp(-vxy^2 / (4 m^2 vz^2))  (P1), SPEC §3.1
 *   E:  L = (2/m^2) F^2 / vz^2 (1 + vxy^2/(m^2 vz^2))^(-3/2)
 *                                                         (P2), SPEC §3.2
 *   F^2 = F_BK^2 (BK), cos ti (VH), F_FC^2 of (P6) (FC)   Table 1, SPEC §3.3
 *
 * Departures from the paper's printed forms, all algebraically exact:
 *   - each variant computes its own factor F^2 directly instead of Table 1's
 *     L_BK * F'/F_BK^2 (F_BK can vanish at grazing geometry; SPEC §3.3);
 *   - (P2) is evaluated as 2 m F^2 |vz| / (m^2 vz^2 + vxy^2)^(3/2), which is
 *     finite where vz -> 0 (multiply numerator and denominator by
 *     (m |vz|)^3);
 *   - where vz = 0 (theta_i = theta_s = pi/2) the formulas are 0/0 and the
 *     limit is returned: 0 when vxy > 0 (the exponential decay wins);
 *     see the note on the grazing corner below for vxy = 0.
 *
 * Domains: BK-G/BK-E are undefined at theta_i = pi/2 (F_BK ~ 1/cos ti; the
 * Kirchhoff approximation fails there): NaN and BF_EDOM (SPEC §3.3).
 */
#include <math.h>
#include <string.h>

#include "fit/block.h"
#include "fit/engine.h"

/* Members of the family: the factor (Table 1, SPEC §3.3) and the
 * correlation function (SPEC §3.1, §3.2). */
enum { FACTOR_BK, FACTOR_VH, FACTOR_FC };
enum { CORR_GAUSS, CORR_EXP };

/* Geometry-only terms of the family at one configuration (SPEC §3): F^2
 * (the factor replacing F_BK^2, Table 1), vz^2, vxy^2, |vz|. */
typedef struct {
    double f2;
    double vz2;
    double vxy2;
    double abs_vz;
} bk_terms_t;

/* The grazing corner theta_i = theta_s = pi/2, phi_s = 0,
 * where vz = 0 and vxy = 0. SPEC §3.3 resolves it: the VH and FC variants
 * return the limit 0 there, never 0/0. For FC with n > 1 this is a true
 * limit: both transmittances vanish like cos theta at grazing, F_FC^2 <=
 * c^2 cos^2 ti cos ts, so L <= c' F_FC^2 / vz^2 <= c' c^2 cos ti -> 0 on
 * every path. For VH (and FC with n = 1, which equals VH) the limit is
 * path-dependent: 0 along the grazing boundary (theta_i = theta_s = pi/2,
 * phi_s -> 0) but 1 / (4 m^2 cos ti) -> infinity along the specular path
 * theta_s = theta_i -> pi/2, phi_s = 0 (tested). The corner value 0 is
 * therefore SPEC's convention for VH, a single point that no measured
 * configuration reaches. */

/* The geometry-only terms of one configuration (SPEC §3) from its sines
 * and cosines: the factor F^2 that replaces F_BK^2 (Table 1, SPEC §3.3),
 * vz^2, vxy^2 and |vz| (n is FC's refractive index). They do not depend on
 * the slope m, so the engine's kernel (below) computes them once per
 * configuration and the plain path once per call; both get the same bits
 * from this one function. Returns BF_EDOM (terms unset) where F_BK
 * diverges: BK at theta_i = pi/2 (SPEC §3.3). */
static int bk_terms_trig(int factor, double n, const bf__trig_t *tr,
                         bk_terms_t *t)
{
    double si = tr->si;
    double ci = tr->ci;
    double ss = tr->ss;
    double cs = tr->cs;
    double sp = tr->sp;
    double cp = tr->cp;
    double vx;
    double vy;
    double vz;
    vx = si - (ss * cp); /* SPEC §3, k = 1 */
    vy = -(ss * sp);     /* SPEC §3 */
    vz = -(ci + cs);     /* SPEC §3 */
    t->vxy2 = (vx * vx) + (vy * vy);
    t->vz2 = vz * vz;
    t->abs_vz = fabs(vz);

    switch (factor) {
    case FACTOR_BK: {
        double f_bk;
        if (ci == 0.0) { /* theta_i = pi/2: F_BK diverges, SPEC §3.3 */
            return BF_EDOM;
        }
        /* F_BK, paper (P3), SPEC §3 */
        f_bk = (1.0 + (ci * cs) - (si * ss * cp)) / (ci * (ci + cs));
        t->f2 = f_bk * f_bk;
        break;
    }
    case FACTOR_VH:
        t->f2 = ci; /* Vernold-Harvey, Table 1, SPEC §3.3 */
        break;
    default:
        /* F_FC^2, paper (P6), SPEC §4.2 */
        t->f2 = bf__fresnel_fc2_sc(si, ci, ss, cs, n);
        break;
    }
    return BF_OK;
}

/* The terms of one configuration g (bf__geom_trig, then bk_terms_trig). */
static int bk_terms(int factor, double n, const bf_geom *g, bk_terms_t *t)
{
    bf__trig_t tr;
    bf__geom_trig(g, &tr);
    return bk_terms_trig(factor, n, &tr, t);
}

/* Evaluates one member of the family at count configurations; m and n were
 * checked by bf_model_eval (n is used by FC only). Called by the six eval
 * functions below. Per configuration: three sine/cosine pairs, one exp or
 * sqrt; no allocation. The per-slope part below is repeated, operation for
 * operation, by the engine's vectorised kernels (below). */
static int bk_family(int factor, int corr, double m, double n, size_t count,
                     const bf_geom *geom, double *out)
{
    int status = BF_OK;
    double m2 = m * m;
    size_t k;
    for (k = 0; k < count; k++) {
        bk_terms_t t;
        if (bk_terms(factor, n, &geom[k], &t) != BF_OK) {
            out[k] = NAN; /* BK at theta_i = pi/2, SPEC §3.3 */
            status = BF_EDOM;
            continue;
        }
        if (t.vz2 == 0.0) { /* theta_i = theta_s = pi/2 (only VH, FC here) */
            /* vxy > 0: the limit of exp(-c/vz^2)/vz^2 and of |vz| is 0;
             * vxy = 0 (the corner, phi_s = 0): see the note above. */
            out[k] = 0.0; /* SPEC §3.3 */
            continue;
        }
        if (corr == CORR_GAUSS) {
            /* (P1), SPEC §3.1 */
            out[k] = t.f2 / (m2 * t.vz2) * exp(-t.vxy2 / (4.0 * m2 * t.vz2));
        } else {
            /* (P2), SPEC §3.2, rearranged: (2/m^2)(1/vz^2)(1 + x)^(-3/2)
             * = 2 m |vz| / (m^2 vz^2 + vxy^2)^(3/2) */
            double d = (m2 * t.vz2) + t.vxy2;
            out[k] = 2.0 * m * t.f2 * t.abs_vz / (d * sqrt(d));
        }
    }
    return status;
}

/* ---------------------------------------------------------------------- */
/* The six eval functions: param[0] = m, FC also param[1] = n.             */
/* ---------------------------------------------------------------------- */

static int eval_bk_g(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_BK, CORR_GAUSS, param[0], 1.0, count, geom, out);
}

static int eval_bk_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_BK, CORR_EXP, param[0], 1.0, count, geom, out);
}

static int eval_vh_g(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_VH, CORR_GAUSS, param[0], 1.0, count, geom, out);
}

static int eval_vh_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_VH, CORR_EXP, param[0], 1.0, count, geom, out);
}

static int eval_fc_g(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_FC, CORR_GAUSS, param[0], param[1], count, geom,
                     out);
}

static int eval_fc_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(FACTOR_FC, CORR_EXP, param[0], param[1], count, geom,
                     out);
}

/* ---------------------------------------------------------------------- */
/* The engine's kernel (src/fit/engine.h) and block kernel                */
/* (src/fit/block.h): the study path's form of (P1), (P2)                  */
/* ---------------------------------------------------------------------- */

/* The math is rearranged against the plain path above, algebraically
 * exactly, to take divisions out of the inner loop: factors that do not
 * depend on the configuration are dropped (1/m^2 of (P1), 2m of (P2):
 * they cancel in the normalisation, SPEC §2);
 *   G:  l = (F^2/vz^2) exp((-vxy^2/(4 vz^2)) / m^2), both brackets once
 *       per configuration, 1/m^2 once per slope, exp the kernels' own
 *       (bf__vexp_nonpos, within 1 ulp of glibc's);
 *   E:  l = F^2 |vz| / (d sqrt d), d = fma(m^2, vz^2, vxy^2).
 * src/fit/kernels.c normalises (by the reciprocal of the maximum) and
 * scores; tests/fit/test_grid.c bounds the difference to the plain path. */

/* A member of the family: its engine kernel and which member it is. */
typedef struct {
    bf_kernel kr; /* first: type->kernel points here */
    int factor;   /* FACTOR_* */
    int corr;     /* CORR_* */
} bk_kernel;

static const bk_kernel *bk_of(const bf_kernel *kr)
{
    return (const bk_kernel *)(const void *)kr; /* kr is its first member */
}

/* The kernel's terms: N_TERMS rows of n, then one extra (1 when some
 * slope gives a curve). */
enum {
    T_SI = 0, T_CI, T_SS, T_CS, /* sines and cosines, for FC's F^2 */
    T_VZ2,                      /* vz^2 (SPEC §3) */
    T_VXY2,                     /* vxy^2 */
    T_AVZ,                      /* |vz| */
    T_A,                        /* G: F^2/vz^2   E: F^2 |vz| (not FC) */
    T_B,                        /* G: -vxy^2/(4 vz^2)   E: vz^2 */
    T_C,                        /* E: vxy^2 */
    T_F2,                       /* F^2 of BK, VH (not FC) */
    N_TERMS
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
    } else if (corr == CORR_GAUSS) {
        /* (P1): L m^2 = F^2/vz^2 exp(-vxy^2/(4 vz^2) / m^2) */
        *a = f2 / vz2;
        *b = -vxy2 / (4.0 * vz2);
        *c = 0.0;
    } else {
        /* (P2) as above: L / (2m) = F^2 |vz| / (m^2 vz^2 + vxy^2)^1.5 */
        *a = f2 * abs_vz;
        *b = vz2;
        *c = vxy2;
    }
    return isfinite(*a) && isfinite(*b);
}

static void bk_kterms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    const bk_kernel *bk = bk_of(kr);
    size_t n = cs->n;
    size_t k;
    int ok = 1;
    for (k = 0; k < n; k++) {
        bk_terms_t bt = {0.0, 0.0, 0.0, 0.0};
        const bf__trig_t *tr = &cs->trig[k];
        double a;
        double b;
        double c;
        /* FC's F^2 depends on n: formed per n in the workspace */
        int fc = bk->factor == FACTOR_FC;
        if (bk_terms_trig(fc ? FACTOR_VH : bk->factor, 1.0, tr, &bt) !=
            BF_OK) {
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
        ok &= bk_abc(bk->corr, bt.f2, bt.vz2, bt.vxy2, bt.abs_vz, &a, &b,
                     &c);
        terms[T_A * n + k] = a;
        terms[T_B * n + k] = b;
        terms[T_C * n + k] = c;
    }
    terms[N_TERMS * n] = ok;
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

static size_t bk_kwork(const bf_kernel *kr, size_t n)
{
    return bk_of(kr)->factor == FACTOR_FC
               ? sizeof(fc_work) + FC_SLOTS * n * sizeof(double)
               : 0;
}

/* bk_abc's a-terms in place of f2 = F_FC^2 (as[k]), vectorised: the same
 * operations per configuration, so the same bits. Its b-terms depend on
 * the geometry alone, checked once in the terms (bk_kterms's flag, which
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
 * bk_terms_trig and the grid form them, from w's slots or into one; *a
 * points at them. Returns 0 when a term is not finite. */
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
    w->ok[slot] = fc_a_terms(n, bk_of(pm->kr)->corr == CORR_GAUSS,
                             t + T_VZ2 * n, t + T_AVZ * n, as);
    w->used[slot] = 1;
    w->n[slot] = n_index;
    *a = as;
    return w->ok[slot];
}

/* The family at one slope m (and FC's n): the block kernels' operations
 * for one lane, vectorised across the configurations instead, so a value
 * has the bits of the same grid value's (before normalisation). */
BF__CLONES
static int bk_kvalues(const bf__prep *pm, const double *param, void *work,
                      double *out)
{
    const bk_kernel *bk = bk_of(pm->kr);
    size_t n = pm->n;
    const double *t = pm->terms;
    const double *fa = t + T_A * n;
    const double *restrict a;
    const double *restrict b = t + T_B * n;
    const double *restrict c = t + T_C * n;
    double m = param[0];
    size_t k;
    int ok = t[N_TERMS * n] != 0.0;
    if (bk->factor == FACTOR_FC) {
        ok &= fc_terms(pm, param[1], work, &fa);
    }
    a = fa;
    if (!ok) {
        for (k = 0; k < n; k++) {
            out[k] = NAN; /* BK at theta_i = pi/2 (SPEC §3.3) */
        }
        return BF_EDOM;
    }
    if (bk->corr == CORR_GAUSS) {
        double inv_m2 = 1.0 / (m * m);
#pragma omp simd
        for (k = 0; k < n; k++) {
            out[k] = a[k] * bf__vexp_nonpos(b[k] * inv_m2); /* (P1) */
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

/* The block kernel's state: the terms of one grid (structure of arrays,
 * 64-byte aligned), copied from the prepared terms; FC's a-terms formed
 * for the grid's n. */
typedef struct {
    double *a; /* G: F^2/vz^2   E: F^2 |vz| */
    double *b; /* G: -vxy^2/(4 vz^2)   E: vz^2 */
    double *c; /* E: vxy^2 */
} bk_block;

/* Gaussian correlation (P1), SPEC §3.1, for BF__BLOCK_LANES slopes m[]:
 * l = a exp(b / m^2), one multiply, one exp and one multiply per value. */
BF__CLONES
static void block_gauss(const bf__block *blk, size_t n, const double *m,
                        size_t stride, double *restrict c, double *mx_out,
                        double *nf_out)
{
    const bk_block *t = blk->state;
    double mx[BF__BLOCK_LANES];
    double nf[BF__BLOCK_LANES];
    double inv_m2[BF__BLOCK_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        inv_m2[j] = 1.0 / (m[j] * m[j]);
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        double a = t->a[k];
        double b = t->b[k];
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(BF__BLOCK_LANES)
        for (j = 0; j < BF__BLOCK_LANES; j++) {
            double v = a * bf__vexp_nonpos(b * inv_m2[j]); /* (P1), §3.1 */
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* Row k of the exponential correlation (P2), SPEC §3.2, in the plain
 * path's form: l = a / (d sqrt d), d = m^2 vz^2 + vxy^2 (one fma, sqrt,
 * multiply, division per value). */
static inline BF__ALWAYS_INLINE void exp_row(const void *state, size_t k,
                                             const double *m,
                                             double *restrict out,
                                             double *mx, double *nf)
{
    const bk_block *t = state;
    double a = t->a[k];
    double vz2 = t->b[k];
    double vxy2 = t->c[k];
    size_t j;
#pragma omp simd simdlen(BF__BLOCK_LANES)
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        double d = fma(m[j] * m[j], vz2, vxy2); /* (P2), SPEC §3.2 */
        double v = a / (d * sqrt(d));
        out[j] = v;
        nf[j] += v - v; /* NaN once a value is not finite */
        mx[j] = (v > mx[j]) ? v : mx[j];
    }
}

/* (P2) for BF__BLOCK_LANES slopes m[]: exp_row for every configuration. */
BF__CLONES
static void block_exp(const bf__block *blk, size_t n, const double *m,
                      size_t stride, double *restrict c, double *mx_out,
                      double *nf_out)
{
    double mx[BF__BLOCK_LANES];
    double nf[BF__BLOCK_LANES];
    size_t j;
    size_t k;
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
    for (k = 0; k < n; k++) {
        exp_row(blk->state, k, m, c + (k * stride), mx, nf);
    }
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* The streaming scorers of E: the next block's rows (a division and a
 * square root per value) computed while the current block is scored, so
 * the divider's work overlaps the scoring's FMA work. */
BF__CLONES
static void exp_score_wide(size_t n, const double *restrict c,
                           const double *restrict rs, const double *const *d,
                           double *restrict lse, bf__rows_t *restrict e)
{
    bf__stream_score(BF__STREAM_SAMPLES, n, c, rs, d, lse, e, exp_row);
}

BF__CLONES
static void exp_score_narrow(size_t n, const double *restrict c,
                             const double *restrict rs,
                             const double *const *d, double *restrict lse,
                             bf__rows_t *restrict e)
{
    bf__stream_score(BF__STREAM_SAMPLES_NARROW, n, c, rs, d, lse, e,
                     exp_row);
}

/* The block kernel on a grid of the slope m (parameter 0; FC's n fixed at
 * lay->base[1], (P6)). */
static int bk_block_init(const bf__prep *pm, const bf__grid_layout_t *lay,
                         bf__block *blk)
{
    const bk_kernel *bk = bk_of(pm->kr);
    const double *tm = pm->terms;
    size_t n = pm->n;
    bk_block *t;
    double *mem;
    size_t k;

    if (lay->free[0] != 0) {
        return 0;
    }
    t = bf__block_state(blk, sizeof *t, 3 * n, &mem);
    if (t == NULL) {
        return -BF_ENOMEM;
    }
    t->a = mem;
    t->b = t->a + n;
    t->c = t->b + n;
    blk->raw = bk->corr == CORR_GAUSS ? block_gauss : block_exp;
    if (bk->corr == CORR_EXP) {
        blk->score[0] = exp_score_wide;
        blk->score[1] = exp_score_narrow;
    }
    memcpy(t->b, tm + T_B * n, n * sizeof *t->b);
    memcpy(t->c, tm + T_C * n, n * sizeof *t->c);
    blk->defined = tm[N_TERMS * n] != 0.0;
    if (bk->factor != FACTOR_FC) {
        memcpy(t->a, tm + T_A * n, n * sizeof *t->a);
    } else {
        /* FC's refractive index is parameter 1, fixed here (P6) */
        bf__fc2_values(n, tm + T_SI * n, tm + T_CI * n, tm + T_SS * n,
                       tm + T_CS * n, lay->base[1], t->a);
        for (k = 0; k < n; k++) {
            double b;
            double c;
            blk->defined &= bk_abc(bk->corr, t->a[k], tm[T_VZ2 * n + k],
                                   tm[T_VXY2 * n + k], tm[T_AVZ * n + k],
                                   &t->a[k], &b, &c);
        }
    }
    return 1;
}

/* ---------------------------------------------------------------------- */
/* Parameters and type objects                                            */
/* ---------------------------------------------------------------------- */

/* Domain of the slope m = sigma/T. Below 1e-3 the lobe is narrower than any
 * measured configuration spacing and exp() underflows everywhere off
 * specular; above 100 the lobe is flat to 1e-4 over the hemisphere. The
 * paper's grid [0.1, 5.1] lies well inside. Grid: SPEC §7.4. */
#define SLOPE_MIN 1e-3
#define SLOPE_MAX 100.0
#define SLOPE_DEFAULT 1.0
#define SLOPE_GRID_LO 0.1
#define SLOPE_GRID_STEP 0.01
#define SLOPE_GRID_N 501

/* Refractive index of FC: a fixed input (SPEC §4.2), default 1.7. n = 1 is
 * allowed (no interface: FC reduces to VH). */
#define N_MIN 1.0
#define N_MAX 10.0

/* The slope m of every member (G and E differ in the label only). */
#define SLOPE_PARAM(lab)                                                    \
    {.name = "m", .label = (lab), .unit = "1", .min = SLOPE_MIN,           \
     .max = SLOPE_MAX, .value = SLOPE_DEFAULT, .fitted = 1,                \
     .grid_lo = SLOPE_GRID_LO, .grid_step = SLOPE_GRID_STEP,               \
     .grid_n = SLOPE_GRID_N, .input = BF_INPUT_DEFAULT}
/* FC's refractive index: an input (SPEC §4.2) the exact fit may free. */
#define INDEX_PARAM                                                         \
    {.name = "n", .label = "refractive index n", .unit = "1", .min = N_MIN, \
     .max = N_MAX, .value = BF_DEFAULT_N, .fitted = 0,                      \
     .input = BF_INPUT_INDEX, .free_lo = BF_FREE_N_LO,                      \
     .free_hi = BF_FREE_N_HI, .free_step = BF_FREE_N_STEP}

static const bf_param param_g[1] = {SLOPE_PARAM("sigma/T (G)")};
static const bf_param param_e[1] = {SLOPE_PARAM("sigma/T (E)")};
static const bf_param param_fc_g[2] = {SLOPE_PARAM("sigma/T (G)"),
                                       INDEX_PARAM};
static const bf_param param_fc_e[2] = {SLOPE_PARAM("sigma/T (E)"),
                                       INDEX_PARAM};

/* The engine's kernels (above): one per member. */
#define BK_KERNEL(fac, cor)                                                 \
    {.kr = {.n_terms = N_TERMS,                                             \
            .n_extra = 1,                                                   \
            .terms = bk_kterms,                                             \
            .work_bytes = bk_kwork,                                         \
            .values = bk_kvalues,                                           \
            .normalise = bf__normalise_recip,                               \
            .block = bk_block_init,                                         \
            .cheap = -1},                                                   \
     .factor = (fac),                                                       \
     .corr = (cor)}
static const bk_kernel kr_bk_g = BK_KERNEL(FACTOR_BK, CORR_GAUSS);
static const bk_kernel kr_bk_e = BK_KERNEL(FACTOR_BK, CORR_EXP);
static const bk_kernel kr_vh_g = BK_KERNEL(FACTOR_VH, CORR_GAUSS);
static const bk_kernel kr_vh_e = BK_KERNEL(FACTOR_VH, CORR_EXP);
static const bk_kernel kr_fc_g = BK_KERNEL(FACTOR_FC, CORR_GAUSS);
static const bk_kernel kr_fc_e = BK_KERNEL(FACTOR_FC, CORR_EXP);

/* Plot styles: the paper's models the lowest slots (FC-E, VH-E first: the
 * two it finds best), BK-G, BK-E after every paper model. */
static const bf_model_type bk_g = {
    .name = "BK-G",
    .title = "Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1),(P3), SPEC §3.1",
    .p = 1,
    .param = param_g,
    .eval = eval_bk_g,
    .kernel = &kr_bk_g.kr,
    .style = 6,
};

static const bf_model_type bk_e = {
    .name = "BK-E",
    .title = "Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2),(P3), SPEC §3.2",
    .p = 1,
    .param = param_e,
    .eval = eval_bk_e,
    .kernel = &kr_bk_e.kr,
    .style = 7,
};

static const bf_model_type vh_g = {
    .name = "VH-G",
    .title = "Vernold-Harvey Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1), Table 1, SPEC §3.1, §3.3",
    .p = 1,
    .param = param_g,
    .eval = eval_vh_g,
    .kernel = &kr_vh_g.kr,
    .style = 4,
};

static const bf_model_type vh_e = {
    .name = "VH-E",
    .title = "Vernold-Harvey Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2), Table 1, SPEC §3.2, §3.3",
    .p = 1,
    .param = param_e,
    .eval = eval_vh_e,
    .kernel = &kr_vh_e.kr,
    .style = 1,
};

static const bf_model_type fc_g = {
    .name = "FC-G",
    .title = "Fresnel-corrected Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1),(P4)-(P6), Table 1, SPEC §3.1, §3.3, §4",
    .p = 2,
    .param = param_fc_g,
    .eval = eval_fc_g,
    .kernel = &kr_fc_g.kr,
    .style = 5,
};

static const bf_model_type fc_e = {
    .name = "FC-E",
    .title = "Fresnel-corrected Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2),(P4)-(P6), Table 1, SPEC §3.2, §3.3, §4",
    .p = 2,
    .param = param_fc_e,
    .eval = eval_fc_e,
    .kernel = &kr_fc_e.kr,
    .style = 0,
};

const bf_model_type *const bf_model_bk_g = &bk_g;
const bf_model_type *const bf_model_bk_e = &bk_e;
const bf_model_type *const bf_model_vh_g = &vh_g;
const bf_model_type *const bf_model_vh_e = &vh_e;
const bf_model_type *const bf_model_fc_g = &fc_g;
const bf_model_type *const bf_model_fc_e = &fc_e;
