/* test_format.c: format names, detection from the content and loading
 * any format through bf_dataset_load (src/data/format.c). */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_run.h"
#include "data/reader.h"
#include "internal.h"
#include "support.h"

/* The files made by a test, removed (with their folders) after it. */
#define MAX_FILES 16
static char made[MAX_FILES][512];
static size_t n_made;

static void remove_made(void)
{
    while (n_made > 0) {
        char *path = made[--n_made];
        unlink(path);
        *strrchr(path, '/') = '\0';
        rmdir(path);
    }
}

TestSuite(format, .fini = remove_made);

/* A file holding len bytes in a fresh folder; its path (valid until the
 * test ends). */
static const char *file_with(const char *name, const void *buf, size_t len)
{
    char *path;
    FILE *fp;
    cr_assert_lt(n_made, MAX_FILES);
    path = made[n_made++];
    snprintf(path, sizeof made[0], "%s/%s", bf_test_tmpdir(), name);
    fp = fopen(path, "wb");
    cr_assert_not_null(fp);
    cr_assert_eq(fwrite(buf, 1, len, fp), len);
    cr_assert_eq(fclose(fp), 0);
    return path;
}

static const char *text_file(const char *name, const char *text)
{
    return file_with(name, text, strlen(text));
}

static void expect_format(const char *path, bf_format expect)
{
    bf_format f = BF_FORMAT_MEMORY;
    bf_error err;
    cr_assert_eq(bf_format_detect(path, &f, &err), BF_OK, "%s: %s", path,
                 err.msg);
    cr_assert_eq(f, expect, "%s: %s, expected %s", path, bf_format_name(f),
                 bf_format_name(expect));
}

static void expect_unknown(const char *path, int code, const char *msg)
{
    bf_format f = BF_FORMAT_MEMORY;
    bf_error err;
    cr_assert_eq(bf_format_detect(path, &f, &err), code, "%s", err.msg);
    cr_assert_eq(f, BF_FORMAT_MEMORY, "unchanged on failure");
    cr_assert_eq(err.line, 0);
    cr_assert_str_eq(err.file, path);
    cr_assert_str_eq(err.msg, msg);
}

static const char csv_text[] = "# angles in degrees\n"
                               "material,theta_i,phi_i,theta_o,phi_o,R\n"
                               "a,10,0,20,180,0.5\n";
static const char astm_text[] = "SOURCE x\nNUM_POINTS 1\n"
                                "VARS theta_i,phi_i,theta_s,phi_s,R\n"
                                "0.1,0,0.2,3,0.5\n";

/* ==== names ==== */

Test(format, names_and_aliases)
{
    static const char *const names[] = {"auto", "curet", "pbrt", "astm",
                                        "merl", "csv",   "memory"};
    bf_format f;
    int k;
    for (k = 0; k <= BF_FORMAT_MEMORY; k++) {
        cr_assert_str_eq(bf_format_name((bf_format)k), names[k]);
        cr_assert_eq(bf_format_find(names[k], &f), BF_OK);
        cr_assert_eq(f, (bf_format)k);
    }
    cr_assert_null(bf_format_name((bf_format)bf__format_count()));
    cr_assert_null(bf_format_name((bf_format)-1));
    cr_assert_eq(bf_format_find("BRDF", &f), BF_OK);
    cr_assert_eq(f, BF_FORMAT_PBRT);
    cr_assert_eq(bf_format_find("Binary", &f), BF_OK);
    cr_assert_eq(f, BF_FORMAT_MERL);
    cr_assert_eq(bf_format_find("CSV", &f), BF_OK);
    cr_assert_eq(f, BF_FORMAT_CSV);
    cr_assert_eq(bf_format_find("tsv", &f), BF_ENOTFOUND);
    cr_assert_eq(bf_format_find("", &f), BF_ENOTFOUND);
}

