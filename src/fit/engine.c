/* engine.c: configuration sets, prepared models and the one
 * evaluate-and-normalise of the fitting engine (src/fit/engine.h).
 *
 * [1] SPEC §2: every model curve is divided by its maximum over the used
 *     configurations, so constant factors cancel.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* ==== configuration sets ================================================= */

int bf__cset_init(bf__cset *cs, size_t n, const bf_geom *geom)
{
    size_t k;
    memset(cs, 0, sizeof *cs);
    if (n == 0 || geom == NULL) {
        return BF_EINVAL;
    }
    cs->n = n;
    cs->geom = geom;
    cs->trig = malloc(n * sizeof *cs->trig);
    cs->cti = malloc(n * sizeof *cs->cti);
    if (cs->trig == NULL || cs->cti == NULL) {
        bf__cset_free(cs);
        return BF_ENOMEM;
    }
    for (k = 0; k < n; k++) {
        bf__geom_trig(&geom[k], &cs->trig[k]);
        cs->cti[k] = cs->trig[k].ci; /* bf__zenith_sincos's cos theta_i */
    }
    return BF_OK;
}

void bf__cset_free(bf__cset *cs)
{
    if (cs == NULL) {
        return;
    }
    free(cs->trig);
    free(cs->cti);
    cs->trig = NULL;
    cs->cti = NULL;
}

/* ==== the plain kernel: a model's own eval ============================== */

/* The reference path (bf_fit_grid, bf_fit_lse, bf_model_eval) and types
 * made outside the library: the configurations are the terms, eval the
 * loop. */
static int plain_values(const bf__prep *pm, const double *param, void *work,
                        double *out)
{
    return pm->type->eval(param, pm->n, pm->geom, out, work);
}

const bf_kernel bf__plain_kernel = {
    .values = plain_values,
    .cheap = -1,
};

/* ==== prepared models ==================================================== */

int bf__prep_init(bf__prep *pm, const bf_model_type *type,
                  const bf__cset *cs)
{
    int rc = cs != NULL ? bf__prep_plain(pm, type, cs->n, cs->geom)
                        : BF_EINVAL;
    if (rc != BF_OK) {
        return rc;
    }
    pm->cs = cs; /* the plain kernel's fits need cos theta_i too (cosw) */
    if (type->kernel == NULL) {
        return rc;
    }
    pm->kr = type->kernel;
    if (pm->kr->n_terms + pm->kr->n_extra > 0) {
        size_t len;
        if (pm->kr->n_terms > (SIZE_MAX / sizeof(double) - 64) / cs->n) {
            return BF_ENOMEM;
        }
        len = pm->kr->n_terms * cs->n + pm->kr->n_extra;
        pm->terms = malloc(len * sizeof *pm->terms);
        if (pm->terms == NULL) {
            return BF_ENOMEM;
        }
        pm->kr->terms(pm->kr, cs, pm->terms);
    }
    pm->work_bytes = pm->kr->work_bytes != NULL
                         ? pm->kr->work_bytes(pm->kr, cs->n)
                         : 0;
    return pm->kr->prepare != NULL ? pm->kr->prepare(pm) : BF_OK;
}

int bf__prep_plain(bf__prep *pm, const bf_model_type *type, size_t n,
                   const bf_geom *geom)
{
    memset(pm, 0, sizeof *pm);
    if (type == NULL || type->eval == NULL || n == 0 || geom == NULL ||
        type->p > BF_MAX_PARAMS) {
        return BF_EINVAL;
    }
    pm->type = type;
    pm->kr = &bf__plain_kernel;
    pm->n = n;
    pm->geom = geom;
    pm->work_bytes = type->work_size;
    return BF_OK;
}

void bf__prep_free(bf__prep *pm)
{
    if (pm == NULL) {
        return;
    }
    if (pm->kr != NULL && pm->kr->release != NULL && pm->cache != NULL) {
        pm->kr->release(pm);
    }
    pm->cache = NULL;
    free(pm->terms);
    pm->terms = NULL;
}

