/* as.c: AS, Ashikhmin & Shirley's anisotropic Phong model, isotropic
 * (nu = nv = n), a complete model with its own diffuse term (SPEC §9.3),
 * in sr^-1.
 *
 * References:
 *   [1] M. Ashikhmin, P. Shirley, "An anisotropic Phong BRDF model",
 *       Journal of Graphics Tools 5(2), 2000 (eqs. 4 and 5).
 *
 * Equations (microfacet.h has the geometry and the frame):
 *   AS = (n + 1) / (8 pi) cos^n th / (cos td max(ci, co)) F(cos td; Rs)
 *        + 28 Rd / (23 pi) (1 - Rs) (1 - (1 - ci/2)^5) (1 - (1 - co/2)^5)
 *                                                   [1] eqs. 4-5, SPEC §9.3
 *   F = Rs + (1 - Rs)(1 - cos td)^5 (Schlick)
 * Rd enters linearly (only the diffuse term has it); Rs does not.
 * Limits: finite on the closed hemisphere; 0 at the grazing corner (both
 * terms vanish there).
 */
#include <math.h>

#include "models/microfacet.h"

/* 1 - (1 - c/2)^5, the diffuse term's factor per direction ([1] eq. 5). */
static double as_fall(double c)
{
    double u = 1.0 - (0.5 * c);
    double u2 = u * u;
    return 1.0 - (u2 * u2 * u);
}

/* param = {Rd, Rs, n}. */
static double as_value(const bf__mf_t *m, const double *p)
{
    double rd = p[0];
    double rs = p[1];
    double n = p[2];
    double spec;
    double diff;
    if (bf__mf_corner(m)) {
        return 0.0;
    }
    spec = (n + 1.0) / (8.0 * BF__PI) * bf__mf_pow(m->ch, n)
           / (m->cd * fmax(m->ci, m->co)) * bf__mf_schlick(m->cd, rs);
    diff = 28.0 * rd / (23.0 * BF__PI) * (1.0 - rs) * as_fall(m->ci)
           * as_fall(m->co);
    return spec + diff;
}

BF__MF_ENTRY(as, as_value);

static const bf_param param_as[3] = {
    BF__PARAM_SCALE("Rd", "diffuse Rd"),
    {.name = "Rs", .label = "specular Rs", .unit = "1",
     .min = 0.0, .max = 1.0, .value = 0.05, .fitted = 1},
    {.name = "n", .label = "exponent n", .unit = "1", .min = 1.0,
     .max = 1e5, .value = 50.0, .fitted = 1},
};

static const bf_model_type as_type = {
    .name = "AS",
    .title = "Ashikhmin-Shirley, isotropic, with its diffuse term, sr^-1",
    .reference = "Ashikhmin & Shirley 2000 eqs. 4-5; SPEC §9.3",
    .p = 3,
    .param = param_as,
    .eval = as_eval,
    .kernel = &as_kernel,
    .style = BF__STYLE_AS,
    .kind = BF_MODEL_SPECULAR,
    .ndf = "Phong in theta_h (cos^n theta_h)",
    .masking = "none (1 / (cos theta_d max(cos theta_i, cos theta_o)))",
    .fresnel_term = "Schlick (Rs), part of the model",
    .own_diffuse = 1, /* fitted alone in the complete comparison */
};

const bf_model_type *const bf_model_as = &as_type;
