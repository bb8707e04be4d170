/* consumer.c: a program outside the tree that uses an installed brdffit,
 * built by tests/install/test_install.sh with pkg-config (shared and
 * --static) and with CMake's find_package. It checks that the header and
 * the library it links agree, evaluates a model against its closed form,
 * fits it (GSL's Brent minimiser) and reaches the study (OpenMP), so a
 * static link that lacks any private dependency fails to link. Exits 0 when
 * every check holds, 1 otherwise, naming the check. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <brdffit.h>
#include <gsl/gsl_errno.h>

#define NCONF 9

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "consumer: FAILED: %s\n", what);
        failures++;
    }
}

int main(void)
{
    /* High-entropy configurations in Beckmann's frame (STYLE §7). */
    static const double theta[NCONF][2] = {
        {0.1313, 0.7313}, {0.2718, 0.3141}, {0.4142, 1.0721},
        {0.5772, 0.1618}, {0.6931, 0.9190}, {0.8414, 0.4330},
        {0.9553, 1.2310}, {1.1071, 0.6124}, {1.2490, 0.2222}};
    const double n_d = 2.3456; /* LFTG exponent to recover */
    const double start = 1.0;  /* its value before the fit */
    const bf_model_type *lftg;
    bf_geom geom[NCONF];
    double value[NCONF];
    double data[NCONF];
    bf_fit_workspace *w;
    bf_fit_result grid;
    bf_fit_result fine;
    bf_problem pb;
    bf_error err;
    size_t k;

    gsl_set_error_handler_off(); /* the library checks every GSL status */
    check(strcmp(bf_version(), BF_VERSION_STRING) == 0,
          "bf_version() is the header's BF_VERSION_STRING");

    lftg = bf_model_find("lftg");
    check(lftg != NULL && strcmp(lftg->name, "LFTG") == 0,
          "bf_model_find finds LFTG case-insensitively");
    if (lftg == NULL) {
        return 1;
    }
    for (k = 0; k < NCONF; k++) {
        geom[k].theta_i = theta[k][0];
        geom[k].phi_i = M_PI;
        geom[k].theta_s = theta[k][1];
        geom[k].phi_s = 0.4 * (double)k - 1.3;
    }
    check(bf_model_eval(lftg, &n_d, NCONF, geom, value) == BF_OK,
          "bf_model_eval(LFTG) succeeds");
    for (k = 0; k < NCONF; k++) {
        /* paper (P7), SPEC §6: (n_d + 2)/(2 pi) (cos ti cos ts)^n_d */
        double expected = (n_d + 2.0) / (2.0 * M_PI) *
                          pow(cos(theta[k][0]) * cos(theta[k][1]), n_d);
        check(fabs(value[k] - expected) <= 1e-14 * expected,
              "LFTG equals its closed form (P7)");
    }

    /* Synthesise normalised data at n_d, then fit: the grid (SPEC §7.4)
     * and GSL's refinement recover n_d. */
    check(bf_normalise(NCONF, value, data) == BF_OK, "bf_normalise");
    w = bf_fit_alloc(NCONF);
    check(w != NULL, "bf_fit_alloc");
    if (w == NULL) {
        return 1;
    }
    check(bf_fit_grid(lftg, &start, 0, NCONF, geom, data, w, &grid) == BF_OK,
          "bf_fit_grid");
    bf_fit_free(w);
    check(fabs(grid.param[0] - n_d) <= 0.04, "grid optimum within a step");
    check(bf_problem_init(&pb, lftg, &start, NCONF, geom, data) == BF_OK,
          "bf_problem_init");
    check(bf_fit_refine(&pb, &grid, &fine) == BF_OK, "bf_fit_refine (GSL)");
    check(fabs(fine.param[0] - n_d) <= 1e-6, "refined n_d recovers 2.3456");

    /* The study (OpenMP): an empty specification is a clear error. */
    memset(&err, 0, sizeof err);
    check(bf_study_run(NULL, NULL, &err) == BF_EINVAL,
          "bf_study_run rejects a NULL specification");
    check(err.code == BF_EINVAL && err.msg[0] != '\0',
          "bf_study_run names the problem");

    if (failures == 0) {
        printf("consumer: brdffit %s, LFTG n_d = %.6f recovered\n",
               bf_version(), fine.param[0]);
    }
    return failures == 0 ? 0 : 1;
}
