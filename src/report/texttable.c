/* texttable.c: aligned Markdown pipe tables (see texttable.h). Widths count
 * UTF-8 code points so that Greek letters in headers align. */
#include "texttable.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

struct bf_tt {
    size_t ncols;
    size_t nrows;     /* body rows */
    char **cells;     /* (nrows + 1) x ncols, row 0 = header */
    unsigned char *right;
    size_t *w;        /* bf_tt_print's column widths */
    int failed;       /* a cell or row could not be stored */
};

bf_tt *bf_tt_alloc(size_t ncols)
{
    bf_tt *t = calloc(1, sizeof *t);
    if (t == NULL) {
        return NULL;
    }
    t->ncols = ncols;
    t->cells = calloc(ncols, sizeof *t->cells);
    t->right = calloc(ncols, 1);
    t->w = calloc(ncols + 1, sizeof *t->w);
    if (t->cells == NULL || t->right == NULL || t->w == NULL) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}

void bf_tt_free(bf_tt *t)
{
    size_t i;
    if (t == NULL) {
        return;
    }
    if (t->cells != NULL) {
        for (i = 0; i < (t->nrows + 1) * t->ncols; i++) {
            free(t->cells[i]);
        }
    }
    free(t->cells);
    free(t->right);
    free(t->w);
    free(t);
}

static int set_cell(bf_tt *t, size_t row, size_t c, const char *text)
{
    char *copy;
    if (c >= t->ncols) {
        return -1;
    }
    copy = malloc(strlen(text) + 1);
    if (copy == NULL) {
        t->failed = 1;
        return -1;
    }
    strcpy(copy, text);
    free(t->cells[row * t->ncols + c]);
    t->cells[row * t->ncols + c] = copy;
    return 0;
}

int bf_tt_header(bf_tt *t, size_t c, const char *text)
{
    return set_cell(t, 0, c, text);
}

void bf_tt_right(bf_tt *t, size_t c)
{
    if (c < t->ncols) {
        t->right[c] = 1;
    }
}

int bf_tt_add_row(bf_tt *t)
{
    size_t n = (t->nrows + 2) * t->ncols;
    char **cells = realloc(t->cells, n * sizeof *cells);
    if (cells == NULL) {
        t->failed = 1;
        return -1;
    }
    memset(cells + (t->nrows + 1) * t->ncols, 0, t->ncols * sizeof *cells);
    t->cells = cells;
    t->nrows++;
    return 0;
}

int bf_tt_set(bf_tt *t, size_t c, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return set_cell(t, t->nrows, c, buf);
}

/* Display width: UTF-8 code points (continuation bytes do not count). */
static size_t width(const char *s)
{
    size_t w = 0;
    if (s == NULL) {
        return 0;
    }
    for (; *s != '\0'; s++) {
        if (((unsigned char)*s & 0xC0) != 0x80) {
            w++;
        }
    }
    return w;
}

static void pad(FILE *fp, size_t n, char ch)
{
    while (n-- > 0) {
        fputc(ch, fp);
    }
}

int bf_tt_failed(const bf_tt *t)
{
    return t == NULL || t->failed;
}

int bf_tt_print(const bf_tt *t, FILE *fp)
{
    size_t *w = t->w;
    size_t r;
    size_t c;
    if (t->failed) {
        return -1;
    }
    memset(w, 0, t->ncols * sizeof *w);
    for (r = 0; r <= t->nrows; r++) {
        for (c = 0; c < t->ncols; c++) {
            size_t cw = width(t->cells[r * t->ncols + c]);
            if (cw > w[c]) {
                w[c] = cw;
            }
        }
    }
    for (r = 0; r <= t->nrows; r++) {
        for (c = 0; c < t->ncols; c++) {
            const char *s = t->cells[r * t->ncols + c];
            size_t fill = w[c] - width(s);
            fputs("| ", fp);
            if (t->right[c] && r > 0) {
                pad(fp, fill, ' ');
            }
            fputs(s != NULL ? s : "", fp);
            if (!(t->right[c] && r > 0)) {
                pad(fp, fill, ' ');
            }
            fputc(' ', fp);
        }
        fputs("|\n", fp);
        if (r == 0) {
            for (c = 0; c < t->ncols; c++) {
                fputs("|", fp);
                pad(fp, 1, t->right[c] ? '-' : ':');
                pad(fp, w[c], '-');
                pad(fp, 1, t->right[c] ? ':' : '-');
            }
            fputs("|\n", fp);
        }
    }
    return ferror(fp) ? -1 : 0;
}

void bf_tt_html_text(FILE *fp, const char *s)
{
    for (; s != NULL && *s != '\0'; s++) {
        switch (*s) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp); break;
        }
    }
}

int bf_tt_print_html(const bf_tt *t, const char *id, FILE *fp)
{
    size_t r;
    size_t c;
    if (t->failed) {
        return -1;
    }
    fputs("<table", fp);
    if (id != NULL) {
        fputs(" id=\"", fp);
        bf_tt_html_text(fp, id);
        fputc('"', fp);
    }
    fputs(">\n<thead><tr>", fp);
    for (c = 0; c < t->ncols; c++) {
        fputs("<th>", fp);
        bf_tt_html_text(fp, t->cells[c]);
        fputs("</th>", fp);
    }
    fputs("</tr></thead>\n<tbody>\n", fp);
    for (r = 1; r <= t->nrows; r++) {
        fputs("<tr>", fp);
        for (c = 0; c < t->ncols; c++) {
            fputs(t->right[c] ? "<td class=\"n\">" : "<td>", fp);
            bf_tt_html_text(fp, t->cells[r * t->ncols + c]);
            fputs("</td>", fp);
        }
        fputs("</tr>\n", fp);
    }
    fputs("</tbody>\n</table>\n", fp);
    return ferror(fp) ? -1 : 0;
}
