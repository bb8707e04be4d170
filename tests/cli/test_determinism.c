/* test_determinism.c: two runs of brdffit with the same inputs give
 * byte-identical outputs -- fits.csv, table2.md, table3.md and the tables
 * on standard output -- on the real CURET data, for the paper's study and
 * for every model on every sample; and the order of the options does not
 * change them. (No figures are written by this CLI; when a plotting
 * command lands, its files belong in the list below.) */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

static const char *const outputs[] = {"fits.csv", "table2.md", "table3.md"};
#define N_OUTPUTS (sizeof outputs / sizeof outputs[0])

/* The outputs of one run: the files' bytes and standard output. */
typedef struct {
    char *file[N_OUTPUTS];
    size_t len[N_OUTPUTS];
    char *out;
} run_result;

static void run_once(const char *const *argv, const char *out_dir,
                     run_result *r)
{
    const char *out = NULL;
    const char *err = NULL;
    size_t i;
    cr_assert_eq(bf_test_run_cli(argv, &out, &err), 0, "%s", err);
    r->out = strdup(out);
    cr_assert_not_null(r->out);
    for (i = 0; i < N_OUTPUTS; i++) {
        char path[1024];
        const char *text;
        snprintf(path, sizeof path, "%s/%s", out_dir, outputs[i]);
        text = bf_test_slurp(path, &r->len[i]);
        cr_assert_not_null(text, "%s missing", path);
        cr_assert_gt(r->len[i], 0u, "%s empty", path);
        r->file[i] = malloc(r->len[i] + 1);
        cr_assert_not_null(r->file[i]);
        memcpy(r->file[i], text, r->len[i] + 1);
    }
}

static void expect_identical(const run_result *a, const run_result *b,
                             const char *what)
{
    size_t i;
    for (i = 0; i < N_OUTPUTS; i++) {
        cr_expect(a->len[i] == b->len[i] &&
                      memcmp(a->file[i], b->file[i], a->len[i]) == 0,
                  "%s: %s differs between the runs", what, outputs[i]);
    }
    cr_expect_str_eq(a->out, b->out, "%s: standard output differs", what);
}

static void free_result(run_result *r)
{
    size_t i;
    for (i = 0; i < N_OUTPUTS; i++) {
        free(r->file[i]);
    }
    free(r->out);
}

/* Runs argv twice into the same output folder, and the reordered argv2
 * once, and compares everything. */
static void check(const char *const *argv, const char *const *argv2,
                  const char *out_dir)
{
    run_result a;
    run_result b;
    run_result c;
    run_once(argv, out_dir, &a);
    run_once(argv, out_dir, &b);
    run_once(argv2, out_dir, &c);
    expect_identical(&a, &b, "same command twice");
    expect_identical(&a, &c, "options in another order");
    free_result(&a);
    free_result(&b);
    free_result(&c);
}

Test(determinism, paper_study_gives_byte_identical_outputs)
{
    char data[4096];
    char on[4096];
    char out_dir[256];
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    snprintf(on, sizeof on, "%s",
             bf_test_reference_path("oren_nayar_params.tsv"));
    snprintf(out_dir, sizeof out_dir, "%s", bf_test_tmpdir());
    {
        const char *argv[] = {"compare", "--data", data, "--samples",
                              "paper", "--on-params", on, "--out", out_dir,
                              NULL};
        const char *argv2[] = {"compare", "--out", out_dir, "--on-params",
                               on, "--samples", "paper", "--data", data,
                               NULL};
        check(argv, argv2, out_dir);
    }
}

Test(determinism, every_model_on_every_sample_gives_byte_identical_outputs)
{
    char data[4096];
    char on[4096];
    char out_dir[256];
    snprintf(data, sizeof data, "%s", bf_test_curet_path("."));
    snprintf(on, sizeof on, "%s",
             bf_test_reference_path("oren_nayar_params.tsv"));
    snprintf(out_dir, sizeof out_dir, "%s", bf_test_tmpdir());
    {
        const char *argv[] = {"compare", "--data", data, "--samples", "all",
                              "--models", "all", "--on-params", on,
                              "--n", "1.55", "--out", out_dir, NULL};
        const char *argv2[] = {"compare", "--n", "1.55", "--models", "all",
                               "--samples", "all", "--out", out_dir,
                               "--on-params", on, "--data", data, NULL};
        check(argv, argv2, out_dir);
    }
}