Test(format, every_format_of_the_registry_round_trips_and_is_detected)
{
    /* each reader's fixture (tests/fixtures/formats/<name>) is detected
     * as that reader, and the registry's values and names agree */
    size_t n = bf__format_count();
    size_t i;
    size_t readers = 0;
    cr_assert_gt(n, (size_t)BF_FORMAT_MEMORY, "the public values stay");
    for (i = 0; i < n; i++) {
        bf_format f = (bf_format)i;
        const bf__reader *r = bf__reader_of(f);
        const char *name = bf_format_name(f);
        char rel[64];
        bf_format g = BF_FORMAT_AUTO;
        bf_error err;
        size_t k;
        cr_assert_not_null(name, "format %zu has a name", i);
        cr_assert_eq(bf_format_find(name, &g), BF_OK, "%s", name);
        cr_assert_eq(g, f, "%s found as %s", name, bf_format_name(g));
        if (r == NULL) {
            cr_assert(f == BF_FORMAT_AUTO || f == BF_FORMAT_MEMORY,
                      "%s has no reader", name);
            continue;
        }
        readers++;
        cr_assert_eq(bf__reader_format(r), f, "%s", name);
        cr_assert((r->load != NULL) != (r->read != NULL),
                  "%s: loads by path or reads a stream, one of them", name);
        cr_assert_not_null(r->title, "%s", name);
        cr_assert((r->detect != NULL) != (r->folder_file != NULL),
                  "%s: a file or a folder format", name);
        cr_assert((r->detect != NULL) == (r->miss != NULL), "%s", name);
        for (k = 0; r->aliases != NULL && r->aliases[k] != NULL; k++) {
            cr_assert_eq(bf_format_find(r->aliases[k], &g), BF_OK);
            cr_assert_eq(g, f, "alias %s of %s", r->aliases[k], name);
        }
        snprintf(rel, sizeof rel, "formats/%s", name);
        g = BF_FORMAT_AUTO;
        cr_assert_eq(bf_format_detect(bf_test_fixture_path(rel), &g, &err),
                     BF_OK, "%s: %s (every reader needs a fixture)", rel,
                     err.msg);
        cr_assert_eq(g, f, "%s detected as %s", rel, bf_format_name(g));
    }
    cr_assert_eq(readers, n - 2, "every format but auto and memory reads");
}

/* ==== detection ==== */

Test(format, each_format_is_detected_from_its_content)
{
    static const unsigned char merl_head[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                                180, 0, 0, 0};
    size_t k;
    for (k = 0; k < BF_TEST_NCORNELL; k++) {
        expect_format(bf_test_cornell_path(bf_test_cornell[k]),
                      BF_FORMAT_PBRT);
    }
    expect_format(bf_test_curet_path("."), BF_FORMAT_CURET);
    /* the name says nothing: a CSV called .brdf is CSV */
    expect_format(text_file("x.brdf", csv_text), BF_FORMAT_CSV);
    expect_format(text_file("x.csv", astm_text), BF_FORMAT_ASTM);
    expect_format(text_file("x", "\xEF\xBB\xBF# c\n  THETA_I , Phi_i,theta_o,"
                                 "\"phi_o\",G\n"),
                  BF_FORMAT_CSV);
    expect_format(text_file("x", "31 # wavelengths\n400 410\n"),
                  BF_FORMAT_PBRT);
    expect_format(text_file("x", "\n# c\n  NUM_POINTS 3\n"), BF_FORMAT_ASTM);
    /* MERL by its dimensions alone: the reader checks the size */
    expect_format(file_with("x", merl_head, sizeof merl_head),
                  BF_FORMAT_MERL);
}

