/* test_plane_abs.c: the plane-of-incidence figures under the objectives
 * that keep the scale (SPEC §10) -- the data they draw (the fit's
 * measured rho = BRDF cos theta_i and each model's rho_hat, absolute),
 * the rule of their logarithmic radiance axis, and the run description
 * (no max-normalisation claimed; the separable fit named). */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
/* A matte CURET sample (its in-plane rho within 2 decades). */
#define MATTE 1

static void setup(void)
{
    gsl_set_error_handler_off();
}

TestSuite(plane_abs, .init = setup);

/* A study spec over every target of ds (no model: the data only); returns
 * its targets, for the caller to free. */
static bf_target *spec_of(bf_dataset *ds, bf_study_spec *spec)
{
    bf_target *targets = NULL;
    size_t n = 0;
    bf_error err;
    cr_assert_eq(bf_study_targets(ds, NULL, 0, NULL, &targets, &n, &err),
                 BF_OK, "%s", err.msg);
    bf_test_study_spec(spec, ds, targets, n, NULL, 0);
    return targets;
}

static bf_dataset *load(const char *path)
{
    bf_dataset *ds = NULL;
    bf_error err;
    cr_assert_eq(bf_dataset_load(path, NULL, &ds, &err), BF_OK, "%s",
                 err.msg);
    return ds;
}

/* The fit's data of target t under obj, into fresh arrays. */
static size_t fit_data(const bf_study_spec *spec, bf_objective obj,
                       size_t t, size_t **sel, double **data)
{
    size_t nconf = bf_dataset_nconf(spec->data, spec->targets[t].material);
    size_t k = 0;
    bf_error err;
    *sel = malloc(nconf * sizeof **sel);
    *data = malloc(nconf * sizeof **data);
    cr_assert(*sel != NULL && *data != NULL);
    cr_assert_eq(bf_study_fit_data(spec, obj, t, *sel, &k, *data, &err),
                 BF_OK, "%s", err.msg);
    return k;
}

Test(plane_abs, fit_data_is_rho_as_measured_within_80_degrees)
{
    bf_dataset *ds = load(bf_test_cornell_path("krylon_blue.brdf"));
    bf_study_spec spec;
    size_t m;
    size_t nconf;
    const bf_geom *g;
    size_t *sel;
    double *rho;
    size_t *sel_max;
    double *norm;
    size_t k;
    size_t k_max;
    size_t j;
    size_t within = 0;
    double mx = 0.0;

    bf_target *tg = spec_of(ds, &spec);
    m = spec.targets[0].material;
    nconf = bf_dataset_nconf(ds, m);
    g = bf_dataset_geom(ds, m);
    k = fit_data(&spec, BF_OBJ_NGAN, 0, &sel, &rho);
    k_max = fit_data(&spec, BF_OBJ_MAX, 0, &sel_max, &norm);
    for (j = 0; j < nconf; j++) {
        within += g[j].theta_i <= 80.0 * DEG + 1e-9 &&
                  g[j].theta_s <= 80.0 * DEG + 1e-9;
    }
    /* SPEC §10: theta_i, theta_o <= 80 deg (all of Krylon's) */
    cr_assert_eq(k, within);
    cr_assert_leq(k, k_max);
    for (j = 0; j < k; j++) {
        double v = NAN;
        cr_assert(bf_dataset_value(ds, m, sel[j], spec.targets[0].channel,
                                   &v));
        /* absolute: the measured BRDF times cos theta_i, no division */
        bf_assert_rel(rho[j], v * cos(g[sel[j]].theta_i), 1e-15);
        mx = fmax(mx, rho[j]);
    }
    cr_assert_gt(mx, 1.5, "Krylon's gloss peak in rho: %g", mx);
    /* the paper's objective: normalised to a maximum of 1 (SPEC §2) */
    for (j = 0, mx = 0.0; j < k_max; j++) {
        mx = fmax(mx, norm[j]);
    }
    cr_assert_eq(mx, 1.0);
    free(sel);
    free(rho);
    free(sel_max);
    free(norm);
    free(tg);
    bf_dataset_free(ds);
}

/* Plane-of-incidence configurations at theta_i over [-90, 90] deg. */
#define NPL 37
static void plane_geom(double theta_i, bf_geom *at)
{
    size_t i;
    for (i = 0; i < NPL; i++) {
        at[i] = bf_geom_in_plane(theta_i, (-90.0 + 5.0 * (double)i) * DEG);
    }
}

