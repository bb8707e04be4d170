/* ranking.h: model selection per sample as the CLI prints it (`rank`,
 * `report --stats`): criterion values, ranks and best models from the
 * library (bf_study_rank, bf_study_wins; doc/methods.md §4-5), the
 * per-sample tables and the summary over samples. */
#ifndef BF_REPORT_RANKING_H
#define BF_REPORT_RANKING_H

#include <stdio.h>

#include "study.h"

struct bf_tt;

/* The criteria of the ranking (doc/methods.md §4-5), as bf_criterion. */
enum { BF_REP_AIC = BF_CRIT_AIC, BF_REP_BIC = BF_CRIT_BIC,
       BF_REP_CV = BF_CRIT_CV, BF_REP_NCRIT = BF_NCRIT };
extern const char *const bf_rep_crit_names[BF_REP_NCRIT];

/* Value of criterion c for row i (NaN when not computed); needs st->stats. */
double bf_rep_rank_value(const bf_rep_study *st, size_t i, int c);
/* Rank (1 = best) of model m for sample s by criterion c; 0 without one. */
size_t bf_rep_rank_of(const bf_rep_study *st, size_t s, size_t m, int c);
/* The best model of sample s by criterion c, (size_t)-1 when none. */
size_t bf_rep_rank_best(const bf_rep_study *st, size_t s, int c);
/* The per-sample table of criterion crit (caller frees), NULL on ENOMEM. */
struct bf_tt *bf_rep_rank_table(const bf_rep_study *st, int crit);
/* "2.345 [1.78, 2.084]": a fitted value and parameter j's interval of f,
 * or "2.345 (ML 1.923) [1.78, 2.084]" where the estimate the interval is
 * about (the noise model's maximum-likelihood one, bf_fit_stats.ml_param)
 * differs from it in the 4 digits shown -- the paper protocol's estimate
 * need not lie inside the likelihood's interval; a split interval as
 * "[1.2, 1.311] \u222a [2.351, 2.5]" (bf_fit_stats.ci_gap_low). Into buf
 * (n bytes); returns what snprintf does. */
int bf_rep_estimate_text(char *buf, size_t n, double value,
                         const bf_fit_stats *f, size_t j);
/* An interval as text into buf (n bytes; returns what snprintf does):
 * "[lo, hi]", or a split one, gap (gap_low, gap_high) finite,
 * "[lo, gap_low] \u222a [gap_high, hi]"; " (bound)" after the low end with
 * bit 0 of open, after the high end with bit 1 (an end at the search
 * range's bound). */
int bf_rep_interval_format(char *buf, size_t n, double lo, double hi,
                           double gap_low, double gap_high, unsigned open);
/* Parameter j's interval of f alone: "[1.78, 2.084]", or a split one
 * "[1.2, 1.311] \u222a [2.351, 2.5]". */
int bf_rep_interval_text(char *buf, size_t n, const bf_fit_stats *f,
                         size_t j);
/* The fitted parameters with their 95% profile intervals (and bootstrap
 * intervals when run) of model m for every sample into *out (caller
 * frees; NULL when m fits nothing). Returns BF_REPORT_OK, or
 * BF_REPORT_SOFTWARE (*out NULL) when out of memory. */
int bf_rep_params_table(const bf_rep_study *st, size_t m,
                        struct bf_tt **out);
/* The best model of each sample by crit with its parameters and
 * intervals (caller frees), NULL on ENOMEM. */
struct bf_tt *bf_rep_best_table(const bf_rep_study *st, int crit);
/* Prints "BIC: FC-E best for 32 of 61 samples, ON 13, ..." and a newline.
 * Returns BF_REPORT_OK, or BF_REPORT_SOFTWARE after the message when out of
 * memory (nothing printed). */
int bf_rep_rank_summary(const bf_rep_study *st, int c, FILE *fp);

#endif
