/* csv.c: brdffit's tidy CSV (README "Tidy CSV"): datasets read and
 * written, and configuration lists read (where a MERL table is sampled).
 *
 * [1] RFC 4180 (comma-separated fields, double quotes).
 * [2] H. Wickham, "Tidy data", J. Stat. Softw. 59(10), 2014: one row per
 *     observation (a configuration of a material), one column per
 *     variable.
 * [3] SPEC §1.5 (the measurement frame of the angles).
 *
 * The format (lines and numbers: lineio.c; fields: bf__lines_split_csv):
 * blank lines and lines whose first non-blank character is '#' are
 * skipped anywhere. The first other line is the header: an optional
 * first column `material`, then theta_i, phi_i, theta_o, phi_o (any case),
 * then one column per channel (distinct, non-empty names that are none of
 * those five; a number, optionally followed by nm, is a wavelength in nm).
 * Every row has as many fields as the header. Angles are degrees in the
 * measurement frame (zeniths in [0, 90], azimuths in [-360, 360], up to
 * bf__angle_ok's tolerance), read by bf__parse_degrees so that any radian
 * value is some decimal's (the writer relies on it). A value field is a
 * finite decimal number (negative ones are kept, SPEC §2), or empty: the
 * value is invalid (not measured) and its configuration is left out of a
 * fit on that channel. The `material` field names the row's material
 * (non-empty); materials come in the order of their first row, each with
 * its rows in file order, which need not be adjacent. Materials whose
 * configuration lists are identical, row for row and bit for bit, share
 * one configuration set. Without a `material` column the file holds one
 * material named after the file (its name without extension). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "data/reader.h"
#include "internal.h"
#include "output/output.h"

/* The angle columns, in the header's order (SPEC §1.5). */
static const char *const angle_col[4] = {"theta_i", "phi_i", "theta_o",
                                         "phi_o"};

/* Most channel columns accepted. */
#define C_MAX 65536

/* One material as read. */
typedef struct {
    char *name;
    long line;              /* its first row */
    size_t n;               /* rows */
    double *angles;         /* n x 4, radians */
    double *values;         /* n x c */
    unsigned char *valid;   /* n x c */
    size_t cap_a;           /* elements each array holds */
    size_t cap_v;
    size_t cap_ok;
    int any_invalid;
} csv_mat;

typedef struct {
    size_t ncol;            /* header columns */
    int has_material;       /* column 1 is `material` */
    size_t col[4];          /* columns of the four angles */
    size_t c;               /* channels */
    char **channel;         /* c names */
    double *wl;             /* c wavelengths, NaN where none */
    int have_wl;
    csv_mat *mat;
    size_t n_mat;
    size_t cap_mat;
    size_t last;            /* material of the previous row */
} csv_state;

static void state_free(csv_state *s)
{
    size_t k;
    for (k = 0; s->channel != NULL && k < s->c; k++) {
        free(s->channel[k]);
    }
    free(s->channel);
    free(s->wl);
    for (k = 0; k < s->n_mat; k++) {
        free(s->mat[k].name);
        free(s->mat[k].angles);
        free(s->mat[k].values);
        free(s->mat[k].valid);
    }
    free(s->mat);
}

/* Index 0..3 of an angle column name, 4 for "material", -1 otherwise. */
static int reserved(const char *name)
{
    int k;
    for (k = 0; k < 4; k++) {
        if (bf__same_nocase(name, angle_col[k])) {
            return k;
        }
    }
    return bf__same_nocase(name, "material") ? 4 : -1;
}

/* ==== lines, header, angles (shared by both readers) ==== */

/* The next non-comment line of r, split into fields; *have = 0 at the
 * end. */
static int next_row(bf__lines *r, int *have, bf_error *err)
{
    int rc;
    do {
        rc = bf__lines_next(r, have, err);
    } while (rc == BF_OK && *have && bf__lines_is_comment(r));
    if (rc == BF_OK && *have) {
        rc = bf__lines_split_csv(r, err);
    }
    return rc;
}

