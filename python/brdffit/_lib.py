"""_lib: the C declarations brdffit uses and the loaded libbrdffit.

cffi in ABI mode: nothing is compiled when the package is installed; the
shared library is opened with dlopen and called through the declarations in
CDEF, which mirror include/brdffit.h (only what the package uses).  Struct
layouts must match the header exactly; python/tests/test_layout.py compiles
every struct's sizeof and offsetof (and the constants below) against the
header and fails on any difference.

cffi releases the GIL around every call into the library, so a long fit in
one Python thread does not stop the others.

Where the library is looked for, in order (library_candidates()):
  1. the environment variable BRDFFIT_LIB: the file libbrdffit.so (any
     name), or a folder holding it;
  2. the location recorded by ``pip install`` (brdffit/_location.py);
  3. the build folder of the source tree this package sits in
     (python/../build/libbrdffit.so: the PYTHONPATH=python way);
  4. the dynamic loader's own search ("libbrdffit.so.0": ld.so.conf,
     LD_LIBRARY_PATH), which finds an install into /usr/local.
"""

import os

from cffi import FFI

CDEF = r"""
typedef struct _IO_FILE FILE;

/* --- version and errors --- */
const char *bf_version(void);
enum { BF_OK = 0, BF_EINVAL, BF_EDOM, BF_ENOMEM, BF_EIO, BF_EPARSE,
       BF_ENOCONV, BF_ENOTFOUND };
const char *bf_strerror(int code);
#define BF_ERROR_FILE_MAX 512
#define BF_ERROR_MSG_MAX 256
typedef struct {
    int code;
    long line;
    char file[512];
    char msg[256];
} bf_error;
char *bf_error_format(const bf_error *err, char *buf, size_t len);

/* --- geometry --- */
typedef struct {
    double theta_i;
    double phi_i;
    double theta_s;
    double phi_s;
} bf_geom;

/* --- models --- */
#define BF_MAX_PARAMS 8
typedef enum { BF_INPUT_DEFAULT = 0, BF_INPUT_INDEX, BF_INPUT_ON } bf_input;
typedef enum {
    BF_HOMOG_NONE = 0, BF_HOMOG_UNIT, BF_HOMOG_SCALED, BF_HOMOG_DEGREE
} bf_homog;
typedef struct {
    const char *name;
    const char *label;
    const char *unit;
    double min, max;
    double value;
    int fitted;
    double grid_lo;
    double grid_step;
    size_t grid_n;
    bf_input input;
    size_t input_col;
    double free_lo;
    double free_hi;
    double free_step;
    int linear;
    bf_homog homog;
} bf_param;
typedef int (*bf_eval_fn)(const double *param, size_t n, const bf_geom *geom,
                          double *out, void *work);
typedef struct bf_kernel bf_kernel;
typedef enum { BF_MODEL_DIFFUSE = 0, BF_MODEL_SPECULAR } bf_model_kind;
typedef struct {
    const char *name;
    const char *title;
    const char *reference;
    size_t p;
    const bf_param *param;
    bf_eval_fn eval;
    size_t work_size;
    const bf_kernel *kernel;
    unsigned style;
    const char *reduces_to;
    size_t reduces_param;
    double reduces_at;
    bf_model_kind kind;
    const char *ndf;
    const char *masking;
    const char *fresnel_term;
    const void *const *variants;
    int own_diffuse;
} bf_model_type;
size_t bf_model_count(void);
const bf_model_type *bf_model_get(size_t i);
const bf_model_type *bf_model_find(const char *name);
const bf_model_type *bf_model_find_why(const char *name, const char **why);
typedef enum { BF_MODELS_PAPER = 0, BF_MODELS_RANKING } bf_model_set;
const char *bf_model_set_names(bf_model_set set);
int bf_model_eval(const bf_model_type *type, const double *param, size_t n,
                  const bf_geom *geom, double *out);
int bf_model_param_index(const bf_model_type *type, const char *name);
typedef enum {
    BF_FRESNEL_DEFAULT = 0, BF_FRESNEL_SCHLICK, BF_FRESNEL_DIELECTRIC,
    BF_FRESNEL_NONE
} bf_fresnel_kind;
typedef enum {
    BF_SMITH_DEFAULT = 0, BF_SMITH_HEIGHT, BF_SMITH_SEPARABLE
} bf_smith_kind;
const bf_model_type *bf_model_specular_variant(const bf_model_type *base,
                                               bf_fresnel_kind f,
                                               bf_smith_kind s,
                                               const char **why);
int bf_fresnel_find(const char *name, bf_fresnel_kind *out);
int bf_smith_find(const char *name, bf_smith_kind *out);

/* --- per-sample tables (ON parameters, refractive index) --- */
typedef struct bf_sample_table bf_sample_table;
void bf_sample_table_free(bf_sample_table *st);
int bf_on_params_load(const char *path, bf_sample_table **out, bf_error *err);
int bf_on_params_read(FILE *fp, const char *name, bf_sample_table **out,
                      bf_error *err);
int bf_n_file_load(const char *path, bf_sample_table **out, bf_error *err);
int bf_n_file_read(FILE *fp, const char *name, bf_sample_table **out,
                   bf_error *err);

/* --- datasets --- */
typedef struct bf_dataset bf_dataset;
typedef enum {
    BF_FORMAT_AUTO = 0, BF_FORMAT_CURET, BF_FORMAT_PBRT, BF_FORMAT_ASTM,
    BF_FORMAT_MERL, BF_FORMAT_CSV, BF_FORMAT_MEMORY
} bf_format;
const char *bf_format_name(bf_format f);
int bf_format_find(const char *name, bf_format *f);
bf_dataset *bf_dataset_alloc(void);
void bf_dataset_free(bf_dataset *ds);
int bf_dataset_add_configs(bf_dataset *ds, size_t n, const double *angles,
                           size_t *set, size_t *bad);
typedef struct {
    const char *name;
    int number;
    bf_format format;
    const char *source;
    long line;
    size_t set;
    size_t n_channels;
    const char *const *channel;
    const double *wavelength;
    const double *values;
    const unsigned char *valid;
} bf_material_desc;
int bf_dataset_add_material(bf_dataset *ds, const bf_material_desc *desc,
                            size_t *index);
size_t bf_dataset_count(const bf_dataset *ds);
const char *bf_dataset_name(const bf_dataset *ds, size_t m);
int bf_dataset_number(const bf_dataset *ds, size_t m);
long bf_dataset_find(const bf_dataset *ds, int number);
bf_format bf_dataset_format(const bf_dataset *ds, size_t m);
const char *bf_dataset_source(const bf_dataset *ds, size_t m);
long bf_dataset_line(const bf_dataset *ds, size_t m);
size_t bf_dataset_nconf(const bf_dataset *ds, size_t m);
size_t bf_dataset_set(const bf_dataset *ds, size_t m);
const bf_geom *bf_dataset_geom(const bf_dataset *ds, size_t m);
const double *bf_dataset_angles(const bf_dataset *ds, size_t m);
size_t bf_dataset_nchannels(const bf_dataset *ds, size_t m);
const char *bf_dataset_channel(const bf_dataset *ds, size_t m, size_t c);
double bf_dataset_wavelength(const bf_dataset *ds, size_t m, size_t c);
const double *bf_dataset_values(const bf_dataset *ds, size_t m);
const unsigned char *bf_dataset_valid(const bf_dataset *ds, size_t m);
int bf_dataset_channel_find(const bf_dataset *ds, size_t m,
                            const char *name, size_t *c);
typedef struct {
    double cone;
    double max_theta;
    const size_t *exclude;
    size_t n_exclude;
} bf_selection;
void bf_selection_init(bf_selection *s);
int bf_dataset_select(const bf_dataset *ds, size_t m, size_t c,
                      const bf_selection *s, size_t *sel, size_t *n,
                      size_t *cone_out);
int bf_dataset_radiance(const bf_dataset *ds, size_t m, size_t c, size_t n,
                        const size_t *sel, double *out);
typedef struct {
    bf_format format;
    size_t n_at;
    const double *at;
    int all_cells;
} bf_load_opts;
int bf_dataset_load(const char *path, const bf_load_opts *opts,
                    bf_dataset **out, bf_error *err);
int bf_csv_write(const bf_dataset *ds, FILE *fp);

/* --- fitting --- */
int bf_normalise(size_t n, const double *in, double *out);
typedef struct {
    double param[8];
    double lse;
    unsigned bound_hit;
    size_t n_eval;
    unsigned flat;
} bf_fit_result;
typedef enum { BF_OBJ_MAX = 0, BF_OBJ_SCALE, BF_OBJ_COSW, BF_OBJ_LOG,
               BF_OBJ_NGAN, BF_OBJ_CUBEROOT, BF_OBJ_LOG1P } bf_objective;
int bf_objective_keeps_scale(bf_objective obj);
const char *bf_objective_name(bf_objective obj);
int bf_objective_find(const char *name, bf_objective *obj);
typedef enum { BF_NOISE_AUTO = 0, BF_NOISE_ABSOLUTE, BF_NOISE_RELATIVE,
               BF_NOISE_OBJECTIVE } bf_noise;
const char *bf_noise_name(bf_noise noise);
int bf_noise_find(const char *name, bf_noise *noise);
typedef enum { BF_CI_NONE = 0, BF_CI_PROFILE, BF_CI_PROFILE_LIK,
               BF_CI_RESIDUAL_BOOTSTRAP, BF_CI_NEYMAN } bf_ci_method;
const char *bf_ci_method_name(bf_ci_method m);

/* --- the study on a dataset --- */
typedef struct {
    size_t material;
    size_t channel;
    int joint;
} bf_target;
int bf_study_targets(const bf_dataset *ds, const size_t *materials,
                     size_t n_materials, const char *channel,
                     bf_target **out, size_t *n_out, bf_error *err);
typedef struct {
    const bf_dataset *data;
    const bf_target *targets;
    size_t n_targets;
    bf_selection select;
    const bf_model_type *const *models;
    size_t n_models;
    double n_default;
    const bf_sample_table *n_file;
    const bf_sample_table *on_params;
    int n_threads;
} bf_study_spec;
int bf_study_target_data(const bf_study_spec *spec, size_t t, size_t *sel,
                         size_t *k, double *data, bf_error *err);
typedef struct {
    size_t target;
    size_t material;
    int sample;
    size_t channel;
    size_t k;
    const bf_model_type *type;
    int status;
    bf_fit_result fit;
    double albedo[4];
} bf_study_row;
int bf_study_run(const bf_study_spec *spec, bf_study_row *rows,
                 bf_error *err);
#define BF_STUDY_NSAMPLES 24
extern const int bf_study_samples[24];
typedef void (*bf_progress_fn)(void *ctx, size_t done, size_t total);
typedef struct {
    bf_objective objective;
    int exact;
    double level;
    size_t n_boot;
    size_t folds;
    unsigned long seed;
    bf_progress_fn progress;
    void *progress_ctx;
    bf_noise noise;
    int no_intervals;
    size_t n_neyman;
    int neyman_every;
} bf_analysis_opts;
void bf_analysis_opts_init(bf_analysis_opts *o);
int bf_analysis_opts_check(const bf_analysis_opts *o, bf_error *err);
enum { BF_STAT_NOCONV = 1, BF_STAT_REDUCED = 2, BF_STAT_CLAMPED = 4,
       BF_STAT_CI_FAIL = 8, BF_STAT_BOOT_FAIL = 16, BF_STAT_BOOT_SPLIT = 32 };
typedef struct {
    int done;
    bf_objective objective;
    unsigned free_mask;
    bf_fit_result grid;
    bf_fit_result refined;
    double ci_low[8];
    double ci_high[8];
    unsigned ci_open;
    double boot_low[8];
    double boot_high[8];
    size_t n;
    size_t k;
    double aic, bic;
    double cv;
    unsigned flags;
    size_t n_clamped;
    const char *reduces_to;
    unsigned boot_split;
    double scale;
    bf_ci_method ci_method;
    double noise_power;
    double noise_sigma;
    double ml_param[8];
    unsigned not_identified;
    bf_ci_method boot_method;
    double ci_robust[8];
    double ci_gap_low[8];
    double ci_gap_high[8];
    unsigned ci_competing;
    unsigned ci_neyman;
} bf_fit_stats;
bf_ci_method bf_fit_stats_ci_method(const bf_fit_stats *st, size_t j);
int bf_study_analyse(const bf_study_spec *spec, const bf_analysis_opts *opts,
                     bf_study_row *rows, bf_fit_stats *stats, bf_error *err);
#define BF_CALIBRATE_MIN_SIM 10
#define BF_NEYMAN_MIN_SIM 100
#define BF_NEYMAN_AUTO_SIM 100
typedef struct {
    size_t n_sim;
    size_t n_failed;
    double truth[8];
    double coverage[8];
    double bias[8];
    double sd[8];
    double ml_bias[8];
    double ml_sd[8];
    double width[8];
    double not_identified[8];
    double boot_coverage[8];
    double boot_width[8];
    double f_coverage[8];
    double f_width[8];
    double competing[8];
} bf_calibration;
typedef struct {
    size_t n;
    double coverage;
    double coverage_sd;
    double band_low;
    double band_high;
    int verdict;
    double bias_sd;
    double width_spread;
    double not_identified;
} bf_calibration_summary;
int bf_calibration_summarise(const bf_calibration *c, size_t j, double level,
                             bf_calibration_summary *out);
int bf_study_profiles(const bf_study_spec *spec, const bf_analysis_opts *opts,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      size_t u, size_t n, double *theta, double *dev,
                      double *thr, bf_error *err);
int bf_study_calibrate(const bf_study_spec *spec,
                       const bf_analysis_opts *opts,
                       const bf_study_row *rows, const bf_fit_stats *stats,
                       size_t u, size_t n_sim, unsigned long seed,
                       bf_calibration *out, bf_error *err);
typedef struct {
    size_t n;
    size_t *pair;
    bf_calibration *cal;
    size_t n_sim;
    double *ml_est;
} bf_study_calibration;
int bf_study_calibrate_all(const bf_study_spec *spec,
                           const bf_analysis_opts *opts,
                           const bf_study_row *rows,
                           const bf_fit_stats *stats, size_t n_sim,
                           unsigned long seed, bf_study_calibration *out,
                           bf_error *err);
void bf_study_calibration_free(bf_study_calibration *c);

/* --- the exact fit's policy, ranking, output files --- */
typedef struct {
    bf_model_type type;
    bf_param param[8];
} bf_model_variant;
#define BF_VARIANT_MAX_GRID 100001
void bf_model_variant_init(bf_model_variant *v, const bf_model_type *base);
int bf_model_variant_fit(bf_model_variant *v, const char *name, double lo,
                         double hi, double step);
int bf_model_variant_range(bf_model_variant *v, const char *name, double lo,
                           double hi);
size_t bf_model_variant_exact(bf_model_variant *v, unsigned keep);
int bf_study_models(const char *list, bf_model_set defaults,
                    bf_objective objective, bf_fresnel_kind fresnel,
                    bf_smith_kind smith, const bf_model_type **out,
                    size_t cap, size_t *n, bf_error *err);
typedef struct {
    const char *name;
    double lo, hi;
} bf_param_range;
#define BF_STUDY_MAX_RANGES 8
int bf_study_variants(const bf_model_type *const *models, size_t n_models,
                      int exact, unsigned keep, const bf_param_range *ranges,
                      size_t n_ranges, bf_model_variant *variants,
                      const bf_model_type **out, size_t *bad_range,
                      size_t *bad_model);
int bf_study_rows_check(const bf_study_row *rows, size_t n, size_t *bad);
typedef enum { BF_CRIT_AIC = 0, BF_CRIT_BIC, BF_CRIT_CV } bf_criterion;
#define BF_NCRIT 3
const char *bf_criterion_name(bf_criterion c);
int bf_criterion_find(const char *name, bf_criterion *c);
double bf_criterion_value(const bf_fit_stats *st, bf_criterion c);
int bf_criterion_tied(double a, double b, bf_criterion c, size_t n);
void bf_criterion_rank(const bf_fit_stats *stats, size_t n_models, bf_criterion c,
             size_t *rank, size_t *best);
const char *bf_criterion_winner(const bf_model_type *const *models,
                           const bf_fit_stats *stats, size_t best);
int bf_study_rank(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, size_t *rank, size_t *best);
int bf_study_wins(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, const char **names, size_t *wins,
                  size_t *n_names);
size_t bf_fit_flags_format(const bf_model_type *type, const bf_fit_stats *st,
                           char *buf, size_t len);
#define BF_FITS_FLAGS_MAX 512
typedef enum { BF_FITS_PARAM = 0, BF_FITS_SCALE, BF_FITS_NONE } bf_fits_kind;
typedef struct {
    size_t row;
    bf_fits_kind kind;
    int joint;
    const char *model;
    const char *parameter;
    const char *unit;
    double value;
    double lse;
    int bound_hit;
    size_t k;
    const char *objective;
    const char *fit;
    int analysed;
    double grid_value, grid_lse, refined_value, refined_lse;
    double ci_low, ci_high;
    double ml_value;
    const char *ci_method;
    int ci_open;
    double ci_robust;
    double ci_gap_low, ci_gap_high;
    double boot_low, boot_high;
    long n_params;
    double aic, bic, cv;
    char flags[512];
    const char *ndf, *masking, *fresnel;
    double albedo[4];
    int albedo_over_1;
} bf_fits_line;
size_t bf_fits_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_fits_line *out);
typedef struct {
    size_t row;
    const char *model;
    const char *objective;
    const char *fit;
    size_t k;
    size_t n;
    double objective_value;
    double aic, bic, cv;
    size_t rank[3];
    int best[3];
    const char *counts_as;
    char flags[512];
    size_t n_params;
    const char *param[8];
    double value[8];
    double ci_low[8], ci_high[8];
    double boot_low[8], boot_high[8];
    double ml[8];
    double ci_gap_low[8], ci_gap_high[8];
} bf_ranking_line;
size_t bf_ranking_slots(const bf_study_spec *spec, const bf_study_row *rows);
int bf_ranking_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_ranking_line *out, size_t *n);
typedef struct {
    size_t row;
    int sample;
    const char *model;
    int joint;
    double wavelength;
    double lambda_lo, lambda_hi;
    double n;
    double ci_low, ci_high;
    double n_ml;
} bf_dispersion_point;
size_t bf_dispersion_points(const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats,
                            bf_dispersion_point *out);
int bf_dispersion_csv_write(FILE *fp, const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats);
int bf_fits_csv_write(FILE *fp, const bf_study_spec *spec,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      const bf_analysis_opts *opts);
int bf_ranking_csv_write(FILE *fp, const bf_study_spec *spec,
                         const bf_study_row *rows, const bf_fit_stats *stats,
                         const bf_analysis_opts *opts);

/* --- GSL (a dependency of libbrdffit): its default handler aborts --- */
typedef void gsl_error_handler_t(const char *reason, const char *file,
                                 int line, int gsl_errno);
gsl_error_handler_t *gsl_set_error_handler_off(void);

/* --- report (types; bf_report_write is in libbrdffit_report, _report.py) --- */
enum { BF_REPORT_OK = 0, BF_REPORT_CONFLICT = 62, BF_REPORT_BADVALUE = 63,
       BF_REPORT_DATAERR = 65, BF_REPORT_NOINPUT = 66,
       BF_REPORT_SOFTWARE = 70, BF_REPORT_CANTCREAT = 73,
       BF_REPORT_IOERR = 74 };
#define BF_REPORT_MAX_RANGES 8
#define BF_REPORT_MAX_INCIDENCE 4
#define BF_REPORT_MAX_FILES 64
typedef struct bf_report_inputs bf_report_inputs;
struct bf_report_inputs {
    const bf_dataset *ds;
    const bf_sample_table *n_file;
    const bf_sample_table *on_params;
    int curet;
    const char *table_path;
    const char *brdf_path;
    const char *names_path;
    const char *configs_path;
    const char *files[64];
    size_t n_files;
    int (*load)(void *ctx, bf_report_inputs *in);
    void *load_ctx;
};
enum { BF_REPORT_MSG_ERROR = 0, BF_REPORT_MSG_USAGE, BF_REPORT_MSG_NOTE };
typedef void (*bf_report_message_fn)(void *ctx, int kind, const char *text);
typedef void (*bf_report_progress_fn)(void *ctx, const char *what,
                                      size_t done, size_t total);
typedef struct {
    const char *models;
    bf_model_set default_models;
    const char *samples;
    const char *channel;
    const char *exclude;
    double cone;
    double max_theta;
    double n;
    int n_given;
    const char *n_file;
    const char *on_file;
    int exact;
    bf_objective objective;
    bf_fresnel_kind fresnel;
    bf_smith_kind smith;
    bf_noise noise;
    const char *range[8];
    size_t n_range;
    size_t n_boot;
    size_t n_neyman;
    int neyman_every;
    size_t folds;
    unsigned long seed;
    int stats;
    int no_intervals;
    size_t calibrate;
    int threads;
    unsigned formats;
    int single_column;
    int log_lse;
    int per_sample;
    double incidence[4];
    size_t n_incidence;
    int argc;
    char **argv;
    FILE *echo;
    bf_report_message_fn message;
    void *message_ctx;
    bf_report_progress_fn progress;
    void *progress_ctx;
} bf_report_options;
enum { BF_REPORT_PNG = 0, BF_REPORT_SVG, BF_REPORT_PDF };
"""

