/* fuzz_merl.c: libFuzzer target for MERL tables (bf_merl_read,
 * bf_merl_lookup, bf_merl_dataset; SPEC §8).
 *
 * The input is used twice. As a file, bf_merl_read on it: below the 35 MB
 * a table needs only the header, dimension and size checks can be
 * reached, and they must refuse the input before allocating the table,
 * with a report at line 0 ("empty file" or "byte N: ..."). As
 * configurations (its bytes as doubles, 4 per configuration) looked up in
 * a fixed full-size table built once, whose cell n holds n, n + N and
 * n + 2 N in R, G, B (every seventh cell with a negative B): every lookup
 * answers without a crash, an answer of "valid" is a cell of the table,
 * and bf_merl_dataset accepts exactly the configurations inside the
 * hemisphere, marking the invalid cells. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"

#define N_CELLS 1458000u
#define TABLE_BYTES (12u + 3u * N_CELLS * 8u)
#define MAX_CONFIGS 64

static const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

static bf_merl *table;

int LLVMFuzzerInitialize(int *argc, char ***argv);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    static const unsigned char dims[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    unsigned char *b = malloc(TABLE_BYTES);
    bf_error err;
    FILE *fp;
    size_t n;
    (void)argc;
    (void)argv;
    if (b == NULL) {
        bf_fuzz_fail("out of memory building the table");
    }
    memcpy(b, dims, sizeof dims);
    for (n = 0; n < 3 * N_CELLS; n++) { /* little-endian host assumed */
        double v = (double)n;
        if (n >= 2 * N_CELLS && (n - 2 * N_CELLS) % 7 == 3) {
            v = -1.0;
        }
        memcpy(b + 12 + 8 * n, &v, 8);
    }
    fp = fmemopen(b, TABLE_BYTES, "r");
    if (fp == NULL || bf_merl_read(fp, "table", &table, &err) != BF_OK) {
        bf_fuzz_fail("the fixed table does not load");
    }
    fclose(fp);
    free(b);
    return 0;
}

/* The input as a file. */
static void as_file(const uint8_t *data, size_t size)
{
    FILE *fp = bf_fuzz_open(data, size);
    bf_merl *t = NULL;
    bf_error err;
    int rc = bf_merl_read(fp, BF_FUZZ_NAME, &t, &err);
    bf_fuzz_check(rc, t != NULL, &err, 0);
    if (rc == BF_OK) {
        bf_fuzz_fail("a table smaller than 35 MB loaded");
    }
    if (strcmp(err.msg, "empty file") != 0 &&
        strncmp(err.msg, "byte ", 5) != 0) {
        bf_fuzz_fail("a MERL error without its byte offset");
    }
    bf_fuzz_close(fp);
}

/* 1 when rgb is the value of a valid cell of the fixed table. */
static int is_cell(const double rgb[3])
{
    double n = nearbyint(rgb[0] / scale[0]);
    return n >= 0.0 && n < N_CELLS && rgb[0] == n * scale[0] &&
           rgb[1] == (n + N_CELLS) * scale[1] &&
           rgb[2] == (n + 2.0 * N_CELLS) * scale[2];
}

static int inside(const double *a)
{
    double half_pi = asin(1.0);
    return a[0] >= 0.0 && a[0] <= half_pi && a[2] >= 0.0 &&
           a[2] <= half_pi && isfinite(a[1]) && isfinite(a[3]);
}

/* The input as configurations. */
static void as_configs(const uint8_t *data, size_t size)
{
    double at[4 * MAX_CONFIGS];
    size_t n = size / 32 < MAX_CONFIGS ? size / 32 : MAX_CONFIGS;
    size_t k;
    int all_inside = 1;
    bf_dataset *ds = NULL;
    bf_error err;
    int rc;
    if (n == 0) {
        return;
    }
    memcpy(at, data, n * 32);
    for (k = 0; k < n; k++) {
        double rgb[3];
        const double *a = at + 4 * k;
        int ok = bf_merl_lookup(table, a[0], a[1], a[2], a[3], rgb);
        all_inside &= inside(a);
        if (ok && (!inside(a) || !is_cell(rgb))) {
            bf_fuzz_fail("a valid lookup that is no valid cell");
        }
        if (!ok && inside(a) && !(rgb[2] < 0.0)) {
            bf_fuzz_fail("an invalid lookup inside the hemisphere with "
                         "B >= 0");
        }
    }
    rc = bf_merl_dataset(table, n, at, "m", BF_FUZZ_NAME, &ds, &err);
    if ((rc == BF_OK) != all_inside || (rc != BF_OK && rc != BF_EINVAL)) {
        bf_fuzz_fail("bf_merl_dataset and the hemisphere disagree");
    }
    if (ds != NULL) {
        bf_fuzz_check_dataset(ds, 0); /* azimuths as given: any finite */
    }
    bf_dataset_free(ds);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    as_file(data, size);
    as_configs(data, size);
    return 0;
}