/* Reads the header line; BF_EPARSE "empty file" when there is none. */
static int read_header(bf__lines *r, bf_error *err)
{
    int have = 0;
    int rc = next_row(r, &have, err);
    if (rc == BF_OK && !have) {
        rc = bf__error_set(err, BF_EPARSE, 0, "empty file");
    }
    return rc;
}

/* Field i of r as angle k (0..3) in degrees, into radians. */
static int read_angle(const bf__lines *r, size_t i, int k, double *rad,
                      bf_error *err)
{
    int st;
    if (r->field[i][0] == '\0') {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "field %zu (%s): empty angle", i + 1,
                             angle_col[k]);
    }
    st = bf__parse_degrees(r->field[i], rad);
    if (st != BF__NUM_OK) {
        return bf__field_error(r, i, angle_col[k], st, 1, 0, err);
    }
    if (!bf__angle_ok(rad, k % 2 == 0)) {
        char q[BF__QUOTE_BUF];
        bf__quote(r->field[i], q, sizeof q);
        return bf__error_set(err, BF_EPARSE, r->line,
                             "field %zu (%s) = %s outside [%s] degrees",
                             i + 1, angle_col[k], q,
                             k % 2 == 0 ? "0, 90" : "-360, 360");
    }
    return BF_OK;
}

/* Checks that a row has the header's field count. */
static int check_count(const bf__lines *r, size_t ncol, bf_error *err)
{
    if (r->nfield != ncol) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "expected %zu fields (the header's columns), "
                             "found %zu",
                             ncol, r->nfield);
    }
    return BF_OK;
}

/* ==== datasets: the header ==== */

static int dataset_header(csv_state *s, const bf__lines *r, bf_error *err)
{
    size_t off;
    size_t k;
    char q[BF__QUOTE_BUF];
    s->ncol = r->nfield;
    s->has_material = reserved(r->field[0]) == 4;
    off = s->has_material ? 1 : 0;
    for (k = 0; k < 4; k++) {
        if (off + k >= r->nfield || reserved(r->field[off + k]) != (int)k) {
            bf__quote(off + k < r->nfield ? r->field[off + k] : "", q,
                      sizeof q);
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "the header must be [material,]theta_i,"
                                 "phi_i,theta_o,phi_o,<channels>: column "
                                 "%zu is \"%s\"",
                                 off + k + 1, q);
        }
        s->col[k] = off + k;
    }
    if (r->nfield == off + 4 || r->nfield - off - 4 > C_MAX) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "the header names %zu channel columns after the "
                             "angles (1 to %d)",
                             r->nfield - off - 4, C_MAX);
    }
    s->c = r->nfield - off - 4;
    s->channel = calloc(s->c, sizeof *s->channel);
    s->wl = malloc(s->c * sizeof *s->wl);
    if (s->channel == NULL || s->wl == NULL) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    for (k = 0; k < s->c; k++) {
        size_t col = off + 4 + k;
        const char *name = r->field[col];
        char num[32];
        size_t j;
        s->wl[k] = NAN;
        bf__quote(name, q, sizeof q);
        if (name[0] == '\0' || reserved(name) >= 0) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "column %zu: \"%s\" cannot name a channel",
                                 col + 1, q);
        }
        if (bf__channel_wavelength(name, &s->wl[k])) {
            bf__format_double(s->wl[k], num);
            name = num;
            s->have_wl = 1;
        }
        for (j = 0; j < k; j++) {
            if (strcmp(s->channel[j], name) == 0) {
                return bf__error_set(err, BF_EPARSE, r->line,
                                     "column %zu: the channel \"%s\" is "
                                     "named twice",
                                     col + 1, q);
            }
        }
        s->channel[k] = bf__strdup(name);
        if (s->channel[k] == NULL) {
            return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
        }
    }
    return BF_OK;
}

