/* test_oom.c: out of memory, always a message (issue 19 item 5). Each
 * command runs once to count its allocations (tests/oom/oom_shim.c,
 * preloaded), then once per allocation with that one failing. Every run
 * must exit (no signal), either as the full run does (same exit status,
 * standard output and files: the failure was absorbed) or with the
 * library's status for it (70) and a message naming the problem on
 * stderr; and the output folder may hold only whole files of the full
 * run (no partial or temporary file). OpenMP's runtime (libgomp) ends the
 * process with its own message and status 1 when its allocations fail:
 * accepted. Plain build only (CMakeLists.txt): the shim replaces malloc,
 * as ASan and valgrind do. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli_run.h"
#include "support.h"

#define WORKERS 2
#define MAX_FILES 64
#define MAX_ARGS 48

typedef struct {
    char name[512];
    char *bytes;
    size_t len;
} file_t;

/* What a run left: status, output streams and files. */
typedef struct {
    int status;
    char *out;
    char *err;
    file_t files[MAX_FILES];
    size_t n_files;
    int bad_name; /* a file beyond MAX_FILES or unreadable */
} result_t;

typedef struct {
    pid_t pid;
    unsigned long n;
    char dir[256];
} worker_t;

static char *read_file(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    char *buf;
    long size;
    cr_assert_not_null(fp, "cannot read %s", path);
    fseek(fp, 0, SEEK_END);
    size = ftell(fp);
    rewind(fp);
    buf = malloc((size_t)size + 1);
    cr_assert_not_null(buf);
    cr_assert_eq(fread(buf, 1, (size_t)size, fp), (size_t)size);
    buf[size] = '\0';
    fclose(fp);
    if (len != NULL) {
        *len = (size_t)size;
    }
    return buf;
}

/* Reads every file under dir/sub (one level of folders) into r. */
static void read_tree(const char *dir, const char *sub, result_t *r)
{
    char path[1024];
    DIR *d;
    struct dirent *e;
    snprintf(path, sizeof path, "%s/%s", dir, sub);
    d = opendir(path);
    if (d == NULL) {
        return;
    }
    while ((e = readdir(d)) != NULL) {
        char rel[512];
        char full[1536];
        struct stat sb;
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        snprintf(rel, sizeof rel, "%s%s%s", sub, sub[0] ? "/" : "",
                 e->d_name);
        snprintf(full, sizeof full, "%s/%s", dir, rel);
        cr_assert_eq(stat(full, &sb), 0);
        if (S_ISDIR(sb.st_mode)) {
            read_tree(dir, rel, r);
            rmdir(full);
            continue;
        }
        if (r->n_files == MAX_FILES) {
            r->bad_name = 1;
        } else {
            file_t *f = &r->files[r->n_files++];
            snprintf(f->name, sizeof f->name, "%s", rel);
            f->bytes = read_file(full, &f->len);
        }
        unlink(full);
    }
    closedir(d);
}

static void result_free(result_t *r)
{
    size_t i;
    free(r->out);
    free(r->err);
    for (i = 0; i < r->n_files; i++) {
        free(r->files[i].bytes);
    }
    memset(r, 0, sizeof *r);
}

/* Starts the CLI in folder dir with args (and --out out) and the shim's
 * settings; standard output and error go to dir/stdout, dir/stderr. */
static pid_t start(const char *const *args, const char *dir, unsigned long n,
                   const char *only)
{
    pid_t pid;
    fflush(NULL);
    pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        const char *argv[MAX_ARGS + 4];
        char num[32];
        size_t k = 0;
        int fd;
        argv[k++] = BF_CLI_PATH;
        while (args[k - 1] != NULL && k < MAX_ARGS) {
            argv[k] = args[k - 1];
            k++;
        }
        argv[k++] = "--out"; /* the same name in every folder */
        argv[k++] = "out";
        argv[k] = NULL;
        snprintf(num, sizeof num, "%lu", n);
        setenv("LD_PRELOAD", BF_OOM_SHIM, 1);
        setenv("BF_OOM_FAIL", num, 1);
        if (only != NULL) {
            setenv("BF_OOM_ONLY", only, 1);
        }
        if (n == 0) {
            setenv("BF_OOM_COUNT", "count", 1);
        }
        if (chdir(dir) != 0) {
            _exit(127);
        }
        fd = open("/dev/null", O_RDONLY);
        dup2(fd, 0);
        fd = open("stdout", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 1);
        fd = open("stderr", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 2);
        execv(BF_CLI_PATH, (char *const *)(void *)argv);
        _exit(127);
    }
    return pid;
}

/* Collects the run that ended with status into r (and empties dir). */
static void collect(const char *dir, int status, result_t *r)
{
    char path[512];
    memset(r, 0, sizeof *r);
    r->status = status;
    snprintf(path, sizeof path, "%s/stdout", dir);
    r->out = read_file(path, NULL);
    unlink(path);
    snprintf(path, sizeof path, "%s/stderr", dir);
    r->err = read_file(path, NULL);
    unlink(path);
    snprintf(path, sizeof path, "%s/out", dir);
    read_tree(path, "", r);
    rmdir(path);
}

static const file_t *find(const result_t *r, const char *name)
{
    size_t i;
    for (i = 0; i < r->n_files; i++) {
        if (strcmp(r->files[i].name, name) == 0) {
            return &r->files[i];
        }
    }
    return NULL;
}

