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
"Data (a CURET folder, or --input files in any format; README 'Data'):\n"
"  --data DIR        CURET folder with table.txt, abrdf.dat and optionally\n"
"                    samples.tsv (default $BRDFFIT_DATA, else %s)\n"
"  --brdf FILE       CURET BRDF file with rows 'sample v1 ... vN' (default\n"
"                    DIR/abrdf.dat; rbrdf.dat, gbrdf.dat, bbrdf.dat work too)\n"
"  --input FILE      measurements in another format (repeatable, at most\n"
"                    %d): pbrt-v2/Cornell .brdf, ASTM E1392 .astm, MERL\n"
"                    .binary, tidy CSV; one material per file (CSV: one or\n"
"                    more), numbered 1, 2, ... in input order\n"
"  --input-format F  force the format of every --input: pbrt, astm, merl,\n"
"                    csv, curet (default: detected from the content)\n"
"  --configs FILE|all  where a MERL table is sampled: the angles of a CSV\n"
"                    file, or every valid cell (default: CURET's 205\n"
"                    configurations, from DIR/table.txt)\n"
"  --channel C       channel to fit: 'mean' (of all channels, default), a\n"
"                    channel name (R, G, B) or wavelength (550), or 'each'\n"
"                    (every channel, one set of rows per channel)\n"
"  --samples SET     'paper' (the study's 24 CURET samples; the default on\n"
"                    CURET), 'all' (the default for --input), or a list of\n"
"                    sample numbers such as 1,5,7-9\n"
"\n"
"Configurations:\n"
"  --exclude-specular DEG  leave out every configuration within DEG degrees\n"
"                    of the mirror direction (SPEC §1.6; default: CURET's 7\n"
"                    specular configurations on CURET, none on other data)\n"
"  --exclude LIST    configuration numbers (1-based, in each material's\n"
"                    order) to leave out as well, e.g. 1-4,17\n"
"  --max-theta DEG   leave out configurations with theta_i or theta_o above\n"
"                    DEG degrees (default 90: none)\n"
"\n"
"Models and fitting:\n"
"  --models LIST     comma-separated model names, or 'all' (default\n"
"                    VH-G,VH-E,FC-G,FC-E,ON,LFTG); see 'brdffit models'\n"
"  --n VALUE         refractive index of the FC models (default %.1f)\n"
"  --n-file FILE     per-sample refractive index, rows 'sample n'\n"
"  --on-params FILE  Oren-Nayar rho, sigma per sample: rows 'sample rho\n"
"                    sigma [kd]' (CURET op.dat layout accepted)\n"
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
"\n"
"Output:\n"
"  --out DIR         output folder (default out; created if missing)\n"
"  --threads N       fit on N threads (default 1; 0: one per core); the\n"
"                    results do not depend on N\n"
"  -q, --quiet       do not print the tables\n"
"  -h, --help        show this help\n",
            BF_DEFAULT_DATA_DIR, BF_CLI_MAX_INPUTS, BF_DEFAULT_N);
}

/* ==== argument parsing =================================================== */

int bf_cli_opts_parse(const char *cmd, int argc, char **argv,
                      void (*usage)(FILE *fp), const bf_cli_extra *extra,
                      bf_cli_opts *o)
{
    enum { O_DATA = 256, O_BRDF, O_SAMPLES, O_MODELS, O_N, O_NFILE, O_ON,
           O_EXCLUDE, O_MAXTHETA, O_OUT, O_FIT, O_OBJECTIVE, O_RANGE,
           O_BOOTSTRAP, O_FOLDS, O_SEED, O_THREADS, O_STATS, O_INPUT,
           O_INFORMAT, O_CONFIGS, O_CHANNEL, O_CONE };
    static const struct option common[] = {
        {"data", required_argument, NULL, O_DATA},
        {"brdf", required_argument, NULL, O_BRDF},
        {"input", required_argument, NULL, O_INPUT},
        {"input-format", required_argument, NULL, O_INFORMAT},
        {"configs", required_argument, NULL, O_CONFIGS},
        {"channel", required_argument, NULL, O_CHANNEL},
        {"exclude-specular", required_argument, NULL, O_CONE},
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
    bf_cli_source_init(&o->src);
    o->cone = -1.0;
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
        case O_DATA: o->src.data_dir = optarg; break;
        case O_BRDF: o->src.brdf_file = optarg; break;
        case O_INPUT:
            if (o->src.n_inputs == BF_CLI_MAX_INPUTS) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--input: at most %d files",
                                         BF_CLI_MAX_INPUTS);
            }
            o->src.inputs[o->src.n_inputs++] = optarg;
            break;
        case O_INFORMAT: {
            int rc = bf_cli_parse_format(hint, optarg, &o->src.format);
            if (rc != BF_EXIT_OK) {
                return rc;
            }
            break;
        }
        case O_CONFIGS: o->src.configs = optarg; break;
        case O_CHANNEL: o->channel = optarg; break;
        case O_CONE:
            if (bf_cli_parse_double(optarg, &o->cone) != 0 ||
                o->cone < 0.0 || o->cone >= 90.0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--exclude-specular: '%s' is not "
                                         "an angle in [0, 90) degrees",
                                         optarg);
            }
            break;
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
    if (o->src.n_inputs > 0 && o->src.brdf_file != NULL) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, hint,
                                 "--brdf (CURET) and --input cannot be "
                                 "combined");
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

