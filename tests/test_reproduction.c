/* test_reproduction.c: `brdffit compare` on the real CURET data reproduces
 * the published results of Ragheb & Hancock (Tables 2 and 3), within the
 * agreement documented in shared/reference/README.md:
 *   - VH-G, VH-E, LFTG parameters and LSE: exact to the printed two decimals;
 *   - ON LSE: +-0.01, except Styrofoam (20) and Brick b (41), whose published
 *     rho, sigma do not give the published LSE;
 *   - FC-G, FC-E at n = 1.7: parameters +-0.01, LSE +-0.02, except
 *     Leather (5), which no single n reproduces.
 * The +- agreements compare printed values with printed values: ours
 * rounded to two decimals as Table 3 prints them, against the published.
 * The exceptions are reported by the test (on stderr), never tuned around.
 * The published values are read from reference/ragheb_hancock_subset.tsv,
 * the fitted ones from the fits.csv that the CLI writes. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

/* Agreement of shared/reference/README.md. */
#define TOL_ON_LSE 0.01
#define TOL_FC_PARAM 0.01
#define TOL_FC_LSE 0.02
/* Grid values such as 0.1 + 0.01 * 224 are not exact in binary. */
#define TOL_REPR 1e-9

#define MAX_ROWS 64

typedef struct {
    int sample;
    char model[16];
    double value; /* NAN when the model has no fitted parameter */
    double lse;
} fit_row;

static fit_row fits[MAX_ROWS * 8];
static size_t n_fits;

static const fit_row *find_fit(int sample, const char *model)
{
    size_t i;
    for (i = 0; i < n_fits; i++) {
        if (fits[i].sample == sample && strcmp(fits[i].model, model) == 0) {
            return &fits[i];
        }
    }
    cr_assert_fail("fits.csv has no row for sample %d, model %s", sample, model);
    return NULL;
}

/* Splits line at sep into at most max fields (in place). Quoted CSV fields
 * are not needed here: the study's names contain no comma. */
static size_t split(char *line, char sep, char **field, size_t max)
{
    size_t n = 0;
    char *p = line;
    while (n < max) {
        char *e = strchr(p, sep);
        field[n++] = p;
        if (e == NULL) {
            break;
        }
        *e = '\0';
        p = e + 1;
    }
    return n;
}

static void run_compare(void)
{
    const char *dir = bf_test_tmpdir();
    char path[512];
    char *text;
    char *line;
    char *save = NULL;
    const char *err = NULL;
    const char *argv[] = {"compare", "--data", NULL, "--samples", "paper",
                          "--on-params", NULL, "--out", dir, "--quiet", NULL};
    char data_dir[4096];
    size_t n_cols = 0;
    size_t col_model = SIZE_MAX;
    size_t col_value = SIZE_MAX;
    size_t col_lse = SIZE_MAX;
    int rc;

    snprintf(data_dir, sizeof data_dir, "%s", bf_test_curet_path("."));
    argv[2] = data_dir;
    argv[6] = bf_test_reference_path("oren_nayar_params.tsv");
    rc = bf_test_run_cli(argv, NULL, &err);
    cr_assert_eq(rc, 0, "brdffit compare failed (%d):\n%s", rc, err);

    snprintf(path, sizeof path, "%s/fits.csv", dir);
    text = strdup(bf_test_slurp(path, NULL));
    cr_assert_not_null(text);
    n_fits = 0;
    for (line = strtok_r(text, "\n", &save); line != NULL;
         line = strtok_r(NULL, "\n", &save)) {
        char *f[64];
        size_t nf = split(line, ',', f, 64);
        if (strcmp(f[0], "sample") == 0) { /* columns by header name */
            size_t c;
            n_cols = nf;
            for (c = 0; c < nf; c++) {
                col_model = strcmp(f[c], "model") == 0 ? c : col_model;
                col_value = strcmp(f[c], "value") == 0 ? c : col_value;
                col_lse = strcmp(f[c], "lse") == 0 ? c : col_lse;
            }
            cr_assert(col_model < nf && col_value < nf && col_lse < nf,
                      "fits.csv header '%s'", line);
            continue;
        }
        cr_assert_eq(nf, n_cols, "fits.csv row '%s'", line);
        fits[n_fits].sample = atoi(f[0]);
        snprintf(fits[n_fits].model, sizeof fits[n_fits].model, "%s",
                 f[col_model]);
        fits[n_fits].value =
            f[col_value][0] != '\0' ? strtod(f[col_value], NULL) : NAN;
        fits[n_fits].lse = strtod(f[col_lse], NULL);
        n_fits++;
    }
    free(text);
    cr_assert_eq(n_fits, 24u * 6u, "24 samples x 6 models expected");
}

