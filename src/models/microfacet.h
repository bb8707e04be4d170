/* microfacet.h: the pieces the specular models of SPEC §9 share -- the
 * vectors of SPEC §9.1 from a configuration, the normal distributions and
 * Smith masking of SPEC §9.2, the V-cavity masking, the Fresnel terms --
 * and the evaluation loops every specular model file uses (the reference
 * eval and the engine's kernel give the same bits: both go through one
 * value function per configuration). Private (bf__ names).
 *
 * References:
 *   [1] B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet
 *       models for refraction through rough surfaces", EGSR 2007.
 *   [2] E. Heitz, "Understanding the masking-shadowing function in
 *       microfacet-based BRDFs", JCGT 3(2), 2014.
 *   [3] R. L. Cook, K. E. Torrance, "A reflectance model for computer
 *       graphics", ACM TOG 1(1), 1982 (the V-cavity masking).
 *   [4] C. Schlick, "An inexpensive BRDF model for physically-based
 *       rendering", Computer Graphics Forum 13(3), 1994.
 *
 * The frame (SPEC §1.2 vs §9.1). SPEC §9.1 writes i and o in the
 * measurement frame of §1.5. A bf_geom is Beckmann's frame, which is the
 * measurement frame turned about the normal by pi - phi_i (SPEC §1.5: phi_s
 * = phi_o - phi_i - pi): i lies at azimuth pi, o at phi_s,
 *     i = (-sin ti, 0, cos ti),   o = (sin to cos phi_s, sin to sin phi_s,
 *                                       cos to),
 * and a rotation about n keeps every dot product of SPEC §9.1, so the
 * values are those of the measurement frame. The mirror direction of i is
 * (sin ti, 0, cos ti): theta_s = theta_i, phi_s = 0 (SPEC §1.2). Only
 * phi_s is read (bf_geom.phi_i is pi by construction, as for every model).
 *
 * With H = i + o (|H| = 2 cos theta_d) and d = i - o (|d| = 2 sin
 * theta_d), written so that swapping i and o gives the same bits
 * (Helmholtz reciprocity) and no difference cancels near the mirror
 * direction (sin^2(phi_s/2) instead of 1 - cos phi_s):
 *     Hx^2 + Hy^2 = (so - si)^2 + 4 si so sin^2(phi_s/2),   Hz = ci + co,
 *     dx^2 + dy^2 = (so - si)^2 + 4 si so cos^2(phi_s/2),   dz = ci - co,
 *     cos^2 theta_h = Hz^2 / |H|^2, tan^2 theta_h = (Hx^2 + Hy^2) / Hz^2,
 *     ix ox + iy oy = -si so cos phi_s.
 * H = 0 only at the grazing corner theta_i = theta_o = pi/2, phi_s = 0;
 * there (ci = co = 0) every specular model returns 0, as VH does (the
 * values have no limit at that corner).
 */
#ifndef BF_MODELS_MICROFACET_H
#define BF_MODELS_MICROFACET_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fit/engine.h"

/* The geometry of one configuration (SPEC §9.1). */
typedef struct {
    double ci, co; /* cos theta_i, cos theta_o */
    double si, so; /* sin theta_i, sin theta_o */
    double c2h;    /* cos^2 theta_h */
    double s2h;    /* sin^2 theta_h */
    double t2h;    /* tan^2 theta_h (+inf only at the corner) */
    double ch;     /* cos theta_h */
    double cd, sd; /* cos, sin theta_d (i.h = o.h) */
    double dxy;    /* ix ox + iy oy */
} bf__mf_t;

/* The rows of the engine's terms (terms[row * n + k]): one per field. */
enum {
    BF__MF_CI = 0, BF__MF_CO, BF__MF_SI, BF__MF_SO, BF__MF_C2H, BF__MF_S2H, BF__MF_T2H,
    BF__MF_CH, BF__MF_CD, BF__MF_SD, BF__MF_DXY, BF__MF_NTERMS
};

/* The vectors of SPEC §9.1 at g (see the frame above). */
void bf__mf_geom(const bf_geom *g, bf__mf_t *m);

/* The grazing corner (ci = co = 0), where every model that divides by
 * the cosines is 0 (its fields of theta_h and theta_d are 0 there). */
static inline int bf__mf_corner(const bf__mf_t *m)
{
    return (m->ci + m->co) == 0.0;
}

