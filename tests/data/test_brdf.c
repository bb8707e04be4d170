/* test_brdf.c: the BRDF file reader (src/data/brdf.c) on CURET's abrdf.dat
 * and on small in-memory files. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "support.h"

#define NAME "b.dat"

static int read_text(const char *text, size_t n_conf, bf_brdf **b,
                     bf_error *err)
{
    FILE *fp = bf_test_memfile(text);
    int rc = bf_brdf_read(fp, NAME, n_conf, b, err);
    fclose(fp);
    return rc;
}

static bf_brdf *read_ok(const char *text, size_t n_conf)
{
    bf_brdf *b = NULL;
    bf_error err;
    int rc = read_text(text, n_conf, &b, &err);
    cr_assert_eq(rc, BF_OK, "%s:%ld: %s", err.file, err.line, err.msg);
    cr_assert_not_null(b);
    return b;
}

/* Asserts an error with code, line and piece of the message; *out NULL. */
static void expect_error(const char *text, size_t n_conf, int code,
                         long line, const char *piece)
{
    bf_brdf *b = (bf_brdf *)&b; /* non-NULL: the reader must reset it */
    bf_error err;
    int rc = read_text(text, n_conf, &b, &err);
    cr_assert_eq(rc, code, "rc %d (%s), expected %d", rc, err.msg, code);
    cr_assert_null(b);
    cr_assert_eq(err.code, code);
    cr_assert_eq(err.line, line, "line %ld, expected %ld (%s)", err.line,
                 line, err.msg);
    cr_assert_not_null(strstr(err.msg, piece), "message \"%s\" lacks \"%s\"",
                       err.msg, piece);
}

/* ==== CURET abrdf.dat ==== */

Test(brdf, curet_abrdf_has_61_samples_of_205_values)
{
    bf_brdf *b = bf_test_load_abrdf();
    size_t r;
    cr_assert_eq(bf_brdf_count(b), 61);
    cr_assert_eq(bf_brdf_nconf(b), BF_CURET_NCONF);
    for (r = 0; r < 61; r++) {
        cr_assert_eq(bf_brdf_sample(b, r), (int)r + 1);
        cr_assert_eq(bf_brdf_find(b, (int)r + 1), (long)r);
    }
    cr_assert_eq(bf_brdf_find(b, 0), -1);
    cr_assert_eq(bf_brdf_find(b, 62), -1);
    cr_assert_eq(bf_brdf_sample(b, 61), -1);
    cr_assert_null(bf_brdf_values(b, 61));
    bf_brdf_free(b);
}

Test(brdf, curet_abrdf_values_match_the_file_text)
{
    bf_brdf *b = bf_test_load_abrdf();
    const double *v1 = bf_brdf_values(b, 0);
    const double *v2 = bf_brdf_values(b, 1);
    const double *v4 = bf_brdf_values(b, 3);
    const double *v55 = bf_brdf_values(b, 54);
    const double *v61 = bf_brdf_values(b, 60);
    /* read with awk from abrdf.dat: row 1 fields 2, 3, 206 = 0.200 0.110
     * 0.862; row 2: 0.204 ... 0.850; row 61: 0.044 0.006 ... 0.157;
     * sample 4 value 192 = -0.009; sample 61 value 104 = -0.016 (the
     * minimum); sample 55 value 202 = 2.590 (the maximum, a specular
     * configuration). Exact: both sides round the same decimal text. */
    cr_assert(v1[0] == 0.200 && v1[1] == 0.110 && v1[204] == 0.862);
    cr_assert(v2[0] == 0.204 && v2[204] == 0.850);
    cr_assert(v61[0] == 0.044 && v61[1] == 0.006 && v61[204] == 0.157);
    cr_assert(v4[191] == -0.009);
    cr_assert(v61[103] == -0.016);
    cr_assert(v55[201] == 2.590);
    bf_brdf_free(b);
}

