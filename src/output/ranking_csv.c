/* ranking_csv.c: ranking.csv -- every analysed (target, model) of a study
 * with its criteria, ranks, best models after the tie-break and fitted
 * parameters with their intervals (doc/methods.md §3-5): its lines as
 * structs (bf_ranking_lines) and the file printed from them. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "output/output.h"

static const char *const slot_cols[] = {
    "", "_value", "_ci_low", "_ci_high", "_ci_gap_low", "_ci_gap_high",
    "_boot_low", "_boot_high", "_ml"};

size_t bf_ranking_slots(const bf_study_spec *spec, const bf_study_row *rows)
{
    size_t most = 0;
    size_t i;
    if (spec == NULL || rows == NULL) {
        return 0;
    }
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
        size_t n = 0;
        size_t j;
        if (rows[i].type == NULL) {
            continue;
        }
        for (j = 0; j < rows[i].type->p; j++) {
            n += (size_t)(rows[i].type->param[j].fitted != 0);
        }
        most = n > most ? n : most;
    }
    return most;
}

/* The line of row i (target t, model m) with the ranks and best models of
 * every criterion (rank: BF_NCRIT x nu, best: BF_NCRIT x n_targets). */
static void fill_line(bf_ranking_line *l, const bf_study_spec *spec,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      const bf_analysis_opts *opts, size_t i,
                      const size_t *rank, const size_t *best)
{
    const bf_study_row *r = &rows[i];
    const bf_fit_stats *f = &stats[i];
    size_t nu = spec->n_targets * spec->n_models;
    size_t t = i / spec->n_models;
    size_t m = i % spec->n_models;
    size_t c;
    size_t j;
    memset(l, 0, sizeof *l);
    l->row = i;
    l->model = r->type->name;
    l->objective = bf_objective_name(f->objective);
    l->fit = opts != NULL && opts->exact ? "exact" : "paper";
    l->k = f->k;
    l->n = f->n;
    l->objective_value = r->fit.lse;
    l->aic = f->aic;
    l->bic = f->bic;
    l->cv = f->cv;
    for (c = 0; c < BF_NCRIT; c++) {
        l->rank[c] = rank[c * nu + i];
        l->best[c] = best[c * spec->n_targets + t] == m;
    }
    l->counts_as =
        bf_criterion_winner(spec->models, stats + t * spec->n_models, m);
    bf_fit_flags_format(r->type, f, l->flags, sizeof l->flags);
    for (j = 0; j < r->type->p; j++) {
        size_t q = l->n_params;
        if (!r->type->param[j].fitted) {
            continue;
        }
        l->param[q] = r->type->param[j].name;
        l->value[q] = r->fit.param[j];
        l->ci_low[q] = f->ci_low[j];
        l->ci_high[q] = f->ci_high[j];
        l->ci_gap_low[q] = f->ci_gap_low[j];
        l->ci_gap_high[q] = f->ci_gap_high[j];
        l->boot_low[q] = f->boot_low[j];
        l->boot_high[q] = f->boot_high[j];
        l->ml[q] = f->ml_param[j];
        l->n_params++;
    }
}

int bf_ranking_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_ranking_line *out, size_t *n)
{
    size_t nu;
    size_t *rank = NULL;
    size_t *best = NULL;
    size_t c;
    size_t i;
    int rc = BF_OK;
    if (spec == NULL || rows == NULL || stats == NULL || n == NULL) {
        return BF_EINVAL;
    }
    *n = 0;
    nu = spec->n_targets * spec->n_models;
    if (out != NULL) {
        rank = malloc((BF_NCRIT * nu + 1) * sizeof *rank);
        best = malloc((BF_NCRIT * spec->n_targets + 1) * sizeof *best);
        for (c = 0; rc == BF_OK && c < BF_NCRIT; c++) {
            rc = rank == NULL || best == NULL
                     ? BF_ENOMEM
                     : bf_study_rank(spec, stats, (bf_criterion)c,
                                     rank + c * nu,
                                     best + c * spec->n_targets);
        }
    }
    for (i = 0; rc == BF_OK && i < nu; i++) {
        if (rows[i].status != BF_OK || !stats[i].done) {
            continue;
        }
        if (out != NULL) {
            fill_line(&out[*n], spec, rows, stats, opts, i, rank, best);
        }
        (*n)++;
    }
    free(rank);
    free(best);
    return rc;
}

