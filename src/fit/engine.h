/* engine.h: the fitting engine's private interface -- model kernels over
 * geometry terms computed once per configuration set, prepared models, the
 * one evaluate-and-normalise, the objective of a fit, one grid layout and
 * enumerator, weighted scoring. Never installed (STYLE §1, §3: bf__ names).
 *
 * Every fit of the library (the study's grids beyond the paper's kernels,
 * the exact refinement, the profile intervals, the bootstrap and the
 * cross-validation) evaluates models through this interface:
 *
 *   configuration set (bf__cset): geometry, sines and cosines, cos theta_i
 *     -> prepared model (bf__prep): the kernel's geometry-only terms
 *        -> bf__curve: values at one parameter vector from the terms (the
 *           kernel's loop, caller workspace, no allocation), normalised
 *           (SPEC §2), the only evaluate-and-normalise of the engine
 *           -> bf__fitctx: the objective S of a problem (doc/methods.md §1)
 */
#ifndef BF_FIT_ENGINE_H
#define BF_FIT_ENGINE_H

#include <gsl/gsl_rng.h>
#include <stddef.h>

#include "internal.h"

/* ======================================================================
 * --- the grid of model curves ---
 * ====================================================================== */

/* The study's grid: precomputed normalised model curves at every point of
 * a parameter grid on one set of configurations. Model curves do not depend on the sample, so a
 * study computes them once and fits every sample against them. The
 * optimum is bf_fit_grid's; for the BK family and LFTG the curves come from
 * vectorised kernels that rearrange the math (no division or pow in the
 * inner loop, libmvec's exp), so the LSE agrees with bf_fit_grid's to a few
 * units in the last place times sqrt(n LSE) (see src/fit/kernels.c).
 * The public face of the same curves is bf_curves (curves.c), built on
 * it. Opaque; owns memory. */
typedef struct bf__grid bf__grid;

/* Builds the grid (arguments as bf_fit_grid). geom is read here and not
 * kept. Returns NULL with *status set on failure. */
bf__grid *bf__grid_alloc(const bf_model_type *type, const double *fixed,
                         unsigned free_mask, size_t n, const bf_geom *geom,
                         int *status);
void bf__grid_free(bf__grid *gr);
/* Number of grid points. */
size_t bf__grid_points(const bf__grid *gr);
/* Best grid point against normalised data of the grid's n configurations. */
int bf__grid_fit(const bf__grid *gr, const double *data, bf_fit_result *result);

/* ======================================================================
 * --- configuration sets ---
 * ====================================================================== */

/* The configurations a group of fits shares and what every model needs of
 * them: sines and cosines (bf__geom_trig) and cos theta_i as the zenith
 * convention gives it (the cosw objective). Owns trig and cti. */
typedef struct {
    size_t n;            /* configurations */
    const bf_geom *geom; /* borrowed */
    bf__trig_t *trig;    /* n */
    double *cti;         /* n: cos theta_i (bf__zenith_sincos) */
} bf__cset;

/* Fills cs for the n configurations geom (borrowed until bf__cset_free).
 * BF_ENOMEM or BF_EINVAL (n = 0). */
int bf__cset_init(bf__cset *cs, size_t n, const bf_geom *geom);
void bf__cset_free(bf__cset *cs);

/* ======================================================================
 * --- kernels (each model file defines its own) ---
 * ====================================================================== */

typedef struct bf__prep bf__prep;
/* A model's block kernel set up for one grid (src/fit/block.h). */
typedef struct bf__block bf__block;

/* A model's evaluation in the engine. The engine never looks at a model's
 * name, eval pointer or parameter names: what it needs is here, filled by
 * the model's file with designated initialisers (STYLE §2; a field left
 * out is 0/NULL: not provided). A model with constants of its own for
 * these functions (the BK family's member) embeds its bf_kernel as the
 * first member of its own struct and converts kr back (src/models/bk.c);
 * the engine never looks beyond the bf_kernel. */
struct bf_kernel {
    /* doubles per configuration of geometry-only terms, and doubles of
     * terms that do not depend on the configuration (after them) */
    size_t n_terms;
    size_t n_extra;
    /* Fills terms[t * n + k] (t < n_terms) for the n configurations of cs,
     * then the n_extra doubles at terms[n_terms * n]. Called once per
     * configuration set and model. */
    void (*terms)(const bf_kernel *kr, const bf__cset *cs, double *terms);
    /* Bytes of workspace values() needs on n configurations (a cache of
     * parameter-dependent terms: FC's Fresnel factor for one n, WNO-R's
     * quadrature nodes for one sigma). NULL: none. */
    size_t (*work_bytes)(const bf_kernel *kr, size_t n);
    /* Values up to a constant factor at param (checked by the caller) into
     * out (pm->n values). work: work_bytes, zeroed before its first use,
     * then only ever touched by this function. BF_OK, or BF_EDOM with NaN
     * where the model is undefined. */
    int (*values)(const bf__prep *pm, const double *param, void *work,
                  double *out);
    /* Number of configurations at which the model's formula was clamped
     * at param (ON's clamp at 0, doc/methods.md §8); NULL: never. */
    size_t (*clamped)(const bf__prep *pm, const double *param);
    /* The normalisation of SPEC §2 for bf__curve when the model's block
     * kernel normalises otherwise than bf_normalise (bf__normalise_recip:
     * by the reciprocal of the maximum, as src/fit/kernels.c does every
     * block), so that a point's curve has the bits of the same grid
     * point's. NULL: bf_normalise. */
    int (*normalise)(size_t n, double *curve);
    /* The model's block kernel for the study/grid/bootstrap path: sets blk
     * up (src/fit/block.h: its state, raw(), optionally its streaming
     * scorers, release()) for the grid lay of one free parameter (lay->
     * n_free == 1, checked by the caller) on pm's configurations, copying
     * what it needs of pm->terms (pm may be freed before blk). Returns 1,
     * 0 when it does not apply to this grid (which parameter is free, its
     * range; blk then holds nothing), or -BF_ENOMEM. NULL: no block
     * kernel; the grid's curves come from values() point by point. Called
     * once per grid; blk's functions once per block of BF__BLOCK_LANES
     * points. */
    int (*block)(const bf__prep *pm, const bf__grid_layout_t *lay,
                 bf__block *blk);
    /* The parameter that is cheap to vary while the others stay (its
     * values need none of the cached terms recomputed: WNO-R's sigma
     * given its ring sums at n), or -1: the refinement of two parameters
     * then nests its searches, this one inside. Not a default: 0 names
     * parameter 0, so every kernel sets it (-1 when none is). */
    int cheap;
    /* Tables a kernel builds for a configuration set on demand (WNO-R's
     * ring sums in Chebyshev form, one panel of n at a time): prepare
     * makes pm->cache (BF_OK or BF_ENOMEM), release frees it. The cache is
     * shared by the threads: values() builds an entry under a lock and
     * publishes it atomically; an entry is a function of the
     * configurations alone, so who builds it does not change any bit.
     * NULL: none. */
    int (*prepare)(bf__prep *pm);
    void (*release)(bf__prep *pm);
    /* The columns of the separable fit (src/fit/varpro.c) at param for the
     * linear parameters lin (a mask, in index order): c0 = values() with
     * those parameters at 0, col[q] = values() with the q-th at 1 and the
     * others at 0, minus c0 -- each part of the model evaluated once
     * (bf__columns_scaled, a composite's own). BF_OK or BF_EDOM. NULL:
     * bf__columns_values, values() n_lin + 1 times. */
    int (*columns)(const bf__prep *pm, const double *param, unsigned lin,
                   void *work, double *c0, double *const *col);
};

