/* study_profile.c: the profiles behind an analysed pair's intervals, as the
 * report draws them (figures/profile_sampleN, doc/methods.md §3) -- the
 * target's data as fitted, the pair's fit, each free parameter's window
 * around the estimate its interval is about, and the curve the interval
 * thresholds (bf_fit_interval_curve, profile_curve.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* The window: the interval widened PROFILE_SPAN times on each side. */
#define PROFILE_SPAN 2.5

/* Study errors name no file: err->msg says what went wrong. */
#define STUDY_ERR(err, code, ...)                                           \
    (bf__error_clear((err), "study"),                                      \
     bf__error_set((err), (code), 0, __VA_ARGS__))

/* n values of parameter j of pb evenly over its window into theta: the
 * interval [lo, hi] around est widened PROFILE_SPAN times on each side
 * (3 of the profile's first steps on a side where it has no width),
 * within pb's range. */
static void window(const bf_problem *pb, size_t j, double est, double lo,
                   double hi, size_t n, double *theta)
{
    double step = bf__profile_step(pb, j, est); /* the profile's own */
    double x0;
    double x1;
    size_t k;
    x0 = est - PROFILE_SPAN *
                   (isfinite(lo) && est - lo > 0.0 ? est - lo : 3.0 * step);
    x1 = est + PROFILE_SPAN *
                   (isfinite(hi) && hi - est > 0.0 ? hi - est : 3.0 * step);
    x0 = fmax(x0, pb->lo[j]);
    x1 = fmin(x1, pb->hi[j]);
    if (!(x1 > x0)) {
        x0 = pb->lo[j];
        x1 = pb->hi[j];
    }
    for (k = 0; k < n; k++) {
        theta[k] = x0 + (x1 - x0) * (double)k / (double)(n - 1);
    }
    theta[n - 1] = x1; /* no rounding past the range */
}

int bf_study_profiles(const bf_study_spec *spec, const bf_analysis_opts *opts,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      size_t u, size_t n, double *theta, double *dev,
                      double *thr, bf_error *err)
{
    const bf_fit_stats *st;
    const bf_study_row *r;
    size_t t;
    size_t mat;
    size_t cap;
    size_t K = 0;
    size_t *sel;
    bf_geom *geom;
    double *data;
    bf_problem pb;
    size_t j;
    size_t q = 0;
    int rc;
    if (spec == NULL || opts == NULL || rows == NULL || stats == NULL ||
        theta == NULL || (dev != NULL && thr == NULL) || n < 2 ||
        spec->n_models == 0 || u >= spec->n_targets * spec->n_models ||
        !stats[u].done || stats[u].free_mask == 0) {
        return STUDY_ERR(err, BF_EINVAL, "profiles: the pair was not "
                                         "analysed or fits nothing");
    }
    st = &stats[u];
    r = &rows[u];
    t = u / spec->n_models;
    if (spec->targets[t].joint) {
        return STUDY_ERR(err, BF_EINVAL,
                         "profiles: a --channel joint fit (SPEC §9.4) has no "
                         "profile interval");
    }
    mat = spec->targets[t].material;
    cap = bf_dataset_nconf(spec->data, mat);
    sel = malloc((cap + 1) * sizeof *sel);
    geom = malloc((cap + 1) * sizeof *geom);
    data = malloc((cap + 1) * sizeof *data);
    rc = sel == NULL || geom == NULL || data == NULL
             ? STUDY_ERR(err, BF_ENOMEM, "profiles: out of memory")
             : bf_study_fit_data(spec, opts->objective, t, sel, &K, data,
                                 err); /* the data as fitted */
    for (j = 0; rc == BF_OK && j < K; j++) {
        geom[j] = bf_dataset_geom(spec->data, mat)[sel[j]];
    }
    if (rc == BF_OK) {
        rc = bf_problem_init(&pb, spec->models[u % spec->n_models],
                             st->refined.param, K, geom, data);
        pb.objective = opts->objective;
        pb.free_mask = st->free_mask; /* as the analysis fitted it */
    }
    for (j = 0; rc == BF_OK && j < pb.type->p; j++) {
        if ((st->free_mask >> j) & 1u) {
            /* around the estimate the interval is about (the fit's where
             * there is none) */
            double est = isfinite(st->ml_param[j]) ? st->ml_param[j]
                                                   : st->refined.param[j];
            window(&pb, j, est, st->ci_low[j], st->ci_high[j], n,
                   theta + q * n);
            q++;
        }
    }
    if (rc == BF_OK && dev != NULL) {
        rc = bf__interval_curves(&pb, &st->refined, opts->noise, opts->level,
                                 st->free_mask, n, theta, dev, thr, NULL);
        if (rc == BF_EDOM) {
            STUDY_ERR(err, rc, "profiles: %s on material %d: its noise "
                               "cannot be estimated", r->type->name,
                      r->sample);
        } else if (rc != BF_OK) {
            STUDY_ERR(err, rc, "profiles: %s on material %d failed (%d)",
                      r->type->name, r->sample, rc);
        }
    }
    free(data);
    free(geom);
    free(sel);
    return rc;
}
