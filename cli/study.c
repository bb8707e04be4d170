/* study.c: the study pipeline shared by the fitting subcommands -- common
 * options, loading, selections of samples, models and configurations
 * (SPEC §1.4, §7), the run itself and the tables it writes (fits.csv,
 * table2.md, table3.md, and Tables 2 and 3 on standard output). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "study.h"
#include "texttable.h"

#define DEG (M_PI / 180.0)

/* Upper limit of --threads (a typo guard, not a machine limit). */
#define BF_CLI_MAX_THREADS 1024

/* The paper's models, the default of --models (Ragheb & Hancock, Table 3). */
static const char *const paper_models[] = {"VH-G", "VH-E", "FC-G",
                                           "FC-E", "ON",   "LFTG"};

void bf_cli_opts_usage(FILE *fp)
{
    fprintf(fp,
"  --data DIR        CURET folder with table.txt, abrdf.dat and optionally\n"
"                    samples.tsv (default $BRDFFIT_DATA, else %s)\n"
"  --brdf FILE       BRDF file with rows 'sample v1 ... v205' (default\n"
"                    DIR/abrdf.dat; rbrdf.dat, gbrdf.dat, bbrdf.dat work too)\n"
"  --samples SET     'paper' (the study's 24 samples, default), 'all', or a\n"
"                    list such as 1,5,7-9\n"
"  --models LIST     comma-separated model names, or 'all' (default\n"
"                    VH-G,VH-E,FC-G,FC-E,ON,LFTG); see 'brdffit models'\n"
"  --n VALUE         refractive index of the FC models (default %.1f)\n"
"  --n-file FILE     per-sample refractive index, rows 'sample n'\n"
"  --on-params FILE  Oren-Nayar rho, sigma per sample: rows 'sample rho\n"
"                    sigma [kd]' (CURET op.dat layout accepted)\n"
"  --exclude LIST    configuration numbers (1-205) to leave out besides the\n"
"                    7 specular ones, e.g. 1-4,17\n"
"  --max-theta DEG   leave out configurations with theta_i or theta_v above\n"
"                    DEG degrees (default 90: none)\n"
"  --fit MODE        'paper' (the paper's grids; default of compare) or\n"
"                    'exact' (grid, then GSL refinement; FC's n and ON's\n"
"                    rho, sigma fitted too; default of rank)\n"
"  --objective NAME  max (paper, default), scale, cosw or log (needs --fit\n"
"                    exact unless max); see doc/methods.md\n"
"  --range P=LO:HI   search range of parameter P, e.g. m=0.01:20 (grid\n"
"                    keeps its step; repeatable)\n"
"  --stats           with --fit paper, also the analysis beyond the paper:\n"
"                    refined optima, 95%% profile intervals, AIC, BIC, CV\n"
"                    (the analysis columns of fits.csv; always on with\n"
"                    --fit exact, --bootstrap and in rank)\n"
"  --bootstrap N     also a percentile bootstrap interval, N resamples\n"
"                    (default 0: profile intervals only)\n"
"  --folds K         K-fold cross-validation (default 10; 0 for none)\n"
"  --seed S          seed of the bootstrap and the folds (default 1)\n"
"  --out DIR         output folder (default out; created if missing)\n"
"  --threads N       fit on N threads (default 1; 0: one per core); the\n"
"                    results do not depend on N\n"
"  -q, --quiet       do not print the tables\n"
"  -h, --help        show this help\n",
            BF_DEFAULT_DATA_DIR, BF_DEFAULT_N);
}

/* ==== argument parsing =================================================== */