void *bf__work_alloc(const bf__prep *pm)
{
    /* at least one line, so a kernel without workspace still gets a
     * distinct non-NULL pointer */
    size_t bytes = (pm->work_bytes + 127) / 64 * 64;
    void *w = aligned_alloc(64, bytes);
    if (w != NULL) {
        memset(w, 0, bytes);
    }
    return w;
}

int bf__curve(const bf__prep *pm, const double *param, void *work,
              double *curve)
{
    int rc = pm->kr->values(pm, param, work, curve);
    if (rc != BF_OK) {
        return BF_EDOM;
    }
    if (pm->type->kind == BF_MODEL_SPECULAR) {
        /* SPEC §10: rho = BRDF cos ti as it is, never normalised */
        size_t k;
        for (k = 0; k < pm->n; k++) {
            double si;
            double ci;
            if (pm->cs != NULL) {
                ci = pm->cs->cti[k]; /* bf__zenith_sincos's, once */
            } else {
                bf__zenith_sincos(pm->geom[k].theta_i, &si, &ci);
            }
            curve[k] *= ci;
            if (!isfinite(curve[k])) {
                return BF_EDOM;
            }
        }
        return BF_OK;
    }
    /* SPEC §2. Models with block kernels normalise as those do (their
     * kr->normalise), so a point's curve has the bits of the same grid
     * point's; the others as bf_normalise, the bits the paper's protocol
     * has for them. */
    if (pm->kr->normalise != NULL) {
        return pm->kr->normalise(pm->n, curve);
    }
    return bf_normalise(pm->n, curve, curve);
}

/* values() at param with the parameters of lin at 0 except index one
 * (SIZE_MAX: none) at 1, into out. */
static int values_at_unit(const bf__prep *pm, const double *param,
                          unsigned lin, size_t one, void *work, double *out)
{
    double p[BF_MAX_PARAMS];
    size_t j;
    memcpy(p, param, pm->type->p * sizeof *p);
    for (j = 0; j < pm->type->p; j++) {
        if ((lin >> j) & 1u) {
            p[j] = j == one ? 1.0 : 0.0;
        }
    }
    return pm->kr->values(pm, p, work, out) == BF_OK ? BF_OK : BF_EDOM;
}

int bf__columns_values(const bf__prep *pm, const double *param, unsigned lin,
                       void *work, double *c0, double *const *col)
{
    size_t q = 0;
    size_t j;
    if (values_at_unit(pm, param, lin, SIZE_MAX, work, c0) != BF_OK) {
        return BF_EDOM;
    }
    for (j = 0; j < pm->type->p; j++) {
        size_t k;
        if (!((lin >> j) & 1u)) {
            continue;
        }
        if (values_at_unit(pm, param, lin, j, work, col[q]) != BF_OK) {
            return BF_EDOM;
        }
        for (k = 0; k < pm->n; k++) {
            col[q][k] -= c0[k];
        }
        q++;
    }
    return BF_OK;
}

int bf__columns_scaled(const bf__prep *pm, const double *param, unsigned lin,
                       void *work, double *c0, double *const *col)
{
    size_t q = 0;
    size_t j;
    for (j = 0; j < pm->type->p; j++) {
        if (pm->type->param[j].linear && !((lin >> j) & 1u)) {
            /* a scale held (a profile's): c0 is not 0 */
            return bf__columns_values(pm, param, lin, work, c0, col);
        }
    }
    memset(c0, 0, pm->n * sizeof *c0);
    for (j = 0; j < pm->type->p; j++) {
        if (((lin >> j) & 1u) &&
            values_at_unit(pm, param, lin, j, work, col[q++]) != BF_OK) {
            return BF_EDOM;
        }
    }
    return BF_OK;
}

/* ==== the objective of a fit ============================================= */

int bf__fitctx_init(bf__fitctx *fc, const bf__prep *pm)
{
    return bf__fitctx_init_blocks(fc, pm, 1);
}

