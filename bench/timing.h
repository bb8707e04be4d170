/* timing.h: what the benchmarks of bench/ share -- a monotonic clock,
 * medians and a fatal error (bench/timing.c). */
#ifndef BF_BENCH_TIMING_H
#define BF_BENCH_TIMING_H

#include "brdffit.h"

/* Seconds of CLOCK_MONOTONIC. */
double bf_bench_now(void);

/* Median of t[0..n) (sorts t). */
double bf_bench_median(double *t, int n);

/* Prints "PROG: WHAT: the error report" and exits with status 1. */
void bf_bench_die(const char *prog, const char *what, const bf_error *err);

#endif