/* The columns from values(): at the linear parameters 0, then at each
 * unit vector, minus c0 (any kernel). */
int bf__columns_values(const bf__prep *pm, const double *param, unsigned lin,
                       void *work, double *c0, double *const *col);
/* The columns of a kernel whose values are linear in its linear
 * parameters without offset (value = sum_q theta_q f_q(others): the
 * specular lobes' rho_s, SPEC §9.3): c0 = 0, one values() per column;
 * bf__columns_values when a linear parameter is not in lin (held). */
int bf__columns_scaled(const bf__prep *pm, const double *param, unsigned lin,
                       void *work, double *c0, double *const *col);

/* The plain kernel: values() is type->eval on the configurations (no
 * terms). The reference path and types made outside the library (kernel
 * NULL) use it. */
extern const bf_kernel bf__plain_kernel;

/* A model prepared on a configuration set: its kernel's geometry terms.
 * Read-only once made, so threads share it; each thread has its own
 * workspace (bf__work_alloc). */
struct bf__prep {
    const bf_model_type *type;
    const bf_kernel *kr;  /* type->kernel, or &bf__plain_kernel */
    const bf__cset *cs;   /* borrowed; NULL for bf__prep_plain */
    size_t n;             /* configurations */
    const bf_geom *geom;  /* borrowed: the n configurations */
    double *terms;        /* kr->n_terms * n + kr->n_extra, owned */
    size_t work_bytes;    /* of a workspace */
    void *cache;          /* the kernel's tables (prepare/release) */
};

/* Prepares type on cs (borrowed): its kernel's terms, or the plain kernel
 * when it has none. BF_OK, BF_ENOMEM, BF_EINVAL. */
int bf__prep_init(bf__prep *pm, const bf_model_type *type,
                  const bf__cset *cs);
/* Prepares type's own eval (the plain kernel) on n configurations geom
 * (borrowed); allocates nothing. BF_OK or BF_EINVAL. */
int bf__prep_plain(bf__prep *pm, const bf_model_type *type, size_t n,
                   const bf_geom *geom);
void bf__prep_free(bf__prep *pm);

/* A zeroed workspace for values() of pm (64-byte aligned; free()), or
 * NULL when out of memory. Never NULL for a kernel without workspace. */
void *bf__work_alloc(const bf__prep *pm);

/* The one evaluate-and-normalise of the engine: pm's values at param,
 * divided by their maximum over the configurations (SPEC §2, as
 * bf_normalise). param must lie in the model's domain. BF_OK, or BF_EDOM
 * when the model is undefined at a configuration or not normalisable. */
int bf__curve(const bf__prep *pm, const double *param, void *work,
              double *curve);
/* The normalisation of bf__curve for models with a block kernel (their
 * bf_kernel.normalise): multiplied by the reciprocal of the maximum, as
 * the grid kernels do (src/fit/kernels.c). BF_EDOM when a value is not
 * finite or the maximum is not positive. */
int bf__normalise_recip(size_t n, double *curve);

/* ======================================================================
 * --- the objective of a fit (doc/methods.md §1) ---
 * ====================================================================== */

/* What one evaluation of a fitting problem needs: the problem (objective,
 * data, weights, ranges), its prepared model and the scratch memory of one
 * thread. Made by bf__fitctx_init for one problem; the refinement, the
 * profile, the bootstrap and the cross-validation each re-point pb at a
 * problem with other weights or fixed values of the same model. */
