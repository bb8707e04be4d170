/* pbrt.c: pbrt-v2 / Cornell .brdf files (SPEC §8), one material with W
 * spectral channels.
 *
 * [1] M. Pharr, G. Humphreys, pbrt-v2, src/materials/measured.cpp: the
 *     layout -- a stream of numbers: W, the W wavelengths (nm), then
 *     records theta_i phi_i theta_o phi_o v_1 ... v_W (radians, BRDF in
 *     sr^-1); N numbers in all with (N - 1 - W) mod (4 + W) = 0.
 * [2] shared/data/cornell-pbrt-v2/SOURCES.md: the five Cornell files (31
 *     wavelengths 400 ... 700 nm, 1439 records each) and their headers.
 *
 * Syntax (lineio.c for lines and numbers): '#' starts a comment that runs
 * to the end of its line, anywhere; numbers are separated by blanks and
 * line ends, and records may wrap across lines. Checks: W is an integer
 * in [1, W_MAX]; wavelengths are positive and increase; angles are those
 * of the measurement frame (SPEC §1.5), zeniths in [0, pi/2], azimuths in
 * [-2 pi, 2 pi] (bf__angle_ok); values are finite (negative ones are kept,
 * SPEC §2); the numbers after the wavelengths form whole records, at
 * least one.
 *
 * The material's name is the file's description: its first block of
 * comment lines, when a blank line ends it (a block that runs straight
 * into the first number is a label, "# num wls"), leaving out lines that
 * name "Cornell University" (the data's provenance, not the material),
 * the rest joined with ", " ("Cayman Metallic, High-gloss Paint"); else
 * the file name without its extension ("acryl_blue"). */
#include <stdlib.h>
#include <string.h>

#include "data/reader.h"
#include "internal.h"

/* Most wavelengths accepted: far above any spectrometer's (Cornell's
 * instrument samples 1024 and files keep 31 or 65). */
#define W_MAX 65536

/* Longest description kept as the material's name, in bytes. */
#define DESC_MAX 200

/* Angles of a record, in order (SPEC §1.5). */
static const char *const angle_name[4] = {"theta_i", "phi_i", "theta_o",
                                          "phi_o"};

/* Where the description stands. */
enum { DESC_COLLECTING, DESC_FOUND, DESC_NONE };

typedef struct {
    long w;            /* wavelength count, 0 until read */
    size_t n_wl;       /* wavelengths read */
    double *wl;        /* W wavelengths */
    size_t n_after;    /* numbers read after the wavelengths */
    size_t n_rec;      /* complete records */
    double *angles;    /* n_rec x 4 (and the one being read) */
    double *values;    /* n_rec x W */
    size_t cap_a;      /* doubles angles holds */
    size_t cap_v;      /* doubles values holds */
    long first_line;   /* line of the first record */
    long rec_line;     /* line where the record being read began */
    int desc_state;    /* DESC_* */
    long block_end;    /* last line of the first comment block, 0: none */
    char desc[DESC_MAX + 1];
} pbrt_state;

static void state_free(pbrt_state *s)
{
    free(s->wl);
    free(s->angles);
    free(s->values);
}

/* ==== the description ==== */

/* Appends the text of a comment line to the description (see the file's
 * comment); control characters become spaces. */
static void desc_add(pbrt_state *s, const char *line)
{
    size_t len = strlen(s->desc);
    size_t n;
    size_t k;
    line += strspn(line, " \t#");
    n = strlen(line);
    while (n > 0 && (line[n - 1] == ' ' || line[n - 1] == '\t')) {
        n--;
    }
    if (n == 0 || strstr(line, "Cornell University") != NULL) {
        return;
    }
    if (len > 0) {
        if (len + 2 >= DESC_MAX) {
            return; /* full */
        }
        memcpy(s->desc + len, ", ", 2);
        len += 2;
    }
    if (len + n > DESC_MAX) {
        n = DESC_MAX - len;
        /* never cut a UTF-8 sequence: drop its continuation bytes */
        while (n > 0 && ((unsigned char)line[n] & 0xC0) == 0x80) {
            n--;
        }
    }
    for (k = 0; k < n; k++) {
        unsigned char c = (unsigned char)line[k];
        s->desc[len + k] = (c < 0x20 || c == 0x7F) ? ' ' : (char)c;
    }
    s->desc[len + n] = '\0';
}

