/* cmd_calibrate.c: `brdffit calibrate` -- whether to trust the intervals
 * on one's own data: fits every model to every sample (--fit exact), then
 * simulates N measurements of each fit under its fitted noise model at
 * the sample's configurations, refits them and reports each parameter's
 * coverage and bias (the library's bf_study_calibrate, doc/methods.md §3);
 * prints a table and writes calibrate.csv atomically into the output
 * folder. */
#include <stdlib.h>
#include <string.h>

#include "setup.h"
#include "texttable.h"

/* calibrate's defaults: the paper's samples on CURET, its six models, the
 * exact fit. */
static const bf_cli_defaults calibrate_defaults = {NULL, BF_MODELS_PAPER, 1,
                                                   1};

/* Fewest simulations (bf_fit_calibrate's). */
#define MIN_SIMS BF_CALIBRATE_MIN_SIM

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit calibrate [OPTIONS] [FILE...]\n"
"\n"
"Checks the 95% intervals on the user's own data: fits each model to each\n"
"sample, then simulates N measurements at the sample's configurations from\n"
"the fitted parameters under the fitted noise model (--noise), normalised\n"
"by their maximum as measured data are (a specular model's or composite's\n"
"kept in sr^-1), refits each and reports how often\n"
"each parameter's interval covers the value simulated (about 95% when the\n"
"intervals can be trusted), the bias and spread of the estimates and the\n"
"median interval width. Writes calibrate.csv into the output folder.\n"
"\n"
"Options:\n"
"  --sims N          simulations per fit, N >= 10 (default 200)\n",
        fp);
    bf_cli_opts_usage_defaults(fp, &calibrate_defaults);
    bf_cli_exit_usage(fp);
}

enum { O_SIMS = 512 };

static int handle(int val, const char *arg, void *ctx)
{
    size_t *sims = ctx;
    char *end = NULL;
    long v;
    if (val != O_SIMS) {
        return BF_EXIT_SOFTWARE;
    }
    v = strtol(arg, &end, 10);
    if (end == arg || *end != '\0' || v < MIN_SIMS || v > 1000000) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, "calibrate ",
                                 "--sims: '%s' is not a number of "
                                 "simulations from %d to 1000000",
                                 arg, MIN_SIMS);
    }
    *sims = (size_t)v;
    return 0;
}

/* The table: one row per (pair, fitted parameter). */
static bf_tt *table(const bf_rep_study *st, const size_t *pairs, size_t n,
                    const bf_calibration *cal)
{
    bf_tt *t = bf_tt_alloc(10);
    size_t i;
    if (t == NULL) {
        return NULL;
    }
    bf_tt_header(t, 0, "sample");
    bf_tt_header(t, 1, "model");
    bf_tt_header(t, 2, "param");
    bf_tt_header(t, 3, "value");
    bf_tt_header(t, 4, "noise p");
    bf_tt_header(t, 5, "covered");
    bf_tt_header(t, 6, "bias");
    bf_tt_header(t, 7, "sd");
    bf_tt_header(t, 8, "ML sd");
    bf_tt_header(t, 9, "width");
    for (i = 0; i < n; i++) {
        const bf_study_row *r = &st->rows[pairs[i]];
        const bf_fit_stats *s = &st->stats[pairs[i]];
        size_t j;
        for (j = 0; j < r->type->p; j++) {
            if (!((s->free_mask >> j) & 1u)) {
                continue;
            }
            bf_tt_add_row(t);
            bf_tt_set(t, 0, "%d", r->sample);
            bf_tt_set(t, 1, "%s", r->type->name);
            bf_tt_set(t, 2, "%s", r->type->param[j].name);
            bf_tt_set(t, 3, "%.4g", cal[i].truth[j]);
            bf_tt_set(t, 4, "%.3g", s->noise_power);
            bf_tt_set(t, 5, "%.3f", cal[i].coverage[j]);
            bf_tt_set(t, 6, "%.3g", cal[i].bias[j]);
            bf_tt_set(t, 7, "%.3g", cal[i].sd[j]);
            bf_tt_set(t, 8, "%.3g", cal[i].ml_sd[j]);
            bf_tt_set(t, 9, "%.3g", cal[i].width[j]);
        }
    }
    for (i = 3; i < 10; i++) {
        bf_tt_right(t, i);
    }
    if (bf_tt_failed(t)) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}

