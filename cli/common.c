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

int bf_cli_parse_double(const char *s, double *out)
{
    char *end = NULL;
    double v;
    if (s == NULL || *s == '\0') {
        return -1;
    }
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        return -1;
    }
    *out = v;
    return 0;
}

static int parse_pos_int(const char *s, const char **end, long *v)
{
    char *e = NULL;
    if (*s < '0' || *s > '9') {
        return -1;
    }
    errno = 0;
    *v = strtol(s, &e, 10);
    if (errno == ERANGE || *v <= 0 || *v > INT_MAX) {
        return -1;
    }
    *end = e;
    return 0;
}

int bf_cli_parse_int_list(const char *s, int **out, size_t *n, char *msg,
                          size_t msglen)
{
    int *list = NULL;
    size_t len = 0;
    size_t cap = 0;
    const char *p = s;

    *out = NULL;
    *n = 0;
    if (s == NULL || *s == '\0') {
        snprintf(msg, msglen, "empty list");
        return -1;
    }
    while (*p != '\0') {
        long lo;
        long hi;
        long v;
        const char *e;
        if (parse_pos_int(p, &e, &lo) != 0) {
            snprintf(msg, msglen, "'%s': expected a positive number at '%s'",
                     s, p);
            goto fail;
        }
        hi = lo;
        if (*e == '-') {
            p = e + 1;
            if (parse_pos_int(p, &e, &hi) != 0 || hi < lo) {
                snprintf(msg, msglen, "'%s': bad range ending at '%s'", s, p);
                goto fail;
            }
        }
        if (*e != ',' && *e != '\0') {
            snprintf(msg, msglen, "'%s': unexpected '%c'", s, *e);
            goto fail;
        }
        if (hi - lo > 1000000) {
            snprintf(msg, msglen, "'%s': range too long", s);
            goto fail;
        }
        for (v = lo; v <= hi; v++) {
            size_t i;
            for (i = 0; i < len; i++) {
                if (list[i] == (int)v) {
                    snprintf(msg, msglen, "'%s': %ld is listed twice", s, v);
                    goto fail;
                }
            }
            if (len == cap) {
                size_t ncap = cap ? 2 * cap : 16;
                int *nl = realloc(list, ncap * sizeof *nl);
                if (nl == NULL) {
                    snprintf(msg, msglen, "out of memory");
                    free(list);
                    return -2;
                }
                list = nl;
                cap = ncap;
            }
            list[len++] = (int)v;
        }
        p = (*e == ',') ? e + 1 : e;
        if (*e == ',' && *p == '\0') {
            snprintf(msg, msglen, "'%s': trailing comma", s);
            goto fail;
        }
    }
    *out = list;
    *n = len;
    return 0;
fail:
    free(list);
    return -1;
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
    bf_table *t = NULL;
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
    if (bf_table_load(in->configs_path, &t, &err) != BF_OK) {
        return bf_cli_load_error(&err);
    }
    *n = bf_table_size(t);
    *angles = malloc(*n * 4 * sizeof **angles);
    if (*angles == NULL) {
        bf_table_free(t);
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    bf_table_angles(t, *angles);
    bf_table_free(t);
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

void bf_cli_material_label(const bf_dataset *ds, size_t m, char *buf,
                           size_t len)
{
    const char *name = bf_dataset_name(ds, m);
    if (name != NULL && name[0] != '\0') {
        snprintf(buf, len, "%d %s", bf_dataset_number(ds, m), name);
    } else {
        snprintf(buf, len, "%d", bf_dataset_number(ds, m));
    }
}

/* ==== atomic output files =============================================== */

int bf_cli_check_outdir(const char *dir)
{
    struct stat st;
    char parent[4096];
    char *slash;
    if (dir[0] == '\0') {
        bf_cli_err("--out: empty folder name");
        return BF_EXIT_CANTCREAT;
    }
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            bf_cli_err("%s: output path exists and is not a folder", dir);
            return BF_EXIT_CANTCREAT;
        }
        /* access() also reports EROFS, which root is not exempt from. */
        if (access(dir, W_OK | X_OK) != 0) {
            bf_cli_err("%s: output folder is not writable: %s", dir,
                       strerror(errno));
            return BF_EXIT_CANTCREAT;
        }
        return BF_EXIT_OK;
    }
    if (errno != ENOENT) {
        bf_cli_err("%s: cannot use as output folder: %s", dir,
                   strerror(errno));
        return BF_EXIT_CANTCREAT;
    }
    /* dir is missing: bf_cli_make_outdir creates one level, so its parent
     * must be a writable folder. */
    snprintf(parent, sizeof parent, "%s", dir);
    slash = strrchr(parent, '/');
    while (slash != NULL && slash > parent && slash[1] == '\0') {
        *slash = '\0'; /* "out/" names the folder out */
        slash = strrchr(parent, '/');
    }
    if (slash == NULL) {
        snprintf(parent, sizeof parent, ".");
    } else if (slash == parent) {
        parent[1] = '\0'; /* "/out": the parent is the root */
    } else {
        *slash = '\0';
    }
    if (stat(parent, &st) != 0 || !S_ISDIR(st.st_mode)) {
        bf_cli_err("%s: cannot create output folder: parent folder %s does "
                   "not exist",
                   dir, parent);
        return BF_EXIT_CANTCREAT;
    }
    /* Permission bits do not stop root, and some folders refuse new
     * entries whatever the user (/proc): try it, and take it back. */
    if (mkdir(dir, 0777) != 0) {
        bf_cli_err("%s: cannot create output folder: %s", dir,
                   strerror(errno));
        return BF_EXIT_CANTCREAT;
    }
    (void)rmdir(dir);
    return BF_EXIT_OK;
}