/* Follows the first comment block through line r (before any number). */
static void desc_line(pbrt_state *s, const bf__lines *r, int comment)
{
    if (s->desc_state != DESC_COLLECTING) {
        return;
    }
    if (s->block_end > 0 && r->line > s->block_end + 1) {
        s->desc_state = DESC_FOUND; /* a blank line ended the block */
    } else if (!comment) {
        s->desc_state = DESC_NONE; /* no block, or a label of a number */
        s->desc[0] = '\0';
    } else {
        desc_add(s, r->buf);
        s->block_end = r->line;
    }
}

/* ==== the numbers ==== */

/* Grows the record arrays to hold record n_rec (the one being read). */
static int reserve(pbrt_state *s, const bf__lines *r, bf_error *err)
{
    size_t need = s->n_rec + 1;
    if (bf__grow((void **)&s->angles, &s->cap_a, 4 * need,
                 sizeof *s->angles) != BF_OK ||
        bf__grow((void **)&s->values, &s->cap_v, (size_t)s->w * need,
                 sizeof *s->values) != BF_OK) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    return BF_OK;
}

/* Takes field i of line r: the count, a wavelength, or a record's next
 * number. */
static int take(pbrt_state *s, const bf__lines *r, size_t i, bf_error *err)
{
    char what[64];
    double v;
    int rc;
    if (s->w == 0) {
        rc = bf__field_long(r, i, "wavelength count", 1, W_MAX, &s->w, err);
        if (rc == BF_OK) {
            s->wl = malloc((size_t)s->w * sizeof *s->wl);
            if (s->wl == NULL) {
                rc = bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
            }
        }
        return rc;
    }
    if (s->n_wl < (size_t)s->w) {
        snprintf(what, sizeof what, "wavelength %zu", s->n_wl + 1);
        rc = bf__field_double(r, i, what, &v, err);
        if (rc == BF_OK && !(v > 0.0)) {
            rc = bf__error_set(err, BF_EPARSE, r->line,
                               "field %zu (%s) = %g: a wavelength (nm) must "
                               "be positive",
                               i + 1, what, v);
        }
        if (rc == BF_OK && s->n_wl > 0 && !(v > s->wl[s->n_wl - 1])) {
            rc = bf__error_set(err, BF_EPARSE, r->line,
                               "field %zu (%s) = %g after %g: wavelengths "
                               "must increase",
                               i + 1, what, v, s->wl[s->n_wl - 1]);
        }
        if (rc == BF_OK) {
            s->wl[s->n_wl++] = v;
        }
        return rc;
    }
    {
        size_t slot = s->n_after % (4 + (size_t)s->w);
        if (slot == 0) {
            rc = reserve(s, r, err);
            if (rc != BF_OK) {
                return rc;
            }
            s->rec_line = r->line;
        }
        if (slot < 4) {
            snprintf(what, sizeof what, "%s of record %zu", angle_name[slot],
                     s->n_rec + 1);
        } else {
            snprintf(what, sizeof what, "value %zu of record %zu", slot - 3,
                     s->n_rec + 1);
        }
        rc = bf__field_double(r, i, what, &v, err);
        if (rc != BF_OK) {
            return rc;
        }
        if (slot < 4 && !bf__angle_ok(&v, slot % 2 == 0)) {
            return bf__error_set(err, BF_EPARSE, r->line,
                                 "field %zu (%s) = %g outside [%s]", i + 1,
                                 what, v,
                                 slot % 2 == 0 ? "0, pi/2" : "-2 pi, 2 pi");
        }
        if (slot < 4) {
            s->angles[4 * s->n_rec + slot] = v;
        } else {
            s->values[s->n_rec * (size_t)s->w + slot - 4] = v;
        }
        s->n_after++;
        if (slot == 3 + (size_t)s->w) {
            if (s->n_rec == 0) {
                s->first_line = s->rec_line;
            }
            s->n_rec++;
        }
    }
    return BF_OK;
}

/* The end-of-file checks: every part present, whole records. last is
 * the last line, lines the count of non-blank ones. */