# libc: in-memory streams for the readers and writers that take a FILE *.
LIBC_CDEF = r"""
FILE *fmemopen(void *buf, size_t size, const char *mode);
FILE *open_memstream(char **ptr, size_t *sizeloc);
int fclose(FILE *fp);
void free(void *ptr);
"""

# Constants the header defines as expressions, which cffi cannot parse.
# test_layout.py checks each against the compiled header.
CHANNEL_MEAN = 2**64 - 1  # BF_CHANNEL_MEAN, ((size_t)-1)
CONE_DEFAULT = -1.0  # BF_CONE_DEFAULT
DEFAULT_N = 1.7  # BF_DEFAULT_N
FREE_N_LO = 1.2  # BF_FREE_N_LO
FREE_N_HI = 2.5  # BF_FREE_N_HI
TIE_REL = 1e-9  # BF_TIE_REL
SONAME = "libbrdffit.so.0"  # SOVERSION = PROJECT_VERSION_MAJOR

ffi = FFI()
ffi.cdef(CDEF)
ffi.cdef(LIBC_CDEF)


def _source_build_folder():
    """The build folder of the checkout holding this package, or None."""
    here = os.path.dirname(os.path.abspath(__file__))
    build = os.path.join(os.path.dirname(os.path.dirname(here)), "build")
    return build if os.path.isdir(build) else None


