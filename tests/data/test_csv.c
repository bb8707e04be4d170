/* test_csv.c: brdffit's tidy CSV (src/data/csv.c) and its angles in
 * degrees (src/data/degrees.c): the bit-for-bit round trip of radians
 * through the fewest decimal digits, on every Cornell angle and on random
 * angles; the reader's syntax, materials and shared configuration sets;
 * the writer against a golden text; configuration lists; and every
 * malformed input with its exact code, line and message. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_run.h"
#include "internal.h"
#include "support.h"

#define NAME "data/my-sample.csv"

/* pi/180 rounded to a double: the plain conversion rad = deg * K. */
#define K_PLAIN 0.017453292519943295

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* rad -> text -> rad, bit for bit; returns the text's significant
 * digits. */
static int round_trip(double rad)
{
    char text[BF__DEGREES_MAX];
    double back = NAN;
    int digits = 0;
    int lead = 1;
    const char *p;
    cr_assert_eq(bf__format_degrees(rad, text), BF_OK, "%.17g", rad);
    cr_assert_eq(bf__parse_degrees(text, &back), BF__NUM_OK, "%s", text);
    cr_assert(same_bits(back, rad), "%.17g -> \"%s\" -> %.17g", rad, text,
              back);
    for (p = text; *p != '\0' && *p != 'e'; p++) {
        if (*p >= '1' && *p <= '9') {
            lead = 0;
        }
        digits += !lead && *p >= '0' && *p <= '9';
    }
    return digits;
}

/* 1 when some double d has fl(d * K_PLAIN) == rad: d * K is monotonic in
 * d, so only the doubles next to rad / K can. */
static int plain_reachable(double rad)
{
    double d = rad / K_PLAIN;
    int k;
    for (k = 0; k < 4; k++) {
        d = nextafter(d, -INFINITY);
    }
    for (k = 0; k < 9; k++) {
        if (d * K_PLAIN == rad) {
            return 1;
        }
        d = nextafter(d, INFINITY);
    }
    return 0;
}

/* Radians of a decimal text in degrees. */
static double rad(const char *deg)
{
    double r = NAN;
    cr_assert_eq(bf__parse_degrees(deg, &r), BF__NUM_OK);
    return r;
}

/* ==== degrees <-> radians ==== */

Test(degrees, every_cornell_angle_round_trips_bit_for_bit)
{
    size_t f;
    size_t unreachable = 0;
    size_t total = 0;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *ds = NULL;
        bf_error err;
        const double *a;
        size_t k;
        cr_assert_eq(bf_pbrt_load(bf_test_cornell_path(bf_test_cornell[f]),
                                  &ds, &err),
                     BF_OK);
        a = bf_dataset_angles(ds, 0);
        for (k = 0; k < 4 * bf_dataset_nconf(ds, 0); k++) {
            cr_assert_leq(round_trip(a[k]), 17);
            unreachable += !plain_reachable(a[k]);
            total++;
        }
        bf_dataset_free(ds);
    }
    cr_assert_eq(total, 5 * 4 * 1439);
    /* why the reader is not rad = deg * K: some Cornell angles are the
     * product of no double at all (degrees of their binade are 64 times
     * coarser; see degrees.c) */
    cr_assert_gt(unreachable, 0, "every Cornell angle is a plain product");
}

Test(degrees, random_angles_round_trip_bit_for_bit_in_at_most_17_digits)
{
    size_t k;
    size_t unreachable = 0;
    srand48(20240611);
    for (k = 0; k < 200000; k++) {
        double r;
        switch (k % 4) {
        case 0:
            r = (4.0 * drand48() - 2.0) * BF__PI; /* azimuths */
            break;
        case 1:
            r = drand48() * BF__PI_2; /* zeniths */
            break;
        case 2: /* magnitudes 1e-12 .. 6 */
            r = (drand48() < 0.5 ? -1.0 : 1.0) *
                pow(10.0, -12.0 + 12.78 * drand48());
            break;
        default: { /* the integral degrees of instruments */
            char deg[32];
            snprintf(deg, sizeof deg, "%ld", (long)(720.0 * drand48()) - 360);
            r = rad(deg);
            break;
        }
        }
        cr_assert_leq(round_trip(r), 17);
        unreachable += (k % 4 == 1) && !plain_reachable(r);
    }
    /* about one radian value in nine is no plain product (degrees.c) */
    cr_assert_gt(unreachable, 50000 / 12);
    cr_assert_lt(unreachable, 50000 / 7);
}

