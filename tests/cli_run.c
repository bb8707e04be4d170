/* cli_run.c: runs the brdffit binary from tests (see cli_run.h). */
#include "cli_run.h"
#include "support.h"

#include <criterion/criterion.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define CAPTURE_MAX (4u << 20)

static char out_buf[CAPTURE_MAX];
static char err_buf[CAPTURE_MAX];

static void read_all(int fd, char *buf)
{
    size_t len = 0;
    ssize_t r;
    FILE *fp = fdopen(fd, "r");
    cr_assert_not_null(fp);
    rewind(fp);
    while ((r = (ssize_t)fread(buf + len, 1, CAPTURE_MAX - 1 - len, fp)) > 0) {
        len += (size_t)r;
    }
    buf[len] = '\0';
    fclose(fp);
}

/* Runs path with args (argv[0] first, NULL-terminated), stdin from
 * /dev/null, stdout into fo and stderr into fe (may be fo); returns the
 * wait status. */
static int run_child(const char *path, const char *const *args, FILE *fo,
                     FILE *fe)
{
    pid_t pid;
    int status;
    fflush(NULL);
    pid = fork();
    cr_assert_geq(pid, 0, "fork failed");
    if (pid == 0) {
        int devnull = open("/dev/null", O_RDONLY);
        dup2(devnull, 0);
        dup2(fileno(fo), 1);
        dup2(fileno(fe), 2);
        execv(path, (char *const *)(uintptr_t)args);
        _exit(127);
    }
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    return status;
}

int bf_test_run_cli(const char *const *argv, const char **out,
                    const char **err)
{
    FILE *fo = tmpfile();
    FILE *fe = tmpfile();
    const char *args[64];
    size_t n = 0;
    int status;

    cr_assert(fo != NULL && fe != NULL);
    args[n++] = BF_CLI_PATH;
    while (argv[n - 1] != NULL) {
        cr_assert_lt(n, 63);
        args[n] = argv[n - 1];
        n++;
    }
    args[n] = NULL;
    status = run_child(BF_CLI_PATH, args, fo, fe);
    read_all(dup(fileno(fo)), out_buf);
    read_all(dup(fileno(fe)), err_buf);
    fclose(fo);
    fclose(fe);
    if (out != NULL) {
        *out = out_buf;
    }
    if (err != NULL) {
        *err = err_buf;
    }
    if (!WIFEXITED(status)) {
        cr_expect_fail("%s did not exit normally (signal %d); stderr:\n%s",
                BF_CLI_PATH, WIFSIGNALED(status) ? WTERMSIG(status) : 0,
                err_buf);
        return -1;
    }
    return WEXITSTATUS(status);
}

