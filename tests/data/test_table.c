/* test_table.c: the configuration table reader (src/data/table.c) and the
 * line syntax shared by every loader (src/data/lineio.c): line ends, BOM,
 * blank lines, NUL bytes, long lines, strict numbers, opening paths. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "internal.h"
#include "support.h"

#define NAME "t.txt"

/* The 7 specular configurations of CURET (1-based), SPEC §1.4. */
static const size_t specular[] = {54, 97, 131, 161, 183, 196, 202};

/* Reads a table from len bytes; closes the stream. */
static int read_buf(const void *buf, size_t len, bf_table **t, bf_error *err)
{
    FILE *fp = bf_test_membuf(buf, len);
    int rc = bf_table_read(fp, NAME, t, err);
    fclose(fp);
    return rc;
}

/* Asserts that reading buf fails with code at line, piece in the message,
 * and leaves the output NULL. */
static void expect_error_buf(const void *buf, size_t len, int code, long line,
                             const char *piece)
{
    bf_table *t = (bf_table *)&t; /* non-NULL: the reader must reset it */
    bf_error err;
    int rc = read_buf(buf, len, &t, &err);
    cr_assert_eq(rc, code, "rc %d (%s), expected %d", rc, err.msg, code);
    cr_assert_null(t);
    cr_assert_eq(err.code, code);
    cr_assert_eq(err.line, line, "line %ld, expected %ld (%s)", err.line,
                 line, err.msg);
    cr_assert_str_eq(err.file, NAME);
    cr_assert_not_null(strstr(err.msg, piece), "message \"%s\" lacks \"%s\"",
                       err.msg, piece);
}

static void expect_error(const char *text, int code, long line,
                         const char *piece)
{
    expect_error_buf(text, strlen(text), code, line, piece);
}

/* Reads text that must be valid. */
static bf_table *read_ok(const char *text)
{
    bf_table *t = NULL;
    bf_error err;
    char msg[1024];
    int rc = read_buf(text, strlen(text), &t, &err);
    cr_assert_eq(rc, BF_OK, "%s", bf_error_format(&err, msg, sizeof msg));
    cr_assert_eq(err.code, BF_OK);
    cr_assert_not_null(t);
    return t;
}

static void expect_raw(const bf_table *t, size_t k, double tv, double pv,
                       double ti, double pi)
{
    double raw[4];
    bf_table_raw(t, k, raw);
    /* both sides are the correctly rounded value of the same decimal text */
    cr_assert(raw[0] == tv, "row %zu theta_v %.17g != %.17g", k, raw[0], tv);
    cr_assert(raw[1] == pv, "row %zu phi_v %.17g != %.17g", k, raw[1], pv);
    cr_assert(raw[2] == ti, "row %zu theta_i %.17g != %.17g", k, raw[2], ti);
    cr_assert(raw[3] == pi, "row %zu phi_i %.17g != %.17g", k, raw[3], pi);
}

/* ==== the real CURET table ==== */

Test(table, curet_table_loads_with_205_rows)
{
    bf_table *t = bf_test_load_table();
    cr_assert_eq(bf_table_size(t), BF_CURET_NCONF);
    bf_table_free(t);
}

Test(table, curet_raw_values_match_the_file_text)
{
    bf_table *t = bf_test_load_table();
    /* table.txt, read with `sed -n '1p;2p;205p'`:
     *   1     1.389566   -1.970402   1.374447   -1.570796
     *   2     0.981748    0.000000   1.374447    0.000000
     *   205   1.464020   -3.065729   1.357866   -0.153484 */
    expect_raw(t, 0, 1.389566, -1.970402, 1.374447, -1.570796);
    expect_raw(t, 1, 0.981748, 0.0, 1.374447, 0.0);
    expect_raw(t, 204, 1.464020, -3.065729, 1.357866, -0.153484);
    bf_table_free(t);
}

Test(table, curet_geometry_is_the_converted_raw_configuration)
{
    bf_table *t = bf_test_load_table();
    bf_geom g = bf_table_geom(t, 0);
    bf_geom h = bf_geom_from_curet(1.389566, -1.970402, 1.374447, -1.570796);
    cr_assert(g.theta_s == 1.389566 && g.theta_i == 1.374447);
    cr_assert(g.phi_s == h.phi_s && g.phi_i == h.phi_i);
    bf_table_free(t);
}