/* Parses --samples before any file is read (usage errors come first): a
 * list goes to *out; 'paper' and 'all' leave *out NULL and set *mode, and
 * are resolved by resolve_samples once the data are read. */
enum { SAMPLES_DEFAULT, SAMPLES_PAPER, SAMPLES_ALL, SAMPLES_LIST };

static int parse_samples(const char *hint, const bf_cli_opts *o, int **out,
                         size_t *n, int *mode)
{
    char msg[256];
    *out = NULL;
    *n = 0;
    *mode = SAMPLES_DEFAULT;
    if (o->samples == NULL) {
        return BF_EXIT_OK;
    }
    if (strcmp(o->samples, "all") == 0) {
        *mode = SAMPLES_ALL;
        return BF_EXIT_OK;
    }
    if (strcmp(o->samples, "paper") == 0) {
        *mode = SAMPLES_PAPER;
        return BF_EXIT_OK;
    }
    *mode = SAMPLES_LIST;
    if (bf_cli_parse_int_list(o->samples, out, n, msg, sizeof msg) != 0) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--samples: %s",
                                 msg);
    }
    return BF_EXIT_OK;
}

/* The materials (dataset indices) of --samples: the paper's 24 on CURET by
 * default, every material otherwise; a list names material numbers. */
static int resolve_samples(const char *hint, const bf_cli_inputs *in,
                           int mode, const int *list, size_t n_list,
                           size_t **out, size_t *n)
{
    const bf_dataset *ds = in->ds;
    size_t count = bf_dataset_count(ds);
    size_t i;
    if (mode == SAMPLES_DEFAULT) {
        mode = in->curet ? SAMPLES_PAPER : SAMPLES_ALL;
    }
    if (mode == SAMPLES_PAPER) {
        if (!in->curet) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                     "--samples paper: the paper's samples "
                                     "are CURET samples; give 'all' or a "
                                     "list of sample numbers");
        }
        list = bf_study_samples;
        n_list = BF_STUDY_NSAMPLES;
    }
    *n = mode == SAMPLES_ALL ? count : n_list;
    *out = malloc((*n + 1) * sizeof **out);
    if (*out == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    for (i = 0; i < *n; i++) {
        long m = mode == SAMPLES_ALL ? (long)i : bf_dataset_find(ds, list[i]);
        if (m < 0) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                     "--samples: sample %d is not in the %s "
                                     "(it has samples 1-%zu)",
                                     list[i],
                                     in->curet ? "BRDF file" : "data", count);
        }
        (*out)[i] = (size_t)m;
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

/* The selection of spec (SPEC §1.4, §1.6, --max-theta, --exclude) for
 * every target: its K and how many the cone left out. An excluded number
 * beyond a material's configurations, or a target left with nothing, is a
 * usage error. */
