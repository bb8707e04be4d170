/* wno_r.c: WNO-R, the Wolff-Nayar-Oren model of rough dielectrics -- a
 * V-cavity surface whose facets each reflect by WNO (the smooth model of
 * src/models/wolff_nayar_oren.c), evaluated by quadrature.
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
 * The quadrature rule (src/models/wno_r_rule.c) is each configuration's
 * own, split at the kinks of the integrand, and the same for every sigma
 * and n: with ring weights q_i(sigma) = exp(-t_i^2 / (2 sigma^2)) w_i,
 *   L(sigma, n) = sum_i q_i(sigma) B_i(n) / (cos t_i 2 pi sum_i q_i),
 * B_i the ring sums of facet values. P is normalised by the same rule, so
 * sigma -> 0 tends to WNO; sigma = 0 is WNO exactly. Within 2e-9 of
 * GSL's adaptive quadrature relative to the value on CURET's 205
 * configurations (doc/methods.md §7; tested against 1e-8). bf_model_eval runs the rule;
 * the engine's kernel interpolates its values in (sigma, n) from tables of
 * a configuration set, each n-panel's built the first time it is needed
 * (below).
 *
 * Limits: the value vanishes at theta_i = pi/2 (the shadowing term 2
 * <a,n><l,n>/<a,l> = 0). n = 1 gives the direct Oren-Nayar surface with
 * Lambertian facets; sigma = 0 gives WNO. At grazing view (<v,n> = 0) the
 * limit is taken: <a,v> G / <v,n> -> 2 <a,n> for every visible facet.
 * Finite and >= 0 on the whole closed hemisphere.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"
#include "models/wno_r_rule.h"

/* ==== the configurations ================================================= */

/* The source and view directions of one configuration in the frame of the
 * rule's azimuths (l[2] = cos ti, v[2] = cos ts). Beckmann's frame (SPEC
 * §1.2) puts the source at phi = pi and the view at phi_s; here l lies at
 * azimuth -w delta and v at (1 - w) delta, delta = wrap(phi_s - pi), w =
 * sin ts / (sin ti + sin ts). At normal incidence (w = 1) or view (w = 0)
 * the undefined azimuth then drops out exactly, and swapping l and v gives
 * the mirror image of the same rule (reciprocity to rounding). */
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

/* One configuration's rule and its ring sums and weights. */
typedef struct {
    wnor_kinks kc;
    wnor_theta th;
    wnor_ring rg;
    double b[WNOR_MAX_RINGS];
    double c[WNOR_MAX_RINGS];
} wnor_direct;

/* The rule of configuration (l, v) and its ring sums at index n into d
 * (l[2] > 0). */
static void direct_sums(const double l[3], const double v[3], double n,
                        wnor_direct *d)
{
    size_t i;
    bf__wnor_kinks(l, v, &d->kc);
    bf__wnor_theta(&d->kc, l[2], v[2], &d->th);
    for (i = 0; i < d->th.nr; i++) {
        bf__wnor_ring(&d->kc, d->th.t[i], &d->rg);
        d->b[i] = bf__wnor_ring_sum(d->rg.ax, d->rg.ay, d->rg.az, d->rg.wp,
                                    d->rg.m, l, v, n);
    }
}

/* The value at sigma > 0 from direct_sums' ring sums. */
static double direct_value(wnor_direct *d, double sigma)
{
    double s = 0.0;
    size_t i;
    bf__wnor_weights(&d->th, sigma, d->c);
    for (i = 0; i < d->th.nr; i++) {
        s += d->c[i] * d->b[i];
    }
    return s;
}

/* Evaluates WNO-R at param = {sigma, n}; both checked by bf_model_eval.
 * sigma = 0 is the smooth surface: WNO itself. */