/* ==== datasets: the rows ==== */

/* The material a row names (created at its first row). */
static int find_material(csv_state *s, const bf__lines *r, const char *name,
                         csv_mat **m, bf_error *err)
{
    size_t k;
    if (s->n_mat > 0 && strcmp(s->mat[s->last].name, name) == 0) {
        *m = &s->mat[s->last];
        return BF_OK;
    }
    for (k = 0; k < s->n_mat; k++) {
        if (strcmp(s->mat[k].name, name) == 0) {
            s->last = k;
            *m = &s->mat[k];
            return BF_OK;
        }
    }
    if (bf__grow((void **)&s->mat, &s->cap_mat, s->n_mat + 1,
                 sizeof *s->mat) != BF_OK) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    *m = &s->mat[s->n_mat];
    memset(*m, 0, sizeof **m);
    (*m)->name = bf__strdup(name);
    if ((*m)->name == NULL) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    (*m)->line = r->line;
    s->last = s->n_mat++;
    return BF_OK;
}

/* Room for one more row of m. */
static int reserve(csv_mat *m, size_t c, const bf__lines *r, bf_error *err)
{
    size_t need = m->n + 1;
    if (bf__grow((void **)&m->angles, &m->cap_a, 4 * need,
                 sizeof *m->angles) != BF_OK ||
        bf__grow((void **)&m->values, &m->cap_v, c * need,
                 sizeof *m->values) != BF_OK ||
        bf__grow((void **)&m->valid, &m->cap_ok, c * need, 1) != BF_OK) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    return BF_OK;
}

static int dataset_row(csv_state *s, const bf__lines *r, const char *stem,
                       bf_error *err)
{
    csv_mat *m = NULL;
    size_t off = s->has_material ? 1 : 0;
    size_t k;
    int rc = check_count(r, s->ncol, err);
    if (rc == BF_OK && s->has_material && r->field[0][0] == '\0') {
        rc = bf__error_set(err, BF_EPARSE, r->line,
                           "field 1 (material): empty material name");
    }
    if (rc == BF_OK) {
        rc = find_material(s, r, s->has_material ? r->field[0] : stem, &m,
                           err);
    }
    if (rc == BF_OK) {
        rc = reserve(m, s->c, r, err);
    }
    for (k = 0; rc == BF_OK && k < 4; k++) {
        rc = read_angle(r, off + k, (int)k, &m->angles[4 * m->n + k], err);
    }
    for (k = 0; rc == BF_OK && k < s->c; k++) {
        size_t i = off + 4 + k;
        size_t at = m->n * s->c + k;
        m->valid[at] = r->field[i][0] != '\0';
        m->values[at] = NAN;
        if (m->valid[at]) {
            rc = bf__field_double(r, i, s->channel[k], &m->values[at], err);
        } else {
            m->any_invalid = 1;
        }
    }
    if (rc == BF_OK) {
        m->n++;
    }
    return rc;
}

/* The dataset: materials in order, identical configuration lists on one
 * set. */
static int build(const csv_state *s, const char *name, bf_dataset **out,
                 bf_error *err)
{
    bf_dataset *ds = bf_dataset_alloc();
    size_t *set = malloc(s->n_mat * sizeof *set);
    size_t k;
    int rc = (ds == NULL || set == NULL) ? BF_ENOMEM : BF_OK;
    for (k = 0; rc == BF_OK && k < s->n_mat; k++) {
        const csv_mat *m = &s->mat[k];
        bf_material_desc d;
        size_t j;
        for (j = 0; j < k; j++) {
            if (s->mat[j].n == m->n &&
                memcmp(s->mat[j].angles, m->angles,
                       m->n * 4 * sizeof *m->angles) == 0) {
                break;
            }
        }
        if (j < k) {
            set[k] = set[j];
        } else {
            rc = bf_dataset_add_configs(ds, m->n, m->angles, &set[k], NULL);
        }
        memset(&d, 0, sizeof d);
        d.name = m->name;
        d.format = BF_FORMAT_CSV;
        d.source = name;
        d.line = m->line;
        d.set = set[k];
        d.n_channels = s->c;
        d.channel = (const char *const *)s->channel;
        d.wavelength = s->have_wl ? s->wl : NULL;
        d.values = m->values;
        d.valid = m->any_invalid ? m->valid : NULL;
        if (rc == BF_OK) {
            rc = bf_dataset_add_material(ds, &d, NULL);
        }
    }
    free(set);
    if (rc != BF_OK) {
        bf_dataset_free(ds);
        return bf__error_set(err, rc, 0, "%s",
                             rc == BF_ENOMEM ? "out of memory"
                                             : "the dataset refuses a "
                                               "material");
    }
    *out = ds;
    return BF_OK;
}

