/* format.c: the formats brdffit reads -- the registry of their readers
 * (reader.h), and through it their names, detection from the content and
 * loading any of them into a dataset (SPEC §8); plus the one-material
 * dataset the single-material readers build.
 *
 * [1] SPEC §8 (the formats and what identifies each).
 *
 * Detection looks at the content, never at the name: a folder is the
 * folder format whose file it holds (CURET: table.txt); of a file, the
 * first BF__DETECT_MAX bytes go to each reader's detect by increasing
 * rank -- the binary formats' magic first (MERL), then, unless a NUL byte
 * makes the file binary, the text formats (tidy CSV's header line, ASTM's
 * header keywords, pbrt's first number). Each reader's file says what its
 * detect looks for. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "data/reader.h"
#include "internal.h"

/* The registry, one line per format: its position is its bf_format value
 * (brdffit.h; Python's cdef relies on the first seven), so a new reader
 * goes at the end. "auto" and "memory" are names without a reader. Adding
 * a format is its reader file in src/data/ (the build takes every file
 * there) defining `const bf__reader bf__<name>_reader`, and one READER()
 * line here; detection order is the readers' rank, not this order. */
#define BF_FORMATS(NAME, READER)                                            \
    NAME("auto")                                                            \
    READER(bf__curet_reader)                                                \
    READER(bf__pbrt_reader)                                                 \
    READER(bf__astm_reader)                                                 \
    READER(bf__merl_reader)                                                 \
    READER(bf__csv_reader)                                                  \
    NAME("memory")

#define FORMAT_NONE(n)
#define FORMAT_DECLARE(v) extern const bf__reader v;
#define FORMAT_NAME(n) {n, NULL},
#define FORMAT_READER(v) {NULL, &v},
BF_FORMATS(FORMAT_NONE, FORMAT_DECLARE)

static const struct {
    const char *name; /* a format without a reader */
    const bf__reader *reader;
} formats[] = {BF_FORMATS(FORMAT_NAME, FORMAT_READER)};

#define N_FORMATS (sizeof formats / sizeof formats[0])

size_t bf__format_count(void)
{
    return N_FORMATS;
}

const bf__reader *bf__reader_of(bf_format f)
{
    return ((int)f >= 0 && (size_t)f < N_FORMATS) ? formats[f].reader : NULL;
}

bf_format bf__reader_format(const bf__reader *r)
{
    size_t i;
    for (i = 0; i < N_FORMATS; i++) {
        if (formats[i].reader == r) {
            return (bf_format)i;
        }
    }
    return BF_FORMAT_AUTO;
}

const char *bf_format_name(bf_format f)
{
    if ((int)f < 0 || (size_t)f >= N_FORMATS) {
        return NULL;
    }
    return formats[f].reader != NULL ? formats[f].reader->name
                                     : formats[f].name;
}

int bf_format_find(const char *name, bf_format *f)
{
    size_t i;
    size_t k;
    if (name == NULL || f == NULL) {
        return BF_EINVAL;
    }
    for (i = 0; i < N_FORMATS; i++) {
        if (bf__same_nocase(name, bf_format_name((bf_format)i))) {
            *f = (bf_format)i;
            return BF_OK;
        }
    }
    for (i = 0; i < N_FORMATS; i++) {
        const bf__reader *r = formats[i].reader;
        for (k = 0; r != NULL && r->aliases != NULL && r->aliases[k] != NULL;
             k++) {
            if (bf__same_nocase(name, r->aliases[k])) {
                *f = (bf_format)i;
                return BF_OK;
            }
        }
    }
    return BF_ENOTFOUND;
}

/* ==== detection ==== */

/* Registry positions of the readers for which keep(r) is 1, ordered by
 * before(a, b) (ties: registry order) into idx; their count. */
static size_t readers_where(int (*keep)(const bf__reader *),
                            int (*before)(const bf__reader *,
                                          const bf__reader *),
                            size_t idx[N_FORMATS])
{
    size_t n = 0;
    size_t i;
    for (i = 0; i < N_FORMATS; i++) {
        size_t j = n;
        if (formats[i].reader == NULL || !keep(formats[i].reader)) {
            continue;
        }
        while (j > 0 && before(formats[i].reader, formats[idx[j - 1]].reader)) {
            idx[j] = idx[j - 1];
            j--;
        }
        idx[j] = i;
        n++;
    }
    return n;
}

static int is_file_format(const bf__reader *r)
{
    return r->detect != NULL;
}

static int is_folder_format(const bf__reader *r)
{
    return r->folder_file != NULL;
}

static int is_text_format(const bf__reader *r)
{
    return r->detect != NULL && !r->binary;
}

static int is_binary_format(const bf__reader *r)
{
    return r->detect != NULL && r->binary;
}

static int by_rank(const bf__reader *a, const bf__reader *b)
{
    return a->rank < b->rank;
}

static int by_name(const bf__reader *a, const bf__reader *b)
{
    return strcmp(a->name, b->name) < 0;
}

static int in_registry_order(const bf__reader *a, const bf__reader *b)
{
    (void)a;
    (void)b;
    return 0;
}

