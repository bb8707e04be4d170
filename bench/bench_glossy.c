/* bench_glossy.c: issue 17 item 11 -- the ten specular models (SPEC §9.3)
 * as LAMBERT+X (AS alone) on the five Cornell paints under --fit exact
 * --objective ngan, the whole `brdffit compare` (fits, profile intervals,
 * cross-validation) and the fits alone (--folds 0 --intervals none), CPU
 * and wall seconds, measured in one run beside the scipy peer
 * (../shared/peers/glossy_peer.py, 24-start least_squares of LAMBERT+GGX,
 * +BECKMANN, +WARD, +WARD-DUER) on the same files, and per file the
 * peer's CPU over brdffit's fits of the same models (issue 17: >= 10x).
 *
 *   bench_glossy [--cli BRDFFIT] [--data DIR] [--peer SCRIPT]
 *                [--python PY] [--threads N]
 *
 * Every run is a child process: wall from CLOCK_MONOTONIC, CPU (user +
 * system) from wait4's rusage. The peer runs only when PY exists and
 * imports scipy. Prints markdown tables (bench/RESULTS.md). */
#define _DEFAULT_SOURCE
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "timing.h"

#define MAX_FILES 16
#define MAX_ARGS 64

static const char *const TEN =
    "LAMBERT+GGX,LAMBERT+BECKMANN,LAMBERT+CT,LAMBERT+BLINN-PHONG,"
    "LAMBERT+WARD,LAMBERT+WARD-DUER,LAMBERT+WARD-GMD,AS,"
    "LAMBERT+LAFORTUNE,LAMBERT+ABC";
/* the peer's models, LAMBERT and its four composites */
static const char *const PEER_MODELS =
    "LAMBERT,LAMBERT+GGX,LAMBERT+BECKMANN,LAMBERT+WARD,LAMBERT+WARD-DUER";

/* A command line: its words copied into buf (execv's argv). */
typedef struct {
    char buf[8192];
    size_t used;
    char *argv[MAX_ARGS];
    size_t n;
} args_t;

static void arg(args_t *c, const char *w)
{
    size_t len = strlen(w) + 1;
    if (c->n + 1 < MAX_ARGS && c->used + len <= sizeof c->buf) {
        memcpy(c->buf + c->used, w, len);
        c->argv[c->n++] = c->buf + c->used;
        c->used += len;
    }
    c->argv[c->n] = NULL;
}

typedef struct {
    double cpu; /* user + system seconds */
    double wall;
    int ok;
} run_t;

