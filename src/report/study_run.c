/* study.c: the study run shared by the fitting subcommands -- loading,
 * the selections of samples, models (the library's exact-fit variants) and
 * configurations (SPEC §1.4, §7) that make the study specification, the
 * run itself (bf_study_run, bf_study_analyse) and the accessors the
 * printers use. Prints only errors. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "calibration.h"
#include "study.h"

#define DEG (M_PI / 180.0)

/* Parses --samples before any file is read (usage errors come first): a
 * list goes to *out; 'paper' and 'all' leave *out NULL and set *mode, and
 * are resolved by resolve_samples once the data are read. */
enum { SAMPLES_DEFAULT, SAMPLES_PAPER, SAMPLES_ALL, SAMPLES_LIST };

static int parse_samples(const char *hint, const bf_report_options *o, int **out,
                         size_t *n, int *mode)
{
    char msg[256];
    *out = NULL;
    *n = 0;
    *mode = SAMPLES_DEFAULT;
    if (o->samples == NULL) {
        return BF_REPORT_OK;
    }
    if (strcmp(o->samples, "all") == 0) {
        *mode = SAMPLES_ALL;
        return BF_REPORT_OK;
    }
    if (strcmp(o->samples, "paper") == 0) {
        *mode = SAMPLES_PAPER;
        return BF_REPORT_OK;
    }
    *mode = SAMPLES_LIST;
    switch (bf_rep_parse_int_list(o->samples, out, n, msg, sizeof msg)) {
    case 0:
        break;
    case -2:
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    default:
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint, "--samples: %s",
                                 msg);
    }
    return BF_REPORT_OK;
}

/* The materials (dataset indices) of --samples: the paper's 24 on CURET by
 * default, every material otherwise; a list names material numbers. */
static int resolve_samples(const char *hint, const bf_report_inputs *in,
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
            return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
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
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    for (i = 0; i < *n; i++) {
        long m = mode == SAMPLES_ALL ? (long)i : bf_dataset_find(ds, list[i]);
        if (m < 0) {
            return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
                                     "--samples: sample %d is not in the %s "
                                     "(it has samples 1-%zu)",
                                     list[i],
                                     in->curet ? "BRDF file" : "data", count);
        }
        (*out)[i] = (size_t)m;
    }
    return BF_REPORT_OK;
}

/* The models of --models (bf_study_models), the message prefixed with
 * the option's name. */
static int select_models(const char *hint, const bf_report_options *o,
                         const bf_model_type ***out, size_t *n)
{
    size_t cap = bf_model_count() + 1;
    bf_error err;
    int rc;
    *n = 0;
    *out = calloc(cap, sizeof **out);
    if (*out == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    rc = bf_study_models(o->models, o->default_models, o->objective,
                         o->fresnel, o->smith, *out, cap, n, &err);
    if (rc == BF_EDOM && bf_objective_keeps_scale(o->objective)) {
        /* --fresnel, --smith: a model that cannot take them (SPEC §9.2) */
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint, "--models: %s",
                                 err.msg);
    }
    if (rc == BF_EDOM) { /* SPEC §9, §10: the others max-normalise */
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
                                 "%s; fit it with --fit exact --objective "
                                 "ngan, cuberoot or log1p", err.msg);
    }
    if (rc != BF_OK) {
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint, "--models: %s%s",
                                 err.msg, rc == BF_ENOTFOUND
                                              ? " (see 'brdffit models')"
                                              : "");
    }
    return BF_REPORT_OK;
}

/* The selection of spec (SPEC §1.4, §1.6, --max-theta, --exclude) for
 * every target: its K and how many the cone left out. An excluded number
 * beyond a material's configurations, or a target left with nothing, is a
 * usage error. */
