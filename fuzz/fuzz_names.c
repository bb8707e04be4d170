/* fuzz_names.c: libFuzzer target for the sample-name reader (bf_names_read,
 * CURET's samples.tsv).
 *
 * Beyond "no crash, leak or sanitizer report" it checks the contract:
 * status, object and error report agree (fuzz.h), and a loaded file gives
 * no empty name for any sample number probed and no name for sample
 * numbers 0 and -1. */

#include "data/curet.h"
#include "fuzz.h"

/* Largest sample number probed after a successful load. */
#define PROBE_MAX 256

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *fp = bf_fuzz_open(data, size);
    bf_names *nm = NULL;
    bf_error err;
    int rc = bf_names_read(fp, BF_FUZZ_NAME, &nm, &err);
    bf_fuzz_check(rc, nm != NULL, &err, bf_fuzz_lines(data, size));
    if (nm != NULL) {
        int s;
        for (s = 1; s <= PROBE_MAX; s++) {
            const char *name = bf_names_get(nm, s);
            if ((name != NULL) && (name[0] == '\0')) {
                bf_fuzz_fail("a loaded name is empty");
            }
        }
        if ((bf_names_get(nm, 0) != NULL) || (bf_names_get(nm, -1) != NULL)) {
            bf_fuzz_fail("a name for a non-positive sample number");
        }
    }
    bf_names_free(nm);
    bf_fuzz_close(fp);
    return 0;
}
