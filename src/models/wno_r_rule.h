/* wno_r_rule.h: WNO-R's quadrature rule of one configuration -- facet
 * normals split at the kinks of the integrand (src/models/wno_r_rule.c;
 * the model is src/models/wno_r.c, doc/methods.md §7). Internal to the two
 * files. */
#ifndef BF_MODELS_WNO_R_RULE_H
#define BF_MODELS_WNO_R_RULE_H

#include <stddef.h>

/* Gauss-Legendre points per piece of theta_a or phi_a. */
#define WNOR_Q 12
/* Pieces of theta_a, at most: 15 geometric panels, 2 tangencies, 10
 * crossings of the kink circles, rounded up. */
#define WNOR_MAX_TP 32
#define WNOR_MAX_RINGS (WNOR_MAX_TP * WNOR_Q)
/* Facets of one ring, at most: 10 kinks of phi_a and pieces no wider than
 * pi/2 give at most 14 pieces; a multiple of 8 (wnor_ring_sum's partial
 * sums). */
#define WNOR_MAX_RF (14 * WNOR_Q)

/* The theta_a rule of one configuration: rings at tilts t[i] with weights
 * w[i] (the Gauss-Legendre weight, the Jacobian of the piece's map and
 * sin t: P's d omega without P and d phi) and 1 / cos t[i]. */
typedef struct {
    size_t nr;
    double t[WNOR_MAX_RINGS];
    double w[WNOR_MAX_RINGS];
    double inv_ct[WNOR_MAX_RINGS];
} wnor_theta;

/* The facets of one ring: normals and azimuthal weights (sum 2 pi), m of
 * them, padded with weight 0 to a multiple of 8. */
typedef struct {
    size_t m;
    double ax[WNOR_MAX_RF];
    double ay[WNOR_MAX_RF];
    double az[WNOR_MAX_RF];
    double wp[WNOR_MAX_RF];
} wnor_ring;

/* The kink circles of a configuration (l, v unit vectors in the rule's
 * frame, l[2] > 0): their poles, nc of them (degenerate ones left out),
 * and the length and azimuth of each pole's horizontal part; cross names
 * the circle where G's two terms cross (a kink only where they are below
 * 1, bf__wnor_ring). */
typedef struct {
    size_t nc;
    size_t cross; /* the index of <v,n> l - <l,n> v, or nc: none */
    double m[5][3];
    double r[5];
    double psi[5];
} wnor_kinks;

void bf__wnor_kinks(const double l[3], const double v[3], wnor_kinks *kc);
/* The theta_a rule of the configuration of kc, l[2] = cos theta_i, v[2] =
 * cos theta_s. */
void bf__wnor_theta(const wnor_kinks *kc, double cl, double cv,
                    wnor_theta *th);
/* The facets of the ring at tilt t. */
void bf__wnor_ring(const wnor_kinks *kc, double t, wnor_ring *rg);
/* The ring's sum of wp L_f <a,v> G / <v,n> ([1]-[4] of wno_r.c) at index
 * n: before the ring weight and 1 / cos t. */
double bf__wnor_ring_sum(const double *ax, const double *ay,
                         const double *az, const double *wp, size_t m,
                         const double l[3], const double v[3], double n);
/* The weights of th's rings at sigma > 0, normalised, 1 / cos t folded
 * in: the value is sum_i c[i] b[i], b the ring sums. */
void bf__wnor_weights(const wnor_theta *th, double sigma, double *c);
/* The Gauss-Legendre rule of WNOR_Q points on [-1, 1], ascending: its
 * abscissae and weights (GSL's table, mirrored). */
void bf__wnor_gl(const double **x, const double **w);

#endif