Test(table, curet_selection_keeps_198_non_specular_configurations)
{
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, BF__PI, sel);
    size_t j;
    size_t s;
    cr_assert_eq(n, 198);
    for (j = 1; j < n; j++) {
        cr_assert_gt(sel[j], sel[j - 1], "selection is increasing");
    }
    for (j = 0; j < n; j++) {
        for (s = 0; s < sizeof specular / sizeof specular[0]; s++) {
            cr_assert_neq(sel[j], specular[s] - 1,
                          "specular configuration %zu selected", specular[s]);
        }
    }
    bf_table_free(t);
}

Test(table, selection_with_a_smaller_max_theta_keeps_only_those_angles)
{
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    double max_theta = 1.2;
    size_t n = bf_table_select(t, max_theta, sel);
    size_t j;
    size_t expect = 0;
    size_t k;
    for (k = 0; k < BF_CURET_NCONF; k++) {
        double raw[4];
        bf_geom g = bf_table_geom(t, k);
        bf_table_raw(t, k, raw);
        if (!bf_geom_is_specular(&g) && raw[0] <= max_theta &&
            raw[2] <= max_theta) {
            expect++;
        }
    }
    cr_assert_lt(n, 198);
    cr_assert_gt(n, 0);
    cr_assert_eq(n, expect);
    for (j = 0; j < n; j++) {
        double raw[4];
        bf_table_raw(t, sel[j], raw);
        cr_assert_leq(raw[0], max_theta);
        cr_assert_leq(raw[2], max_theta);
    }
    bf_table_free(t);
}

Test(table, out_of_range_row_gives_nan_and_null_table_is_empty)
{
    bf_table *t = read_ok("1 0.5 0.1 0.6 0.2\n");
    double raw[4];
    bf_geom g = bf_table_geom(t, 1);
    bf_table_raw(t, 1, raw);
    cr_assert(isnan(g.theta_i) && isnan(g.theta_s));
    cr_assert(isnan(raw[0]) && isnan(raw[3]));
    cr_assert_eq(bf_table_size(NULL), 0);
    bf_table_free(t);
    bf_table_free(NULL);
}

/* ==== line syntax ==== */

static const char lf_text[] = "1 0.7313 1.2 0.5 -2.1\n"
                              "2 0.25 -0.5 1.1 3.0\n";

static void expect_same_as_lf(const bf_table *t)
{
    cr_assert_eq(bf_table_size(t), 2);
    expect_raw(t, 0, 0.7313, 1.2, 0.5, -2.1);
    expect_raw(t, 1, 0.25, -0.5, 1.1, 3.0);
}

Test(table, lf_file_gives_the_written_values)
{
    bf_table *t = read_ok(lf_text);
    expect_same_as_lf(t);
    bf_table_free(t);
}

Test(table, crlf_trailing_blanks_and_no_final_newline_read_like_lf)
{
    bf_table *t = read_ok("1 0.7313 1.2 0.5 -2.1  \t\r\n"
                          "2\t0.25\t-0.5 1.1 3.0   ");
    expect_same_as_lf(t);
    bf_table_free(t);
}

Test(table, cr_at_the_very_end_of_the_file_ends_the_last_line)
{
    bf_table *t = read_ok("1 0.7313 1.2 0.5 -2.1\r\n2 0.25 -0.5 1.1 3.0\r");
    expect_same_as_lf(t);
    bf_table_free(t);
}

Test(table, utf8_bom_at_the_start_is_skipped)
{
    bf_table *t = read_ok("\xEF\xBB\xBF"
                          "1 0.7313 1.2 0.5 -2.1\n2 0.25 -0.5 1.1 3.0\n");
    expect_same_as_lf(t);
    bf_table_free(t);
}

Test(table, utf8_bom_after_the_start_is_junk)
{
    expect_error("1 0.7313 1.2 0.5 -2.1\n\xEF\xBB\xBF"
                 "2 0.25 -0.5 1.1 3.0\n",
                 BF_EPARSE, 2, "field 1 (index)");
}

Test(table, partial_bom_is_ordinary_text)
{
    expect_error("\xEF\xBB"
                 "1 0.7313 1.2 0.5 -2.1\n",
                 BF_EPARSE, 1, "\\xEF\\xBB1");
}

