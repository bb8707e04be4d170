/* test_corpus.c: the malformed-input corpus, run through the brdffit CLI.
 *
 * Every committed case in tests/corpus/files/ has one line in
 * tests/corpus/expect.tsv giving its exact outcome; the cases that cannot
 * be committed as files (NUL bytes, binary garbage, a 1 MiB line, a
 * directory, a FIFO, a device, a missing or unreadable file) are made here
 * at test time. For every case:
 *   - a rejected input exits with the expected status, prints nothing on
 *     standard output and exactly one line on standard error:
 *     "brdffit: FILE:LINE: problem" (the whole line is compared);
 *   - it creates no output and touches none: the output folder holds a
 *     previous run's fits.csv, which keeps its bytes and its mtime and
 *     stays the only entry;
 *   - an accepted input exits 0 and gives the fits.csv stated in
 *     expect.tsv (equal to the clean files' run, or containing a value
 *     computed by hand there). */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_DATAERR 65
#define EXIT_NOINPUT 66

/* The tiny valid data folder every case starts from: 3 configurations
 * (none specular), samples 1 and 2 (the same as tests/cli/test_cli.c). */
static const char clean_table[] = "1 0.2 0.0 0.3 1.0\n"
                                  "2 0.5 2.0 0.6 0.5\n"
                                  "3 0.9 -1.0 1.1 0.2\n";
static const char clean_brdf[] = "1 0.30 0.20 0.10\n"
                                 "2 0.25 0.35 0.05\n";

/* What a previous run left in the output folder. */
static const char previous[] = "sample,name,model\nprevious run\n";

/* Longest line of expect.tsv, longest data folder name (a temporary
 * folder) and longest path. */
#define LINE_LEN 1024
#define DATA_LEN 256
#define PATH_LEN 1024

static void write_bytes(const char *path, const void *buf, size_t len)
{
    FILE *fp = fopen(path, "wb");
    cr_assert_not_null(fp, "cannot write %s", path);
    cr_assert_eq(fwrite(buf, 1, len, fp), len);
    cr_assert_eq(fclose(fp), 0);
}

static void write_text(const char *dir, const char *name, const char *text)
{
    char path[2 * PATH_LEN];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    write_bytes(path, text, strlen(text));
}

/* A fresh data folder with the clean files and an output folder holding
 * a previous run's fits.csv; the folder's path is copied into data. */
static void fresh_data(char *data, size_t len)
{
    char out[PATH_LEN];
    snprintf(data, len, "%s", bf_test_tmpdir());
    write_text(data, "table.txt", clean_table);
    write_text(data, "abrdf.dat", clean_brdf);
    snprintf(out, sizeof out, "%s/out", data);
    cr_assert_eq(mkdir(out, 0755), 0);
    write_text(out, "fits.csv", previous);
}

/* Asserts that DATA/out still holds only the previous fits.csv, unchanged
 * in bytes and mtime (st_before). */
static void expect_out_untouched(const char *data, const struct stat *before,
                                 const char *what)
{
    char path[PATH_LEN];
    struct stat after;
    const char *text;
    size_t entries = 0;
    FILE *p;
    int ch;
    snprintf(path, sizeof path, "%s/out/fits.csv", data);
    text = bf_test_slurp(path, NULL);
    cr_expect(text != NULL && strcmp(text, previous) == 0,
              "%s: the previous fits.csv was changed", what);
    cr_assert_eq(stat(path, &after), 0);
    cr_expect(after.st_mtim.tv_sec == before->st_mtim.tv_sec &&
                  after.st_mtim.tv_nsec == before->st_mtim.tv_nsec,
              "%s: the previous fits.csv was touched", what);
    snprintf(path, sizeof path, "ls -A '%s/out'", data);
    p = popen(path, "r");
    cr_assert_not_null(p);
    while ((ch = fgetc(p)) != EOF) {
        entries += ch == '\n';
    }
    pclose(p);
    cr_expect_eq(entries, 1u, "%s: files created in the output folder", what);
}