typedef struct {
    const bf_problem *pb;
    const bf__prep *pm;
    void *work;      /* the kernel's workspace (owned) */
    double *curve;   /* n */
    double *scratch; /* n */
    double *log_d;   /* n: bf__data_transform of pb->data */
    double *cols;    /* 3 n: a specular model's columns (varpro.c), or
                        NULL */
    /* The point cols were evaluated at (varpro.c): its parameters and
     * lin_mask, valid when cols_ok. The columns are a function of them
     * (and pm) alone, so an evaluation at the same point -- a clamped
     * coordinate's finite difference, a trial step clamped back -- reuses
     * them. */
    double cols_at[BF_MAX_PARAMS];
    unsigned cols_lin;
    int cols_ok;
    size_t n_eval;   /* evaluations since init */
    /* The separable fit (varpro.c): bit j when parameter j is a scale
     * (bf_param.linear) that bf__fit_value solves exactly instead of
     * taking it from param (0: none is), and the values it solved. */
    unsigned lin_mask;
    double lin[BF_MAX_PARAMS];
    /* A joint fit (--channel joint, SPEC §9.4; varpro.c): pb->data holds
     * blocks x n values, channel-major, one shape for all and the scales
     * solved per block into block_lin[c * BF_MAX_PARAMS + j] (lin: block
     * 0's); curve holds blocks x n. 1 for every other fit. */
    size_t blocks;
    double *block_lin;
    /* Levenberg-Marquardt's stall stop (varpro.c): 0, or the relative
     * decrease of the cost below which an iteration ends the run (the
     * profiles' inner fits, profile.c; there Nelder-Mead off a bound
     * makes one coarser pass, which LM finishes). */
    double stall;
    /* Levenberg-Marquardt's workspace for lm_n residuals and lm_p
     * parameters and lm_n square roots of the weights (varpro.c), kept
     * between its runs: a dense table's is tens of MB, whose allocation
     * and page faults cost more than a run's iterations. NULL: none. */
    void *lm;
    double *lm_sw;
    size_t lm_n;
    size_t lm_p;
} bf__fitctx;

/* Scratch memory for pm. BF_OK or BF_ENOMEM. */
int bf__fitctx_init(bf__fitctx *fc, const bf__prep *pm);
/* The same for a joint fit of blocks >= 1 channels (a specular model's
 * separable fit only). BF_OK, BF_ENOMEM, BF_EINVAL. */
int bf__fitctx_init_blocks(bf__fitctx *fc, const bf__prep *pm,
                           size_t blocks);
void bf__fitctx_free(bf__fitctx *fc);
/* Frees what the separable fit keeps in fc between runs (varpro.c). */
void bf__varpro_free(bf__fitctx *fc);

/* Points fc at pb (same model and configurations as fc->pm; borrowed):
 * every change of problem, data or weights goes through here, so that
 * what is derived from the data (the log objective's logs) follows. */
void bf__fitctx_use(bf__fitctx *fc, const bf_problem *pb);

/* S of fc->pb at param (type->p values in the domain): BF_OK, or BF_EDOM
 * where the model is undefined or not normalisable. Counts an
 * evaluation. */
int bf__fit_value(bf__fitctx *fc, const double *param, double *value);

/* Residuals r_k of fc->pb at param (S = sum w_k r_k^2). */
int bf__fit_residuals(bf__fitctx *fc, const double *param, double *resid);

/* S of pb on a normalised curve (scratch: n doubles; log_d for
 * BF_OBJ_LOG, else NULL): sum_k w_k r_k^2 with one fma per term, in index
 * order. */
double bf__objective(const bf_problem *pb, const double *cti,
                     const double *log_d, const double *curve,
                     double *scratch);

/* sum_k w_k f_k (c_k - d_k)^2 in index order, the rounded squares added
 * by one fma each (w NULL: an add; f NULL: 1): the max and cosw
 * objectives (src/fit/kernels.c). */
double bf__sum_weighted(size_t n, const double *c, const double *d,
                        const double *w, const double *f);

/* What the objective needs of pb->data, per configuration, into out (n
 * values; nothing for the objectives that need none): the floored logs
 * (BF_OBJ_LOG), the cube roots (BF_OBJ_CUBEROOT), ln(1 + rho)
 * (BF_OBJ_LOG1P). The log_d argument of bf__objective and bf__residuals. */
void bf__data_transform(const bf_problem *pb, double *out);

/* The scale s of pb on a normalised curve (log_d from bf__data_transform):
 * BF_OBJ_SCALE's s*, the free scale s >= 0 of the objectives that keep it
 * (SPEC §10; cuberoot: s = t^3), 1 for the others. */
double bf__fit_scale_of(const bf_problem *pb, const double *log_d,
                        const double *curve);

/* Residuals of pb on a normalised curve (see bf_objective). */
void bf__residuals(const bf_problem *pb, const double *cti,
                   const double *log_d, const double *curve, double *resid);

/* The likelihood of the noise model (src/fit/noise.c, doc/methods.md §3)
 * as an objective of the engine: never a user's objective (no name), set
 * by the intervals on a copy of the problem with pb->noise_power = p:
 *   S = g * sum_k w_k (D_k - s* L_k)^2 / v_k,  v_k = max(L_k, f)^p,
 *   s* = sum w L D / v / sum w L^2 / v,  g = exp(sum w ln v / sum w),
 * so that -2 ln(profile likelihood over s, sigma^2) = n ln S + const. */
#define BF__OBJ_LIK ((bf_objective)64)

/* S of the likelihood objective on a normalised curve (scratch: n
 * doubles), and its residuals r_k (S = sum w r_k^2). */
double bf__lik_value(const bf_problem *pb, const double *curve,
                     double *scratch);
void bf__lik_residuals(const bf_problem *pb, const double *curve,
                       double *resid);
/* The noise power p in [0, BF_NOISE_PMAX] that maximises the likelihood
 * at the normalised curve (sigma and s profiled; scratch: n doubles), its
 * residuals standardised by the fit's leverages lev (n; NULL: none). */
double bf__noise_power(const bf_problem *pb, const double *curve,
                       const double *lev, double *scratch);
/* The largest leverage a residual is standardised by (noise.c's noise
 * power, sandwich.c's HC2 terms): a configuration the fit interpolates
 * (h = 1) tells nothing of its variance, and its residual (zero to
 * rounding) is not blown up by 1 / (1 - h). */
#define BF__LEV_MAX 0.99
/* The leverages h (n) of the fit at param (mean scale times the model's
 * curve fit, n, of maximum top) under fc->pb's weights and noise power p
 * (leverage.c); z: n (BF_MAX_PARAMS + 1), t0, t1: n doubles of scratch. */
