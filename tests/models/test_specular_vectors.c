/* test_specular_vectors.c: every specular model of SPEC §9.3 against the
 * independent values of shared/reference/microfacet_vectors.tsv (1e-12
 * relative; read in place, the test fails when the file is missing), the
 * Mitsuba values of shared/reference/README.md, the engine's kernel
 * against the reference eval (same bits), and the variants' table. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"
#include "models/microfacet.h"
#include "support.h"

#ifndef VECTORS
#define VECTORS BF_REFERENCE_DIR "/microfacet_vectors.tsv"
#endif
#define TOL_REF 1e-12

/* The variant a row names: "GGX separable" is the separable Smith form;
 * GGX, BECKMANN and CT rows without F0 have F = 1 (the file's header). */
static const bf_model_type *row_type(char *model, const char *params)
{
    bf_smith_kind s = BF_SMITH_DEFAULT;
    bf_fresnel_kind f = BF_FRESNEL_DEFAULT;
    char *space = strchr(model, ' ');
    const bf_model_type *base;
    const bf_model_type *t;
    const char *why = NULL;
    if (space != NULL) {
        cr_assert_str_eq(space + 1, "separable", "row model '%s'", model);
        *space = '\0';
        s = BF_SMITH_SEPARABLE;
    }
    base = bf_model_find(model);
    cr_assert_not_null(base, "unknown model '%s' in %s", model, VECTORS);
    cr_assert_eq(base->kind, BF_MODEL_SPECULAR, "%s", model);
    if (base->variants != NULL && strstr(params, "F0=") == NULL) {
        f = BF_FRESNEL_NONE;
    }
    t = bf_model_specular_variant(base, f, s, &why);
    cr_assert_not_null(t, "%s: %s", model, why ? why : "?");
    return t;
}

/* The parameter vector of "name=value,..." for t: every name of t once. */
static void row_params(const bf_model_type *t, const char *params, double *p)
{
    char buf[256];
    char *save = NULL;
    char *tok;
    size_t n = 0;
    cr_assert_lt(strlen(params), sizeof buf);
    strcpy(buf, params);
    for (tok = strtok_r(buf, ",", &save); tok != NULL;
         tok = strtok_r(NULL, ",", &save)) {
        char *eq = strchr(tok, '=');
        int j;
        cr_assert_not_null(eq, "parameter '%s'", tok);
        *eq = '\0';
        j = bf_model_param_index(t, tok);
        cr_assert_geq(j, 0, "%s has no parameter '%s'", t->name, tok);
        p[j] = strtod(eq + 1, NULL);
        n++;
    }
    cr_assert_eq(n, t->p, "%s: %zu of %zu parameters", t->name, n, t->p);
}

/* The engine's kernel of t on the n configurations g: its configuration
 * set cs, prepared model pm and a workspace (returned; kernel_close). */
static void *kernel_open(const bf_model_type *t, size_t n, const bf_geom *g,
                         bf__cset *cs, bf__prep *pm)
{
    void *work;
    cr_assert_eq(bf__cset_init(cs, n, g), BF_OK);
    cr_assert_eq(bf__prep_init(pm, t, cs), BF_OK);
    work = bf__work_alloc(pm);
    cr_assert_not_null(work);
    return work;
}

static void kernel_close(void *work, bf__prep *pm, bf__cset *cs)
{
    free(work);
    bf__prep_free(pm);
    bf__cset_free(cs);
}

/* The kernel's values at p on the configurations g equal eval's bits. */
static void expect_kernel_bits(const bf_model_type *t, const double *p,
                               size_t n, const bf_geom *g, const double *ref)
{
    bf__cset cs;
    bf__prep pm;
    void *work;
    double out[8];
    size_t k;
    cr_assert_leq(n, 8);
    cr_assert_not_null(t->kernel, "%s", t->name);
    work = kernel_open(t, n, g, &cs, &pm);
    (void)pm.kr->values(&pm, p, work, out);
    for (k = 0; k < n; k++) {
        cr_expect(memcmp(&out[k], &ref[k], sizeof out[k]) == 0,
                  "%s kernel at %zu: %.17g vs eval %.17g", t->name, k,
                  out[k], ref[k]);
    }
    kernel_close(work, &pm, &cs);
}

