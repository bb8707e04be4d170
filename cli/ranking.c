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
    if (st->rows[i].status != BF_OK) {
        return NAN;
    }
    return bf_criterion_value(&st->stats[i], (bf_criterion)c);
}

/* Rank (1 = best) of model m of sample s by criterion c; 0 when it has no
 * value. Ties (BF_TIE_REL) share the better rank (bf_rank). */
size_t bf_cli_rank_of(const bf_cli_study *st, size_t s, size_t m, int c)
{
    size_t rank[64];
    size_t best;
    if (st->n_models > 64 || !isfinite(bf_cli_rank_value(st, s * st->n_models + m, c))) {
        return 0;
    }
    bf_rank(&st->stats[s * st->n_models], st->n_models, (bf_criterion)c, rank,
            &best);
    return rank[m];
}

/* Index of the best model of sample s by c, or SIZE_MAX (bf_rank: fewer
 * parameters among ties, then the first listed). */
size_t bf_cli_rank_best(const bf_cli_study *st, size_t s, int c)
{
    size_t rank[64];
    size_t best = (size_t)-1;
    if (st->n_models <= 64) {
        bf_rank(&st->stats[s * st->n_models], st->n_models, (bf_criterion)c,
                rank, &best);
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

/* "BIC: FC-E best for 34 of 61 samples, VH-E 12, ..." (most wins first).
 * A best fit that reduces to another model (ON at sigma = 0) counts for
 * that model (bf_rank_winner), never for the larger one. */
void bf_cli_rank_summary(const bf_cli_study *st, int c, FILE *fp)
{
    const char **names = calloc(st->n_samples + 1, sizeof *names);
    size_t *wins = calloc(st->n_samples + 1, sizeof *wins);
    size_t n_names = 0;
    size_t s;
    size_t i;
    size_t printed = 0;
    if (wins == NULL || names == NULL) {
        free(wins);
        free(names);
        return;
    }
    for (s = 0; s < st->n_samples; s++) {
        size_t b = bf_cli_rank_best(st, s, c);
        const char *w = b == (size_t)-1
                            ? NULL
                            : bf_rank_winner(st->models,
                                             &st->stats[s * st->n_models], b);
        if (w == NULL) {
            continue;
        }
        for (i = 0; i < n_names && strcmp(names[i], w) != 0; i++) {
        }
        if (i == n_names) {
            names[n_names++] = w;
        }
        wins[i]++;
    }
    fprintf(fp, "%s:", bf_cli_crit_names[c]);
    while (printed < n_names) {
        size_t best = 0;
        for (i = 1; i < n_names; i++) {
            if (wins[i] > wins[best]) {
                best = i;
            }
        }
        if (wins[best] == 0) {
            break;
        }
        if (printed == 0) {
            fprintf(fp, " %s best for %zu of %zu samples", names[best],
                    wins[best], st->n_samples);
        } else {
            fprintf(fp, ", %s %zu", names[best], wins[best]);
        }
        wins[best] = 0;
        printed++;
    }
    fputs(printed == 0 ? " no model could be ranked\n" : "\n", fp);
    free(wins);
    free(names);
}
