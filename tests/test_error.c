/* test_error.c: bf_version, bf_strerror and bf_error_format (src/error.c). */
#include <criterion/criterion.h>
#include <string.h>

#include "support.h"

/* Every code of the public enum, BF_OK first. */
static const int all_codes[] = {BF_OK,    BF_EINVAL, BF_EDOM,    BF_ENOMEM,
                                BF_EIO,   BF_EPARSE, BF_ENOCONV, BF_ENOTFOUND};
#define NCODES (sizeof all_codes / sizeof all_codes[0])

Test(error, version_string_matches_the_header_macros)
{
    char expect[32];
    snprintf(expect, sizeof expect, "%d.%d.%d", BF_VERSION_MAJOR,
             BF_VERSION_MINOR, BF_VERSION_PATCH);
    cr_assert_str_eq(bf_version(), BF_VERSION_STRING);
    cr_assert_str_eq(bf_version(), expect);
}

Test(error, strerror_of_every_code_is_non_empty_and_distinct)
{
    size_t a;
    size_t b;
    for (a = 0; a < NCODES; a++) {
        const char *s = bf_strerror(all_codes[a]);
        cr_assert_not_null(s, "code %d", all_codes[a]);
        cr_assert_gt(strlen(s), 0, "code %d", all_codes[a]);
        for (b = 0; b < a; b++) {
            cr_assert_str_neq(s, bf_strerror(all_codes[b]),
                              "codes %d and %d share a text", all_codes[a],
                              all_codes[b]);
        }
    }
}

Test(error, strerror_of_an_unknown_code_is_a_distinct_text)
{
    size_t a;
    const char *s = bf_strerror(-1);
    cr_assert_not_null(s);
    cr_assert_str_eq(bf_strerror(9999), s);
    for (a = 0; a < NCODES; a++) {
        cr_assert_str_neq(s, bf_strerror(all_codes[a]));
    }
}

Test(error, format_with_a_line_gives_file_colon_line_colon_message)
{
    bf_error err = {BF_EPARSE, 17, "table.txt", "expected 5 numbers, found 4"};
    char buf[256];
    cr_assert_eq(bf_error_format(&err, buf, sizeof buf), buf);
    cr_assert_str_eq(buf, "table.txt:17: expected 5 numbers, found 4");
}

Test(error, format_without_a_line_omits_it)
{
    bf_error err = {BF_EPARSE, 0, "abrdf.dat", "empty file"};
    char buf[256];
    bf_error_format(&err, buf, sizeof buf);
    cr_assert_str_eq(buf, "abrdf.dat: empty file");
}

Test(error, format_truncates_to_the_buffer_and_terminates_it)
{
    bf_error err = {BF_EIO, 3, "some/long/path.dat", "cannot open"};
    char buf[8];
    memset(buf, 'x', sizeof buf);
    bf_error_format(&err, buf, sizeof buf);
    cr_assert_str_eq(buf, "some/lo");
}

Test(error, format_of_a_null_report_still_writes_a_text)
{
    char buf[64] = "";
    cr_assert_eq(bf_error_format(NULL, buf, sizeof buf), buf);
    cr_assert_gt(strlen(buf), 0);
    /* len 0 writes nothing and returns buf */
    cr_assert_eq(bf_error_format(NULL, buf, 0), buf);
}