static int select_configs(const char *hint, bf_cli_study *st)
{
    const bf_dataset *ds = st->in.ds;
    size_t *sel = NULL;
    size_t cap = 0;
    size_t s;
    size_t j;
    int rc = BF_EXIT_OK;

    st->k = calloc(st->n_samples + 1, sizeof *st->k);
    st->n_cone = calloc(st->n_samples + 1, sizeof *st->n_cone);
    if (st->k == NULL || st->n_cone == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    for (s = 0; s < st->n_samples && rc == BF_EXIT_OK; s++) {
        size_t m = st->targets[s].material;
        size_t nconf = bf_dataset_nconf(ds, m);
        char who[256];
        bf_cli_material_label(ds, m, who, sizeof who);
        for (j = 0; j < st->n_exclude; j++) {
            if (st->exclude[j] > nconf) {
                rc = bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                       "--exclude: configuration %zu does "
                                       "not exist (sample %s has %zu)",
                                       st->exclude[j], who, nconf);
            }
        }
        if (rc != BF_EXIT_OK) {
            break;
        }
        if (nconf > cap) {
            free(sel);
            cap = nconf;
            sel = malloc(cap * sizeof *sel);
            if (sel == NULL) {
                bf_cli_err("out of memory");
                return BF_EXIT_SOFTWARE;
            }
        }
        if (bf_dataset_select(ds, m, st->targets[s].channel,
                              &st->spec.select, sel, &st->k[s],
                              &st->n_cone[s]) != BF_OK) {
            bf_cli_err("internal error: configuration selection failed");
            rc = BF_EXIT_SOFTWARE;
        } else if (st->k[s] == 0) {
            rc = bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                   "--exclude/--exclude-specular/"
                                   "--max-theta: no configuration is left "
                                   "to fit for sample %s",
                                   who);
        }
    }
    free(sel);
    st->n_sel = st->n_samples > 0 ? st->k[0] : 0;
    for (s = 1; s < st->n_samples; s++) {
        if (st->k[s] != st->n_sel) {
            st->n_sel = 0; /* K differs between targets */
        }
    }
    return rc;
}

/* ==== the run ============================================================= */

int bf_cli_study_prepare(bf_cli_study *st)
{
    const bf_cli_opts *o = &st->opts;
    int *list = NULL;
    size_t n_list = 0;
    size_t *materials = NULL;
    size_t n_materials = 0;
    int mode;
    char hint[64];
    bf_error err;
    size_t i;
    int rc;

    snprintf(hint, sizeof hint, "%s ", st->cmd);
    rc = select_models(hint, o, &st->models, &st->n_models);
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_exact_models(st); /* variants of --fit exact, --range */
    }
    if (rc == BF_EXIT_OK) {
        rc = parse_samples(hint, o, &list, &n_list, &mode);
    }
    if (rc == BF_EXIT_OK && o->exclude != NULL) {
        /* syntax now; range once the data are read */
        char msg[256];
        int *ex = NULL;
        if (bf_cli_parse_int_list(o->exclude, &ex, &st->n_exclude, msg,
                                  sizeof msg) != 0) {
            rc = bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--exclude: %s",
                                   msg);
        } else {
            st->exclude = malloc((st->n_exclude + 1) * sizeof *st->exclude);
            for (i = 0; st->exclude != NULL && i < st->n_exclude; i++) {
                st->exclude[i] = (size_t)ex[i];
            }
            if (st->exclude == NULL) {
                bf_cli_err("out of memory");
                rc = BF_EXIT_SOFTWARE;
            }
        }
        free(ex);
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_check_outdir(o->out_dir); /* fail before the work */
    }
    if (rc == BF_EXIT_OK) {
        rc = bf_cli_load_data(&o->src, o->n_file, o->on_file, &st->in);
    }
    if (rc == BF_EXIT_OK) {
        rc = resolve_samples(hint, &st->in, mode, list, n_list, &materials,
                             &n_materials);
    }
    free(list);
    if (rc == BF_EXIT_OK &&
        bf_study_targets(st->in.ds, materials, n_materials, o->channel,
                         &st->targets, &st->n_samples, &err) != BF_OK) {
        rc = err.code == BF_ENOMEM
                 ? BF_EXIT_SOFTWARE
                 : bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--channel: %s",
                                     err.msg);
    }
    free(materials);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    st->samples = malloc((st->n_samples + 1) * sizeof *st->samples);
    st->rows = calloc(st->n_samples * st->n_models + 1, sizeof *st->rows);
    if (st->samples == NULL || st->rows == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    for (i = 0; i < st->n_samples; i++) {
        st->samples[i] = bf_dataset_number(st->in.ds,
                                           st->targets[i].material);
    }
    memset(&st->spec, 0, sizeof st->spec);
    st->spec.data = st->in.ds;
    st->spec.targets = st->targets;
    st->spec.n_targets = st->n_samples;
    bf_select_init(&st->spec.select);
    st->spec.select.cone = o->cone < 0.0 ? BF_CONE_DEFAULT : o->cone * DEG;
    st->spec.select.max_theta = o->max_theta * DEG;
    st->spec.select.exclude = st->exclude;
    st->spec.select.n_exclude = st->n_exclude;
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
    return select_configs(hint, st);
}