int bf__leverages(bf__fitctx *fc, const double *param, double scale,
                  double p, const double *fit, double top, double *z,
                  double *t0, double *t1, double *h);
/* Each free parameter j's robust factor c[j] >= 1 of a specular model's
 * fit at param (sandwich.c): its variance from the residuals (the HC2
 * sandwich) over the noise model's, at least 1, with fit = rho_hat there
 * (n, maximum top), noise power p and nu degrees of freedom of sigma^2;
 * NaN for the others; 1 for every free one where the leverages'
 * derivatives fail (that code returned). buf: (BF_MAX_PARAMS + 4) n
 * doubles. */
int bf__robust_factors(bf__fitctx *fc, const double *param, double p,
                       const double *fit, double top, double nu, double *buf,
                       double *c);
/* The likelihood's scale s* and sigma^2 = RSS_v / dof at the curve
 * (scratch: n doubles). */
void bf__lik_scale(const bf_problem *pb, const double *curve, double dof,
                   double *scratch, double *scale, double *sigma2);

/* One problem's own engine (the public API's fits: bf_fit_refine,
 * bf_fit_profile_ci, ... called on a bf_problem): a configuration set, the
 * prepared model and one context, made per call. */
typedef struct {
    bf__cset cs;
    bf__prep pm;
    bf__fitctx fc;
} bf__solo;

/* Makes s for pb (its geometry checked) and points s->fc at pb. BF_OK,
 * BF_EINVAL, BF_ENOMEM (s then needs no free). */
int bf__solo_init(bf__solo *s, const bf_problem *pb);
void bf__solo_free(bf__solo *s);

/* ======================================================================
 * --- separable least squares for the specular models (varpro.c) ---
 * ====================================================================== */

/* S of fc->pb (objective BF_OBJ_NGAN) at param with the scales of
 * fc->lin_mask solved exactly, non-negative, into fc->lin (param's values
 * of them are not read). At most two scales. BF_OK, BF_EDOM. */
int bf__varpro_value(bf__fitctx *fc, const double *param, double *value);

/* Dense data: above this many configurations (every cell of a MERL
 * table, issue 17 item 10) the separable fit picks its basin on a
 * subsample (varpro.c) and a profile's bracket is narrowed by prediction
 * (profile.c). */
#define BF__DENSE_K 65536

/* The distinct minima a separable fit's descents ended at, in the order
 * reached (bf__varpro_fit): full parameter vectors, the scales as solved
 * there. At most BF__VP_MINIMA, the fit's descents. */
#define BF__VP_MINIMA 6
typedef struct {
    size_t n;
    double x[BF__VP_MINIMA][BF_MAX_PARAMS];
} bf__vp_minima;

/* What the separable fit of the whole data leaves its cross-validation
 * folds (bf__varpro_fit, bf__cv): the distinct minima its descents ended
 * at, and with fold set every fold's values at its grid's points,
 * computed in its own pass over the grid, where it evaluates the model
 * anyway (bf__varpro_fold_grids' values; none where the fit uses no grid
 * of its problem: dense data, a joint fit). */
typedef struct {
    const size_t *fold; /* in: each configuration's fold, or NULL */
    size_t folds;       /* in */
    bf__vp_minima minima;
    double *vals;       /* folds x points, or NULL (bf__vp_whole_free) */
    size_t points;
} bf__vp_whole;
void bf__vp_whole_free(bf__vp_whole *wh);

/* The fit of a specular model (BF_MODEL_SPECULAR: SPEC §9.3 and the
 * composites of §9.4) under an objective that keeps the scale (SPEC §10):
 * the scales (bf_param.linear) solved exactly for every value of the
 * other free parameters, those searched on a product grid (log-spaced
 * over a wide positive domain) and refined from the grid's best local
 * minima with the scales re-solved (variable projection); under cuberoot
 * and log1p that solution starts a refinement of every free parameter.
 * grid (may be NULL) gets the grid optimum, result the fit (lse: S of the
 * objective, not its report), whole (may be NULL) what its folds take
 * from it (bf__vp_whole: the ngan search's distinct minima, none on dense
 * data or a joint fit; the folds' grid values). BF_OK, BF_EDOM (no point
 * defined), BF_EINVAL (more than two free scales, or not such a model),
 * BF_ENOMEM. */
int bf__varpro_fit(bf__fitctx *fc, bf_fit_result *grid,
                   bf_fit_result *result, bf__vp_whole *whole);
/* Cross-validation's folds share the separable fit's grid: the ngan
 * values of its every point under each fold's training problem (fc->pb's
 * data, weight 1 off fold f -- fold[k] != f -- and 0 on it), the model
 * evaluated once per point and every fold's scales and S from sums over
 * the configurations (to rounding: the normal equations' form of S),
 * into *vals (folds x *points, malloc; the caller frees it). BF_EINVAL
 * (*vals NULL) where bf__varpro_fit would not use a grid of fc->pb (dense
 * data, a joint fit); BF_ENOMEM. */
int bf__varpro_fold_grids(bf__fitctx *fc, const size_t *fold, size_t folds,
                          double **vals, size_t *points);
/* bf__varpro_fit of a fold's problem fc->pb with its grid's values vals
 * (one fold's of bf__varpro_fold_grids) instead of computing them: with
 * warm (the whole data's minima; NULL or none: the grid's minima as a
 * whole fit), a descent from each of warm's minima and one from the
 * grid's lowest minimum, which stops where it joins a minimum reached
 * before at no lower value (varpro.c; doc/methods.md §5); the lowest of
 * those minima. */
int bf__varpro_fit_grid(bf__fitctx *fc, const double *vals,
                        const bf__vp_minima *warm, bf_fit_result *result);
/* The free scales of pb (bf_param.linear): the mask the separable fit
 * solves. */
