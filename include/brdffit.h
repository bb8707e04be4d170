/* brdffit.h: the public API of libbrdffit -- rough-surface reflectance models,
 * measured BRDF loaders and model fitting.
 *
 * Conventions (SPEC §1), stated once for the whole library:
 *   - angles are in radians; zenith angles are measured from the surface normal;
 *   - suffix i is the incident (illumination) direction, s the scattered
 *     (viewing) direction;
 *   - model formulas use Beckmann's frame: the incident beam's projection on the
 *     tangent plane points along -X, i.e. phi_i = pi; the specular direction is
 *     theta_s = theta_i, phi_s = 0 (SPEC §1.2);
 *   - model values are radiances up to a constant factor; the study normalises
 *     every curve by its maximum over the used configurations (SPEC §2).
 *
 * Errors: a function that can fail returns BF_OK (0) or a BF_E* code;
 * constructors return NULL on failure. Loaders fill an optional bf_error with
 * the file name, line and a short message. The library never prints, never
 * exits and never reads argv.
 *
 * Contents, in the order a user works:
 *   basics   version and errors, geometry, Fresnel terms, the model
 *            registry and model variants, the objectives of a fit;
 *   load     datasets (bf_dataset, the one data model) and the readers of
 *            every format, the per-sample inputs (bf_sample_table);
 *   select   which configurations, targets and models a study uses
 *            (bf_selection, bf_study_spec);
 *   fit      one fit (bf_fit_grid, bf_problem, bf_fit_refine, bf_curves)
 *            and the paper's study (bf_study_run);
 *   analyse  intervals, information criteria, cross-validation, the
 *            study's analysis (bf_study_analyse), ranking, and what the
 *            figures draw;
 *   write    fits.csv, ranking.csv and calibrate.csv and their lines as
 *            structs, tidy CSV;
 *   report   the report (libbrdffit_report).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (equations (P1)-(P7) in SPEC.md).
 *   [2] M. Oren, S. K. Nayar, "Generalization of the Lambertian model and
 *       implications for machine vision", IJCV 14(3), 1995.
 *   [3] E. P. F. Lafortune et al., "Non-linear approximation of reflectance
 *       functions", SIGGRAPH 1997.
 *   [4] K. J. Dana et al., "Reflectance and Texture of Real-World Surfaces",
 *       ACM TOG 18(1), 1999 (the CURET database).
 *   [5] L. B. Wolff, S. K. Nayar, M. Oren, "Improved diffuse reflection
 *       models for computer vision", IJCV 30(1), 1998; L. B. Wolff,
 *       "Diffuse-reflectance model for smooth dielectric surfaces", JOSA A
 *       11(11), 1994 (the WNO model).
 */
#ifndef BRDFFIT_H
#define BRDFFIT_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================
 * --- basics: version and errors ---
 * ====================================================================== */

#define BF_VERSION_MAJOR 0
#define BF_VERSION_MINOR 1
#define BF_VERSION_PATCH 0
#define BF_VERSION_STRING "0.1.0"

/* Returns the library's version string (static storage). */
const char *bf_version(void);

enum {
    BF_OK = 0,   /* success */
    BF_EINVAL,   /* invalid argument (bad parameter, NULL pointer, bad size) */
    BF_EDOM,     /* outside the domain of a model or function */
    BF_ENOMEM,   /* out of memory */
    BF_EIO,      /* file could not be opened, read or written */
    BF_EPARSE,   /* malformed input file */
    BF_ENOCONV,  /* an iterative method did not converge */
    BF_ENOTFOUND /* a named item (model, sample) does not exist */
};

/* Returns a static, human-readable text for an error code. */
const char *bf_strerror(int code);

#define BF_ERROR_FILE_MAX 512
#define BF_ERROR_MSG_MAX 256

/* Where and why a loader failed. line is 1-based; 0 means "the file as a
 * whole" (e.g. empty file, missing rows). file is a copy of the name given
 * to the loader. */
typedef struct {
    int code;                        /* BF_E* code, BF_OK when no error */
    long line;                       /* 1-based line number, 0 if none */
    char file[BF_ERROR_FILE_MAX];    /* file name as given to the loader */
    char msg[BF_ERROR_MSG_MAX];      /* short description of the problem */
} bf_error;

/* Formats err as "file:line: msg" (or "file: msg" when line is 0) into buf
 * of size len; returns buf. */
char *bf_error_format(const bf_error *err, char *buf, size_t len);

/* ======================================================================
 * --- basics: geometry (SPEC §1) ---
 * ====================================================================== */

/* One illumination/viewing configuration in Beckmann's frame. */
typedef struct {
    double theta_i; /* incidence zenith angle, [0, pi/2] */
    double phi_i;   /* incidence azimuth; pi in Beckmann's frame */
    double theta_s; /* scattering (viewing) zenith angle, [0, pi/2] */
    double phi_s;   /* scattering azimuth, (-pi, pi]; 0 is specular */
} bf_geom;

/* Wraps an angle to (-pi, pi]. */
double bf_geom_wrap_angle(double a);

/* Converts a configuration in CURET's sample frame (view theta_v, phi_v;
 * illumination theta_i, phi_i) to Beckmann's frame (SPEC §1.3):
 * theta_s = theta_v, phi_s = wrap(phi_v - phi_i - pi), phi_i = pi. */
bf_geom bf_geom_from_curet(double theta_v, double phi_v, double theta_i,
                           double phi_i);

/* The angle delta between the viewing direction and the mirror direction
 * of the incident one (SPEC §1.6), in radians, [0, pi]. The same in either
 * frame; computed here from Beckmann's. */
double bf_geom_mirror_angle(const bf_geom *g);

/* Converts a configuration in the measurement frame of SPEC §1.5 to
 * Beckmann's: theta_s = theta_o, phi_s = wrap(phi_o - phi_i - pi),
 * phi_i = pi. bf_geom_from_curet(tv, pv, ti, pi) is
 * bf_geom_from_measurement(ti, pi, tv, pv), bit for bit. */
bf_geom bf_geom_from_measurement(double theta_i, double phi_i,
                                 double theta_o, double phi_o);

/* Tolerance of the specular test, SPEC §1.4 (radians). */
#define BF_SPECULAR_TOL 1e-3

/* Returns 1 when g is a specular configuration (SPEC §1.4):
 * |theta_s - theta_i| < BF_SPECULAR_TOL and |phi_s| < BF_SPECULAR_TOL. */
int bf_geom_is_specular(const bf_geom *g);

/* ======================================================================
 * --- basics: Fresnel terms (SPEC §4) ---
 * ====================================================================== */

/* Unpolarised Fresnel reflectance f(alpha_i, r) for light arriving at angle
 * alpha_i in [0, pi/2] on an interface of relative index r > 0 (SPEC §4.1,
 * paper (P4) with the factor 1/2). Returns 1 beyond the critical angle (total
 * internal reflection when r < 1), ((r-1)/(r+1))^2 at alpha_i = 0, 1 at
 * alpha_i = pi/2 for r > 1, and 0 everywhere for r = 1 (no interface).
 * Returns NaN when r <= 0, an argument is not finite or alpha_i is outside
 * [0, pi/2]. */
double bf_fresnel(double alpha_i, double r);

/* Fresnel correction factor F_FC^2 of paper (P6), SPEC §4.2, for refractive
 * index n >= 1 (n = 1 gives cos theta_i). Returns NaN when n < 1, an
 * argument is not finite or an angle is outside [0, pi/2]. */
double bf_fresnel_fc2(double theta_i, double theta_s, double n);

/* ======================================================================
 * --- basics: models and their variants (SPEC §3-6, §9) ---
 * ====================================================================== */

#define BF_MAX_PARAMS 8

/* Where a parameter that a fit holds fixed takes its value for one
 * material of a study (bf_study_spec): the model type says it, so the
 * study never guesses from parameter names. BF_INPUT_INDEX marks every
 * refractive index, fitted ones too (WNO's n, the specular models' n
 * under --fresnel dielectric, ABC's ior), which is how the dispersion
 * finds them (bf_dispersion_points): AS's and Lafortune's exponents are
 * named n as well. */
typedef enum {
    BF_INPUT_DEFAULT = 0, /* bf_param.value */
    BF_INPUT_INDEX,       /* the material's refractive index: the study's
                             n_file, else its n_default (SPEC §4.2) */
    BF_INPUT_ON           /* column input_col of the study's on_params
                             (SPEC §5: rho 0, sigma 1) */
} bf_input;

/* Lafortune et al.'s lobe (SPEC §9.3) at (t Cxy, t Cz, n) is t^n times its
 * value at (Cxy, Cz, n): homogeneous of degree n in Cxy and Cz. A search
 * can hold the BF_HOMOG_UNIT parameter (Cz) at 1 and solve the lobe's size
 * t^n exactly, as a scale, then multiply it and the BF_HOMOG_SCALED ones
 * (Cxy) by t; BF_HOMOG_DEGREE marks the degree (n). */
typedef enum {
    BF_HOMOG_NONE = 0,
    BF_HOMOG_UNIT,
    BF_HOMOG_SCALED,
    BF_HOMOG_DEGREE
} bf_homog;

/* One parameter of a model. */
typedef struct {
    const char *name;   /* short name: "m", "n", "n_d", "rho", "sigma" */
    const char *label;  /* label for tables and plots, e.g. "sigma/T (G)" */
    const char *unit;   /* "1" for dimensionless, "rad" for radians */
    double min, max;    /* valid domain, inclusive */
    double value;       /* default value when the parameter is held fixed */
    int fitted;         /* 1 if the paper's protocol fits it, 0 if an input */
    double grid_lo;     /* paper grid: grid_lo + grid_step * i, */
    double grid_step;   /*   i = 0 .. grid_n - 1 (SPEC §7.4) */
    size_t grid_n;      /* 0 when the parameter has no grid */
    bf_input input;     /* where a fixed value comes from (not fitted) */
    size_t input_col;   /* BF_INPUT_ON: the column of on_params */
    double free_lo;     /* the exact fit (doc/methods.md §6) frees this */
    double free_hi;     /*   input over the grid free_lo, free_lo + */
    double free_step;   /*   free_step, ... <= free_hi; 0: never freed */
    /* 1 when the model's value is this parameter times a function of the
     * other parameters alone (a scale: SPEC §9.3's rho_s, A and AS's Rd,
     * not AS's Rs), so that a separable least-squares fit solves it
     * exactly; 0 otherwise (every parameter of the diffuse models, whose
     * values are compared after max-normalisation, SPEC §2). */
    int linear;
    bf_homog homog; /* its part in a homogeneous lobe (bf_homog) */
} bf_param;

/* Evaluates a model at n configurations. param holds type->p values, already
 * checked to lie in the domain. Writes n radiances (up to scale) to out;
 * a specular model (BF_MODEL_SPECULAR) writes BRDF values in sr^-1.
 * work is the caller's scratch memory of type->work_size bytes (NULL when
 * that is 0), aligned for double; its content on entry does not matter,
 * so one buffer serves any number of calls and no call allocates.
 * Returns BF_OK or BF_EDOM (out then holds NaN where undefined). */
typedef int (*bf_eval_fn)(const double *param, size_t n, const bf_geom *geom,
                          double *out, void *work);

/* The engine's evaluation of a registry model (library-internal, see
 * src/fit/engine.h): geometry-only terms precomputed once per
 * configuration set, values for any parameters from them through a
 * vectorised loop, a caller workspace. Opaque here. */
typedef struct bf_kernel bf_kernel;

/* What a model's values are (bf_model_type.kind). Zero is the diffuse
 * family of SPEC §3-6 (radiance up to scale, compared after the
 * max-normalisation of SPEC §2); BF_MODEL_SPECULAR the models of SPEC
 * §9.3, absolute BRDF values in sr^-1 whose scale parameters are real
 * parameters (bf_param.linear), fitted under the objectives of SPEC §10,
 * never max-normalised. */
typedef enum { BF_MODEL_DIFFUSE = 0, BF_MODEL_SPECULAR } bf_model_kind;

/* A model family: a constant type object (cf. gsl_rng_type). Adding a
 * model to the library is one file defining its type object (with its
 * kernel) and one line in the registry (src/models/registry.c). */
typedef struct bf_model_type {
    const char *name;        /* registry name, e.g. "FC-E" */
    const char *title;       /* one-line description */
    const char *reference;   /* equations implemented, e.g. "paper (P2),(P6)" */
    size_t p;                /* number of parameters (<= BF_MAX_PARAMS) */
    const bf_param *param;   /* p parameter descriptions */
    bf_eval_fn eval;         /* evaluation function (the reference path) */
    size_t work_size;        /* bytes of workspace eval needs (0: none) */
    const bf_kernel *kernel; /* the engine's evaluation; NULL for a type
                                made outside the library (eval is used) */
    unsigned style;          /* plot style slot (colour and marker of the
                                figures): distinct for every registry
                                model, the paper's models the lowest */
    const char *reduces_to;  /* the registry model this one is exactly when
                                parameter reduces_param equals reduces_at
                                (ON at sigma = 0 is LAMBERT, WNO-R at
                                sigma = 0 is WNO), or NULL */
    size_t reduces_param;
    double reduces_at;
    /* The fields below are zero (NULL) for the diffuse models. */
    bf_model_kind kind;      /* BF_MODEL_DIFFUSE (0) or BF_MODEL_SPECULAR */
    /* Specular models (SPEC §9.2: every output names them): the normal
     * distribution ("GGX", "Beckmann", "Blinn-Phong", "Ward", ...), the
     * masking form ("Smith height-correlated", "Smith separable",
     * "V-cavity", "none", ...) and the Fresnel term ("Schlick (F0)",
     * "dielectric (n)", "none (F = 1)", ...), for outputs. */
    const char *ndf;
    const char *masking;
    const char *fresnel_term;
    /* The type objects of SPEC §9.2's options (--fresnel, --smith) of this
     * model, BF_SPECULAR_VARIANTS of them (BF_VARIANT_INDEX), NULL where
     * an option does not apply; the same table in every variant. NULL:
     * the model takes none (bf_model_specular_variant). */
    const struct bf_model_type *const *variants;
    /* 1 for a specular model with its own diffuse term (AS, SPEC §9.3):
     * the complete glossy comparison (bf_study_models' "all" under an
     * objective that keeps the scale) fits it alone; 0 for the others,
     * which it fits as LAMBERT+S (SPEC §9.4). */
    int own_diffuse;
} bf_model_type;

extern const bf_model_type *const bf_model_bk_g;   /* BK-G  SPEC §3.1 */
extern const bf_model_type *const bf_model_bk_e;   /* BK-E  SPEC §3.2 */
extern const bf_model_type *const bf_model_vh_g;   /* VH-G  SPEC §3.3 */
extern const bf_model_type *const bf_model_vh_e;   /* VH-E  SPEC §3.3 */
extern const bf_model_type *const bf_model_fc_g;   /* FC-G  SPEC §3.3, §4.2 */
extern const bf_model_type *const bf_model_fc_e;   /* FC-E  SPEC §3.3, §4.2 */
extern const bf_model_type *const bf_model_on;     /* ON    SPEC §5 */
extern const bf_model_type *const bf_model_lftg;   /* LFTG  SPEC §6 */
extern const bf_model_type *const bf_model_lambert;/* LAMBERT SPEC §6a */
extern const bf_model_type *const bf_model_wno;    /* WNO  Wolff's smooth
                                                      dielectric, doc/methods.md */
extern const bf_model_type *const bf_model_wno_r;  /* WNO-R rough dielectric:
                                                      V-cavities of WNO facets,
                                                      doc/methods.md §7 */

/* The registry: number of models, the i-th model (NULL past the end). */
size_t bf_model_count(void);
const bf_model_type *bf_model_get(size_t i);

