/* test_merl.c: the MERL reader (src/data/merl.c). No MERL file exists
 * here, so every table is written by the test: full-size tables whose
 * cells encode their own index (to check the layout, the scales and the
 * cell lookup against an independent construction of the half and
 * difference angles), tables filled from analytic models (fitted back:
 * exactly at cell centres, within the lookup error elsewhere), and small
 * or broken files for the error paths (exact code, byte offset, message).
 *
 * Independent geometry (Rusinkiewicz, EGWR 1998, in MERL's orientation):
 * the half vector h = (sin th cos ph, sin th sin ph, cos th) and its frame
 * t = (cos th cos ph, cos th sin ph, -sin th), b = (-sin ph, cos ph, 0);
 * omega_i = cos td h + sin td (cos pd t + sin pd b) and omega_o its mirror
 * image about h, 2 (omega_i . h) h - omega_i. Going back: h is omega_i +
 * omega_o normalised, and the difference angles are those of
 * (omega_i . t, omega_i . b, omega_i . h). The reader rotates vectors
 * instead of taking dot products. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_run.h"
#include "internal.h"
#include "support.h"

#define NAME "t.binary"
#define N_CELLS 1458000u              /* 90 x 90 x 180 (SPEC §8) */
#define TABLE_BYTES (12u + 3u * N_CELLS * 8u) /* 34,992,012 */

/* SPEC §8: value = raw x scale. */
static const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

/* Cell (i, j, k) = theta_h, theta_d, phi_d indices (SPEC §8). */
static size_t cell(size_t i, size_t j, size_t k)
{
    return k + 180 * (j + 90 * i);
}

/* ==== files ==== */

/* A new table file in memory: the dimensions, then raw values set by
 * set_raw (every raw value 0 to begin with). */
