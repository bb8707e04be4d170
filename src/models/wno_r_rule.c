/* wno_r_rule.c: WNO-R's quadrature rule of one configuration (the model
 * and its equations [1]-[4]: src/models/wno_r.c; doc/methods.md §7).
 *
 * The integrand has kinks on five great circles of facet normals,
 * <a,m> = 0 for m = l, v (a facet turns unlit or unseen), 2 <v,n> n - v and
 * 2 <l,n> n - l (a masking or shadowing term of G reaches 1 [4]) and
 * <v,n> l - <l,n> v (the two terms cross); elsewhere it is analytic (the
 * Fresnel factors are, for n > 1 from air). The rule splits at all of
 * them, per configuration:
 *   - theta_a: at the edges of 15 panels of [0, pi/2] whose widths double
 *     from pi/2^14 (narrow slope distributions, sigma down to 1e-4), at
 *     pi/2 - theta_i and pi/2 - theta_s, where a circle touches the ring of
 *     tilt theta_a (above it the ring's integral has a (theta - theta0)^
 *     {3/2} term), and at the tilts where two circles cross;
 *   - phi_a: each ring at its crossings with the circles (the fifth, the
 *     crossing of G's two terms, only where they are below 1: elsewhere
 *     G = 1 on both sides), and no piece wider than pi/2. Pieces unlit or
 *     unseen throughout are left out (their facets give 0). A ring that
 *     crosses no circle (the rings near the normal) is periodic and
 *     analytic in phi_a: the trapezoid rule on it, with as many points as
 *     its strip of analyticity needs (smooth_ring).
 * WNOR_Q-point Gauss-Legendre on every piece; a theta piece that starts at
 * a tangency ts, or less than its width above one, is mapped theta = ts +
 * u^2, which turns the half-integer powers into odd powers of u, so that
 * Gauss-Legendre converges there as fast as elsewhere. The nodes do not depend on sigma
 * or n: the value is smooth in both, and sigma enters only through the
 * weights of the rings (bf__wnor_weights). */
#include "models/wno_r_rule.h"

#include <math.h>
#include <string.h>

#include "internal.h"

/* Breakpoints of theta_a closer than this are one (bf__wnor_theta). */
#define WNOR_MERGE 1e-5

/* The WNOR_Q = 12 point Gauss-Legendre rule on [-1, 1], ascending: GSL's
 * precomputed table of gsl_integration_glfixed_table_alloc(12) (its
 * positive abscissae and their weights) mirrored, bit for bit
 * (tests/models/test_wno_r.c checks it). */
static const double gl_x[WNOR_Q] = {
    -0x1.f68f1d8e42e81p-1, -0x1.cee874ffb88b4p-1, -0x1.8a30aeed88f36p-1,
    -0x1.2cb4f05c077f9p-1, -0x1.78a8d20a8b19dp-2, -0x1.007a5f8f630e4p-3,
    0x1.007a5f8f630e4p-3,  0x1.78a8d20a8b19dp-2,  0x1.2cb4f05c077f9p-1,
    0x1.8a30aeed88f36p-1,  0x1.cee874ffb88b4p-1,  0x1.f68f1d8e42e81p-1};
static const double gl_w[WNOR_Q] = {
    0x1.8275d9dea6d8fp-5, 0x1.b60602bce6181p-4, 0x1.47d7258f22d8fp-3,
    0x1.a0163e6b1ab72p-3, 0x1.de3155c256ab5p-3, 0x1.fe40ce6d4f025p-3,
    0x1.fe40ce6d4f025p-3, 0x1.de3155c256ab5p-3, 0x1.a0163e6b1ab72p-3,
    0x1.47d7258f22d8fp-3, 0x1.b60602bce6181p-4, 0x1.8275d9dea6d8fp-5};

void bf__wnor_gl(const double **x, const double **w)
{
    *x = gl_x;
    *w = gl_w;
}

