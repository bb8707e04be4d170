/* fuzz_sample_table.c: libFuzzer target for the per-sample tables -- the
 * Oren-Nayar parameter file (bf_on_params_read, SPEC §5), the refractive
 * index file (bf_n_file_read, SPEC §4.2) and the generic reader under them
 * (bf_sample_table_read). Each input is read by all three.
 *
 * Beyond "no crash, leak or sanitizer report" it checks the contract:
 * status, object and error report agree (fuzz.h); a loaded table has unique
 * sample numbers that bf_sample_table_get finds, a common row width within
 * the requested bounds, finite values, rho in [0, 1] and sigma in
 * [0, pi/2] for ON files, and n in (1, 10] for n files. */
#include <math.h>

#include "fuzz.h"

/* Column bounds of the generic read: a range, so the width checks run. */
#define GENERIC_MIN 1
#define GENERIC_MAX 4

static void check_table(const bf_sample_table *st, size_t min_cols,
                        size_t max_cols)
{
    size_t n = bf_sample_table_count(st);
    size_t k = bf_sample_table_cols(st);
    size_t r;
    size_t c;
    double x;
    if ((n == 0) || (k < min_cols) || (k > max_cols)) {
        bf_fuzz_fail("a loaded sample table is empty or has a bad width");
    }
    for (r = 0; r < n; r++) {
        int s = bf_sample_table_sample(st, r);
        size_t q;
        if (s < 1) {
            bf_fuzz_fail("a loaded sample number is not positive");
        }
        for (q = 0; q < r; q++) {
            if (bf_sample_table_sample(st, q) == s) {
                bf_fuzz_fail("a loaded sample number appears twice");
            }
        }
        for (c = 0; c < k; c++) {
            if ((bf_sample_table_get(st, s, c, &x) != BF_OK) || !isfinite(x)) {
                bf_fuzz_fail("a loaded value is missing or not finite");
            }
        }
        if (bf_sample_table_get(st, s, k, &x) != BF_EINVAL) {
            bf_fuzz_fail("a column past the width is not refused");
        }
    }
    if (bf_sample_table_sample(st, n) != -1) {
        bf_fuzz_fail("a row past the end is not refused");
    }
}

/* Every value of column col lies in [lo, hi] (lo excluded if lo_open). */
static void check_column(const bf_sample_table *st, size_t col, double lo,
                         int lo_open, double hi)
{
    size_t r;
    for (r = 0; r < bf_sample_table_count(st); r++) {
        double x = 0.0;
        (void)bf_sample_table_get(st, bf_sample_table_sample(st, r), col, &x);
        if ((lo_open ? !(x > lo) : !(x >= lo)) || !(x <= hi)) {
            bf_fuzz_fail("a loaded value is outside its documented range");
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long lines = bf_fuzz_lines(data, size);
    bf_sample_table *st = NULL;
    bf_error err;
    FILE *fp;
    int rc;

    fp = bf_fuzz_open(data, size);
    rc = bf_sample_table_read(fp, BF_FUZZ_NAME, GENERIC_MIN, GENERIC_MAX, &st,
                              &err);
    bf_fuzz_check(rc, st != NULL, &err, lines);
    if (st != NULL) {
        check_table(st, GENERIC_MIN, GENERIC_MAX);
    }
    bf_sample_table_free(st);
    bf_fuzz_close(fp);

    fp = bf_fuzz_open(data, size);
    rc = bf_on_params_read(fp, BF_FUZZ_NAME, &st, &err);
    bf_fuzz_check(rc, st != NULL, &err, lines);
    if (st != NULL) {
        check_table(st, 2, 3);
        check_column(st, 0, 0.0, 0, 1.0);        /* rho, SPEC §5 */
        check_column(st, 1, 0.0, 0, asin(1.0));  /* sigma, radians */
    }
    bf_sample_table_free(st);
    bf_fuzz_close(fp);

    fp = bf_fuzz_open(data, size);
    rc = bf_n_file_read(fp, BF_FUZZ_NAME, &st, &err);
    bf_fuzz_check(rc, st != NULL, &err, lines);
    if (st != NULL) {
        check_table(st, 1, 1);
        check_column(st, 0, 1.0, 1, 10.0); /* n in (1, 10], SPEC §4.2 */
    }
    bf_sample_table_free(st);
    bf_fuzz_close(fp);
    return 0;
}
