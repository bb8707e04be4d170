/* study_calibrate.c: bf_fit_calibrate for the pairs of an analysed study --
 * the target's configurations and data as the analysis fitted them, the
 * pair's refined parameters and fitted noise model (doc/methods.md §3,
 * `brdffit calibrate`, `brdffit report --calibrate`): one pair
 * (bf_study_calibrate) or every analysed pair, in parallel
 * (bf_study_calibrate_all). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Study errors name no file: err->msg says what went wrong. */
#define STUDY_ERR(err, code, ...)                                           \
    (bf__error_clear((err), "study"),                                      \
     bf__error_set((err), (code), 0, __VA_ARGS__))

/* What can be checked of pair u before any work. */
static int check_pair(const bf_study_spec *spec, const bf_study_row *rows,
                      const bf_fit_stats *stats, size_t u, size_t n_sim,
                      bf_error *err)
{
    const bf_study_row *r;
    const bf_fit_stats *st;
    if (spec->n_models == 0 || u >= spec->n_targets * spec->n_models ||
        !stats[u].done) {
        return STUDY_ERR(err, BF_EINVAL, "calibrate: the pair was not "
                                         "analysed");
    }
    if (n_sim < BF_CALIBRATE_MIN_SIM) {
        return STUDY_ERR(err, BF_EINVAL, "calibrate: %zu simulations: at "
                                         "least %d are needed", n_sim,
                         BF_CALIBRATE_MIN_SIM);
    }
    r = &rows[u];
    st = &stats[u];
    if (spec->targets[u / spec->n_models].joint) { /* one channel's
                                                      simulation is not it */
        return STUDY_ERR(err, BF_EINVAL,
                         "calibrate: a --channel joint fit (SPEC §9.4) is "
                         "not simulated; calibrate one channel");
    }
    if ((st->ci_method != BF_CI_PROFILE_LIK &&
         st->ci_method != BF_CI_NEYMAN) ||
        !isfinite(st->noise_sigma)) {
        return STUDY_ERR(err, BF_EDOM,
                         "calibrate: %s on material %d: its noise cannot be "
                         "estimated (K = %zu configurations for %zu "
                         "parameters, the scale and the noise power)",
                         r->type->name, r->sample, st->n, st->k);
    }
    return BF_OK;
}

/* Pair u (checked) on the groups gs of the fitted data; ml_est as
 * bf__fit_calibrate's. */
static int calibrate_pair(const bf_study_spec *spec,
                          const bf_analysis_opts *opts,
                          const bf_study_row *rows,
                          const bf_fit_stats *stats, const bf__groups_t *gs,
                          size_t u, size_t n_sim, unsigned long seed,
                          double *ml_est, const bf__tick *tick,
                          bf_calibration *out, bf_error *err)
{
    const bf_study_row *r = &rows[u];
    const bf_fit_stats *st = &stats[u];
    size_t t = u / spec->n_models;
    bf_problem pb;
    size_t i;
    int rc = BF_EINVAL;
    for (i = 0; i < gs->n; i++) {
        const bf__group_t *g = &gs->g[i];
        size_t s;
        for (s = 0; s < g->n_members && g->members[s] != t; s++) {
        }
        if (s == g->n_members) {
            continue;
        }
        rc = bf_problem_init(&pb, spec->models[u % spec->n_models],
                             st->refined.param, g->n_sel, g->geom,
                             g->data + s * g->n_sel);
        if (rc == BF_OK) {
            pb.objective = opts->objective;
            rc = bf__fit_calibrate(&pb, st->refined.param, st->noise_power,
                                   st->noise_sigma, opts->noise, n_sim,
                                   opts->n_boot,
                                   pb.type->kind == BF_MODEL_SPECULAR
                                       ? 0
                                       : opts->n_neyman,
                                   opts->neyman_every, seed, opts->level,
                                   ml_est, tick, out);
        }
        break;
    }
    if (rc == BF_EDOM) {
        STUDY_ERR(err, rc, "calibrate: %s on material %d: no simulation "
                           "could be fitted, or its noise cannot be "
                           "estimated", r->type->name, r->sample);
    } else if (rc != BF_OK) {
        STUDY_ERR(err, rc, "calibrate: %s on material %d failed (%d)",
                  r->type->name, r->sample, rc);
    }
    return rc;
}

int bf_study_calibrate(const bf_study_spec *spec,
                       const bf_analysis_opts *opts,
                       const bf_study_row *rows, const bf_fit_stats *stats,
                       size_t u, size_t n_sim, unsigned long seed,
                       bf_calibration *out, bf_error *err)
{
    bf__groups_t gs;
    int rc;
    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        out == NULL) {
        return STUDY_ERR(err, BF_EINVAL, "calibrate: the pair was not "
                                         "analysed");
    }
    rc = check_pair(spec, rows, stats, u, n_sim, err);
    if (rc == BF_OK) {
        /* the data as fitted */
        rc = bf__study_groups_fit(spec, opts->objective, &gs, err);
    }
    if (rc != BF_OK) {
        return rc;
    }
    rc = calibrate_pair(spec, opts, rows, stats, &gs, u, n_sim, seed, NULL,
                        NULL, out, err);
    bf__study_groups_free(&gs);
    return rc;
}