void bf__wnor_kinks(const double l[3], const double v[3], wnor_kinks *kc)
{
    double m[5][3] = {{l[0], l[1], l[2]},
                      {v[0], v[1], v[2]},
                      {-v[0], -v[1], v[2]},
                      {-l[0], -l[1], l[2]},
                      {(v[2] * l[0]) - (l[2] * v[0]),
                       (v[2] * l[1]) - (l[2] * v[1]), 0.0}};
    size_t i;
    kc->nc = 0;
    kc->cross = 5;
    for (i = 0; i < 5; i++) {
        /* the fifth vanishes in the plane of incidence's backscatter
         * (l = v: masking and shadowing are one term) */
        if (hypot(hypot(m[i][0], m[i][1]), m[i][2]) > 1e-12) {
            memcpy(kc->m[kc->nc], m[i], sizeof m[i]);
            kc->r[kc->nc] = hypot(m[i][0], m[i][1]);
            kc->psi[kc->nc] = atan2(m[i][1], m[i][0]);
            kc->cross = i == 4 ? kc->nc : kc->cross;
            kc->nc++;
        }
    }
}

/* Sorts x[0..n) ascending (insertion: n <= 32), carrying flag f. */
static void sort2(double *x, int *f, size_t n)
{
    size_t i;
    for (i = 1; i < n; i++) {
        double xi = x[i];
        int fi = f[i];
        size_t j = i;
        while (j > 0 && x[j - 1] > xi) {
            x[j] = x[j - 1];
            f[j] = f[j - 1];
            j--;
        }
        x[j] = xi;
        f[j] = fi;
    }
}

/* Adds tilt t to the breakpoints when it lies inside (0, pi/2). */
static void add_point(double t, int tangency, double *x, int *f, size_t *n)
{
    if (t > 0.0 && t < BF__PI_2 && *n < WNOR_MAX_TP + 1) {
        x[*n] = t;
        f[*n] = tangency;
        (*n)++;
    }
}

