/* fuzz_table.c: libFuzzer target for the configuration table reader
 * (bf_table_read, CURET's table.txt; SPEC §1.3).
 *
 * Beyond "no crash, leak or sanitizer report", it checks the reader's
 * contract: the status, the returned table and the error report agree
 * (fuzz.h), and a table that loads holds only configurations that every
 * model accepts (zeniths in the closed hemisphere, finite azimuths), so
 * bf_model_eval never answers BF_EINVAL for a loaded table and gives finite,
 * non-negative values. */
#include <math.h>
#include <stdlib.h>

#include "data/curet.h"
#include "fuzz.h"

/* Checks a loaded table: sizes, angle ranges and one model evaluation. */
static void check_table(const bf_table *t)
{
    size_t n = bf_table_size(t);
    size_t *sel;
    bf_geom *geom;
    double *out;
    double param[1] = {1.0};
    size_t k;
    size_t n_sel;
    int rc;
    if (n == 0) {
        bf_fuzz_fail("a loaded table is empty");
    }
    sel = malloc(n * sizeof *sel);
    geom = malloc(n * sizeof *geom);
    out = malloc(n * sizeof *out);
    if ((sel == NULL) || (geom == NULL) || (out == NULL)) {
        bf_fuzz_fail("out of memory");
    }
    for (k = 0; k < n; k++) {
        double raw[4];
        bf_table_raw(t, k, raw);
        if (!(raw[0] >= 0.0) || !(raw[0] <= asin(1.0)) || !(raw[2] >= 0.0)
            || !(raw[2] <= asin(1.0)) || !isfinite(raw[1])
            || !isfinite(raw[3])) {
            bf_fuzz_fail("a loaded angle is outside its range");
        }
        geom[k] = bf_table_geom(t, k);
    }
    n_sel = bf_table_select(t, 10.0, sel);
    for (k = 0; k < n_sel; k++) {
        if ((sel[k] >= n) || ((k > 0) && (sel[k] <= sel[k - 1]))) {
            bf_fuzz_fail("selection not increasing or out of range");
        }
    }
    /* VH-E is finite on the whole closed hemisphere (SPEC §3.3). */
    rc = bf_model_eval(bf_model_vh_e, param, n, geom, out);
    if (rc != BF_OK) {
        bf_fuzz_fail("VH-E rejects a loaded table's configurations");
    }
    for (k = 0; k < n; k++) {
        if (!isfinite(out[k]) || (out[k] < 0.0)) {
            bf_fuzz_fail("VH-E not finite and >= 0 on a loaded table");
        }
    }
    free(sel);
    free(geom);
    free(out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *fp = bf_fuzz_open(data, size);
    bf_table *t = NULL;
    bf_error err;
    int rc = bf_table_read(fp, BF_FUZZ_NAME, &t, &err);
    bf_fuzz_check(rc, t != NULL, &err, bf_fuzz_lines(data, size));
    if (t != NULL) {
        check_table(t);
    }
    bf_table_free(t);
    bf_fuzz_close(fp);
    return 0;
}