static unsigned char *new_table(void)
{
    static const unsigned char dims[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    unsigned char *b = calloc(1, TABLE_BYTES);
    cr_assert_not_null(b);
    memcpy(b, dims, sizeof dims);
    return b;
}

/* Raw value of channel c of a cell, stored little-endian. */
static void set_raw(unsigned char *b, size_t c, size_t at, double raw)
{
    uint64_t u;
    size_t k;
    memcpy(&u, &raw, 8);
    for (k = 0; k < 8; k++) {
        b[12 + 8 * (c * N_CELLS + at) + k] = (unsigned char)(u >> (8 * k));
    }
}

/* Reads len bytes as a MERL table (a seekable in-memory stream). */
static int read_table(const void *b, size_t len, bf_merl **t, bf_error *err)
{
    FILE *fp = bf_test_membuf(b, len);
    int rc = bf_merl_read(fp, NAME, t, err);
    fclose(fp);
    return rc;
}

static bf_merl *table_ok(const unsigned char *b)
{
    bf_merl *t = NULL;
    bf_error err;
    cr_assert_eq(read_table(b, TABLE_BYTES, &t, &err), BF_OK, "%s",
                 err.msg);
    return t;
}

/* A table whose channel c of cell n holds raw n + c N_CELLS, except the
 * cells of the invalid test (every seventh has a negative blue). */
static unsigned char *index_table(int with_invalid)
{
    unsigned char *b = new_table();
    size_t n;
    size_t c;
    for (n = 0; n < N_CELLS; n++) {
        for (c = 0; c < 3; c++) {
            set_raw(b, c, n, (double)(n + c * N_CELLS));
        }
        if (with_invalid && n % 7 == 3) {
            set_raw(b, 2, n, -1.0);
        }
    }
    return b;
}

/* What channel c of cell n of index_table reads as. */
static double index_value(size_t n, size_t c)
{
    return (double)(n + c * N_CELLS) * scale[c];
}

/* ==== the independent geometry (see the file's comment) ==== */

static double dot(const double a[3], const double b[3])
{
    return (a[0] * b[0]) + (a[1] * b[1]) + (a[2] * b[2]);
}

/* Angles (theta_i, phi_i, theta_o, phi_o) of half and difference angles;
 * 1 when both directions lie on or above the horizon. */
static int from_half_diff(double th, double ph, double td, double pd,
                          double a[4])
{
    double h[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
    double t[3] = {cos(th) * cos(ph), cos(th) * sin(ph), -sin(th)};
    double b[3] = {-sin(ph), cos(ph), 0.0};
    double wi[3];
    double wo[3];
    double ih;
    size_t k;
    for (k = 0; k < 3; k++) {
        wi[k] = (cos(td) * h[k]) +
                (sin(td) * ((cos(pd) * t[k]) + (sin(pd) * b[k])));
    }
    ih = dot(wi, h);
    for (k = 0; k < 3; k++) {
        wo[k] = (2.0 * ih * h[k]) - wi[k];
    }
    if (wi[2] < 0.0 || wo[2] < 0.0) {
        return 0;
    }
    a[0] = acos(fmin(1.0, wi[2]));
    a[1] = atan2(wi[1], wi[0]);
    a[2] = acos(fmin(1.0, wo[2]));
    a[3] = atan2(wo[1], wo[0]);
    return 1;
}

/* The cell of a configuration by the dot-product route and the index
 * formulas of SPEC §8. */
static size_t cell_of(const double a[4])
{
    double wi[3] = {sin(a[0]) * cos(a[1]), sin(a[0]) * sin(a[1]), cos(a[0])};
    double wo[3] = {sin(a[2]) * cos(a[3]), sin(a[2]) * sin(a[3]), cos(a[2])};
    double h[3];
    double norm;
    double th;
    double ph;
    double t[3];
    double b[3];
    double td;
    double pd;
    double x;
    size_t i;
    size_t j;
    size_t k;
    for (k = 0; k < 3; k++) {
        h[k] = wi[k] + wo[k];
    }
    norm = sqrt(dot(h, h));
    for (k = 0; k < 3; k++) {
        h[k] /= norm;
    }
    th = acos(fmin(1.0, h[2]));
    ph = atan2(h[1], h[0]);
    t[0] = cos(th) * cos(ph);
    t[1] = cos(th) * sin(ph);
    t[2] = -sin(th);
    b[0] = -sin(ph);
    b[1] = cos(ph);
    b[2] = 0.0;
    td = acos(fmax(-1.0, fmin(1.0, dot(wi, h))));
    pd = atan2(dot(wi, b), dot(wi, t));
    if (pd < 0.0) {
        pd += BF__PI;
    }
    x = sqrt(th / BF__PI_2) * 90.0;
    i = x < 89.0 ? (size_t)x : 89;
    x = td / BF__PI_2 * 90.0;
    j = x < 89.0 ? (size_t)x : 89;
    x = pd / BF__PI * 180.0;
    k = x < 179.0 ? (size_t)x : 179;
    return cell(i, j, k);
}

/* The half and difference angles of the centre of cell (i, j, k). */
static void centre_angles(size_t i, size_t j, size_t k, double *th,
                          double *td, double *pd)
{
    *th = ((i + 0.5) / 90.0) * ((i + 0.5) / 90.0) * BF__PI_2;
    *td = (j + 0.5) / 90.0 * BF__PI_2;
    *pd = (k + 0.5) / 180.0 * BF__PI;
}

/* A random configuration well inside a random cell (index coordinates
 * 0.05 to 0.95 of a unit from its borders), random phi_h and, when swap,
 * phi_d on either side of pi (in and out swapped: the same cell by
 * reciprocity); its cell in *n. 0 when below the horizon. */
static int random_config(double a[4], size_t *n, int swap)
{
    size_t i = (size_t)(90.0 * drand48());
    size_t j = (size_t)(90.0 * drand48());
    size_t k = (size_t)(180.0 * drand48());
    double ui = i + 0.05 + 0.9 * drand48();
    double th = (ui / 90.0) * (ui / 90.0) * BF__PI_2;
    double td = (j + 0.05 + 0.9 * drand48()) / 90.0 * BF__PI_2;
    double pd = (k + 0.05 + 0.9 * drand48()) / 180.0 * BF__PI;
    double ph = (2.0 * drand48() - 1.0) * BF__PI;
    if (swap && drand48() < 0.5) {
        pd -= BF__PI; /* the other half: the same cell by reciprocity */
    }
    *n = cell(i, j, k);
    return from_half_diff(th, ph, td, pd, a);
}

/* ==== layout, scales, lookup ==== */

Test(merl, the_lookup_finds_the_cell_of_its_half_and_difference_angles)
{
    unsigned char *b = index_table(0);
    bf_merl *t = table_ok(b);
    size_t tried = 0;
    srand48(1);
    while (tried < 30000) {
        double a[4];
        double rgb[3];
        size_t n;
        size_t c;
        if (!random_config(a, &n, 1)) {
            continue;
        }
        tried++;
        cr_assert_eq(bf_merl_lookup(t, a[0], a[1], a[2], a[3], rgb), 1);
        for (c = 0; c < 3; c++) {
            cr_assert(rgb[c] == index_value(n, c),
                      "(%.17g, %.17g, %.17g, %.17g) channel %zu: cell %.0f, "
                      "expected %zu", a[0], a[1], a[2], a[3], c,
                      rgb[c] / scale[c] - (double)(c * N_CELLS), n);
        }
        /* the dot-product route agrees */
        cr_assert_eq(cell_of(a), n);
    }
    bf_merl_free(t);
    free(b);
}

Test(merl, swapping_incidence_and_view_finds_the_same_cell)
{
    /* reciprocity [MERL]: (o, i) has phi_d + pi, the same cell */
    unsigned char *b = index_table(0);
    bf_merl *t = table_ok(b);
    size_t k;
    srand48(2);
    for (k = 0; k < 20000; k++) {
        double a[4];
        double x[3];
        double y[3];
        size_t n;
        if (!random_config(a, &n, 1)) {
            continue;
        }
        bf_merl_lookup(t, a[0], a[1], a[2], a[3], x);
        bf_merl_lookup(t, a[2], a[3], a[0], a[1], y);
        cr_assert(x[0] == y[0] && x[1] == y[1] && x[2] == y[2]);
    }
    bf_merl_free(t);
    free(b);
}

Test(merl, special_configurations_land_in_their_cells)
{
    unsigned char *b = index_table(0);
    bf_merl *t = table_ok(b);
    double rgb[3];
    /* normal incidence and view: theta_h = theta_d = 0, phi_d = 0 */
    cr_assert_eq(bf_merl_lookup(t, 0.0, 0.0, 0.0, 0.0, rgb), 1);
    cr_assert_eq(rgb[0], index_value(0, 0));
    /* retro-reflection at theta: h = omega_i, theta_h = theta, theta_d =
     * 0: i = floor(sqrt(0.6 / (pi/2)) 90) = 55 (0.6/(pi/2) = 0.38197,
     * sqrt = 0.61804, x 90 = 55.62) */
    cr_assert_eq(bf_merl_lookup(t, 0.6, 1.0, 0.6, 1.0, rgb), 1);
    cr_assert_eq(rgb[0] / scale[0] >= (double)cell(55, 0, 0) &&
                     rgb[0] / scale[0] < (double)cell(56, 0, 0),
                 1);
    /* below the horizon or not finite: no lookup */
    cr_assert_eq(bf_merl_lookup(t, 1.6, 0.0, 0.2, 0.0, rgb), 0);
    cr_assert(isnan(rgb[0]) && isnan(rgb[1]) && isnan(rgb[2]));
    cr_assert_eq(bf_merl_lookup(t, 0.2, NAN, 0.2, 0.0, rgb), 0);
    cr_assert_eq(bf_merl_lookup(t, -0.1, 0.0, 0.2, 0.0, rgb), 0);
    cr_assert_eq(bf_merl_lookup(t, 0.2, 0.0, 0.2, INFINITY, rgb), 0);
    bf_merl_free(t);
    free(b);
}

Test(merl, a_negative_cell_is_invalid_and_never_clamped)
{
    unsigned char *b = index_table(1);
    bf_merl *t = table_ok(b);
    bf_dataset *ds = NULL;
    bf_error err;
    double at[8];
    double rgb[3];
    size_t n[2];
    size_t k = 0;
    srand48(3);
    /* one configuration in an invalid cell, one in a valid one */
    while (k < 2) {
        if (random_config(at + 4 * k, &n[k], 1) &&
            (n[k] % 7 == 3) == (k == 0)) {
            k++;
        }
    }
    cr_assert_eq(bf_merl_lookup(t, at[0], at[1], at[2], at[3], rgb), 0);
    cr_assert_eq(rgb[2], -1.0 * scale[2], "the negative value is kept");
    cr_assert_eq(bf_merl_dataset(t, 2, at, "m", NAME, &ds, &err), BF_OK,
                 "%s", err.msg);
    cr_assert_not_null(bf_dataset_valid(ds, 0));
    for (k = 0; k < 3; k++) {
        cr_assert_eq(bf_dataset_valid(ds, 0)[k], 0);
        cr_assert_eq(bf_dataset_valid(ds, 0)[3 + k], 1);
        cr_assert_eq(bf_dataset_values(ds, 0)[3 + k], index_value(n[1], k));
    }
    cr_assert_eq(bf_dataset_values(ds, 0)[2], -1.0 * scale[2]);
    cr_assert_eq(bf_dataset_values(ds, 0)[0], index_value(n[0], 0));
    cr_assert_str_eq(bf_dataset_name(ds, 0), "m");
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 1), "G");
    cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_MERL);
    bf_dataset_free(ds);
    /* configurations outside the hemisphere are refused */
    at[6] = 1.7;
    cr_assert_eq(bf_merl_dataset(t, 2, at, "m", NAME, &ds, &err), BF_EINVAL);
    cr_assert_null(ds);
    cr_assert_str_eq(err.msg, "configuration 2 lies outside the hemisphere");
    cr_assert_eq(bf_merl_dataset(t, 0, at, "m", NAME, &ds, &err), BF_EINVAL);
    bf_merl_free(t);
    free(b);
}