int bf_cli_opts_parse(const char *cmd, int argc, char **argv,
                      void (*usage)(FILE *fp), const bf_cli_extra *extra,
                      bf_cli_opts *o)
{
    enum { O_DATA = 256, O_BRDF, O_SAMPLES, O_MODELS, O_N, O_NFILE, O_ON,
           O_EXCLUDE, O_MAXTHETA, O_OUT, O_FIT, O_OBJECTIVE, O_RANGE,
           O_BOOTSTRAP, O_FOLDS, O_SEED, O_THREADS, O_STATS };
    static const struct option common[] = {
        {"data", required_argument, NULL, O_DATA},
        {"brdf", required_argument, NULL, O_BRDF},
        {"samples", required_argument, NULL, O_SAMPLES},
        {"models", required_argument, NULL, O_MODELS},
        {"n", required_argument, NULL, O_N},
        {"n-file", required_argument, NULL, O_NFILE},
        {"on-params", required_argument, NULL, O_ON},
        {"exclude", required_argument, NULL, O_EXCLUDE},
        {"max-theta", required_argument, NULL, O_MAXTHETA},
        {"out", required_argument, NULL, O_OUT},
        {"fit", required_argument, NULL, O_FIT},
        {"objective", required_argument, NULL, O_OBJECTIVE},
        {"range", required_argument, NULL, O_RANGE},
        {"bootstrap", required_argument, NULL, O_BOOTSTRAP},
        {"folds", required_argument, NULL, O_FOLDS},
        {"seed", required_argument, NULL, O_SEED},
        {"stats", no_argument, NULL, O_STATS},
        {"threads", required_argument, NULL, O_THREADS},
        {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'}};
    struct option longopts[64];
    size_t n_long = sizeof common / sizeof *common;
    char hint[64];
    int c;

    memcpy(longopts, common, sizeof common);
    if (extra != NULL && extra->longopts != NULL) {
        const struct option *e;
        for (e = extra->longopts; e->name != NULL && n_long < 63; e++) {
            longopts[n_long++] = *e;
        }
    }
    memset(&longopts[n_long], 0, sizeof longopts[n_long]);
    snprintf(hint, sizeof hint, "%s ", cmd);

    memset(o, 0, sizeof *o);
    o->data_dir = getenv("BRDFFIT_DATA");
    if (o->data_dir == NULL || o->data_dir[0] == '\0') {
        o->data_dir = BF_DEFAULT_DATA_DIR;
    }
    o->samples = "paper";
    o->out_dir = "out";
    o->n = BF_DEFAULT_N;
    o->max_theta = 90.0;
    o->folds = 10;
    o->seed = 1;
    o->threads = 1;

    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, ":qh", longopts, NULL)) != -1) {
        switch (c) {
        case O_DATA: o->data_dir = optarg; break;
        case O_BRDF: o->brdf_file = optarg; break;
        case O_SAMPLES: o->samples = optarg; o->samples_given = 1; break;
        case O_MODELS: o->models = optarg; break;
        case O_NFILE: o->n_file = optarg; break;
        case O_ON: o->on_file = optarg; break;
        case O_EXCLUDE: o->exclude = optarg; break;
        case O_OUT: o->out_dir = optarg; break;
        case 'q': o->quiet = 1; break;
        case 'h': usage(stdout); return -1;
        case O_N:
            if (bf_cli_parse_double(optarg, &o->n) != 0 || o->n <= 1.0 ||
                o->n > 10.0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--n: '%s' is not a "
                                          "refractive index in (1, 10]",
                                          optarg);
            }
            o->n_given = 1;
            break;
        case O_THREADS: {
            double t = -1.0;
            if (bf_cli_parse_double(optarg, &t) != 0 || t < 0.0 ||
                t > BF_CLI_MAX_THREADS || t != floor(t)) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--threads: '%s' is not a "
                                          "whole number in [0, %d]",
                                          optarg, BF_CLI_MAX_THREADS);
            }
            o->threads = (int)t;
            break;
        }
        case O_MAXTHETA:
            if (bf_cli_parse_double(optarg, &o->max_theta) != 0 ||
                o->max_theta <= 0.0 || o->max_theta > 90.0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--max-theta: '%s' is "
                                          "not an angle in (0, 90] degrees",
                                          optarg);
            }
            break;
        case O_STATS: o->stats = 1; break;
        case O_FIT:
            if (strcmp(optarg, "paper") != 0 && strcmp(optarg, "exact") != 0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--fit: '%s' is not 'paper' "
                                          "or 'exact'", optarg);
            }
            o->exact = strcmp(optarg, "exact") == 0;
            o->fit_given = 1;
            break;
        case O_OBJECTIVE:
            if (bf_objective_find(optarg, &o->objective) != BF_OK) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--objective: '%s' is not "
                                          "max, scale, cosw or log", optarg);
            }
            break;
        case O_RANGE: {
            char name[32];
            char msg[128];
            double lo;
            double hi;
            if (o->n_range == BF_CLI_MAX_RANGES) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--range: at most %d",
                                          BF_CLI_MAX_RANGES);
            }
            if (bf_cli_parse_range(optarg, name, sizeof name, &lo, &hi, msg,
                                   sizeof msg) != 0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--range: %s", msg);
            }
            o->range[o->n_range++] = optarg;
            break;
        }
        case O_BOOTSTRAP:
        case O_FOLDS:
        case O_SEED: {
            int *list = NULL;
            size_t count = 0;
            char msg[128];
            int zero = strcmp(optarg, "0") == 0;
            if (!zero && (bf_cli_parse_int_list(optarg, &list, &count, msg,
                                                sizeof msg) != 0 ||
                          count != 1 || strchr(optarg, ',') != NULL ||
                          strchr(optarg, '-') != NULL)) {
                free(list);
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "%s: '%s' is not a "
                                          "non-negative integer",
                                          argv[optind - 2], optarg);
            }
            if (c == O_BOOTSTRAP) {
                o->n_boot = zero ? 0 : (size_t)list[0];
            } else if (c == O_FOLDS) {
                o->folds = zero ? 0 : (size_t)list[0];
            } else {
                o->seed = zero ? 0 : (unsigned long)list[0];
            }
            free(list);
            break;
        }
        case ':':
            return bf_cli_usage_fail(BF_EXIT_NOVALUE, hint,
                                     "option '%s' needs a value",
                                      argv[optind - 1]);
        case '?':
            return bf_cli_usage_error(hint, "unknown option '%s'",
                                      argv[optind - 1]);
        default: {
            int rc = extra != NULL ? extra->handle(c, optarg, extra->ctx)
                                   : BF_EXIT_SOFTWARE;
            if (rc != 0) {
                return rc;
            }
            break;
        }
        }
    }
    if (optind < argc) {
        return bf_cli_usage_error(hint, "unexpected argument '%s'",
                                  argv[optind]);
    }
    if (o->n_given && o->n_file != NULL) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, hint,
                                 "--n and --n-file cannot be combined");
    }
    if (!o->exact && o->objective != BF_OBJ_MAX) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, hint, "--objective %s needs --fit exact "
                                  "(the paper's protocol minimises max)",
                                  bf_objective_name(o->objective));
    }
    if (o->n_boot == 1 || o->folds == 1) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--bootstrap and --folds need at "
                                  "least 2 (or 0 for none)");
    }
    return 0;
}

