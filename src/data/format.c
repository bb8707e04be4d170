/* format.c: the formats brdffit reads -- their names, detection from the
 * content, and loading any of them into a dataset (SPEC §8); plus the
 * one-material dataset the single-material readers build.
 *
 * [1] SPEC §8 (the formats and what identifies each).
 *
 * Detection looks at the content, never at the name: a folder holding
 * table.txt is CURET; a file whose first 12 bytes are the little-endian
 * int32 dimensions 90, 90, 180 is MERL (bf_merl_read then checks the size
 * they imply); any other file with a NUL byte in its first DETECT_MAX
 * bytes is binary and unknown; a text file is ASTM when its first lines
 * (after blank and '#' lines) are header lines "KEY value" among which
 * NUM_POINTS or VARS appears, tidy CSV when its first line names theta_i,
 * phi_i, theta_o and phi_o as comma-separated columns, and pbrt when its
 * first number (comments removed) is a wavelength count, an integer in
 * [1, 65536]. */
#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "internal.h"

/* Bytes of a file read to detect its format. */
#define DETECT_MAX 65536

/* The MERL dimensions (SPEC §8) as they start a file. */
static const unsigned char merl_magic[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                             180, 0, 0, 0};

/* Largest wavelength count of a plausible pbrt file (pbrt.c's W_MAX). */
#define PBRT_W_MAX 65536

static const char *const format_names[] = {"auto", "curet", "pbrt", "astm",
                                           "merl", "csv",   "memory"};

#define N_FORMATS (sizeof format_names / sizeof format_names[0])

const char *bf_format_name(bf_format f)
{
    return ((int)f >= 0 && (size_t)f < N_FORMATS) ? format_names[f] : NULL;
}

int bf_format_find(const char *name, bf_format *f)
{
    size_t i;
    if (name == NULL || f == NULL) {
        return BF_EINVAL;
    }
    for (i = 0; i < N_FORMATS; i++) {
        if (bf__same_nocase(name, format_names[i])) {
            *f = (bf_format)i;
            return BF_OK;
        }
    }
    if (bf__same_nocase(name, "brdf")) {
        *f = BF_FORMAT_PBRT;
        return BF_OK;
    }
    if (bf__same_nocase(name, "binary")) {
        *f = BF_FORMAT_MERL;
        return BF_OK;
    }
    return BF_ENOTFOUND;
}

/* ==== detection ==== */

/* The next line of text[0..n) from *pos (its end excluded, CR too). */
static int next_line(const char *text, size_t n, size_t *pos,
                     const char **line, size_t *len)
{
    size_t start = *pos;
    size_t end = start;
    if (start >= n) {
        return 0;
    }
    while (end < n && text[end] != '\n') {
        end++;
    }
    *pos = end + 1;
    *line = text + start;
    *len = end;
    while (*len > start && (text[*len - 1] == '\r' || text[*len - 1] == ' ' ||
                            text[*len - 1] == '\t')) {
        (*len)--;
    }
    *len -= start;
    return 1;
}

/* Length of the first token of line (up to a blank, or a comma). */
static size_t token_len(const char *line, size_t len, int comma)
{
    size_t k = 0;
    while (k < len && line[k] != ' ' && line[k] != '\t' &&
           !(comma && line[k] == ',')) {
        k++;
    }
    return k;
}

/* 1 when line[0..len) starts with an ASTM header keyword: a capital
 * letter, then capitals, digits or underscores, then a blank or the end. */
static int is_keyword(const char *line, size_t len)
{
    size_t k = token_len(line, len, 0);
    size_t j;
    if (k == 0 || !isupper((unsigned char)line[0])) {
        return 0;
    }
    for (j = 1; j < k; j++) {
        if (!isupper((unsigned char)line[j]) &&
            !isdigit((unsigned char)line[j]) && line[j] != '_') {
            return 0;
        }
    }
    return 1;
}

