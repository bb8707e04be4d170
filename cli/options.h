/* options.h: the options every study command accepts (compare, rank,
 * report), their defaults per command, parsing and help text. */
#ifndef BF_CLI_OPTIONS_H
#define BF_CLI_OPTIONS_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"

/* Upper limit of --threads (a typo guard, not a machine limit). */
#define BF_CLI_MAX_THREADS BF_REPORT_MAX_THREADS

/* At most this many --range options. */
#define BF_CLI_MAX_RANGES BF_REPORT_MAX_RANGES

/* The options every study command accepts (see bf_cli_opts_usage). */
typedef struct {
    bf_cli_source src;        /* --data, --brdf, --input, --input-format,
                                 --configs */
    const char *channel;      /* --channel NAME|mean|each (NULL: mean) */
    double cone;              /* --exclude-specular DEG, in degrees; < 0:
                                 the data's default (CURET: its 7) */
    const char *samples;      /* NULL: 'paper' on CURET, else 'all' */
    const char *models;       /* --models list or 'all'; NULL when not
                                 given (defaults->models) */
    const char *n_file;
    const char *on_file;
    const char *exclude;
    const char *out_dir;
    double n;
    int n_given;
    double max_theta; /* degrees */
    int quiet;
    /* beyond the paper (doc/methods.md) */
    int exact;                /* --fit exact */
    bf_objective objective;   /* --objective */
    bf_fresnel_kind fresnel;  /* --fresnel (0: each model's own) */
    bf_smith_kind smith;      /* --smith (0: each model's own) */
    bf_noise noise;           /* --noise (BF_NOISE_AUTO) */
    const char *range[BF_CLI_MAX_RANGES]; /* --range NAME=LO:HI */
    size_t n_range;
    size_t n_boot;            /* --bootstrap N */
    size_t n_neyman;          /* --neyman auto|off|N: its simulations */
    int neyman_every;         /*   1 with N: every parameter's */
    int no_intervals;         /* --intervals none */
    size_t folds;             /* --folds K (0: no cross-validation) */
    unsigned long seed;       /* --seed S */
    int samples_given;        /* --samples was on the command line */
    int fit_given;            /* --fit was on the command line */
    int stats;                /* --stats: the analysis with --fit paper */
    int threads;      /* --threads: 0 (the default) = one per core */
    const struct bf_cli_defaults *defaults; /* the command's (never NULL
                                               after parsing) */
} bf_cli_opts;

/* What a command assumes when an option is not given. */
typedef struct bf_cli_defaults {
    const char *samples;  /* NULL: 'paper' on CURET, 'all' otherwise */
    bf_model_set models;  /* the --models list (bf_model_set_names) */
    int exact;            /* 1: --fit exact */
    int stats;            /* 1: the analysis always runs */
} bf_cli_defaults;

/* compare's (and report's) defaults: the paper's samples and six models,
 * --fit paper. */
extern const bf_cli_defaults bf_cli_compare_defaults;

/* A command's own options: getopt_long entries (val >= 512) and a handler
 * called with the entry's val and optarg; it returns 0, or an exit status
 * after printing a usage error. */
typedef struct {
    const struct option *longopts; /* NULL-terminated, may be NULL */
    int (*handle)(int val, const char *arg, void *ctx);
    void *ctx;
} bf_cli_extra;

/* Parses argv of command cmd ("compare") into o, starting from defaults
 * d. usage prints the command's help. Returns 0 to go on, -1 after --help
 * (exit 0), or an exit status after a usage error. */
int bf_cli_opts_parse_defaults(const char *cmd, int argc, char **argv,
                               void (*usage)(FILE *fp),
                               const bf_cli_extra *extra,
                               const bf_cli_defaults *d, bf_cli_opts *o);

/* bf_cli_opts_parse_defaults with bf_cli_compare_defaults. */
int bf_cli_opts_parse(const char *cmd, int argc, char **argv,
                      void (*usage)(FILE *fp), const bf_cli_extra *extra,
                      bf_cli_opts *o);

/* Prints the help lines of the common options with the defaults d. */
void bf_cli_opts_usage_defaults(FILE *fp, const bf_cli_defaults *d);

/* bf_cli_opts_usage_defaults with bf_cli_compare_defaults. */
void bf_cli_opts_usage(FILE *fp);

/* Parses the value of --fresnel (schlick, dielectric, none) or --smith
 * (height, separable), SPEC §9.2, into *f or *s. Returns BF_EXIT_OK, or
 * BF_EXIT_BADVALUE after a usage message naming cmd (e.g. "models "). */
int bf_cli_parse_fresnel(const char *cmd, const char *arg,
                         bf_fresnel_kind *f);
int bf_cli_parse_smith(const char *cmd, const char *arg, bf_smith_kind *s);

#endif
