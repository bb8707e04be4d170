/* oom_shim.c: an LD_PRELOAD allocator for tests/oom/test_oom.c that fails
 * one chosen allocation of a process and counts the rest.
 *
 * It replaces malloc, calloc, realloc, aligned_alloc, memalign,
 * posix_memalign, strdup and strndup (glibc's own strdup, getline, fopen
 * and the rest call the replaced malloc, so they count too) and forwards
 * to glibc's allocator (__libc_malloc and friends; free is glibc's). The
 * counting starts when main is entered (the start signal: __libc_start_main
 * is wrapped), so the dynamic loader's and the libraries' constructors'
 * allocations never count. Environment:
 *   BF_OOM_FAIL=N    the Nth allocation after the start (1-based) returns
 *                    NULL with errno ENOMEM; every other one succeeds
 *                    (0 or unset: none fails)
 *   BF_OOM_COUNT=F   at exit, the number of allocations counted is
 *                    written to file F
 *   BF_OOM_TRACE=1   the failed allocation's call stack goes to stderr
 *   BF_OOM_ONLY=A:B  only the allocations made by the program itself or
 *                    by a shared object whose path contains A or B count
 *                    (and may fail); libc's count for their caller. Set,
 *                    it leaves the report's plotting stack alone (PLplot,
 *                    its drivers, cairo, fontconfig ...); unset, every
 *                    allocation counts
 * A realloc to size 0 and a forked child's allocations count as any other
 * (the tests run with --threads 1, so nothing forks or races). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <link.h>
#include <errno.h>
#include <execinfo.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern void *__libc_malloc(size_t n);
extern void *__libc_calloc(size_t n, size_t size);
extern void *__libc_realloc(void *p, size_t n);
extern void *__libc_memalign(size_t align, size_t n);
void *memalign(size_t align, size_t n); /* glibc's malloc.h */
typedef int (*main_fn)(int, char **, char **);
int __libc_start_main(main_fn main, int argc, char **argv,
                      void (*init)(void), void (*fini)(void),
                      void (*rtld_fini)(void), void *stack_end);

static volatile int started;
static unsigned long counted;
static unsigned long fail_at;
static int trace;
static char only[512];
static __thread int inside; /* the shim's own calls (backtrace) */

/* Code ranges of the loaded objects seen so far: what their allocations
 * are (found with dl_iterate_phdr on the first address in each). */
enum { OTHER, SKIPPED, PASSING }; /* PASSING: libc, the shim */
typedef struct {
    uintptr_t lo, hi;
    int kind;
} range_t;
static range_t ranges[512];
static int n_ranges;

static int name_listed(const char *f)
{
    const char *p = only;
    while (*p != '\0') {
        const char *e = strchr(p, ':');
        size_t len = e != NULL ? (size_t)(e - p) : strlen(p);
        const char *c;
        for (c = f; *c != '\0'; c++) {
            if (len > 0 && strncmp(c, p, len) == 0) {
                return 1;
            }
        }
        p += len + (e != NULL);
    }
    return 0;
}

static int fails(const void *caller);

/* dl_iterate_phdr callback: records the segments of the object holding
 * the address *arg. */
static int add_object(struct dl_phdr_info *info, size_t size, void *arg)
{
    uintptr_t a = *(const uintptr_t *)arg;
    uintptr_t self = (uintptr_t)&fails;
    int holds = 0;
    int has_self = 0;
    int kind;
    int i;
    (void)size;
    for (i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        uintptr_t lo = info->dlpi_addr + ph->p_vaddr;
        if (ph->p_type == PT_LOAD && a >= lo && a < lo + ph->p_memsz) {
            holds = 1;
        }
        if (ph->p_type == PT_LOAD && self >= lo && self < lo + ph->p_memsz) {
            has_self = 1;
        }
    }
    if (!holds) {
        return 0;
    }
    kind = has_self || strstr(info->dlpi_name, "/libc.so") != NULL
               ? PASSING
               : info->dlpi_name[0] == '\0' || name_listed(info->dlpi_name)
                     ? OTHER
                     : SKIPPED;
    for (i = 0; i < info->dlpi_phnum && n_ranges < 512; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type == PT_LOAD) {
            ranges[n_ranges].lo = info->dlpi_addr + ph->p_vaddr;
            ranges[n_ranges].hi = ranges[n_ranges].lo + ph->p_memsz;
            ranges[n_ranges++].kind = kind;
        }
    }
    return 1;
}

static int kind_of(const void *addr)
{
    uintptr_t a = (uintptr_t)addr;
    int i;
    for (i = 0; i < n_ranges; i++) {
        if (a >= ranges[i].lo && a < ranges[i].hi) {
            return ranges[i].kind;
        }
    }
    return dl_iterate_phdr(add_object, &a) != 0 ? kind_of(addr) : OTHER;
}

