/* wno_r.c: WNO-R, the Wolff-Nayar-Oren model of rough dielectrics -- a
 * V-cavity surface whose facets each reflect by WNO (the smooth model of
 * src/models/wolff_nayar_oren.c), evaluated by a fixed quadrature rule.
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
 *
 * Equations (n refractive index of the body, f of SPEC §4.1, T(x) =
 * 1 - f(x, n); T(asin(sin x / n), 1/n) = T(x) by Fresnel reciprocity, SPEC
 * §4.2):
 *   L = integral over facet normals a of
 *       P(a) L_f(a) <a,v> G(a) / (<a,n> <v,n>) d omega_a               [3]
 *   L_f(a) = rho <a,l> T(acos <a,l>) T(acos <a,v>)  (WNO on the facet)  [1,2]
 *   P(a) = c(sigma) exp(-theta_a^2 / (2 sigma^2)), integral of P = 1    [3]
 *   G = min(1, 2 <a,n><v,n>/<a,v>, 2 <a,n><l,n>/<a,l>)                  [4]
 *   (facets with <a,l> <= 0 or <a,v> <= 0 contribute nothing)
 * rho cancels in the normalisation (SPEC §2): the parameters are sigma
 * and n. It is the direct (single-scattering) component: light exchanged
 * between the facets of a cavity is not modelled; [1]'s closed-form
 * approximation to the integral is not used (doc/methods.md §7).
 *
 * The quadrature rule is fixed -- the same facet normals for every sigma:
 * theta_a by 4-point Gauss-Legendre on each of WNOR_PANELS panels of
 * [0, pi/2] whose widths double from pi/2^13 (so that narrow slope
 * distributions, sigma down to 1e-4, are resolved near the normal), phi_a
 * by WNOR_NP midpoints, turned to each configuration (wnor_dirs). P is
 * normalised by the same rule, so sigma -> 0 tends to WNO (the innermost
 * facets are tilted by 2.6e-5 rad) and sigma = 0 is WNO exactly. Because
 * the nodes do not move with sigma, sigma enters only through the weight
 * of each ring of facets:
 *   L(sigma, n) = sum_i q_i(sigma) B_i(n) / sum_i q_i(sigma) NP,
 *   q_i = exp(-(t_i^2 - t_0^2) / (2 sigma^2)) w_i sin t_i dphi,
 *   B_i(n) = (1 / cos t_i) sum_j [L_f <a,v> G / <v,n>] at (t_i, phi_j),
 * so L is smooth in sigma (a rule whose nodes scale with sigma makes the
 * value jump by up to 1e-5 whenever a node crosses a masking edge) and,
 * once the ring sums B_i(n) are known, any sigma costs one pass over the
 * rings. The rule agrees with GSL's adaptive quadrature to within 7e-4 of
 * the surface's normal-incidence value at the test's geometries (tested);
 * relative to the value it is up to 1.4e-2 off on CURET's sigma, n grids
 * (sigma = 1.55), because the kinks of G and of the visibility cut-offs
 * lie at places that differ per configuration (doc/methods.md §7).
 *
 * Limits: the value vanishes at theta_i = pi/2 (the shadowing term 2
 * <a,n><l,n>/<a,l> = 0). n = 1 gives the direct Oren-Nayar surface with
 * Lambertian facets; sigma = 0 gives WNO. At grazing view (<v,n> = 0) the
 * limit is taken: <a,v> G / <v,n> -> 2 <a,n> for every visible facet.
 * Finite and >= 0 on the whole closed hemisphere.
 */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* ==== the rule =========================================================== */

#define WNOR_PANELS 12
#define WNOR_GL 4
#define WNOR_NT (WNOR_PANELS * WNOR_GL) /* rings of facets (theta_a) */
#define WNOR_NP 48                      /* facets per ring (phi_a) */
#define WNOR_NODES (WNOR_NT * WNOR_NP)

