/* cmd_rank.c: `brdffit rank` -- model selection per sample: fits every
 * model to every sample (by default all samples of the data, --fit exact),
 * ranks the models of each sample by AIC, BIC and cross-validated error
 * (doc/methods.md §4-5), prints the ranking, the best model's parameters
 * and a summary over samples, and writes ranking.csv (the library's
 * bf_ranking_csv_write) and ranking.md atomically into the output folder. */
#include <string.h>

#include "ranking.h"
#include "setup.h"
#include "tables.h"
#include "texttable.h"

/* rank's defaults: every sample of the data, the exact fit, the paper's
 * six models, the Lambert baseline and the two Wolff-Nayar-Oren models. */
static const bf_cli_defaults rank_defaults = {"all", BF_MODELS_RANKING, 1,
                                              1};

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit rank [OPTIONS] [FILE...]\n"
"\n"
"Ranks reflectance models per sample by AIC, BIC and K-fold\n"
"cross-validated error (doc/methods.md), after fitting each model.\n"
"Prints the ranking, the best model of each sample with its fitted\n"
"parameters and 95% profile intervals, and a summary over samples ('FC-E\n"
"best for 32 of 61 samples, ...'); writes ranking.csv (criteria, ranks,\n"
"parameters and intervals of every model) and ranking.md into the output\n"
"folder. A tie (values within a relative 1e-9) goes to the model with\n"
"fewer parameters; a fit that reduces to a smaller model (ON at sigma = 0\n"
"is LAMBERT) wins for that model.\n"
"\n"
"Options:\n"
"  --criterion C     aic, bic or cv: the one the tables and the summary\n"
"                    lead with (ranking.csv has all three; default bic)\n",
        fp);
    bf_cli_opts_usage_defaults(fp, &rank_defaults);
    bf_cli_exit_usage(fp);
}

enum { O_CRITERION = 512 };

static int handle(int val, const char *arg, void *ctx)
{
    bf_criterion *crit = ctx;
    if (val != O_CRITERION) {
        return BF_EXIT_SOFTWARE;
    }
    if (bf_criterion_find(arg, crit) != BF_OK) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, "rank ",
                                 "--criterion: '%s' is not aic, bic or cv",
                                 arg);
    }
    return 0;
}

static int write_md(const bf_rep_study *st, const bf_tt *t,
                    const bf_tt *best, int crit, FILE *fp)
{
    size_t m;
    int c;
    fputs("# Model ranking\n\n", fp);
    if (bf_rep_study_describe(st, fp) != BF_EXIT_OK) {
        return BF_EXIT_SOFTWARE;
    }
    fprintf(fp, "%s per sample (lower is better; * the best):\n\n",
            bf_rep_crit_names[crit]);
    bf_tt_print(t, fp);
    fputs("\nSummary over samples:\n\n", fp);
    for (c = 0; c < BF_REP_NCRIT; c++) {
        fputs("- ", fp);
        if (bf_rep_rank_summary(st, c, fp) != BF_EXIT_OK) {
            return BF_EXIT_SOFTWARE;
        }
    }
    fprintf(fp, "\nBest model by %s and its fitted parameters:\n\n",
            bf_rep_crit_names[crit]);
    bf_tt_print(best, fp);
    fputs("\n## Fitted parameters of every model\n\n"
          "value (the maximum-likelihood estimate the interval is about, "
          "where it differs) [95% profile interval] {bootstrap interval, "
          "when run}; "
          "flags as in fits.csv (README \"Output files\").\n",
          fp);
    for (m = 0; m < st->n_models; m++) {
        bf_tt *p = NULL;
        if (bf_rep_params_table(st, m, &p) != BF_EXIT_OK) {
            bf_cli_err("out of memory");
            return BF_EXIT_SOFTWARE;
        }
        if (p == NULL) {
            continue; /* nothing fitted */
        }
        fprintf(fp, "\n### %s\n\n", st->models[m]->name);
        bf_tt_print(p, fp);
        bf_tt_free(p);
    }
    return BF_EXIT_OK;
}

static int write_files(const bf_rep_study *st, const bf_tt *t,
                       const bf_tt *best, int crit)
{
    bf_out csv;
    bf_out md;
    int rc = bf_rep_make_outdir(st->out_dir);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_out_open(&csv, st->out_dir, "ranking.csv");
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_out_open(&md, st->out_dir, "ranking.md");
    if (rc != BF_EXIT_OK) {
        bf_out_abort(&csv);
        return rc;
    }
    rc = bf_ranking_csv_write(csv.fp, &st->spec, st->rows, st->stats,
                              &st->analysis);
    if (rc != BF_OK) {
        bf_out_abort(&csv);
        bf_out_abort(&md);
        return bf_rep_write_error("ranking.csv", rc);
    }
    if (write_md(st, t, best, crit, md.fp) != BF_EXIT_OK) {
        bf_out_abort(&csv);
        bf_out_abort(&md);
        return BF_EXIT_SOFTWARE;
    }
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
    bf_criterion crit = BF_CRIT_BIC;
    bf_cli_extra extra = {longopts, handle, &crit};
    bf_rep_study st;
    bf_cli_run r;
    bf_tt *t = NULL;
    bf_tt *best = NULL;
    int rc;

    memset(&st, 0, sizeof st);
    memset(&r, 0, sizeof r);
    st.cmd = "rank";
    rc = bf_cli_opts_parse_defaults(st.cmd, argc, argv, usage, &extra,
                                    &rank_defaults, &r.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    r.opts.stats = 1; /* the ranking needs AIC, BIC and CV */
    if (crit == BF_CRIT_CV && r.opts.folds < 2) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, "rank ",
                                 "--criterion cv needs --folds >= 2");
    }
    rc = bf_cli_study_setup(st.cmd, &r, &st);
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        t = bf_rep_rank_table(&st, (int)crit);
        best = bf_rep_best_table(&st, (int)crit);
        if (t == NULL || best == NULL) {
            bf_cli_err("out of memory");
            rc = BF_EXIT_SOFTWARE;
        }
    }
    if (rc == BF_EXIT_OK) {
        rc = write_files(&st, t, best, (int)crit);
    }
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        rc = bf_rep_study_describe(&st, stdout);
    }
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        int c;
        printf("%s per sample (lower is better; * the best)\n\n",
               bf_rep_crit_names[crit]);
        bf_tt_print(t, stdout);
        printf("\nBest model by %s and its fitted parameters\n\n",
               bf_rep_crit_names[crit]);
        bf_tt_print(best, stdout);
        printf("\nSummary over samples:\n");
        for (c = 0; c < BF_REP_NCRIT && rc == BF_EXIT_OK; c++) {
            rc = bf_rep_rank_summary(&st, c, stdout);
        }
    }
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        printf("\nWritten: %s/ranking.csv (parameters and intervals of "
               "every model), %s/ranking.md\n",
               st.out_dir, st.out_dir);
    }
    bf_tt_free(t);
    bf_tt_free(best);
    bf_rep_study_free(&st);
    bf_cli_run_free(&r);
    return rc;
}
