/* merl.c: MERL .binary tables (SPEC §8): read whole, looked up cell by
 * cell, sampled at chosen configurations or at every valid cell.
 *
 * [1] W. Matusik, H. Pfister, M. Brand, L. McMillan, "A Data-Driven
 *     Reflectance Model", ACM TOG 22(3), 2003, and MERL's reference reader
 *     BRDFRead.cpp: the layout (three int32 dimensions, then 90 * 90 * 180
 *     float64 values per channel, R then G then B), the scales (1/1500,
 *     1.15/1500, 1.66/1500) and the index formulas below; the ALTA,
 *     pbrt-v2 and libbsdf readers agree on all of it.
 * [2] S. M. Rusinkiewicz, "A New Change of Variables for Efficient BRDF
 *     Representation", EGWR 1998: the half vector h of omega_i and
 *     omega_o, and the difference vector d = omega_i seen from a frame
 *     whose pole is h.
 *
 * The index of a configuration (all of [1], in its order of operations,
 * so cells split where the reference reader splits them):
 *   i = floor(sqrt(theta_h / (pi/2) * 90 * 90))   (0 when theta_h <= 0)
 *   j = floor(theta_d / (pi/2) * 90)
 *   k = floor(phi_d / pi * 360 / 2)                (phi_d < 0: add pi first;
 *                                                   reciprocity)
 * each clamped into its range; cell = k + 180 (j + 90 i). A cell is
 * invalid when a channel is negative (MERL's mark for "not measured"); it
 * is never clamped to 0.
 *
 * A cell's centre is the middle of its index intervals:
 *   theta_h = ((i + 1/2) / 90)^2 pi/2,  theta_d = (j + 1/2) / 90 pi/2,
 *   phi_d = (k + 1/2) / 180 pi,
 * turned into directions with phi_h = 0: omega_i = R_y(theta_h) d and
 * omega_o = R_y(theta_h) (-d_x, -d_y, d_z), d the difference vector. Its
 * index coordinates lie half a cell from every border: at least 1/4 of a
 * unit of sqrt(theta_h / (pi/2)) * 90 (the smallest margin, 4.8e-5 rad in
 * theta_h at i = 0) and pi/360 in theta_d and phi_d, while the round trip
 * through directions moves them by about 1e-12 rad at most (acos near 1 at
 * i = 0). So the lookup of a centre finds its own cell (tested on every
 * cell). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "data/reader.h"
#include "internal.h"

/* The dimensions (theta_h, theta_d, phi_d) of [1]. */
#define N_TH 90
#define N_TD 90
#define N_PD 180
#define N_CELLS ((size_t)N_TH * N_TD * N_PD) /* 1,458,000 */
#define HEADER_BYTES 12
#define FILE_BYTES (HEADER_BYTES + 3 * N_CELLS * sizeof(double))

/* The channel scales of [1]: value = raw * scale. */
static const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

static const char *const channel_name[3] = {"R", "G", "B"};

struct bf_merl {
    double *v; /* 3 x N_CELLS, channel-planar, scaled */
};

void bf_merl_free(bf_merl *t)
{
    if (t == NULL) {
        return;
    }
    free(t->v);
    free(t);
}

/* ==== reading ==== */

/* A little-endian int32 of the header. */
static long le32(const unsigned char *b)
{
    uint32_t u = (uint32_t)b[0] | ((uint32_t)b[1] << 8) |
                 ((uint32_t)b[2] << 16) | ((uint32_t)b[3] << 24);
    return u <= INT32_MAX ? (long)u : (long)u - 4294967296L;
}

/* 1 when the 12 bytes of head are the dimensions 90, 90, 180. */
static int dims_ok(const unsigned char *head)
{
    return le32(head) == N_TH && le32(head + 4) == N_TD &&
           le32(head + 8) == N_PD;
}

/* 1 on a little-endian host (the file's byte order). */
static int host_le(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

/* Byte-swaps the n doubles of v (a big-endian host). */
static void swap64(double *v, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++) {
        unsigned char b[8];
        unsigned char s[8];
        size_t j;
        memcpy(b, &v[k], 8);
        for (j = 0; j < 8; j++) {
            s[j] = b[7 - j];
        }
        memcpy(&v[k], s, 8);
    }
}

