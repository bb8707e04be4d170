/* bench_study.c: the speed benchmark of brdffit (issue 6). A benchmark,
 * never a test: `make bench` runs it. Prints, as Markdown tables, each
 * figure the median of repeated runs:
 *   - the machine: cores, clock and 512-bit throughputs (bench/machine.c);
 *   - model evaluations per second, plain (bf_model_eval) and study path
 *     (bf__grid_alloc's kernels), for every model;
 *   - the paper protocol (24 samples x 6 models, tables only): fit compute
 *     on 1 and 2 threads, and the whole process `brdffit compare -q`;
 *   - the numpy baseline (bench/numpy_baseline.py), compute and process,
 *     when /usr/bin/python3 has numpy;
 *   - all 61 samples x all 9 models; a bootstrap (1000 resamples of the
 *     configurations of one sample, every paper model refitted);
 *   - scaling with samples, grid size, configurations and threads;
 *   - the floor: the lower bound of the paper protocol's fit compute on
 *     one core from its operation counts and the measured throughputs.
 *
 *   bench_study [--data DIR] [--reference DIR] [--cli PATH]
 *               [--numpy SCRIPT] [--quick]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "brdffit.h"
#include "data/curet.h"
#include "fit/engine.h"
#include "machine.h"
#include "timing.h"

#ifndef BF_BUILD_TYPE
#define BF_BUILD_TYPE "?"
#endif
#ifndef BF_C_FLAGS
#define BF_C_FLAGS "?"
#endif

/* Repetitions (medians): full run and --quick. */
typedef struct {
    int study;    /* paper protocol, fit compute */
    int process;  /* whole processes */
    int all;      /* 61 x 9 */
    int boot;     /* bootstrap runs of BOOT_RESAMPLES */
    int scale;    /* each scaling point */
    int eval;     /* per-model rates */
} reps_t;

#define BOOT_RESAMPLES 1000
#define BOOT_SEED 20260611u
#define MAX_MODELS 16

/* ==== helpers ============================================================ */


static void die(const char *what, const bf_error *err)
{
    bf_bench_die("bench_study", what, err);
}

/* Inputs shared by every measurement. */
typedef struct {
    bf_table *t;
    bf_brdf *b;
    bf_dataset *ds;            /* the same data as a dataset */
    bf_target paper_t[BF_STUDY_NSAMPLES]; /* the study's 24 samples */
    bf_sample_table *on;
    size_t sel[BF_CURET_NCONF];
    size_t n_sel;
    bf_geom geom[BF_CURET_NCONF];
    const bf_model_type *paper[6]; /* VH-G VH-E FC-G FC-E ON LFTG */
} inputs_t;

static void spec_init(const inputs_t *in, bf_study_spec *spec)
{
    memset(spec, 0, sizeof *spec);
    spec->data = in->ds;
    bf_selection_init(&spec->select); /* SPEC §1.4: K = 198 */
    spec->targets = in->paper_t;
    spec->n_targets = BF_STUDY_NSAMPLES;
    spec->models = in->paper;
    spec->n_models = 6;
    spec->n_default = BF_DEFAULT_N;
    spec->on_params = in->on;
    spec->n_threads = 1;
}

/* The fastest of the runs time_study last timed (seconds): on a machine
 * shared with other work, the run least disturbed by it. */
static double last_min;

/* Median time of reps runs of the study spec (seconds); last_min gets the
 * fastest. */
static double time_study(const bf_study_spec *spec, int reps)
{
    bf_study_row *rows = calloc(spec->n_targets * spec->n_models + 1,
                                sizeof *rows);
    double *t = malloc((size_t)reps * sizeof *t);
    bf_error err;
    double med;
    int i;
    if (rows == NULL || t == NULL) {
        die("out of memory", NULL);
    }
    for (i = 0; i < reps; i++) {
        double t0 = bf_bench_now();
        if (bf_study_run(spec, rows, &err) != BF_OK) {
            die("study", &err);
        }
        t[i] = bf_bench_now() - t0;
    }
    med = bf_bench_median(t, reps);
    last_min = t[0]; /* sorted by bf_bench_median() */
    free(rows);
    free(t);
    return med;
}

/* CPU time (user + system) of the last child timed by time_process. */
static double last_cpu;

/* Runs argv as a child process with its output discarded; returns the
 * wall time, or -1 when it did not exit with status 0. */