Test(plane_abs, model_curve_is_the_fitted_rho_hat)
{
    bf_dataset *ds = load(bf_test_cornell_path("krylon_blue.brdf"));
    static const char *const specular[] = {"GGX", "LAMBERT+GGX",
                                           "LAMBERT+BECKMANN"};
    bf_study_spec spec;
    size_t *sel;
    double *rho;
    bf_geom *used;
    bf_geom at[NPL];
    double out[NPL];
    double val[NPL];
    double param[BF_MAX_PARAMS];
    double num = 0.0;
    double den = 0.0;
    double rho_d;
    const bf_model_type *type;
    bf_problem pb;
    size_t k;
    size_t i;
    size_t j;

    bf_target *tg = spec_of(ds, &spec);
    k = fit_data(&spec, BF_OBJ_NGAN, 0, &sel, &rho);
    used = malloc(k * sizeof *used);
    cr_assert(used != NULL);
    for (j = 0; j < k; j++) {
        used[j] = bf_dataset_geom(ds, spec.targets[0].material)[sel[j]];
    }
    plane_geom(60.0 * DEG, at);
    /* specular models and composites: BRDF cos theta_i with the scales
     * in param, evaluated independently through bf_model_eval */
    for (i = 0; i < sizeof specular / sizeof *specular; i++) {
        type = bf_model_find(specular[i]);
        cr_assert(type != NULL, "%s", specular[i]);
        for (j = 0; j < type->p; j++) {
            param[j] = type->param[j].value;
        }
        cr_assert_eq(bf_problem_init(&pb, type, param, k, used, rho), BF_OK);
        pb.objective = BF_OBJ_NGAN;
        cr_assert_eq(bf_fit_rho_curve(&pb, param, NPL, at, out), BF_OK);
        cr_assert_eq(bf_model_eval(type, param, NPL, at, val), BF_OK);
        for (j = 0; j < NPL; j++) {
            bf_assert_rel(out[j], val[j] * cos(at[j].theta_i), 1e-14);
        }
    }
    /* LAMBERT: rho_hat = rho_d cos ti / pi (SPEC §9.4) with ngan's
     * least-squares rho_d = pi sum rho c / sum c^2, c = cos ti, written
     * out here */
    for (j = 0; j < k; j++) {
        double c = cos(used[j].theta_i);
        num += rho[j] * c;
        den += c * c;
    }
    rho_d = PI * num / den;
    type = bf_model_find("LAMBERT");
    cr_assert_eq(bf_problem_init(&pb, type, NULL, k, used, rho), BF_OK);
    pb.objective = BF_OBJ_NGAN;
    cr_assert_eq(bf_fit_rho_curve(&pb, param, NPL, at, out), BF_OK);
    for (j = 0; j < NPL; j++) {
        bf_assert_rel(out[j], rho_d * cos(at[j].theta_i) / PI, 1e-12);
    }
    /* not for the paper's objectives: they max-normalise */
    pb.objective = BF_OBJ_MAX;
    cr_assert_eq(bf_fit_rho_curve(&pb, param, NPL, at, out), BF_EINVAL);
    free(sel);
    free(rho);
    free(used);
    free(tg);
    bf_dataset_free(ds);
}

Test(plane_abs, log_axis_rule)
{
    const double two[] = {1.0, 100.0, 0.0, -3.0, NAN};
    const double more[] = {1.0, 100.5, 0.0, INFINITY};
    cr_assert_eq(bf_fit_log_axis(5, two), 0); /* exactly 2 decades */
    cr_assert_eq(bf_fit_log_axis(4, more), 1);
    cr_assert_eq(bf_fit_log_axis(0, two), 0);
}

/* The in-plane measured rho of target t that a figure draws: at the
 * incidence angles bf_geom_plane_incidences chooses (4 at most, as the
 * report's), within 1 degree of the plane and of the angle; into v,
 * returns their count. */
static size_t in_plane(const bf_study_spec *spec, size_t t, double *v,
                       size_t max)
{
    const bf_geom *g = bf_dataset_geom(spec->data,
                                       spec->targets[t].material);
    size_t nconf = bf_dataset_nconf(spec->data, spec->targets[t].material);
    double inc[4];
    size_t n_inc = 0;
    size_t *sel;
    double *rho;
    size_t k = fit_data(spec, BF_OBJ_NGAN, t, &sel, &rho);
    size_t n = 0;
    size_t j;
    size_t a;
    cr_assert_eq(bf_geom_plane_incidences(nconf, g, DEG, 4, inc, &n_inc),
                 BF_OK);
    cr_assert_gt(n_inc, 1);
    for (j = 0; j < k && n < max; j++) {
        double off;
        bf_geom_plane_angle(&g[sel[j]], &off);
        for (a = 0; a < n_inc; a++) {
            if (off <= DEG && fabs(g[sel[j]].theta_i - inc[a]) <= DEG) {
                v[n++] = rho[j];
                break;
            }
        }
    }
    free(sel);
    free(rho);
    return n;
}

