/* study.c: the study protocol of SPEC §7 -- every sample against every
 * model on one configuration selection, grid search per fitted model.
 *
 * [1] Ragheb & Hancock, "Comparing Variants of the Beckmann Model", §5.
 * [2] SPEC §7 (protocol), §4.2 (n fixed per sample, default 1.7), §5 (ON at
 *     the tabulated rho, sigma).
 */
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

    /* SPEC §2: normalised measured radiance of every sample. */
    for (s = 0; s < spec->n_samples; s++) {
        long row = bf_brdf_find(spec->brdf, spec->samples[s]);
        if (row < 0) {
            rc = BF_ENOTFOUND;
            set_error(err, rc, "sample %d is not in the BRDF file",
                      spec->samples[s]);
            return rc;
        }
        rc = bf_data_radiance(spec->table,
                              bf_brdf_values(spec->brdf, (size_t)row),
                              spec->n_sel, spec->sel,
                              data + s * spec->n_sel);
        if (rc != BF_OK) {
            set_error(err, rc,
                      "sample %d: the measured radiance has no positive "
                      "maximum over the used configurations",
                      spec->samples[s]);
            return rc;
        }
    }
    return BF_OK;
}

int bf_study_run(const bf_study_spec *spec, bf_study_row *rows, bf_error *err)
{
    bf_geom *geom = NULL;
    double *data = NULL;
    bf_grid **grids = NULL;
    double *grid_fixed = NULL;
    size_t s;
    size_t m;
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
    grids = calloc(spec->n_models + 1, sizeof *grids);
    grid_fixed = calloc((spec->n_models + 1) * BF_MAX_PARAMS,
                        sizeof *grid_fixed);
    if (geom == NULL || data == NULL || grids == NULL || grid_fixed == NULL) {
        rc = BF_ENOMEM;
        set_error(err, rc, "out of memory");
        goto done;
    }
    rc = bf__study_data(spec, geom, data, err);
    if (rc != BF_OK) {
        goto done;
    }

    /* SPEC §7.3-7.5: each model, each sample. The grid of a model is built
     * once and rebuilt only when a sample's fixed inputs differ. */
    for (m = 0; m < spec->n_models; m++) {
        const bf_model_type *type = spec->models[m];
        double *gfix = grid_fixed + m * BF_MAX_PARAMS;
        for (s = 0; s < spec->n_samples; s++) {
            bf_study_row *r = &rows[s * spec->n_models + m];
            double fixed[BF_MAX_PARAMS] = {0};
            memset(r, 0, sizeof *r);
            r->sample = spec->samples[s];
            r->type = type;
            r->status = bf__study_inputs(spec, type, r->sample, fixed);
            if (r->status != BF_OK) {
                continue;
            }
            if (grids[m] == NULL ||
                memcmp(gfix, fixed, sizeof fixed) != 0) {
                int st = BF_OK;
                bf_grid_free(grids[m]);
                grids[m] = bf_grid_alloc(type, fixed, 0, spec->n_sel, geom,
                                         &st);
                memcpy(gfix, fixed, sizeof fixed);
                if (grids[m] == NULL) {
                    r->status = st;
                    continue;
                }
            }
            r->status = bf_grid_fit(grids[m], data + s * spec->n_sel,
                                    &r->fit);
        }
        bf_grid_free(grids[m]);
        grids[m] = NULL;
    }

done:
    free(geom);
    free(data);
    free(grids);
    free(grid_fixed);
    return rc;
}