/* Parses --samples before any file is read (usage errors come first). A
 * list is returned in *out; 'paper' gives the study's samples; 'all' gives
 * *out = NULL, resolved by resolve_samples once the BRDF file is read. */
static int parse_samples(const char *hint, const bf_cli_opts *o, int **out, size_t *n)
{
    char msg[256];
    *out = NULL;
    *n = 0;
    if (strcmp(o->samples, "all") == 0) {
        return BF_EXIT_OK;
    }
    if (strcmp(o->samples, "paper") == 0) {
        *out = malloc(sizeof bf_study_samples);
        if (*out == NULL) {
            return BF_EXIT_SOFTWARE;
        }
        memcpy(*out, bf_study_samples, sizeof bf_study_samples);
        *n = BF_STUDY_NSAMPLES;
        return BF_EXIT_OK;
    }
    if (bf_cli_parse_int_list(o->samples, out, n, msg, sizeof msg) != 0) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--samples: %s",
                                 msg);
    }
    return BF_EXIT_OK;
}

/* Fills in 'all' and checks that every listed sample is in the file. */
static int resolve_samples(const char *hint, const bf_brdf *brdf,
                           int **samples, size_t *n)
{
    size_t i;
    if (*samples == NULL) {
        *n = bf_brdf_count(brdf);
        *samples = malloc((*n ? *n : 1) * sizeof **samples);
        if (*samples == NULL) {
            return BF_EXIT_SOFTWARE;
        }
        for (i = 0; i < *n; i++) {
            (*samples)[i] = bf_brdf_sample(brdf, i);
        }
    }
    for (i = 0; i < *n; i++) {
        if (bf_brdf_find(brdf, (*samples)[i]) < 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                     "--samples: sample %d is not in the "
                                     "BRDF file (it has samples 1-%zu)",
                                     (*samples)[i], bf_brdf_count(brdf));
        }
    }
    return BF_EXIT_OK;
}

