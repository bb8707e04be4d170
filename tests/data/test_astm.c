/* test_astm.c: the ASTM E1392 reader (src/data/astm.c) on small in-memory
 * files in the layout of Cornell's RGB and spectral exports, and every
 * malformed input with its exact code, line and message. (No Cornell
 * .astm file is in shared/data; test_convert.c reads the Cornell .brdf
 * measurements back from an ASTM file written by an independent writer.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_run.h"
#include "internal.h"
#include "support.h"

#define NAME "paint.astm"

/* An RGB export in Cornell's layout: keyword lines, then VARS. */
static const char rgb[] =
    "FORMAT_ID \"ASTM E1392-96\"\n"
    "SOURCE \"Cornell University Program of Computer Graphics\"\n"
    "SAMPLE_NAME \"Krylon Blue\"\n"
    "NUM_POINTS 3\n"
    "VARS theta_i,phi_i,theta_s,phi_s,R,G,B\n"
    "0.872665,0.000000,0.573513,0.000000,0.0123,0.0456,-0.0007\n"
    "0.174533, 0.0 , 0.141539 ,3.141593,12.5,13.25,14\n"
    "1.396263,0,1.379634,-2.5,1e-3,2E-3,3.5e+0\n";

/* Reading text (a valid file; a malformed one: code, line, message). */
#define read_ok(text) bf_test_read_ok(bf_astm_read, NAME, (text))
#define expect_error(text, code, line, msg)                          \
    bf_test_expect_read_error(bf_astm_read, NAME, (text), strlen(text),    \
                              (code), (line), (msg))

/* The header of a 1-row RGB file with NUM_POINTS n, then rows. */
static const char *with_rows(const char *num_points, const char *rows)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "NUM_POINTS %s\nVARS theta_i,phi_i,theta_s,phi_s,R,G,B\n%s",
             num_points, rows);
    return text;
}

/* ==== what is read ==== */

Test(astm, an_rgb_export_gives_three_channels_and_the_sample_name)
{
    bf_dataset *ds = read_ok(rgb);
    const double *a = bf_dataset_angles(ds, 0);
    const double *v = bf_dataset_values(ds, 0);
    cr_assert_eq(bf_dataset_count(ds), 1);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "Krylon Blue");
    cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_ASTM);
    cr_assert_eq(bf_dataset_nconf(ds, 0), 3);
    cr_assert_eq(bf_dataset_nchannels(ds, 0), 3);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 0), "R");
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 2), "B");
    cr_assert(isnan(bf_dataset_wavelength(ds, 0, 0)));
    cr_assert_eq(bf_dataset_line(ds, 0), 6);
    /* the rows' text, blanks around fields removed */
    cr_assert(a[0] == 0.872665 && a[1] == 0.0 && a[2] == 0.573513 &&
              a[3] == 0.0);
    cr_assert(a[4] == 0.174533 && a[6] == 0.141539 && a[7] == 3.141593);
    cr_assert(a[11] == -2.5);
    cr_assert(v[0] == 0.0123 && v[1] == 0.0456 && v[2] == -0.0007);
    cr_assert(v[3] == 12.5 && v[5] == 14.0 && v[8] == 3.5);
    bf_dataset_free(ds);
}

Test(astm, the_angles_are_the_measurement_frame_of_spec_1_5)
{
    /* row 2: phi_s - phi_i = 3.141593 ~ pi, the mirror side: phi_s = 0
     * in Beckmann's frame after conversion */
    bf_dataset *ds = read_ok(rgb);
    const bf_geom *g = bf_dataset_geom(ds, 0);
    bf_assert_abs(g[1].phi_s, 0.0, 5e-7);
    cr_assert_eq(g[1].theta_s, 0.141539);
    bf_dataset_free(ds);
}

