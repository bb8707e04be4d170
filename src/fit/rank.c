/* rank.c: model selection per target -- the criteria, ties, ranks and the
 * best model (doc/methods.md §4-5), and the count of wins over targets.
 *
 * [1] doc/methods.md §5: models ranked by AIC, BIC or CV (1 = lowest,
 *     ties share the rank); among the models tied for the best the one
 *     with fewer parameters wins, then the first listed; a fit that reduces
 *     to another model (ON at sigma = 0 is LAMBERT) wins for that model.
 *
 * Ties: two values are tied when they differ by at most BF_TIE_REL of
 * their scale: for CV the larger magnitude; for AIC and BIC, which are
 * n ln(RSS/n) + const, the number of configurations n (a relative change
 * e of RSS moves them by n e), so the tie means the same relative
 * difference of the residual sums for every criterion.
 */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

static const char *const crit_names[BF_NCRIT] = {"AIC", "BIC", "CV"};

const char *bf_criterion_name(bf_criterion c)
{
    return (unsigned)c < BF_NCRIT ? crit_names[c] : NULL;
}

int bf_criterion_find(const char *name, bf_criterion *c)
{
    size_t i;
    if (name == NULL || c == NULL) {
        return BF_EINVAL;
    }
    for (i = 0; i < BF_NCRIT; i++) {
        const char *a = crit_names[i];
        const char *b = name;
        while (*a != '\0' && *b != '\0' &&
               tolower((unsigned char)*a) == tolower((unsigned char)*b)) {
            a++;
            b++;
        }
        if (*a == '\0' && *b == '\0') {
            *c = (bf_criterion)i;
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}

double bf_criterion_value(const bf_fit_stats *st, bf_criterion c)
{
    if (st == NULL || !st->done) {
        return NAN;
    }
    switch (c) {
    case BF_CRIT_AIC:
        return st->aic;
    case BF_CRIT_BIC:
        return st->bic;
    default:
        return st->cv;
    }
}

int bf_criterion_tied(double a, double b, bf_criterion c, size_t n)
{
    double scale = c == BF_CRIT_CV ? fmax(fabs(a), fabs(b)) : (double)n;
    return fabs(a - b) <= BF_TIE_REL * scale; /* [1]; NaN never ties */
}

void bf_criterion_rank(const bf_fit_stats *stats, size_t n_models,
                       bf_criterion c, size_t *rank, size_t *best)
{
    size_t m;
    size_t q;
    *best = SIZE_MAX;
    for (m = 0; m < n_models; m++) {
        double v = bf_criterion_value(&stats[m], c);
        size_t r = 0;
        if (isfinite(v)) {
            r = 1;
            for (q = 0; q < n_models; q++) {
                double w = bf_criterion_value(&stats[q], c);
                if (isfinite(w) && w < v &&
                    !bf_criterion_tied(v, w, c, stats[m].n)) {
                    r++; /* clearly better than m */
                }
            }
        }
        if (rank != NULL) {
            rank[m] = r;
        }
        /* of rank 1: fewer parameters, then the first */
        if (r == 1 && (*best == SIZE_MAX || stats[m].k < stats[*best].k)) {
            *best = m;
        }
    }
}

const char *bf_criterion_winner(const bf_model_type *const *models,
                                const bf_fit_stats *stats, size_t best)
{
    if (best == SIZE_MAX) {
        return NULL;
    }
    if ((stats[best].flags & BF_STAT_REDUCED) && stats[best].reduces_to) {
        return stats[best].reduces_to; /* [1]: a win of the reduced model */
    }
    return models[best]->name;
}

int bf_study_rank(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, size_t *rank, size_t *best)
{
    size_t nm;
    size_t t;
    size_t *scratch;
    if (spec == NULL || stats == NULL) {
        return BF_EINVAL;
    }
    nm = spec->n_models;
    scratch = malloc((nm + 1) * sizeof *scratch);
    if (scratch == NULL) {
        return BF_ENOMEM;
    }
    for (t = 0; t < spec->n_targets; t++) {
        size_t b;
        bf_criterion_rank(stats + t * nm, nm, c,
                          rank != NULL ? rank + t * nm : scratch, &b);
        if (best != NULL) {
            best[t] = b;
        }
    }
    free(scratch);
    return BF_OK;
}

int bf_study_wins(const bf_study_spec *spec, const bf_fit_stats *stats,
                  bf_criterion c, const char **names, size_t *wins,
                  size_t *n_names)
{
    size_t *best;
    size_t n = 0;
    size_t t;
    size_t i;
    int rc;
    if (spec == NULL || stats == NULL || names == NULL || wins == NULL ||
        n_names == NULL) {
        return BF_EINVAL;
    }
    *n_names = 0;
    best = malloc((spec->n_targets + 1) * sizeof *best);
    if (best == NULL) {
        return BF_ENOMEM;
    }
    rc = bf_study_rank(spec, stats, c, NULL, best);
    for (t = 0; rc == BF_OK && t < spec->n_targets; t++) {
        const char *w = bf_criterion_winner(
            spec->models, stats + t * spec->n_models, best[t]);
        if (w == NULL) {
            continue;
        }
        for (i = 0; i < n && strcmp(names[i], w) != 0; i++) {
        }
        if (i == n) { /* a new name: n <= 2 n_models (models, reductions) */
            names[n] = w;
            wins[n++] = 0;
        }
        wins[i]++;
    }
    free(best);
    /* most wins first; a stable insertion sort keeps first-win order */
    for (i = 1; i < n; i++) {
        const char *nm = names[i];
        size_t w = wins[i];
        size_t q = i;
        for (; q > 0 && wins[q - 1] < w; q--) {
            names[q] = names[q - 1];
            wins[q] = wins[q - 1];
        }
        names[q] = nm;
        wins[q] = w;
    }
    *n_names = n;
    return rc;
}