/* The 4-point Gauss-Legendre rule on [-1, 1]: GSL's precomputed table of
 * gsl_integration_glfixed_table_alloc(4) (positive abscissae x, weights
 * w), bit for bit (tests/models/test_wno_r.c checks it). Not const only
 * because GSL's struct points to non-const doubles; never written. */
static double gl4_x[WNOR_GL / 2] = {0x1.5c23fd9dd3dfcp-2,
                                    0x1.b8e6dbcf63985p-1};
static double gl4_w[WNOR_GL / 2] = {0x1.4de5f840c24cap-1,
                                    0x1.64340f7e7b66bp-2};

void bf__wnor_gl4(const double **x, const double **w)
{
    *x = gl4_x;
    *w = gl4_w;
}

/* The facets of the rule: normals (ring-major, ring i at j in [i * NP,
 * (i + 1) * NP)) and per ring its tilt, the sigma-independent part of its
 * weight, and 1 / cos t. */
typedef struct {
    double ax[WNOR_NODES];
    double ay[WNOR_NODES];
    double az[WNOR_NODES];
    double t[WNOR_NT];
    double ws[WNOR_NT];     /* w_i sin t_i dphi */
    double inv_ct[WNOR_NT]; /* 1 / cos t_i, the 1/<a,n> of [3] */
} wnor_rule;

/* Fills the rule (no allocation: GSL's point function on the table). */
static void wnor_rule_init(wnor_rule *r)
{
    gsl_integration_glfixed_table gl;
    double dphi = 2.0 * BF__PI / WNOR_NP;
    size_t p;
    size_t i;
    size_t j;
    gl.n = WNOR_GL;
    gl.x = gl4_x;
    gl.w = gl4_w;
    gl.precomputed = 1;
    for (p = 0; p < WNOR_PANELS; p++) {
        /* panel p: [pi/2 2^(p-P), pi/2 2^(p+1-P)], the first from 0 */
        double a = p == 0 ? 0.0 : BF__PI_2 * ldexp(1.0, (int)p - WNOR_PANELS);
        double b = BF__PI_2 * ldexp(1.0, (int)p + 1 - WNOR_PANELS);
        for (i = 0; i < WNOR_GL; i++) {
            size_t ring = p * WNOR_GL + i;
            double wt;
            gsl_integration_glfixed_point(a, b, i, &r->t[ring], &wt, &gl);
            r->ws[ring] = wt * sin(r->t[ring]) * dphi; /* P's d omega */
            r->inv_ct[ring] = 1.0 / cos(r->t[ring]);
        }
    }
    for (i = 0; i < WNOR_NT; i++) {
        double st = sin(r->t[i]);
        double ct = cos(r->t[i]); /* > 0: Gauss nodes are interior */
        for (j = 0; j < WNOR_NP; j++) {
            double ph = dphi * ((double)j + 0.5);
            size_t k = (i * WNOR_NP) + j;
            r->ax[k] = st * cos(ph);
            r->ay[k] = st * sin(ph);
            r->az[k] = ct;
        }
    }
}

/* The weights of the rings for sigma > 0, normalised with 1/cos t folded
 * in: c_i = q_i / cos t_i / sum_i q_i NP. The exponents are taken relative
 * to the innermost ring so that no weight underflows for tiny sigma. */
static void wnor_weights(const wnor_rule *r, double sigma, double *c)
{
    double total = 0.0;
    double t0 = r->t[0];
    size_t i;
    for (i = 0; i < WNOR_NT; i++) {
        double d = (r->t[i] - t0) * (r->t[i] + t0); /* t^2 - t0^2 */
        c[i] = exp(-d / (2.0 * sigma * sigma)) * r->ws[i]; /* P d omega */
        total += c[i] * WNOR_NP;                           /* P's norm */
    }
    for (i = 0; i < WNOR_NT; i++) {
        c[i] = c[i] * r->inv_ct[i] / total;
    }
}

/* ==== the ring sums ====================================================== */