unsigned bf__varpro_lin(const bf_problem *pb);
/* The separable fit of fc->pb (objective ngan, any weights) refined from
 * start alone: Levenberg-Marquardt over the free non-scale parameters
 * with the free scales solved at every point (Nelder-Mead off a bound),
 * no grid; the profile intervals' inner fits, the bootstrap's refits
 * (intervals.c, profile.c, bootstrap.c). result->param holds the solved
 * scales. BF_OK, BF_EDOM (start undefined), BF_EINVAL, BF_ENOMEM. */
int bf__varpro_refine(bf__fitctx *fc, const double *start,
                      bf_fit_result *result);
/* The likelihood's weights of a specular model (intervals.c): w_k =
 * w0_k / v_k, v_k = max(rho_hat_k / M, f)^p at param (M = max_k
 * rho_hat_k, f = BF_LOG_FLOOR; w0 = pb->weight or 1), scaled to the sum
 * of w0 (so n of the profile criterion stays K). *m (may be NULL) gets M.
 * Uses fc->curve. BF_OK or BF_EDOM (rho_hat not positive somewhere). */
int bf__spec_weights(bf__fitctx *fc, const double *param, double p,
                     double *w, double *m);

/* The scales the separable fit solves at param's other values, for each
 * of fc->blocks channels: out[c * BF_MAX_PARAMS + j] = param[j] for the
 * shape parameters, channel c's solved scale for the free linear ones
 * (the joint fit's channels, SPEC §9.4; one block: the ordinary fit).
 * BF_OK, BF_EDOM where the model is undefined, BF_EINVAL. */
int bf__varpro_scales(bf__fitctx *fc, const double *param, double *out);

/* ======================================================================
 * --- exact refinement, minimisation (refine.c) ---
 * ====================================================================== */

/* bf_fit_refine and bf_fit_minimise on the engine: fc->pb is the problem
 * (checked by the callers). */
int bf__refine(bf__fitctx *fc, const bf_fit_result *start,
               bf_fit_result *result);
/* A simulated measurement's fit as the data's: fc->pb's optimum on the
 * stored grid gr (bf__grid_optima), refined. BF_OK or BF_ENOCONV (*result
 * the best point reached), BF_EDOM when no grid point is defined,
 * BF_ENOMEM, or the refinement's error. */
int bf__grid_refine(bf__fitctx *fc, const bf__grid *gr,
                    bf_fit_result *result);
int bf__minimise(bf__fitctx *fc, const double *start, bf_fit_result *result);

/* ======================================================================
 * --- the analysis of many pairs (analysis.c) ---
 * ====================================================================== */

/* What bf_study_analyse (or any driver) hands the engine: targets on
 * configuration sets, models, the inputs of every pair. Borrowed. */
typedef struct {
    size_t n_sets;
    const bf__cset *sets;
    size_t n_targets;
    const size_t *set_of;        /* per target: its configuration set */
    const double *const *data;   /* per target: normalised data (SPEC §2) */
    size_t n_models;
    const bf_model_type *const *models;
    const double *fixed;         /* per unit u = t * n_models + m:
                                    BF_MAX_PARAMS inputs (fixed values,
                                    starting values of the free ones) */
    const int *status;           /* per unit: BF_OK, or why it has no
                                    inputs (BF_ENOTFOUND) */
    const bf_fit_result *grid;   /* per unit, the study's grid optima to
                                    reuse where they are the analysis's
                                    (n_eval 0: none), or NULL */
    const bf_analysis_opts *opts;
    int n_threads;               /* 0 or 1: one */
    const size_t *joint_n;       /* per target (NULL: none is joint): 0
                                    for a target fitted on its own; the
                                    first target of a joint fit (SPEC
                                    §9.4) the number C of its channels,
                                    targets t .. t + C - 1 on one
                                    configuration set; SIZE_MAX for the
                                    others (the first's unit fills them) */
} bf__job;

/* Analyses every unit of job into stats (cleared first; done = 1 where
 * analysed) and unit_status (BF_OK, the unit's input status, or why the
 * model cannot fit: BF_EDOM). Returns BF_OK or BF_ENOMEM. */
int bf__analyse(const bf__job *job, bf_fit_stats *stats, int *unit_status);

/* ======================================================================
 * --- grids: one layout, one enumerator ---
 * ====================================================================== */

/* Builds the layout of type's free parameters (bit j of mask) over the
 * ranges [lo[j], hi[j]] with each parameter's grid step: points lo + step
 * t <= hi (1e-9 of a step absorbs the rounding of the span). fixed holds
 * every parameter's value. The paper's grids are the ranges [grid_lo,
 * grid_lo + grid_step (grid_n - 1)] and give the same points. BF_EINVAL
 * when a free parameter has no grid or leaves its domain. */
int bf__grid_layout_range(const bf_model_type *type, const double *fixed,
                          unsigned mask, const double *lo, const double *hi,
                          bf__grid_layout_t *g);
/* Thins g to every s-th point of each free parameter, s the least step
 * multiple that leaves at most max points (max >= 1): the same first
 * point, the step s times longer. */
void bf__grid_layout_coarsen(bf__grid_layout_t *g, size_t max);

/* ======================================================================
 * --- grid optima under weights (curves.c) ---
 * ====================================================================== */

/* The grid optimum of pb's objective on gr's curves (same model,
 * configurations and free parameters as pb) for each of n_w weight vectors
 * w[b] (NULL: all 1; pb->weight is not used) into results[b]; ties keep
 * the first point. A vector under which no point is defined gets lse NaN.
 * cti: cos theta_i of the configurations (the cosw objective). BF_OK or
 * BF_ENOMEM. */
int bf__grid_optima(const bf__grid *gr, const bf_problem *pb,
                    const double *cti, size_t n_w, const double *const *w,
                    bf_fit_result *results);