Test(brdf, curet_abrdf_has_29_negative_entries_in_minus_0_016_to_2_59)
{
    bf_brdf *b = bf_test_load_abrdf();
    size_t negative = 0;
    double lo = INFINITY;
    double hi = -INFINITY;
    size_t r;
    size_t k;
    for (r = 0; r < bf_brdf_count(b); r++) {
        const double *v = bf_brdf_values(b, r);
        for (k = 0; k < bf_brdf_nconf(b); k++) {
            cr_assert(isfinite(v[k]));
            negative += (v[k] < 0.0);
            lo = fmin(lo, v[k]);
            hi = fmax(hi, v[k]);
        }
    }
    /* SOURCES.md: "29 entries in the whole file are negative", values in
     * [-0.016, 2.59]; none among the 24 study samples. */
    cr_assert_eq(negative, 29);
    cr_assert(lo == -0.016, "min %.17g", lo);
    cr_assert(hi == 2.59, "max %.17g", hi);
    for (r = 0; r < BF_STUDY_NSAMPLES; r++) {
        const double *v = bf_brdf_values(b, (size_t)bf_brdf_find(
                                                b, bf_study_samples[r]));
        for (k = 0; k < BF_CURET_NCONF; k++) {
            cr_assert_geq(v[k], 0.0, "study sample %d",
                          bf_study_samples[r]);
        }
    }
    bf_brdf_free(b);
}

/* ==== small files ==== */

Test(brdf, negative_values_are_kept_as_measured)
{
    bf_brdf *b = read_ok("1 0.5 -0.016 0.25\n", 3);
    cr_assert(bf_brdf_values(b, 0)[1] == -0.016);
    bf_brdf_free(b);
}

Test(brdf, crlf_trailing_blanks_and_no_final_newline_read_like_lf)
{
    bf_brdf *a = read_ok("1 0.5 0.7313 0.25\n2 1.5 2.5 3.5\n", 3);
    bf_brdf *b = read_ok("1 0.5 0.7313 0.25   \r\n2 1.5 2.5 3.5 \t", 3);
    size_t r;
    cr_assert_eq(bf_brdf_count(b), 2);
    for (r = 0; r < 2; r++) {
        cr_assert_eq(bf_brdf_sample(a, r), bf_brdf_sample(b, r));
        cr_assert_arr_eq(bf_brdf_values(a, r), bf_brdf_values(b, r),
                         3 * sizeof(double));
    }
    bf_brdf_free(a);
    bf_brdf_free(b);
}

Test(brdf, rows_in_any_order_are_stored_by_sample_number)
{
    bf_brdf *b = read_ok("3 0.3 0.3\n1 0.1 0.1\n2 0.2 0.2\n", 2);
    cr_assert_eq(bf_brdf_sample(b, 0), 1);
    cr_assert_eq(bf_brdf_sample(b, 2), 3);
    cr_assert(bf_brdf_values(b, 0)[0] == 0.1);
    cr_assert(bf_brdf_values(b, 2)[1] == 0.3);
    cr_assert_eq(bf_brdf_find(b, 3), 2);
    bf_brdf_free(b);
}

Test(brdf, empty_file_is_an_error)
{
    expect_error("", 3, BF_EPARSE, 0, "empty file");
    expect_error("\n\n", 3, BF_EPARSE, 0, "empty file");
}

Test(brdf, too_few_values_name_expected_and_found)
{
    expect_error("1 0.5 0.5 0.5\n2 0.5 0.5\n", 3, BF_EPARSE, 2,
                 "expected 3 values after the sample number, found 2");
}

