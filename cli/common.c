/* common.c: messages, argument parsing, input loading and atomic output
 * files shared by the brdffit subcommands. */
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

const char *bf_cli_prog = "brdffit";

void bf_cli_err(const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", bf_cli_prog);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

static int usage_v(int status, const char *cmd, const char *fmt, va_list ap)
{
    fprintf(stderr, "%s: ", bf_cli_prog);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\nTry '%s %s--help' for more information.\n",
            bf_cli_prog, cmd != NULL ? cmd : "");
    return status;
}

int bf_cli_usage_fail(int status, const char *cmd, const char *fmt, ...)
{
    va_list ap;
    int rc;
    va_start(ap, fmt);
    rc = usage_v(status, cmd, fmt, ap);
    va_end(ap);
    return rc;
}

int bf_cli_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    int rc;
    va_start(ap, fmt);
    rc = usage_v(BF_EXIT_USAGE, cmd, fmt, ap);
    va_end(ap);
    return rc;
}

void bf_cli_exit_usage(FILE *fp)
{
    fputs("\n"
          "Exit status: 0 success; 61 option without its value; 62 conflicting\n"
          "options; 63 malformed or out-of-range option value; 64 unknown option or\n"
          "unexpected argument; 65 bad input data; 66 input file not found; 70\n"
          "internal error; 73 output folder cannot be created or written; 74 write\n"
          "error.\n",
          fp);
}

int bf_cli_load_error(const bf_error *err)
{
    char buf[BF_ERROR_FILE_MAX + BF_ERROR_MSG_MAX + 64];
    bf_cli_err("%s", bf_error_format(err, buf, sizeof buf));
    if (err->code == BF_EIO) {
        return BF_EXIT_NOINPUT;
    }
    if (err->code == BF_ENOMEM) {
        return BF_EXIT_SOFTWARE;
    }
    return BF_EXIT_DATAERR;
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The configurations a MERL file is sampled at (SPEC §8): CURET's 205 by
 * default (the table of src->data_dir), a CSV list, or every valid cell.
 * *angles is malloc'ed (NULL for all cells). */
static int merl_configs(const bf_cli_source *src, bf_cli_inputs *in,
                        double **angles, size_t *n, int *all)
{
    bf_error err;
    *angles = NULL;
    *n = 0;
    *all = 0;
    if (src->configs != NULL && strcmp(src->configs, "all") == 0) {
        *all = 1;
        snprintf(in->configs_path, sizeof in->configs_path, "all");
        return BF_EXIT_OK;
    }
    if (src->configs != NULL) {
        snprintf(in->configs_path, sizeof in->configs_path, "%s",
                 src->configs);
        if (bf_configs_load(src->configs, angles, n, &err) != BF_OK) {
            return bf_cli_load_error(&err);
        }
        return BF_EXIT_OK;
    }
    snprintf(in->configs_path, sizeof in->configs_path, "%s/table.txt",
             src->data_dir);
    if (!file_exists(in->configs_path)) {
        bf_cli_err("%s: CURET's configuration table not found: a MERL file "
                   "is sampled at CURET's 205 configurations by default "
                   "(give --data DIR), at the angles of a CSV file "
                   "(--configs FILE) or at every valid cell (--configs all)",
                   in->configs_path);
        return BF_EXIT_NOINPUT;
    }
    if (bf_curet_configs_load(in->configs_path, angles, n, &err) != BF_OK) {
        return bf_cli_load_error(&err);
    }
    return BF_EXIT_OK;
}

/* Loads one --input file and appends it to in->ds. */
static int load_input(const bf_cli_source *src, const char *path,
                      bf_cli_inputs *in)
{
    bf_load_opts lo;
    bf_error err;
    bf_dataset *one = NULL;
    double *angles = NULL;
    int rc;

    memset(&lo, 0, sizeof lo);
    lo.format = src->format;
    if (lo.format == BF_FORMAT_AUTO && !is_dir(path) &&
        bf_format_detect(path, &lo.format, &err) != BF_OK) {
        return bf_cli_load_error(&err);
    }
    if (lo.format == BF_FORMAT_MERL) {
        rc = merl_configs(src, in, &angles, &lo.n_at, &lo.all_cells);
        if (rc != BF_EXIT_OK) {
            return rc;
        }
        lo.at = angles;
    }
    rc = bf_dataset_load(path, &lo, &one, &err);
    free(angles);
    if (rc != BF_OK) {
        return bf_cli_load_error(&err);
    }
    rc = bf_dataset_append(in->ds, one);
    bf_dataset_free(one);
    if (rc != BF_OK) {
        bf_cli_err("%s: %s", path,
                   rc == BF_ENOMEM ? "out of memory"
                                   : "cannot be combined with the other "
                                     "inputs (material numbers clash)");
        return rc == BF_ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_DATAERR;
    }
    return BF_EXIT_OK;
}

int bf_cli_load_data(const bf_cli_source *src, const char *n_file,
                     const char *on_file, bf_cli_inputs *in)
{
    bf_error err;
    size_t i;
    int rc;

    memset(in, 0, sizeof *in);
    if (src->n_inputs == 0) { /* CURET */
        if (!is_dir(src->data_dir)) {
            bf_cli_err("%s: data folder not found (give --data DIR with "
                       "CURET's table.txt and abrdf.dat, or --input FILE; "
                       "scripts/curet-data.sh fetches CURET's files into a "
                       "cache and prints their folder; see README.md)",
                       src->data_dir);
            return BF_EXIT_NOINPUT;
        }
        in->curet = 1;
        snprintf(in->table_path, sizeof in->table_path, "%s/table.txt",
                 src->data_dir);
        if (src->brdf_file != NULL) {
            snprintf(in->brdf_path, sizeof in->brdf_path, "%s",
                     src->brdf_file);
        } else {
            snprintf(in->brdf_path, sizeof in->brdf_path, "%s/abrdf.dat",
                     src->data_dir);
        }
        snprintf(in->names_path, sizeof in->names_path, "%s/samples.tsv",
                 src->data_dir);
        if (!file_exists(in->names_path)) {
            in->names_path[0] = '\0';
        }
        if (bf_curet_load(src->data_dir, src->brdf_file, &in->ds, &err) !=
            BF_OK) {
            return bf_cli_load_error(&err);
        }
    } else {
        in->ds = bf_dataset_alloc();
        if (in->ds == NULL) {
            bf_cli_err("out of memory");
            return BF_EXIT_SOFTWARE;
        }
        for (i = 0; i < src->n_inputs; i++) {
            rc = load_input(src, src->inputs[i], in);
            if (rc != BF_EXIT_OK) {
                return rc;
            }
        }
    }
    if (n_file != NULL && bf_n_file_load(n_file, &in->n_file, &err) != BF_OK) {
        return bf_cli_load_error(&err);
    }
    if (on_file != NULL &&
        bf_on_params_load(on_file, &in->on_params, &err) != BF_OK) {
        return bf_cli_load_error(&err);
    }
    return BF_EXIT_OK;
}

void bf_cli_free_inputs(bf_cli_inputs *in)
{
    bf_dataset_free(in->ds);
    bf_sample_table_free(in->n_file);
    bf_sample_table_free(in->on_params);
    memset(in, 0, sizeof *in);
}

void bf_cli_source_init(bf_cli_source *src)
{
    memset(src, 0, sizeof *src);
    src->data_dir = getenv("BRDFFIT_DATA");
    if (src->data_dir == NULL || src->data_dir[0] == '\0') {
        src->data_dir = BF_DEFAULT_DATA_DIR;
    }
}

int bf_cli_parse_format(const char *cmd, const char *arg, bf_format *f)
{
    if (bf_format_find(arg, f) != BF_OK || *f == BF_FORMAT_MEMORY) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, cmd,
                                 "--input-format: '%s' is not pbrt, astm, "
                                 "merl, csv, curet or auto",
                                 arg);
    }
    return BF_EXIT_OK;
}

