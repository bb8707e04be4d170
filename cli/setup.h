/* setup.h: the CLI's side of a study run (compare, rank, calibrate,
 * report): its parsed options as the report library's bf_report_options,
 * its loader as the inputs' load callback, and the library's messages and
 * progress printed on stderr. */
#ifndef BF_CLI_SETUP_H
#define BF_CLI_SETUP_H

#include "options.h"
#include "study.h"

/* What a command's study owns on the CLI's side: its parsed options, the
 * loaded inputs and the progress line. */
typedef struct {
    bf_cli_opts opts;
    bf_cli_inputs in;
    bf_cli_progress progress;
} bf_cli_run;

/* Fills ro and rin (the load callback reading r->opts.src, the n and ON
 * files into r->in) from r->opts: the descriptions and tables printed on
 * stdout unless quiet, progress on stderr when it is a terminal. */
void bf_cli_report_options(bf_cli_run *r, bf_report_options *ro,
                           bf_report_inputs *rin);

/* Sets st up for command cmd from r (bf_cli_report_options) and prepares
 * it (bf_rep_study_prepare). Returns BF_EXIT_OK or an exit status after
 * the message. */
int bf_cli_study_setup(const char *cmd, bf_cli_run *r, bf_rep_study *st);

/* Frees what r owns (the loaded inputs). */
void bf_cli_run_free(bf_cli_run *r);

/* The library's messages on stderr ("brdffit: ..."; an option's error
 * with the hint to run 'brdffit CMD --help', ctx the command name): a
 * bf_report_message_fn. */
void bf_cli_message(void *ctx, int kind, const char *text);

#endif
