/* test_convert.c: the same measurements in different formats give the
 * same dataset and the same fits -- the five Cornell .brdf files written
 * as tidy CSV (bf_csv_write) and as ASTM (an independent writer here) and
 * read back -- and data synthesised from every fitted model at known
 * parameters on irregular configuration sets, written as CSV and read
 * back, are fitted back to exactly those parameters. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "internal.h"
#include "support.h"

/* --exclude-specular 15 (SPEC §1.6): the Cornell paints' gloss peak. */
#define CONE_15 (15.0 * BF__PI / 180.0)

static bf_dataset *load_cornell(const char *file)
{
    bf_dataset *ds = NULL;
    bf_error err;
    cr_assert_eq(bf_pbrt_load(bf_test_cornell_path(file), &ds, &err), BF_OK,
                 "%s", err.msg);
    return ds;
}

/* Reads a memstream's text back with a reader. */
static bf_dataset *read_back(bf_test_reader rd, const char *text)
{
    return bf_test_read_ok(rd, "converted", text);
}

/* The ASTM E1392 text of a one-material spectral dataset, written here
 * without the library's help: SAMPLE_NAME, NUM_POINTS, VARS with the
 * wavelengths in nm, one row per configuration, radians and values with
 * 17 significant digits (which read back bit for bit). */
static char *astm_text(const bf_dataset *ds)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    const double *a = bf_dataset_angles(ds, 0);
    const double *v = bf_dataset_values(ds, 0);
    size_t nc = bf_dataset_nchannels(ds, 0);
    size_t k;
    size_t c;
    cr_assert_not_null(fp);
    fprintf(fp, "FORMAT_ID \"ASTM E1392-96\"\n");
    fprintf(fp, "SAMPLE_NAME \"%s\"\n", bf_dataset_name(ds, 0));
    fprintf(fp, "NUM_POINTS %zu\n", bf_dataset_nconf(ds, 0));
    fprintf(fp, "VARS theta_i,phi_i,theta_s,phi_s");
    for (c = 0; c < nc; c++) {
        fprintf(fp, ",%gnm", bf_dataset_wavelength(ds, 0, c));
    }
    fprintf(fp, "\n");
    for (k = 0; k < bf_dataset_nconf(ds, 0); k++) {
        fprintf(fp, "%.17g,%.17g,%.17g,%.17g", a[4 * k], a[4 * k + 1],
                a[4 * k + 2], a[4 * k + 3]);
        for (c = 0; c < nc; c++) {
            fprintf(fp, ",%.17g", v[k * nc + c]);
        }
        fprintf(fp, "\n");
    }
    cr_assert_eq(fclose(fp), 0);
    return text;
}

static char *csv_text(const bf_dataset *ds)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    cr_assert_not_null(fp);
    cr_assert_eq(bf_csv_write(ds, fp), BF_OK);
    cr_assert_eq(fclose(fp), 0);
    return text;
}

/* The paper's models on every material of ds, on channel ch ("mean" or
 * a wavelength), outside the 15 degree cone, into rows. */
static void study(const bf_dataset *ds, const char *ch, bf_study_row *rows,
                  size_t n_rows)
{
    static const bf_model_type *const *const models[] = {
        &bf_model_vh_g, &bf_model_fc_e, &bf_model_lftg};
    const bf_model_type *m[3];
    bf_target *t = NULL;
    size_t n_t = 0;
    size_t k;
    bf_study_spec spec;
    bf_error err;
    for (k = 0; k < 3; k++) {
        m[k] = *models[k];
    }
    cr_assert_eq(bf_study_targets(ds, NULL, 0, ch, &t, &n_t, &err), BF_OK,
                 "%s", err.msg);
    cr_assert_eq(n_t * 3, n_rows);
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_selection_init(&spec.select);
    spec.select.cone = CONE_15;
    spec.targets = t;
    spec.n_targets = n_t;
    spec.models = m;
    spec.n_models = 3;
    spec.n_default = BF_DEFAULT_N;
    cr_assert_eq(bf_study_run(&spec, rows, &err), BF_OK, "%s", err.msg);
    free(t);
}

/* The same fits on the mean and (for one file, f == 1) on 550 nm. */
static void expect_same_fits(const bf_dataset *a, const bf_dataset *b,
                             size_t f)
{
    bf_study_row ra[3];
    bf_study_row rb[3];
    const char *channels[2] = {"mean", "550"};
    size_t c;
    size_t k;
    for (c = 0; c < (f == 1 ? 2u : 1u); c++) {
        study(a, channels[c], ra, 3);
        study(b, channels[c], rb, 3);
        for (k = 0; k < 3; k++) {
            cr_assert_eq(ra[k].status, BF_OK);
            cr_assert_eq(ra[k].k, rb[k].k);
            cr_assert(isfinite(ra[k].fit.lse));
            cr_assert_eq(memcmp(&ra[k].fit, &rb[k].fit, sizeof ra[k].fit), 0,
                         "%s on %s: LSE %.17g and %.17g", ra[k].type->name,
                         channels[c], ra[k].fit.lse, rb[k].fit.lse);
        }
    }
}

Test(convert, cornell_files_as_csv_read_back_identically)
{
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *brdf = load_cornell(bf_test_cornell[f]);
        char *text = csv_text(brdf);
        bf_dataset *csv = read_back(bf_csv_read, text);
        bf_test_expect_same_dataset(brdf, csv);
        expect_same_fits(brdf, csv, f);
        free(text);
        bf_dataset_free(brdf);
        bf_dataset_free(csv);
    }
}