/* A kernel that keeps factors of earlier calls in its workspace (ABC: F
 * per ior in a few slots, the power per (B, C)) gives eval's bits in any
 * order of calls: one workspace over a sequence that changes ior, B or C
 * alone, cycles ior through more values than the slots and comes back. */
Test(specular_vectors, a_kernels_kept_factors_give_evals_bits_in_any_order)
{
    const bf_model_type *t = bf_model_find("ABC");
    bf_geom g[6];
    bf__cset cs;
    bf__prep pm;
    void *work;
    double out[6];
    double ref[6];
    size_t i;
    size_t k;
    cr_assert_not_null(t);
    for (k = 0; k < 6; k++) {
        g[k] = bf_geom_from_measurement(0.1 + 0.2 * (double)k, 0.3,
                                        0.15 + 0.2 * (double)k, 3.0);
    }
    work = kernel_open(t, 6, g, &cs, &pm);
    for (i = 0; i < 60; i++) {
        /* ior through 11 values (eight slots), B every 7th call, C every
         * 5th; A every call */
        double p[4] = {1.0 + (double)i, 300.0 * (double)(1 + (i / 7) % 3),
                       0.5 + 0.25 * (double)((i / 5) % 4),
                       1.1 + 0.2 * (double)((i * 3) % 11)};
        cr_assert_eq(bf_model_eval(t, p, 6, g, ref), BF_OK);
        (void)pm.kr->values(&pm, p, work, out);
        for (k = 0; k < 6; k++) {
            cr_expect(memcmp(&out[k], &ref[k], sizeof out[k]) == 0,
                      "call %zu at %zu: %.17g vs eval %.17g", i, k, out[k],
                      ref[k]);
        }
    }
    kernel_close(work, &pm, &cs);
}

/* A composite's kernel keeps D's term (values, divisors, d(n, n)) in its
 * workspace for D's parameters: one workspace over a sequence that
 * changes rho_d and S's parameters at every call and D's (ON's rho,
 * sigma) every third, back and forth, with a grazing incidence among the
 * configurations (D's limit there), gives eval's values every time, and
 * so does its columns' sum. A term kept for other parameters than D's
 * would be off by far more than the 1e-14 allowed. */
Test(specular_vectors, a_composites_kept_diffuse_term_follows_its_parameters)
{
    const bf_model_type *t = bf_model_find("ON+GGX");
    bf_geom g[6];
    bf__cset cs;
    bf__prep pm;
    void *work;
    double out[6];
    double ref[6];
    double c0[6];
    double buf[2][6];
    double *col[2] = {buf[0], buf[1]};
    size_t i;
    size_t k;
    cr_assert_not_null(t);
    for (k = 0; k < 5; k++) {
        g[k] = bf_geom_from_measurement(0.1 + 0.25 * (double)k, 0.3,
                                        0.15 + 0.2 * (double)k, 3.0);
    }
    g[5] = bf_geom_from_measurement(BF__PI_2, 0.0, 0.7, 2.0); /* grazing */
    work = kernel_open(t, 6, g, &cs, &pm);
    for (i = 0; i < 24; i++) {
        /* rho_d, ON's rho and sigma, GGX's rho_s, alpha, F0 */
        double s = (double)((i / 3) % 4);
        double p[6] = {0.1 + 0.05 * (double)i, 0.3 + 0.1 * s,
                       0.1 + 0.2 * s, 0.5 + 0.01 * (double)i,
                       0.05 + 0.01 * (double)i, 0.04};
        cr_assert_eq(bf_model_eval(t, p, 6, g, ref), BF_OK);
        cr_assert_eq(pm.kr->values(&pm, p, work, out), BF_OK);
        cr_assert_eq(pm.kr->columns(&pm, p, 1u | 8u, work, c0, col),
                     BF_OK);
        for (k = 0; k < 6; k++) {
            double sum = c0[k] + p[0] * col[0][k] + p[3] * col[1][k];
            cr_expect(fabs(out[k] - ref[k]) <= 1e-14 * fabs(ref[k]),
                      "call %zu at %zu: %.17g vs eval %.17g", i, k, out[k],
                      ref[k]);
            cr_expect(fabs(sum - ref[k]) <= 1e-14 * fabs(ref[k]),
                      "call %zu at %zu: columns %.17g vs eval %.17g", i, k,
                      sum, ref[k]);
        }
    }
    kernel_close(work, &pm, &cs);
}

