/* test_calibration_summary.c: bf_calibration_summarise (doc/methods.md
 * §3), the numbers of the calibration tables, on constructed
 * calibrations: the band of coverages against the binomial tails computed
 * here term by term, the verdicts below, inside and above it, bias and
 * width in units of the spread, and bad arguments. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "support.h"

/* P(X <= x) and P(X >= x) for X ~ Binomial(n, p), summed term by term
 * from the probability mass function. */
static double tail(unsigned n, double p, unsigned x, int upper)
{
    double s = 0.0;
    unsigned k;
    for (k = upper ? x : 0; k <= (upper ? n : x); k++) {
        s += exp(lgamma(n + 1.0) - lgamma(k + 1.0) - lgamma(n - k + 1.0) +
                 k * log(p) + (n - k) * log1p(-p));
    }
    return s;
}

/* A calibration of n simulations of one parameter (index 1) covering
 * cover of them. */
static bf_calibration make(size_t n, size_t cover)
{
    bf_calibration c;
    memset(&c, 0, sizeof c);
    c.n_sim = n;
    c.coverage[0] = NAN;
    c.coverage[1] = (double)cover / (double)n;
    c.ml_bias[1] = 0.01;
    c.ml_sd[1] = 0.04;
    c.width[1] = 0.2;
    c.not_identified[1] = 0.25;
    return c;
}

Test(calibration_summary, the_band_is_the_binomial_tails)
{
    static const unsigned ns[3] = {10, 40, 200};
    size_t i;
    for (i = 0; i < 3; i++) {
        unsigned n = ns[i];
        bf_calibration c = make(n, n);
        bf_calibration_summary s;
        unsigned lo = 0;
        unsigned hi = 0;
        unsigned x;
        for (x = 0; x <= n; x++) { /* both tails at least 0.005 */
            if (tail(n, 0.95, x, 0) >= 0.005 &&
                tail(n, 0.95, x, 1) >= 0.005) {
                lo = lo == 0 ? x : lo;
                hi = x;
            }
        }
        cr_assert_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_OK);
        cr_expect_eq(s.n, (size_t)n);
        bf_assert_abs(s.band_low, (double)lo / n, 1e-12);
        bf_assert_abs(s.band_high, (double)hi / n, 1e-12);
        bf_assert_rel(s.coverage_sd, sqrt(0.95 * 0.05 / n), TOL2);
    }
}

Test(calibration_summary, verdicts_below_inside_and_above_the_band)
{
    bf_calibration_summary s;
    bf_calibration c = make(200, 150); /* 0.75: far below 0.95 */
    cr_assert_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_OK);
    cr_expect_eq(s.verdict, -1);
    c = make(200, 190);
    cr_assert_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_OK);
    cr_expect_eq(s.verdict, 0);
    c = make(200, 200); /* P(X = 200) = 0.95^200 = 3.5e-5 */
    cr_assert_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_OK);
    cr_expect_eq(s.verdict, 1);
    c = make(40, 40); /* 0.95^40 = 0.13: chance */
    cr_assert_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_OK);
    cr_expect_eq(s.verdict, 0);
    /* the units of the spread: bias / sd, width / (2 z sd) */
    bf_assert_rel(s.bias_sd, 0.25, TOL2);
    bf_assert_rel(s.width_spread, 0.2 / (2.0 * 1.959963984540054 * 0.04),
                  1e-9);
    bf_assert_rel(s.not_identified, 0.25, TOL0);
}

Test(calibration_summary, refuses_what_was_not_calibrated)
{
    bf_calibration_summary s;
    bf_calibration c = make(40, 38);
    cr_expect_eq(bf_calibration_summarise(&c, 0, 0.95, &s), BF_EINVAL,
                 "NaN coverage: not a fitted parameter");
    cr_expect_eq(bf_calibration_summarise(&c, BF_MAX_PARAMS, 0.95, &s),
                 BF_EINVAL);
    cr_expect_eq(bf_calibration_summarise(&c, 1, 1.0, &s), BF_EINVAL);
    cr_expect_eq(bf_calibration_summarise(NULL, 1, 0.95, &s), BF_EINVAL);
    c.n_sim = 0;
    cr_expect_eq(bf_calibration_summarise(&c, 1, 0.95, &s), BF_EINVAL);
}