static int check_end(const pbrt_state *s, long last, long lines,
                     bf_error *err)
{
    size_t partial;
    if (s->w == 0) {
        return bf__error_set(err, BF_EPARSE, 0,
                             lines == 0 ? "empty file"
                                        : "no numbers (a .brdf file starts "
                                          "with its wavelength count)");
    }
    if (s->n_wl < (size_t)s->w) {
        return bf__error_set(err, BF_EPARSE, last,
                             "the file ends after %zu of its %ld "
                             "wavelengths",
                             s->n_wl, s->w);
    }
    partial = s->n_after % (4 + (size_t)s->w);
    if (partial != 0) {
        return bf__error_set(err, BF_EPARSE, last,
                             "the file ends inside record %zu (from line "
                             "%ld): %zu of its 4 + %ld numbers",
                             s->n_rec + 1, s->rec_line, partial, s->w);
    }
    if (s->n_rec == 0) {
        return bf__error_set(err, BF_EPARSE, last,
                             "no records after the %ld wavelengths", s->w);
    }
    return BF_OK;
}

/* ==== the reader ==== */

/* The dataset of a complete file. */
static int build(const pbrt_state *s, const char *name, bf_dataset **out,
                 bf_error *err)
{
    char stem[BF_ERROR_FILE_MAX];
    char (*names)[32] = malloc((size_t)s->w * sizeof *names);
    const char **channel = malloc((size_t)s->w * sizeof *channel);
    bf_material_desc d;
    size_t c;
    int rc;
    if (names == NULL || channel == NULL) {
        free(names);
        free((void *)channel);
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    for (c = 0; c < (size_t)s->w; c++) {
        bf__format_double(s->wl[c], names[c]);
        channel[c] = names[c];
    }
    bf__stem(name, stem, sizeof stem);
    memset(&d, 0, sizeof d);
    d.name = s->desc_state == DESC_FOUND && s->desc[0] != '\0' ? s->desc
                                                                 : stem;
    d.format = BF_FORMAT_PBRT;
    d.source = name;
    d.line = s->first_line;
    d.n_channels = (size_t)s->w;
    d.channel = channel;
    d.wavelength = s->wl;
    d.values = s->values;
    rc = bf__dataset_single(&d, s->n_rec, s->angles, out, err);
    free(names);
    free((void *)channel);
    return rc;
}

int bf_pbrt_read(FILE *fp, const char *name, bf_dataset **out, bf_error *err)
{
    bf__lines r;
    pbrt_state s;
    long lines = 0;
    int have = 0;
    int rc;

    memset(&s, 0, sizeof s);
    rc = bf__reader_begin(&r, fp, name, out, err);
    if (rc != BF_OK) {
        return rc;
    }
    for (;;) {
        char *hash;
        size_t i;
        rc = bf__lines_next(&r, &have, err);
        if (rc != BF_OK || !have) {
            break;
        }
        lines++;
        if (s.w == 0) {
            desc_line(&s, &r, bf__lines_is_comment(&r));
        }
        hash = strchr(r.buf, '#');
        if (hash != NULL) {
            *hash = '\0'; /* a comment runs to the end of the line [1] */
        }
        rc = bf__lines_split_ws(&r, err);
        for (i = 0; rc == BF_OK && i < r.nfield; i++) {
            rc = take(&s, &r, i, err);
        }
        if (rc != BF_OK) {
            break;
        }
    }
    if (rc == BF_OK) {
        rc = check_end(&s, r.line, lines, err);
    }
    if (rc == BF_OK) {
        rc = build(&s, name, out, err);
    }
    bf__lines_free(&r);
    state_free(&s);
    return rc;
}

int bf_pbrt_load(const char *path, bf_dataset **out, bf_error *err)
{
    return bf__load_dataset(path, bf_pbrt_read, out, err);
}

/* ==== the reader (reader.h) ==== */

/* Detection: the first number of the text (comments cut) is a plausible
 * wavelength count, an integer in [1, W_MAX]. */
static int detect(const char *text, size_t n)
{
    size_t pos = 0;
    const char *line;
    size_t len;
    while (bf__detect_line(text, n, &pos, &line, &len)) {
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
        k = 0;
        while (k < len && line[k] != ' ' && line[k] != '\t') {
            k++;
        }
        if (k >= sizeof tok) {
            return 0;
        }
        memcpy(tok, line, k);
        tok[k] = '\0';
        return bf__parse_long(tok, 1, W_MAX, &w) == BF__NUM_OK;
    }
    return 0;
}

static const char *const aliases[] = {"brdf", NULL};

const bf__reader bf__pbrt_reader = {
    .name = "pbrt",
    .aliases = aliases,
    .title = "pbrt",
    .detect = detect,
    .rank = BF__RANK_GUESS,
    .miss = "not pbrt (no wavelength count first)",
    .read = bf_pbrt_read,
};
