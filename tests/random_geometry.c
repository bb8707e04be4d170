/* random_geometry.c: random measurement directions (random_geometry.h). */
#include "random_geometry.h"

#include <gsl/gsl_rng.h>
#include <math.h>

size_t bf_random_geometry(bf_geom *geom, size_t n, unsigned long seed,
                          int mirror)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double cmin = cos(80.0 * M_PI / 180.0);
    size_t k;
    if (rng == NULL) {
        return 0;
    }
    gsl_rng_set(rng, seed);
    for (k = 0; k < n; k++) {
        geom[k].theta_i = acos(cmin + (1.0 - cmin) * gsl_rng_uniform(rng));
        geom[k].phi_i = M_PI;
        if (!mirror || k % 2 == 0) {
            geom[k].theta_s = acos(cmin + (1.0 - cmin) * gsl_rng_uniform(rng));
            geom[k].phi_s = M_PI * (2.0 * gsl_rng_uniform(rng) - 1.0);
        } else { /* phi_s = 0, theta_s = theta_i: the mirror (SPEC §1.2) */
            double t = geom[k].theta_i +
                       10.0 * M_PI / 180.0 * (2.0 * gsl_rng_uniform(rng) - 1.0);
            geom[k].theta_s = fmin(fabs(t), 80.0 * M_PI / 180.0);
            geom[k].phi_s = 0.2 * (2.0 * gsl_rng_uniform(rng) - 1.0);
        }
    }
    gsl_rng_free(rng);
    return n;
}