/* The arguments of compare on the data folder with models and one extra
 * option (opt NULL: none), output to DATA/out (out_dir, PATH_LEN). */
static void data_args(const char *data, const char *models, const char *opt,
                      const char *value, const char **argv, char *out_dir)
{
    const char *a[12] = {"compare", "--data", data, "--samples", "1,2",
                         "--models", models, "--out", out_dir, NULL};
    snprintf(out_dir, PATH_LEN, "%s/out", data);
    if (opt != NULL) {
        a[9] = opt;
        a[10] = value;
    }
    memcpy(argv, a, sizeof a);
}

/* The arguments of compare --input FILE with models and one extra option
 * (--input-format F, --configs FILE; opt NULL: none), every material,
 * output to DATA/out. */
static void input_args(const char *data, const char *models,
                       const char *input, const char *opt, const char *value,
                       const char **argv, char *out_dir)
{
    const char *a[12] = {"compare", "--input", input, "--models", models,
                         "--out",   out_dir, NULL};
    snprintf(out_dir, PATH_LEN, "%s/out", data);
    if (opt != NULL) {
        a[7] = opt;
        a[8] = value;
    }
    memcpy(argv, a, sizeof a);
}

static int run(const char *data, const char *models, const char *opt,
               const char *value, const char **out, const char **err)
{
    char out_dir[PATH_LEN];
    const char *argv[12];
    data_args(data, models, opt, value, argv, out_dir);
    return bf_test_run_cli(argv, out, err);
}

/* Runs argv, a case expected to fail, and checks status, the exact
 * message line (prefix only when exact is 0) and the untouched output
 * folder. */
static void expect_rejected_argv(const char *what, const char *data,
                                 const char *const *argv, int status,
                                 const char *message, int exact)
{
    char path[PATH_LEN];
    char line[2 * PATH_LEN];
    struct stat before;
    const char *out = NULL;
    const char *err = NULL;
    int rc;
    snprintf(path, sizeof path, "%s/out/fits.csv", data);
    cr_assert_eq(stat(path, &before), 0);
    rc = bf_test_run_cli(argv, &out, &err);
    cr_expect_eq(rc, status, "%s: exit %d, expected %d; stderr: %s", what,
                 rc, status, err);
    cr_expect_str_empty(out, "%s: standard output not empty", what);
    snprintf(line, sizeof line, "brdffit: %s%s", message, exact ? "\n" : "");
    if (exact) {
        cr_expect(strcmp(err, line) == 0, "%s:\nexpected: %sobtained: %s",
                  what, line, err);
    } else {
        cr_expect(strncmp(err, line, strlen(line)) == 0 &&
                      strchr(err, '\n') == err + strlen(err) - 1,
                  "%s: expected one line starting '%s', got '%s'", what,
                  line, err);
    }
    expect_out_untouched(data, &before, what);
}

/* A case on the data folder (see data_args). */
static void expect_rejected(const char *what, const char *data,
                            const char *models, const char *opt,
                            const char *value, int status,
                            const char *message, int exact)
{
    char out_dir[PATH_LEN];
    const char *argv[12];
    data_args(data, models, opt, value, argv, out_dir);
    expect_rejected_argv(what, data, argv, status, message, exact);
}

/* A case given as --input (see input_args); the message is exact. */
static void expect_input_rejected(const char *what, const char *data,
                                  const char *input, const char *opt,
                                  const char *value, int status,
                                  const char *message)
{
    char out_dir[PATH_LEN];
    const char *argv[12];
    input_args(data, "LAMBERT", input, opt, value, argv, out_dir);
    expect_rejected_argv(what, data, argv, status, message, 1);
}

/* fits.csv of a successful run on data (static buffer of cli_run.c). */
static const char *fits_csv(const char *data)
{
    char path[PATH_LEN];
    snprintf(path, sizeof path, "%s/out/fits.csv", data);
    return bf_test_slurp(path, NULL);
}

/* fits.csv of the clean files (a heap copy). */
static char *baseline_csv(const char *models)
{
    char data[DATA_LEN];
    char *csv;
    fresh_data(data, sizeof data);
    cr_assert_eq(run(data, models, NULL, NULL, NULL, NULL), 0);
    csv = strdup(fits_csv(data));
    cr_assert_not_null(csv);
    return csv;
}