/* The size of a seekable stream from the current position on, plus pos;
 * -1 when it cannot be told (a pipe). */
static long long stream_size(FILE *fp, long long pos)
{
    long here = ftell(fp);
    long end;
    if (here < 0 || fseek(fp, 0, SEEK_END) != 0) {
        clearerr(fp);
        return -1;
    }
    end = ftell(fp);
    if (fseek(fp, here, SEEK_SET) != 0 || end < 0) {
        clearerr(fp);
        return -1;
    }
    return pos + (end - here);
}

/* Checks and scales the values just read: every one finite (a negative
 * one marks its cell invalid and is kept). */
static int convert(double *v, bf_error *err)
{
    size_t c;
    size_t k;
    if (!host_le()) {
        swap64(v, 3 * N_CELLS);
    }
    for (c = 0; c < 3; c++) {
        double *p = v + c * N_CELLS;
        for (k = 0; k < N_CELLS; k++) {
            if (!isfinite(p[k])) {
                return bf__error_set(err, BF_EPARSE, 0,
                                     "byte %zu: value %zu of channel %s "
                                     "(cell %zu) is not a finite number",
                                     HEADER_BYTES + 8 * (c * N_CELLS + k),
                                     k + 1, channel_name[c], k);
            }
            p[k] *= scale[c];
        }
    }
    return BF_OK;
}

int bf_merl_read(FILE *fp, const char *name, bf_merl **out, bf_error *err)
{
    unsigned char head[HEADER_BYTES];
    bf_merl *t = NULL;
    long long size;
    size_t got;
    int rc;

    bf__error_clear(err, name);
    if (out != NULL) {
        *out = NULL;
    }
    if (out == NULL || fp == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    got = fread(head, 1, HEADER_BYTES, fp);
    if (ferror(fp)) {
        return bf__error_set(err, BF_EIO, 0, "read error: %s",
                             strerror(errno));
    }
    if (got < HEADER_BYTES) {
        return bf__error_set(err, BF_EPARSE, 0,
                             got == 0 ? "empty file"
                                      : "byte %zu: the file ends inside the "
                                        "12-byte header (three int32 "
                                        "dimensions)",
                             got);
    }
    if (!dims_ok(head)) {
        return bf__error_set(err, BF_EPARSE, 0,
                             "byte 0: dimensions %ld x %ld x %ld; a MERL "
                             "table has 90 x 90 x 180 (theta_h, theta_d, "
                             "phi_d)",
                             le32(head), le32(head + 4), le32(head + 8));
    }
    /* the size the dimensions imply, before allocating anything */
    size = stream_size(fp, HEADER_BYTES);
    if (size >= 0 && size != (long long)FILE_BYTES) {
        return bf__error_set(err, BF_EPARSE, 0,
                             "byte %lld: the file has %lld bytes, but its "
                             "dimensions 90 x 90 x 180 imply %zu (3 x "
                             "1458000 float64 after the header)",
                             size < (long long)FILE_BYTES
                                 ? size
                                 : (long long)FILE_BYTES,
                             size, (size_t)FILE_BYTES);
    }
    t = calloc(1, sizeof *t);
    if (t != NULL) {
        t->v = malloc(3 * N_CELLS * sizeof *t->v);
    }
    if (t == NULL || t->v == NULL) {
        bf_merl_free(t);
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    got = fread(t->v, 1, FILE_BYTES - HEADER_BYTES, fp); /* one read */
    if (ferror(fp)) {
        rc = bf__error_set(err, BF_EIO, 0, "read error: %s",
                           strerror(errno));
    } else if (got < FILE_BYTES - HEADER_BYTES) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "byte %zu: the file ends early; its dimensions "
                           "90 x 90 x 180 imply %zu bytes",
                           HEADER_BYTES + got, (size_t)FILE_BYTES);
    } else if (getc(fp) != EOF) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           "byte %zu: data after the table (its dimensions "
                           "90 x 90 x 180 imply %zu bytes)",
                           (size_t)FILE_BYTES, (size_t)FILE_BYTES);
    } else {
        rc = convert(t->v, err);
    }
    if (rc != BF_OK) {
        bf_merl_free(t);
        return rc;
    }
    *out = t;
    return BF_OK;
}

