/* options.c: the options every study command accepts -- parsing, the
 * checks that need no data, each command's defaults and the help text. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

/* The paper's models (Ragheb & Hancock, Table 3) and samples (Table 2). */
const bf_cli_defaults bf_cli_compare_defaults = {NULL, BF_MODELS_PAPER, 0,
                                                 0};

/* Prints text wrapped at column 76, continuation lines indented to
 * column 21 (the help's value column); breaks after commas or spaces. */
static void wrapped(FILE *fp, const char *text, size_t col)
{
    while (*text != '\0') {
        size_t room = col < 76 ? 76 - col : 20;
        size_t n = strlen(text);
        size_t cut = n;
        if (n > room) {
            for (cut = room; cut > 0 && text[cut - 1] != ',' &&
                             text[cut - 1] != ' ';
                 cut--) {
            }
            cut = cut == 0 ? room : cut;
        }
        fprintf(fp, "%.*s", (int)cut, text);
        text += cut;
        if (*text != '\0') {
            fputs("\n                    ", fp);
            col = 20;
        }
    }
}

void bf_cli_opts_usage_defaults(FILE *fp, const bf_cli_defaults *d)
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
"                    more), numbered 1, 2, ... in input order; FILE...\n"
"                    after the options are inputs too, after any --input\n"
"  --input-format F  force the format of every --input: pbrt, astm, merl,\n"
"                    csv, curet (default: detected from the content)\n"
"  --configs FILE|all  where a MERL table is sampled: the angles of a CSV\n"
"                    file, or every valid cell (default: CURET's 205\n"
"                    configurations, from DIR/table.txt)\n"
"  --channel C       channel to fit: 'mean' (of all channels, default), a\n"
"                    channel name (R, G, B) or wavelength (550), 'each'\n"
"                    (every channel, one set of rows per channel) or\n"
"                    'joint' (one shape for all channels, the scales\n"
"                    rho_d, rho_s, A, Rd per channel, SPEC 9.4; needs\n"
"                    --fit exact --objective ngan and models with scales;\n"
"                    fits.csv: the shape on channel 'joint')\n",
            BF_DEFAULT_DATA_DIR, BF_CLI_MAX_INPUTS);
    if (d->samples == NULL) {
        fputs(
"  --samples SET     'paper' (the study's 24 CURET samples; the default on\n"
"                    CURET), 'all' (the default for --input), or a list of\n"
"                    sample numbers such as 1,5,7-9\n", fp);
    } else {
        fprintf(fp,
"  --samples SET     'paper' (the study's 24 CURET samples), 'all' (every\n"
"                    sample of the data), or a list of sample numbers such\n"
"                    as 1,5,7-9 (default %s)\n", d->samples);
    }
    fputs(
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
"  --models LIST     comma-separated model names, or 'all' (the diffuse\n"
"                    models; with --objective ngan, cuberoot, log1p also\n"
"                    LAMBERT+S for every specular model S, AS alone);\n"
"                    composites D+S such as LAMBERT+GGX (with --objective\n"
"                    ngan); see\n"
"                    'brdffit models' (default ", fp);
    wrapped(fp, bf_model_set_names(d->models), 38);
    fprintf(fp, ")\n"
"  --n VALUE         refractive index of the FC models (default %.1f)\n"
"  --n-file FILE     per-sample refractive index, rows 'sample n'\n"
"  --on-params FILE  Oren-Nayar rho, sigma per sample: rows 'sample rho\n"
"                    sigma [kd]' (CURET op.dat layout accepted)\n"
"  --fit MODE        'paper' (the paper's grids) or 'exact' (grid, then GSL\n"
"                    refinement; FC's n and ON's rho, sigma fitted too;\n"
"                    doc/methods.md §6) (default %s)\n"
"  --objective NAME  max (paper, default), scale, cosw, log, or ngan,\n"
"                    cuberoot, log1p (SPEC §10: BRDF values kept at their\n"
"                    scale, theta <= 80 deg, a free scale rho_d); needs\n"
"                    --fit exact unless max; see doc/methods.md\n"
"  --fresnel F       the specular models' Fresnel term (SPEC §9.2):\n"
"                    schlick (F0, their default), dielectric (index n in\n"
"                    [1.01, 4] in F0's place) or none (F = 1, no F0);\n"
"                    GGX, BECKMANN, CT and the S of their composites D+S\n"
"                    (diffuse models are unaffected; another specular\n"
"                    model is an error)\n"
"  --smith M         the Smith masking of GGX and BECKMANN (and their\n"
"                    composites): height (correlated, the default) or\n"
"                    separable (Heitz 2014 eqs. 99, 98)\n"
"  --range P=LO:HI   search range of parameter P, e.g. m=0.01:20 (grid\n"
"                    keeps its step; repeatable)\n"
"  --noise MODEL     the intervals' noise model: auto (power law var ~\n"
"                    mu^p, p from the residuals; default), absolute,\n"
"                    relative, or objective (the objective's own profile,\n"
"                    the intervals before issue 18); doc/methods.md §3\n"
"  --intervals I     profile (the default: 95%% profile intervals under the\n"
"                    noise model) or none (no interval and no noise model:\n"
"                    the fits, AIC, BIC and CV only, in a fraction of the\n"
"                    time; compare and rank, not with --bootstrap)\n",
            BF_DEFAULT_N, d->exact ? "exact" : "paper");
    if (d->stats) {
        fputs(
"  --stats           the analysis beyond the paper: refined optima, 95%\n"
"                    profile intervals, AIC, BIC, CV (always on here)\n", fp);
    } else {
        fputs(
"  --stats           with --fit paper, also the analysis beyond the paper:\n"
"                    refined optima, 95% profile intervals, AIC, BIC, CV\n"
"                    (the analysis columns of fits.csv; always on with\n"
"                    --fit exact, --bootstrap and --neyman N)\n", fp);
    }
    fputs(
"  --bootstrap N     also a residual-bootstrap interval under the noise\n"
"                    model, N refits (default 0: profile intervals only)\n"
"  --neyman auto|off|N  a diffuse model's intervals by the Neyman\n"
"                    construction: each end's threshold the 95% quantile of\n"
"                    N (>= 100) simulated refits there (ci_method neyman;\n"
"                    about 4 N fits per parameter). auto (default): 100, for\n"
"                    a parameter whose profile has a second minimum that\n"
"                    competes (flag competing); N: every parameter; off: the\n"
"                    F threshold alone\n"
"  --folds K         K-fold cross-validation (default 10; 0 for none)\n"
"  --seed S          seed of the bootstrap, the Neyman construction and\n"
"                    the folds (default 1)\n"
"\n"
"Output:\n"
"  --out DIR         output folder (default out; created if missing)\n"
"  --threads N       fit on at most N threads (default 0: one per core);\n"
"                    the results do not depend on N\n"
"  -q, --quiet       do not print the tables, nor the progress line (on\n"
"                    stderr when it is a terminal and the run is long)\n"
"  -h, --help        show this help\n", fp);
}