int bf_cli_target_data(const bf_cli_study *st, size_t s, size_t *sel,
                       size_t *k, double *data)
{
    bf_error err;
    return bf_study_target_data(&st->spec, s, sel, k, data, &err);
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
                   "§2); leave configurations out with --exclude, "
                   "--exclude-specular or --max-theta",
                   r->type->name, r->sample, r->k);
        return BF_EXIT_DATAERR;
    }
    return BF_EXIT_OK;
}

int bf_cli_study_error(const bf_error *err)
{
    char buf[BF_ERROR_FILE_MAX + BF_ERROR_MSG_MAX + 64];
    if (strcmp(err->file, "study") == 0) { /* no file to name */
        bf_cli_err("%s", err->msg);
    } else {
        bf_cli_err("%s", bf_error_format(err, buf, sizeof buf));
    }
    return err->code == BF_ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_DATAERR;
}

int bf_cli_study_run_protocol(bf_cli_study *st)
{
    bf_error err;
    if (st->opts.exact) { /* the analysis is the study */
        return BF_EXIT_OK;
    }
    if (bf_study_run(&st->spec, st->rows, &err) != BF_OK) {
        return bf_cli_study_error(&err);
    }
    return check_rows(st);
}

int bf_cli_study_run_analysis(bf_cli_study *st)
{
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
    return st->opts.exact ? check_rows(st) : BF_EXIT_OK;
}

int bf_cli_study_run(bf_cli_study *st)
{
    int rc = bf_cli_study_run_protocol(st);
    return rc == BF_EXIT_OK ? bf_cli_study_run_analysis(st) : rc;
}

