/* wolff_nayar_oren.c: WNO, the diffuse reflection of a smooth dielectric
 * after Wolff (subsurface scattering seen through a Fresnel boundary), the
 * smooth-surface model of Wolff, Nayar & Oren -- the paper's ref. [5].
 *
 * References:
 *   [1] L. B. Wolff, S. K. Nayar, M. Oren, "Improved diffuse reflection
 *       models for computer vision", IJCV 30(1):55-71, 1998 (§2: the
 *       smooth-surface model that its rough-surface model builds on).
 *   [2] L. B. Wolff, "Diffuse-reflectance model for smooth dielectric
 *       surfaces", JOSA A 11(11):2956-2968, 1994 (the model itself).
 *   [3] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann
 *       Model", ref. [5] and (P6) (the same Fresnel transmittances).
 *
 * Equations (n refractive index of the body, f of SPEC §4.1):
 *   L = rho cos ti [1 - f(ti, n)] [1 - f(asin(sin ts / n), 1/n)]   [2]
 * rho (and the constant of the subsurface scattering) cancel in the
 * normalisation (SPEC §2), so n is the only parameter. The bracket is F_FC^2
 * of (P6), SPEC §4.2 (bf__fresnel_fc2_sc): WNO is FC's Fresnel factor
 * without the Beckmann lobe.
 *
 * Not implemented: the rough-surface form of [1] (Wolff's factors combined
 * with Oren-Nayar's facet geometry); see doc/methods.md §7.
 *
 * Limits: 0 at theta_i = pi/2 (cos ti and 1 - f = 0); n = 1 gives Lambert
 * (no interface); finite on the whole closed hemisphere.
 */
#include "internal.h"

/* Evaluates WNO at param = {n}; n checked by bf_model_eval. */
static int eval_wno(const double *param, size_t count, const bf_geom *geom,
                    double *out)
{
    double n = param[0];
    size_t k;
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

/* n is fitted over [1.2, 2.5] (typical dielectrics, SPEC §4.2), step 0.01;
 * the domain is that of FC's n. */
static const bf_param param_wno[1] = {
    {"n", "refractive index n", "1", 1.0, 10.0, BF_DEFAULT_N, 1, BF_FREE_N_LO,
     0.01, 131},
};

static const bf_model_type wno_type = {
    "WNO", "Wolff-Nayar-Oren smooth dielectric diffuse (Wolff 1994)",
    "Wolff JOSA A 1994; Wolff, Nayar & Oren IJCV 1998; SPEC §4; "
    "doc/methods.md §7",
    1, param_wno, eval_wno};

const bf_model_type *const bf_model_wno = &wno_type;
