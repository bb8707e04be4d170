/* test_sha256.c: the SHA-256 wrapper (src/report/sha256.c over GNU Nettle)
 * against the published examples of NIST (FIPS 180-2 Appendix B; the CSRC
 * "SHA256.pdf" example values), fed whole and in pieces, and against the
 * system's sha256sum on a real data file. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "sha256.h"
#include "support.h"

static void digest_of(const void *data, size_t len, char hex[BF_SHA256_HEX])
{
    bf_sha256 c;
    uint8_t d[BF_SHA256_SIZE];
    bf_sha256_init(&c);
    bf_sha256_update(&c, data, len);
    bf_sha256_final(&c, d);
    bf_sha256_hex(d, hex);
}

Test(sha256, matches_the_fips_180_2_one_block_example_abc)
{
    char hex[BF_SHA256_HEX];
    digest_of("abc", 3, hex);
    cr_assert_str_eq(hex, "ba7816bf8f01cfea414140de5dae2223"
                          "b00361a396177a9cb410ff61f20015ad");
}

Test(sha256, matches_the_fips_180_2_two_block_example)
{
    const char *msg =
        "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    char hex[BF_SHA256_HEX];
    digest_of(msg, strlen(msg), hex);
    cr_assert_str_eq(hex, "248d6a61d20638b8e5c026930c3e6039"
                          "a33ce45964ff2167f6ecedd419db06c1");
}

Test(sha256, matches_the_published_digest_of_the_empty_message)
{
    char hex[BF_SHA256_HEX];
    digest_of("", 0, hex);
    cr_assert_str_eq(hex, "e3b0c44298fc1c149afbf4c8996fb924"
                          "27ae41e4649b934ca495991b7852b855");
}

Test(sha256, matches_the_fips_180_2_million_a_example_fed_in_odd_pieces)
{
    static char a[1000000];
    bf_sha256 c;
    uint8_t d[BF_SHA256_SIZE];
    char hex[BF_SHA256_HEX];
    size_t off = 0;
    size_t piece = 1;
    memset(a, 'a', sizeof a);
    bf_sha256_init(&c);
    while (off < sizeof a) { /* pieces of 1, 2, ... 97 bytes, repeating */
        size_t n = sizeof a - off < piece ? sizeof a - off : piece;
        bf_sha256_update(&c, a + off, n);
        off += n;
        piece = piece % 97 + 1;
    }
    bf_sha256_final(&c, d);
    bf_sha256_hex(d, hex);
    cr_assert_str_eq(hex, "cdc76e5c9914fb9281a1c7e284d73e67"
                          "f1809a48a497200e046d39ccc7112cd0");
}

Test(sha256, pads_correctly_at_every_length_around_a_block_boundary)
{
    /* Lengths 55 and 56 straddle the one/two padding-block boundary
     * (FIPS 180-4 §5.1.1); a one-shot and a byte-by-byte digest must
     * agree at every length, and the lengths give distinct digests. */
    char msg[130];
    char prev[BF_SHA256_HEX] = "";
    size_t len;
    memset(msg, 'x', sizeof msg);
    for (len = 50; len <= 130; len++) {
        char one[BF_SHA256_HEX];
        char bytes[BF_SHA256_HEX];
        bf_sha256 c;
        uint8_t d[BF_SHA256_SIZE];
        size_t i;
        digest_of(msg, len, one);
        bf_sha256_init(&c);
        for (i = 0; i < len; i++) {
            bf_sha256_update(&c, msg + i, 1);
        }
        bf_sha256_final(&c, d);
        bf_sha256_hex(d, bytes);
        cr_assert_str_eq(one, bytes, "length %zu", len);
        cr_assert_str_neq(one, prev, "length %zu", len);
        memcpy(prev, one, sizeof prev);
    }
}

Test(sha256, agrees_with_the_system_sha256sum_on_the_curet_table)
{
    const char *path = bf_test_curet_path("table.txt");
    char cmd[1200];
    char expected[BF_SHA256_HEX] = "";
    char hex[BF_SHA256_HEX];
    FILE *p;
    snprintf(cmd, sizeof cmd, "sha256sum '%s'", path);
    p = popen(cmd, "r");
    cr_assert_not_null(p);
    cr_assert_eq(fscanf(p, "%64s", expected), 1, "sha256sum gave nothing");
    pclose(p);
    cr_assert_eq(bf_sha256_file(path, hex), BF_OK);
    cr_assert_str_eq(hex, expected);
}

Test(sha256, reports_a_missing_file_as_an_io_error)
{
    char hex[BF_SHA256_HEX];
    cr_assert_eq(bf_sha256_file("/nonexistent/brdffit/file", hex), BF_EIO);
}