Test(plane_abs, log_axis_on_glossy_data_not_on_matte)
{
    bf_dataset *gloss = load(bf_test_cornell_path("krylon_blue.brdf"));
    bf_dataset *matte = NULL;
    bf_study_spec spec;
    double v[256];
    size_t n;
    size_t t;
    bf_error err;

    bf_target *tg = spec_of(gloss, &spec);
    n = in_plane(&spec, 0, v, 256);
    cr_assert_gt(n, 5);
    cr_assert_eq(bf_fit_log_axis(n, v), 1);
    free(tg);
    bf_dataset_free(gloss);

    cr_assert_eq(bf_curet_load(bf_test_curet_path(""), NULL, &matte, &err),
                 BF_OK, "%s", err.msg);
    tg = spec_of(matte, &spec);
    for (t = 0; t < spec.n_targets; t++) {
        if (bf_dataset_number(matte, spec.targets[t].material) == MATTE) {
            break;
        }
    }
    cr_assert_lt(t, spec.n_targets);
    n = in_plane(&spec, t, v, 256);
    cr_assert_gt(n, 3);
    cr_assert_eq(bf_fit_log_axis(n, v), 0);
    free(tg);
    bf_dataset_free(matte);
}

Test(plane_abs, description_under_ngan)
{
    const char *dir = bf_test_tmpdir();
    const char *argv[] = {"report", "--input", NULL, "--models",
                          "LAMBERT,GGX", "--fit", "exact", "--objective",
                          "ngan", "--out", NULL, "--format", "svg", NULL};
    const char *out = NULL;
    const char *html;
    char path[1024];
    char *copy;
    argv[2] = bf_test_cornell_path("krylon_blue.brdf");
    argv[10] = dir;
    cr_assert_eq(bf_test_run_cli(argv, &out, NULL), 0);
    copy = strdup(out);
    cr_assert(copy != NULL);
    snprintf(path, sizeof path, "%s/report.html", dir);
    html = bf_test_slurp(path, NULL);
    cr_assert(html != NULL);
    /* SPEC §10: nothing is divided by its maximum */
    cr_assert(strstr(copy, "Normalisation: none (SPEC §10)") != NULL, "%s",
              copy);
    cr_assert(strstr(copy, "divided by its maximum") == NULL, "%s", copy);
    cr_assert(strstr(html, "Normalisation: none (SPEC §10)") != NULL);
    /* the page's first sentence names the objective, not the paper's
     * protocol */
    cr_assert(strstr(html, "in absolute units under the ngan objective") !=
              NULL);
    cr_assert(strstr(html, "with the protocol of Ragheb") == NULL);
    cr_assert(strstr(html, "Normalisation: radiance") == NULL);
    cr_assert(strstr(html, "Every figure shows radiance normalised") ==
              NULL);
    cr_assert(strstr(html, "LSE (the sum over") == NULL); /* Fig. 2(b) */
    /* the page's Tables 2 and 3 are titled as the printed ones: the exact
     * optima, and E of the ngan objective, never an LSE sum */
    cr_assert(strstr(html, "<h3>Table 2: fitted parameters (exact optima")
              != NULL);
    cr_assert(strstr(html, "<h3>Table 3: E = sqrt(S / K) of the ngan "
                           "objective") != NULL);
    cr_assert(strstr(html, "<h3>Table 3: LSE") == NULL);
    cr_assert(strstr(copy, "Table 2: fitted parameters (exact optimum (grid "
                           "optimum)") != NULL);
    /* the wins figure and the conventions name E too */
    cr_assert(strstr(html, "the lowest E (Table 3)") != NULL);
    cr_assert(strstr(html, "<li>E = √(Σ") != NULL);
    cr_assert(strstr(html, "lowest LSE") == NULL);
    cr_assert(strstr(html, "<li>LSE = ") == NULL);
    /* the specular model's fit is the separable one, not Brent / NM */
    cr_assert(strstr(copy, "Fit of GGX: separable least squares") != NULL,
              "%s", copy);
    cr_assert(strstr(copy, "diffuse models: grid optimum") != NULL);
    /* the plane figure's caption: absolute units, the objective's E */
    cr_assert(strstr(html, "in absolute units as fitted under the ngan "
                           "objective") != NULL);
    cr_assert(strstr(html, "L/L_max") == NULL);
    /* table3.md names E, as the printed Table 3 does, never LSE */
    snprintf(path, sizeof path, "%s/table3.md", dir);
    html = bf_test_slurp(path, NULL);
    cr_assert(html != NULL);
    cr_assert(strncmp(html, "Table 3: E = sqrt(S / K) of the ngan objective",
                      46) == 0, "%.120s", html);
    free(copy);
}
