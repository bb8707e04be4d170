/* summary.c: what a material of a dataset holds -- angle ranges, how near
 * its configurations come to the mirror direction, negative, zero and
 * invalid values (SPEC §1.4, §1.6, §2). Used by `brdffit info`.
 */
#include <math.h>
#include <string.h>

#include "internal.h"

const double bf_summary_cones_deg[BF_SUMMARY_NCONES] = {1.0, 5.0, 10.0, 15.0,
                                                        25.0};

/* Widens [*lo, *hi] to hold x. */
static void widen(double x, double *lo, double *hi)
{
    *lo = fmin(*lo, x);
    *hi = fmax(*hi, x);
}

int bf_dataset_summary(const bf_dataset *ds, size_t m,
                       bf_material_summary *out)
{
    const double *a = bf_dataset_angles(ds, m);
    const bf_geom *g = bf_dataset_geom(ds, m);
    const double *v = bf_dataset_values(ds, m);
    const unsigned char *ok = bf_dataset_valid(ds, m);
    size_t nc = bf_dataset_nchannels(ds, m);
    size_t k;
    size_t c;
    size_t j;

    if (a == NULL || out == NULL) {
        return BF_EINVAL;
    }
    memset(out, 0, sizeof *out);
    out->n_conf = bf_dataset_nconf(ds, m);
    out->n_channels = nc;
    out->theta_i_min = out->theta_o_min = INFINITY;
    out->phi_i_min = out->phi_o_min = INFINITY;
    out->theta_i_max = out->theta_o_max = -INFINITY;
    out->phi_i_max = out->phi_o_max = -INFINITY;
    out->delta_min = INFINITY;
    out->value_min = INFINITY;
    out->value_max = -INFINITY;
    for (k = 0; k < out->n_conf; k++) {
        const double *ak = a + 4 * k;
        double delta = bf_geom_mirror_angle(&g[k]); /* SPEC §1.6 */
        int any_invalid = 0;
        widen(ak[0], &out->theta_i_min, &out->theta_i_max);
        widen(ak[1], &out->phi_i_min, &out->phi_i_max);
        widen(ak[2], &out->theta_o_min, &out->theta_o_max);
        widen(ak[3], &out->phi_o_min, &out->phi_o_max);
        out->n_specular += (size_t)bf_geom_is_specular(&g[k]);
        out->delta_min = fmin(out->delta_min, delta);
        for (j = 0; j < BF_SUMMARY_NCONES; j++) {
            out->n_cone[j] +=
                (size_t)(delta < bf_summary_cones_deg[j] * (BF__PI / 180.0));
        }
        for (c = 0; c < nc; c++) {
            double x = v[k * nc + c];
            if (ok != NULL && !ok[k * nc + c]) {
                out->n_invalid++;
                any_invalid = 1;
                continue;
            }
            out->n_negative += (size_t)(x < 0.0);
            out->n_zero += (size_t)(x == 0.0);
            widen(x, &out->value_min, &out->value_max);
        }
        out->n_conf_invalid += (size_t)any_invalid;
    }
    return BF_OK;
}
