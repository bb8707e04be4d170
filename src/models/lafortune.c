/* lafortune.c: Lafortune's diffuse lobe, LFTG (SPEC §6).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (equation (P7)).
 *   [2] E. P. F. Lafortune, S.-C. Foo, K. E. Torrance, D. P. Greenberg,
 *       "Non-linear approximation of reflectance functions", SIGGRAPH 1997.
 *
 * Equations:
 *   L = (n_d + 2)/(2 pi) (cos ti cos ts)^n_d            (P7), SPEC §6
 * (P7) is read as a radiance: no extra cos ti factor (SPEC §6). The albedo
 * cancels in the normalisation (SPEC §2) and is not a parameter. At n_d = 0
 * the value is the constant 1/pi, also at grazing (pow(0, 0) = 1 in C99).
 */
#include <math.h>
#include <string.h>

#include "fit/block.h"
#include "fit/engine.h"

/* The base cos ti cos ts of (P7) at one configuration: the only geometry
 * the model needs (the engine's terms take its logarithm once per
 * configuration). */
static double lftg_base(const bf_geom *g)
{
    double si;
    double ci;
    double ss;
    double cs;
    bf__zenith_sincos(g->theta_i, &si, &ci);
    bf__zenith_sincos(g->theta_s, &ss, &cs);
    return ci * cs;
}

/* Evaluates LFTG at param = {n_d}, checked by bf_model_eval. */
static int eval_lftg(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    double n_d = param[0];
    double scale = (n_d + 2.0) / (2.0 * BF__PI);
    size_t k;
    (void)work;
    for (k = 0; k < count; k++) {
        out[k] = scale * pow(lftg_base(&geom[k]), n_d); /* (P7), SPEC §6 */
    }
    return BF_OK;
}

/* n_d: grid 0.1 + 0.04 i, i = 0..500, i.e. [0.1, 20.1] (SPEC §7.4). The
 * domain [0, 100] keeps the lobe representable: (cos ti cos ts)^100 is still
 * above 1e-300 for cos > 1e-3. */
static const bf_param param_lftg[1] = {
    {.name = "n_d", .label = "exponent n_d", .unit = "1", .min = 0.0,
     .max = 100.0, .value = 1.0, .fitted = 1, .grid_lo = 0.1,
     .grid_step = 0.04, .grid_n = 501, .input = BF_INPUT_DEFAULT},
};

/* ---- the engine's kernel (src/fit/engine.h) and block kernel ---------- */

/* The engine's terms: ln(cos ti cos ts) per configuration (-inf at
 * grazing), the only geometry (P7) needs. */
static void lftg_terms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t k;
    (void)kr;
    for (k = 0; k < cs->n; k++) {
        terms[k] = log(cs->trig[k].ci * cs->trig[k].cs); /* (P7) */
    }
}

/* (P7), SPEC §6, at one n_d: (cos ti cos ts)^n_d = exp(n_d ln(cos ti
 * cos ts)) with the kernels' exp (bf__vexp_nonpos, within 1 ulp of
 * glibc's); the constant (n_d + 2)/(2 pi) cancels (SPEC §2). At grazing
 * the base is 0: the value 0 for n_d > 0, 1 for n_d = 0 (pow(0, 0) = 1, as
 * eval_lftg). */
BF__CLONES
static int lftg_values(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    const double *restrict lnb = pm->terms;
    double n_d = param[0];
    size_t k;
    (void)work;
#pragma omp simd
    for (k = 0; k < pm->n; k++) {
        double x = lnb[k];
        double e = bf__vexp_nonpos(n_d * x); /* (P7), SPEC §6 */
        out[k] = (n_d == 0.0) ? 1.0 : e;
    }
    return BF_OK;
}

/* The block kernel's state for one grid of n_d (64-byte aligned). */
typedef struct {
    double *ln_base; /* n: ln(cos ti cos ts) */
    double *e0;      /* n: scratch */
    double *p;       /* n x BF__BLOCK_LANES: exp(j step ln(cos ti cos ts)) */
} lftg_block;

