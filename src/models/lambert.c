/* lambert.c: the Lambertian baseline, LAMBERT (SPEC §6a).
 *
 * References:
 *   [1] J. H. Lambert, "Photometria", 1760.
 *
 * Equations:
 *   L = (rho/pi) cos ti; after normalisation (SPEC §2) simply cos ti, so the
 *   model has no parameter.                             SPEC §6a
 */
#include "internal.h"

/* Evaluates LAMBERT (no parameters; param is ignored and may be NULL). */
static int eval_lambert(const double *param, size_t count, const bf_geom *geom,
                        double *out)
{
    size_t k;
    (void)param;
    for (k = 0; k < count; k++) {
        double si;
        double ci;
        bf__zenith_sincos(geom[k].theta_i, &si, &ci);
        out[k] = ci; /* SPEC §6a */
    }
    return BF_OK;
}

static const bf_model_type lambert_type = {
    "LAMBERT", "Lambertian baseline (cos theta_i)", "SPEC §6a", 0, NULL,
    eval_lambert};

const bf_model_type *const bf_model_lambert = &lambert_type;
