/* test_sample_table.c: per-sample tables (src/data/sample_table.c): the
 * Oren-Nayar parameter file, CURET's op.dat layout and the refractive index
 * file. */
#include <criterion/criterion.h>
#include <string.h>

#include "internal.h"
#include "support.h"

#define NAME "s.tsv"

typedef int (*reader_fn)(FILE *fp, const char *name, bf_sample_table **out,
                         bf_error *err);

/* bf_sample_table_read with 1..3 columns, as a reader_fn. */
static int read_1_to_3(FILE *fp, const char *name, bf_sample_table **out,
                       bf_error *err)
{
    return bf_sample_table_read(fp, name, 1, 3, out, err);
}

static int read_text(reader_fn f, const char *text, bf_sample_table **st,
                     bf_error *err)
{
    FILE *fp = bf_test_memfile(text);
    int rc = f(fp, NAME, st, err);
    fclose(fp);
    return rc;
}

static bf_sample_table *read_ok(reader_fn f, const char *text)
{
    bf_sample_table *st = NULL;
    bf_error err;
    int rc = read_text(f, text, &st, &err);
    cr_assert_eq(rc, BF_OK, "%s:%ld: %s", err.file, err.line, err.msg);
    cr_assert_not_null(st);
    return st;
}

static void expect_error(reader_fn f, const char *text, int code, long line,
                         const char *piece)
{
    bf_sample_table *st = (bf_sample_table *)&st; /* reader must reset it */
    bf_error err;
    int rc = read_text(f, text, &st, &err);
    cr_assert_eq(rc, code, "rc %d (%s), expected %d", rc, err.msg, code);
    cr_assert_null(st);
    cr_assert_eq(err.code, code);
    cr_assert_eq(err.line, line, "line %ld, expected %ld (%s)", err.line,
                 line, err.msg);
    cr_assert_not_null(strstr(err.msg, piece), "message \"%s\" lacks \"%s\"",
                       err.msg, piece);
}

static double get(const bf_sample_table *st, int sample, size_t col)
{
    double x = -1.0;
    cr_assert_eq(bf_sample_table_get(st, sample, col, &x), BF_OK,
                 "sample %d column %zu", sample, col);
    return x;
}

/* ==== Oren-Nayar parameters ==== */

Test(sample_table, reference_on_parameters_load_24_rows_after_the_header)
{
    bf_sample_table *st = NULL;
    bf_error err;
    char msg[1024];
    size_t r;
    int rc = bf_on_params_load(
        bf_test_reference_path("oren_nayar_params.tsv"), &st, &err);
    cr_assert_eq(rc, BF_OK, "%s", bf_error_format(&err, msg, sizeof msg));
    cr_assert_eq(bf_sample_table_count(st), 24);
    cr_assert_eq(bf_sample_table_cols(st), 2);
    /* oren_nayar_params.tsv lines 2 and 25: "1 0.387 0.415", "56 0.673
     * 0.351"; line 6: "9 0.142 0.416" */
    cr_assert(get(st, 1, 0) == 0.387 && get(st, 1, 1) == 0.415);
    cr_assert(get(st, 56, 0) == 0.673 && get(st, 56, 1) == 0.351);
    cr_assert(get(st, 9, 0) == 0.142 && get(st, 9, 1) == 0.416);
    /* the file lists exactly the study's samples, in increasing order */
    for (r = 0; r < BF_STUDY_NSAMPLES; r++) {
        cr_assert_eq(bf_sample_table_sample(st, r), bf_study_samples[r]);
    }
    cr_assert_eq(bf_sample_table_sample(st, 24), -1);
    bf_sample_table_free(st);
}

Test(sample_table, absent_sample_is_not_found_and_bad_column_is_invalid)
{
    bf_sample_table *st = read_ok(bf_on_params_read, "1 0.387 0.415\n");
    double x = 42.0;
    cr_assert_eq(bf_sample_table_get(st, 3, 0, &x), BF_ENOTFOUND);
    cr_assert_eq(bf_sample_table_get(st, 1, 2, &x), BF_EINVAL);
    cr_assert_eq(bf_sample_table_get(NULL, 1, 0, &x), BF_EINVAL);
    cr_assert(x == 42.0);
    bf_sample_table_free(st);
    bf_sample_table_free(NULL);
}

