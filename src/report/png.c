/* png.c: a small palette PNG writer for the report's figures (png.h).
 *
 * References:
 *   [1] W3C, "Portable Network Graphics (PNG) Specification (Second
 *       Edition)", 2003: §5.2 signature, §5.3 chunk layout and CRC,
 *       §11.2.2 IHDR (colour type 3: palette, bit depth 8), §11.2.3 PLTE,
 *       §11.2.4 IDAT (zlib stream of filtered scanlines, filter type 0),
 *       §11.2.5 IEND.
 *   [2] RFC 1950 (zlib), RFC 1951 (deflate): zlib's compress2. */
#include "png.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "brdffit.h"

/* The colour -> palette index cache: open addressing on 24-bit keys. */
#define CACHE_BITS 16
#define CACHE_SIZE (1u << CACHE_BITS)
#define EMPTY_KEY 0xFFFFFFFFu

typedef struct {
    uint32_t key[CACHE_SIZE];
    unsigned char val[CACHE_SIZE];
    size_t used;
} cache_t;

static uint32_t rgb_key(const unsigned char *p)
{
    return ((uint32_t)p[0] << 16) | ((uint32_t)p[1] << 8) | p[2];
}

/* The slot of key (found or free); NULL when the table is full. */
static size_t cache_slot(const cache_t *c, uint32_t key)
{
    uint32_t h = (key * 2654435761u) >> (32 - CACHE_BITS); /* Knuth */
    while (c->key[h] != EMPTY_KEY && c->key[h] != key) {
        h = (h + 1) & (CACHE_SIZE - 1);
    }
    return h;
}

static void put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* Writes one chunk [1] §5.3: length, type, data, CRC of type and data. */
static int chunk(FILE *fp, const char *type, const unsigned char *data,
                 size_t len)
{
    unsigned char head[8];
    unsigned char crc[4];
    uLong c = crc32(0L, (const Bytef *)type, 4);
    if (len > 0) {
        c = crc32(c, data, (uInt)len);
    }
    put_u32(head, (uint32_t)len);
    memcpy(head + 4, type, 4);
    put_u32(crc, (uint32_t)c);
    return fwrite(head, 1, 8, fp) == 8 &&
           (len == 0 || fwrite(data, 1, len, fp) == len) &&
           fwrite(crc, 1, 4, fp) == 4;
}

/* Exact palette: the image's colours in order of first appearance, when
 * there are at most 256. Returns their number, 0 when more. */
static size_t exact_palette(cache_t *c, const unsigned char *rgb, size_t n,
                            unsigned char (*pal)[3])
{
    size_t np = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        uint32_t key;
        size_t h;
        if (i > 0 && memcmp(&rgb[3 * i], &rgb[3 * i - 3], 3) == 0) {
            continue; /* runs of one colour: seen */
        }
        key = rgb_key(&rgb[3 * i]);
        h = cache_slot(c, key);
        if (c->key[h] == key) {
            continue;
        }
        if (np == 256) {
            return 0;
        }
        c->key[h] = key;
        c->val[h] = (unsigned char)np;
        memcpy(pal[np++], &rgb[3 * i], 3);
    }
    return np;
}

/* White and `levels` blends of each distinct base colour with white. */
static size_t blend_palette(const unsigned char (*base)[3], size_t n_base,
                            unsigned char (*pal)[3])
{
    unsigned char uniq[255][3];
    size_t nu = 0;
    size_t np = 1;
    size_t levels;
    size_t i;
    size_t k;
    int ch;
    for (i = 0; i < n_base && nu < 255; i++) {
        int seen = 0;
        for (k = 0; k < nu && !seen; k++) {
            seen = memcmp(uniq[k], base[i], 3) == 0;
        }
        if (!seen && !(base[i][0] == 255 && base[i][1] == 255 &&
                       base[i][2] == 255)) {
            memcpy(uniq[nu++], base[i], 3);
        }
    }
    levels = nu > 0 ? 255 / nu : 1;
    levels = levels > 16 ? 16 : levels;
    pal[0][0] = pal[0][1] = pal[0][2] = 255;
    for (i = 0; i < nu; i++) {
        for (k = 1; k <= levels; k++) {
            double t = (double)k / (double)levels;
            for (ch = 0; ch < 3; ch++) {
                pal[np][ch] = (unsigned char)(255.0 + (uniq[i][ch] - 255.0) *
                                                          t + 0.5);
            }
            np++;
        }
    }
    return np;
}