Test(degrees, round_angles_are_written_as_people_write_them)
{
    static const char *const text[] = {"0",  "-0",  "90",   "180",  "-180",
                                       "45", "360", "12.5", "0.001",
                                       "1e-05", "-7.25"};
    size_t k;
    for (k = 0; k < sizeof text / sizeof text[0]; k++) {
        double r;
        char out[BF__DEGREES_MAX];
        cr_assert_eq(bf__parse_degrees(text[k], &r), BF__NUM_OK);
        cr_assert_eq(bf__format_degrees(r, out), BF_OK);
        cr_assert_str_eq(out, text[k]);
    }
}

Test(degrees, the_writer_uses_the_fewest_digits)
{
    /* no decimal of one digit fewer -- the nearest one, or its
     * neighbours -- reads back into the same radians */
    size_t k;
    srand48(7);
    for (k = 0; k < 20000; k++) {
        double r = (4.0 * drand48() - 2.0) * BF__PI;
        char text[BF__DEGREES_MAX];
        int p = round_trip(r);
        double deg;
        int d;
        cr_assert_eq(bf__format_degrees(r, text), BF_OK);
        deg = strtod(text, NULL);
        for (d = -1; p > 1 && d <= 1; d++) {
            char shorter[64];
            double back;
            double m;
            int e;
            snprintf(shorter, sizeof shorter, "%.*e", p - 2, deg);
            m = strtod(shorter, NULL);
            e = (int)floor(log10(fabs(m))) - (p - 2);
            snprintf(shorter, sizeof shorter, "%.*e", p - 2,
                     m + d * pow(10.0, e));
            cr_assert_eq(bf__parse_degrees(shorter, &back), BF__NUM_OK);
            cr_assert(!same_bits(back, r), "%.17g: \"%s\" (%d digits) also "
                      "reads back, shorter than \"%s\"", r, shorter, p - 1,
                      text);
        }
    }
}

Test(degrees, the_reader_rounds_the_decimal_value_not_a_double)
{
    double r;
    /* 90 and 180 degrees are the doubles nearest pi/2 and pi */
    cr_assert_eq(bf__parse_degrees("90", &r), BF__NUM_OK);
    cr_assert(same_bits(r, BF__PI_2));
    cr_assert_eq(bf__parse_degrees("180.000", &r), BF__NUM_OK);
    cr_assert(same_bits(r, BF__PI));
    cr_assert_eq(bf__parse_degrees("-0", &r), BF__NUM_OK);
    cr_assert(same_bits(r, -0.0));
    /* digits past the 30th change nothing */
    cr_assert_eq(bf__parse_degrees("45.0000000000000000000000000000001",
                                   &r),
                 BF__NUM_OK);
    cr_assert(same_bits(r, BF__PI / 4.0));
    /* tiny and huge magnitudes are multiplied in plain double */
    cr_assert_eq(bf__parse_degrees("1e-250", &r), BF__NUM_OK);
    cr_assert(same_bits(r, 1e-250 * K_PLAIN));
    /* the strict syntax of bf__parse_double */
    cr_assert_eq(bf__parse_degrees("nan", &r), BF__NUM_NONFINITE);
    cr_assert_eq(bf__parse_degrees("1e999", &r), BF__NUM_RANGE);
    cr_assert_eq(bf__parse_degrees("12deg", &r), BF__NUM_TRAILING);
    cr_assert_eq(bf__format_degrees(NAN, (char[BF__DEGREES_MAX]){0}),
                 BF_EINVAL);
}

/* ==== reading ==== */

