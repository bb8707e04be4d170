/* main.c: the brdffit command-line tool -- dispatches to subcommands. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <string.h>

#include "setup.h"

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit COMMAND [OPTIONS]\n"
"\n"
"Fit rough-surface reflectance models to measured BRDF data and compare\n"
"them (Ragheb & Hancock, \"Comparing Variants of the Beckmann Model\").\n"
"\n"
"Commands:\n"
"  compare   fit models to measured BRDFs (CURET, Cornell .brdf, ASTM,\n"
"            MERL, CSV); print Tables 2 and 3, write CSV\n"
"  report    run compare and write every figure and report.html\n"
"  rank      rank the models per sample by AIC, BIC and cross-validation\n"
"  calibrate check the 95% intervals on simulated copies of one's own fits\n"
"  info      describe a data file or folder (format, materials, angles)\n"
"  convert   write any data file brdffit reads as tidy CSV\n"
"  models    list the models, their parameters, ranges and equations\n"
"\n"
"Options:\n"
"  -h, --help     show this help ('brdffit COMMAND --help' for a command)\n"
"  -V, --version  show the version\n"
"\n"
"Exit status: 0 success; 61 missing argument (no command, option without\n"
"its value); 62 conflicting options; 63 malformed or out-of-range option\n"
"value; 64 unknown command or option, unexpected argument; 65 bad input\n"
"data; 66 input file not found; 70 internal error; 73 cannot create\n"
"output; 74 write error. See brdffit(1) and README.md.\n",
        fp);
}

int main(int argc, char **argv)
{
    static char hint[64];
    const char *cmd;
    gsl_set_error_handler_off(); /* every GSL status is checked (STYLE §4) */
    if (argc < 2) {
        return bf_cli_usage_fail(BF_EXIT_NOVALUE, NULL, "no command given");
    }
    cmd = argv[1];
    /* the report library's messages (bf_out_*, the study): on stderr, an
     * option's error with the hint to run 'brdffit CMD --help' */
    snprintf(hint, sizeof hint, "%.60s ", cmd);
    bf_rep_set_sink(bf_cli_message, hint);
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 ||
        strcmp(cmd, "help") == 0) {
        usage(stdout);
        return BF_EXIT_OK;
    }
    if (strcmp(cmd, "-V") == 0 || strcmp(cmd, "--version") == 0) {
        printf("brdffit %s\n", bf_version());
        return BF_EXIT_OK;
    }
    if (strcmp(cmd, "compare") == 0) {
        return bf_cmd_compare(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "report") == 0) {
        return bf_cmd_report(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "models") == 0) {
        return bf_cmd_models(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "rank") == 0) {
        return bf_cmd_rank(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "calibrate") == 0) {
        return bf_cmd_calibrate(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "info") == 0) {
        return bf_cmd_info(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "convert") == 0) {
        return bf_cmd_convert(argc - 1, argv + 1);
    }
    return bf_cli_usage_error(NULL, "unknown command '%s'", cmd);
}
