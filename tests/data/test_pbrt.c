/* test_pbrt.c: the pbrt-v2 / Cornell .brdf reader (src/data/pbrt.c) on
 * the five real Cornell files and on small in-memory files: layout,
 * names, the frame conversion on real data (SPEC §1.5), and every
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

#define NAME "m.brdf"

/* Cornell's files give angles with 6 decimals: 10 degrees is 0.174533. */
#define THETA_10 0.174533

static bf_dataset *load_cornell(const char *file)
{
    bf_dataset *ds = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_pbrt_load(bf_test_cornell_path(file), &ds, &err);
    cr_assert_eq(rc, BF_OK, "%s", bf_error_format(&err, msg, sizeof msg));
    return ds;
}

/* Reading text (a valid file; a malformed one: code, line, message). */
#define read_ok(text) bf_test_read_ok(bf_pbrt_read, NAME, (text))
#define expect_error(text, code, line, msg)                          \
    bf_test_expect_read_error(bf_pbrt_read, NAME, (text), strlen(text),    \
                              (code), (line), (msg))

/* ==== the real Cornell files ==== */

Test(pbrt, cornell_files_hold_1439_records_of_31_wavelengths)
{
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *ds = load_cornell(bf_test_cornell[f]);
        size_t c;
        cr_assert_eq(bf_dataset_count(ds), 1);
        cr_assert_eq(bf_dataset_nconf(ds, 0), 1439, "%s",
                     bf_test_cornell[f]); /* SOURCES.md */
        cr_assert_eq(bf_dataset_nchannels(ds, 0), 31);
        for (c = 0; c < 31; c++) {
            char name[16];
            snprintf(name, sizeof name, "%zu", 400 + 10 * c);
            cr_assert_eq(bf_dataset_wavelength(ds, 0, c), 400.0 + 10.0 * c);
            cr_assert_str_eq(bf_dataset_channel(ds, 0, c), name);
        }
        cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_PBRT);
        cr_assert_null(bf_dataset_valid(ds, 0));
        bf_dataset_free(ds);
    }
}

Test(pbrt, cornell_values_match_the_file_text)
{
    bf_dataset *ds = load_cornell("acryl_blue.brdf");
    const double *a = bf_dataset_angles(ds, 0);
    const double *v = bf_dataset_values(ds, 0);
    /* acryl_blue.brdf, comments and CRs removed, as one number per line:
     * record 1 = numbers 33..67, record 1439 = the last 35:
     *   0.872665 0.000000 0.573513 0.000000 0.014369 ... 0.000008
     *   1.396263 0.000000 1.379634 3.141593 24.972427 ... 21.668278 */
    cr_assert(a[0] == 0.872665 && a[1] == 0.0 && a[2] == 0.573513 &&
              a[3] == 0.0);
    cr_assert(v[0] == 0.014369 && v[30] == 0.000008);
    a += 4 * 1438;
    v += 31 * 1438;
    cr_assert(a[0] == 1.396263 && a[1] == 0.0 && a[2] == 1.379634 &&
              a[3] == 3.141593);
    cr_assert(v[0] == 24.972427 && v[30] == 21.668278);
    cr_assert_eq(bf_dataset_line(ds, 0), 10); /* `grep -n` */
    bf_dataset_free(ds);
}

Test(pbrt, cornell_names_come_from_the_description_comment)
{
    /* SOURCES.md's "header description" column; acryl_blue has none */
    static const char *const expect[BF_TEST_NCORNELL] = {
        "acryl_blue", "Cayman Metallic, High-gloss Paint",
        "Garnet Red, Medium-gloss Paint",
        "Krylon spray enamel 7205, \"True Blue\"; overcoat Plasti-kote 33 "
        "Glass Frosting Spray",
        "Ford Mystic lacquer (BASF, 2-2-95)"};
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *ds = load_cornell(bf_test_cornell[f]);
        cr_assert_str_eq(bf_dataset_name(ds, 0), expect[f]);
        bf_dataset_free(ds);
    }
}

Test(pbrt, brightest_value_at_theta_i_10_is_at_phi_s_0_after_conversion)
{
    /* SPEC §1.5: both directions point away from the surface, so the gloss
     * peak lies at phi_o - phi_i = pi, which the conversion maps to
     * Beckmann's specular direction phi_s = 0 (SPEC §1.2). */
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *ds = load_cornell(bf_test_cornell[f]);
        const double *a = bf_dataset_angles(ds, 0);
        const bf_geom *g = bf_dataset_geom(ds, 0);
        size_t best = SIZE_MAX;
        double top = -INFINITY;
        size_t k;
        for (k = 0; k < bf_dataset_nconf(ds, 0); k++) {
            double v;
            if (a[4 * k] == THETA_10 &&
                bf_dataset_value(ds, 0, k, BF_CHANNEL_MEAN, &v) && v > top) {
                top = v;
                best = k;
            }
        }
        cr_assert_neq(best, SIZE_MAX, "%s: no theta_i = 10 deg",
                      bf_test_cornell[f]);
        /* the file's phi_o - phi_i is pi to its 6 decimals (3.141593) */
        bf_assert_abs(a[4 * best + 3] - a[4 * best + 1], BF__PI, 5e-7);
        bf_assert_abs(g[best].phi_s, 0.0, 5e-7);
        cr_assert_eq(g[best].phi_i, BF__PI);
        cr_assert_eq(g[best].theta_i, THETA_10);
        bf_dataset_free(ds);
    }
}

