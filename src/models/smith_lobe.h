/* smith_lobe.h: the microfacet lobe with Smith masking of SPEC §9.2 --
 * rho_s F(cos theta_d) D(h) G2(i, o, h) / (4 cos ti cos to), Walter et al.
 * 2007 eq. 20 -- and its six option variants (--fresnel schlick,
 * dielectric, none x --smith height, separable), shared by GGX and
 * BECKMANN, which differ only in D and Lambda (microfacet.h). Private.
 *
 * References: Walter et al. EGSR 2007 eq. 20; Heitz, JCGT 3(2) 2014,
 * eqs. 98 (separable), 99 (height-correlated); SPEC §9.2, §9.3.
 */
#ifndef BF_MODELS_SMITH_LOBE_H
#define BF_MODELS_SMITH_LOBE_H

#include "models/microfacet.h"

typedef enum { BF__NDF_GGX = 0, BF__NDF_BECKMANN } bf__ndf_kind;

/* rho_s F D G2 / (4 ci co) at param = {rho_s, alpha[, F0 or n]}: Walter
 * eq. 20 with D and c Lambda of ndf, G2 of Heitz eq. 99 or 98. */
static inline double bf__smith_lobe(const bf__mf_t *m, const double *p,
                                    bf__ndf_kind ndf, bf_fresnel_kind f,
                                    bf_smith_kind s)
{
    double alpha = p[1];
    double li;
    double lo;
    double d;
    double g;
    if (bf__mf_corner(m)) {
        return 0.0;
    }
    if (ndf == BF__NDF_GGX) {
        li = bf__mf_clambda_ggx(m->ci, m->si, alpha);
        lo = bf__mf_clambda_ggx(m->co, m->so, alpha);
        d = bf__mf_d_ggx(m, alpha);
    } else {
        li = bf__mf_clambda_beckmann(m->ci, m->si, alpha);
        lo = bf__mf_clambda_beckmann(m->co, m->so, alpha);
        d = bf__mf_d_beckmann(m, alpha);
    }
    g = (s == BF_SMITH_SEPARABLE) ? bf__mf_g2_separable(m, li, lo)
                                  : bf__mf_g2_height(m, li, lo);
    return p[0] * bf__mf_fresnel(m, f, p + 2) * d * g;
}

/* The parameters of the three Fresnel options (microfacet.c): {rho_s,
 * alpha, F0}, {rho_s, alpha, n}, {rho_s, alpha}; CT uses them too. */
extern const bf_param bf__mf_param_schlick[3];
extern const bf_param bf__mf_param_dielectric[3];
extern const bf_param bf__mf_param_none[2];

#define BF__SMITH_VALUE(tag, ndf, f, s)                                    \
    static double tag##_value(const bf__mf_t *m, const double *p)          \
    {                                                                      \
        return bf__smith_lobe(m, p, ndf, f, s);                            \
    }                                                                      \
    BF__MF_SCALED(tag, tag##_value)

#define BF__SMITH_TYPE(tag, fam, np, params, mask, fres, nm, ndfname, ttl, \
                       ref, st)                                            \
    static const bf_model_type tag##_type = {                              \
        .name = nm, .title = ttl, .reference = ref, .p = np,               \
        .param = params, .eval = tag##_eval, .kernel = &tag##_kernel,      \
        .style = st, .kind = BF_MODEL_SPECULAR, .ndf = ndfname,            \
        .masking = mask, .fresnel_term = fres, .variants = fam##_variants, \
    }

/* Defines the six variants of the lobe with distribution ndf, their table
 * and `const bf_model_type *const bf_model_<fam>` (Schlick, height-
 * correlated: the registry's), named nm. */
#define BF__SMITH_FAMILY(fam, ndf, nm, ndfname, ttl, ref, st)              \
    BF__SMITH_VALUE(fam##_sh, ndf, BF_FRESNEL_SCHLICK, BF_SMITH_HEIGHT);   \
    BF__SMITH_VALUE(fam##_ss, ndf, BF_FRESNEL_SCHLICK, BF_SMITH_SEPARABLE);\
    BF__SMITH_VALUE(fam##_dh, ndf, BF_FRESNEL_DIELECTRIC, BF_SMITH_HEIGHT);\
    BF__SMITH_VALUE(fam##_ds, ndf, BF_FRESNEL_DIELECTRIC,                  \
                    BF_SMITH_SEPARABLE);                                   \
    BF__SMITH_VALUE(fam##_nh, ndf, BF_FRESNEL_NONE, BF_SMITH_HEIGHT);      \
    BF__SMITH_VALUE(fam##_ns, ndf, BF_FRESNEL_NONE, BF_SMITH_SEPARABLE);   \
    static const bf_model_type fam##_sh_type, fam##_ss_type,               \
        fam##_dh_type, fam##_ds_type, fam##_nh_type, fam##_ns_type;        \
    static const bf_model_type *const fam##_variants[BF_SPECULAR_VARIANTS] \
        = {&fam##_sh_type, &fam##_ss_type, &fam##_dh_type,                 \
           &fam##_ds_type, &fam##_nh_type, &fam##_ns_type};                \
    BF__SMITH_TYPE(fam##_sh, fam, 3, bf__mf_param_schlick,                 \
                   BF__MASK_HEIGHT, BF__FRES_SCHLICK, nm, ndfname, ttl,    \
                   ref, st);                                               \
    BF__SMITH_TYPE(fam##_ss, fam, 3, bf__mf_param_schlick,                 \
                   BF__MASK_SEPARABLE, BF__FRES_SCHLICK, nm, ndfname, ttl, \
                   ref, st);                                               \
    BF__SMITH_TYPE(fam##_dh, fam, 3, bf__mf_param_dielectric,              \
                   BF__MASK_HEIGHT, BF__FRES_DIELECTRIC, nm, ndfname, ttl, \
                   ref, st);                                               \
    BF__SMITH_TYPE(fam##_ds, fam, 3, bf__mf_param_dielectric,              \
                   BF__MASK_SEPARABLE, BF__FRES_DIELECTRIC, nm, ndfname,   \
                   ttl, ref, st);                                          \
    BF__SMITH_TYPE(fam##_nh, fam, 2, bf__mf_param_none, BF__MASK_HEIGHT,   \
                   BF__FRES_NONE, nm, ndfname, ttl, ref, st);              \
    BF__SMITH_TYPE(fam##_ns, fam, 2, bf__mf_param_none,                    \
                   BF__MASK_SEPARABLE, BF__FRES_NONE, nm, ndfname, ttl,    \
                   ref, st);                                               \
    const bf_model_type *const bf_model_##fam = &fam##_sh_type

#endif