/* "Exact to the printed two decimals": obtained rounds to the published. */
static int same_to_2dp(double obtained, double published)
{
    return lround(obtained * 100.0) == lround(published * 100.0);
}

/* The value as our Table 3 prints it (two decimals, like the paper). */
static double printed(double x)
{
    return (double)lround(x * 100.0) / 100.0;
}

static int failures;

static void check(int sample, const char *what, double obtained,
                  double published, double tol)
{
    /* Both sides are compared as printed (two decimals): the published
     * values are rounded, and so are the 3-decimal rho, sigma they came
     * from (ON LSE of sample 31 is 10.2495 at the tabulated rho, sigma and
     * spans 10.242-10.257 within their rounding; published 10.26). */
    int ok = tol == 0.0
                 ? same_to_2dp(obtained, published)
                 : fabs(printed(obtained) - published) <= tol + TOL_REPR;
    if (!ok) {
        failures++;
        cr_log_error("sample %d %s: published %.2f, obtained %.6f, "
                     "difference %.4f, tolerance %s%.2f",
                     sample, what, published, obtained,
                     obtained - published, tol == 0.0 ? "printed digits " : "",
                     tol);
    }
}

static void exception(int sample, const char *what, double obtained,
                      double published, const char *why)
{
    fprintf(stderr,
            "documented exception: sample %d %s: published %.2f, obtained "
            "%.4f (%s)\n",
            sample, what, published, obtained, why);
}

Test(reproduction, compare_reproduces_the_published_tables_within_tolerance)
{
    static const char *const slope_models[4] = {"VH-G", "VH-E", "FC-G",
                                                "FC-E"};
    static const char *const lse_models[6] = {"VH-G", "VH-E", "FC-G",
                                              "FC-E", "ON",   "LFTG"};
    FILE *fp = fopen(bf_test_reference_path("ragheb_hancock_subset.tsv"),
                     "r");
    char line[1024];
    int rows = 0;
    int exceptions = 0;

    run_compare();
    cr_assert_not_null(fp);
    cr_assert_not_null(fgets(line, sizeof line, fp)); /* header */
    cr_assert(strncmp(line, "sample\tname\tslope_VH_G", 22) == 0,
              "unexpected reference header: %s", line);
    while (fgets(line, sizeof line, fp) != NULL) {
        char *f[16];
        size_t nf;
        int sample;
        size_t m;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0') {
            continue;
        }
        nf = split(line, '\t', f, 16);
        cr_assert_eq(nf, 13u, "reference row '%s'", line);
        sample = atoi(f[0]);
        rows++;
        for (m = 0; m < 4; m++) {
            const fit_row *r = find_fit(sample, slope_models[m]);
            double pub = strtod(f[2 + m], NULL);
            int fc = strncmp(slope_models[m], "FC", 2) == 0;
            if (fc && sample == 5) {
                exception(sample, slope_models[m], r->value, pub,
                          "no single n reproduces Leather");
                exceptions++;
                continue;
            }
            check(sample, slope_models[m], r->value, pub,
                  fc ? TOL_FC_PARAM : 0.0);
        }
        check(sample, "LFTG n_d", find_fit(sample, "LFTG")->value,
              strtod(f[6], NULL), 0.0);
        for (m = 0; m < 6; m++) {
            const fit_row *r = find_fit(sample, lse_models[m]);
            double pub = strtod(f[7 + m], NULL);
            int fc = strncmp(lse_models[m], "FC", 2) == 0;
            int on = strcmp(lse_models[m], "ON") == 0;
            char what[32];
            snprintf(what, sizeof what, "LSE %s", lse_models[m]);
            if ((fc && sample == 5) || (on && (sample == 20 || sample == 41))) {
                exception(sample, what, r->lse, pub,
                          fc ? "no single n reproduces Leather"
                             : "published rho, sigma do not give the "
                               "published LSE");
                exceptions++;
                continue;
            }
            check(sample, what, r->lse, pub,
                  fc ? TOL_FC_LSE : (on ? TOL_ON_LSE : 0.0));
        }
    }
    fclose(fp);
    cr_assert_eq(rows, 12, "the reference subset has 12 rows");
    cr_assert_eq(exceptions, 5, "2 FC slopes and 2 FC LSE of Leather + ON LSE of "
                                "Styrofoam are the documented exceptions");
    cr_assert_eq(failures, 0, "%d published values not reproduced", failures);
}
