/* random_geometry.h: random measurement directions shared by the tests
 * (support.c) and the coverage bench (bench/bench_coverage.c). Plain C
 * (no test framework), so that both can compile it. */
#ifndef BF_TESTS_RANDOM_GEOMETRY_H
#define BF_TESTS_RANDOM_GEOMETRY_H

#include <stddef.h>

#include "brdffit.h"

/* n directions uniform on the hemisphere up to 80 degrees into geom
 * (GSL mt19937 seeded with seed; phi_i = pi); with mirror every second
 * within 10 degrees of the mirror direction instead (phi_s = 0, SPEC
 * §1.2: where a lobe is measured). Returns n, or 0 when the generator
 * cannot be allocated. */
size_t bf_random_geometry(bf_geom *geom, size_t n, unsigned long seed,
                          int mirror);

#endif
