/* ranking.c: model selection per sample as the CLI prints it
 * (doc/methods.md §4-5) -- criterion values, ranks and best models from
 * the library (bf_criterion_rank, bf_study_wins), the per-sample tables
 * (criteria, fitted parameters with their intervals) and the summary over
 * samples. Shared by `brdffit rank` (ranking.md, standard output) and `brdffit
 * report --stats`. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ranking.h"
#include "texttable.h"

const char *const bf_rep_crit_names[BF_REP_NCRIT] = {"AIC", "BIC", "CV"};

double bf_rep_rank_value(const bf_rep_study *st, size_t i, int c)
{
    if (st->rows[i].status != BF_OK) {
        return NAN;
    }
    return bf_criterion_value(&st->stats[i], (bf_criterion)c);
}

/* bf_criterion_rank of sample s into rank (n_models entries; NULL: not wanted);
 * returns the best model or SIZE_MAX. */
static size_t rank_sample(const bf_rep_study *st, size_t s, int c,
                          size_t *rank)
{
    size_t best = SIZE_MAX;
    bf_criterion_rank(&st->stats[s * st->n_models], st->n_models,
                      (bf_criterion)c, rank, &best);
    return best;
}

size_t bf_rep_rank_of(const bf_rep_study *st, size_t s, size_t m, int c)
{
    size_t *rank = malloc((st->n_models + 1) * sizeof *rank);
    size_t r = 0;
    if (rank != NULL && isfinite(bf_rep_rank_value(st, s * st->n_models + m,
                                                   c))) {
        rank_sample(st, s, c, rank);
        r = rank[m];
    }
    free(rank);
    return r;
}

size_t bf_rep_rank_best(const bf_rep_study *st, size_t s, int c)
{
    return rank_sample(st, s, c, NULL);
}

/* "No." and "Sample" columns, right-aligned number. */
static void sample_headers(bf_tt *t)
{
    bf_tt_header(t, 0, "No.");
    bf_tt_header(t, 1, "Sample");
    bf_tt_right(t, 0);
}

static void sample_cells(bf_tt *t, const bf_rep_study *st, size_t s)
{
    char title[512];
    bf_rep_sample_title(st, s, title, sizeof title);
    bf_tt_set(t, 0, "%d", st->samples[s]);
    bf_tt_set(t, 1, "%s", title);
}

/* The best model b of sample s as the tables name it: "FC-E", or
 * "ON = LAMBERT" for a fit that reduces to another model (its win counts
 * for that one, bf_criterion_winner). */
static const char *best_name(const bf_rep_study *st, size_t s, size_t b,
                             char *buf, size_t len)
{
    const char *w;
    if (b == SIZE_MAX) {
        return "-";
    }
    w = bf_criterion_winner(st->models, &st->stats[s * st->n_models], b);
    if (strcmp(w, st->models[b]->name) == 0) {
        return w;
    }
    snprintf(buf, len, "%s = %s", st->models[b]->name, w);
    return buf;
}

/* t, or NULL (t freed) when a cell could not be stored. */
static bf_tt *complete(bf_tt *t)
{
    if (bf_tt_failed(t)) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}