Test(specular_vectors, every_model_gives_the_reference_values)
{
    FILE *fp = fopen(VECTORS, "r");
    char line[1024];
    size_t rows = 0;
    size_t models_seen = 0;
    char seen[16][32];
    cr_assert_not_null(fp, "cannot open %s (shared/reference missing?)",
                       VECTORS);
    while (fgets(line, sizeof line, fp) != NULL) {
        char model[64];
        char params[256];
        double ti, pi, to, po, want, got;
        double p[BF_MAX_PARAMS];
        const bf_model_type *t;
        bf_geom g;
        size_t j;
        if (line[0] == '#' || strncmp(line, "model\t", 6) == 0) {
            continue;
        }
        cr_assert_eq(sscanf(line, "%63[^\t]\t%255[^\t]\t%lf\t%lf\t%lf\t%lf\t%lf",
                            model, params, &ti, &pi, &to, &po, &want),
                     7, "bad row: %s", line);
        t = row_type(model, params);
        row_params(t, params, p);
        g = bf_geom_from_measurement(ti, pi, to, po);
        cr_assert_eq(bf_model_eval(t, p, 1, &g, &got), BF_OK, "%s", line);
        cr_expect(fabs(got - want) <= TOL_REF * fabs(want),
                  "%s %s at (%g, %g, %g, %g): %.17g, reference %.17g "
                  "(rel %.3g)",
                  t->name, params, ti, pi, to, po, got, want,
                  fabs(got - want) / fabs(want));
        expect_kernel_bits(t, p, 1, &g, &got);
        for (j = 0; j < models_seen && strcmp(seen[j], t->name) != 0; j++) {
        }
        if (j == models_seen && models_seen < 16) {
            strcpy(seen[models_seen++], t->name);
        }
        rows++;
    }
    fclose(fp);
    cr_assert_geq(rows, 200u, "%zu rows", rows);
    cr_assert_eq(models_seen, 10u, "%zu models in %s", models_seen, VECTORS);
}

/* Mitsuba 3's src/render/tests/test_microfacet.py (shared/reference/
 * README.md): Beckmann D at alpha = 0.1 and GGX G1 at 0.98 pi/2. */
Test(specular_vectors, mitsuba_values)
{
    static const double th[] = {0.0, BF__PI / 19.0, 2.0 * BF__PI / 19.0,
                                0.1};
    static const double d[] = {31.8309879, 2.07673073, 3.02855828e-04,
                               11.86709118};
    size_t j;
    for (j = 0; j < 4; j++) {
        bf__mf_t m;
        memset(&m, 0, sizeof m);
        m.c2h = cos(th[j]) * cos(th[j]);
        m.s2h = sin(th[j]) * sin(th[j]);
        m.t2h = m.s2h / m.c2h;
        /* Mitsuba's values are single precision (31.8309879 against
         * 1 / (pi 0.01) = 31.83098862); the tail value's exponent, 11.7,
         * multiplies float's 6e-8 */
        bf_assert_rel(bf__mf_d_beckmann(&m, 0.1), d[j], 2e-6);
    }
    bf_assert_rel(1.0 / (1.0 + bf__mf_lambda_ggx(0.98 * BF__PI_2, 0.1)),
                  0.46130955, 1e-7);
}

/* ==== the separable fit's columns (bf_kernel.columns) ==================== */

/* A parameter vector of t inside its domain from u in [0, 1): the scales
 * in [0.2, 2.2], the others uniform (log-uniform over a factor 50). */
static void param_at(const bf_model_type *t, unsigned *seed, double *p)
{
    size_t j;
    for (j = 0; j < t->p; j++) {
        double u = (double)rand_r(seed) / ((double)RAND_MAX + 1.0);
        double lo = t->param[j].min;
        double hi = t->param[j].max;
        if (t->param[j].linear) {
            p[j] = 0.2 + 2.0 * u;
        } else if (lo > 0.0 && hi / lo >= 50.0) {
            p[j] = lo * exp(u * log(hi / lo));
        } else {
            p[j] = lo + u * (hi - lo);
        }
    }
}

