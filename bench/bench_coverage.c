/* bench_coverage.c: the coverage table of the default 95% intervals
 * (doc/methods.md §3, issue 18): for every fitted parameter of every
 * fittable registry model (the exact fit's freed inputs free too), at
 * CURET's 198 configurations and at 198 random ones, under relative (5%)
 * and absolute (2% of the maximum) noise, under the objectives max,
 * scale, log and cosw, R simulations each through bf_fit_calibrate (data
 * normalised by their own maximum, as measured data are).
 *
 * Usage: bench_coverage [R [NOISE [OBJECTIVES [CURET_DIR [MODELS [SEED
 * [B]]]]]]]
 * (R = 400, NOISE = auto, "objective" gives the intervals before issue 18;
 * OBJECTIVES = all, or one objective's name: the likelihood intervals do
 * not depend on the objective, which only starts their fit; MODELS = all,
 * or names separated by commas; SEED = 1000, the simulations' seed is
 * SEED + 10 geometry + noise; B = 0, else the bootstrap's replicates: two
 * more columns, the bootstrap's coverage and width over the spread). Prints one Markdown
 * row per (model, parameter, geometry, noise, objective): coverage, the
 * median width over the spread of the maximum-likelihood estimates
 * (2 z sd; 1 is calibrated), the sd of the objective's estimates over
 * that of the ML ones, and the share of intervals flagged not identified
 * (open to a bound the estimate is not on). Never part of the tests. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdffit.h"
#include "data/curet.h"
#include "internal.h"

#define NCONF 198

static size_t curet_geom(const char *dir, bf_geom *geom)
{
    char path[4096];
    bf_table *t = NULL;
    bf_error err;
    size_t sel[BF_CURET_NCONF];
    size_t n;
    size_t k;
    snprintf(path, sizeof path, "%s/table.txt", dir);
    if (bf_table_load(path, &t, &err) != BF_OK) {
        fprintf(stderr, "bench_coverage: cannot load %s\n", path);
        exit(1);
    }
    n = bf_table_select(t, M_PI, sel);
    for (k = 0; k < n && k < NCONF; k++) {
        geom[k] = bf_table_geom(t, sel[k]);
    }
    bf_table_free(t);
    return k;
}

/* Directions uniform on the hemisphere up to 80 degrees (fixed seed). */
static size_t random_geom(bf_geom *geom)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double cmin = cos(80.0 * M_PI / 180.0);
    size_t k;
    gsl_rng_set(rng, 7);
    for (k = 0; k < NCONF; k++) {
        geom[k].theta_i = acos(cmin + (1.0 - cmin) * gsl_rng_uniform(rng));
        geom[k].phi_i = M_PI;
        geom[k].theta_s = acos(cmin + (1.0 - cmin) * gsl_rng_uniform(rng));
        geom[k].phi_s = M_PI * (2.0 * gsl_rng_uniform(rng) - 1.0);
    }
    gsl_rng_free(rng);
    return NCONF;
}

/* 1 when name is in the comma-separated list (or the list is "all"). */
static int listed(const char *list, const char *name)
{
    size_t len = strlen(name);
    const char *p = list;
    if (strcmp(list, "all") == 0) {
        return 1;
    }
    while ((p = strstr(p, name)) != NULL) {
        if ((p == list || p[-1] == ',') && (p[len] == ',' || p[len] == '\0')) {
            return 1;
        }
        p += len;
    }
    return 0;
}

