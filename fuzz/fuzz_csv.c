/* fuzz_csv.c: libFuzzer target for brdffit's tidy CSV (bf_csv_read,
 * bf_csv_write, bf_configs_read; README "Tidy CSV").
 *
 * Beyond "no crash, leak or sanitizer report" it checks the contract:
 * status, object and error report agree (fuzz.h); a loaded dataset has its
 * angles in range and finite valid values, and writing it and reading it
 * back gives it again bit for bit (so every angle the reader produces has
 * a decimal the writer finds); a configuration list that loads has n >= 1
 * rows of angles in range. */
#include <math.h>
#include <stdlib.h>

#include "fuzz.h"

static void configs(const uint8_t *data, size_t size)
{
    FILE *fp = bf_fuzz_open(data, size);
    double *a = NULL;
    size_t n = 0;
    size_t k;
    bf_error err;
    int rc = bf_configs_read(fp, BF_FUZZ_NAME, &a, &n, &err);
    bf_fuzz_check(rc, a != NULL, &err, bf_fuzz_lines(data, size));
    if ((rc == BF_OK) != (n > 0)) {
        bf_fuzz_fail("configuration count and status disagree");
    }
    for (k = 0; k < n; k++) {
        if (!(a[4 * k] >= 0.0 && a[4 * k] <= asin(1.0) &&
              a[4 * k + 2] >= 0.0 && a[4 * k + 2] <= asin(1.0) &&
              isfinite(a[4 * k + 1]) && isfinite(a[4 * k + 3]))) {
            bf_fuzz_fail("a configuration is outside the hemisphere");
        }
    }
    free(a);
    bf_fuzz_close(fp);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bf_fuzz_dataset_reader(bf_csv_read, data, size);
    configs(data, size);
    return 0;
}
