/* test_cli_calibrate.c: `brdffit calibrate` (doc/methods.md §3): the
 * table and calibrate.csv of a real sample's fits, and its bad input --
 * too few simulations, an unknown noise word, a fit whose noise cannot be
 * estimated (K <= the estimated parameters). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_BADVALUE 63
#define EXIT_DATAERR 65

Test(cli_calibrate, writes_coverage_and_bias_of_every_fitted_parameter)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"compare", "--data", "DATA", "--samples", "12",
                          "--models", "BK-E,FC-E", "--sims", "20", "--out",
                          dir, "-q", NULL};
    size_t r;
    argv[0] = "calibrate";
    cr_assert_eq(bf_test_run_curet(argv), 0);
    cr_assert_eq(bf_test_csv_load(dir, "calibrate.csv"), 4u,
                 "header + BK-E m + FC-E m, n");
    for (r = 1; r < 4; r++) {
        double c = bf_test_csv_num(r, "coverage");
        cr_assert_eq(bf_test_csv_num(r, "n_sim"), 20.0);
        cr_assert(c >= 0.0 && c <= 1.0, "coverage %g", c);
        cr_assert_gt(bf_test_csv_num(r, "sd"), 0.0);
        cr_assert_gt(bf_test_csv_num(r, "width"), 0.0);
        cr_assert(isfinite(bf_test_csv_num(r, "bias")));
        cr_assert_eq(bf_test_csv_num(r, "level"), 0.95);
    }
    r = bf_test_csv_find("12", "FC-E", "n");
    cr_assert_str_eq(bf_test_csv_cell(r, "objective"), "max");
    cr_assert(bf_test_csv_num(r, "noise_power") >= 0.0 &&
              bf_test_csv_num(r, "noise_power") <= 3.0);
}

Test(cli_calibrate, fewer_than_ten_simulations_are_refused)
{
    const char *err = NULL;
    const char *argv[] = {"calibrate", "--sims", "9", NULL};
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_BADVALUE);
    cr_assert_not_null(strstr(err, "--sims: '9'"), "%s", err);
}

Test(cli_calibrate, an_unknown_noise_word_is_refused)
{
    const char *err = NULL;
    const char *argv[] = {"calibrate", "--noise", "gaussian", NULL};
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_BADVALUE);
    cr_assert_not_null(strstr(err, "--noise: 'gaussian' is not auto, "
                                   "absolute, relative or objective"),
                       "%s", err);
}

Test(cli_calibrate, a_fit_whose_noise_cannot_be_estimated_is_an_error)
{
    /* --max-theta 25: K = 3 configurations of sample 12 for FC-E's m, n,
     * the scale and the noise power */
    const char *dir = bf_test_tmpdir();
    const char *err = NULL;
    char data[4096];
    const char *argv[] = {"calibrate", "--data", data, "--samples", "12",
                          "--models", "FC-E", "--max-theta", "25",
                          "--sims", "10", "--out", dir, "-q", NULL};
    snprintf(data, sizeof data, "%s", bf_test_curet_path(""));
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_DATAERR, "%s", err);
    cr_assert_not_null(strstr(err, "its noise cannot be estimated"), "%s",
                       err);
    cr_assert_null(bf_test_slurp(strcat(strcpy(data, dir), "/calibrate.csv"),
                                 NULL),
                   "no partial file");
}