void bf__wnor_theta(const wnor_kinks *kc, double cl, double cv,
                    wnor_theta *th)
{
    double x[WNOR_MAX_TP + 2];
    int f[WNOR_MAX_TP + 2];
    size_t n = 0;
    size_t i;
    size_t j;
    size_t p;
    size_t kept;
    x[n] = 0.0;
    f[n++] = 0;
    for (i = 0; i <= 14; i++) { /* the geometric panels' edges */
        x[n] = BF__PI_2 * ldexp(1.0, (int)i - 14);
        f[n++] = 0;
    }
    add_point(asin(cl), 1, x, f, &n); /* pi/2 - theta_i */
    add_point(asin(cv), 1, x, f, &n); /* pi/2 - theta_s */
    for (i = 0; i < kc->nc; i++) {
        for (j = i + 1; j < kc->nc; j++) {
            const double *a = kc->m[i];
            const double *b = kc->m[j];
            double c[3] = {(a[1] * b[2]) - (a[2] * b[1]),
                           (a[2] * b[0]) - (a[0] * b[2]),
                           (a[0] * b[1]) - (a[1] * b[0])};
            double h = hypot(c[0], c[1]);
            if (hypot(h, c[2]) > 1e-12) { /* the circles cross */
                add_point(atan2(h, fabs(c[2])), 0, x, f, &n);
            }
        }
    }
    sort2(x, f, n);
    /* Points closer than WNOR_MERGE are one; a tangency wins (its place and
     * its flag): CURET's angles repeat to 6 digits (0.589048, 0.589049),
     * so a tangency can lie 1e-6 from a panel edge or from the other
     * tangency, and a piece that began there would start just above the
     * singularity. Merging two tangencies at most WNOR_MERGE apart leaves
     * the other's singularity within WNOR_MERGE of the piece's start: a
     * term of order WNOR_MERGE^2 relative. */
    kept = 1;
    for (i = 1; i < n; i++) {
        double gap = x[i] - x[kept - 1];
        if (gap > WNOR_MERGE || (kept == 1 && gap > 1e-12)) {
            x[kept] = x[i]; /* 0 stays and takes no neighbour */
            f[kept++] = f[i];
        } else if (i == n - 1) {
            x[kept - 1] = x[i]; /* pi/2 stays: a singularity this near */
            f[kept - 1] = 0;    /* the end weighs below 1e-12 */
        } else if (f[i] && !f[kept - 1] && kept > 1) {
            x[kept - 1] = x[i];
            f[kept - 1] = 1;
        }
    }
    th->nr = 0;
    for (p = 0; p + 1 < kept; p++) {
        double a = x[p];
        double b = x[p + 1];
        double ts = -1.0; /* the nearest tangency at or below a */
        for (i = 0; i <= p; i++) {
            ts = f[i] ? x[i] : ts;
        }
        /* within a piece's width above a tangency the (theta - ts)^(3/2)
         * term is near: theta = ts + u^2 makes it u^3 */
        if (ts >= 0.0 && a - ts >= b - a) {
            ts = -1.0;
        }
        for (j = 0; j < WNOR_Q; j++) {
            double gx = gl_x[j];
            double gw = gl_w[j];
            double t;
            double w;
            if (ts >= 0.0) { /* u in [sqrt(a - ts), sqrt(b - ts)] */
                double ua = sqrt(a - ts);
                double ub = sqrt(b - ts);
                double u = (0.5 * (ua + ub)) + (0.5 * (ub - ua) * gx);
                t = ts + (u * u);
                w = gw * (ub - ua) * u; /* d theta = 2 u du */
            } else {
                t = (0.5 * (a + b)) + (0.5 * (b - a) * gx);
                w = gw * 0.5 * (b - a);
            }
            th->t[th->nr] = t;
            th->w[th->nr] = w * sin(t); /* d omega's sin theta */
            th->inv_ct[th->nr] = 1.0 / cos(t); /* the 1/<a,n> of [3] */
            th->nr++;
        }
    }
}

/* sin u and cos u for |u| <= pi/4 by their Taylor series to u^17 and u^18
 * (the first terms left out are below 1e-19): no library call per facet. */
static inline void sincos_small(double u, double *su, double *cu)
{
    double z = u * u;
    double s = 1.0 / 355687428096000.0;
    double c = 1.0 / 6402373705728000.0;
    s = (s * z) - (1.0 / 1307674368000.0);
    s = (s * z) + (1.0 / 6227020800.0);
    s = (s * z) - (1.0 / 39916800.0);
    s = (s * z) + (1.0 / 362880.0);
    s = (s * z) - (1.0 / 5040.0);
    s = (s * z) + (1.0 / 120.0);
    s = (s * z) - (1.0 / 6.0);
    s = (s * z) + 1.0;
    c = (c * z) - (1.0 / 20922789888000.0);
    c = (c * z) + (1.0 / 87178291200.0);
    c = (c * z) - (1.0 / 479001600.0);
    c = (c * z) + (1.0 / 3628800.0);
    c = (c * z) - (1.0 / 40320.0);
    c = (c * z) + (1.0 / 720.0);
    c = (c * z) - (1.0 / 24.0);
    c = (c * z) + (1.0 / 2.0);
    *su = s * u;
    *cu = 1.0 - (c * z);
}

/* sin c and cos c for c in [-pi, 5 pi]: reduced to |r| <= pi/4 by the
 * nearest multiple q of pi/2, then turned by q quarter turns. */
static inline void sincos_any(double c, double *sc, double *cc)
{
    double q = floor((c / BF__PI_2) + 0.5);
    double su;
    double cu;
    int quad = ((int)q % 4 + 4) % 4;
    sincos_small(c - (q * BF__PI_2), &su, &cu);
    *sc = quad == 0 ? su : (quad == 1 ? cu : (quad == 2 ? -su : -cu));
    *cc = quad == 0 ? cu : (quad == 1 ? -su : (quad == 2 ? -cu : su));
}

