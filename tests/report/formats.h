/* formats.h: checks of the figure files the report writes -- a PNG's
 * signature, IHDR size and IEND trailer (PNG spec §5.2, §11.2.2, §11.2.5)
 * and its chunks (no text or time chunk: §11.3.4, §11.3.6), an SVG that
 * is well-formed XML with an <svg> root and its width/height, a PDF's
 * header, %%EOF trailer, page count and MediaBox (ISO 32000-1 §7.5.2,
 * §7.5.5, §7.7.3.3), and that no figure carries a title in its metadata.
 * Shared by the report tests; static inline so a test file that uses some
 * of them builds without warnings. */
#ifndef BF_TEST_REPORT_FORMATS_H
#define BF_TEST_REPORT_FORMATS_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reads a whole file into a new buffer (NUL-terminated; caller frees).
 * Fails the test when it cannot be read. */
static inline char *fmt_read(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    char *buf;
    long n;
    cr_assert_not_null(fp, "%s: cannot open", path);
    fseek(fp, 0, SEEK_END);
    n = ftell(fp);
    rewind(fp);
    cr_assert_gt(n, 0, "%s: empty file", path);
    buf = malloc((size_t)n + 1);
    cr_assert_not_null(buf);
    cr_assert_eq(fread(buf, 1, (size_t)n, fp), (size_t)n, "%s: short read",
                 path);
    buf[n] = '\0';
    fclose(fp);
    *len = (size_t)n;
    return buf;
}

/* First occurrence of needle (n bytes) in hay (len bytes), or NULL. */
static inline const char *fmt_find(const char *hay, size_t len,
                                   const char *needle, size_t n)
{
    size_t i;
    for (i = 0; i + n <= len; i++) {
        if (memcmp(hay + i, needle, n) == 0) {
            return hay + i;
        }
    }
    return NULL;
}

static inline unsigned long fmt_be32(const unsigned char *p)
{
    return ((unsigned long)p[0] << 24) | ((unsigned long)p[1] << 16) |
           ((unsigned long)p[2] << 8) | (unsigned long)p[3];
}

/* Asserts path is a PNG of w x h pixels: the 8-byte signature, IHDR as
 * the first chunk (length 13) and IEND as the last. */
static inline void fmt_check_png(const char *path, unsigned long w,
                                 unsigned long h)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G',
                                         '\r', '\n', 0x1a, '\n'};
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E',
                                           'N', 'D', 0xae, 0x42, 0x60, 0x82};
    size_t len;
    unsigned char *d = (unsigned char *)fmt_read(path, &len);
    cr_assert_gt(len, 8 + 25 + 12, "%s: too short for a PNG", path);
    cr_assert(memcmp(d, sig, 8) == 0, "%s: no PNG signature", path);
    cr_assert_eq(fmt_be32(d + 8), 13ul, "%s: IHDR length", path);
    cr_assert(memcmp(d + 12, "IHDR", 4) == 0, "%s: first chunk not IHDR",
              path);
    cr_assert_eq(fmt_be32(d + 16), w, "%s: width %lu, expected %lu", path,
                 fmt_be32(d + 16), w);
    cr_assert_eq(fmt_be32(d + 20), h, "%s: height %lu, expected %lu", path,
                 fmt_be32(d + 20), h);
    cr_assert(memcmp(d + len - 12, iend, 12) == 0, "%s: no IEND trailer",
              path);
    free(d);
}

/* Asserts the PNG at path has no metadata chunk that could carry a title
 * or a date (tEXt, zTXt, iTXt, tIME): walks every chunk from IHDR to IEND
 * by its length. Returns its colour type (IHDR byte 9). */
static inline int fmt_check_png_plain(const char *path)
{
    static const char *const meta[4] = {"tEXt", "zTXt", "iTXt", "tIME"};
    size_t len;
    unsigned char *d = (unsigned char *)fmt_read(path, &len);
    size_t at = 8;
    int type = d[25];
    int k;
    while (at + 12 <= len) {
        unsigned long n = fmt_be32(d + at);
        for (k = 0; k < 4; k++) {
            cr_assert(memcmp(d + at + 4, meta[k], 4) != 0,
                      "%s: a %s chunk (metadata) at byte %zu", path, meta[k],
                      at);
        }
        cr_assert_leq(at + 12 + n, len, "%s: chunk runs past the end",
                      path);
        at += 12 + n;
    }
    cr_assert_eq(at, len, "%s: %zu bytes after the last chunk", path,
                 len - at);
    free(d);
    return type;
}

/* Occurrences of needle in the NUL-terminated text s. */
static inline size_t fmt_count(const char *s, const char *needle)
{
    size_t n = 0;
    size_t k = strlen(needle);
    for (; (s = strstr(s, needle)) != NULL; s += k) {
        n++;
    }
    return n;
}

/* Asserts the SVG at path has no <title> or <desc> element, and returns
 * its number of <path elements. */
static inline size_t fmt_check_svg_plain(const char *path)
{
    size_t len;
    char *s = fmt_read(path, &len);
    size_t n;
    cr_assert_null(strstr(s, "<title"), "%s: a <title> element", path);
    cr_assert_null(strstr(s, "<desc"), "%s: a <desc> element", path);
    n = fmt_count(s, "<path");
    free(s);
    return n;
}

/* Asserts the PDF at path has no /Title entry and no creation date. */
static inline void fmt_check_pdf_plain(const char *path)
{
    size_t len;
    char *s = fmt_read(path, &len);
    cr_assert_null(fmt_find(s, len, "/Title", 6), "%s: a /Title entry",
                   path);
    cr_assert_null(fmt_find(s, len, "/CreationDate", 13),
                   "%s: a creation date (the bytes would change per run)",
                   path);
    free(s);
}

