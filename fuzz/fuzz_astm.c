/* fuzz_astm.c: libFuzzer target for the ASTM E1392 reader
 * (bf_astm_read; SPEC §8).
 *
 * Beyond "no crash, leak or sanitizer report" it checks the contract:
 * status, dataset and error report agree (fuzz.h); a loaded dataset has
 * its angles in range and finite valid values; and written as tidy CSV and
 * read back it is the same dataset bit for bit. */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bf_fuzz_dataset_reader(bf_astm_read, data, size);
    return 0;
}