int bf_csv_read(FILE *fp, const char *name, bf_dataset **out, bf_error *err)
{
    char stem[BF_ERROR_FILE_MAX];
    bf__lines r;
    csv_state s;
    int have = 1;
    int rc;

    memset(&s, 0, sizeof s);
    rc = bf__reader_begin(&r, fp, name, out, err);
    if (rc != BF_OK) {
        return rc;
    }
    bf__stem(name, stem, sizeof stem);
    rc = read_header(&r, err);
    if (rc == BF_OK) {
        rc = dataset_header(&s, &r, err);
    }
    while (rc == BF_OK) {
        rc = next_row(&r, &have, err);
        if (rc != BF_OK || !have) {
            break;
        }
        rc = dataset_row(&s, &r, stem, err);
    }
    if (rc == BF_OK && s.n_mat == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0, "no data rows after the header");
    }
    if (rc == BF_OK) {
        rc = build(&s, name, out, err);
    }
    bf__lines_free(&r);
    state_free(&s);
    return rc;
}

int bf_csv_load(const char *path, bf_dataset **out, bf_error *err)
{
    return bf__load_dataset(path, bf_csv_read, out, err);
}

/* ==== configuration lists ==== */

/* The four angle columns, anywhere in the header, each exactly once. */
static int configs_header(const bf__lines *r, size_t col[4], bf_error *err)
{
    size_t i;
    int k;
    for (k = 0; k < 4; k++) {
        col[k] = SIZE_MAX;
    }
    for (i = 0; i < r->nfield; i++) {
        k = reserved(r->field[i]);
        if (k >= 0 && k < 4 && col[k] != SIZE_MAX) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "columns %zu and %zu are both %s",
                                 col[k] + 1, i + 1, angle_col[k]);
        }
        if (k >= 0 && k < 4) {
            col[k] = i;
        }
    }
    for (k = 0; k < 4; k++) {
        if (col[k] == SIZE_MAX) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "the header has no %s column (a "
                                 "configuration list names theta_i, phi_i, "
                                 "theta_o, phi_o)",
                                 angle_col[k]);
        }
    }
    return BF_OK;
}

int bf_configs_read(FILE *fp, const char *name, double **angles, size_t *n,
                    bf_error *err)
{
    bf__lines r;
    size_t col[4];
    size_t ncol = 0;
    size_t cap = 0;
    double *a = NULL;
    int have = 1;
    int rc;

    bf__error_clear(err, name);
    bf__lines_init(&r, fp);
    if (angles != NULL) {
        *angles = NULL;
    }
    if (n != NULL) {
        *n = 0;
    }
    if (fp == NULL || angles == NULL || n == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    rc = read_header(&r, err);
    if (rc == BF_OK) {
        ncol = r.nfield;
        rc = configs_header(&r, col, err);
    }
    while (rc == BF_OK) {
        size_t k;
        rc = next_row(&r, &have, err);
        if (rc != BF_OK || !have) {
            break;
        }
        rc = check_count(&r, ncol, err);
        if (rc == BF_OK &&
            bf__grow((void **)&a, &cap, 4 * (*n + 1), sizeof *a) != BF_OK) {
            rc = bf__error_set(err, BF_ENOMEM, r.line, "out of memory");
        }
        for (k = 0; rc == BF_OK && k < 4; k++) {
            rc = read_angle(&r, col[k], (int)k, &a[4 * *n + k], err);
        }
        if (rc == BF_OK) {
            (*n)++;
        }
    }
    if (rc == BF_OK && *n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "no configurations after the header");
    }
    bf__lines_free(&r);
    if (rc != BF_OK) {
        free(a);
        *n = 0;
        return rc;
    }
    *angles = a;
    return BF_OK;
}

