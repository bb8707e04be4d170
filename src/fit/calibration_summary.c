/* calibration_summary.c: what a calibration (bf_fit_calibrate) says of
 * one parameter's intervals, as the tables of `brdffit calibrate` and of
 * the report's calibration show it (doc/methods.md §3): the coverage
 * against the band that calibrated intervals give by chance, and the bias
 * and width in units of the estimates' spread.
 *
 * The band: if each of n independent simulated intervals holds the truth
 * with probability level, the count that does is Binomial(n, level); the
 * band holds the counts whose lower and upper tail probabilities are both
 * at least (1 - BF_CALIBRATION_BAND) / 2 (an exact, equal-tailed
 * acceptance region; a coverage outside it is unlikely at that level for
 * intervals that mean what they say). */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <string.h>

#include "brdffit.h"

/* The band's lowest and highest counts for n trials at probability p. */
static void band(size_t n, double p, size_t *lo, size_t *hi)
{
    double tail = 0.5 * (1.0 - BF_CALIBRATION_BAND);
    unsigned nn = (unsigned)n;
    size_t x;
    *lo = n;
    for (x = 0; x <= n; x++) { /* P(X <= x) >= tail */
        if (gsl_cdf_binomial_P((unsigned)x, p, nn) >= tail) {
            *lo = x;
            break;
        }
    }
    *hi = 0;
    for (x = n + 1; x-- > 0;) { /* P(X >= x) = Q(x - 1) >= tail */
        if (x == 0 || gsl_cdf_binomial_Q((unsigned)x - 1, p, nn) >= tail) {
            *hi = x;
            break;
        }
    }
}

int bf_calibration_summarise(const bf_calibration *c, size_t j, double level,
                             bf_calibration_summary *out)
{
    size_t lo;
    size_t hi;
    size_t x;
    double n;
    double z;
    if (out != NULL) {
        memset(out, 0, sizeof *out);
    }
    if (c == NULL || out == NULL || j >= BF_MAX_PARAMS || c->n_sim == 0 ||
        c->n_sim > 4294967295u || !isfinite(c->coverage[j]) ||
        !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    n = (double)c->n_sim;
    out->n = c->n_sim;
    out->coverage = c->coverage[j];
    out->coverage_sd = sqrt(level * (1.0 - level) / n);
    band(c->n_sim, level, &lo, &hi);
    out->band_low = (double)lo / n;
    out->band_high = (double)hi / n;
    x = (size_t)lround(c->coverage[j] * n);
    out->verdict = x < lo ? -1 : x > hi ? 1 : 0;
    z = gsl_cdf_ugaussian_Pinv(0.5 * (1.0 + level));
    out->bias_sd = c->ml_sd[j] > 0.0 ? c->ml_bias[j] / c->ml_sd[j] : NAN;
    out->width_spread = c->ml_sd[j] > 0.0
                            ? c->width[j] / (2.0 * z * c->ml_sd[j])
                            : NAN;
    out->not_identified = c->not_identified[j];
    return BF_OK;
}