/* Appends the WNOR_Q facets of the azimuths [a, b] (b - a <= pi/2) at
 * tilt (st, ct): cos(c + u) = cos c cos u - sin c sin u, and so on. */
static inline void ring_piece(double a, double b, double st, double ct,
                       wnor_ring *rg)
{
    double c = 0.5 * (a + b);
    double h = 0.5 * (b - a);
    double cc;
    double sc;
    double *ax = rg->ax + rg->m;
    double *ay = rg->ay + rg->m;
    double *az = rg->az + rg->m;
    double *wp = rg->wp + rg->m;
    size_t j;
    sincos_any(c, &sc, &cc);
#pragma omp simd
    for (j = 0; j < WNOR_Q; j++) {
        double su;
        double cu;
        sincos_small(h * gl_x[j], &su, &cu);
        ax[j] = st * ((cc * cu) - (sc * su));
        ay[j] = st * ((sc * cu) + (cc * su));
        az[j] = ct;
        wp[j] = gl_w[j] * h;
    }
    rg->m += WNOR_Q;
}

/* Whether the facet at azimuth ph of the ring (st, ct) is lit and seen
 * (<a,l> > 0 and <a,v> > 0; kc->m[0] = l, kc->m[1] = v: never left out).
 * The ring's pieces end at the circles <a,l> = 0 and <a,v> = 0, so a
 * piece's midpoint tells for the whole piece. */
static int piece_visible(const wnor_kinks *kc, double ph, double st,
                         double ct)
{
    double sp;
    double cp;
    double ax;
    double ay;
    int q;
    sincos_any(ph, &sp, &cp);
    ax = st * cp;
    ay = st * sp;
    for (q = 0; q < 2; q++) {
        const double *m = kc->m[q];
        if (!((ax * m[0]) + (ay * m[1]) + (ct * m[2]) > 0.0)) {
            return 0;
        }
    }
    return 1;
}

/* The kinks of the ring (st, ct) on the circle kc->cross (its pole
 * horizontal: the azimuths psi +- pi/2, in [0, 2 pi)) into k: those where
 * the masking term 2 <a,n><v,n>/<a,v> (there equal to the shadowing term)
 * is below 1, so that G switches between them; elsewhere G = 1 on both
 * sides. Returns how many. */
static size_t cross_kinks(const wnor_kinks *kc, double st, double ct,
                          double *k)
{
    const double *v = kc->m[1];
    size_t nk = 0;
    int s;
    for (s = -1; s <= 1; s += 2) {
        double ph = kc->psi[kc->cross] + (s * BF__PI_2);
        double sp;
        double cp;
        double av;
        ph = ph < 0.0 ? ph + 2.0 * BF__PI
                      : (ph >= 2.0 * BF__PI ? ph - 2.0 * BF__PI : ph);
        sincos_any(ph, &sp, &cp);
        av = (st * ((cp * v[0]) + (sp * v[1]))) + (ct * v[2]);
        if (!(2.0 * ct * v[2] >= av)) { /* masking below 1 (or unseen) */
            k[nk++] = ph;
        }
    }
    return nk;
}

/* A ring that crosses no kink circle: its integrand is periodic and
 * analytic in ph on the strip |Im ph| < ln rho (rho from the nearest
 * circle's complex crossing cos(ph - psi) = q, |q| >= 1, rho = |q| +
 * sqrt(q^2 - 1): a conservative bound, as the circles of <a,l>, <a,v> = 0
 * and of G's branches are kinks on the real ring only, and the Fresnel
 * factors' branch points <a,l>^2 = 1 - n^2 lie farther out), so the
 * M-point trapezoid rule errs by O(rho^-M) [Trefethen & Weideman, SIAM
 * Review 56(3), 2014, Thm 3.2]: M = 8 j points with rho^-M <= 1e-17,
 * at most WNOR_SMOOTH_MAX; 0 (the Gauss-Legendre pieces then) above. */