/* The frame of configuration k of n from a kernel's terms (bf__mf_kterms:
 * row BF__MF_X holds X of every configuration). */
static inline void bf__mf_at(const double *t, size_t n, size_t k,
                             bf__mf_t *m)
{
    m->ci = t[(BF__MF_CI * n) + k];
    m->co = t[(BF__MF_CO * n) + k];
    m->si = t[(BF__MF_SI * n) + k];
    m->so = t[(BF__MF_SO * n) + k];
    m->c2h = t[(BF__MF_C2H * n) + k];
    m->s2h = t[(BF__MF_S2H * n) + k];
    m->t2h = t[(BF__MF_T2H * n) + k];
    m->ch = t[(BF__MF_CH * n) + k];
    m->cd = t[(BF__MF_CD * n) + k];
    m->sd = t[(BF__MF_SD * n) + k];
    m->dxy = t[(BF__MF_DXY * n) + k];
}

/* pow(x, y) for the lobes' x >= 0 and exponents y > 0, the same value
 * every time. A normal x = 2^(e - 1) (1 + f), f in [i / 16, (i + 1) / 16)
 * with e its exponent field less 1022 and i the top four bits of its
 * fraction, lies below 2^(e - 1) (1 + (i + 1) / 16); a subnormal x below
 * 2^-1022. Where that bound's log2 times y is <= -1100, x^y < 2^-1100
 * lies below half the least subnormal and pow rounds it to 0 -- returned
 * without pow's slow underflow path, which a sharp lobe (n in the
 * hundreds) takes at most configurations. */
static inline double bf__mf_pow(double x, double y)
{
    /* log2(1 + (i + 1) / 16), i = 0 .. 15 */
    static const double top[16] = {
        0.087462841250339401, 0.16992500144231237, 0.24792751344358549,
        0.32192809488736235,  0.39231742277876031, 0.45943161863729726,
        0.52356195605701283,  0.58496250072115619, 0.6438561897747247,
        0.70043971814109218,  0.75488750216346856, 0.80735492205760406,
        0.85798099512757209,  0.90689059560851848, 0.95419631038687525,
        1.0};
    if (x > 0.0 && x < 1.0 && y > 0.0) {
        uint64_t bits;
        int e;
        double log2_above;
        memcpy(&bits, &x, sizeof bits);
        e = (int)((bits >> 52) & 0x7ffu) - 1022;
        log2_above = e == -1022 ? -1022.0
                                : (double)(e - 1) + top[(bits >> 48) & 0xfu];
        if (log2_above * y <= -1100.0) {
            return 0.0;
        }
    }
    return pow(x, y);
}

/* A specular model's value at one configuration from its geometry and the
 * parameters (checked): the one formula of a model file. */
typedef double (*bf__mf_value_fn)(const bf__mf_t *m, const double *param);

/* The reference eval of a specular model through f: BF_OK, or BF_EDOM
 * where f gives NaN (WARD, WARD-DUER at grazing, where they diverge). */
int bf__mf_eval(const double *param, size_t n, const bf_geom *geom,
                double *out, bf__mf_value_fn f);

/* The engine's kernel: terms (the rows above, once per configuration set)
 * and values through f from them (the same bits as bf__mf_eval). The
 * values' loop is inline, so that each model file's kernel (BF__MF_ENTRY)
 * has its value function inlined into it rather than called through a
 * pointer per configuration, with its terms in registers. */
void bf__mf_kterms(const bf_kernel *kr, const bf__cset *cs, double *terms);
static inline int bf__mf_kvalues(const bf__prep *pm, const double *param,
                                 double *out, bf__mf_value_fn f)
{
    const double *t = pm->terms;
    size_t n = pm->n;
    int rc = BF_OK;
    size_t k;
    for (k = 0; k < n; k++) {
        bf__mf_t m;
        bf__mf_at(t, n, k, &m);
        out[k] = f(&m, param);
        if (isnan(out[k])) {
            rc = BF_EDOM;
        }
    }
    return rc;
}

/* The eval function, kernel values and kernel of one type object whose
 * value function is value (`name_eval`, `name_kernel`); cols the
 * kernel's separable-fit columns (bf_kernel.columns). BF__MF_ENTRY: a
 * value with an offset at zero scales (AS's specular term beside Rd);
 * BF__MF_SCALED: value = rho_s times a function of the others. */
