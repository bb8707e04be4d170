/* texttable.h: a small grid of strings printed as an aligned Markdown pipe
 * table (readable in a terminal, pasteable into documents) or as an HTML
 * table (report.html). */
#ifndef BF_TEXTTABLE_H
#define BF_TEXTTABLE_H

#include <stdio.h>

typedef struct bf_tt bf_tt;

/* A table with ncols columns; column 0.. headers set with bf_tt_header.
 * Returns NULL when out of memory. */
bf_tt *bf_tt_alloc(size_t ncols);
void bf_tt_free(bf_tt *t);
/* Sets the text of header column c (copied). Returns 0, -1 on ENOMEM. */
int bf_tt_header(bf_tt *t, size_t c, const char *text);
/* Marks column c right-aligned (numbers). */
void bf_tt_right(bf_tt *t, size_t c);
/* Appends an empty row; returns 0, -1 on ENOMEM. */
int bf_tt_add_row(bf_tt *t);
/* Sets cell c of the last row (printf format). Returns 0, -1 on ENOMEM. */
int bf_tt_set(bf_tt *t, size_t c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* 1 when a header, row or cell could not be stored (out of memory) since
 * bf_tt_alloc (or t is NULL): the table is incomplete, and the print
 * functions write nothing and return -1. One check after building it. */
int bf_tt_failed(const bf_tt *t);
/* Prints the table; returns 0, or -1 when a write failed. */
int bf_tt_print(const bf_tt *t, FILE *fp);
/* Writes the table as an HTML <table> (id attribute when id is not NULL;
 * the header row in <thead>, right-aligned columns with class "n"), text
 * escaped. Returns 0, or -1 when a write failed. */
int bf_tt_print_html(const bf_tt *t, const char *id, FILE *fp);
/* Writes s (NULL: nothing) with HTML's special characters escaped. */
void bf_tt_html_text(FILE *fp, const char *s);

#endif
