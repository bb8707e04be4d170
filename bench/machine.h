/* machine.h: throughput of one core (bench/machine.c), for the floor. */
#ifndef BF_BENCH_MACHINE_H
#define BF_BENCH_MACHINE_H

enum { BF_BENCH_FMA, BF_BENCH_ADD, BF_BENCH_DIV, BF_BENCH_SQRT };

/* Clock in cycles per second (dependent integer adds). */
double bf_bench_clock_hz(void);

/* Double-precision lanes per second of operations of one kind on vectors
 * of bits 512 (needs AVX-512F) or 256 (needs AVX2 and FMA), independent
 * chains (throughput, not latency). */
double bf_bench_lanes_per_second(int kind, int bits);

#endif