/* Finds a model by name (case-insensitive); NULL if unknown. A name "D+S"
 * is the composite of SPEC §9.4: a diffuse model D and a specular model S
 * of the registry ("LAMBERT+GGX", "ON+GGX", "FC-E+CT"), value rho_d d(i,
 * o) + S(i, o) in sr^-1 with d D's shape scaled to 1/pi at normal
 * incidence and view (LAMBERT: d = 1/pi), parameters rho_d (linear), D's,
 * S's; kind BF_MODEL_SPECULAR, ndf/masking/fresnel_term S's; a type
 * object of static storage (the same pointer for the same pair), not
 * counted by bf_model_count. */
const bf_model_type *bf_model_find(const char *name);

/* The specular part of type: S of a composite D+S (its parameters start
 * at index *first = 1 + D's count), type itself for a specular model of
 * SPEC §9.3 (*first = 0; AS with its diffuse term), NULL for a diffuse
 * model. first may be NULL. */
const bf_model_type *bf_model_specular_part(const bf_model_type *type,
                                            size_t *first);

/* The same, with *why (when why is not NULL) a sentence saying why name
 * names no model (static storage): unknown, an unknown part of a
 * composite, S+D order, two specular or two diffuse parts; NULL when it
 * names one. */
const bf_model_type *bf_model_find_why(const char *name, const char **why);

/* The default models of a study, as a comma-separated list of registry
 * names (static storage): for BF_MODELS_PAPER the paper's six,
 * "VH-G,VH-E,FC-G,FC-E,ON,LFTG" (its Tables 2-3; `compare`, `report`);
 * for BF_MODELS_RANKING those and the baselines LAMBERT, WNO and WNO-R
 * (`rank`). NULL for another value. */
typedef enum { BF_MODELS_PAPER = 0, BF_MODELS_RANKING } bf_model_set;
const char *bf_model_set_names(bf_model_set set);

/* Index of the parameter called name in type, or -1. */
int bf_model_param_index(const bf_model_type *type, const char *name);

/* The options of the specular models (SPEC §9.2). DEFAULT keeps what base
 * has (the registry models: Schlick's F0, height-correlated Smith). */
typedef enum {
    BF_FRESNEL_DEFAULT = 0,
    BF_FRESNEL_SCHLICK,    /* F0 + (1 - F0)(1 - cos theta_d)^5, F0 in [0, 1] */
    BF_FRESNEL_DIELECTRIC, /* SPEC §4.1 with a real index n in [1.01, 4]
                              (parameter "n" in F0's place) */
    BF_FRESNEL_NONE        /* F = 1 (no F0) */
} bf_fresnel_kind;
typedef enum {
    BF_SMITH_DEFAULT = 0,
    BF_SMITH_HEIGHT,   /* height-correlated G2, Heitz 2014 eq. 99 */
    BF_SMITH_SEPARABLE /* G1(i) G1(o), Heitz 2014 eq. 98 */
} bf_smith_kind;
#define BF_SPECULAR_VARIANTS 6
#define BF_VARIANT_INDEX(f, s) (((size_t)(f) - 1) * 2 + ((size_t)(s) - 1))

/* The variant of base (a registry model, one of its variants, a
 * composite D+S of either, or a bf_model_variant copy of any of them) with
 * Fresnel term f and masking s: a type object of static storage with the
 * same name (GGX stays "GGX") and the parameters of the option (rho_s,
 * alpha, n for GGX with BF_FRESNEL_DIELECTRIC; rho_s, alpha without F0; a
 * composite's are rho_d, D's, then those of S's variant, which
 * bf_model_specular_part returns).
 * The options apply as SPEC §9.2 says: --fresnel to GGX, BECKMANN and CT,
 * --smith to GGX and BECKMANN. Returns NULL where an option does not
 * apply, with *why (when why is not NULL) a sentence saying so (static
 * storage, to follow the model's name: "has no Fresnel term ..."). */
const bf_model_type *bf_model_specular_variant(const bf_model_type *base,
                                               bf_fresnel_kind f,
                                               bf_smith_kind s,
                                               const char **why);

/* Names of the options as the CLI spells them ("schlick", "dielectric",
 * "none"; "height", "separable"): BF_OK, or BF_ENOTFOUND (*out unchanged). */
int bf_fresnel_find(const char *name, bf_fresnel_kind *out);
int bf_smith_find(const char *name, bf_smith_kind *out);

/* The directional albedo of type at param for light from theta_i (SPEC
 * §9; the white-furnace check): the integral of the value
 * times cos theta_o over the outgoing hemisphere, by adaptive quadrature
 * (GSL QAG over theta_o and phi_o, the inner integral split at the mirror
 * direction so narrow lobes are followed; relative error about 1e-8).
 * Specular models only (their values are BRDFs in sr^-1); theta_i in
 * [0, pi/2). BF_OK; BF_EINVAL on bad arguments, a diffuse model or
 * parameters outside the domain; BF_EDOM when the quadrature does not
 * reach its tolerance or the model is undefined somewhere inside (*albedo
 * holds the estimate). GSL's error handler must be off
 * (gsl_set_error_handler_off(), as the CLI and the Python package do), or
 * a quadrature that fails aborts the program. Allocates (two GSL
 * workspaces): not for inner loops. */
int bf_model_albedo(const bf_model_type *type, const double *param,
                    double theta_i, double *albedo);

/* Evaluates type at n configurations after checking every parameter against
 * its domain (BF_EINVAL when out of range or not finite) and every geometry
 * against the closed hemisphere (BF_EINVAL; on BF_EINVAL out is all NaN).
 * Returns BF_ENOMEM (all NaN) when the model's workspace cannot be
 * allocated.
 * Returns BF_EDOM when the model is undefined at a configuration, with NaN
 * there and the other values filled: BK-G, BK-E at theta_i = pi/2 (F_BK
 * diverges, SPEC §3.3); WARD and WARD-DUER at theta_i or theta_s = pi/2
 * (1/sqrt(cos ti cos to), 1/(cos ti cos to) diverge, SPEC §9.3); LAFORTUNE
 * where its base exceeds 1 and base^n overflows a double (the domain's far
 * corner, Cxy or Cz near 2 with a large n). The specular models (SPEC §9)
 * are 0 at the grazing corner theta_i = theta_s = pi/2 (LAFORTUNE is
 * continuous there). Every other model is finite and >= 0 on the whole
 * closed hemisphere. VH-G, VH-E (and FC with n = 1) return 0, SPEC §3.3's
 * value, at the single corner theta_i = theta_s = pi/2, phi_s = 0, where
 * the value has no limit (it is 0 along the grazing boundary but
 * 1/(4 m^2 cos theta_i) along the specular path).
 * A zenith angle equal to the double nearest pi/2 (asin(1)) counts as
 * exactly grazing (cos = 0), so the grazing limits are taken exactly. */
int bf_model_eval(const bf_model_type *type, const double *param, size_t n,
                  const bf_geom *geom, double *out);

/* The same with the caller's workspace of type->work_size bytes (NULL when
 * that is 0): bf_model_eval allocates it for the call when the model needs
 * one (WNO-R), this never allocates. Same checks and codes. */
int bf_model_eval_work(const bf_model_type *type, const double *param,
                       size_t n, const bf_geom *geom, double *out,
                       void *work);

/* ---- model variants: other parameters fitted, other search ranges ---- */

/* A model type with some parameters' status or search range changed (n
 * freed in FC, rho and sigma fitted in ON, a wider --range). Initialise
 * with bf_model_variant_init and use &v->type; v must not be moved or
 * copied afterwards (type.param points into it). Owns no memory. */
typedef struct {
    bf_model_type type;
    bf_param param[BF_MAX_PARAMS];
} bf_model_variant;

/* Copies base into v (every parameter as in base). */
void bf_model_variant_init(bf_model_variant *v, const bf_model_type *base);

/* Makes parameter name fitted over the grid lo, lo + step, ... (the last
 * point is hi, rounded to the step; at most BF_VARIANT_MAX_GRID points).
 * BF_ENOTFOUND for an unknown name, BF_EINVAL when lo < min, hi > max,
 * lo >= hi, step <= 0 or too many points. */
#define BF_VARIANT_MAX_GRID 100001
int bf_model_variant_fit(bf_model_variant *v, const char *name, double lo,
                         double hi, double step);

/* Makes parameter name fitted over [lo, hi] with its own grid step (its
 * paper grid's, or (hi - lo) / 100 for a parameter without a grid): the
 * policy of a user's search range (--range NAME=LO:HI). BF_ENOTFOUND when
 * v has no such parameter; BF_EINVAL as bf_model_variant_fit (outside
 * [min, max], lo >= hi, more than BF_VARIANT_MAX_GRID points). */
int bf_model_variant_range(bf_model_variant *v, const char *name, double lo,
                           double hi);

/* The exact fit's policy (doc/methods.md §6): frees every input parameter
 * of v that has an exact-fit range (bf_param.free_lo < free_hi: FC's n
 * over [BF_FREE_N_LO, BF_FREE_N_HI], ON's rho over [0.05, 1] and sigma over
 * [0, 1.57]), fitted over the grid free_lo, free_lo + free_step, ...,
 * except inputs of the kinds in keep (bit 1u << BF_INPUT_INDEX: the user
 * gave n, so n stays the input). Returns the number of parameters freed. */
size_t bf_model_variant_exact(bf_model_variant *v, unsigned keep);

/* Ranges that --fit exact frees by default (doc/methods.md §6). */
#define BF_FREE_N_LO 1.2
#define BF_FREE_N_HI 2.5
#define BF_FREE_N_STEP 0.05

/* ======================================================================
 * --- basics: what a fit minimises (doc/methods.md §1, SPEC §10) ---
 * ====================================================================== */

/* What a fit minimises. Every objective is a weighted sum of squared
 * residuals S = sum_k w_k r_k^2 between the model curve L (normalised by
 * its maximum over the used configurations, SPEC §2) and the normalised
 * data D (doc/methods.md §1):
 *   BF_OBJ_MAX    r_k = L_k - D_k, the paper's LSE (SPEC §7.3; default);
 *   BF_OBJ_SCALE  r_k = s* L_k - D_k with the least-squares optimal scale
 *                 s* = sum w L D / sum w L^2 (closed form, per evaluation);
 *   BF_OBJ_COSW   r_k = sqrt(cos theta_i,k) (L_k - D_k);
 *   BF_OBJ_LOG    r_k = ln max(L_k, BF_LOG_FLOOR) - ln max(D_k, BF_LOG_FLOOR)
 *                 (non-positive and tiny values are floored, never dropped).
 */
typedef enum {
    BF_OBJ_MAX = 0,
    BF_OBJ_SCALE,
    BF_OBJ_COSW,
    BF_OBJ_LOG,
    /* The objectives that keep the scale (SPEC §10): pb->data holds
     * rho_k = measured BRDF x cos theta_i as measured (not normalised) and
     * the model's value is s L_k with its free scale s >= 0 solved exactly
     * at every evaluation (for the paper's diffuse models s L_k =
     * rho_d d_k cos theta_i, d scaled to 1/pi at normal incidence and
     * view, SPEC §9.4; bf_fit_scale gives rho_d):
     *   BF_OBJ_NGAN      r_k = s L_k - rho_k, s = max(0, sum w L rho /
     *                    sum w L^2) (Ngan, Durand, Matusik 2005);
     *   BF_OBJ_CUBEROOT  r_k = t cbrt(L_k) - cbrt(rho_k), t = cbrt(s) =
     *                    max(0, sum w cbrt(L) cbrt(rho) / sum w cbrt(L)^2)
     *                    (Fores, Ferwerda, Gu 2012);
     *   BF_OBJ_LOG1P     r_k = ln(1 + s L_k) - ln(1 + rho_k), s >= 0 the
     *                    minimiser (safeguarded Newton on the derivative)
     *                    (Low et al. 2012, E2).
     * S = sum w r^2 as for every objective; the value SPEC §10 reports is
     * bf_objective_report's (ngan: sqrt(S / K)). SPEC §10 sums over the
     * configurations with theta_i, theta_o <= 80 degrees: the study
     * selects them (BF_KEEP_SCALE_THETA); a bf_problem holds what its
     * caller chose. */
    BF_OBJ_NGAN,
    BF_OBJ_CUBEROOT,
    BF_OBJ_LOG1P
} bf_objective;

/* 1 for the objectives that keep the scale (SPEC §10), else 0. */
int bf_objective_keeps_scale(bf_objective obj);

/* The value SPEC §10 reports for objective S of a fit on n configurations
 * (sum of weights): sqrt(S / n) for BF_OBJ_NGAN, S for every other
 * objective (NaN stays NaN). */
double bf_objective_report(bf_objective obj, double s, double n);

/* The largest theta_i and theta_o (radians) of the configurations the
 * scale-keeping objectives use (SPEC §10: 80 degrees, and 1e-9 rad for
 * the rounding of angles read in degrees). */
#define BF_KEEP_SCALE_THETA (80.0 * 3.14159265358979323846 / 180.0 + 1e-9)

/* Floor of the log objective, in units of the normalised maximum. */
#define BF_LOG_FLOOR 1e-3

/* Name of an objective ("max", "scale", "cosw", "log", "ngan",
 * "cuberoot", "log1p"; static storage),
 * or NULL for an unknown value. */
const char *bf_objective_name(bf_objective obj);

/* Finds an objective by name; BF_ENOTFOUND when unknown. */
int bf_objective_find(const char *name, bf_objective *obj);

/* ======================================================================
 * --- load: datasets and their readers (SPEC §1.5, §2, §8) ---
 * ====================================================================== */

/* A dataset holds materials. Each material has a name, a number, its own
 * list of configurations, its channels and one BRDF value (sr^-1) per
 * configuration and channel, each with a valid mark. Configurations are
 * stored twice: as given, in the measurement frame of SPEC §1.5 (theta_i,
 * phi_i, theta_o, phi_o; radians; the mirror direction of (theta_i, phi_i)
 * is (theta_i, phi_i + pi)), and converted to Beckmann's frame
 * (bf_geom_from_measurement). CURET's table.txt, whose columns are view
 * first, is stored in the same order (theta_o = theta_v, phi_o = phi_v).
 *
 * Materials that share a configuration list share one "configuration set"
 * (the study computes the geometry once per set). Readers produce
 * datasets; the study, the analysis, the report and rank take a dataset
 * and never a format's own tables. Opaque; owns all its memory (every
 * input is copied). */
typedef struct bf_dataset bf_dataset;

/* The formats brdffit reads (SPEC §8). A format's value is its position
 * in the registry of readers (src/data/format.c): the constants below keep
 * their values, and a format added later takes the next value after
 * BF_FORMAT_MEMORY without a constant here (bf_format_find gives it by
 * name; bf_format_name is NULL past the last one). */
typedef enum {
    BF_FORMAT_AUTO = 0, /* detect from the content (bf_format_detect) */
    BF_FORMAT_CURET,    /* folder: table.txt + abrdf.dat (or r/g/bbrdf.dat),
                           samples.tsv optional (SPEC §1.3, §2) */
    BF_FORMAT_PBRT,     /* pbrt-v2 / Cornell .brdf (spectral) */
    BF_FORMAT_ASTM,     /* ASTM E1392 .astm (Cornell's exports) */
    BF_FORMAT_MERL,     /* MERL .binary (dense RGB table) */
    BF_FORMAT_CSV,      /* brdffit's tidy CSV (README "Tidy CSV") */
    BF_FORMAT_MEMORY    /* built by the caller (bf_dataset_add_material) */
} bf_format;

/* Name of a format: "auto", "curet", "pbrt", "astm", "merl", "csv",
 * "memory", then any later reader's (static storage), NULL for an unknown
 * value. */
const char *bf_format_name(bf_format f);

/* Finds a format by name (case-insensitive; also a reader's aliases:
 * "brdf" for pbrt, "binary" for merl). BF_ENOTFOUND when unknown. */
