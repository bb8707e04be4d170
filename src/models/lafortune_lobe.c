/* lafortune_lobe.c: LAFORTUNE, one isotropic generalised cosine lobe of
 * Lafortune et al. (SPEC §9.3), in sr^-1. (LFTG, the paper's diffuse lobe,
 * is lafortune.c.)
 *
 * References:
 *   [1] E. P. F. Lafortune, S.-C. Foo, K. E. Torrance, D. P. Greenberg,
 *       "Non-linear approximation of reflectance functions", SIGGRAPH 1997
 *       (eq. 5, one lobe, Cx = Cy).
 *
 * Equations (microfacet.h has the geometry and the frame: ix ox + iy oy
 * = -sin ti sin to cos phi_s):
 *   LAFORTUNE = max(0, Cxy (ix ox + iy oy) + Cz iz oz)^n   [1], SPEC §9.3
 * Cxy < 0 puts the lobe at the mirror direction, Cxy > 0 at backscatter.
 * Homogeneous of degree n in (Cxy, Cz) (bf_homog): the separable fit
 * (src/fit/varpro.c) solves the lobe's size exactly on its grid.
 * Limits: continuous on the closed hemisphere (no division). Where base
 * > 1 (the domain allows up to 2) and base^n exceeds the largest double
 * the value is NaN (BF_EDOM), not infinity.
 */
#include <math.h>

#include "models/microfacet.h"

/* param = {Cxy, Cz, n}. */
static double lafortune_value(const bf__mf_t *m, const double *p)
{
    double base = (p[0] * m->dxy) + (p[1] * (m->ci * m->co));
    double v = bf__mf_pow(fmax(0.0, base), p[2]);
    return isinf(v) ? NAN : v; /* base > 1 and large n: not a double */
}

BF__MF_ENTRY(lafortune, lafortune_value);

static const bf_param param_lafortune[3] = {
    {.name = "Cxy", .label = "lobe Cxy", .unit = "1", .min = -2.0,
     .max = 2.0, .value = -1.0, .fitted = 1, .homog = BF_HOMOG_SCALED},
    {.name = "Cz", .label = "lobe Cz", .unit = "1", .min = 0.0, .max = 2.0,
     .value = 1.0, .fitted = 1, .homog = BF_HOMOG_UNIT},
    {.name = "n", .label = "exponent n", .unit = "1", .min = 1.0,
     .max = 1e4, .value = 20.0, .fitted = 1, .homog = BF_HOMOG_DEGREE},
};

static const bf_model_type lafortune_type = {
    .name = "LAFORTUNE",
    .title = "Lafortune generalised cosine lobe, isotropic, sr^-1",
    .reference = "Lafortune et al. 1997 eq. 5; SPEC §9.3",
    .p = 3,
    .param = param_lafortune,
    .eval = lafortune_eval,
    .kernel = &lafortune_kernel,
    .style = BF__STYLE_LAFORTUNE,
    .kind = BF_MODEL_SPECULAR,
    .ndf = "generalised cosine lobe",
    .masking = BF__MASK_NONE,
    .fresnel_term = BF__FRES_ABSENT,
};

const bf_model_type *const bf_model_lafortune = &lafortune_type;