static void copy_file(const char *from, const char *to)
{
    size_t len = 0;
    const char *text = bf_test_slurp(from, &len);
    cr_assert_not_null(text, "corpus file %s is missing", from);
    write_bytes(to, text, len);
}

/* Splits a tab-separated line into at most n fields in place. */
static size_t split_tabs(char *s, char **field, size_t n)
{
    size_t k = 0;
    while (k < n) {
        field[k++] = s;
        s = strchr(s, '\t');
        if (s == NULL) {
            break;
        }
        *s++ = '\0';
    }
    return k;
}

/* Copies text into buf, replacing each "{DATA}" by the data folder. */
static void expand_data(char *buf, size_t len, const char *text,
                        const char *data)
{
    size_t at = 0;
    while (*text != '\0' && at + 1 < len) {
        if (strncmp(text, "{DATA}", 6) == 0) {
            at += (size_t)snprintf(buf + at, len - at, "%s", data);
            text += 6;
        } else {
            buf[at++] = *text++;
        }
    }
    buf[at < len ? at : len - 1] = '\0';
}

/* Runs a case of role input or input-FORMAT (--input CASE, with
 * --input-format FORMAT): the file is given in place. */
static void run_input_line(char *const *f, const char *data,
                           const char *case_path)
{
    const char *fmt = f[1][5] == '-' ? f[1] + 6 : NULL;
    char out_dir[PATH_LEN];
    char message[2 * PATH_LEN];
    const char *argv[12];
    int status = atoi(f[3]);
    input_args(data, f[2], case_path, fmt != NULL ? "--input-format" : NULL,
               fmt, argv, out_dir);
    if (status == 0) {
        const char *csv;
        cr_expect_eq(bf_test_run_cli(argv, NULL, NULL), 0, "%s", f[0]);
        csv = fits_csv(data);
        cr_assert(strncmp(f[5], "csv:", 4) == 0, "%s", f[5]);
        cr_expect(csv != NULL && strstr(csv, f[5] + 4) != NULL,
                  "%s: %s not in %s", f[0], f[5] + 4, csv);
        return;
    }
    cr_assert_str_eq(f[4], "case", "%s: an input case names itself", f[0]);
    snprintf(message, sizeof message, "%s", case_path);
    expand_data(message + strlen(message), sizeof message - strlen(message),
                f[5], data);
    expect_rejected_argv(f[0], data, argv, status, message, 1);
}

/* Runs the case described by one line of expect.tsv. */
static void run_expect_line(char *line, const char *baseline)
{
    char *f[6];
    char data[DATA_LEN];
    char case_path[PATH_LEN];
    char given[PATH_LEN];
    char named[PATH_LEN];
    char message[2 * PATH_LEN];
    const char *opt = NULL;
    int status;
    cr_assert_eq(split_tabs(line, f, 6), 6u, "bad expect.tsv line: %s", line);
    fresh_data(data, sizeof data);
    snprintf(case_path, sizeof case_path, "%s/files/%s", BF_CORPUS_DIR, f[0]);
    snprintf(given, sizeof given, "%s", case_path);
    if (strncmp(f[1], "input", 5) == 0) {
        run_input_line(f, data, case_path);
        return;
    }
    if (strcmp(f[1], "table") == 0) {
        snprintf(given, sizeof given, "%s/table.txt", data);
        copy_file(case_path, given);
    } else if (strcmp(f[1], "names") == 0) {
        snprintf(given, sizeof given, "%s/samples.tsv", data);
        copy_file(case_path, given);
    } else if (strcmp(f[1], "brdf") == 0) {
        opt = "--brdf";
    } else if (strcmp(f[1], "on") == 0) {
        opt = "--on-params";
    } else {
        cr_assert_str_eq(f[1], "nfile", "unknown role in expect.tsv");
        opt = "--n-file";
    }
    status = atoi(f[3]);
    if (status == 0) {
        const char *csv;
        cr_expect_eq(run(data, f[2], opt, given, NULL, NULL), 0, "%s", f[0]);
        csv = fits_csv(data);
        if (strcmp(f[5], "same") == 0) {
            cr_expect(strcmp(csv, baseline) == 0,
                      "%s: results differ:\n%s\nclean files:\n%s", f[0], csv,
                      baseline);
        } else {
            cr_assert(strncmp(f[5], "csv:", 4) == 0, "%s", f[5]);
            cr_expect(strstr(csv, f[5] + 4) != NULL, "%s: %s not in %s",
                      f[0], f[5] + 4, csv);
        }
        return;
    }
    if (strcmp(f[4], "case") == 0) {
        snprintf(named, sizeof named, "%s", given);
    } else if (strcmp(f[4], "abrdf") == 0) {
        snprintf(named, sizeof named, "%s/abrdf.dat", data);
    } else {
        named[0] = '\0';
    }
    snprintf(message, sizeof message, "%s", named);
    expand_data(message + strlen(message), sizeof message - strlen(message),
                f[5], data);
    expect_rejected(f[0], data, f[2], opt, given, status, message,
                    named[0] != '\0');
}

