/* fuzz_common.c: helpers shared by the libFuzzer targets (see fuzz.h). */
#include "fuzz.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void bf_fuzz_fail(const char *what)
{
    fprintf(stderr, "fuzz: contract broken: %s\n", what);
    abort();
}

/* fmemopen needs a buffer it may keep; the copy has one spare byte so that
 * an empty input is a valid (empty) stream. */
static char *copy;

FILE *bf_fuzz_open(const uint8_t *data, size_t size)
{
    FILE *fp;
    copy = malloc(size + 1);
    if (copy == NULL) {
        bf_fuzz_fail("out of memory copying the input");
    }
    if (size > 0) {
        memcpy(copy, data, size);
    }
    copy[size] = '\0';
    fp = fmemopen(copy, size > 0 ? size : 1, "r");
    if (fp == NULL) {
        bf_fuzz_fail("fmemopen failed");
    }
    if (size == 0) {
        (void)getc(fp); /* consume the spare NUL: the stream is now empty */
        if (getc(fp) != EOF) {
            bf_fuzz_fail("empty stream is not empty");
        }
        clearerr(fp);
    }
    return fp;
}

void bf_fuzz_close(FILE *fp)
{
    fclose(fp);
    free(copy);
    copy = NULL;
}

long bf_fuzz_lines(const uint8_t *data, size_t size)
{
    long n = 1;
    size_t k;
    for (k = 0; k < size; k++) {
        n += (data[k] == '\n') || (data[k] == '\r');
    }
    return n;
}

void bf_fuzz_check(int rc, int ok, const bf_error *err, long lines)
{
    if ((rc == BF_OK) != (ok != 0)) {
        bf_fuzz_fail("status and returned object disagree");
    }
    if (err->code != rc) {
        bf_fuzz_fail("err->code differs from the returned status");
    }
    if (strcmp(err->file, BF_FUZZ_NAME) != 0) {
        bf_fuzz_fail("error report does not name the file");
    }
    if (memchr(err->msg, '\0', sizeof err->msg) == NULL) {
        bf_fuzz_fail("error message is not terminated");
    }
    if (rc == BF_OK) {
        return;
    }
    if ((rc != BF_EPARSE) && (rc != BF_EIO) && (rc != BF_ENOMEM)) {
        bf_fuzz_fail("unexpected error code from a reader");
    }
    if (err->msg[0] == '\0') {
        bf_fuzz_fail("error without a message");
    }
    if ((err->line < 0) || (err->line > lines)) {
        bf_fuzz_fail("error line outside the input");
    }
}

/* ==== datasets ==== */

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

void bf_fuzz_check_dataset(const bf_dataset *ds, int bounded)
{
    const double half_pi = asin(1.0);
    const double two_pi = bounded ? 8.0 * atan(1.0) : INFINITY;
    size_t m;
    if (bf_dataset_count(ds) == 0) {
        bf_fuzz_fail("a loaded dataset has no material");
    }
    for (m = 0; m < bf_dataset_count(ds); m++) {
        size_t n = bf_dataset_nconf(ds, m);
        size_t nc = bf_dataset_nchannels(ds, m);
        const double *a = bf_dataset_angles(ds, m);
        const double *v = bf_dataset_values(ds, m);
        const unsigned char *ok = bf_dataset_valid(ds, m);
        size_t k;
        size_t c;
        if (n == 0 || nc == 0 || bf_dataset_name(ds, m) == NULL) {
            bf_fuzz_fail("a material without configurations or channels");
        }
        for (k = 0; k < n; k++) {
            const double *r = a + 4 * k;
            if (!(r[0] >= 0.0 && r[0] <= half_pi && r[2] >= 0.0 &&
                  r[2] <= half_pi && fabs(r[1]) <= two_pi &&
                  fabs(r[3]) <= two_pi && isfinite(r[1]) &&
                  isfinite(r[3]))) {
                bf_fuzz_fail("a loaded angle is outside its range");
            }
        }
        for (c = 0; c < nc; c++) {
            const char *name = bf_dataset_channel(ds, m, c);
            if (name == NULL || name[0] == '\0') {
                bf_fuzz_fail("a channel without a name");
            }
        }
        for (k = 0; k < n * nc; k++) {
            if ((ok == NULL || ok[k]) && !isfinite(v[k])) {
                bf_fuzz_fail("a valid value is not finite");
            }
        }
    }
}

