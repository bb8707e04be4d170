/* machine.h: throughput of one core (bench/machine.c), for the floor. */
#ifndef BF_BENCH_MACHINE_H
#define BF_BENCH_MACHINE_H

enum { BF_BENCH_FMA, BF_BENCH_ADD, BF_BENCH_DIV, BF_BENCH_SQRT };

/* Clock in cycles per second (dependent integer adds). */
double bf_bench_clock_hz(void);

/* Double-precision lanes per second of 512-bit operations of one kind,
 * independent chains (throughput, not latency). Needs AVX-512F. */
double bf_bench_lanes_per_second(int kind);

#endif