int bf__fitctx_init_blocks(bf__fitctx *fc, const bf__prep *pm,
                           size_t blocks)
{
    int specular = pm->type->kind == BF_MODEL_SPECULAR;
    size_t len;
    memset(fc, 0, sizeof *fc);
    if (blocks == 0 || (blocks > 1 && !specular) ||
        blocks > (SIZE_MAX / sizeof(double)) / (pm->n + BF_MAX_PARAMS) - 5) {
        return BF_EINVAL;
    }
    fc->pm = pm;
    fc->blocks = blocks;
    fc->work = bf__work_alloc(pm);
    /* curve (blocks x n), scratch, log_d, a specular model's columns
     * (varpro.c: 3 n) and its scales per block */
    len = (blocks + 2 + (specular ? 3 : 0)) * pm->n +
          (specular ? blocks * BF_MAX_PARAMS : 0);
    fc->curve = malloc(len * sizeof *fc->curve);
    if (fc->work == NULL || fc->curve == NULL) {
        bf__fitctx_free(fc);
        return BF_ENOMEM;
    }
    fc->scratch = fc->curve + blocks * pm->n;
    fc->log_d = fc->scratch + pm->n;
    fc->cols = specular ? fc->log_d + pm->n : NULL;
    fc->block_lin = specular ? fc->cols + 3 * pm->n : NULL;
    return BF_OK;
}

void bf__fitctx_free(bf__fitctx *fc)
{
    if (fc == NULL) {
        return;
    }
    bf__varpro_free(fc);
    free(fc->work);
    free(fc->curve);
    fc->work = NULL;
    fc->curve = NULL;
}

void bf__fitctx_use(bf__fitctx *fc, const bf_problem *pb)
{
    fc->pb = pb;
    bf__data_transform(pb, fc->log_d);
}

static const double *log_data(const bf__fitctx *fc)
{
    return fc->pb->objective == BF_OBJ_LOG ||
                   fc->pb->objective == BF_OBJ_CUBEROOT ||
                   fc->pb->objective == BF_OBJ_LOG1P
               ? fc->log_d
               : NULL;
}

int bf__fit_value(bf__fitctx *fc, const double *param, double *value)
{
    int rc;
    if (fc->lin_mask != 0) { /* the scales solved exactly (varpro.c) */
        return bf__varpro_value(fc, param, value);
    }
    fc->n_eval++;
    rc = bf__curve(fc->pm, param, fc->work, fc->curve);
    if (rc != BF_OK) {
        return rc;
    }
    *value = bf__objective(fc->pb, fc->pm->cs->cti, log_data(fc), fc->curve,
                           fc->scratch);
    return BF_OK;
}

int bf__fit_residuals(bf__fitctx *fc, const double *param, double *resid)
{
    int rc = bf__curve(fc->pm, param, fc->work, fc->curve);
    if (rc != BF_OK) {
        return rc;
    }
    bf__residuals(fc->pb, fc->pm->cs->cti, log_data(fc), fc->curve, resid);
    return BF_OK;
}

/* ==== one problem's own engine =========================================== */

int bf__solo_init(bf__solo *s, const bf_problem *pb)
{
    int rc;
    memset(s, 0, sizeof *s);
    if (pb == NULL || pb->type == NULL || pb->n == 0 || pb->geom == NULL) {
        return BF_EINVAL;
    }
    rc = bf__geom_check(pb->n, pb->geom);
    if (rc == BF_OK) {
        rc = bf__cset_init(&s->cs, pb->n, pb->geom);
    }
    if (rc == BF_OK) {
        rc = bf__prep_init(&s->pm, pb->type, &s->cs);
    }
    if (rc == BF_OK) {
        rc = bf__fitctx_init(&s->fc, &s->pm);
    }
    if (rc != BF_OK) {
        bf__solo_free(s);
        return rc;
    }
    bf__fitctx_use(&s->fc, pb);
    return BF_OK;
}

void bf__solo_free(bf__solo *s)
{
    bf__fitctx_free(&s->fc);
    bf__prep_free(&s->pm);
    bf__cset_free(&s->cs);
}
