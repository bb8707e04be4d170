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

#include "internal.h"

const int bf_study_samples[BF_STUDY_NSAMPLES] = {
    1,  2,  5,  7,  9,  12, 16, 17, 20, 22, 23, 25,
    29, 31, 33, 34, 36, 37, 39, 41, 44, 54, 55, 56}; /* paper, Table 2 */

static void set_error(bf_error *err, int code, const char *fmt, ...)
{
    va_list ap;
    if (err == NULL) {
        return;
    }
    memset(err, 0, sizeof *err);
    err->code = code;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
}

/* The fixed parameter values of type for one sample: defaults, with n from
 * the n file or spec->n_default (SPEC §4.2) and rho, sigma from the ON
 * parameter file (SPEC §5). Returns BF_ENOTFOUND when a needed input is
 * absent for this sample. Also used by bf_study_analyse (analyse.c). */
int bf__study_inputs(const bf_study_spec *spec, const bf_model_type *type,
                     int sample, double *fixed)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        fixed[j] = pj->value;
        if (pj->fitted) {
            continue;
        }
        if (strcmp(pj->name, "n") == 0) {
            fixed[j] = spec->n_default;
            if (spec->n_file != NULL &&
                bf_sample_table_get(spec->n_file, sample, 0, &fixed[j]) !=
                    BF_OK) {
                return BF_ENOTFOUND;
            }
        } else if (strcmp(pj->name, "rho") == 0 ||
                   strcmp(pj->name, "sigma") == 0) {
            size_t col = strcmp(pj->name, "rho") == 0 ? 0 : 1;
            if (spec->on_params == NULL ||
                bf_sample_table_get(spec->on_params, sample, col,
                                    &fixed[j]) != BF_OK) {
                return BF_ENOTFOUND;
            }
        }
    }
    return BF_OK;
}

/* The configurations of spec in Beckmann's frame (geom, n_sel values) and
 * the normalised measured radiance of every sample (data, n_samples x
 * n_sel, SPEC §2). Shared by bf_study_run and bf_study_analyse. */
int bf__study_data(const bf_study_spec *spec, bf_geom *geom, double *data,
                   bf_error *err)
{
    double *cti;
    size_t s;
    size_t k;
    int rc;
    for (k = 0; k < spec->n_sel; k++) {
        if (spec->sel[k] >= bf_table_size(spec->table)) {
            set_error(err, BF_EINVAL, "configuration selection out of range");
            return BF_EINVAL;
        }
        geom[k] = bf_table_geom(spec->table, spec->sel[k]);
    }

    /* SPEC §2: normalised measured radiance of every sample, as
     * bf_data_radiance forms it (the same products, bf_normalise), with
     * cos(theta_i) taken once per configuration for all samples. */
    cti = malloc(spec->n_sel * sizeof *cti);
    if (cti == NULL) {
        set_error(err, BF_ENOMEM, "out of memory");
        return BF_ENOMEM;
    }
    for (k = 0; k < spec->n_sel; k++) {
        cti[k] = cos(geom[k].theta_i);
    }
    for (s = 0; s < spec->n_samples; s++) {
        long row = bf_brdf_find(spec->brdf, spec->samples[s]);
        const double *v;
        double *out = data + s * spec->n_sel;
        if (row < 0) {
            rc = BF_ENOTFOUND;
            set_error(err, rc, "sample %d is not in the BRDF file",
                      spec->samples[s]);
            free(cti);
            return rc;
        }
        v = bf_brdf_values(spec->brdf, (size_t)row);
        for (k = 0; k < spec->n_sel; k++) {
            out[k] = v[spec->sel[k]] * cti[k]; /* SPEC §2: BRDF x cos(ti) */
        }
        rc = bf_normalise(spec->n_sel, out, out);
        if (rc != BF_OK) {
            set_error(err, rc,
                      "sample %d: the measured radiance has no positive "
                      "maximum over the used configurations",
                      spec->samples[s]);
            free(cti);
            return rc;
        }
    }
    free(cti);
    return BF_OK;
}