#define BF__MF_ENTRY_COLS(name, value, cols)                               \
    static int name##_eval(const double *param, size_t count,              \
                           const bf_geom *geom, double *out, void *work)   \
    {                                                                      \
        (void)work;                                                        \
        return bf__mf_eval(param, count, geom, out, value);                \
    }                                                                      \
    static int name##_kvalues(const bf__prep *pm, const double *param,     \
                              void *work, double *out)                     \
    {                                                                      \
        (void)work;                                                        \
        return bf__mf_kvalues(pm, param, out, value);                      \
    }                                                                      \
    static const bf_kernel name##_kernel = {                               \
        .n_terms = BF__MF_NTERMS,                                          \
        .terms = bf__mf_kterms,                                            \
        .values = name##_kvalues,                                          \
        .cheap = -1,                                                       \
        .columns = cols,                                                   \
    }
#define BF__MF_ENTRY(name, value) BF__MF_ENTRY_COLS(name, value, NULL)
#define BF__MF_SCALED(name, value)                                         \
    BF__MF_ENTRY_COLS(name, value, bf__columns_scaled)

/* ==== what the type objects share (SPEC §9.3) ========================== */

/* The parameters of SPEC §9.3 with its domains. The scales have no upper
 * bound in SPEC §9.3 (they are solved linearly); BF__SCALE_MAX keeps the
 * values finite for any parameters of the domain. No paper grid: these
 * models are fitted under SPEC §10's objectives, not on §7.4's grids. */
#define BF__SCALE_MAX 1e6
#define BF__PARAM_SCALE(nm, lab)                                           \
    {.name = nm, .label = lab, .unit = "1", .min = 0.0,                     \
     .max = BF__SCALE_MAX, .value = 1.0, .fitted = 1, .linear = 1}
#define BF__PARAM_RHO_S BF__PARAM_SCALE("rho_s", "specular scale rho_s")
#define BF__PARAM_ALPHA                                                    \
    {.name = "alpha", .label = "NDF width alpha", .unit = "1",             \
     .min = 1e-3, .max = 2.0, .value = 0.1, .fitted = 1}
#define BF__PARAM_F0                                                       \
    {.name = "F0", .label = "Schlick F0", .unit = "1", .min = 0.0,         \
     .max = 1.0, .value = 0.04, .fitted = 1}
#define BF__PARAM_INDEX(nm)                                                \
    {.name = nm, .label = "refractive index " nm, .unit = "1",             \
     .min = 1.01, .max = 4.0, .value = 1.5, .fitted = 1,                   \
     .input = BF_INPUT_INDEX}
#define BF__PARAM_N BF__PARAM_INDEX("n")

/* The names of the masking forms and Fresnel terms (bf_model_type). */
#define BF__MASK_HEIGHT "Smith height-correlated (Heitz 2014 eq. 99)"
#define BF__MASK_SEPARABLE "Smith separable (Heitz 2014 eq. 98)"
#define BF__MASK_VCAVITY "V-cavity (Cook-Torrance 1982)"
#define BF__MASK_NONE "none"
#define BF__FRES_SCHLICK "Schlick (F0)"
#define BF__FRES_DIELECTRIC "dielectric (n, SPEC §4.1)"
#define BF__FRES_NONE "none (F = 1)"
#define BF__FRES_ABSENT "none (not in the model)"

/* The style slots of the specular models, after the diffuse ones (0-10). */
enum {
    BF__STYLE_GGX = 11, BF__STYLE_BECKMANN, BF__STYLE_CT,
    BF__STYLE_BLINN_PHONG, BF__STYLE_WARD, BF__STYLE_WARD_DUER,
    BF__STYLE_WARD_GMD, BF__STYLE_AS, BF__STYLE_LAFORTUNE, BF__STYLE_ABC
};

/* ==== normal distributions (SPEC §9.2) ================================= */

/* GGX (Trowbridge-Reitz), Walter et al. eq. 33:
 * D = a^2 / (pi cos^4 th (a^2 + tan^2 th)^2) = a^2 / (pi (a^2 c2h + s2h)^2)
 * (multiplying out cos^4 th; finite wherever h is defined). */
double bf__mf_d_ggx(const bf__mf_t *m, double alpha);

