/* support.h: shared helpers of the test suite -- named tolerances, checks
 * that print expected/obtained/difference/tolerance, loud access to the
 * CURET data and in-memory files for loader tests. */
#ifndef BF_TEST_SUPPORT_H
#define BF_TEST_SUPPORT_H

#include <float.h>
#include <stdio.h>

#include "brdffit.h"

/* Named tolerances (STYLE §7, after GSL's TEST_TOL0..6). */
#define TOL0 (2.0 * DBL_EPSILON)
#define TOL1 (16.0 * DBL_EPSILON)
#define TOL2 (256.0 * DBL_EPSILON)
#define TOL3 (2048.0 * DBL_EPSILON)
#define TOL4 (16384.0 * DBL_EPSILON)
#define TOL_FIT 1e-6

/* 1 in a build with AddressSanitizer (make test-asan), whose code runs
 * tens of times slower: the few tests whose claim needs many repetitions
 * (interval coverage) or the plain path on every sample (WNO-R's grid)
 * make it there on fewer; the plain build makes the full claim. */
#if defined(__SANITIZE_ADDRESS__)
#define BF_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BF_TEST_SANITIZED 1
#endif
#endif
#ifndef BF_TEST_SANITIZED
#define BF_TEST_SANITIZED 0
#endif

/* Asserts |obtained - expected| <= tol * max(|expected|, 1e-300) and prints
 * expected, obtained, relative difference and tolerance when it fails. */
#define bf_assert_rel(obtained, expected, tol) \
    bf__assert_rel((obtained), (expected), (tol), #obtained, __FILE__, __LINE__)
/* Asserts |obtained - expected| <= tol. */
#define bf_assert_abs(obtained, expected, tol) \
    bf__assert_abs((obtained), (expected), (tol), #obtained, __FILE__, __LINE__)

void bf__assert_rel(double obtained, double expected, double tol,
                    const char *what, const char *file, int line);
void bf__assert_abs(double obtained, double expected, double tol,
                    const char *what, const char *file, int line);

/* Path of a file in the CURET data folder (BF_CURET_DIR, overridable by the
 * environment variable BRDFFIT_CURET_DIR). Fails the test loudly when the
 * file does not exist: tests never skip for missing data. Static buffer. */
const char *bf_test_curet_path(const char *file);

/* Path of a file in the reference folder (BF_REFERENCE_DIR, or
 * BRDFFIT_REFERENCE_DIR); fails loudly when missing. Static buffer. */
const char *bf_test_reference_path(const char *file);

/* Path of a fixture in tests/fixtures (static buffer). */
const char *bf_test_fixture_path(const char *file);

/* Loads CURET's table.txt and abrdf.dat, failing the test loudly. */
bf_table *bf_test_load_table(void);
bf_brdf *bf_test_load_abrdf(void);

/* Opens a read-only in-memory stream over the NUL-terminated text. The
 * caller closes it with fclose. */
FILE *bf_test_memfile(const char *text);

/* Opens a read-only in-memory stream over len bytes (may contain NUL). */
FILE *bf_test_membuf(const void *buf, size_t len);

#endif