/* The local minima of pb's objective (weights pb->weight) over gr's
 * points -- no lattice neighbour lower, a plateau once -- the max lowest
 * in increasing order into results (*count of them). BF_OK, BF_ENOMEM. */
int bf__grid_minima(const bf__grid *gr, const bf_problem *pb,
                    const double *cti, size_t max, bf_fit_result *results,
                    size_t *count);
/* The grid of a bf_curves, and BF_OK when c was made for pb's model,
 * configurations and free parameters (else BF_EINVAL). */
const bf__grid *bf__curves_grid(const bf_curves *c);
int bf__curves_check(const bf_curves *c, const bf_problem *pb);

/* ======================================================================
 * --- intervals and cross-validation on the engine ---
 * ====================================================================== */

/* bf_fit_profile_ci on fc (fc->pb the problem; restored on return). */
int bf__profile_ci(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                   double level, double *low, double *high, unsigned *open);
/* The sum of pb's weights (n without weights): the n of the profile
 * criteria. */
double bf__weight_sum(const bf_problem *pb);
/* The default first outward step of parameter j's profile from est: a
 * grid step (1 % of the range without a grid); a specular model's 5 % of
 * est (1e-3 of its domain, at most 1e-3, from 0). */
double bf__profile_step(const bf_problem *pb, size_t j, double est);
/* The first outward steps of the profiles of fc->pb around best with the
 * threshold thr, d0[j] for every parameter j: bf__profile_step's; on
 * dense data (more than BF__DENSE_K configurations) of a specular model
 * predicted by Gauss-Newton at best, from one Jacobian for all of them.
 * BF_OK, BF_ENOMEM. */
int bf__profile_steps(bf__fitctx *fc, const bf_fit_result *best, double thr,
                      double *d0);
/* bf__profile_ci with the criterion n ln(S_p / S_min) <= thr and the
 * first outward step d0 (bf__profile_steps); gap (NULL: not wanted; else
 * 2 doubles) gets the gap of a split set of two regions, gap[0] < gap[1]
 * (the set is [low, gap[0]] and [gap[1], high]), NaN when the set is one
 * region or more than two. */
int bf__profile_ci_thr(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                       double thr, double d0, double *low, double *high,
                       unsigned *open, double *gap);
/* The curve of that criterion, dev[k] = n ln(S_p(theta[k]) / S_min) (n
 * values, increasing; NaN where the inner fit fails), with the inner fits
 * the intervals take (profile.c) at every point: outward from best, the
 * refinement warm-started from the inner neighbour and the thorough
 * (grid) fit, the lower. BF_OK, BF_ENOMEM, or bf__fit_value's failure at
 * best. */
int bf__profile_curve(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                      size_t n, const double *theta, double *dev);
/* One point of that curve: *dev = n ln(S_p(theta) / S_min) (at least 0)
 * with the thorough inner fit alone, param (BF_MAX_PARAMS, may be NULL)
 * its parameters (theta at j). BF_OK, BF_ENOMEM, BF_EDOM where the inner
 * fit fails, or bf__fit_value's failure at best. */
int bf__profile_point(bf__fitctx *fc, const bf_fit_result *best, size_t j,
                      double theta, double *dev, double *param);
/* The maximum-likelihood fit of fc->pb (a likelihood problem): the lower
 * of the refinement from start and a minimisation over the whole range
 * from it (intervals.c). */
int bf__ml_fit(bf__fitctx *fc, const double *start, bf_fit_result *out);
/* One simulated measurement of the normalised curve (pb->n values) into
 * d: curve + sigma max(curve, f)^(p/2) eps, eps ~ N(0, 1) from rng,
 * divided by its maximum (m > 0: a specular model's, multiplied by m and
 * kept in sr^-1; calibrate.c). 0 when it cannot be normalised. */
int bf__simulate(const bf_problem *pb, const double *curve, double m,
                 double p, double sigma, gsl_rng *rng, double *d);
/* The likelihood's residual degrees of freedom nu = n - k under noise
 * (intervals.c): n the sum of pb's weights, k its free parameters, a
 * diffuse model's scale and, under BF_NOISE_AUTO, the noise power. */
double bf__lik_dof(const bf_problem *pb, bf_noise noise);
/* The likelihood intervals' threshold n ln(1 + F_{1,nu}(level) / nu)
 * (intervals.c, [Bates & Watts §6.1.2]) for n the sum of the weights and
 * nu = n - k, finite at every nu >= 1. */
double bf__lik_threshold(double n, double nu, double level);
/* What bf__intervals thresholds, without the profiles: out gets the
 * estimate the intervals are about (ml), the noise power, sigma, scale
 * and method; *lik the problem whose profile they take (fc->pb under a
 * noise model's likelihood: BF__OBJ_LIK at the noise power, or a specular
 * model's ngan under the weights w, n + 1 doubles, borrowed; under
 * BF_NOISE_OBJECTIVE fc->pb itself) and *thr the criterion's threshold
 * (n ln(S_p / S_min) <= thr). fc->pb is restored on return. */
int bf__interval_problem(bf__fitctx *fc, const bf_fit_result *best,
                         bf_noise noise, double level, double *w,
                         bf_interval *out, bf_problem *lik, double *thr);
/* bf_fit_interval_curve for every free parameter j of mask at once (one
 * noise fit): theta, dev n values per parameter, parameter-major in the
 * order of j (dev NaN where not computed); thr one per parameter; iv as
 * bf_fit_interval_curve's (may be NULL). BF_EINVAL for a parameter that is
 * not free or values outside its range or not increasing. */
int bf__interval_curves(const bf_problem *pb, const bf_fit_result *best,
                        bf_noise noise, double level, unsigned mask, size_t n,
                        const double *theta, double *dev, double *thr,
                        bf_interval *iv);
/* bf_fit_intervals on fc (fc->pb the problem; restored on return). */
int bf__intervals(bf__fitctx *fc, const bf_fit_result *best, bf_noise noise,
                  double level, bf_interval *out);