static int select_configs(const char *hint, bf_rep_study *st)
{
    const bf_dataset *ds = st->in.ds;
    size_t *sel = NULL;
    size_t cap = 0;
    size_t s;
    size_t j;
    int rc = BF_REPORT_OK;

    st->k = calloc(st->n_samples + 1, sizeof *st->k);
    st->n_cone = calloc(st->n_samples + 1, sizeof *st->n_cone);
    if (st->k == NULL || st->n_cone == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    for (s = 0; s < st->n_samples && rc == BF_REPORT_OK; s++) {
        size_t m = st->targets[s].material;
        size_t nconf = bf_dataset_nconf(ds, m);
        char who[256];
        bf_rep_material_label(ds, m, who, sizeof who);
        for (j = 0; j < st->n_exclude; j++) {
            if (st->exclude[j] > nconf) {
                rc = bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
                                       "--exclude: configuration %zu does "
                                       "not exist (sample %s has %zu)",
                                       st->exclude[j], who, nconf);
            }
        }
        if (rc != BF_REPORT_OK) {
            break;
        }
        if (nconf > cap) {
            free(sel);
            cap = nconf;
            sel = malloc(cap * sizeof *sel);
            if (sel == NULL) {
                bf_rep_err("out of memory");
                return BF_REPORT_SOFTWARE;
            }
        }
        if (bf_dataset_select(ds, m, st->targets[s].channel,
                              &st->spec.select, sel, &st->k[s],
                              &st->n_cone[s]) != BF_OK) {
            bf_rep_err("internal error: configuration selection failed");
            rc = BF_REPORT_SOFTWARE;
        } else if (st->k[s] == 0) {
            rc = bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
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

/* The models the study fits: with --fit exact, the library's exact-fit
 * variants (n kept when the user gave it; doc/methods.md §6), every
 * --range applied (bf_study_variants). A --range that names no parameter
 * of any model is a usage error. */
static int make_variants(const char *hint, bf_rep_study *st)
{
    const bf_report_options *o = &st->opts;
    unsigned keep = (o->n_given || o->n_file != NULL)
                        ? 1u << BF_INPUT_INDEX
                        : 0u;
    bf_param_range ranges[BF_REPORT_MAX_RANGES];
    char names[BF_REPORT_MAX_RANGES][32];
    size_t bad_range = 0;
    size_t bad_model = 0;
    size_t r;
    int rc;
    if (!o->exact && o->n_range == 0) {
        return BF_REPORT_OK;
    }
    for (r = 0; r < o->n_range; r++) {
        char msg[128];
        bf_rep_parse_range(o->range[r], names[r], sizeof names[r],
                           &ranges[r].lo, &ranges[r].hi, msg, sizeof msg);
        ranges[r].name = names[r];
    }
    st->variants = calloc(st->n_models + 1, sizeof *st->variants);
    if (st->variants == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    rc = bf_study_variants(st->models, st->n_models, o->exact, keep, ranges,
                           o->n_range, st->variants, st->models, &bad_range,
                           &bad_model);
    if (rc == BF_ENOTFOUND) {
        return bf_rep_usage_fail(BF_REPORT_BADVALUE, hint,
                                 "--range %s: no selected model has "
                                 "that parameter",
                                 o->range[bad_range]);
    }
    if (rc != BF_OK) {
        const bf_model_type *t = st->models[bad_model];
        const bf_param *pj =
            &t->param[bf_model_param_index(t, names[bad_range])];
        return bf_rep_usage_fail(
            BF_REPORT_BADVALUE, hint,
            "--range %s: %s's %s must stay in [%g, %g] with at most "
            "%d grid points",
            o->range[bad_range], t->name, names[bad_range], pj->min,
            pj->max, BF_VARIANT_MAX_GRID);
    }
    return BF_REPORT_OK;
}

/* ==== the run ============================================================= */

/* The paths of in that are NULL made "" (the printers test their first
 * character). */
static void no_null_paths(bf_report_inputs *in)
{
    const char **p[4];
    size_t i;
    p[0] = &in->table_path;
    p[1] = &in->brdf_path;
    p[2] = &in->names_path;
    p[3] = &in->configs_path;
    for (i = 0; i < 4; i++) {
        if (*p[i] == NULL) {
            *p[i] = "";
        }
    }
}

/* --intervals none: a study without intervals has no bootstrap, no
 * calibration (which checks the intervals) and no report's analysis
 * (its forest plots and profiles draw them). */
static int intervals_check(const char *hint, const bf_rep_study *st)
{
    const bf_report_options *o = &st->opts;
    if (!o->no_intervals) {
        return BF_REPORT_OK;
    }
    if (o->n_boot > 0) {
        return bf_rep_usage_fail(BF_REPORT_CONFLICT, hint,
                                 "--intervals none: --bootstrap computes "
                                 "an interval too; drop one of them");
    }
    if (o->n_neyman > 0 && o->neyman_every) {
        return bf_rep_usage_fail(BF_REPORT_CONFLICT, hint,
                                 "--intervals none: --neyman computes "
                                 "the intervals; drop one of them");
    }
    if (o->calibrate > 0 || strcmp(st->cmd, "calibrate") == 0) {
        return bf_rep_usage_fail(BF_REPORT_CONFLICT, hint,
                                 "--intervals none: calibration checks "
                                 "the intervals");
    }
    if (strcmp(st->cmd, "report") == 0 && (o->exact || o->stats)) {
        return bf_rep_usage_fail(BF_REPORT_CONFLICT, hint,
                                 "--intervals none: the report's analysis "
                                 "draws the intervals (forest plots, "
                                 "profiles); 'brdffit compare' writes the "
                                 "fits without them");
    }
    return BF_REPORT_OK;
}

int bf_rep_study_prepare(bf_rep_study *st)
{
    const bf_report_options *o = &st->opts;
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
    rc = bf_rep_calibrate_check(hint, o);
    if (rc == BF_REPORT_OK) {
        rc = intervals_check(hint, st);
    }
    if (rc == BF_REPORT_OK) {
        rc = select_models(hint, o, &st->models, &st->n_models);
    }
    if (rc == BF_REPORT_OK) {
        rc = make_variants(hint, st); /* --fit exact, --range */
    }
    if (rc == BF_REPORT_OK) {
        rc = parse_samples(hint, o, &list, &n_list, &mode);
    }
    if (rc == BF_REPORT_OK && o->exclude != NULL) {
        /* syntax now; range once the data are read */
        char msg[256];
        int *ex = NULL;
        int e = bf_rep_parse_int_list(o->exclude, &ex, &st->n_exclude, msg,
                                      sizeof msg);
        if (e == -2) {
            bf_rep_err("out of memory");
            rc = BF_REPORT_SOFTWARE;
        } else if (e != 0) {
            rc = bf_rep_usage_fail(BF_REPORT_BADVALUE, hint, "--exclude: %s",
                                   msg);
        } else {
            st->exclude = malloc((st->n_exclude + 1) * sizeof *st->exclude);
            for (i = 0; st->exclude != NULL && i < st->n_exclude; i++) {
                st->exclude[i] = (size_t)ex[i];
            }
            if (st->exclude == NULL) {
                bf_rep_err("out of memory");
                rc = BF_REPORT_SOFTWARE;
            }
        }
        free(ex);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_check_outdir(st->out_dir); /* fail before the work */
    }
    if (rc == BF_REPORT_OK) {
        rc = st->in.ds == NULL && st->in.load != NULL
                 ? st->in.load(st->in.load_ctx, &st->in)
                 : BF_REPORT_OK;
    }
    if (rc == BF_REPORT_OK && st->in.ds == NULL) {
        bf_rep_err("internal error: no data to fit");
        rc = BF_REPORT_SOFTWARE;
    }
    if (rc == BF_REPORT_OK) {
        no_null_paths(&st->in);
    }
    if (rc == BF_REPORT_OK) {
        rc = resolve_samples(hint, &st->in, mode, list, n_list, &materials,
                             &n_materials);
    }
    free(list);
    if (rc == BF_REPORT_OK &&
        bf_study_targets(st->in.ds, materials, n_materials, o->channel,
                         &st->targets, &st->n_samples, &err) != BF_OK) {
        rc = err.code == BF_ENOMEM
                 ? bf_rep_study_error(&err)
                 : bf_rep_usage_fail(BF_REPORT_BADVALUE, hint, "--channel: %s",
                                     err.msg);
    }
    free(materials);
    if (rc != BF_REPORT_OK) {
        return rc;
    }
    st->samples = malloc((st->n_samples + 1) * sizeof *st->samples);
    st->rows = calloc(st->n_samples * st->n_models + 1, sizeof *st->rows);
    if (st->samples == NULL || st->rows == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    for (i = 0; i < st->n_samples; i++) {
        st->samples[i] = bf_dataset_number(st->in.ds,
                                           st->targets[i].material);
    }
    memset(&st->spec, 0, sizeof st->spec);
    st->spec.data = st->in.ds;
    st->spec.targets = st->targets;
    st->spec.n_targets = st->n_samples;
    bf_selection_init(&st->spec.select);
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
        st->spec.n_threads = cores > 0 && cores <= BF_REPORT_MAX_THREADS
                                 ? (int)cores
                                 : 1;
    }
    return select_configs(hint, st);
}

int bf_rep_target_data(const bf_rep_study *st, size_t s, size_t *sel,
                       size_t *k, double *data)
{
    bf_error err;
    return bf_study_target_data(&st->spec, s, sel, k, data, &err);
}

/* A row whose model could not be normalised on the used configurations
 * (BF_EDOM: undefined at one of them, e.g. BK at theta_i = 90 deg, SPEC
 * §3.3, or zero at all of them, SPEC §2) is an error, not a gap in the
 * tables; a missing per-sample input (BF_ENOTFOUND) is a noted gap. */
static int check_rows(const bf_rep_study *st)
{
    size_t i = 0;
    int rc = bf_study_rows_check(st->rows, st->n_samples * st->n_models, &i);
    if (rc == BF_OK) {
        return BF_REPORT_OK;
    }
    if (rc == BF_ENOMEM) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    bf_rep_err("%s cannot be fitted to sample %d: the model is "
               "undefined at some of the K = %zu used configurations or "
               "zero at all of them, so it cannot be normalised (SPEC "
               "§2); leave configurations out with --exclude, "
               "--exclude-specular or --max-theta",
               st->rows[i].type->name, st->rows[i].sample, st->rows[i].k);
    return BF_REPORT_DATAERR;
}

int bf_rep_study_error(const bf_error *err)
{
    char buf[BF_ERROR_FILE_MAX + BF_ERROR_MSG_MAX + 64];
    if (strcmp(err->file, "study") == 0) { /* no file to name */
        bf_rep_err("%s", err->msg);
    } else {
        bf_rep_err("%s", bf_error_format(err, buf, sizeof buf));
    }
    return err->code == BF_ENOMEM ? BF_REPORT_SOFTWARE : BF_REPORT_DATAERR;
}

int bf_rep_study_run_protocol(bf_rep_study *st)
{
    bf_error err;
    if (st->opts.exact) { /* the analysis is the study */
        return BF_REPORT_OK;
    }
    if (bf_study_run(&st->spec, st->rows, &err) != BF_OK) {
        return bf_rep_study_error(&err);
    }
    return check_rows(st);
}

/* The analysis's progress (a bf_progress_fn) as the options' callback. */
static void analysis_tick(void *ctx, size_t done, size_t total)
{
    const bf_rep_study *st = ctx;
    st->opts.progress(st->opts.progress_ctx,
                      "analysing (sample, model) pairs", done, total);
}

/* The analysis beyond the paper (refinement, intervals, AIC, BIC, CV; with
 * --fit exact also the study itself), with a progress line. */
static int run_analysis(bf_rep_study *st)
{
    const bf_report_options *o = &st->opts;
    bf_error err;
    int rc;
    st->stats = calloc(st->n_samples * st->n_models + 1, sizeof *st->stats);
    if (st->stats == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    bf_analysis_opts_init(&st->analysis);
    st->analysis.objective = o->objective;
    st->analysis.noise = o->noise;
    st->analysis.exact = o->exact;
    st->analysis.n_boot = o->n_boot;
    st->analysis.n_neyman = o->n_neyman;
    st->analysis.neyman_every = o->neyman_every;
    st->analysis.no_intervals = o->no_intervals;
    st->analysis.folds = o->folds;
    st->analysis.seed = o->seed;
    st->analysis.progress = o->progress != NULL ? analysis_tick : NULL;
    st->analysis.progress_ctx = st;
    rc = bf_study_analyse(&st->spec, &st->analysis, st->rows, st->stats,
                          &err);
    if (o->progress != NULL) {
        o->progress(o->progress_ctx, NULL, 0, 0);
    }
    st->analysis.progress = NULL;
    st->analysis.progress_ctx = NULL;
    if (rc != BF_OK) {
        return bf_rep_study_error(&err);
    }
    return BF_REPORT_OK;
}

int bf_rep_neyman_scope(const bf_rep_study *st)
{
    const bf_report_options *o = &st->opts;
    if (o->n_neyman == 0 || o->no_intervals ||
        o->noise == BF_NOISE_OBJECTIVE) {
        return BF_REP_NEYMAN_NONE;
    }
    return o->neyman_every ? BF_REP_NEYMAN_EVERY : BF_REP_NEYMAN_COMPETING;
}

int bf_rep_study_run_analysis(bf_rep_study *st)
{
    /* The analysis runs with --fit exact, --stats, --bootstrap, --neyman
     * or --calibrate: the paper's protocol alone stays the fast default of
     * compare and report. */
    int rc = BF_REPORT_OK;
    if (st->opts.exact || st->opts.stats || st->opts.n_boot > 0 ||
        (st->opts.n_neyman > 0 && st->opts.neyman_every) ||
        st->opts.calibrate > 0) {
        rc = run_analysis(st);
    }
    if (rc == BF_REPORT_OK && st->opts.exact) {
        rc = check_rows(st);
    }
    return rc == BF_REPORT_OK ? bf_rep_study_calibrate(st) : rc;
}

int bf_rep_study_run(bf_rep_study *st)
{
    int rc = bf_rep_study_run_protocol(st);
    return rc == BF_REPORT_OK ? bf_rep_study_run_analysis(st) : rc;
}

void bf_rep_study_free(bf_rep_study *st)
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
    bf_study_calibration_free(&st->cal);
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

/* ==== accessors =========================================================== */

/* Table 2 shows fitted parameters, or the inputs of a model that fits
 * none (ON). */
int bf_rep_shows_param(const bf_model_type *type, size_t j)
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

const char *bf_rep_sample_name(const bf_rep_study *st, size_t s)
{
    const char *nm = bf_dataset_name(st->in.ds, st->targets[s].material);
    return nm != NULL ? nm : "";
}

const char *bf_rep_channel_name(const bf_rep_study *st, size_t s)
{
    return bf_dataset_channel(st->in.ds, st->targets[s].material,
                              st->targets[s].channel);
}

void bf_rep_sample_title(const bf_rep_study *st, size_t s, char *buf,
                         size_t len)
{
    if (st->targets[s].channel == BF_CHANNEL_MEAN) {
        snprintf(buf, len, "%s", bf_rep_sample_name(st, s));
    } else {
        snprintf(buf, len, "%s [%s]", bf_rep_sample_name(st, s),
                 bf_rep_channel_name(st, s));
    }
}
