/* machine.c: measures what one core of this machine can do -- its clock and
 * the throughput of fused multiply-adds, adds, divisions and square roots
 * on 512-bit (AVX-512) or 256-bit (AVX2) vectors, the widths the kernels'
 * clones use -- for the floor of bench_study (the lower bound of the paper
 * protocol's time). Compiled with -mavx512f -mfma (bench/CMakeLists.txt);
 * bench_study calls the 512-bit loops only when the CPU has AVX-512, the
 * 256-bit ones (target attribute avx2,fma) only when it has AVX2.
 *
 * Each loop keeps enough independent chains in flight to hide latency, so
 * its time is set by throughput. Results are per cycle, from the clock
 * measured by a chain of dependent integer adds (one cycle each on every
 * x86-64 core).
 */
#include <immintrin.h>
#include <time.h>

#include "machine.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (1e-9 * (double)ts.tv_nsec);
}

/* Short runs, best of many: on a shared machine a run that was not
 * interrupted shows the core's own speed. */
#define TRIES 40

/* Cycles per second: 8 dependent register adds per iteration, 1 cycle
 * each (about 3 ms per try). */
double bf_bench_clock_hz(void)
{
    double best = 0.0;
    int rep;
    for (rep = 0; rep < TRIES; rep++) {
        long n = 1000000;
        long x = 0;
        double t0 = now();
        double hz;
        __asm__ volatile("1:\n\t"
                         "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\t"
                         "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\t"
                         "add $1, %0\n\tadd $1, %0\n\t"
                         "sub $1, %1\n\tjnz 1b"
                         : "+r"(x), "+r"(n));
        hz = 8.0 * 1000000.0 / (now() - t0);
        if (hz > best) {
            best = hz;
        }
    }
    return best;
}

#define CHAINS 12

/* Runs OP on CHAINS independent zmm registers reps times and returns double
 * lanes per second; the sum of the registers is stored so that the work
 * stays alive. */
#define THROUGHPUT_LOOP(name, OP)                                          \
    static double name(long reps)                                          \
    {                                                                      \
        __m512d a[CHAINS];                                                 \
        const __m512d m = _mm512_set1_pd(0.999999999);                     \
        const __m512d c = _mm512_set1_pd(1e-9);                            \
        const __m512d two = _mm512_set1_pd(2.0);                           \
        double sink[8];                                                    \
        double t0;                                                         \
        double dt;                                                         \
        long r;                                                            \
        int i;                                                             \
        for (i = 0; i < CHAINS; i++) {                                     \
            a[i] = _mm512_set1_pd(1.0 + (0.01 * i));                       \
        }                                                                  \
        t0 = now();                                                        \
        for (r = 0; r < reps; r++) {                                       \
            for (i = 0; i < CHAINS; i++) {                                 \
                a[i] = OP;                                                 \
            }                                                              \
        }                                                                  \
        dt = now() - t0;                                                   \
        for (i = 1; i < CHAINS; i++) {                                     \
            a[0] = _mm512_add_pd(a[0], a[i]);                              \
        }                                                                  \
        _mm512_storeu_pd(sink, a[0]);                                      \
        bf_bench_sink += sink[0];                                          \
        (void)m;                                                           \
        (void)c;                                                           \
        (void)two;                                                         \
        return 8.0 * CHAINS * (double)reps / dt;                           \
    }

/* The same on 256-bit registers (AVX2 + FMA), 4 lanes each. */
#define THROUGHPUT_LOOP256(name, OP)                                       \
    __attribute__((target("avx2,fma"))) static double name(long reps)     \
    {                                                                      \
        __m256d a[CHAINS];                                                 \
        const __m256d m = _mm256_set1_pd(0.999999999);                     \
        const __m256d c = _mm256_set1_pd(1e-9);                            \
        const __m256d two = _mm256_set1_pd(2.0);                           \
        double sink[4];                                                    \
        double t0;                                                         \
        double dt;                                                         \
        long r;                                                            \
        int i;                                                             \
        for (i = 0; i < CHAINS; i++) {                                     \
            a[i] = _mm256_set1_pd(1.0 + (0.01 * i));                       \
        }                                                                  \
        t0 = now();                                                        \
        for (r = 0; r < reps; r++) {                                       \
            for (i = 0; i < CHAINS; i++) {                                 \
                a[i] = OP;                                                 \
            }                                                              \
        }                                                                  \
        dt = now() - t0;                                                   \
        for (i = 1; i < CHAINS; i++) {                                     \
            a[0] = _mm256_add_pd(a[0], a[i]);                              \
        }                                                                  \
        _mm256_storeu_pd(sink, a[0]);                                      \
        bf_bench_sink += sink[0];                                          \
        (void)m;                                                           \
        (void)c;                                                           \
        (void)two;                                                         \
        return 4.0 * CHAINS * (double)reps / dt;                           \
    }

/* Where the loops store their result (never read). */
static volatile double bf_bench_sink;

THROUGHPUT_LOOP(run_fma, _mm512_fmadd_pd(a[i], m, c))
THROUGHPUT_LOOP(run_add, _mm512_add_pd(a[i], c))
THROUGHPUT_LOOP(run_div, _mm512_div_pd(two, a[i])) /* a, 2/a, a, ... */
THROUGHPUT_LOOP(run_sqrt, _mm512_sqrt_pd(a[i]))    /* tends to 1 */
THROUGHPUT_LOOP256(run_fma256, _mm256_fmadd_pd(a[i], m, c))
THROUGHPUT_LOOP256(run_add256, _mm256_add_pd(a[i], c))
THROUGHPUT_LOOP256(run_div256, _mm256_div_pd(two, a[i]))
THROUGHPUT_LOOP256(run_sqrt256, _mm256_sqrt_pd(a[i]))

double bf_bench_lanes_per_second(int kind, int bits)
{
    double best = 0.0;
    int t;
    for (t = 0; t < TRIES; t++) {
        double rate;
        switch (kind) {
        case BF_BENCH_FMA:
            rate = bits == 512 ? run_fma(200000) : run_fma256(200000);
            break;
        case BF_BENCH_ADD:
            rate = bits == 512 ? run_add(200000) : run_add256(200000);
            break;
        case BF_BENCH_DIV:
            rate = bits == 512 ? run_div(20000) : run_div256(20000);
            break;
        default:
            rate = bits == 512 ? run_sqrt(20000) : run_sqrt256(20000);
            break;
        }
        if (rate > best) {
            best = rate;
        }
    }
    return best;
}
