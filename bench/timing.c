/* timing.c: the clock, medians and fatal errors of the benchmarks
 * (timing.h). */
#include "timing.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

double bf_bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (1e-9 * (double)ts.tv_nsec);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

double bf_bench_median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return (n % 2 == 1) ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

void bf_bench_die(const char *prog, const char *what, const bf_error *err)
{
    char buf[1024];
    fprintf(stderr, "%s: %s: %s\n", prog, what,
            err != NULL ? bf_error_format(err, buf, sizeof buf) : "failed");
    exit(1);
}