/* 1 - f(x, n) for a facet with cos x = c in (0, 1] and n >= 1, inv_n2 =
 * 1/n^2 (SPEC §4.1, from air, so no total internal reflection): f = 1/2
 * a^2 (1 + b^2) with a = (n ct - c)/(n ct + c), b = (n c ct - s^2)/(n c ct
 * + s^2) (bf__fresnel_s2ct), over one common denominator: one division
 * instead of two. */
static inline double wnor_trans(double c, double n, double inv_n2)
{
    double s2 = (1.0 - c) * (1.0 + c);     /* sin^2 x */
    double ct = sqrt(1.0 - (s2 * inv_n2)); /* cos of the refracted */
    double an = (n * ct) - c;              /* (P4), SPEC §4.1 */
    double ad = (n * ct) + c;
    double bn = (n * c * ct) - s2;
    double bd = (n * c * ct) + s2;
    double a2 = an * an;
    double bd2 = bd * bd;
    return 1.0 - (0.5 * a2 * (bd2 + (bn * bn)) / ((ad * ad) * bd2));
}

/* The ring sums of one configuration: b[i * stride] = sum over ring i's
 * facets of L_f <a,v> G / <v,n> ([1]-[4]; before the weights), l, v unit
 * vectors in the frame of the rule's azimuths, l[2] = <l,n> > 0. The facet
 * loop is branch-free and division-light so that it vectorises (the file
 * is built like src/fit/kernels.c: -O3, one clone per ISA); each ring is
 * summed in a fixed order (8 interleaved partial sums), so the value has
 * the same bits on every ISA and thread count. */