int bf_cli_make_outdir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            bf_cli_err("%s: output path exists and is not a folder", dir);
            return BF_EXIT_CANTCREAT;
        }
    } else if (mkdir(dir, 0777) != 0) {
        bf_cli_err("%s: cannot create output folder: %s", dir,
                   strerror(errno));
        return BF_EXIT_CANTCREAT;
    }
    if (access(dir, W_OK) != 0) {
        bf_cli_err("%s: output folder is not writable: %s", dir,
                   strerror(errno));
        return BF_EXIT_CANTCREAT;
    }
    return BF_EXIT_OK;
}

int bf_out_open(bf_out *o, const char *dir, const char *name)
{
    int fd;
    memset(o, 0, sizeof *o);
    snprintf(o->path, sizeof o->path, "%s/%s", dir, name);
    snprintf(o->tmp, sizeof o->tmp, "%s/.%s.XXXXXX", dir, name);
    fd = mkstemp(o->tmp);
    if (fd < 0) {
        bf_cli_err("%s: cannot create: %s", o->path, strerror(errno));
        o->tmp[0] = '\0';
        return BF_EXIT_CANTCREAT;
    }
    (void)fchmod(fd, 0644);
    o->fp = fdopen(fd, "w");
    if (o->fp == NULL) { /* fdopen fails only for want of memory */
        int e = errno;
        bf_cli_err("%s: cannot open: %s", o->path, strerror(e));
        close(fd);
        unlink(o->tmp);
        o->tmp[0] = '\0';
        return e == ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_CANTCREAT;
    }
    return BF_EXIT_OK;
}

int bf_out_commit(bf_out *o)
{
    int bad = ferror(o->fp);
    if (fflush(o->fp) != 0) {
        bad = 1;
    }
    if (fsync(fileno(o->fp)) != 0 && errno != EINVAL) {
        bad = 1;
    }
    if (fclose(o->fp) != 0) {
        bad = 1;
    }
    o->fp = NULL;
    if (bad) {
        bf_cli_err("%s: write failed: %s", o->path, strerror(errno));
        unlink(o->tmp);
        return BF_EXIT_IOERR;
    }
    if (rename(o->tmp, o->path) != 0) {
        bf_cli_err("%s: cannot rename into place: %s", o->path,
                   strerror(errno));
        unlink(o->tmp);
        return BF_EXIT_IOERR;
    }
    return BF_EXIT_OK;
}

void bf_out_abort(bf_out *o)
{
    if (o->fp != NULL) {
        fclose(o->fp);
        o->fp = NULL;
    }
    if (o->tmp[0] != '\0') {
        unlink(o->tmp);
        o->tmp[0] = '\0';
    }
}
