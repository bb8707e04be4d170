/* astm.c: ASTM E1392 BRDF files as Cornell exports them (SPEC §8), one
 * material with RGB, XYZ or spectral channels.
 *
 * [1] ASTM E1392-96, Standard Practice for Angle Resolved Optical Scatter
 *     Measurements on Specular or Diffuse Surfaces (the file layout).
 * [2] Cornell University Program of Computer Graphics, reflectance data
 *     pages (www.graphics.cornell.edu/online/measurements/reflectance):
 *     RGB, XYZ and spectral exports; RGB values may be negative.
 * [3] The ASTM readers of ALTA (plugins/data_astm) and libbsdf
 *     (AstmReader): header lines "KEY value" ending with VARS, NUM_POINTS
 *     required, comma-separated rows, angles in radians.
 *
 * What is accepted (lines and numbers: lineio.c): a header of lines
 * "KEY value", KEY a word of capitals, digits and underscores; '#' lines
 * and blank lines are skipped anywhere. NUM_POINTS (an integer >= 1) must
 * come once, before VARS; SAMPLE_NAME (optional, once; double quotes
 * around it are removed) names the material; other keywords (SOURCE,
 * DATE, FORMAT, ...) are ignored. VARS ends the header: comma-separated
 * names theta_i, phi_i, theta_s, phi_s (in that order, any case), then the
 * channels: any distinct non-empty names; a number, optionally followed
 * by nm, is a wavelength in nm (bf__channel_wavelength). Then exactly
 * NUM_POINTS rows of 4 + C comma-separated finite numbers: angles in
 * radians in the measurement frame (SPEC §1.5; theta_s is theta_o), checked
 * by bf__angle_ok, and BRDF values (negative ones kept, SPEC §2). The
 * rows are stored as read: NUM_POINTS never allocates anything before
 * the rows exist, so a header that lies about it costs nothing. */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "data/reader.h"
#include "internal.h"

/* Most channels accepted (Cornell's spectral exports have 31 or 65). */
#define C_MAX 65536

/* The variables that start VARS, in order (SPEC §8). */
static const char *const angle_var[4] = {"theta_i", "phi_i", "theta_s",
                                         "phi_s"};

typedef struct {
    long num_points;   /* 0 until NUM_POINTS */
    long num_line;     /* its line */
    char *sample_name; /* or NULL */
    size_t c;          /* channels */
    char **channel;    /* c names */
    double *wl;        /* c wavelengths, NaN where none */
    int have_wl;       /* 1 when some channel is a wavelength */
    size_t n;          /* rows read */
    double *angles;    /* n x 4 */
    double *values;    /* n x c */
    size_t cap_a;      /* doubles angles holds */
    size_t cap_v;      /* doubles values holds */
    long first_line;   /* line of the first row */
} astm_state;

static void state_free(astm_state *s)
{
    size_t k;
    free(s->sample_name);
    for (k = 0; s->channel != NULL && k < s->c; k++) {
        free(s->channel[k]);
    }
    free(s->channel);
    free(s->wl);
    free(s->angles);
    free(s->values);
}

/* ==== the header ==== */

/* Length of the header keyword starting line[0..len) (0 when it is
 * none): a capital letter, then capitals, digits or underscores, then a
 * blank or the end. */
static size_t keyword_len(const char *line, size_t len)
{
    size_t k = 0;
    if (len == 0 || !isupper((unsigned char)line[0])) {
        return 0;
    }
    while (k < len && (isupper((unsigned char)line[k]) ||
                       isdigit((unsigned char)line[k]) || line[k] == '_')) {
        k++;
    }
    return (k == len || line[k] == ' ' || line[k] == '\t') ? k : 0;
}

/* The channels of the VARS line, whose value starts at r->buf (moved
 * there by the caller). */
