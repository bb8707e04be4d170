/* test_numbers.c: bf__parse_double gives strtod's double, bit for bit,
 * for every number of the real CURET and Cornell files and for random and
 * edge-case decimals (its exact fast path and the strtod fallback, issue
 * 19 item 7); the line reader reads a file whose lines cross its reads. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "support.h"

/* Asserts bf__parse_double(s) is strtod(s) bit for bit. */
static void same_as_strtod(const char *s)
{
    double want = strtod(s, NULL);
    double got = -12345.0;
    uint64_t a;
    uint64_t b;
    int st = bf__parse_double(s, &got);
    cr_assert_eq(st, BF__NUM_OK, "'%s' refused (%d)", s, st);
    memcpy(&a, &want, sizeof a);
    memcpy(&b, &got, sizeof b);
    cr_assert_eq(a, b, "'%s': strtod %.17g, parsed %.17g", s, want, got);
}

/* Every whitespace-separated token of path that strtod reads whole. */
static size_t every_number_of(const char *path)
{
    FILE *fp = fopen(path, "r");
    char tok[512];
    size_t n = 0;
    cr_assert_not_null(fp, "%s missing", path);
    while (fscanf(fp, "%511s", tok) == 1) {
        char *end;
        (void)strtod(tok, &end);
        if (end != tok && *end == '\0' && strpbrk(tok, "xXnNiI") == NULL) {
            same_as_strtod(tok);
            n++;
        }
    }
    fclose(fp);
    return n;
}

Test(numbers, every_number_of_the_real_files_is_strtods)
{
    static const char *const cornell[] = {"acryl_blue.brdf", "cayman.brdf",
                                          "garnet_red.brdf",
                                          "krylon_blue.brdf",
                                          "mystique.brdf"};
    size_t n = every_number_of(bf_test_curet_path("abrdf.dat"));
    size_t i;
    cr_assert_gt(n, 61 * 205, "abrdf.dat: %zu numbers", n);
    cr_assert_gt(every_number_of(bf_test_curet_path("table.txt")), 205 * 4);
    for (i = 0; i < sizeof cornell / sizeof *cornell; i++) {
        cr_assert_gt(every_number_of(bf_test_cornell_path(cornell[i])), 1000);
    }
}

Test(numbers, edge_cases_are_strtods)
{
    static const char *const s[] = {
        "0", "-0", "+0", "0.0", "-0.0", ".5", "5.", "-.5", "1e0", "1E+0",
        "1e-0", "00000000000000000000000001", "0.000000000000000000000001",
        "9007199254740991", "9007199254740992", "9007199254740993",
        "900719925474099.1", "90071992547409.93", "123456789012345678",
        "1e22", "1e23", "1e-22", "1e-23", "9007199254740991e22",
        "9007199254740991e-22", "4503599627370497e22", "0.1", "0.2", "0.3",
        "2.2250738585072014e-308", "4.9e-324", "1e-320", "1.7976931348623157e308",
        "123.456e-3", "-987654321.123456789", "3.14159265358979323846",
        "0.30000000000000004", "1.00000000000000011102230246251565404",
        "1e-400", "-1e-400", "8.98846567431158e307", "1e+22", "10e21",
        "0.00000000000000000000000000000000000001e38", "100000000000000000000000",
        "0.0022000", "220.00e-5", "7.3890560989306495"};
    size_t i;
    for (i = 0; i < sizeof s / sizeof *s; i++) {
        same_as_strtod(s[i]);
    }
}

/* A small generator of its own (the test must not depend on rand's). */
static uint64_t next(uint64_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
    return *x;
}

Test(numbers, random_decimals_are_strtods)
{
    uint64_t x = 0x9E3779B97F4A7C15u;
    char s[96];
    int i;
    for (i = 0; i < 200000; i++) {
        uint64_t r = next(&x);
        int ndig = 1 + (int)(r % 19);          /* significant digits */
        int point = (int)((r >> 8) % (unsigned)(ndig + 2)); /* its place */
        int ex = (int)((r >> 16) % 61) - 30;   /* exponent */
        int k = 0;
        int d;
        if ((r >> 24) & 1) {
            s[k++] = '-';
        }
        for (d = 0; d < ndig; d++) {
            if (d == point) {
                s[k++] = '.';
            }
            s[k++] = (char)('0' + next(&x) % 10);
        }
        if ((r >> 25) & 1) {
            k += snprintf(s + k, sizeof s - (size_t)k, "e%d", ex);
        }
        s[k] = '\0';
        same_as_strtod(s);
    }
}

Test(numbers, printed_doubles_read_back)
{
    uint64_t x = 12345;
    char s[64];
    int i;
    for (i = 0; i < 100000; i++) {
        uint64_t bits = next(&x);
        double v;
        memcpy(&v, &bits, sizeof v);
        if (!isfinite(v)) {
            continue;
        }
        snprintf(s, sizeof s, "%.*g", 1 + (int)(bits % 17), v);
        if (isfinite(strtod(s, NULL))) { /* rounded past DBL_MAX: refused */
            same_as_strtod(s);
        }
    }
}

/* Reads the 200 lines of 1000 numbers that write_lines wrote from in. */
static void read_lines(FILE *in)
{
    bf__lines r;
    bf_error err;
    int have = 0;
    long line = 0;
    size_t j;
    bf__lines_init(&r, in);
    bf__error_clear(&err, "lines");
    for (;;) {
        cr_assert_eq(bf__lines_next(&r, &have, &err), BF_OK, "%s", err.msg);
        if (!have) {
            break;
        }
        cr_assert_eq(bf__lines_split_ws(&r, &err), BF_OK);
        cr_assert_eq(r.nfield, 1000, "line %ld: %zu fields", r.line,
                     r.nfield);
        for (j = 0; j < 1000; j += 333) {
            double v;
            cr_assert_eq(bf__field_double(&r, j, "v", &v, &err), BF_OK);
            bf_assert_rel(v, (double)line + (double)j / 1000.0, TOL0);
        }
        line++;
        cr_assert_eq(r.line, line);
    }
    cr_assert_eq(line, 200);
    bf__lines_free(&r);
}

Test(numbers, lines_crossing_the_reads_of_a_pipe_are_whole)
{
    /* about 1.4 MB: a pipe is read 64 KiB at a time, so lines cross the
     * reads; a regular file is read in one */
    char path[] = "/tmp/brdffit-lines-XXXXXX";
    char cmd[64];
    int fd = mkstemp(path);
    FILE *fp = fd >= 0 ? fdopen(fd, "w") : NULL;
    FILE *in;
    int i;
    int j;
    cr_assert_not_null(fp);
    for (i = 0; i < 200; i++) {
        for (j = 0; j < 1000; j++) {
            fprintf(fp, "%s%d.%03d", j ? " " : "", i, j);
        }
        fputs(i % 2 ? "\r\n" : "\n", fp);
    }
    cr_assert_eq(fclose(fp), 0);
    snprintf(cmd, sizeof cmd, "cat %s", path);
    in = popen(cmd, "r");
    cr_assert_not_null(in);
    read_lines(in);
    cr_assert_eq(pclose(in), 0);
    in = fopen(path, "r");
    cr_assert_not_null(in);
    read_lines(in);
    fclose(in);
    remove(path);
}