/* Appends text to buf (size BF_ERROR_MSG_MAX, truncated). */
static void append(char *buf, const char *a, const char *b)
{
    size_t used = strlen(buf);
    snprintf(buf + used, BF_ERROR_MSG_MAX - used, "%s%s", a, b);
}

/* The folder format whose file dir holds; with fallback, the first folder
 * format when none does (its reader then names the file it lacks), else
 * BF_FORMAT_AUTO. */
static bf_format folder_format(const char *dir, int fallback)
{
    char file[BF_ERROR_FILE_MAX + 64];
    size_t idx[N_FORMATS];
    size_t n = readers_where(is_folder_format, in_registry_order, idx);
    struct stat st;
    size_t k;
    for (k = 0; k < n; k++) {
        snprintf(file, sizeof file, "%s/%s", dir,
                 formats[idx[k]].reader->folder_file);
        if (stat(file, &st) == 0) {
            return (bf_format)idx[k];
        }
    }
    return fallback && n > 0 ? (bf_format)idx[0] : BF_FORMAT_AUTO;
}

static int folder_error(bf_error *err)
{
    char files[BF_ERROR_MSG_MAX] = "";
    char titles[BF_ERROR_MSG_MAX] = "";
    size_t idx[N_FORMATS];
    size_t n = readers_where(is_folder_format, in_registry_order, idx);
    size_t k;
    for (k = 0; k < n; k++) {
        append(files, k > 0 ? " or " : "", formats[idx[k]].reader->folder_file);
        append(titles, k > 0 ? " or " : "", formats[idx[k]].reader->title);
    }
    return bf__error_set(err, BF_EIO, 0,
                         "a folder without %s (only %s data is a folder)",
                         files, titles);
}

/* What no reader recognised in buf: a binary file (a NUL byte) is none of
 * the binary formats; a text file is none of them all. */
static int unknown_error(int binary, bf_error *err)
{
    char msg[BF_ERROR_MSG_MAX] = "";
    size_t idx[N_FORMATS];
    size_t n;
    size_t k;
    if (binary) {
        n = readers_where(is_binary_format, by_name, idx);
        for (k = 0; k < n; k++) {
            append(msg, k > 0 ? " or " : "", formats[idx[k]].reader->miss);
        }
        return bf__error_set(err, BF_EPARSE, 0,
                             "a binary file that is not %s", msg);
    }
    n = readers_where(is_text_format, by_name, idx);
    for (k = 0; k < n; k++) {
        append(msg, k > 0 ? ", " : "", formats[idx[k]].reader->miss);
    }
    n = readers_where(is_binary_format, by_name, idx);
    for (k = 0; k < n; k++) {
        append(msg, msg[0] != '\0' ? ", not " : "not ",
               formats[idx[k]].reader->title);
    }
    return bf__error_set(err, BF_EPARSE, 0, "no format recognised: %s", msg);
}

/* The format of the n >= 1 bytes of buf, by rank; an error when none. */
static int detect_bytes(const char *buf, size_t n, bf_format *f,
                        bf_error *err)
{
    int binary = memchr(buf, '\0', n) != NULL;
    size_t idx[N_FORMATS];
    size_t m = readers_where(is_file_format, by_rank, idx);
    size_t k;
    for (k = 0; k < m; k++) {
        const bf__reader *r = formats[idx[k]].reader;
        if ((r->binary || !binary) && r->detect(buf, n)) {
            *f = (bf_format)idx[k];
            return BF_OK;
        }
    }
    return unknown_error(binary, err);
}

int bf_format_detect(const char *path, bf_format *f, bf_error *err)
{
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
        return bf__error_set(err, bf__errno_code(errno), 0,
                             "cannot open: %s", strerror(errno));
    }
    if (S_ISDIR(st.st_mode)) {
        bf_format g = folder_format(path, 0);
        if (g == BF_FORMAT_AUTO) {
            return folder_error(err);
        }
        *f = g;
        return BF_OK;
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
    buf = malloc(BF__DETECT_MAX);
    if (buf == NULL) {
        fclose(fp);
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    n = fread(buf, 1, BF__DETECT_MAX, fp);
    if (ferror(fp)) {
        rc = bf__error_set(err, BF_EIO, 0, "read error: %s", strerror(errno));
    } else if (n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "empty file (no format recognised)");
    } else {
        rc = detect_bytes(buf, n, f, err);
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

int bf_dataset_load(const char *path, const bf_load_opts *opts,
                    bf_dataset **out, bf_error *err)
{
    bf_format f = opts != NULL ? opts->format : BF_FORMAT_AUTO;
    const bf__reader *r;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    bf__error_clear(err, path);
    if (path == NULL || out == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no file name or no output");
    }
    if (f == BF_FORMAT_AUTO && is_dir(path)) {
        f = folder_format(path, 1); /* a folder is read, not detected */
    }
    if (f == BF_FORMAT_AUTO) {
        rc = bf_format_detect(path, &f, err);
        if (rc != BF_OK) {
            return rc;
        }
    }
    r = bf__reader_of(f);
    if (r == NULL) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "no reader for the format \"%s\"",
                             bf_format_name(f) != NULL ? bf_format_name(f)
                                                       : "?");
    }
    return r->load != NULL ? r->load(path, opts, out, err)
                           : bf__load_dataset(path, r->read, out, err);
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
