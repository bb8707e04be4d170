/* test_energy.c: the report's energy table (src/report/energy.c, issue 17
 * item 8) of rows whose albedo bf_study_row_albedo filled: one row per
 * specular fit (a diffuse model has none), the albedo at 0, 30, 60, 80
 * degrees, "OVER 1" exactly where the white-furnace check fails:
 * WARD-DUER with rho_s = 1.2 and a narrow lobe (albedo about rho_s at
 * every incidence) is over 1, GGX with F0 = 0.04 is far below it. */
#include <criterion/criterion.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "energy.h"

Test(energy, one_row_per_specular_fit_flagged_over_1)
{
    static const double at[4] = {0.3, 3.14159265358979323846, 0.3, 0.0};
    static const double value[1] = {0.1};
    const bf_model_type *types[3];
    bf_dataset *ds = bf_dataset_alloc();
    bf_material_desc d;
    bf_target tg = {0, 0, 0};
    bf_study_spec spec;
    bf_study_row rows[3];
    size_t set;
    size_t n;
    size_t over;
    size_t m;
    char *text = NULL;
    size_t len = 0;
    FILE *fp;
    bf_tt *t;
    const char *ward;
    const char *ggx;
    double a0;
    gsl_set_error_handler_off();
    cr_assert_not_null(ds);
    types[0] = bf_model_lambert;
    types[1] = bf_model_find("GGX");
    types[2] = bf_model_find("WARD-DUER");
    cr_assert_eq(bf_dataset_add_configs(ds, 1, at, &set, NULL), BF_OK);
    memset(&d, 0, sizeof d);
    d.name = "paint";
    d.format = BF_FORMAT_MEMORY;
    d.set = set;
    d.n_channels = 1;
    d.values = value;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    memset(&spec, 0, sizeof spec);
    memset(rows, 0, sizeof rows);
    spec.data = ds;
    spec.targets = &tg;
    spec.n_targets = 1;
    spec.models = types;
    spec.n_models = 3;
    for (m = 0; m < 3; m++) {
        rows[m].sample = 1;
        rows[m].type = types[m];
        rows[m].status = BF_OK;
    }
    rows[1].fit.param[0] = 1.0; /* GGX: rho_s, alpha, F0 */
    rows[1].fit.param[1] = 0.2;
    rows[1].fit.param[2] = 0.04;
    rows[2].fit.param[0] = 1.2; /* WARD-DUER: rho_s, alpha */
    rows[2].fit.param[1] = 0.01;
    for (m = 0; m < 3; m++) { /* as bf_study_analyse does after the fit */
        bf_study_row_albedo(&rows[m]);
    }
    cr_assert(isnan(rows[0].albedo[0]) && isnan(rows[0].albedo[3]));
    cr_assert(rows[1].albedo[0] > 0.0 && rows[1].albedo[0] < 1.0);
    t = bf_rep_energy_table(&spec, rows, &n, &over);
    cr_assert_not_null(t);
    cr_assert_eq(n, 2);
    cr_assert_eq(over, 1);
    fp = open_memstream(&text, &len);
    cr_assert_not_null(fp);
    cr_assert_eq(bf_tt_print(t, fp), 0);
    fclose(fp);
    bf_tt_free(t);
    cr_assert_null(strstr(text, "LAMBERT "), "a diffuse row: %s", text);
    ward = strstr(text, "WARD-DUER");
    ggx = strstr(text, "GGX");
    cr_assert(ward != NULL && ggx != NULL, "%s", text);
    cr_assert_not_null(strstr(ward, "OVER 1"));
    cr_assert(strstr(ggx, "OVER 1") == strstr(ward, "OVER 1"),
              "GGX flagged: %s", text);
    /* Dur's narrow lobe: albedo rho_s (1 - O(alpha^2)) at normal
     * incidence */
    cr_assert_eq(sscanf(strchr(ward, '|') + 1, " %lf", &a0), 1);
    cr_assert(a0 > 1.19 && a0 <= 1.2, "WARD-DUER a(0) %g", a0);
    free(text);
    /* a failed row has no albedo and no line */
    rows[2].status = BF_EDOM;
    bf_study_row_albedo(&rows[2]);
    cr_assert(isnan(rows[2].albedo[0]) && isnan(rows[2].albedo[3]));
    t = bf_rep_energy_table(&spec, rows, &n, &over);
    cr_assert_not_null(t);
    cr_assert(n == 1 && over == 0, "n %zu over %zu", n, over);
    bf_tt_free(t);
    /* no specular fit: no table */
    spec.n_models = 1;
    cr_assert_null(bf_rep_energy_table(&spec, rows, &n, &over));
    cr_assert_eq(n, 0);
    bf_dataset_free(ds);
}

/* bf_study_row_albedo_over_1, the check fits.csv and the energy table
 * share: 1 exactly when an albedo exceeds 1; NaN (none) never counts. */
Test(energy, albedo_over_1_counts_only_values_above_1)
{
    bf_study_row r;
    memset(&r, 0, sizeof r);
    r.albedo[0] = 0.2;
    r.albedo[1] = 0.5;
    r.albedo[2] = 0.9;
    r.albedo[3] = 1.0; /* at 1: passive, not over */
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 0);
    r.albedo[2] = 1.0000001;
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 1);
    r.albedo[2] = 0.9;
    r.albedo[3] = 1.3; /* the last incidence counts too */
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 1);
    r.albedo[0] = r.albedo[1] = r.albedo[2] = r.albedo[3] = NAN;
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 0, "all NaN");
    r.albedo[1] = 0.7; /* NaN beside values at most 1 */
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 0);
    r.albedo[3] = 2.0; /* NaN beside one over 1 */
    cr_assert_eq(bf_study_row_albedo_over_1(&r), 1);
    cr_assert_eq(bf_study_row_albedo_over_1(NULL), 0);
}