Test(corpus, every_committed_case_has_the_outcome_stated_in_expect_tsv)
{
    char path[PATH_LEN];
    char line[LINE_LEN];
    char *baseline = baseline_csv("LAMBERT");
    size_t cases = 0;
    FILE *fp;
    snprintf(path, sizeof path, "%s/expect.tsv", BF_CORPUS_DIR);
    fp = fopen(path, "r");
    cr_assert_not_null(fp, "%s is missing", path);
    while (fgets(line, sizeof line, fp) != NULL) {
        size_t len = strlen(line);
        cr_assert(len > 0 && line[len - 1] == '\n', "line too long: %s",
                  line);
        line[len - 1] = '\0';
        if (line[0] == '#' || line[0] == '\0') {
            continue;
        }
        run_expect_line(line, baseline);
        cases++;
    }
    fclose(fp);
    free(baseline);
    /* every file of files/ is listed, and nothing else */
    snprintf(path, sizeof path, "ls '%s/files' | wc -l", BF_CORPUS_DIR);
    fp = popen(path, "r");
    cr_assert_not_null(fp);
    cr_assert_not_null(fgets(line, sizeof line, fp));
    pclose(fp);
    cr_expect_eq((size_t)atol(line), cases,
                 "files/ holds %ld cases, expect.tsv lists %zu", atol(line),
                 cases);
}

/* ==== cases made at test time =========================================== */

Test(corpus, nul_byte_in_the_table_is_rejected_at_its_line_and_column)
{
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    static const char text[] = "1 0.2 0.0 0.3 1.0\n2 0.\0 2.0 0.6 0.5\n"
                               "3 0.9 -1.0 1.1 0.2\n";
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/table.txt", data);
    write_bytes(path, text, sizeof text - 1);
    snprintf(message, sizeof message,
             "%s:2: NUL byte at column 5 (binary file?)", path);
    expect_rejected("NUL byte", data, "LAMBERT", NULL, NULL, EXIT_DATAERR,
                    message, 1);
}

Test(corpus, binary_garbage_given_as_brdf_file_is_rejected)
{
    /* 4 KiB of bytes 0x80-0xFF from a fixed linear congruential sequence:
     * no blank, no line end, no NUL, so the file is one line of one field
     * and the reader finds no value after it. */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    unsigned char buf[4096];
    unsigned long x = 12345;
    size_t k;
    for (k = 0; k < sizeof buf; k++) {
        x = (x * 1103515245ul + 12345ul) & 0x7ffffffful;
        buf[k] = (unsigned char)(0x80u | (x >> 16));
    }
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/garbage.bin", data);
    write_bytes(path, buf, sizeof buf);
    snprintf(message, sizeof message,
             "%s:1: expected 3 values after the sample number, found 0",
             path);
    expect_rejected("binary garbage", data, "LAMBERT", "--brdf", path,
                    EXIT_DATAERR, message, 1);
}