/* bf_fit_bootstrap on fc around iv (bf__intervals of fc->pb); est
 * (n_boot x BF_MAX_PARAMS, parameter-major, sorted per parameter on
 * return, NULL: not kept) and *n_est (may be NULL) get the estimates;
 * *split (may be NULL) bit j when parameter j's estimates fall into
 * separate groups (replicates in different basins). */
int bf__bootstrap(bf__fitctx *fc, const bf_interval *iv, size_t n_boot,
                  unsigned long seed, double level, double *est,
                  size_t *n_est, double *low, double *high, unsigned *split);
/* bf_fit_neyman on fc around iv (bf__intervals of fc->pb, a diffuse
 * model's likelihood; neyman.c, doc/methods.md §3) for the free
 * parameters of which at once; gr: fc->pb's grid (the simulations' first
 * fits), or NULL to make one. *out starts as *iv; *failed gets bit j when
 * parameter j's construction failed (its ends left at iv's), and the
 * first such failure's code is returned. BF_OK at once when which has no
 * free parameter; BF_EDOM (every bit of which in *failed) when iv has no
 * noise model or for a specular model; BF_ENOMEM. */
int bf__neyman(bf__fitctx *fc, const bf_interval *iv, const bf__grid *gr,
               unsigned which, size_t n_sim, unsigned long seed,
               double level, bf_interval *out, unsigned *failed);
/* The parameters whose intervals the construction makes for iv, pb's
 * intervals, under the analysis's n_neyman and neyman_every
 * (bf_analysis_opts): every free one, or those that compete
 * (iv->competing); none without n_neyman, for a specular model, or where
 * iv is not the likelihood's (BF_NOISE_OBJECTIVE, a failed interval). */
unsigned bf__neyman_which(const bf_problem *pb, const bf_interval *iv,
                          size_t n_neyman, int every);
/* A call after each unit of work (progress). */
typedef struct {
    void (*fn)(void *ctx);
    void *ctx;
} bf__tick;
/* bf_fit_calibrate keeping each simulation's maximum-likelihood estimate:
 * ml_est (NULL: not kept; else n_sim x BF_MAX_PARAMS, parameter-major)
 * gets the estimate of free parameter j in the r-th simulation fitted at
 * ml_est[j * n_sim + r], r < out->n_sim, NaN elsewhere; tick (NULL: none)
 * is called after each simulation, fitted or not. */
int bf__fit_calibrate(const bf_problem *pb, const double *truth,
                      double noise_power, double sigma, bf_noise noise,
                      size_t n_sim, size_t n_boot, size_t n_neyman,
                      int neyman_every, unsigned long seed, double level,
                      double *ml_est, const bf__tick *tick,
                      bf_calibration *out);
/* bf_fit_cv on fc with the grid gr and the folds fold (bf_fit_cv_folds);
 * fold_grid: the folds' grid optima (results 1.. of
 * bf__grid_optima_folds), or NULL to compute them; whole (NULL: none)
 * what the whole data's separable fit left its folds (bf__varpro_fit with
 * these folds): a specular model's folds' fits start from its minima
 * (bf__varpro_fit_grid) on its grid values. */
int bf__cv(bf__fitctx *fc, const bf__grid *gr, const size_t *fold,
           size_t folds, const bf_fit_result *fold_grid,
           const bf__vp_whole *whole, double *cv);

/* ======================================================================
 * --- scoring many weight vectors against stored curves (weights.c) ---
 * ====================================================================== */

/* S[b * cols + g] = sum_k w[b][k] c[k][g] (r_kg)^2, r = curve - data,
 * for the transposed curves (curves[k * stride + g], g < cols, cols a
 * multiple of BF__SCORE_LANES) and n_w weight vectors (w[b] NULL: all
 * 1), c the per-configuration factor cw (NULL: 1). Sums in index order,
 * one fma per term, as the engine's objective. */
void bf__score_weights(size_t n, size_t cols, size_t stride,
                       const double *curves, const double *data,
                       const double *cw, size_t n_w, const double *const *w,
                       double *lse);
/* The grid optima of the same sums without storing them: for each weight
 * vector the smallest S over the points g < points with ok[g] and its
 * first index (bf__argmin's choice; SIZE_MAX when none), from one pass
 * over the curves for all n_w vectors. BF_OK or BF_ENOMEM. */
int bf__weights_argmin(size_t n, size_t cols, size_t stride,
                       const double *curves, const unsigned char *ok,
                       size_t points, const double *data, const double *cw,
                       size_t n_w, const double *const *w, double *best_lse,
                       size_t *best);
/* One tile of those sums (src/fit/weights.c): out[q * 8 + j] = sum_k
 * w[q][k] rho[k * 128 + j] for 6 weight rows and 8 columns, one fma per
 * term in index order, unless every candidate column's (cand[j] != 0)
 * partial sum exceeds its row's bound[q] at a test (returns 0; NaN never
 * does; else 1). generic: the portable C kernel instead of the
 * processor's (the same bits; tests compare them). */
int bf__weights_tile(int generic, size_t n, const double *rho,
                     const double *const *w, const double *bound,
                     const int *cand, double *out);

/* ======================================================================
 * --- grids and the study path (grid.c, kernels.c: any model's block
 *     kernel, src/fit/block.h) ---
 * ====================================================================== */

/* Transposed normalised curves curves[k * stride + g], g < cols, of every
 * grid point of lay by pm's block kernel (bf_kernel.block, one free
 * parameter). Returns 1 when done, 0 when no block kernel applies,
 * -BF_ENOMEM. */
int bf__curves_fast(const bf__prep *pm, const bf__grid_layout_t *lay,
                    size_t cols, size_t stride, double *curves,
                    unsigned char *ok);
/* The study path without stored curves: the normalised curves of each
 * block of grid points are computed (same kernels, same bits as
 * bf__curves_fast) and scored against every sample at once (same sums as
 * bf__score_all), keeping per sample the smallest LSE of the defined
 * points and its first index (as bf__argmin; SIZE_MAX when none). Returns
 * 1 when done, 0 when no block kernel applies, -BF_ENOMEM. */