bf_tt *bf_rep_rank_table(const bf_rep_study *st, int crit)
{
    bf_tt *t = bf_tt_alloc(2 + st->n_models + BF_REP_NCRIT);
    size_t *rank = malloc((st->n_models + 1) * sizeof *rank);
    size_t s;
    size_t m;
    int c;
    if (t == NULL || rank == NULL) {
        bf_tt_free(t);
        free(rank);
        return NULL;
    }
    sample_headers(t);
    for (m = 0; m < st->n_models; m++) {
        bf_tt_header(t, 2 + m, st->models[m]->name);
        bf_tt_right(t, 2 + m);
    }
    for (c = 0; c < BF_REP_NCRIT; c++) {
        char head[32];
        snprintf(head, sizeof head, "best %s", bf_rep_crit_names[c]);
        bf_tt_header(t, 2 + st->n_models + (size_t)c, head);
    }
    for (s = 0; s < st->n_samples; s++) {
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            free(rank);
            return NULL;
        }
        sample_cells(t, st, s);
        rank_sample(st, s, crit, rank);
        for (m = 0; m < st->n_models; m++) {
            double v = bf_rep_rank_value(st, s * st->n_models + m, crit);
            if (isfinite(v)) {
                bf_tt_set(t, 2 + m, "%.1f%s", v, rank[m] == 1 ? "*" : "");
            } else {
                bf_tt_set(t, 2 + m, "-");
            }
        }
        for (c = 0; c < BF_REP_NCRIT; c++) {
            char name[128];
            bf_tt_set(t, 2 + st->n_models + (size_t)c, "%s",
                      best_name(st, s, rank_sample(st, s, c, NULL), name,
                                sizeof name));
        }
    }
    free(rank);
    return complete(t);
}

int bf_rep_interval_format(char *buf, size_t n, double lo, double hi,
                           double gap_low, double gap_high, unsigned open)
{
    const char *b0 = (open & 1u) ? " (bound)" : "";
    const char *b1 = (open & 2u) ? " (bound)" : "";
    if (isfinite(gap_low) && isfinite(gap_high)) {
        return snprintf(buf, n, "[%.4g%s, %.4g] \xe2\x88\xaa [%.4g, %.4g%s]",
                        lo, b0, gap_low, gap_high, hi,
                        b1); /* U+222A, the union */
    }
    return snprintf(buf, n, "[%.4g%s, %.4g%s]", lo, b0, hi, b1);
}

int bf_rep_interval_text(char *buf, size_t n, const bf_fit_stats *f,
                         size_t j)
{
    return bf_rep_interval_format(buf, n, f->ci_low[j], f->ci_high[j],
                                  f->ci_gap_low[j], f->ci_gap_high[j], 0);
}

int bf_rep_estimate_text(char *buf, size_t n, double value,
                         const bf_fit_stats *f, size_t j)
{
    char v[32];
    char m[40] = "";
    char iv[96];
    snprintf(v, sizeof v, "%.4g", value);
    snprintf(m, sizeof m, "%.4g", f->ml_param[j]);
    bf_rep_interval_text(iv, sizeof iv, f, j);
    if (!isfinite(f->ml_param[j]) || strcmp(v, m) == 0) {
        return snprintf(buf, n, "%s %s", v, iv);
    }
    return snprintf(buf, n, "%s (ML %s) %s", v, m, iv);
}

/* bf_rep_estimate_text's cell, with " {1.21, 1.29}" for the bootstrap
 * interval when there is one; "-" without a value. */
static void param_cell(bf_tt *t, size_t col, const bf_fit_stats *f,
                       const bf_study_row *r, size_t j)
{
    char est[128];
    char boot[96] = "";
    if (r->status != BF_OK || !f->done) {
        bf_tt_set(t, col, "-");
        return;
    }
    if (isfinite(f->boot_low[j]) && isfinite(f->boot_high[j])) {
        snprintf(boot, sizeof boot, " {%.4g, %.4g}", f->boot_low[j],
                 f->boot_high[j]);
    }
    bf_rep_estimate_text(est, sizeof est, r->fit.param[j], f, j);
    bf_tt_set(t, col, "%s%s", est, boot);
}

/* Fitted parameters of model type, in order, into idx; returns count. */
static size_t fitted_params(const bf_model_type *type, size_t *idx)
{
    size_t n = 0;
    size_t j;
    for (j = 0; j < type->p; j++) {
        if (type->param[j].fitted) {
            idx[n++] = j;
        }
    }
    return n;
}