Test(convert, cornell_files_as_astm_read_back_identically)
{
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *brdf = load_cornell(bf_test_cornell[f]);
        char *text = astm_text(brdf);
        bf_dataset *astm = read_back(bf_astm_read, text);
        bf_test_expect_same_dataset(brdf, astm);
        expect_same_fits(brdf, astm, f);
        free(text);
        bf_dataset_free(brdf);
        bf_dataset_free(astm);
    }
}

Test(convert, all_five_cornell_files_in_one_csv_keep_their_sets_and_names)
{
    bf_dataset *all = bf_dataset_alloc();
    bf_dataset *back;
    char *text;
    size_t f;
    for (f = 0; f < BF_TEST_NCORNELL; f++) {
        bf_dataset *ds = load_cornell(bf_test_cornell[f]);
        cr_assert_eq(bf_dataset_append(all, ds), BF_OK);
        bf_dataset_free(ds);
    }
    text = csv_text(all);
    back = read_back(bf_csv_read, text);
    /* the five files list the same 1439 configurations: after the round
     * trip they share one set (the source had five) */
    cr_assert_eq(bf_dataset_count(back), 5);
    for (f = 1; f < 5; f++) {
        cr_assert_eq(bf_dataset_set(back, f), bf_dataset_set(back, 0));
        cr_assert_str_eq(bf_dataset_name(back, f), bf_dataset_name(all, f));
        cr_assert_eq(memcmp(bf_dataset_values(back, f),
                            bf_dataset_values(all, f),
                            1439 * 31 * sizeof(double)),
                     0);
    }
    free(text);
    bf_dataset_free(all);
    bf_dataset_free(back);
}

/* ==== fitted back from analytic models ==== */

/* Irregular configurations: random directions, zeniths up to 80 deg. */
static void random_configs(size_t n, double *a)
{
    size_t k;
    for (k = 0; k < n; k++) {
        a[4 * k] = 1.3962634 * drand48();
        a[4 * k + 1] = (2.0 * drand48() - 1.0) * BF__PI;
        a[4 * k + 2] = 1.3962634 * drand48();
        a[4 * k + 3] = (2.0 * drand48() - 1.0) * BF__PI;
    }
}

/* 1 when type has a parameter the paper's protocol fits. */
static int fits_something(const bf_model_type *type)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        if (type->param[j].fitted) {
            return 1;
        }
    }
    return 0;
}

Test(convert, every_fitted_model_is_fitted_back_exactly_through_csv)
{
    /* One material per fitted model, each synthesised from its model at a
     * known grid point on its own irregular configurations (WNO-R, whose
     * grid of 4192 points runs a quadrature per value, on fewer), all in
     * one CSV file. The data are the model's values, so the grid's
     * optimum is the known point and the CSV round trip changes no bit. */
    bf_dataset *ds = bf_dataset_alloc();
    bf_dataset *back;
    const bf_model_type *type[16];
    double p[16][BF_MAX_PARAMS];
    size_t n_types = 0;
    char *text;
    size_t m;
    srand48(42);
    for (m = 0; m < bf_model_count(); m++) {
        const bf_model_type *t = bf_model_get(m);
        size_t n = t == bf_model_wno_r ? 40 : 250;
        if (t->kind != BF_MODEL_DIFFUSE) {
            continue; /* SPEC §9: fitted under SPEC §10, not max-normalised */
        }
        double *a = malloc(n * 4 * sizeof *a);
        double *v = malloc(n * sizeof *v);
        bf_geom *g = malloc(n * sizeof *g);
        bf_material_desc d;
        size_t k;
        if (!fits_something(t)) {
            free(a);
            free(v);
            free(g);
            continue;
        }
        random_configs(n, a);
        for (k = 0; k < n; k++) {
            g[k] = bf_geom_from_measurement(a[4 * k], a[4 * k + 1],
                                            a[4 * k + 2], a[4 * k + 3]);
        }
        bf_test_grid_point(t, 0.23, p[n_types]);
        bf_test_model_brdf(t, p[n_types], n, g, v);
        memset(&d, 0, sizeof d);
        d.name = t->name;
        d.n_channels = 1;
        d.values = v;
        cr_assert_eq(bf_dataset_add_configs(ds, n, a, &d.set, NULL), BF_OK);
        cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
        type[n_types++] = t;
        free(a);
        free(v);
        free(g);
    }
    text = csv_text(ds);
    back = read_back(bf_csv_read, text);
    bf_test_expect_same_dataset(ds, back);
    for (m = 0; m < n_types; m++) {
        size_t k;
        bf_fit_result fit = bf_test_fit_one(back, m, type[m], &k);
        size_t j;
        cr_assert_eq(k, bf_dataset_nconf(back, m));
        for (j = 0; j < type[m]->p; j++) {
            cr_assert_eq(fit.param[j], p[m][j], "%s %s: %.17g, expected %.17g",
                         type[m]->name, type[m]->param[j].name, fit.param[j],
                         p[m][j]);
        }
        cr_assert_lt(fit.lse, 1e-20, "%s: LSE %g", type[m]->name, fit.lse);
    }
    free(text);
    bf_dataset_free(ds);
    bf_dataset_free(back);
}
