/* study_analysis.c: the study beyond the paper on a study specification -- its
 * targets' data, inputs and the study's grid optima handed to the engine's
 * analysis (src/fit/analysis.c): for every target and model the grid
 * optimum under the chosen objective, its exact refinement, profile and
 * bootstrap intervals, AIC, BIC and the cross-validated error
 * (doc/methods.md).
 *
 * [1] SPEC §2, §7 (data, configurations, grid), doc/methods.md §1-§5.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Study errors name no file: err->msg says what went wrong. */
#define STUDY_ERR(err, code, ...)                                           \
    (bf__error_clear((err), "study"),                                      \
     bf__error_set((err), (code), 0, __VA_ARGS__))

int bf_study_analyse(const bf_study_spec *spec, const bf_analysis_opts *opts,
                     bf_study_row *rows, bf_fit_stats *stats, bf_error *err)
{
    bf__groups_t gs = {NULL, 0};
    size_t n_units;
    const double **tdata = NULL;
    size_t *set_of = NULL;
    size_t *k_of = NULL;
    size_t *joint_n = NULL;
    double *fixed = NULL;
    int *status = NULL;
    int *unit_status = NULL;
    bf_fit_result *grid = NULL;
    bf__cset *sets = NULL;
    bf__job job;
    size_t i;
    size_t s;
    size_t m;
    int rc;

    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        spec->data == NULL ||
        (spec->n_targets > 0 && spec->targets == NULL) ||
        (spec->n_models > 0 && spec->models == NULL)) {
        STUDY_ERR(err, BF_EINVAL, "invalid analysis specification");
        return BF_EINVAL;
    }
    if (bf_analysis_opts_check(opts, err) != BF_OK) {
        return BF_EINVAL;
    }
    for (m = 0; m < spec->n_models; m++) {
        if (spec->models[m] != NULL &&
            spec->models[m]->kind == BF_MODEL_SPECULAR &&
            !bf_objective_keeps_scale(opts->objective)) {
            /* SPEC §9, §10: its scale is physical */
            STUDY_ERR(err, BF_EINVAL,
                      "%s gives absolute BRDF values (SPEC §9); the %s "
                      "objective max-normalises them: use --objective "
                      "ngan, cuberoot or log1p",
                      spec->models[m]->name,
                      bf_objective_name(opts->objective));
            return BF_EINVAL;
        }
    }
    if (bf__study_joint_check(spec, 1, opts->objective, err) != BF_OK) {
        return BF_EINVAL;
    }
    /* SPEC §10: the objectives that keep the scale compare rho as
     * measured on the configurations with theta_i, theta_o <= 80 deg */
    rc = bf__study_groups_fit(spec, opts->objective, &gs, err);
    if (rc != BF_OK) {
        return rc;
    }
    n_units = spec->n_targets * spec->n_models;
    tdata = malloc((spec->n_targets + 1) * sizeof *tdata);
    set_of = calloc(spec->n_targets + 1, sizeof *set_of);
    k_of = calloc(spec->n_targets + 1, sizeof *k_of);
    joint_n = calloc(spec->n_targets + 1, sizeof *joint_n);
    fixed = calloc((n_units + 1) * BF_MAX_PARAMS, sizeof *fixed);
    status = malloc((n_units + 1) * sizeof *status);
    unit_status = malloc((n_units + 1) * sizeof *unit_status);
    grid = calloc(n_units + 1, sizeof *grid);
    sets = calloc(gs.n + 1, sizeof *sets);
    if (tdata == NULL || set_of == NULL || k_of == NULL || joint_n == NULL ||
        fixed == NULL ||
        status == NULL || unit_status == NULL || grid == NULL ||
        sets == NULL) {
        rc = STUDY_ERR(err, BF_ENOMEM, "out of memory");
        goto done;
    }
    /* one configuration set per group: the targets sharing configurations
     * share geometry, model curves and grids */
    for (i = 0; i < gs.n; i++) {
        const bf__group_t *g = &gs.g[i];
        rc = bf__cset_init(&sets[i], g->n_sel, g->geom);
        if (rc != BF_OK) {
            rc = STUDY_ERR(err, rc, "out of memory");
            goto done;
        }
        for (s = 0; s < g->n_members; s++) {
            size_t t = g->members[s];
            set_of[t] = i;
            k_of[t] = g->n_sel;
            tdata[t] = g->data + s * g->n_sel;
        }
    }
    for (s = 0; s < spec->n_targets; s++) {
        /* a joint fit (SPEC §9.4): the material's consecutive joint
         * targets, on one configuration set (the mean's selection) */
        const bf_target *tg = &spec->targets[s];
        size_t e = s + 1;
        if (!tg->joint || (s > 0 && joint_n[s - 1] > 0 &&
                           spec->targets[s - 1].material == tg->material)) {
            continue;
        }
        while (e < spec->n_targets && spec->targets[e].joint &&
               spec->targets[e].material == tg->material) {
            joint_n[e] = SIZE_MAX;
            if (set_of[e] != set_of[s]) { /* never from bf_study_targets */
                rc = STUDY_ERR(err, BF_EINVAL, "--channel joint: the "
                               "channels of sample %d are not on the same "
                               "configurations", bf_dataset_number(
                                   spec->data, tg->material));
                goto done;
            }
            e++;
        }
        joint_n[s] = e - s;
    }
    for (s = 0; s < spec->n_targets; s++) {
        for (m = 0; m < spec->n_models; m++) {
            size_t u = s * spec->n_models + m;
            status[u] = bf__study_inputs(spec, spec->models[m], s,
                                         fixed + u * BF_MAX_PARAMS);
            /* with the paper's fit, the study's grid optima stand */
            if (!opts->exact && rows[u].status == BF_OK &&
                rows[u].type == spec->models[m]) {
                grid[u] = rows[u].fit;
            }
        }
    }
    memset(&job, 0, sizeof job);
    job.n_sets = gs.n;
    job.sets = sets;
    job.n_targets = spec->n_targets;
    job.set_of = set_of;
    job.data = tdata;
    job.n_models = spec->n_models;
    job.models = spec->models;
    job.fixed = fixed;
    job.status = status;
    job.grid = grid;
    job.opts = opts;
    job.n_threads = spec->n_threads;
    job.joint_n = joint_n;
    rc = bf__analyse(&job, stats, unit_status);
    if (rc != BF_OK) {
        rc = STUDY_ERR(err, rc, "out of memory");
        goto done;
    }
    for (s = 0; opts->exact && s < spec->n_targets; s++) {
        const bf_target *tg = &spec->targets[s];
        for (m = 0; m < spec->n_models; m++) { /* the refined optimum */
            size_t u = s * spec->n_models + m;
            bf_study_row *r = &rows[u];
            r->target = s;
            r->material = tg->material;
            r->sample = bf_dataset_number(spec->data, tg->material);
            r->channel = tg->channel;
            r->k = k_of[s];
            r->type = spec->models[m];
            r->status = unit_status[u];
            if (r->status == BF_OK) {
                r->fit = stats[u].refined;
            }
        }
    }
    if (opts->exact) {
        bf__study_rows_albedo(rows, spec->n_targets * spec->n_models,
                              spec->n_threads);
    }
    for (s = 0; opts->objective == BF_OBJ_NGAN && s < n_units; s++) {
        /* SPEC §10: the value reported is E = sqrt(S / K); a joint fit's
         * over its K C values (st->n) */
        bf_fit_stats *st = &stats[s];
        double nk = (double)st->n;
        if (st->done) {
            st->grid.lse = bf_objective_report(st->objective, st->grid.lse,
                                               nk);
            st->refined.lse = bf_objective_report(st->objective,
                                                  st->refined.lse, nk);
            if (opts->exact && rows[s].status == BF_OK) {
                rows[s].fit.lse = st->refined.lse;
            }
        }
    }

done:
    for (i = 0; sets != NULL && i < gs.n; i++) {
        bf__cset_free(&sets[i]);
    }
    free(sets);
    bf__study_groups_free(&gs);
    free(tdata);
    free(set_of);
    free(k_of);
    free(joint_n);
    free(fixed);
    free(status);
    free(unit_status);
    free(grid);
    return rc;
}
