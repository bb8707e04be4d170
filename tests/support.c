/* support.c: shared helpers of the test suite (see support.h). */
#include "support.h"
#include "random_geometry.h"

#include <criterion/criterion.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void bf__assert_rel(double obtained, double expected, double tol,
                    const char *what, const char *file, int line)
{
    double scale = fabs(expected) > 1e-300 ? fabs(expected) : 1e-300;
    double rel = fabs(obtained - expected) / scale;
    if (!(rel <= tol)) {
        cr_expect_fail("%s:%d: %s: expected %.17g, obtained %.17g, "
                "relative difference %.3g, tolerance %.3g",
                file, line, what, expected, obtained, rel, tol);
    }
}

void bf__assert_abs(double obtained, double expected, double tol,
                    const char *what, const char *file, int line)
{
    double diff = fabs(obtained - expected);
    if (!(diff <= tol)) {
        cr_expect_fail("%s:%d: %s: expected %.17g, obtained %.17g, "
                "absolute difference %.3g, tolerance %.3g",
                file, line, what, expected, obtained, diff, tol);
    }
}

static const char *path_in(const char *env, const char *dflt, const char *file)
{
    static char buf[4096];
    const char *dir = getenv(env);
    struct stat st;
    if (dir == NULL || dir[0] == '\0') {
        dir = dflt;
    }
    snprintf(buf, sizeof buf, "%s/%s", dir, file);
    if (stat(buf, &st) != 0) {
        cr_assert_fail("required data file %s is missing (set %s or configure "
                 "BF_SHARED_DIR); tests never skip for missing data",
                 buf, env);
    }
    return buf;
}

const char *bf_test_curet_path(const char *file)
{
    return path_in("BRDFFIT_CURET_DIR", BF_CURET_DIR, file);
}

const char *bf_test_reference_path(const char *file)
{
    return path_in("BRDFFIT_REFERENCE_DIR", BF_REFERENCE_DIR, file);
}

const char *bf_test_cornell_path(const char *file)
{
    return path_in("BRDFFIT_CORNELL_DIR", BF_CORNELL_DIR, file);
}

const char *const bf_test_cornell[BF_TEST_NCORNELL] = {
    "acryl_blue.brdf", "cayman.brdf", "garnet_red.brdf", "krylon_blue.brdf",
    "mystique.brdf"};

/* 1 when two doubles have the same bits. */
static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

void bf_test_expect_same_dataset(const bf_dataset *a, const bf_dataset *b)
{
    size_t m;
    cr_assert_eq(bf_dataset_count(a), bf_dataset_count(b),
                 "material counts %zu and %zu", bf_dataset_count(a),
                 bf_dataset_count(b));
    for (m = 0; m < bf_dataset_count(a); m++) {
        size_t n = bf_dataset_nconf(a, m);
        size_t nc = bf_dataset_nchannels(a, m);
        const double *aa = bf_dataset_angles(a, m);
        const double *ba = bf_dataset_angles(b, m);
        const double *av = bf_dataset_values(a, m);
        const double *bv = bf_dataset_values(b, m);
        const unsigned char *aok = bf_dataset_valid(a, m);
        const unsigned char *bok = bf_dataset_valid(b, m);
        size_t j;
        size_t k;
        size_t c;
        cr_assert_str_eq(bf_dataset_name(a, m), bf_dataset_name(b, m));
        cr_assert_eq(bf_dataset_number(a, m), bf_dataset_number(b, m));
        cr_assert_eq(bf_dataset_nconf(b, m), n, "material %zu: %zu and %zu "
                     "configurations", m, n, bf_dataset_nconf(b, m));
        cr_assert_eq(bf_dataset_nchannels(b, m), nc);
        for (j = 0; j < m; j++) {
            cr_assert_eq(bf_dataset_set(a, m) == bf_dataset_set(a, j),
                         bf_dataset_set(b, m) == bf_dataset_set(b, j),
                         "materials %zu and %zu share a set in one dataset "
                         "only", j, m);
        }
        for (k = 0; k < 4 * n; k++) {
            cr_assert(same_bits(aa[k], ba[k]),
                      "material %zu, configuration %zu, angle %zu: %.17g "
                      "and %.17g", m, k / 4, k % 4, aa[k], ba[k]);
        }
        for (c = 0; c < nc; c++) {
            double wa = bf_dataset_wavelength(a, m, c);
            double wb = bf_dataset_wavelength(b, m, c);
            cr_assert_str_eq(bf_dataset_channel(a, m, c),
                             bf_dataset_channel(b, m, c));
            cr_assert(same_bits(wa, wb) || (isnan(wa) && isnan(wb)),
                      "channel %zu: wavelengths %g and %g", c, wa, wb);
        }
        cr_assert_eq(aok == NULL, bok == NULL,
                     "material %zu: valid marks in one dataset only", m);
        for (k = 0; k < n * nc; k++) {
            int ok = aok == NULL || aok[k];
            cr_assert_eq(ok, bok == NULL || bok[k]);
            cr_assert(!ok || same_bits(av[k], bv[k]),
                      "material %zu, value %zu: %.17g and %.17g", m, k,
                      av[k], bv[k]);
        }
    }
}

