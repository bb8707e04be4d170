/* fuzz_common.c: helpers shared by the libFuzzer targets (see fuzz.h). */
#include "fuzz.h"

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
