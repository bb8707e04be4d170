/* bench_coverage.c: the coverage table of the default 95% intervals
 * (doc/methods.md §3, issue 18): for every fitted parameter of every
 * fittable registry model (the exact fit's freed inputs free too), at
 * CURET's 198 configurations and at 198 random ones, under relative (5%)
 * and absolute (2% of the maximum) noise, under the objectives max,
 * scale, log, cosw and ngan (a free scale, SPEC §10), R simulations each
 * through bf_fit_calibrate (data normalised by their own maximum, as
 * measured data are).
 *
 * Usage: bench_coverage [R [NOISE [OBJECTIVES [CURET_DIR [MODELS [SEED
 * [B [CORNELL_FILE [GEOMETRY [TRUTHS [NEYMAN]]]]]]]]]]]
 * (R = 400, NOISE = auto, "objective" gives the intervals before issue 18;
 * OBJECTIVES = all, or one objective's name: the likelihood intervals do
 * not depend on the objective, which only starts their fit; MODELS = all,
 * or names separated by commas; SEED = 1000, the simulations' seed is
 * SEED + 10 geometry + noise; B = 0, else the bootstrap's replicates: two
 * more columns, the bootstrap's coverage and width over the spread;
 * GEOMETRY = all, or one geometry's name: CURET, Cornell or random;
 * TRUTHS = default, or name=value pairs separated by commas: a diffuse
 * model's parameters simulated at value instead of 37 % of their range,
 * and "at=f" for every other at f of its range; NEYMAN = auto, the
 * default intervals: the Neyman construction (BF_NEYMAN_AUTO_SIM) where a
 * second minimum of the profile competes; 0: the profile threshold
 * alone; N: every parameter's construction with N simulations per
 * threshold, a diffuse model's only; with a construction, three more
 * columns: the profile threshold's coverage and width over the spread
 * before it, and the share of simulations whose profile competes).
 * Prints one Markdown
 * row per (model, parameter, geometry, noise, objective): coverage, the
 * median width over the spread of the maximum-likelihood estimates
 * (2 z sd; 1 is calibrated), the sd of the objective's estimates over
 * that of the ML ones, and the share of intervals flagged not identified
 * (open to a bound the estimate is not on, or split in two regions). Never part of the tests.
 *
 * The specular family (SPEC §9; issue 17 item 6): MODELS may name
 * the composites LAMBERT+X of every specular model X and AS alone (the
 * truths below; "all" means the diffuse table only), fitted under
 * ngan at the Cornell geometry (argument 9, CORNELL_FILE, default
 * ../shared/data/cornell-pbrt-v2/krylon_blue.brdf: its 1439
 * configurations with theta_i, theta_o <= 80 deg) and at 300 random ones
 * (half within 10 deg of the mirror direction), the data kept in sr^-1
 * (bf_calibrate). */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdffit.h"
#include "data/curet.h"
#include "internal.h"
#include "random_geometry.h"

#define NCONF 198
/* The objectives of the diffuse table (issue 18 item 2: max, scale, log,
 * ngan; and cosw). */
#define NOBJ 5

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

/* The truth of parameter name from truths ("name=value,..."), or dflt
 * when truths does not name it. */