bf_dataset *bf_test_read_ok(bf_test_reader rd, const char *name,
                            const char *text)
{
    bf_dataset *ds = NULL;
    bf_error err;
    char msg[1024];
    FILE *fp = bf_test_memfile(text);
    int rc = rd(fp, name, &ds, &err);
    fclose(fp);
    cr_assert_eq(rc, BF_OK, "%s", bf_error_format(&err, msg, sizeof msg));
    cr_assert_eq(err.code, BF_OK);
    cr_assert_not_null(ds);
    return ds;
}

void bf_test_expect_read_error(bf_test_reader rd, const char *name,
                               const void *buf, size_t len, int code,
                               long line, const char *msg)
{
    bf_dataset *ds = (bf_dataset *)&ds; /* the reader must reset it */
    bf_error err;
    FILE *fp = bf_test_membuf(buf, len);
    int rc = rd(fp, name, &ds, &err);
    fclose(fp);
    cr_assert_eq(rc, code, "rc %d, expected %d (%s)", rc, code, err.msg);
    cr_assert_null(ds);
    cr_assert_eq(err.code, code);
    cr_assert_eq(err.line, line, "line %ld, expected %ld (%s)", err.line,
                 line, err.msg);
    cr_assert_str_eq(err.file, name);
    cr_assert_str_eq(err.msg, msg);
}

void bf_test_grid_point(const bf_model_type *type, double frac,
                        double *param)
{
    size_t j;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        param[j] = pj->value;
        if (pj->fitted && pj->grid_n > 0) {
            size_t i = (size_t)(frac * (double)(pj->grid_n - 1));
            param[j] = pj->grid_lo + pj->grid_step * (double)i; /* grid.c */
        }
    }
}

void bf_test_model_brdf(const bf_model_type *type, const double *param,
                        size_t n, const bf_geom *geom, double *out)
{
    size_t k;
    cr_assert_eq(bf_model_eval(type, param, n, geom, out), BF_OK, "%s",
                 type->name);
    for (k = 0; k < n; k++) {
        out[k] /= cos(geom[k].theta_i);
    }
}

bf_fit_result bf_test_fit_one(const bf_dataset *ds, size_t m,
                              const bf_model_type *type, size_t *k)
{
    bf_target t = {m, BF_CHANNEL_MEAN, 0};
    bf_study_row row;
    bf_study_spec spec;
    bf_error err;
    memset(&spec, 0, sizeof spec);
    spec.data = ds;
    bf_selection_init(&spec.select);
    spec.targets = &t;
    spec.n_targets = 1;
    spec.models = &type;
    spec.n_models = 1;
    spec.n_default = BF_DEFAULT_N;
    cr_assert_eq(bf_study_run(&spec, &row, &err), BF_OK, "%s", err.msg);
    cr_assert_eq(row.status, BF_OK, "%s", type->name);
    if (k != NULL) {
        *k = row.k;
    }
    return row.fit;
}