int bf_configs_load(const char *path, double **angles, size_t *n,
                    bf_error *err)
{
    FILE *fp = NULL;
    int rc;
    if (angles != NULL) {
        *angles = NULL;
    }
    if (n != NULL) {
        *n = 0;
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_configs_read(fp, path, angles, n, err);
    fclose(fp);
    return rc;
}

/* ==== writing ==== */

/* Writes a name or channel as one field: quoted when needed
 * (bf__csv_field), "" when empty (read back as empty, not as missing). */
static void put_field(FILE *fp, const char *text)
{
    if (text[0] == '\0') {
        fputs("\"\"", fp);
    } else {
        bf__csv_field(fp, text);
    }
}

/* 1 when text cannot stand in one CSV line: a line break (the reader
 * takes no quoted field across lines). */
static int breaks_line(const char *text)
{
    return strpbrk(text, "\r\n") != NULL;
}

/* The name material m is written under: its name, or its number when it
 * has none (CURET without samples.tsv). */
static const char *label(const bf_dataset *ds, size_t m, char num[32])
{
    const char *name = bf_dataset_name(ds, m);
    if (name[0] != '\0') {
        return name;
    }
    snprintf(num, 32, "%d", bf_dataset_number(ds, m));
    return num;
}

/* The header text of channel c (of material 0) is its wavelength and nm
 * ("550nm") for a wavelength channel, its name for any other. 1 when
 * that reads back as the channel itself: not for a wavelength channel
 * named otherwise than by its wavelength, nor for a name the reader takes
 * for a wavelength or for one of its own columns (theta_i, ..., material).
 * num gets the wavelength's text. */
static int channel_ok(const bf_dataset *ds, size_t c, char num[32])
{
    const char *name = bf_dataset_channel(ds, 0, c);
    double wl = bf_dataset_wavelength(ds, 0, c);
    double nm;
    if (isnan(wl)) {
        return !bf__channel_wavelength(name, &nm) && reserved(name) < 0;
    }
    bf__format_double(wl, num);
    return strcmp(num, name) == 0;
}

/* Checks that every material has material 0's channels, that each reads
 * back as itself, that no name breaks a line and that no two materials
 * are written under one name (they would read back as one material). */
static int check_writable(const bf_dataset *ds)
{
    size_t nc = bf_dataset_nchannels(ds, 0);
    size_t m;
    size_t j;
    size_t c;
    for (c = 0; c < nc; c++) {
        char num[32];
        if (!channel_ok(ds, c, num)) {
            return BF_EINVAL;
        }
    }
    for (m = 0; m < bf_dataset_count(ds); m++) {
        char a[32];
        if (bf_dataset_nchannels(ds, m) != nc ||
            breaks_line(bf_dataset_name(ds, m))) {
            return BF_EINVAL;
        }
        for (c = 0; c < nc; c++) {
            double w0 = bf_dataset_wavelength(ds, 0, c);
            double wm = bf_dataset_wavelength(ds, m, c);
            if (strcmp(bf_dataset_channel(ds, m, c),
                       bf_dataset_channel(ds, 0, c)) != 0 ||
                !(w0 == wm || (isnan(w0) && isnan(wm))) ||
                breaks_line(bf_dataset_channel(ds, m, c))) {
                return BF_EINVAL;
            }
        }
        for (j = 0; j < m; j++) {
            char b[32];
            if (strcmp(label(ds, m, a), label(ds, j, b)) == 0) {
                return BF_EINVAL;
            }
        }
    }
    return BF_OK;
}

int bf_csv_write(const bf_dataset *ds, FILE *fp)
{
    size_t nc;
    size_t m;
    size_t c;
    if (ds == NULL || fp == NULL || bf_dataset_count(ds) == 0 ||
        check_writable(ds) != BF_OK) {
        return BF_EINVAL;
    }
    nc = bf_dataset_nchannels(ds, 0);
    fputs("material", fp);
    for (c = 0; c < 4; c++) {
        fprintf(fp, ",%s", angle_col[c]);
    }
    for (c = 0; c < nc; c++) {
        char num[32];
        putc(',', fp);
        if (isnan(bf_dataset_wavelength(ds, 0, c))) {
            put_field(fp, bf_dataset_channel(ds, 0, c));
        } else {
            channel_ok(ds, c, num);
            fprintf(fp, "%snm", num);
        }
    }
    putc('\n', fp);
    for (m = 0; m < bf_dataset_count(ds); m++) {
        const double *a = bf_dataset_angles(ds, m);
        const double *v = bf_dataset_values(ds, m);
        const unsigned char *ok = bf_dataset_valid(ds, m);
        char num[32];
        const char *name = label(ds, m, num);
        size_t k;
        for (k = 0; k < bf_dataset_nconf(ds, m); k++) {
            put_field(fp, name);
            for (c = 0; c < 4; c++) {
                char deg[BF__DEGREES_MAX];
                if (bf__format_degrees(a[4 * k + c], deg) != BF_OK) {
                    return BF_EINVAL;
                }
                putc(',', fp);
                fputs(deg, fp);
            }
            for (c = 0; c < nc; c++) {
                char text[32];
                putc(',', fp);
                if (ok == NULL || ok[k * nc + c]) {
                    bf__format_double(v[k * nc + c], text);
                    fputs(text, fp);
                }
            }
            if (putc('\n', fp) == EOF) {
                return BF_EIO;
            }
        }
    }
    return (fflush(fp) != 0 || ferror(fp)) ? BF_EIO : BF_OK;
}

/* ==== the reader (reader.h) ==== */

/* 1 when the comma-separated line[0..len) names the four angle columns
 * (blanks and double quotes around a name left out, any case). */
static int is_header(const char *line, size_t len)
{
    unsigned found = 0;
    size_t k = 0;
    while (k <= len) {
        char name[16];
        size_t a = k;
        size_t b;
        size_t j;
        while (a < len && (line[a] == ' ' || line[a] == '\t' ||
                           line[a] == '"')) {
            a++;
        }
        b = a;
        while (b < len && line[b] != ',') {
            b++;
        }
        k = b + 1;
        while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t' ||
                         line[b - 1] == '"')) {
            b--;
        }
        if (b - a < sizeof name) {
            memcpy(name, line + a, b - a);
            name[b - a] = '\0';
            for (j = 0; j < 4; j++) {
                found |= bf__same_nocase(name, angle_col[j]) ? 1u << j : 0u;
            }
        }
    }
    return found == 15u;
}

/* Detection: the first line (after blank and '#' lines) is a header
 * naming theta_i, phi_i, theta_o and phi_o as comma-separated columns. */
static int detect(const char *text, size_t n)
{
    size_t pos = 0;
    const char *line;
    size_t len;
    return bf__detect_content_line(text, n, &pos, &line, &len) &&
           is_header(line, len);
}

const bf__reader bf__csv_reader = {
    .name = "csv",
    .title = "tidy CSV",
    .detect = detect,
    .rank = BF__RANK_HEADER,
    .miss = "not tidy CSV (no header theta_i,phi_i,theta_o,phi_o)",
    .read = bf_csv_read,
};