static int eval_wnor(const double *param, size_t count, const bf_geom *geom,
                     double *out, void *work)
{
    double sigma = param[0];
    double n = param[1];
    wnor_direct *d = work;
    size_t k;
    if (sigma == 0.0) { /* level facets: WNO, [2], (P6) */
        return bf_model_wno->eval(&param[1], count, geom, out, NULL);
    }
    for (k = 0; k < count; k++) {
        bf__trig_t tr;
        double l[3];
        double v[3];
        bf__geom_trig(&geom[k], &tr);
        wnor_dirs(&tr, l, v);
        out[k] = 0.0; /* theta_i = pi/2: the shadowing term vanishes */
        if (tr.ci > 0.0) {
            direct_sums(l, v, n, d);
            out[k] = direct_value(d, sigma);
        }
    }
    return BF_OK;
}

/* ==== the engine's kernel: Chebyshev tables in sigma and n ============== */

/* Terms: l and v of wnor_dirs (6 rows of n), the sines and cosines of WNO
 * (sigma = 0; 4 rows). */
enum { R_L0 = 0, R_L1, R_L2, R_V0, R_V1, R_V2, R_SI, R_CI, R_SS, R_CS,
       R_NT };

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
}

/* Each configuration's value is analytic in n > 1 and in sigma > 0, and in
 * sigma^2 near 0 (the rule's nodes do not move with either): on each
 * panel of (sigma, n) it is its two-dimensional Chebyshev series. In n
 * the singularities are the Fresnel factors' branch points n = +-sin x
 * (x a facet's angle, SPEC §4.1), all in [-1, 1]: in the variable w =
 * ln(n - 1) they lie on Im w = +-pi, so a panel [w0 - h, w0 + h] has
 * Bernstein ellipses up to rho = pi/h + sqrt(pi^2/h^2 + 1) and its
 * degree-d series errs by O(rho^-d). Two n-panels: [1.1, 2.6] (the fit's
 * grid and box, rho = 4.7) and [2.6, 10.1] (rho = 7.3), degree 24
 * (4.7^-24 = 6e-17); sigma-panels [0, s1] in the variable sigma^2 (s1 =
 * pi/2^9: within it the value is a polynomial in sigma^2 to rounding) and
 * [s1 2^(p-1), s1 2^p] for p = 1..8 in sigma, 16 nodes each. A table
 * holds the coefficients of one n-panel for every sigma-panel and
 * configuration, built the first time an n in it is needed: a fit inside
 * the grid's box builds one. Below n = 1.1 the values at the sigma-nodes
 * come from the rule directly. */
#define WNOR_NQ 2
#define WNOR_ND 25 /* n-nodes per panel: degree 24 */
#define WNOR_NPS 9 /* sigma-panels */
#define WNOR_NS 16 /* sigma-nodes per panel */
#define WNOR_S1 (BF__PI_2 / 256.0)
#define WNOR_NSN (WNOR_NPS * WNOR_NS)
static const double n_edge[WNOR_NQ + 1] = {1.1, 2.6, 10.1};

/* The position of n in n-panel q in the variable ln(n - 1), in [-1, 1]
 * inside. */
static double n_pos(int q, double n)
{
    double a = log(n_edge[q] - 1.0);
    double b = log(n_edge[q + 1] - 1.0);
    return (2.0 * log(n - 1.0) - a - b) / (b - a);
}

/* The n of position y in panel q (n_pos inverted). */
static double n_node(int q, double y)
{
    double a = log(n_edge[q] - 1.0);
    double b = log(n_edge[q + 1] - 1.0);
    return 1.0 + exp((0.5 * (a + b)) + (0.5 * (b - a) * y));
}

/* The n-panel of n and its position y in [-1, 1], or -1 outside. */
static int n_panel(double n, double *y)
{
    int q;
    for (q = 0; q < WNOR_NQ; q++) {
        if (n >= n_edge[q] && n < n_edge[q + 1]) {
            *y = n_pos(q, n);
            return q;
        }
    }
    return -1;
}

