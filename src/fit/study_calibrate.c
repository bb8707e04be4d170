/* study_calibrate.c: bf_fit_calibrate for a pair of an analysed study -- the
 * target's configurations and data as the analysis fitted them, the pair's
 * refined parameters and fitted noise model (doc/methods.md §3,
 * `brdffit calibrate`). */
#include <math.h>
#include <string.h>

#include "fit/engine.h"

/* Study errors name no file: err->msg says what went wrong. */
#define STUDY_ERR(err, code, ...)                                           \
    (bf__error_clear((err), "study"),                                      \
     bf__error_set((err), (code), 0, __VA_ARGS__))

int bf_study_calibrate(const bf_study_spec *spec,
                       const bf_analysis_opts *opts,
                       const bf_study_row *rows, const bf_fit_stats *stats,
                       size_t u, size_t n_sim, unsigned long seed,
                       bf_calibration *out, bf_error *err)
{
    bf__groups_t gs;
    const bf_study_row *r;
    const bf_fit_stats *st;
    bf_problem pb;
    size_t t;
    size_t i;
    int rc;
    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        out == NULL || spec->n_models == 0 ||
        u >= spec->n_targets * spec->n_models || !stats[u].done) {
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
    t = u / spec->n_models;
    if (spec->targets[t].joint) { /* one channel's simulation is not it */
        return STUDY_ERR(err, BF_EINVAL,
                         "calibrate: a --channel joint fit (SPEC §9.4) is "
                         "not simulated; calibrate one channel");
    }
    if (st->ci_method != BF_CI_PROFILE_LIK || !isfinite(st->noise_sigma)) {
        return STUDY_ERR(err, BF_EDOM,
                         "calibrate: %s on material %d: its noise cannot be "
                         "estimated (K = %zu configurations for %zu "
                         "parameters, the scale and the noise power)",
                         r->type->name, r->sample, st->n, st->k);
    }
    rc = bf__study_groups_fit(spec, opts->objective, &gs, err); /* as fitted */
    if (rc != BF_OK) {
        return rc;
    }
    rc = BF_EINVAL;
    for (i = 0; i < gs.n; i++) {
        const bf__group_t *g = &gs.g[i];
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
            rc = bf_fit_calibrate(&pb, st->refined.param, st->noise_power,
                                  st->noise_sigma, opts->noise, n_sim,
                                  opts->n_boot, seed, opts->level, out);
        }
        break;
    }
    bf__study_groups_free(&gs);
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