const char *bf_test_fixture_path(const char *file)
{
    return path_in("BRDFFIT_FIXTURES_DIR", BF_FIXTURES_DIR, file);
}

void bf_test_study_spec(bf_study_spec *spec, const bf_dataset *ds,
                        const bf_target *targets, size_t n_targets,
                        const bf_model_type *const *models, size_t n_models)
{
    memset(spec, 0, sizeof *spec);
    spec->data = ds;
    spec->targets = targets;
    spec->n_targets = n_targets;
    bf_selection_init(&spec->select);
    spec->models = models;
    spec->n_models = n_models;
    spec->n_default = BF_DEFAULT_N;
}

bf_table *bf_test_load_table(void)
{
    bf_table *t = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_table_load(bf_test_curet_path("table.txt"), &t, &err);
    if (rc != BF_OK) {
        cr_assert_fail("cannot load table.txt: %s",
                 bf_error_format(&err, msg, sizeof msg));
    }
    return t;
}

void bf_test_random_geometry(bf_geom *geom, size_t n, unsigned long seed,
                             int mirror)
{
    cr_assert_eq(bf_random_geometry(geom, n, seed, mirror), n,
                 "cannot allocate the random geometry's generator");
}

size_t bf_test_curet_geometry(bf_geom *geom, size_t stride)
{
    bf_table *t = bf_test_load_table();
    size_t sel[BF_CURET_NCONF];
    size_t n = bf_table_select(t, M_PI, sel);
    size_t k;
    size_t m = 0;
    for (k = 0; k < n; k += stride) {
        geom[m++] = bf_table_geom(t, sel[k]);
    }
    bf_table_free(t);
    return m;
}

bf_brdf *bf_test_load_abrdf(void)
{
    bf_brdf *b = NULL;
    bf_error err;
    char msg[1024];
    int rc = bf_brdf_load(bf_test_curet_path("abrdf.dat"), BF_CURET_NCONF, &b,
                          &err);
    if (rc != BF_OK) {
        cr_assert_fail("cannot load abrdf.dat: %s",
                 bf_error_format(&err, msg, sizeof msg));
    }
    return b;
}

FILE *bf_test_memfile(const char *text)
{
    return bf_test_membuf(text, strlen(text));
}

FILE *bf_test_membuf(const void *buf, size_t len)
{
    /* fmemopen with size 0 is unspecified; an empty stream is a tmpfile. */
    FILE *fp;
    if (len == 0) {
        fp = tmpfile();
    } else {
        fp = fmemopen((void *)(uintptr_t)buf, len, "r");
    }
    cr_assert_not_null(fp, "cannot open an in-memory stream");
    return fp;
}

/* ==== synthetic glossy materials through tidy CSV ======================= */

void bf_test_glossy_configs(double *at)
{
    const double pi = 3.14159265358979323846;
    const double deg = pi / 180.0;
    size_t n = 0;
    int a;
    for (a = 0; a < 8; a++) {
        double ti = (5.0 + 10.0 * a) * deg;
        int u;
        int w;
        for (u = -2; u <= 2; u++) {
            for (w = -2; w <= 2; w++) {
                at[4 * n + 0] = ti;
                at[4 * n + 1] = 0.0;
                at[4 * n + 2] = fabs(ti + 2.0 * u * deg);
                at[4 * n + 3] = pi + 3.0 * w * deg;
                n++;
            }
        }
        for (u = 0; u < 5; u++) {
            for (w = 0; w < 5; w++) {
                at[4 * n + 0] = ti;
                at[4 * n + 1] = 0.0;
                at[4 * n + 2] = (5.0 + 15.0 * u) * deg;
                at[4 * n + 3] = (72.0 * w + 10.0) * deg;
                n++;
            }
        }
    }
    cr_assert_eq(n, BF_TEST_GLOSSY_NCONF);
}

