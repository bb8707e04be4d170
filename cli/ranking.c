/* ranking.c: model selection per sample (doc/methods.md §4-5) -- the
 * criterion values, ranks and best models of a study run with its analysis,
 * the per-sample table and the summary over samples. Shared by `brdffit
 * rank` (ranking.csv, ranking.md) and `brdffit report --stats`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "texttable.h"

const char *const bf_cli_crit_names[BF_CLI_NCRIT] = {"AIC", "BIC", "CV"};

double bf_cli_rank_value(const bf_cli_study *st, size_t i, int c)
{
    const bf_fit_stats *s = &st->stats[i];
    if (st->rows[i].status != BF_OK || !s->done) {
        return NAN;
    }
    return c == BF_CLI_AIC ? s->aic : (c == BF_CLI_BIC ? s->bic : s->cv);
}

/* Rank (1 = best) of model m of sample s by criterion c; 0 when it has no
 * value. Ties share the better rank. */
size_t bf_cli_rank_of(const bf_cli_study *st, size_t s, size_t m, int c)
{
    size_t base = s * st->n_models;
    double v = bf_cli_rank_value(st, base + m, c);
    size_t rank = 1;
    size_t q;
    if (!isfinite(v)) {
        return 0;
    }
    for (q = 0; q < st->n_models; q++) {
        double w = bf_cli_rank_value(st, base + q, c);
        rank += isfinite(w) && w < v;
    }
    return rank;
}

/* Index of the best model of sample s by c, or SIZE_MAX. Among models
 * tied for rank 1 (ON at sigma = 0 is LAMBERT exactly) the one with fewer
 * parameters wins, then the first listed. */
size_t bf_cli_rank_best(const bf_cli_study *st, size_t s, int c)
{
    size_t best = (size_t)-1;
    size_t m;
    for (m = 0; m < st->n_models; m++) {
        if (bf_cli_rank_of(st, s, m, c) == 1 &&
            (best == (size_t)-1 ||
             st->stats[s * st->n_models + m].k <
                 st->stats[s * st->n_models + best].k)) {
            best = m;
        }
    }
    return best;
}

/* The per-sample table: criterion values of every model, * on the best,
 * and the best model by each criterion. */
bf_tt *bf_cli_rank_table(const bf_cli_study *st, int crit)
{
    bf_tt *t = bf_tt_alloc(2 + st->n_models + BF_CLI_NCRIT);
    size_t s;
    size_t m;
    int c;
    if (t == NULL) {
        return NULL;
    }
    bf_tt_header(t, 0, "No.");
    bf_tt_header(t, 1, "Sample");
    bf_tt_right(t, 0);
    for (m = 0; m < st->n_models; m++) {
        bf_tt_header(t, 2 + m, st->models[m]->name);
        bf_tt_right(t, 2 + m);
    }
    for (c = 0; c < BF_CLI_NCRIT; c++) {
        char head[32];
        snprintf(head, sizeof head, "best %s", bf_cli_crit_names[c]);
        bf_tt_header(t, 2 + st->n_models + (size_t)c, head);
    }
    for (s = 0; s < st->n_samples; s++) {
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            return NULL;
        }
        bf_tt_set(t, 0, "%d", st->samples[s]);
        bf_tt_set(t, 1, "%s", bf_cli_sample_name(st, s));
        for (m = 0; m < st->n_models; m++) {
            double v = bf_cli_rank_value(st, s * st->n_models + m, crit);
            if (isfinite(v)) {
                bf_tt_set(t, 2 + m, "%.1f%s", v,
                          bf_cli_rank_of(st, s, m, crit) == 1 ? "*" : "");
            } else {
                bf_tt_set(t, 2 + m, "-");
            }
        }
        for (c = 0; c < BF_CLI_NCRIT; c++) {
            size_t b = bf_cli_rank_best(st, s, c);
            bf_tt_set(t, 2 + st->n_models + (size_t)c, "%s",
                      b == (size_t)-1 ? "-" : st->models[b]->name);
        }
    }
    return t;
}

/* "BIC: FC-E best for 34 of 61 samples, VH-E 12, ..." (most wins first). */
void bf_cli_rank_summary(const bf_cli_study *st, int c, FILE *fp)
{
    size_t *wins = calloc(st->n_models + 1, sizeof *wins);
    size_t s;
    size_t m;
    size_t printed = 0;
    if (wins == NULL) {
        return;
    }
    for (s = 0; s < st->n_samples; s++) {
        size_t b = bf_cli_rank_best(st, s, c);
        if (b != (size_t)-1) {
            wins[b]++;
        }
    }
    fprintf(fp, "%s:", bf_cli_crit_names[c]);
    while (printed < st->n_models) {
        size_t best = 0;
        for (m = 1; m < st->n_models; m++) {
            if (wins[m] > wins[best]) {
                best = m;
            }
        }
        if (wins[best] == 0) {
            break;
        }
        if (printed == 0) {
            fprintf(fp, " %s best for %zu of %zu samples", st->models[best]->name,
                    wins[best], st->n_samples);
        } else {
            fprintf(fp, ", %s %zu", st->models[best]->name, wins[best]);
        }
        wins[best] = 0;
        printed++;
    }
    fputs(printed == 0 ? " no model could be ranked\n" : "\n", fp);
    free(wins);
}

