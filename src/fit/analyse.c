/* analyse.c: the study beyond the paper -- for every sample and model, the
 * grid optimum under the chosen objective, its exact refinement, profile
 * and bootstrap intervals, AIC, BIC and the cross-validated error
 * (doc/methods.md).
 *
 * [1] SPEC §2, §7 (data, configurations, grid), doc/methods.md §1-§5.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* Study errors name no file: err->msg says what went wrong. */
#define STUDY_ERR(err, code, ...)                                           \
    (bf__error_clear((err), "study"),                                      \
     bf__error_set((err), (code), 0, __VA_ARGS__))

static void stats_clear(bf_fit_stats *st)
{
    size_t j;
    memset(st, 0, sizeof *st);
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        st->ci_low[j] = NAN;
        st->ci_high[j] = NAN;
        st->boot_low[j] = NAN;
        st->boot_high[j] = NAN;
    }
    st->aic = NAN;
    st->bic = NAN;
    st->cv = NAN;
}

/* Analyses one (sample, model) problem. Returns BF_OK, or a code for the
 * row (BF_EDOM: the model cannot fit these data), or BF_ENOMEM. */
static int analyse_one(const bf_problem *pb, const bf_curves *curves,
                       const bf_analysis_opts *opts, bf_fit_stats *st)
{
    size_t j;
    int rc;

    st->objective = pb->objective;
    st->free_mask = pb->free_mask;
    st->n = pb->n;
    st->k = bf_problem_nparams(pb);
    rc = bf_curves_best(curves, pb, &st->grid);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_fit_refine(pb, &st->grid, &st->refined);
    if (rc != BF_OK && rc != BF_ENOCONV) {
        return rc;
    }
    for (j = 0; j < pb->type->p; j++) {
        unsigned open = 0;
        if (!((pb->free_mask >> j) & 1u)) {
            continue;
        }
        rc = bf_fit_profile_ci(pb, &st->refined, j, opts->level,
                               &st->ci_low[j], &st->ci_high[j], &open);
        if (rc == BF_ENOMEM) {
            return rc;
        }
        st->ci_open |= open << (2 * j);
    }
    if (opts->n_boot >= 2) {
        rc = bf_fit_bootstrap(pb, curves, opts->n_boot, opts->seed,
                              opts->level, st->boot_low, st->boot_high);
        if (rc == BF_ENOMEM) {
            return rc;
        }
    }
    if (st->refined.lse > 0.0) {
        st->aic = bf_aic(st->refined.lse, pb->n, st->k);
        st->bic = bf_bic(st->refined.lse, pb->n, st->k);
    }
    if (opts->folds >= 2 && opts->folds <= pb->n) {
        rc = bf_fit_cv(pb, curves, opts->folds, opts->seed, &st->cv);
        if (rc == BF_ENOMEM) {
            return rc;
        }
    }
    st->done = 1;
    return BF_OK;
}

/* Analyses every model for the targets of group g; curves are built once
 * per model and rebuilt only when a target's fixed inputs differ (as the
 * study's grids). Returns BF_OK or BF_ENOMEM (err filled). */
static int analyse_group(const bf_study_spec *spec, const bf__group_t *g,
                         const bf_analysis_opts *opts, bf_study_row *rows,
                         bf_fit_stats *stats, bf_error *err)
{
    bf_curves *curves = NULL;
    double cur_fixed[BF_MAX_PARAMS];
    size_t s;
    size_t m;
    int rc = BF_OK;

    for (m = 0; m < spec->n_models && rc == BF_OK; m++) {
        const bf_model_type *type = spec->models[m];
        for (s = 0; s < g->n_members; s++) {
            size_t t = g->members[s];
            size_t i = t * spec->n_models + m;
            bf_study_row *r = &rows[i];
            bf_fit_stats *st = &stats[i];
            double fixed[BF_MAX_PARAMS] = {0};
            bf_problem pb;
            int status;
            stats_clear(st);
            status = bf__study_inputs(spec, type, t, fixed);
            if (status == BF_OK) {
                bf_problem_init(&pb, type, fixed, g->n_sel, g->geom,
                                g->data + s * g->n_sel);
                pb.objective = opts->objective;
                if (curves == NULL ||
                    memcmp(cur_fixed, fixed, sizeof fixed) != 0) {
                    bf_curves_free(curves);
                    curves = bf_curves_alloc(&pb, &status);
                    memcpy(cur_fixed, fixed, sizeof fixed);
                }
            }
            if (status == BF_OK) {
                status = analyse_one(&pb, curves, opts, st);
            }
            if (status == BF_ENOMEM) {
                rc = BF_ENOMEM;
                STUDY_ERR(err, rc, "out of memory (%s, %zu configurations)",
                          type->name, g->n_sel);
                break;
            }
            if (opts->exact) { /* the refined optimum is the result */
                const bf_target *tg = &spec->targets[t];
                r->target = t;
                r->material = tg->material;
                r->sample = bf_dataset_number(spec->data, tg->material);
                r->channel = tg->channel;
                r->k = g->n_sel;
                r->type = type;
                r->status = status;
                if (status == BF_OK) {
                    r->fit = st->refined;
                }
            }
        }
        bf_curves_free(curves);
        curves = NULL;
    }
    return rc;
}

int bf_study_analyse(const bf_study_spec *spec, const bf_analysis_opts *opts,
                     bf_study_row *rows, bf_fit_stats *stats, bf_error *err)
{
    bf__groups_t gs = {NULL, 0};
    size_t i;
    int rc;

    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        spec->data == NULL ||
        (spec->n_targets > 0 && spec->targets == NULL) ||
        (spec->n_models > 0 && spec->models == NULL) ||
        bf_objective_name(opts->objective) == NULL ||
        !(opts->level > 0.0 && opts->level < 1.0)) {
        STUDY_ERR(err, BF_EINVAL, "invalid analysis specification");
        return BF_EINVAL;
    }
    rc = bf__study_groups(spec, &gs, err);
    for (i = 0; rc == BF_OK && i < gs.n; i++) {
        rc = analyse_group(spec, &gs.g[i], opts, rows, stats, err);
    }
    bf__study_groups_free(&gs);
    return rc;
}
