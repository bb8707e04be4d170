/* test_names.c: the sample name reader (src/data/names.c) on CURET's
 * samples.tsv and on small in-memory files. */
#include <criterion/criterion.h>
#include <string.h>

#include "support.h"

#define NAME "n.tsv"

static int read_text(const char *text, bf_names **nm, bf_error *err)
{
    FILE *fp = bf_test_memfile(text);
    int rc = bf_names_read(fp, NAME, nm, err);
    fclose(fp);
    return rc;
}

static bf_names *read_ok(const char *text)
{
    bf_names *nm = NULL;
    bf_error err;
    int rc = read_text(text, &nm, &err);
    cr_assert_eq(rc, BF_OK, "%s:%ld: %s", err.file, err.line, err.msg);
    cr_assert_not_null(nm);
    return nm;
}

static void expect_error(const char *text, int code, long line,
                         const char *piece)
{
    bf_names *nm = (bf_names *)&nm; /* non-NULL: the reader must reset it */
    bf_error err;
    int rc = read_text(text, &nm, &err);
    cr_assert_eq(rc, code, "rc %d (%s), expected %d", rc, err.msg, code);
    cr_assert_null(nm);
    cr_assert_eq(err.line, line, "line %ld, expected %ld (%s)", err.line,
                 line, err.msg);
    cr_assert_not_null(strstr(err.msg, piece), "message \"%s\" lacks \"%s\"",
                       err.msg, piece);
}

static bf_names *load_curet_names(void)
{
    bf_names *nm = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_names_load(bf_test_curet_path("samples.tsv"), &nm, &err);
    cr_assert_eq(rc, BF_OK, "%s", bf_error_format(&err, msg, sizeof msg));
    return nm;
}

Test(names, curet_names_of_felt_linen_and_a_zoomed_view)
{
    bf_names *nm = load_curet_names();
    /* samples.tsv lines 2, 45, 30 and 62 */
    cr_assert_str_eq(bf_names_get(nm, 1), "Felt");
    cr_assert_str_eq(bf_names_get(nm, 44), "Linen");
    cr_assert_str_eq(bf_names_get(nm, 29), "Polyester (zoomed view of 2)");
    cr_assert_str_eq(bf_names_get(nm, 61), "Moss");
    bf_names_free(nm);
}

Test(names, curet_names_cover_samples_1_to_61_and_nothing_else)
{
    bf_names *nm = load_curet_names();
    int s;
    for (s = 1; s <= 61; s++) {
        cr_assert_not_null(bf_names_get(nm, s), "sample %d", s);
    }
    cr_assert_null(bf_names_get(nm, 0));
    cr_assert_null(bf_names_get(nm, 62));
    cr_assert_null(bf_names_get(nm, -1));
    cr_assert_null(bf_names_get(NULL, 1));
    bf_names_free(nm);
    bf_names_free(NULL);
}

Test(names, file_without_header_and_without_flags_is_accepted)
{
    bf_names *nm = read_ok("7\tRough Paper\n3\tTerrycloth\t0\n");
    cr_assert_str_eq(bf_names_get(nm, 7), "Rough Paper");
    cr_assert_str_eq(bf_names_get(nm, 3), "Terrycloth");
    cr_assert_null(bf_names_get(nm, 1));
    bf_names_free(nm);
}

Test(names, spaces_around_fields_and_crlf_are_trimmed)
{
    bf_names *nm =
        read_ok("\xEF\xBB\xBFsample\tname\tflag\r\n 2 \t  Polyester \t 1 \r\n");
    cr_assert_str_eq(bf_names_get(nm, 2), "Polyester");
    bf_names_free(nm);
}

Test(names, empty_file_and_header_only_are_errors)
{
    expect_error("", BF_EPARSE, 0, "empty file");
    expect_error("sample\tname\tflag\n", BF_EPARSE, 0,
                 "header line but no rows");
}

Test(names, wrong_field_count_is_an_error)
{
    expect_error("sample\tname\n1 Felt\n", BF_EPARSE, 2,
                 "expected 2 or 3 tab-separated fields (sample, name, flag), "
                 "found 1");
    expect_error("1\tFelt\t1\textra\n", BF_EPARSE, 1, "found 4");
}

Test(names, empty_name_is_an_error)
{
    expect_error("1\tFelt\n2\t  \t1\n", BF_EPARSE, 2, "field 2 (name) is empty");
}

Test(names, flag_must_be_zero_or_one)
{
    expect_error("1\tFelt\t2\n", BF_EPARSE, 1,
                 "field 3 (flag): out of range (must be 0 to 1)");
    expect_error("1\tFelt\tyes\n", BF_EPARSE, 1,
                 "field 3 (flag): not a decimal number");
}

Test(names, bad_or_duplicate_sample_number_is_an_error)
{
    expect_error("1\tFelt\n1.5\tPolyester\n", BF_EPARSE, 2,
                 "field 1 (sample): not an integer");
    expect_error("1\tFelt\n\n1\tPolyester\n", BF_EPARSE, 3,
                 "sample 1 appears twice, first at line 1");
}

Test(names, nonexistent_and_directory_paths_are_io_errors)
{
    bf_names *nm = NULL;
    bf_error err;
    cr_assert_eq(bf_names_load("/nonexistent-brdffit/samples.tsv", &nm, &err),
                 BF_EIO);
    cr_assert_null(nm);
    cr_assert_eq(bf_names_load(BF_CURET_DIR, &nm, &err), BF_EIO);
    cr_assert_null(nm);
    cr_assert_not_null(strstr(err.msg, "is a directory"), "%s", err.msg);
}