int bf_format_find(const char *name, bf_format *f);

/* Detects the format of path from its content, never from its name alone
 * (src/data/format.c asks each reader, strongest evidence first; each
 * reader's file says what it looks for): a folder holding table.txt is
 * CURET; MERL by its first 12 bytes, the little-endian int32 dimensions
 * 90, 90, 180 (the file size they imply is checked by bf_merl_read, which
 * names it); CSV by a first line naming theta_i, phi_i, theta_o, phi_o;
 * ASTM by its header keywords (NUM_POINTS, VARS); pbrt by a first number
 * token that is a plausible wavelength count (an integer in [1, 65536]).
 * BF_OK and *f, or BF_EIO (cannot open; a folder without table.txt; a
 * pipe, which cannot be read twice: name its format instead) / BF_EPARSE
 * (empty, binary or no format recognised: err names the file and says
 * which formats were tried). */
int bf_format_detect(const char *path, bf_format *f, bf_error *err);

/* ---- building a dataset (readers, tests, Python) ---- */

/* A new, empty dataset. NULL when out of memory. */
bf_dataset *bf_dataset_alloc(void);

/* Frees ds; NULL does nothing. */
void bf_dataset_free(bf_dataset *ds);

/* Adds a configuration set of n >= 1 configurations, given in the
 * measurement frame as n rows (theta_i, phi_i, theta_o, phi_o) in radians
 * (SPEC §1.5), copied. Zeniths must lie in [0, pi/2] and azimuths be
 * finite (BF_EINVAL otherwise; *bad, when not NULL, gets the offending
 * row). Its id, 0, 1, ..., goes to *set. */
int bf_dataset_add_configs(bf_dataset *ds, size_t n, const double *angles,
                           size_t *set, size_t *bad);

/* What bf_dataset_add_material copies into a dataset. */
typedef struct {
    const char *name;    /* material name; NULL or "": none (CURET
                            without samples.tsv) */
    int number;          /* material number > 0 (CURET's sample number),
                            or 0: its position, 1-based (index + 1) */
    bf_format format;    /* format it was read from */
    const char *source;  /* file or folder it was read from, or NULL */
    long line;           /* 1-based line of source where its data start
                            (for messages), 0 when none */
    size_t set;          /* its configuration set */
    size_t n_channels;   /* >= 1 */
    const char *const *channel; /* n_channels names ("R", "G", "B",
                            "550", "mean"); NULL: "1", "2", ... */
    const double *wavelength;   /* n_channels wavelengths in nm, or NULL */
    const double *values;       /* n_conf x n_channels, row-major: value
                                   of configuration k, channel c at
                                   values[k * n_channels + c] */
    const unsigned char *valid; /* same layout, 1 valid, 0 invalid (e.g.
                                   MERL's negative cells); NULL: all valid.
                                   A valid value must be finite (negative
                                   is fine: kept as measured, SPEC §2). */
} bf_material_desc;

/* Adds a material (every field copied). BF_EINVAL when the set does not
 * exist, a count is 0, a valid value is not finite, a channel name is
 * empty or the material's number (explicit, or its position) is already taken.
 * Its index goes to *index (may be NULL). */
int bf_dataset_add_material(bf_dataset *ds, const bf_material_desc *desc,
                            size_t *index);

/* Appends every material of src (with their configuration sets) to dst;
 * materials numbered by position get their new position. BF_EINVAL on a
 * number clash (dst unchanged). Used for several --input files. */
int bf_dataset_append(bf_dataset *dst, const bf_dataset *src);

/* ---- reading a dataset (all borrowed pointers live until
 *      bf_dataset_free; m is a material index < bf_dataset_count) ---- */

size_t bf_dataset_count(const bf_dataset *ds);    /* materials */
const char *bf_dataset_name(const bf_dataset *ds, size_t m);
int bf_dataset_number(const bf_dataset *ds, size_t m);
/* Index of the material numbered number, or -1. */
long bf_dataset_find(const bf_dataset *ds, int number);
bf_format bf_dataset_format(const bf_dataset *ds, size_t m);
const char *bf_dataset_source(const bf_dataset *ds, size_t m); /* or "" */
long bf_dataset_line(const bf_dataset *ds, size_t m);  /* or 0 */
size_t bf_dataset_nconf(const bf_dataset *ds, size_t m);
/* Configuration set id of material m: materials with the same id share
 * their configurations (the same geom and angle arrays). */
size_t bf_dataset_set(const bf_dataset *ds, size_t m);
/* The configurations in Beckmann's frame (nconf values). */
const bf_geom *bf_dataset_geom(const bf_dataset *ds, size_t m);
/* The configurations as given, nconf x 4: theta_i, phi_i, theta_o, phi_o
 * (measurement frame, radians). */
const double *bf_dataset_angles(const bf_dataset *ds, size_t m);
size_t bf_dataset_nchannels(const bf_dataset *ds, size_t m);
const char *bf_dataset_channel(const bf_dataset *ds, size_t m, size_t c);
/* Wavelength of channel c in nm, NaN when the channel has none. */
double bf_dataset_wavelength(const bf_dataset *ds, size_t m, size_t c);
/* Values, nconf x nchannels row-major (see bf_material_desc). */
const double *bf_dataset_values(const bf_dataset *ds, size_t m);
/* Valid marks in the same layout, or NULL when every value is valid. */
const unsigned char *bf_dataset_valid(const bf_dataset *ds, size_t m);

/* The channel "mean": the mean over every channel (the default; CURET's
 * abrdf.dat is itself the mean of R, G, B). A configuration has a mean
 * only when every channel is valid there. For one channel the mean is the
 * channel's value, bit for bit. */
#define BF_CHANNEL_MEAN ((size_t)-1)

/* Finds channel name of material m: its name (case-insensitive) or, for a
 * spectral channel, its wavelength in nm ("550" matches 550 nm); "mean"
 * gives BF_CHANNEL_MEAN. BF_ENOTFOUND when absent. */
int bf_dataset_channel_find(const bf_dataset *ds, size_t m,
                            const char *name, size_t *c);

/* The value of configuration k of material m for channel c (or the mean),
 * into *value; returns 1 when valid, 0 when not. */
int bf_dataset_value(const bf_dataset *ds, size_t m, size_t k, size_t c,
                     double *value);

/* What one material holds, for `brdffit info` and for users checking
 * their data (all angles in radians, in the measurement frame). */
#define BF_SUMMARY_NCONES 5
extern const double bf_summary_cones_deg[BF_SUMMARY_NCONES]; /* 1 5 10 15
                                                                25 deg */
typedef struct {
    size_t n_conf;              /* configurations */
    size_t n_channels;
    double theta_i_min, theta_i_max;
    double theta_o_min, theta_o_max;
    double phi_i_min, phi_i_max; /* as given */
    double phi_o_min, phi_o_max;
    size_t n_specular;          /* SPEC §1.4's test (CURET's default) */
    size_t n_cone[BF_SUMMARY_NCONES]; /* with delta < bf_summary_cones_deg */
    double delta_min;           /* the nearest to the mirror direction */
    size_t n_negative;          /* valid values < 0 (kept, SPEC §2) */
    size_t n_zero;              /* valid values == 0 */
    size_t n_invalid;           /* values marked invalid */
    size_t n_conf_invalid;      /* configurations with an invalid value */
    double value_min, value_max; /* over the valid values */
} bf_material_summary;

/* Fills out for material m. BF_EINVAL when m is out of range. */
int bf_dataset_summary(const bf_dataset *ds, size_t m,
                       bf_material_summary *out);

/* File syntax accepted by every reader below (src/data/lineio.c):
 *   - LF or CRLF line ends, the last line with or without one; a CR not
 *     followed by LF is an error (old Mac line ends are not supported);
 *   - a UTF-8 byte order mark at the start of the file is skipped;
 *   - blank lines (empty or only spaces/tabs) are skipped anywhere, but
 *     counted, so reported line numbers are an editor's line numbers;
 *   - trailing spaces and tabs are ignored;
 *   - NUL bytes and lines longer than 1 MiB are errors (BF_EPARSE);
 *   - numbers are decimal ([+-]digits[.digits][e[+-]digits]): hex floats,
 *     nan, inf, values overflowing a double and trailing characters
 *     ("1.5abc") are errors naming the field and quoting the text;
 *   - sample numbers and indices are integers in [1, INT_MAX] ("1.5" and
 *     "-3" are errors).
 * The _load functions open the path (BF_EIO with the system's reason at
 * line 0 when it cannot be opened; a directory, device or socket is also
 * BF_EIO) and accept regular files and FIFOs/pipes. On any error *out is
 * NULL and nothing leaks; err may be NULL. Readers never close fp. */

/* The number of configurations in CURET's table.txt. */
#define BF_CURET_NCONF 205

/* ---- readers: each has a read-from-FILE form (name used in messages;
 *      fp is never closed) and a load-from-path form; on error *out is
 *      NULL and err names the file and the line (text formats) or the byte
 *      offset (MERL: err->line is 0, the message says "byte N") ---- */

/* CURET (SPEC §1.3, §2): table.txt and a BRDF file (brdf_path, or
 * dir/abrdf.dat when NULL) and, when present, dir/samples.tsv (names).
 * One material per sample row, numbered by its sample number, named from
 * samples.tsv (else no name), one channel ("mean" for abrdf.dat, "R",
 * "G", "B" for rbrdf/gbrdf/bbrdf.dat, else the file's base name), all on
 * one configuration set. A table and a BRDF file whose counts differ is an
 * error naming both files and both counts. */
int bf_curet_load(const char *dir, const char *brdf_path, bf_dataset **out,
                  bf_error *err);
/* CURET's table.txt (path) as a configuration list in the measurement
 * frame (SPEC §1.3, §1.5): *angles gets n x 4 radians, rows theta_i,
 * phi_i, theta_o = theta_v, phi_o = phi_v, allocated with malloc (the
 * caller frees it with free()); the table's syntax and errors are
 * bf_curet_load's. Also MERL's default sampling (bf_configs_load for a
 * CSV list). */
int bf_curet_configs_load(const char *path, double **angles, size_t *n,
                          bf_error *err);

/* pbrt-v2 / Cornell .brdf (SPEC §8): one material, W spectral channels
 * named by wavelength; name from the file's description comment, else the
 * file name without its extension. */
int bf_pbrt_read(FILE *fp, const char *name, bf_dataset **out,
                 bf_error *err);
int bf_pbrt_load(const char *path, bf_dataset **out, bf_error *err);

/* ASTM E1392 (SPEC §8): one material; channels from VARS (R, G, B, X, Y,
 * Z, or wavelengths); name from SAMPLE_NAME, else the file name without
 * its extension. */
int bf_astm_read(FILE *fp, const char *name, bf_dataset **out,
                 bf_error *err);
int bf_astm_load(const char *path, bf_dataset **out, bf_error *err);

/* Tidy CSV (README "Tidy CSV"): header theta_i,phi_i,theta_o,phi_o
 * (degrees, SPEC §1.5) and one column per channel, optionally a first
 * column `material`; '#' comment lines; an empty value field is invalid.
 * One or more materials (in order of first appearance); materials listing
 * the same configurations share a configuration set. A channel named
 * "<number>nm" is a wavelength channel, named by the number. */
int bf_csv_read(FILE *fp, const char *name, bf_dataset **out,
                bf_error *err);
int bf_csv_load(const char *path, bf_dataset **out, bf_error *err);

/* Reads a configuration list: a tidy CSV (bf_csv_read's syntax) whose
 * header names theta_i, phi_i, theta_o, phi_o (degrees, SPEC §1.5); any
 * other column is ignored. *angles gets n x 4 radians (measurement frame),
 * allocated with malloc (the caller frees it with free()). Used to choose
 * where a MERL table is sampled. */
int bf_configs_read(FILE *fp, const char *name, double **angles, size_t *n,
                    bf_error *err);
int bf_configs_load(const char *path, double **angles, size_t *n,
                    bf_error *err);

/* MERL .binary (SPEC §8): the dense table, read whole. Opaque. */
typedef struct bf_merl bf_merl;

/* Reads a MERL table: the three dimensions must be 90, 90, 180 and the
 * stream must hold exactly the values they imply (checked against the
 * file size before any allocation when fp is seekable), each finite (a
 * negative one marks its cell invalid and is kept). The table is read
 * with one fread and scaled in place. */
int bf_merl_read(FILE *fp, const char *name, bf_merl **out, bf_error *err);
int bf_merl_load(const char *path, bf_merl **out, bf_error *err);
void bf_merl_free(bf_merl *t);

/* R, G, B values (scaled, SPEC §8) at a configuration in the measurement
 * frame (radians) by MERL's cell lookup; returns 1 when the cell is valid
 * (every channel >= 0), 0 when invalid (rgb still written) or the
 * directions are below the horizon. */
int bf_merl_lookup(const bf_merl *t, double theta_i, double phi_i,
                   double theta_o, double phi_o, double rgb[3]);

/* A dataset of one material (channels R, G, B) sampled from t at n
 * configurations (measurement frame, n x 4, as bf_dataset_add_configs), or
 * -- when at is NULL -- at every valid cell (one configuration per cell, at
 * the directions of the cell's centre, for the cells whose centre lies
 * above the horizon: 1,096,216 of the 1,458,000; the lookup of a centre
 * finds its own cell, src/data/merl.c). An invalid cell gives invalid
 * values on all three channels, kept as read (never clamped to 0).
 * BF_EINVAL for a configuration outside the hemisphere, BF_EDOM when no
 * cell is valid. */
int bf_merl_dataset(const bf_merl *t, size_t n, const double *at,
                    const char *material, const char *source,
                    bf_dataset **out, bf_error *err);

/* Options of bf_dataset_load. */
typedef struct {
    bf_format format;  /* BF_FORMAT_AUTO: bf_format_detect */
    /* MERL only: the configurations to sample (n_at x 4, measurement
     * frame), or all_cells = 1 for every valid cell (which wins over at).
     * A MERL file without either is BF_EINVAL, before it is read (the CLI
     * passes CURET's 205 by default). */
    size_t n_at;
    const double *at;
    int all_cells;
} bf_load_opts;

/* Loads path in any format (opts may be NULL: detect, and MERL fails as
 * above). A folder is read as CURET. */
int bf_dataset_load(const char *path, const bf_load_opts *opts,
                    bf_dataset **out, bf_error *err);

/* ---- per-sample inputs: ON's parameters, refractive indices ---- */

/* A per-sample table of numbers: rows "sample x1 ... xk" with an optional
 * header line (first field not a number). Used for the Oren-Nayar parameter
 * file ("sample rho sigma", or CURET's op.dat "sample rho sigma kd") and the
 * per-sample refractive index file ("sample n"). Opaque; owns memory. */
typedef struct bf_sample_table bf_sample_table;

/* Reads rows with between min_cols and max_cols numbers after the sample
 * number; every value must be finite. Duplicate samples are errors. Every
 * row must have the same number of values. A header line with no rows is
 * BF_EPARSE "header line but no rows" (line 0). max_cols = 0 or
 * min_cols > max_cols: BF_EINVAL. */
int bf_sample_table_read(FILE *fp, const char *name, size_t min_cols,
                         size_t max_cols, bf_sample_table **out,
                         bf_error *err);
int bf_sample_table_load(const char *path, size_t min_cols, size_t max_cols,
                         bf_sample_table **out, bf_error *err);
void bf_sample_table_free(bf_sample_table *st);
size_t bf_sample_table_count(const bf_sample_table *st);
/* Value of column col (0-based, after the sample number) for sample s.
 * Returns BF_OK, or BF_ENOTFOUND when s is absent (BF_EINVAL when col >=
 * bf_sample_table_cols(st)). */
int bf_sample_table_get(const bf_sample_table *st, int sample, size_t col,
                        double *value);