void bf_test_write_model_csv(const char *path, size_t K, const double *at,
                             size_t n, const bf_test_material *mat)
{
    bf_test_write_noisy_csv(path, K, at, n, mat, 0.0, 0);
}

bf_dataset *bf_test_channels_dataset(size_t K, const double *at, size_t n,
                                     const char *const *names, size_t C,
                                     const char *const *channel,
                                     const double *wavelength,
                                     const double *values)
{
    bf_dataset *ds = bf_dataset_alloc();
    size_t set;
    size_t i;
    cr_assert_not_null(ds);
    cr_assert_eq(bf_dataset_add_configs(ds, K, at, &set, NULL), BF_OK);
    for (i = 0; i < n; i++) {
        bf_material_desc d;
        memset(&d, 0, sizeof d);
        d.name = names[i];
        d.format = BF_FORMAT_MEMORY;
        d.set = set;
        d.n_channels = C;
        d.channel = channel;
        d.wavelength = wavelength;
        d.values = values + i * K * C;
        cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK, "%s",
                     names[i]);
    }
    return ds;
}

void bf_test_write_channels_csv(const char *path, size_t K,
                                const double *at, size_t n,
                                const char *const *names, size_t C,
                                const char *const *channel,
                                const double *wavelength,
                                const double *values)
{
    bf_dataset *ds = bf_test_channels_dataset(K, at, n, names, C, channel,
                                              wavelength, values);
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp, "%s", path);
    cr_assert_eq(bf_csv_write(ds, fp), BF_OK);
    cr_assert_eq(fclose(fp), 0);
    bf_dataset_free(ds);
}

void bf_test_write_noisy_csv(const char *path, size_t K, const double *at,
                             size_t n, const bf_test_material *mat,
                             double noise, unsigned long seed)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double *v = malloc((n + 1) * K * sizeof *v);
    const char **names = malloc((n + 1) * sizeof *names);
    bf_geom *g = malloc(K * sizeof *g);
    size_t i;
    size_t k;
    cr_assert(v != NULL && names != NULL && g != NULL && rng != NULL);
    gsl_rng_set(rng, seed);
    for (k = 0; k < K; k++) {
        g[k] = bf_geom_from_measurement(at[4 * k], at[4 * k + 1],
                                        at[4 * k + 2], at[4 * k + 3]);
    }
    for (i = 0; i < n; i++) {
        cr_assert_eq(bf_model_eval(mat[i].type, mat[i].param, K, g,
                                   v + i * K),
                     BF_OK, "%s", mat[i].name);
        for (k = 0; noise > 0.0 && k < K; k++) { /* relative noise */
            v[i * K + k] *= 1.0 + noise * gsl_ran_gaussian(rng, 1.0);
        }
        names[i] = mat[i].name;
    }
    bf_test_write_channels_csv(path, K, at, n, names, 1, NULL, NULL, v);
    gsl_rng_free(rng);
    free(g);
    free(names);
    free(v);
}

void bf_test_write_glossy_csv(const char *path, size_t n,
                              const bf_test_material *mat)
{
    double *at = malloc(4 * BF_TEST_GLOSSY_NCONF * sizeof *at);
    cr_assert_not_null(at);
    bf_test_glossy_configs(at);
    bf_test_write_model_csv(path, BF_TEST_GLOSSY_NCONF, at, n, mat);
    free(at);
}

double bf_test_truth_at(const bf_problem *pb, size_t j)
{
    double f = pb->type->kind != BF_MODEL_SPECULAR &&
                       strcmp(pb->type->param[j].name, "n") == 0
                   ? 0.15
                   : 0.3731;
    return pb->lo[j] + f * (pb->hi[j] - pb->lo[j]);
}