BF__CLONES
static void wnor_rings(const wnor_rule *r, const double l[3],
                       const double v[3], double n, double *b, size_t stride)
{
    double term[WNOR_NP];
    double cl = l[2];
    double cv = v[2];
    double inv_n2 = 1.0 / (n * n);
    /* <a,l> <a,v> G / <v,n> [3], [4] is min(<a,l> <a,v>, 2 <a,n> <v,n>
     * <a,l>, 2 <a,n> <l,n> <a,v>) / <v,n> (G's min multiplied by <a,l> >
     * 0, no division); at grazing view (<v,n> = 0) its limit is 2 <a,n>
     * <a,l> (the light is never grazing here: cl > 0). The arguments are
     * scaled by ms = 1/<v,n> up front (+inf at grazing view) so that one
     * loop serves both cases. */
    double ms = (cv > 0.0) ? 1.0 / cv : HUGE_VAL;
    size_t i;
    size_t j;
    size_t q;
    for (i = 0; i < WNOR_NT; i++) {
        const double *ax = r->ax + (i * WNOR_NP);
        const double *ay = r->ay + (i * WNOR_NP);
        const double *az = r->az + (i * WNOR_NP);
        double acc[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        double sum = 0.0;
#pragma omp simd
        for (j = 0; j < WNOR_NP; j++) {
            double al = (ax[j] * l[0]) + (ay[j] * l[1]) + (az[j] * l[2]);
            double av = (ax[j] * v[0]) + (ay[j] * v[1]) + (az[j] * v[2]);
            /* a facet unlit or turned away from the viewer gives nothing;
             * the stand-in 1 keeps its (discarded) arithmetic finite */
            int vis = (al > 0.0) & (av > 0.0);
            double als = vis ? al : 1.0;
            double avs = vis ? av : 1.0;
            double m2 = 2.0 * az[j];                /* 2 <a,n> */
            double g1 = (als * avs) * ms;           /* no masking */
            double g2 = (m2 * als);                 /* masking, x <a,l> */
            double g3 = (m2 * cl * avs) * ms;       /* shadowing */
            double gal = (g1 < g2) ? g1 : g2;
            double t;
            gal = (g3 < gal) ? g3 : gal;
            /* L_f <a,v> G / <v,n>, [1]-[4] */
            t = wnor_trans(als, n, inv_n2) * wnor_trans(avs, n, inv_n2) * gal;
            term[j] = vis ? t : 0.0;
        }
        for (j = 0; j < WNOR_NP; j += 8) {
            for (q = 0; q < 8; q++) {
                acc[q] += term[j + q];
            }
        }
        for (q = 0; q < 8; q++) {
            sum += acc[q];
        }
        b[i * stride] = sum;
    }
}

/* The value of one configuration from its ring sums and the weights. */
static double wnor_combine(const double *c, const double *b, size_t stride)
{
    double s = 0.0;
    size_t i;
    for (i = 0; i < WNOR_NT; i++) {
        s += c[i] * b[i * stride]; /* sum_i q_i B_i / sum q NP */
    }
    return s;
}

/* ==== the configurations ================================================= */

/* The source and view directions of one configuration in the frame of the
 * rule's azimuths (l[2] = cos ti, v[2] = cos ts). Beckmann's frame (SPEC
 * §1.2) puts the source at phi = pi and the view at phi_s. The azimuthal
 * rule is turned to the geometry: its origin goes to pi + w delta, delta =
 * wrap(phi_s - pi), w = sin ts / (sin ti + sin ts), i.e. l at azimuth -w
 * delta and v at (1 - w) delta relative to the nodes. At normal incidence
 * (w = 1) or view (w = 0) the undefined azimuth then drops out exactly;
 * swapping l and v gives the same rule (reciprocity to rounding); at the
 * wrap delta = +-pi (forward plane) both choices are mirror images of a
 * mirror-symmetric geometry, so the value is continuous there. */
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

/* ==== the reference path: bf_model_eval ================================== */

/* Workspace of eval_wnor: the rule, the ring weights, one ring-sum row. */
typedef struct {
    wnor_rule r;
    double c[WNOR_NT];
    double b[WNOR_NT];
} wnor_eval_work;

/* Evaluates WNO-R at param = {sigma, n}; both checked by bf_model_eval.
 * sigma = 0 is the smooth surface: WNO itself. */
static int eval_wnor(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    double sigma = param[0];
    double n = param[1];
    wnor_eval_work *w = work;
    size_t k;
    if (sigma == 0.0) { /* level facets: WNO, [2], (P6) */
        return bf_model_wno->eval(&param[1], count, geom, out, NULL);
    }
    wnor_rule_init(&w->r);
    wnor_weights(&w->r, sigma, w->c);
    for (k = 0; k < count; k++) {
        bf__trig_t tr;
        double l[3];
        double v[3];
        bf__geom_trig(&geom[k], &tr);
        wnor_dirs(&tr, l, v);
        out[k] = 0.0;
        if (tr.ci > 0.0) {
            wnor_rings(&w->r, l, v, n, w->b, 1);
            out[k] = wnor_combine(w->c, w->b, 1);
        }
    }
    return BF_OK;
}

/* ==== the engine's kernel ================================================= */

/* Terms: l and v of wnor_dirs (6 rows of n), the sines and cosines of WNO
 * (sigma = 0; 4 rows), then the rule (extra). */
enum { R_L0 = 0, R_L1, R_L2, R_V0, R_V1, R_V2, R_SI, R_CI, R_SS, R_CS,
       R_NT };
#define R_EXTRA ((sizeof(wnor_rule) + sizeof(double) - 1) / sizeof(double))

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
        terms[R_SI * n + k] = cs->trig[k].si;
        terms[R_CI * n + k] = cs->trig[k].ci;
        terms[R_SS * n + k] = cs->trig[k].ss;
        terms[R_CS * n + k] = cs->trig[k].cs;
    }
    wnor_rule_init((wnor_rule *)(void *)(terms + R_NT * n));
}

/* ==== the ring sums as Chebyshev series in n ============================ */

/* The ring sums B_i(n) of every configuration are analytic in n on n > 1
 * (their singularities lie at n = sqrt(1 - c^2) <= 1 for facet cosines
 * c): on each panel of n they are their Chebyshev series, to the last
 * bits. Panels: 0.1 wide from 1.1 to 2.6, 0.5 wide to 10.1; their degree
 * is where the coefficients fall to 1e-16 of the leading one for CURET's
 * geometry (tested against the exact sums at random n: within 2e-15 of
 * the curve's maximum). Below 1.1 the sums are taken exactly. A panel's
 * table is built the first time an n in it is needed: its Chebyshev nodes'
 * exact sums (the degree + 1 of them), then the coefficients. */