Test(astm, spectral_channels_are_wavelengths_named_by_their_number)
{
    bf_dataset *ds = read_ok("NUM_POINTS 1\n"
                             "VARS theta_i,phi_i,theta_s,phi_s,400nm,410 nm,"
                             "420.0,552.5NM\n"
                             "0.1,0,0.2,3,0.5,0.6,0.7,0.8\n");
    /* a bare number is a name, not a wavelength (libbsdf's rule) */
    static const char *const names[4] = {"400", "410", "420.0", "552.5"};
    static const double nm[4] = {400.0, 410.0, NAN, 552.5};
    size_t c;
    for (c = 0; c < 4; c++) {
        double w = bf_dataset_wavelength(ds, 0, c);
        cr_assert_str_eq(bf_dataset_channel(ds, 0, c), names[c]);
        cr_assert(w == nm[c] || (isnan(w) && isnan(nm[c])));
    }
    cr_assert_str_eq(bf_dataset_name(ds, 0), "paint"); /* no SAMPLE_NAME */
    bf_dataset_free(ds);
}

Test(astm, xyz_comments_blank_lines_crlf_and_any_case_vars)
{
    bf_dataset *ds = read_ok("# exported\r\n"
                             "\r\n"
                             "  NUM_POINTS   2\r\n"
                             "DATE 1999-03-02\r\n"
                             "VARS Theta_I,PHI_I,theta_s,phi_s,X,Y,Z\r\n"
                             "# rows\r\n"
                             "0.1,0,0.2,3,1,2,3\r\n"
                             "\r\n"
                             "0.2,0,0.3,3,4,5,6\r\n");
    cr_assert_eq(bf_dataset_nconf(ds, 0), 2);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 1), "Y");
    cr_assert_eq(bf_dataset_line(ds, 0), 7);
    bf_dataset_free(ds);
}

/* ==== malformed input ==== */

Test(astm, empty_files_and_missing_vars_are_errors)
{
    expect_error("", BF_EPARSE, 0, "empty file");
    expect_error("\n \n", BF_EPARSE, 0, "empty file");
    expect_error("NUM_POINTS 3\nSOURCE x\n", BF_EPARSE, 0,
                 "no VARS line (the header ends with VARS theta_i,phi_i,"
                 "theta_s,phi_s,<channels>)");
    expect_error("VARS theta_i,phi_i,theta_s,phi_s,R\n", BF_EPARSE, 1,
                 "VARS before NUM_POINTS (the header must give the number "
                 "of rows)");
}

Test(astm, garbage_is_not_a_header)
{
    expect_error("0.1,0,0.2,3,1\n", BF_EPARSE, 1,
                 "expected a header line \"KEYWORD value\" (the header ends "
                 "with VARS), found \"0.1,0,0.2,3,1\"");
    expect_error("NUM_POINTS 2\n\x01\xff garbage\n", BF_EPARSE, 2,
                 "expected a header line \"KEYWORD value\" (the header ends "
                 "with VARS), found \"\\x01\\xFF garbage\"");
}

Test(astm, num_points_must_be_one_whole_number)
{
    expect_error(with_rows("2.5", ""), BF_EPARSE, 1,
                 "NUM_POINTS must be a whole number >= 1, found \"2.5\"");
    expect_error(with_rows("0", ""), BF_EPARSE, 1,
                 "NUM_POINTS must be a whole number >= 1, found \"0\"");
    expect_error(with_rows("", ""), BF_EPARSE, 1,
                 "NUM_POINTS must be a whole number >= 1, found \"\"");
    expect_error("NUM_POINTS 1\nNUM_POINTS 1\n", BF_EPARSE, 2,
                 "NUM_POINTS given twice (first at line 1)");
    expect_error("SAMPLE_NAME a\nSAMPLE_NAME b\n", BF_EPARSE, 2,
                 "SAMPLE_NAME given twice");
}

