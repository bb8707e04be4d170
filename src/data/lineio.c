/* lineio.c: the line reader and strict number parsers shared by every
 * text-file loader of src/data/ (declared in internal.h).
 *
 * Accepted file syntax, decided once for all loaders:
 *   - line ends are LF or CRLF; the last line may lack a line end. A CR that
 *     is not followed by LF (or by the end of the file) is an error: old Mac
 *     line ends would otherwise silently merge the whole file into one line;
 *   - a UTF-8 byte order mark (EF BB BF) at the very start of the file is
 *     skipped (editors on Windows add one); anywhere else it is ordinary text
 *     and fails number parsing;
 *   - trailing spaces and tabs are ignored (CURET's abrdf.dat has them);
 *   - blank lines (empty or only spaces and tabs) are skipped wherever they
 *     are, but still counted, so reported line numbers match an editor's;
 *   - a NUL byte is an error (a binary file given by mistake);
 *   - a line longer than BF__LINE_MAX bytes is an error. Lines are read with
 *     getc into a buffer that grows up to that cap, rather than with getline,
 *     so a huge or endless line cannot make us allocate without bound.
 * Numbers are decimal only (see bf__parse_double): no hex floats, no
 * nan/inf, no overflow to infinity, no trailing characters. */
#include "internal.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ==== line reader ==== */

void bf__lines_init(bf__lines *r, FILE *fp)
{
    memset(r, 0, sizeof *r);
    r->fp = fp;
}

void bf__lines_free(bf__lines *r)
{
    if (r == NULL) {
        return;
    }
    free(r->buf);
    free(r->field);
    r->buf = NULL;
    r->field = NULL;
    r->len = 0;
    r->cap = 0;
    r->nfield = 0;
    r->field_cap = 0;
}

/* Appends byte c to r->buf, growing it up to BF__LINE_MAX + 1 bytes. */
static int push_byte(bf__lines *r, int c, long line, bf_error *err)
{
    if (r->len >= BF__LINE_MAX) {
        return bf__error_set(err, BF_EPARSE, line,
                             "line longer than %zu bytes", BF__LINE_MAX);
    }
    if (r->len + 1 >= r->cap) {
        size_t cap = r->cap == 0 ? 256 : 2 * r->cap;
        char *buf;
        if (cap > BF__LINE_MAX + 1) {
            cap = BF__LINE_MAX + 1;
        }
        buf = realloc(r->buf, cap);
        if (buf == NULL) {
            return bf__error_set(err, BF_ENOMEM, line,
                                 "out of memory reading a line");
        }
        r->buf = buf;
        r->cap = cap;
    }
    r->buf[r->len++] = (char)c;
    return BF_OK;
}

/* Reads one physical line (any content) into r->buf. *eof is set when the
 * stream ended before any byte of the line. */
static int read_line(bf__lines *r, int *eof, bf_error *err)
{
    static const unsigned char bom[3] = {0xEF, 0xBB, 0xBF};
    long line = r->line + 1;
    int rc;
    int c;

    r->len = 0;
    *eof = 0;
    if (!r->started) {
        /* Skip a UTF-8 BOM; a partial match is kept as ordinary text. */
        size_t k = 0;
        r->started = 1;
        while (k < 3) {
            c = getc(r->fp);
            if (c != bom[k]) {
                if (c != EOF) {
                    ungetc(c, r->fp);
                }
                break;
            }
            k++;
        }
        if (k < 3) {
            size_t j;
            for (j = 0; j < k; j++) {
                rc = push_byte(r, bom[j], line, err);
                if (rc != BF_OK) {
                    return rc;
                }
            }
        }
    }
    for (;;) {
        c = getc(r->fp);
        if (c == EOF) {
            if (ferror(r->fp)) {
                return bf__error_set(err, BF_EIO, line, "read error: %s",
                                     strerror(errno));
            }
            if (r->len == 0 && feof(r->fp)) {
                *eof = 1;
            }
            break;
        }
        if (c == '\n') {
            break;
        }
        if (c == '\r') {
            int next = getc(r->fp);
            if (next == '\n' || next == EOF) {
                if (next == EOF && ferror(r->fp)) {
                    return bf__error_set(err, BF_EIO, line, "read error: %s",
                                         strerror(errno));
                }
                break;
            }
            return bf__error_set(err, BF_EPARSE, line,
                                 "carriage return not followed by a line "
                                 "feed (only LF and CRLF line ends are "
                                 "accepted)");
        }
        if (c == '\0') {
            return bf__error_set(err, BF_EPARSE, line,
                                 "NUL byte at column %zu (binary file?)",
                                 r->len + 1);
        }
        rc = push_byte(r, c, line, err);
        if (rc != BF_OK) {
            return rc;
        }
    }
    if (!*eof) {
        r->line = line;
    }
    /* Make sure buf exists and is terminated, even for an empty line. */
    if (r->cap == 0) {
        r->buf = malloc(256);
        if (r->buf == NULL) {
            return bf__error_set(err, BF_ENOMEM, line,
                                 "out of memory reading a line");
        }
        r->cap = 256;
    }
    r->buf[r->len] = '\0';
    return BF_OK;
}

