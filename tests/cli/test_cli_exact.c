/* test_cli_exact.c: the CLI beyond the paper -- --fit exact, --objective,
 * --range, --bootstrap, the analysis columns of fits.csv (found by header
 * name) and `brdffit rank` (doc/methods.md). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_CONFLICT 62
#define EXIT_BADVALUE 63
#define EXIT_USAGE 64
/* The paper's slope grid step (SPEC §7.4). */
#define GRID_STEP 0.01

/* fits.csv and ranking.csv are read by header name (tests/cli_run.h). */
static size_t n_lines;
#define load_csv(dir, name) (n_lines = bf_test_csv_load((dir), (name)))
#define num(row, name) bf_test_csv_num((row), (name))
#define row_of(model, param) bf_test_csv_find(NULL, (model), (param))

#define run(argv) bf_test_run_curet(argv)

Test(cli_exact, exact_fit_reports_grid_and_refined_optima_side_by_side)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "12",
                          "--models", "VH-E,FC-E", "--fit", "exact",
                          "--bootstrap", "30", "--out", dir, "-q", NULL};
    size_t r;
    cr_assert_eq(run(argv), 0);
    load_csv(dir, "fits.csv");
    cr_assert_eq(n_lines, 4u, "header + VH-E m + FC-E m, n");
    for (r = 1; r < n_lines; r++) {
        double v = num(r, "value");
        cr_assert_str_eq(bf_test_csv_cell(r, "fit"), "exact");
        cr_assert_str_eq(bf_test_csv_cell(r, "objective"), "max");
        cr_assert_str_eq(bf_test_csv_cell(r, "ci_method"), "profile-lik");
        bf_assert_rel(v, num(r, "refined_value"), TOL0);
        cr_assert_leq(num(r, "refined_lse"), num(r, "grid_lse"));
        /* the interval is about the maximum-likelihood estimate of the
         * noise model (doc/methods.md §3), not the max objective's v */
        cr_assert(num(r, "ci_low") < num(r, "ci_high"));
        cr_assert_not_null(strstr(bf_test_csv_cell(r, "flags"), "noise="));
        cr_assert(num(r, "boot_low") < num(r, "boot_high"));
        cr_assert(isfinite(num(r, "aic")) && isfinite(num(r, "bic")) &&
                  isfinite(num(r, "cv")));
    }
    r = row_of("VH-E", "m");
    cr_assert_leq(fabs(num(r, "value") - num(r, "grid_value")),
                  GRID_STEP * (1 + 1e-9));
    cr_assert_eq(num(r, "n_params"), 1.0);
    r = row_of("FC-E", "n"); /* n is fitted with --fit exact */
    cr_assert(num(r, "value") >= 1.2 && num(r, "value") <= 2.5);
    cr_assert_eq(num(r, "n_params"), 2.0);
}

Test(cli_exact, paper_fit_keeps_grid_values_and_adds_the_exact_optimum)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "12",
                          "--models", "VH-G", "--stats", "--out", dir, "-q",
                          NULL};
    size_t r;
    double steps;
    cr_assert_eq(run(argv), 0);
    load_csv(dir, "fits.csv");
    r = row_of("VH-G", "m");
    cr_assert_str_eq(bf_test_csv_cell(r, "fit"), "paper");
    cr_assert_eq(num(r, "value"), num(r, "grid_value"));
    steps = (num(r, "value") - 0.1) / GRID_STEP; /* on the paper grid */
    cr_assert_lt(fabs(steps - round(steps)), 1e-6);
    cr_assert_leq(num(r, "refined_lse"), num(r, "lse"));
}

/* Without --stats, compare is the paper's protocol alone: the analysis
 * columns are present (same header) but empty, the objective is named. */
Test(cli_exact, paper_fit_without_stats_leaves_the_analysis_columns_empty)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "12",
                          "--models", "VH-G", "--out", dir, "-q", NULL};
    static const char *const empty[] = {"grid_value", "refined_value",
                                        "ci_low",     "ci_high",
                                        "aic",        "bic",
                                        "cv"};
    size_t r;
    size_t i;
    cr_assert_eq(run(argv), 0);
    load_csv(dir, "fits.csv");
    r = row_of("VH-G", "m");
    cr_assert_str_eq(bf_test_csv_cell(r, "objective"), "max");
    cr_assert_str_eq(bf_test_csv_cell(r, "fit"), "paper");
    cr_assert(isfinite(num(r, "value")));
    for (i = 0; i < sizeof empty / sizeof *empty; i++) {
        cr_assert_str_eq(bf_test_csv_cell(r, empty[i]), "", "%s", empty[i]);
    }
}

Test(cli_exact, range_widens_the_search_beyond_the_paper_grid)
{
    const char *dir = bf_test_tmpdir();
    /* Velvet (7): VH-E's paper optimum is the grid bound 5.10 */
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "7",
                          "--models", "VH-E", "--fit", "exact", "--range",
                          "m=0.1:20", "--folds", "0", "--out", dir, "-q",
                          NULL};
    size_t r;
    cr_assert_eq(run(argv), 0);
    load_csv(dir, "fits.csv");
    r = row_of("VH-E", "m");
    cr_assert_gt(num(r, "value"), 5.1);
    cr_assert_str_eq(bf_test_csv_cell(r, "bound_hit"), "0");
    cr_assert(isnan(num(r, "cv")), "--folds 0: no cross-validation");
}

