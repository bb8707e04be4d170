/* bench_merl.c: the speed of MERL tables (issue 10): loading a full-size
 * table, sampling it at every valid cell, and the paper's grid fit over
 * every valid cell through the study (bf_study_run on a one-material
 * dataset). A benchmark, never a test: `make bench` runs it after
 * bench_study. No MERL file exists here, so it writes one: FC-E's BRDF
 * (m = 0.42, n = 1.7, about Cayman's fit) at every cell's centre, the
 * cells whose centre lies below the horizon marked invalid (negative), as
 * MERL marks cells it did not measure.
 *
 * Prints, as Markdown tables, each figure the median of repeated runs:
 *   - bf_merl_load of the 35 MB file (in the page cache) and its rate;
 *   - bf_merl_dataset at every valid cell, and at CURET's 205 (--data);
 *   - the study over every valid cell: the paper's fitted models (VH-G,
 *     VH-E, FC-G, FC-E, LFTG; ON has no inputs for this material), one at
 *     a time on 1 thread, and all five on 1 and 2 threads;
 *   - the study's cost per model evaluation against K (every valid cell,
 *     and evenly spaced subsets of it), which shows where it leaves the
 *     caches;
 *   - with --numpy, the same fits as a user would write them in numpy
 *     (bench/numpy_cells.py: one grid value at a time, vectorised over the
 *     configurations), on the same configurations and data.
 *
 *   bench_merl [--data DIR] [--numpy SCRIPT] [--quick] [--keep FILE]
 *   bench_merl --glossy FILE   (writes LAMBERT+GGX's table to FILE, no
 *                               more: bench/glossy_peer.sh fits it)
 *   bench_merl --glossy-noisy FILE  (the same with 5 % log-normal noise
 *                               per cell, fixed seed: the dense profile
 *                               intervals' bench, bench/RESULTS.md)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "brdffit.h"
#include "timing.h"

#define N_CELLS 1458000u
#define TABLE_BYTES (12u + 3u * N_CELLS * 8u)
#define N_PAPER 5

static const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};


static void die(const char *what, const bf_error *err)
{
    bf_bench_die("bench_merl", what, err);
}

/* ==== the table ==== */

/* The directions of the centre of cell (i, j, k) (SPEC §8; src/data/
 * merl.c): half vector at theta_h, phi_h = 0; 1 when above the horizon. */
static int centre(size_t i, size_t j, size_t k, double a[4])
{
    double th = ((i + 0.5) / 90.0) * ((i + 0.5) / 90.0) * (M_PI / 2.0);
    double td = (j + 0.5) / 90.0 * (M_PI / 2.0);
    double pd = (k + 0.5) / 180.0 * M_PI;
    double dx = sin(td) * cos(pd);
    double dy = sin(td) * sin(pd);
    double dz = cos(td);
    double iz = (dz * cos(th)) - (dx * sin(th));
    double oz = (dz * cos(th)) + (dx * sin(th));
    if (iz < 0.0 || oz < 0.0) {
        return 0;
    }
    a[0] = acos(fmin(1.0, iz));
    a[1] = atan2(dy, (dx * cos(th)) + (dz * sin(th)));
    a[2] = acos(fmin(1.0, oz));
    a[3] = atan2(-dy, (-dx * cos(th)) + (dz * sin(th)));
    return 1;
}

/* A standard normal deviate from the 64-bit xorshift state *x
 * (Box-Muller; deterministic across platforms' libc). */
