/* study.c: the study protocol of SPEC §7 -- every sample against every
 * model on one configuration selection, grid search per fitted model.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model", §5.
 * [2] SPEC §7 (protocol), §4.2 (n fixed per sample, default 1.7), §5 (ON at
 *     the tabulated rho, sigma).
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

const int bf_study_samples[BF_STUDY_NSAMPLES] = {
    1,  2,  5,  7,  9,  12, 16, 17, 20, 22, 23, 25,
    29, 31, 33, 34, 36, 37, 39, 41, 44, 54, 55, 56}; /* paper, Table 2 */

/* The study's shared state while it runs one group of targets (the
 * targets sharing configurations; "samples" below are its members). */
typedef struct {
    const bf_study_spec *spec;
    size_t n_sel;         /* K of the group */
    const bf__cset *cs;   /* its n_sel configurations, their sines and
                             cosines once per group */
    const double *data;   /* n_samples x n_sel normalised radiances */
    size_t n_samples;     /* members of the group */
    const size_t *members; /* their target indices */
    double *fixed;        /* n_models x n_samples x BF_MAX_PARAMS inputs */
    size_t *leader;       /* n_models x n_samples: the first sample with the
                             same inputs, SIZE_MAX when the row failed */
    bf_study_row *rows;
} study_t;

/* The row of member s and model m. */
static bf_study_row *row_of(const study_t *st, size_t s, size_t m)
{
    return &st->rows[st->members[s] * st->spec->n_models + m];
}

/* One unit of work: model m for the group of samples led by `leader`
 * (they share one precomputed grid), or for every sample when the model
 * fits nothing (leader = SIZE_MAX). Units are independent: each writes its
 * own rows, so they run on any thread in any order. */
typedef struct {
    size_t m;
    size_t leader;
} work_t;

/* Fills the rows of model m with each sample's inputs (or the status that
 * says they are missing) and groups samples with equal inputs. */
static void prepare_model(study_t *st, size_t m)
{
    const bf_study_spec *spec = st->spec;
    size_t ns = st->n_samples;
    size_t s;
    size_t q;
    for (s = 0; s < ns; s++) {
        bf_study_row *r = row_of(st, s, m);
        double *fx = st->fixed + ((m * ns) + s) * BF_MAX_PARAMS;
        const bf_target *tg = &spec->targets[st->members[s]];
        memset(r, 0, sizeof *r);
        memset(fx, 0, BF_MAX_PARAMS * sizeof *fx);
        r->target = st->members[s];
        r->material = tg->material;
        r->sample = bf_dataset_number(spec->data, tg->material);
        r->channel = tg->channel;
        r->k = st->n_sel;
        r->type = spec->models[m];
        r->status = bf__study_inputs(spec, r->type, r->target, fx);
        st->leader[m * ns + s] = SIZE_MAX;
        if (r->status != BF_OK) {
            continue;
        }
        st->leader[m * ns + s] = s;
        for (q = 0; q < s; q++) {
            if (st->leader[m * ns + q] == q &&
                memcmp(st->fixed + ((m * ns) + q) * BF_MAX_PARAMS, fx,
                       BF_MAX_PARAMS * sizeof *fx) == 0) {
                st->leader[m * ns + s] = q;
                break;
            }
        }
    }
}

/* A model with nothing to fit (ON, LAMBERT): one value per sample, the
 * geometry-only terms shared (SPEC §7.5). */
static int run_fixed(const study_t *st, size_t m)
{
    const bf_study_spec *spec = st->spec;
    size_t ns = st->n_samples;
    bf__fixed_model *fm = bf__fixed_alloc(spec->models[m], st->cs);
    size_t s;
    if (fm == NULL) {
        return BF_ENOMEM;
    }
    for (s = 0; s < ns; s++) {
        bf_study_row *r = row_of(st, s, m);
        if (r->status == BF_OK) {
            r->status = bf__fixed_fit(fm, st->fixed + ((m * ns) + s) *
                                                          BF_MAX_PARAMS,
                                      st->data + s * st->n_sel, &r->fit);
        }
    }
    bf__fixed_free(fm);
    return BF_OK;
}

/* The grid search of model m for the samples led by `leader`: one grid,
 * every member scored against it (SPEC §7.3-7.4). */