Test(corpus, line_longer_than_1_mib_is_rejected_without_reading_it_all)
{
    /* Line cap of the readers: 1 MiB (brdffit.h). A 2 MiB line of digits
     * after a valid first line. */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    size_t len = (size_t)2 << 20;
    char *buf = malloc(len + 32);
    size_t head;
    cr_assert_not_null(buf);
    head = (size_t)sprintf(buf, "1 0.30 0.20 0.10\n2 ");
    memset(buf + head, '7', len);
    buf[head + len] = '\n';
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/long.dat", data);
    write_bytes(path, buf, head + len + 1);
    free(buf);
    snprintf(message, sizeof message, "%s:2: line longer than 1048576 bytes",
             path);
    expect_rejected("1 MiB line", data, "LAMBERT", "--brdf", path,
                    EXIT_DATAERR, message, 1);
}

Test(corpus, directory_given_as_a_file_is_rejected)
{
    char data[DATA_LEN];
    char message[2 * PATH_LEN];
    fresh_data(data, sizeof data);
    snprintf(message, sizeof message, "%s: is a directory, not a data file",
             data);
    expect_rejected("directory", data, "LAMBERT", "--brdf", data,
                    EXIT_NOINPUT, message, 1);
}

Test(corpus, device_given_as_a_file_is_rejected)
{
    char data[DATA_LEN];
    fresh_data(data, sizeof data);
    expect_rejected("/dev/null", data, "ON", "--on-params", "/dev/null",
                    EXIT_NOINPUT,
                    "/dev/null: not a regular file or pipe", 1);
}

Test(corpus, missing_file_is_rejected_with_the_system_reason)
{
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/no-such-file.tsv", data);
    snprintf(message, sizeof message,
             "%s: cannot open: No such file or directory", path);
    expect_rejected("missing file", data, "FC-E", "--n-file", path,
                    EXIT_NOINPUT, message, 1);
}

Test(corpus, file_that_cannot_be_read_is_rejected_with_the_system_reason)
{
    /* Tests run as root here, and permission bits do not stop root, so a
     * mode-000 file would be read. /proc/self/mem opens (a regular file)
     * but reading its first page fails with EIO whoever the user: the
     * reader's read-error path. A non-root run also checks mode 000. */
    char data[DATA_LEN];
    fresh_data(data, sizeof data);
    expect_rejected("unreadable", data, "ON", "--on-params",
                    "/proc/self/mem", EXIT_NOINPUT,
                    "/proc/self/mem:1: read error: Input/output error", 1);
    if (geteuid() != 0) {
        char path[PATH_LEN];
        char message[2 * PATH_LEN];
        snprintf(path, sizeof path, "%s/secret.tsv", data);
        write_text(data, "secret.tsv", "sample rho sigma\n1 0.4 0.4\n");
        cr_assert_eq(chmod(path, 0), 0);
        snprintf(message, sizeof message,
                 "%s: cannot open: Permission denied", path);
        expect_rejected("mode 000", data, "ON", "--on-params", path,
                        EXIT_NOINPUT, message, 1);
    }
}

Test(corpus, fifo_is_read_like_a_file_and_its_errors_name_the_line)
{
    /* A FIFO is accepted (brdffit.h): a shell writes a BRDF file with a bad
     * value on line 2 into it while brdffit reads. */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    static const char text[] = "1 0.30 0.20 0.10\n2 0.25 x 0.05\n";
    pid_t writer;
    int status;
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/fifo.dat", data);
    cr_assert_eq(mkfifo(path, 0600), 0);
    writer = fork();
    cr_assert_geq(writer, 0);
    if (writer == 0) {
        /* A fresh program rather than this process's fork: a fork of the
         * test would carry Criterion's state, which valgrind reports as
         * leaked when the fork exits. */
        execl("/bin/sh", "sh", "-c", "printf '%s' \"$1\" > \"$0\"", path,
              text, (char *)NULL);
        _exit(127);
    }
    snprintf(message, sizeof message,
             "%s:2: field 3 (value 2): not a decimal number: \"x\"", path);
    expect_rejected("FIFO", data, "LAMBERT", "--brdf", path, EXIT_DATAERR,
                    message, 1);
    cr_assert_eq(waitpid(writer, &status, 0), writer);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "the writer could not write the FIFO");
}