void bf_study_calibration_free(bf_study_calibration *c)
{
    if (c == NULL) {
        return;
    }
    free(c->pair);
    free(c->cal);
    free(c->ml_est);
    memset(c, 0, sizeof *c);
}

/* The progress of bf_study_calibrate_all: simulations done of total, from
 * any thread (one at a time). */
typedef struct {
    const bf_analysis_opts *opts;
    size_t done;
    size_t total;
} progress_t;

static void progress_tick(void *ctx)
{
    progress_t *p = ctx;
#pragma omp critical(bf_calibrate_progress)
    {
        p->done++;
        p->opts->progress(p->opts->progress_ctx, p->done, p->total);
    }
}

/* The pairs of stats analysed with free parameters into out->pair. */
static int list_pairs(const bf_study_spec *spec, const bf_fit_stats *stats,
                      bf_study_calibration *out)
{
    size_t n_units = spec->n_targets * spec->n_models;
    size_t u;
    out->pair = malloc((n_units + 1) * sizeof *out->pair);
    if (out->pair == NULL) {
        return BF_ENOMEM;
    }
    for (u = 0; u < n_units; u++) {
        if (stats[u].done && stats[u].free_mask != 0) {
            out->pair[out->n++] = u;
        }
    }
    return BF_OK;
}

int bf_study_calibrate_all(const bf_study_spec *spec,
                           const bf_analysis_opts *opts,
                           const bf_study_row *rows,
                           const bf_fit_stats *stats, size_t n_sim,
                           unsigned long seed, bf_study_calibration *out,
                           bf_error *err)
{
    bf__groups_t gs;
    bf_error *errs = NULL;
    int *status = NULL;
    progress_t pr;
    bf__tick tk;
    const bf__tick *tick = NULL;
    int oom = 0;
    size_t i;
    int n_threads;
    long q;
    int rc;

    if (out != NULL) {
        memset(out, 0, sizeof *out);
    }
    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        out == NULL) {
        return STUDY_ERR(err, BF_EINVAL, "calibrate: no analysed study");
    }
    out->n_sim = n_sim;
    rc = list_pairs(spec, stats, out);
    for (i = 0; rc == BF_OK && i < out->n; i++) { /* before any work */
        rc = check_pair(spec, rows, stats, out->pair[i], n_sim, err);
    }
    if (rc != BF_OK) {
        return rc == BF_ENOMEM ? STUDY_ERR(err, rc, "out of memory") : rc;
    }
    out->cal = calloc(out->n + 1, sizeof *out->cal);
    out->ml_est = malloc((out->n * BF_MAX_PARAMS * n_sim + 1) *
                         sizeof *out->ml_est);
    errs = calloc(out->n + 1, sizeof *errs);
    status = calloc(out->n + 1, sizeof *status);
    if (out->cal == NULL || out->ml_est == NULL || errs == NULL ||
        status == NULL) {
        free(errs);
        free(status);
        return STUDY_ERR(err, BF_ENOMEM, "out of memory");
    }
    rc = bf__study_groups_fit(spec, opts->objective, &gs, err); /* as fitted */
    if (rc != BF_OK) {
        free(errs);
        free(status);
        return rc;
    }
    pr.opts = opts;
    pr.done = 0;
    pr.total = out->n * n_sim;
    tk.fn = progress_tick;
    tk.ctx = &pr;
    tick = opts->progress != NULL ? &tk : NULL;
    n_threads = spec->n_threads > 1 ? spec->n_threads : 1;
    /* every pair runs (the error reported is the first in order, for any
     * thread count) unless memory ran out */
#pragma omp parallel for schedule(dynamic, 1) num_threads(n_threads)      \
    if (n_threads > 1)
    for (q = 0; q < (long)out->n; q++) {
        size_t k = (size_t)q;
        int stop;
#pragma omp atomic read
        stop = oom;
        status[k] = stop ? BF_ENOMEM
                         : calibrate_pair(spec, opts, rows, stats, &gs,
                                          out->pair[k], n_sim, seed,
                                          out->ml_est +
                                              k * BF_MAX_PARAMS * n_sim,
                                          tick, &out->cal[k], &errs[k]);
        if (status[k] == BF_ENOMEM) {
#pragma omp atomic write
            oom = 1;
        }
    }
    bf__study_groups_free(&gs);
    for (i = 0; i < out->n && rc == BF_OK && !oom; i++) {
        if (status[i] != BF_OK) { /* the first in order that failed */
            rc = status[i];
            if (err != NULL) {
                *err = errs[i];
            }
        }
    }
    if (oom) {
        rc = STUDY_ERR(err, BF_ENOMEM, "out of memory");
    }
    free(errs);
    free(status);
    return rc;
}