/* Reading text (a valid file; a malformed one: code, line, message). */
#define read_ok(text) bf_test_read_ok(bf_csv_read, NAME, (text))
#define expect_error(text, code, line, msg)                          \
    bf_test_expect_read_error(bf_csv_read, NAME, (text), strlen(text),    \
                              (code), (line), (msg))

Test(csv, one_material_is_named_after_the_file)
{
    bf_dataset *ds = read_ok("\xEF\xBB\xBF# my gonioreflectometer\r\n"
                             "Theta_I, phi_i ,theta_o,PHI_O,R,G\r\n"
                             "10,0,20,180,0.5,-0.25\r\n"
                             "\r\n"
                             "# a comment between rows\r\n"
                             "  60 , -90 , 0 , 45.5 , 1e-3 , 2\r\n");
    const double *a = bf_dataset_angles(ds, 0);
    const double *v = bf_dataset_values(ds, 0);
    cr_assert_eq(bf_dataset_count(ds), 1);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "my-sample");
    cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_CSV);
    cr_assert_eq(bf_dataset_nconf(ds, 0), 2);
    cr_assert_eq(bf_dataset_line(ds, 0), 3);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 1), "G");
    cr_assert(same_bits(a[0], rad("10")) && same_bits(a[3], BF__PI));
    cr_assert(same_bits(a[4], rad("60")) && same_bits(a[5], -BF__PI_2));
    cr_assert(a[6] == 0.0 && same_bits(a[7], rad("45.5")));
    cr_assert(v[0] == 0.5 && v[1] == -0.25 && v[2] == 1e-3 && v[3] == 2.0);
    cr_assert_null(bf_dataset_valid(ds, 0));
    /* the mirror direction of (10, 0) is (10, 180): phi_s = 0 */
    cr_assert(fabs(bf_dataset_geom(ds, 0)[0].phi_s) < 1e-15);
    bf_dataset_free(ds);
}

Test(csv, materials_come_in_order_of_first_appearance)
{
    bf_dataset *ds = read_ok("material,theta_i,phi_i,theta_o,phi_o,550nm\n"
                             "felt,10,0,20,180,1\n"
                             "\"paint, blue \"\"A\"\"\",10,0,20,180,2\n"
                             "felt,30,0,40,90,3\n"
                             "\"paint, blue \"\"A\"\"\",30,0,40,90,4\n"
                             "cork,10,0,20,180,5\n");
    cr_assert_eq(bf_dataset_count(ds), 3);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "felt");
    cr_assert_str_eq(bf_dataset_name(ds, 1), "paint, blue \"A\"");
    cr_assert_str_eq(bf_dataset_name(ds, 2), "cork");
    cr_assert_eq(bf_dataset_number(ds, 2), 3);
    cr_assert_eq(bf_dataset_line(ds, 1), 3);
    cr_assert_eq(bf_dataset_nconf(ds, 0), 2);
    cr_assert_eq(bf_dataset_values(ds, 0)[1], 3.0);
    cr_assert_eq(bf_dataset_values(ds, 1)[1], 4.0);
    cr_assert_eq(bf_dataset_nconf(ds, 2), 1);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 0), "550");
    cr_assert_eq(bf_dataset_wavelength(ds, 0, 0), 550.0);
    /* felt and paint list the same configurations; cork does not */
    cr_assert_eq(bf_dataset_set(ds, 0), bf_dataset_set(ds, 1));
    cr_assert_neq(bf_dataset_set(ds, 0), bf_dataset_set(ds, 2));
    cr_assert_eq(bf_dataset_angles(ds, 0), bf_dataset_angles(ds, 1));
    bf_dataset_free(ds);
}

Test(csv, an_empty_value_field_is_an_invalid_value)
{
    bf_dataset *ds = read_ok("theta_i,phi_i,theta_o,phi_o,R,G,B\n"
                             "10,0,20,180,1,,3\n"
                             "10,0,30,180,4,5,6\n");
    const unsigned char *ok = bf_dataset_valid(ds, 0);
    double v;
    cr_assert_not_null(ok);
    cr_assert(ok[0] && !ok[1] && ok[2] && ok[3] && ok[4] && ok[5]);
    cr_assert_eq(bf_dataset_value(ds, 0, 0, 1, &v), 0);
    cr_assert_eq(bf_dataset_value(ds, 0, 0, BF_CHANNEL_MEAN, &v), 0);
    cr_assert_eq(bf_dataset_value(ds, 0, 1, BF_CHANNEL_MEAN, &v), 1);
    cr_assert_eq(v, 5.0);
    bf_dataset_free(ds);
}

