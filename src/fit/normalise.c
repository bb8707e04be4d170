/* normalise.c: max-normalisation of radiance curves and the measured
 * radiance of SPEC §2.
 *
 * [1] SPEC §2: L_data,k = v_k cos(theta_i,k), divided by its maximum over the
 *     K used configurations (never all of them).
 */
#include <math.h>

#include "data/curet.h"
#include "internal.h"

BF__CLONES
int bf_normalise(size_t n, const double *in, double *out)
{
    double max = -INFINITY;
    double nf = 0.0;
    size_t k;

    if (n == 0 || in == NULL || out == NULL) {
        return BF_EINVAL;
    }
    /* vectorised: the sum of v - v is +0 when every value is finite and
     * NaN otherwise, in any order; the maximum of finite values does not
     * depend on the order */
#pragma omp simd reduction(max : max) reduction(+ : nf)
    for (k = 0; k < n; k++) {
        double v = in[k];
        nf += v - v;
        max = v > max ? v : max;
    }
    if (nf != 0.0) {
        return BF_EDOM; /* a value is not finite */
    }
    if (!(max > 0.0)) { /* SPEC §2: a non-positive maximum cannot normalise */
        return BF_EDOM;
    }
#pragma omp simd
    for (k = 0; k < n; k++) {
        out[k] = in[k] / max;
    }
    return BF_OK;
}

int bf_data_radiance(const bf_table *t, const double *v, size_t n,
                     const size_t *sel, double *out)
{
    size_t j;
    size_t size;

    if (t == NULL || v == NULL || sel == NULL || out == NULL || n == 0) {
        return BF_EINVAL;
    }
    size = bf_table_size(t);
    for (j = 0; j < n; j++) {
        bf_geom g;
        if (sel[j] >= size) {
            return BF_EINVAL;
        }
        g = bf_table_geom(t, sel[j]);
        out[j] = v[sel[j]] * cos(g.theta_i); /* SPEC §2: BRDF x cos(theta_i) */
    }
    return bf_normalise(n, out, out);
}