/* The sigma-panel of sigma in (0, pi/2] and its position y in [-1, 1]. */
static int s_panel(double sigma, double *y)
{
    int e;
    double lo;
    if (sigma <= WNOR_S1) {
        *y = 2.0 * (sigma / WNOR_S1) * (sigma / WNOR_S1) - 1.0;
        return 0;
    }
    (void)frexp(sigma / WNOR_S1, &e); /* in [2^(e-1), 2^e) */
    e = e > WNOR_NPS - 1 ? WNOR_NPS - 1 : e;
    lo = ldexp(WNOR_S1, e - 1);
    *y = (2.0 * sigma - 3.0 * lo) / lo;
    return e;
}

/* Chebyshev node j of m on [-1, 1]. */
static double cheb_node(size_t j, size_t m)
{
    return cos(BF__PI * ((double)j + 0.5) / (double)m);
}

/* sigma-node j of panel p. */
static double s_node(int p, size_t j)
{
    double y = cheb_node(j, WNOR_NS);
    double lo = ldexp(WNOR_S1, p - 1);
    return p == 0 ? WNOR_S1 * sqrt(0.5 * (1.0 + y)) : 0.5 * lo * (3.0 + y);
}

/* The matrix of cheb_coef for m nodes: cm[d * m + j] = (2 - [d = 0]) / m
 * cos(pi d (j + 1/2) / m). */
static void cheb_matrix(size_t m, double *cm)
{
    size_t d;
    size_t j;
    for (d = 0; d < m; d++) {
        for (j = 0; j < m; j++) {
            cm[d * m + j] = (d == 0 ? 1.0 : 2.0) / (double)m *
                            cos(BF__PI * (double)d * ((double)j + 0.5) /
                                (double)m);
        }
    }
}

/* Chebyshev coefficients of m values f[j * step] at the nodes, into
 * c[d]: c_d = sum_j cm[d m + j] f_j (cheb_matrix). */
static void cheb_coef(const double *cm, const double *f, size_t m,
                      size_t step, double *c)
{
    size_t d;
    size_t j;
    for (d = 0; d < m; d++) {
        double s = 0.0;
        for (j = 0; j < m; j++) {
            s += cm[d * m + j] * f[j * step];
        }
        c[d] = s;
    }
}

/* T_0..T_(m-1) at y. */
static void cheb_t(double y, size_t m, double *t)
{
    size_t d;
    t[0] = 1.0;
    t[1] = y;
    for (d = 2; d < m; d++) {
        t[d] = 2.0 * y * t[d - 1] - t[d - 2];
    }
}

typedef struct {
    int built[WNOR_NQ];    /* published with an atomic write */
    double *coef[WNOR_NQ]; /* [((k NPS + p) NS + js) ND + d] */
} wnor_tables;

static int wnor_prepare(bf__prep *pm)
{
    pm->cache = calloc(1, sizeof(wnor_tables));
    return pm->cache != NULL ? BF_OK : BF_ENOMEM;
}

static void wnor_release(bf__prep *pm)
{
    wnor_tables *tb = pm->cache;
    size_t q;
    for (q = 0; q < WNOR_NQ; q++) {
        free(tb->coef[q]);
    }
    free(tb);
}

/* Configuration k's l and v from the terms. */
static void term_dirs(const bf__prep *pm, size_t k, double *l, double *v)
{
    const double *t = pm->terms;
    size_t n = pm->n;
    l[0] = t[R_L0 * n + k];
    l[1] = t[R_L1 * n + k];
    l[2] = t[R_L2 * n + k];
    v[0] = t[R_V0 * n + k];
    v[1] = t[R_V1 * n + k];
    v[2] = t[R_V2 * n + k];
}

/* The scratch of a table's build: one configuration's rule, its facets,
 * the weights of its rings at every sigma-node, its values. */
typedef struct {
    wnor_direct d;
    size_t start[WNOR_MAX_RINGS + 1];
    double *ax, *ay, *az, *wp; /* WNOR_MAX_RINGS x WNOR_MAX_RF */
    double cw[WNOR_MAX_RINGS][WNOR_NSN]; /* ring weights at the nodes */
    double c[WNOR_MAX_RINGS];
    double val[WNOR_ND][WNOR_NSN];
    double cn[WNOR_NSN][WNOR_ND];
    double cm_n[WNOR_ND * WNOR_ND];     /* cheb_matrix */
    double cm_s[WNOR_NS * WNOR_NS];
} wnor_build;