/* (P7), SPEC §6: l = (cos ti cos ts)^n_d = exp(n_d L), L = ln(cos ti
 * cos ts) taken once per configuration (0 at grazing gives exp(-inf) = 0,
 * the value of pow for n_d > 0). The lanes' exponents n_d = n_0 + j step
 * are an arithmetic progression, so exp(n_d L) = exp(n_0 L) exp(j step L):
 * one exp per configuration and block (e0, vectorised across
 * configurations) times a factor computed once per grid (p), instead of
 * one exp per value. The rounding of n_d and of the two factors moves a
 * normalised value v by at most a few v |n_d L| eps <= a few eps / e. */
BF__CLONES
static void block_lftg(const bf__block *blk, size_t n, const double *n_d,
                       size_t stride, double *restrict c, double *mx_out,
                       double *nf_out)
{
    const lftg_block *t = blk->state;
    double mx[BF__BLOCK_LANES];
    double nf[BF__BLOCK_LANES];
    double *restrict e0 = t->e0;
    const double *restrict ln_base = t->ln_base;
    double n0 = n_d[0];
    size_t j;
    size_t k;
    for (j = 0; j < BF__BLOCK_LANES; j++) {
        mx[j] = -INFINITY;
        nf[j] = 0.0;
    }
#pragma omp simd
    for (k = 0; k < n; k++) {
        e0[k] = bf__vexp_nonpos(n0 * ln_base[k]); /* (P7), SPEC §6 */
    }
    for (k = 0; k < n; k++) {
        double e = e0[k];
        const double *restrict pk = t->p + (k * BF__BLOCK_LANES);
        double *restrict ck = c + (k * stride);
#pragma omp simd simdlen(BF__BLOCK_LANES)
        for (j = 0; j < BF__BLOCK_LANES; j++) {
            double v = e * pk[j];
            ck[j] = v;
            nf[j] += v - v; /* NaN once a value is not finite */
            mx[j] = (v > mx[j]) ? v : mx[j];
        }
    }
    memcpy(mx_out, mx, sizeof mx);
    memcpy(nf_out, nf, sizeof nf);
}

/* The factors exp(j step L_k) of block_lftg for j < BF__BLOCK_LANES. */
BF__CLONES
static void lftg_factors(size_t n, double step, const double *ln_base,
                         double *restrict p)
{
    size_t j;
    size_t k;
    for (k = 0; k < n; k++) {
        double l = ln_base[k];
#pragma omp simd simdlen(BF__BLOCK_LANES)
        for (j = 0; j < BF__BLOCK_LANES; j++) {
            /* j = 0: exp(0 L) = 1; at grazing 0 (-inf) = NaN gives 0,
             * harmless: e0 is 0 there */
            p[(k * BF__BLOCK_LANES) + j] =
                bf__vexp_nonpos(((double)j * step) * l);
        }
    }
}

/* The block kernel on a grid of positive n_d (parameter 0). */
static int lftg_block_init(const bf__prep *pm, const bf__grid_layout_t *lay,
                           bf__block *blk)
{
    size_t n = pm->n;
    lftg_block *t;
    double *mem;
    if (lay->free[0] != 0 || !(lay->lo[0] > 0.0)) {
        return 0;
    }
    t = bf__block_state(blk, sizeof *t, (2 + BF__BLOCK_LANES) * n, &mem);
    if (t == NULL) {
        return -BF_ENOMEM;
    }
    blk->raw = block_lftg;
    blk->defined = 1;
    t->ln_base = mem;
    t->e0 = t->ln_base + n;
    t->p = t->e0 + n;
    /* ln(cos ti cos ts), -inf at grazing (the kernel's terms) */
    memcpy(t->ln_base, pm->terms, n * sizeof *t->ln_base);
    lftg_factors(n, lay->step[0], t->ln_base, t->p);
    return 1;
}

static const bf_kernel lftg_kernel = {
    .n_terms = 1,
    .terms = lftg_terms,
    .values = lftg_values,
    .normalise = bf__normalise_recip,
    .block = lftg_block_init,
    .cheap = -1,
};

static const bf_model_type lftg_type = {
    .name = "LFTG",
    .title = "Lafortune diffuse lobe",
    .reference = "paper (P7), Lafortune et al. 1997, SPEC §6",
    .p = 1,
    .param = param_lftg,
    .eval = eval_lftg,
    .kernel = &lftg_kernel,
    .style = 3,
};

const bf_model_type *const bf_model_lftg = &lftg_type;