/* --neyman N: a diffuse model's intervals by the Neyman construction,
 * named in ci_method, about the same estimate as the F threshold's, and
 * reproducible (the same seed, the same numbers). */
Test(cli_exact, neyman_intervals_are_named_and_reproducible)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "1",
                          "--models", "VH-E", "--fit", "exact", "--folds",
                          "0", "--neyman", "100", "--out", dir, "-q", NULL};
    char path[512];
    const char *once;
    char *first;
    const char *again;
    size_t r;
    cr_assert_eq(run(argv), 0);
    snprintf(path, sizeof path, "%s/fits.csv", dir);
    once = bf_test_slurp(path, NULL);
    cr_assert_not_null(once);
    first = strdup(once); /* slurp's buffer is static */
    load_csv(dir, "fits.csv");
    for (r = 1; r < n_lines; r++) {
        double lo = num(r, "ci_low");
        double hi = num(r, "ci_high");
        double ml = num(r, "ml_value");
        cr_assert_str_eq(bf_test_csv_cell(r, "ci_method"), "neyman");
        cr_assert(lo <= ml && ml <= hi, "row %zu: %g not in [%g, %g]", r, ml,
                  lo, hi);
    }
    cr_assert_eq(run(argv), 0);
    again = bf_test_slurp(path, NULL);
    cr_assert_not_null(again);
    cr_assert_str_eq(again, first, "the same command, the same numbers");
    free(first);
}

Test(cli_exact, bad_options_are_usage_errors)
{
    const char *a1[] = {"compare", "--objective", "log", NULL};
    const char *a2[] = {"compare", "--objective", "median", "--fit", "exact",
                        NULL};
    const char *a3[] = {"compare", "--fit", "fast", NULL};
    const char *a4[] = {"compare", "--range", "m=2:1", NULL};
    const char *a5[] = {"compare", "--range", "m", NULL};
    const char *a6[] = {"compare", "--data", "DATA", "--models", "VH-E",
                        "--range", "m=0:2", NULL}; /* m >= 1e-3 */
    const char *a7[] = {"compare", "--data", "DATA", "--models", "VH-E",
                        "--range", "n=1.2:2", NULL}; /* VH-E has no n */
    const char *a8[] = {"compare", "--bootstrap", "1", NULL};
    const char *a9[] = {"rank", "--folds", "x", NULL};
    const char *a10[] = {"rank", "--criterion", "r2", NULL};
    const char *a11[] = {"compare", "--neyman", "99", NULL};
    const char *a12[] = {"compare", "--neyman", "100", "--intervals", "none",
                         NULL};
    const char *a13[] = {"compare", "--neyman", "100", "--noise", "objective",
                         NULL};
    const char *a14[] = {"compare", "--neyman", "sometimes", NULL};
    const char **all[] = {a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12,
                          a13, a14};
    /* a1, a12 and a13 combine options that exclude each other; the others
     * give a value that is malformed or out of range (README: exit
     * statuses). */
    static const int code[] = {EXIT_CONFLICT, EXIT_BADVALUE, EXIT_BADVALUE,
                               EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE,
                               EXIT_BADVALUE, EXIT_BADVALUE, EXIT_BADVALUE,
                               EXIT_BADVALUE, EXIT_BADVALUE,
                               EXIT_CONFLICT, EXIT_CONFLICT, EXIT_BADVALUE};
    size_t i;
    for (i = 0; i < sizeof all / sizeof *all; i++) {
        cr_assert_eq(run(all[i]), code[i], "case %zu", i + 1);
    }
}

Test(cli_exact, rank_writes_a_ranking_per_sample_and_a_summary)
{
    const char *dir = bf_test_tmpdir();
    /* --neyman off: the ranking, not the intervals, is tested here (FC-E's
     * n competes on one of these samples, and its construction would
     * triple the file's time under valgrind) */
    const char *argv[] = {"rank", "--data", "DATA", "--samples", "1,12,33",
                          "--models", "VH-E,FC-E,LAMBERT", "--folds", "3",
                          "--neyman", "off", "--out", dir, "-q", NULL};
    char path[512];
    const char *md;
    size_t r;
    size_t best = 0;
    cr_assert_eq(run(argv), 0);
    load_csv(dir, "ranking.csv");
    cr_assert_eq(n_lines, 1u + 3u * 3u);
    for (r = 1; r < n_lines; r++) {
        double k = num(r, "k");
        double n = num(r, "n");
        double rss = num(r, "objective_value");
        /* AIC = n ln(RSS/n) + 2k, BIC = n ln(RSS/n) + k ln n */
        bf_assert_rel(num(r, "aic"), n * log(rss / n) + 2 * k, 1e-9);
        bf_assert_rel(num(r, "bic"), n * log(rss / n) + k * log(n), 1e-9);
        cr_assert(num(r, "rank_bic") >= 1 && num(r, "rank_bic") <= 3);
        best += num(r, "rank_bic") == 1;
        cr_assert_str_eq(bf_test_csv_cell(r, "fit"), "exact");
    }
    cr_assert_eq(best, 3u, "one best model per sample");
    snprintf(path, sizeof path, "%s/ranking.md", dir);
    md = bf_test_slurp(path, NULL);
    cr_assert_not_null(md);
    cr_assert(strstr(md, "- BIC: ") != NULL && strstr(md, " of 3 samples"),
              "%s", md);
}
