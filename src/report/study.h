/* study.h: the study run behind the report and the CLI's subcommands that
 * fit models to samples (compare, rank, report): the selections of
 * samples, models and configurations (from bf_report_options) that make
 * the library's study specification, the run itself and the accessors the
 * tables and figures use. */
#ifndef BF_REPORT_STUDY_H
#define BF_REPORT_STUDY_H

#include <stdio.h>

#include "rep.h"

/* A study run: its inputs, selections and results. The study's targets
 * (material x channel) are called samples below, as in the paper: target
 * s is material targets[s].material, numbered samples[s]. */
typedef struct {
    const char *cmd;      /* "compare", for messages */
    bf_report_options opts;
    bf_report_inputs in;  /* the data (in.ds) and their files */
    const char *out_dir;  /* the output folder */
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
    bf_model_variant *variants; /* n_models derived types: --fit exact's
                                   freed inputs, --range */
    const bf_model_type **base; /* n_models registry types (the models
                                   before --fit exact and --range) */
    bf_analysis_opts analysis;  /* the analysis run (with stats) */
    bf_fit_stats *stats;  /* analysis of each row, or NULL */
    bf_study_calibration cal; /* opts.calibrate > 0: the calibration of
                                 every analysed pair (calibration.h) */
} bf_rep_study;

/* Loads the inputs and resolves the selections of st->opts. Returns
 * BF_REPORT_OK or a status after the message. */
int bf_rep_study_prepare(bf_rep_study *st);

/* Reports a study error (naming the material's file and line when known)
 * and returns its status. */
int bf_rep_study_error(const bf_error *err);

/* Runs the study (after prepare): the paper's protocol, then the analysis
 * when asked. Returns BF_REPORT_OK or a status. */
int bf_rep_study_run(bf_rep_study *st);

/* The two halves of bf_rep_study_run: the paper's protocol (nothing with
 * --fit exact, where the analysis is the study), then the analysis
 * (--stats, --fit exact, --bootstrap; nothing otherwise). The report
 * draws the paper's figures while the analysis runs. */
int bf_rep_study_run_protocol(bf_rep_study *st);
int bf_rep_study_run_analysis(bf_rep_study *st);

/* Which diffuse intervals the Neyman construction makes in st's analysis:
 * BF_REP_NEYMAN_NONE (no construction: --neyman off, no intervals, or the
 * objective's own noise model), BF_REP_NEYMAN_COMPETING (the default:
 * where a second minimum competes) or BF_REP_NEYMAN_EVERY (--neyman N). */
enum { BF_REP_NEYMAN_NONE, BF_REP_NEYMAN_COMPETING, BF_REP_NEYMAN_EVERY };
int bf_rep_neyman_scope(const bf_rep_study *st);

/* Frees everything st owns. */
void bf_rep_study_free(bf_rep_study *st);

/* Whether Table 2 shows parameter j of type: fitted parameters, and the
 * inputs of a model that fits none (ON's tabulated rho, sigma). */
int bf_rep_shows_param(const bf_model_type *type, size_t j);

/* Name of target s's material (borrowed; "" when it has none). */
const char *bf_rep_sample_name(const bf_rep_study *st, size_t s);

/* Name of target s's channel: "mean", or the channel's name (borrowed). */
const char *bf_rep_channel_name(const bf_rep_study *st, size_t s);

/* "Leather" or, when the study fits single channels, "Leather [R]", into
 * buf (the label of Tables 2 and 3 and of the figures). */
void bf_rep_sample_title(const bf_rep_study *st, size_t s, char *buf,
                         size_t len);

/* The used configurations (sel, capacity bf_dataset_nconf of its
 * material), their number *k and the normalised data of target s, as the
 * study fitted them. Returns BF_OK or a BF_E* code. */
int bf_rep_target_data(const bf_rep_study *st, size_t s, size_t *sel,
                       size_t *k, double *data);

#endif
