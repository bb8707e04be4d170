/* lambert.c: the Lambertian baseline, LAMBERT (SPEC §6a).
 *
 * References:
 *   [1] J. H. Lambert, "Photometria", 1760.
 *
 * Equations:
 *   L = (rho/pi) cos ti; after normalisation (SPEC §2) simply cos ti, so the
 *   model has no parameter.                             SPEC §6a
 */
#include <string.h>

#include "fit/engine.h"

/* Evaluates LAMBERT (no parameters; param is ignored and may be NULL). */
static int eval_lambert(const double *param, size_t count, const bf_geom *geom,
                        double *out, void *work)
{
    size_t k;
    (void)param;
    (void)work;
    for (k = 0; k < count; k++) {
        double si;
        double ci;
        bf__zenith_sincos(geom[k].theta_i, &si, &ci);
        out[k] = ci; /* SPEC §6a */
    }
    return BF_OK;
}

/* The engine's kernel: cos ti per configuration is the curve. */
static void lambert_terms(const bf_kernel *kr, const bf__cset *cs,
                          double *terms)
{
    (void)kr;
    memcpy(terms, cs->cti, cs->n * sizeof *terms); /* SPEC §6a */
}

static int lambert_values(const bf__prep *pm, const double *param,
                          void *work, double *out)
{
    (void)param;
    (void)work;
    memcpy(out, pm->terms, pm->n * sizeof *out);
    return BF_OK;
}

static const bf_kernel lambert_kernel = {
    .n_terms = 1,
    .terms = lambert_terms,
    .values = lambert_values,
    .cheap = -1,
};

static const bf_model_type lambert_type = {
    .name = "LAMBERT",
    .title = "Lambertian baseline (cos theta_i)",
    .reference = "SPEC §6a",
    .p = 0,
    .eval = eval_lambert,
    .kernel = &lambert_kernel,
    .style = 8,
};

const bf_model_type *const bf_model_lambert = &lambert_type;
