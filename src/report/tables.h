/* tables.h: what a study run prints and writes -- the description of the
 * run (data, configurations, conventions, fit), Tables 2 and 3 of the
 * paper, and the files fits.csv (the library's writer), table2.md and
 * table3.md. */
#ifndef BF_REPORT_TABLES_H
#define BF_REPORT_TABLES_H

#include <stdio.h>

#include "study.h"

/* Prints the "Data:" lines: CURET's files, or each material's file,
 * format, configurations and channels. */
void bf_rep_describe_data(const bf_rep_study *st, FILE *fp);

/* The specular exclusion in words, into buf. */
void bf_rep_describe_cone(const bf_rep_study *st, char *buf, size_t len);

/* The longest title bf_rep_table2_title and bf_rep_table3_title write. */
#define BF_REP_TITLE_LEN 320

/* Table 2's title, "Table 2: fitted parameters (...)" without a line end,
 * as table2.md, the terminal and report.html give it: grid or exact
 * optima (grid_beside: the exact optimum with the grid's beside it, as
 * the text tables show them), and what an asterisk means when some fit
 * is on a bound. Into buf (len bytes, BF_REP_TITLE_LEN suffice). */
void bf_rep_table2_title(const bf_rep_study *st, int grid_beside, char *buf,
                         size_t len);

/* Table 3's title, "Table 3: ..." without a line end: the value it holds
 * under the run's objective (LSE, objective S, or SPEC §10's E; a joint
 * fit's E over K C values) and the configurations it sums over -- "the K
 * used" in table3.md (file), with K's value where every sample has the
 * same otherwise. Into buf as bf_rep_table2_title. */
void bf_rep_table3_title(const bf_rep_study *st, int file, char *buf,
                         size_t len);

/* How many of st's models are specular or composites D+S (SPEC §9); the
 * others are the paper's kind, fitted on its grids (SPEC §7.4). */
size_t bf_rep_n_specular(const bf_rep_study *st);

/* 1 when the study's model v (a variant: bf_model_variant_exact) fits its
 * parameter j though the registry's model of that name holds it (FC's n,
 * ON's rho and sigma under --fit exact): the run's "Free parameters". */
int bf_rep_param_freed(const bf_model_type *v, size_t j);

/* How st's models use inputs of kind `kind` (bf_param.input), a set of
 * BF_REP_INPUT_*: HELD when one holds such a parameter (the study gives
 * its value: --n, --n-file, --on-params), FREED when one fits it though
 * the paper's protocol holds it (bf_rep_param_freed: FC's n, ON's rho
 * and sigma under --fit exact), OWN when one fits it as a parameter of
 * its own (a specular model's n under --fresnel dielectric, ABC's ior,
 * WNO's n). The description's and the page's Fresnel and Oren-Nayar
 * lines follow it. */
enum { BF_REP_INPUT_HELD = 1, BF_REP_INPUT_FREED = 2, BF_REP_INPUT_OWN = 4 };
unsigned bf_rep_input_use(const bf_rep_study *st, bf_input kind);

/* Prints what was run: data, configurations used, conventions, the fit,
 * its free parameters and the analysis. Returns BF_REPORT_OK, or
 * BF_REPORT_SOFTWARE after the message when out of memory. */
int bf_rep_study_describe(const bf_rep_study *st, FILE *fp);

/* Writes fits.csv, table2.md and table3.md atomically into the output
 * folder and, when st->opts.echo is set, prints the description and both
 * tables there. Returns BF_REPORT_OK or a status after the message. */
int bf_rep_study_write_tables(const bf_rep_study *st);

#endif