/* Number of values per row (the same for every row). */
size_t bf_sample_table_cols(const bf_sample_table *st);
/* Sample number of row r (file order), or -1 when out of range. */
int bf_sample_table_sample(const bf_sample_table *st, size_t row);

/* Loads an Oren-Nayar parameter file (SPEC §5) and checks rho in [0, 1] and
 * sigma in [0, pi/2] (BF_EPARSE with the line otherwise). */
int bf_on_params_load(const char *path, bf_sample_table **out, bf_error *err);
/* The same from a stream (name is used in messages). */
int bf_on_params_read(FILE *fp, const char *name, bf_sample_table **out,
                      bf_error *err);

/* Loads a per-sample refractive index file ("sample n", n in (1, 10]). */
int bf_n_file_load(const char *path, bf_sample_table **out, bf_error *err);
/* The same from a stream (name is used in messages). */
int bf_n_file_read(FILE *fp, const char *name, bf_sample_table **out,
                   bf_error *err);

/* ======================================================================
 * --- select: configurations, targets and models (SPEC §1.6, §7) ---
 * ====================================================================== */

/* ---- the configurations of a material (SPEC §1.6, §2) ---- */

/* Which configurations of a material the study uses. */
typedef struct {
    /* Half-angle Delta (radians) of the specular cone left out: every
     * configuration with bf_geom_mirror_angle < Delta (SPEC §1.6).
     * BF_CONE_DEFAULT: the format's default -- for CURET the specular
     * test of SPEC §1.4 (bf_geom_is_specular: its 7 configurations), for
     * every other format none. 0: none. */
    double cone;
    /* Leave out configurations whose theta_i or theta_o exceeds it
     * (radians); >= pi/2 keeps all. */
    double max_theta;
    /* Configuration numbers (1-based positions in the material's list, as
     * CURET numbers its 205) to leave out as well. */
    const size_t *exclude;
    size_t n_exclude;
} bf_selection;

#define BF_CONE_DEFAULT (-1.0)

/* Fills s with the defaults: BF_CONE_DEFAULT, max_theta pi/2, nothing
 * excluded. */
void bf_selection_init(bf_selection *s);

/* The used configurations of material m for channel c (or
 * BF_CHANNEL_MEAN): valid for that channel, outside the cone, within
 * max_theta, not excluded. Writes their indices (0-based, increasing) into
 * sel (capacity bf_dataset_nconf(ds, m)) and the count K into *n (K may be
 * 0). *cone_out, when not NULL, gets how many were left out by the cone
 * (or CURET's specular test). BF_EINVAL on bad arguments; BF_ENOTFOUND
 * when an excluded number exceeds the material's configuration count. */
int bf_dataset_select(const bf_dataset *ds, size_t m, size_t c,
                      const bf_selection *s, size_t *sel, size_t *n,
                      size_t *cone_out);

/* Measured radiance of SPEC §2 for material m, channel c, on the n
 * configurations sel: out[j] = value[sel[j]] * cos(theta_i of sel[j]),
 * divided by its maximum over the n values (bf_normalise). BF_EDOM when
 * that maximum is not positive or a selected value is invalid; BF_EINVAL
 * on bad arguments or n = 0. */
int bf_dataset_radiance(const bf_dataset *ds, size_t m, size_t c, size_t n,
                        const size_t *sel, double *out);

/* ---- a study: its targets, samples, models and search ranges ---- */

/* One thing the study fits: a material of the dataset on one channel, or
 * on the mean over its channels (SPEC §2). */
typedef struct {
    size_t material; /* index in the dataset */
    size_t channel;  /* channel index, or BF_CHANNEL_MEAN */
    int joint;       /* 1: fitted jointly with the material's other joint
                        targets (--channel joint, SPEC §9.4): the targets
                        of one material with joint set, consecutive, share
                        the shape parameters and each has its own scales
                        (bf_param.linear) */
} bf_target;

/* Expands materials (n_materials indices; materials = NULL: every material
 * in order) and a channel request into targets, material-major: NULL or
 * "mean": one target per material on BF_CHANNEL_MEAN; "each": one per
 * channel of each material, in channel order; "joint": the same targets
 * as "each" with joint set (SPEC §9.4: one shape for all channels, scales
 * per channel; every channel's data on the configurations valid on all
 * of them, as the mean's); any other text: that channel
 * of every material (bf_dataset_channel_find; BF_ENOTFOUND with err->msg
 * naming the first material that lacks it). *out (n_out targets) is
 * allocated with malloc; the caller frees it with free(). */
int bf_study_targets(const bf_dataset *ds, const size_t *materials,
                     size_t n_materials, const char *channel,
                     bf_target **out, size_t *n_out, bf_error *err);

/* The 24 CURET samples of Ragheb & Hancock's study, in increasing order. */
#define BF_STUDY_NSAMPLES 24
extern const int bf_study_samples[BF_STUDY_NSAMPLES];

/* The models of a study from list, a comma-separated list of registry
 * names (bf_model_find_why: composites D+S too), "all" or NULL
 * (bf_model_set_names(defaults)), into out (room for cap;
 * bf_model_count() + 1 is enough), under the
 * options of SPEC §9.2: with fresnel or smith not DEFAULT, every specular
 * model and the S part of every composite is its variant
 * (bf_model_specular_variant: GGX under BF_FRESNEL_DIELECTRIC has rho_s,
 * alpha, n; LAMBERT+GGX rho_d, rho_s, alpha, n); diffuse models are
 * unaffected. Returns BF_OK; BF_ENOTFOUND for an unknown name; BF_EINVAL
 * for a bad list (an empty name, a trailing comma), a model listed twice,
 * more than cap, or fresnel or smith not a value of its enum; BF_EDOM for
 * a specular model, or fresnel or smith given, under an objective that
 * max-normalises (SPEC §9, §10: !bf_objective_keeps_scale), and -- under
 * one that keeps the scale -- for a specular model that cannot take an
 * option given or options that no listed model takes. err->msg says which
 * ("unknown model 'XX'", "'ON' listed twice", "GGX gives absolute BRDF
 * values (SPEC §9)", "WARD has no Fresnel term (SPEC §9.3): --fresnel
 * applies to GGX, BECKMANN and CT"), for the caller to prefix with its own
 * option's name. "all" is every diffuse model of the registry, in
 * order; under an objective that keeps the scale (bf_objective_keeps_scale:
 * ngan, cuberoot, log1p) it is the complete glossy comparison: those, then
 * for every specular model of the registry (SPEC §9.3), in order, LAMBERT+S
 * (SPEC §9.4), or S alone when it has its own diffuse term (own_diffuse:
 * AS) -- bf_model_count() models. */
int bf_study_models(const char *list, bf_model_set defaults,
                    bf_objective objective, bf_fresnel_kind fresnel,
                    bf_smith_kind smith, const bf_model_type **out,
                    size_t cap, size_t *n, bf_error *err);

/* A user's search range of the parameter called name (--range NAME=LO:HI). */
typedef struct {
    const char *name;
    double lo, hi;
} bf_param_range;
#define BF_STUDY_MAX_RANGES 8

/* The types a study fits for models (n_models registry types): with exact,
 * the exact fit's variants (bf_model_variant_exact(v, keep)); each of the
 * n_ranges ranges (at most BF_STUDY_MAX_RANGES) applied to every model
 * that has the parameter (bf_model_variant_range). out[m] is models[m]
 * when neither applies, else &variants[m].type (variants: room for
 * n_models, not moved afterwards; unused when neither applies, may then be
 * NULL). Returns BF_OK; BF_EINVAL when range *bad_range does not fit model
 * *bad_model's parameter (bf_model_variant_range) or for bad arguments;
 * BF_ENOTFOUND when range *bad_range names no parameter of any model. */
int bf_study_variants(const bf_model_type *const *models, size_t n_models,
                      int exact, unsigned keep, const bf_param_range *ranges,
                      size_t n_ranges, bf_model_variant *variants,
                      const bf_model_type **out, size_t *bad_range,
                      size_t *bad_model);

/* What to fit: targets x models, each target on its own configuration
 * selection (bf_dataset_select with select, for the target's channel). */
typedef struct {
    const bf_dataset *data;       /* the measurements (borrowed) */
    const bf_target *targets;     /* what to fit */
    size_t n_targets;
    bf_selection select;             /* which configurations are used */
    const bf_model_type *const *models; /* models to fit */
    size_t n_models;
    double n_default;             /* refractive index for FC models */
    const bf_sample_table *n_file;    /* n per material number (NULL:
                                         n_default) */
    const bf_sample_table *on_params; /* ON (rho, sigma) per material
                                         number */
    int n_threads;                /* OpenMP threads; 0 or 1: one. The
                                     results do not depend on it. */
} bf_study_spec;

/* The used configurations and the normalised measured radiance (SPEC §2)
 * of target t of spec, exactly as the study fits them: sel and data need
 * the capacity bf_dataset_nconf of the target's material; *k gets K.
 * BF_EDOM (err->msg naming the material) when K = 0 or the data cannot be
 * normalised; BF_ENOTFOUND when an excluded number does not exist. */
int bf_study_target_data(const bf_study_spec *spec, size_t t, size_t *sel,
                         size_t *k, double *data, bf_error *err);

/* The used configurations and measured data of target t exactly as the
 * analysis fits them under objective obj: bf_study_target_data's for the
 * max-normalised objectives; for those that keep the scale (SPEC §10)
 * rho = BRDF x cos theta_i as measured, not normalised, on the
 * configurations with theta_i, theta_o <= 80 degrees
 * (BF_KEEP_SCALE_THETA). Same capacities and errors. */
int bf_study_fit_data(const bf_study_spec *spec, bf_objective obj, size_t t,
                      size_t *sel, size_t *k, double *data, bf_error *err);

/* ======================================================================
 * --- fit: one fit and the paper's study (SPEC §7) ---
 * ====================================================================== */

/* Divides in[0..n) by its maximum into out (may alias). Returns BF_EDOM when
 * the maximum is not positive or a value is not finite; BF_EINVAL if n = 0. */
int bf_normalise(size_t n, const double *in, double *out);

/* The result of one fit. */
typedef struct {
    double param[BF_MAX_PARAMS]; /* all parameters (fitted and fixed) */
    double lse;                  /* sum of squared residuals (SPEC §7.3) */
    unsigned bound_hit;          /* bit j set: fitted param j on a grid bound */
    size_t n_eval;               /* model evaluations used */
    unsigned flat;               /* bit j set: the objective does not depend
                                    on free parameter j at param (ON's rho
                                    at sigma = 0), so the refinement held
                                    it (bf_fit_refine) */
} bf_fit_result;

/* Reusable workspace for fits on up to n configurations. */
typedef struct bf_fit_workspace bf_fit_workspace;
bf_fit_workspace *bf_fit_alloc(size_t n);
void bf_fit_free(bf_fit_workspace *w);

/* LSE of SPEC §7.3 for a model at param against normalised data:
 * sum_k (L_model,k / max L_model - data_k)^2. BF_EDOM when the model is not
 * normalisable there. */
int bf_fit_lse(const bf_model_type *type, const double *param, size_t n,
               const bf_geom *geom, const double *data, bf_fit_workspace *w,
               double *lse);

/* The paper's exhaustive search (SPEC §7.4): every fitted parameter (the
 * ones with param[j].fitted, unless free_mask is nonzero, in which case bit j
 * of free_mask selects parameter j) runs over its grid; the others keep the
 * values of fixed[] (type->p values). Ties keep the first (smallest) grid
 * point. result->bound_hit flags optima on a grid bound. A model with no free
 * parameter is evaluated once. */
int bf_fit_grid(const bf_model_type *type, const double *fixed,
                unsigned free_mask, size_t n, const bf_geom *geom,
                const double *data, bf_fit_workspace *w,
                bf_fit_result *result);

/* ---- a fitting problem and its exact optimum (doc/methods.md §2) ---- */

/* A fitting problem: one model on n configurations against normalised data,
 * under an objective, with optional per-configuration weights (NULL: all 1;
 * the bootstrap and cross-validation pass counts and 0/1 masks). Parameter
 * j is free when bit j of free_mask is set; the others keep fixed[j]. A
 * free parameter is searched in [lo[j], hi[j]], which must lie in its
 * domain [min, max]. Plain value struct; owns nothing. */
typedef struct {
    const bf_model_type *type;
    double fixed[BF_MAX_PARAMS]; /* values of every parameter (free ones:
                                    a starting value) */
    unsigned free_mask;          /* bit j: parameter j is fitted */
    double lo[BF_MAX_PARAMS];    /* search range of the free parameters */
    double hi[BF_MAX_PARAMS];
    size_t n;                    /* configurations */
    const bf_geom *geom;         /* n configurations */
    const double *data;          /* n normalised measured values */
    const double *weight;        /* n weights >= 0, or NULL for all 1 */
    bf_objective objective;
    double noise_power;          /* p of the likelihood's noise model
                                    (bf_fit_intervals sets it; 0 else) */
} bf_problem;

/* Fills pb for type on (n, geom, data): free parameters are the ones the
 * paper fits (param[j].fitted) with their grid range as search range,
 * fixed[] copies fixed (type->p values; NULL: the defaults), objective
 * BF_OBJ_MAX, no weights. Returns BF_EINVAL on bad arguments. */
int bf_problem_init(bf_problem *pb, const bf_model_type *type,
                    const double *fixed, size_t n, const bf_geom *geom,
                    const double *data);

/* Number of free parameters of pb. */
size_t bf_problem_nfree(const bf_problem *pb);

/* Objective S of pb at param (type->p values). work holds 2 n doubles.
 * Returns BF_OK, BF_EDOM when the model is undefined or not normalisable
 * there, or BF_EINVAL (parameter outside its domain, bad arguments). */
int bf_problem_value(const bf_problem *pb, const double *param, double *work,
                     double *value);

/* Residuals r_k of pb at param (see bf_objective) into resid (n values;
 * the objective is sum_k w_k r_k^2). work holds n doubles. */
int bf_problem_residuals(const bf_problem *pb, const double *param,
                         double *work, double *resid);

/* Exact refinement (doc/methods.md §2): starting from start (a grid
 * optimum), minimises pb's objective over the free parameters within
 * [max(lo_j, x_j - step_j), min(hi_j, x_j + step_j)] (step_j: the
 * parameter's grid step; the whole search range when it has none) with
 * GSL's Brent minimiser for one free parameter and the Nelder-Mead simplex
 * (nmsimplex2, on a sine-mapped box so that no trial point leaves it) for
 * two or more, to |delta param| < BF_REFINE_TOL. The result never has a
 * larger objective than start (the better of the two is kept) and never
 * leaves the search range. When the minimum ends on an edge of the box
 * inside the search range -- the grid optimum was more than a step away
 * from it, as where two parameters trade off on a coarse grid (WNO-R's
 * sigma and n) -- the box is re-centred there and the search repeated, at
 * most BF_REFINE_WALKS times, while the objective decreases. On the
 * paper's grids this never happens for the 24 study samples (tested).
 * result->bound_hit flags free parameters that end on a bound of the
 * search range [lo, hi]; result->n_eval counts every evaluation. Returns
 * BF_OK, BF_ENOCONV (iteration limit; result holds the best point found),
 * BF_EDOM or BF_EINVAL. */
#define BF_REFINE_TOL 1e-6
#define BF_REFINE_MAXITER 2000
#define BF_REFINE_WALKS 20
int bf_fit_refine(const bf_problem *pb, const bf_fit_result *start,
                  bf_fit_result *result);

/* Minimises pb's objective over its free parameters within the whole search
 * box [lo, hi], starting from start (used for the profile's nuisance
 * parameters): 1 free parameter by a 17-point scan and Brent, more by the
 * mapped simplex. Same contract as bf_fit_refine. */
int bf_fit_minimise(const bf_problem *pb, const double *start,
                    bf_fit_result *result);