/* Skips a quoted attribute value or markup up to the closing text end;
 * returns the position after it or NULL. */
static inline const char *fmt_skip_to(const char *p, const char *end)
{
    const char *q = strstr(p, end);
    return q != NULL ? q + strlen(end) : NULL;
}

/* Asserts the text is well-formed XML as far as structure goes -- every
 * start tag closed by a matching end tag, attribute values quoted, one
 * root element -- and returns the root's start tag in root (size len). */
static inline void fmt_check_xml(const char *path, const char *s, char *root,
                                 size_t rootlen)
{
    char stack[128][64];
    size_t depth = 0;
    size_t roots = 0;
    const char *p = s;
    root[0] = '\0';
    while ((p = strchr(p, '<')) != NULL) {
        if (strncmp(p, "<?", 2) == 0) {
            p = fmt_skip_to(p, "?>");
        } else if (strncmp(p, "<!--", 4) == 0) {
            p = fmt_skip_to(p, "-->");
        } else if (strncmp(p, "<![CDATA[", 9) == 0) {
            p = fmt_skip_to(p, "]]>");
        } else if (strncmp(p, "<!", 2) == 0) {
            p = fmt_skip_to(p, ">");
        } else if (p[1] == '/') {
            size_t n = strcspn(p + 2, " \t\r\n>");
            cr_assert_gt(depth, 0, "%s: end tag without start tag", path);
            depth--;
            cr_assert(n == strlen(stack[depth]) &&
                          strncmp(p + 2, stack[depth], n) == 0,
                      "%s: </%.*s> closes <%s>", path, (int)n, p + 2,
                      stack[depth]);
            p = fmt_skip_to(p, ">");
        } else {
            const char *start = p;
            size_t n = strcspn(p + 1, " \t\r\n/>");
            char quote = 0;
            cr_assert(n > 0 && n < sizeof stack[0], "%s: bad tag name",
                      path);
            cr_assert_lt(depth, 128, "%s: nesting too deep", path);
            memcpy(stack[depth], p + 1, n);
            stack[depth][n] = '\0';
            for (p += 1 + n; *p != '\0'; p++) { /* attributes */
                if (quote != 0) {
                    quote = *p == quote ? 0 : quote;
                } else if (*p == '"' || *p == '\'') {
                    quote = *p;
                } else if (*p == '>') {
                    break;
                }
            }
            cr_assert_eq(*p, '>', "%s: unterminated tag <%s", path,
                         stack[depth]);
            if (depth == 0) {
                roots++;
                snprintf(root, rootlen, "%.*s", (int)(p - start + 1), start);
            }
            if (p[-1] != '/') {
                depth++;
            }
            p++;
        }
        cr_assert_not_null(p, "%s: unterminated markup", path);
    }
    cr_assert_eq(depth, 0, "%s: %zu element(s) left open", path, depth);
    cr_assert_eq(roots, 1, "%s: %zu root elements", path, roots);
}

/* Value of attribute name in a start tag, as a number (its unit ignored). */
static inline double fmt_attr(const char *tag, const char *name)
{
    char key[64];
    const char *p;
    snprintf(key, sizeof key, " %s=\"", name);
    p = strstr(tag, key);
    cr_assert_not_null(p, "no %s attribute in %s", name, tag);
    return strtod(p + strlen(key), NULL);
}

/* Asserts path is a well-formed SVG document whose root <svg> is w x h
 * (points). */
static inline void fmt_check_svg(const char *path, double w, double h)
{
    size_t len;
    char root[4096];
    char *s = fmt_read(path, &len);
    fmt_check_xml(path, s, root, sizeof root);
    cr_assert(strncmp(root, "<svg", 4) == 0 && strchr(" \t\r\n", root[4]),
              "%s: root element is not <svg>: %.60s", path, root);
    cr_assert_eq(fmt_attr(root, "width"), w, "%s: width", path);
    cr_assert_eq(fmt_attr(root, "height"), h, "%s: height", path);
    free(s);
}

/* Asserts path is a PDF of one page of w x h points. */
static inline void fmt_check_pdf(const char *path, double w, double h)
{
    size_t len;
    char *s = fmt_read(path, &len);
    const char *p = s;
    const char *box;
    size_t pages = 0;
    double mb[4];
    cr_assert(strncmp(s, "%PDF-", 5) == 0, "%s: no %%PDF- header", path);
    cr_assert(len > 32 && fmt_find(s + len - 32, 32, "%%EOF", 5) != NULL,
              "%s: no %%%%EOF trailer", path);
    while ((p = fmt_find(p, len - (size_t)(p - s), "/Type /Page", 11)) !=
           NULL) {
        p += 11;
        pages += *p != 's'; /* /Type /Pages is the page tree */
    }
    cr_assert_eq(pages, 1, "%s: %zu pages, expected 1", path, pages);
    box = fmt_find(s, len, "/MediaBox [", 11);
    cr_assert_not_null(box, "%s: no MediaBox", path);
    cr_assert_eq(sscanf(box + 11, "%lf %lf %lf %lf", &mb[0], &mb[1], &mb[2],
                        &mb[3]),
                 4, "%s: bad MediaBox", path);
    cr_assert(mb[0] == 0.0 && mb[1] == 0.0 && mb[2] == w && mb[3] == h,
              "%s: MediaBox [%g %g %g %g], expected [0 0 %g %g]", path,
              mb[0], mb[1], mb[2], mb[3], w, h);
    free(s);
}

#endif