Test(merl, every_valid_cell_gives_its_centre_which_maps_back_to_it)
{
    /* One configuration per valid cell above the horizon, in cell order,
     * at the cell's centre (merl.c): the count, the order and the values
     * follow from the independent geometry, and looking the centre up
     * finds its own cell again. */
    unsigned char *b = index_table(1);
    bf_merl *t = table_ok(b);
    bf_dataset *ds = NULL;
    bf_error err;
    const double *a;
    const double *v;
    size_t i;
    size_t j;
    size_t k;
    size_t q = 0;
    cr_assert_eq(bf_merl_dataset(t, 0, NULL, "all", NAME, &ds, &err), BF_OK,
                 "%s", err.msg);
    a = bf_dataset_angles(ds, 0);
    v = bf_dataset_values(ds, 0);
    cr_assert_null(bf_dataset_valid(ds, 0));
    for (i = 0; i < 90; i++) {
        for (j = 0; j < 90; j++) {
            for (k = 0; k < 180; k++) {
                size_t n = cell(i, j, k);
                double th;
                double td;
                double pd;
                double c[4];
                double rgb[3];
                size_t ch;
                centre_angles(i, j, k, &th, &td, &pd);
                if (n % 7 == 3 || !from_half_diff(th, 0.0, td, pd, c)) {
                    continue;
                }
                cr_assert_lt(q, bf_dataset_nconf(ds, 0));
                for (ch = 0; ch < 4; ch++) {
                    /* the azimuths of near-normal directions carry up to
                     * 1e-16 / sin(theta) of rounding */
                    bf_assert_abs(a[4 * q + ch], c[ch], 1e-9);
                }
                for (ch = 0; ch < 3; ch++) {
                    cr_assert_eq(v[3 * q + ch], index_value(n, ch));
                }
                cr_assert_eq(bf_merl_lookup(t, a[4 * q], a[4 * q + 1],
                                            a[4 * q + 2], a[4 * q + 3], rgb),
                             1);
                cr_assert_eq(rgb[0], index_value(n, 0), "cell %zu", n);
                q++;
            }
        }
    }
    cr_assert_eq(q, bf_dataset_nconf(ds, 0));
    /* 1,096,216 of the 1,458,000 cell centres lie above the horizon
     * (cos td cos th >= |sin td cos pd sin th|); every seventh cell
     * marked invalid leaves 939,619 (both counted by
     * tests/ref/merl_cells.py) */
    cr_assert_eq(q, 939619);
    bf_dataset_free(ds);
    bf_merl_free(t);
    free(b);
}