Test(table, blank_lines_are_skipped_but_counted)
{
    bf_table *t = read_ok("\n  \n1 0.7313 1.2 0.5 -2.1\n\t\n\n"
                          "2 0.25 -0.5 1.1 3.0\n\n\n");
    expect_same_as_lf(t);
    bf_table_free(t);
    expect_error("\n\n1 0.7313 1.2 0.5 -2.1\n\n2 0.25 -0.5 1.1\n", BF_EPARSE,
                 5, "expected 5 numbers, found 4");
}

Test(table, lone_carriage_return_is_an_error)
{
    expect_error("1 0.7313 1.2 0.5 -2.1\r2 0.25 -0.5 1.1 3.0\r", BF_EPARSE, 1,
                 "carriage return");
    expect_error("1 0.7313 1.2 0.5 -2.1\n2 0.25 -0.5\r1.1 3.0\n", BF_EPARSE,
                 2, "carriage return");
}

Test(table, nul_byte_is_an_error_with_its_line)
{
    static const char buf[] = "1 0.7313 1.2 0.5 -2.1\n2 0.25\0 -0.5 1.1 3.0\n";
    expect_error_buf(buf, sizeof buf - 1, BF_EPARSE, 2, "NUL byte");
}

Test(table, line_longer_than_the_cap_is_an_error)
{
    size_t len = BF__LINE_MAX + 100;
    char *buf = malloc(len);
    const char *row = "1 0.7313 1.2 0.5 -2.1\n";
    cr_assert_not_null(buf);
    memcpy(buf, row, strlen(row));
    memset(buf + strlen(row), '7', len - strlen(row));
    expect_error_buf(buf, len, BF_EPARSE, 2, "line longer than");
    free(buf);
}