/* Configuration k's part of n-panel q's table: its values at every
 * (sigma-node, n-node), then their two-dimensional coefficients. */
BF__CLONES
static void build_config(const bf__prep *pm, size_t k, int q, wnor_build *s,
                         double *coef)
{
    double l[3];
    double v[3];
    size_t i;
    size_t j;
    size_t r;
    size_t p;
    size_t d;
    term_dirs(pm, k, l, v);
    if (!(l[2] > 0.0)) { /* theta_i = pi/2: L = 0 */
        memset(coef, 0, WNOR_NSN * WNOR_ND * sizeof *coef);
        return;
    }
    bf__wnor_kinks(l, v, &s->d.kc);
    bf__wnor_theta(&s->d.kc, l[2], v[2], &s->d.th);
    s->start[0] = 0;
    for (r = 0; r < s->d.th.nr; r++) { /* the facets, once for all n */
        size_t o = s->start[r];
        bf__wnor_ring(&s->d.kc, s->d.th.t[r], &s->d.rg);
        memcpy(s->ax + o, s->d.rg.ax, s->d.rg.m * sizeof(double));
        memcpy(s->ay + o, s->d.rg.ay, s->d.rg.m * sizeof(double));
        memcpy(s->az + o, s->d.rg.az, s->d.rg.m * sizeof(double));
        memcpy(s->wp + o, s->d.rg.wp, s->d.rg.m * sizeof(double));
        s->start[r + 1] = o + s->d.rg.m;
    }
    for (j = 0; j < WNOR_NSN; j++) {
        bf__wnor_weights(&s->d.th, s_node((int)(j / WNOR_NS), j % WNOR_NS),
                         s->c);
        for (r = 0; r < s->d.th.nr; r++) {
            s->cw[r][j] = s->c[r];
        }
    }
    for (i = 0; i < WNOR_ND; i++) {
        double n = n_node(q, cheb_node(i, WNOR_ND));
        double *val = s->val[i];
        for (j = 0; j < WNOR_NSN; j++) {
            val[j] = 0.0;
        }
        for (r = 0; r < s->d.th.nr; r++) { /* sum_r c_r b_r, r ascending */
            size_t o = s->start[r];
            double b = bf__wnor_ring_sum(s->ax + o, s->ay + o, s->az + o,
                                         s->wp + o, s->start[r + 1] - o, l,
                                         v, n);
            const double *cw = s->cw[r];
#pragma omp simd
            for (j = 0; j < WNOR_NSN; j++) {
                val[j] += cw[j] * b;
            }
        }
    }
    for (j = 0; j < WNOR_NSN; j++) { /* in n */
        cheb_coef(s->cm_n, &s->val[0][j], WNOR_ND, WNOR_NSN, s->cn[j]);
    }
    for (p = 0; p < WNOR_NPS; p++) { /* in sigma, panel by panel */
        for (d = 0; d < WNOR_ND; d++) {
            double f[WNOR_NS];
            double c[WNOR_NS];
            for (j = 0; j < WNOR_NS; j++) {
                f[j] = s->cn[p * WNOR_NS + j][d];
            }
            cheb_coef(s->cm_s, f, WNOR_NS, 1, c);
            for (j = 0; j < WNOR_NS; j++) {
                coef[((p * WNOR_NS + j) * WNOR_ND) + d] = c[j];
            }
        }
    }
}