/* ==== files that are not MERL tables ==== */

static void expect_error(const void *buf, size_t len, int code,
                         const char *msg)
{
    bf_merl *t = (bf_merl *)&t; /* the reader must reset it */
    bf_error err;
    int rc = read_table(buf, len, &t, &err);
    cr_assert_eq(rc, code, "rc %d (%s)", rc, err.msg);
    cr_assert_null(t);
    cr_assert_eq(err.code, code);
    cr_assert_eq(err.line, 0, "a binary format reports byte offsets");
    cr_assert_str_eq(err.file, NAME);
    cr_assert_str_eq(err.msg, msg);
}

Test(merl, short_files_and_wrong_dimensions_are_errors)
{
    static const unsigned char dims_360[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                               104, 1, 0, 0};
    static const unsigned char dims_neg[12] = {255, 255, 255, 255, 90, 0, 0,
                                               0, 180, 0, 0, 0};
    unsigned char *b = new_table();
    expect_error(b, 0, BF_EPARSE, "empty file");
    expect_error(b, 5, BF_EPARSE,
                 "byte 5: the file ends inside the 12-byte header (three "
                 "int32 dimensions)");
    expect_error(dims_360, 12, BF_EPARSE,
                 "byte 0: dimensions 90 x 90 x 360; a MERL table has 90 x 90 "
                 "x 180 (theta_h, theta_d, phi_d)");
    expect_error(dims_neg, 12, BF_EPARSE,
                 "byte 0: dimensions -1 x 90 x 180; a MERL table has 90 x 90 "
                 "x 180 (theta_h, theta_d, phi_d)");
    expect_error("table.txt\n1 0.2 0.3", 20, BF_EPARSE,
                 "byte 0: dimensions 1818386804 x 2020879973 x 540084852; a "
                 "MERL table has 90 x 90 x 180 (theta_h, theta_d, phi_d)");
    free(b);
}