Test(sample_table, curet_op_dat_layout_with_kd_is_accepted)
{
    bf_sample_table *st = read_ok(bf_on_params_read,
                                  "1 0.387 0.415 0.7313\n"
                                  "2\t0.380\t0.577\t0.25\n");
    cr_assert_eq(bf_sample_table_cols(st), 3);
    cr_assert(get(st, 1, 2) == 0.7313);
    cr_assert(get(st, 2, 1) == 0.577);
    bf_sample_table_free(st);
}

Test(sample_table, boundary_values_of_rho_and_sigma_are_accepted)
{
    bf_sample_table *st =
        read_ok(bf_on_params_read, "1 0 0\n2 1 1.5707963267948966\n");
    cr_assert(get(st, 2, 1) == BF__PI_2);
    bf_sample_table_free(st);
}

Test(sample_table, rho_out_of_range_is_an_error_with_its_line)
{
    expect_error(bf_on_params_read, "sample rho sigma\n1 0.387 0.415\n"
                                    "2 1.2 0.577\n",
                 BF_EPARSE, 3, "sample 2: rho = 1.2 outside [0, 1]");
    expect_error(bf_on_params_read, "1 -0.01 0.4\n", BF_EPARSE, 1,
                 "rho = -0.01 outside [0, 1]");
}

Test(sample_table, sigma_out_of_range_is_an_error_with_its_line)
{
    expect_error(bf_on_params_read, "1 0.387 0.415\n\n7 0.171 1.6\n",
                 BF_EPARSE, 3, "sample 7: sigma = 1.6 outside [0, pi/2]");
}

Test(sample_table, on_file_with_one_or_four_numbers_is_an_error)
{
    expect_error(bf_on_params_read, "1 0.387\n", BF_EPARSE, 1,
                 "expected 2 to 3 numbers after the sample number, found 1");
    expect_error(bf_on_params_read, "1 0.387 0.415 0.5 0.5\n", BF_EPARSE, 1,
                 "found 4");
}

Test(sample_table, rows_with_different_column_counts_are_an_error)
{
    expect_error(bf_on_params_read, "1 0.387 0.415\n2 0.380 0.577 0.3\n",
                 BF_EPARSE, 2,
                 "found 3 numbers after the sample number, but line 1 has 2");
}

Test(sample_table, empty_file_and_header_only_are_errors)
{
    expect_error(bf_on_params_read, "", BF_EPARSE, 0, "empty file");
    expect_error(bf_on_params_read, "sample\trho\tsigma\n", BF_EPARSE, 0,
                 "header line but no rows");
    expect_error(bf_on_params_read, "sample\trho\tsigma\r\n\r\n", BF_EPARSE,
                 0, "header line but no rows");
}

Test(sample_table, header_is_only_allowed_on_the_first_line)
{
    expect_error(bf_on_params_read, "1 0.387 0.415\nsample rho sigma\n",
                 BF_EPARSE, 2,
                 "field 1 (sample): not a decimal number: \"sample\"");
    expect_error(read_1_to_3, "1 0.387 0.415\nsample rho\n", BF_EPARSE, 2,
                 "field 1 (sample): not a decimal number: \"sample\"");
}

Test(sample_table, bad_numbers_name_the_column)
{
    expect_error(bf_on_params_read, "1 0.387 nan\n", BF_EPARSE, 1,
                 "field 3 (column 2): not a finite number: \"nan\"");
    expect_error(bf_on_params_read, "1 inf 0.4\n", BF_EPARSE, 1,
                 "field 2 (column 1): not a finite number");
    expect_error(bf_on_params_read, "1 0x1p-2 0.4\n", BF_EPARSE, 1,
                 "hexadecimal numbers are not accepted");
    expect_error(bf_on_params_read, "1 1e999 0.4\n", BF_EPARSE, 1,
                 "out of range (overflows a double)");
    expect_error(bf_on_params_read, "1 0.3rho 0.4\n", BF_EPARSE, 1,
                 "unexpected characters after the number: \"0.3rho\"");
}

