/* test_cli.c: the brdffit command line -- help and version, documented exit
 * statuses, error messages naming file and line, atomic outputs (a failed
 * run leaves no file), and `compare --samples all` on the real data. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_run.h"
#include "support.h"

/* Exit statuses documented in README.md, --help and brdffit.1. */
#define EXIT_NOVALUE 61
#define EXIT_CONFLICT 62
#define EXIT_BADVALUE 63
#define EXIT_USAGE 64
#define EXIT_DATAERR 65
#define EXIT_NOINPUT 66
#define EXIT_CANTCREAT 73

/* The first columns of fits.csv (README.md); the analysis columns follow. */
#define CSV_HEADER \
    "sample,name,channel,model,parameter,unit,value,lse,bound_hit,k,"

static void write_file(const char *dir, const char *name, const char *text)
{
    char path[512];
    FILE *fp;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    fp = fopen(path, "w");
    cr_assert_not_null(fp, "cannot write %s", path);
    fputs(text, fp);
    fclose(fp);
}

static int exists(const char *dir, const char *name)
{
    char path[512];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &st) == 0;
}

/* A tiny data folder: 3 configurations (none specular), 2 samples. */
static const char *tiny_data(const char *table, const char *brdf)
{
    const char *dir = bf_test_tmpdir();
    static char copy[256];
    write_file(dir, "table.txt",
               table != NULL ? table
                             : "1 0.2 0.0 0.3 1.0\n"
                               "2 0.5 2.0 0.6 0.5\n"
                               "3 0.9 -1.0 1.1 0.2\n");
    write_file(dir, "abrdf.dat",
               brdf != NULL ? brdf
                            : "1 0.30 0.20 0.10\n"
                              "2 0.25 0.35 0.05\n");
    snprintf(copy, sizeof copy, "%s", dir);
    return copy;
}

static size_t count_entries(const char *dir)
{
    char cmd[600];
    FILE *p;
    size_t n = 0;
    int ch;
    snprintf(cmd, sizeof cmd, "ls -A '%s'", dir);
    p = popen(cmd, "r");
    cr_assert_not_null(p);
    while ((ch = fgetc(p)) != EOF) {
        n += ch == '\n';
    }
    pclose(p);
    return n;
}

Test(cli, help_and_version_succeed_and_describe_the_tool)
{
    const char *out = NULL;
    const char *a1[] = {"--help", NULL};
    const char *a2[] = {"--version", NULL};
    const char *a3[] = {"compare", "--help", NULL};
    cr_assert_eq(bf_test_run_cli(a1, &out, NULL), 0);
    cr_assert(strstr(out, "compare") != NULL);
    cr_assert(strstr(out, "Exit status") != NULL);
    cr_assert_eq(bf_test_run_cli(a2, &out, NULL), 0);
    cr_assert(strncmp(out, "brdffit ", 8) == 0, "%s", out);
    cr_assert(strstr(out, bf_version()) != NULL);
    cr_assert_eq(bf_test_run_cli(a3, &out, NULL), 0);
    cr_assert(strstr(out, "--samples") != NULL);
    cr_assert(strstr(out, "--on-params") != NULL);
}

