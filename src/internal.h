/* internal.h: private declarations shared across libbrdffit's source files.
 * Never installed. Private names use the bf__ prefix (STYLE §3). */
#ifndef BF_INTERNAL_H
#define BF_INTERNAL_H

#include <stdio.h>
#include <stdlib.h>

#include "brdffit.h"

#if defined(__GNUC__)
#define BF__PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define BF__PRINTF(fmt, args)
#endif

/* ======================================================================
 * --- memory ---
 * ====================================================================== */

/* bytes rounded up to whole 64-byte cache lines (a workspace's parts
 * apart, so no two threads' writes share a line). */
static inline size_t bf__line_bytes(size_t bytes)
{
    return (bytes + 63) / 64 * 64;
}

/* A 64-byte-aligned block of at least bytes (aligned_alloc wants a size
 * that is a multiple of the alignment); free() releases it. */
static inline void *bf__alloc_lines(size_t bytes)
{
    return aligned_alloc(64, bf__line_bytes(bytes));
}

/* ======================================================================
 * --- error reports (src/error.c) ---
 * ====================================================================== */

/* File name used in reports when a reader is given name == NULL. */
#define BF__NONAME "(stream)"

/* Resets err (may be NULL) to BF_OK, line 0, empty message, and copies name
 * (truncated to BF_ERROR_FILE_MAX - 1 bytes; NULL gives BF__NONAME). Every
 * loader calls it first. */
void bf__error_clear(bf_error *err, const char *name);

/* Sets err's code, line and printf-style message (truncated to
 * BF_ERROR_MSG_MAX - 1 bytes); err->file is left as bf__error_clear set it.
 * err may be NULL. Returns code, so callers can write
 * `return bf__error_set(err, BF_EPARSE, line, "...")`. */
int bf__error_set(bf_error *err, int code, long line, const char *fmt, ...)
    BF__PRINTF(4, 5);

/* The code of a failed system call on a file (open, stat) whose errno is
 * e: BF_ENOMEM when the kernel or libc ran out of memory, else BF_EIO. */
int bf__errno_code(int e);

/* ======================================================================
 * --- line reader and strict number parsing (src/data/lineio.c) ---
 * ====================================================================== */

/* Longest accepted line, in bytes, without its line end. Longer lines are a
 * BF_EPARSE error instead of an unbounded allocation. CURET's longest line
 * (abrdf.dat) is about 1.7 KB. */
#define BF__LINE_MAX ((size_t)1 << 20)
/* Most bytes the line reader takes from its stream in one read. */
#define BF__LINES_READ_MAX ((size_t)64 << 20)

/* At most this many bytes of an offending field are quoted in a message. */
#define BF__QUOTE_MAX 24

/* Size of a buffer for bf__quote. */
#define BF__QUOTE_BUF (4 * BF__QUOTE_MAX + 8)

/* Writes a printable, truncated copy of text into out (size n, at least
 * BF__QUOTE_BUF for the whole of it): bytes outside printable ASCII become
 * \xNN, and text longer than BF__QUOTE_MAX bytes ends in "...". For
 * quoting what a file holds in a message. */
void bf__quote(const char *text, char *out, size_t n);

/* A line reader over a FILE * (see lineio.c for the accepted syntax: LF or
 * CRLF line ends, optional final newline, optional UTF-8 BOM, blank lines
 * skipped, trailing blanks ignored; NUL bytes, lone CRs and lines longer
 * than BF__LINE_MAX are errors). Fields are split in place. */
typedef struct {
    FILE *fp;         /* the stream (not owned) */
    char *in;         /* what was read of it: a regular file's whole rest
                         in one read (up to BF__LINES_READ_MAX at a time),
                         a pipe's 64 KiB at a time */
    size_t in_len;    /* bytes in in */
    size_t in_pos;    /* the next byte to take */
    size_t in_cap;    /* allocated size of in */
    int in_end;       /* 1 once the stream gave no more bytes */
    long line;        /* 1-based number of the current line, 0 before any */
    int started;      /* 1 once the BOM check has been done */
    char *buf;        /* current line, NUL-terminated, line end removed */
    size_t len;       /* its length in bytes */
    size_t cap;       /* allocated size of buf */
    char **field;     /* fields of the current line after a split */
    size_t nfield;    /* number of fields */
    size_t field_cap; /* allocated size of field */
} bf__lines;