/* The index of the palette colour nearest to p (squared RGB distance;
 * the first of equals). */
static unsigned char nearest(const unsigned char (*pal)[3], size_t np,
                             const unsigned char *p)
{
    long best = -1;
    size_t bi = 0;
    size_t i;
    for (i = 0; i < np; i++) {
        long d0 = (long)pal[i][0] - p[0];
        long d1 = (long)pal[i][1] - p[1];
        long d2 = (long)pal[i][2] - p[2];
        long d = d0 * d0 + d1 * d1 + d2 * d2;
        if (best < 0 || d < best) {
            best = d;
            bi = i;
        }
    }
    return (unsigned char)bi;
}

int bf__png_write(const char *path, unsigned w, unsigned h,
                  const unsigned char *rgb, const unsigned char (*base)[3],
                  size_t n_base)
{
    size_t n = (size_t)w * h;
    size_t row = (size_t)w + 1;
    cache_t *c = malloc(sizeof *c);
    unsigned char pal[256][3];
    unsigned char *raw = malloc(row * h);
    uLongf zlen = compressBound((uLong)(row * h));
    unsigned char *z = malloc(zlen);
    unsigned char ihdr[13];
    size_t np;
    unsigned x;
    unsigned y;
    FILE *fp;
    int ok;

    if (w == 0 || h == 0 || rgb == NULL) {
        free(c);
        free(raw);
        free(z);
        return BF_EINVAL;
    }
    if (c == NULL || raw == NULL || z == NULL) {
        free(c);
        free(raw);
        free(z);
        return BF_ENOMEM;
    }
    memset(c->key, 0xFF, sizeof c->key);
    c->used = 0;
    np = exact_palette(c, rgb, n, pal);
    if (np == 0) { /* more than 256 colours: the blends of the bases */
        np = blend_palette(base, n_base, pal);
        memset(c->key, 0xFF, sizeof c->key);
    }
    for (y = 0; y < h; y++) {
        const unsigned char *p = &rgb[3 * (size_t)y * w];
        unsigned char *out = &raw[(size_t)y * row];
        *out++ = 0; /* filter type 0, none [1] §9 */
        for (x = 0; x < w; x++, p += 3) {
            uint32_t key;
            size_t hs;
            if (x > 0 && p[0] == p[-3] && p[1] == p[-2] && p[2] == p[-1]) {
                out[x] = out[x - 1]; /* runs of one colour (the white) */
                continue;
            }
            key = rgb_key(p);
            hs = cache_slot(c, key);
            if (c->key[hs] == key) {
                out[x] = c->val[hs];
                continue;
            }
            out[x] = nearest((const unsigned char(*)[3])pal, np, p);
            if (c->used < CACHE_SIZE / 2) { /* keep probes short */
                c->key[hs] = key;
                c->val[hs] = out[x];
                c->used++;
            }
        }
    }
    free(c);
    /* zlib's default level: 5% larger than level 9, and 15 times faster
     * on these images */
    ok = compress2(z, &zlen, raw, (uLong)(row * h), Z_DEFAULT_COMPRESSION) ==
         Z_OK;
    free(raw);
    put_u32(ihdr, w);
    put_u32(ihdr + 4, h);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 3;  /* palette colour */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering (each row says its filter) */
    ihdr[12] = 0; /* no interlace */
    fp = ok ? fopen(path, "wb") : NULL;
    if (fp == NULL) {
        free(z);
        return ok ? BF_EIO : BF_ENOMEM;
    }
    ok = fwrite("\x89PNG\r\n\x1a\n", 1, 8, fp) == 8 &&
         chunk(fp, "IHDR", ihdr, sizeof ihdr) &&
         chunk(fp, "PLTE", &pal[0][0], 3 * np) && chunk(fp, "IDAT", z, zlen) &&
         chunk(fp, "IEND", NULL, 0);
    free(z);
    if (fclose(fp) != 0) {
        ok = 0;
    }
    return ok ? BF_OK : BF_EIO;
}