/* Builds n-panel q's table. NULL when out of memory. */
static double *build_panel(const bf__prep *pm, int q)
{
    size_t cap = (size_t)WNOR_MAX_RINGS * WNOR_MAX_RF;
    double *coef = malloc((size_t)WNOR_NSN * WNOR_ND * pm->n * sizeof *coef);
    wnor_build *s = malloc(sizeof *s);
    double *facets = malloc(4 * cap * sizeof *facets);
    size_t k;
    if (coef == NULL || s == NULL || facets == NULL) {
        free(coef);
        free(s);
        free(facets);
        return NULL;
    }
    s->ax = facets;
    s->ay = facets + cap;
    s->az = facets + 2 * cap;
    s->wp = facets + 3 * cap;
    cheb_matrix(WNOR_ND, s->cm_n);
    cheb_matrix(WNOR_NS, s->cm_s);
    for (k = 0; k < pm->n; k++) {
        build_config(pm, k, q, s, coef + k * WNOR_NSN * WNOR_ND);
    }
    free(s);
    free(facets);
    return coef;
}

/* The table of n-panel q, built on first use (under a lock; every thread
 * then reads it). NULL when out of memory. */
static const double *panel_table(const bf__prep *pm, int q)
{
    wnor_tables *tb = pm->cache;
    int built;
#pragma omp atomic read
    built = tb->built[q];
    if (!built) {
#pragma omp critical(bf_wnor_tables)
        {
            if (!tb->built[q]) {
                tb->coef[q] = build_panel(pm, q);
                if (tb->coef[q] != NULL) {
#pragma omp atomic write
                    tb->built[q] = 1;
                }
            }
        }
#pragma omp atomic read
        built = tb->built[q];
    }
    return built ? tb->coef[q] : NULL;
}

/* The workspace: for the most recently used (n, sigma-panel) pairs (up to
 * WNOR_SLOTS, fewer for large K: slots()) the sigma-series of every
 * configuration at that n, b[js * K + k]. A refinement comes back to the
 * same few n -- its start, the grid values either side, the bound --
 * replicate after replicate, so the least recently used slot is the one
 * replaced. A slot's content is a function of its key alone, so hits and
 * misses give the same bits. */
#define WNOR_SLOTS 8
#define WNOR_SLOT_BYTES (4u << 20) /* all slots of a workspace, at most */
typedef struct {
    wnor_direct d; /* the rule itself, for n outside the panels */
    double n[WNOR_SLOTS];
    int sp[WNOR_SLOTS];
    unsigned long last[WNOR_SLOTS]; /* use stamp, 0: empty */
    unsigned long clock;
    double b[];    /* slots(K) x WNOR_NS x K */
} wnor_work;

/* Slots of a workspace on n configurations: as many as fit
 * WNOR_SLOT_BYTES, between 2 and WNOR_SLOTS. */
static size_t slots(size_t n)
{
    size_t per = WNOR_NS * n * sizeof(double);
    size_t s = WNOR_SLOT_BYTES / per;
    return s < 2 ? 2 : (s > WNOR_SLOTS ? WNOR_SLOTS : s);
}

static size_t wnor_work_bytes(const bf_kernel *kr, size_t n)
{
    (void)kr;
    return sizeof(wnor_work) + slots(n) * WNOR_NS * n * sizeof(double);
}

/* out[k] = sum_r t[r] rows[r K + k] for k < K, r ascending from 0. */
static inline void weighted_rows(const double *restrict rows, size_t m,
                                 const double *t, size_t K,
                                 double *restrict out)
{
    size_t r;
    size_t k;
    for (k = 0; k < K; k++) {
        out[k] = 0.0;
    }
    for (r = 0; r < m; r++) {
        const double *restrict row = rows + r * K;
        double c = t[r];
#pragma omp simd
        for (k = 0; k < K; k++) {
            out[k] += c * row[k];
        }
    }
}

/* The sigma-series of every configuration at n on sigma-panel p from n's
 * table: the series in n of each coefficient, summed from degree 0 up
 * (each configuration's block of the table is contiguous). */