Test(csv, a_zenith_rounded_past_90_is_clamped_onto_it)
{
    bf_dataset *ds = read_ok("theta_i,phi_i,theta_o,phi_o,R\n"
                             "90.00000000001,0,0,0,1\n");
    cr_assert(same_bits(bf_dataset_angles(ds, 0)[0], BF__PI_2));
    bf_dataset_free(ds);
}

Test(csv, empty_and_header_only_files_are_errors)
{
    expect_error("", BF_EPARSE, 0, "empty file");
    expect_error("# nothing\n\n", BF_EPARSE, 0, "empty file");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n# no rows\n", BF_EPARSE, 0,
                 "no data rows after the header");
}

Test(csv, the_header_must_name_the_angles_then_channels)
{
    expect_error("phi_i,theta_i,theta_o,phi_o,R\n", BF_EPARSE, 1,
                 "the header must be [material,]theta_i,phi_i,theta_o,phi_o,"
                 "<channels>: column 1 is \"phi_i\"");
    expect_error("material,theta_i,phi_i,theta_s,phi_s,R\n", BF_EPARSE, 1,
                 "the header must be [material,]theta_i,phi_i,theta_o,phi_o,"
                 "<channels>: column 4 is \"theta_s\"");
    expect_error("10,0,20,180,0.5\n", BF_EPARSE, 1,
                 "the header must be [material,]theta_i,phi_i,theta_o,phi_o,"
                 "<channels>: column 1 is \"10\"");
    expect_error("theta_i,phi_i,theta_o,phi_o\n", BF_EPARSE, 1,
                 "the header names 0 channel columns after the angles (1 to "
                 "65536)");
    expect_error("theta_i,phi_i,theta_o,phi_o,R,\n", BF_EPARSE, 1,
                 "column 6: \"\" cannot name a channel");
    expect_error("theta_i,phi_i,theta_o,phi_o,R,Material\n", BF_EPARSE, 1,
                 "column 6: \"Material\" cannot name a channel");
    expect_error("theta_i,phi_i,theta_o,phi_o,R,G,R\n", BF_EPARSE, 1,
                 "column 7: the channel \"R\" is named twice");
    expect_error("theta_i,phi_i,theta_o,phi_o,550,550.0nm\n", BF_EPARSE, 1,
                 "column 6: the channel \"550.0nm\" is named twice");
}

Test(csv, rows_must_match_the_header)
{
    expect_error("theta_i,phi_i,theta_o,phi_o,R,G\n10,0,20,180,1\n",
                 BF_EPARSE, 2,
                 "expected 6 fields (the header's columns), found 5");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,0,20,180,1,2\n",
                 BF_EPARSE, 2,
                 "expected 5 fields (the header's columns), found 6");
    expect_error("material,theta_i,phi_i,theta_o,phi_o,R\n,10,0,20,180,1\n",
                 BF_EPARSE, 2, "field 1 (material): empty material name");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,,20,180,1\n", BF_EPARSE,
                 2, "field 2 (phi_i): empty angle");
}

Test(csv, nan_inf_and_angles_out_of_range_are_errors)
{
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,0,20,180,nan\n",
                 BF_EPARSE, 2, "field 5 (R): not a finite number: \"nan\"");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,0,inf,180,1\n",
                 BF_EPARSE, 2,
                 "field 3 (theta_o): not a finite number: \"inf\"");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,0,95,180,1\n", BF_EPARSE,
                 2, "field 3 (theta_o) = 95 outside [0, 90] degrees");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n-1,0,20,180,1\n", BF_EPARSE,
                 2, "field 1 (theta_i) = -1 outside [0, 90] degrees");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n10,0,20,361,1\n", BF_EPARSE,
                 2, "field 4 (phi_o) = 361 outside [-360, 360] degrees");
    expect_error("theta_i,phi_i,theta_o,phi_o,R\n0.17,0,20,180,1\n"
                 "10,0,20,3.14rad,1\n",
                 BF_EPARSE, 3,
                 "field 4 (phi_o): unexpected characters after the number: "
                 "\"3.14rad\"");
}

