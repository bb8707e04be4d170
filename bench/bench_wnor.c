/* bench_wnor.c: the accuracy of WNO-R's quadrature (src/models/wno_r.c,
 * doc/methods.md §7) on CURET's 205 configurations, and its speed.
 *
 *   bench_wnor --data DIR [--stride S] [--skip-gsl] [--skip-engine]
 *
 * 1. The engine's tables (bf_problem_residuals' curve) against the rule
 *    itself (bf_model_eval) over the fit's sigma and n grids, their
 *    midpoints and extremes: the largest relative difference of a value.
 * 2. The rule against GSL's nested qagp (tests/models/wnor_ref.h, relative
 *    tolerances 1e-12 outside, 1e-13 inside) on every S-th configuration
 *    at sigma = 0.003, 0.05, 0.3, 0.9, 1.55 and n = 1.2, 1.85, 2.5.
 * 3. Wall time of one value by the rule and of a curve by the engine.
 * Never part of the tests (make bench does not run it either: minutes). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdffit.h"
#include "fit/engine.h"
#include "timing.h"
#include "wnor_ref.h"

static double rel(double a, double b)
{
    if (a == b) {
        return 0.0;
    }
    return fabs(a - b) / fmax(fabs(a), fabs(b));
}

int main(int argc, char **argv)
{
    const char *dir = NULL;
    size_t stride = 1;
    int skip_gsl = 0;
    int skip_engine = 0;
    char path[4096];
    bf_table *t = NULL;
    bf_error err;
    bf_geom g[BF_CURET_NCONF];
    double a[BF_CURET_NCONF];
    double b[BF_CURET_NCONF];
    size_t n;
    size_t k;
    size_t i;
    size_t j;
    bf__cset cs;
    bf__prep pm;
    void *work = NULL;
    double sig[80];
    double nn[40];
    size_t ns = 0;
    size_t nn_count = 0;
    double worst = 0.0;
    double wsig = 0.0;
    double wn = 0.0;
    size_t wk = 0;
    int arg;
    for (arg = 1; arg < argc; arg++) {
        if (strcmp(argv[arg], "--data") == 0 && arg + 1 < argc) {
            dir = argv[++arg];
        } else if (strcmp(argv[arg], "--stride") == 0 && arg + 1 < argc) {
            stride = (size_t)strtoul(argv[++arg], NULL, 10);
        } else if (strcmp(argv[arg], "--skip-gsl") == 0) {
            skip_gsl = 1;
        } else if (strcmp(argv[arg], "--skip-engine") == 0) {
            skip_engine = 1;
        } else {
            fprintf(stderr, "usage: bench_wnor --data DIR [--stride S] "
                            "[--skip-gsl] [--skip-engine]\n");
            return 2;
        }
    }
    if (dir == NULL || stride == 0) {
        fprintf(stderr, "bench_wnor: --data DIR is required\n");
        return 2;
    }
    snprintf(path, sizeof path, "%s/table.txt", dir);
    if (bf_table_load(path, &t, &err) != BF_OK) {
        fprintf(stderr, "bench_wnor: cannot load %s\n", path);
        return 1;
    }
    n = bf_table_size(t); /* all 205, the 7 specular ones too */
    for (k = 0; k < n; k++) {
        g[k] = bf_table_geom(t, k);
    }
    bf_table_free(t);
    printf("configurations: %zu\n", n);
    /* the fit's grids (sigma = 0.05 i, n = 1.2 + 0.1 i), midpoints and
     * extremes */
    for (i = 1; i <= 31; i++) {
        sig[ns++] = 0.05 * (double)i;
        sig[ns++] = 0.05 * (double)i - 0.025;
    }
    sig[ns++] = 1e-6;
    sig[ns++] = 1e-4;
    sig[ns++] = 0.003;
    sig[ns++] = 3.14159265358979323846 / 512.0;
    sig[ns++] = 0.0062;
    sig[ns++] = 0.5 * 3.14159265358979323846;
    for (i = 0; i < 14; i++) {
        nn[nn_count++] = 1.2 + 0.1 * (double)i;
        nn[nn_count++] = 1.25 + 0.1 * (double)i;
    }
    nn[nn_count++] = 1.0;
    nn[nn_count++] = 1.05;
    nn[nn_count++] = 5.0;
    nn[nn_count++] = 10.0;
    if (bf__cset_init(&cs, n, g) != BF_OK ||
        bf__prep_init(&pm, bf_model_wno_r, &cs) != BF_OK ||
        (work = bf__work_alloc(&pm)) == NULL) {
        return 1;
    }
    if (!skip_engine) {
        double t0 = bf_bench_now();
        for (j = 0; j < nn_count; j++) {
            for (i = 0; i < ns; i++) {
                double p[2] = {sig[i], nn[j]};
                if (bf__curve(&pm, p, work, a) != BF_OK ||
                    bf_model_eval(bf_model_wno_r, p, n, g, b) != BF_OK ||
                    bf_normalise(n, b, b) != BF_OK) {
                    return 1;
                }
                for (k = 0; k < n; k++) {
                    double r = rel(a[k], b[k]);
                    if (r > worst) {
                        worst = r;
                        wsig = sig[i];
                        wn = nn[j];
                        wk = k;
                    }
                }
            }
        }
        printf("engine tables against the rule: %zu sigma x %zu n x %zu "
               "configurations: largest relative difference %.2e "
               "(sigma %.4g, n %.3g, configuration %zu); %.1f s\n",
               ns, nn_count, n, worst, wsig, wn, wk, bf_bench_now() - t0);
    }
    free(work);
    bf__prep_free(&pm);
    bf__cset_free(&cs);
    {
        double p[2] = {0.4, 1.6};
        double t0 = bf_bench_now();
        int reps = 20;
        int r;
        for (r = 0; r < reps; r++) {
            bf_model_eval(bf_model_wno_r, p, n, g, b);
        }
        printf("the rule: %.1f us per value\n",
               1e6 * (bf_bench_now() - t0) / (reps * (double)n));
    }
    if (!skip_gsl) {
        static const double gs[] = {0.003, 0.05, 0.3, 0.9, 1.55};
        static const double gn[] = {1.2, 1.85, 2.5};
        double t0 = bf_bench_now();
        size_t s;
        size_t q;
        for (s = 0; s < sizeof gs / sizeof gs[0]; s++) {
            for (q = 0; q < sizeof gn / sizeof gn[0]; q++) {
                double p[2] = {gs[s], gn[q]};
                double w = 0.0;
                double west = 0.0;
                size_t at = 0;
                int bad = 0;
                bf_model_eval(bf_model_wno_r, p, n, g, b);
                for (k = 0; k < n; k += stride) {
                    int st;
                    double e;
                    double ref = wref_value(g[k].theta_i, g[k].theta_s,
                                            g[k].phi_s, gs[s], gn[q], 1e-12,
                                            1e-13, &st, &e);
                    double r = rel(b[k], ref);
                    bad += st != GSL_SUCCESS;
                    west = fmax(west, e);
                    if (r > w) {
                        w = r;
                        at = k;
                    }
                }
                printf("sigma %.3f n %.2f: rule against qagp: largest "
                       "relative error %.2e (configuration %zu); GSL's "
                       "largest error estimate %.1e, %d statuses not "
                       "success\n",
                       gs[s], gn[q], w, at, west, bad);
                fflush(stdout);
            }
        }
        printf("qagp reference: %.1f s\n", bf_bench_now() - t0);
    }
    return 0;
}
