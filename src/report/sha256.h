/* sha256.h: SHA-256 message digests (FIPS 180-4, computed by GNU Nettle),
 * used by the report to record checksums of the data files it was made
 * from. Private: not installed. */
#ifndef BF_REPORT_SHA256_H
#define BF_REPORT_SHA256_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <nettle/sha2.h>

#define BF_SHA256_SIZE 32 /* digest bytes */
#define BF_SHA256_HEX (2 * BF_SHA256_SIZE + 1) /* hex digest + NUL */

/* Running state of one digest (Nettle's). */
typedef struct {
    struct sha256_ctx ctx;
} bf_sha256;

/* Starts a digest. */
void bf_sha256_init(bf_sha256 *c);
/* Adds len bytes of message. */
void bf_sha256_update(bf_sha256 *c, const void *data, size_t len);
/* Writes the digest of the message added so far. */
void bf_sha256_final(bf_sha256 *c, uint8_t digest[BF_SHA256_SIZE]);

/* Writes the digest as 64 lowercase hex digits and a NUL into hex. */
void bf_sha256_hex(const uint8_t digest[BF_SHA256_SIZE],
                   char hex[BF_SHA256_HEX]);

/* Digest of everything left in fp, as hex. Returns BF_OK or BF_EIO on a
 * read error. */
int bf_sha256_stream(FILE *fp, char hex[BF_SHA256_HEX]);

/* Digest of the file at path, as hex. Returns BF_OK, or BF_EIO when it
 * cannot be opened or read (BF_ENOMEM when opening it ran out of
 * memory). */
int bf_sha256_file(const char *path, char hex[BF_SHA256_HEX]);

#endif