static int select_models(const char *hint, const bf_cli_opts *o, const bf_model_type ***out,
                         size_t *n)
{
    const bf_model_type **list;
    size_t cap = bf_model_count() + 1;
    size_t i;
    *n = 0;
    list = calloc(cap, sizeof *list);
    *out = list;
    if (list == NULL) {
        return BF_EXIT_SOFTWARE;
    }
    if (o->models == NULL) {
        for (i = 0; i < sizeof paper_models / sizeof *paper_models; i++) {
            list[(*n)++] = bf_model_find(paper_models[i]);
        }
    } else if (strcmp(o->models, "all") == 0) {
        for (i = 0; i < bf_model_count(); i++) {
            list[(*n)++] = bf_model_get(i);
        }
    } else {
        const char *p = o->models;
        while (*p != '\0') {
            char name[64];
            size_t len = strcspn(p, ",");
            const bf_model_type *t;
            size_t j;
            if (len == 0 || len >= sizeof name) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--models: bad list "
                                          "'%s'", o->models);
            }
            memcpy(name, p, len);
            name[len] = '\0';
            t = bf_model_find(name);
            if (t == NULL) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--models: unknown "
                                          "model '%s' (see 'brdffit models')",
                                          name);
            }
            for (j = 0; j < *n; j++) {
                if (list[j] == t) {
                    return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                             "--models: '%s' "
                                              "listed twice", name);
                }
            }
            if (*n + 1 >= cap) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--models: too many");
            }
            list[(*n)++] = t;
            p += len;
            if (*p == ',') {
                p++;
                if (*p == '\0') {
                    return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                             "--models: trailing "
                                              "comma");
                }
            }
        }
    }
    return BF_EXIT_OK;
}

/* Fills sel with the used configurations: SPEC §1.4 (non-specular), within
 * --max-theta, minus --exclude. */
static int select_configs(const char *hint, const bf_cli_opts *o,
                          const int *ex, size_t n_ex, const bf_table *t,
                          size_t *sel, size_t *n)
{
    size_t i;
    size_t j;
    size_t k = 0;
    size_t size = bf_table_size(t);

    *n = bf_table_select(t, o->max_theta * DEG, sel);
    for (j = 0; j < n_ex; j++) {
        if ((size_t)ex[j] > size) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                     "--exclude: configuration %d does "
                                     "not exist (the table has %zu)",
                                     ex[j], size);
        }
    }
    for (i = 0; i < *n; i++) {
        int keep = 1;
        for (j = 0; j < n_ex; j++) {
            if ((size_t)ex[j] == sel[i] + 1) {
                keep = 0;
            }
        }
        if (keep) {
            sel[k++] = sel[i];
        }
    }
    *n = k;
    if (k == 0) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                 "--exclude/--max-theta: no configuration "
                                 "is left to fit");
    }
    return BF_EXIT_OK;
}

/* ==== the run ============================================================= */

