/* microfacet.c: the shared pieces of the specular models (SPEC §9.1,
 * §9.2): the vectors of a configuration, GGX's and Beckmann's D and
 * Lambda, the V-cavity masking and the evaluation loops. The equations and
 * the frame are listed in microfacet.h.
 *
 * References:
 *   [1] B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet
 *       models for refraction through rough surfaces", EGSR 2007
 *       (eqs. 25, 26, 33, 34).
 *   [2] E. Heitz, "Understanding the masking-shadowing function in
 *       microfacet-based BRDFs", JCGT 3(2), 2014 (eqs. 98, 99).
 *   [3] R. L. Cook, K. E. Torrance, ACM TOG 1(1), 1982 (V-cavity G).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "models/smith_lobe.h"

/* 1 / sqrt(pi) */
#define MF_1_SQRTPI 0.56418958354775628695

/* SPEC §9.1 in Beckmann's frame (microfacet.h): i = (-si, 0, ci),
 * o = (so cos phi_s, so sin phi_s, co). */
/* The zenith sines and cosines of the last configuration of this thread:
 * a quadrature over phi_s at fixed zeniths (albedo.c) asks for the same
 * two angles hundreds of times in a row. The same bits as computing them
 * (a pure function of the two angles, compared bit for bit). */
typedef struct {
    double ti, to, si, ci, so, co;
} zenith_memo_t;
static _Thread_local zenith_memo_t zenith_memo = {NAN, NAN, 0, 0, 0, 0};

static void zeniths(const bf_geom *g, bf__mf_t *m)
{
    zenith_memo_t *z = &zenith_memo;
    if (memcmp(&z->ti, &g->theta_i, sizeof z->ti) != 0 ||
        memcmp(&z->to, &g->theta_s, sizeof z->to) != 0) {
        z->ti = g->theta_i;
        z->to = g->theta_s;
        bf__zenith_sincos(g->theta_i, &z->si, &z->ci);
        bf__zenith_sincos(g->theta_s, &z->so, &z->co);
    }
    m->si = z->si;
    m->ci = z->ci;
    m->so = z->so;
    m->co = z->co;
}

/* sin(phi_s / 2), cos(phi_s / 2) and cos phi_s of the last PHI_MEMO
 * azimuths of this thread, direct-mapped by a hash of phi_s's bits: the
 * albedo's inner quadratures (albedo.c) evaluate the same Gauss-Kronrod
 * nodes in phi_s at every theta_o. The same bits as computing them. */
#define PHI_MEMO 2048u
typedef struct {
    uint64_t tag; /* the bits of phi_s plus 1; 0: empty */
    double hs, hc, c;
} phi_memo_t;
static _Thread_local phi_memo_t phi_memo[PHI_MEMO];

static void azimuth(double phi, double *hs, double *hc, double *c)
{
    uint64_t bits;
    phi_memo_t *e;
    memcpy(&bits, &phi, sizeof bits);
    e = &phi_memo[(bits * UINT64_C(0x9E3779B97F4A7C15)) >> 53];
    if (e->tag != bits + 1u) {
        e->tag = bits + 1u;
        e->hs = sin(0.5 * phi);
        e->hc = cos(0.5 * phi);
        e->c = cos(phi);
    }
    *hs = e->hs;
    *hc = e->hc;
    *c = e->c;
}

void bf__mf_geom(const bf_geom *g, bf__mf_t *m)
{
    double hs;
    double hc;
    double cp;
    double dso;
    double hxy2;
    double hz;
    double h2;
    double dz;
    double dxy2;
    zeniths(g, m);
    azimuth(g->phi_s, &hs, &hc, &cp);
    m->dxy = -(m->si * m->so) * cp; /* ix ox + iy oy */
    dso = m->so - m->si;
    hz = m->ci + m->co; /* H = i + o */
    if (hz == 0.0) {
        /* the grazing corner: h undefined (microfacet.h) */
        m->c2h = m->s2h = m->t2h = m->ch = m->cd = m->sd = 0.0;
        return;
    }
    hxy2 = (dso * dso) + (4.0 * (m->si * m->so) * (hs * hs));
    h2 = hxy2 + (hz * hz); /* |H|^2 = 4 cos^2 theta_d */
    m->c2h = (hz * hz) / h2;
    m->s2h = hxy2 / h2;
    m->t2h = hxy2 / (hz * hz);
    m->ch = hz / sqrt(h2);
    m->cd = fmin(1.0, 0.5 * sqrt(h2));
    dz = m->ci - m->co; /* d = i - o, |d| = 2 sin theta_d */
    dxy2 = (dso * dso) + (4.0 * (m->si * m->so) * (hc * hc));
    m->sd = fmin(1.0, 0.5 * sqrt(dxy2 + (dz * dz)));
}

int bf__mf_eval(const double *param, size_t n, const bf_geom *geom,
                double *out, bf__mf_value_fn f)
{
    int rc = BF_OK;
    size_t k;
    for (k = 0; k < n; k++) {
        bf__mf_t m;
        bf__mf_geom(&geom[k], &m);
        out[k] = f(&m, param);
        if (isnan(out[k])) {
            rc = BF_EDOM;
        }
    }
    return rc;
}