static int run_group(const study_t *st, size_t m, size_t leader)
{
    const bf_study_spec *spec = st->spec;
    size_t ns = st->n_samples;
    const double **group = malloc((ns + 1) * sizeof *group);
    size_t *members = malloc((ns + 1) * sizeof *members);
    double *lse = NULL;
    bf__grid *gr = NULL;
    bf__grid_layout_t lay;
    size_t n_group = 0;
    size_t cols;
    size_t q;
    int status = BF_OK;
    int rc = BF_OK;

    if (group == NULL || members == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    for (q = leader; q < ns; q++) {
        if (st->leader[m * ns + q] == leader) {
            members[n_group] = q;
            group[n_group++] = st->data + q * st->n_sel;
        }
    }
    /* the streaming kernels where the model has one: no stored curves */
    if (n_group > 0 && bf__grid_layout(spec->models[m],
                                       st->fixed + ((m * ns) + leader) *
                                                       BF_MAX_PARAMS,
                                       0, &lay) == BF_OK) {
        double *best_lse = malloc(n_group * sizeof *best_lse);
        size_t *best = malloc(n_group * sizeof *best);
        int done = -BF_ENOMEM;
        if (best_lse != NULL && best != NULL) {
            done = bf__stream_fast(spec->models[m], &lay, st->cs, n_group,
                                   group, best_lse, best);
        }
        for (q = 0; done == 1 && q < n_group; q++) {
            bf_study_row *r = row_of(st, members[q], m);
            r->status = bf__grid_result(&lay, best[q], best_lse[q],
                                        &r->fit);
        }
        free(best_lse);
        free(best);
        if (done != 0) {
            rc = done < 0 ? -done : BF_OK;
            goto done;
        }
    }
    gr = bf__grid_build(spec->models[m],
                        st->fixed + ((m * ns) + leader) * BF_MAX_PARAMS, 0,
                        st->cs, &status);
    if (gr == NULL) {
        for (q = 0; q < n_group; q++) {
            row_of(st, members[q], m)->status = status;
        }
        goto done;
    }
    cols = bf__grid_cols(gr);
    lse = malloc(n_group * cols * sizeof *lse);
    if (lse == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    bf__grid_score(gr, n_group, group, lse);
    for (q = 0; q < n_group; q++) {
        bf_study_row *r = row_of(st, members[q], m);
        r->status = bf__grid_best(gr, lse + q * cols, &r->fit);
    }

done:
    bf__grid_free(gr);
    free(lse);
    free(group);
    free(members);
    return rc;
}

/* Fits every model to every member of the group: the units of work are
 * shared among spec->n_threads OpenMP threads in one parallel loop (one
 * fork and one join per group, so a busy machine delays it once, not per
 * grid). */
static int fit_all(study_t *st)
{
    const bf_study_spec *spec = st->spec;
    size_t ns = st->n_samples;
    int n_threads = spec->n_threads > 1 ? spec->n_threads : 1;
    work_t *work = malloc((spec->n_models * (ns + 1) + 1) * sizeof *work);
    long n_work = 0;
    long w;
    size_t m;
    size_t s;
    int rc = BF_OK;

    if (work == NULL) {
        return BF_ENOMEM;
    }
    for (m = 0; m < spec->n_models; m++) {
        prepare_model(st, m);
        if (bf__fits_nothing(spec->models[m])) {
            work[n_work].m = m;
            work[n_work++].leader = SIZE_MAX;
            continue;
        }
        for (s = 0; s < ns; s++) {
            if (st->leader[m * ns + s] == s) {
                work[n_work].m = m;
                work[n_work++].leader = s;
            }
        }
    }
#pragma omp parallel for schedule(dynamic, 1) num_threads(n_threads)      \
    if (n_threads > 1)
    for (w = 0; w < n_work; w++) {
        int r = work[w].leader == SIZE_MAX
                    ? run_fixed(st, work[w].m)
                    : run_group(st, work[w].m, work[w].leader);
        if (r != BF_OK) {
#pragma omp critical(bf_study_status)
            rc = r;
        }
    }
    free(work);
    return rc;
}

/* Runs the study on one group of targets. */
static int run_group_of_targets(const bf_study_spec *spec,
                                const bf__group_t *g, bf_study_row *rows)
{
    bf__cset cs;
    double *fixed = malloc((spec->n_models * g->n_members + 1) *
                           BF_MAX_PARAMS * sizeof *fixed);
    size_t *leader = malloc((spec->n_models * g->n_members + 1) *
                            sizeof *leader);
    study_t st;
    int rc = BF_ENOMEM;

    memset(&cs, 0, sizeof cs);
    if (fixed != NULL && leader != NULL &&
        bf__cset_init(&cs, g->n_sel, g->geom) == BF_OK) {
        /* SPEC §7.3-7.5: each model, each target of the group. */
        st.spec = spec;
        st.n_sel = g->n_sel;
        st.cs = &cs;
        st.data = g->data;
        st.n_samples = g->n_members;
        st.members = g->members;
        st.fixed = fixed;
        st.leader = leader;
        st.rows = rows;
        rc = fit_all(&st);
    }
    bf__cset_free(&cs);
    free(fixed);
    free(leader);
    return rc;
}

int bf_study_run(const bf_study_spec *spec, bf_study_row *rows, bf_error *err)
{
    bf__groups_t gs = {NULL, 0};
    size_t i;
    int rc;

    bf__error_clear(err, "study");
    if (spec == NULL || rows == NULL || spec->data == NULL ||
        (spec->n_targets > 0 && spec->targets == NULL) ||
        (spec->n_models > 0 && spec->models == NULL)) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "invalid study specification");
    }
    for (i = 0; i < spec->n_models; i++) {
        if (spec->models[i] != NULL
            && spec->models[i]->kind == BF_MODEL_SPECULAR) {
            /* the study max-normalises (SPEC §2); SPEC §9's values are
             * absolute and need the objectives of SPEC §10 */
            return bf__error_set(err, BF_EINVAL, 0,
                                 "%s gives absolute BRDF values (SPEC §9); "
                                 "fit it with --fit exact --objective ngan, "
                                 "cuberoot or log1p",
                                 spec->models[i]->name);
        }
    }
    rc = bf__study_joint_check(spec, 0, BF_OBJ_MAX, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__study_groups(spec, &gs, err);
    for (i = 0; rc == BF_OK && i < gs.n; i++) {
        rc = run_group_of_targets(spec, &gs.g[i], rows);
        if (rc != BF_OK) {
            bf__error_clear(err, "study");
            bf__error_set(err, rc, 0, "out of memory");
        }
    }
    bf__study_groups_free(&gs);
    if (rc == BF_OK) { /* NaN: the models are diffuse */
        bf__study_rows_albedo(rows, spec->n_targets * spec->n_models,
                              spec->n_threads);
    }
    return rc;
}