int bf_test_run_sh(const char *cmd, const char **out)
{
    const char *args[4] = {"sh", "-c", cmd, NULL};
    FILE *fo = tmpfile();
    int status;
    cr_assert_not_null(fo);
    status = run_child("/bin/sh", args, fo, fo);
    read_all(dup(fileno(fo)), out_buf);
    fclose(fo);
    if (out != NULL) {
        *out = out_buf;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The folders bf_test_tmpdir made in this process, removed with what
 * they hold when it exits (BF_TEST_KEEP set: kept, to look at). */
#define MAX_TMPDIRS 512
static char made[MAX_TMPDIRS][256];
static size_t n_made;

static int remove_entry(const char *path, const struct stat *sb, int flag,
                        struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

static void remove_tmpdirs(void)
{
    size_t i;
    if (getenv("BF_TEST_KEEP") != NULL) {
        return;
    }
    for (i = 0; i < n_made; i++) {
        (void)nftw(made[i], remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    }
}

const char *bf_test_tmpdir(void)
{
    static char dir[256];
    const char *base = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/brdffit-test-XXXXXX",
             base != NULL ? base : "/tmp");
    cr_assert_not_null(mkdtemp(dir), "mkdtemp failed");
    if (n_made == 0) {
        cr_assert_eq(atexit(remove_tmpdirs), 0);
    }
    if (n_made < MAX_TMPDIRS) {
        memcpy(made[n_made++], dir, sizeof dir);
    }
    return dir;
}

const char *bf_test_slurp(const char *path, size_t *len)
{
    static char buf[8u << 20];
    size_t n;
    FILE *fp = fopen(path, "rb");
    if (fp == NULL) {
        return NULL;
    }
    n = fread(buf, 1, sizeof buf - 1, fp);
    buf[n] = '\0';
    fclose(fp);
    if (len != NULL) {
        *len = n;
    }
    return buf;
}

char *bf_test_copy(const char *path, size_t *len)
{
    const char *s = bf_test_slurp(path, len);
    char *c;
    cr_assert_not_null(s, "%s missing", path);
    c = malloc(*len + 1);
    cr_assert_not_null(c);
    memcpy(c, s, *len + 1);
    return c;
}

const char *bf_test_join(const char *dir, const char *name)
{
    static char path[4][2048];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", dir, name);
    return path[k];
}

int bf_test_exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* ==== CSV outputs, found by header name ================================== */

#define CSV_MAX_FIELDS 64
#define CSV_MAX_LINES 4096
static char *csv_cells[CSV_MAX_LINES][CSV_MAX_FIELDS];
static size_t csv_lines;
static size_t csv_cols;
static char csv_text[4u << 20];

size_t bf_test_csv_load(const char *dir, const char *name)
{
    char path[1024];
    const char *text;
    char *save = NULL;
    char *line;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    text = bf_test_slurp(path, NULL);
    cr_assert_not_null(text, "%s missing", path);
    cr_assert_lt(strlen(text), sizeof csv_text);
    strcpy(csv_text, text);
    csv_lines = 0;
    for (line = strtok_r(csv_text, "\n", &save); line != NULL;
         line = strtok_r(NULL, "\n", &save)) {
        size_t nf = 0;
        char *p = line;
        cr_assert_lt(csv_lines, CSV_MAX_LINES);
        while (nf < CSV_MAX_FIELDS) {
            char *e;
            if (*p == '"') { /* a quoted field ("" is a quote) */
                char *w = ++p;
                e = p;
                while (*e != '\0' && !(e[0] == '"' && e[1] != '"')) {
                    *w++ = *e;
                    e += e[0] == '"' ? 2 : 1;
                }
                e = *e == '"' ? e + 1 : e; /* past the closing quote */
                *w = '\0';
                e = *e == ',' ? e : NULL;
            } else {
                e = strchr(p, ',');
            }
            csv_cells[csv_lines][nf++] = p;
            if (e == NULL) {
                break;
            }
            *e = '\0';
            p = e + 1;
        }
        if (csv_lines == 0) {
            csv_cols = nf;
        }
        cr_assert_eq(nf, csv_cols, "%s line %zu", name, csv_lines + 1);
        csv_lines++;
    }
    return csv_lines;
}

size_t bf_test_csv_col(const char *name)
{
    size_t c;
    for (c = 0; c < csv_cols; c++) {
        if (strcmp(csv_cells[0][c], name) == 0) {
            return c;
        }
    }
    cr_assert_fail("no column '%s'", name);
    return 0;
}

const char *bf_test_csv_cell(size_t row, const char *name)
{
    cr_assert_lt(row, csv_lines);
    return csv_cells[row][bf_test_csv_col(name)];
}

double bf_test_csv_num(size_t row, const char *name)
{
    const char *s = bf_test_csv_cell(row, name);
    return s[0] != '\0' ? strtod(s, NULL) : NAN;
}

size_t bf_test_csv_find(const char *sample, const char *model,
                        const char *param)
{
    size_t r;
    for (r = 1; r < csv_lines; r++) {
        if ((sample == NULL ||
             strcmp(csv_cells[r][bf_test_csv_col("sample")], sample) == 0) &&
            strcmp(csv_cells[r][bf_test_csv_col("model")], model) == 0 &&
            (param == NULL ||
             strcmp(csv_cells[r][bf_test_csv_col("parameter")], param) == 0)) {
            return r;
        }
    }
    cr_assert_fail("no row for sample %s, %s %s", sample ? sample : "*",
                   model, param ? param : "");
    return 0;
}

int bf_test_run_curet(const char **argv)
{
    static char data[4096];
    size_t i;
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    for (i = 0; argv[i] != NULL; i++) {
        if (strcmp(argv[i], "DATA") == 0) {
            argv[i] = data;
        }
    }
    return bf_test_run_cli(argv, NULL, NULL);
}
