/* cmd_rank.c: `brdffit rank` -- model selection per sample: fits every
 * model to every sample (by default all samples of the data, --fit exact),
 * ranks the models of each sample by AIC, BIC and cross-validated error
 * (doc/methods.md §4-5), prints the ranking and a summary over samples and
 * writes ranking.csv and ranking.md atomically into the output folder. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "texttable.h"

/* The models rank compares by default: the paper's six, the Lambert
 * baseline and the two Wolff-Nayar-Oren models. */
#define RANK_MODELS "VH-G,VH-E,FC-G,FC-E,ON,LFTG,LAMBERT,WNO,WNO-R"


static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit rank [OPTIONS]\n"
"\n"
"Ranks reflectance models per sample by AIC, BIC and K-fold\n"
"cross-validated error (doc/methods.md), after fitting each model (by\n"
"default with --fit exact, on every sample of the data, models\n"
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
    bf_cli_exit_usage(fp);
}

enum { O_CRITERION = 512 };

static int handle(int val, const char *arg, void *ctx)
{
    int *crit = ctx;
    size_t c;
    if (val != O_CRITERION) {
        return BF_EXIT_SOFTWARE;
    }
    for (c = 0; c < BF_CLI_NCRIT; c++) {
        char lower[8];
        size_t i;
        for (i = 0; bf_cli_crit_names[c][i] != '\0'; i++) {
            lower[i] = (char)(bf_cli_crit_names[c][i] - 'A' + 'a');
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
static void write_csv(const bf_cli_study *st, FILE *fp)
{
    size_t s;
    size_t m;
    fputs("sample,name,channel,model,objective,fit,k,n,objective_value,aic,bic,cv,"
          "rank_aic,rank_bic,rank_cv\n",
          fp);
    for (s = 0; s < st->n_samples; s++) {
        for (m = 0; m < st->n_models; m++) {
            size_t i = s * st->n_models + m;
            const bf_fit_stats *f = &st->stats[i];
            if (st->rows[i].status != BF_OK || !f->done) {
                continue;
            }
            bf_cli_csv_sample(fp, st, s);
            fprintf(fp, ",%s,%s,%s,%zu,%zu,%.10g,%.10g,%.10g,",
                    st->models[m]->name, bf_objective_name(f->objective),
                    st->opts.exact ? "exact" : "paper", f->k, f->n,
                    st->rows[i].fit.lse, f->aic, f->bic);
            if (isfinite(f->cv)) {
                fprintf(fp, "%.10g", f->cv);
            }
            fprintf(fp, ",%zu,%zu,%zu\n", bf_cli_rank_of(st, s, m, BF_CLI_AIC),
                    bf_cli_rank_of(st, s, m, BF_CLI_BIC), bf_cli_rank_of(st, s, m, BF_CLI_CV));
        }
    }
}

static void write_md(const bf_cli_study *st, const bf_tt *t, int crit,
                     FILE *fp)
{
    int c;
    fputs("# Model ranking\n\n", fp);
    bf_cli_study_describe(st, fp);
    fprintf(fp, "%s per sample (lower is better; * the best):\n\n",
            bf_cli_crit_names[crit]);
    bf_tt_print(t, fp);
    fputs("\nSummary over samples:\n\n", fp);
    for (c = 0; c < BF_CLI_NCRIT; c++) {
        fputs("- ", fp);
        bf_cli_rank_summary(st, c, fp);
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
    int crit = BF_CLI_BIC;
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
        st.opts.samples = "all"; /* every sample of the data */
    }
    if (st.opts.models == NULL) {
        st.opts.models = RANK_MODELS;
    }
    if (!st.opts.fit_given) {
        st.opts.exact = 1;
    }
    st.opts.stats = 1; /* the ranking needs AIC, BIC and CV */
    if (crit == BF_CLI_CV && st.opts.folds < 2) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, "rank ", "--criterion cv needs --folds "
                                  ">= 2");
    }
    rc = bf_cli_study_prepare(&st);
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        t = bf_cli_rank_table(&st, crit);
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
               bf_cli_crit_names[crit]);
        bf_tt_print(t, stdout);
        printf("\nSummary over samples:\n");
        for (c = 0; c < BF_CLI_NCRIT; c++) {
            bf_cli_rank_summary(&st, c, stdout);
        }
        printf("\nWritten: %s/ranking.csv, %s/ranking.md\n",
               st.opts.out_dir, st.opts.out_dir);
    }
    bf_tt_free(t);
    bf_cli_study_free(&st);
    return rc;
}