/* 1 when the comma-separated line names the four angle columns. */
static int is_csv_header(const char *line, size_t len)
{
    static const char *const need[4] = {"theta_i", "phi_i", "theta_o",
                                        "phi_o"};
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
                found |= bf__same_nocase(name, need[j]) ? 1u << j : 0u;
            }
        }
    }
    return found == 15u;
}

/* 1 when the first number of the text (comments cut) is a plausible
 * wavelength count. */
static int is_pbrt(const char *text, size_t n)
{
    size_t pos = 0;
    const char *line;
    size_t len;
    while (next_line(text, n, &pos, &line, &len)) {
        char tok[16];
        const char *hash = memchr(line, '#', len);
        size_t k;
        long w;
        if (hash != NULL) {
            len = (size_t)(hash - line);
        }
        while (len > 0 && (*line == ' ' || *line == '\t')) {
            line++;
            len--;
        }
        if (len == 0) {
            continue;
        }
        k = token_len(line, len, 0);
        if (k >= sizeof tok) {
            return 0;
        }
        memcpy(tok, line, k);
        tok[k] = '\0';
        return bf__parse_long(tok, 1, PBRT_W_MAX, &w) == BF__NUM_OK;
    }
    return 0;
}

/* The text formats, from the first DETECT_MAX bytes. */
static int detect_text(const char *text, size_t n, bf_format *f)
{
    size_t pos = 0;
    const char *line;
    size_t len;
    int first = 1;
    int astm = 0;
    if (n >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0) {
        pos = 3; /* a UTF-8 byte order mark (lineio.c) */
    }
    while (next_line(text, n, &pos, &line, &len)) {
        while (len > 0 && (*line == ' ' || *line == '\t')) {
            line++;
            len--;
        }
        if (len == 0 || line[0] == '#') {
            continue;
        }
        if (first && is_csv_header(line, len)) {
            *f = BF_FORMAT_CSV;
            return 1;
        }
        first = 0;
        if (!is_keyword(line, len)) {
            break; /* the end of a header, if any */
        }
        astm |= token_len(line, len, 0) == 10 &&
                memcmp(line, "NUM_POINTS", 10) == 0;
        astm |= token_len(line, len, 0) == 4 && memcmp(line, "VARS", 4) == 0;
    }
    if (astm) {
        *f = BF_FORMAT_ASTM;
        return 1;
    }
    if (is_pbrt(text, n)) {
        *f = BF_FORMAT_PBRT;
        return 1;
    }
    return 0;
}

int bf_format_detect(const char *path, bf_format *f, bf_error *err)
{
    char table[BF_ERROR_FILE_MAX + 16];
    struct stat st;
    FILE *fp = NULL;
    char *buf;
    size_t n;
    int rc;

    bf__error_clear(err, path);
    if (path == NULL || f == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no file name given");
    }
    if (stat(path, &st) != 0) {
        return bf__error_set(err, BF_EIO, 0, "cannot open: %s",
                             strerror(errno));
    }
    if (S_ISDIR(st.st_mode)) {
        snprintf(table, sizeof table, "%s/table.txt", path);
        if (stat(table, &st) == 0) {
            *f = BF_FORMAT_CURET;
            return BF_OK;
        }
        return bf__error_set(err, BF_EIO, 0,
                             "a folder without table.txt (only CURET data "
                             "is a folder)");
    }
    if (S_ISFIFO(st.st_mode)) {
        return bf__error_set(err, BF_EIO, 0,
                             "a pipe: its format cannot be detected "
                             "without consuming it (name the format)");
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    buf = malloc(DETECT_MAX);
    if (buf == NULL) {
        fclose(fp);
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    n = fread(buf, 1, DETECT_MAX, fp);
    if (ferror(fp)) {
        rc = bf__error_set(err, BF_EIO, 0, "read error: %s", strerror(errno));
    } else if (n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "empty file (no format recognised)");
    } else if (n >= sizeof merl_magic &&
               memcmp(buf, merl_magic, sizeof merl_magic) == 0) {
        *f = BF_FORMAT_MERL;
    } else if (memchr(buf, '\0', n) != NULL) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "a binary file that is not a MERL table (it "
                           "does not start with the int32 dimensions 90, "
                           "90, 180)");
    } else if (!detect_text(buf, n, f)) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "no format recognised: not ASTM (no NUM_POINTS "
                           "or VARS header), not tidy CSV (no header "
                           "theta_i,phi_i,theta_o,phi_o), not pbrt (no "
                           "wavelength count first), not MERL");
    }
    free(buf);
    fclose(fp);
    return rc;
}