/* The verdict on run r (allocation n failed) against the full run ref:
 * NULL when right, else what is wrong (static). */
static const char *judge(const result_t *r, const result_t *ref)
{
    static char why[1024];
    size_t i;
    int absorbed;
    if (!WIFEXITED(r->status)) {
        snprintf(why, sizeof why, "killed by signal %d",
                 WIFSIGNALED(r->status) ? WTERMSIG(r->status) : 0);
        return why;
    }
    if (strstr(r->err, "Sanitizer") != NULL ||
        strstr(r->err, "runtime error") != NULL) {
        return "a sanitizer report";
    }
    if (r->bad_name) {
        return "too many output files";
    }
    for (i = 0; i < r->n_files; i++) {
        const file_t *f = find(ref, r->files[i].name);
        if (f == NULL) {
            snprintf(why, sizeof why, "left %s, which the full run does not "
                     "write", r->files[i].name);
            return why;
        }
        if (f->len != r->files[i].len ||
            memcmp(f->bytes, r->files[i].bytes, f->len) != 0) {
            snprintf(why, sizeof why, "left a partial or different %s",
                     f->name);
            return why;
        }
    }
    absorbed = WEXITSTATUS(r->status) == WEXITSTATUS(ref->status);
    if (absorbed) {
        if (strcmp(r->out, ref->out) != 0) {
            return "exit status of the full run but another standard output";
        }
        if (r->n_files != ref->n_files) {
            return "exit status of the full run but files missing";
        }
        return NULL;
    }
    if (WEXITSTATUS(r->status) == 1 &&
        strstr(r->err, "libgomp: Out of memory") != NULL) {
        return NULL; /* OpenMP's runtime: its message, its exit */
    }
    if (WEXITSTATUS(r->status) != 70) {
        snprintf(why, sizeof why, "exit status %d, not 70",
                 WEXITSTATUS(r->status));
        return why;
    }
    if (strstr(r->err, "out of memory") == NULL &&
        strstr(r->err, "Cannot allocate memory") == NULL) {
        return "no message naming the lack of memory on stderr";
    }
    return NULL;
}

/* Runs the CLI with args, counting its allocations, then once with each
 * allocation failing in turn; every run must pass judge. */
static void sweep(const char *const *args, const char *only)
{
    char dirs[WORKERS][256];
    char count_path[512];
    worker_t w[WORKERS];
    result_t ref;
    unsigned long total;
    unsigned long next = 1;
    unsigned long bad = 0;
    int status;
    int busy = 0;
    int k;
    char *count;
    struct timespec t0, t1;

    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (k = 0; k < WORKERS; k++) {
        snprintf(dirs[k], sizeof dirs[k], "%s", bf_test_tmpdir());
    }
    cr_assert_eq(waitpid(start(args, dirs[0], 0, only), &status, 0) > 0, 1);
    collect(dirs[0], status, &ref);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "the full run failed (status %d):\n%s", status, ref.err);
    snprintf(count_path, sizeof count_path, "%s/count", dirs[0]);
    count = read_file(count_path, NULL);
    total = strtoul(count, NULL, 10);
    free(count);
    unlink(count_path);
    cr_assert_gt(total, 10, "the shim counted %lu allocations", total);

    for (k = 0; k < WORKERS; k++) {
        w[k].pid = 0;
        snprintf(w[k].dir, sizeof w[k].dir, "%s", dirs[k]);
    }
    while (next <= total || busy > 0) {
        for (k = 0; k < WORKERS && next <= total; k++) {
            if (w[k].pid == 0) {
                w[k].n = next++;
                w[k].pid = start(args, w[k].dir, w[k].n, only);
                busy++;
            }
        }
        {
            pid_t pid = wait(&status);
            result_t r;
            const char *why;
            cr_assert_gt(pid, 0);
            for (k = 0; k < WORKERS && w[k].pid != pid; k++) {
            }
            cr_assert_lt(k, WORKERS);
            w[k].pid = 0;
            busy--;
            collect(w[k].dir, status, &r);
            why = judge(&r, &ref);
            if (why != NULL && bad++ < 10) {
                cr_expect_fail("allocation %lu of %lu failing: %s; stderr:\n%s",
                               w[k].n, total, why, r.err);
            }
            result_free(&r);
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    cr_log_info("%lu allocations failed in turn, %lu wrong, %.1f s", total,
                bad, (double)(t1.tv_sec - t0.tv_sec) +
                         1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    cr_expect_eq(bad, 0, "%lu of %lu runs went wrong", bad, total);
    result_free(&ref);
    for (k = 0; k < WORKERS; k++) {
        rmdir(dirs[k]);
    }
}

Test(oom, compare)
{
    const char *args[] = {"compare", "--data", bf_test_curet_path(""),
                          "--samples", "4", "--models", "VH-G",
                          "--threads", "1", NULL};
    sweep(args, NULL);
}

Test(oom, compare_exact_stats)
{
    const char *args[] = {"compare", "--data", bf_test_curet_path(""),
                          "--samples", "4", "--models", "LFTG", "--fit",
                          "exact", "--stats", "--threads", "1", NULL};
    sweep(args, NULL);
}

Test(oom, cornell_file)
{
    const char *args[] = {"compare", "--input",
                          bf_test_cornell_path("acryl_blue.brdf"),
                          "--models", "LFTG", "--threads", "1", NULL};
    sweep(args, NULL);
}
