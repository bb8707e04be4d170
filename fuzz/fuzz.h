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

/* Checks a dataset a reader returned: at least one material, each with
 * configurations and channels, angles in their ranges (zeniths in [0,
 * pi/2], azimuths finite and, when bounded, in [-2 pi, 2 pi] as the text
 * readers check them), finite valid values, names that are strings. */
void bf_fuzz_check_dataset(const bf_dataset *ds, int bounded);

/* Writes ds as tidy CSV and reads it back: bit for bit the same dataset
 * (or, when bf_csv_write refuses it, BF_EINVAL and nothing else). */
void bf_fuzz_csv_round_trip(const bf_dataset *ds);

/* One dataset reader on the fuzzer's bytes, with every check above. */
void bf_fuzz_dataset_reader(int (*read)(FILE *, const char *, bf_dataset **,
                                        bf_error *),
                            const uint8_t *data, size_t size);

#endif