void bf_cli_opts_usage(FILE *fp)
{
    bf_cli_opts_usage_defaults(fp, &bf_cli_compare_defaults);
}

/* ==== argument parsing =================================================== */

int bf_cli_opts_parse(const char *cmd, int argc, char **argv,
                      void (*usage)(FILE *fp), const bf_cli_extra *extra,
                      bf_cli_opts *o)
{
    return bf_cli_opts_parse_defaults(cmd, argc, argv, usage, extra,
                                      &bf_cli_compare_defaults, o);
}

int bf_cli_opts_parse_defaults(const char *cmd, int argc, char **argv,
                               void (*usage)(FILE *fp),
                               const bf_cli_extra *extra,
                               const bf_cli_defaults *d, bf_cli_opts *o)
{
    enum { O_DATA = 256, O_BRDF, O_SAMPLES, O_MODELS, O_N, O_NFILE, O_ON,
           O_EXCLUDE, O_MAXTHETA, O_OUT, O_FIT, O_OBJECTIVE, O_RANGE,
           O_BOOTSTRAP, O_NEYMAN, O_FOLDS, O_SEED, O_THREADS, O_STATS, O_INPUT,
           O_INFORMAT, O_CONFIGS, O_CHANNEL, O_CONE, O_NOISE, O_FRESNEL,
           O_SMITH, O_INTERVALS };
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
        {"fresnel", required_argument, NULL, O_FRESNEL},
        {"smith", required_argument, NULL, O_SMITH},
        {"range", required_argument, NULL, O_RANGE},
        {"noise", required_argument, NULL, O_NOISE},
        {"intervals", required_argument, NULL, O_INTERVALS},
        {"bootstrap", required_argument, NULL, O_BOOTSTRAP},
        {"neyman", required_argument, NULL, O_NEYMAN},
        {"folds", required_argument, NULL, O_FOLDS},
        {"seed", required_argument, NULL, O_SEED},
        {"stats", no_argument, NULL, O_STATS},
        {"threads", required_argument, NULL, O_THREADS},
        {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'}};
    struct option longopts[64];
    size_t n_long = sizeof common / sizeof *common;
    char hint[64];
    bf_analysis_opts analysis;
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
    bf_analysis_opts_init(&analysis); /* the library's defaults */
    o->folds = analysis.folds;
    o->seed = analysis.seed;
    o->n_neyman = analysis.n_neyman;
    o->neyman_every = analysis.neyman_every;
    o->threads = 0; /* one per core */
    o->samples = d->samples;
    o->defaults = d;
    o->exact = d->exact;
    o->stats = d->stats;

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
            if (bf_rep_parse_double(optarg, &o->cone) != 0 ||
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
            if (bf_rep_parse_double(optarg, &o->n) != 0 || o->n <= 1.0 ||
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
            if (bf_rep_parse_double(optarg, &t) != 0 || t < 0.0 ||
                t > BF_CLI_MAX_THREADS || t != floor(t)) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--threads: '%s' is not a "
                                          "whole number in [0, %d]",
                                          optarg, BF_CLI_MAX_THREADS);
            }
            o->threads = (int)t;
            break;
        }
        case O_MAXTHETA:
            if (bf_rep_parse_double(optarg, &o->max_theta) != 0 ||
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
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--objective: '%s' is not max, scale, "
                                         "cosw, log, ngan, cuberoot or log1p",
                                         optarg);
            }
            break;
        case O_FRESNEL:
        case O_SMITH: {
            int rc = c == O_FRESNEL
                         ? bf_cli_parse_fresnel(hint, optarg, &o->fresnel)
                         : bf_cli_parse_smith(hint, optarg, &o->smith);
            if (rc != BF_EXIT_OK) {
                return rc;
            }
            break;
        }
        case O_NOISE:
            if (bf_noise_find(optarg, &o->noise) != BF_OK) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--noise: '%s' is not "
                                          "auto, absolute, relative or objective",
                                          optarg);
            }
            break;
        case O_INTERVALS:
            if (strcmp(optarg, "profile") != 0 &&
                strcmp(optarg, "none") != 0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                         "--intervals: '%s' is not profile "
                                         "or none", optarg);
            }
            o->no_intervals = strcmp(optarg, "none") == 0;
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
            if (bf_rep_parse_range(optarg, name, sizeof name, &lo, &hi, msg,
                                   sizeof msg) != 0) {
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--range: %s", msg);
            }
            o->range[o->n_range++] = optarg;
            break;
        }
        case O_NEYMAN:
            if (strcmp(optarg, "auto") == 0 || strcmp(optarg, "off") == 0) {
                o->n_neyman = optarg[0] == 'a' ? BF_NEYMAN_AUTO_SIM : 0;
                o->neyman_every = 0;
                break;
            }
            /* N: every parameter's */
            /* fall through */
        case O_BOOTSTRAP:
        case O_FOLDS:
        case O_SEED: {
            int *list = NULL;
            size_t count = 0;
            char msg[128];
            int zero = strcmp(optarg, "0") == 0;
            int e = zero ? 0 : bf_rep_parse_int_list(optarg, &list, &count,
                                                     msg, sizeof msg);
            if (e == -2) {
                bf_cli_err("out of memory");
                return BF_EXIT_SOFTWARE;
            }
            if (!zero && (e != 0 ||
                          count != 1 || strchr(optarg, ',') != NULL ||
                          strchr(optarg, '-') != NULL)) {
                free(list);
                return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "%s: '%s' is not a "
                                          "non-negative integer%s",
                                          argv[optind - 2], optarg,
                                          c == O_NEYMAN ? " (nor auto, off)"
                                                        : "");
            }
            if (c == O_BOOTSTRAP) {
                o->n_boot = zero ? 0 : (size_t)list[0];
            } else if (c == O_NEYMAN) {
                o->n_neyman = zero ? 0 : (size_t)list[0];
                o->neyman_every = !zero;
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
    /* FILE... after the options: more --input files, in their order */
    for (; optind < argc; optind++) {
        if (o->src.n_inputs == BF_CLI_MAX_INPUTS) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                     "at most %d input files",
                                     BF_CLI_MAX_INPUTS);
        }
        o->src.inputs[o->src.n_inputs++] = argv[optind];
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
    if (o->n_neyman > 0 && o->neyman_every &&
        o->noise == BF_NOISE_OBJECTIVE) {
        return bf_cli_usage_fail(BF_EXIT_CONFLICT, hint,
                                 "--neyman simulates the noise model: not "
                                 "with --noise objective");
    }
    if (o->n_neyman > 0 && o->n_neyman < BF_NEYMAN_MIN_SIM) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint,
                                 "--neyman needs at least %d simulations "
                                 "(or auto, or off)", BF_NEYMAN_MIN_SIM);
    }
    return 0;
}

int bf_cli_parse_fresnel(const char *cmd, const char *arg,
                         bf_fresnel_kind *f)
{
    if (bf_fresnel_find(arg, f) != BF_OK) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, cmd,
                                 "--fresnel: '%s' is not schlick, dielectric "
                                 "or none", arg);
    }
    return BF_EXIT_OK;
}

int bf_cli_parse_smith(const char *cmd, const char *arg, bf_smith_kind *s)
{
    if (bf_smith_find(arg, s) != BF_OK) {
        return bf_cli_usage_fail(BF_EXIT_BADVALUE, cmd,
                                 "--smith: '%s' is not height or separable",
                                 arg);
    }
    return BF_EXIT_OK;
}
