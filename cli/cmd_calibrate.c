/* cmd_calibrate.c: `brdffit calibrate` -- whether to trust the intervals
 * on one's own data: fits every model to every sample (--fit exact), then
 * simulates N measurements of each fit under its fitted noise model at
 * the sample's configurations, refits them and reports each parameter's
 * coverage and bias (the library's bf_study_calibrate_all, in parallel on
 * --threads threads, doc/methods.md §3); prints the table and writes
 * calibrate.csv atomically into the output folder (the report library's
 * calibration.h, which `brdffit report --calibrate N` shares). */
#include <stdlib.h>
#include <string.h>

#include "calibration.h"
#include "setup.h"

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
"median interval width. The table gives the value simulated (the\n"
"objective's optimum) beside the ML estimate the interval is about (far\n"
"apart where the model does not fit), the coverage +- its binomial sd,\n"
"the band calibrated intervals give 99% of the time, a check (low: the\n"
"intervals cover less than they say, ok, high), the bias of the\n"
"maximum-likelihood estimates in their sds and the median width over\n"
"2 x 1.96 sd (1 is calibrated); a note under the table names the fits\n"
"whose noise power, estimated (--noise auto), sits at its bound 2 (the\n"
"data would take a variance growing faster than the squared mean: a lack\n"
"of fit; such checks were low on glossy paints, doc/methods.md §3). The fits\n"
"are simulated in parallel on --threads threads (the same numbers for\n"
"any count). Writes calibrate.csv into the output folder; 'brdffit\n"
"report --calibrate N' adds the same check, with a figure per sample, to\n"
"the report.\n"
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

int bf_cmd_calibrate(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"sims", required_argument, NULL, O_SIMS}, {NULL, 0, NULL, 0}};
    size_t sims = 200;
    bf_cli_extra extra = {longopts, handle, &sims};
    bf_rep_study st;
    bf_cli_run r;
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
    st.opts.calibrate = sims; /* the run calibrates after the analysis */
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_study_run(&st);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_rep_calibration_write(&st);
    }
    if (rc == BF_EXIT_OK && !r.opts.quiet) {
        rc = bf_rep_calibration_print(&st, stdout);
        printf("Written: %s/calibrate.csv\n", st.out_dir);
    }
    bf_rep_study_free(&st);
    bf_cli_run_free(&r);
    return rc;
}