Test(cli, each_kind_of_usage_error_has_its_code_a_one_line_reason_and_a_hint)
{
    const char *err = NULL;
    const char *out = NULL;
    const char *cases[][5] = {
        {"compare", "--bogus", NULL, NULL, NULL},
        {"models", "extra", "more", NULL, NULL},
        {"models", "extra", NULL, NULL, NULL},
        {"nosuchcommand", NULL, NULL, NULL, NULL},
        {"compare", "--samples", NULL, NULL, NULL},
        {"compare", "--n", "1.5", "--n-file", NULL},
        {NULL, NULL, NULL, NULL, NULL},
        {"compare", "--n", "1.5", "--n-file", "x.tsv"},
        {"compare", "--n", "0.5", NULL, NULL},
        {"compare", "--n", "abc", NULL, NULL},
        {"compare", "--n", "1e999", NULL, NULL},
        {"compare", "--models", "XX", NULL, NULL},
        {"compare", "--models", "ON,ON", NULL, NULL},
        {"compare", "--samples", "3-1", NULL, NULL},
        {"compare", "--samples", "0", NULL, NULL},
        {"compare", "--exclude", "1,", NULL, NULL},
        {"compare", "--max-theta", "120", NULL, NULL},
        {"compare", "--max-theta", "nan", NULL, NULL},
        {"compare", "--threads", "-1", NULL, NULL},
        {"compare", "--threads", "1.5", NULL, NULL},
    };
    static const int code[] = {
        EXIT_USAGE,    EXIT_USAGE,    EXIT_USAGE,    EXIT_USAGE,
        EXIT_NOVALUE,  EXIT_NOVALUE,  EXIT_NOVALUE,  EXIT_CONFLICT,
        EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE,
        EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE,
        EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE,
    };
    static const char *const expect[] = {
        "unknown option '--bogus'",
        "unexpected argument 'extra'",
        "unexpected argument 'extra'",
        "unknown command 'nosuchcommand'",
        "option '--samples' needs a value",
        "option '--n-file' needs a value",
        "no command given",
        "--n and --n-file cannot be combined",
        "--n: '0.5' is not a refractive index in (1, 10]",
        "--n: 'abc' is not a refractive index",
        "--n: '1e999' is not a refractive index",
        "unknown model 'XX'",
        "'ON' listed twice",
        "bad range",
        "expected a positive number",
        "trailing comma",
        "--max-theta: '120' is not an angle in (0, 90] degrees",
        "--max-theta: 'nan' is not an angle",
        "--threads",
        "--threads",
    };
    size_t i;
    cr_assert_eq(sizeof cases / sizeof *cases, sizeof code / sizeof *code);
    cr_assert_eq(sizeof cases / sizeof *cases,
                 sizeof expect / sizeof *expect);
    for (i = 0; i < sizeof cases / sizeof *cases; i++) {
        const char *argv[6] = {NULL};
        const char *nl;
        const char *why;
        memcpy(argv, cases[i], sizeof cases[i]);
        cr_expect_eq(bf_test_run_cli(argv, &out, &err), code[i],
                     "case %zu (%s)", i, expect[i]);
        cr_expect_str_empty(out, "case %zu: stdout not empty", i);
        /* one line naming the problem, then the hint to run --help */
        nl = strchr(err, '\n');
        cr_assert_not_null(nl, "case %zu: %s", i, err);
        why = strstr(err, expect[i]);
        cr_expect(strncmp(err, "brdffit: ", 9) == 0, "case %zu: %s", i, err);
        cr_expect(why != NULL && why < nl,
                  "case %zu: reason not on the first line: %s", i, err);
        cr_expect(strncmp(nl + 1, "Try 'brdffit ", 13) == 0 &&
                      strstr(nl + 1, "--help' for more information.\n") !=
                          NULL,
                  "case %zu: no hint: %s", i, err);
        cr_expect(strchr(nl + 1, '\n')[1] == '\0',
                  "case %zu: more than two lines: %s", i, err);
    }
}

Test(cli, missing_data_folder_exits_66)
{
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", "/nonexistent/curet", NULL};
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_NOINPUT);
    cr_assert(strstr(err, "/nonexistent/curet") != NULL, "%s", err);
}

Test(cli, tiny_data_set_fits_and_writes_all_outputs)
{
    const char *data = tiny_data(NULL, NULL);
    char out_dir[300];
    const char *out = NULL;
    const char *csv;
    const char *argv[] = {"compare", "--data", data, "--samples", "1,2",
                          "--models", "lambert,LFTG", "--out", out_dir, NULL};
    snprintf(out_dir, sizeof out_dir, "%s/out", data);
    cr_assert_eq(bf_test_run_cli(argv, &out, NULL), 0);
    cr_assert(strstr(out, "K = 3 of 3") != NULL, "%s", out);
    cr_assert(exists(out_dir, "fits.csv"));
    cr_assert(exists(out_dir, "table2.md"));
    cr_assert(exists(out_dir, "table3.md"));
    cr_assert_eq(count_entries(out_dir), 3u, "no temporary file is left");
    snprintf(out_dir + strlen(out_dir), 20, "/fits.csv");
    csv = bf_test_slurp(out_dir, NULL);
    cr_assert(strncmp(csv, CSV_HEADER, strlen(CSV_HEADER)) == 0, "%s", csv);
    cr_assert(strstr(csv, ",ci_low,ci_high,") != NULL, "%s", csv);
    /* no samples.tsv: no names; the default channel is the mean */
    cr_assert(strstr(csv, "\n1,,mean,LAMBERT,,,,") != NULL, "%s", csv);
    cr_assert(strstr(csv, "\n2,,mean,LFTG,n_d,1,") != NULL, "%s", csv);
}

Test(cli, malformed_input_names_file_and_line_and_leaves_no_output)
{
    const char *data = tiny_data(NULL, "1 0.30 0.20 0.10\n"
                                       "2 0.25 oops 0.05\n");
    char out_dir[300];
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", data, "--samples", "1,2",
                          "--models", "LAMBERT", "--out", out_dir, NULL};
    snprintf(out_dir, sizeof out_dir, "%s/out", data);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_DATAERR);
    cr_assert(strstr(err, "abrdf.dat:2:") != NULL, "%s", err);
    cr_assert(strstr(err, "oops") != NULL, "%s", err);
    cr_assert(!exists(data, "out"), "no output folder on failure");
}