static double time_process(char *const *argv)
{
    double t0;
    int status = 0;
    pid_t pid;
    struct rusage ru;
    fflush(stdout); /* the child must not repeat buffered output */
    fflush(stderr);
    t0 = bf_bench_now();
    pid = fork();
    if (pid < 0) {
        return -1.0;
    }
    if (pid == 0) {
        if (freopen("/dev/null", "w", stdout) == NULL ||
            freopen("/dev/null", "w", stderr) == NULL) {
            _exit(127);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) ||
        WEXITSTATUS(status) != 0) {
        return -1.0;
    }
    /* the children's CPU so far, minus what earlier children used */
    getrusage(RUSAGE_CHILDREN, &ru);
    {
        static double before;
        double all = (double)ru.ru_utime.tv_sec +
                     1e-6 * (double)ru.ru_utime.tv_usec +
                     (double)ru.ru_stime.tv_sec +
                     1e-6 * (double)ru.ru_stime.tv_usec;
        last_cpu = all - before;
        before = all;
    }
    return bf_bench_now() - t0;
}

static double median_process(char *const *argv, int reps)
{
    double *t = malloc((size_t)reps * sizeof *t);
    double med;
    int i;
    if (t == NULL) {
        die("out of memory", NULL);
    }
    for (i = 0; i < reps; i++) {
        t[i] = time_process(argv);
        if (t[i] < 0.0) {
            free(t);
            return -1.0;
        }
    }
    med = bf_bench_median(t, reps);
    free(t);
    return med;
}

/* A writable copy of s for an argv (the benchmark never frees it). */
static char *arg(const char *s)
{
    size_t len = strlen(s) + 1;
    char *p = malloc(len);
    if (p == NULL) {
        die("out of memory", NULL);
    }
    memcpy(p, s, len);
    return p;
}

static void print_rate(const char *what, double evals, double seconds)
{
    printf("| %s | %.3g | %.1f |\n", what, evals / seconds,
           1e9 * seconds / evals);
}

/* ==== the machine ======================================================== */

typedef struct {
    int cores;
    double hz;
    double fma;  /* lanes per cycle */
    double add;
    double div;
    double sqrt;
    int avx512;
    int bits; /* vector width of the kernels' clone (0: baseline) */
} machine_t;

static void cpu_model(char *buf, size_t len)
{
    FILE *fp = fopen("/proc/cpuinfo", "r");
    char line[512];
    snprintf(buf, len, "unknown CPU");
    if (fp == NULL) {
        return;
    }
    while (fgets(line, sizeof line, fp) != NULL) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon != NULL) {
            snprintf(buf, len, "%s", colon + 2);
            buf[strcspn(buf, "\n")] = '\0';
            break;
        }
    }
    fclose(fp);
}

static machine_t machine(void)
{
    machine_t mc;
    char model[256];
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    memset(&mc, 0, sizeof mc);
    __builtin_cpu_init();
    mc.cores = cores > 0 ? (int)cores : 1;
    mc.avx512 = __builtin_cpu_supports("avx512f");
    mc.hz = bf_bench_clock_hz();
    cpu_model(model, sizeof model);
    printf("## Machine and build\n\n");
    printf("| item | value |\n|---|---|\n");
    printf("| CPU | %s, %d online cores |\n", model, mc.cores);
    printf("| clock (dependent integer adds) | %.2f GHz |\n", mc.hz * 1e-9);
    {
        FILE *fp = fopen("/proc/loadavg", "r");
        char load[128] = "?";
        const char *policy = getenv("OMP_WAIT_POLICY");
        if (fp != NULL) {
            if (fgets(load, sizeof load, fp) == NULL) {
                snprintf(load, sizeof load, "?");
            }
            load[strcspn(load, "\n")] = '\0';
            fclose(fp);
        }
        printf("| load average at start (other users of the machine) | %s "
               "|\n", load);
        printf("| OMP_WAIT_POLICY | %s |\n",
               policy != NULL ? policy : "(unset: libgomp spins, then "
                                         "sleeps)");
    }
    printf("| ISA of the kernels | %s |\n",
           mc.avx512 ? "x86-64-v4 (AVX-512)"
           : __builtin_cpu_supports("avx2") ? "x86-64-v3 (AVX2)"
                                            : "baseline x86-64");
    printf("| build | %s; C flags: %s |\n", BF_BUILD_TYPE, BF_C_FLAGS);
    printf("| kernels (src/fit/kernels.c) | -O3 -fno-math-errno, "
           "target_clones x86-64-v4 / x86-64-v3 / default |\n");
    mc.bits = mc.avx512 ? 512
              : (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
                  ? 256
                  : 0;
    if (mc.bits > 0) { /* the width the kernels' clone uses */
        mc.fma = bf_bench_lanes_per_second(BF_BENCH_FMA, mc.bits) / mc.hz;
        mc.add = bf_bench_lanes_per_second(BF_BENCH_ADD, mc.bits) / mc.hz;
        mc.div = bf_bench_lanes_per_second(BF_BENCH_DIV, mc.bits) / mc.hz;
        mc.sqrt = bf_bench_lanes_per_second(BF_BENCH_SQRT, mc.bits) / mc.hz;
        printf("| %d-bit FMA throughput | %.1f double lanes/cycle |\n",
               mc.bits, mc.fma);
        printf("| %d-bit add throughput | %.1f lanes/cycle |\n", mc.bits,
               mc.add);
        printf("| %d-bit division throughput | %.2f lanes/cycle |\n",
               mc.bits, mc.div);
        printf("| %d-bit square root throughput | %.2f lanes/cycle |\n",
               mc.bits, mc.sqrt);
    }
    printf("\n");
    return mc;
}

/* ==== model evaluations per second ======================================= */

static void defaults(const bf_model_type *type, double *param)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        param[j] = type->param[j].value;
    }
}

