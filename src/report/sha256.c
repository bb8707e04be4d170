/* sha256.c: SHA-256 digests of the report's input files (sha256.h),
 * computed by GNU Nettle's implementation of FIPS 180-4 (nettle/sha2.h);
 * this file only streams a file through it and writes the digest as hex. */
#include "sha256.h"

#include <errno.h>

#include "brdffit.h"

void bf_sha256_init(bf_sha256 *c)
{
    sha256_init(&c->ctx);
}

void bf_sha256_update(bf_sha256 *c, const void *data, size_t len)
{
    sha256_update(&c->ctx, len, data);
}

void bf_sha256_final(bf_sha256 *c, uint8_t digest[BF_SHA256_SIZE])
{
    sha256_digest(&c->ctx, BF_SHA256_SIZE, digest);
}

void bf_sha256_hex(const uint8_t digest[BF_SHA256_SIZE],
                   char hex[BF_SHA256_HEX])
{
    static const char digits[] = "0123456789abcdef";
    size_t i;
    for (i = 0; i < BF_SHA256_SIZE; i++) {
        hex[2 * i] = digits[digest[i] >> 4];
        hex[2 * i + 1] = digits[digest[i] & 15];
    }
    hex[2 * BF_SHA256_SIZE] = '\0';
}

int bf_sha256_stream(FILE *fp, char hex[BF_SHA256_HEX])
{
    bf_sha256 c;
    uint8_t buf[65536];
    uint8_t digest[BF_SHA256_SIZE];
    size_t n;
    bf_sha256_init(&c);
    while ((n = fread(buf, 1, sizeof buf, fp)) > 0) {
        bf_sha256_update(&c, buf, n);
    }
    if (ferror(fp)) {
        return BF_EIO;
    }
    bf_sha256_final(&c, digest);
    bf_sha256_hex(digest, hex);
    return BF_OK;
}

int bf_sha256_file(const char *path, char hex[BF_SHA256_HEX])
{
    FILE *fp = fopen(path, "rb");
    int rc;
    if (fp == NULL) {
        return errno == ENOMEM ? BF_ENOMEM : BF_EIO;
    }
    rc = bf_sha256_stream(fp, hex);
    fclose(fp);
    return rc;
}
