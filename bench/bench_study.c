/* bench_study.c: times the paper's 24-sample study (SPEC §7, tables only:
 * loading excluded, no output written) as the median of repeated runs.
 * A benchmark, never a test: `make bench` runs it.
 *
 *   bench_study [--data DIR] [--reps N]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "brdffit.h"

#define DEFAULT_REPS 21

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a;
    double y = *(const double *)b;
    return (x > y) - (x < y);
}

static int die(const bf_error *err)
{
    char buf[1024];
    fprintf(stderr, "bench_study: %s\n", bf_error_format(err, buf, sizeof buf));
    return 1;
}

int main(int argc, char **argv)
{
    const char *dir = "../shared/data/curet";
    int reps = DEFAULT_REPS;
    char path[4096];
    char ref[4096];
    bf_table *t = NULL;
    bf_brdf *b = NULL;
    bf_sample_table *on = NULL;
    bf_error err;
    size_t sel[BF_CURET_NCONF];
    size_t n_sel;
    const bf_model_type *models[6];
    bf_study_row rows[BF_STUDY_NSAMPLES * 6];
    bf_study_spec spec;
    double *times;
    long evals = 0;
    int i;

    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--data") == 0 && i + 1 < argc) {
            dir = argv[++i];
        } else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
            reps = atoi(argv[++i]);
        } else {
            fprintf(stderr, "usage: bench_study [--data DIR] [--reps N]\n");
            return 2;
        }
    }
    if (reps < 1) {
        reps = 1;
    }
    snprintf(path, sizeof path, "%s/table.txt", dir);
    if (bf_table_load(path, &t, &err) != BF_OK) {
        return die(&err);
    }
    snprintf(path, sizeof path, "%s/abrdf.dat", dir);
    if (bf_brdf_load(path, bf_table_size(t), &b, &err) != BF_OK) {
        return die(&err);
    }
    snprintf(ref, sizeof ref, "%s/../../reference/oren_nayar_params.tsv",
             dir);
    if (bf_on_params_load(ref, &on, &err) != BF_OK) {
        return die(&err);
    }
    n_sel = bf_table_select(t, M_PI_2, sel); /* SPEC §1.4: K = 198 */
    models[0] = bf_model_vh_g;
    models[1] = bf_model_vh_e;
    models[2] = bf_model_fc_g;
    models[3] = bf_model_fc_e;
    models[4] = bf_model_on;
    models[5] = bf_model_lftg;
    memset(&spec, 0, sizeof spec);
    spec.table = t;
    spec.brdf = b;
    spec.sel = sel;
    spec.n_sel = n_sel;
    spec.samples = bf_study_samples;
    spec.n_samples = BF_STUDY_NSAMPLES;
    spec.models = models;
    spec.n_models = 6;
    spec.n_default = BF_DEFAULT_N;
    spec.on_params = on;

    times = malloc((size_t)reps * sizeof *times);
    if (times == NULL) {
        return 1;
    }
    for (i = 0; i < reps; i++) {
        double t0 = now();
        if (bf_study_run(&spec, rows, &err) != BF_OK) {
            return die(&err);
        }
        times[i] = now() - t0;
    }
    for (i = 0; i < BF_STUDY_NSAMPLES * 6; i++) {
        evals += (long)rows[i].fit.n_eval;
    }
    qsort(times, (size_t)reps, sizeof *times, cmp_double);
    printf("brdffit %s benchmark: paper study, 24 samples x 6 models, "
           "K = %zu\n", bf_version(), n_sel);
    printf("grid points scored: %ld (each %zu configurations)\n", evals,
           n_sel);
    printf("fit compute time: median %.3f ms, min %.3f ms, max %.3f ms "
           "over %d runs\n",
           1e3 * times[reps / 2], 1e3 * times[0], 1e3 * times[reps - 1],
           reps);
    free(times);
    bf_sample_table_free(on);
    bf_brdf_free(b);
    bf_table_free(t);
    return 0;
}