#define WNOR_N_LO 1.1
#define WNOR_N_MID 2.6
#define WNOR_N_HI 10.1
#define WNOR_NARROW 15  /* panels of 0.1 in [1.1, 2.6] */
#define WNOR_WIDE 15    /* panels of 0.5 in [2.6, 10.1] */
#define WNOR_NPANEL (WNOR_NARROW + WNOR_WIDE)
#define WNOR_DEG_MAX 19

/* The lower edge of panel p (p = WNOR_NPANEL: the upper end). */
static double panel_edge(int p)
{
    return p <= WNOR_NARROW ? WNOR_N_LO + 0.1 * p
                            : WNOR_N_MID + 0.5 * (p - WNOR_NARROW);
}

/* The panel of n, or -1 outside [1.1, 10.1); its ends and degree. The
 * edges are the doubles panel_edge gives, whatever the rounding of the
 * first guess. */
static int n_panel(double n, double *lo, double *hi, size_t *deg)
{
    int p;
    if (!(n >= WNOR_N_LO) || !(n < WNOR_N_HI)) {
        return -1;
    }
    p = n < WNOR_N_MID ? (int)floor((n - WNOR_N_LO) / 0.1)
                       : WNOR_NARROW + (int)floor((n - WNOR_N_MID) / 0.5);
    p = p < 0 ? 0 : (p >= WNOR_NPANEL ? WNOR_NPANEL - 1 : p);
    while (p > 0 && n < panel_edge(p)) {
        p--;
    }
    while (p + 1 < WNOR_NPANEL && n >= panel_edge(p + 1)) {
        p++;
    }
    *lo = panel_edge(p);
    *hi = panel_edge(p + 1);
    *deg = p == 0 ? WNOR_DEG_MAX : 15; /* [1.1, 1.2] nearest to 1 */
    return n >= *lo && n < *hi ? p : -1;
}

typedef struct {
    int built[WNOR_NPANEL];   /* published with an atomic write */
    double *coef[WNOR_NPANEL]; /* blocks of (deg + 1) x WNOR_EB */
} wnor_tables;

static int wnor_prepare(bf__prep *pm)
{
    pm->cache = calloc(1, sizeof(wnor_tables));
    return pm->cache != NULL ? BF_OK : BF_ENOMEM;
}

static void wnor_release(bf__prep *pm)
{
    wnor_tables *tb = pm->cache;
    size_t p;
    for (p = 0; p < WNOR_NPANEL; p++) {
        free(tb->coef[p]);
    }
    free(tb);
}

/* The exact ring sums of every configuration at n into b (WNOR_NT x K,
 * ring-major). */
static void exact_sums(const bf__prep *pm, double n_index, double *b)
{
    const double *t = pm->terms;
    const wnor_rule *r = (const wnor_rule *)(const void *)(t + R_NT * pm->n);
    size_t n = pm->n;
    size_t k;
    size_t i;
    for (k = 0; k < n; k++) {
        double l[3] = {t[R_L0 * n + k], t[R_L1 * n + k], t[R_L2 * n + k]};
        double v[3] = {t[R_V0 * n + k], t[R_V1 * n + k], t[R_V2 * n + k]};
        if (l[2] > 0.0) {
            wnor_rings(r, l, v, n_index, b + k, n);
        } else {
            for (i = 0; i < WNOR_NT; i++) {
                b[i * n + k] = 0.0; /* theta_i = pi/2: L = 0 */
            }
        }
    }
}

/* Elements (ring sums) per block of a panel's table: each block holds its
 * coefficients of every degree together, highest degree first, c[(blk *
 * (deg + 1) + deg - d) * EB + j], so that series_sums reads one ascending
 * stream and keeps a block's sums in registers over the degrees. */