static double gauss(unsigned long long *x)
{
    double u[2];
    int i;
    for (i = 0; i < 2; i++) {
        *x ^= *x << 13;
        *x ^= *x >> 7;
        *x ^= *x << 17;
        u[i] = ((double)(*x >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(2.0 * M_PI * u[1]);
}

/* Writes model's table to path, each cell's value times exp(noise z),
 * z standard normal (one per cell, all channels; noise 0: exact). */
static void write_table(const char *path, const bf_model_type *model,
                        const double *param, double noise)
{
    unsigned long long state = 20261204ull;
    static const int dims[3] = {90, 90, 180};
    double *raw = malloc(3 * (size_t)N_CELLS * sizeof *raw);
    bf_geom *g = malloc(N_CELLS * sizeof *g);
    size_t *at = malloc(N_CELLS * sizeof *at);
    double *f = malloc(N_CELLS * sizeof *f);
    size_t n = 0;
    size_t i;
    size_t j;
    size_t k;
    FILE *fp;
    if (raw == NULL || g == NULL || at == NULL || f == NULL) {
        die("out of memory", NULL);
    }
    for (i = 0; i < 3 * (size_t)N_CELLS; i++) {
        raw[i] = -1.0; /* invalid unless set below */
    }
    for (i = 0; i < 90; i++) {
        for (j = 0; j < 90; j++) {
            for (k = 0; k < 180; k++) {
                double a[4];
                if (centre(i, j, k, a)) {
                    g[n] = bf_geom_from_measurement(a[0], a[1], a[2], a[3]);
                    at[n++] = k + 180 * (j + 90 * i);
                }
            }
        }
    }
    if (bf_model_eval(model, param, n, g, f) != BF_OK) {
        die("the model on the cell centres", NULL);
    }
    for (k = 0; k < n; k++) {
        /* SPEC §2: a diffuse model's value is BRDF cos theta_i; a
         * specular model's is the BRDF (sr^-1, SPEC §9) */
        double brdf = model->kind == BF_MODEL_SPECULAR
                          ? f[k]
                          : f[k] / fmax(cos(g[k].theta_i), 1e-300);
        if (noise > 0.0) {
            brdf *= exp(noise * gauss(&state));
        }
        for (j = 0; j < 3; j++) {
            raw[j * N_CELLS + at[k]] = brdf / scale[j];
        }
    }
    fp = fopen(path, "wb");
    if (fp == NULL || fwrite(dims, 4, 3, fp) != 3 || /* little-endian host */
        fwrite(raw, sizeof *raw, 3 * (size_t)N_CELLS, fp) !=
            3 * (size_t)N_CELLS ||
        fclose(fp) != 0) {
        die("cannot write the table", NULL);
    }
    free(raw);
    free(g);
    free(at);
    free(f);
}

/* ==== measurements ==== */

static double time_load(const char *path, int reps)
{
    double *t = malloc((size_t)reps * sizeof *t);
    double med;
    int r;
    for (r = 0; r < reps; r++) {
        bf_merl *m = NULL;
        bf_error err;
        double t0 = bf_bench_now();
        if (bf_merl_load(path, &m, &err) != BF_OK) {
            die("load", &err);
        }
        t[r] = bf_bench_now() - t0;
        bf_merl_free(m);
    }
    med = bf_bench_median(t, reps);
    free(t);
    return med;
}

static double time_dataset(const bf_merl *m, size_t n, const double *at,
                           int reps, bf_dataset **keep)
{
    double *t = malloc((size_t)reps * sizeof *t);
    double med;
    int r;
    for (r = 0; r < reps; r++) {
        bf_dataset *ds = NULL;
        bf_error err;
        double t0 = bf_bench_now();
        if (bf_merl_dataset(m, n, at, "fc-e", "bench", &ds, &err) != BF_OK) {
            die("dataset", &err);
        }
        t[r] = bf_bench_now() - t0;
        if (r == reps - 1 && keep != NULL) {
            *keep = ds;
        } else {
            bf_dataset_free(ds);
        }
    }
    med = bf_bench_median(t, reps);
    free(t);
    return med;
}

/* Median time of the study of material 0 of ds with models (rows[0..n)
 * keep the last run's results). */
static double time_study(const bf_dataset *ds,
                         const bf_model_type *const *models, size_t n_models,
                         int threads, int reps, bf_study_row *rows)
{
    bf_target t = {0, BF_CHANNEL_MEAN, 0};
    bf_study_spec spec;
    double *tm = malloc((size_t)reps * sizeof *tm);
    double med;
    int r;
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_selection_init(&spec.select);
    spec.targets = &t;
    spec.n_targets = 1;
    spec.models = models;
    spec.n_models = n_models;
    spec.n_default = BF_DEFAULT_N;
    spec.n_threads = threads;
    for (r = 0; r < reps; r++) {
        bf_error err;
        double t0 = bf_bench_now();
        if (bf_study_run(&spec, rows, &err) != BF_OK) {
            die("study", &err);
        }
        tm[r] = bf_bench_now() - t0;
    }
    med = bf_bench_median(tm, reps);
    free(tm);
    return med;
}

/* Every step-th configuration of ds (material 0) as a new dataset. */
static bf_dataset *subset(const bf_merl *m, const bf_dataset *ds, size_t step,
                          size_t *n)
{
    const double *a = bf_dataset_angles(ds, 0);
    size_t all = bf_dataset_nconf(ds, 0);
    double *at = malloc((all / step + 1) * 4 * sizeof *at);
    bf_dataset *out = NULL;
    bf_error err;
    size_t k;
    *n = 0;
    for (k = 0; k < all; k += step) {
        memcpy(at + 4 * *n, a + 4 * k, 4 * sizeof *at);
        (*n)++;
    }
    if (bf_merl_dataset(m, *n, at, "subset", "bench", &out, &err) != BF_OK) {
        die("subset", &err);
    }
    free(at);
    return out;
}

/* Writes K, theta_i, theta_s, phi_s and the normalised radiance of the
 * study's target (material 0, mean, every configuration) to path for
 * numpy_cells.py. */
static void dump_cells(const bf_dataset *ds, const char *path)
{
    bf_target t = {0, BF_CHANNEL_MEAN, 0};
    bf_study_spec spec;
    size_t n = bf_dataset_nconf(ds, 0);
    size_t *sel = malloc(n * sizeof *sel);
    double *d = malloc(n * sizeof *d);
    const bf_geom *g = bf_dataset_geom(ds, 0);
    double kd;
    size_t k = 0;
    size_t i;
    bf_error err;
    FILE *fp;
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_selection_init(&spec.select);
    spec.targets = &t;
    spec.n_targets = 1;
    if (sel == NULL || d == NULL ||
        bf_study_target_data(&spec, 0, sel, &k, d, &err) != BF_OK) {
        die("the study's data", &err);
    }
    fp = fopen(path, "wb");
    if (fp == NULL) {
        die("cannot write the cells", NULL);
    }
    kd = (double)k;
    fwrite(&kd, sizeof kd, 1, fp);
    for (i = 0; i < k; i++) {
        fwrite(&g[sel[i]].theta_i, sizeof(double), 1, fp);
    }
    for (i = 0; i < k; i++) {
        fwrite(&g[sel[i]].theta_s, sizeof(double), 1, fp);
    }
    for (i = 0; i < k; i++) {
        fwrite(&g[sel[i]].phi_s, sizeof(double), 1, fp);
    }
    fwrite(d, sizeof *d, k, fp);
    if (fclose(fp) != 0) {
        die("cannot write the cells", NULL);
    }
    free(sel);
    free(d);
}

/* Runs numpy_cells.py on the cells of ds; prints brdffit's time (t_one of
 * VH-E, LFTG, VH-G) against numpy's. */
static void numpy_compare(const char *script, const bf_dataset *ds,
                          const double *t_one)
{
    char path[] = "/tmp/bench_merl_cells.XXXXXX";
    char cmd[8192];
    char line[256];
    FILE *p;
    int fd = mkstemp(path);
    if (fd < 0 || access("/usr/bin/python3", X_OK) != 0) {
        return;
    }
    close(fd);
    dump_cells(ds, path);
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 '%s' '%s'", script, path);
    p = popen(cmd, "r");
    if (p == NULL) {
        unlink(path);
        return;
    }
    printf("\n## Against numpy (bench/numpy_cells.py: one grid value at a "
           "time, vectorised over the K configurations)\n\n");
    printf("| model | numpy | brdffit (1 thread) | brdffit faster by |\n"
           "|---|---|---|---|\n");
    while (fgets(line, sizeof line, p) != NULL) {
        char name[16];
        double sec;
        double value;
        double lse;
        if (sscanf(line, "%15s %lf %lf %lf", name, &sec, &value, &lse) == 4) {
            double ours = strcmp(name, "VH-E") == 0   ? t_one[1]
                          : strcmp(name, "LFTG") == 0 ? t_one[4]
                                                      : t_one[0];
            printf("| %s (best %.2f) | %.2f s | %.2f s | %.1fx |\n", name,
                   value, sec, ours, sec / ours);
        }
    }
    pclose(p);
    unlink(path);
}

int main(int argc, char **argv)
{
    const bf_model_type *paper[N_PAPER] = {bf_model_vh_g, bf_model_vh_e,
                                           bf_model_fc_g, bf_model_fc_e,
                                           bf_model_lftg};
    const char *dir = "../shared/data/curet";
    const char *keep = NULL;
    const char *numpy = NULL;
    char path[] = "/tmp/bench_merl.XXXXXX";
    int reps_load = 21;
    int reps_big = 3;
    bf_study_row rows[N_PAPER];
    bf_merl *m = NULL;
    bf_dataset *all = NULL;
    size_t n_curet = 0;
    bf_error err;
    double t_load;
    double t_all;
    double t_curet = -1.0;
    double t_sum = 0.0;
    double t_one[N_PAPER];
    double t5;
    double t5_2;
    size_t n_all;
    size_t k;
    int fd;
    int a;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--data") == 0 && a + 1 < argc) {
            dir = argv[++a];
        } else if (strcmp(argv[a], "--keep") == 0 && a + 1 < argc) {
            keep = argv[++a];
        } else if (strcmp(argv[a], "--numpy") == 0 && a + 1 < argc) {
            numpy = argv[++a];
        } else if ((strcmp(argv[a], "--glossy") == 0 ||
                    strcmp(argv[a], "--glossy-noisy") == 0) &&
                   a + 1 < argc) {
            /* only the table of a glossy paint, for the dense fit of
             * bench/glossy_peer.sh: LAMBERT+GGX about krylon_blue's fit
             * (rho_d, rho_s, alpha, F0) */
            const double param[4] = {0.14, 1.0, 0.113, 0.0588};
            int noisy = strcmp(argv[a], "--glossy-noisy") == 0;
            write_table(argv[++a], bf_model_find("LAMBERT+GGX"), param,
                        noisy ? 0.05 : 0.0);
            return 0;
        } else if (strcmp(argv[a], "--quick") == 0) {
            reps_load = 5;
            reps_big = 1;
        } else {
            fprintf(stderr,
                    "usage: bench_merl [--data DIR] [--numpy SCRIPT] "
                    "[--quick] [--keep FILE] [--glossy FILE] "
                    "[--glossy-noisy FILE]\n");
            return 2;
        }
    }
    fd = mkstemp(path);
    if (fd < 0) {
        die("mkstemp", NULL);
    }
    close(fd);
    {
        const double param[2] = {0.42, BF_DEFAULT_N};
        write_table(path, bf_model_fc_e, param, 0.0);
    }

    printf("# brdffit %s: MERL tables\n\n", bf_version());
    printf("A full-size table (%u bytes) written from FC-E (m = 0.42, n = "
           "1.7) at every cell's centre, cells below the horizon invalid. "
           "Medians of %d loads (file in the page cache) and of %d runs of "
           "every study over all cells.\n\n",
           TABLE_BYTES, reps_load, reps_big);

    /* loading and sampling */
    t_load = time_load(path, reps_load);
    if (bf_merl_load(path, &m, &err) != BF_OK) {
        die("load", &err);
    }
    t_all = time_dataset(m, 0, NULL, reps_big, &all);
    n_all = bf_dataset_nconf(all, 0);
    {
        char tp[4096];
        snprintf(tp, sizeof tp, "%s/table.txt", dir);
        double *at = NULL;
        if (bf_curet_configs_load(tp, &at, &n_curet, &err) == BF_OK) {
            t_curet = time_dataset(m, n_curet, at, reps_load, NULL);
        }
        free(at);
    }
    printf("## Loading and sampling\n\n| step | median | |\n|---|---|---|\n");
    printf("| `bf_merl_load` (one fread, then checks and scales) | %.1f ms "
           "| %.0f MB/s |\n",
           1e3 * t_load, TABLE_BYTES / t_load / 1e6);
    printf("| `bf_merl_dataset`, every valid cell (K = %zu) | %.0f ms | "
           "%.0f ns per cell |\n",
           n_all, 1e3 * t_all, 1e9 * t_all / N_CELLS);
    if (t_curet >= 0.0) {
        printf("| `bf_merl_dataset` at CURET's %zu configurations | %.3f ms "
               "| |\n",
               n_curet, 1e3 * t_curet);
    }

    /* the study over every valid cell */
    printf("\n## The paper's grid fit over every valid cell (K = %zu, 501 "
           "grid values)\n\n",
           n_all);
    printf("| model | fit | 1 thread | ns per evaluation |\n|---|---|---|---|"
           "\n");
    for (k = 0; k < N_PAPER; k++) {
        t_one[k] = time_study(all, &paper[k], 1, 1, reps_big, rows);
        t_sum += t_one[k];
        printf("| %s | %s = %.2f, LSE %.3g | %.2f s | %.2f |\n",
               paper[k]->name, paper[k]->param[0].name, rows[0].fit.param[0],
               rows[0].fit.lse, t_one[k],
               1e9 * t_one[k] / (501.0 * (double)n_all));
    }
    t5 = time_study(all, paper, N_PAPER, 1, reps_big, rows);
    t5_2 = time_study(all, paper, N_PAPER, 2, reps_big, rows);
    printf("| all five, one study | | %.2f s (sum of the above %.2f s) | "
           "|\n",
           t5, t_sum);
    printf("| all five, 2 threads | | %.2f s (speed-up %.2f) | |\n", t5_2,
           t5 / t5_2);

    /* the cost per evaluation against K */
    printf("\n## Cost per model evaluation against K (1 thread; every "
           "step-th valid cell)\n\n");
    printf("| K | VH-G ns | VH-E ns | LFTG ns |\n|---|---|---|---|\n");
    {
        static const size_t steps[] = {500, 50, 5};
        size_t s;
        for (s = 0; s < sizeof steps / sizeof steps[0]; s++) {
            size_t n;
            bf_dataset *sub = subset(m, all, steps[s], &n);
            int reps = steps[s] >= 50 ? 11 : reps_big;
            double tg = time_study(sub, &paper[0], 1, 1, reps, rows);
            double te = time_study(sub, &paper[1], 1, 1, reps, rows);
            double tl = time_study(sub, &paper[4], 1, 1, reps, rows);
            printf("| %zu | %.2f | %.2f | %.2f |\n", n,
                   1e9 * tg / (501.0 * n), 1e9 * te / (501.0 * n),
                   1e9 * tl / (501.0 * n));
            bf_dataset_free(sub);
        }
        printf("| %zu | %.2f | %.2f | %.2f |\n", n_all,
               1e9 * t_one[0] / (501.0 * n_all),
               1e9 * t_one[1] / (501.0 * n_all),
               1e9 * t_one[4] / (501.0 * n_all));
    }

    if (numpy != NULL) {
        numpy_compare(numpy, all, t_one);
    }

    bf_dataset_free(all);
    bf_merl_free(m);
    if (keep != NULL) {
        if (rename(path, keep) != 0) {
            perror("bench_merl: --keep");
        }
    } else {
        unlink(path);
    }
    return 0;
}
