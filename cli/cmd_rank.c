/* cmd_rank.c: `brdffit rank` -- model selection per sample: fits every
 * model to every sample (by default all 61 CURET samples, --fit exact),
 * ranks the models of each sample by AIC, BIC and cross-validated error
 * (doc/methods.md §4-5), prints the ranking and a summary over samples and
 * writes ranking.csv and ranking.md atomically into the output folder. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "texttable.h"

/* The models rank compares by default: the paper's six, the Lambert
 * baseline and WNO. */
#define RANK_MODELS "VH-G,VH-E,FC-G,FC-E,ON,LFTG,LAMBERT,WNO"

enum { CRIT_AIC, CRIT_BIC, CRIT_CV, N_CRIT };
static const char *const crit_names[N_CRIT] = {"AIC", "BIC", "CV"};

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit rank [OPTIONS]\n"
"\n"
"Ranks reflectance models per CURET sample by AIC, BIC and K-fold\n"
"cross-validated error (doc/methods.md), after fitting each model (by\n"
"default with --fit exact, on all 61 samples, models\n"
RANK_MODELS ").\n"
"Prints the ranking and a summary over samples ('FC-E best for 32 of 61\n"
"samples, ...') and writes ranking.csv and ranking.md into the output\n"
"folder.\n"
"\n"
"Options:\n"
"  --criterion C     aic, bic (default) or cv: the one the table and the\n"
"                    summary lead with (ranking.csv has all three)\n",
        fp);
    bf_cli_opts_usage(fp);
    fputs(
"\n"
"Exit status: 0 success, 64 usage error, 65 bad input data, 66 input file\n"
"not found, 70 internal error, 73 cannot create output, 74 write error.\n",
        fp);
}

enum { O_CRITERION = 512 };

static int handle(int val, const char *arg, void *ctx)
{
    int *crit = ctx;
    size_t c;
    if (val != O_CRITERION) {
        return BF_EXIT_SOFTWARE;
    }
    for (c = 0; c < N_CRIT; c++) {
        char lower[8];
        size_t i;
        for (i = 0; crit_names[c][i] != '\0'; i++) {
            lower[i] = (char)(crit_names[c][i] - 'A' + 'a');
        }
        lower[i] = '\0';
        if (strcmp(arg, lower) == 0) {
            *crit = (int)c;
            return 0;
        }
    }
    return bf_cli_usage_fail(BF_EXIT_BADVALUE, "rank ", "--criterion: '%s' is not aic, bic "
                              "or cv", arg);
}

/* Criterion c of a row, NaN when the row has no value. */
static double crit_value(const bf_cli_study *st, size_t i, int c)
{
    const bf_fit_stats *s = &st->stats[i];
    if (st->rows[i].status != BF_OK || !s->done) {
        return NAN;
    }
    return c == CRIT_AIC ? s->aic : (c == CRIT_BIC ? s->bic : s->cv);
}

/* Rank (1 = best) of model m of sample s by criterion c; 0 when it has no
 * value. Ties share the better rank. */
static size_t rank_of(const bf_cli_study *st, size_t s, size_t m, int c)
{
    size_t base = s * st->n_models;
    double v = crit_value(st, base + m, c);
    size_t rank = 1;
    size_t q;
    if (!isfinite(v)) {
        return 0;
    }
    for (q = 0; q < st->n_models; q++) {
        double w = crit_value(st, base + q, c);
        rank += isfinite(w) && w < v;
    }
    return rank;
}

/* Index of the best model of sample s by c, or SIZE_MAX. Among models
 * tied for rank 1 (ON at sigma = 0 is LAMBERT exactly) the one with fewer
 * parameters wins, then the first listed. */
static size_t best_of(const bf_cli_study *st, size_t s, int c)
{
    size_t best = (size_t)-1;
    size_t m;
    for (m = 0; m < st->n_models; m++) {
        if (rank_of(st, s, m, c) == 1 &&
            (best == (size_t)-1 ||
             st->stats[s * st->n_models + m].k <
                 st->stats[s * st->n_models + best].k)) {
            best = m;
        }
    }
    return best;
}

static void write_csv(const bf_cli_study *st, FILE *fp)
{
    size_t s;
    size_t m;
    fputs("sample,name,model,objective,fit,k,n,objective_value,aic,bic,cv,"
          "rank_aic,rank_bic,rank_cv\n",
          fp);
    for (s = 0; s < st->n_samples; s++) {
        for (m = 0; m < st->n_models; m++) {
            size_t i = s * st->n_models + m;
            const bf_fit_stats *f = &st->stats[i];
            if (st->rows[i].status != BF_OK || !f->done) {
                continue;
            }
            fprintf(fp, "%d,", st->samples[s]);
            bf_cli_csv_field(fp, bf_cli_sample_name(st, st->samples[s]));
            fprintf(fp, ",%s,%s,%s,%zu,%zu,%.10g,%.10g,%.10g,",
                    st->models[m]->name, bf_objective_name(f->objective),
                    st->opts.exact ? "exact" : "paper", f->k, f->n,
                    st->rows[i].fit.lse, f->aic, f->bic);
            if (isfinite(f->cv)) {
                fprintf(fp, "%.10g", f->cv);
            }
            fprintf(fp, ",%zu,%zu,%zu\n", rank_of(st, s, m, CRIT_AIC),
                    rank_of(st, s, m, CRIT_BIC), rank_of(st, s, m, CRIT_CV));
        }
    }
}

