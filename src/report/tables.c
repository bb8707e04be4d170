/* tables.c: what a study run prints and writes -- the description of the
 * run (data, configurations, conventions, the fit and its analysis),
 * Tables 2 and 3 in the paper's layout, the Oren-Nayar comparison of
 * --fit exact, and the files fits.csv (bf_fits_csv_write), table2.md and
 * table3.md. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "calibration.h"
#include "energy.h"
#include "ranking.h"
#include "tables.h"
#include "texttable.h"

/* At most this many left-out configuration numbers are listed. */
#define LIST_MAX 40

void bf_rep_describe_data(const bf_rep_study *st, FILE *fp)
{
    const bf_report_inputs *in = &st->in;
    const bf_dataset *ds = in->ds;
    size_t m;
    if (in->curet) {
        fprintf(fp, "Data: CURET, %s (%zu samples), %s\n", in->brdf_path,
                bf_dataset_count(ds), in->table_path);
        return;
    }
    fprintf(fp, "Data: %zu material%s from %zu file%s\n",
            bf_dataset_count(ds), bf_dataset_count(ds) == 1 ? "" : "s",
            st->in.n_files, st->in.n_files == 1 ? "" : "s");
    for (m = 0; m < bf_dataset_count(ds); m++) {
        size_t nc = bf_dataset_nchannels(ds, m);
        char who[256];
        bf_rep_material_label(ds, m, who, sizeof who);
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
void bf_rep_describe_cone(const bf_rep_study *st, char *buf, size_t len)
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
static int describe_configs(const bf_rep_study *st, FILE *fp)
{
    const bf_dataset *ds = st->in.ds;
    size_t s;
    size_t *sel = NULL;
    double *data = NULL;
    size_t cap = 0;
    char cone[256];
    bf_rep_describe_cone(st, cone, sizeof cone);
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
                free(sel);
                free(data);
                return -1;
            }
        }
        if (bf_rep_target_data(st, s, sel, &k, data) != BF_OK) {
            continue;
        }
        fprintf(fp, "Configurations");
        if (!st->in.curet || st->n_sel == 0) {
            fprintf(fp, " (%s)", bf_rep_sample_name(st, s));
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
    return 0;
}

int bf_rep_param_freed(const bf_model_type *v, size_t j)
{
    const bf_model_type *base = bf_model_find(v->name);
    return base != NULL && j < v->p && j < base->p && v->param[j].fitted &&
           !base->param[j].fitted;
}

/* bf_rep_input_use of one model. */
static unsigned model_input_use(const bf_model_type *v, bf_input kind)
{
    unsigned use = 0;
    size_t j;
    for (j = 0; j < v->p; j++) {
        if (v->param[j].input != kind) {
            continue;
        }
        use |= !v->param[j].fitted        ? BF_REP_INPUT_HELD
               : bf_rep_param_freed(v, j) ? BF_REP_INPUT_FREED
                                          : BF_REP_INPUT_OWN;
    }
    return use;
}

unsigned bf_rep_input_use(const bf_rep_study *st, bf_input kind)
{
    unsigned use = 0;
    size_t m;
    for (m = 0; m < st->n_models; m++) {
        use |= model_input_use(st->models[m], kind);
    }
    return use;
}

/* The "Free parameters" line of the exact fit: each model's parameters
 * the variant fits that the registry's model holds fixed, with their
 * ranges (bf_model_variant_exact). */
static void describe_freed(const bf_rep_study *st, FILE *fp)
{
    size_t n_freed = 0;
    size_t m;
    size_t j;
    fputs("Free parameters (besides the paper's):", fp);
    for (m = 0; m < st->n_models; m++) {
        const bf_model_type *v = st->models[m];
        int first = 1;
        for (j = 0; j < v->p; j++) {
            const bf_param *pj = &v->param[j];
            if (!bf_rep_param_freed(v, j)) {
                continue;
            }
            if (first) {
                fprintf(fp, "%s %s", n_freed > 0 ? ";" : "", v->name);
            }
            fprintf(fp, "%s %s in [%g, %g]", first ? "" : ",", pj->name,
                    pj->grid_lo,
                    pj->grid_lo + pj->grid_step * (double)(pj->grid_n - 1));
            first = 0;
            n_freed++;
        }
    }
    fputs(n_freed == 0 ? " none" : "", fp);
    if (st->opts.n_given || st->opts.n_file != NULL) {
        fputs(" (n given: fixed)", fp);
    }
    fputc('\n', fp);
}

size_t bf_rep_n_specular(const bf_rep_study *st)
{
    size_t m;
    size_t n = 0;
    for (m = 0; m < st->n_models; m++) {
        n += st->models[m]->kind == BF_MODEL_SPECULAR;
    }
    return n;
}

/* The fit of the specular models and composites (src/fit/varpro.c). */
static void describe_separable(const bf_rep_study *st, FILE *fp)
{
    size_t m;
    const char *sep = "";
    if (bf_rep_n_specular(st) == 0) {
        return;
    }
    fputs("Specular models (SPEC §9.2: NDF, masking, Fresnel):", fp);
    for (m = 0; m < st->n_models; m++) {
        const bf_model_type *t = st->models[m];
        if (t->kind == BF_MODEL_SPECULAR) {
            fprintf(fp, "%s %s (%s, %s, %s)", sep, t->name, t->ndf,
                    t->masking, t->fresnel_term);
            sep = ";";
        }
    }
    fputc('\n', fp);
    sep = "";
    fputs("Fit of", fp);
    for (m = 0; m < st->n_models; m++) {
        if (st->models[m]->kind == BF_MODEL_SPECULAR) {
            fprintf(fp, "%s %s", sep, st->models[m]->name);
            sep = ",";
        }
    }
    fprintf(fp, ": separable least squares -- the scales solved exactly "
                "(non-negative least squares) at every point, a product "
                "grid over the other parameters, then Levenberg-Marquardt "
                "(turning quasi-Newton near a large-residual minimum) from "
                "the grid's lowest local minima%s (doc/methods.md §1, "
                "\"The specular models and the composites: separable least "
                "squares\")\n",
            st->opts.objective == BF_OBJ_NGAN
                ? ""
                : ", from whose ngan optimum Nelder-Mead minimises the "
                  "objective over every free parameter");
}

/* What Table 3 shows under obj. */
static const char *table3_label(bf_objective obj)
{
    return obj == BF_OBJ_MAX    ? "LSE"
           : obj == BF_OBJ_NGAN ? "E = sqrt(S / K) of the ngan objective"
                                : "objective S";
}

/* 1 when some fit ended on a bound (Table 2's asterisk). */
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

void bf_rep_table2_title(const bf_rep_study *st, int grid_beside, char *buf,
                         size_t len)
{
    const char *what = !st->opts.exact ? "grid optima"
                       : grid_beside  ? "exact optimum (grid optimum)"
                                      : "exact optima";
    const char *note = !any_bound_hit(&st->spec, st->rows) ? ""
                       : st->opts.exact ? "; * on a bound of the search range"
                                        : "; * on a grid bound";
    snprintf(buf, len, "Table 2: fitted parameters (%s%s)", what, note);
}

void bf_rep_table3_title(const bf_rep_study *st, int file, char *buf,
                         size_t len)
{
    const char *label = table3_label(st->opts.objective);
    if (st->opts.channel != NULL && strcmp(st->opts.channel, "joint") == 0) {
        /* SPEC §9.4: one E per joint fit, the same on its channels' rows */
        snprintf(buf, len,
                 "Table 3: E = sqrt(S / (K C)) of the ngan objective of each "
                 "joint fit, S over the K used configurations (theta_i, "
                 "theta_o <= 80 deg) of all C channels; the same on every "
                 "channel's row (SPEC §9.4, §10)");
    } else if (bf_objective_keeps_scale(st->opts.objective)) {
        snprintf(buf, len,
                 "Table 3: %s (over each sample's used configurations with "
                 "theta_i, theta_o <= 80 deg: K in fits.csv's k, SPEC §10)",
                 label);
    } else if (file) {
        snprintf(buf, len, "Table 3: %s (sum over the K used configurations)",
                 label);
    } else if (st->n_sel > 0) {
        snprintf(buf, len,
                 "Table 3: %s (sum over the K = %zu used configurations)",
                 label, st->n_sel);
    } else {
        snprintf(buf, len,
                 "Table 3: %s (sum over each sample's K used configurations)",
                 label);
    }
}

/* The fit, objective, interval and selection lines of the description. */
static void describe_fit(const bf_rep_study *st, FILE *fp)
{
    const bf_report_options *o = &st->opts;
    size_t r;
    size_t n_spec = bf_rep_n_specular(st);
    int gridded = n_spec < st->n_models; /* a model of the paper's kind */
    if (o->exact) {
        if (gridded) {
            fprintf(fp, "Fit: exact -- %sgrid optimum, then GSL Brent (1 "
                        "parameter) or Nelder-Mead (2+) within one grid "
                        "step, |d param| < %g (doc/methods.md §2)\n",
                    n_spec > 0 ? "diffuse models: " : "", BF_REFINE_TOL);
        }
        describe_separable(st, fp);
        if (gridded) {
            describe_freed(st, fp);
        }
    }
    for (r = 0; r < o->n_range; r++) {
        fprintf(fp, "Search range: %s\n", o->range[r]);
    }
    if (bf_objective_keeps_scale(o->objective)) {
        fprintf(fp, "Objective: %s (SPEC §10): rho = BRDF x cos(theta_i) as "
                    "measured on the configurations with theta_i, theta_o "
                    "<= 80 deg, the model's scale rho_d (SPEC §9.4) solved "
                    "exactly at each evaluation%s\n",
                bf_objective_name(o->objective),
                o->objective == BF_OBJ_NGAN
                    ? "; reported E = sqrt(sum (rho - rho^)^2 / K)"
                    : "");
    } else {
        fprintf(fp, "Objective: %s (doc/methods.md §1)\n",
                bf_objective_name(o->objective));
    }
    if (st->stats == NULL) {
        fprintf(fp, "Analysis: none (add --stats for refined optima, "
                    "intervals, AIC, BIC and CV)\n");
        return;
    }
    if (st->analysis.no_intervals) {
        fprintf(fp, "Intervals: none (--intervals none: fits.csv's ci_low, "
                    "ci_high, ml_value and noise power left empty)");
    } else if (st->analysis.noise == BF_NOISE_OBJECTIVE) {
        fprintf(fp, "Intervals: 95%% profile of the objective, "
                    "n ln(S_p/S_min) <= 3.841");
    } else {
        fprintf(fp, "Intervals: 95%% profile likelihood under the noise "
                    "model '%s' (%s; fits.csv noise), n ln(S_p/S_min) <= "
                    "n ln(1 + F_{1,n-k}(0.95)/(n-k))",
                bf_noise_name(st->analysis.noise),
                bf_noise_variance(st->analysis.noise));
    }
    if (bf_rep_neyman_scope(st) == BF_REP_NEYMAN_EVERY) {
        fprintf(fp, "; a diffuse model's by the Neyman construction, each "
                    "end's threshold from %zu simulations, seed %lu "
                    "(fits.csv ci_method neyman)",
                o->n_neyman, o->seed);
    } else if (bf_rep_neyman_scope(st) == BF_REP_NEYMAN_COMPETING) {
        fprintf(fp, "; where a second minimum of a diffuse model's profile "
                    "competes with the estimate's (flag competing), the "
                    "Neyman construction, each end's threshold from %zu "
                    "simulations, seed %lu (fits.csv ci_method neyman)",
                o->n_neyman, o->seed);
    }
    if (o->n_boot >= 2) {
        fprintf(fp, "; residual bootstrap, %zu replicates, seed %lu",
                o->n_boot, o->seed);
    }
    fprintf(fp, " (doc/methods.md §3)\n");
    fprintf(fp, "Selection: AIC, BIC with Gaussian errors");
    if (o->folds >= 2) {
        fprintf(fp, "; %zu-fold cross-validation, seed %lu", o->folds,
                o->seed);
    }
    fprintf(fp, " (doc/methods.md §4-5)\n");
}

int bf_rep_study_describe(const bf_rep_study *st, FILE *fp)
{
    const bf_report_options *o = &st->opts;
    unsigned n_use = bf_rep_input_use(st, BF_INPUT_INDEX);
    unsigned on_use = bf_rep_input_use(st, BF_INPUT_ON);
    bf_rep_describe_data(st, fp);
    if (describe_configs(st, fp) != 0) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    if (bf_objective_keeps_scale(o->objective)) {
        fprintf(fp, "Normalisation: none (SPEC §10): rho = BRDF x "
                    "cos(theta_i) as measured, in sr^-1\n");
    } else {
        fprintf(fp, "Normalisation: radiance = BRDF x cos(theta_i), divided "
                    "by its maximum over the K used configurations (SPEC "
                    "§2)\n");
    }
    if (o->channel != NULL && strcmp(o->channel, "joint") == 0) {
        fprintf(fp, "Channel: joint (SPEC §9.4) -- one shape (every "
                    "parameter but the scales) for all channels, the "
                    "scales (rho_d, rho_s, A, Rd) per channel; one E = "
                    "sqrt(S / (K C)) over the K configurations of all C "
                    "channels, S summed over them; fits.csv: the shape on "
                    "channel 'joint', the scales on each channel's name\n");
    } else if (o->channel != NULL && strcmp(o->channel, "mean") != 0) {
        fprintf(fp, "Channel: %s\n", o->channel);
    }
    if (!o->exact) {
        fprintf(fp, "Fit: exhaustive 501-point grids (SPEC §7.4), LSE = sum "
                    "of squared differences\n");
    }
    describe_fit(st, fp);
    /* the inputs of the models that ran (bf_rep_input_use) */
    if ((n_use & BF_REP_INPUT_HELD) && o->n_file != NULL) {
        fprintf(fp, "Refractive index (FC): per sample from %s\n", o->n_file);
    } else if (n_use & BF_REP_INPUT_HELD) {
        fprintf(fp, "Refractive index (FC): n = %g\n", o->n);
    }
    if (on_use != 0 && o->on_file != NULL) {
        fprintf(fp, "Oren-Nayar: rho, sigma %s %s\n",
                (on_use & BF_REP_INPUT_FREED)
                    ? "fitted; tabulated values (compared) from"
                    : "from",
                o->on_file);
    }
    fputc('\n', fp);
    return BF_REPORT_OK;
}

static int build_tables(const bf_rep_study *st, bf_tt **t2, bf_tt **t3)
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
            ncols2 += (size_t)bf_rep_shows_param(spec->models[m], j);
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
            if (bf_rep_shows_param(type, j)) {
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
        bf_rep_sample_title(st, s, title, sizeof title);
        bf_tt_set(*t2, 0, "%d", sample);
        bf_tt_set(*t2, 1, "%s", title);
        bf_tt_set(*t3, 0, "%d", sample);
        bf_tt_set(*t3, 1, "%s", title);
        c = 2;
        for (m = 0; m < spec->n_models; m++) {
            const bf_study_row *r = &rows[s * spec->n_models + m];
            for (j = 0; j < r->type->p; j++) {
                if (!bf_rep_shows_param(r->type, j)) {
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
    return bf_tt_failed(*t2) || bf_tt_failed(*t3) ? -1 : 0;
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
            bf_rep_note("note: %s not evaluated for %zu of %zu sample%s (%s)",
                        spec->models[m]->name, missing, spec->n_targets,
                        spec->n_targets == 1 ? "" : "s",
                        (model_input_use(spec->models[m], BF_INPUT_ON) &
                         BF_REP_INPUT_HELD)
                            ? "no rho, sigma given: use --on-params"
                            : "missing per-sample input");
        }
    }
}

static int write_outputs(const bf_rep_study *st, const bf_tt *t2,
                         const bf_tt *t3)
{
    bf_out f[3];
    char title[BF_REP_TITLE_LEN];
    size_t i;
    size_t opened = 0;
    int rc = bf_rep_make_outdir(st->out_dir);
    static const char *const names[3] = {"fits.csv", "table2.md",
                                         "table3.md"};
    if (rc != BF_REPORT_OK) {
        return rc;
    }
    for (i = 0; i < 3; i++) {
        rc = bf_out_open(&f[i], st->out_dir, names[i]);
        if (rc != BF_REPORT_OK) {
            goto fail;
        }
        opened++;
    }
    rc = bf_fits_csv_write(f[0].fp, &st->spec, st->rows, st->stats,
                           st->stats != NULL ? &st->analysis : NULL);
    if (rc != BF_OK) {
        rc = bf_rep_write_error("fits.csv", rc);
        goto fail;
    }
    bf_rep_table2_title(st, 1, title, sizeof title);
    fprintf(f[1].fp, "%s\n\n", title);
    bf_tt_print(t2, f[1].fp);
    bf_rep_table3_title(st, 1, title, sizeof title);
    fprintf(f[2].fp, "%s\n\n", title);
    bf_tt_print(t3, f[2].fp);
    for (i = 0; i < 3; i++) {
        rc = bf_out_commit(&f[i]);
        if (rc != BF_REPORT_OK) {
            opened = 3; /* the committed ones stay; abort the rest */
            for (i = i + 1; i < 3; i++) {
                bf_out_abort(&f[i]);
            }
            return rc;
        }
    }
    return BF_REPORT_OK;
fail:
    for (i = 0; i < opened; i++) {
        bf_out_abort(&f[i]);
    }
    return rc;
}

/* dispersion.csv (bf_dispersion_csv_write), when some fit gives n against
 * wavelength (--fresnel dielectric on spectral channels); *written = 1
 * then. */
static int write_dispersion(const bf_rep_study *st, int *written)
{
    bf_out f;
    int rc;
    *written = bf_dispersion_points(&st->spec, st->rows, st->stats, NULL) > 0;
    if (!*written) {
        return BF_REPORT_OK;
    }
    rc = bf_out_open(&f, st->out_dir, "dispersion.csv");
    if (rc != BF_REPORT_OK) {
        return rc;
    }
    rc = bf_dispersion_csv_write(f.fp, &st->spec, st->rows, st->stats);
    if (rc != BF_OK) {
        bf_out_abort(&f);
        return bf_rep_write_error("dispersion.csv", rc);
    }
    return bf_out_commit(&f);
}

/* The energy table (energy.h) when some fit is specular. */
static void energy(const bf_rep_study *st, FILE *fp)
{
    size_t n;
    size_t over;
    bf_tt *t = bf_rep_energy_table(&st->spec, st->rows, &n, &over);
    if (t == NULL) {
        return;
    }
    fprintf(fp, "\n%s: %zu of %zu over 1\n\n", BF_REP_ENERGY_TITLE, over,
            n);
    bf_tt_print(t, fp);
    bf_tt_free(t);
}

/* With --fit exact and --on-params: the fitted values of the model whose
 * inputs are the ON table (rho, sigma; its profile intervals) beside the
 * tabulated ones. */
static void on_compare(const bf_rep_study *st, FILE *fp)
{
    bf_tt *t;
    size_t m;
    size_t s;
    if (!st->opts.exact || st->in.on_params == NULL || st->stats == NULL) {
        return;
    }
    for (m = 0; m < st->n_models; m++) {
        const bf_model_type *v = st->models[m];
        if (v->p == 2 && v->param[0].input == BF_INPUT_ON &&
            v->param[1].input == BF_INPUT_ON && v->param[0].fitted &&
            v->param[1].fitted) {
            break; /* ON with its tabulated inputs fitted */
        }
    }
    if (m == st->n_models || (t = bf_tt_alloc(6)) == NULL) {
        return;
    }
    bf_tt_header(t, 0, "No.");
    bf_tt_header(t, 1, "Sample");
    bf_tt_header(t, 2, "rho fitted (ML) [95% CI]");
    bf_tt_header(t, 3, "rho CURET");
    bf_tt_header(t, 4, "sigma fitted (ML) [95% CI]");
    bf_tt_header(t, 5, "sigma CURET");
    for (s = 0; s < st->n_samples; s++) {
        size_t i = s * st->n_models + m;
        const bf_fit_stats *f = &st->stats[i];
        double rho;
        double sigma;
        char cell[128];
        if (st->rows[i].status != BF_OK || !f->done ||
            bf_sample_table_get(st->in.on_params, st->samples[s],
                                st->models[m]->param[0].input_col, &rho) !=
                BF_OK ||
            bf_sample_table_get(st->in.on_params, st->samples[s],
                                st->models[m]->param[1].input_col, &sigma) != BF_OK ||
            bf_tt_add_row(t) != 0) {
            continue;
        }
        bf_tt_set(t, 0, "%d", st->samples[s]);
        bf_tt_set(t, 1, "%s", bf_rep_sample_name(st, s));
        bf_rep_estimate_text(cell, sizeof cell, f->refined.param[0], f, 0);
        bf_tt_set(t, 2, "%s", cell);
        bf_tt_set(t, 3, "%.2f", rho);
        bf_rep_estimate_text(cell, sizeof cell, f->refined.param[1], f, 1);
        bf_tt_set(t, 4, "%s", cell);
        bf_tt_set(t, 5, "%.2f", sigma);
    }
    fprintf(fp, "\nOren-Nayar fitted (exact) against CURET's tabulated "
                "rho, sigma\n\n");
    bf_tt_print(t, fp);
    bf_tt_free(t);
}

int bf_rep_study_write_tables(const bf_rep_study *st)
{
    bf_tt *t2 = NULL;
    bf_tt *t3 = NULL;
    FILE *fp = st->opts.echo;
    char title[BF_REP_TITLE_LEN];
    int dispersion = 0;
    int rc;

    report_missing(&st->spec, st->rows);
    if (build_tables(st, &t2, &t3) != 0) {
        bf_rep_err("out of memory");
        rc = BF_REPORT_SOFTWARE;
        goto done;
    }
    rc = write_outputs(st, t2, t3);
    if (rc == BF_REPORT_OK) {
        rc = write_dispersion(st, &dispersion);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_calibration_write(st); /* --calibrate */
    }
    if (rc != BF_REPORT_OK || st->opts.echo == NULL) {
        goto done;
    }
    rc = bf_rep_study_describe(st, fp);
    if (rc != BF_REPORT_OK) {
        goto done;
    }
    bf_rep_table2_title(st, 1, title, sizeof title);
    fprintf(fp, "%s\n\n", title);
    bf_tt_print(t2, fp);
    fputc('\n', fp);
    bf_rep_table3_title(st, 0, title, sizeof title);
    fprintf(fp, "%s\n\n", title);
    bf_tt_print(t3, fp);
    energy(st, fp);
    on_compare(st, fp);
    if (st->opts.calibrate > 0) {
        rc = bf_rep_calibration_print(st, fp);
    }
    fprintf(fp, "\nWritten: %s/fits.csv, %s/table2.md, %s/table3.md",
           st->out_dir, st->out_dir, st->out_dir);
    if (st->opts.calibrate > 0) {
        fprintf(fp, ", %s/calibrate.csv", st->out_dir);
    }
    if (dispersion) {
        fprintf(fp, ", %s/dispersion.csv", st->out_dir);
    }
    fputc('\n', fp);
done:
    bf_tt_free(t2);
    bf_tt_free(t3);
    return rc;
}
