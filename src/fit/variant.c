/* variant.c: model types derived from the registry's, with parameters
 * freed or their search ranges changed (FC with n fitted, ON with rho and
 * sigma fitted, --range; doc/methods.md §6). The evaluation function and
 * the domain [min, max] of every parameter stay those of the base model.
 */
#include <math.h>
#include <string.h>

#include "internal.h"

void bf_model_variant_init(bf_model_variant *v, const bf_model_type *base)
{
    memset(v, 0, sizeof *v);
    v->type = *base;
    if (base->p > 0 && base->p <= BF_MAX_PARAMS) {
        memcpy(v->param, base->param, base->p * sizeof *base->param);
    }
    v->type.param = v->param;
}

int bf_model_variant_fit(bf_model_variant *v, const char *name, double lo,
                         double hi, double step)
{
    int j = bf_model_param_index(&v->type, name);
    bf_param *pj;
    double count;
    if (j < 0) {
        return BF_ENOTFOUND;
    }
    pj = &v->param[j];
    if (!isfinite(lo) || !isfinite(hi) || !isfinite(step) || !(lo < hi) ||
        !(step > 0.0) || lo < pj->min || hi > pj->max) {
        return BF_EINVAL;
    }
    count = floor((hi - lo) / step + 1e-9) + 1.0;
    if (count > (double)BF_VARIANT_MAX_GRID) {
        return BF_EINVAL;
    }
    pj->fitted = 1;
    pj->grid_lo = lo;
    pj->grid_step = step;
    pj->grid_n = (size_t)count;
    return BF_OK;
}

int bf_model_variant_range(bf_model_variant *v, const char *name, double lo,
                           double hi)
{
    int j = bf_model_param_index(&v->type, name);
    const bf_param *pj;
    if (j < 0) {
        return BF_ENOTFOUND;
    }
    pj = &v->param[j];
    /* a user's range keeps the parameter's grid step; a parameter without
     * a grid gets 100 intervals (doc/methods.md §6) */
    return bf_model_variant_fit(v, name, lo, hi,
                                pj->grid_n > 0 ? pj->grid_step
                                               : (hi - lo) / 100.0);
}

size_t bf_model_variant_exact(bf_model_variant *v, unsigned keep)
{
    size_t freed = 0;
    size_t j;
    for (j = 0; j < v->type.p; j++) {
        const bf_param *pj = &v->param[j];
        if (pj->fitted || !(pj->free_lo < pj->free_hi) ||
            ((keep >> pj->input) & 1u)) {
            continue; /* fitted already, never freed, or kept */
        }
        freed += bf_model_variant_fit(v, pj->name, pj->free_lo, pj->free_hi,
                                      pj->free_step) == BF_OK;
    }
    return freed;
}