Test(merl, a_header_that_lies_about_the_size_is_refused_before_reading)
{
    unsigned char *b = new_table();
    unsigned char *longer = malloc(TABLE_BYTES + 8);
    expect_error(b, 1000, BF_EPARSE,
                 "byte 1000: the file has 1000 bytes, but its dimensions 90 "
                 "x 90 x 180 imply 34992012 (3 x 1458000 float64 after the "
                 "header)");
    expect_error(b, TABLE_BYTES - 1, BF_EPARSE,
                 "byte 34992011: the file has 34992011 bytes, but its "
                 "dimensions 90 x 90 x 180 imply 34992012 (3 x 1458000 "
                 "float64 after the header)");
    memcpy(longer, b, TABLE_BYTES);
    memset(longer + TABLE_BYTES, 0, 8);
    expect_error(longer, TABLE_BYTES + 8, BF_EPARSE,
                 "byte 34992012: the file has 34992020 bytes, but its "
                 "dimensions 90 x 90 x 180 imply 34992012 (3 x 1458000 "
                 "float64 after the header)");
    free(longer);
    free(b);
}

Test(merl, a_value_that_is_not_finite_is_an_error_at_its_byte)
{
    unsigned char *b = new_table();
    set_raw(b, 1, 12345, NAN);
    /* byte 12 + 8 (1458000 + 12345) = 11762772 */
    expect_error(b, TABLE_BYTES, BF_EPARSE,
                 "byte 11762772: value 12346 of channel G (cell 12345) is "
                 "not a finite number");
    set_raw(b, 1, 12345, 0.0);
    set_raw(b, 2, N_CELLS - 1, -INFINITY);
    expect_error(b, TABLE_BYTES, BF_EPARSE,
                 "byte 34992004: value 1458000 of channel B (cell 1457999) is "
                 "not a finite number");
    free(b);
}

/* Writes len bytes of b to a new file; returns its path (static). */
static const char *write_file(const unsigned char *b, size_t len)
{
    static char path[512];
    FILE *fp;
    snprintf(path, sizeof path, "%s/table.binary", bf_test_tmpdir());
    fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(b, 1, len, fp), len);
    cr_assert_eq(fclose(fp), 0);
    return path;
}

static void remove_file(const char *path)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = '\0';
    unlink(path);
    rmdir(dir);
}

Test(merl, a_pipe_is_read_without_knowing_its_size)
{
    /* not seekable: the size is checked as the table is read */
    unsigned char *b = index_table(0);
    const char *path = write_file(b, TABLE_BYTES);
    char cmd[1024];
    bf_merl *t = NULL;
    bf_error err;
    FILE *fp;
    double rgb[3];
    snprintf(cmd, sizeof cmd, "cat '%s'", path);
    fp = popen(cmd, "r");
    cr_assert_eq(bf_merl_read(fp, NAME, &t, &err), BF_OK, "%s", err.msg);
    pclose(fp);
    cr_assert_eq(bf_merl_lookup(t, 0.0, 0.0, 0.0, 0.0, rgb), 1);
    cr_assert_eq(rgb[1], index_value(0, 1));
    bf_merl_free(t);
    snprintf(cmd, sizeof cmd, "head -c 5000 '%s'", path);
    fp = popen(cmd, "r");
    cr_assert_eq(bf_merl_read(fp, NAME, &t, &err), BF_EPARSE);
    pclose(fp);
    cr_assert_null(t);
    cr_assert_str_eq(err.msg, "byte 5000: the file ends early; its "
                              "dimensions 90 x 90 x 180 imply 34992012 "
                              "bytes");
    snprintf(cmd, sizeof cmd, "cat '%s'; printf x", path);
    fp = popen(cmd, "r");
    cr_assert_eq(bf_merl_read(fp, NAME, &t, &err), BF_EPARSE);
    pclose(fp);
    cr_assert_str_eq(err.msg, "byte 34992012: data after the table (its "
                              "dimensions 90 x 90 x 180 imply 34992012 "
                              "bytes)");
    remove_file(path);
    free(b);
}