int bf__stream_fast(const bf_model_type *type, const bf__grid_layout_t *lay,
                    const bf__cset *cs, size_t n_samples,
                    const double *const *data, double *best_lse,
                    size_t *best);

/* The normalised curves of every point of lay for pm, stored transposed
 * (block kernels where they apply, else bf__curve per point). NULL with
 * *status (BF_ENOMEM) on failure. */
bf__grid *bf__grid_make(const bf__prep *pm, const bf__grid_layout_t *lay,
                        int *status);
/* The same for type's paper grids (free_mask as bf_fit_grid) on cs. */
bf__grid *bf__grid_build(const bf_model_type *type, const double *fixed,
                         unsigned free_mask, const bf__cset *cs, int *status);
/* Row length of the grid's LSE arrays (>= bf__grid_points, padded). */
size_t bf__grid_cols(const bf__grid *gr);
/* The grid's layout, and its flags (1 where a point's curve is defined). */
const bf__grid_layout_t *bf__grid_lay(const bf__grid *gr);
const unsigned char *bf__grid_ok(const bf__grid *gr);
/* Scores n_samples samples at once: lse must hold n_samples * cols. */
void bf__grid_score(const bf__grid *gr, size_t n_samples,
                    const double *const *data, double *lse);
/* bf__score_weights on the grid's curves: lse holds n_w * cols. */
void bf__grid_score_weights(const bf__grid *gr, const double *data,
                            const double *cw, size_t n_w,
                            const double *const *w, double *lse);
/* bf__weights_argmin on the grid's curves: each weight vector's grid
 * optimum as bf__grid_best reports it (no defined point: lse NaN, n_eval
 * the points, as bf__grid_optima). BF_OK or BF_ENOMEM. */
int bf__grid_weights_argmin(const bf__grid *gr, const double *data,
                            const double *cw, size_t n_w,
                            const double *const *w, bf_fit_result *results);
/* Row k of the transposed curves and their row pitch. */
const double *bf__grid_curve_row(const bf__grid *gr, size_t k,
                                 size_t *stride);
/* Grid points whose curves are stored or read at once (curves_by_point,
 * bf__grid_curves' callers): runs of this many doubles from each
 * configuration's row instead of one double a row apart (the curves are
 * stored by configuration). */
#define BF__GRID_BLOCK 32
/* The curves of the nb grid points from idx0 (nb <= the points left), one
 * after another (n values each), read row by row. */
void bf__grid_curves(const bf__grid *gr, size_t idx0, size_t nb,
                     double *curves);
/* The result of a grid search whose best point is best (SIZE_MAX: none,
 * BF_EDOM) with that LSE: n_eval, bound flags and parameters as
 * bf_fit_grid reports them. */
int bf__grid_result(const bf__grid_layout_t *g, size_t best, double best_lse,
                    bf_fit_result *result);
/* The best grid point of one row of LSE values (ties keep the first),
 * as bf__grid_fit reports it. */
int bf__grid_best(const bf__grid *gr, const double *lse,
                  bf_fit_result *result);

/* Models with no fitted parameter (ON, LAMBERT), evaluated once per sample
 * at its fixed inputs through the engine, bit for bit as bf_fit_grid. */
typedef struct bf__fixed_model bf__fixed_model;
/* cs is borrowed until bf__fixed_free. NULL when out of memory. */
bf__fixed_model *bf__fixed_alloc(const bf_model_type *type,
                                 const bf__cset *cs);
int bf__fixed_fit(const bf__fixed_model *fm, const double *fixed,
                  const double *data, bf_fit_result *result);
void bf__fixed_free(bf__fixed_model *fm);

/* The full-data scores (lse[g], as bf__score_weights with weights 1, the
 * same bits) and the training scores of every cross-validation fold
 * (lse[(f + 1) * cols + g]: all configurations but those with fold[k] ==
 * f, formed as the full sum minus the fold's) in one pass. */
void bf__score_folds(size_t n, size_t cols, size_t stride,
                     const double *curves, const double *data,
                     const double *cw, const size_t *fold, size_t folds,
                     double *lse);
/* The grid optima (values and first indices, SIZE_MAX: none) of n_data
 * data vectors and of their folds' training sets, best[q * (folds + 1) +
 * b] (b = 0 the full data, 1 + f fold f), from one pass over the curves
 * for all of them: bf__score_folds's sums, bf__argmin's choice. Points
 * with ok 0 never win. Returns BF_OK, or BF_ENOMEM (no optimum) when its
 * workspace cannot be allocated. */
int bf__folds_argmin(size_t n, size_t cols, size_t stride,
                     const double *curves, const unsigned char *ok,
                     size_t points, size_t n_data, const double *const *data,
                     const double *cw, const size_t *fold, size_t folds,
                     double *best_lse, size_t *best);
/* The same on a grid (folds may be 0: only the full data). BF_OK or
 * BF_ENOMEM. */
int bf__grid_folds_argmin(const bf__grid *gr, size_t n_data,
                          const double *const *data, const double *cw,
                          const size_t *fold, size_t folds,
                          bf_fit_result *results);
/* bf__score_folds on a grid's curves: lse holds (folds + 1) * cols. */
void bf__grid_score_folds(const bf__grid *gr, const double *data,
                          const double *cw, const size_t *fold, size_t folds,
                          double *lse);
/* The grid optima of pb (no weights) and of each fold's training set
 * (results[0], results[1 + f]) from one pass (max and cosw objectives;
 * the others through bf__grid_optima). BF_OK or BF_ENOMEM. */
int bf__grid_optima_folds(const bf__grid *gr, const bf_problem *pb,
                          const double *cti, const size_t *fold,
                          size_t folds, bf_fit_result *results);

#endif