void bf__mf_kterms(const bf_kernel *kr, const bf__cset *cs, double *terms)
{
    size_t n = cs->n;
    size_t k;
    (void)kr;
    for (k = 0; k < n; k++) {
        bf__mf_t m;
        bf__mf_geom(&cs->geom[k], &m);
        terms[(BF__MF_CI * n) + k] = m.ci;
        terms[(BF__MF_CO * n) + k] = m.co;
        terms[(BF__MF_SI * n) + k] = m.si;
        terms[(BF__MF_SO * n) + k] = m.so;
        terms[(BF__MF_C2H * n) + k] = m.c2h;
        terms[(BF__MF_S2H * n) + k] = m.s2h;
        terms[(BF__MF_T2H * n) + k] = m.t2h;
        terms[(BF__MF_CH * n) + k] = m.ch;
        terms[(BF__MF_CD * n) + k] = m.cd;
        terms[(BF__MF_SD * n) + k] = m.sd;
        terms[(BF__MF_DXY * n) + k] = m.dxy;
    }
}

/* Walter et al. eq. 33 (SPEC §9.2), cos^4 th multiplied out. */
double bf__mf_d_ggx(const bf__mf_t *m, double alpha)
{
    double a2 = alpha * alpha;
    double q = (a2 * m->c2h) + m->s2h;
    return a2 / (BF__PI * q * q);
}

/* Walter et al. eq. 25 (SPEC §9.2). */
double bf__mf_d_beckmann(const bf__mf_t *m, double alpha)
{
    double a2 = alpha * alpha;
    return bf__mf_exp_neg(-m->t2h / a2) / (BF__PI * a2 * (m->c2h * m->c2h));
}

/* cos theta Lambda of Walter et al. eq. 34 (SPEC §9.2), microfacet.h. */
double bf__mf_clambda_ggx(double c, double s, double alpha)
{
    double a2s2 = (alpha * s) * (alpha * s);
    return a2s2 / (2.0 * (sqrt((c * c) + a2s2) + c));
}

/* cos theta Lambda of SPEC §9.2's exact Beckmann form (Walter et al.
 * eq. 26 before its rational approximation, eq. 27), microfacet.h. */
static double clambda_beckmann(double c, double s, double alpha)
{
    double as = alpha * s;
    double a;
    if (s == 0.0) {
        return 0.0; /* the normal: Lambda = 0 */
    }
    a = c / as;
    if (a >= 28.0) {
        return 0.0; /* erfc(a) and exp(-a^2) are +0 in double there */
    }
    return fmax(0.0, 0.5 * ((as * bf__mf_exp_neg(-(a * a)) * MF_1_SQRTPI)
                            - (c * erfc(a))));
}

/* c Lambda of the last LAMBDA_MEMO (c, s, alpha) of this thread, direct-
 * mapped by a hash of c's and alpha's bits: a lobe asks for Lambda(i) and
 * Lambda(o) at every configuration, and measured data have few zeniths
 * (the Cornell files' 1439 configurations: 8 incident and 10 outgoing),
 * which recur at every evaluation -- as do the albedo's quadrature nodes
 * (albedo.c). The same bits as computing them (a pure function, its
 * arguments compared bit for bit). */
#define LAMBDA_MEMO 256u
typedef struct {
    double key[3]; /* c, s, alpha */
    double val;
} lambda_memo_t;
/* All zero at first: the entry of (+0, +0, +0), whose value is 0 (s = 0),
 * so an entry never read is never wrong. */
static _Thread_local lambda_memo_t lambda_memo[LAMBDA_MEMO];

double bf__mf_clambda_beckmann(double c, double s, double alpha)
{
    const double key[3] = {c, s, alpha};
    uint64_t bc;
    uint64_t ba;
    lambda_memo_t *e;
    memcpy(&bc, &c, sizeof bc);
    memcpy(&ba, &alpha, sizeof ba);
    e = &lambda_memo[((bc ^ (ba * UINT64_C(0xC2B2AE3D27D4EB4F))) *
                      UINT64_C(0x9E3779B97F4A7C15)) >> 56];
    if (memcmp(e->key, key, sizeof key) != 0) {
        memcpy(e->key, key, sizeof key);
        e->val = clambda_beckmann(c, s, alpha);
    }
    return e->val;
}

double bf__mf_lambda_ggx(double theta, double alpha)
{
    double s;
    double c;
    bf__zenith_sincos(theta, &s, &c);
    return bf__mf_clambda_ggx(c, s, alpha) / c;
}

double bf__mf_lambda_beckmann(double theta, double alpha)
{
    double s;
    double c;
    bf__zenith_sincos(theta, &s, &c);
    return bf__mf_clambda_beckmann(c, s, alpha) / c;
}

/* SPEC §9.2's V-cavity G over 4 ci co (microfacet.h). */
double bf__mf_gv_over(const bf__mf_t *m)
{
    double a = 4.0 * (m->ci * m->co);
    double mx = fmax(m->ci, m->co);
    if ((2.0 * m->cd * mx) <= (a * m->ch)) {
        return 1.0 / a; /* G = 1 */
    }
    return m->ch / (2.0 * m->cd * mx);
}

/* The parameters of the Fresnel options (smith_lobe.h), SPEC §9.3. */
const bf_param bf__mf_param_schlick[3] = {BF__PARAM_RHO_S, BF__PARAM_ALPHA,
                                          BF__PARAM_F0};
const bf_param bf__mf_param_dielectric[3] = {BF__PARAM_RHO_S,
                                             BF__PARAM_ALPHA, BF__PARAM_N};
const bf_param bf__mf_param_none[2] = {BF__PARAM_RHO_S, BF__PARAM_ALPHA};
