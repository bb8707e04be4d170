/* study.h: the study pipeline shared by the subcommands that fit models to
 * samples (compare, and the commands built on it): common options, input
 * loading, selections of samples, models and configurations, running the
 * study and writing its tables. */
#ifndef BF_CLI_STUDY_H
#define BF_CLI_STUDY_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"

/* At most this many --range options. */
#define BF_CLI_MAX_RANGES 8

/* The options every study command accepts (see bf_cli_study_usage). */
typedef struct {
    bf_cli_source src;        /* --data, --brdf, --input, --input-format,
                                 --configs */
    const char *channel;      /* --channel NAME|mean|each (NULL: mean) */
    double cone;              /* --exclude-specular DEG, in degrees; < 0:
                                 the data's default (CURET: its 7) */
    const char *samples;      /* NULL: 'paper' on CURET, else 'all' */
    const char *models;
    const char *n_file;
    const char *on_file;
    const char *exclude;
    const char *out_dir;
    double n;
    int n_given;
    double max_theta; /* degrees */
    int quiet;
    /* beyond the paper (cli/exact.c, doc/methods.md) */
    int exact;                /* --fit exact */
    bf_objective objective;   /* --objective */
    const char *range[BF_CLI_MAX_RANGES]; /* --range NAME=LO:HI */
    size_t n_range;
    size_t n_boot;            /* --bootstrap N */
    size_t folds;             /* --folds K (0: no cross-validation) */
    unsigned long seed;       /* --seed S */
    int samples_given;        /* --samples was on the command line */
    int fit_given;            /* --fit was on the command line */
    int stats;                /* --stats: the analysis with --fit paper */
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

/* A study run: its inputs, selections and results. The study's targets
 * (material x channel) are called samples below, as in the paper: target
 * s is material targets[s].material, numbered samples[s]. */
typedef struct {
    const char *cmd;      /* "compare", for messages */
    bf_cli_opts opts;
    bf_cli_inputs in;
    bf_target *targets;   /* what is fitted */
    int *samples;         /* n_samples material numbers, one per target */
    size_t n_samples;     /* number of targets */
    const bf_model_type **models;
    size_t n_models;
    size_t *exclude;      /* --exclude, parsed (configuration numbers) */
    size_t n_exclude;
    size_t *k;            /* K of each target */
    size_t *n_cone;       /* configurations each target lost to the cone */
    size_t n_sel;         /* K when every target has the same K, else 0 */
    bf_study_spec spec;
    bf_study_row *rows;   /* n_samples x n_models, sample-major */
    bf_model_variant *variants; /* n_models derived types (cli/exact.c) */
    bf_fit_stats *stats;  /* analysis of each row (cli/exact.c) */
} bf_cli_study;

/* Loads the inputs and resolves the selections of st->opts. Returns
 * BF_EXIT_OK or an exit status after printing the error. */
int bf_cli_study_prepare(bf_cli_study *st);

/* Prints a study error (naming the material's file and line when known)
 * and returns its exit status. */
int bf_cli_study_error(const bf_error *err);

/* Runs the study (after prepare): the paper's protocol, then the analysis
 * when asked. Returns BF_EXIT_OK or an exit status. */
int bf_cli_study_run(bf_cli_study *st);

/* The two halves of bf_cli_study_run: the paper's protocol (nothing with
 * --fit exact, where the analysis is the study), then the analysis
 * (--stats, --fit exact, --bootstrap; nothing otherwise). The report
 * draws the paper's figures while the analysis runs. */
int bf_cli_study_run_protocol(bf_cli_study *st);
int bf_cli_study_run_analysis(bf_cli_study *st);

/* Frees everything st owns. */
void bf_cli_study_free(bf_cli_study *st);

/* Whether Table 2 shows parameter j of type: fitted parameters, and the
 * inputs of a model that fits none (ON's tabulated rho, sigma). */
int bf_cli_shows_param(const bf_model_type *type, size_t j);

/* Name of target s's material (borrowed; "" when it has none). */
const char *bf_cli_sample_name(const bf_cli_study *st, size_t s);

/* Name of target s's channel: "mean", or the channel's name (borrowed). */
const char *bf_cli_channel_name(const bf_cli_study *st, size_t s);

/* "Leather" or, when the study fits single channels, "Leather [R]", into
 * buf (the label of Tables 2 and 3 and of the figures). */
void bf_cli_sample_title(const bf_cli_study *st, size_t s, char *buf,
                         size_t len);

/* The used configurations (sel, capacity bf_dataset_nconf of its
 * material), their number *k and the normalised data of target s, as the
 * study fitted them. Returns BF_OK or a BF_E* code. */
int bf_cli_target_data(const bf_cli_study *st, size_t s, size_t *sel,
                       size_t *k, double *data);

/* Prints the "Data:" lines: CURET's files, or each material's file,
 * format, configurations and channels. */
void bf_cli_describe_data(const bf_cli_study *st, FILE *fp);

/* The specular exclusion in words, into buf. */
void bf_cli_describe_cone(const bf_cli_study *st, char *buf, size_t len);

/* Prints what was run: data, configurations used, conventions. */
void bf_cli_study_describe(const bf_cli_study *st, FILE *fp);

/* Writes fits.csv, table2.md and table3.md atomically into the output
 * folder and, unless quiet, prints the description and both tables. Returns
 * BF_EXIT_OK or an exit status after printing the error. */
int bf_cli_study_write_tables(const bf_cli_study *st);

/* ==== beyond the paper (cli/exact.c) ==================================== */

/* Replaces st->models by variants: with --fit exact FC's n is fitted over
 * [BF_FREE_N_LO, BF_FREE_N_HI] (unless --n or --n-file fixes it) and ON's
 * rho and sigma are fitted; every --range applies. Returns BF_EXIT_OK or an
 * exit status after printing the error. */
int bf_cli_exact_models(bf_cli_study *st);

/* Runs the analysis (refinement, intervals, criteria) after the study;
 * with --fit exact it is the study. Returns BF_EXIT_OK or an exit status. */
int bf_cli_exact_run(bf_cli_study *st);

/* Prints the fit, objective, interval and selection lines of the
 * description. */
void bf_cli_exact_describe(const bf_cli_study *st, FILE *fp);

/* With --fit exact and --on-params: prints ON's fitted rho, sigma (and
 * their profile intervals) beside CURET's tabulated values. */
void bf_cli_exact_on_compare(const bf_cli_study *st, FILE *fp);

/* The columns fits.csv gains (header, and the values for row i and
 * parameter j, j = SIZE_MAX for a model without fitted parameter). */
void bf_cli_exact_csv_header(FILE *fp);
void bf_cli_exact_csv_cols(const bf_cli_study *st, size_t i, size_t j,
                           FILE *fp);

/* Parses --range NAME=LO:HI. Returns 0, or -1 with a message in msg. */
int bf_cli_parse_range(const char *s, char *name, size_t name_len,
                       double *lo, double *hi, char *msg, size_t msg_len);

/* Writes the sample, name and channel fields of target s (no trailing
 * comma) to a CSV file. */
void bf_cli_csv_sample(FILE *fp, const bf_cli_study *st, size_t s);

/* Writes a field to a CSV file, quoted when needed (cli/study.c). */
void bf_cli_csv_field(FILE *fp, const char *s);


/* ==== model selection (cli/ranking.c) ==================================== */

/* The criteria of the ranking (doc/methods.md §4-5). */
enum { BF_CLI_AIC, BF_CLI_BIC, BF_CLI_CV, BF_CLI_NCRIT };
extern const char *const bf_cli_crit_names[BF_CLI_NCRIT];

/* Value of criterion c for row i (NaN when not computed); needs st->stats. */
double bf_cli_rank_value(const bf_cli_study *st, size_t i, int c);
/* Rank (1 = best) of model m for sample s by criterion c. */
size_t bf_cli_rank_of(const bf_cli_study *st, size_t s, size_t m, int c);
/* The best model of sample s by criterion c, (size_t)-1 when none. */
size_t bf_cli_rank_best(const bf_cli_study *st, size_t s, int c);
/* The per-sample table of criterion crit (caller frees), NULL on ENOMEM. */
struct bf_tt *bf_cli_rank_table(const bf_cli_study *st, int crit);
/* Prints "BIC: FC-E best for 32 of 61 samples, ON 13, ..." and a newline. */
void bf_cli_rank_summary(const bf_cli_study *st, int c, FILE *fp);

#endif
