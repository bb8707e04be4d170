/* exact.c: the study beyond the paper in the CLI -- model variants for
 * --fit exact and --range, the analysis run (refinement, intervals, AIC,
 * BIC, cross-validation; doc/methods.md), its description lines and the
 * columns it adds to fits.csv. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "texttable.h"

/* Search range of ON's parameters when --fit exact fits them: rho in
 * [0.05, 1] (rho = 0 gives no radiance to normalise), sigma in [0, 1.57]
 * radians (SPEC §5's domain is [0, pi/2]). */
#define ON_RHO_LO 0.05
#define ON_RHO_STEP 0.05
#define ON_SIGMA_HI 1.57
#define ON_SIGMA_STEP 0.01

int bf_cli_parse_range(const char *s, char *name, size_t name_len,
                       double *lo, double *hi, char *msg, size_t msg_len)
{
    const char *eq = strchr(s, '=');
    const char *colon = eq != NULL ? strchr(eq + 1, ':') : NULL;
    char num[64];
    size_t len;
    if (eq == NULL || colon == NULL || eq == s ||
        (size_t)(eq - s) >= name_len) {
        snprintf(msg, msg_len, "'%s' is not NAME=LO:HI", s);
        return -1;
    }
    memcpy(name, s, (size_t)(eq - s));
    name[eq - s] = '\0';
    len = (size_t)(colon - eq - 1);
    if (len == 0 || len >= sizeof num) {
        snprintf(msg, msg_len, "'%s': bad lower bound", s);
        return -1;
    }
    memcpy(num, eq + 1, len);
    num[len] = '\0';
    if (bf_cli_parse_double(num, lo) != 0 ||
        bf_cli_parse_double(colon + 1, hi) != 0 || !(*lo < *hi)) {
        snprintf(msg, msg_len, "'%s': LO and HI must be numbers, LO < HI",
                 s);
        return -1;
    }
    return 0;
}

/* Applies the --range options to variant v of model type; *used gets bit
 * r set when range r names a parameter of the model. */
static int apply_ranges(const char *hint, const bf_cli_opts *o,
                        bf_model_variant *v, unsigned *used)
{
    size_t r;
    for (r = 0; r < o->n_range; r++) {
        char name[32];
        char msg[128];
        double lo;
        double hi;
        int j;
        const bf_param *pj;
        double step;
        bf_cli_parse_range(o->range[r], name, sizeof name, &lo, &hi, msg,
                           sizeof msg);
        j = bf_model_param_index(&v->type, name);
        if (j < 0) {
            continue;
        }
        *used |= 1u << r;
        pj = &v->type.param[j];
        /* keep the parameter's grid step; a parameter without a grid gets
         * 100 intervals */
        step = pj->grid_n > 0 ? pj->grid_step : (hi - lo) / 100.0;
        if (bf_model_variant_fit(v, name, lo, hi, step) != BF_OK) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, 
                hint, "--range %s: %s's %s must stay in [%g, %g] with "
                "at most %d grid points (step %g)",
                o->range[r], v->type.name, name, pj->min, pj->max,
                BF_VARIANT_MAX_GRID, step);
        }
    }
    return BF_EXIT_OK;
}

