/* fuzz_brdf.c: libFuzzer target for the BRDF row reader (bf_brdf_read,
 * CURET's abrdf.dat and per-channel files; SPEC §2).
 *
 * The number of values per row is a parameter of the reader; the target
 * reads each input twice: with n_conf = the number of fields of the first
 * line minus one (so mutations of real rows are often accepted and reach
 * the sample-number checks) and with CURET's 205. Beyond "no crash, leak or
 * sanitizer report" it checks the contract: status, object and error report
 * agree (fuzz.h); a loaded file holds samples 1..count in order with
 * n_conf finite values each, and bf_brdf_find inverts bf_brdf_sample. */
#include <math.h>

#include "data/curet.h"
#include "fuzz.h"

/* Fields of the first non-blank line, minus one (at least 1). */
static size_t guess_nconf(const uint8_t *data, size_t size)
{
    size_t fields = 0;
    size_t k = 0;
    int in_field = 0;
    while ((k < size) && ((data[k] == '\n') || (data[k] == '\r')
                          || (data[k] == ' ') || (data[k] == '\t'))) {
        k++;
    }
    for (; (k < size) && (data[k] != '\n') && (data[k] != '\r'); k++) {
        int blank = (data[k] == ' ') || (data[k] == '\t');
        if (!blank && !in_field) {
            fields++;
        }
        in_field = !blank;
    }
    return (fields > 1) ? fields - 1 : 1;
}

static void check_brdf(const bf_brdf *b, size_t n_conf)
{
    size_t n = bf_brdf_count(b);
    size_t r;
    size_t k;
    if ((n == 0) || (bf_brdf_nconf(b) != n_conf)) {
        bf_fuzz_fail("a loaded BRDF file has no rows or the wrong width");
    }
    for (r = 0; r < n; r++) {
        const double *v = bf_brdf_values(b, r);
        int s = bf_brdf_sample(b, r);
        if ((s != (int)r + 1) || (bf_brdf_find(b, s) != (long)r)) {
            bf_fuzz_fail("loaded samples are not 1..count in order");
        }
        for (k = 0; k < n_conf; k++) {
            if (!isfinite(v[k])) {
                bf_fuzz_fail("a loaded BRDF value is not finite");
            }
        }
    }
    if ((bf_brdf_values(b, n) != NULL) || (bf_brdf_find(b, 0) != -1)
        || (bf_brdf_find(b, (int)n + 1) != -1)) {
        bf_fuzz_fail("out-of-range access not refused");
    }
}

static void read_once(const uint8_t *data, size_t size, size_t n_conf)
{
    FILE *fp = bf_fuzz_open(data, size);
    bf_brdf *b = NULL;
    bf_error err;
    int rc = bf_brdf_read(fp, BF_FUZZ_NAME, n_conf, &b, &err);
    bf_fuzz_check(rc, b != NULL, &err, bf_fuzz_lines(data, size));
    if (b != NULL) {
        check_brdf(b, n_conf);
    }
    bf_brdf_free(b);
    bf_fuzz_close(fp);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t n_conf = guess_nconf(data, size);
    read_once(data, size, n_conf);
    if (n_conf != BF_CURET_NCONF) {
        read_once(data, size, BF_CURET_NCONF);
    }
    return 0;
}
