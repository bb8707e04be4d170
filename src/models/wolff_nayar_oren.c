/* wolff_nayar_oren.c: the Wolff-Nayar-Oren diffuse models of dielectrics,
 * the paper's ref. [5]: WNO, the smooth-surface model (Wolff's subsurface
 * scattering seen through a Fresnel boundary), and WNO-R, its rough-surface
 * form (a V-cavity surface whose facets each reflect by WNO).
 *
 * References:
 *   [1] L. B. Wolff, S. K. Nayar, M. Oren, "Improved diffuse reflection
 *       models for computer vision", IJCV 30(1):55-71, 1998 (the smooth
 *       model, and its combination with Oren-Nayar's facet geometry into a
 *       model for rough dielectrics).
 *   [2] L. B. Wolff, "Diffuse-reflectance model for smooth dielectric
 *       surfaces", JOSA A 11(11):2956-2968, 1994 (the smooth model itself).
 *   [3] M. Oren, S. K. Nayar, "Generalization of the Lambertian model and
 *       implications for machine vision", IJCV 14(3):227-251, 1995 (the
 *       rough surface: long symmetric V-cavities, isotropic Gaussian
 *       slope-area distribution of standard deviation sigma, projected
 *       radiance, masking and shadowing).
 *   [4] K. E. Torrance, E. M. Sparrow, "Theory for off-specular reflection
 *       from roughened surfaces", JOSA 57(9), 1967 (the V-cavity masking
 *       and shadowing factor G).
 *   [5] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann
 *       Model", ref. [5] and (P6) (the same Fresnel transmittances).
 *
 * Equations (n refractive index of the body, f of SPEC §4.1, T(x) =
 * 1 - f(x, n); T(asin(sin x / n), 1/n) = T(x) by Fresnel reciprocity, SPEC
 * §4.2):
 *   WNO:   L = rho cos ti T(ti) T'(ts),  T'(ts) = 1 - f(asin(sin ts/n), 1/n)
 *                                                                   [2]
 *   WNO-R: L = integral over facet normals a of
 *              P(a) L_f(a) <a,v> G(a) / (<a,n> <v,n>) d omega_a       [3]
 *          L_f(a) = rho <a,l> T(acos <a,l>) T(acos <a,v>)  (WNO on the
 *                   facet: incidence and view measured from a)       [1,2]
 *          P(a) = c(sigma) exp(-theta_a^2 / (2 sigma^2)),
 *                 integral of P over the hemisphere = 1              [3]
 *          G = min(1, 2 <a,n><v,n>/<a,v>, 2 <a,n><l,n>/<a,l>)        [4]
 *          (facets with <a,l> <= 0 or <a,v> <= 0 contribute nothing)
 * rho (and the constant of the subsurface scattering) cancel in the
 * normalisation (SPEC §2): WNO has the parameter n, WNO-R sigma and n.
 * The WNO bracket is F_FC^2 of (P6), SPEC §4.2 (bf__fresnel_fc2_sc): WNO is
 * FC's Fresnel factor without the Beckmann lobe.
 *
 * WNO-R is [1]'s construction (Oren-Nayar's surface [3] with WNO facets
 * instead of Lambertian ones) evaluated by quadrature; the closed-form
 * approximation that [1] fits to it is not used (doc/methods.md §7). It is
 * the direct (single-scattering) component: light exchanged between the
 * facets of a cavity (Oren-Nayar's L2 term for Lambertian facets) is not
 * modelled. Quadrature: WNOR_NT Gauss-Legendre nodes (GSL) in theta_a over
 * [0, min(pi/2, 6 sigma)] (the Gaussian beyond 6 sigma weighs < 2e-8),
 * WNOR_NP midpoint nodes in phi_a (periodic); P is normalised by the same
 * rule, so a surface of level facets gives WNO exactly. Quadrature error:
 * below 1e-3 of the surface's value at normal incidence and view over
 * CURET's range of geometry (zeniths up to 1.46), sigma up to 1.5 (tested
 * against GSL's adaptive quadrature).
 *
 * Limits: both vanish at theta_i = pi/2 (WNO: cos ti and T = 0; WNO-R: the
 * shadowing term 2 <a,n><l,n>/<a,l> = 0). n = 1 gives Lambert (WNO) and
 * the direct Oren-Nayar surface with Lambertian facets (WNO-R); sigma = 0
 * gives WNO. At grazing view (<v,n> = 0) WNO-R takes its limit: <a,v> G /
 * <v,n> -> 2 <a,n> for every visible facet. Finite and >= 0 on the whole
 * closed hemisphere.
 */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

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