/* Normalised model curves at every point of the grid of pb's free
 * parameters (their grid step, over [lo, hi]) for pb's configurations, so
 * that the grid optimum of any data, weights and objective costs no model
 * evaluation. Opaque; owns memory. */
typedef struct bf_curves bf_curves;

/* Builds the curves of pb (its data and weights are not used). NULL with
 * *status (BF_EINVAL: a free parameter without grid; BF_ENOMEM) on
 * failure. */
bf_curves *bf_curves_alloc(const bf_problem *pb, int *status);
void bf_curves_free(bf_curves *c);
/* Number of grid points. */
size_t bf_curves_points(const bf_curves *c);
/* Grid optimum of pb (same type, free parameters, geometry as the curves)
 * under its objective and weights; ties keep the first point; bound_hit
 * flags optima on a bound of the grid. BF_EDOM when no point is defined. */
int bf_curves_best(const bf_curves *c, const bf_problem *pb,
                   bf_fit_result *result);

/* The free scale of pb at param under an objective that keeps the scale
 * (SPEC §9.4, §10): rho_d with the model's value rho_d d(i, o), d its shape
 * scaled so that d = 1/pi at normal incidence and view (LAMBERT: rho_d is
 * the albedo), into *rho_d. BF_EINVAL for another objective or bad
 * arguments, BF_EDOM where the model is undefined or its value at normal
 * incidence and view is not positive. */
int bf_fit_scale(const bf_problem *pb, const double *param, double *rho_d);

/* ---- the paper's study on a dataset (SPEC §7) ---- */

/* The outcome of one (target, model) pair. */
typedef struct {
    size_t target;                /* index into spec->targets */
    size_t material;              /* its material (dataset index) */
    int sample;                   /* the material's number
                                     (bf_dataset_number) */
    size_t channel;               /* its channel, or BF_CHANNEL_MEAN */
    size_t k;                     /* K, configurations used */
    const bf_model_type *type;    /* model */
    int status;                   /* BF_OK; BF_ENOTFOUND when an input is
                                     missing (ON without parameters) */
    bf_fit_result fit;            /* valid when status == BF_OK */
    double albedo[4];             /* the directional albedo of the fit's
                                     specular part at theta_i = 0, 30, 60,
                                     80 degrees; NaN: none (a diffuse
                                     model, a failed quadrature, a failed
                                     row); bf_study_row_albedo */
} bf_study_row;

/* Runs the paper's protocol (SPEC §7) for every target and model, writing
 * n_targets * n_models rows (target-major) into rows. Targets that share a
 * configuration set and selection share the model curves. A target whose
 * data cannot be normalised, or that keeps no configuration, is an error
 * (returned, with err->msg naming the material); a model that cannot be
 * evaluated for a target for lack of inputs gets its row's status set and
 * the study goes on. */
int bf_study_run(const bf_study_spec *spec, bf_study_row *rows,
                 bf_error *err);

/* The check of the n rows a study wrote (bf_study_run, bf_study_analyse):
 * BF_OK when every row is BF_OK or BF_ENOTFOUND (a missing input: a gap
 * the tables leave and the caller notes); otherwise the first other row's
 * status (BF_EDOM: the model cannot be normalised on the used
 * configurations, SPEC §2; BF_ENOMEM), its index in *bad (may be NULL). */
int bf_study_rows_check(const bf_study_row *rows, size_t n, size_t *bad);

/* Fills row->albedo from row->type and row->fit: the directional albedo of
 * the specular part (bf_model_specular_part, bf_model_albedo) at theta_i
 * = 0, 30, 60 and 80 degrees, NaN where the quadrature fails, for a
 * diffuse model and for a row whose status is not BF_OK. bf_study_run and
 * bf_study_analyse call it once for every row whose fit they write, so
 * that fits.csv (bf_fits_lines) and the report's energy table read it;
 * a row built by hand needs it before those. NULL row: nothing. */
void bf_study_row_albedo(bf_study_row *row);

/* 1 when any of row->albedo (bf_study_row_albedo) is over 1, the
 * white-furnace check's failure (fits.csv's albedo_over_1, the report's
 * energy table); 0 otherwise: a NaN albedo (none) never counts, so a
 * diffuse model's or a failed row's is 0. NULL row: 0. */
int bf_study_row_albedo_over_1(const bf_study_row *row);

/* The paper's default refractive index for FC models (SPEC §4.2). */
#define BF_DEFAULT_N 1.7

/* ======================================================================
 * --- analyse: intervals, criteria, ranking (doc/methods.md §3-5) ---
 * ====================================================================== */

/* ---- intervals and their calibration (doc/methods.md §3) ---- */

/* Profile interval (doc/methods.md §3): the set of values theta_j for
 * which n ln(S_p(theta_j) / S_min) <= chi2_1(level), where S_p is the
 * objective minimised over the other free parameters and n the sum of the
 * weights. best is the exact optimum (bf_fit_refine). The interval is
 * clipped to [lo_j, hi_j]; *open gets bit 0 (low end) and bit 1 (high end)
 * when it reaches the search range there, and bit 2 when that set is
 * split: besides the optimum's region the profile is below the threshold
 * in another, apart from it or behind a ridge inside it (found by a scan
 * of the search range and a check between the estimate and each end; a
 * diffuse model's only); low and high are then the hull of them all
 * (bf_fit_intervals reports the gap of a set in two regions,
 * bf_interval.gap_low; doc/methods.md §3). Bit 3 when a second minimum
 * competes with the estimate's: the set is split, or the scan found
 * another minimum of the profile whose criterion is at most 4
 * chi2_1(level) (bf_interval.competing). */
int bf_fit_profile_ci(const bf_problem *pb, const bf_fit_result *best,
                      size_t j, double level, double *low, double *high,
                      unsigned *open);

/* The noise model behind the intervals (doc/methods.md §3): the data are
 * D_k = s L_k(theta) + e_k with an unknown scale s (a nuisance parameter,
 * never the one noisy maximum), e_k independent Gaussian, var e_k =
 * sigma^2 max(L_k, BF_LOG_FLOOR)^p:
 *   BF_NOISE_AUTO      p estimated from the residuals (power law, p in
 *                      [0, BF_NOISE_PMAX]; the default);
 *   BF_NOISE_ABSOLUTE  p = 0 (constant variance);
 *   BF_NOISE_RELATIVE  p = 2 (sd proportional to the value);
 *   BF_NOISE_OBJECTIVE the objective's own S as a constant-variance RSS
 *                      with the scale the objective gives it: the profile
 *                      intervals of the objective alone, kept to compare
 *                      with earlier results (they undercover under max).
 * A specular model or composite (SPEC §9; its scales are parameters, in
 * sr^-1): rho_k = rho_hat_k(theta) + e_k, var e_k = sigma^2 M^2
 * max(rho_hat_k / M, BF_LOG_FLOOR)^p, M = max_k rho_hat_k, the variances
 * held at the fit (generalised least squares, doc/methods.md §3); its
 * scales are solved by NNLS at every point of a profile. */
typedef enum {
    BF_NOISE_AUTO = 0,
    BF_NOISE_ABSOLUTE,
    BF_NOISE_RELATIVE,
    BF_NOISE_OBJECTIVE
} bf_noise;

/* Largest noise power p BF_NOISE_AUTO considers: relative noise (a variance
 * growing faster than the squared mean is a lack of fit, not noise;
 * doc/methods.md §3). */
#define BF_NOISE_PMAX 2.0

/* "auto", "absolute", "relative", "objective" (static storage), NULL for
 * an unknown value; bf_noise_find: BF_ENOTFOUND for an unknown name. */
const char *bf_noise_name(bf_noise noise);
/* The variance the noise model states, for captions: "constant
 * variance", "variance ~ value^2", "variance ~ value^p, p fitted per fit"
 * (auto), "the objective's own S" (static storage), NULL for an unknown
 * value. */
const char *bf_noise_variance(bf_noise noise);
int bf_noise_find(const char *name, bf_noise *noise);

/* How an interval was computed (bf_interval.method, fits.csv ci_method). */
typedef enum {
    BF_CI_NONE = 0,
    BF_CI_PROFILE,    /* "profile": the objective's S (BF_NOISE_OBJECTIVE) */
    BF_CI_PROFILE_LIK, /* "profile-lik": the noise model's likelihood, scale
                          and noise level profiled, F threshold */
    BF_CI_RESIDUAL_BOOTSTRAP, /* "residual-bootstrap": percentiles of
                                maximum-likelihood refits of the fitted
                                curve plus resampled standardised
                                residuals (bf_fit_bootstrap) */
    BF_CI_NEYMAN /* "neyman": the likelihood's profile with each end's
                    threshold calibrated by simulation there (the Neyman
                    construction, bf_fit_neyman) */
} bf_ci_method;

/* "", "profile", "profile-lik", "residual-bootstrap", "neyman" (static
 * storage), NULL for unknown. */
const char *bf_ci_method_name(bf_ci_method m);

/* The intervals of every free parameter of one fit. */
typedef struct {
    bf_ci_method method;
    bf_noise noise;           /* the model asked for */
    double noise_power;       /* p used (NaN for BF_NOISE_OBJECTIVE) */
    double sigma;             /* noise sd at the fitted curve's maximum,
                                 relative to it: sqrt(RSS_v / (n - k)) /
                                 scale (bf_fit_calibrate's sigma) */
    double scale;             /* maximum-likelihood scale s */
    bf_fit_result ml;         /* the estimate the intervals are about: the
                                 maximum-likelihood one (BF_NOISE_OBJECTIVE:
                                 best) */
    double low[BF_MAX_PARAMS]; /* NaN for parameters that are not free */
    double high[BF_MAX_PARAMS];
    unsigned open;            /* bits 2j, 2j+1: low/high end at the range */
    unsigned not_identified;  /* bit j: the profile stays below the
                                 threshold to a bound of the search range
                                 on a side where the estimate is not on
                                 that bound (the end is the bound), or is
                                 below it in a region apart from the
                                 estimate's too (bf_fit_profile_ci's
                                 split: two segments, gap_low and
                                 gap_high; more: the interval their
                                 hull) */
    double robust[BF_MAX_PARAMS]; /* BF_CI_PROFILE_LIK: the factor >= 1
                                 parameter j's threshold was multiplied by,
                                 its variance from the residuals (sandwich)
                                 over the noise model's where larger
                                 (doc/methods.md §3); NaN otherwise */
    double gap_low[BF_MAX_PARAMS]; /* a split set of two regions (bit j of
                                 not_identified): [low, gap_low] and
                                 [gap_high, high], the values between them
                                 outside; NaN when the set is one region
                                 (or more than two: the hull stands) */
    double gap_high[BF_MAX_PARAMS];
    unsigned competing;       /* bit j: a second minimum of parameter j's
                                 profile competes with the estimate's (bit
                                 3 of bf_fit_profile_ci's open): the set
                                 is split, or the profile has another
                                 minimum whose criterion is at most 4
                                 times the threshold (look-elsewhere: a
                                 measurement's optimum can fall into it;
                                 doc/methods.md §3) */
    unsigned neyman;          /* bit j: parameter j's interval is the
                                 Neyman construction's (bf_fit_neyman);
                                 method is
                                 BF_CI_NEYMAN when every free parameter's
                                 is */
} bf_interval;

/* 1 when x lies in parameter j's interval of iv: in [low, high] and not
 * strictly inside its gap; 0 otherwise (NaN ends: 0). */
int bf_interval_holds(const bf_interval *iv, size_t j, double x);
/* The length of parameter j's interval of iv: high - low less its gap
 * (NaN without an interval). */
double bf_interval_length(const bf_interval *iv, size_t j);

/* The intervals at level (e.g. 0.95) of pb's free parameters around the
 * fit best (bf_fit_refine under pb's objective) under the noise model
 * noise (doc/methods.md §3). BF_EDOM when the noise cannot be estimated
 * (the sum of the weights is not above the number of estimated
 * parameters: free ones, the scale, p when estimated) or no interval can
 * be found; BF_EINVAL, BF_ENOMEM. */
int bf_fit_intervals(const bf_problem *pb, const bf_fit_result *best,
                     bf_noise noise, double level, bf_interval *out);

/* What simulated measurements say about a fit's intervals
 * (bf_fit_calibrate, `brdffit calibrate`, doc/methods.md §3). */
typedef struct {
    size_t n_sim;                    /* simulations fitted */
    size_t n_failed;                 /* simulations that could not be */
    double truth[BF_MAX_PARAMS];     /* the parameters simulated */
    double coverage[BF_MAX_PARAMS];  /* share of intervals with the truth
                                        (bf_interval_holds: a split one's
                                        gap is outside): the intervals the
                                        analysis gives with the same
                                        noise, n_neyman and neyman_every */
    double bias[BF_MAX_PARAMS];      /* mean estimate - truth (the
                                        objective's estimate) */
    double sd[BF_MAX_PARAMS];        /* sd of those estimates */
    double ml_bias[BF_MAX_PARAMS];   /* the same for the maximum-likelihood */
    double ml_sd[BF_MAX_PARAMS];     /*   estimates the intervals are about */
    double width[BF_MAX_PARAMS];     /* median interval width (less the
                                        gap of a split one,
                                        bf_interval_length) */
    double not_identified[BF_MAX_PARAMS]; /* share flagged not identified */
    double boot_coverage[BF_MAX_PARAMS]; /* the same share for the
                                            bootstrap's intervals (NaN
                                            without n_boot) */
    double boot_width[BF_MAX_PARAMS];    /* their median width */
    double f_coverage[BF_MAX_PARAMS];    /* the same share for the
                                            profile threshold's intervals
                                            before any Neyman construction
                                            (coverage when none is made) */
    double f_width[BF_MAX_PARAMS];       /* their median width */
    double competing[BF_MAX_PARAMS];     /* share whose profile has a
                                            competing second minimum
                                            (bf_interval.competing) */
} bf_calibration;

/* Fewest simulations bf_fit_calibrate accepts. */
#define BF_CALIBRATE_MIN_SIM 10
/* Fewest simulations per threshold bf_fit_neyman accepts: its 95 %
 * quantile is then the 96th of 100 (at 20 it would be the largest, and the
 * ends of WNO's n on CURET sample 1 swung between 1.25 and the range's
 * 2.5 from one pass to the next; at 200 they settle at 1.222). */
#define BF_NEYMAN_MIN_SIM 100
/* Simulations per threshold of the default intervals' construction, where
 * a second minimum competes (bf_analysis_opts_init, BF_REPORT_OPTIONS_INIT,
 * `--neyman auto`). */
#define BF_NEYMAN_AUTO_SIM 100

/* Simulates n_sim measurements of pb's model at truth on pb's
 * configurations -- D_k = L_k(truth) + sigma max(L_k, BF_LOG_FLOOR)^(p/2)
 * eps_k, eps ~ N(0, 1) (GSL mt19937 seeded with seed), normalised by
 * their maximum as measured data are (a specular model's: rho_k =
 * M (L_k + sigma max(L_k, f)^(p/2) eps_k), L = rho_hat(truth) / M, kept
 * in sr^-1) -- fits each under pb's objective (grid optimum, refinement;
 * a specular model's separable fit) and computes its intervals under noise at
 * level; out gets each free parameter's coverage, bias, spread and median
 * width (NaN for the others); with n_boot >= 2 also the coverage and
 * median width of each simulation's bootstrap interval (bf_fit_bootstrap,
 * n_boot replicates, seed seed + 1 + the simulation's index; a simulation
 * whose bootstrap fails counts as failed). With n_neyman >=
 * BF_NEYMAN_MIN_SIM each simulation's intervals are the analysis's
 * (bf_analysis_opts): the Neyman construction (bf_fit_neyman, n_neyman
 * simulations per threshold, seed seed + 1 + n_sim + the simulation's
 * index) for every free parameter with neyman_every, else for those whose
 * profile has a competing second minimum (none for a specular model, nor
 * under BF_NOISE_OBJECTIVE); f_coverage, f_width are the profile
 * threshold's before it. BF_EINVAL for bad arguments, n_sim < 10, or
 * neyman_every with a specular model or BF_NOISE_OBJECTIVE; BF_EDOM when
 * pb's noise cannot be estimated (bf_fit_intervals), BF_ENOMEM. */
