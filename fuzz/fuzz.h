/* fuzz.h: shared pieces of the libFuzzer targets of fuzz/ -- an in-memory
 * stream over the fuzzer's bytes and the checks every loader's error report
 * must pass. A broken invariant calls bf_fuzz_fail, which aborts, so
 * libFuzzer records the input as a crash. */
#ifndef BF_FUZZ_H
#define BF_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "brdffit.h"

/* The name the targets give the loaders; error reports must carry it. */
#define BF_FUZZ_NAME "fuzz-input"

/* Aborts with a message: the input broke a loader's documented contract. */
void bf_fuzz_fail(const char *what);

/* Opens a read-only stream over size bytes of data (a private copy, so
 * size 0 works too). The caller closes it with bf_fuzz_close. */
FILE *bf_fuzz_open(const uint8_t *data, size_t size);
void bf_fuzz_close(FILE *fp);

/* Number of lines of data (newlines + 1): no error may point past it. */
long bf_fuzz_lines(const uint8_t *data, size_t size);

/* Checks one loader call: rc is BF_OK exactly when the object (ok != 0)
 * was returned; on failure err carries rc, the file name, a line within
 * [0, lines] and a non-empty, terminated message. */
void bf_fuzz_check(int rc, int ok, const bf_error *err, long lines);

#endif