/* Fails unless a and b hold the same measurements bit for bit. */
static void expect_same(const bf_dataset *a, const bf_dataset *b)
{
    size_t m;
    if (bf_dataset_count(a) != bf_dataset_count(b)) {
        bf_fuzz_fail("CSV round trip: material count");
    }
    for (m = 0; m < bf_dataset_count(a); m++) {
        size_t n = bf_dataset_nconf(a, m);
        size_t nc = bf_dataset_nchannels(a, m);
        const unsigned char *oa = bf_dataset_valid(a, m);
        const unsigned char *ob = bf_dataset_valid(b, m);
        size_t k;
        size_t c;
        if (bf_dataset_nconf(b, m) != n || bf_dataset_nchannels(b, m) != nc) {
            bf_fuzz_fail("CSV round trip: configuration or channel count");
        }
        for (k = 0; k < 4 * n; k++) {
            if (!same_bits(bf_dataset_angles(a, m)[k],
                           bf_dataset_angles(b, m)[k])) {
                bf_fuzz_fail("CSV round trip: an angle changed");
            }
        }
        for (c = 0; c < nc; c++) {
            double wa = bf_dataset_wavelength(a, m, c);
            double wb = bf_dataset_wavelength(b, m, c);
            if (strcmp(bf_dataset_channel(a, m, c),
                       bf_dataset_channel(b, m, c)) != 0 ||
                !(same_bits(wa, wb) || (isnan(wa) && isnan(wb)))) {
                bf_fuzz_fail("CSV round trip: a channel changed");
            }
        }
        for (k = 0; k < n * nc; k++) {
            int va = oa == NULL || oa[k];
            int vb = ob == NULL || ob[k];
            if (va != vb || (va && !same_bits(bf_dataset_values(a, m)[k],
                                             bf_dataset_values(b, m)[k]))) {
                bf_fuzz_fail("CSV round trip: a value changed");
            }
        }
        if (bf_dataset_name(a, m)[0] != '\0' &&
            strcmp(bf_dataset_name(a, m), bf_dataset_name(b, m)) != 0) {
            bf_fuzz_fail("CSV round trip: a name changed");
        }
    }
}

void bf_fuzz_csv_round_trip(const bf_dataset *ds)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    bf_dataset *back = NULL;
    bf_error err;
    int rc;
    if (fp == NULL) {
        bf_fuzz_fail("open_memstream failed");
    }
    rc = bf_csv_write(ds, fp);
    fclose(fp);
    if (rc == BF_OK) {
        fp = fmemopen(text, len, "r");
        if (fp == NULL) {
            bf_fuzz_fail("fmemopen failed");
        }
        rc = bf_csv_read(fp, BF_FUZZ_NAME, &back, &err);
        fclose(fp);
        if (rc != BF_OK) {
            fprintf(stderr, "fuzz: %s\n", err.msg);
            bf_fuzz_fail("CSV round trip: what bf_csv_write wrote is "
                         "refused");
        }
        expect_same(ds, back);
        bf_dataset_free(back);
    } else if (rc != BF_EINVAL) {
        bf_fuzz_fail("bf_csv_write failed other than BF_EINVAL");
    }
    free(text);
}

void bf_fuzz_dataset_reader(int (*read)(FILE *, const char *, bf_dataset **,
                                        bf_error *),
                            const uint8_t *data, size_t size)
{
    FILE *fp = bf_fuzz_open(data, size);
    bf_dataset *ds = NULL;
    bf_error err;
    int rc = read(fp, BF_FUZZ_NAME, &ds, &err);
    bf_fuzz_check(rc, ds != NULL, &err, bf_fuzz_lines(data, size));
    if (ds != NULL) {
        bf_fuzz_check_dataset(ds, 1);
        bf_fuzz_csv_round_trip(ds);
    }
    bf_dataset_free(ds);
    bf_fuzz_close(fp);
}
