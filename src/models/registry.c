/* registry.c: the table of model types, lookup by name and the checked
 * evaluation entry point bf_model_eval (SPEC §3-6).
 *
 * References:
 *   [1] H. Ragheb, E. R. Hancock, "Comparing Variants of the Beckmann Model"
 *       (the models of its Table 1, plus ON and LFTG).
 *
 * Equations: none here; each model file lists its own.
 */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "models/registry.h"

/* The registry: the lists of models/registry.h (one line per model;
 * their composites D+S, SPEC §9.4, are found by name, not listed). The
 * public header's declarations of the first models are for callers who
 * name them, a new model needs none (bf_model_find). */
#define BF_REGISTRY_ADDRESS(v) &v,
BF_REGISTRY(BF_REGISTRY_DECLARE)

/* The addresses of the pointer variables are constant expressions; the
 * pointers themselves are not. */
static const bf_model_type *const *const registry[] = {
    BF_REGISTRY(BF_REGISTRY_ADDRESS)};

#define REGISTRY_N (sizeof registry / sizeof registry[0])

const char *bf_model_set_names(bf_model_set set)
{
    switch (set) {
    case BF_MODELS_PAPER: return "VH-G,VH-E,FC-G,FC-E,ON,LFTG";
    case BF_MODELS_RANKING:
        return "VH-G,VH-E,FC-G,FC-E,ON,LFTG,LAMBERT,WNO,WNO-R";
    }
    return NULL;
}

size_t bf_model_count(void)
{
    return REGISTRY_N;
}

const bf_model_type *bf_model_get(size_t i)
{
    return (i < REGISTRY_N) ? *registry[i] : NULL;
}

int bf__name_equal(const char *a, const char *b, size_t len)
{
    size_t k;
    for (k = 0; (k < len) && (*a != '\0') && (b[k] != '\0'); k++, a++) {
        if (tolower((unsigned char)*a) != tolower((unsigned char)b[k])) {
            return 0;
        }
    }
    return (*a == '\0') && ((k == len) || (b[k] == '\0'));
}

const bf_model_type *bf_model_find_why(const char *name, const char **why)
{
    const char *ignored;
    size_t i;
    if (why == NULL) {
        why = &ignored;
    }
    *why = "unknown model (see 'brdffit models')";
    if (name == NULL) {
        return NULL;
    }
    for (i = 0; i < REGISTRY_N; i++) {
        if (bf__name_equal((*registry[i])->name, name, SIZE_MAX)) {
            *why = NULL;
            return *registry[i];
        }
    }
    return strchr(name, '+') != NULL ? bf__composite_find(name, why) : NULL;
}

const bf_model_type *bf_model_find(const char *name)
{
    return bf_model_find_why(name, NULL);
}

int bf_model_param_index(const bf_model_type *type, const char *name)
{
    size_t j;
    if ((type == NULL) || (name == NULL)) {
        return -1;
    }
    for (j = 0; j < type->p; j++) {
        if (strcmp(type->param[j].name, name) == 0) {
            return (int)j;
        }
    }
    return -1;
}

/* A zenith angle of the closed hemisphere [0, pi/2]; pi/2 is the double
 * nearest it (what asin(1) and 2 atan(1) return). */
static int zenith_ok(double theta)
{
    return (theta >= 0.0) && (theta <= BF__PI_2);
}

int bf__geom_check(size_t n, const bf_geom *geom)
{
    size_t k;
    if (n > 0 && geom == NULL) {
        return BF_EINVAL;
    }
    for (k = 0; k < n; k++) {
        const bf_geom *g = &geom[k];
        if (!zenith_ok(g->theta_i) || !zenith_ok(g->theta_s)
            || !isfinite(g->phi_i) || !isfinite(g->phi_s)) {
            return BF_EINVAL;
        }
    }
    return BF_OK;
}

/* Checks inputs once (STYLE §4), then calls the model's eval. On BF_EINVAL
 * out (when given) is filled with NaN so no stale value survives. */
int bf_model_eval_work(const bf_model_type *type, const double *param,
                       size_t n, const bf_geom *geom, double *out,
                       void *work)
{
    size_t j;
    size_t k;
    int status = BF_OK;
    /* check inputs */
    if ((type == NULL) || (type->eval == NULL) || (type->p > BF_MAX_PARAMS)
        || ((type->p > 0) && (param == NULL))
        || ((type->work_size > 0) && (work == NULL))) {
        status = BF_EINVAL;
    }
    if ((n > 0) && ((geom == NULL) || (out == NULL))) {
        return BF_EINVAL; /* nowhere to write NaN */
    }
    for (j = 0; (status == BF_OK) && (j < type->p); j++) {
        const bf_param *pj = &type->param[j];
        if (!isfinite(param[j]) || (param[j] < pj->min)
            || (param[j] > pj->max)) {
            status = BF_EINVAL;
        }
    }
    if (status == BF_OK) {
        status = bf__geom_check(n, geom);
    }
    if (status != BF_OK) {
        for (k = 0; k < n; k++) {
            out[k] = NAN;
        }
        return status;
    }
    if (n == 0) {
        return BF_OK;
    }
    return type->eval(param, n, geom, out, work);
}

int bf_model_eval(const bf_model_type *type, const double *param, size_t n,
                  const bf_geom *geom, double *out)
{
    void *work = NULL;
    size_t k;
    int rc;
    if ((type != NULL) && (type->work_size > 0)) {
        work = bf__alloc_lines(type->work_size);
        if (work == NULL) {
            for (k = 0; (out != NULL) && (k < n); k++) {
                out[k] = NAN;
            }
            return BF_ENOMEM;
        }
    }
    rc = bf_model_eval_work(type, param, n, geom, out, work);
    free(work);
    return rc;
}