static int is_blank(char c)
{
    return (c == ' ') || (c == '\t');
}

int bf__lines_next(bf__lines *r, int *have_line, bf_error *err)
{
    *have_line = 0;
    r->nfield = 0;
    for (;;) {
        int eof = 0;
        int rc = read_line(r, &eof, err);
        if (rc != BF_OK) {
            return rc;
        }
        if (eof) {
            return BF_OK;
        }
        while ((r->len > 0) && is_blank(r->buf[r->len - 1])) {
            r->buf[--r->len] = '\0';
        }
        if (r->buf[strspn(r->buf, " \t")] != '\0') {
            *have_line = 1;
            return BF_OK;
        }
        /* A blank line: skipped, but counted in r->line. */
    }
}

/* Appends a field pointer, growing r->field. */
static int push_field(bf__lines *r, char *f, bf_error *err)
{
    if (r->nfield == r->field_cap) {
        size_t cap = r->field_cap == 0 ? 16 : 2 * r->field_cap;
        char **field = realloc(r->field, cap * sizeof *field);
        if (field == NULL) {
            return bf__error_set(err, BF_ENOMEM, r->line,
                                 "out of memory splitting a line");
        }
        r->field = field;
        r->field_cap = cap;
    }
    r->field[r->nfield++] = f;
    return BF_OK;
}

int bf__lines_split_ws(bf__lines *r, bf_error *err)
{
    char *p = r->buf;
    r->nfield = 0;
    for (;;) {
        int rc;
        while (is_blank(*p)) {
            p++;
        }
        if (*p == '\0') {
            return BF_OK;
        }
        rc = push_field(r, p, err);
        if (rc != BF_OK) {
            return rc;
        }
        while ((*p != '\0') && !is_blank(*p)) {
            p++;
        }
        if (*p != '\0') {
            *p++ = '\0';
        }
    }
}

int bf__lines_split_tab(bf__lines *r, bf_error *err)
{
    char *p = r->buf;
    r->nfield = 0;
    for (;;) {
        char *end = strchr(p, '\t');
        char *q;
        int rc;
        if (end != NULL) {
            *end = '\0';
        }
        while (*p == ' ') {
            p++;
        }
        q = p + strlen(p);
        while ((q > p) && (q[-1] == ' ')) {
            *--q = '\0';
        }
        rc = push_field(r, p, err);
        if (rc != BF_OK) {
            return rc;
        }
        if (end == NULL) {
            return BF_OK;
        }
        p = end + 1;
    }
}

/* ==== strict number parsing ==== */

/* Length of the longest prefix of s of the form [+-] digits [. digits]
 * [(e|E) [+-] digits] with at least one mantissa digit; 0 if none. *is_int
 * is set when the prefix has neither a point nor an exponent. */