/* The per-sample table: criterion values of every model, * on the best,
 * and the best model by each criterion. */
static bf_tt *build_table(const bf_cli_study *st, int crit)
{
    bf_tt *t = bf_tt_alloc(2 + st->n_models + N_CRIT);
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
    for (c = 0; c < N_CRIT; c++) {
        char head[32];
        snprintf(head, sizeof head, "best %s", crit_names[c]);
        bf_tt_header(t, 2 + st->n_models + (size_t)c, head);
    }
    for (s = 0; s < st->n_samples; s++) {
        if (bf_tt_add_row(t) != 0) {
            bf_tt_free(t);
            return NULL;
        }
        bf_tt_set(t, 0, "%d", st->samples[s]);
        bf_tt_set(t, 1, "%s", bf_cli_sample_name(st, st->samples[s]));
        for (m = 0; m < st->n_models; m++) {
            double v = crit_value(st, s * st->n_models + m, crit);
            if (isfinite(v)) {
                bf_tt_set(t, 2 + m, "%.1f%s", v,
                          rank_of(st, s, m, crit) == 1 ? "*" : "");
            } else {
                bf_tt_set(t, 2 + m, "-");
            }
        }
        for (c = 0; c < N_CRIT; c++) {
            size_t b = best_of(st, s, c);
            bf_tt_set(t, 2 + st->n_models + (size_t)c, "%s",
                      b == (size_t)-1 ? "-" : st->models[b]->name);
        }
    }
    return t;
}

/* "BIC: FC-E best for 34 of 61 samples, VH-E 12, ..." (most wins first). */
static void summary(const bf_cli_study *st, int c, FILE *fp)
{
    size_t *wins = calloc(st->n_models + 1, sizeof *wins);
    size_t s;
    size_t m;
    size_t printed = 0;
    if (wins == NULL) {
        return;
    }
    for (s = 0; s < st->n_samples; s++) {
        size_t b = best_of(st, s, c);
        if (b != (size_t)-1) {
            wins[b]++;
        }
    }
    fprintf(fp, "%s:", crit_names[c]);
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

static void write_md(const bf_cli_study *st, const bf_tt *t, int crit,
                     FILE *fp)
{
    int c;
    fputs("# Model ranking\n\n", fp);
    bf_cli_study_describe(st, fp);
    fprintf(fp, "%s per sample (lower is better; * the best):\n\n",
            crit_names[crit]);
    bf_tt_print(t, fp);
    fputs("\nSummary over samples:\n\n", fp);
    for (c = 0; c < N_CRIT; c++) {
        fputs("- ", fp);
        summary(st, c, fp);
    }
}

static int write_files(const bf_cli_study *st, const bf_tt *t, int crit)
{
    bf_out csv;
    bf_out md;
    int rc = bf_cli_make_outdir(st->opts.out_dir);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_out_open(&csv, st->opts.out_dir, "ranking.csv");
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_out_open(&md, st->opts.out_dir, "ranking.md");
    if (rc != BF_EXIT_OK) {
        bf_out_abort(&csv);
        return rc;
    }
    write_csv(st, csv.fp);
    write_md(st, t, crit, md.fp);
    rc = bf_out_commit(&csv);
    if (rc != BF_EXIT_OK) {
        bf_out_abort(&md);
        return rc;
    }
    return bf_out_commit(&md);
}

int bf_cmd_rank(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"criterion", required_argument, NULL, O_CRITERION},
        {NULL, 0, NULL, 0}};
    int crit = CRIT_BIC;
    bf_cli_extra extra = {longopts, handle, &crit};
    bf_cli_study st;
    bf_tt *t = NULL;
    int rc;

    memset(&st, 0, sizeof st);
    st.cmd = "rank";
    rc = bf_cli_opts_parse(st.cmd, argc, argv, usage, &extra, &st.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    if (!st.opts.samples_given) {
        st.opts.samples = "all"; /* every CURET sample */
    }
    if (st.opts.models == NULL) {
        st.opts.models = RANK_MODELS;
    }
    if (!st.opts.fit_given) {
        st.opts.exact = 1;
    }
    st.opts.stats = 1; /* the ranking needs AIC, BIC and CV */
    if (crit == CRIT_CV && st.opts.folds < 2) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, "rank ", "--criterion cv needs --folds "
                                  ">= 2");
    }
    rc = bf_cli_study_prepare(&st);
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        t = build_table(&st, crit);
        if (t == NULL) {
            bf_cli_err("out of memory");
            rc = BF_EXIT_SOFTWARE;
        }
    }
    if (rc == BF_EXIT_OK) {
        rc = write_files(&st, t, crit);
    }
    if (rc == BF_EXIT_OK && !st.opts.quiet) {
        int c;
        bf_cli_study_describe(&st, stdout);
        printf("%s per sample (lower is better; * the best)\n\n",
               crit_names[crit]);
        bf_tt_print(t, stdout);
        printf("\nSummary over samples:\n");
        for (c = 0; c < N_CRIT; c++) {
            summary(&st, c, stdout);
        }
        printf("\nWritten: %s/ranking.csv, %s/ranking.md\n",
               st.opts.out_dir, st.opts.out_dir);
    }
    bf_tt_free(t);
    bf_cli_study_free(&st);
    return rc;
}