#define WNOR_EB 32

/* Blocks of a table of m elements. */
static size_t table_blocks(size_t m)
{
    return (m + WNOR_EB - 1) / WNOR_EB;
}

/* Builds panel p's table: the exact sums at its deg + 1 Chebyshev nodes,
 * then c_d = (2 - [d = 0]) / (deg + 1) sum_j B(n_j) cos(pi d (j + 1/2) /
 * (deg + 1)), stored by blocks (WNOR_EB; the last one padded with 0).
 * NULL when out of memory. */
static double *build_panel(const bf__prep *pm, double lo, double hi,
                           size_t deg)
{
    size_t m = WNOR_NT * pm->n;
    size_t nodes = deg + 1;
    double *vals = malloc(nodes * m * sizeof *vals);
    double *cd = calloc(m, sizeof *cd);
    double *coef = calloc(table_blocks(m) * nodes * WNOR_EB, sizeof *coef);
    size_t j;
    size_t d;
    size_t e;
    if (vals == NULL || cd == NULL || coef == NULL) {
        free(vals);
        free(cd);
        free(coef);
        return NULL;
    }
    for (j = 0; j < nodes; j++) {
        double x = cos(BF__PI * ((double)j + 0.5) / (double)nodes);
        exact_sums(pm, 0.5 * (lo + hi) + 0.5 * (hi - lo) * x, vals + j * m);
    }
    for (d = 0; d < nodes; d++) {
        double f = (d == 0 ? 1.0 : 2.0) / (double)nodes;
        memset(cd, 0, m * sizeof *cd);
        for (j = 0; j < nodes; j++) {
            double w = f * cos(BF__PI * (double)d * ((double)j + 0.5) /
                               (double)nodes);
            const double *vj = vals + j * m;
            for (e = 0; e < m; e++) {
                cd[e] += w * vj[e];
            }
        }
        for (e = 0; e < m; e++) {
            coef[((e / WNOR_EB) * nodes + (deg - d)) * WNOR_EB +
                 e % WNOR_EB] = cd[e];
        }
    }
    free(vals);
    free(cd);
    return coef;
}

/* The table of panel p, built on first use (under a lock; every thread
 * then reads it). NULL when out of memory. */
static const double *panel_table(const bf__prep *pm, int p, double lo,
                                 double hi, size_t deg)
{
    wnor_tables *tb = pm->cache;
    int built;
#pragma omp atomic read
    built = tb->built[p];
    if (!built) {
#pragma omp critical(bf_wnor_tables)
        {
            if (!tb->built[p]) {
                tb->coef[p] = build_panel(pm, lo, hi, deg);
                if (tb->coef[p] != NULL) {
#pragma omp atomic write
                    tb->built[p] = 1;
                }
            }
        }
#pragma omp atomic read
        built = tb->built[p];
    }
    return built ? tb->coef[p] : NULL;
}

/* The ring sums at n from panel table c (degree deg, on [lo, hi]): the
 * Chebyshev series sum_d c_d T_d(y), y the position in the panel, added
 * from the highest degree down (b = 0, then b += c_d T_d), one block of
 * WNOR_EB sums at a time. */