static size_t decimal_prefix(const char *s, int *is_int)
{
    size_t k = 0;
    size_t digits = 0;
    *is_int = 1;
    if ((s[k] == '+') || (s[k] == '-')) {
        k++;
    }
    while (isdigit((unsigned char)s[k])) {
        k++;
        digits++;
    }
    if (s[k] == '.') {
        size_t frac = 0;
        while (isdigit((unsigned char)s[k + 1 + frac])) {
            frac++;
        }
        if (digits + frac > 0) {
            k += 1 + frac;
            digits += frac;
            *is_int = 0;
        }
    }
    if (digits == 0) {
        return 0;
    }
    if ((s[k] == 'e') || (s[k] == 'E')) {
        size_t e = k + 1;
        if ((s[e] == '+') || (s[e] == '-')) {
            e++;
        }
        if (isdigit((unsigned char)s[e])) {
            while (isdigit((unsigned char)s[e])) {
                e++;
            }
            k = e;
            *is_int = 0;
        }
    }
    return k;
}

/* 1 when s starts with word (lower case), ignoring the case of s. */
static int starts_with_nocase(const char *s, const char *word)
{
    while (*word != '\0') {
        if (tolower((unsigned char)*s) != *word) {
            return 0;
        }
        s++;
        word++;
    }
    return 1;
}

/* Classifies a text that is not a plain decimal number. */
static int classify_bad(const char *s)
{
    const char *p = s;
    if ((*p == '+') || (*p == '-')) {
        p++;
    }
    if ((p[0] == '0') && ((p[1] == 'x') || (p[1] == 'X'))) {
        return BF__NUM_HEX;
    }
    if (starts_with_nocase(p, "nan") || starts_with_nocase(p, "inf")) {
        return BF__NUM_NONFINITE;
    }
    return BF__NUM_SYNTAX;
}

int bf__parse_double(const char *text, double *value)
{
    int is_int;
    size_t k = decimal_prefix(text, &is_int);
    char *end = NULL;
    double v;
    if ((k == 0) || (text[k] != '\0')) {
        int bad = classify_bad(text);
        if ((k > 0) && (bad == BF__NUM_SYNTAX)) {
            return BF__NUM_TRAILING;
        }
        return bad;
    }
    errno = 0;
    v = strtod(text, &end);
    /* strtod follows the C locale's decimal point; the library never calls
     * setlocale, but an application might: refuse rather than misread. */
    if (end != text + k) {
        return BF__NUM_SYNTAX;
    }
    if (!isfinite(v)) {
        return BF__NUM_RANGE;
    }
    if ((errno == ERANGE) && (fabs(v) > 1.0)) {
        return BF__NUM_RANGE;
    }
    /* ERANGE with a tiny result is underflow: accepted, v is 0 or
     * subnormal. */
    *value = v;
    return BF__NUM_OK;
}

int bf__parse_long(const char *text, long min, long max, long *value)
{
    int is_int;
    size_t k = decimal_prefix(text, &is_int);
    char *end = NULL;
    long v;
    if ((k == 0) || (text[k] != '\0')) {
        int bad = classify_bad(text);
        if ((k > 0) && (bad == BF__NUM_SYNTAX)) {
            return BF__NUM_TRAILING;
        }
        return bad;
    }
    if (!is_int) {
        return BF__NUM_NOTINT;
    }
    errno = 0;
    v = strtol(text, &end, 10);
    if (end != text + k) {
        return BF__NUM_SYNTAX;
    }
    if ((errno == ERANGE) || (v < min) || (v > max)) {
        return BF__NUM_RANGE;
    }
    *value = v;
    return BF__NUM_OK;
}

/* Writes a printable, truncated copy of text into out (size n): bytes
 * outside printable ASCII become \xNN, and text longer than BF__QUOTE_MAX
 * bytes ends in "...". */
void bf__quote(const char *text, char *out, size_t n)
{
    size_t k = 0;
    size_t j = 0;
    while ((text[k] != '\0') && (k < BF__QUOTE_MAX) && (j + 5 < n)) {
        unsigned char c = (unsigned char)text[k++];
        if ((c >= 0x20) && (c < 0x7f)) {
            out[j++] = (char)c;
        } else {
            j += (size_t)snprintf(out + j, n - j, "\\x%02X", c);
        }
    }
    if ((text[k] != '\0') && (j + 4 < n)) {
        memcpy(out + j, "...", 3);
        j += 3;
    }
    out[j] = '\0';
}