int bf_fit_calibrate(const bf_problem *pb, const double *truth,
                     double noise_power, double sigma, bf_noise noise,
                     size_t n_sim, size_t n_boot, size_t n_neyman,
                     int neyman_every, unsigned long seed, double level,
                     bf_calibration *out);

/* The band of bf_calibration_summarise: the central share of the
 * coverages that calibrated intervals give by chance. */
#define BF_CALIBRATION_BAND 0.99

/* What a calibration says of parameter j's intervals, as the tables show
 * it (`brdffit calibrate`, `brdffit report --calibrate`; doc/methods.md
 * §3), from c (bf_fit_calibrate) at the intervals' level. */
typedef struct {
    size_t n;              /* simulations fitted (c->n_sim) */
    double coverage;       /* c->coverage[j] */
    double coverage_sd;    /* sd of the coverage of calibrated intervals
                              over n simulations: sqrt(level (1 - level)
                              / n) */
    double band_low;       /* the band: the shares x/n of the counts x */
    double band_high;      /*   whose lower and upper tail probabilities
                              under Binomial(n, level) are both at least
                              (1 - BF_CALIBRATION_BAND) / 2 */
    int verdict;           /* -1 coverage below the band (the intervals
                              cover less than they say), 1 above it, 0
                              inside */
    double bias_sd;        /* c->ml_bias[j] / c->ml_sd[j]: the bias of the
                              estimate the intervals are about, in sds */
    double width_spread;   /* c->width[j] / (2 z c->ml_sd[j]), z the
                              standard normal quantile of (1 + level) / 2:
                              1 when the median interval is as wide as the
                              estimates' spread asks */
    double not_identified; /* c->not_identified[j] */
} bf_calibration_summary;

/* Fills out for parameter j of c at level. BF_EINVAL for a parameter
 * that was not calibrated (NaN coverage, no simulation), j out of range
 * or level outside (0, 1). */
int bf_calibration_summarise(const bf_calibration *c, size_t j, double level,
                             bf_calibration_summary *out);

/* The residual bootstrap under a fit's noise model (doc/methods.md §3,
 * ci_method "residual-bootstrap"): iv from bf_fit_intervals(pb, ...) (its
 * maximum-likelihood estimate, scale and noise power; BF_EDOM unless
 * iv->method is BF_CI_PROFILE_LIK); n_boot replicates D*_k = s L_k(ml) +
 * sqrt(v_k) u*_k, u* drawn with replacement from the centred residuals
 * standardised by the noise model's sd sqrt(v_k) and the leverage
 * sqrt(1 - h_k) (a GSL mt19937 seeded with seed), each refitted by
 * maximum likelihood at iv's noise power with the scale profiled (a
 * specular model: D* = rho_hat(ml) + sqrt(v_k) u*_k, refitted with its
 * scales solved under the weights of iv's fit). low[j], high[j] get the (1 -+ level)/2 quantiles of the replicate
 * estimates of every free parameter j (NaN for the others). pb->weight
 * must be NULL. BF_EINVAL, BF_EDOM, BF_ENOMEM. */
int bf_fit_bootstrap(const bf_problem *pb, const bf_interval *iv,
                     size_t n_boot, unsigned long seed, double level,
                     double *low, double *high);

/* The Neyman construction (doc/methods.md §3, ci_method "neyman";
 * Feldman & Cousins 1998, the profile construction): iv from
 * bf_fit_intervals(pb, ...) (BF_EDOM unless iv->method is
 * BF_CI_PROFILE_LIK, or for a specular model); for every free parameter j
 * of which (bits j; iv->competing: those of the analysis's default,
 * bf_analysis_opts.neyman_every 0; pb->free_mask: every one) the set { theta_j : D(theta_j) <= c(theta_j) }, D the profile criterion
 * of iv's likelihood, c(theta_j) the level-quantile of D over n_sim
 * measurements simulated under iv's noise model (power, sigma) at theta_j
 * and the other parameters' constrained estimate there, each fitted as
 * data are (grid optimum, refinement, maximum likelihood at iv's power;
 * a GSL mt19937 seeded with seed, the same deviates at every theta_j).
 * Each end is the fixed point of end -> the profile's end under the
 * threshold c(end), from iv's end. *out gets *iv with those ends (low,
 * high; open bits 2j, 2j+1 when the low/high end is the search range's),
 * the gap of a split set from the profile under its side's end's c
 * (gap_low, gap_high; NaN: none), bit j of neyman for each parameter
 * constructed, and method BF_CI_NEYMAN when every free parameter's is. It
 * costs about 4 n_sim fits per parameter constructed; none when which
 * holds no free parameter. A parameter whose construction fails keeps iv's ends,
 * and the first such failure's code is returned (BF_EDOM). BF_EINVAL for
 * n_sim < BF_NEYMAN_MIN_SIM or bad arguments, BF_ENOMEM. */
int bf_fit_neyman(const bf_problem *pb, const bf_interval *iv, unsigned which,
                  size_t n_sim, unsigned long seed, double level,
                  bf_interval *out);

/* ---- information criteria, cross-validation (doc/methods.md §4-5) ---- */

/* Information criteria with Gaussian errors (doc/methods.md §4) for a
 * residual sum of squares rss > 0 on n points with k parameters:
 * AIC = n ln(rss/n) + 2k, BIC = n ln(rss/n) + k ln n. */
double bf_criterion_aic(double rss, size_t n, size_t k);
double bf_criterion_bic(double rss, size_t n, size_t k);

/* Number of parameters counted by AIC/BIC for pb: its free parameters,
 * plus 1 for the fitted scale of BF_OBJ_SCALE (the max-normalisation of
 * the other objectives is not a parameter; doc/methods.md §4). */
size_t bf_problem_nparams(const bf_problem *pb);

/* Deterministic assignment of n configurations to folds (0..folds-1): a
 * fixed-seed (seed) shuffle of 0..n-1, position p in fold p mod folds, so
 * fold sizes differ by at most one. BF_EINVAL unless 2 <= folds <= n. */
int bf_fit_cv_folds(size_t n, size_t folds, unsigned long seed, size_t *fold);

/* k-fold cross-validated error (doc/methods.md §5): for each fold the
 * model is fitted to the other folds (grid optimum on curves, then
 * bf_fit_refine) and the squared residuals r_k^2 of the held-out
 * configurations under that fit are summed; *cv is that sum over all n
 * configurations (comparable to the LSE, which is a sum too). */
int bf_fit_cv(const bf_problem *pb, const bf_curves *curves, size_t folds,
              unsigned long seed, double *cv);

/* ---- the study's analysis ---- */

/* Progress of a long computation: done of total units of work (one
 * (target, model) pair each) are finished. Called from the thread that
 * finished one, never from two threads at once; done grows by one per
 * call, the last call has done == total. */
typedef void (*bf_progress_fn)(void *ctx, size_t done, size_t total);

/* What bf_study_analyse computes for each (target, model). */
typedef struct {
    bf_objective objective; /* what is minimised */
    int exact;              /* 1: rows' fit is the refined optimum */
    double level;           /* interval level, e.g. 0.95 */
    size_t n_boot;          /* bootstrap replicates, 0 for none */
    size_t folds;           /* cross-validation folds, 0 for none */
    unsigned long seed;     /* of the bootstrap and the folds */
    bf_progress_fn progress; /* NULL: none */
    void *progress_ctx;
    bf_noise noise;         /* the intervals' noise model (BF_NOISE_AUTO) */
    int no_intervals;       /* 1: no interval -- neither the profile
                               intervals nor the noise model's fit they are
                               about (ci_low, ci_high, ml_param,
                               noise_power stay NaN, ci_method
                               BF_CI_NONE); the fits, AIC, BIC and CV as
                               always. n_boot must then be 0. */
    size_t n_neyman;        /* 0: the profile intervals alone; else a
                               diffuse model's intervals are the Neyman
                               construction's, with this many simulations
                               per threshold (bf_fit_neyman, ci_method
                               "neyman"; at least BF_NEYMAN_MIN_SIM;
                               seeded with seed), for the parameters
                               neyman_every says */
    int neyman_every;       /* 1: every free parameter's; 0: those whose
                               profile has a second minimum that competes
                               with the estimate's (bf_interval.competing:
                               where the profile threshold's look-elsewhere
                               makes it cover less than it says;
                               doc/methods.md §3), and none under the
                               objective's own noise model or without
                               intervals */
} bf_analysis_opts;

/* Fills o with the defaults of the analysis (the CLI's): objective max
 * (the paper's), exact 0, level 0.95, no bootstrap, 10 folds, seed 1, no
 * progress callback, the intervals computed (no_intervals 0), the
 * construction where a second minimum competes (n_neyman
 * BF_NEYMAN_AUTO_SIM, neyman_every 0). */
void bf_analysis_opts_init(bf_analysis_opts *o);

/* BF_OK when o is an analysis bf_study_analyse can run (a known objective
 * and noise model, level in (0, 1), no bootstrap nor every parameter's
 * Neyman construction with no_intervals, n_neyman 0 or at least
 * BF_NEYMAN_MIN_SIM, and not every parameter's construction with the
 * objective's own noise model), else
 * BF_EINVAL with err (NULL allowed) saying which field is wrong. The
 * check bf_study_analyse makes first; a caller can make it before the
 * fits. */
int bf_analysis_opts_check(const bf_analysis_opts *o, bf_error *err);

/* What the analysis of one pair says about its fit (bf_fit_stats.flags). */
enum {
    BF_STAT_NOCONV = 1u << 0,  /* the refinement stopped at its iteration
                                  limit (BF_REFINE_MAXITER): the optimum is
                                  the best point found, not converged */
    BF_STAT_REDUCED = 1u << 1, /* the optimum is on the face where the model
                                  is another one (type->reduces_to: ON at
                                  sigma = 0 is LAMBERT) */
    BF_STAT_CLAMPED = 1u << 2, /* the model's formula was clamped at the
                                  optimum (ON at 0 on n_clamped
                                  configurations, doc/methods.md §8) */
    BF_STAT_CI_FAIL = 1u << 3, /* a profile interval could not be found
                                  (its ends are NaN) */
    BF_STAT_BOOT_FAIL = 1u << 4, /* the bootstrap could not be done */
    BF_STAT_BOOT_SPLIT = 1u << 5 /* a parameter's replicate estimates fall
                                   into separate groups (optima in
                                   different basins): its percentile
                                   interval spans them (boot_split) */
};

/* The analysis of one (sample, model) pair. Fields of parameters that are
 * not free are NaN. */
typedef struct {
    int done;                       /* 1 when filled */
    bf_objective objective;
    unsigned free_mask;             /* parameters fitted */
    bf_fit_result grid;             /* grid optimum under the objective */
    bf_fit_result refined;          /* exact optimum (bf_fit_refine) */
    double ci_low[BF_MAX_PARAMS];   /* profile interval */
    double ci_high[BF_MAX_PARAMS];
    unsigned ci_open;               /* bits 2j, 2j+1: low/high end of param
                                       j's interval at the search range */
    double boot_low[BF_MAX_PARAMS]; /* bootstrap interval (NaN if none) */
    double boot_high[BF_MAX_PARAMS];
    size_t n;                       /* configurations */
    size_t k;                       /* parameters counted by AIC/BIC */
    double aic, bic;                /* of the refined optimum */
    double cv;                      /* cross-validated error, NaN if none */
    unsigned flags;                 /* BF_STAT_* */
    size_t n_clamped;               /* BF_STAT_CLAMPED: configurations */
    const char *reduces_to;         /* BF_STAT_REDUCED: the model it is
                                       (static storage), else NULL */
    unsigned boot_split;            /* bit j: parameter j's replicates
                                       split (BF_STAT_BOOT_SPLIT) */
    double scale;                   /* the refined optimum's free scale:
                                       rho_d (SPEC §9.4) under the
                                       objectives that keep the scale
                                       (bf_fit_scale), NaN otherwise */
    bf_ci_method ci_method;         /* of ci_low, ci_high */
    double noise_power;             /* p of the noise model (NaN: none) */
    double noise_sigma;             /* its sd at the fitted maximum,
                                       relative (bf_interval.sigma) */
    double ml_param[BF_MAX_PARAMS]; /* the estimate the intervals are
                                       about (bf_interval.ml) */
    unsigned not_identified;        /* bit j (bf_interval.not_identified) */
    bf_ci_method boot_method;       /* of boot_low, boot_high
                                       (BF_CI_RESIDUAL_BOOTSTRAP; NONE if none) */
    double ci_robust[BF_MAX_PARAMS]; /* the robust factor of ci_low, ci_high
                                        (bf_interval.robust; NaN if none) */
    double ci_gap_low[BF_MAX_PARAMS]; /* the gap of a split interval:
                                         ci_low..ci_gap_low and
                                         ci_gap_high..ci_high
                                         (bf_interval.gap_low, gap_high;
                                         NaN if none) */
    double ci_gap_high[BF_MAX_PARAMS];
    unsigned ci_competing;          /* bit j: a second minimum of param
                                       j's profile competes with the
                                       estimate's (bf_interval.competing) */
    unsigned ci_neyman;             /* bit j: param j's interval is the
                                       Neyman construction's
                                       (bf_interval.neyman; fits.csv's
                                       ci_method "neyman" on its row) */
} bf_fit_stats;

/* How parameter j's interval in st was computed: BF_CI_NEYMAN when it is
 * the Neyman construction's (bit j of st->ci_neyman: the default
 * construction where a second minimum competes, or every parameter's),
 * else st->ci_method. */
bf_ci_method bf_fit_stats_ci_method(const bf_fit_stats *st, size_t j);

/* Analyses every (target, model) of spec under opts: grid optimum under
 * the objective, exact refinement, profile (and bootstrap) intervals,
 * AIC, BIC and cross-validated error, into stats (n_targets x n_models,
 * target-major, like rows; stats[i].done = 0 where a row could not be
 * analysed). When opts->exact, each row's target fields, type and status
 * are set here and its fit is the refined optimum; otherwise rows are left as
 * bf_study_run wrote them (the paper's grid optima) and only read. Errors
 * as bf_study_run. Under the objectives that keep the scale (SPEC §10)
 * the targets' data are rho as measured on the configurations with
 * theta_i, theta_o <= 80 degrees (K counts those), and the lse of the
 * stats' grid and refined optima and of the rows is the value SPEC §10
 * reports (bf_objective_report: ngan's E); AIC and BIC use the sum S.
 * Joint targets (bf_target.joint, SPEC §9.4) are fitted together: one
 * shape, each channel's scales solved exactly (ngan only), S summed over
 * the channels, each channel's row and stats holding the shape and its
 * own scales, lse E = sqrt(S / (K C)), stats' n = K C; BF_EINVAL (err->msg
 * why) under another objective or for a model without a free scale
 * (bf_param.linear). bf_study_run refuses joint targets (BF_EINVAL): the
 * paper's protocol max-normalises the scales away. */
int bf_study_analyse(const bf_study_spec *spec, const bf_analysis_opts *opts,
                     bf_study_row *rows, bf_fit_stats *stats, bf_error *err);

/* bf_fit_calibrate for pair u (target u / n_models, model u % n_models) of a
 * study analysed by bf_study_analyse(spec, opts, rows, stats): at the
 * target's configurations, the pair's refined parameters as the truth and
 * its fitted noise model (stats[u].noise_power, noise_sigma), under
 * opts's objective, noise, level and bootstrap (opts->n_boot); n_sim simulations, seed. Errors as
 * bf_fit_calibrate (BF_EDOM, err->msg naming the pair, when its noise could
 * not be estimated); BF_EINVAL for a pair that was not analysed or
 * that is a joint fit's (bf_target.joint). */
