/* support.c: shared helpers of the test suite (see support.h). */
#include "support.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void bf__assert_rel(double obtained, double expected, double tol,
                    const char *what, const char *file, int line)
{
    double scale = fabs(expected) > 1e-300 ? fabs(expected) : 1e-300;
    double rel = fabs(obtained - expected) / scale;
    if (!(rel <= tol)) {
        cr_expect_fail("%s:%d: %s: expected %.17g, obtained %.17g, "
                "relative difference %.3g, tolerance %.3g",
                file, line, what, expected, obtained, rel, tol);
    }
}

void bf__assert_abs(double obtained, double expected, double tol,
                    const char *what, const char *file, int line)
{
    double diff = fabs(obtained - expected);
    if (!(diff <= tol)) {
        cr_expect_fail("%s:%d: %s: expected %.17g, obtained %.17g, "
                "absolute difference %.3g, tolerance %.3g",
                file, line, what, expected, obtained, diff, tol);
    }
}

static const char *path_in(const char *env, const char *dflt, const char *file)
{
    static char buf[4096];
    const char *dir = getenv(env);
    struct stat st;
    if (dir == NULL || dir[0] == '\0') {
        dir = dflt;
    }
    snprintf(buf, sizeof buf, "%s/%s", dir, file);
    if (stat(buf, &st) != 0) {
        cr_assert_fail("required data file %s is missing (set %s or configure "
                 "BF_SHARED_DIR); tests never skip for missing data",
                 buf, env);
    }
    return buf;
}

const char *bf_test_curet_path(const char *file)
{
    return path_in("BRDFFIT_CURET_DIR", BF_CURET_DIR, file);
}

const char *bf_test_reference_path(const char *file)
{
    return path_in("BRDFFIT_REFERENCE_DIR", BF_REFERENCE_DIR, file);
}

const char *bf_test_fixture_path(const char *file)
{
    return path_in("BRDFFIT_FIXTURES_DIR", BF_FIXTURES_DIR, file);
}

bf_table *bf_test_load_table(void)
{
    bf_table *t = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_table_load(bf_test_curet_path("table.txt"), &t, &err);
    if (rc != BF_OK) {
        cr_assert_fail("cannot load table.txt: %s",
                 bf_error_format(&err, msg, sizeof msg));
    }
    return t;
}

bf_brdf *bf_test_load_abrdf(void)
{
    bf_brdf *b = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_brdf_load(bf_test_curet_path("abrdf.dat"), BF_CURET_NCONF, &b,
                          &err);
    if (rc != BF_OK) {
        cr_assert_fail("cannot load abrdf.dat: %s",
                 bf_error_format(&err, msg, sizeof msg));
    }
    return b;
}

FILE *bf_test_memfile(const char *text)
{
    return bf_test_membuf(text, strlen(text));
}

FILE *bf_test_membuf(const void *buf, size_t len)
{
    /* fmemopen with size 0 is unspecified; an empty stream is a tmpfile. */
    FILE *fp;
    if (len == 0) {
        fp = tmpfile();
    } else {
        fp = fmemopen((void *)(uintptr_t)buf, len, "r");
    }
    cr_assert_not_null(fp, "cannot open an in-memory stream");
    return fp;
}
