/* varpro.h: what the files of the separable fit share (SPEC §9.3, §10;
 * varpro.c: the search over the nonlinear parameters; varpro_scales.c:
 * the scales solved exactly; varpro_folds.c: the cross-validation folds'
 * grid values; varpro_homog.c: the grid of a homogeneous lobe). Private
 * to src/fit, never installed. */
#ifndef BF_FIT_VARPRO_H
#define BF_FIT_VARPRO_H

#include "fit/engine.h"

/* Scales solved exactly per point (columns besides c0), at most. */
#define BF__VP_MAX_LIN 2
/* Descents from the grid's lowest local minima (each can be one of a
 * fit's minima). */
#define BF__VP_STARTS BF__VP_MINIMA
/* The value of a point where the objective is not defined. */
#define BF__VP_UNDEFINED 1e300

/* The normal equations of the scales: g11 = <c1, c1>, g12, g22, b1 =
 * <c1, R - c0>, b2 (weighted). */
typedef struct {
    double g11, g12, g22, b1, b2;
} bf__vp_normal;

/* The residuals sw_k (curve_k - R_k) of fc's last evaluation (fc->curve,
 * every block's, block after block; sw NULL: 1) into f: Levenberg-
 * Marquardt's vector (varpro.c, lmq.c). */
void bf__vp_residuals(const bf__fitctx *fc, const double *sw, double *f);

/* NNLS from the normal equations ne (two columns when two): 1 with t the
 * unconstrained optimum when it is inside [0, hi]; else 0 with t the two
 * one-column optima clamped into [0, hi] (one column: always 1). */
int bf__vp_nnls_solve(const bf__vp_normal *ne, int two, const double *hi,
                      double *t);

/* What moves in a search: parameter idx[i] over [lo_i, hi_i], in ln x when
 * lg[i] (lo > 0). */
typedef struct {
    bf__fitctx *fc;
    double base[BF_MAX_PARAMS];
    size_t m;
    size_t idx[BF_MAX_PARAMS];
    int lg[BF_MAX_PARAMS];
    double lo[BF_MAX_PARAMS];
    double hi[BF_MAX_PARAMS];
    size_t count[BF_MAX_PARAMS]; /* grid points */
    double zero_first[BF_MAX_PARAMS]; /* 1: grid point 0 is x = 0 */
    const double *sw; /* sqrt of the weights (levenberg), NULL: 1 */
    double flat_f;  /* Nelder-Mead's last trial value */
    size_t flat_n;  /* trial values in a row equal to it */
    /* A fold's fit (bf__varpro_fit_grid): the minima its descents have
     * reached (search coordinates, values), n_known of them; a descent
     * that comes within near (per axis) of one at no lower value stops
     * there, merged (its basin's minimum is known). */
    int merge;
    size_t n_known;
    double known_u[BF__VP_STARTS][BF_MAX_PARAMS];
    double known_f[BF__VP_STARTS];
    double near[BF_MAX_PARAMS];
    int merged;
    /* A grid over a homogeneous lobe (bf_homog; bf__vp_grid_init): its
     * unit parameter (not an axis, held at 1 on the grid), its degree and
     * its scaled parameters (a mask). */
    int hg;
    size_t hg_unit;
    size_t hg_degree;
    unsigned hg_scaled;
} bf__vp_space;

/* The search of fc's problem over the free parameters of mask (its
 * domains, grid sizes and coordinates). */
void bf__vp_space_init(bf__vp_space *sp, bf__fitctx *fc, unsigned mask);

/* The grid of the search over mask: bf__vp_space_init's, except where
 * the model's lobe is homogeneous (bf_homog) and its unit and scaled
 * parameters are in mask (one block, at most one other scale): then the
 * unit parameter is no axis but 1 at every grid point, and the lobe's
 * size solved there (bf__vp_grid_value). */
void bf__vp_grid_init(bf__vp_space *gs, bf__fitctx *fc, unsigned mask);

/* The value of grid point x of gs (a full vector, bf__vp_point_of;
 * BF__VP_UNDEFINED where not defined) and in y (not NULL) the point it
 * stands for: x itself, or with gs->hg the unit parameter t (the lobe's
 * solved size t^n) and the scaled ones times t, each clamped into its
 * domain. */
double bf__vp_grid_value(const bf__vp_space *gs, const double *x, double *y);

/* 1 when gs->hg and grid point x (after a descent in gs) stands for y
 * (bf__vp_grid_value) inside the domain: every unit and scaled parameter
 * of y off its bounds (nothing clamped) and the scaled ones of x (the
 * ratio to the unit parameter, whose axis bounds are not the model's) off
 * their axis's bounds (1e-6 of the span). Such a stationary point of the
 * search with the lobe's size solved is one over every parameter: the map
 * (x, size) -> y is one-to-one where the unit parameter is positive. */
int bf__vp_grid_inside(const bf__vp_space *gs, const double *x,
                       const double *y);

/* The lobe's size at param, solved exactly: the NNLS scales of fc's
 * columns with c_0 (the lobe at param) one more scaled column (one block,
 * at most one scale in fc->lin_mask); *mag the lobe's scale, *value the
 * objective there; fc->lin and fc->curve as bf__varpro_value leaves them. */
int bf__varpro_magnitude(bf__fitctx *fc, const double *param, double *mag,
                         double *value);

/* Every cross-validation fold's ngan value at each point of a separable
 * fit's grid (varpro_folds.c), filled point by point in a pass over it:
 * bf__varpro_fold_grids' own pass, or the whole data's fit's
 * (varpro_ngan), which evaluates the model there anyway. */
typedef struct {
    const size_t *fold; /* each configuration's fold */
    size_t folds;
    size_t points;      /* the grid's */
    size_t n_lin;       /* the scales solved */
    double hi[BF__VP_MAX_LIN + 1]; /* their bounds */
    bf_problem whole;   /* fc's problem under ngan, unweighted */
    double *mom;        /* 6 (folds + 1) sums, then n weights */
    double *vals;       /* folds x points: fold f's at point g in
                           vals[f * points + g] */
} bf__vp_foldpass;

/* The pass for fc's problem (its grid: bf__vp_grid_init of its free
 * parameters but the scales) and the folds fold. BF_OK; BF_EINVAL where
 * the fit uses no grid of its problem (dense data, a joint fit, not a
 * specular model: points 0) or no folds; BF_ENOMEM. */
int bf__vp_foldpass_init(bf__vp_foldpass *fp, bf__fitctx *fc,
                         const size_t *fold, size_t folds);
/* Grid point g (x its vector; fc's columns evaluated there, as
 * bf__vp_grid_value of gs leaves them, defined when defined): every
 * fold's value. fc's problem is left as it was. */
void bf__vp_foldpass_point(bf__vp_foldpass *fp, bf__fitctx *fc,
                           const bf__vp_space *gs, size_t g,
                           const double *x, int defined);
void bf__vp_foldpass_free(bf__vp_foldpass *fp);

/* Grid point idx of sp (the first axis slowest) as a full vector. */
void bf__vp_point_of(const bf__vp_space *sp, size_t idx, double *x);

/* The objective at x (full vector; the scales solved when the context
 * says so), BF__VP_UNDEFINED where not defined. */
double bf__vp_value_at(bf__fitctx *fc, const double *x);

#endif