static void eval_rates(const inputs_t *in, int reps)
{
    double *out = malloc(in->n_sel * sizeof *out);
    double *t = malloc((size_t)reps * sizeof *t);
    size_t i;
    if (out == NULL || t == NULL) {
        die("out of memory", NULL);
    }
    printf("## Model evaluations per second (K = %zu configurations)\n\n",
           in->n_sel);
    printf("Plain: `bf_model_eval` at every point of the model's grid. "
           "Study path: `bf__grid_alloc` (vector kernels, normalised "
           "curves of the whole grid). One evaluation = one model value "
           "at one configuration.\n\n");
    printf("| model | path | evaluations/s | ns/evaluation |\n");
    printf("|---|---|---|---|\n");
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *type = bf_model_get(i);
        double param[BF_MAX_PARAMS];
        size_t points = 1;
        size_t g;
        int r;
        char label[64];
        defaults(type, param);
        if (type->p > 0 && type->param[0].fitted) {
            points = type->param[0].grid_n;
        }
        for (r = 0; r < reps; r++) {
            double t0 = bf_bench_now();
            size_t rounds = points == 1 ? 100 : 1;
            size_t q;
            for (q = 0; q < rounds; q++) {
                for (g = 0; g < points; g++) {
                    if (points > 1) {
                        param[0] = type->param[0].grid_lo +
                                   type->param[0].grid_step * (double)g;
                    }
                    if (bf_model_eval(type, param, in->n_sel, in->geom,
                                      out) != BF_OK) {
                        die(type->name, NULL);
                    }
                }
            }
            t[r] = (bf_bench_now() - t0) / (double)rounds;
        }
        snprintf(label, sizeof label, "%s | plain", type->name);
        print_rate(label, (double)(points * in->n_sel), bf_bench_median(t, reps));
        if (points > 1) {
            size_t grid_points = points;
            for (r = 0; r < reps; r++) {
                int st;
                double t0 = bf_bench_now();
                bf__grid *gr;
                defaults(type, param);
                gr = bf__grid_alloc(type, param, 0, in->n_sel, in->geom, &st);
                t[r] = bf_bench_now() - t0;
                if (gr == NULL) {
                    die(type->name, NULL);
                }
                /* the whole grid: every fitted parameter (WNO-R has two) */
                grid_points = bf__grid_points(gr);
                bf__grid_free(gr);
            }
            snprintf(label, sizeof label, "%s | study", type->name);
            print_rate(label, (double)(grid_points * in->n_sel),
                       bf_bench_median(t, reps));
        }
    }
    printf("\n");
    free(out);
    free(t);
}

/* ==== the floor ========================================================== */

/* Operations of the minimal algorithm per curve value (one model at one
 * grid value and one configuration), geometry-only terms taken once per
 * configuration, and per LSE term (one sample, grid value, configuration).
 * "fma" counts multiplies, fused multiply-adds and exp's polynomial (pipes
 * of the FMA units), "add" adds and max (the FP add pipes), "div"/"sqrt"
 * the divider. exp costs EXP_OPS fma-class operations: argument reduction
 * (3) and a degree-5 polynomial on a table-driven reduced range (5) -- the
 * cheapest accurate double exp; libmvec's uses more. */
#define EXP_OPS 8.0

typedef struct {
    double fma;
    double add;
    double div;
    double sqrt;
} ops_t;

/* G (P1): v = a * exp(b * (1/m^2)): mul, exp, mul; max; normalise: mul.
 * E (P2): d = fma(m^2, vz^2, vxy^2), v = a / (d * sqrt d): fma, mul, div,
 *         sqrt; max; normalise: mul.
 * LFTG (P7): v = exp(n_d * ln(cos ti cos ts)): mul, exp; max; normalise.
 * LSE term: one fma (sum of l.D; sum of l^2 and max come with the curve). */
static const ops_t OPS_G = {2.0 + EXP_OPS + 1.0, 1.0, 0.0, 0.0};
static const ops_t OPS_E = {3.0, 1.0, 1.0, 1.0};
static const ops_t OPS_LFTG = {1.0 + EXP_OPS + 1.0, 1.0, 0.0, 0.0};
static const ops_t OPS_LSE = {1.0, 0.0, 0.0, 0.0};