/* Runs c (its output to /dev/null) and measures it. */
static run_t run(const args_t *c)
{
    run_t r = {0.0, 0.0, 0};
    struct rusage ru;
    int status = 0;
    double t0 = bf_bench_now();
    pid_t pid;
    fflush(stdout);
    pid = fork();
    if (pid < 0) {
        return r;
    }
    if (pid == 0) {
        if (freopen("/dev/null", "w", stdout) == NULL) {
            _exit(127);
        }
        if (freopen("/dev/null", "w", stderr) == NULL) {
            _exit(127);
        }
        execv(c->argv[0], c->argv);
        _exit(127);
    }
    if (wait4(pid, &status, 0, &ru) != pid) {
        return r;
    }
    r.wall = bf_bench_now() - t0;
    r.cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
            (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    return r;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The .brdf files of dir, sorted, into files (n of them). */
static size_t brdf_files(const char *dir, char **files)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    size_t n = 0;
    if (d == NULL) {
        return 0;
    }
    while ((e = readdir(d)) != NULL && n < MAX_FILES) {
        size_t len = strlen(e->d_name);
        if (len > 5 && strcmp(e->d_name + len - 5, ".brdf") == 0) {
            size_t sz = strlen(dir) + len + 2;
            files[n] = malloc(sz);
            if (files[n] == NULL) {
                break;
            }
            snprintf(files[n++], sz, "%s/%s", dir, e->d_name);
        }
    }
    closedir(d);
    qsort(files, n, sizeof *files, by_name);
    return n;
}

/* `brdffit compare --models MODELS --fit exact --objective ngan` on the
 * files, with folds and threads, without intervals when bare (--intervals
 * none: the fits alone, what the peer computes), its output in out. */
static run_t compare_as(const char *cli, const char *models, char **files,
                        size_t n, const char *folds, const char *threads,
                        int bare, const char *out)
{
    args_t c;
    size_t i;
    c.used = 0;
    c.n = 0;
    arg(&c, cli);
    arg(&c, "compare");
    arg(&c, "--models");
    arg(&c, models);
    arg(&c, "--fit");
    arg(&c, "exact");
    arg(&c, "--objective");
    arg(&c, "ngan");
    arg(&c, "--threads");
    arg(&c, threads);
    if (folds != NULL) {
        arg(&c, "--folds");
        arg(&c, folds);
    }
    if (bare) {
        arg(&c, "--intervals");
        arg(&c, "none");
    }
    arg(&c, "--quiet");
    arg(&c, "--out");
    arg(&c, out);
    for (i = 0; i < n; i++) {
        arg(&c, files[i]);
    }
    return run(&c);
}

static run_t compare(const char *cli, const char *models, char **files,
                     size_t n, const char *folds, const char *threads,
                     const char *out)
{
    return compare_as(cli, models, files, n, folds, threads, 0, out);
}

/* Runs `py a1 a2`. */
static run_t python(const char *py, const char *a1, const char *a2)
{
    args_t c;
    c.used = 0;
    c.n = 0;
    arg(&c, py);
    arg(&c, a1);
    arg(&c, a2);
    return run(&c);
}

int main(int argc, char **argv)
{
    const char *cli = "build/brdffit";
    const char *data = "../shared/data/cornell-pbrt-v2";
    const char *peer = "../shared/peers/glossy_peer.py";
    const char *py = "/usr/bin/python3";
    const char *threads = "2";
    char out[] = "/tmp/bench_glossy.XXXXXX";
    char *files[MAX_FILES];
    char rm[256];
    size_t n;
    size_t i;
    run_t whole;
    run_t nocv;
    run_t ours;
    run_t bare;
    run_t ours_bare;
    double peer_cpu = 0.0;
    double peer_wall = 0.0;
    int peer_ok;
    int a;
    for (a = 1; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], "--cli") == 0) {
            cli = argv[a + 1];
        } else if (strcmp(argv[a], "--data") == 0) {
            data = argv[a + 1];
        } else if (strcmp(argv[a], "--peer") == 0) {
            peer = argv[a + 1];
        } else if (strcmp(argv[a], "--python") == 0) {
            py = argv[a + 1];
        } else if (strcmp(argv[a], "--threads") == 0) {
            threads = argv[a + 1];
        } else {
            break;
        }
    }
    if (a != argc) {
        fprintf(stderr, "usage: bench_glossy [--cli BRDFFIT] [--data DIR] "
                        "[--peer SCRIPT] [--python PY] [--threads N]\n");
        return 2;
    }
    n = brdf_files(data, files);
    if (n == 0 || mkdtemp(out) == NULL) {
        fprintf(stderr, "bench_glossy: no .brdf file in %s\n", data);
        return 1;
    }
    whole = compare(cli, TEN, files, n, NULL, threads, out);
    nocv = compare(cli, TEN, files, n, "0", threads, out);
    ours = compare(cli, PEER_MODELS, files, n, "0", threads, out);
    bare = compare_as(cli, TEN, files, n, "0", threads, 1, out);
    ours_bare = compare_as(cli, PEER_MODELS, files, n, "0", threads, 1, out);
    if (!whole.ok || !nocv.ok || !ours.ok || !bare.ok || !ours_bare.ok) {
        fprintf(stderr, "bench_glossy: %s compare failed\n", cli);
        return 1;
    }
    printf("## Issue 17 item 11: ten specular models x %zu Cornell files "
           "(--fit exact --objective ngan, --threads %s)\n\n",
           n, threads);
    printf("| run | CPU s | wall s |\n|---|---:|---:|\n");
    printf("| ten models, whole compare (10 folds) | %.2f | %.2f |\n",
           whole.cpu, whole.wall);
    printf("| ten models, --folds 0 (fits + intervals) | %.2f | %.2f |\n",
           nocv.cpu, nocv.wall);
    printf("| the peer's five models, --folds 0 | %.2f | %.2f |\n",
           ours.cpu, ours.wall);
    printf("| ten models, --folds 0 --intervals none (the fits) | %.2f | "
           "%.2f |\n", bare.cpu, bare.wall);
    printf("| the peer's five models, --folds 0 --intervals none | %.2f | "
           "%.2f |\n\n", ours_bare.cpu, ours_bare.wall);
    peer_ok = access(py, X_OK) == 0 &&
              python(py, "-c", "import scipy.optimize").ok;
    if (peer_ok) {
        printf("Per file, the peer's five models, one thread (brdffit: "
               "--folds 0 --intervals none, the fits the peer computes):"
               "\n\n| file | peer CPU s | brdffit CPU s | peer / brdffit "
               "|\n|---|---:|---:|---:|\n");
    }
    for (i = 0; peer_ok && i < n; i++) {
        run_t p = python(py, peer, files[i]);
        run_t b = compare_as(cli, PEER_MODELS, &files[i], 1, "0", "1", 1,
                             out);
        const char *base = strrchr(files[i], '/');
        peer_ok = p.ok && b.ok;
        peer_cpu += p.cpu;
        peer_wall += p.wall;
        printf("| %s | %.2f | %.2f | %.1fx |\n",
               base != NULL ? base + 1 : files[i], p.cpu, b.cpu,
               p.cpu / b.cpu);
    }
    if (peer_ok) {
        printf("\n");
        printf("The peer (%s, its five models on every file, one process "
               "per file): %.2f s CPU, %.2f s wall; its CPU over "
               "brdffit's on the same five models: %.1fx (with the "
               "intervals brdffit computes and the peer does not), "
               "%.1fx over its fits alone (--intervals none).\n",
               peer, peer_cpu, peer_wall, peer_cpu / ours.cpu,
               peer_cpu / ours_bare.cpu);
    } else {
        printf("The peer was not run (%s without scipy, or it failed).\n",
               py);
    }
    snprintf(rm, sizeof rm, "rm -rf '%s'", out);
    if (system(rm) != 0) {
        fprintf(stderr, "bench_glossy: could not remove %s\n", out);
    }
    for (i = 0; i < n; i++) {
        free(files[i]);
    }
    return 0;
}
