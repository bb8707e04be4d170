/* ct.c: CT, Cook-Torrance's microfacet model in SPEC §9.3's normalisation
 * (Beckmann D, V-cavity masking), in sr^-1, with its --fresnel variants.
 *
 * References:
 *   [1] R. L. Cook, K. E. Torrance, "A reflectance model for computer
 *       graphics", ACM TOG 1(1), 1982 (the V-cavity G; its pi in place of
 *       4 only rescales rho_s, SPEC §9.3).
 *   [2] B. Walter et al., EGSR 2007, eq. 20 (the lobe), eq. 25 (D).
 *
 * Equations (microfacet.h has the pieces and the frame):
 *   CT = rho_s F(cos theta_d) D(h) G(i, o, h) / (4 cos ti cos to)
 *                                                   SPEC §9.2, §9.3
 *   D = exp(-tan^2 th / alpha^2) / (pi alpha^2 cos^4 th)  Walter eq. 25
 *   G = min(1, 2 ch co / (o.h), 2 ch ci / (o.h))         SPEC §9.2 [1]
 *   F = Schlick(F0), dielectric(n) (SPEC §4.1) or 1     SPEC §9.2
 * Limits: finite on the closed hemisphere (G / (4 ci co) stays finite at
 * one grazing zenith); 0 at the grazing corner.
 */
#include "models/smith_lobe.h"

/* rho_s F D G / (4 ci co): param = {rho_s, alpha[, F0 or n]}. */
static inline double ct(const bf__mf_t *m, const double *p,
                        bf_fresnel_kind f)
{
    if (bf__mf_corner(m)) {
        return 0.0;
    }
    return p[0] * bf__mf_fresnel(m, f, p + 2) * bf__mf_d_beckmann(m, p[1])
           * bf__mf_gv_over(m);
}

#define CT_VALUE(tag, f)                                                   \
    static double tag##_value(const bf__mf_t *m, const double *p)          \
    {                                                                      \
        return ct(m, p, f);                                                \
    }                                                                      \
    BF__MF_SCALED(tag, tag##_value)

CT_VALUE(ct_s, BF_FRESNEL_SCHLICK);
CT_VALUE(ct_d, BF_FRESNEL_DIELECTRIC);
CT_VALUE(ct_n, BF_FRESNEL_NONE);

static const bf_model_type ct_s_type, ct_d_type, ct_n_type;

/* The masking is V-cavity: only the first Smith slot is used
 * (bf_model_specular_variant refuses --smith for CT). */
static const bf_model_type *const ct_variants[BF_SPECULAR_VARIANTS] = {
    [BF_VARIANT_INDEX(BF_FRESNEL_SCHLICK, BF_SMITH_HEIGHT)] = &ct_s_type,
    [BF_VARIANT_INDEX(BF_FRESNEL_DIELECTRIC, BF_SMITH_HEIGHT)] = &ct_d_type,
    [BF_VARIANT_INDEX(BF_FRESNEL_NONE, BF_SMITH_HEIGHT)] = &ct_n_type,
};

#define CT_TYPE(tag, np, params, fres)                                     \
    static const bf_model_type tag##_type = {                              \
        .name = "CT",                                                      \
        .title = "Cook-Torrance (Beckmann D, V-cavity G), sr^-1",          \
        .reference = "Cook & Torrance 1982; Walter et al. 2007 eqs. 20, "  \
                     "25; SPEC §9.2, §9.3",                                \
        .p = np,                                                           \
        .param = params,                                                   \
        .eval = tag##_eval,                                                \
        .kernel = &tag##_kernel,                                           \
        .style = BF__STYLE_CT,                                             \
        .kind = BF_MODEL_SPECULAR,                                         \
        .ndf = "Beckmann",                                                 \
        .masking = BF__MASK_VCAVITY,                                       \
        .fresnel_term = fres,                                              \
        .variants = ct_variants,                                           \
    }

CT_TYPE(ct_s, 3, bf__mf_param_schlick, BF__FRES_SCHLICK);
CT_TYPE(ct_d, 3, bf__mf_param_dielectric, BF__FRES_DIELECTRIC);
CT_TYPE(ct_n, 2, bf__mf_param_none, BF__FRES_NONE);

const bf_model_type *const bf_model_ct = &ct_s_type;