Test(astm, a_num_points_that_lies_about_the_rows_is_an_error)
{
    /* fewer: reported at the NUM_POINTS line; more: at the extra row */
    expect_error(with_rows("3", "0.1,0,0.2,3,1,2,3\n0.1,0,0.2,3,1,2,3\n"),
                 BF_EPARSE, 1, "NUM_POINTS = 3 but the file has 2 rows");
    expect_error(with_rows("1", "0.1,0,0.2,3,1,2,3\n0.1,0,0.2,3,1,2,3\n"),
                 BF_EPARSE, 4, "more rows than NUM_POINTS = 1 (line 1)");
    /* a huge NUM_POINTS allocates nothing ahead of the rows */
    expect_error(with_rows("9223372036854775807", "0.1,0,0.2,3,1,2,3\n"),
                 BF_EPARSE, 1,
                 "NUM_POINTS = 9223372036854775807 but the file has 1 row");
}

Test(astm, vars_must_start_with_the_angles_and_name_channels_once)
{
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_r,phi_r,R\n",
                 BF_EPARSE, 2,
                 "VARS must start with theta_i,phi_i,theta_s,phi_s "
                 "(variable 3 is \"theta_r\")");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i\n", BF_EPARSE, 2,
                 "VARS must start with theta_i,phi_i,theta_s,phi_s "
                 "(variable 3 is \"\")");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s\n",
                 BF_EPARSE, 2,
                 "VARS names 0 channels after the angles (1 to 65536)");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s,R,,B\n",
                 BF_EPARSE, 2, "VARS variable 6 is empty");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s,R,G,R\n",
                 BF_EPARSE, 2, "VARS names the channel \"R\" twice");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s,550,550nm\n",
                 BF_EPARSE, 2, "VARS names the channel \"550\" twice");
    expect_error("NUM_POINTS 1\nVARS theta_i,phi_i,theta_s,phi_s,\"R\n",
                 BF_EPARSE, 2,
                 "field 5: quote not closed before the end of the line");
}

Test(astm, rows_must_have_the_vars_count_of_finite_numbers)
{
    expect_error(with_rows("1", "0.1,0,0.2,3,1,2\n"), BF_EPARSE, 3,
                 "expected 7 comma-separated numbers (VARS), found 6");
    expect_error(with_rows("1", "0.1 0 0.2 3 1 2 3\n"), BF_EPARSE, 3,
                 "expected 7 comma-separated numbers (VARS), found 1");
    expect_error(with_rows("1", "0.1,0,0.2,3,1,NaN,3\n"), BF_EPARSE, 3,
                 "field 6 (G): not a finite number: \"NaN\"");
    expect_error(with_rows("1", "0.1,0,0.2,3,1,-Infinity,3\n"), BF_EPARSE, 3,
                 "field 6 (G): not a finite number: \"-Infinity\"");
    expect_error(with_rows("1", "0.1,0,0.2,3,1,,3\n"), BF_EPARSE, 3,
                 "field 6 (G): not a decimal number: \"\"");
    expect_error(with_rows("1", "0.1,0,0.2,3,1,2,3x\n"), BF_EPARSE, 3,
                 "field 7 (B): unexpected characters after the number: "
                 "\"3x\"");
}

Test(astm, angles_out_of_range_are_errors)
{
    expect_error(with_rows("1", "1.6,0,0.2,3,1,2,3\n"), BF_EPARSE, 3,
                 "field 1 (theta_i) = 1.6 outside [0, pi/2]");
    expect_error(with_rows("1", "0.1,0,0.2,-6.3,1,2,3\n"), BF_EPARSE, 3,
                 "field 4 (phi_s) = -6.3 outside [-2 pi, 2 pi]");
}

Test(astm, a_directory_is_an_io_error)
{
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    const char *dir = bf_test_tmpdir();
    cr_assert_eq(bf_astm_load(dir, &ds, &err), BF_EIO);
    cr_assert_null(ds);
    cr_assert_eq(err.line, 0);
    cr_assert_str_eq(err.msg, "is a directory, not a data file");
    rmdir(dir);
}