static int read_vars(astm_state *s, bf__lines *r, bf_error *err)
{
    size_t k;
    int rc = bf__lines_split_csv(r, err);
    if (rc != BF_OK) {
        return rc;
    }
    for (k = 0; k < 4; k++) {
        if (k >= r->nfield || !bf__same_nocase(r->field[k], angle_var[k])) {
            char q[BF__QUOTE_BUF];
            bf__quote(k < r->nfield ? r->field[k] : "", q, sizeof q);
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "VARS must start with theta_i,phi_i,"
                                 "theta_s,phi_s (variable %zu is \"%s\")",
                                 k + 1, q);
        }
    }
    if (r->nfield == 4 || r->nfield - 4 > C_MAX) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "VARS names %zu channels after the angles (1 to "
                             "%d)",
                             r->nfield - 4, C_MAX);
    }
    s->c = r->nfield - 4;
    s->channel = calloc(s->c, sizeof *s->channel);
    s->wl = malloc(s->c * sizeof *s->wl);
    if (s->channel == NULL || s->wl == NULL) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    for (k = 0; k < s->c; k++) {
        const char *name = r->field[4 + k];
        char num[32];
        size_t j;
        s->wl[k] = NAN;
        if (name[0] == '\0') {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "VARS variable %zu is empty", k + 5);
        }
        if (bf__channel_wavelength(name, &s->wl[k])) {
            bf__format_double(s->wl[k], num);
            name = num;
            s->have_wl = 1;
        }
        for (j = 0; j < k; j++) {
            if (strcmp(s->channel[j], name) == 0) {
                char q[BF__QUOTE_BUF];
                bf__quote(name, q, sizeof q);
                return bf__error_set(err, BF_EPARSE, r->line,
                                     "VARS names the channel \"%s\" twice",
                                     q);
            }
        }
        s->channel[k] = bf__strdup(name);
        if (s->channel[k] == NULL) {
            return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
        }
    }
    return BF_OK;
}

/* One header line; *done is set at VARS. */
static int header_line(astm_state *s, bf__lines *r, int *done,
                       bf_error *err)
{
    char *line = r->buf + strspn(r->buf, " \t");
    size_t k = keyword_len(line, strlen(line));
    char *value = line + k;
    value += strspn(value, " \t");
    if (k == 0) {
        char q[BF__QUOTE_BUF];
        bf__quote(line, q, sizeof q);
        return bf__error_set(err, BF_EPARSE, r->line,
                             "expected a header line \"KEYWORD value\" "
                             "(the header ends with VARS), found \"%s\"",
                             q);
    }
    if (k == 10 && memcmp(line, "NUM_POINTS", 10) == 0) {
        int st;
        if (s->num_points > 0) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "NUM_POINTS given twice (first at line "
                                 "%ld)",
                                 s->num_line);
        }
        st = bf__parse_long(value, 1, LONG_MAX, &s->num_points);
        if (st != BF__NUM_OK) {
            char q[BF__QUOTE_BUF];
            bf__quote(value, q, sizeof q);
            s->num_points = 0;
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "NUM_POINTS must be a whole number >= 1, "
                                 "found \"%s\"",
                                 q);
        }
        s->num_line = r->line;
    } else if (k == 11 && memcmp(line, "SAMPLE_NAME", 11) == 0) {
        size_t n = strlen(value);
        if (s->sample_name != NULL) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "SAMPLE_NAME given twice");
        }
        if (n >= 2 && value[0] == '"' && value[n - 1] == '"') {
            value[n - 1] = '\0';
            value++;
        }
        s->sample_name = bf__strdup(value);
        if (s->sample_name == NULL) {
            return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
        }
    } else if (k == 4 && memcmp(line, "VARS", 4) == 0) {
        if (s->num_points == 0) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "VARS before NUM_POINTS (the header must "
                                 "give the number of rows)");
        }
        memmove(r->buf, value, strlen(value) + 1);
        *done = 1;
        return read_vars(s, r, err);
    }
    return BF_OK;
}

/* ==== the rows ==== */

static int reserve(astm_state *s, const bf__lines *r, bf_error *err)
{
    size_t need = s->n + 1;
    if (bf__grow((void **)&s->angles, &s->cap_a, 4 * need,
                 sizeof *s->angles) != BF_OK ||
        bf__grow((void **)&s->values, &s->cap_v, s->c * need,
                 sizeof *s->values) != BF_OK) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    return BF_OK;
}