int bf_cli_study_prepare(bf_cli_study *st)
{
    const bf_cli_opts *o = &st->opts;
    char hint[64];
    int rc;

    snprintf(hint, sizeof hint, "%s ", st->cmd);
    rc = select_models(hint, o, &st->models, &st->n_models);
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_exact_models(st); /* variants of --fit exact, --range */
    }
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = parse_samples(hint, o, &st->samples, &st->n_samples);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    if (o->exclude != NULL) { /* syntax now; range once the table is read */
        char msg[256];
        if (bf_cli_parse_int_list(o->exclude, &st->exclude, &st->n_exclude,
                                  msg, sizeof msg) != 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--exclude: %s",
                                     msg);
        }
    }
    rc = bf_cli_check_outdir(o->out_dir); /* fail before the work */
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = bf_cli_load_inputs(o->data_dir, o->brdf_file, o->n_file, o->on_file,
                            &st->in);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rc = resolve_samples(hint, st->in.brdf, &st->samples, &st->n_samples);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    st->sel = malloc(bf_table_size(st->in.table) * sizeof *st->sel);
    st->rows = calloc(st->n_samples * st->n_models + 1, sizeof *st->rows);
    if (st->sel == NULL || st->rows == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    rc = select_configs(hint, o, st->exclude, st->n_exclude, st->in.table,
                        st->sel, &st->n_sel);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    memset(&st->spec, 0, sizeof st->spec);
    st->spec.table = st->in.table;
    st->spec.brdf = st->in.brdf;
    st->spec.sel = st->sel;
    st->spec.n_sel = st->n_sel;
    st->spec.samples = st->samples;
    st->spec.n_samples = st->n_samples;
    st->spec.models = st->models;
    st->spec.n_models = st->n_models;
    st->spec.n_default = o->n;
    st->spec.n_file = st->in.n_file;
    st->spec.on_params = st->in.on_params;
    st->spec.n_threads = o->threads;
    if (o->threads == 0) { /* one per core */
        long cores = sysconf(_SC_NPROCESSORS_ONLN);
        st->spec.n_threads = cores > 0 && cores <= BF_CLI_MAX_THREADS
                                 ? (int)cores
                                 : 1;
    }
    return BF_EXIT_OK;
}

/* A row whose model could not be normalised on the used configurations
 * (BF_EDOM: undefined at one of them, e.g. BK at theta_i = 90 deg, SPEC
 * §3.3, or zero at all of them, SPEC §2) is an error, not a gap in the
 * tables; a missing per-sample input (BF_ENOTFOUND) is a noted gap. */
static int check_rows(const bf_cli_study *st)
{
    size_t i;
    for (i = 0; i < st->n_samples * st->n_models; i++) {
        const bf_study_row *r = &st->rows[i];
        if (r->status == BF_OK || r->status == BF_ENOTFOUND) {
            continue;
        }
        if (r->status == BF_ENOMEM) {
            bf_cli_err("out of memory");
            return BF_EXIT_SOFTWARE;
        }
        bf_cli_err("%s cannot be fitted to sample %d: the model is "
                   "undefined at some of the K = %zu used configurations or "
                   "zero at all of them, so it cannot be normalised (SPEC "
                   "§2); leave configurations out with --exclude or "
                   "--max-theta",
                   r->type->name, r->sample, st->n_sel);
        return BF_EXIT_DATAERR;
    }
    return BF_EXIT_OK;
}

int bf_cli_study_run(bf_cli_study *st)
{
    bf_error err;
    if (!st->opts.exact &&
        bf_study_run(&st->spec, st->rows, &err) != BF_OK) {
        bf_cli_err("%s", err.msg);
        return err.code == BF_ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_DATAERR;
    }
    /* The analysis beyond the paper (refinement, intervals, AIC, BIC, CV;
     * with --fit exact also the study itself) runs with --fit exact,
     * --stats or --bootstrap: the paper's protocol alone stays the fast
     * default of compare and report. */
    if (st->opts.exact || st->opts.stats || st->opts.n_boot > 0) {
        int rc = bf_cli_exact_run(st);
        if (rc != BF_EXIT_OK) {
            return rc;
        }
    }
    return check_rows(st);
}

void bf_cli_study_free(bf_cli_study *st)
{
    free(st->rows);
    free(st->stats);
    free(st->variants);
    free(st->exclude);
    free(st->sel);
    free(st->models);
    free(st->samples);
    bf_cli_free_inputs(&st->in);
    st->rows = NULL;
    st->stats = NULL;
    st->variants = NULL;
    st->exclude = NULL;
    st->sel = NULL;
    st->models = NULL;
    st->samples = NULL;
}