Test(cli, sample_with_no_positive_radiance_is_a_data_error)
{
    const char *data = tiny_data(NULL, "1 0.30 0.20 0.10\n"
                                       "2 0.00 -0.01 0.00\n");
    char out_dir[300];
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", data, "--samples", "2",
                          "--models", "LAMBERT", "--out", out_dir, NULL};
    snprintf(out_dir, sizeof out_dir, "%s/out", data);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_DATAERR);
    cr_assert(strstr(err, "sample 2: the measured radiance has no positive "
                          "maximum") != NULL,
              "%s", err);
    cr_assert(!exists(data, "out"), "no output folder on failure");
}

Test(cli, unknown_sample_is_an_out_of_range_value)
{
    const char *data = tiny_data(NULL, NULL);
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", data, "--samples", "3",
                          "--models", "LAMBERT", NULL};
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_BADVALUE);
    cr_assert(strstr(err, "sample 3 is not in the BRDF file") != NULL, "%s",
              err);
}

Test(cli, output_folder_that_cannot_be_created_exits_73)
{
    const char *data = tiny_data(NULL, NULL);
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", data, "--samples", "1",
                          "--models", "LAMBERT", "--out",
                          "/nonexistent/deeper/out", NULL};
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_CANTCREAT);
    cr_assert(strstr(err, "/nonexistent/deeper/out") != NULL, "%s", err);
}

Test(cli, failed_run_keeps_the_previous_outputs_untouched)
{
    /* A second run that fails must not replace or truncate the first run's
     * files (outputs are written by rename, after every check). */
    const char *data = tiny_data(NULL, NULL);
    char out_dir[300];
    char csv_path[320];
    char *before;
    const char *after;
    const char *ok[] = {"compare", "--data", data, "--samples", "1",
                        "--models", "LAMBERT", "--out", out_dir, "-q", NULL};
    const char *bad[] = {"compare", "--data", data, "--samples", "1",
                         "--models", "LAMBERT", "--exclude", "1-3",
                         "--out", out_dir, NULL};
    snprintf(out_dir, sizeof out_dir, "%s/out", data);
    snprintf(csv_path, sizeof csv_path, "%s/fits.csv", out_dir);
    cr_assert_eq(bf_test_run_cli(ok, NULL, NULL), 0);
    before = strdup(bf_test_slurp(csv_path, NULL));
    cr_assert_eq(bf_test_run_cli(bad, NULL, NULL), EXIT_BADVALUE);
    after = bf_test_slurp(csv_path, NULL);
    cr_assert_str_eq(after, before);
    cr_assert_eq(count_entries(out_dir), 3u);
    free(before);
}

Test(cli, exclude_and_max_theta_shrink_the_reported_selection)
{
    const char *out = NULL;
    char data[4096];
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", data, "--samples", "1",
                          "--models", "LAMBERT", "--exclude", "1-4,17",
                          "--out", dir, NULL};
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    cr_assert_eq(bf_test_run_cli(argv, &out, NULL), 0);
    cr_assert(strstr(out, "K = 193 of 205 used; left out: 1 2 3 4 17 54 97 "
                          "131 161 183 196 202") != NULL,
              "%s", out);
}

Test(cli, all_61_samples_give_finite_results_for_every_model)
{
    char data[4096];
    char csv_path[512];
    const char *dir = bf_test_tmpdir();
    const char *csv;
    const char *line;
    size_t rows = 0;
    const char *argv[] = {"compare", "--data", data, "--samples", "all",
                          "--models", "all", "--on-params", NULL, "--out",
                          dir, "-q", NULL};
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    argv[8] = bf_test_reference_path("oren_nayar_params.tsv");
    cr_assert_eq(bf_test_run_cli(argv, NULL, NULL), 0);
    snprintf(csv_path, sizeof csv_path, "%s/fits.csv", dir);
    csv = bf_test_slurp(csv_path, NULL);
    cr_assert_not_null(csv);
    for (line = strchr(csv, '\n'); line != NULL && line[1] != '\0';
         line = strchr(line + 1, '\n')) {
        char f[9][64];
        int n = sscanf(line + 1,
                       "%63[^,],%63[^,],%63[^,],%63[^,],%63[^,],%63[^,],"
                       "%63[^,],%63[^,],%63[^\n]",
                       f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8]);
        rows++;
        if (n == 9) { /* a fitted parameter: value and LSE finite */
            cr_assert(isfinite(strtod(f[5], NULL)), "%.80s", line + 1);
            cr_assert(isfinite(strtod(f[6], NULL)), "%.80s", line + 1);
        }
        cr_assert(strstr(line + 1, "nan") == NULL, "%.80s", line + 1);
        cr_assert(strstr(line + 1, "inf") == NULL, "%.80s", line + 1);
    }
    /* a row per fitted parameter (one for a model that fits none) for
     * every diffuse registry model (--models all; SPEC §9's are fitted
     * under SPEC §10) and all 61 samples, ON for the 24 samples whose
     * parameters are given */
    {
        size_t want = 0;
        size_t i;
        for (i = 0; i < bf_model_count(); i++) {
            const bf_model_type *t = bf_model_get(i);
            size_t fitted = 0;
            size_t j;
            if (t->kind != BF_MODEL_DIFFUSE) {
                continue;
            }
            for (j = 0; j < t->p; j++) {
                fitted += t->param[j].fitted != 0;
            }
            want += (t == bf_model_on ? 24u : 61u) * (fitted ? fitted : 1u);
        }
        cr_assert_eq(rows, want, "%zu rows, %zu expected", rows, want);
    }
}