Test(sample_table, bad_or_duplicate_sample_number_is_an_error)
{
    expect_error(bf_on_params_read, "1.5 0.3 0.4\n", BF_EPARSE, 1,
                 "field 1 (sample): not an integer: \"1.5\"");
    expect_error(bf_on_params_read, "-2 0.3 0.4\n", BF_EPARSE, 1,
                 "field 1 (sample): out of range");
    expect_error(bf_on_params_read, "sample rho sigma\n5 0.3 0.4\n"
                                    "6 0.3 0.4\n5 0.1 0.1\n",
                 BF_EPARSE, 4, "sample 5 appears twice, first at line 2");
}

Test(sample_table, on_paths_nonexistent_and_directory_are_io_errors)
{
    bf_sample_table *st = NULL;
    bf_error err;
    cr_assert_eq(bf_on_params_load("/nonexistent-brdffit/op.dat", &st, &err),
                 BF_EIO);
    cr_assert_null(st);
    cr_assert_eq(err.line, 0);
    cr_assert_not_null(strstr(err.msg, "No such file"), "%s", err.msg);
    cr_assert_eq(bf_on_params_load(BF_REFERENCE_DIR, &st, &err), BF_EIO);
    cr_assert_null(st);
    cr_assert_not_null(strstr(err.msg, "is a directory"), "%s", err.msg);
}

/* ==== refractive index file ==== */

Test(sample_table, n_file_loads_indices_with_header_and_crlf)
{
    bf_sample_table *st =
        read_ok(bf_n_file_read, "sample n\r\n1 1.7\r\n44 1.52\r\n61 10");
    cr_assert_eq(bf_sample_table_count(st), 3);
    cr_assert_eq(bf_sample_table_cols(st), 1);
    cr_assert(get(st, 44, 0) == 1.52);
    cr_assert(get(st, 61, 0) == 10.0);
    bf_sample_table_free(st);
}

Test(sample_table, n_not_above_one_is_an_error)
{
    expect_error(bf_n_file_read, "1 1.7\n2 1\n", BF_EPARSE, 2,
                 "sample 2: n = 1 outside (1, 10]");
    expect_error(bf_n_file_read, "1 0.9\n", BF_EPARSE, 1, "n = 0.9 outside");
}

Test(sample_table, n_above_ten_is_an_error)
{
    expect_error(bf_n_file_read, "1 10.5\n", BF_EPARSE, 1,
                 "n = 10.5 outside (1, 10]");
}

Test(sample_table, n_file_with_two_numbers_is_an_error)
{
    expect_error(bf_n_file_read, "1 1.7 1.8\n", BF_EPARSE, 1,
                 "expected 1 number after the sample number, found 2");
}

Test(sample_table, n_file_path_that_is_a_directory_is_an_io_error)
{
    bf_sample_table *st = NULL;
    bf_error err;
    cr_assert_eq(bf_n_file_load(BF_CURET_DIR, &st, &err), BF_EIO);
    cr_assert_null(st);
    cr_assert_eq(bf_n_file_load("/nonexistent-brdffit/n.tsv", &st, &err),
                 BF_EIO);
}

/* ==== generic tables ==== */

Test(sample_table, generic_table_keeps_rows_in_file_order_with_gaps)
{
    bf_sample_table *st = read_ok(read_1_to_3, "9 1 2\n3 4 5\n");
    cr_assert_eq(bf_sample_table_sample(st, 0), 9);
    cr_assert_eq(bf_sample_table_sample(st, 1), 3);
    cr_assert(get(st, 3, 1) == 5.0);
    cr_assert(get(st, 9, 0) == 1.0);
    bf_sample_table_free(st);
}

Test(sample_table, bad_column_range_is_invalid)
{
    bf_sample_table *st = NULL;
    bf_error err;
    FILE *fp = bf_test_memfile("1 2\n");
    cr_assert_eq(bf_sample_table_read(fp, NAME, 2, 1, &st, &err), BF_EINVAL);
    cr_assert_eq(bf_sample_table_read(fp, NAME, 0, 0, &st, &err), BF_EINVAL);
    cr_assert_null(st);
    fclose(fp);
}