static void ops_add(ops_t *sum, const ops_t *per, double count)
{
    sum->fma += per->fma * count;
    sum->add += per->add * count;
    sum->div += per->div * count;
    sum->sqrt += per->sqrt * count;
}

/* Lower bound (seconds) of the paper protocol's fit compute on one core:
 * each unit must do its share; the units work in parallel, so the bound is
 * the slowest unit's time. ON (24 evaluations of 198 values) and the data
 * normalisation are below 1% of the work and left out. */
static double floor_seconds(const machine_t *mc, size_t k, size_t points,
                            size_t samples, ops_t *total)
{
    double values = (double)points * (double)k;
    double cyc[3];
    memset(total, 0, sizeof *total);
    ops_add(total, &OPS_G, 2.0 * values);    /* VH-G, FC-G */
    ops_add(total, &OPS_E, 2.0 * values);    /* VH-E, FC-E */
    ops_add(total, &OPS_LFTG, values);       /* LFTG */
    ops_add(total, &OPS_LSE, 5.0 * values * (double)samples);
    cyc[0] = total->fma / mc->fma;
    cyc[1] = total->add / mc->add;
    cyc[2] = (total->div / mc->div) + (total->sqrt / mc->sqrt);
    return fmax(cyc[0], fmax(cyc[1], cyc[2])) / mc->hz;
}

/* ==== bootstrap ========================================================== */