/* ==== tables ============================================================== */

/* Table 2 shows fitted parameters, or the inputs of a model that fits
 * none (ON). */
int bf_cli_shows_param(const bf_model_type *type, size_t j)
{
    size_t i;
    if (type->param[j].fitted) {
        return 1;
    }
    for (i = 0; i < type->p; i++) {
        if (type->param[i].fitted) {
            return 0;
        }
    }
    return 1;
}

const char *bf_cli_sample_name(const bf_cli_study *st, int sample)
{
    const char *nm = bf_names_get(st->in.names, sample);
    return nm != NULL ? nm : "";
}

void bf_cli_study_describe(const bf_cli_study *st, FILE *fp)
{
    const bf_cli_opts *o = &st->opts;
    const bf_cli_inputs *in = &st->in;
    const size_t *sel = st->sel;
    size_t n_sel = st->n_sel;
    size_t k;
    size_t j = 0;
    size_t size = bf_table_size(in->table);
    fprintf(fp, "Data: %s (%zu samples), %s\n", in->brdf_path,
            bf_brdf_count(in->brdf), in->table_path);
    fprintf(fp, "Configurations: K = %zu of %zu used; left out:", n_sel,
            size);
    for (k = 0; k < size; k++) {
        if (j < n_sel && sel[j] == k) {
            j++;
            continue;
        }
        fprintf(fp, " %zu", k + 1);
    }
    fprintf(fp, "\nNormalisation: radiance = BRDF x cos(theta_i), divided by "
                "its maximum over the K used configurations (SPEC §2)\n");
    if (!o->exact) {
        fprintf(fp, "Fit: exhaustive 501-point grids (SPEC §7.4), LSE = sum "
                    "of squared differences\n");
    }
    bf_cli_exact_describe(st, fp);
    if (o->n_file != NULL) {
        fprintf(fp, "Refractive index (FC): per sample from %s\n", o->n_file);
    } else if (!o->exact || o->n_given) {
        fprintf(fp, "Refractive index (FC): n = %g\n", o->n);
    }
    if (o->on_file != NULL) {
        fprintf(fp, "Oren-Nayar: rho, sigma %s %s\n",
                o->exact ? "fitted; tabulated values (compared) from"
                         : "from",
                o->on_file);
    }
    fputc('\n', fp);
}