def _recorded():
    """The library path recorded by pip install (setup.py), or None."""
    try:
        from . import _location  # written by setup.py; absent in a checkout
    except ImportError:
        return None
    return _location.LIBRARY


def _in_folder(folder):
    """The libbrdffit shared object in folder (the unversioned link, else
    the soname), or the folder's libbrdffit.so path when neither exists."""
    for name in ("libbrdffit.so", SONAME):
        path = os.path.join(folder, name)
        if os.path.exists(path):
            return path
    return os.path.join(folder, "libbrdffit.so")


def library_candidates():
    """The places the library is looked for, in order, as (how, path)
    pairs; path is a file name for the dynamic loader in the last one."""
    out = []
    env = os.environ.get("BRDFFIT_LIB", "")
    if env:
        out.append(("BRDFFIT_LIB", _in_folder(env) if os.path.isdir(env)
                    else env))
    recorded = _recorded()
    if recorded:
        out.append(("recorded by pip install", recorded))
    build = _source_build_folder()
    if build:
        out.append(("source tree's build folder", _in_folder(build)))
    out.append(("dynamic loader", SONAME))
    return out


def _open():
    """Opens the first candidate that loads; BRDFFIT_LIB, when set, must
    load (no fallback hides a wrong setting). Raises ImportError listing
    every attempt."""
    tried = []
    for how, path in library_candidates():
        if how != "dynamic loader" and not os.path.exists(path):
            tried.append("%s: %s (no such file)" % (how, path))
            if how == "BRDFFIT_LIB":
                break
            continue
        try:
            handle = ffi.dlopen(path)
            return handle, path
        except OSError as exc:
            tried.append("%s: %s (%s)" % (how, path, exc))
            if how == "BRDFFIT_LIB":
                break
    raise ImportError(
        "brdffit: cannot load libbrdffit; tried:\n  " + "\n  ".join(tried) +
        "\nBuild it (make, in the repository) or install it (make install),"
        " or set BRDFFIT_LIB to the path of libbrdffit.so.")


def _check_symbols(handle, where):
    """Resolves every declared name now, so that a library of another
    version fails the import, naming what it lacks, rather than a later
    call."""
    missing = []
    for name in dir(handle):
        try:
            getattr(handle, name)
        except AttributeError:
            missing.append(name)
    if missing:
        raise ImportError("brdffit: %s lacks %s: it is not the libbrdffit "
                          "this package was written for (rebuild it, or point "
                          "BRDFFIT_LIB at the matching build)"
                          % (where, ", ".join(missing)))


lib, path = _open()
_check_symbols(lib, path)
libc = ffi.dlopen(None)
# Every GSL status is checked by the library; GSL's default handler would
# abort the Python process instead (STYLE §4). Process-wide, as in the CLI.
lib.gsl_set_error_handler_off()


def text(ptr):
    """A borrowed C string as str (None for NULL)."""
    return None if ptr == ffi.NULL else ffi.string(ptr).decode("utf-8")