int bf_study_calibrate(const bf_study_spec *spec,
                       const bf_analysis_opts *opts,
                       const bf_study_row *rows, const bf_fit_stats *stats,
                       size_t u, size_t n_sim, unsigned long seed,
                       bf_calibration *out, bf_error *err);

/* The calibration of a whole analysed study (bf_study_calibrate_all). */
typedef struct {
    size_t n;             /* pairs calibrated */
    size_t *pair;         /* their indices u (as rows, target-major),
                             increasing */
    bf_calibration *cal;  /* cal[i]: pair[i]'s */
    size_t n_sim;         /* simulations asked per pair */
    double *ml_est;       /* the maximum-likelihood estimate of free
                             parameter j in the r-th simulation of pair[i]
                             fitted, at ml_est[(i * BF_MAX_PARAMS + j) *
                             n_sim + r], r < cal[i].n_sim; NaN elsewhere */
} bf_study_calibration;

/* bf_study_calibrate(spec, opts, rows, stats, u, n_sim, seed) for every
 * pair u that was analysed (stats[u].done) and has free parameters, in
 * parallel on spec->n_threads threads (the same numbers for any count:
 * every pair is simulated from seed), opts->progress called after each
 * simulation (done of out->n x n_sim: its units are simulations), into
 * out (zeroed first; free it with
 * bf_study_calibration_free, also after an error). Errors as
 * bf_study_calibrate's for the first pair that fails (err->msg naming
 * it); BF_ENOMEM. */
int bf_study_calibrate_all(const bf_study_spec *spec,
                           const bf_analysis_opts *opts,
                           const bf_study_row *rows,
                           const bf_fit_stats *stats, size_t n_sim,
                           unsigned long seed, bf_study_calibration *out,
                           bf_error *err);
void bf_study_calibration_free(bf_study_calibration *c);

/* ---- model selection: ranks, ties, the best model (§5) ---- */

/* The criteria a ranking can use. */
typedef enum { BF_CRIT_AIC = 0, BF_CRIT_BIC, BF_CRIT_CV } bf_criterion;
#define BF_NCRIT 3

/* "AIC", "BIC", "CV" (static storage), NULL for an unknown value. */
const char *bf_criterion_name(bf_criterion c);
/* Finds a criterion by name, case-insensitive ("bic"); BF_ENOTFOUND. */
int bf_criterion_find(const char *name, bf_criterion *c);

/* The value of criterion c in st (NaN when st was not analysed or the
 * value was not computed: no folds). */
double bf_criterion_value(const bf_fit_stats *st, bf_criterion c);

/* Relative tolerance of a tie between two criterion values. */
#define BF_TIE_REL 1e-9

/* 1 when a and b are tied for criterion c on n configurations: |a - b| <=
 * BF_TIE_REL * scale, scale max(|a|, |b|) for CV and n for AIC and BIC
 * (n ln(RSS/n) moves by n e for a relative change e of RSS), so a tie is
 * the same relative difference of the residual sums for every criterion.
 * ON at sigma = 0 and LAMBERT differ only by rounding: they tie. */
int bf_criterion_tied(double a, double b, bf_criterion c, size_t n);

/* Ranks the n_models analyses of one target by c: rank[m] = 1 + the
 * number of models with a lower value not tied with m's (ties share the
 * rank), 0 when m has no value; *best = the model of rank 1 with the
 * fewest parameters (k), the first listed among equals, or SIZE_MAX when
 * none has a value. rank may be NULL (only *best wanted). */
void bf_criterion_rank(const bf_fit_stats *stats, size_t n_models,
                       bf_criterion c, size_t *rank, size_t *best);

/* The name a win of model best counts for (static storage): the model's,
 * or the model it reduces to when its fit is on that face
 * (BF_STAT_REDUCED: ON at sigma = 0 wins for LAMBERT); NULL when best is
 * SIZE_MAX. models and stats: the target's n_models entries. */
const char *bf_criterion_winner(const bf_model_type *const *models,
                                const bf_fit_stats *stats, size_t best);

/* bf_criterion_rank for every target of a study analysed with bf_study_analyse
 * (stats: n_targets x n_models, target-major): rank (n_targets x
 * n_models) and best (n_targets; SIZE_MAX for a target no model could be
 * ranked on), either may be NULL. BF_EINVAL for a NULL spec or stats,
 * BF_ENOMEM. */
int bf_study_rank(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, size_t *rank, size_t *best);

/* The wins of each model over the study's targets by criterion c (the
 * best model of each target, bf_study_rank; a win counts for the model
 * bf_criterion_winner names: ON at sigma = 0 wins for LAMBERT): *n_names
 * entries of names (static storage) and wins, most wins first, equal
 * counts in the order of the first win. names and wins need room for
 * 2 * spec->n_models entries. Targets without a best model are not
 * counted. BF_EINVAL for NULL arguments, BF_ENOMEM. */
int bf_study_wins(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, const char **names, size_t *wins,
                  size_t *n_names);

/* ---- what the figures draw ---- */

/* The profile of pb's objective along free parameter j as a curve
 * (doc/methods.md §3): dev[i] = n ln(S_p(theta[i]) / S_min) at the n
 * increasing values theta[i] within the search range [lo_j, hi_j], S_p
 * minimised over the other free parameters as the profile intervals do
 * (the refinement warm-started outward from the optimum and the grid
 * fit, the lower), S_min the objective at best (the exact optimum,
 * bf_fit_refine), n the sum of the weights. The profile interval is where
 * dev <= chi2_1(level) (3.841 at 95%). dev[i] is NaN where the model is
 * undefined. BF_EINVAL on bad arguments or theta out of range or not
 * increasing; BF_ENOMEM. (src/fit/profile_curve.c) */
int bf_fit_profile_curve(const bf_problem *pb, const bf_fit_result *best,
                         size_t j, size_t n, const double *theta,
                         double *dev);

/* The profile that bf_fit_intervals(pb, best, noise, level, ...)
 * thresholds, as a curve along free parameter j (doc/methods.md §3):
 * dev[i] = n ln(S_p(theta[i]) / S_min) of that criterion -- under a noise
 * model (ci_method profile-lik) the likelihood of its fitted noise power
 * (a specular model's: ngan under the noise weights), S_min at its
 * maximum-likelihood estimate; under BF_NOISE_OBJECTIVE the objective's,
 * as bf_fit_profile_curve around best. *thr gets the interval's
 * threshold: the interval is where dev <= *thr (n ln(1 + F_{1,nu}(level)
 * / nu) times the parameter's robust factor, bf_interval.robust, under a
 * noise model; chi2_1(level) under the objective). iv, when not NULL,
 * gets the noise model's fit (method, noise power, sigma, robust factors,
 * ml; its low, high NaN: the ends are bf_fit_intervals'). theta as
 * bf_fit_profile_curve's. BF_EINVAL on bad arguments, BF_EDOM when the
 * noise cannot be estimated, BF_ENOMEM. (src/fit/profile_curve.c) */
int bf_fit_interval_curve(const bf_problem *pb, const bf_fit_result *best,
                          bf_noise noise, double level, size_t j, size_t n,
                          const double *theta, double *dev, double *thr,
                          bf_interval *iv);

/* The profiles behind pair u's reported intervals (u: target u / n_models,
 * model u % n_models of a study analysed by bf_study_analyse(spec, opts,
 * rows, stats)), as the report draws them (figures/profile_sampleN): for
 * each free parameter, in order, n >= 2 values theta evenly over its
 * window -- its interval around the estimate the interval is about
 * (stats[u].ml_param) widened 2.5 times on each side (3 of the profile's
 * first steps on a side where it has no width), within its search range
 * -- and dev there, n ln(S_p/S_min) of the criterion the interval
 * thresholds (bf_fit_interval_curve under opts's noise model and level, on the
 * target's data as fitted: bf_study_fit_data); thr gets each parameter's
 * threshold. theta, dev: n x (free parameters) doubles, parameter-major
 * (dev NaN where the model is undefined); thr: one per free parameter.
 * With dev NULL only the windows (thr unused: what a layout needs).
 * BF_EINVAL (bad arguments; a pair not analysed, without free parameters,
 * or a joint fit's: it has no profile interval), BF_EDOM (its noise cannot
 * be estimated), BF_ENOMEM; err->msg names the pair.
 * (src/fit/study_profile.c) */
int bf_study_profiles(const bf_study_spec *spec, const bf_analysis_opts *opts,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      size_t u, size_t n, double *theta, double *dev,
                      double *thr, bf_error *err);

/* A fitted model drawn anywhere, normalised as in the fit (SPEC §2): the
 * model at the n configurations at[], divided by its maximum over the
 * n_used configurations used[] the fit saw. work holds n_used doubles.
 * out[i] is NaN where the model is undefined at at[i]. BF_EDOM when the
 * model cannot be normalised on used[] (maximum not positive or
 * undefined); BF_EINVAL on bad arguments. (src/fit/plane.c) */
int bf_fit_curve(const bf_model_type *type, const double *param,
                 size_t n_used, const bf_geom *used, size_t n,
                 const bf_geom *at, double *work, double *out);

/* A fitted model drawn anywhere in absolute units under an objective
 * that keeps the scale (SPEC §10): its rho_hat = BRDF x cos theta_i at
 * the n configurations at[], the fitted scales included, never
 * normalised. A specular model or composite (SPEC §9.3, §9.4) carries its
 * scales in param: bf_model_eval x cos theta_i. A diffuse model's scale
 * is the fit's, solved on pb (its data rho, configurations, weights and
 * objective; bf_fit_scale's rho_d): rho_d v(at) / (pi v(normal)), v the
 * model's value (SPEC §9.4). out[i] is NaN where the model is undefined.
 * BF_EINVAL for another objective or bad arguments; bf_fit_scale's
 * errors. (src/fit/plane.c) */
int bf_fit_rho_curve(const bf_problem *pb, const double *param, size_t n,
                     const bf_geom *at, double *out);

/* The radiance axis of a figure of fitted and measured rho (SPEC §10):
 * 1 when the positive finite values of v[0..n-1] span more than
 * BF_LOG_AXIS_DECADES decades (max / min > 10^2), so that a linear axis
 * would flatten the lower ones to the baseline (a gloss peak above a
 * diffuse floor): the figure then draws a logarithmic axis; else 0.
 * (src/fit/plane.c) */
#define BF_LOG_AXIS_DECADES 2.0
int bf_fit_log_axis(size_t n, const double *v);

/* The configuration of the plane of incidence at incidence theta_i and
 * signed viewing angle t in [-pi/2, pi/2] (t > 0 on the forward, specular
 * side; Beckmann's frame, SPEC §1.2). */
bf_geom bf_geom_in_plane(double theta_i, double t);

/* The signed viewing angle of g in its plane of incidence (> 0 forward),
 * and in *off_plane (may be NULL) the angle between the viewing direction
 * and that plane, radians. */
double bf_geom_plane_angle(const bf_geom *g, double *off_plane);

/* The incidence angles at which a figure of the plane of incidence shows
 * measurements: the configurations of g whose viewing direction lies
 * within tol of their plane of incidence, grouped by theta_i (angles
 * within tol of a group's smallest are one; each group is represented by
 * its median member, a measured angle). The candidates are the groups of
 * more than half as many configurations as the largest group. At most
 * max angles, in increasing order, into theta_i, their number in *n (0
 * when no configuration is in its plane); more candidates than max are
 * thinned evenly over their range, the first and the last kept (CURET:
 * 6 or 7 in-plane views at each multiple of 11.25 degrees, 3 at normal
 * incidence, give 11.25, 33.75, 56.25 and 78.75 for max = 4). BF_OK, BF_EINVAL,
 * BF_ENOMEM. */
int bf_geom_plane_incidences(size_t K, const bf_geom *g, double tol,
                             size_t max, double *theta_i, size_t *n);

/* ======================================================================
 * --- write: the output files and tidy CSV (README "Output files") ---
 * ====================================================================== */

/* What the analysis says about a fit, as words separated by spaces into
 * buf (len bytes, always terminated; "" for none): reduces_to=MODEL,
 * not_identified=PARAM (a flat direction of the refinement),
 * competing=PARAM (a second minimum of its profile competes with the
 * estimate's: its interval is the Neyman construction's by default),
 * clamped=COUNT (ON clamped at 0 on COUNT configurations), not_converged,
 * interval_failed, bootstrap_failed, bootstrap_split=PARAM (doc/methods.md
 * §2, §3, §8). type: the row's model. Returns the length of the full text
 * (as snprintf). */
size_t bf_fit_flags_format(const bf_model_type *type, const bf_fit_stats *st,
                           char *buf, size_t len);

/* One line of fits.csv (below): the values of its columns after sample,
 * name and channel (those of target rows[row].target, bf_dataset_number,
 * bf_dataset_name, bf_dataset_channel). NaN, NULL and -1 stand for an
 * empty field. */
#define BF_FITS_FLAGS_MAX 512
typedef enum {
    BF_FITS_PARAM = 0, /* a fitted parameter of the model */
    BF_FITS_SCALE,     /* the free scale rho_d (SPEC §9.4) */
    BF_FITS_NONE       /* a model without fitted parameters */
} bf_fits_kind;
typedef struct {
    size_t row;              /* index into the study's rows */
    bf_fits_kind kind;
    int joint;               /* 1: a shape parameter shared by the
                                channels of a joint fit (--channel joint,
                                SPEC §9.4): channel "joint", written once,
                                at the fit's first channel's row */
    const char *model;       /* rows[row].type->name */
    const char *parameter;   /* NULL for BF_FITS_NONE */
    const char *unit;
    double value;            /* NaN for BF_FITS_NONE */
    double lse;
    int bound_hit;
    size_t k;                /* configurations used */
    const char *objective;   /* bf_objective_name */
    const char *fit;         /* "paper" or "exact" */
    int analysed;            /* 0: grid_value ... flags are empty */
    double grid_value, grid_lse, refined_value, refined_lse;
    double ci_low, ci_high;
    double ml_value;         /* the estimate ci_low, ci_high are about
                                (bf_fit_stats.ml_param): the noise
                                model's maximum-likelihood estimate, which
                                can differ from value (the objective's
                                optimum); NaN: none */
    const char *ci_method;   /* NULL: none */
    int ci_open;             /* -1: none */
    double ci_robust;        /* the threshold's robust factor
                                (bf_fit_stats.ci_robust); NaN: none */
    double ci_gap_low, ci_gap_high; /* a split interval's gap
                                (bf_fit_stats.ci_gap_low); NaN: none */
    double boot_low, boot_high;
    long n_params;           /* -1: none */
    double aic, bic, cv;
    char flags[BF_FITS_FLAGS_MAX]; /* bf_fit_flags_format */
    const char *ndf, *masking, *fresnel; /* NULL for a diffuse model */
    double albedo[4];        /* at 0, 30, 60, 80 degrees (rows[row].albedo,
                                bf_study_row_albedo); NaN: none */
    int albedo_over_1;       /* -1 for a diffuse model */
} bf_fits_line;

/* The lines of fits.csv (below) for a study, in order, into out (NULL:
 * only counted; otherwise room for the count). Returns their number;
 * 0 for NULL spec or rows. */
size_t bf_fits_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_fits_line *out);