int bf__field_error(const bf__lines *r, size_t i, const char *what,
                    int status, long min, long max, bf_error *err)
{
    char q[BF__QUOTE_BUF];
    char range[64];
    const char *reason;
    bf__quote(r->field[i], q, sizeof q);
    switch (status) {
    case BF__NUM_TRAILING:
        reason = "unexpected characters after the number";
        break;
    case BF__NUM_HEX:
        reason = "hexadecimal numbers are not accepted";
        break;
    case BF__NUM_NONFINITE:
        reason = "not a finite number";
        break;
    case BF__NUM_NOTINT:
        reason = "not an integer";
        break;
    case BF__NUM_RANGE:
        if (min <= max) {
            snprintf(range, sizeof range, "out of range (must be %ld to %ld)",
                     min, max);
            reason = range;
        } else {
            reason = "out of range (overflows a double)";
        }
        break;
    default:
        reason = "not a decimal number";
        break;
    }
    return bf__error_set(err, BF_EPARSE, r->line, "field %zu (%s): %s: \"%s\"",
                         i + 1, what, reason, q);
}

int bf__field_double(const bf__lines *r, size_t i, const char *what,
                     double *value, bf_error *err)
{
    int st = bf__parse_double(r->field[i], value);
    if (st != BF__NUM_OK) {
        return bf__field_error(r, i, what, st, 1, 0, err);
    }
    return BF_OK;
}

int bf__field_long(const bf__lines *r, size_t i, const char *what, long min,
                   long max, long *value, bf_error *err)
{
    int st = bf__parse_long(r->field[i], min, max, value);
    if (st != BF__NUM_OK) {
        return bf__field_error(r, i, what, st, min, max, err);
    }
    return BF_OK;
}

/* ==== opening files ==== */

int bf__open(const char *path, FILE **fp, bf_error *err)
{
    struct stat st;
    FILE *f;
    *fp = NULL;
    bf__error_clear(err, path); /* every report of a _load names its file */
    if (path == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no file name given");
    }
    /* fopen succeeds on a directory on Linux; fstat tells what we opened.
     * A FIFO blocks in fopen until a writer opens it, as FIFOs do. */
    f = fopen(path, "r");
    if (f == NULL) {
        return bf__error_set(err, bf__errno_code(errno), 0,
                             "cannot open: %s", strerror(errno));
    }
    if (fstat(fileno(f), &st) != 0) {
        int e = errno;
        fclose(f);
        return bf__error_set(err, BF_EIO, 0, "cannot stat: %s", strerror(e));
    }
    if (S_ISDIR(st.st_mode)) {
        fclose(f);
        return bf__error_set(err, BF_EIO, 0,
                             "is a directory, not a data file");
    }
    if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
        fclose(f);
        return bf__error_set(err, BF_EIO, 0,
                             "not a regular file or pipe");
    }
    *fp = f;
    return BF_OK;
}

/* ==== comments, comma-separated fields, file names, angles ==== */

int bf__lines_is_comment(const bf__lines *r)
{
    return r->buf[strspn(r->buf, " \t")] == '#';
}

int bf__lines_split_csv(bf__lines *r, bf_error *err)
{
    char *p = r->buf;
    r->nfield = 0;
    for (;;) {
        char *start;
        char *end;
        int rc;
        while (is_blank(*p)) {
            p++;
        }
        start = p;
        if (*p == '"') {
            /* Quoted: copy the content down over the quotes, "" -> ". */
            char *w = p;
            p++;
            for (;;) {
                if (*p == '\0') {
                    return bf__error_set(err, BF_EPARSE, r->line,
                                         "field %zu: quote not closed "
                                         "before the end of the line",
                                         r->nfield + 1);
                }
                if (*p == '"' && p[1] == '"') {
                    *w++ = '"';
                    p += 2;
                } else if (*p == '"') {
                    p++;
                    break;
                } else {
                    *w++ = *p++;
                }
            }
            end = w;
            while (is_blank(*p)) {
                p++;
            }
            if (*p != ',' && *p != '\0') {
                return bf__error_set(err, BF_EPARSE, r->line,
                                     "field %zu: text after the closing "
                                     "quote",
                                     r->nfield + 1);
            }
        } else {
            while (*p != ',' && *p != '\0') {
                p++;
            }
            end = p;
            while (end > start && is_blank(end[-1])) {
                end--;
            }
        }
        rc = push_field(r, start, err);
        if (rc != BF_OK) {
            return rc;
        }
        if (*p == '\0') {
            *end = '\0';
            return BF_OK;
        }
        *end = '\0'; /* end <= p: the comma (or before it) */
        p++;
    }
}

