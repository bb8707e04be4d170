/* ranking_csv.c: ranking.csv -- every analysed (target, model) of a study
 * with its criteria, ranks, best models after the tie-break and fitted
 * parameters with their intervals (doc/methods.md §3-5). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "output/output.h"

static const char *const slot_cols[] = {"", "_value", "_ci_low", "_ci_high",
                                        "_boot_low", "_boot_high"};

/* The most fitted parameters of any model of spec. */
static size_t n_slots(const bf_study_spec *spec, const bf_study_row *rows)
{
    size_t most = 0;
    size_t i;
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

/* The parameter slots of row r: its fitted parameters in order, then
 * empty slots up to n. */
static void slots(FILE *fp, const bf_study_row *r, const bf_fit_stats *f,
                  size_t n)
{
    size_t used = 0;
    size_t j;
    for (j = 0; j < r->type->p; j++) {
        if (!r->type->param[j].fitted) {
            continue;
        }
        fputc(',', fp);
        bf__csv_field(fp, r->type->param[j].name);
        bf__csv_num(fp, r->fit.param[j]);
        bf__csv_num(fp, f->ci_low[j]);
        bf__csv_num(fp, f->ci_high[j]);
        bf__csv_num(fp, f->boot_low[j]);
        bf__csv_num(fp, f->boot_high[j]);
        used++;
    }
    for (; used < n; used++) {
        fputs(",,,,,,", fp);
    }
}

int bf_ranking_csv_write(FILE *fp, const bf_study_spec *spec,
                         const bf_study_row *rows, const bf_fit_stats *stats,
                         const bf_analysis_opts *opts)
{
    size_t nu;
    size_t *rank = NULL;
    size_t *best = NULL;
    size_t n_par;
    size_t c;
    size_t i;
    size_t q;
    int rc = bf__csv_check(fp, spec, rows, stats, 1);
    if (rc != BF_OK) {
        return rc;
    }
    nu = spec->n_targets * spec->n_models;
    rank = malloc((BF_NCRIT * nu + 1) * sizeof *rank);
    best = malloc((BF_NCRIT * spec->n_targets + 1) * sizeof *best);
    for (c = 0; rc == BF_OK && c < BF_NCRIT; c++) {
        rc = rank == NULL || best == NULL
                 ? BF_ENOMEM
                 : bf_study_rank(spec, stats, (bf_criterion)c, rank + c * nu,
                                 best + c * spec->n_targets);
    }
    if (rc != BF_OK) {
        goto done;
    }
    n_par = n_slots(spec, rows);
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
    for (i = 0; i < nu; i++) {
        const bf_study_row *r = &rows[i];
        const bf_fit_stats *f = &stats[i];
        size_t t = i / spec->n_models;
        size_t m = i % spec->n_models;
        char flags[512];
        const char *counts;
        if (r->status != BF_OK || !f->done) {
            continue;
        }
        bf__csv_target(fp, spec, t);
        fputc(',', fp);
        bf__csv_field(fp, r->type->name);
        fprintf(fp, ",%s,%s,%zu,%zu", bf_objective_name(f->objective),
                opts != NULL && opts->exact ? "exact" : "paper", f->k, f->n);
        bf__csv_num(fp, r->fit.lse);
        bf__csv_num(fp, f->aic);
        bf__csv_num(fp, f->bic);
        bf__csv_num(fp, f->cv);
        for (c = 0; c < BF_NCRIT; c++) {
            fprintf(fp, ",%zu", rank[c * nu + i]);
        }
        for (c = 0; c < BF_NCRIT; c++) {
            fprintf(fp, ",%d", best[c * spec->n_targets + t] == m);
        }
        counts = bf_rank_winner(spec->models, stats + t * spec->n_models, m);
        fputc(',', fp);
        bf__csv_field(fp, counts != NULL ? counts : "");
        bf_fit_flags_format(r->type, f, flags, sizeof flags);
        fputc(',', fp);
        bf__csv_field(fp, flags);
        slots(fp, r, f, n_par);
        fputc('\n', fp);
    }
    rc = bf__csv_status(fp);
done:
    free(rank);
    free(best);
    return rc;
}
