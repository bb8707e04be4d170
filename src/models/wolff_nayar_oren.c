/* wolff_nayar_oren.c: WNO, the Wolff-Nayar-Oren diffuse model of smooth
 * dielectrics, the paper's ref. [5] (Wolff's subsurface scattering seen
 * through a Fresnel boundary). Its rough-surface form WNO-R (a V-cavity
 * surface whose facets each reflect by WNO) is src/models/wno_r.c.
 *
 * References:
 *   [1] L. B. Wolff, S. K. Nayar, M. Oren, "Improved diffuse reflection
 *       models for computer vision", IJCV 30(1):55-71, 1998.
 *   [2] L. B. Wolff, "Diffuse-reflectance model for smooth dielectric
 *       surfaces", JOSA A 11(11):2956-2968, 1994 (the model itself).
 *   [3] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann
 *       Model", ref. [5] and (P6) (the same Fresnel transmittances).
 *
 * Equations (n refractive index of the body, f of SPEC §4.1):
 *   L = rho cos ti [1 - f(ti, n)] [1 - f(asin(sin ts / n), 1/n)]     [2]
 * rho (and the constant of the subsurface scattering) cancel in the
 * normalisation (SPEC §2): n is the only parameter. The bracket is F_FC^2
 * of (P6), SPEC §4.2 (bf__fresnel_fc2_sc): WNO is FC's Fresnel factor
 * without the Beckmann lobe [3].
 *
 * Limits: 0 at grazing incidence (cos ti and the transmittance) and at
 * grazing view (light leaves the body at the critical angle); n = 1 gives
 * Lambert. Finite and >= 0 on the whole closed hemisphere.
 */
#include <math.h>

#include "fit/engine.h"

/* Evaluates WNO at param = {n}; n checked by bf_model_eval. */
static int eval_wno(const double *param, size_t count, const bf_geom *geom,
                    double *out, void *work)
{
    double n = param[0];
    size_t k;
    (void)work;
    for (k = 0; k < count; k++) {
        double si;
        double ci;
        double ss;
        double cs;
        bf__zenith_sincos(geom[k].theta_i, &si, &ci);
        bf__zenith_sincos(geom[k].theta_s, &ss, &cs);
        out[k] = bf__fresnel_fc2_sc(si, ci, ss, cs, n); /* [2], (P6) */
    }
    return BF_OK;
}

/* The engine's kernel of WNO: sines and cosines of the configurations as
 * terms (4 rows of n), the values F_FC^2 (bf__fc2_values, the bits of
 * bf__fresnel_fc2_sc). */
enum { F_SI = 0, F_CI, F_SS, F_CS, F_NT };

static void trig_rows(const bf__cset *cs, double *terms, size_t n)
{
    size_t k;
    for (k = 0; k < cs->n; k++) {
        terms[F_SI * n + k] = cs->trig[k].si;
        terms[F_CI * n + k] = cs->trig[k].ci;
        terms[F_SS * n + k] = cs->trig[k].ss;
        terms[F_CS * n + k] = cs->trig[k].cs;
    }
}

static void wno_terms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    (void)kr;
    trig_rows(cs, terms, cs->n);
}

/* F_FC^2 at index n_index from the trig rows at t (pm->n configurations). */
static void wno_rows(const bf__prep *pm, const double *t, double n_index,
                     double *out)
{
    size_t n = pm->n;
    bf__fc2_values(n, t + F_SI * n, t + F_CI * n, t + F_SS * n, t + F_CS * n,
                   n_index, out); /* [2], (P6) */
}

static int wno_values(const bf__prep *pm, const double *param, void *work,
                      double *out)
{
    (void)work;
    wno_rows(pm, pm->terms, param[0], out);
    return BF_OK;
}

static const bf_kernel wno_kernel = {
    .n_terms = F_NT,
    .terms = wno_terms,
    .values = wno_values,
    .cheap = -1,
};

/* n is fitted over [1.2, 2.5] (typical dielectrics, SPEC §4.2), step 0.01;
 * the domain is that of FC's n. */
static const bf_param param_wno[1] = {
    {.name = "n", .label = "refractive index n", .unit = "1", .min = 1.0,
     .max = 10.0, .value = BF_DEFAULT_N, .fitted = 1,
     .grid_lo = BF_FREE_N_LO, .grid_step = 0.01, .grid_n = 131,
     .input = BF_INPUT_INDEX},
};

static const bf_model_type wno_type = {
    .name = "WNO",
    .title = "Wolff-Nayar-Oren smooth dielectric diffuse (Wolff 1994)",
    .reference = "Wolff JOSA A 1994; Wolff, Nayar & Oren IJCV 1998; SPEC §4; "
                 "doc/methods.md §7",
    .p = 1,
    .param = param_wno,
    .eval = eval_wno,
    .kernel = &wno_kernel,
    .style = 9,
};

const bf_model_type *const bf_model_wno = &wno_type;