/* ---- WNO-R ---------------------------------------------------------- */

/* Quadrature of the facet integral: theta_a nodes, phi_a nodes. */
#define WNOR_NT 24
#define WNOR_NP 48
#define WNOR_NODES (WNOR_NT * WNOR_NP) /* a multiple of 8 */

/* Facet normals a = (ax, ay, az) and weights w of the quadrature for one
 * sigma; w includes P(a), the solid angle and the 1/<a,n> of [3]. */
typedef struct {
    double ax[WNOR_NODES];
    double ay[WNOR_NODES];
    double az[WNOR_NODES];
    double w[WNOR_NODES];
} wnor_nodes;

/* Fills the nodes for sigma > 0. Returns BF_OK or BF_ENOMEM (GSL's table). */
static int wnor_nodes_init(double sigma, wnor_nodes *q)
{
    gsl_integration_glfixed_table *gl;
    double tmax = fmin(BF__PI_2, 6.0 * sigma);
    double dphi = 2.0 * BF__PI / WNOR_NP;
    double total = 0.0;
    size_t i;
    size_t j;
    gl = gsl_integration_glfixed_table_alloc(WNOR_NT);
    if (gl == NULL) {
        return BF_ENOMEM;
    }
    for (i = 0; i < WNOR_NT; i++) {
        double t;
        double wt;
        double st;
        double ct;
        double p;
        gsl_integration_glfixed_point(0.0, tmax, i, &t, &wt, gl);
        st = sin(t);
        ct = cos(t); /* > 0: Gauss nodes are interior, t < pi/2 */
        p = exp(-(t * t) / (2.0 * sigma * sigma)) * wt * st * dphi; /* P dw */
        for (j = 0; j < WNOR_NP; j++) {
            double ph = dphi * ((double)j + 0.5);
            size_t k = (i * WNOR_NP) + j;
            q->ax[k] = st * cos(ph);
            q->ay[k] = st * sin(ph);
            q->az[k] = ct;
            q->w[k] = p / ct; /* the 1/<a,n> of the projected radiance [3] */
            total += p;       /* normalisation of P [3] */
        }
    }
    gsl_integration_glfixed_table_free(gl);
    for (j = 0; j < WNOR_NODES; j++) {
        q->w[j] /= total;
    }
    return BF_OK;
}

/* 1 - f(x, n) for a facet with cos x = c in (0, 1] and n >= 1 (SPEC §4.1;
 * from air, so no total internal reflection). */
static inline double wnor_trans(double c, double n)
{
    double s2 = (1.0 - c) * (1.0 + c);           /* sin^2 x */
    double ct = sqrt(1.0 - (s2 / (n * n)));      /* cos of the refracted */
    return 1.0 - bf__fresnel_s2ct(s2, c, ct, n); /* SPEC §4.1 */
}

/* WNO-R at one configuration: l, v unit vectors in the frame of the
 * quadrature's azimuths (see eval_wnor), l[2] = <l,n> > 0. The facet loop is branch-free so that it vectorises (the
 * file is built like src/fit/kernels.c: -O3, one clone per ISA); the terms
 * are then summed in a fixed order (8 interleaved partial sums), so the
 * value has the same bits on every ISA and thread count. */
