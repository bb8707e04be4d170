/* study.c: the study protocol of SPEC §7 -- every sample against every
 * model on one configuration selection, grid search per fitted model.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model", §5.
 * [2] SPEC §7 (protocol), §4.2 (n fixed per sample, default 1.7), §5 (ON at
 *     the tabulated rho, sigma).
 */
#include <math.h>
#include <stdarg.h>
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
 * absent for this sample. */
static int sample_inputs(const bf_study_spec *spec, const bf_model_type *type,
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

/* Fits one model to every sample of spec (SPEC §7.3-7.5). Samples whose
 * fixed inputs are equal share one precomputed grid (for the paper's
 * protocol: one grid per model, or one per sample for ON), and the samples
 * of a grid are scored together. fixed holds n_samples x BF_MAX_PARAMS
 * scratch values; rows are filled at stride n_models. */
static int fit_model(const bf_study_spec *spec, size_t m, const bf_geom *geom,
                     const double *data, double *fixed, bf_study_row *rows)
{
    const bf_model_type *type = spec->models[m];
    size_t n_sel = spec->n_sel;
    int n_threads = spec->n_threads > 1 ? spec->n_threads : 1;
    const double **group = NULL;
    size_t *members = NULL;
    unsigned char *done = NULL;
    double *lse = NULL;
    size_t s;
    int rc = BF_OK;

    group = malloc((spec->n_samples + 1) * sizeof *group);
    members = malloc((spec->n_samples + 1) * sizeof *members);
    done = calloc(spec->n_samples + 1, 1);
    if (group == NULL || members == NULL || done == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    for (s = 0; s < spec->n_samples; s++) {
        bf_study_row *r = &rows[s * spec->n_models + m];
        double *fx = fixed + s * BF_MAX_PARAMS;
        memset(r, 0, sizeof *r);
        memset(fx, 0, BF_MAX_PARAMS * sizeof *fx);
        r->sample = spec->samples[s];
        r->type = type;
        r->status = sample_inputs(spec, type, r->sample, fx);
        done[s] = r->status != BF_OK;
    }
    if (bf__fits_nothing(type)) { /* ON, LAMBERT: one value per sample */
        bf__fixed_model *fm = bf__fixed_alloc(type, n_sel, geom);
        if (fm == NULL) {
            rc = BF_ENOMEM;
            goto done;
        }
        for (s = 0; s < spec->n_samples; s++) {
            bf_study_row *r = &rows[s * spec->n_models + m];
            if (r->status == BF_OK) {
                r->status = bf__fixed_fit(fm, fixed + s * BF_MAX_PARAMS,
                                          data + s * n_sel, &r->fit);
            }
        }
        bf__fixed_free(fm);
        goto done;
    }
    for (s = 0; s < spec->n_samples; s++) {
        const double *fx = fixed + s * BF_MAX_PARAMS;
        size_t n_group = 0;
        size_t q;
        size_t stride;
        int st = BF_OK;
        bf_grid *gr;
        if (done[s]) {
            continue;
        }
        for (q = s; q < spec->n_samples; q++) {
            if (!done[q] && memcmp(fixed + q * BF_MAX_PARAMS, fx,
                                   BF_MAX_PARAMS * sizeof *fx) == 0) {
                members[n_group] = q;
                group[n_group++] = data + q * n_sel;
                done[q] = 1;
            }
        }
        gr = bf__grid_build(type, fx, 0, n_sel, geom, n_threads, &st);
        if (gr == NULL) {
            for (q = 0; q < n_group; q++) {
                rows[members[q] * spec->n_models + m].status = st;
            }
            continue;
        }
        stride = bf__grid_cols(gr);
        lse = malloc(n_group * stride * sizeof *lse);
        if (lse == NULL) {
            bf_grid_free(gr);
            rc = BF_ENOMEM;
            goto done;
        }
        bf__grid_score(gr, n_group, group, lse, n_threads);
        for (q = 0; q < n_group; q++) {
            bf_study_row *r = &rows[members[q] * spec->n_models + m];
            r->status = bf__grid_best(gr, lse + q * stride, &r->fit);
        }
        free(lse);
        lse = NULL;
        bf_grid_free(gr);
    }

done:
    free(group);
    free(members);
    free(done);
    free(lse);
    return rc;
}

int bf_study_run(const bf_study_spec *spec, bf_study_row *rows, bf_error *err)
{
    bf_geom *geom = NULL;
    double *data = NULL;
    double *fixed = NULL;
    double *cos_ti = NULL;
    size_t s;
    size_t m;
    size_t k;
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
    data = malloc(spec->n_samples * spec->n_sel * sizeof *data + 1);
    fixed = malloc((spec->n_samples + 1) * BF_MAX_PARAMS * sizeof *fixed);
    cos_ti = malloc(spec->n_sel * sizeof *cos_ti);
    if (geom == NULL || data == NULL || fixed == NULL || cos_ti == NULL) {
        rc = BF_ENOMEM;
        set_error(err, rc, "out of memory");
        goto done;
    }
    for (k = 0; k < spec->n_sel; k++) {
        if (spec->sel[k] >= bf_table_size(spec->table)) {
            rc = BF_EINVAL;
            set_error(err, rc, "configuration selection out of range");
            goto done;
        }
        geom[k] = bf_table_geom(spec->table, spec->sel[k]);
    }

    /* SPEC §2: normalised measured radiance of every sample, as
     * bf_data_radiance computes it, cos(theta_i) taken once. */
    for (k = 0; k < spec->n_sel; k++) {
        cos_ti[k] = cos(geom[k].theta_i);
    }
    for (s = 0; s < spec->n_samples; s++) {
        long row = bf_brdf_find(spec->brdf, spec->samples[s]);
        const double *v;
        double *d = data + s * spec->n_sel;
        if (row < 0) {
            rc = BF_ENOTFOUND;
            set_error(err, rc, "sample %d is not in the BRDF file",
                      spec->samples[s]);
            goto done;
        }
        v = bf_brdf_values(spec->brdf, (size_t)row);
        for (k = 0; k < spec->n_sel; k++) {
            d[k] = v[spec->sel[k]] * cos_ti[k]; /* SPEC §2 */
        }
        rc = bf_normalise(spec->n_sel, d, d);
        if (rc != BF_OK) {
            set_error(err, rc,
                      "sample %d: the measured radiance has no positive "
                      "maximum over the used configurations",
                      spec->samples[s]);
            goto done;
        }
    }

    /* SPEC §7.3-7.5: each model, each sample. */
    for (m = 0; m < spec->n_models; m++) {
        rc = fit_model(spec, m, geom, data, fixed, rows);
        if (rc != BF_OK) {
            set_error(err, rc, "out of memory");
            goto done;
        }
    }

done:
    free(geom);
    free(data);
    free(fixed);
    free(cos_ti);
    return rc;
}