/* Writes fits.csv for a study: a header line, then one line per (target,
 * model, fitted parameter) in target-major order, a model without fitted
 * parameters on one line with parameter, unit and value empty; rows whose
 * status is not BF_OK are left out. Columns: sample, name, channel,
 * model, parameter, unit, value, lse, bound_hit, k (configurations used),
 * objective, fit (paper|exact), grid_value, grid_lse, refined_value,
 * refined_lse, ci_low, ci_high, ml_value (the estimate the interval is
 * about), ci_method, ci_open, ci_robust, boot_low, boot_high,
 * n_params, aic, bic, cv, flags (bf_fit_flags_format), ndf, masking,
 * fresnel, albedo_0, albedo_30, albedo_60, albedo_80, albedo_over_1: the
 * lines of bf_fits_lines. A joint fit (bf_target.joint, SPEC §9.4) writes
 * its shape parameters once, on channel "joint", at its first channel's
 * row, and each channel's scales (bf_param.linear) on the channel's name;
 * every line's lse is the fit's E = sqrt(S / (K C)) over the K
 * configurations of all C channels (SPEC §10), k is K, n_params, aic and
 * bic those of the whole fit (K C values, the shape and C sets of
 * scales). rows: from
 * bf_study_run or bf_study_analyse; stats: from bf_study_analyse, or NULL
 * (the analysis columns empty); opts: the analysis's, or NULL (objective
 * max, fit paper). Numbers with %.10g, NaN as an empty field; text fields
 * quoted as RFC 4180 when needed. BF_EINVAL for NULL fp, spec or rows;
 * BF_EIO when the stream reports a write error. */
int bf_fits_csv_write(FILE *fp, const bf_study_spec *spec,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      const bf_analysis_opts *opts);

/* One point of a material's dispersion n(lambda) (issue 17 item 7): the
 * refractive index n of a specular model under --fresnel dielectric
 * (SPEC §9.2), fitted per spectral channel, with its interval. */
typedef struct {
    size_t row;          /* index into the study's rows */
    int sample;          /* rows[row].sample */
    const char *model;   /* rows[row].type->name */
    int joint;           /* 1: one n shared by every channel (--channel
                            joint, SPEC §9.4): wavelength is NaN and
                            lambda_lo, lambda_hi span the channels */
    double wavelength;   /* the channel's wavelength, nm (NaN: joint) */
    double lambda_lo, lambda_hi; /* joint: the channels' wavelength range */
    double n;            /* the fit's value (fits.csv's value) */
    double ci_low, ci_high; /* its interval (fits.csv's ci_low, ci_high;
                               NaN: not analysed) */
    double n_ml;         /* the estimate the interval is about
                            (bf_fit_stats.ml_param; NaN: none) */
} bf_dispersion_point;

/* The dispersion points of a study, in row order, into out (NULL: only
 * counted; otherwise room for the count). A row gives a point when its
 * status is BF_OK, its model has a fitted parameter named "n"
 * (bf_model_param_index) and its target is a channel with a wavelength
 * (bf_dataset_wavelength), or is the first channel of a joint fit whose
 * channels all have one (one point for the fit, joint set). stats: from
 * bf_study_analyse, or NULL (intervals NaN). Returns their number; 0 for
 * NULL spec or rows. */
size_t bf_dispersion_points(const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats,
                            bf_dispersion_point *out);

/* Writes dispersion.csv: a header line, then one line per point of
 * bf_dispersion_points. Columns: sample, name, channel ("joint" for a
 * joint fit), model, wavelength_nm (empty for joint), n, ci_low, ci_high,
 * n_ml (the estimate the interval is about). Numbers with %.10g, NaN as
 * an empty field. BF_EINVAL for NULL fp, spec or rows; BF_EIO when the
 * stream reports a write error. */
int bf_dispersion_csv_write(FILE *fp, const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats);

/* One line of ranking.csv (below): the values of its columns after sample,
 * name and channel (those of target rows[row].target). NaN and NULL stand
 * for an empty field. */
typedef struct {
    size_t row;              /* index into the study's rows */
    const char *model;       /* rows[row].type->name */
    const char *objective;   /* bf_objective_name */
    const char *fit;         /* "paper" or "exact" */
    size_t k;                /* parameters counted */
    size_t n;                /* configurations */
    double objective_value;  /* the fit's objective */
    double aic, bic, cv;
    size_t rank[BF_NCRIT];   /* by bf_criterion (bf_study_rank) */
    int best[BF_NCRIT];      /* 1 on the target's best model */
    const char *counts_as;   /* bf_criterion_winner, NULL: none */
    char flags[BF_FITS_FLAGS_MAX]; /* bf_fit_flags_format */
    size_t n_params;         /* the model's fitted parameters: slots
                                0 .. n_params - 1 below */
    const char *param[BF_MAX_PARAMS];
    double value[BF_MAX_PARAMS];
    double ci_low[BF_MAX_PARAMS], ci_high[BF_MAX_PARAMS];
    double boot_low[BF_MAX_PARAMS], boot_high[BF_MAX_PARAMS];
    double ml[BF_MAX_PARAMS]; /* the estimate the interval is about
                                 (bf_fit_stats.ml_param) */
    double ci_gap_low[BF_MAX_PARAMS], ci_gap_high[BF_MAX_PARAMS]; /* a
                                 split interval's gap
                                 (bf_fit_stats.ci_gap_low); NaN: none */
} bf_ranking_line;

/* The number P of parameter slots of ranking.csv for a study's rows: the
 * most fitted parameters of any of its models. */
size_t bf_ranking_slots(const bf_study_spec *spec, const bf_study_row *rows);

/* The lines of ranking.csv (below) for an analysed study, in order, into
 * out (NULL: only counted; otherwise room for the count), their number in
 * *n. BF_EINVAL for NULL spec, rows, stats or n; BF_ENOMEM. */
int bf_ranking_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_ranking_line *out, size_t *n);

/* Writes ranking.csv for an analysed study: a header line, then one line
 * per (target, model) that was analysed. Columns: sample, name, channel,
 * model, objective, fit, k (parameters counted), n (configurations),
 * objective_value (the fit's objective), aic, bic, cv, rank_aic, rank_bic,
 * rank_cv (bf_study_rank), best_aic, best_bic, best_cv (1 on the target's
 * best model after the tie-break), counts_as (the model its wins count for,
 * bf_criterion_winner), flags (bf_fit_flags_format), then for each of the
 * study's P fitted-parameter slots (P = the most fitted parameters of any
 * of its models) pJ, pJ_value, pJ_ci_low, pJ_ci_high, pJ_ci_gap_low,
 * pJ_ci_gap_high, pJ_boot_low, pJ_boot_high, pJ_ml (J = 1..P: the model's
 * J-th fitted parameter, its value, profile interval with the gap of a
 * split one (empty: none), bootstrap interval and the estimate the
 * interval is about; empty beyond the model's own): the
 * lines of bf_ranking_lines, P of bf_ranking_slots. Formats and errors as
 * bf_fits_csv_write; stats is required. */
int bf_ranking_csv_write(FILE *fp, const bf_study_spec *spec,
                         const bf_study_row *rows, const bf_fit_stats *stats,
                         const bf_analysis_opts *opts);

/* Writes calibrate.csv: a header line, then one line per (pair of pairs[],
 * fitted parameter): sample, name, channel, model, parameter, value (the
 * truth simulated), objective, noise_power (p), noise_sd,
 * n_sim, coverage, bias, sd, ml_bias, ml_sd, width (median), level,
 * not_identified (share), boot_coverage, boot_width (empty without the
 * bootstrap). Formats as bf_fits_csv_write. */
int bf_calibration_csv_write(FILE *fp, const bf_study_spec *spec,
                             const bf_study_row *rows,
                             const bf_fit_stats *stats,
                             const bf_analysis_opts *opts,
                             const size_t *pairs, size_t n_pairs,
                             const bf_calibration *cal);

/* Writes ds as tidy CSV (the `material` column always present; a material
 * without a name is written under its number). Angles are written in
 * degrees with as few digits as read back (bf_csv_read) into the same
 * radians bit for bit; values with the fewest of %.15g, %.16g, %.17g that
 * read back bit for bit; invalid values as empty fields; wavelength
 * channels as "<nm>nm". So bf_csv_read gives ds back. BF_EINVAL when it
 * could not: materials with different channels, two materials written
 * under one name, a line break in a name, a channel that would not read
 * back as itself (a wavelength channel not named by its wavelength, a
 * name ending in nm, or one of the CSV's own column names), or an angle
 * below 1e-200 degrees that no decimal reads back into. BF_EIO on a
 * write error. */
int bf_csv_write(const bf_dataset *ds, FILE *fp);

/* ======================================================================
 * --- report: a study's tables, figures and report.html (libbrdffit_report)
 * ======================================================================
 * The report is the work of `brdffit report`: the study of SPEC §7 on a
 * dataset (the paper's protocol, and the analysis with stats, exact or
 * n_boot), its tables (fits.csv, table2.md, table3.md), every figure in
 * out_dir/figures and report.html, written atomically (a failed run leaves
 * no output behind). These functions live in libbrdffit_report (it draws
 * with PLplot): link -lbrdffit_report -lbrdffit. */

/* What went wrong, the classes of BSD sysexits.h (the CLI exits with them). */
typedef enum {
    BF_REPORT_OK = 0,
    BF_REPORT_CONFLICT = 62,  /* options that cannot be combined */
    BF_REPORT_BADVALUE = 63,  /* an option's value does not fit the data */
    BF_REPORT_DATAERR = 65,   /* the data cannot be fitted as asked */
    BF_REPORT_NOINPUT = 66,   /* an input file cannot be read */
    BF_REPORT_SOFTWARE = 70,  /* out of memory, or an internal error */
    BF_REPORT_CANTCREAT = 73, /* the output folder cannot be used */
    BF_REPORT_IOERR = 74      /* an output file cannot be written */
} bf_report_status;

/* Most --range options, incidence angles. */
#define BF_REPORT_MAX_RANGES 8
#define BF_REPORT_MAX_INCIDENCE 4
/* Most measurement files named in the provenance. */
#define BF_REPORT_MAX_FILES 64

typedef struct bf_report_inputs bf_report_inputs;

/* The data of a report and the files they came from (for the page's
 * provenance and the description of the run). Paths may be NULL. */
struct bf_report_inputs {
    const bf_dataset *ds;          /* borrowed; NULL when load fills it */
    const bf_sample_table *n_file; /* refractive indices, or NULL */
    const bf_sample_table *on_params; /* ON's rho and sigma, or NULL */
    int curet;                     /* the data are a CURET folder */
    const char *table_path;        /* CURET: table.txt, abrdf.dat and */
    const char *brdf_path;         /*   samples.tsv (NULL: none) */
    const char *names_path;
    const char *configs_path;      /* MERL: the sampling file, "all" */
    const char *files[BF_REPORT_MAX_FILES]; /* other formats: the files */
    size_t n_files;
    /* Called once the options are checked and before any data are used,
     * when ds is NULL: fills in (everything above) and returns
     * BF_REPORT_OK or a status (its messages are its own). */
    int (*load)(void *ctx, bf_report_inputs *in);
    void *load_ctx;
};

/* A message of the run (kind): the error that ends it, an option's error
 * (BF_REPORT_CONFLICT, BF_REPORT_BADVALUE: the CLI adds its --help hint),
 * or a note (a model left out for want of its inputs). */
enum { BF_REPORT_MSG_ERROR = 0, BF_REPORT_MSG_USAGE, BF_REPORT_MSG_NOTE };
typedef void (*bf_report_message_fn)(void *ctx, int kind, const char *text);
/* Progress of the run: what (a phase: "analysing (sample, model) pairs",
 * "drawing figures"), done of total; what NULL ends the phase. */
typedef void (*bf_report_progress_fn)(void *ctx, const char *what,
                                      size_t done, size_t total);

/* The options of a report: those of `brdffit report` (README, brdffit.1).
 * Initialise with BF_REPORT_OPTIONS_INIT and change what differs. */
typedef struct {
    /* the study */
    const char *models;    /* "VH-G,FC-E", "all", NULL: default_models */
    bf_model_set default_models;
    const char *samples;   /* "all", "paper", "1,5-9"; NULL: paper on
                              CURET data, all otherwise */
    const char *channel;   /* a channel name, "mean" or "each"; NULL: mean */
    const char *exclude;   /* configuration numbers "3,7-9", or NULL */
    double cone;           /* specular exclusion, degrees; < 0: the data's */
    double max_theta;      /* degrees */
    double n;              /* refractive index when no file gives one */
    int n_given;           /* n was given (kept by the exact fit) */
    const char *n_file;    /* the files of inputs' n_file and on_params */
    const char *on_file;   /*   (described and checksummed), or NULL */
    int exact;             /* the exact fit (doc/methods.md §1) */
    bf_objective objective;
    bf_fresnel_kind fresnel; /* SPEC §9.2 options of the specular models */
    bf_smith_kind smith;     /*   (bf_study_models); 0: each model's own */
    bf_noise noise;
    const char *range[BF_REPORT_MAX_RANGES]; /* "NAME=LO:HI" */
    size_t n_range;
    size_t n_boot;         /* bootstrap replicates (0: none) */
    size_t n_neyman;       /* the Neyman construction's simulations per
                              threshold (bf_analysis_opts.n_neyman; 0:
                              none; BF_NEYMAN_AUTO_SIM by default) */
    int neyman_every;      /* 1: every parameter's (bf_analysis_opts);
                              0: where a second minimum competes */
    size_t folds;          /* cross-validation folds (0: none) */
    unsigned long seed;
    int stats;             /* the analysis with the paper's fit */
    int no_intervals;      /* the analysis without intervals
                              (bf_analysis_opts.no_intervals): compare and
                              rank only -- not with n_boot, calibrate, nor
                              a report's analysis, whose figures draw
                              them */
    size_t calibrate;      /* simulations per (sample, model) pair that
                              check the intervals (bf_study_calibrate_all,
                              calibrate.csv; runs the analysis); 0: none,
                              else at least BF_CALIBRATE_MIN_SIM */
    int threads;           /* 0: one per core; also drawing processes */
    /* the figures */
    unsigned formats;      /* bits 1 << BF_REPORT_PNG, _SVG, _PDF */
    int single_column;     /* 3.5 in wide figures instead of 7 in */
    int log_lse;           /* Figure 2(b) on a logarithmic LSE axis */
    int per_sample;        /* one scatter figure per sample too */
    double incidence[BF_REPORT_MAX_INCIDENCE]; /* plane-of-incidence */
    size_t n_incidence;    /*   angles, radians; 0: chosen from the data */
    /* what the page records and the caller sees */
    int argc;              /* the command line (argv[0] the subcommand); */
    char **argv;           /*   argc 0: the page names bf_report_write */
    FILE *echo;            /* description and tables also printed here */
    bf_report_message_fn message; /* notes and errors; NULL: none */
    void *message_ctx;
    bf_report_progress_fn progress; /* NULL: none */
    void *progress_ctx;
} bf_report_options;

/* Figure formats (bits of bf_report_options.formats). */
enum { BF_REPORT_PNG = 0, BF_REPORT_SVG, BF_REPORT_PDF };

#define BF_REPORT_OPTIONS_INIT                                            \
    {.cone = -1.0, .max_theta = 90.0, .n = BF_DEFAULT_N, .folds = 10,     \
     .seed = 1, .n_neyman = BF_NEYMAN_AUTO_SIM,                           \
     .formats = (1u << BF_REPORT_PNG) | (1u << BF_REPORT_PDF)}

/* Runs the study of in's data with o and writes the report into out_dir
 * (created, one level, if missing): fits.csv, table2.md, table3.md,
 * report.html and figures/. *n_figures (may be NULL) gets the number of
 * figures. Returns BF_REPORT_OK, or a status with err (may be NULL)
 * holding the message (code BF_EINVAL for the option errors, BF_ENOMEM,
 * BF_EIO, BF_EDOM for data that cannot be fitted). */
int bf_report_write(bf_report_inputs *in, const bf_report_options *o,
                    const char *out_dir, size_t *n_figures, bf_error *err);

#ifdef __cplusplus
}
#endif

#endif /* BRDFFIT_H */
