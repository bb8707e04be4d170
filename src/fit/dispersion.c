/* dispersion.c: a material's refractive index against wavelength, n(lambda)
 * (issue 17 item 7), read off a study's fits: the refractive index of a
 * specular model -- n under --fresnel dielectric (SPEC §9.2, the
 * dielectric Fresnel factor of SPEC §4.1), ABC's ior -- fitted on each
 * spectral channel, with its profile interval (doc/methods.md
 * "Dispersion"). */
#include <math.h>
#include <string.h>

#include "internal.h"

/* The wavelength range of the joint fit starting at target t: *lo, *hi;
 * 0 when a channel of it has no wavelength. */
static int joint_range(const bf_study_spec *spec, size_t t, double *lo,
                       double *hi)
{
    const bf_target *tg = &spec->targets[t];
    size_t u;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (u = t; u < spec->n_targets && spec->targets[u].joint &&
                spec->targets[u].material == tg->material;
         u++) {
        double w = bf_dataset_wavelength(spec->data, tg->material,
                                         spec->targets[u].channel);
        if (!isfinite(w)) {
            return 0;
        }
        *lo = w < *lo ? w : *lo;
        *hi = w > *hi ? w : *hi;
    }
    return u > t;
}

/* The refractive index that type fits (bf_param.input BF_INPUT_INDEX,
 * never a parameter's name: AS's and Lafortune's exponents are named n),
 * of a specular model or composite only (SPEC §9.2); a composite's
 * specular part's where its diffuse part has one too (FC's n, freed by
 * the exact fit): S's parameters follow D's (SPEC §9.4). -1: none. */
static int index_param(const bf_model_type *type)
{
    int found = -1;
    size_t j;
    if (type->kind != BF_MODEL_SPECULAR) {
        return -1;
    }
    for (j = 0; j < type->p; j++) {
        if (type->param[j].fitted &&
            type->param[j].input == BF_INPUT_INDEX) {
            found = (int)j;
        }
    }
    return found;
}

/* Fills p (when not NULL) for row i of spec; 1 when the row gives a
 * point. */
static int point(const bf_study_spec *spec, const bf_study_row *rows,
                 const bf_fit_stats *stats, size_t i, bf_dispersion_point *p)
{
    const bf_study_row *r = &rows[i];
    const bf_target *tg = &spec->targets[r->target];
    const bf_fit_stats *s = stats != NULL ? &stats[i] : NULL;
    int j = index_param(r->type);
    int analysed = s != NULL && s->done;
    double w = NAN;
    double lo = NAN;
    double hi = NAN;
    if (r->status != BF_OK || j < 0 || tg->channel == BF_CHANNEL_MEAN) {
        return 0;
    }
    if (tg->joint) {
        int first = r->target == 0 || !tg[-1].joint ||
                    tg[-1].material != tg->material;
        if (!first || !joint_range(spec, r->target, &lo, &hi)) {
            return 0;
        }
    } else {
        w = bf_dataset_wavelength(spec->data, tg->material, tg->channel);
        if (!isfinite(w)) {
            return 0;
        }
        lo = hi = w;
    }
    if (p != NULL) {
        memset(p, 0, sizeof *p);
        p->row = i;
        p->sample = r->sample;
        p->model = r->type->name;
        p->joint = tg->joint;
        p->wavelength = w;
        p->lambda_lo = lo;
        p->lambda_hi = hi;
        p->n = r->fit.param[j];
        p->ci_low = analysed ? s->ci_low[j] : NAN;
        p->ci_high = analysed ? s->ci_high[j] : NAN;
        p->n_ml = analysed ? s->ml_param[j] : NAN;
    }
    return 1;
}

size_t bf_dispersion_points(const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats,
                            bf_dispersion_point *out)
{
    size_t n = 0;
    size_t i;
    if (spec == NULL || rows == NULL || spec->data == NULL) {
        return 0;
    }
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
        n += (size_t)point(spec, rows, stats, i,
                           out != NULL ? &out[n] : NULL);
    }
    return n;
}