/* ==== layout, comments, names ==== */

Test(pbrt, records_may_wrap_across_lines_and_comments_end_lines)
{
    bf_dataset *ds = read_ok("2 # two wavelengths\n"
                             "450.5 551\n"
                             "0.1 0.0 0.2 # record 1 wraps\n"
                             "3.0 0.25 -0.5\n"
                             "0.3 1.0 0.4 -2.0 1e-3 2.5E+1\n");
    const double *a = bf_dataset_angles(ds, 0);
    const double *v = bf_dataset_values(ds, 0);
    cr_assert_eq(bf_dataset_nconf(ds, 0), 2);
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 0), "450.5");
    cr_assert_str_eq(bf_dataset_channel(ds, 0, 1), "551");
    cr_assert(a[0] == 0.1 && a[1] == 0.0 && a[2] == 0.2 && a[3] == 3.0);
    cr_assert(a[4] == 0.3 && a[5] == 1.0 && a[6] == 0.4 && a[7] == -2.0);
    cr_assert(v[0] == 0.25 && v[1] == -0.5 && v[2] == 1e-3 && v[3] == 25.0);
    cr_assert_eq(bf_dataset_line(ds, 0), 3);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "m"); /* no description */
    bf_dataset_free(ds);
}

Test(pbrt, description_is_the_first_comment_block_ended_by_a_blank_line)
{
    bf_dataset *ds = read_ok("# Mystique data from Cornell University, PCG\n"
                             "#   Blue  lacquer\t\n"
                             "#\n"
                             "# (sample 2)\n"
                             "\n"
                             "# num wls\n"
                             "1\n"
                             "500\n"
                             "0.1 0 0.2 3 0.5\n");
    cr_assert_str_eq(bf_dataset_name(ds, 0), "Blue  lacquer, (sample 2)");
    bf_dataset_free(ds);
    /* a block that runs into the first number is a label, not a name */
    ds = read_ok("# num wls\n1\n500\n0.1 0 0.2 3 0.5\n");
    cr_assert_str_eq(bf_dataset_name(ds, 0), "m");
    bf_dataset_free(ds);
    /* only a provenance line: the file name */
    ds = read_ok("# Cornell University, Program of Computer Graphics\n\n"
                 "1 500 0.1 0 0.2 3 0.5\n");
    cr_assert_str_eq(bf_dataset_name(ds, 0), "m");
    bf_dataset_free(ds);
}

Test(pbrt, long_descriptions_are_cut_at_200_bytes_and_control_bytes_blanked)
{
    char text[1024];
    char line[301];
    bf_dataset *ds;
    memset(line, 'x', 300);
    line[300] = '\0';
    line[3] = '\x01';
    snprintf(text, sizeof text, "#%s\n\n1 500 0.1 0 0.2 3 0.5\n", line);
    ds = read_ok(text);
    cr_assert_eq(strlen(bf_dataset_name(ds, 0)), 200);
    cr_assert_eq(bf_dataset_name(ds, 0)[3], ' ');
    bf_dataset_free(ds);
}

Test(pbrt, a_zenith_rounded_past_pi_over_2_is_clamped_onto_it)
{
    bf_dataset *ds = read_ok("1 500 1.5707963268 0 0.2 3 0.5\n");
    cr_assert_eq(bf_dataset_angles(ds, 0)[0], BF__PI_2);
    bf_dataset_free(ds);
}

Test(pbrt, the_stream_name_may_be_null)
{
    bf_dataset *ds = NULL;
    bf_error err;
    FILE *fp = bf_test_memfile("1 500 0.1 0 0.2 3 0.5\n");
    cr_assert_eq(bf_pbrt_read(fp, NULL, &ds, &err), BF_OK);
    fclose(fp);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "");
    bf_dataset_free(ds);
}

/* ==== malformed input ==== */

Test(pbrt, empty_and_number_free_files_are_errors)
{
    expect_error("", BF_EPARSE, 0, "empty file");
    expect_error("\n\n  \n", BF_EPARSE, 0, "empty file");
    expect_error("# only\n# comments\n", BF_EPARSE, 0,
                 "no numbers (a .brdf file starts with its wavelength "
                 "count)");
}