/* --threads changes who computes, never what: fits.csv of the paper's study
 * is byte for byte the same on 1, 2 and one-per-core threads. */
Test(cli, thread_count_does_not_change_the_outputs)
{
    char data[4096];
    char path[512];
    char first[1 << 16];
    static const char *const threads[] = {"1", "2", "0"};
    size_t len0 = 0;
    size_t i;
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    for (i = 0; i < sizeof threads / sizeof threads[0]; i++) {
        const char *dir = bf_test_tmpdir();
        const char *argv[] = {"compare", "--data", data, "--on-params", NULL,
                              "--threads", threads[i], "--out", dir, "-q",
                              NULL};
        const char *csv;
        size_t len = 0;
        argv[4] = bf_test_reference_path("oren_nayar_params.tsv");
        cr_assert_eq(bf_test_run_cli(argv, NULL, NULL), 0, "--threads %s",
                     threads[i]);
        snprintf(path, sizeof path, "%s/fits.csv", dir);
        csv = bf_test_slurp(path, &len);
        cr_assert_not_null(csv);
        cr_assert_lt(len, sizeof first);
        if (i == 0) {
            memcpy(first, csv, len);
            len0 = len;
        } else {
            cr_assert_eq(len, len0, "--threads %s", threads[i]);
            cr_assert_eq(memcmp(csv, first, len), 0, "--threads %s",
                         threads[i]);
        }
    }
}

Test(cli, unusable_out_folders_exit_73_before_any_work_and_create_nothing)
{
    /* --out is checked before the inputs are read: a bad --data is not
     * reported, the output problem is. Cases: missing parent folder, a file
     * where a folder is expected (as --out and as its parent), and a folder
     * that cannot be written. Tests run as root here, for whom permission
     * bits grant everything (access(W_OK) is true), so the read-only case
     * uses /proc, where no file can be created whatever the user; a
     * non-root run also checks a mode-0555 folder. */
    const char *dir = bf_test_tmpdir();
    char file[300];
    char under_file[320];
    char ro[300];
    char ro_out[320];
    const char *err = NULL;
    const char *targets[5];
    size_t n = 0;
    size_t i;
    snprintf(file, sizeof file, "%s/plain", dir);
    snprintf(under_file, sizeof under_file, "%s/plain/out", dir);
    write_file(dir, "plain", "not a folder\n");
    targets[n++] = "/nonexistent/deeper/out";
    targets[n++] = file;
    targets[n++] = under_file;
    targets[n++] = "/proc/brdffit-out";
    if (geteuid() != 0) {
        snprintf(ro, sizeof ro, "%s/ro", dir);
        snprintf(ro_out, sizeof ro_out, "%s/ro/out", dir);
        cr_assert_eq(mkdir(ro, 0555), 0);
        targets[n++] = ro_out;
    }
    for (i = 0; i < n; i++) {
        const char *argv[] = {"compare", "--data", "/nonexistent/curet",
                              "--out", targets[i], NULL};
        cr_expect_eq(bf_test_run_cli(argv, NULL, &err), EXIT_CANTCREAT,
                     "--out %s", targets[i]);
        cr_expect(strstr(err, targets[i]) != NULL, "%s", err);
        cr_expect(strstr(err, "/nonexistent/curet") == NULL,
                  "inputs read before --out was checked: %s", err);
        cr_expect(strchr(err, '\n')[1] == '\0', "one line: %s", err);
    }
    cr_assert_eq(count_entries(dir), n > 4 ? 2u : 1u, "nothing created");
}