static int build_tables(const bf_cli_study *st, bf_tt **t2, bf_tt **t3)
{
    const bf_study_spec *spec = &st->spec;
    const bf_study_row *rows = st->rows;
    size_t ncols2 = 2;
    size_t m;
    size_t j;
    size_t s;
    size_t c;

    for (m = 0; m < spec->n_models; m++) {
        for (j = 0; j < spec->models[m]->p; j++) {
            ncols2 += (size_t)bf_cli_shows_param(spec->models[m], j);
        }
    }
    *t2 = bf_tt_alloc(ncols2);
    *t3 = bf_tt_alloc(2 + spec->n_models);
    if (*t2 == NULL || *t3 == NULL) {
        return -1;
    }
    bf_tt_header(*t2, 0, "No.");
    bf_tt_header(*t2, 1, "Sample");
    bf_tt_header(*t3, 0, "No.");
    bf_tt_header(*t3, 1, "Sample");
    bf_tt_right(*t2, 0);
    bf_tt_right(*t3, 0);
    c = 2;
    for (m = 0; m < spec->n_models; m++) {
        const bf_model_type *type = spec->models[m];
        char head[128];
        for (j = 0; j < type->p; j++) {
            if (bf_cli_shows_param(type, j)) {
                snprintf(head, sizeof head, "%s %s", type->name,
                         type->param[j].label);
                bf_tt_header(*t2, c, head);
                bf_tt_right(*t2, c++);
            }
        }
        bf_tt_header(*t3, 2 + m, type->name);
        bf_tt_right(*t3, 2 + m);
    }
    for (s = 0; s < spec->n_samples; s++) {
        int sample = spec->samples[s];
        if (bf_tt_add_row(*t2) != 0 || bf_tt_add_row(*t3) != 0) {
            return -1;
        }
        bf_tt_set(*t2, 0, "%d", sample);
        bf_tt_set(*t2, 1, "%s", bf_cli_sample_name(st, sample));
        bf_tt_set(*t3, 0, "%d", sample);
        bf_tt_set(*t3, 1, "%s", bf_cli_sample_name(st, sample));
        c = 2;
        for (m = 0; m < spec->n_models; m++) {
            const bf_study_row *r = &rows[s * spec->n_models + m];
            for (j = 0; j < r->type->p; j++) {
                if (!bf_cli_shows_param(r->type, j)) {
                    continue;
                }
                if (r->status != BF_OK) {
                    bf_tt_set(*t2, c++, "-");
                } else if (st->opts.exact && r->type->param[j].fitted) {
                    /* exact optimum (grid optimum), side by side */
                    bf_tt_set(*t2, c++, "%.4f (%.2f)%s", r->fit.param[j],
                              st->stats[s * spec->n_models + m]
                                  .grid.param[j],
                              (r->fit.bound_hit & (1u << j)) ? "*" : "");
                } else {
                    bf_tt_set(*t2, c++, "%.2f%s", r->fit.param[j],
                              (r->fit.bound_hit & (1u << j)) ? "*" : "");
                }
            }
            if (r->status != BF_OK) {
                bf_tt_set(*t3, 2 + m, "-");
            } else {
                bf_tt_set(*t3, 2 + m, st->opts.exact ? "%.4f" : "%.2f",
                          r->fit.lse);
            }
        }
    }
    return 0;
}

void bf_cli_csv_field(FILE *fp, const char *s)
{
    if (strpbrk(s, ",\"\n\r") == NULL) {
        fputs(s, fp);
        return;
    }
    fputc('"', fp);
    for (; *s != '\0'; s++) {
        if (*s == '"') {
            fputc('"', fp);
        }
        fputc(*s, fp);
    }
    fputc('"', fp);
}

/* fits.csv: one row per (sample, model, fitted parameter); a model with no
 * fitted parameter has one row with parameter and value empty. */
static void write_csv(FILE *fp, const bf_cli_study *st)
{
    const bf_study_spec *spec = &st->spec;
    const bf_study_row *rows = st->rows;
    size_t i;
    fputs("sample,name,model,parameter,unit,value,lse,bound_hit,k", fp);
    bf_cli_exact_csv_header(fp); /* columns added at the end */
    fputc('\n', fp);
    for (i = 0; i < spec->n_samples * spec->n_models; i++) {
        const bf_study_row *r = &rows[i];
        size_t j;
        int any = 0;
        if (r->status != BF_OK) {
            continue;
        }
        for (j = 0; j < r->type->p; j++) {
            if (!r->type->param[j].fitted) {
                continue;
            }
            any = 1;
            fprintf(fp, "%d,", r->sample);
            bf_cli_csv_field(fp, bf_cli_sample_name(st, r->sample));
            fprintf(fp, ",%s,%s,%s,%.10g,%.10g,%d,%zu", r->type->name,
                    r->type->param[j].name, r->type->param[j].unit,
                    r->fit.param[j], r->fit.lse,
                    (r->fit.bound_hit & (1u << j)) ? 1 : 0, spec->n_sel);
            bf_cli_exact_csv_cols(st, i, j, fp);
            fputc('\n', fp);
        }
        if (!any) {
            fprintf(fp, "%d,", r->sample);
            bf_cli_csv_field(fp, bf_cli_sample_name(st, r->sample));
            fprintf(fp, ",%s,,,,%.10g,0,%zu", r->type->name, r->fit.lse,
                    spec->n_sel);
            bf_cli_exact_csv_cols(st, i, SIZE_MAX, fp);
            fputc('\n', fp);
        }
    }
}