/* Prepares r to read fp. Never fails (allocation happens on first use). */
void bf__lines_init(bf__lines *r, FILE *fp);

/* Frees r's buffers (not the stream). */
void bf__lines_free(bf__lines *r);

/* Reads the next non-blank line into r->buf (trailing spaces and tabs
 * removed) and sets *have_line to 1, or to 0 at end of file. Returns BF_OK,
 * BF_EPARSE (NUL byte, lone CR, line too long), BF_EIO (read error) or
 * BF_ENOMEM, with err filled (line = the offending line). */
int bf__lines_next(bf__lines *r, int *have_line, bf_error *err);

/* Splits r->buf in place into fields separated by runs of spaces and tabs.
 * Returns BF_OK or BF_ENOMEM (err filled). */
int bf__lines_split_ws(bf__lines *r, bf_error *err);

/* Splits r->buf in place at every tab (empty fields are kept) and trims
 * spaces around each field. Returns BF_OK or BF_ENOMEM (err filled). */
int bf__lines_split_tab(bf__lines *r, bf_error *err);

/* Results of the strict number parsers. */
enum {
    BF__NUM_OK = 0,
    BF__NUM_SYNTAX,    /* not a decimal number at all */
    BF__NUM_TRAILING,  /* a number followed by other characters ("1.5abc") */
    BF__NUM_HEX,       /* hexadecimal ("0x1p3") */
    BF__NUM_NONFINITE, /* "nan", "inf", "infinity" in any case */
    BF__NUM_RANGE,     /* overflows a double (1e999) or the integer range */
    BF__NUM_NOTINT     /* a decimal number that is not an integer ("1.5") */
};

/* Parses text as a decimal floating-point number: [+-] digits [. digits]
 * [(e|E) [+-] digits], at least one mantissa digit, nothing else. Values
 * that underflow are accepted (rounded towards 0). Returns BF__NUM_*. */
int bf__parse_double(const char *text, double *value);

/* Parses text as a decimal integer in [min, max]: [+-] digits, nothing else.
 * Returns BF__NUM_OK, BF__NUM_NOTINT ("1.5", "1e3"), BF__NUM_RANGE or one
 * of the codes of bf__parse_double for non-numbers. */
int bf__parse_long(const char *text, long min, long max, long *value);

/* Parses field i (0-based) of r as a double; on failure fills err with
 * BF_EPARSE at r->line: 'field <i+1> (<what>): <reason>: "<text>"'. */
int bf__field_double(const bf__lines *r, size_t i, const char *what,
                     double *value, bf_error *err);

/* Same for an integer in [min, max]. */
int bf__field_long(const bf__lines *r, size_t i, const char *what, long min,
                   long max, long *value, bf_error *err);

/* Fills err (BF_EPARSE, r->line) for a field whose parse returned status:
 * 'field <i+1> (<what>): <reason>: "<quoted text>"'. min and max are used
 * for BF__NUM_RANGE of integers (pass min > max for doubles). Returns
 * BF_EPARSE. */
int bf__field_error(const bf__lines *r, size_t i, const char *what,
                    int status, long min, long max, bf_error *err);

/* Opens path for reading for a _load function. First resets err to name
 * path (bf__error_clear), so every report of the load names its file. Then
 * BF_EIO (message with strerror(errno), line 0) when it cannot be opened,
 * is a directory, or is neither a regular file nor a FIFO/pipe. On success
 * *fp is the stream. */
int bf__open(const char *path, FILE **fp, bf_error *err);

/* 1 when the current line of r is a comment: its first non-blank
 * character is '#' (the pbrt, ASTM and tidy CSV readers). */
int bf__lines_is_comment(const bf__lines *r);

/* Splits r->buf in place into comma-separated fields (the ASTM and tidy
 * CSV readers): spaces and tabs around a field are removed and empty
 * fields are kept. A field may be enclosed in double quotes (RFC 4180;
 * "" inside stands for one "), which keeps its commas and blanks; after
 * the closing quote only blanks may follow. Returns BF_OK, BF_EPARSE (a
 * quote not closed on the line, text after a closing quote; err names the
 * field) or BF_ENOMEM. */
int bf__lines_split_csv(bf__lines *r, bf_error *err);