static int write_csv(const bf_rep_study *st, const size_t *pairs, size_t n,
                     const bf_calibration *cal)
{
    bf_out csv;
    int rc = bf_rep_make_outdir(st->out_dir);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_out_open(&csv, st->out_dir, "calibrate.csv");
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    if (bf_calibration_csv_write(csv.fp, &st->spec, st->rows, st->stats,
                                 &st->analysis, pairs, n, cal) != BF_OK) {
        bf_cli_err("internal error: calibrate.csv could not be written");
        bf_out_abort(&csv);
        return BF_EXIT_SOFTWARE;
    }
    return bf_out_commit(&csv);
}

/* Calibrates every analysed pair with fitted parameters into pairs, cal
 * (*n of them). */
static int calibrate_all(const bf_rep_study *st, size_t sims, size_t *pairs,
                         bf_calibration *cal, size_t *n)
{
    size_t u;
    *n = 0;
    for (u = 0; u < st->n_samples * st->n_models; u++) {
        bf_error err;
        int rc;
        if (!st->stats[u].done || st->stats[u].free_mask == 0) {
            continue;
        }
        rc = bf_study_calibrate(&st->spec, &st->analysis, st->rows,
                                st->stats, u, sims, st->opts.seed, &cal[*n],
                                &err);
        if (rc == BF_ENOMEM) {
            bf_cli_err("out of memory");
            return BF_EXIT_SOFTWARE;
        }
        if (rc != BF_OK) {
            return bf_rep_study_error(&err);
        }
        pairs[(*n)++] = u;
    }
    return BF_EXIT_OK;
}

int bf_cmd_calibrate(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"sims", required_argument, NULL, O_SIMS}, {NULL, 0, NULL, 0}};
    size_t sims = 200;
    bf_cli_extra extra = {longopts, handle, &sims};
    bf_rep_study st;
    bf_cli_run r;
    size_t *pairs = NULL;
    bf_calibration *cal = NULL;
    size_t n = 0;
    bf_tt *t = NULL;
    int rc;

    memset(&st, 0, sizeof st);
    memset(&r, 0, sizeof r);
    st.cmd = "calibrate";
    rc = bf_cli_opts_parse_defaults(st.cmd, argc, argv, usage, &extra,
                                    &calibrate_defaults, &r.opts);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    r.opts.stats = 1;
    rc = bf_cli_study_setup(st.cmd, &r, &st);
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        size_t units = st.n_samples * st.n_models + 1;
        pairs = malloc(units * sizeof *pairs);
        cal = malloc(units * sizeof *cal);
        rc = pairs == NULL || cal == NULL ? BF_EXIT_SOFTWARE : BF_EXIT_OK;
        if (rc != BF_EXIT_OK) {
            bf_cli_err("out of memory");
        }
    }
    if (rc == BF_EXIT_OK) {
        rc = calibrate_all(&st, sims, pairs, cal, &n);
    }
    if (rc == BF_EXIT_OK) {
        t = table(&st, pairs, n, cal);
        if (t == NULL) {
            bf_cli_err("out of memory");
            rc = BF_EXIT_SOFTWARE;
        }
    }
    if (rc == BF_EXIT_OK) {
        rc = write_csv(&st, pairs, n, cal);
    }
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        printf("Calibration: %zu simulations per fit under the fitted noise "
               "model (--noise %s), objective %s\n\n",
               sims, bf_noise_name(st.analysis.noise),
               bf_objective_name(st.analysis.objective));
        bf_tt_print(t, stdout);
        printf("\ncovered: share of the %.0f%% intervals holding the value "
               "simulated; bias, sd: of the objective's estimates; ML sd: of "
               "the estimates the intervals are about\nWritten: "
               "%s/calibrate.csv\n",
               100.0 * st.analysis.level, st.out_dir);
    }
    bf_tt_free(t);
    free(pairs);
    free(cal);
    bf_rep_study_free(&st);
    bf_cli_run_free(&r);
    return rc;
}