Test(table, line_of_exactly_the_cap_is_accepted)
{
    const char *row = "1 0.7313 1.2 0.5 -2.1";
    size_t len = BF__LINE_MAX + 1; /* the line, then its LF */
    char *buf = malloc(len);
    bf_table *t = NULL;
    bf_error err;
    cr_assert_not_null(buf);
    memset(buf, ' ', len);
    memcpy(buf, row, strlen(row));
    buf[len - 1] = '\n';
    cr_assert_eq(read_buf(buf, len, &t, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(bf_table_size(t), 1);
    bf_table_free(t);
    free(buf);
}

Test(table, empty_file_is_an_error_at_line_zero)
{
    expect_error("", BF_EPARSE, 0, "empty file");
    expect_error("\n \n\t\r\n", BF_EPARSE, 0, "empty file");
    expect_error("\xEF\xBB\xBF", BF_EPARSE, 0, "empty file");
}

/* ==== row checks ==== */

Test(table, wrong_number_of_fields_names_expected_and_found)
{
    expect_error("1 0.7313 1.2 0.5 -2.1\n2 0.25 -0.5 1.1\n", BF_EPARSE, 2,
                 "expected 5 numbers, found 4");
    expect_error("1 0.7313 1.2 0.5 -2.1 9\n", BF_EPARSE, 1,
                 "expected 5 numbers, found 6");
}

Test(table, index_out_of_order_is_an_error)
{
    expect_error("1 0.7313 1.2 0.5 -2.1\n3 0.25 -0.5 1.1 3.0\n", BF_EPARSE, 2,
                 "index 3 out of order: expected 2");
    expect_error("2 0.7313 1.2 0.5 -2.1\n", BF_EPARSE, 1,
                 "index 2 out of order: expected 1");
    expect_error("1 0.7313 1.2 0.5 -2.1\n1 0.25 -0.5 1.1 3.0\n", BF_EPARSE, 2,
                 "index 1 out of order");
}

Test(table, index_must_be_a_positive_integer)
{
    expect_error("1.5 0.7313 1.2 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 1 (index): not an integer: \"1.5\"");
    expect_error("-1 0.7313 1.2 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 1 (index): out of range");
    expect_error("99999999999999999999999 0.7313 1.2 0.5 -2.1\n", BF_EPARSE,
                 1, "field 1 (index): out of range");
}

Test(table, zenith_out_of_range_is_an_error)
{
    expect_error("1 1.6 1.2 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 2 (theta_v) = 1.6 outside [0, pi/2]");
    expect_error("1 0.7 1.2 -0.01 -2.1\n", BF_EPARSE, 1,
                 "field 4 (theta_i) = -0.01 outside [0, pi/2]");
}

Test(table, azimuth_out_of_range_is_an_error)
{
    expect_error("1 0.7 6.3 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v) = 6.3 outside [-2 pi, 2 pi]");
    expect_error("1 0.7 6.28 0.5 -6.3\n", BF_EPARSE, 1,
                 "field 5 (phi_i) = -6.3 outside [-2 pi, 2 pi]");
}

Test(table, zenith_within_tolerance_of_the_range_is_clamped)
{
    /* 1.5707963268 exceeds pi/2 by 5e-12; -1e-10 is below 0 */
    bf_table *t = read_ok("1 1.5707963268 0 -1e-10 0\n");
    double raw[4];
    bf_table_raw(t, 0, raw);
    cr_assert(raw[0] == BF__PI_2, "theta_v %.17g", raw[0]);
    cr_assert(raw[2] == 0.0, "theta_i %.17g", raw[2]);
    bf_table_free(t);
    /* 2e-9 above pi/2 is beyond the tolerance */
    expect_error("1 1.570796329 0 0 0\n", BF_EPARSE, 1, "outside [0, pi/2]");
}

/* ==== strict numbers ==== */

Test(table, non_numeric_field_is_named_and_quoted)
{
    expect_error("1 0.7 abc 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v): not a decimal number: \"abc\"");
}

Test(table, nan_is_not_accepted)
{
    expect_error("1 0.7 NaN 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v): not a finite number: \"NaN\"");
    expect_error("1 0.7 0.1 -nan 0.1\n", BF_EPARSE, 1,
                 "field 4 (theta_i): not a finite number");
}

Test(table, infinity_is_not_accepted)
{
    expect_error("1 0.7 0.1 0.5 -inf\n", BF_EPARSE, 1,
                 "field 5 (phi_i): not a finite number: \"-inf\"");
    expect_error("1 Infinity 0.1 0.5 0.1\n", BF_EPARSE, 1,
                 "field 2 (theta_v): not a finite number");
}

Test(table, hex_float_is_not_accepted)
{
    expect_error("1 0.7 0x1p-2 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v): hexadecimal numbers are not accepted: "
                 "\"0x1p-2\"");
}

Test(table, overflowing_exponent_is_out_of_range)
{
    expect_error("1 0.7 1e999 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v): out of range (overflows a double): "
                 "\"1e999\"");
}

Test(table, underflowing_exponent_reads_as_zero)
{
    bf_table *t = read_ok("1 0.7 1e-999 0.5 -2.1\n");
    double raw[4];
    bf_table_raw(t, 0, raw);
    cr_assert(raw[1] == 0.0);
    bf_table_free(t);
}

Test(table, trailing_junk_after_a_number_is_an_error)
{
    expect_error("1 0.7 1.5abc 0.5 -2.1\n", BF_EPARSE, 1,
                 "field 3 (phi_v): unexpected characters after the number: "
                 "\"1.5abc\"");
    expect_error("1 0.7 1,5 0.5 -2.1\n", BF_EPARSE, 1,
                 "unexpected characters after the number: \"1,5\"");
    expect_error("1 0.7 1e 0.5 -2.1\n", BF_EPARSE, 1,
                 "unexpected characters after the number: \"1e\"");
}

Test(table, decimal_forms_with_signs_points_and_exponents_are_accepted)
{
    bf_table *t = read_ok("+1 .5 -1. 5E-1 +0.5e+0\n");
    expect_raw(t, 0, 0.5, -1.0, 0.5, 0.5);
    bf_table_free(t);
}

Test(table, long_offending_text_is_truncated_in_the_message)
{
    bf_table *t = NULL;
    bf_error err;
    const char *text =
        "1 0.7 abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ 0.5 0\n";
    cr_assert_eq(read_buf(text, strlen(text), &t, &err), BF_EPARSE);
    cr_assert_not_null(strstr(err.msg, "\"abcdefghijklmnopqrstuvwx...\""),
                       "%s", err.msg);
    cr_assert_null(strstr(err.msg, "XYZ"));
}

Test(table, control_bytes_are_escaped_in_the_message)
{
    expect_error("1 0.7 \x01\x7f 0.5 0\n", BF_EPARSE, 1, "\"\\x01\\x7F\"");
}

/* ==== arguments, paths and reports ==== */

Test(table, null_report_is_allowed)
{
    bf_table *t = NULL;
    FILE *fp = bf_test_memfile("1 0.7 0.1\n");
    cr_assert_eq(bf_table_read(fp, NAME, &t, NULL), BF_EPARSE);
    cr_assert_null(t);
    fclose(fp);
}

Test(table, null_name_is_reported_as_stream)
{
    bf_table *t = NULL;
    bf_error err;
    FILE *fp = bf_test_memfile("");
    cr_assert_eq(bf_table_read(fp, NULL, &t, &err), BF_EPARSE);
    cr_assert_str_eq(err.file, BF__NONAME);
    fclose(fp);
}

Test(table, null_stream_or_output_is_invalid)
{
    bf_table *t = NULL;
    bf_error err;
    FILE *fp = bf_test_memfile(lf_text);
    cr_assert_eq(bf_table_read(NULL, NAME, &t, &err), BF_EINVAL);
    cr_assert_eq(bf_table_read(fp, NAME, NULL, &err), BF_EINVAL);
    cr_assert_eq(bf_table_load(NULL, &t, &err), BF_EINVAL);
    fclose(fp);
}

Test(table, nonexistent_path_is_an_io_error_with_the_system_reason)
{
    bf_table *t = NULL;
    bf_error err;
    const char *path = "/nonexistent-brdffit-dir/table.txt";
    cr_assert_eq(bf_table_load(path, &t, &err), BF_EIO);
    cr_assert_null(t);
    cr_assert_eq(err.code, BF_EIO);
    cr_assert_eq(err.line, 0);
    cr_assert_str_eq(err.file, path);
    cr_assert_not_null(strstr(err.msg, "No such file or directory"), "%s",
                       err.msg);
}

Test(table, directory_path_is_a_clear_io_error)
{
    bf_table *t = NULL;
    bf_error err;
    cr_assert_eq(bf_table_load(BF_CURET_DIR, &t, &err), BF_EIO);
    cr_assert_null(t);
    cr_assert_eq(err.line, 0);
    cr_assert_not_null(strstr(err.msg, "is a directory"), "%s", err.msg);
}

Test(table, character_device_is_rejected)
{
    bf_table *t = NULL;
    bf_error err;
    cr_assert_eq(bf_table_load("/dev/null", &t, &err), BF_EIO);
    cr_assert_not_null(strstr(err.msg, "not a regular file or pipe"), "%s",
                       err.msg);
}

Test(table, fifo_path_is_read_like_a_file)
{
    char dir[] = "/tmp/bf_fifo_XXXXXX";
    char path[64];
    bf_table *t = NULL;
    bf_error err;
    pid_t pid;
    int status = 0;
    int rc;
    cr_assert_not_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/table", dir);
    cr_assert_eq(mkfifo(path, 0600), 0);
    pid = fork();
    cr_assert_geq(pid, 0);
    if (pid == 0) {
        /* A fresh program, not a fork of the test: under valgrind a fork
         * carries Criterion's buffers, reported as lost when it exits. */
        execl("/bin/sh", "sh", "-c", "printf '%s' \"$1\" > \"$0\"", path,
              lf_text, (char *)NULL);
        _exit(127);
    }
    rc = bf_table_load(path, &t, &err);
    waitpid(pid, &status, 0);
    unlink(path);
    rmdir(dir);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "the writer failed");
    cr_assert_eq(rc, BF_OK, "%s", err.msg);
    expect_same_as_lf(t);
    bf_table_free(t);
}

Test(table, successful_load_clears_the_report)
{
    bf_table *t = NULL;
    bf_error err;
    memset(&err, 'x', sizeof err);
    cr_assert_eq(bf_table_load(bf_test_curet_path("table.txt"), &t, &err),
                 BF_OK);
    cr_assert_eq(err.code, BF_OK);
    cr_assert_eq(err.line, 0);
    cr_assert_str_eq(err.msg, "");
    bf_table_free(t);
}