/* The file name of path without its folders and its last extension
 * ("data/cayman.brdf" -> "cayman"; a leading dot is kept: ".x" -> ".x"),
 * into out (size len, truncated); "" when path is NULL. Readers name a
 * material after its file with it. */
void bf__stem(const char *path, char *out, size_t len);

/* Tolerance on the angle ranges of every reader (radians): absorbs the
 * rounding of angles printed with 10 or more decimals, far below the 6 of
 * CURET's and Cornell's files. */
#define BF__ANGLE_TOL 1e-9

/* Checks an angle in radians read from a file: a zenith (zenith = 1) must
 * lie in [0, pi/2], an azimuth in [-2 pi, 2 pi], each up to BF__ANGLE_TOL;
 * a zenith within the tolerance outside [0, pi/2] is clamped onto it, so
 * that a pi/2 printed with rounding passes the models' closed-hemisphere
 * check. Returns 1 when *a is accepted, 0 when it is out of range. */
int bf__angle_ok(double *a, int zenith);

/* 1 when a channel name of an ASTM or CSV header names a wavelength: a
 * positive decimal number followed by the unit nm, in any case, blanks
 * allowed before it ("550nm", "552.5 nm", as libbsdf's ASTM reader
 * requires); a bare number ("550") is a name like any other. *nm gets it.
 * The readers then name the channel bf__format_double(*nm) ("550"), as
 * the pbrt reader names its wavelengths, so one spectrum has the same
 * channels in every format. */
int bf__channel_wavelength(const char *text, double *nm);

/* A new dataset of one material (desc, whose set is filled here) on one
 * configuration set of n configurations (angles n x 4, measurement frame):
 * what the pbrt, ASTM, MERL and single-material CSV readers return. On
 * failure *out is NULL and err says why at line 0: BF_ENOMEM, or BF_EINVAL
 * when the dataset refuses what the reader should have checked.
 * src/data/format.c. */
int bf__dataset_single(const bf_material_desc *desc, size_t n,
                       const double *angles, bf_dataset **out,
                       bf_error *err);

/* A malloc'ed copy of s (NULL when out of memory). */
char *bf__strdup(const char *s);

/* 1 when a and b are equal ignoring ASCII case (header keywords, column
 * and format names; strcasecmp is POSIX, and locale-dependent). */
int bf__same_nocase(const char *a, const char *b);

/* Grows *p, an array of elements of size bytes with room for *cap, to
 * hold need elements (doubling from 64). BF_OK, or BF_ENOMEM with *p and
 * *cap unchanged. */
int bf__grow(void **p, size_t *cap, size_t need, size_t size);

/* The entry of a dataset reader: resets err to name (bf__error_clear),
 * *out to NULL and r to read fp. BF_EINVAL (err filled) when fp or out is
 * NULL. */
int bf__reader_begin(bf__lines *r, FILE *fp, const char *name,
                     bf_dataset **out, bf_error *err);

/* The load-from-path form of a dataset reader: opens path (bf__open),
 * calls read(fp, path, out, err), closes it. */
int bf__load_dataset(const char *path,
                     int (*read)(FILE *, const char *, bf_dataset **,
                                 bf_error *),
                     bf_dataset **out, bf_error *err);

/* ======================================================================
 * --- angles in degrees as text (src/data/degrees.c) ---
 * ====================================================================== */

/* Parses text (bf__parse_double's strict syntax) as degrees and returns
 * the radians nearest its decimal value times pi/180, computed from the
 * decimal digits in double-double arithmetic (so every double in
 * [-2 pi, 2 pi] is the value of some decimal text, which a single double
 * multiplication cannot give). Returns BF__NUM_*. */
int bf__parse_degrees(const char *text, double *rad);

/* Longest text bf__format_degrees writes, with its terminating NUL. */
#define BF__DEGREES_MAX 32

/* Writes rad (finite) in degrees into buf (BF__DEGREES_MAX bytes): the
 * decimal with the fewest significant digits that bf__parse_degrees reads
 * back into rad bit for bit (plain notation from 1e-4 up to 1e17, else
 * with an exponent, as %g). Returns BF_OK, or BF_EINVAL when rad is not finite. */
int bf__format_degrees(double rad, char *buf);

/* Writes a finite double v into buf (32 bytes) with the fewest digits of
 * %.15g, %.16g, %.17g that strtod reads back bit for bit. */
