/* cmd_convert.c: `brdffit convert` -- any dataset brdffit reads, written
 * as tidy CSV (bf_csv_write), so measurements move between tools. The file
 * is written to a temporary name and renamed into place. */
#include <getopt.h>
#include <libgen.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

static void usage(FILE *fp)
{
    fprintf(fp,
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
"  --to csv          the output format (required; csv is the only one)\n"
"  --input-format F  force the format of IN (pbrt, astm, merl, csv, curet)\n"
"  --configs FILE|all  where a MERL table is sampled (default: CURET's\n"
"                    205 configurations from --data DIR/table.txt)\n"
"  --data DIR        CURET folder for MERL's default configurations\n"
"                    (default $BRDFFIT_DATA, else %s)\n"
"  -h, --help        show this help\n",
            BF_DEFAULT_DATA_DIR);
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
    rc = bf_cli_check_outdir(dirname(dir_buf));
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
    enum { O_TO = 256, O_FORMAT, O_CONFIGS, O_DATA };
    static const struct option longopts[] = {
        {"to", required_argument, NULL, O_TO},
        {"input-format", required_argument, NULL, O_FORMAT},
        {"format", required_argument, NULL, O_FORMAT},
        {"configs", required_argument, NULL, O_CONFIGS},
        {"data", required_argument, NULL, O_DATA},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    bf_cli_source src;
    bf_cli_inputs in;
    const char *to = NULL;
    struct stat sb;
    int c;
    int rc;

    memset(&src, 0, sizeof src);
    src.data_dir = getenv("BRDFFIT_DATA");
    if (src.data_dir == NULL || src.data_dir[0] == '\0') {
        src.data_dir = BF_DEFAULT_DATA_DIR;
    }
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        switch (c) {
        case O_TO: to = optarg; break;
        case O_FORMAT:
            if (bf_format_find(optarg, &src.format) != BF_OK ||
                src.format == BF_FORMAT_MEMORY) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, "convert ",
                                         "--input-format: '%s' is not "
                                         "pbrt, astm, merl, csv, curet or "
                                         "auto", optarg);
            }
            break;
        case O_CONFIGS: src.configs = optarg; break;
        case O_DATA: src.data_dir = optarg; break;
        case 'h': usage(stdout); return BF_EXIT_OK;
        case ':':
            return bf_cli_usage_fail(BF_EXIT_NOVALUE, "convert ",
                                     "option '%s' needs a value",
                                     argv[optind - 1]);
        default:
            return bf_cli_usage_error("convert ", "unknown option '%s'",
                                      argv[optind - 1]);
        }
    }
    if (argc - optind != 2) {
        return argc - optind < 2
                   ? bf_cli_usage_fail(BF_EXIT_NOVALUE, "convert ",
                                       "give IN and OUT")
                   : bf_cli_usage_error("convert ",
                                        "unexpected argument '%s'",
                                        argv[optind + 2]);
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
    if (stat(argv[optind], &sb) == 0 && S_ISDIR(sb.st_mode)) {
        src.data_dir = argv[optind]; /* a folder is CURET */
    } else {
        src.inputs[0] = argv[optind];
        src.n_inputs = 1;
    }
    rc = bf_cli_load_data(&src, NULL, NULL, &in);
    if (rc == BF_EXIT_OK) {
        rc = write_csv(in.ds, argv[optind + 1]);
    }
    bf_cli_free_inputs(&in);
    return rc;
}