/* 1 when the allocation comes from an object left alone: its caller, or
 * the first caller outside libc and the shim (strdup, fopen on behalf of
 * it), is neither the program nor an object named in only. */
static int skipped(const void *caller)
{
    void *frames[16];
    int n;
    int i;
    int kind;
    if (only[0] == '\0') {
        return 0;
    }
    kind = kind_of(caller);
    if (kind != PASSING) {
        return kind == SKIPPED;
    }
    inside = 1;
    n = backtrace(frames, 16);
    inside = 0;
    for (i = 1; i < n; i++) {
        kind = kind_of(frames[i]);
        if (kind != PASSING) {
            return kind == SKIPPED;
        }
    }
    return 0;
}

/* 1 when this allocation is the one to fail (counted after the start). */
static int fails(const void *caller)
{
    unsigned long k;
    if (!started || inside || skipped(caller)) {
        return 0;
    }
    k = __atomic_add_fetch(&counted, 1, __ATOMIC_RELAXED);
    if (k != fail_at) {
        return 0;
    }
    if (trace) {
        void *frames[32];
        int n = backtrace(frames, 32);
        static const char head[] = "oom_shim: failing this allocation:\n";
        (void)!write(2, head, sizeof head - 1);
        backtrace_symbols_fd(frames, n, 2);
    }
    errno = ENOMEM;
    return 1;
}

void *malloc(size_t n)
{
    return fails(__builtin_return_address(0)) ? NULL : __libc_malloc(n);
}

void *calloc(size_t n, size_t size)
{
    return fails(__builtin_return_address(0)) ? NULL : __libc_calloc(n, size);
}

void *realloc(void *p, size_t n)
{
    return fails(__builtin_return_address(0)) ? NULL : __libc_realloc(p, n);
}

void *memalign(size_t align, size_t n)
{
    return fails(__builtin_return_address(0)) ? NULL : __libc_memalign(align, n);
}

void *aligned_alloc(size_t align, size_t n)
{
    return fails(__builtin_return_address(0)) ? NULL : __libc_memalign(align, n);
}

int posix_memalign(void **out, size_t align, size_t n)
{
    void *p;
    if (align < sizeof(void *) || (align & (align - 1)) != 0) {
        return EINVAL;
    }
    if (fails(__builtin_return_address(0))) {
        return ENOMEM;
    }
    p = __libc_memalign(align, n);
    if (p == NULL) {
        return ENOMEM;
    }
    *out = p;
    return 0;
}

char *strndup(const char *s, size_t n)
{
    size_t len = strnlen(s, n);
    char *d = malloc(len + 1);
    if (d != NULL) {
        memcpy(d, s, len);
        d[len] = '\0';
    }
    return d;
}

char *strdup(const char *s)
{
    return strndup(s, strlen(s));
}

static void write_count(void)
{
    const char *path = getenv("BF_OOM_COUNT");
    char buf[32];
    int fd;
    int len;
    if (path == NULL || path[0] == '\0') {
        return;
    }
    started = 0; /* what follows is the shim's own */
    fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) {
        return;
    }
    len = snprintf(buf, sizeof buf, "%lu\n", counted);
    (void)!write(fd, buf, (size_t)len);
    close(fd);
}

static main_fn real_main;

static int counting_main(int argc, char **argv, char **envp)
{
    const char *f = getenv("BF_OOM_FAIL");
    const char *t = getenv("BF_OOM_TRACE");
    const char *sk = getenv("BF_OOM_ONLY");
    fail_at = f != NULL ? strtoul(f, NULL, 10) : 0;
    trace = t != NULL && t[0] == '1';
    if (sk != NULL) {
        snprintf(only, sizeof only, "%s", sk);
    }
    if (trace || only[0] != '\0') { /* backtrace loads libgcc_s once */
        void *frame[1];
        backtrace(frame, 1);
    }
    atexit(write_count);
    started = 1;
    return real_main(argc, argv, envp);
}

typedef int (*start_fn)(main_fn, int, char **, void (*)(void),
                        void (*)(void), void (*)(void), void *);

int __libc_start_main(main_fn main, int argc, char **argv,
                      void (*init)(void), void (*fini)(void),
                      void (*rtld_fini)(void), void *stack_end)
{
    start_fn real = (start_fn)(uintptr_t)dlsym(RTLD_NEXT,
                                                "__libc_start_main");
    real_main = main;
    return real(counting_main, argc, argv, init, fini, rtld_fini, stack_end);
}
