/* study.h: the study pipeline shared by the subcommands that fit models to
 * samples (compare, and the commands built on it): common options, input
 * loading, selections of samples, models and configurations, running the
 * study and writing its tables. */
#ifndef BF_CLI_STUDY_H
#define BF_CLI_STUDY_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"

/* The options every study command accepts (see bf_cli_study_usage). */
typedef struct {
    const char *data_dir;
    const char *brdf_file;
    const char *samples;
    const char *models;
    const char *n_file;
    const char *on_file;
    const char *exclude;
    const char *out_dir;
    double n;
    int n_given;
    double max_theta; /* degrees */
    int quiet;
    int threads;      /* --threads: 1 by default, 0 = one per core */
} bf_cli_opts;

/* A command's own options: getopt_long entries (val >= 512) and a handler
 * called with the entry's val and optarg; it returns 0, or an exit status
 * after printing a usage error. */
typedef struct {
    const struct option *longopts; /* NULL-terminated, may be NULL */
    int (*handle)(int val, const char *arg, void *ctx);
    void *ctx;
} bf_cli_extra;

/* Parses argv of command cmd ("compare") into o. usage prints the
 * command's help. Returns 0 to go on, -1 after --help (exit 0), or an exit
 * status after a usage error. */
int bf_cli_opts_parse(const char *cmd, int argc, char **argv,
                      void (*usage)(FILE *fp), const bf_cli_extra *extra,
                      bf_cli_opts *o);

/* Prints the help lines of the common options. */
void bf_cli_opts_usage(FILE *fp);

/* A study run: its inputs, selections and results. */
typedef struct {
    const char *cmd;      /* "compare", for messages */
    bf_cli_opts opts;
    bf_cli_inputs in;
    int *samples;
    size_t n_samples;
    const bf_model_type **models;
    size_t n_models;
    size_t *sel;          /* used configurations (0-based) */
    size_t n_sel;
    bf_study_spec spec;
    bf_study_row *rows;   /* n_samples x n_models, sample-major */
} bf_cli_study;

/* Loads the inputs and resolves the selections of st->opts. Returns
 * BF_EXIT_OK or an exit status after printing the error. */
int bf_cli_study_prepare(bf_cli_study *st);

/* Runs the study (after prepare). Returns BF_EXIT_OK or an exit status. */
int bf_cli_study_run(bf_cli_study *st);

/* Frees everything st owns. */
void bf_cli_study_free(bf_cli_study *st);

/* Name of a sample from samples.tsv, or "" (borrowed). */
const char *bf_cli_sample_name(const bf_cli_study *st, int sample);

/* Prints what was run: data, configurations used, conventions. */
void bf_cli_study_describe(const bf_cli_study *st, FILE *fp);

/* Writes fits.csv, table2.md and table3.md atomically into the output
 * folder and, unless quiet, prints the description and both tables. Returns
 * BF_EXIT_OK or an exit status after printing the error. */
int bf_cli_study_write_tables(const bf_cli_study *st);

#endif