/* e^x for x <= 0, the bits of exp(x): +0 below -746 without calling exp,
 * whose result there underflows to +0 (its smallest subnormal is
 * e^-744.4) through libm's slow error path (errno, the underflow flag);
 * a narrow lobe's exp(-tan^2 th / a^2) is there at most configurations. */
static inline double bf__mf_exp_neg(double x)
{
    return x < -746.0 ? 0.0 : exp(x);
}

/* Beckmann, Walter et al. eq. 25: D = exp(-tan^2 th / a^2) / (pi a^2
 * cos^4 th). */
double bf__mf_d_beckmann(const bf__mf_t *m, double alpha);

/* ==== Smith masking (SPEC §9.2) ========================================= */

/* cos theta_v Lambda(v) for a direction of cosine c and sine s: finite at
 * grazing (c = 0), where Lambda diverges; 0 at the normal.
 *   GGX, Walter eq. 34: Lambda = (-1 + sqrt(1 + a^2 tan^2))/2, so
 *     c Lambda = a^2 s^2 / (2 (sqrt(c^2 + a^2 s^2) + c))  (no cancellation);
 *   Beckmann, Walter eq. 26 in SPEC §9.2's exact form, a_v = c / (a s):
 *     Lambda = (erf(a_v) - 1)/2 + exp(-a_v^2) / (2 a_v sqrt(pi)), so
 *     c Lambda = (a s exp(-a_v^2) / sqrt(pi) - c erfc(a_v)) / 2. */
double bf__mf_clambda_ggx(double c, double s, double alpha);
double bf__mf_clambda_beckmann(double c, double s, double alpha);

/* Lambda(v) itself (tests; the projected-area identity): c Lambda / c. */
double bf__mf_lambda_ggx(double theta, double alpha);
double bf__mf_lambda_beckmann(double theta, double alpha);

/* G2 / (4 cos ti cos to) from ci Lambda(i) = li, co Lambda(o) = lo:
 *   height-correlated, Heitz eq. 99: 1 / (4 (ci co + co li + ci lo));
 *   separable, Heitz eq. 98:         1 / (4 (ci + li)(co + lo)).
 * (chi+(i.h) chi+(o.h) = 1: i.h = o.h = cos theta_d > 0 off the corner.) */
static inline double bf__mf_g2_height(const bf__mf_t *m, double li,
                                      double lo)
{
    return 1.0 / (4.0 * ((m->ci * m->co) + (m->co * li) + (m->ci * lo)));
}

static inline double bf__mf_g2_separable(const bf__mf_t *m, double li,
                                         double lo)
{
    return 1.0 / (4.0 * (m->ci + li) * (m->co + lo));
}

/* G_V / (4 cos ti cos to) with the V-cavity G of SPEC §9.2 (Cook-Torrance
 * 1982): G = min(1, 2 ch co / (o.h), 2 ch ci / (o.h)), so
 *   G / (4 ci co) = min(1 / (4 ci co), ch / (2 cd max(ci, co))),
 * finite when one zenith is grazing (compared without dividing by 0). */
double bf__mf_gv_over(const bf__mf_t *m);

/* ==== Fresnel (SPEC §9.2) =============================================== */

/* The Fresnel term of an option (SPEC §9.2): Schlick at F0 = *fp,
 * dielectric at n = *fp, or 1 (fp not read). */
static inline double bf__mf_fresnel(const bf__mf_t *m, bf_fresnel_kind f,
                                    const double *fp);

/* Schlick: F0 + (1 - F0)(1 - cos theta_d)^5. */
static inline double bf__mf_schlick(double cd, double f0)
{
    double u = 1.0 - cd;
    double u2 = u * u;
    return f0 + ((1.0 - f0) * (u2 * u2 * u));
}

/* The exact unpolarised dielectric reflectance of SPEC §4.1 at theta_d for
 * index n (src/fresnel.c). */
static inline double bf__mf_dielectric(const bf__mf_t *m, double n)
{
    return bf__fresnel_sc(m->sd, m->cd, n);
}

static inline double bf__mf_fresnel(const bf__mf_t *m, bf_fresnel_kind f,
                                    const double *fp)
{
    if (f == BF_FRESNEL_DIELECTRIC) {
        return bf__mf_dielectric(m, *fp);
    }
    return (f == BF_FRESNEL_NONE) ? 1.0 : bf__mf_schlick(m->cd, *fp);
}

#endif