void bf_cli_study_free(bf_cli_study *st)
{
    free(st->rows);
    free(st->stats);
    free(st->variants);
    free(st->exclude);
    free(st->k);
    free(st->n_cone);
    free(st->models);
    free(st->samples);
    free(st->targets);
    bf_cli_free_inputs(&st->in);
    st->rows = NULL;
    st->stats = NULL;
    st->variants = NULL;
    st->exclude = NULL;
    st->k = NULL;
    st->n_cone = NULL;
    st->models = NULL;
    st->samples = NULL;
    st->targets = NULL;
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

const char *bf_cli_sample_name(const bf_cli_study *st, size_t s)
{
    const char *nm = bf_dataset_name(st->in.ds, st->targets[s].material);
    return nm != NULL ? nm : "";
}

const char *bf_cli_channel_name(const bf_cli_study *st, size_t s)
{
    return bf_dataset_channel(st->in.ds, st->targets[s].material,
                              st->targets[s].channel);
}

void bf_cli_sample_title(const bf_cli_study *st, size_t s, char *buf,
                         size_t len)
{
    if (st->targets[s].channel == BF_CHANNEL_MEAN) {
        snprintf(buf, len, "%s", bf_cli_sample_name(st, s));
    } else {
        snprintf(buf, len, "%s [%s]", bf_cli_sample_name(st, s),
                 bf_cli_channel_name(st, s));
    }
}

/* At most this many left-out configuration numbers are listed. */
#define LIST_MAX 40

void bf_cli_describe_data(const bf_cli_study *st, FILE *fp)
{
    const bf_cli_inputs *in = &st->in;
    const bf_dataset *ds = in->ds;
    size_t m;
    if (in->curet) {
        fprintf(fp, "Data: CURET, %s (%zu samples), %s\n", in->brdf_path,
                bf_dataset_count(ds), in->table_path);
        return;
    }
    fprintf(fp, "Data: %zu material%s from %zu file%s\n",
            bf_dataset_count(ds), bf_dataset_count(ds) == 1 ? "" : "s",
            st->opts.src.n_inputs, st->opts.src.n_inputs == 1 ? "" : "s");
    for (m = 0; m < bf_dataset_count(ds); m++) {
        size_t nc = bf_dataset_nchannels(ds, m);
        char who[256];
        bf_cli_material_label(ds, m, who, sizeof who);
        fprintf(fp, "  %s: %s (%s), %zu configurations, %zu channel%s", who,
                bf_dataset_source(ds, m),
                bf_format_name(bf_dataset_format(ds, m)),
                bf_dataset_nconf(ds, m), nc, nc == 1 ? "" : "s");
        if (nc > 1) {
            fprintf(fp, " (%s ... %s)", bf_dataset_channel(ds, m, 0),
                    bf_dataset_channel(ds, m, nc - 1));
        }
        fputc('\n', fp);
    }
    if (in->configs_path[0] != '\0') {
        fprintf(fp, "MERL sampled at: %s\n",
                strcmp(in->configs_path, "all") == 0
                    ? "every valid cell"
                    : in->configs_path);
    }
}

/* The specular exclusion in words (SPEC §1.4, §1.6). */
void bf_cli_describe_cone(const bf_cli_study *st, char *buf, size_t len)
{
    double cone = st->opts.cone;
    if (cone < 0.0 && st->in.curet && st->n_samples > 0) {
        /* the configurations of SPEC §1.4's test, from the data */
        size_t m = st->targets[0].material;
        const bf_geom *g = bf_dataset_geom(st->in.ds, m);
        size_t n = bf_dataset_nconf(st->in.ds, m);
        size_t count = 0;
        size_t k;
        size_t at;
        for (k = 0; k < n; k++) {
            count += (size_t)bf_geom_is_specular(&g[k]);
        }
        at = (size_t)snprintf(buf, len, "CURET's %zu specular "
                                        "configurations (",
                              count);
        for (k = 0; k < n && at < len; k++) {
            if (bf_geom_is_specular(&g[k])) {
                at += (size_t)snprintf(buf + at, len - at, "%s%zu",
                                       buf[at - 1] == '(' ? "" : ", ", k + 1);
            }
        }
        if (at < len) {
            snprintf(buf + at, len - at, "; SPEC §1.4)");
        }
    } else if (cone < 0.0) {
        snprintf(buf, len, "none (no --exclude-specular)");
    } else if (cone == 0.0) {
        snprintf(buf, len, "none (--exclude-specular 0)");
    } else {
        snprintf(buf, len, "every configuration within %g deg of the "
                           "mirror direction (SPEC §1.6)",
                 cone);
    }
}

/* One line per group of targets with the same material configuration
 * list and selection: K, how many the cone left out, and which ones. */
static void describe_configs(const bf_cli_study *st, FILE *fp)
{
    const bf_dataset *ds = st->in.ds;
    size_t s;
    size_t *sel = NULL;
    double *data = NULL;
    size_t cap = 0;
    char cone[256];
    bf_cli_describe_cone(st, cone, sizeof cone);
    fprintf(fp, "Specular exclusion: %s\n", cone);
    for (s = 0; s < st->n_samples; s++) {
        size_t m = st->targets[s].material;
        size_t nconf = bf_dataset_nconf(ds, m);
        size_t k;
        size_t j = 0;
        size_t c;
        size_t listed = 0;
        if (s > 0 && bf_dataset_set(ds, st->targets[s - 1].material) ==
                         bf_dataset_set(ds, m) &&
            st->k[s - 1] == st->k[s] && st->n_cone[s - 1] == st->n_cone[s]) {
            continue; /* the same as the line above */
        }
        if (nconf > cap) {
            free(sel);
            free(data);
            cap = nconf;
            sel = malloc(cap * sizeof *sel);
            data = malloc(cap * sizeof *data);
            if (sel == NULL || data == NULL) {
                break;
            }
        }
        if (bf_cli_target_data(st, s, sel, &k, data) != BF_OK) {
            continue;
        }
        fprintf(fp, "Configurations");
        if (!st->in.curet || st->n_sel == 0) {
            fprintf(fp, " (%s)", bf_cli_sample_name(st, s));
        }
        fprintf(fp, ": K = %zu of %zu used", k, nconf);
        if (st->opts.cone >= 0.0 || !st->in.curet) {
            fprintf(fp, " (%zu in the specular cone)", st->n_cone[s]);
        }
        if (nconf - k > LIST_MAX) {
            fprintf(fp, "; %zu left out\n", nconf - k);
            continue;
        }
        fprintf(fp, "; left out:");
        for (c = 0; c < nconf; c++) {
            if (j < k && sel[j] == c) {
                j++;
                continue;
            }
            fprintf(fp, " %zu", c + 1);
            listed++;
        }
        fprintf(fp, "%s\n", listed == 0 ? " none" : "");
    }
    free(sel);
    free(data);
}

void bf_cli_study_describe(const bf_cli_study *st, FILE *fp)
{
    const bf_cli_opts *o = &st->opts;
    bf_cli_describe_data(st, fp);
    describe_configs(st, fp);
    fprintf(fp, "Normalisation: radiance = BRDF x cos(theta_i), divided by "
                "its maximum over the K used configurations (SPEC §2)\n");
    if (o->channel != NULL && strcmp(o->channel, "mean") != 0) {
        fprintf(fp, "Channel: %s\n", o->channel);
    }
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
    for (s = 0; s < st->n_samples; s++) {
        int sample = st->samples[s];
        char title[512];
        if (bf_tt_add_row(*t2) != 0 || bf_tt_add_row(*t3) != 0) {
            return -1;
        }
        bf_cli_sample_title(st, s, title, sizeof title);
        bf_tt_set(*t2, 0, "%d", sample);
        bf_tt_set(*t2, 1, "%s", title);
        bf_tt_set(*t3, 0, "%d", sample);
        bf_tt_set(*t3, 1, "%s", title);
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

void bf_cli_csv_sample(FILE *fp, const bf_cli_study *st, size_t s)
{
    fprintf(fp, "%d,", st->samples[s]);
    bf_cli_csv_field(fp, bf_cli_sample_name(st, s));
    fputc(',', fp);
    bf_cli_csv_field(fp, bf_cli_channel_name(st, s));
}

/* fits.csv: one row per (sample, model, fitted parameter); a model with no
 * fitted parameter has one row with parameter and value empty. */
static void write_csv(FILE *fp, const bf_cli_study *st)
{
    const bf_study_spec *spec = &st->spec;
    const bf_study_row *rows = st->rows;
    size_t i;
    fputs("sample,name,channel,model,parameter,unit,value,lse,bound_hit,k",
          fp);
    bf_cli_exact_csv_header(fp); /* columns added at the end */
    fputc('\n', fp);
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
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
            bf_cli_csv_sample(fp, st, r->target);
            fprintf(fp, ",%s,%s,%s,%.10g,%.10g,%d,%zu", r->type->name,
                    r->type->param[j].name, r->type->param[j].unit,
                    r->fit.param[j], r->fit.lse,
                    (r->fit.bound_hit & (1u << j)) ? 1 : 0, r->k);
            bf_cli_exact_csv_cols(st, i, j, fp);
            fputc('\n', fp);
        }
        if (!any) {
            bf_cli_csv_sample(fp, st, r->target);
            fprintf(fp, ",%s,,,,%.10g,0,%zu", r->type->name, r->fit.lse,
                    r->k);
            bf_cli_exact_csv_cols(st, i, SIZE_MAX, fp);
            fputc('\n', fp);
        }
    }
}

static int any_bound_hit(const bf_study_spec *spec, const bf_study_row *rows)
{
    size_t i;
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
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
        for (s = 0; s < spec->n_targets; s++) {
            missing += rows[s * spec->n_models + m].status != BF_OK;
        }
        if (missing > 0) {
            bf_cli_err("note: %s not evaluated for %zu of %zu samples (%s)",
                       spec->models[m]->name, missing, spec->n_targets,
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
    if (st->n_sel > 0) {
        printf("\nTable 3: %s (sum over the K = %zu used configurations)"
               "\n\n",
               st->opts.objective == BF_OBJ_MAX ? "LSE" : "objective S",
               st->n_sel);
    } else {
        printf("\nTable 3: %s (sum over each sample's K used "
               "configurations)\n\n",
               st->opts.objective == BF_OBJ_MAX ? "LSE" : "objective S");
    }
    bf_tt_print(t3, stdout);
    bf_cli_exact_on_compare(st, stdout);
    printf("\nWritten: %s/fits.csv, %s/table2.md, %s/table3.md\n",
           st->opts.out_dir, st->opts.out_dir, st->opts.out_dir);
done:
    bf_tt_free(t2);
    bf_tt_free(t3);
    return rc;
}