Test(format, what_no_reader_recognises_is_an_error)
{
    static const char bin[] = "\x01\x02\0\x03";
    const char *dir = bf_test_tmpdir();
    const char *path;
    char fifo[512];
    expect_unknown(text_file("empty", ""), BF_EPARSE,
                   "empty file (no format recognised)");
    expect_unknown(file_with("bin", bin, sizeof bin - 1), BF_EPARSE,
                   "a binary file that is not a MERL table (it does not "
                   "start with the int32 dimensions 90, 90, 180)");
    path = text_file("garbage", "hello world\nthis is not data\n");
    expect_unknown(path, BF_EPARSE,
                   "no format recognised: not ASTM (no NUM_POINTS or VARS "
                   "header), not tidy CSV (no header theta_i,phi_i,theta_o,"
                   "phi_o), not pbrt (no wavelength count first), not MERL");
    /* CURET's abrdf.dat starts with a sample number, not a count of 1..
     * 65536 wavelengths followed by wavelengths: it is pbrt by content */
    expect_unknown(text_file("count0", "0 400\n"), BF_EPARSE,
                   "no format recognised: not ASTM (no NUM_POINTS or VARS "
                   "header), not tidy CSV (no header theta_i,phi_i,theta_o,"
                   "phi_o), not pbrt (no wavelength count first), not MERL");
    expect_unknown(dir, BF_EIO,
                   "a folder without table.txt (only CURET data is a "
                   "folder)");
    snprintf(fifo, sizeof fifo, "%s/pipe", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    expect_unknown(fifo, BF_EIO,
                   "a pipe: its format cannot be detected without consuming "
                   "it (name the format)");
    unlink(fifo);
    rmdir(dir);
    expect_unknown("/nonexistent/data.csv", BF_EIO,
                   "cannot open: No such file or directory");
}

/* ==== loading ==== */

Test(format, bf_dataset_load_reads_each_format_as_its_reader_does)
{
    const char *cayman = bf_test_cornell_path("cayman.brdf");
    bf_dataset *a = NULL;
    bf_dataset *b = NULL;
    bf_error err;
    bf_load_opts opts;
    memset(&opts, 0, sizeof opts);
    cr_assert_eq(bf_dataset_load(cayman, NULL, &a, &err), BF_OK, "%s",
                 err.msg);
    cr_assert_eq(bf_pbrt_load(cayman, &b, &err), BF_OK);
    bf_test_expect_same_dataset(a, b);
    bf_dataset_free(a);
    bf_dataset_free(b);
    cr_assert_eq(bf_dataset_load(text_file("m.csv", csv_text), &opts, &a,
                                 &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(bf_dataset_format(a, 0), BF_FORMAT_CSV);
    bf_dataset_free(a);
    cr_assert_eq(bf_dataset_load(text_file("m.astm", astm_text), &opts, &a,
                                 &err),
                 BF_OK, "%s", err.msg);
    cr_assert_str_eq(bf_dataset_name(a, 0), "m");
    bf_dataset_free(a);
    cr_assert_eq(bf_dataset_load(bf_test_curet_path("."), &opts, &a, &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(bf_dataset_count(a), 61);
    cr_assert_eq(bf_dataset_format(a, 0), BF_FORMAT_CURET);
    bf_dataset_free(a);
}

Test(format, a_folder_is_read_as_curet)
{
    /* bf_dataset_load does not detect a folder: CURET's reader names the
     * file it lacks (bf_format_detect alone says what the folder lacks) */
    char dir[512];
    char table[600];
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    snprintf(dir, sizeof dir, "%s", bf_test_tmpdir());
    snprintf(table, sizeof table, "%s/table.txt", dir);
    cr_assert_eq(bf_dataset_load(dir, NULL, &ds, &err), BF_EIO);
    cr_assert_null(ds);
    cr_assert_str_eq(err.file, table);
    cr_assert_str_eq(err.msg, "cannot open: No such file or directory");
    rmdir(dir);
}

Test(format, a_forced_format_is_read_as_that_format)
{
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    bf_load_opts opts;
    const char *cayman = bf_test_cornell_path("cayman.brdf");
    memset(&opts, 0, sizeof opts);
    opts.format = BF_FORMAT_CSV;
    cr_assert_eq(bf_dataset_load(cayman, &opts, &ds, &err), BF_EPARSE);
    cr_assert_null(ds);
    cr_assert_eq(err.line, 6); /* the first line that is not a comment */
    cr_assert_str_eq(err.msg,
                     "the header must be [material,]theta_i,phi_i,theta_o,"
                     "phi_o,<channels>: column 1 is \"31\"");
    opts.format = BF_FORMAT_MEMORY;
    cr_assert_eq(bf_dataset_load(cayman, &opts, &ds, &err), BF_EINVAL);
    cr_assert_str_eq(err.msg, "no reader for the format \"memory\"");
}

Test(format, a_merl_table_needs_its_configurations)
{
    /* a full-size table of zeros: every cell valid (0 >= 0) */
    unsigned char *b = calloc(1, 12 + 3 * 1458000 * 8);
    static const unsigned char dims[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    const char *saved;
    bf_table *t = bf_test_load_table();
    double *at = malloc(4 * bf_table_size(t) * sizeof *at);
    bf_dataset *ds = (bf_dataset *)&ds;
    bf_error err;
    bf_load_opts opts;
    cr_assert_not_null(b);
    memcpy(b, dims, sizeof dims);
    saved = file_with("gold.binary", b, 12 + 3 * 1458000 * 8);
    free(b);
    memset(&opts, 0, sizeof opts);
    cr_assert_eq(bf_dataset_load(saved, &opts, &ds, &err), BF_EINVAL);
    cr_assert_null(ds);
    cr_assert_str_eq(err.file, saved);
    cr_assert_str_eq(err.msg, "a MERL table is fitted at chosen "
                              "configurations, and none were given");
    /* CURET's 205, the default of the command line */
    bf_table_angles(t, at);
    opts.n_at = bf_table_size(t);
    opts.at = at;
    cr_assert_eq(bf_dataset_load(saved, &opts, &ds, &err), BF_OK, "%s",
                 err.msg);
    cr_assert_eq(bf_dataset_nconf(ds, 0), 205);
    cr_assert_str_eq(bf_dataset_name(ds, 0), "gold");
    cr_assert_str_eq(bf_dataset_source(ds, 0), saved);
    cr_assert_eq(bf_dataset_format(ds, 0), BF_FORMAT_MERL);
    cr_assert_eq(memcmp(bf_dataset_angles(ds, 0), at, 205 * 4 * sizeof *at),
                 0);
    bf_dataset_free(ds);
    /* every valid cell: all_cells wins over given configurations */
    opts.all_cells = 1;
    cr_assert_eq(bf_dataset_load(saved, &opts, &ds, &err), BF_OK);
    /* the centres above the horizon: tests/ref/merl_cells.py */
    cr_assert_eq(bf_dataset_nconf(ds, 0), 1096216);
    bf_dataset_free(ds);
    bf_table_free(t);
    free(at);
}