/* ==== --input cases made at test time =================================== */

/* A MERL file of len bytes in DATA: the dimensions 90, 90, 180 (dims
 * NULL) or dims, then zeros (every cell valid, value 0) up to len. */
static void write_merl(const char *path, const unsigned char *dims,
                       size_t len)
{
    static const unsigned char merl[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    unsigned char *buf = calloc(1, len);
    cr_assert_not_null(buf);
    memcpy(buf, dims != NULL ? dims : merl, len < 12 ? len : 12);
    write_bytes(path, buf, len);
    free(buf);
}

/* Size of a full MERL table (SPEC §8): 12 + 3 x 1,458,000 x 8 bytes. */
#define MERL_BYTES ((size_t)34992012)

Test(corpus, input_binary_garbage_is_no_format)
{
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    static const char bin[] = "\x7f" "ELF\x02\x01\x01\0\0\0";
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/program", data);
    write_bytes(path, bin, sizeof bin - 1);
    snprintf(message, sizeof message,
             "%s: a binary file that is not a MERL table (it does not start "
             "with the int32 dimensions 90, 90, 180)",
             path);
    expect_input_rejected("ELF header", data, path, NULL, NULL, EXIT_DATAERR,
                          message);
}

Test(corpus, input_merl_whose_header_lies_about_the_size)
{
    /* the dimensions imply 34992012 bytes; the file has 1000: refused
     * before anything is allocated, whatever the configurations */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/short.binary", data);
    write_merl(path, NULL, 1000);
    snprintf(message, sizeof message,
             "%s: byte 1000: the file has 1000 bytes, but its dimensions 90 "
             "x 90 x 180 imply 34992012 (3 x 1458000 float64 after the "
             "header)",
             path);
    expect_input_rejected("short MERL", data, path, "--configs", "all",
                          EXIT_DATAERR, message);
    write_merl(path, NULL, MERL_BYTES + 3);
    snprintf(message, sizeof message,
             "%s: byte 34992012: the file has 34992015 bytes, but its "
             "dimensions 90 x 90 x 180 imply 34992012 (3 x 1458000 float64 "
             "after the header)",
             path);
    expect_input_rejected("long MERL", data, path, "--configs", "all",
                          EXIT_DATAERR, message);
}

Test(corpus, input_merl_with_other_dimensions)
{
    /* 90 x 90 x 360 (a full phi_d range): not detected as MERL; read as
     * MERL when the format is forced */
    static const unsigned char d360[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           104, 1, 0, 0};
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/wide.binary", data);
    write_merl(path, d360, 4096);
    snprintf(message, sizeof message,
             "%s: byte 0: dimensions 90 x 90 x 360; a MERL table has 90 x "
             "90 x 180 (theta_h, theta_d, phi_d)",
             path);
    {
        char out_dir[PATH_LEN];
        const char *argv[14] = {"compare", "--input", path, "--models",
                                "LAMBERT", "--out", out_dir,
                                "--input-format", "merl", "--configs",
                                "all", NULL};
        snprintf(out_dir, sizeof out_dir, "%s/out", data);
        expect_rejected_argv("MERL 90 x 90 x 360", data, argv, EXIT_DATAERR,
                             message, 1);
    }
}

Test(corpus, input_merl_at_configurations_of_a_csv_file)
{
    /* A full table of zeros but for R = G = B = 1500 (value 1, 1.15,
     * 1.66): constant per channel, so its radiance is cos theta_i and
     * LAMBERT fits with LSE 0 at any K = 3 configurations; a malformed
     * configuration list is named with its line. */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char configs[PATH_LEN];
    char message[2 * PATH_LEN];
    char out_dir[PATH_LEN];
    const char *argv[12];
    unsigned char *buf = calloc(1, MERL_BYTES);
    static const unsigned char merl[12] = {90, 0, 0, 0, 90, 0, 0, 0,
                                           180, 0, 0, 0};
    const double raw = 1500.0;
    size_t k;
    const char *csv;
    cr_assert_not_null(buf);
    memcpy(buf, merl, 12);
    for (k = 0; k < 3 * (size_t)1458000; k++) {
        memcpy(buf + 12 + 8 * k, &raw, 8); /* little-endian host */
    }
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/flat.binary", data);
    write_bytes(path, buf, MERL_BYTES);
    free(buf);
    write_text(data, "at.csv",
               "theta_i,phi_i,theta_o,phi_o\n20,0,30,180\n40,0,35,90\n"
               "60,0,50,-90\n");
    snprintf(configs, sizeof configs, "%s/at.csv", data);
    input_args(data, "LAMBERT", path, "--configs", configs, argv, out_dir);
    cr_expect_eq(bf_test_run_cli(argv, NULL, NULL), 0);
    csv = fits_csv(data);
    cr_expect(csv != NULL && strstr(csv, "1,flat,mean,LAMBERT,,,,0,0,3,"),
              "%s", csv);
    fresh_data(data, sizeof data);
    write_text(data, "at.csv",
               "theta_i,phi_i,theta_o,phi_o\n20,0,30,180\n40,0,95,90\n");
    snprintf(configs, sizeof configs, "%s/at.csv", data);
    snprintf(message, sizeof message,
             "%s:3: field 3 (theta_o) = 95 outside [0, 90] degrees", configs);
    expect_input_rejected("bad configurations", data, path, "--configs",
                          configs, EXIT_DATAERR, message);
    unlink(path);
}

Test(corpus, input_folder_without_table_and_missing_file)
{
    char data[DATA_LEN];
    char dir[PATH_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    fresh_data(data, sizeof data);
    snprintf(dir, sizeof dir, "%s/empty-folder", data);
    cr_assert_eq(mkdir(dir, 0755), 0);
    /* a folder is read as CURET (brdffit.h): its table is missing */
    snprintf(message, sizeof message,
             "%s/table.txt: cannot open: No such file or directory", dir);
    expect_input_rejected("folder", data, dir, NULL, NULL, EXIT_NOINPUT,
                          message);
    snprintf(path, sizeof path, "%s/no-such.csv", data);
    snprintf(message, sizeof message,
             "%s: cannot open: No such file or directory", path);
    expect_input_rejected("missing input", data, path, NULL, NULL,
                          EXIT_NOINPUT, message);
}

Test(corpus, input_fifo_needs_its_format_and_is_then_read_by_line)
{
    /* detection would consume the pipe: refused; with --input-format csv
     * it is read, and its error names the line */
    char data[DATA_LEN];
    char path[PATH_LEN];
    char message[2 * PATH_LEN];
    static const char text[] =
        "theta_i,phi_i,theta_o,phi_o,R\n20,0,30,180,0.3\n40,0,35,x,0.2\n";
    pid_t writer;
    int status;
    fresh_data(data, sizeof data);
    snprintf(path, sizeof path, "%s/fifo.csv", data);
    cr_assert_eq(mkfifo(path, 0600), 0);
    snprintf(message, sizeof message,
             "%s: a pipe: its format cannot be detected without consuming "
             "it (name the format)",
             path);
    expect_input_rejected("FIFO, no format", data, path, NULL, NULL,
                          EXIT_NOINPUT, message);
    writer = fork();
    cr_assert_geq(writer, 0);
    if (writer == 0) {
        execl("/bin/sh", "sh", "-c", "printf '%s' \"$1\" > \"$0\"", path,
              text, (char *)NULL);
        _exit(127);
    }
    snprintf(message, sizeof message,
             "%s:3: field 4 (phi_o): not a decimal number: \"x\"", path);
    expect_input_rejected("FIFO as csv", data, path, "--input-format", "csv",
                          EXIT_DATAERR, message);
    cr_assert_eq(waitpid(writer, &status, 0), writer);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 0,
              "the writer could not write the FIFO");
}