#define WNOR_SMOOTH_MAX 48
static int smooth_ring(const wnor_kinks *kc, double rho, double st,
                       double ct, wnor_ring *rg)
{
    double need = rho > 1.0 ? 39.2 / log(rho) : HUGE_VAL; /* 17 ln 10 */
    size_t m = 8;
    size_t j;
    while ((double)m < need && m < WNOR_SMOOTH_MAX) {
        m += 8;
    }
    if ((double)m < need) {
        return 0;
    }
    rg->m = 0;
    if (!piece_visible(kc, 0.0, st, ct)) {
        return 1; /* unlit or unseen all round */
    }
    for (j = 0; j < m / 4; j++) { /* the first quarter, ph in [0, pi/2) */
        size_t i = j <= m / 8 ? j : (m / 4) - j; /* from the nearer axis */
        double su;
        double cu;
        sincos_small(2.0 * BF__PI * (double)i / (double)m, &su, &cu);
        rg->ax[j] = j <= m / 8 ? cu : su;
        rg->ay[j] = j <= m / 8 ? su : cu;
    }
    for (j = m / 4; j < m; j++) { /* a quarter turn on: (x, y) -> (-y, x) */
        rg->ax[j] = -rg->ay[j - (m / 4)];
        rg->ay[j] = rg->ax[j - (m / 4)];
    }
    for (j = 0; j < m; j++) {
        rg->ax[j] *= st;
        rg->ay[j] *= st;
        rg->az[j] = ct;
        rg->wp[j] = 2.0 * BF__PI / (double)m;
    }
    rg->m = m;
    return 1;
}

BF__CLONES
void bf__wnor_ring(const wnor_kinks *kc, double t, wnor_ring *rg)
{
    double k[12];
    double st = sin(t);
    double ct = cos(t);
    size_t nk = 0;
    size_t i;
    double rho = HUGE_VAL; /* the smooth ring's strip of analyticity */
    for (i = 0; i < kc->nc; i++) {
        /* sin t (mx cos ph + my sin ph) + cos t mz = 0 */
        double q = kc->r[i] > 0.0 ? -(ct * kc->m[i][2]) / (st * kc->r[i])
                                  : HUGE_VAL;
        if (i == kc->cross) {
            /* through the normal (q = 0): G's terms cross at ph = psi +-
             * pi/2, a kink only where they are below 1 */
            nk += cross_kinks(kc, st, ct, k + nk);
        } else if (fabs(q) >= 1.0) {
            /* crossed at complex ph, Im ph = acosh |q| */
            double e = fabs(q) + sqrt((fabs(q) - 1.0) * (fabs(q) + 1.0));
            rho = e < rho ? e : rho;
        } else {
            double d = acos(q);
            double k1 = kc->psi[i] + d; /* in [-pi, 2 pi] */
            double k2 = kc->psi[i] - d; /* in [-2 pi, pi] */
            k[nk++] = k1 >= 2.0 * BF__PI ? k1 - 2.0 * BF__PI
                                         : (k1 < 0.0 ? k1 + 2.0 * BF__PI : k1);
            k[nk++] = k2 < 0.0 ? k2 + 2.0 * BF__PI : k2;
        }
    }
    for (i = 1; i < nk; i++) { /* insertion sort, nk <= 10 */
        double ki = k[i];
        size_t j = i;
        while (j > 0 && k[j - 1] > ki) {
            k[j] = k[j - 1];
            j--;
        }
        k[j] = ki;
    }
    if (nk == 0 && smooth_ring(kc, rho, st, ct, rg)) {
        return;
    }
    if (nk == 0) {
        k[nk++] = 0.0;
    }
    k[nk] = k[0] + 2.0 * BF__PI; /* the piece across the wrap */
    rg->m = 0;
    for (i = 0; i < nk; i++) {
        double a = k[i];
        double b = k[i + 1];
        size_t parts = (size_t)ceil((b - a) / BF__PI_2);
        size_t q;
        if (!(b > a)) {
            continue; /* two kinks at one azimuth */
        }
        if (!piece_visible(kc, 0.5 * (a + b), st, ct)) {
            continue; /* unlit or unseen throughout: its facets give 0 */
        }
        parts = parts < 1 ? 1 : parts;
        for (q = 0; q < parts; q++) {
            ring_piece(a + ((b - a) * (double)q / (double)parts),
                       a + ((b - a) * (double)(q + 1) / (double)parts), st,
                       ct, rg);
        }
    }
    while (rg->m % 8 != 0) { /* padding: weight 0, a finite normal */
        rg->ax[rg->m] = 0.0;
        rg->ay[rg->m] = 0.0;
        rg->az[rg->m] = 1.0;
        rg->wp[rg->m] = 0.0;
        rg->m++;
    }
}

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