int bf_cli_exact_models(bf_cli_study *st)
{
    const bf_cli_opts *o = &st->opts;
    unsigned used = 0;
    size_t m;
    size_t r;
    char hint[64];
    snprintf(hint, sizeof hint, "%s ", st->cmd);
    if (!o->exact && o->n_range == 0) {
        return BF_EXIT_OK;
    }
    st->variants = calloc(st->n_models + 1, sizeof *st->variants);
    if (st->variants == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    for (m = 0; m < st->n_models; m++) {
        bf_model_variant *v = &st->variants[m];
        const bf_model_type *base = st->models[m];
        int rc;
        bf_model_variant_init(v, base);
        if (o->exact) {
            /* doc/methods.md §6: n free unless fixed by the user; ON fitted */
            if (bf_model_param_index(base, "m") >= 0 &&
                bf_model_param_index(base, "n") >= 0 && !o->n_given &&
                o->n_file == NULL) {
                bf_model_variant_fit(v, "n", BF_FREE_N_LO, BF_FREE_N_HI,
                                     BF_FREE_N_STEP);
            }
            if (base == bf_model_on) {
                bf_model_variant_fit(v, "rho", ON_RHO_LO, 1.0, ON_RHO_STEP);
                bf_model_variant_fit(v, "sigma", 0.0, ON_SIGMA_HI,
                                     ON_SIGMA_STEP);
            }
        }
        rc = apply_ranges(hint, o, v, &used);
        if (rc != BF_EXIT_OK) {
            return rc;
        }
        st->models[m] = &v->type;
    }
    for (r = 0; r < o->n_range; r++) {
        if (!((used >> r) & 1u)) {
            return bf_cli_usage_fail(BF_EXIT_BADVALUE, hint, "--range %s: no selected "
                                      "model has that parameter",
                                      o->range[r]);
        }
    }
    return BF_EXIT_OK;
}

int bf_cli_exact_run(bf_cli_study *st)
{
    const bf_cli_opts *o = &st->opts;
    bf_analysis_opts a;
    bf_cli_progress progress;
    bf_error err;
    int rc;
    st->stats = calloc(st->n_samples * st->n_models + 1, sizeof *st->stats);
    if (st->stats == NULL) {
        bf_cli_err("out of memory");
        return BF_EXIT_SOFTWARE;
    }
    memset(&a, 0, sizeof a);
    a.objective = o->objective;
    a.exact = o->exact;
    a.level = 0.95;
    a.n_boot = o->n_boot;
    a.folds = o->folds;
    a.seed = o->seed;
    bf_cli_progress_init(&progress, "analysing (material, model) pairs",
                         o->quiet);
    a.progress = bf_cli_progress_cb;
    a.progress_ctx = &progress;
    rc = bf_study_analyse(&st->spec, &a, st->rows, st->stats, &err);
    bf_cli_progress_end(&progress);
    if (rc != BF_OK) {
        bf_cli_err("%s", err.msg);
        return err.code == BF_ENOMEM ? BF_EXIT_SOFTWARE : BF_EXIT_DATAERR;
    }
    return BF_EXIT_OK;
}

void bf_cli_exact_describe(const bf_cli_study *st, FILE *fp)
{
    const bf_cli_opts *o = &st->opts;
    size_t r;
    if (o->exact) {
        fprintf(fp, "Fit: exact -- grid optimum, then GSL Brent (1 "
                    "parameter) or Nelder-Mead (2+) within one grid step, "
                    "|d param| < %g (doc/methods.md §2)\n",
                BF_REFINE_TOL);
        fprintf(fp, "Free parameters: FC's n in [%g, %g]%s; ON's rho, sigma "
                    "fitted\n",
                BF_FREE_N_LO, BF_FREE_N_HI,
                (o->n_given || o->n_file != NULL) ? " (not: n given)" : "");
    }
    for (r = 0; r < o->n_range; r++) {
        fprintf(fp, "Search range: %s\n", o->range[r]);
    }
    fprintf(fp, "Objective: %s (doc/methods.md §1)\n",
            bf_objective_name(o->objective));
    if (st->stats == NULL) {
        fprintf(fp, "Analysis: none (add --stats for refined optima, "
                    "intervals, AIC, BIC and CV)\n");
        return;
    }
    fprintf(fp, "Intervals: 95%% profile, n ln(S/S_min) <= 3.841");
    if (o->n_boot >= 2) {
        fprintf(fp, "; percentile bootstrap, %zu resamples, seed %lu",
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

void bf_cli_exact_csv_header(FILE *fp)
{
    fputs(",objective,fit,grid_value,grid_lse,refined_value,refined_lse,"
          "ci_low,ci_high,ci_method,ci_open,boot_low,boot_high,n_params,aic,"
          "bic,cv,flags",
          fp);
}

/* What the fit says about itself: space-separated words (empty: none). */
static void flags_field(FILE *fp, const bf_model_type *type,
                        const bf_fit_stats *s)
{
    const char *sep = "";
    size_t j;
    fputc(',', fp);
    if (s->flags & BF_STAT_REDUCED) {
        fprintf(fp, "%sreduces_to=%s", sep, s->reduces_to);
        sep = " ";
    }
    for (j = 0; j < type->p; j++) {
        if ((s->refined.flat >> j) & 1u) {
            fprintf(fp, "%snot_identified=%s", sep, type->param[j].name);
            sep = " ";
        }
    }
    if (s->flags & BF_STAT_CLAMPED) {
        fprintf(fp, "%sclamped=%zu", sep, s->n_clamped);
        sep = " ";
    }
    if (s->flags & BF_STAT_NOCONV) {
        fprintf(fp, "%snot_converged", sep);
        sep = " ";
    }
    if (s->flags & BF_STAT_CI_FAIL) {
        fprintf(fp, "%sinterval_failed", sep);
        sep = " ";
    }
    if (s->flags & BF_STAT_BOOT_FAIL) {
        fprintf(fp, "%sbootstrap_failed", sep);
        sep = " ";
    }
    for (j = 0; j < type->p; j++) {
        if ((s->boot_split >> j) & 1u) {
            fprintf(fp, "%sbootstrap_split=%s", sep, type->param[j].name);
            sep = " ";
        }
    }
}

/* A number, or an empty field for NaN. */
static void num(FILE *fp, double x)
{
    if (isfinite(x)) {
        fprintf(fp, ",%.10g", x);
    } else {
        fputc(',', fp);
    }
}

void bf_cli_exact_csv_cols(const bf_cli_study *st, size_t i, size_t j,
                           FILE *fp)
{
    const bf_fit_stats *s = st->stats != NULL ? &st->stats[i] : NULL;
    int has = j != SIZE_MAX;
    fprintf(fp, ",%s,%s", bf_objective_name(st->opts.objective),
            st->opts.exact ? "exact" : "paper");
    if (s == NULL || !s->done) {
        fputs(",,,,,,,,,,,,,,,", fp);
        return;
    }
    num(fp, has ? s->grid.param[j] : NAN);
    num(fp, s->grid.lse);
    num(fp, has ? s->refined.param[j] : NAN);
    num(fp, s->refined.lse);
    num(fp, has ? s->ci_low[j] : NAN);
    num(fp, has ? s->ci_high[j] : NAN);
    fprintf(fp, ",%s", has ? "profile" : "");
    if (has) {
        fprintf(fp, ",%u", (s->ci_open >> (2 * j)) & 3u);
    } else {
        fputc(',', fp);
    }
    num(fp, has ? s->boot_low[j] : NAN);
    num(fp, has ? s->boot_high[j] : NAN);
    fprintf(fp, ",%zu", s->k);
    num(fp, s->aic);
    num(fp, s->bic);
    num(fp, s->cv);
    flags_field(fp, st->rows[i].type, s);
}

void bf_cli_exact_on_compare(const bf_cli_study *st, FILE *fp)
{
    bf_tt *t;
    size_t m;
    size_t s;
    if (!st->opts.exact || st->in.on_params == NULL || st->stats == NULL) {
        return;
    }
    for (m = 0; m < st->n_models; m++) {
        if (strcmp(st->models[m]->name, "ON") == 0) {
            break;
        }
    }
    if (m == st->n_models || (t = bf_tt_alloc(6)) == NULL) {
        return;
    }
    bf_tt_header(t, 0, "No.");
    bf_tt_header(t, 1, "Sample");
    bf_tt_header(t, 2, "rho fitted [95% CI]");
    bf_tt_header(t, 3, "rho CURET");
    bf_tt_header(t, 4, "sigma fitted [95% CI]");
    bf_tt_header(t, 5, "sigma CURET");
    for (s = 0; s < st->n_samples; s++) {
        size_t i = s * st->n_models + m;
        const bf_fit_stats *f = &st->stats[i];
        double rho;
        double sigma;
        if (st->rows[i].status != BF_OK || !f->done ||
            bf_sample_table_get(st->in.on_params, st->samples[s], 0, &rho) !=
                BF_OK ||
            bf_sample_table_get(st->in.on_params, st->samples[s], 1,
                                &sigma) != BF_OK ||
            bf_tt_add_row(t) != 0) {
            continue;
        }
        bf_tt_set(t, 0, "%d", st->samples[s]);
        bf_tt_set(t, 1, "%s", bf_cli_sample_name(st, s));
        bf_tt_set(t, 2, "%.3f [%.3f, %.3f]", f->refined.param[0],
                  f->ci_low[0], f->ci_high[0]);
        bf_tt_set(t, 3, "%.2f", rho);
        bf_tt_set(t, 4, "%.3f [%.3f, %.3f]", f->refined.param[1],
                  f->ci_low[1], f->ci_high[1]);
        bf_tt_set(t, 5, "%.2f", sigma);
    }
    fprintf(fp, "\nOren-Nayar fitted (exact) against CURET's tabulated "
                "rho, sigma\n\n");
    bf_tt_print(t, fp);
    bf_tt_free(t);
}