void bf__format_double(double v, char *buf);

/* ======================================================================
 * --- geometry and model helpers (src/geometry.c, src/fresnel.c,
 *     src/models/) ---
 * ====================================================================== */

#include <math.h>

/* Run-time dispatch of the vector loops (src/fit/kernels.c, weights.c and
 * the models' kernels, src/models/): compiled for x86-64-v4 (AVX-512), x86-64-v3 (AVX2 + FMA) and
 * the baseline; the loader picks one (GCC's target_clones). Never
 * -march=native. Empty elsewhere. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&   \
    defined(__has_attribute)
#if __has_attribute(target_clones)
#define BF__CLONES                                                         \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3",     \
                                 "default")))
#endif
#endif
#ifndef BF__CLONES
#define BF__CLONES
#endif

/* pi and pi/2 to double precision (M_PI is not part of strict C11). */
#define BF__PI 3.14159265358979323846
#define BF__PI_2 1.57079632679489661923

/* Sine and cosine of a zenith angle theta in [0, pi/2]. The double nearest
 * pi/2 (and anything above it) is treated as exactly grazing, sin = 1 and
 * cos = 0, so that the grazing limits of SPEC §3.3, §4.1 and §5 are taken
 * exactly: cos(1.5707963267948966) is 6.1e-17, not 0. Used by every model
 * and by the Fresnel terms. */
static inline void bf__zenith_sincos(double theta, double *s, double *c)
{
    if (theta >= BF__PI_2) {
        *s = 1.0;
        *c = 0.0;
    } else {
        *s = sin(theta);
        *c = cos(theta);
    }
}

/* f(alpha_i, r) of SPEC §4.1 from s2 = sin^2 alpha_i, c = cos alpha_i and
 * ct = cos alpha_t (sin alpha_t = sin alpha_i / r by Snell, (P5)).
 *
 * Expanding the sines and cosines of alpha_i +- alpha_t and dividing
 * numerator and denominator by sin(alpha_i) / r (resp. 1 / r) gives
 *     sin(ai - at) / sin(ai + at) = (r ct - c) / (r ct + c)
 *     cos(ai + at) / cos(ai - at) = (r c ct - s^2) / (r c ct + s^2).
 * Neither quotient is 0/0 anywhere on [0, pi/2] (for r != 1, or r = 1 below
 * grazing), so f is continuous at alpha_i = 0 and equals the SPEC §4.1 limit
 * ((r - 1)/(r + 1))^2 there without a special case. At grazing on the air
 * side (c = 0, r > 1) it gives 1/2 * 1 * (1 + 1) = 1. Inline so that the
 * facet loop of WNO-R (src/models/wolff_nayar_oren.c) vectorises. */
static inline double bf__fresnel_s2ct(double s2, double c, double ct,
                                      double r)
{
    double a = (r * ct - c) / (r * ct + c); /* sin(ai-at)/sin(ai+at), (P4) */
    /* cos(ai+at)/cos(ai-at), (P4) */
    double b = (r * c * ct - s2) / (r * c * ct + s2);
    return 0.5 * (a * a) * (1.0 + (b * b)); /* (P4) with the 1/2, SPEC §4.1 */
}

/* F_FC^2 of (P6), SPEC §4.2, from the sines and cosines of theta_i and
 * theta_s (si, ci, ss, cs) for n >= 1, branch-free so that the kernels
 * vectorise it: [1 - f(theta_i, n)] [1 - f(asin(sin theta_s / n), 1/n)]
 * cos theta_i, f of SPEC §4.1 through bf__fresnel_s2ct with cos alpha_t =
 * sqrt((1 - st)(1 + st)), st = sin alpha_t (Snell, (P5)). n = 1 is no
 * interface (f = 0). Both sides of every select are computed, the
 * discarded one may be NaN. bf__fresnel_fc2_sc is this function. */
