/* report_html.h: writes report.html -- one self-contained page (no
 * network: inline style, images by relative path into the output folder)
 * that describes the data it was given, with a table of contents, every
 * table as an HTML table, the figures with captions and alternative text
 * (per-sample figures in collapsible sections), the conventions of the run
 * and its provenance (version, command line, SHA-256 of every input file).
 * report_html.c writes the page, report_tables.c its tables. */
#ifndef BF_REPORT_REPORT_HTML_H
#define BF_REPORT_REPORT_HTML_H

#include <stdio.h>

#include "figures.h"
#include "ranking.h"
#include "sha256.h"
#include "tables.h"

/* An input file and its checksum. */
typedef struct {
    const char *role;         /* "configuration table", ... */
    char path[4096];
    long long size;           /* bytes */
    char sha256[BF_SHA256_HEX];
} bf_report_input;

#define BF_REPORT_MAX_INPUTS 8

/* Everything the page records besides the study and the figures. */
typedef struct {
    int argc;                 /* the command's arguments (argv[0] is the */
    char **argv;              /*   subcommand name) */
    bf_report_input inputs[BF_REPORT_MAX_INPUTS];
    size_t n_inputs;
    const bf_fig_opts *fig;   /* how the figures were drawn */
} bf_report_meta;

/* Fills meta->inputs with the input files of st and their SHA-256. Returns
 * BF_REPORT_OK or a status after the message. */
int bf_report_checksums(const bf_rep_study *st, bf_report_meta *meta);

/* Writes the page to fp. Deterministic: the same run gives the same bytes
 * (no dates). Returns 0, -1 when a write failed, or -2 when a part of the
 * page could not be formed for want of memory (the page is incomplete). */
int bf_report_html(const bf_rep_study *st, const bf_fig_set *figs,
                   const bf_report_meta *meta, FILE *fp);

/* ---- the tables (report_tables.c) ---- */

/* Table 2 (id "table2"): fitted parameters, * on a grid bound. */
void bf_report_table2(FILE *fp, const bf_rep_study *st);
/* Table 3 (id "table3"): LSE, the lowest of each sample marked. */
void bf_report_table3(FILE *fp, const bf_rep_study *st);
/* Model selection (needs st->stats): samples won per criterion (id
 * "wins-table") and, collapsed, BIC per sample (id "bic-table"). */
void bf_report_selection(FILE *fp, const bf_rep_study *st);
/* The fitted parameters with their intervals (needs st->stats; id
 * "intervals"): one row per sample, model and free parameter. */
void bf_report_intervals(FILE *fp, const bf_rep_study *st);

#endif