Test(csv, broken_quotes_are_errors)
{
    expect_error("material,theta_i,phi_i,theta_o,phi_o,R\n\"felt,10,0,20,180,"
                 "1\n",
                 BF_EPARSE, 2,
                 "field 1: quote not closed before the end of the line");
    expect_error("material,theta_i,phi_i,theta_o,phi_o,R\n\"felt\"x,10,0,20,"
                 "180,1\n",
                 BF_EPARSE, 2, "field 1: text after the closing quote");
}

Test(csv, a_directory_is_an_io_error)
{
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    const char *dir = bf_test_tmpdir();
    cr_assert_eq(bf_csv_load(dir, &ds, &err), BF_EIO);
    cr_assert_null(ds);
    cr_assert_str_eq(err.msg, "is a directory, not a data file");
    rmdir(dir);
}

/* ==== writing ==== */

/* A two-material dataset with a name that needs quotes, an unnamed
 * material (written under its number) and an invalid value. */
static bf_dataset *small_dataset(void)
{
    static const char *const ch[2] = {"R", "G,2"};
    double a1[8];
    double a2[4];
    const double v1[4] = {0.5, 0.25, 1e-3, -2.0};
    const unsigned char ok1[4] = {1, 1, 0, 1};
    const double v2[2] = {0.1, 3.0};
    bf_dataset *ds = bf_dataset_alloc();
    bf_material_desc d;
    size_t s1;
    size_t s2;
    a1[0] = rad("10");
    a1[1] = 0.0;
    a1[2] = rad("20");
    a1[3] = BF__PI;
    a1[4] = rad("60");
    a1[5] = -0.0;
    a1[6] = 0.872665; /* Cornell's 50.000021428783985 deg */
    a1[7] = rad("-90");
    a2[0] = 0.0;
    a2[1] = 0.0;
    a2[2] = BF__PI_2;
    a2[3] = rad("45");
    cr_assert_eq(bf_dataset_add_configs(ds, 2, a1, &s1, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_configs(ds, 1, a2, &s2, NULL), BF_OK);
    memset(&d, 0, sizeof d);
    d.name = " #1, \"blue\"";
    d.set = s1;
    d.n_channels = 2;
    d.channel = ch;
    d.values = v1;
    d.valid = ok1;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    d.name = NULL;
    d.number = 7;
    d.set = s2;
    d.values = v2;
    d.valid = NULL;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    return ds;
}

/* bf_csv_write into a string (static buffer). */
static const char *write_text(const bf_dataset *ds)
{
    static char buf[4096];
    FILE *fp = fmemopen(buf, sizeof buf, "w");
    cr_assert_not_null(fp);
    cr_assert_eq(bf_csv_write(ds, fp), BF_OK);
    cr_assert_eq(fclose(fp), 0);
    return buf;
}

Test(csv, the_writer_writes_the_golden_text)
{
    bf_dataset *ds = small_dataset();
    /* written by hand from the format: angles in the fewest digits,
     * values shortest, the invalid value empty, names quoted where the
     * reader would otherwise change them */
    cr_assert_str_eq(write_text(ds),
                     "material,theta_i,phi_i,theta_o,phi_o,R,\"G,2\"\n"
                     "\" #1, \"\"blue\"\"\",10,0,20,180,0.5,0.25\n"
                     "\" #1, \"\"blue\"\"\",60,-0,50.000021428783985,-90,,"
                     "-2\n"
                     "7,0,0,90,45,0.1,3\n");
    bf_dataset_free(ds);
}

Test(csv, what_the_writer_writes_reads_back_into_the_same_dataset)
{
    bf_dataset *ds = small_dataset();
    bf_dataset *back = read_ok(write_text(ds));
    /* the unnamed material comes back named "7" and numbered by position */
    cr_assert_str_eq(bf_dataset_name(back, 1), "7");
    cr_assert_eq(bf_dataset_number(back, 1), 2);
    cr_assert_str_eq(bf_dataset_name(back, 0), " #1, \"blue\"");
    bf_dataset_free(ds);
    bf_dataset_free(back);
}

Test(csv, random_configurations_and_values_round_trip_exactly)
{
    enum { N = 3000 };
    double *a = malloc(N * 4 * sizeof *a);
    double *v = malloc(N * sizeof *v);
    bf_dataset *ds = bf_dataset_alloc();
    bf_dataset *back;
    bf_material_desc d;
    char *text;
    size_t len = 0;
    FILE *fp;
    size_t k;
    srand48(99);
    for (k = 0; k < N; k++) {
        a[4 * k] = drand48() * BF__PI_2;
        a[4 * k + 1] = (2.0 * drand48() - 1.0) * 2.0 * BF__PI;
        a[4 * k + 2] = drand48() * BF__PI_2;
        a[4 * k + 3] = (2.0 * drand48() - 1.0) * BF__PI;
        v[k] = (drand48() - 0.1) * pow(10.0, 6.0 * drand48() - 3.0);
    }
    memset(&d, 0, sizeof d);
    d.name = "random";
    d.n_channels = 1;
    d.values = v;
    cr_assert_eq(bf_dataset_add_configs(ds, N, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    fp = open_memstream(&text, &len);
    cr_assert_eq(bf_csv_write(ds, fp), BF_OK);
    fclose(fp);
    back = read_ok(text);
    bf_test_expect_same_dataset(ds, back);
    free(text);
    free(a);
    free(v);
    bf_dataset_free(ds);
    bf_dataset_free(back);
}

Test(csv, the_writer_refuses_what_it_cannot_write_back)
{
    static const char *const other[2] = {"R", "B"};
    bf_dataset *ds = small_dataset();
    bf_dataset *two = bf_dataset_alloc();
    bf_material_desc d;
    double a[4] = {0.1, 0.0, 0.2, 3.0};
    double v[2] = {1.0, 2.0};
    FILE *fp;
    /* channels that differ between materials */
    memset(&d, 0, sizeof d);
    d.n_channels = 2;
    d.channel = other;
    d.values = v;
    cr_assert_eq(bf_dataset_add_configs(ds, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    fp = fopen("/dev/null", "w");
    cr_assert_eq(bf_csv_write(ds, fp), BF_EINVAL);
    /* two materials written under one name; a line break in a name */
    d.channel = NULL;
    d.name = "x";
    cr_assert_eq(bf_dataset_add_configs(two, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(two, &d, NULL), BF_OK);
    cr_assert_eq(bf_csv_write(two, fp), BF_OK);
    d.number = 5;
    cr_assert_eq(bf_dataset_add_material(two, &d, NULL), BF_OK);
    cr_assert_eq(bf_csv_write(two, fp), BF_EINVAL);
    bf_dataset_free(two);
    two = bf_dataset_alloc();
    d.name = "a\nb";
    cr_assert_eq(bf_dataset_add_configs(two, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(two, &d, NULL), BF_OK);
    cr_assert_eq(bf_csv_write(two, fp), BF_EINVAL);
    cr_assert_eq(bf_csv_write(NULL, fp), BF_EINVAL);
    fclose(fp);
    bf_dataset_free(two);
    bf_dataset_free(ds);
}

Test(csv, wavelength_channels_are_written_with_their_unit)
{
    static const char *const good[2] = {"550", "R"};
    static const char *const bad_nm[1] = {"550nm"};
    static const char *const bad_r[1] = {"R"};
    const double wl[2] = {550.0, NAN};
    double a[4] = {0.0, 0.0, 0.0, 0.0};
    double v[2] = {1.0, 2.0};
    bf_dataset *ds = bf_dataset_alloc();
    bf_material_desc d;
    FILE *fp = fopen("/dev/null", "w");
    memset(&d, 0, sizeof d);
    d.name = "m";
    d.n_channels = 2;
    d.channel = good;
    d.wavelength = wl;
    d.values = v;
    cr_assert_eq(bf_dataset_add_configs(ds, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    cr_assert_str_eq(write_text(ds),
                     "material,theta_i,phi_i,theta_o,phi_o,550nm,R\n"
                     "m,0,0,0,0,1,2\n");
    bf_dataset_free(ds);
    /* channels that would not read back as themselves */
    d.n_channels = 1;
    d.channel = bad_nm; /* a name that reads as a wavelength */
    d.wavelength = NULL;
    ds = bf_dataset_alloc();
    cr_assert_eq(bf_dataset_add_configs(ds, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    cr_assert_eq(bf_csv_write(ds, fp), BF_EINVAL);
    bf_dataset_free(ds);
    d.channel = bad_r; /* a wavelength not named by its wavelength */
    d.wavelength = wl;
    ds = bf_dataset_alloc();
    cr_assert_eq(bf_dataset_add_configs(ds, 1, a, &d.set, NULL), BF_OK);
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    cr_assert_eq(bf_csv_write(ds, fp), BF_EINVAL);
    bf_dataset_free(ds);
    fclose(fp);
}

Test(csv, a_write_error_is_an_io_error)
{
    bf_dataset *ds = small_dataset();
    FILE *fp = fopen("/dev/full", "w");
    cr_assert_not_null(fp);
    cr_assert_eq(bf_csv_write(ds, fp), BF_EIO);
    fclose(fp);
    bf_dataset_free(ds);
}

/* ==== configuration lists ==== */

static int configs_text(const char *text, double **a, size_t *n,
                        bf_error *err)
{
    FILE *fp = bf_test_memfile(text);
    int rc = bf_configs_read(fp, "at.csv", a, n, err);
    fclose(fp);
    return rc;
}

Test(configs, columns_may_come_in_any_order_and_others_are_ignored)
{
    double *a = NULL;
    size_t n = 0;
    bf_error err;
    cr_assert_eq(configs_text("# where to sample\n"
                              "note,phi_o,theta_o,phi_i,theta_i,R\n"
                              "anything,180,20,0,10,x\n"
                              ",90,40,-90,30,\n",
                              &a, &n, &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(n, 2);
    cr_assert(same_bits(a[0], rad("10")) && a[1] == 0.0 &&
              same_bits(a[2], rad("20")) && same_bits(a[3], BF__PI));
    cr_assert(same_bits(a[4], rad("30")) && same_bits(a[5], -BF__PI_2) &&
              same_bits(a[6], rad("40")) && same_bits(a[7], BF__PI_2));
    free(a);
}

Test(configs, malformed_lists_are_errors)
{
    static const struct {
        const char *text;
        long line;
        const char *msg;
    } bad[] = {
        {"", 0, "empty file"},
        {"theta_i,phi_i,theta_o\n10,0,20\n", 1,
         "the header has no phi_o column (a configuration list names "
         "theta_i, phi_i, theta_o, phi_o)"},
        {"theta_i,phi_i,theta_o,phi_o,THETA_I\n", 1,
         "columns 1 and 5 are both theta_i"},
        {"theta_i,phi_i,theta_o,phi_o\n", 0,
         "no configurations after the header"},
        {"theta_i,phi_i,theta_o,phi_o\n10,0,20\n", 2,
         "expected 4 fields (the header's columns), found 3"},
        {"theta_i,phi_i,theta_o,phi_o\n10,0,91,0\n", 2,
         "field 3 (theta_o) = 91 outside [0, 90] degrees"},
    };
    size_t k;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        double *a = (double *)&a;
        size_t n = 99;
        bf_error err;
        cr_assert_eq(configs_text(bad[k].text, &a, &n, &err), BF_EPARSE,
                     "case %zu", k);
        cr_assert_null(a);
        cr_assert_eq(n, 0);
        cr_assert_eq(err.line, bad[k].line, "case %zu: %s", k, err.msg);
        cr_assert_str_eq(err.file, "at.csv");
        cr_assert_str_eq(err.msg, bad[k].msg);
    }
}