int bf_merl_load(const char *path, bf_merl **out, bf_error *err)
{
    FILE *fp = NULL;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_merl_read(fp, path, out, err);
    fclose(fp);
    return rc;
}

/* ==== the lookup [1], [2] ==== */

/* The index of the cell holding a configuration (directions above or on
 * the horizon), as the reference reader computes it [1]. */
static size_t cell_of(double theta_i, double phi_i, double theta_o,
                      double phi_o)
{
    double in[3];
    double out[3];
    double h[3];
    double t[3];
    double d[3];
    double norm;
    double theta_h;
    double phi_h;
    double theta_d;
    double phi_d;
    double x;
    long i;
    long j;
    long k;
    in[0] = sin(theta_i) * cos(phi_i);
    in[1] = sin(theta_i) * sin(phi_i);
    in[2] = cos(theta_i);
    out[0] = sin(theta_o) * cos(phi_o);
    out[1] = sin(theta_o) * sin(phi_o);
    out[2] = cos(theta_o);
    h[0] = in[0] + out[0]; /* the half vector [2] */
    h[1] = in[1] + out[1];
    h[2] = in[2] + out[2];
    norm = sqrt((h[0] * h[0]) + (h[1] * h[1]) + (h[2] * h[2]));
    if (!(norm > 1e-300)) {
        /* omega_o = -omega_i: the mirror configuration at grazing, whose
         * half vector tends to the normal */
        h[0] = 0.0;
        h[1] = 0.0;
        h[2] = 1.0;
        norm = 1.0;
    }
    theta_h = acos(fmin(1.0, h[2] / norm));
    phi_h = atan2(h[1], h[0]);
    /* d: omega_i rotated by -phi_h about the normal, then by -theta_h
     * about the binormal (0, 1, 0) [2] */
    t[0] = (in[0] * cos(phi_h)) + (in[1] * sin(phi_h));
    t[1] = (in[1] * cos(phi_h)) - (in[0] * sin(phi_h));
    t[2] = in[2];
    d[0] = (t[0] * cos(theta_h)) - (t[2] * sin(theta_h));
    d[1] = t[1];
    d[2] = (t[2] * cos(theta_h)) + (t[0] * sin(theta_h));
    theta_d = acos(fmax(-1.0, fmin(1.0, d[2])));
    phi_d = atan2(d[1], d[0]);

    /* the indices [1] */
    if (theta_h <= 0.0) {
        i = 0;
    } else {
        x = sqrt(((theta_h / BF__PI_2) * N_TH) * N_TH);
        i = x < N_TH ? (long)x : N_TH - 1;
    }
    x = (theta_d / BF__PI_2) * N_TD;
    j = x < N_TD ? (long)x : N_TD - 1;
    if (phi_d < 0.0) {
        phi_d += BF__PI; /* reciprocity: phi_d and phi_d + pi agree */
    }
    x = ((phi_d / BF__PI) * (2 * N_PD)) / 2;
    k = x < 0.0 ? 0 : (x < N_PD ? (long)x : N_PD - 1);
    return (size_t)k + (size_t)N_PD * ((size_t)j + (size_t)N_TD * (size_t)i);
}

/* 1 when a direction pair lies on or above the horizon, finite. */
static int above(double theta_i, double phi_i, double theta_o, double phi_o)
{
    return theta_i >= 0.0 && theta_i <= BF__PI_2 && theta_o >= 0.0 &&
           theta_o <= BF__PI_2 && isfinite(phi_i) && isfinite(phi_o);
}

/* The scaled values of a cell; 1 when every channel is >= 0. */
static int cell_values(const bf_merl *t, size_t cell, double rgb[3])
{
    rgb[0] = t->v[cell];
    rgb[1] = t->v[cell + N_CELLS];
    rgb[2] = t->v[cell + 2 * N_CELLS];
    return rgb[0] >= 0.0 && rgb[1] >= 0.0 && rgb[2] >= 0.0;
}