BF__CLONES
static void series_sums(const double *restrict c, size_t m, size_t deg,
                        double y, double *restrict b)
{
    double tdeg[WNOR_DEG_MAX + 1];
    size_t nodes = deg + 1;
    size_t blk;
    size_t d;
    size_t j;
    tdeg[0] = 1.0;
    tdeg[1] = y;
    for (d = 2; d <= deg; d++) {
        tdeg[d] = 2.0 * y * tdeg[d - 1] - tdeg[d - 2]; /* T_d(y) */
    }
    for (blk = 0; blk < table_blocks(m); blk++) {
        const double *restrict cb = c + blk * nodes * WNOR_EB;
        size_t width = m - blk * WNOR_EB < WNOR_EB ? m - blk * WNOR_EB
                                                   : WNOR_EB;
        double acc[WNOR_EB];
#pragma omp simd
        for (j = 0; j < WNOR_EB; j++) {
            acc[j] = 0.0 + cb[j] * tdeg[deg]; /* b = 0, b += c_deg T_deg */
        }
        for (d = deg; d-- > 0;) {
            const double *restrict cd = cb + (deg - d) * WNOR_EB;
            double td = tdeg[d];
#pragma omp simd
            for (j = 0; j < WNOR_EB; j++) {
                acc[j] += cd[j] * td;
            }
        }
        if (width == WNOR_EB) {
#pragma omp simd
            for (j = 0; j < WNOR_EB; j++) {
                b[blk * WNOR_EB + j] = acc[j];
            }
        } else {
            for (j = 0; j < width; j++) {
                b[blk * WNOR_EB + j] = acc[j];
            }
        }
    }
}

/* The workspace: the ring sums of the most recently used indices n (ring-
 * major rows of the configurations, b[i * K + k]; up to WNOR_SLOTS of
 * them, fewer for large K: slots()) and the weights of the last sigma. A
 * refinement comes back to the same few n -- its start, the grid values
 * either side, the bound -- replicate after replicate, so the least
 * recently used slot is the one replaced. A slot's content is a function
 * of its n alone, so hits and misses give the same bits. */
#define WNOR_SLOTS 8
#define WNOR_SLOT_BYTES (4u << 20) /* all slots of a workspace, at most */
typedef struct {
    double sigma;             /* the weights' sigma (0: none yet) */
    double c[WNOR_NT];
    double n[WNOR_SLOTS];
    unsigned long last[WNOR_SLOTS]; /* use stamp, 0: empty */
    unsigned long clock;
    double b[];               /* slots(K) x WNOR_NT x K */
} wnor_work;

/* Slots of a workspace on n configurations: as many as fit
 * WNOR_SLOT_BYTES, between 2 and WNOR_SLOTS. */
static size_t slots(size_t n)
{
    size_t per = WNOR_NT * n * sizeof(double);
    size_t s = WNOR_SLOT_BYTES / per;
    return s < 2 ? 2 : (s > WNOR_SLOTS ? WNOR_SLOTS : s);
}

static size_t wnor_work_bytes(const bf_kernel *kr, size_t n)
{
    (void)kr;
    return sizeof(wnor_work) + slots(n) * WNOR_NT * n * sizeof(double);
}

/* The ring sums of every configuration at index n_index: from its panel's
 * series (the exact sums outside the panels). NULL when out of memory. */
static const double *wnor_sums(const bf__prep *pm, double n_index,
                               wnor_work *w)
{
    size_t n = pm->n;
    size_t count = slots(n);
    size_t slot;
    size_t old = 0;
    double lo;
    double hi;
    size_t deg;
    int p;
    double *b;
    for (slot = 0; slot < count; slot++) {
        if (w->last[slot] != 0 && w->n[slot] == n_index) {
            w->last[slot] = ++w->clock;
            return w->b + slot * WNOR_NT * n;
        }
        old = w->last[slot] < w->last[old] ? slot : old;
    }
    slot = old; /* the least recently used (or an empty one) */
    b = w->b + slot * WNOR_NT * n;
    p = n_panel(n_index, &lo, &hi, &deg);
    if (p < 0) {
        exact_sums(pm, n_index, b);
    } else {
        const double *c = panel_table(pm, p, lo, hi, deg);
        if (c == NULL) {
            return NULL;
        }
        series_sums(c, WNOR_NT * n, deg, (2.0 * n_index - lo - hi) / (hi - lo),
                    b);
    }
    w->last[slot] = ++w->clock;
    w->n[slot] = n_index;
    return b;
}

/* Configurations whose values wnor_values sums at once (in registers). */
#define WNOR_KB 32

/* The values of eval_wnor from the terms: the rings' sums at n (cached),
 * their weights at sigma (cached), one pass over the rings. */