static inline double bf__fc2_inline(double si, double ci, double ss,
                                    double cs, double n)
{
    double s2 = ss / n;                        /* sin of the internal angle */
    double c2 = sqrt((1.0 - s2) * (1.0 + s2)); /* its cosine */
    double st = si / n;                        /* Snell (P5): sin alpha_t */
    double ct = sqrt((1.0 - st) * (1.0 + st)); /* cos alpha_t */
    double f_in = bf__fresnel_s2ct(si * si, ci, ct, n);
    double f_out = bf__fresnel_s2ct(s2 * s2, c2, cs, 1.0 / n); /* f(., 1/n) */
    double t_in;
    double t_out;
    f_in = (st >= 1.0) ? 1.0 : f_in; /* at the critical angle (n = 1 only) */
    t_in = (n == 1.0) ? 1.0 : 1.0 - f_in;  /* into the body */
    t_out = (n == 1.0) ? 1.0 : 1.0 - f_out; /* out of it */
    return t_in * t_out * ci; /* (P6), SPEC §4.2 */
}

/* Unpolarised Fresnel reflectance f of SPEC §4.1 from the sine s and cosine
 * c (both >= 0) of the angle of arrival, relative index r > 0. Defined in
 * src/fresnel.c; called by bf_fresnel, bf_fresnel_fc2 and the FC models,
 * which already have s and c and so skip the trigonometry. */
double bf__fresnel_sc(double s, double c, double r);

/* Transmittances of F_FC^2 (SPEC §4.2, paper (P6)) from the sines and
 * cosines of theta_i and theta_s (si, ci, ss, cs): returns
 * [1 - f(theta_i, n)] * [1 - f(asin(sin theta_s / n), 1/n)] * cos theta_i.
 * Defined in src/fresnel.c; used by bf_fresnel_fc2 and the FC models.
 * n >= 1 is not checked. */
double bf__fresnel_fc2_sc(double si, double ci, double ss, double cs,
                          double n);

/* F_FC^2 of (P6), SPEC §4.2, at n >= 1 for n configurations given by
 * their sines and cosines (SoA), vectorised: bf__fc2_inline per value, the
 * same bits as bf__fresnel_fc2_sc (src/fresnel.c; the kernels of the
 * models with this factor use it). */
void bf__fc2_values(size_t n, const double *si, const double *ci,
                    const double *ss, const double *cs, double n_index,
                    double *out);

/* Sines and cosines of one configuration: zenith angles as
 * bf__zenith_sincos gives them, sin and cos of phi_s. */
typedef struct {
    double si, ci, ss, cs, sp, cp;
} bf__trig_t;

/* The sines and cosines of g (src/geometry.c): the engine takes them once
 * per configuration for all models (bf__cset). */
void bf__geom_trig(const bf_geom *g, bf__trig_t *tr);

/* ======================================================================
 * --- fitting (src/fit) ---
 * ====================================================================== */

/* The one grid layout of the library: which parameters a grid search
 * varies, over which points, and the values of the others. Free parameter
 * i (in index order) takes the values lo[i] + step[i] t, t < count[i]. */
typedef struct {
    double base[BF_MAX_PARAMS]; /* fixed values; free ones overwritten */
    size_t free[BF_MAX_PARAMS]; /* indices of the free parameters */
    size_t n_free;              /* number of free parameters */
    double lo[BF_MAX_PARAMS];   /* grid of free parameter i */
    double step[BF_MAX_PARAMS];
    size_t count[BF_MAX_PARAMS];
    size_t points;              /* product of the counts */
    unsigned mask;              /* bit j: parameter j is free */
} bf__grid_layout_t;

/* Checks type/fixed/free_mask and fills g with the paper's grids of the
 * free parameters (src/fit/grid.c; bf__grid_layout_range in
 * src/fit/engine.h for other ranges). */
int bf__grid_layout(const bf_model_type *type, const double *fixed,
                    unsigned free_mask, bf__grid_layout_t *g);
/* The one grid enumerator: parameter vector of grid point idx (mixed
 * radix, the first free parameter varying slowest); returns its bound
 * flags (bit j: parameter j on an end of its grid). */
unsigned bf__grid_point(const bf__grid_layout_t *g, size_t idx,
                        double *param);
/* sum_k (curve_k - data_k)^2 in index order (SPEC §7.3). */
double bf__sum_sq_diff(size_t n, const double *curve, const double *data);

/* Fixed parameter values of type for target t of spec
 * (src/fit/targets.c): defaults, n from the n file or n_default, ON's
 * rho, sigma from the parameter file, looked up by the material's number;
 * BF_ENOTFOUND when an input is missing. */
int bf__study_inputs(const bf_study_spec *spec, const bf_model_type *type,
                     size_t t, double *fixed);