int bf_merl_lookup(const bf_merl *t, double theta_i, double phi_i,
                   double theta_o, double phi_o, double rgb[3])
{
    if (t == NULL || rgb == NULL) {
        return 0;
    }
    if (!above(theta_i, phi_i, theta_o, phi_o)) {
        rgb[0] = NAN;
        rgb[1] = NAN;
        rgb[2] = NAN;
        return 0;
    }
    return cell_values(t, cell_of(theta_i, phi_i, theta_o, phi_o), rgb);
}

/* ==== sampling ==== */

/* Sines and cosines of the cells' centre angles (theta_h by i, theta_d
 * by j, phi_d by k), each computed once. */
typedef struct {
    double sh[N_TH], ch[N_TH];
    double sd[N_TD], cd[N_TD];
    double sp[N_PD], cp[N_PD];
} centres_t;

static void centres_init(centres_t *c)
{
    size_t i;
    for (i = 0; i < N_TH; i++) {
        double theta_h = ((i + 0.5) / N_TH) * ((i + 0.5) / N_TH) * BF__PI_2;
        c->sh[i] = sin(theta_h);
        c->ch[i] = cos(theta_h);
    }
    for (i = 0; i < N_TD; i++) {
        double theta_d = ((i + 0.5) / N_TD) * BF__PI_2;
        c->sd[i] = sin(theta_d);
        c->cd[i] = cos(theta_d);
    }
    for (i = 0; i < N_PD; i++) {
        double phi_d = ((i + 0.5) / N_PD) * BF__PI;
        c->sp[i] = sin(phi_d);
        c->cp[i] = cos(phi_d);
    }
}

/* The directions of the centre of cell (i, j, k) (see the file's
 * comment); 1 when both lie on or above the horizon. */
static int centre(const centres_t *c, size_t i, size_t j, size_t k,
                  double angles[4])
{
    double d[3];
    double in[3];
    double out[3];
    d[0] = c->sd[j] * c->cp[k];
    d[1] = c->sd[j] * c->sp[k];
    d[2] = c->cd[j];
    /* R_y(theta_h): the inverse of the lookup's rotation, phi_h = 0 */
    in[0] = (d[0] * c->ch[i]) + (d[2] * c->sh[i]);
    in[1] = d[1];
    in[2] = (d[2] * c->ch[i]) - (d[0] * c->sh[i]);
    out[0] = (-d[0] * c->ch[i]) + (d[2] * c->sh[i]);
    out[1] = -d[1];
    out[2] = (d[2] * c->ch[i]) + (d[0] * c->sh[i]);
    if (in[2] < 0.0 || out[2] < 0.0) {
        return 0;
    }
    angles[0] = acos(fmin(1.0, in[2]));
    angles[1] = atan2(in[1], in[0]);
    angles[2] = acos(fmin(1.0, out[2]));
    angles[3] = atan2(out[1], out[0]);
    return 1;
}

/* Every valid cell above the horizon, at its centre: *n configurations
 * into *angles (n x 4) and their values (n x 3), allocated here for every
 * cell and shrunk to n. */
static int all_cells(const bf_merl *t, size_t *n, double **angles,
                     double **values)
{
    centres_t c;
    size_t i;
    size_t j;
    size_t k;
    void *p;
    *n = 0;
    *angles = malloc(N_CELLS * 4 * sizeof **angles);
    *values = malloc(N_CELLS * 3 * sizeof **values);
    if (*angles == NULL || *values == NULL) {
        return BF_ENOMEM;
    }
    centres_init(&c);
    for (i = 0; i < N_TH; i++) {
        for (j = 0; j < N_TD; j++) {
            for (k = 0; k < N_PD; k++) {
                size_t cell = k + N_PD * (j + N_TD * i);
                if (cell_values(t, cell, *values + 3 * *n) &&
                    centre(&c, i, j, k, *angles + 4 * *n)) {
                    (*n)++;
                }
            }
        }
    }
    if (*n == 0) {
        return BF_EDOM;
    }
    p = realloc(*angles, *n * 4 * sizeof **angles);
    *angles = p != NULL ? p : *angles;
    p = realloc(*values, *n * 3 * sizeof **values);
    *values = p != NULL ? p : *values;
    return BF_OK;
}