static int any_bound_hit(const bf_study_spec *spec, const bf_study_row *rows)
{
    size_t i;
    for (i = 0; i < spec->n_samples * spec->n_models; i++) {
        if (rows[i].status == BF_OK && rows[i].fit.bound_hit != 0) {
            return 1;
        }
    }
    return 0;
}

static void report_missing(const bf_study_spec *spec,
                           const bf_study_row *rows)
{
    size_t m;
    size_t s;
    for (m = 0; m < spec->n_models; m++) {
        size_t missing = 0;
        for (s = 0; s < spec->n_samples; s++) {
            missing += rows[s * spec->n_models + m].status != BF_OK;
        }
        if (missing > 0) {
            bf_cli_err("note: %s not evaluated for %zu of %zu samples (%s)",
                       spec->models[m]->name, missing, spec->n_samples,
                       strcmp(spec->models[m]->name, "ON") == 0
                           ? "no rho, sigma given: use --on-params"
                           : "missing per-sample input");
        }
    }
}

static int write_outputs(const bf_cli_study *st, const bf_tt *t2,
                         const bf_tt *t3)
{
    const bf_cli_opts *o = &st->opts;
    bf_out f[3];
    size_t i;
    size_t opened = 0;
    int rc = bf_cli_make_outdir(o->out_dir);
    static const char *const names[3] = {"fits.csv", "table2.md",
                                         "table3.md"};
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    for (i = 0; i < 3; i++) {
        rc = bf_out_open(&f[i], o->out_dir, names[i]);
        if (rc != BF_EXIT_OK) {
            goto fail;
        }
        opened++;
    }
    write_csv(f[0].fp, st);
    fputs(o->exact ? "Table 2: fitted parameters (exact optimum (grid "
                     "optimum); * on a bound of the search range)\n\n"
                   : "Table 2: fitted parameters (grid optima; * on a grid "
                     "bound)\n\n",
          f[1].fp);
    bf_tt_print(t2, f[1].fp);
    fputs("Table 3: LSE (sum over the K used configurations)\n\n", f[2].fp);
    bf_tt_print(t3, f[2].fp);
    for (i = 0; i < 3; i++) {
        rc = bf_out_commit(&f[i]);
        if (rc != BF_EXIT_OK) {
            opened = 3; /* the committed ones stay; abort the rest */
            for (i = i + 1; i < 3; i++) {
                bf_out_abort(&f[i]);
            }
            return rc;
        }
    }
    return BF_EXIT_OK;
fail:
    for (i = 0; i < opened; i++) {
        bf_out_abort(&f[i]);
    }
    return rc;
}

int bf_cli_study_write_tables(const bf_cli_study *st)
{
    bf_tt *t2 = NULL;
    bf_tt *t3 = NULL;
    int rc;

    report_missing(&st->spec, st->rows);
    if (build_tables(st, &t2, &t3) != 0) {
        bf_cli_err("out of memory");
        rc = BF_EXIT_SOFTWARE;
        goto done;
    }
    rc = write_outputs(st, t2, t3);
    if (rc != BF_EXIT_OK || st->opts.quiet) {
        goto done;
    }
    bf_cli_study_describe(st, stdout);
    printf("Table 2: fitted parameters (%s%s)\n\n",
           st->opts.exact ? "exact optimum (grid optimum)" : "grid optima",
           any_bound_hit(&st->spec, st->rows)
               ? (st->opts.exact ? "; * on a bound of the search range"
                                 : "; * on a grid bound")
               : "");
    bf_tt_print(t2, stdout);
    printf("\nTable 3: %s (sum over the K = %zu used configurations)\n\n",
           st->opts.objective == BF_OBJ_MAX ? "LSE" : "objective S",
           st->n_sel);
    bf_tt_print(t3, stdout);
    bf_cli_exact_on_compare(st, stdout);
    printf("\nWritten: %s/fits.csv, %s/table2.md, %s/table3.md\n",
           st->opts.out_dir, st->opts.out_dir, st->opts.out_dir);
done:
    bf_tt_free(t2);
    bf_tt_free(t3);
    return rc;
}
