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

#include "fit/engine.h"

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

/* The geometry-only terms of one configuration (SPEC §3): the factor F^2
 * that replaces F_BK^2 (Table 1, SPEC §3.3), vz^2, vxy^2 and |vz|. They do
 * not depend on the slope m, so the study path (src/fit/kernels.c)
 * computes them once per configuration and the plain path once per call;
 * both get the same bits from this one function. Returns BF_EDOM (terms
 * unset) where F_BK diverges: BK at theta_i = pi/2 (SPEC §3.3). */
int bf__bk_terms(int factor, double n, const bf_geom *g, bf__bk_terms_t *t)
{
    bf__trig_t tr;
    bf__geom_trig(g, &tr);
    return bf__bk_terms_trig(factor, n, &tr, t);
}

void bf__geom_trig(const bf_geom *g, bf__trig_t *tr)
{
    tr->sp = sin(g->phi_s);
    tr->cp = cos(g->phi_s);
    bf__zenith_sincos(g->theta_i, &tr->si, &tr->ci);
    bf__zenith_sincos(g->theta_s, &tr->ss, &tr->cs);
}

int bf__bk_terms_trig(int factor, double n, const bf__trig_t *tr,
                      bf__bk_terms_t *t)
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
    case BF__BK_FACTOR_BK: {
        double f_bk;
        if (ci == 0.0) { /* theta_i = pi/2: F_BK diverges, SPEC §3.3 */
            return BF_EDOM;
        }
        /* F_BK, paper (P3), SPEC §3 */
        f_bk = (1.0 + (ci * cs) - (si * ss * cp)) / (ci * (ci + cs));
        t->f2 = f_bk * f_bk;
        break;
    }
    case BF__BK_FACTOR_VH:
        t->f2 = ci; /* Vernold-Harvey, Table 1, SPEC §3.3 */
        break;
    default:
        /* F_FC^2, paper (P6), SPEC §4.2 */
        t->f2 = bf__fresnel_fc2_sc(si, ci, ss, cs, n);
        break;
    }
    return BF_OK;
}

/* Evaluates one member of the family at count configurations; m and n were
 * checked by bf_model_eval (n is used by FC only). Called by the six eval
 * functions below. Per configuration: three sine/cosine pairs, one exp or
 * sqrt; no allocation. The per-slope part below is repeated, operation for
 * operation, by the study path's vectorised kernel (src/fit/kernels.c). */
static int bk_family(int factor, int corr, double m, double n, size_t count,
                     const bf_geom *geom, double *out)
{
    int status = BF_OK;
    double m2 = m * m;
    size_t k;
    for (k = 0; k < count; k++) {
        bf__bk_terms_t t;
        if (bf__bk_terms(factor, n, &geom[k], &t) != BF_OK) {
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
        if (corr == BF__BK_CORR_GAUSS) {
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
    return bk_family(BF__BK_FACTOR_BK, BF__BK_CORR_GAUSS, param[0], 1.0, count, geom, out);
}

static int eval_bk_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(BF__BK_FACTOR_BK, BF__BK_CORR_EXP, param[0], 1.0, count, geom, out);
}

static int eval_vh_g(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(BF__BK_FACTOR_VH, BF__BK_CORR_GAUSS, param[0], 1.0, count, geom, out);
}

static int eval_vh_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(BF__BK_FACTOR_VH, BF__BK_CORR_EXP, param[0], 1.0, count, geom, out);
}

static int eval_fc_g(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(BF__BK_FACTOR_FC, BF__BK_CORR_GAUSS, param[0], param[1], count, geom,
                     out);
}

static int eval_fc_e(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    (void)work;
    return bk_family(BF__BK_FACTOR_FC, BF__BK_CORR_EXP, param[0], param[1], count, geom,
                     out);
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

/* The engine's kernels (src/fit/kernels.c): one per member. */
#define BK_KERNEL(fac, cor)                                                 \
    {.n_terms = BF__BK_NTERMS, .n_extra = BF__BK_NEXTRA,                    \
     .terms = bf__bk_kterms, .work_bytes = bf__bk_kwork,                    \
     .values = bf__bk_kvalues, .block = BF__BLOCK_BK, .factor = (fac),      \
     .corr = (cor), .cheap = -1}
static const bf_kernel kr_bk_g = BK_KERNEL(BF__BK_FACTOR_BK, BF__BK_CORR_GAUSS);
static const bf_kernel kr_bk_e = BK_KERNEL(BF__BK_FACTOR_BK, BF__BK_CORR_EXP);
static const bf_kernel kr_vh_g = BK_KERNEL(BF__BK_FACTOR_VH, BF__BK_CORR_GAUSS);
static const bf_kernel kr_vh_e = BK_KERNEL(BF__BK_FACTOR_VH, BF__BK_CORR_EXP);
static const bf_kernel kr_fc_g = BK_KERNEL(BF__BK_FACTOR_FC, BF__BK_CORR_GAUSS);
static const bf_kernel kr_fc_e = BK_KERNEL(BF__BK_FACTOR_FC, BF__BK_CORR_EXP);

/* Plot styles: the paper's models the lowest slots (FC-E, VH-E first: the
 * two it finds best), BK-G, BK-E after every paper model. */
static const bf_model_type bk_g = {
    .name = "BK-G",
    .title = "Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1),(P3), SPEC §3.1",
    .p = 1,
    .param = param_g,
    .eval = eval_bk_g,
    .kernel = &kr_bk_g,
    .style = 6,
};

static const bf_model_type bk_e = {
    .name = "BK-E",
    .title = "Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2),(P3), SPEC §3.2",
    .p = 1,
    .param = param_e,
    .eval = eval_bk_e,
    .kernel = &kr_bk_e,
    .style = 7,
};

static const bf_model_type vh_g = {
    .name = "VH-G",
    .title = "Vernold-Harvey Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1), Table 1, SPEC §3.1, §3.3",
    .p = 1,
    .param = param_g,
    .eval = eval_vh_g,
    .kernel = &kr_vh_g,
    .style = 4,
};

static const bf_model_type vh_e = {
    .name = "VH-E",
    .title = "Vernold-Harvey Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2), Table 1, SPEC §3.2, §3.3",
    .p = 1,
    .param = param_e,
    .eval = eval_vh_e,
    .kernel = &kr_vh_e,
    .style = 1,
};

static const bf_model_type fc_g = {
    .name = "FC-G",
    .title = "Fresnel-corrected Beckmann-Kirchhoff, Gaussian correlation",
    .reference = "paper (P1),(P4)-(P6), Table 1, SPEC §3.1, §3.3, §4",
    .p = 2,
    .param = param_fc_g,
    .eval = eval_fc_g,
    .kernel = &kr_fc_g,
    .style = 5,
};

static const bf_model_type fc_e = {
    .name = "FC-E",
    .title = "Fresnel-corrected Beckmann-Kirchhoff, exponential correlation",
    .reference = "paper (P2),(P4)-(P6), Table 1, SPEC §3.2, §3.3, §4",
    .p = 2,
    .param = param_fc_e,
    .eval = eval_fc_e,
    .kernel = &kr_fc_e,
    .style = 0,
};

const bf_model_type *const bf_model_bk_g = &bk_g;
const bf_model_type *const bf_model_bk_e = &bk_e;
const bf_model_type *const bf_model_vh_g = &vh_g;
const bf_model_type *const bf_model_vh_e = &vh_e;
const bf_model_type *const bf_model_fc_g = &fc_g;
const bf_model_type *const bf_model_fc_e = &fc_e;