int main(int argc, char **argv)
{
    static bf_geom geoms[2][NCONF];
    size_t n_geom[2];
    const char *gname[2] = {"CURET", "random"};
    const char *nname[2] = {"rel 5%", "abs 2%"};
    const double npow[2] = {2.0, 0.0};
    const double nsd[2] = {0.05, 0.02};
    const bf_objective objs[4] = {BF_OBJ_MAX, BF_OBJ_SCALE, BF_OBJ_LOG,
                                  BF_OBJ_COSW};
    size_t reps = argc > 1 ? (size_t)atol(argv[1]) : 400;
    bf_noise noise = BF_NOISE_AUTO;
    const char *only = argc > 3 ? argv[3] : "all";
    const char *dir = argc > 4 ? argv[4] : "../shared/data/curet";
    const char *models = argc > 5 ? argv[5] : "all";
    unsigned long seed0 = argc > 6 ? strtoul(argv[6], NULL, 10) : 1000;
    size_t n_boot = argc > 7 ? (size_t)atol(argv[7]) : 0;
    size_t i;
    gsl_set_error_handler_off();
    if (argc > 2 && bf_noise_find(argv[2], &noise) != BF_OK) {
        fprintf(stderr, "bench_coverage: unknown noise '%s'\n", argv[2]);
        return 2;
    }
    n_geom[0] = curet_geom(dir, geoms[0]);
    n_geom[1] = random_geom(geoms[1]);
    printf("| model | param | geometry | noise | objective | covered | "
           "width / spread | sd obj / sd ML | not identified |%s\n"
           "|---|---|---|---|---|---|---|---|---|%s\n",
           n_boot >= 2 ? " bootstrap covered | bootstrap width / spread |"
                       : "",
           n_boot >= 2 ? "---|---|" : "");
    for (i = 0; i < bf_model_count(); i++) {
        bf_model_variant v;
        size_t g;
        bf_model_variant_init(&v, bf_model_get(i));
        bf_model_variant_exact(&v, 0);
        if (bf__fits_nothing(&v.type) || !listed(models, v.type.name)) {
            continue;
        }
        for (g = 0; g < 2; g++) {
            size_t q;
            for (q = 0; q < 2; q++) {
                size_t o;
                for (o = 0; o < 4; o++) {
                    bf_problem pb;
                    bf_calibration cal;
                    double truth[BF_MAX_PARAMS];
                    size_t j;
                    int rc;
                    if (strcmp(only, "all") != 0 &&
                        strcmp(only, bf_objective_name(objs[o])) != 0) {
                        continue;
                    }
                    bf_problem_init(&pb, &v.type, NULL, n_geom[g], geoms[g],
                                    NULL);
                    pb.objective = objs[o];
                    for (j = 0; j < v.type.p; j++) {
                        truth[j] = pb.fixed[j];
                        if ((pb.free_mask >> j) & 1u) {
                            truth[j] = pb.lo[j] + 0.3731 * (pb.hi[j] - pb.lo[j]);
                        }
                        pb.fixed[j] = truth[j];
                    }
                    rc = bf_fit_calibrate(&pb, truth, npow[q], nsd[q], noise,
                                          reps, n_boot, seed0 + 10 * g + q, 0.95, &cal);
                    if (rc != BF_OK) {
                        printf("| %s | | %s | %s | %s | error %d | | | |\n",
                               v.type.name, gname[g], nname[q],
                               bf_objective_name(objs[o]), rc);
                        continue;
                    }
                    for (j = 0; j < v.type.p; j++) {
                        if (!((pb.free_mask >> j) & 1u)) {
                            continue;
                        }
                        printf("| %s | %s | %s | %s | %s | %.3f | %.2f | "
                               "%.2f | %.3f |",
                               v.type.name, v.type.param[j].name, gname[g],
                               nname[q], bf_objective_name(objs[o]),
                               cal.coverage[j],
                               cal.width[j] / (2.0 * 1.959964 * cal.ml_sd[j]),
                               cal.sd[j] / cal.ml_sd[j],
                               cal.not_identified[j]);
                        if (n_boot >= 2) {
                            printf(" %.3f | %.2f |", cal.boot_coverage[j],
                                   cal.boot_width[j] /
                                       (2.0 * 1.959964 * cal.ml_sd[j]));
                        }
                        printf("\n");
                        fflush(stdout);
                    }
                }
            }
        }
    }
    return 0;
}
