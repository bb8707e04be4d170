/* cmd_convert.c: `brdffit convert` -- any dataset brdffit reads, written
 * as tidy CSV (bf_csv_write), so measurements move between tools. The file
 * is written to a temporary name and renamed into place. */
#include <libgen.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void usage(FILE *fp)
{
    fputs(
"Usage: brdffit convert [OPTIONS] IN --to csv OUT\n"
"\n"
"Reads IN in any format brdffit reads (a CURET folder, pbrt-v2/Cornell\n"
".brdf, ASTM E1392 .astm, MERL .binary, tidy CSV) and writes it to OUT as\n"
"tidy CSV (README 'Tidy CSV'): a material column, theta_i, phi_i,\n"
"theta_o, phi_o in degrees (measurement frame, SPEC §1.5; read back to the\n"
"same radians bit for bit) and one column per channel; an invalid value\n"
"is an empty field. OUT '-' writes to standard output.\n"
"\n"
"Options:\n"
"  --to csv          the output format (required; csv is the only one)\n",
          fp);
    bf_cli_file_args_usage(fp);
    bf_cli_exit_usage(fp);
}

/* Writes ds to path atomically (or to standard output for "-"). */
static int write_csv(const bf_dataset *ds, const char *path)
{
    char dir_buf[4096];
    char base_buf[4096];
    bf_out o;
    int rc;
    if (strcmp(path, "-") == 0) {
        if (bf_csv_write(ds, stdout) != BF_OK || fflush(stdout) != 0) {
            bf_cli_err("standard output: write error");
            return BF_EXIT_IOERR;
        }
        return BF_EXIT_OK;
    }
    snprintf(dir_buf, sizeof dir_buf, "%s", path);
    snprintf(base_buf, sizeof base_buf, "%s", path);
    rc = bf_rep_check_outdir(dirname(dir_buf));
    if (rc == BF_EXIT_OK) {
        snprintf(dir_buf, sizeof dir_buf, "%s", path);
        rc = bf_out_open(&o, dirname(dir_buf), basename(base_buf));
    }
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_csv_write(ds, o.fp);
    if (rc != BF_OK) {
        bf_out_abort(&o);
        if (rc == BF_EINVAL) {
            bf_cli_err("%s: the materials have different channels; tidy "
                       "CSV needs the same channel columns for all",
                       path);
            return BF_EXIT_DATAERR;
        }
        bf_cli_err("%s: write error", path);
        return BF_EXIT_IOERR;
    }
    return bf_out_commit(&o);
}

int bf_cmd_convert(int argc, char **argv)
{
    bf_cli_source src;
    bf_cli_inputs in;
    const char *to = NULL;
    int first;
    int rc = bf_cli_file_args("convert ", argc, argv, usage, &to, &src,
                              &first);
    if (rc != 0) {
        return rc < 0 ? BF_EXIT_OK : rc;
    }
    if (argc - first != 2) {
        return argc - first < 2
                   ? bf_cli_usage_fail(BF_EXIT_NOVALUE, "convert ",
                                       "give IN and OUT")
                   : bf_cli_usage_error("convert ",
                                        "unexpected argument '%s'",
                                        argv[first + 2]);
    }
    if (to == NULL) {
        return bf_cli_usage_fail(BF_EXIT_NOVALUE, "convert ",
                                 "--to FORMAT is required (csv)");
    }
    if (strcmp(to, "csv") != 0) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, "convert ",
                                 "--to: '%s' is not csv (the only output "
                                 "format)", to);
    }
    bf_cli_source_path(&src, argv[first]);
    rc = bf_cli_load_data(&src, NULL, NULL, &in);
    if (rc == BF_EXIT_OK) {
        rc = write_csv(in.ds, argv[first + 1]);
    }
    bf_cli_free_inputs(&in);
    return rc;
}