BF__CLONES
static int wnor_values(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    const double *t = pm->terms;
    const wnor_rule *r = (const wnor_rule *)(const void *)(t + R_NT * pm->n);
    size_t n = pm->n;
    wnor_work *w = work;
    const double *b;
    size_t i;
    size_t k;
    size_t k0;
    if (param[0] == 0.0) { /* level facets: WNO, [2], (P6) */
        bf__fc2_values(n, t + R_SI * n, t + R_CI * n, t + R_SS * n,
                       t + R_CS * n, param[1], out);
        return BF_OK;
    }
    b = wnor_sums(pm, param[1], w);
    if (b == NULL) {
        for (k = 0; k < n; k++) {
            out[k] = NAN; /* out of memory for a table */
        }
        return BF_EDOM;
    }
    if (w->sigma != param[0]) {
        wnor_weights(r, param[0], w->c);
        w->sigma = param[0];
    }
    for (k0 = 0; k0 < n; k0 += WNOR_KB) { /* wnor_combine's order */
        double acc[WNOR_KB];
        size_t width = n - k0 < WNOR_KB ? n - k0 : WNOR_KB;
        if (width < WNOR_KB) {
            for (k = 0; k < width; k++) {
                out[k0 + k] = wnor_combine(w->c, b + k0 + k, n);
            }
            break;
        }
#pragma omp simd
        for (k = 0; k < WNOR_KB; k++) {
            acc[k] = 0.0 + w->c[0] * b[k0 + k]; /* s = 0, s += c_0 B_0 */
        }
        for (i = 1; i < WNOR_NT; i++) {
            const double *restrict bi = b + i * n + k0;
            double ci = w->c[i];
#pragma omp simd
            for (k = 0; k < WNOR_KB; k++) {
                acc[k] += ci * bi[k];
            }
        }
#pragma omp simd
        for (k = 0; k < WNOR_KB; k++) {
            out[k0 + k] = acc[k];
        }
    }
    return BF_OK;
}

static const bf_kernel wnor_kernel = {
    .n_terms = R_NT,
    .n_extra = R_EXTRA,
    .terms = wnor_terms,
    .work_bytes = wnor_work_bytes,
    .values = wnor_values,
    .cheap = 0,
    .prepare = wnor_prepare,
    .release = wnor_release,
};

/* ==== the type ============================================================ */

/* sigma as Oren-Nayar's (radians, [0, pi/2]), fitted over [0, 1.55] step
 * 0.05; n as WNO's, over [1.2, 2.5] step 0.1. */
static const bf_param param_wnor[2] = {
    {.name = "sigma", .label = "facet slope sigma", .unit = "rad",
     .min = 0.0, .max = BF__PI_2, .value = 0.0, .fitted = 1, .grid_lo = 0.0,
     .grid_step = 0.05, .grid_n = 32, .input = BF_INPUT_DEFAULT},
    {.name = "n", .label = "refractive index n", .unit = "1", .min = 1.0,
     .max = 10.0, .value = BF_DEFAULT_N, .fitted = 1,
     .grid_lo = BF_FREE_N_LO, .grid_step = 0.1, .grid_n = 14,
     .input = BF_INPUT_DEFAULT},
};

/* At sigma = 0 the facets are level: WNO itself. */
static const bf_model_type wnor_type = {
    .name = "WNO-R",
    .title = "Wolff-Nayar-Oren rough dielectric (V-cavities of WNO facets)",
    .reference = "Wolff, Nayar & Oren IJCV 1998; Oren & Nayar IJCV 1995; "
                 "Torrance & Sparrow JOSA 1967; SPEC §4.1, §5; "
                 "doc/methods.md §7",
    .p = 2,
    .param = param_wnor,
    .eval = eval_wnor,
    .work_size = sizeof(wnor_eval_work),
    .kernel = &wnor_kernel,
    .style = 10,
    .reduces_to = "WNO",
    .reduces_param = 0,
    .reduces_at = 0.0,
};

const bf_model_type *const bf_model_wno_r = &wnor_type;
