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

#include "fit/engine.h"

/* The base cos ti cos ts of (P7) at one configuration: the only geometry
 * the model needs. Shared with the study path (src/fit/kernels.c), which
 * computes it once per configuration, so both paths raise the same bits to
 * the power n_d. */
double bf__lftg_base(const bf_geom *g)
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
        out[k] = scale * pow(bf__lftg_base(&geom[k]), n_d); /* (P7), SPEC §6 */
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

/* The engine's terms: ln(cos ti cos ts) per configuration (-inf at
 * grazing), the only geometry (P7) needs; the values are
 * bf__lftg_kvalues (src/fit/kernels.c). */
static void lftg_terms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t k;
    (void)kr;
    for (k = 0; k < cs->n; k++) {
        terms[k] = log(cs->trig[k].ci * cs->trig[k].cs); /* (P7) */
    }
}

static const bf_kernel lftg_kernel = {
    .n_terms = 1,
    .terms = lftg_terms,
    .values = bf__lftg_kvalues,
    .block = BF__BLOCK_LFTG,
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