static int data_row(astm_state *s, bf__lines *r, bf_error *err)
{
    size_t k;
    int rc;
    if (s->n == (size_t)s->num_points) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "more rows than NUM_POINTS = %ld (line %ld)",
                             s->num_points, s->num_line);
    }
    rc = bf__lines_split_csv(r, err);
    if (rc == BF_OK && r->nfield != 4 + s->c) {
        rc = bf__error_set(err, BF_EPARSE, r->line,
                           "expected %zu comma-separated numbers (VARS), "
                           "found %zu",
                           4 + s->c, r->nfield);
    }
    if (rc == BF_OK) {
        rc = reserve(s, r, err);
    }
    for (k = 0; rc == BF_OK && k < 4 + s->c; k++) {
        double v;
        const char *what = k < 4 ? angle_var[k] : s->channel[k - 4];
        rc = bf__field_double(r, k, what, &v, err);
        if (rc == BF_OK && k < 4 && !bf__angle_ok(&v, k % 2 == 0)) {
            rc = bf__error_set(err, BF_EPARSE, r->line,
                               "field %zu (%s) = %g outside [%s]", k + 1,
                               what, v,
                               k % 2 == 0 ? "0, pi/2" : "-2 pi, 2 pi");
        }
        if (rc == BF_OK && k < 4) {
            s->angles[4 * s->n + k] = v;
        } else if (rc == BF_OK) {
            s->values[s->n * s->c + k - 4] = v;
        }
    }
    if (rc == BF_OK) {
        if (s->n == 0) {
            s->first_line = r->line;
        }
        s->n++;
    }
    return rc;
}

/* ==== the reader ==== */

static int build(const astm_state *s, const char *name, bf_dataset **out,
                 bf_error *err)
{
    char stem[BF_ERROR_FILE_MAX];
    bf_material_desc d;
    bf__stem(name, stem, sizeof stem);
    memset(&d, 0, sizeof d);
    d.name = (s->sample_name != NULL && s->sample_name[0] != '\0')
                 ? s->sample_name
                 : stem;
    d.format = BF_FORMAT_ASTM;
    d.source = name;
    d.line = s->first_line;
    d.n_channels = s->c;
    d.channel = (const char *const *)s->channel;
    d.wavelength = s->have_wl ? s->wl : NULL;
    d.values = s->values;
    return bf__dataset_single(&d, s->n, s->angles, out, err);
}

int bf_astm_read(FILE *fp, const char *name, bf_dataset **out, bf_error *err)
{
    bf__lines r;
    astm_state s;
    long lines = 0;
    int in_header = 1;
    int have = 0;
    int rc;

    memset(&s, 0, sizeof s);
    rc = bf__reader_begin(&r, fp, name, out, err);
    if (rc != BF_OK) {
        return rc;
    }
    for (;;) {
        int done = 0;
        rc = bf__lines_next(&r, &have, err);
        if (rc != BF_OK || !have) {
            break;
        }
        lines++;
        if (bf__lines_is_comment(&r)) {
            continue;
        }
        if (in_header) {
            rc = header_line(&s, &r, &done, err);
            in_header = !done;
        } else {
            rc = data_row(&s, &r, err);
        }
        if (rc != BF_OK) {
            break;
        }
    }
    if (rc == BF_OK && in_header) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           lines == 0 ? "empty file"
                                       : "no VARS line (the header ends "
                                         "with VARS theta_i,phi_i,theta_s,"
                                         "phi_s,<channels>)");
    }
    if (rc == BF_OK && s.n < (size_t)s.num_points) {
        rc = bf__error_set(err, BF_EPARSE, s.num_line,
                           "NUM_POINTS = %ld but the file has %zu row%s",
                           s.num_points, s.n, s.n == 1 ? "" : "s");
    }
    if (rc == BF_OK) {
        rc = build(&s, name, out, err);
    }
    bf__lines_free(&r);
    state_free(&s);
    return rc;
}

int bf_astm_load(const char *path, bf_dataset **out, bf_error *err)
{
    return bf__load_dataset(path, bf_astm_read, out, err);
}

/* ==== the reader (reader.h) ==== */

/* Detection: the first lines (after blank and '#' lines) are header lines
 * "KEY value" among which NUM_POINTS or VARS appears. */
static int detect(const char *text, size_t n)
{
    size_t pos = 0;
    const char *line;
    size_t len;
    size_t k;
    while (bf__detect_content_line(text, n, &pos, &line, &len) &&
           (k = keyword_len(line, len)) > 0) {
        if ((k == 10 && memcmp(line, "NUM_POINTS", 10) == 0) ||
            (k == 4 && memcmp(line, "VARS", 4) == 0)) {
            return 1;
        }
    }
    return 0;
}

const bf__reader bf__astm_reader = {
    .name = "astm",
    .title = "ASTM",
    .detect = detect,
    .rank = BF__RANK_KEYWORD,
    .miss = "not ASTM (no NUM_POINTS or VARS header)",
    .read = bf_astm_read,
};