/* The facet loop is branch-free and division-light so that it vectorises
 * (-O3, one clone per ISA); the ring is summed in a fixed order (8
 * interleaved partial sums), so the value has the same bits on every ISA
 * and thread count. */
BF__CLONES
double bf__wnor_ring_sum(const double *ax, const double *ay,
                         const double *az, const double *wp, size_t m,
                         const double l[3], const double v[3], double n)
{
    double term[WNOR_MAX_RF];
    double acc[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
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
    double sum = 0.0;
    size_t j;
    size_t q;
#pragma omp simd
    for (j = 0; j < m; j++) {
        double al = (ax[j] * l[0]) + (ay[j] * l[1]) + (az[j] * l[2]);
        double av = (ax[j] * v[0]) + (ay[j] * v[1]) + (az[j] * v[2]);
        /* a facet unlit or turned away from the viewer gives nothing;
         * the stand-in 1 keeps its (discarded) arithmetic finite */
        int vis = (al > 0.0) & (av > 0.0);
        double als = vis ? al : 1.0;
        double avs = vis ? av : 1.0;
        double m2 = 2.0 * az[j];          /* 2 <a,n> */
        double g1 = (als * avs) * ms;     /* no masking */
        double g2 = (m2 * als);           /* masking, x <a,l> */
        double g3 = (m2 * cl * avs) * ms; /* shadowing */
        double gal = (g1 < g2) ? g1 : g2;
        double t;
        gal = (g3 < gal) ? g3 : gal;
        /* L_f <a,v> G / <v,n>, [1]-[4] */
        t = wnor_trans(als, n, inv_n2) * wnor_trans(avs, n, inv_n2) * gal;
        term[j] = vis ? wp[j] * t : 0.0;
    }
    for (j = 0; j < m; j += 8) {
        for (q = 0; q < 8; q++) {
            acc[q] += term[j + q];
        }
    }
    for (q = 0; q < 8; q++) {
        sum += acc[q];
    }
    return sum;
}

void bf__wnor_weights(const wnor_theta *th, double sigma, double *c)
{
    double total = 0.0;
    double t0 = th->t[0];
    size_t i;
    for (i = 0; i < th->nr; i++) {
        /* relative to the innermost ring: no weight underflows for tiny
         * sigma */
        double d = (th->t[i] - t0) * (th->t[i] + t0); /* t^2 - t0^2 */
        double e = d / (2.0 * sigma * sigma);
        c[i] = e < 745.0 ? exp(-e) * th->w[i] : 0.0; /* P d omega */
        total += c[i];
    }
    total *= 2.0 * BF__PI; /* P's norm: the azimuths' weights sum to 2 pi */
    for (i = 0; i < th->nr; i++) {
        c[i] = c[i] * th->inv_ct[i] / total;
    }
}