void bf__stem(const char *path, char *out, size_t len)
{
    const char *base;
    const char *dot;
    size_t n;
    if (len == 0) {
        return;
    }
    out[0] = '\0';
    if (path == NULL) {
        return;
    }
    base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    dot = strrchr(base, '.');
    n = (dot != NULL && dot != base) ? (size_t)(dot - base) : strlen(base);
    if (n >= len) {
        n = len - 1;
    }
    memcpy(out, base, n);
    out[n] = '\0';
}

int bf__angle_ok(double *a, int zenith)
{
    double lo = zenith ? 0.0 : -2.0 * BF__PI;
    double hi = zenith ? BF__PI_2 : 2.0 * BF__PI;
    if (!(*a >= lo - BF__ANGLE_TOL) || !(*a <= hi + BF__ANGLE_TOL)) {
        return 0;
    }
    if (*a < lo) {
        *a = lo;
    } else if (*a > hi) {
        *a = hi;
    }
    return 1;
}

void bf__format_double(double v, char *buf)
{
    int p;
    for (p = 15; p <= 17; p++) {
        snprintf(buf, 32, "%.*g", p, v);
        if (strtod(buf, NULL) == v) {
            return;
        }
    }
}

int bf__channel_wavelength(const char *text, double *nm)
{
    char num[64];
    size_t n = strlen(text);
    double v;
    /* the unit nm (any case), possibly after blanks, is required: a bare
     * number is a name like any other */
    if (n < 2 || tolower((unsigned char)text[n - 1]) != 'm' ||
        tolower((unsigned char)text[n - 2]) != 'n') {
        return 0;
    }
    n -= 2;
    while (n > 0 && is_blank(text[n - 1])) {
        n--;
    }
    if (n == 0 || n >= sizeof num) {
        return 0;
    }
    memcpy(num, text, n);
    num[n] = '\0';
    if (bf__parse_double(num, &v) != BF__NUM_OK || !(v > 0.0)) {
        return 0;
    }
    *nm = v;
    return 1;
}

/* ==== small helpers of the readers ==== */

char *bf__strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d != NULL) {
        memcpy(d, s, n);
    }
    return d;
}

int bf__same_nocase(const char *a, const char *b)
{
    while (*a != '\0' &&
           tolower((unsigned char)*a) == tolower((unsigned char)*b)) {
        a++;
        b++;
    }
    return *a == '\0' && *b == '\0';
}

int bf__grow(void **p, size_t *cap, size_t need, size_t size)
{
    size_t c;
    void *q;
    if (need <= *cap) {
        return BF_OK;
    }
    c = *cap == 0 ? 64 : *cap;
    while (c < need) {
        if (c > SIZE_MAX / 2) {
            return BF_ENOMEM;
        }
        c *= 2;
    }
    if (c > SIZE_MAX / size) {
        return BF_ENOMEM;
    }
    q = realloc(*p, c * size);
    if (q == NULL) {
        return BF_ENOMEM;
    }
    *p = q;
    *cap = c;
    return BF_OK;
}

int bf__load_dataset(const char *path,
                     int (*read)(FILE *, const char *, bf_dataset **,
                                 bf_error *),
                     bf_dataset **out, bf_error *err)
{
    FILE *fp = NULL;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = read(fp, path, out, err);
    fclose(fp);
    return rc;
}

int bf__reader_begin(bf__lines *r, FILE *fp, const char *name,
                     bf_dataset **out, bf_error *err)
{
    bf__error_clear(err, name);
    bf__lines_init(r, fp);
    if (out != NULL) {
        *out = NULL;
    }
    if (out == NULL || fp == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    return BF_OK;
}