/* ==== loading ==== */

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* A MERL file at the configurations of opts (checked first: nothing is
 * read without them). */
static int load_merl(const char *path, const bf_load_opts *opts,
                     bf_dataset **out, bf_error *err)
{
    char stem[BF_ERROR_FILE_MAX];
    bf_merl *t = NULL;
    int rc;
    if (opts == NULL || (!opts->all_cells &&
                         (opts->at == NULL || opts->n_at == 0))) {
        bf__error_clear(err, path);
        return bf__error_set(err, BF_EINVAL, 0,
                             "a MERL table is fitted at chosen "
                             "configurations, and none were given");
    }
    rc = bf_merl_load(path, &t, err);
    if (rc == BF_OK) {
        bf__stem(path, stem, sizeof stem);
        rc = bf_merl_dataset(t, opts->all_cells ? 0 : opts->n_at,
                             opts->all_cells ? NULL : opts->at, stem, path,
                             out, err);
    }
    bf_merl_free(t);
    return rc;
}

int bf_dataset_load(const char *path, const bf_load_opts *opts,
                    bf_dataset **out, bf_error *err)
{
    bf_format f = opts != NULL ? opts->format : BF_FORMAT_AUTO;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    bf__error_clear(err, path);
    if (path == NULL || out == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no file name or no output");
    }
    if (f == BF_FORMAT_AUTO && is_dir(path)) {
        f = BF_FORMAT_CURET; /* a folder is read as CURET (brdffit.h) */
    }
    if (f == BF_FORMAT_AUTO) {
        rc = bf_format_detect(path, &f, err);
        if (rc != BF_OK) {
            return rc;
        }
    }
    switch (f) {
    case BF_FORMAT_CURET:
        return bf_curet_load(path, NULL, out, err);
    case BF_FORMAT_PBRT:
        return bf_pbrt_load(path, out, err);
    case BF_FORMAT_ASTM:
        return bf_astm_load(path, out, err);
    case BF_FORMAT_CSV:
        return bf_csv_load(path, out, err);
    case BF_FORMAT_MERL:
        return load_merl(path, opts, out, err);
    default:
        return bf__error_set(err, BF_EINVAL, 0,
                             "no reader for the format \"%s\"",
                             bf_format_name(f) != NULL ? bf_format_name(f)
                                                       : "?");
    }
}

/* ==== the one-material dataset of the readers ==== */

int bf__dataset_single(const bf_material_desc *desc, size_t n,
                       const double *angles, bf_dataset **out,
                       bf_error *err)
{
    bf_material_desc d = *desc;
    bf_dataset *ds = bf_dataset_alloc();
    size_t bad = 0;
    int rc;
    *out = NULL;
    if (ds == NULL) {
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    rc = bf_dataset_add_configs(ds, n, angles, &d.set, &bad);
    if (rc == BF_EINVAL) {
        rc = bf__error_set(err, BF_EINVAL, 0,
                           "configuration %zu lies outside the hemisphere",
                           bad + 1);
    } else if (rc == BF_OK) {
        rc = bf_dataset_add_material(ds, &d, NULL);
        if (rc == BF_EINVAL) {
            rc = bf__error_set(err, BF_EINVAL, 0,
                               "the dataset refuses the material (a value "
                               "that is not finite, or a channel without a "
                               "name)");
        }
    }
    if (rc == BF_ENOMEM) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    if (rc != BF_OK) {
        bf_dataset_free(ds);
        return rc;
    }
    *out = ds;
    return BF_OK;
}
