/* blinn_phong.c: BLINN-PHONG, the normalised Blinn-Phong lobe (SPEC §9.3),
 * in sr^-1.
 *
 * References:
 *   [1] J. F. Blinn, "Models of light reflection for computer synthesized
 *       pictures", SIGGRAPH 1977 (cos^e of the half-vector angle).
 *   [2] A. Ngan, F. Durand, W. Matusik, "Experimental
 *       analysis of BRDF models", EGSR 2005 (the (e + 8) / (8 pi)
 *       normalisation and the comparison it is used in).
 *
 * Equations (microfacet.h has the geometry and the frame):
 *   BLINN-PHONG = rho_s (e + 8) / (8 pi) cos^e th          SPEC §9.3
 * Limits: finite on the closed hemisphere; 0 at the grazing corner
 * (cos th = 0 there).
 */
#include <math.h>

#include "models/microfacet.h"

static double bp_value(const bf__mf_t *m, const double *p)
{
    return p[0] * (p[1] + 8.0) / (8.0 * BF__PI) * bf__mf_pow(m->ch, p[1]);
}

BF__MF_SCALED(bp, bp_value);

static const bf_param param_bp[2] = {
    BF__PARAM_RHO_S,
    {.name = "e", .label = "exponent e", .unit = "1", .min = 1.0,
     .max = 1e5, .value = 50.0, .fitted = 1},
};

static const bf_model_type bp_type = {
    .name = "BLINN-PHONG",
    .title = "normalised Blinn-Phong lobe, sr^-1",
    .reference = "Blinn 1977; Ngan, Durand, Matusik 2005; SPEC §9.3",
    .p = 2,
    .param = param_bp,
    .eval = bp_eval,
    .kernel = &bp_kernel,
    .style = BF__STYLE_BLINN_PHONG,
    .kind = BF_MODEL_SPECULAR,
    .ndf = "Blinn-Phong (cos^e theta_h)",
    .masking = BF__MASK_NONE,
    .fresnel_term = BF__FRES_ABSENT,
};

const bf_model_type *const bf_model_blinn_phong = &bp_type;