Test(pbrt, garbage_and_bad_counts_name_the_field)
{
    expect_error("hello world\n", BF_EPARSE, 1,
                 "field 1 (wavelength count): not a decimal number: "
                 "\"hello\"");
    expect_error("# c\n2.5\n", BF_EPARSE, 2,
                 "field 1 (wavelength count): not an integer: \"2.5\"");
    expect_error("0\n", BF_EPARSE, 1,
                 "field 1 (wavelength count): out of range (must be 1 to "
                 "65536): \"0\"");
    expect_error("65537\n", BF_EPARSE, 1,
                 "field 1 (wavelength count): out of range (must be 1 to "
                 "65536): \"65537\"");
}

Test(pbrt, wavelengths_must_be_positive_increasing_and_complete)
{
    expect_error("3\n400 500\n", BF_EPARSE, 2,
                 "the file ends after 2 of its 3 wavelengths");
    expect_error("2\n500 400\n", BF_EPARSE, 2,
                 "field 2 (wavelength 2) = 400 after 500: wavelengths must "
                 "increase");
    expect_error("2 500 500\n", BF_EPARSE, 1,
                 "field 3 (wavelength 2) = 500 after 500: wavelengths must "
                 "increase");
    expect_error("1\n-5\n", BF_EPARSE, 2,
                 "field 1 (wavelength 1) = -5: a wavelength (nm) must be "
                 "positive");
    expect_error("1\nnan\n", BF_EPARSE, 2,
                 "field 1 (wavelength 1): not a finite number: \"nan\"");
}

Test(pbrt, the_numbers_must_form_whole_records)
{
    /* SPEC §8: (N - 1 - W) mod (4 + W) = 0, and at least one record */
    expect_error("2\n400 500\n", BF_EPARSE, 2,
                 "no records after the 2 wavelengths");
    expect_error("2\n400 500\n0.1 0 0.2 3.1 0.5\n", BF_EPARSE, 3,
                 "the file ends inside record 1 (from line 3): 5 of its "
                 "4 + 2 numbers");
    /* a header that lies about the count: 2 wavelengths but 1 value */
    expect_error("2\n400 500\n0.1 0.1 0.1 0.1 0.1\n0.1 0.1 0.1 0.1 0.1\n"
                 "0.1 0.1 0.1 0.1 0.1\n",
                 BF_EPARSE, 5,
                 "the file ends inside record 3 (from line 5): 3 of its "
                 "4 + 2 numbers");
}

Test(pbrt, nan_inf_and_hex_values_are_errors)
{
    expect_error("1 500\n0.1 0 0.2 3 nan\n", BF_EPARSE, 2,
                 "field 5 (value 1 of record 1): not a finite number: "
                 "\"nan\"");
    expect_error("1 500\ninf 0 0.2 3 0.5\n", BF_EPARSE, 2,
                 "field 1 (theta_i of record 1): not a finite number: "
                 "\"inf\"");
    expect_error("1 500\n0.1 0 0.2 3 0x1p3\n", BF_EPARSE, 2,
                 "field 5 (value 1 of record 1): hexadecimal numbers are "
                 "not accepted: \"0x1p3\"");
    expect_error("1 500\n0.1 0 0.2 3 1e999\n", BF_EPARSE, 2,
                 "field 5 (value 1 of record 1): out of range (overflows a "
                 "double): \"1e999\"");
}

Test(pbrt, angles_out_of_range_are_errors)
{
    expect_error("1 500\n0.1 0 1.6 3 0.5\n", BF_EPARSE, 2,
                 "field 3 (theta_o of record 1) = 1.6 outside [0, pi/2]");
    expect_error("1 500\n-0.1 0 0.2 3 0.5\n", BF_EPARSE, 2,
                 "field 1 (theta_i of record 1) = -0.1 outside [0, pi/2]");
    expect_error("1 500\n0.1 0 0.2 3 0.5\n0.1 7 0.2 3 0.5\n", BF_EPARSE, 3,
                 "field 2 (phi_i of record 2) = 7 outside [-2 pi, 2 pi]");
}

Test(pbrt, binary_bytes_are_errors)
{
    static const char bin[] = "1 500\n0.1 0\0 0.2 3 0.5\n";
    bf_test_expect_read_error(bf_pbrt_read, NAME, bin, sizeof bin - 1,
                              BF_EPARSE, 2,
                              "NUL byte at column 6 (binary file?)");
}

Test(pbrt, a_directory_and_a_missing_file_are_io_errors)
{
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    const char *dir = bf_test_tmpdir();
    cr_assert_eq(bf_pbrt_load(dir, &ds, &err), BF_EIO);
    cr_assert_null(ds);
    cr_assert_eq(err.line, 0);
    cr_assert_str_eq(err.file, dir);
    cr_assert_str_eq(err.msg, "is a directory, not a data file");
    rmdir(dir);
    cr_assert_eq(bf_pbrt_load("/nonexistent/x.brdf", &ds, &err), BF_EIO);
    cr_assert_str_eq(err.msg, "cannot open: No such file or directory");
}
