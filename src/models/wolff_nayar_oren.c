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

static const bf_kernel wno_kernel = {F_NT, 0, wno_terms, NULL, wno_values,
                                     NULL, BF__BLOCK_NONE, 0, 0};

/* n is fitted over [1.2, 2.5] (typical dielectrics, SPEC §4.2), step 0.01;
 * the domain is that of FC's n. */
static const bf_param param_wno[1] = {
    {"n", "refractive index n", "1", 1.0, 10.0, BF_DEFAULT_N, 1, BF_FREE_N_LO,
     0.01, 131, BF_INPUT_DEFAULT, 0, 0.0, 0.0, 0.0},
};

static const bf_model_type wno_type = {
    "WNO", "Wolff-Nayar-Oren smooth dielectric diffuse (Wolff 1994)",
    "Wolff JOSA A 1994; Wolff, Nayar & Oren IJCV 1998; SPEC §4; "
    "doc/methods.md §7",
    1, param_wno, eval_wno, 0, &wno_kernel, 9, NULL, 0, 0.0};

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

/* The 24-point Gauss-Legendre rule on [-1, 1] as GSL's
 * gsl_integration_glfixed_table_alloc(24) computes it (positive abscissae
 * x and weights w, GSL's layout), so that evaluations allocate nothing;
 * tests/models/test_wno_r.c checks every bit against GSL's table. Not
 * const only because GSL's table struct points to non-const doubles; never
 * written. */
static double gl24_x[WNOR_NT / 2] = {
    0x1.0660853eda2e7p-4, 0x1.8769542b94f8dp-3, 0x1.429a8c588e91p-2,
    0x1.bc345d81e24b5p-2, 0x1.17417bac4d72bp-1, 0x1.4bd2ee5fa1086p-1,
    0x1.7af18edb9ddd6p-1, 0x1.a3d74ce0d37p-1,   0x1.c5d841864d0f5p-1,
    0x1.e06585a70aa4dp-1, 0x1.f30f9f0cbf876p-1, 0x1.fd892de691983p-1};
static double gl24_w[WNOR_NT / 2] = {
    0x1.060475e763733p-3, 0x1.01b7117cf8bd5p-3, 0x1.f25cbce1d1ff3p-4,
    0x1.d91c78acb1b22p-4, 0x1.b8177ba4a68cdp-4, 0x1.8fd8936444b1ep-4,
    0x1.6108ef5044636p-4, 0x1.2c6d5c2eff068p-4, 0x1.e5c6255d25ed5p-5,
    0x1.6ab884f57c974p-5, 0x1.d375514486f1bp-6, 0x1.9465bd31121c8p-7};

void bf__wnor_gl24(const double **x, const double **w)
{
    *x = gl24_x;
    *w = gl24_w;
}

/* Fills the nodes for sigma > 0 (no allocation: GSL's point function on
 * the table above). */
