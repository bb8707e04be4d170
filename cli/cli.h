/* cli.h: shared pieces of the brdffit command-line tool -- exit codes,
 * messages, argument lists, input loading and atomic output files. */
#ifndef BF_CLI_H
#define BF_CLI_H

#include <stdio.h>

#include "brdffit.h"
#include "rep.h"

/* Exit statuses (documented in README.md, --help and brdffit.1); 64-74
 * follow BSD sysexits.h. Command-line errors get one code per kind (61-64)
 * so scripts can tell a typo from a bad value. */
enum {
    BF_EXIT_OK = 0,       /* success */
    BF_EXIT_NOVALUE = 61, /* missing argument: no command, or an option
                             without its value */
    BF_EXIT_CONFLICT = BF_REPORT_CONFLICT, /* options that cannot be
                                              combined (62) */
    BF_EXIT_BADVALUE = BF_REPORT_BADVALUE, /* malformed or out-of-range
                                              option value (63) */
    BF_EXIT_USAGE = 64,   /* unknown command or option, unexpected
                             argument */
    BF_EXIT_DATAERR = BF_REPORT_DATAERR,   /* malformed or unusable input
                                              data (65) */
    BF_EXIT_NOINPUT = BF_REPORT_NOINPUT,   /* an input file cannot be
                                              opened (66) */
    BF_EXIT_SOFTWARE = BF_REPORT_SOFTWARE, /* internal error (a bug:
                                              please report it; 70) */
    BF_EXIT_CANTCREAT = BF_REPORT_CANTCREAT, /* the output folder or a
                                                file cannot be created */
    BF_EXIT_IOERR = BF_REPORT_IOERR        /* an output file cannot be
                                              written (74) */
};

extern const char *bf_cli_prog; /* "brdffit" */

/* Prints "brdffit: <message>" to stderr. */
void bf_cli_err(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Prints a one-line usage error and the hint to run --help (cmd is the
 * subcommand followed by a space, e.g. "compare ", or NULL); returns
 * status, one of BF_EXIT_NOVALUE, _CONFLICT, _BADVALUE, _USAGE. */
int bf_cli_usage_fail(int status, const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* bf_cli_usage_fail with BF_EXIT_USAGE (unknown option or argument). */
int bf_cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Prints the exit statuses of the study commands (after a blank line):
 * the text of their --help. */
void bf_cli_exit_usage(FILE *fp);

/* Maps a loader failure to a message on stderr and an exit status. */
int bf_cli_load_error(const bf_error *err);

/* At most this many --input files. */
#define BF_CLI_MAX_INPUTS 64

/* Where a run's measurements come from: a CURET folder, or --input files
 * in any format (SPEC §8). */
typedef struct {
    const char *data_dir;    /* CURET folder: read when there is no input,
                                and MERL's default configurations */
    const char *brdf_file;   /* CURET: --brdf, or NULL for abrdf.dat */
    const char *inputs[BF_CLI_MAX_INPUTS]; /* --input files, in order */
    size_t n_inputs;
    bf_format format;        /* --input-format, BF_FORMAT_AUTO to detect */
    const char *configs;     /* MERL: NULL (CURET's table of data_dir),
                                "all" (every valid cell) or a CSV file */
} bf_cli_source;

/* The inputs of a run: the dataset and the per-sample tables, with the
 * files they came from (for provenance). */
typedef struct {
    int curet;                /* 1 when the data are a CURET folder */
    char table_path[4096];    /* CURET's files ("" otherwise) */
    char brdf_path[4096];
    char names_path[4096];    /* "" when there is no samples.tsv */
    char configs_path[4096];  /* the file MERL was sampled at, or "" */
    bf_dataset *ds;
    bf_sample_table *n_file;  /* NULL unless --n-file */
    bf_sample_table *on_params;
} bf_cli_inputs;

/* Loads the measurements of src (a CURET folder, or every --input
 * appended in order, MERL sampled as src->configs says) and the optional n
 * and ON files. Returns BF_EXIT_OK or an exit status after printing the
 * error. */
int bf_cli_load_data(const bf_cli_source *src, const char *n_file,
                     const char *on_file, bf_cli_inputs *in);
void bf_cli_free_inputs(bf_cli_inputs *in);

/* Fills src with the defaults: the CURET folder of $BRDFFIT_DATA or
 * BF_DEFAULT_DATA_DIR, no input, format detected. */
void bf_cli_source_init(bf_cli_source *src);

/* Parses a --input-format value into *f; a usage error (status returned,
 * message printed) when it names no format. cmd is "compare " etc. */
int bf_cli_parse_format(const char *cmd, const char *arg, bf_format *f);

/* Parses the options of the commands that read files (info, convert):
 * --input-format, --configs, --data, and --to when to is not NULL. *first
 * gets the index of the first operand. Returns 0, -1 after --help, or an
 * exit status after a usage error. */
int bf_cli_file_args(const char *cmd, int argc, char **argv,
                     void (*usage)(FILE *fp), const char **to,
                     bf_cli_source *src, int *first);

/* Prints the help lines of the options bf_cli_file_args parses. */
void bf_cli_file_args_usage(FILE *fp);

/* Makes path src's only input: a folder is read as CURET, anything else
 * as an --input file. */
void bf_cli_source_path(bf_cli_source *src, const char *path);

/* Subcommands. */
/* The progress line of a long run (cli/progress.c): on stderr when it is
 * a terminal and not quiet, once the run has lasted a second, with the time
 * left at the mean rate; bf_cli_progress_cb is a bf_progress_fn (ctx: the
 * bf_cli_progress). */
typedef struct {
    const char *what;
    int enabled;
    int shown;
    double t0;
    double last;
} bf_cli_progress;
void bf_cli_progress_init(bf_cli_progress *p, const char *what, int quiet);
void bf_cli_progress_cb(void *ctx, size_t done, size_t total);
/* Ends the line (a final "done in ..."), when one was shown. */
void bf_cli_progress_end(bf_cli_progress *p);

int bf_cmd_compare(int argc, char **argv);
int bf_cmd_convert(int argc, char **argv);
int bf_cmd_info(int argc, char **argv);
int bf_cmd_models(int argc, char **argv);
int bf_cmd_report(int argc, char **argv);
int bf_cmd_rank(int argc, char **argv);
int bf_cmd_calibrate(int argc, char **argv);

#endif