static unsigned long long xorshift(unsigned long long *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

/* BOOT_RESAMPLES case resamples of sample 1's configurations (drawn with
 * replacement), every paper model refitted on each: a grid per model and
 * resample (the curves' normalisation depends on the resample). Returns
 * the seconds taken. */
static double bootstrap(const inputs_t *in)
{
    size_t n = in->n_sel;
    bf_geom *g = malloc(n * sizeof *g);
    double *raw = malloc(n * sizeof *raw);
    double *d = malloc(n * sizeof *d);
    bf_fit_workspace *w = bf_fit_alloc(n);
    const double *v = bf_brdf_values(in->b, (size_t)bf_brdf_find(in->b, 1));
    unsigned long long seed = BOOT_SEED;
    double on_param[2];
    double t0;
    size_t r;
    size_t k;
    if (g == NULL || raw == NULL || d == NULL || w == NULL) {
        die("out of memory", NULL);
    }
    bf_sample_table_get(in->on, 1, 0, &on_param[0]);
    bf_sample_table_get(in->on, 1, 1, &on_param[1]);
    t0 = bf_bench_now();
    for (r = 0; r < BOOT_RESAMPLES; r++) {
        size_t m;
        for (k = 0; k < n; k++) {
            size_t j = (size_t)(xorshift(&seed) % n);
            g[k] = in->geom[j];
            raw[k] = v[in->sel[j]] * cos(g[k].theta_i); /* SPEC §2 */
        }
        if (bf_normalise(n, raw, d) != BF_OK) {
            continue;
        }
        for (m = 0; m < 6; m++) {
            const bf_model_type *type = in->paper[m];
            double param[BF_MAX_PARAMS];
            bf_fit_result res;
            bf__grid *gr;
            int st;
            defaults(type, param);
            if (type == bf_model_on) { /* evaluated, not fitted */
                bf_fit_grid(type, on_param, 0, n, g, d, w, &res);
                continue;
            }
            gr = bf__grid_alloc(type, param, 0, n, g, &st);
            if (gr == NULL || bf__grid_fit(gr, d, &res) != BF_OK) {
                die("bootstrap fit", NULL);
            }
            bf__grid_free(gr);
        }
    }
    t0 = bf_bench_now() - t0;
    free(g);
    free(raw);
    free(d);
    bf_fit_free(w);
    return t0;
}

/* ==== scaling ============================================================ */

/* The paper's five grid models with grids of grid_n points (copies of the
 * type objects; the kernels recognise them) plus ON. */
typedef struct {
    bf_model_type type[6];
    bf_param par[6][BF_MAX_PARAMS];
    const bf_model_type *list[6];
} resized_t;

static void resize(const inputs_t *in, size_t grid_n, resized_t *rz)
{
    size_t m;
    for (m = 0; m < 6; m++) {
        rz->type[m] = *in->paper[m];
        if (rz->type[m].p > 0 && rz->type[m].param[0].fitted) {
            memcpy(rz->par[m], rz->type[m].param,
                   rz->type[m].p * sizeof(bf_param));
            rz->par[m][0].grid_n = grid_n;
            rz->type[m].param = rz->par[m];
        }
        rz->list[m] = &rz->type[m];
    }
}

/* One scaling row: the size, its median time and the marginal time per
 * unit of size against the previous row (constant when time is linear:
 * t = fixed + size x marginal). */
static void scaling_row(const char *what, size_t size, double t,
                        size_t *prev_size, double *prev_t, const char *unit)
{
    printf("| %s | %zu | %.3f |", what, size, 1e3 * t);
    if (*prev_size > 0 && size > *prev_size) {
        printf(" %.2f us per %s |\n",
               1e6 * (t - *prev_t) / (double)(size - *prev_size), unit);
    } else {
        printf(" |\n");
    }
    *prev_size = size;
    *prev_t = t;
}

static void scaling(const inputs_t *in, const reps_t *reps)
{
    static const size_t n_samples[] = {6, 12, 24, 48, 96};
    static const size_t grids[] = {125, 250, 501, 1002, 2004};
    static const size_t ks[] = {50, 100, 150, 198};
    bf_target samples[96];
    size_t excl[BF_CURET_NCONF];
    bf_study_spec spec;
    size_t prev = 0;
    double prev_t = 0.0;
    size_t i;

    printf("## Scaling (paper protocol, fit compute, 1 thread)\n\n");
    printf("Each block changes one size of the protocol (24 samples x 6 "
           "models x 501 grid values x 198 configurations). Time is linear "
           "when the marginal time per unit (last column, from the row "
           "above) is constant: the curves are computed once per model "
           "(a fixed cost in the number of samples), the LSE once per "
           "sample. Samples beyond the paper's 24 repeat them.\n\n");
    printf("| size | value | median ms | marginal |\n|---|---|---|---|\n");
    for (i = 0; i < 96; i++) {
        samples[i] = in->paper_t[i % BF_STUDY_NSAMPLES];
    }
    for (i = 0; i < sizeof n_samples / sizeof *n_samples; i++) {
        spec_init(in, &spec);
        spec.targets = samples;
        spec.n_targets = n_samples[i];
        scaling_row("samples", n_samples[i], time_study(&spec, reps->scale),
                    &prev, &prev_t, "sample");
    }
    prev = 0;
    for (i = 0; i < sizeof grids / sizeof *grids; i++) {
        resized_t rz;
        resize(in, grids[i], &rz);
        spec_init(in, &spec);
        spec.models = rz.list;
        scaling_row("grid values", grids[i], time_study(&spec, reps->scale),
                    &prev, &prev_t, "grid value");
    }
    prev = 0;
    for (i = 0; i < sizeof ks / sizeof *ks; i++) {
        size_t k = ks[i] < in->n_sel ? ks[i] : in->n_sel;
        size_t j;
        spec_init(in, &spec);
        /* the first k used configurations: leave out the others */
        for (j = k; j < in->n_sel; j++) {
            excl[j - k] = in->sel[j] + 1;
        }
        spec.select.exclude = excl;
        spec.select.n_exclude = in->n_sel - k;
        scaling_row("configurations", k,
                    time_study(&spec, reps->scale), &prev, &prev_t,
                    "configuration");
    }
    printf("\n");
}

/* ==== numpy baseline ===================================================== */

/* Runs the numpy baseline once with reps inner repetitions and returns its
 * reported median compute time (seconds), or -1. */
static double numpy_compute(const char *script, const char *data,
                            const char *on, int reps)
{
    char cmd[8192];
    char line[256];
    double ms = -1.0;
    FILE *p;
    fflush(stdout);
    snprintf(cmd, sizeof cmd,
             "/usr/bin/python3 '%s' --data '%s' --on-params '%s' --reps %d "
             "2>/dev/null",
             script, data, on, reps);
    p = popen(cmd, "r");
    if (p == NULL) {
        return -1.0;
    }
    while (fgets(line, sizeof line, p) != NULL) {
        sscanf(line, "compute_ms_median %lf", &ms);
    }
    if (pclose(p) != 0) {
        return -1.0;
    }
    return ms < 0.0 ? -1.0 : 1e-3 * ms;
}

/* ==== the analysis beyond the paper (issue 11) =========================== */

/* The figures before the engine (same machine): rank with its 9
 * default models 196 s, without WNO-R 30 s (0.84x the numpy/scipy peer's
 * 24.7 s), compare --fit exact --bootstrap 1000 --models all 341 s for ONE
 * sample (so about 61 x 341 s = 5.8 h for all). */
#define NOW_RANK 196.0
#define NOW_RANK8 30.0
#define NOW_PEER_RATIO 0.84
#define NOW_BOOT_ALL (61.0 * 341.0)

static void analysis(const char *cli, const char *peer, const char *dir,
                     int reps)
{
    char tmpl[] = "/tmp/bench_analysis.XXXXXX";
    char peer_out[4096];
    double t_rank[16];
    double c_rank[16];
    double t_rank8[16];
    double c_rank8[16];
    double t_peer[16];
    double c_peer[16];
    double t_boot;
    double c_boot;
    double t_auto;
    double c_auto;
    int have_peer = peer != NULL && access("/usr/bin/python3", X_OK) == 0;
    int r;
    if (mkdtemp(tmpl) == NULL) {
        die("temporary folder", NULL);
    }
    snprintf(peer_out, sizeof peer_out, "%s/peer.csv", tmpl);
    for (r = 0; r < reps && r < 16; r++) { /* alternating runs */
        /* the F threshold's intervals, as before issue 18's default and
         * as the peer's (its profile intervals at chi2_1) */
        char *a9[] = {arg(cli), arg("rank"), arg("--data"), arg(dir),
                      arg("--neyman"), arg("off"), arg("--out"), tmpl,
                      arg("-q"), NULL};
        char *a8[] = {arg(cli), arg("rank"), arg("--data"), arg(dir),
                      arg("--models"),
                      arg("VH-G,VH-E,FC-G,FC-E,ON,LFTG,LAMBERT,WNO"),
                      arg("--neyman"), arg("off"), arg("--out"), tmpl,
                      arg("-q"), NULL};
        /* without --peer, no peer command line (arg(NULL) would crash) */
        char *ap[] = {arg("/usr/bin/python3"), arg(have_peer ? peer : ""),
                      arg("--data"), arg(dir), arg("--out"), peer_out, NULL};
        t_rank[r] = time_process(a9);
        c_rank[r] = last_cpu;
        t_rank8[r] = time_process(a8);
        c_rank8[r] = last_cpu;
        t_peer[r] = have_peer ? time_process(ap) : -1.0;
        c_peer[r] = last_cpu;
    }
    {
        /* rank's default: the Neyman construction where a second minimum
         * competes (issue 18; doc/methods.md §3) */
        char *aa[] = {arg(cli), arg("rank"), arg("--data"), arg(dir),
                      arg("--out"), tmpl, arg("-q"), NULL};
        t_auto = time_process(aa);
        c_auto = last_cpu;
    }
    {
        char *ab[] = {arg(cli), arg("compare"), arg("--data"), arg(dir),
                      arg("--fit"), arg("exact"), arg("--bootstrap"),
                      arg("1000"), arg("--samples"), arg("all"),
                      arg("--models"), arg("all"), arg("--out"), tmpl,
                      arg("-q"), NULL};
        t_boot = time_process(ab);
        c_boot = last_cpu;
    }
    printf("## The analysis beyond the paper (issue 11; whole processes, "
           "all cores, median of %d alternating runs)\n\n", r);
    printf("| run | wall | CPU | before (issue 11) | ratio |\n"
           "|---|---|---|---|---|\n");
    printf("| `brdffit rank` (61 samples, 9 default models), --neyman off "
           "| %.2f s | %.2f s | %.0f s | %.0fx faster |\n",
           bf_bench_median(t_rank, r), bf_bench_median(c_rank, r), NOW_RANK,
           NOW_RANK / bf_bench_median(t_rank, r));
    printf("| `brdffit rank` without WNO-R (8 models), --neyman off | "
           "%.2f s | %.2f s | %.0f s | %.0fx faster |\n",
           bf_bench_median(t_rank8, r), bf_bench_median(c_rank8, r), NOW_RANK8,
           NOW_RANK8 / bf_bench_median(t_rank8, r));
    if (have_peer && bf_bench_median(t_peer, r) > 0.0) {
        printf("| numpy/scipy peer (`rank_baseline.py`, the same 8 models) "
               "| %.2f s | %.2f s | | brdffit %.1fx faster (before: "
               "%.2fx) |\n",
               bf_bench_median(t_peer, r), bf_bench_median(c_peer, r),
               bf_bench_median(t_peer, r) / bf_bench_median(t_rank8, r), NOW_PEER_RATIO);
    }
    printf("| `brdffit rank` (9 models), its default --neyman auto (1 run) "
           "| %.1f s | %.1f s | | %.0fx the F threshold's CPU |\n",
           t_auto, c_auto, c_auto / bf_bench_median(c_rank, r));
    if (t_boot > 0.0) {
        printf("| `compare --fit exact --bootstrap 1000 --samples all "
               "--models all` (1 run) | %.1f s | %.1f s | about %.0f s | "
               "%.0fx faster |\n",
               t_boot, c_boot, NOW_BOOT_ALL, NOW_BOOT_ALL / t_boot);
    }
    printf("\n");
}

/* ==== main =============================================================== */

int main(int argc, char **argv)
{
    const char *dir = "../shared/data/curet";
    const char *refdir = NULL;
    const char *cli = NULL;
    const char *numpy = NULL;
    const char *peer = NULL;
    reps_t reps = {51, 21, 21, 3, 11, 5};
    char path[4096];
    char on_path[4096];
    char tmpl[] = "/tmp/bench_study.XXXXXX";
    inputs_t in;
    bf_error err;
    bf_study_spec spec;
    machine_t mc;
    double t_paper;
    double t_paper_min;
    double t_paper2;
    double t_proc = -1.0;
    double t_proc2 = -1.0;
    double np_compute = -1.0;
    double np_proc = -1.0;
    size_t i;
    int a;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--data") == 0 && a + 1 < argc) {
            dir = argv[++a];
        } else if (strcmp(argv[a], "--reference") == 0 && a + 1 < argc) {
            refdir = argv[++a];
        } else if (strcmp(argv[a], "--cli") == 0 && a + 1 < argc) {
            cli = argv[++a];
        } else if (strcmp(argv[a], "--numpy") == 0 && a + 1 < argc) {
            numpy = argv[++a];
        } else if (strcmp(argv[a], "--peer") == 0 && a + 1 < argc) {
            peer = argv[++a];
        } else if (strcmp(argv[a], "--quick") == 0) {
            reps = (reps_t){5, 3, 3, 1, 3, 1};
        } else {
            fprintf(stderr, "usage: bench_study [--data DIR] [--reference "
                            "DIR] [--cli PATH] [--numpy SCRIPT] [--peer "
                            "SCRIPT] [--quick]\n");
            return 2;
        }
    }

    /* inputs */
    memset(&in, 0, sizeof in);
    snprintf(path, sizeof path, "%s/table.txt", dir);
    if (bf_table_load(path, &in.t, &err) != BF_OK) {
        die("table", &err);
    }
    snprintf(path, sizeof path, "%s/abrdf.dat", dir);
    if (bf_brdf_load(path, bf_table_size(in.t), &in.b, &err) != BF_OK) {
        die("BRDF", &err);
    }
    if (refdir != NULL) {
        snprintf(on_path, sizeof on_path, "%s/oren_nayar_params.tsv", refdir);
    } else {
        snprintf(on_path, sizeof on_path,
                 "%s/../../reference/oren_nayar_params.tsv", dir);
    }
    if (bf_on_params_load(on_path, &in.on, &err) != BF_OK) {
        die("ON parameters", &err);
    }
    if (bf_curet_dataset(in.t, in.b, NULL, dir, "mean", &in.ds, &err) !=
        BF_OK) {
        die("dataset", &err);
    }
    for (i = 0; i < BF_STUDY_NSAMPLES; i++) {
        in.paper_t[i].material = (size_t)bf_dataset_find(in.ds,
                                                         bf_study_samples[i]);
        in.paper_t[i].channel = BF_CHANNEL_MEAN;
    }
    in.n_sel = bf_table_select(in.t, M_PI_2, in.sel); /* SPEC §1.4 */
    for (i = 0; i < in.n_sel; i++) {
        in.geom[i] = bf_table_geom(in.t, in.sel[i]);
    }
    in.paper[0] = bf_model_vh_g;
    in.paper[1] = bf_model_vh_e;
    in.paper[2] = bf_model_fc_g;
    in.paper[3] = bf_model_fc_e;
    in.paper[4] = bf_model_on;
    in.paper[5] = bf_model_lftg;

    printf("# brdffit %s speed benchmark\n\n", bf_version());
    printf("Every time is the median of repeated runs (fit compute: "
           "%d runs; processes: %d runs); the machine is shared, so the "
           "ratios, measured in this one run, are the robust figures.\n\n",
           reps.study, reps.process);
    mc = machine();
    eval_rates(&in, reps.eval);

    /* the paper protocol */
    spec_init(&in, &spec);
    t_paper = time_study(&spec, reps.study);
    t_paper_min = last_min;
    spec.n_threads = 2;
    t_paper2 = time_study(&spec, reps.study);
    if (cli != NULL && mkdtemp(tmpl) != NULL) {
        char *args[] = {arg(cli), arg("compare"), arg("--data"), arg(dir),
                        arg("--on-params"), on_path, arg("--out"), tmpl,
                        arg("-q"), NULL};
        char *args2[] = {arg(cli), arg("compare"), arg("--data"), arg(dir),
                         arg("--on-params"), on_path, arg("--out"), tmpl,
                         arg("-q"), arg("--threads"), arg("2"), NULL};
        t_proc = median_process(args, reps.process);
        t_proc2 = median_process(args2, reps.process);
    }
    if (numpy != NULL && access("/usr/bin/python3", X_OK) == 0) {
        char *args[] = {arg("/usr/bin/python3"), arg(numpy), arg("--data"),
                        arg(dir), arg("--on-params"), on_path, arg("--reps"),
                        arg("1"), NULL};
        np_compute = numpy_compute(numpy, dir, on_path, 11);
        if (np_compute > 0.0) {
            np_proc = median_process(args, reps.process > 5 ? 5 : 3);
        }
    }
    printf("## The paper protocol (24 samples x 6 models, 501 grid values, "
           "K = %zu; tables only)\n\n", in.n_sel);
    printf("| measurement | median | vs numpy |\n|---|---|---|\n");
    printf("| fit compute, 1 thread (`bf_study_run`) | %.3f ms | %s |\n",
           1e3 * t_paper, "");
    printf("| fit compute, 2 threads | %.3f ms (speed-up %.2f) | |\n",
           1e3 * t_paper2, t_paper / t_paper2);
    if (t_proc > 0.0) {
        printf("| whole process `brdffit compare -q` (1 thread) | %.2f ms | "
               "|\n", 1e3 * t_proc);
        printf("| whole process `brdffit compare -q --threads 2` | %.2f ms "
               "| |\n", 1e3 * t_proc2);
    }
    if (np_compute > 0.0) {
        printf("| numpy baseline, compute | %.2f ms | %.0fx slower than "
               "brdffit's fit compute |\n",
               1e3 * np_compute, np_compute / t_paper);
        if (np_proc > 0.0 && t_proc > 0.0) {
            printf("| numpy baseline, whole process | %.1f ms | %.0fx "
                   "slower than brdffit's process |\n",
                   1e3 * np_proc, np_proc / t_proc);
        }
    } else if (numpy != NULL) {
        printf("| numpy baseline | not run (no /usr/bin/python3 with numpy; "
               "Debian: python3-numpy) | |\n");
    }
    printf("\n");

    /* the floor */
    if (mc.bits > 0) {
        ops_t ops;
        double fl = floor_seconds(&mc, in.n_sel, 501, BF_STUDY_NSAMPLES,
                                  &ops);
        printf("## The floor (one core)\n\n");
        printf("Operations of the minimal algorithm for the paper protocol "
               "(see bench/RESULTS.md): %.3g FMA-pipe, %.3g add-pipe, "
               "%.3g divisions, %.3g square roots (double lanes).\n\n",
               ops.fma, ops.add, ops.div, ops.sqrt);
        printf("| FMA pipes | add pipes | divider | floor | measured "
               "(1 thread, median) | fastest run | median / floor | "
               "fastest / floor |\n");
        printf("|---|---|---|---|---|---|---|---|\n");
        printf("| %.3f ms | %.3f ms | %.3f ms | %.3f ms | %.3f ms | %.3f ms "
               "| %.2f | %.2f |\n\n",
               1e3 * ops.fma / mc.fma / mc.hz, 1e3 * ops.add / mc.add / mc.hz,
               1e3 * ((ops.div / mc.div) + (ops.sqrt / mc.sqrt)) / mc.hz,
               1e3 * fl, 1e3 * t_paper, 1e3 * t_paper_min, t_paper / fl,
               t_paper_min / fl);
    }

    /* all 61 samples x all models; bootstrap */
    {
        const bf_model_type *all[MAX_MODELS];
        bf_target samples[128];
        double t;
        double tb[8];
        size_t n_all = bf_model_count();
        int r;
        for (i = 0; i < n_all && i < MAX_MODELS; i++) {
            all[i] = bf_model_get(i);
        }
        for (i = 0; i < bf_dataset_count(in.ds) && i < 128; i++) {
            samples[i].material = i;
            samples[i].channel = BF_CHANNEL_MEAN;
            samples[i].joint = 0;
        }
        spec_init(&in, &spec);
        spec.models = all;
        spec.n_models = n_all;
        spec.targets = samples;
        spec.n_targets = i;
        t = time_study(&spec, reps.all);
        spec.n_threads = 2;
        printf("## Larger runs\n\n| run | median | 2 threads |\n|---|---|---|"
               "\n");
        printf("| all %zu samples x all %zu models (ON for the 24 with "
               "parameters) | %.3f ms | %.3f ms |\n",
               spec.n_targets, n_all, 1e3 * t,
               1e3 * time_study(&spec, reps.all));
        for (r = 0; r < reps.boot && r < 8; r++) {
            tb[r] = bootstrap(&in);
        }
        printf("| bootstrap: %d resamples of sample 1's configurations, the "
               "6 paper models refitted on each (grid per model and "
               "resample) | %.1f ms (%.1f us per resample) | |\n\n",
               BOOT_RESAMPLES, 1e3 * bf_bench_median(tb, r),
               1e6 * bf_bench_median(tb, r) / BOOT_RESAMPLES);
    }

    scaling(&in, &reps);
    if (cli != NULL) {
        analysis(cli, peer, dir, reps.process > 5 ? 3 : 1);
    }
    printf("Threads: the paper protocol's fit compute on 2 threads is "
           "%.2fx faster than on 1 (the machine has %d cores).\n",
           t_paper / t_paper2, mc.cores);

    bf_sample_table_free(in.on);
    bf_brdf_free(in.b);
    bf_table_free(in.t);
    return 0;
}