static double truth_of(const char *truths, const char *name, double dflt)
{
    size_t len = strlen(name);
    const char *p = truths;
    while ((p = strstr(p, name)) != NULL) {
        if ((p == truths || p[-1] == ',') && p[len] == '=') {
            return strtod(p + len + 1, NULL);
        }
        p += len;
    }
    return dflt;
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

/* One row of the table: parameter j of cal. */
static void print_row(const char *model, const char *param, const char *geom,
                      const char *noise, const char *obj,
                      const bf_calibration *cal, size_t j, size_t n_boot,
                      size_t n_ny)
{
    double spread = 2.0 * 1.959964 * cal->ml_sd[j];
    printf("| %s | %s | %s | %s | %s | %.3f | %.2f | %.2f | %.3f |", model,
           param, geom, noise, obj, cal->coverage[j], cal->width[j] / spread,
           cal->sd[j] / cal->ml_sd[j], cal->not_identified[j]);
    if (n_boot >= 2) {
        printf(" %.3f | %.2f |", cal->boot_coverage[j],
               cal->boot_width[j] / spread);
    }
    if (n_ny > 0) {
        printf(" %.3f | %.2f | %.3f |", cal->f_coverage[j],
               cal->f_width[j] / spread, cal->competing[j]);
    }
    printf("\n");
    fflush(stdout);
}

#define MAX_SPEC_CONF 1500
#define N_SPEC_RANDOM 300

/* The Cornell file's configurations with theta_i, theta_o <= 80 deg. */
static size_t cornell_geom(const char *path, bf_geom *geom)
{
    static size_t sel[MAX_SPEC_CONF];
    bf_dataset *ds = NULL;
    bf_error err;
    bf_selection s;
    size_t n = 0;
    size_t k;
    if (bf_dataset_load(path, NULL, &ds, &err) != BF_OK ||
        bf_dataset_nconf(ds, 0) > MAX_SPEC_CONF) {
        fprintf(stderr, "bench_coverage: cannot load %s\n", path);
        exit(1);
    }
    bf_selection_init(&s);
    s.max_theta = BF_KEEP_SCALE_THETA;
    if (bf_dataset_select(ds, 0, BF_CHANNEL_MEAN, &s, sel, &n, NULL) != BF_OK) {
        fprintf(stderr, "bench_coverage: cannot select %s\n", path);
        exit(1);
    }
    for (k = 0; k < n; k++) {
        geom[k] = bf_dataset_geom(ds, 0)[sel[k]];
    }
    bf_dataset_free(ds);
    return n;
}

/* The specular rows: each composite with a truth below, both geometries,
 * both noises, objective ngan. */
static void specular_rows(const char *models, const char *cornell,
                          const char *geometry, size_t reps, bf_noise noise,
                          unsigned long seed0, size_t n_boot)
{
    /* krylon_blue's ngan fits (compare --fit exact --objective ngan),
     * rounded, except LAMBERT+WARD: a broader lobe than krylon_blue's
     * alpha 0.019 */
    static const struct {
        const char *name;
        double truth[BF_MAX_PARAMS];
    } spec[] = {{"LAMBERT+GGX", {0.077, 0.76, 0.113, 0.059}},
                {"LAMBERT+WARD", {0.1, 0.05, 0.08}},
                {"LAMBERT+BECKMANN", {0.093, 0.45, 0.095, 0.068}},
                {"LAMBERT+CT", {0.093, 0.45, 0.095, 0.068}},
                {"LAMBERT+BLINN-PHONG", {0.12, 0.008, 8500.0}},
                {"LAMBERT+WARD-DUER", {0.063, 0.062, 0.065}},
                {"LAMBERT+WARD-GMD", {0.063, 0.063, 0.065}},
                {"AS", {0.095, 0.043, 107.0}},
                {"LAMBERT+LAFORTUNE", {0.118, -1.03, 0.89, 142.0}},
                {"LAMBERT+ABC", {0.057, 13.2, 395.0, 1.12, 1.66}}};
    static bf_geom geoms[2][MAX_SPEC_CONF];
    const char *gname[2] = {"Cornell", "random"};
    const char *nname[2] = {"rel 5%", "abs 2%"};
    const double npow[2] = {2.0, 0.0};
    const double nsd[2] = {0.05, 0.02};
    size_t n_geom[2] = {0, 0};
    size_t i;
    for (i = 0; i < sizeof spec / sizeof spec[0]; i++) {
        const bf_model_type *t = bf_model_find(spec[i].name);
        size_t g;
        if (strcmp(models, "all") == 0 || !listed(models, spec[i].name)) {
            continue;
        }
        if (t == NULL) {
            fprintf(stderr, "bench_coverage: no model %s\n", spec[i].name);
            exit(1);
        }
        if (n_geom[0] == 0) {
            n_geom[0] = cornell_geom(cornell, geoms[0]);
            n_geom[1] = bf_random_geometry(geoms[1], N_SPEC_RANDOM, 11, 1);
        }
        for (g = 0; g < 2; g++) {
            size_t q;
            if (!listed(geometry, gname[g])) {
                continue;
            }
            for (q = 0; q < 2; q++) {
                bf_problem pb;
                bf_calibration cal;
                size_t j;
                int rc;
                bf_problem_init(&pb, t, spec[i].truth, n_geom[g], geoms[g],
                                NULL);
                pb.objective = BF_OBJ_NGAN;
                rc = bf_fit_calibrate(&pb, spec[i].truth, npow[q], nsd[q], noise,
                                  reps, n_boot, 0, 0, seed0 + 10 * g + q,
                                  0.95, &cal);
                for (j = 0; j < t->p; j++) {
                    if (rc != BF_OK) {
                        printf("| %s | | %s | %s | ngan | error %d | | | |\n",
                               t->name, gname[g], nname[q], rc);
                        break;
                    }
                    print_row(t->name, t->param[j].name, gname[g], nname[q],
                              "ngan", &cal, j, n_boot, 0);
                }
            }
        }
    }
}

int main(int argc, char **argv)
{
    static bf_geom geoms[2][NCONF];
    size_t n_geom[2];
    const char *gname[2] = {"CURET", "random"};
    const char *nname[2] = {"rel 5%", "abs 2%"};
    const double npow[2] = {2.0, 0.0};
    const double nsd[2] = {0.05, 0.02};
    const bf_objective objs[NOBJ] = {BF_OBJ_MAX, BF_OBJ_SCALE, BF_OBJ_LOG,
                                     BF_OBJ_COSW, BF_OBJ_NGAN};
    size_t reps = argc > 1 ? (size_t)atol(argv[1]) : 400;
    bf_noise noise = BF_NOISE_AUTO;
    const char *only = argc > 3 ? argv[3] : "all";
    const char *dir = argc > 4 ? argv[4] : "../shared/data/curet";
    const char *models = argc > 5 ? argv[5] : "all";
    unsigned long seed0 = argc > 6 ? strtoul(argv[6], NULL, 10) : 1000;
    size_t n_boot = argc > 7 ? (size_t)atol(argv[7]) : 0;
    const char *cornell =
        argc > 8 ? argv[8]
                 : "../shared/data/cornell-pbrt-v2/krylon_blue.brdf";
    const char *geometry = argc > 9 ? argv[9] : "all";
    const char *truths = argc > 10 ? argv[10] : "default";
    /* the default intervals' construction, where a second minimum
     * competes; a number: every parameter's, with that many simulations */
    int ny_every = argc > 11 && strcmp(argv[11], "auto") != 0;
    size_t n_ny = ny_every ? (size_t)atol(argv[11]) : BF_NEYMAN_AUTO_SIM;
    size_t i;
    gsl_set_error_handler_off();
    if (argc > 2 && bf_noise_find(argv[2], &noise) != BF_OK) {
        fprintf(stderr, "bench_coverage: unknown noise '%s'\n", argv[2]);
        return 2;
    }
    n_geom[0] = curet_geom(dir, geoms[0]);
    n_geom[1] = bf_random_geometry(geoms[1], NCONF, 7, 0);
    printf("| model | param | geometry | noise | objective | covered | "
           "width / spread | sd obj / sd ML | not identified |%s%s\n"
           "|---|---|---|---|---|---|---|---|---|%s%s\n",
           n_boot >= 2 ? " bootstrap covered | bootstrap width / spread |"
                       : "",
           n_ny > 0 ? " F covered | F width / spread | competing |" : "",
           n_boot >= 2 ? "---|---|" : "", n_ny > 0 ? "---|---|---|" : "");
    specular_rows(models, cornell, geometry, reps, noise, seed0, n_boot);
    for (i = 0; i < bf_model_count(); i++) {
        bf_model_variant v;
        size_t g;
        bf_model_variant_init(&v, bf_model_get(i));
        bf_model_variant_exact(&v, 0);
        if (bf__fits_nothing(&v.type) || v.type.kind == BF_MODEL_SPECULAR ||
            !listed(models, v.type.name)) { /* specular: specular_rows */
            continue;
        }
        for (g = 0; g < 2; g++) {
            size_t q;
            if (!listed(geometry, gname[g])) {
                continue;
            }
            for (q = 0; q < 2; q++) {
                size_t o;
                for (o = 0; o < NOBJ; o++) {
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
                            double f = truth_of(truths, "at", 0.3731);
                            truth[j] = truth_of(
                                truths, v.type.param[j].name,
                                pb.lo[j] + f * (pb.hi[j] - pb.lo[j]));
                        }
                        pb.fixed[j] = truth[j];
                    }
                    rc = bf_fit_calibrate(&pb, truth, npow[q], nsd[q], noise,
                                          reps, n_boot, n_ny, ny_every,
                                          seed0 + 10 * g + q, 0.95, &cal);
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
                        print_row(v.type.name, v.type.param[j].name,
                                  gname[g], nname[q],
                                  bf_objective_name(objs[o]), &cal, j,
                                  n_boot, n_ny);
                    }
                }
            }
        }
    }
    return 0;
}