/* Every specular model's and composite's columns: c0 + sum theta_q
 * col_q gives values() at param (so a lobe declared proportional to rho_s
 * is), and they equal the columns from values() alone. */
static void expect_columns(const bf_model_type *t, unsigned *seed)
{
    enum { N = 48 };
    bf_geom g[N];
    double c0[N], ref0[N], val[N], buf[4][N];
    double *col[2] = {buf[0], buf[1]};
    double *ref[2] = {buf[2], buf[3]};
    double p[BF_MAX_PARAMS];
    bf__cset cs;
    bf__prep pm;
    unsigned lin = 0;
    size_t n_lin = 0;
    void *work;
    size_t j;
    size_t k;
    int trial;
    int ok = 0;
    for (k = 0; k < N; k++) {
        double u[4];
        for (j = 0; j < 4; j++) {
            u[j] = (double)rand_r(seed) / ((double)RAND_MAX + 1.0);
        }
        g[k] = bf_geom_from_measurement(1.5 * u[0], 2.0 * BF__PI * u[1],
                                        1.5 * u[2], 2.0 * BF__PI * u[3]);
    }
    for (j = 0; j < t->p; j++) {
        if (t->param[j].linear) {
            lin |= 1u << j;
            n_lin++;
        }
    }
    cr_assert_leq(n_lin, 2u, "%s", t->name);
    work = kernel_open(t, N, g, &cs, &pm);
    for (trial = 0; trial < 40 && ok < 4; trial++) {
        param_at(t, seed, p);
        if (pm.kr->values(&pm, p, work, val) != BF_OK) {
            continue; /* undefined there (a clamp of D at the normal) */
        }
        ok++;
        cr_assert_eq(bf__columns_values(&pm, p, lin, work, ref0, ref),
                     BF_OK, "%s", t->name);
        cr_assert_eq((pm.kr->columns != NULL ? pm.kr->columns
                                             : bf__columns_values)(
                         &pm, p, lin, work, c0, col),
                     BF_OK, "%s", t->name);
        for (k = 0; k < N; k++) {
            double sum = c0[k];
            double q0 = ref0[k];
            size_t q = 0;
            for (j = 0; j < t->p; j++) {
                if ((lin >> j) & 1u) {
                    sum += p[j] * col[q][k];
                    q0 += p[j] * ref[q][k];
                    cr_expect(fabs(col[q][k] - ref[q][k])
                                  <= 1e-12 * fabs(val[k]) / p[j] + 1e-290,
                              "%s column %zu at %zu: %.17g vs %.17g",
                              t->name, q, k, col[q][k], ref[q][k]);
                    q++;
                }
            }
            cr_expect(fabs(sum - val[k]) <= 1e-12 * fabs(val[k]) + 1e-290,
                      "%s at %zu: columns give %.17g, values %.17g",
                      t->name, k, sum, val[k]);
            cr_expect(fabs(q0 - val[k]) <= 1e-12 * fabs(val[k]) + 1e-290,
                      "%s at %zu: differences give %.17g, values %.17g",
                      t->name, k, q0, val[k]);
        }
    }
    cr_expect_eq(ok, 4, "%s: defined at %d of %d parameter draws", t->name,
                 ok, trial);
    kernel_close(work, &pm, &cs);
}

Test(specular_vectors, columns_reproduce_the_values)
{
    static const char *const diffuse[] = {"LAMBERT", "ON", "FC-E", "VH-G"};
    unsigned seed = 17u;
    size_t tested = 0;
    size_t i;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *s = bf_model_get(i);
        size_t d;
        if (s->kind != BF_MODEL_SPECULAR) {
            continue;
        }
        expect_columns(s, &seed);
        tested++;
        for (d = 0; d < sizeof diffuse / sizeof diffuse[0]; d++) {
            char name[64];
            const bf_model_type *t;
            snprintf(name, sizeof name, "%s+%s", diffuse[d], s->name);
            t = bf_model_find(name);
            cr_assert_not_null(t, "%s", name);
            expect_columns(t, &seed);
            tested++;
        }
    }
    cr_assert_eq(tested, 50u, "%zu models and composites", tested);
}