Test(merl, a_file_on_disk_loads_and_a_directory_does_not)
{
    unsigned char *b = index_table(0);
    const char *path = write_file(b, TABLE_BYTES);
    char saved[512];
    bf_merl *t = NULL;
    bf_error err;
    bf_format f = BF_FORMAT_AUTO;
    double rgb[3];
    snprintf(saved, sizeof saved, "%s", path);
    cr_assert_eq(bf_merl_load(saved, &t, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(bf_merl_lookup(t, 0.0, 0.0, 0.0, 0.0, rgb), 1);
    cr_assert_eq(rgb[2], index_value(0, 2));
    bf_merl_free(t);
    cr_assert_eq(bf_format_detect(saved, &f, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(f, BF_FORMAT_MERL);
    remove_file(saved);
    path = bf_test_tmpdir();
    cr_assert_eq(bf_merl_load(path, &t, &err), BF_EIO);
    cr_assert_null(t);
    cr_assert_str_eq(err.msg, "is a directory, not a data file");
    rmdir(path);
    free(b);
}

/* ==== analytic tables fitted back ==== */

/* Sets every channel of cell n to the BRDF value f (raw = f / scale). */
static void set_brdf(unsigned char *b, size_t n, double f)
{
    size_t c;
    for (c = 0; c < 3; c++) {
        set_raw(b, c, n, f / scale[c]);
    }
}

/* Models with a fitted parameter whose grid search is cheap enough here
 * (WNO-R's two-parameter quadrature is fitted back in test_convert.c). */
static int cheap_fitted(const bf_model_type *type)
{
    size_t j;
    int fitted = 0;
    for (j = 0; j < type->p; j++) {
        fitted |= type->param[j].fitted;
    }
    return fitted && type != bf_model_wno_r;
}

/* The geometry of n configurations in the measurement frame. */
static bf_geom *geoms(size_t n, const double *a)
{
    bf_geom *g = malloc(n * sizeof *g);
    size_t k;
    for (k = 0; k < n; k++) {
        g[k] = bf_geom_from_measurement(a[4 * k], a[4 * k + 1], a[4 * k + 2],
                                        a[4 * k + 3]);
    }
    return g;
}

/* Random configurations with zeniths up to 80 deg (cos theta_i > 0.17,
 * so BRDF = radiance / cos theta_i stays moderate). */
#define N_RANDOM 300
#define ZENITH_MAX 1.3962634

static void random_configs(double *a, size_t *cells)
{
    size_t k = 0;
    while (k < N_RANDOM) {
        if (random_config(a + 4 * k, &cells[k], 0) && a[4 * k] < ZENITH_MAX &&
            a[4 * k + 2] < ZENITH_MAX) {
            k++;
        }
    }
}

Test(merl, models_are_fitted_back_exactly_at_cell_centres)
{
    /* An irregular set: the centres of random cells. Each cell holds the
     * model's BRDF at its centre, so the data are the model's values at
     * the configurations and the grid finds the known point exactly. */
    unsigned char *b = new_table();
    double at[4 * N_RANDOM];
    size_t cells[N_RANDOM];
    size_t m;
    srand48(4);
    {
        size_t k = 0;
        while (k < N_RANDOM) {
            size_t i = (size_t)(90.0 * drand48());
            size_t j = (size_t)(90.0 * drand48());
            size_t q = (size_t)(180.0 * drand48());
            double th;
            double td;
            double pd;
            centre_angles(i, j, q, &th, &td, &pd);
            if (from_half_diff(th, 0.0, td, pd, at + 4 * k) &&
                at[4 * k] < ZENITH_MAX && at[4 * k + 2] < ZENITH_MAX) {
                cells[k++] = cell(i, j, q);
            }
        }
    }
    for (m = 0; m < bf_model_count(); m++) {
        const bf_model_type *type = bf_model_get(m);
        if (type->kind != BF_MODEL_DIFFUSE) {
            continue; /* SPEC §9: fitted under SPEC §10, not max-normalised */
        }
        bf_geom *g = geoms(N_RANDOM, at);
        double f[N_RANDOM];
        double p[BF_MAX_PARAMS];
        bf_merl *t;
        bf_dataset *ds = NULL;
        bf_error err;
        bf_fit_result fit;
        size_t k;
        size_t j;
        if (!cheap_fitted(type)) {
            free(g);
            continue;
        }
        bf_test_grid_point(type, 0.37, p);
        bf_test_model_brdf(type, p, N_RANDOM, g, f);
        for (k = 0; k < N_RANDOM; k++) {
            set_brdf(b, cells[k], f[k]);
        }
        t = table_ok(b);
        cr_assert_eq(bf_merl_dataset(t, N_RANDOM, at, "m", NAME, &ds, &err),
                     BF_OK, "%s", err.msg);
        fit = bf_test_fit_one(ds, 0, type, &k);
        cr_assert_eq(k, N_RANDOM);
        for (j = 0; j < type->p; j++) {
            cr_assert_eq(fit.param[j], p[j], "%s %s: %.17g, expected %.17g",
                         type->name, type->param[j].name, fit.param[j],
                         p[j]);
        }
        cr_assert_lt(fit.lse, 1e-20, "%s", type->name);
        bf_dataset_free(ds);
        bf_merl_free(t);
        free(g);
    }
    free(b);
}

Test(merl, models_are_fitted_back_within_the_lookup_error_elsewhere)
{
    /* Random configurations (phi_d in [0, pi), as the table stores it:
     * the models of BK's family are not reciprocal, and a swapped pair
     * would read the value of (o, i), which MERL's reciprocity assumes
     * equal): each reads the model's value at the centre of its cell.
     * With D* the model's normalised radiance at the
     * configurations (known parameters p*) and D the data's, the lookup
     * error is delta = D - D*: the model's change from a configuration to
     * its cell's centre, at most half a cell away in theta_h, theta_d and
     * phi_d. The grid holds p*, so the optimum p^ has
     *   |L(p^) - D|^2 = LSE(p^) <= LSE(p*) = |delta|^2,
     * and |L(p^) - L(p*)| <= |L(p^) - D| + |D - L(p*)| <= 2 |delta|
     * (triangle inequality; L normalised curves, |.| the Euclidean norm
     * over the K configurations). Asserted for every model, with 1e-9 of
     * slack for the kernels' rounding (src/fit/kernels.c); and p^ must be
     * among the grid points whose curves lie that close to L(p*), which
     * the test lists by scanning the grid. */
    unsigned char *b = new_table();
    double at[4 * N_RANDOM];
    size_t cells[N_RANDOM];
    bf_geom *g;
    size_t m;
    srand48(5);
    random_configs(at, cells);
    g = geoms(N_RANDOM, at);
    for (m = 0; m < bf_model_count(); m++) {
        const bf_model_type *type = bf_model_get(m);
        if (type->kind != BF_MODEL_DIFFUSE) {
            continue; /* SPEC §9: fitted under SPEC §10, not max-normalised */
        }
        bf_fit_workspace *w = bf_fit_alloc(N_RANDOM);
        double p[BF_MAX_PARAMS];
        double star[N_RANDOM];
        double data[N_RANDOM];
        double f;
        double delta = 0.0;
        double dist;
        size_t sel[N_RANDOM];
        size_t k;
        size_t i;
        size_t j = 0;
        size_t admissible = 0;
        int found = 0;
        bf_merl *t;
        bf_dataset *ds = NULL;
        bf_error err;
        bf_fit_result fit;
        bf_study_spec spec;
        bf_target target = {0, BF_CHANNEL_MEAN, 0};
        if (!cheap_fitted(type)) {
            bf_fit_free(w);
            continue;
        }
        bf_test_grid_point(type, 0.37, p);
        /* each configuration's cell holds the model at the cell's centre */
        for (k = 0; k < N_RANDOM; k++) {
            size_t n = cells[k];
            double th;
            double td;
            double pd;
            double c[4];
            bf_geom gc;
            centre_angles(n / (180 * 90), (n / 180) % 90, n % 180, &th, &td,
                          &pd);
            cr_assert(from_half_diff(th, 0.0, td, pd, c));
            gc = bf_geom_from_measurement(c[0], c[1], c[2], c[3]);
            bf_test_model_brdf(type, p, 1, &gc, &f);
            set_brdf(b, n, f);
        }
        t = table_ok(b);
        cr_assert_eq(bf_merl_dataset(t, N_RANDOM, at, "m", NAME, &ds, &err),
                     BF_OK, "%s", err.msg);
        fit = bf_test_fit_one(ds, 0, type, &k);
        cr_assert_eq(k, N_RANDOM);
        /* D*, D and |delta| */
        cr_assert_eq(bf_model_eval(type, p, N_RANDOM, g, star), BF_OK);
        cr_assert_eq(bf_normalise(N_RANDOM, star, star), BF_OK);
        memset(&spec, 0, sizeof spec);
        spec.data = ds;
        bf_select_init(&spec.select);
        spec.targets = &target;
        spec.n_targets = 1;
        cr_assert_eq(bf_study_target_data(&spec, 0, sel, &k, data, &err),
                     BF_OK);
        for (k = 0; k < N_RANDOM; k++) {
            delta += (data[k] - star[k]) * (data[k] - star[k]);
        }
        delta = sqrt(delta);
        cr_assert_gt(delta, 0.0, "%s: the lookup moved nothing",
                     type->name);
        cr_assert_eq(bf_fit_lse(type, fit.param, N_RANDOM, g, star, w, &dist),
                     BF_OK);
        cr_assert_leq(sqrt(dist), 2.0 * delta + 1e-9,
                      "%s: |L(p^) - L(p*)| = %g > 2 |delta| = %g", type->name,
                      sqrt(dist), 2.0 * delta);
        /* p^ among the grid points within 2 |delta| of L(p*) */
        while (!type->param[j].fitted) {
            j++;
        }
        for (i = 0; i < type->param[j].grid_n; i++) {
            double q[BF_MAX_PARAMS];
            memcpy(q, p, sizeof q);
            q[j] = type->param[j].grid_lo +
                   type->param[j].grid_step * (double)i;
            if (bf_fit_lse(type, q, N_RANDOM, g, star, w, &dist) == BF_OK &&
                sqrt(dist) <= 2.0 * delta + 1e-9) {
                admissible++;
                found |= q[j] == fit.param[j];
            }
        }
        cr_assert(found, "%s: %s = %g is not within 2 |delta| = %g",
                  type->name, type->param[j].name, fit.param[j], 2 * delta);
        cr_assert_lt(admissible, type->param[j].grid_n,
                     "%s: the bound admits every grid point", type->name);
        bf_dataset_free(ds);
        bf_merl_free(t);
        bf_fit_free(w);
    }
    free(g);
    free(b);
}

/* Cells of the all-cells fit: one in 25 (the others negative, invalid),
 * so the test stays fast; bench/bench_merl.c fits every cell. */
#define EVERY 25

Test(merl, an_all_cells_table_is_fitted_back_exactly)
{
    /* every valid cell holds LFTG's BRDF at its centre: fitting every
     * valid cell (the paper's grid, about 40,000 configurations) finds
     * n_d exactly */
    const bf_model_type *type = bf_model_lftg;
    unsigned char *b = new_table();
    double p[BF_MAX_PARAMS];
    bf_geom *g = malloc(N_CELLS * sizeof *g);
    double *f = malloc(N_CELLS * sizeof *f);
    size_t *at = malloc(N_CELLS * sizeof *at);
    size_t n = 0;
    size_t i;
    size_t j;
    size_t k;
    bf_merl *t;
    bf_dataset *ds = NULL;
    bf_error err;
    bf_fit_result fit;
    bf_test_grid_point(type, 0.37, p);
    for (i = 0; i < 90; i++) {
        for (j = 0; j < 90; j++) {
            for (k = 0; k < 180; k++) {
                double th;
                double td;
                double pd;
                double c[4];
                centre_angles(i, j, k, &th, &td, &pd);
                /* grazing cells give BRDF = L / cos theta_i with cos ~ 0:
                 * leave the outermost zeniths out too (negative: invalid) */
                if (cell(i, j, k) % EVERY == 0 &&
                    from_half_diff(th, 0.0, td, pd, c) && c[0] < ZENITH_MAX) {
                    g[n] = bf_geom_from_measurement(c[0], c[1], c[2], c[3]);
                    at[n++] = cell(i, j, k);
                } else {
                    set_brdf(b, cell(i, j, k), -1.0);
                }
            }
        }
    }
    bf_test_model_brdf(type, p, n, g, f);
    for (k = 0; k < n; k++) {
        set_brdf(b, at[k], f[k]);
    }
    t = table_ok(b);
    free(b);
    free(g);
    free(f);
    free(at);
    cr_assert_eq(bf_merl_dataset(t, 0, NULL, "all", NAME, &ds, &err), BF_OK,
                 "%s", err.msg);
    cr_assert_eq(bf_dataset_nconf(ds, 0), n);
    fit = bf_test_fit_one(ds, 0, type, &k);
    cr_assert_eq(k, n);
    cr_assert_eq(fit.param[0], p[0], "n_d %.17g, expected %.17g",
                 fit.param[0], p[0]);
    cr_assert_lt(fit.lse, 1e-18);
    bf_dataset_free(ds);
    bf_merl_free(t);
}