BF__CLONES
static void series_slot(const double *restrict c, size_t K, int p, double y,
                        double *restrict b)
{
    double tn[WNOR_ND];
    size_t js;
    size_t k;
    size_t d;
    cheb_t(y, WNOR_ND, tn);
    for (k = 0; k < K; k++) {
        const double *restrict ck =
            c + ((k * WNOR_NPS + (size_t)p) * WNOR_NS) * WNOR_ND;
        for (js = 0; js < WNOR_NS; js++) {
            const double *restrict cj = ck + js * WNOR_ND;
            double acc = 0.0;
            for (d = 0; d < WNOR_ND; d++) {
                acc += tn[d] * cj[d];
            }
            b[js * K + k] = acc;
        }
    }
}

/* The same from the rule directly (n outside the panels). */
static void direct_slot(const bf__prep *pm, double n, int p, wnor_direct *d,
                        double *b)
{
    size_t K = pm->n;
    size_t k;
    size_t j;
    double cm[WNOR_NS * WNOR_NS];
    cheb_matrix(WNOR_NS, cm);
    for (k = 0; k < K; k++) {
        double l[3];
        double v[3];
        double f[WNOR_NS] = {0.0};
        double c[WNOR_NS];
        term_dirs(pm, k, l, v);
        if (l[2] > 0.0) {
            direct_sums(l, v, n, d);
            for (j = 0; j < WNOR_NS; j++) {
                f[j] = direct_value(d, s_node(p, j));
            }
        }
        cheb_coef(cm, f, WNOR_NS, 1, c);
        for (j = 0; j < WNOR_NS; j++) {
            b[j * K + k] = c[j];
        }
    }
}

/* The sigma-series at (n, sigma-panel p), cached. NULL when out of
 * memory. */
static const double *wnor_slot(const bf__prep *pm, double n, int p,
                               wnor_work *w)
{
    size_t K = pm->n;
    size_t count = slots(K);
    size_t slot;
    size_t old = 0;
    double y;
    int q;
    double *b;
    for (slot = 0; slot < count; slot++) {
        if (w->last[slot] != 0 && w->n[slot] == n && w->sp[slot] == p) {
            w->last[slot] = ++w->clock;
            return w->b + slot * WNOR_NS * K;
        }
        old = w->last[slot] < w->last[old] ? slot : old;
    }
    slot = old; /* the least recently used (or an empty one) */
    b = w->b + slot * WNOR_NS * K;
    q = n_panel(n, &y);
    if (q < 0) {
        direct_slot(pm, n, p, &w->d, b);
    } else {
        const double *c = panel_table(pm, q);
        if (c == NULL) {
            return NULL;
        }
        series_slot(c, K, p, y, b);
    }
    w->last[slot] = ++w->clock;
    w->n[slot] = n;
    w->sp[slot] = p;
    return b;
}

/* The values of eval_wnor from the tables: the sigma-series at n (cached),
 * summed at sigma. */
BF__CLONES
static int wnor_values(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    const double *t = pm->terms;
    size_t K = pm->n;
    wnor_work *w = work;
    double ts[WNOR_NS];
    double y;
    const double *b;
    size_t k;
    int p;
    if (param[0] == 0.0) { /* level facets: WNO, [2], (P6) */
        bf__fc2_values(K, t + R_SI * K, t + R_CI * K, t + R_SS * K,
                       t + R_CS * K, param[1], out);
        return BF_OK;
    }
    p = s_panel(param[0], &y);
    b = wnor_slot(pm, param[1], p, w);
    if (b == NULL) {
        for (k = 0; k < K; k++) {
            out[k] = NAN; /* out of memory for a table */
        }
        return BF_EDOM;
    }
    cheb_t(y, WNOR_NS, ts);
    weighted_rows(b, WNOR_NS, ts, K, out);
    return BF_OK;
}

static const bf_kernel wnor_kernel = {
    .n_terms = R_NT,
    .n_extra = 0,
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
     .input = BF_INPUT_INDEX},
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
    .work_size = sizeof(wnor_direct),
    .kernel = &wnor_kernel,
    .style = 10,
    .reduces_to = "WNO",
    .reduces_param = 0,
    .reduces_at = 0.0,
};

const bf_model_type *const bf_model_wno_r = &wnor_type;