int bf_rep_params_table(const bf_rep_study *st, size_t m, bf_tt **out)
{
    const bf_model_type *type = st->models[m];
    size_t idx[BF_MAX_PARAMS];
    size_t np = fitted_params(type, idx);
    bf_tt *t;
    size_t s;
    size_t q;
    *out = NULL;
    if (np == 0) {
        return BF_REPORT_OK;
    }
    if ((t = bf_tt_alloc(3 + np)) == NULL) {
        return BF_REPORT_SOFTWARE;
    }
    sample_headers(t);
    for (q = 0; q < np; q++) {
        bf_tt_header(t, 2 + q, type->param[idx[q]].label);
    }
    bf_tt_header(t, 2 + np, "flags");
    for (s = 0; s < st->n_samples; s++) {
        size_t i = s * st->n_models + m;
        char flags[512];
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            return BF_REPORT_SOFTWARE;
        }
        sample_cells(t, st, s);
        for (q = 0; q < np; q++) {
            param_cell(t, 2 + q, &st->stats[i], &st->rows[i], idx[q]);
        }
        bf_fit_flags_format(type, &st->stats[i], flags, sizeof flags);
        bf_tt_set(t, 2 + np, "%s", flags);
    }
    *out = complete(t);
    return *out != NULL ? BF_REPORT_OK : BF_REPORT_SOFTWARE;
}

bf_tt *bf_rep_best_table(const bf_rep_study *st, int crit)
{
    bf_tt *t = bf_tt_alloc(4);
    size_t s;
    size_t q;
    if (t == NULL) {
        return NULL;
    }
    sample_headers(t);
    bf_tt_header(t, 2, "best");
    bf_tt_header(t, 3, "fitted parameters (ML estimate) [95% interval]");
    for (s = 0; s < st->n_samples; s++) {
        size_t b = rank_sample(st, s, crit, NULL);
        size_t idx[BF_MAX_PARAMS];
        char cell[512] = "";
        char name[128];
        size_t at = 0;
        size_t np;
        size_t i;
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            return NULL;
        }
        sample_cells(t, st, s);
        if (b == SIZE_MAX) {
            bf_tt_set(t, 2, "-");
            continue;
        }
        i = s * st->n_models + b;
        bf_tt_set(t, 2, "%s", best_name(st, s, b, name, sizeof name));
        np = fitted_params(st->models[b], idx);
        for (q = 0; q < np && at < sizeof cell; q++) {
            const bf_fit_stats *f = &st->stats[i];
            size_t j = idx[q];
            char est[128];
            bf_rep_estimate_text(est, sizeof est, st->rows[i].fit.param[j],
                                 f, j);
            at += (size_t)snprintf(cell + at, sizeof cell - at, "%s%s %s",
                                   q > 0 ? "; " : "",
                                   st->models[b]->param[j].name, est);
        }
        bf_tt_set(t, 3, "%s", np == 0 ? "(none)" : cell);
    }
    return complete(t);
}

/* "BIC: FC-E best for 34 of 61 samples, VH-E 12, ..." (most wins first;
 * bf_study_wins: a fit that reduces to another model counts for that
 * model, never for the larger one). */
int bf_rep_rank_summary(const bf_rep_study *st, int c, FILE *fp)
{
    const char **names = calloc(2 * st->n_models + 1, sizeof *names);
    size_t *wins = calloc(2 * st->n_models + 1, sizeof *wins);
    size_t n = 0;
    size_t i;
    int e = names == NULL || wins == NULL
                ? BF_ENOMEM
                : bf_study_wins(&st->spec, st->stats, (bf_criterion)c, names,
                                wins, &n);
    if (e == BF_ENOMEM) {
        free(wins);
        free(names);
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    if (e != BF_OK) {
        n = 0;
    }
    fprintf(fp, "%s:", bf_rep_crit_names[c]);
    for (i = 0; i < n; i++) {
        if (i == 0) {
            fprintf(fp, " %s best for %zu of %zu sample%s", names[i],
                    wins[i], st->n_samples, st->n_samples == 1 ? "" : "s");
        } else {
            fprintf(fp, ", %s %zu", names[i], wins[i]);
        }
    }
    fputs(n == 0 ? " no model could be ranked\n" : "\n", fp);
    free(wins);
    free(names);
    return BF_REPORT_OK;
}
