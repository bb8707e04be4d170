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
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* The registry, one line per model: the pointer variable its file
 * defines (`const bf_model_type *const bf_model_x = &x_type;`). Order is
 * part of the API (bf_model_get): the paper's six Beckmann variants, then
 * ON, LFTG, the Lambert baseline, WNO and WNO-R, then the specular models
 * of SPEC §9.3 in its table's order (each added after the others so
 * earlier indices keep their meaning; their option variants are reached
 * through bf_model_specular_variant, not listed). Adding a model means one new file in
 * src/models/ (the build takes every file there) and one line here; the
 * public header's declarations of the first models are for callers who
 * name them, a new model needs none (bf_model_find). */
#define BF_REGISTRY(X)                                                      \
    X(bf_model_bk_g)                                                        \
    X(bf_model_bk_e)                                                        \
    X(bf_model_vh_g)                                                        \
    X(bf_model_vh_e)                                                        \
    X(bf_model_fc_g)                                                        \
    X(bf_model_fc_e)                                                        \
    X(bf_model_on)                                                          \
    X(bf_model_lftg)                                                        \
    X(bf_model_lambert)                                                     \
    X(bf_model_wno)                                                         \
    X(bf_model_wno_r)                                                       \
    X(bf_model_ggx)                                                         \
    X(bf_model_beckmann)                                                    \
    X(bf_model_ct)                                                          \
    X(bf_model_blinn_phong)                                                 \
    X(bf_model_ward)                                                        \
    X(bf_model_ward_duer)                                                   \
    X(bf_model_ward_gmd)                                                    \
    X(bf_model_as)                                                          \
    X(bf_model_lafortune)                                                   \
    X(bf_model_abc)

#define BF_REGISTRY_DECLARE(v) extern const bf_model_type *const v;
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

/* ASCII case-insensitive equality (strcasecmp is POSIX, not C11, and is
 * locale-dependent). */
static int name_equal(const char *a, const char *b)
{
    while ((*a != '\0') && (*b != '\0')) {
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) {
            return 0;
        }
        a++;
        b++;
    }
    return (*a == '\0') && (*b == '\0');
}

const bf_model_type *bf_model_find(const char *name)
{
    size_t i;
    if (name == NULL) {
        return NULL;
    }
    for (i = 0; i < REGISTRY_N; i++) {
        if (name_equal((*registry[i])->name, name)) {
            return *registry[i];
        }
    }
    return NULL;
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
        work = aligned_alloc(64, (type->work_size + 63) / 64 * 64);
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