/* The parameter slots of line l, then empty slots up to n_par. */
static void slots(FILE *fp, const bf_ranking_line *l, size_t n_par)
{
    size_t q;
    for (q = 0; q < l->n_params; q++) {
        fputc(',', fp);
        bf__csv_field(fp, l->param[q]);
        bf__csv_num(fp, l->value[q]);
        bf__csv_num(fp, l->ci_low[q]);
        bf__csv_num(fp, l->ci_high[q]);
        bf__csv_num(fp, l->ci_gap_low[q]);
        bf__csv_num(fp, l->ci_gap_high[q]);
        bf__csv_num(fp, l->boot_low[q]);
        bf__csv_num(fp, l->boot_high[q]);
        bf__csv_num(fp, l->ml[q]);
    }
    for (; q < n_par; q++) {
        fputs(",,,,,,,,,", fp);
    }
}

int bf_ranking_csv_write(FILE *fp, const bf_study_spec *spec,
                         const bf_study_row *rows, const bf_fit_stats *stats,
                         const bf_analysis_opts *opts)
{
    bf_ranking_line *lines = NULL;
    size_t n = 0;
    size_t n_par;
    size_t c;
    size_t i;
    size_t q;
    int rc = bf__csv_check(fp, spec, rows, stats, 1);
    if (rc == BF_OK) {
        rc = bf_ranking_lines(spec, rows, stats, opts, NULL, &n);
    }
    if (rc == BF_OK) {
        lines = malloc((n + 1) * sizeof *lines);
        rc = lines == NULL ? BF_ENOMEM
                           : bf_ranking_lines(spec, rows, stats, opts, lines,
                                              &n);
    }
    if (rc != BF_OK) {
        free(lines);
        return rc;
    }
    n_par = bf_ranking_slots(spec, rows);
    fputs("sample,name,channel,model,objective,fit,k,n,objective_value,aic,"
          "bic,cv,rank_aic,rank_bic,rank_cv,best_aic,best_bic,best_cv,"
          "counts_as,flags",
          fp);
    for (q = 0; q < n_par; q++) {
        for (c = 0; c < sizeof slot_cols / sizeof *slot_cols; c++) {
            fprintf(fp, ",p%zu%s", q + 1, slot_cols[c]);
        }
    }
    fputc('\n', fp);
    for (i = 0; i < n; i++) {
        const bf_ranking_line *l = &lines[i];
        bf__csv_target(fp, spec, l->row / spec->n_models);
        fputc(',', fp);
        bf__csv_field(fp, l->model);
        fprintf(fp, ",%s,%s,%zu,%zu", l->objective, l->fit, l->k, l->n);
        bf__csv_num(fp, l->objective_value);
        bf__csv_num(fp, l->aic);
        bf__csv_num(fp, l->bic);
        bf__csv_num(fp, l->cv);
        for (c = 0; c < BF_NCRIT; c++) {
            fprintf(fp, ",%zu", l->rank[c]);
        }
        for (c = 0; c < BF_NCRIT; c++) {
            fprintf(fp, ",%d", l->best[c]);
        }
        fputc(',', fp);
        bf__csv_field(fp, l->counts_as != NULL ? l->counts_as : "");
        fputc(',', fp);
        bf__csv_field(fp, l->flags);
        slots(fp, l, n_par);
        fputc('\n', fp);
    }
    free(lines);
    return bf__csv_status(fp);
}