BF__CLONES
static double wnor_value(const wnor_nodes *q, const double l[3],
                         const double v[3], double n)
{
    double term[WNOR_NODES];
    double acc[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double cl = l[2];
    double cv = v[2];
    double inv_cv = (cv > 0.0) ? 1.0 / cv : 0.0;
    double sum = 0.0;
    size_t k;
    size_t j;
    /* <a,v> G / <v,n> [3], [4] is min(<a,v>, 2 <a,n> <v,n>, 2 <a,n> <l,n>
     * <a,v> / <a,l>) / <v,n>; at grazing view (<v,n> = 0) its limit is
     * 2 <a,n> (0 when the light is grazing too, never here: cl > 0). The
     * first two arguments are scaled by 1/<v,n> up front so that one loop
     * serves both cases: mv = <a,v>/<v,n> (+inf at grazing view) and
     * 2 <a,n>, the shadowing term times 1/<v,n>. */
    double ms = (cv > 0.0) ? inv_cv : HUGE_VAL;
#pragma omp simd
    for (k = 0; k < WNOR_NODES; k++) {
        double az = q->az[k];
        double al = (q->ax[k] * l[0]) + (q->ay[k] * l[1]) + (az * l[2]);
        double av = (q->ax[k] * v[0]) + (q->ay[k] * v[1]) + (az * v[2]);
        /* a facet unlit or turned away from the viewer gives nothing; the
         * stand-in 1 keeps its (discarded) arithmetic finite */
        int vis = (al > 0.0) & (av > 0.0);
        double als = vis ? al : 1.0;
        double avs = vis ? av : 1.0;
        double mv = avs * ms;                   /* <a,v> / <v,n> */
        double m2 = 2.0 * az;                   /* 2 <a,n> <v,n> / <v,n> */
        double m3 = m2 * cl * (avs / als) * ms; /* shadowing / <v,n> */
        double gav = (mv < m2) ? mv : m2;
        double t;
        gav = (m3 < gav) ? m3 : gav;
        /* P L_f <a,v> G / (<a,n> <v,n>), [1]-[4] */
        t = q->w[k] * als * wnor_trans(als, n) * wnor_trans(avs, n) * gav;
        term[k] = vis ? t : 0.0;
    }
    for (k = 0; k < WNOR_NODES; k += 8) {
        for (j = 0; j < 8; j++) {
            acc[j] += term[k + j];
        }
    }
    for (j = 0; j < 8; j++) {
        sum += acc[j];
    }
    return sum;
}

/* Evaluates WNO-R at param = {sigma, n}; both checked by bf_model_eval.
 * sigma = 0 is the smooth surface: WNO itself. */
static int eval_wnor(const double *param, size_t count, const bf_geom *geom,
                     double *out)
{
    double sigma = param[0];
    double n = param[1];
    wnor_nodes *q;
    size_t k;
    if (sigma == 0.0) {
        return eval_wno(&param[1], count, geom, out); /* level facets */
    }
    q = malloc(sizeof *q);
    if ((q == NULL) || (wnor_nodes_init(sigma, q) != BF_OK)) {
        free(q);
        for (k = 0; k < count; k++) {
            out[k] = NAN;
        }
        return BF_ENOMEM;
    }
    for (k = 0; k < count; k++) {
        bf__trig_t tr;
        double l[3];
        double v[3];
        double delta;
        double w;
        bf__geom_trig(&geom[k], &tr);
        /* Beckmann's frame (SPEC §1.2) puts the source at phi = pi and the
         * view at phi_s. The azimuthal rule is turned to the geometry: its
         * origin goes to pi + w delta, delta = wrap(phi_s - pi), w = sin ts
         * / (sin ti + sin ts), i.e. l at azimuth -w delta and v at (1 - w)
         * delta relative to the nodes. At normal incidence (w = 1) or view
         * (w = 0) the undefined azimuth then drops out exactly; swapping l
         * and v gives the same rule (reciprocity to rounding); at the wrap
         * delta = +-pi (forward plane) both choices are mirror images of a
         * mirror-symmetric geometry, so the value is continuous there. */
        delta = atan2(-tr.sp, -tr.cp); /* wrap(phi_s - pi) */
        w = (tr.si + tr.ss > 0.0) ? tr.ss / (tr.si + tr.ss) : 0.0;
        l[0] = tr.si * cos(-w * delta);
        l[1] = tr.si * sin(-w * delta);
        l[2] = tr.ci;
        v[0] = tr.ss * cos((1.0 - w) * delta);
        v[1] = tr.ss * sin((1.0 - w) * delta);
        v[2] = tr.cs;
        out[k] = (tr.ci > 0.0) ? wnor_value(q, l, v, n) : 0.0;
    }
    free(q);
    return BF_OK;
}

/* sigma as Oren-Nayar's (radians, [0, pi/2]), fitted over [0, 1.55] step
 * 0.05; n as WNO's, over [1.2, 2.5] step 0.1. The grid is coarse because
 * one evaluation is a quadrature of 1152 facets per configuration; the
 * exact fit (--fit exact) refines it. */
static const bf_param param_wnor[2] = {
    {"sigma", "facet slope sigma", "rad", 0.0, BF__PI_2, 0.0, 1, 0.0, 0.05,
     32},
    {"n", "refractive index n", "1", 1.0, 10.0, BF_DEFAULT_N, 1, BF_FREE_N_LO,
     0.1, 14},
};

static const bf_model_type wnor_type = {
    "WNO-R", "Wolff-Nayar-Oren rough dielectric (V-cavities of WNO facets)",
    "Wolff, Nayar & Oren IJCV 1998; Oren & Nayar IJCV 1995; "
    "Torrance & Sparrow JOSA 1967; SPEC §4.1, §5; doc/methods.md §7",
    2, param_wnor, eval_wnor};

const bf_model_type *const bf_model_wno_r = &wnor_type;