void bf_cli_file_args_usage(FILE *fp)
{
    fprintf(fp,
"  --input-format F  force the format (pbrt, astm, merl, csv, curet)\n"
"  --configs FILE|all  where a MERL table is sampled (default: CURET's\n"
"                    205 configurations from --data DIR/table.txt)\n"
"  --data DIR        CURET folder for MERL's default configurations\n"
"                    (default $BRDFFIT_DATA, else %s)\n"
"  -h, --help        show this help\n",
            BF_DEFAULT_DATA_DIR);
}

int bf_cli_file_args(const char *cmd, int argc, char **argv,
                     void (*usage)(FILE *fp), const char **to,
                     bf_cli_source *src, int *first)
{
    enum { O_FORMAT = 256, O_CONFIGS, O_DATA, O_TO };
    static const struct option longopts[] = {
        {"input-format", required_argument, NULL, O_FORMAT},
        {"format", required_argument, NULL, O_FORMAT},
        {"configs", required_argument, NULL, O_CONFIGS},
        {"data", required_argument, NULL, O_DATA},
        {"to", required_argument, NULL, O_TO},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    int c;
    bf_cli_source_init(src);
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":h", longopts, NULL)) != -1) {
        int rc = BF_EXIT_OK;
        switch (c) {
        case O_FORMAT: rc = bf_cli_parse_format(cmd, optarg, &src->format);
            break;
        case O_CONFIGS: src->configs = optarg; break;
        case O_DATA: src->data_dir = optarg; break;
        case O_TO:
            if (to == NULL) {
                return bf_cli_usage_error(cmd, "unknown option '--to'");
            }
            *to = optarg;
            break;
        case 'h': usage(stdout); return -1;
        case ':':
            return bf_cli_usage_fail(BF_EXIT_NOVALUE, cmd,
                                     "option '%s' needs a value",
                                     argv[optind - 1]);
        default:
            return bf_cli_usage_error(cmd, "unknown option '%s'",
                                      argv[optind - 1]);
        }
        if (rc != BF_EXIT_OK) {
            return rc;
        }
    }
    *first = optind;
    return BF_EXIT_OK;
}

void bf_cli_source_path(bf_cli_source *src, const char *path)
{
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        src->data_dir = path; /* a folder is CURET */
        src->n_inputs = 0;
    } else {
        src->inputs[0] = path;
        src->n_inputs = 1;
    }
}