static void wnor_nodes_init(double sigma, wnor_nodes *q)
{
    gsl_integration_glfixed_table gl;
    double tmax = fmin(BF__PI_2, 6.0 * sigma);
    double dphi = 2.0 * BF__PI / WNOR_NP;
    double total = 0.0;
    size_t i;
    size_t j;
    gl.n = WNOR_NT;
    gl.x = gl24_x;
    gl.w = gl24_w;
    gl.precomputed = 1;
    for (i = 0; i < WNOR_NT; i++) {
        double t;
        double wt;
        double st;
        double ct;
        double p;
        gsl_integration_glfixed_point(0.0, tmax, i, &t, &wt, &gl);
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
    for (j = 0; j < WNOR_NODES; j++) {
        q->w[j] /= total;
    }
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

/* The source and view directions of one configuration in the frame of
 * the quadrature's azimuths (l[2] = cos ti, v[2] = cos ts). Beckmann's
 * frame (SPEC §1.2) puts the source at phi = pi and the view at phi_s.
 * The azimuthal rule is turned to the geometry: its origin goes to pi + w
 * delta, delta = wrap(phi_s - pi), w = sin ts / (sin ti + sin ts), i.e. l
 * at azimuth -w delta and v at (1 - w) delta relative to the nodes. At
 * normal incidence (w = 1) or view (w = 0) the undefined azimuth then
 * drops out exactly; swapping l and v gives the same rule (reciprocity to
 * rounding); at the wrap delta = +-pi (forward plane) both choices are
 * mirror images of a mirror-symmetric geometry, so the value is
 * continuous there. */
static void wnor_dirs(const bf__trig_t *tr, double *l, double *v)
{
    double delta = atan2(-tr->sp, -tr->cp); /* wrap(phi_s - pi) */
    double w = (tr->si + tr->ss > 0.0) ? tr->ss / (tr->si + tr->ss) : 0.0;
    l[0] = tr->si * cos(-w * delta);
    l[1] = tr->si * sin(-w * delta);
    l[2] = tr->ci;
    v[0] = tr->ss * cos((1.0 - w) * delta);
    v[1] = tr->ss * sin((1.0 - w) * delta);
    v[2] = tr->cs;
}

/* Evaluates WNO-R at param = {sigma, n}; both checked by bf_model_eval.
 * sigma = 0 is the smooth surface: WNO itself. work: a wnor_nodes. */
static int eval_wnor(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    double sigma = param[0];
    double n = param[1];
    wnor_nodes *q = work;
    size_t k;
    if (sigma == 0.0) {
        return eval_wno(&param[1], count, geom, out, NULL); /* level facets */
    }
    wnor_nodes_init(sigma, q);
    for (k = 0; k < count; k++) {
        bf__trig_t tr;
        double l[3];
        double v[3];
        bf__geom_trig(&geom[k], &tr);
        wnor_dirs(&tr, l, v);
        out[k] = (tr.ci > 0.0) ? wnor_value(q, l, v, n) : 0.0;
    }
    return BF_OK;
}

/* ==== WNO-R's kernel ====================================================== */

/* Terms: l and v of wnor_dirs (6 rows of n), then the trig rows of WNO
 * (sigma = 0). The workspace keeps the nodes of the last sigma. */
enum { R_L0 = 0, R_L1, R_L2, R_V0, R_V1, R_V2, R_TRIG, R_NT = R_TRIG + F_NT };

static void wnor_terms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t n = cs->n;
    size_t k;
    (void)kr;
    for (k = 0; k < n; k++) {
        double l[3];
        double v[3];
        wnor_dirs(&cs->trig[k], l, v);
        terms[R_L0 * n + k] = l[0];
        terms[R_L1 * n + k] = l[1];
        terms[R_L2 * n + k] = l[2];
        terms[R_V0 * n + k] = v[0];
        terms[R_V1 * n + k] = v[1];
        terms[R_V2 * n + k] = v[2];
    }
    trig_rows(cs, terms + R_TRIG * n, n);
}

typedef struct {
    double valid; /* 1 once q holds the nodes of sigma */
    double sigma;
    wnor_nodes q;
} wnor_work;

static size_t wnor_work_bytes(const bf_kernel *kr, size_t n)
{
    (void)kr;
    (void)n;
    return sizeof(wnor_work);
}

/* The values of eval_wnor, bit for bit, from the terms. */
static int wnor_values(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    const double *t = pm->terms;
    size_t n = pm->n;
    wnor_work *w = work;
    size_t k;
    if (param[0] == 0.0) {
        wno_rows(pm, t + R_TRIG * n, param[1], out); /* level facets */
        return BF_OK;
    }
    if (!(w->valid == 1.0 && w->sigma == param[0])) {
        wnor_nodes_init(param[0], &w->q);
        w->valid = 1.0;
        w->sigma = param[0];
    }
    for (k = 0; k < n; k++) {
        double l[3] = {t[R_L0 * n + k], t[R_L1 * n + k], t[R_L2 * n + k]};
        double v[3] = {t[R_V0 * n + k], t[R_V1 * n + k], t[R_V2 * n + k]};
        out[k] = (l[2] > 0.0) ? wnor_value(&w->q, l, v, param[1]) : 0.0;
    }
    return BF_OK;
}

static const bf_kernel wnor_kernel = {R_NT, 0, wnor_terms, wnor_work_bytes,
                                      wnor_values, NULL, BF__BLOCK_NONE, 0,
                                      0};

/* sigma as Oren-Nayar's (radians, [0, pi/2]), fitted over [0, 1.55] step
 * 0.05; n as WNO's, over [1.2, 2.5] step 0.1. The grid is coarse because
 * one evaluation is a quadrature of 1152 facets per configuration; the
 * exact fit (--fit exact) refines it. */
static const bf_param param_wnor[2] = {
    {"sigma", "facet slope sigma", "rad", 0.0, BF__PI_2, 0.0, 1, 0.0, 0.05,
     32, BF_INPUT_DEFAULT, 0, 0.0, 0.0, 0.0},
    {"n", "refractive index n", "1", 1.0, 10.0, BF_DEFAULT_N, 1, BF_FREE_N_LO,
     0.1, 14, BF_INPUT_DEFAULT, 0, 0.0, 0.0, 0.0},
};

/* At sigma = 0 the facets are level: WNO itself. */
static const bf_model_type wnor_type = {
    "WNO-R", "Wolff-Nayar-Oren rough dielectric (V-cavities of WNO facets)",
    "Wolff, Nayar & Oren IJCV 1998; Oren & Nayar IJCV 1995; "
    "Torrance & Sparrow JOSA 1967; SPEC §4.1, §5; doc/methods.md §7",
    2, param_wnor, eval_wnor, sizeof(wnor_nodes), &wnor_kernel, 10, "WNO", 0,
    0.0};

const bf_model_type *const bf_model_wno_r = &wnor_type;
