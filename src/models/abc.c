/* abc.c: ABC, the model of Low, Kronander, Ynnerman and Unger (SPEC
 * §9.3), in sr^-1.
 *
 * References:
 *   [1] J. Low, J. Kronander, A. Ynnerman, J. Unger, "BRDF models for
 *       accurate and efficient rendering of glossy surfaces", ACM TOG
 *       31(1), 2012 (the ABC distribution, eq. 9 with the microfacet
 *       lobe of their eq. 3).
 *
 * Equations (microfacet.h has the pieces and the frame):
 *   ABC = F(cos td; ior) A / (1 + B (1 - cos th))^C G_V / (pi ci co)
 *                                                   [1], SPEC §9.3
 *   F: the dielectric reflectance of SPEC §4.1; G_V: the V-cavity G of
 *   SPEC §9.2; 1 - cos th = sin^2 th / (1 + cos th) (no cancellation).
 * A enters linearly. Limits: finite on the closed hemisphere (G_V / (ci
 * co) stays finite at one grazing zenith); 0 at the grazing corner.
 */
#include <math.h>

#include "models/microfacet.h"

/* param = {A, B, C, ior}. */
static double abc_value(const bf__mf_t *m, const double *p)
{
    double one_minus_ch;
    if (bf__mf_corner(m)) {
        return 0.0;
    }
    one_minus_ch = m->s2h / (1.0 + m->ch);
    return bf__mf_dielectric(m, p[3]) * p[0]
           / pow(1.0 + (p[1] * one_minus_ch), p[2])
           * (4.0 / BF__PI) * bf__mf_gv_over(m);
}

BF__MF_SCALED(abc, abc_value);

static const bf_param param_abc[4] = {
    BF__PARAM_SCALE("A", "scale A"),
    {.name = "B", .label = "sharpness B", .unit = "1", .min = 0.0,
     .max = 1e6, .value = 300.0, .fitted = 1},
    {.name = "C", .label = "fall-off C", .unit = "1", .min = 0.01,
     .max = 10.0, .value = 1.0, .fitted = 1},
    BF__PARAM_INDEX("ior"),
};

static const bf_model_type abc_type = {
    .name = "ABC",
    .title = "Low et al. ABC microfacet model, sr^-1",
    .reference = "Low, Kronander, Ynnerman, Unger 2012; SPEC §9.2, §9.3",
    .p = 4,
    .param = param_abc,
    .eval = abc_eval,
    .kernel = &abc_kernel,
    .style = BF__STYLE_ABC,
    .kind = BF_MODEL_SPECULAR,
    .ndf = "ABC (A / (1 + B (1 - cos theta_h))^C)",
    .masking = BF__MASK_VCAVITY,
    .fresnel_term = "dielectric (ior, SPEC §4.1), part of the model",
};

const bf_model_type *const bf_model_abc = &abc_type;