Test(brdf, too_many_values_name_expected_and_found)
{
    expect_error("1 0.5 0.5 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "expected 3 values after the sample number, found 4");
}

Test(brdf, wrong_configuration_count_on_curet_data_is_reported)
{
    /* abrdf.dat rows have 205 values; asking for 204 fails on line 1 */
    bf_brdf *b = NULL;
    bf_error err;
    int rc = bf_brdf_load(bf_test_curet_path("abrdf.dat"), 204, &b, &err);
    cr_assert_eq(rc, BF_EPARSE);
    cr_assert_null(b);
    cr_assert_eq(err.line, 1);
    cr_assert_not_null(strstr(err.msg, "expected 204 values after the "
                                       "sample number, found 205"),
                       "%s", err.msg);
}

Test(brdf, non_numeric_value_names_the_field)
{
    expect_error("1 0.5 0.5 0.5\n2 0.5 abc 0.5\n", 3, BF_EPARSE, 2,
                 "field 3 (value 2): not a decimal number: \"abc\"");
}

Test(brdf, non_finite_values_are_errors)
{
    expect_error("1 0.5 nan 0.5\n", 3, BF_EPARSE, 1,
                 "field 3 (value 2): not a finite number: \"nan\"");
    expect_error("1 0.5 0.5 INF\n", 3, BF_EPARSE, 1,
                 "field 4 (value 3): not a finite number: \"INF\"");
    expect_error("1 0.5 0.5 -1e999\n", 3, BF_EPARSE, 1,
                 "field 4 (value 3): out of range (overflows a double)");
    expect_error("1 0x10 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "field 2 (value 1): hexadecimal numbers are not accepted");
    expect_error("1 0.5 0.5 0.5x\n", 3, BF_EPARSE, 1,
                 "field 4 (value 3): unexpected characters after the number");
}

Test(brdf, sample_number_must_be_a_positive_integer)
{
    expect_error("1.5 0.5 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "field 1 (sample): not an integer: \"1.5\"");
    expect_error("0 0.5 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "field 1 (sample): out of range (must be 1 to");
    expect_error("-3 0.5 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "field 1 (sample): out of range");
    expect_error("4294967296 0.5 0.5 0.5\n", 3, BF_EPARSE, 1,
                 "field 1 (sample): out of range");
}

Test(brdf, duplicate_sample_names_both_lines)
{
    expect_error("1 0.1 0.1\n2 0.2 0.2\n\n3 0.3 0.3\n2 0.4 0.4\n", 2,
                 BF_EPARSE, 5, "sample 2 appears twice, first at line 2");
}

Test(brdf, first_duplicate_in_file_order_is_reported)
{
    expect_error("5 0 0\n1 0 0\n5 0 0\n1 0 0\n", 2, BF_EPARSE, 3,
                 "sample 5 appears twice, first at line 1");
}

Test(brdf, gap_in_sample_numbers_names_the_missing_one)
{
    expect_error("1 0.1 0.1\n2 0.2 0.2\n4 0.4 0.4\n5 0.5 0.5\n", 2,
                 BF_EPARSE, 0, "sample 3 is missing");
    expect_error("2 0.2 0.2\n", 2, BF_EPARSE, 0, "sample 1 is missing");
}

Test(brdf, zero_configurations_takes_the_count_from_the_first_row)
{
    /* the count comes from row 1; row 2 is then checked against it */
    bf_brdf *b = read_ok("1 0.1 0.2 0.3\n\n2 0.4 0.5 0.6\n", 0);
    cr_assert_eq(bf_brdf_nconf(b), 3);
    cr_assert_eq(bf_brdf_line(b, 0), 1);
    cr_assert_eq(bf_brdf_line(b, 1), 3);
    bf_brdf_free(b);
    expect_error("1 0.1 0.2 0.3\n2 0.4 0.5\n", 0, BF_EPARSE, 2,
                 "expected 3 values after the sample number, found 2");
    expect_error("1\n", 0, BF_EPARSE, 1, "a sample number without values");
}

Test(brdf, nonexistent_path_is_an_io_error)
{
    bf_brdf *b = NULL;
    bf_error err;
    cr_assert_eq(bf_brdf_load("/nonexistent-brdffit/abrdf.dat", 205, &b, &err),
                 BF_EIO);
    cr_assert_null(b);
    cr_assert_eq(err.line, 0);
    cr_assert_not_null(strstr(err.msg, "cannot open"), "%s", err.msg);
}

Test(brdf, directory_path_is_an_io_error)
{
    bf_brdf *b = NULL;
    bf_error err;
    cr_assert_eq(bf_brdf_load(BF_CURET_DIR, 205, &b, &err), BF_EIO);
    cr_assert_null(b);
    cr_assert_not_null(strstr(err.msg, "is a directory"), "%s", err.msg);
}

Test(brdf, accessors_of_null_are_empty)
{
    cr_assert_eq(bf_brdf_count(NULL), 0);
    cr_assert_eq(bf_brdf_nconf(NULL), 0);
    cr_assert_eq(bf_brdf_sample(NULL, 0), -1);
    cr_assert_null(bf_brdf_values(NULL, 0));
    cr_assert_eq(bf_brdf_find(NULL, 1), -1);
    bf_brdf_free(NULL);
}