int bf_merl_dataset(const bf_merl *t, size_t n, const double *at,
                    const char *material, const char *source,
                    bf_dataset **out, bf_error *err)
{
    double *angles = NULL;
    double *values = NULL;
    unsigned char *valid = NULL;
    int any_invalid = 0;
    bf_material_desc d;
    size_t k;
    int rc = BF_OK;

    bf__error_clear(err, source);
    if (out != NULL) {
        *out = NULL;
    }
    if (t == NULL || out == NULL || (at != NULL && n == 0)) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "no table, no output or no configuration");
    }
    if (at == NULL) {
        rc = all_cells(t, &n, &angles, &values);
        if (rc == BF_EDOM) {
            rc = bf__error_set(err, BF_EDOM, 0,
                               "no valid cell: every cell of the table has "
                               "a negative value");
        }
    } else {
        values = malloc(n * 3 * sizeof *values);
        valid = malloc(n * 3);
        rc = values == NULL || valid == NULL ? BF_ENOMEM : BF_OK;
        for (k = 0; rc == BF_OK && k < n; k++) {
            const double *a = at + 4 * k;
            int ok;
            if (!above(a[0], a[1], a[2], a[3])) {
                rc = bf__error_set(err, BF_EINVAL, 0,
                                   "configuration %zu lies outside the "
                                   "hemisphere",
                                   k + 1);
                break;
            }
            ok = bf_merl_lookup(t, a[0], a[1], a[2], a[3], values + 3 * k);
            memset(valid + 3 * k, ok, 3);
            any_invalid |= !ok;
        }
    }
    if (rc == BF_ENOMEM) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    if (rc == BF_OK) {
        memset(&d, 0, sizeof d);
        d.name = material;
        d.format = BF_FORMAT_MERL;
        d.source = source;
        d.n_channels = 3;
        d.channel = channel_name;
        d.values = values;
        d.valid = any_invalid ? valid : NULL;
        rc = bf__dataset_single(&d, n, at != NULL ? at : angles, out, err);
    }
    free(angles);
    free(values);
    free(valid);
    return rc;
}

/* ==== the reader (reader.h) ==== */

/* Detection: the file starts with the dimensions (bf_merl_read checks the
 * size they imply, and names it). */
static int detect(const char *buf, size_t n)
{
    return n >= HEADER_BYTES && dims_ok((const unsigned char *)buf);
}

/* A MERL file at the configurations of opts (checked first: nothing is
 * read without them). */
static int load(const char *path, const bf_load_opts *opts, bf_dataset **out,
                bf_error *err)
{
    char stem[BF_ERROR_FILE_MAX];
    bf_merl *t = NULL;
    int rc;
    if (opts == NULL || (!opts->all_cells &&
                         (opts->at == NULL || opts->n_at == 0))) {
        bf__error_clear(err, path);
        return bf__error_set(err, BF_EINVAL, 0,
                             "a MERL table is fitted at chosen "
                             "configurations, and none were given");
    }
    rc = bf_merl_load(path, &t, err);
    if (rc == BF_OK) {
        bf__stem(path, stem, sizeof stem);
        rc = bf_merl_dataset(t, opts->all_cells ? 0 : opts->n_at,
                             opts->all_cells ? NULL : opts->at, stem, path,
                             out, err);
    }
    bf_merl_free(t);
    return rc;
}

static const char *const aliases[] = {"binary", NULL};

const bf__reader bf__merl_reader = {
    .name = "merl",
    .aliases = aliases,
    .title = "MERL",
    .detect = detect,
    .binary = 1,
    .rank = BF__RANK_MAGIC,
    .miss = "a MERL table (it does not start with the int32 dimensions 90, "
            "90, 180)",
    .load = load,
};