/* The study's shared state while it runs. */
typedef struct {
    const bf_study_spec *spec;
    const bf_geom *geom;  /* n_sel used configurations */
    const bf__trig_t *trig; /* their sines and cosines, once per study */
    const double *data;   /* n_samples x n_sel normalised radiances */
    double *fixed;        /* n_models x n_samples x BF_MAX_PARAMS inputs */
    size_t *leader;       /* n_models x n_samples: the first sample with the
                             same inputs, SIZE_MAX when the row failed */
    bf_study_row *rows;
} study_t;

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
    size_t ns = spec->n_samples;
    size_t s;
    size_t q;
    for (s = 0; s < ns; s++) {
        bf_study_row *r = &st->rows[s * spec->n_models + m];
        double *fx = st->fixed + ((m * ns) + s) * BF_MAX_PARAMS;
        memset(r, 0, sizeof *r);
        memset(fx, 0, BF_MAX_PARAMS * sizeof *fx);
        r->sample = spec->samples[s];
        r->type = spec->models[m];
        r->status = bf__study_inputs(spec, r->type, r->sample, fx);
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
    size_t ns = spec->n_samples;
    bf__fixed_model *fm = bf__fixed_alloc(spec->models[m], spec->n_sel,
                                          st->geom);
    size_t s;
    if (fm == NULL) {
        return BF_ENOMEM;
    }
    for (s = 0; s < ns; s++) {
        bf_study_row *r = &st->rows[s * spec->n_models + m];
        if (r->status == BF_OK) {
            r->status = bf__fixed_fit(fm, st->fixed + ((m * ns) + s) *
                                                          BF_MAX_PARAMS,
                                      st->data + s * spec->n_sel, &r->fit);
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
    size_t ns = spec->n_samples;
    const double **group = malloc((ns + 1) * sizeof *group);
    size_t *members = malloc((ns + 1) * sizeof *members);
    double *lse = NULL;
    bf_grid *gr = NULL;
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
            group[n_group++] = st->data + q * spec->n_sel;
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
            done = bf__stream_fast(spec->models[m], &lay, spec->n_sel,
                                   st->geom, st->trig, n_group, group, best_lse, best);
        }
        for (q = 0; done == 1 && q < n_group; q++) {
            bf_study_row *r = &st->rows[members[q] * spec->n_models + m];
            r->status = bf__grid_result(spec->models[m], &lay, best[q],
                                        best_lse[q], &r->fit);
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
                        spec->n_sel, st->geom, &status);
    if (gr == NULL) {
        for (q = 0; q < n_group; q++) {
            st->rows[members[q] * spec->n_models + m].status = status;
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
        bf_study_row *r = &st->rows[members[q] * spec->n_models + m];
        r->status = bf__grid_best(gr, lse + q * cols, &r->fit);
    }

done:
    bf_grid_free(gr);
    free(lse);
    free(group);
    free(members);
    return rc;
}

/* Fits every model to every sample: the units of work are shared among
 * spec->n_threads OpenMP threads in one parallel loop (one fork and one
 * join per study, so a busy machine delays it once, not per grid). */
static int fit_all(study_t *st)
{
    const bf_study_spec *spec = st->spec;
    size_t ns = spec->n_samples;
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

int bf_study_run(const bf_study_spec *spec, bf_study_row *rows, bf_error *err)
{
    bf_geom *geom = NULL;
    bf__trig_t *trig = NULL;
    double *data = NULL;
    double *fixed = NULL;
    size_t *leader = NULL;
    size_t k;
    study_t st;
    int rc = BF_OK;

    if (spec == NULL || rows == NULL || spec->table == NULL ||
        spec->brdf == NULL || spec->sel == NULL || spec->n_sel == 0 ||
        (spec->n_samples > 0 && spec->samples == NULL) ||
        (spec->n_models > 0 && spec->models == NULL) ||
        bf_brdf_nconf(spec->brdf) != bf_table_size(spec->table)) {
        set_error(err, BF_EINVAL, "invalid study specification");
        return BF_EINVAL;
    }
    geom = malloc(spec->n_sel * sizeof *geom);
    trig = malloc(spec->n_sel * sizeof *trig);
    data = malloc(spec->n_samples * spec->n_sel * sizeof *data + 1);
    fixed = malloc((spec->n_models * spec->n_samples + 1) * BF_MAX_PARAMS *
                   sizeof *fixed);
    leader = malloc((spec->n_models * spec->n_samples + 1) *
                    sizeof *leader);
    if (geom == NULL || trig == NULL || data == NULL || fixed == NULL ||
        leader == NULL) {
        rc = BF_ENOMEM;
        set_error(err, rc, "out of memory");
        goto done;
    }
    rc = bf__study_data(spec, geom, data, err);
    if (rc != BF_OK) {
        goto done;
    }

    for (k = 0; k < spec->n_sel; k++) {
        bf__geom_trig(&geom[k], &trig[k]);
    }

    /* SPEC §7.3-7.5: each model, each sample. */
    st.spec = spec;
    st.geom = geom;
    st.trig = trig;
    st.data = data;
    st.fixed = fixed;
    st.leader = leader;
    st.rows = rows;
    rc = fit_all(&st);
    if (rc != BF_OK) {
        set_error(err, rc, "out of memory");
        goto done;
    }

done:
    free(geom);
    free(trig);
    free(data);
    free(fixed);
    free(leader);
    return rc;
}