/* The joint fits of spec (bf_target.joint, --channel joint, SPEC §9.4)
 * under the analysis's objective obj, or under the paper's protocol when
 * analysed is 0 (src/fit/targets.c): BF_OK when no target is joint or
 * every model can be fitted jointly; else BF_EINVAL with err->msg saying
 * why not (the protocol max-normalises; only ngan solves the scales by
 * least squares; a model without a free scale, bf_param.linear). */
int bf__study_joint_check(const bf_study_spec *spec, int analysed,
                          bf_objective obj, bf_error *err);

/* Targets of a study that share a configuration set and selection, and so
 * the geometry and every model curve (src/fit/targets.c). */
typedef struct {
    size_t set;        /* the dataset's configuration set */
    size_t n_sel;      /* K */
    size_t *sel;       /* K configuration indices in the set */
    bf_geom *geom;     /* their K configurations, Beckmann's frame */
    size_t n_members;
    size_t *members;   /* target indices, increasing */
    double *data;      /* n_members x K normalised radiances (SPEC §2),
                          or rho as measured (bf__study_groups_data) */
} bf__group_t;

typedef struct {
    bf__group_t *g;
    size_t n;
} bf__groups_t;

/* Groups the targets of spec (selection and data of each target as
 * bf_study_target_data); err names the material on failure. */
int bf__study_groups(const bf_study_spec *spec, bf__groups_t *gs,
                     bf_error *err);
/* The same with each target's rho_k = BRDF x cos theta_i as measured (not
 * normalised, SPEC §10) when raw is 1 (data then holds those values). */
int bf__study_groups_data(const bf_study_spec *spec, int raw,
                          bf__groups_t *gs, bf_error *err);
/* The groups with the data a fit under obj uses (as bf_study_fit_data):
 * under the objectives that keep the scale rho as measured on the
 * configurations with theta_i, theta_o <= 80 deg (SPEC §10), else the
 * normalised radiances. The analysis and the calibration share them. */
int bf__study_groups_fit(const bf_study_spec *spec, bf_objective obj,
                         bf__groups_t *gs, bf_error *err);
/* rho = BRDF x cos theta_i of material m, channel c on the n
 * configurations sel, as measured (bf_dataset_radiance before its
 * normalisation; src/data/select.c). */
int bf__dataset_rho(const bf_dataset *ds, size_t m, size_t c, size_t n,
                    const size_t *sel, double *out);
void bf__study_groups_free(bf__groups_t *gs);
/* bf_study_row_albedo of rows[0 .. n) on n_threads OpenMP threads (0 or
 * 1: one; src/fit/study_albedo.c): the same values for any count. */
void bf__study_rows_albedo(bf_study_row *rows, size_t n, int n_threads);

/* --- the study path's kernels (src/fit/kernels.c) --- */

/* Grid points per scoring block; a precomputed grid's columns (grid points
 * padded) are a multiple of it. */
#define BF__SCORE_LANES 32
/* Extra doubles per row of transposed curves (one cache line): a row pitch
 * of a power of two would map every row to the same cache set. */
#define BF__ROW_PAD 8

/* e^x for x <= 0 as the block kernels compute it (bf__vexp_nonpos of
 * src/fit/block.h: within 1 ulp of exp on [-708, 0], 0 below); exposed
 * for the tests. */
double bf__exp_nonpos(double x);
/* lse[s * cols + g] = LSE of grid column g < cols against data[s]
 * (SPEC §7.3) in index order. */
void bf__score_all(size_t n, size_t cols, size_t stride,
                   const double *curves, size_t n_samples,
                   const double *const *data, double *lse);
/* The smallest LSE of the defined points (ok) and its first index in
 * *best (SIZE_MAX when none is defined and finite). */
double bf__argmin(size_t points, const double *restrict lse,
                  const unsigned char *restrict ok, size_t *best);

/* 1 when no parameter of type is fitted by the paper's protocol. */
int bf__fits_nothing(const bf_model_type *type);

/* BF_OK when every configuration lies on the closed hemisphere (zeniths
 * in [0, pi/2], finite azimuths), else BF_EINVAL (src/models/registry.c;
 * the public entry points check once, the engine assumes it). */
int bf__geom_check(size_t n, const bf_geom *geom);

#endif
