/* test_before.c: the analysis beyond the paper on the engine equals the
 * code before it (commit 6d1ece6; tests/ref/analysis_6d1ece6.sh made the
 * fixture) within the tolerances doc/methods.md §9 states, on every CURET
 * sample and every registry model, except where issue 11 changed a result
 * on purpose: WNO-R's quadrature rule (§7; not in the fixture), a
 * parameter the refinement found not identified (flat: ON's rho at
 * sigma = 0 wandered before, §2), the profile end of defect 2 (sample
 * 61, FC-G, n), and the intervals of split sets (a profile below the
 * threshold in two regions, doc/methods.md §3: the interval is now their
 * hull, which must hold the interval before). The run uses only the library's API (what a Python user
 * calls): exact-fit variants, bf_study_analyse, bf_study_rank.
 * The interval columns are those of the profile of the objective's own S,
 * the code before's only method: since issue 18 the default intervals are
 * the noise model's likelihood (doc/methods.md §3), so the run asks for
 * the old method by name (BF_NOISE_OBJECTIVE) -- the fixture's intervals
 * undercover on data with noise and are kept only as this comparison. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

/* doc/methods.md §9: parameters and interval ends to 1e-5 of max(|x|,
 * 0.01); LSE and CV to 1e-7 relative; AIC and BIC to 1e-6 absolute. */
#define PARAM_TOL 1e-5
#define PARAM_FLOOR 0.01
#define SUM_TOL 1e-7
#define IC_TOL 1e-6

/* The fixture's rows: sample, model, parameter and the numbers. */
#define MAX_ROWS 2048
typedef struct {
    int sample;
    char model[16];
    char param[16];
    double v[7]; /* refined_value, refined_lse, ci_low, ci_high, aic, bic,
                    cv (NaN where empty) */
    int seen;
} ref_row;

static ref_row ref[MAX_ROWS];
static size_t n_ref;

static void load_fixture(void)
{
    FILE *fp = fopen(bf_test_fixture_path("analysis_6d1ece6.csv"), "r");
    char line[512];
    cr_assert_not_null(fp);
    cr_assert_not_null(fgets(line, sizeof line, fp)); /* header */
    n_ref = 0;
    while (fgets(line, sizeof line, fp) != NULL && n_ref < MAX_ROWS) {
        ref_row *r = &ref[n_ref];
        char *f[10];
        size_t nf = 0;
        char *p = line;
        size_t k;
        line[strcspn(line, "\n")] = '\0';
        while (nf < 10) {
            f[nf++] = p;
            p = strchr(p, ',');
            if (p == NULL) {
                break;
            }
            *p++ = '\0';
        }
        cr_assert_eq(nf, 10, "fixture line %zu", n_ref + 2);
        r->sample = atoi(f[0]);
        snprintf(r->model, sizeof r->model, "%s", f[1]);
        snprintf(r->param, sizeof r->param, "%s", f[2]);
        for (k = 0; k < 7; k++) {
            r->v[k] = f[3 + k][0] == '\0' ? NAN : strtod(f[3 + k], NULL);
        }
        r->seen = 0;
        n_ref++;
    }
    fclose(fp);
    cr_assert_gt(n_ref, 0);
}

static ref_row *find(int sample, const char *model, const char *param)
{
    size_t i;
    for (i = 0; i < n_ref; i++) {
        if (ref[i].sample == sample && strcmp(ref[i].model, model) == 0 &&
            strcmp(ref[i].param, param) == 0) {
            return &ref[i];
        }
    }
    return NULL;
}

/* |a - b| <= tol * scale, NaN equal to NaN. */
/* 1 when the fixture has rows of model (models added after it have
 * none: they have no "before"). */
static int in_fixture(const char *model)
{
    size_t i;
    for (i = 0; i < n_ref; i++) {
        if (strcmp(ref[i].model, model) == 0) {
            return 1;
        }
    }
    return 0;
}

static void close_to(double now, double before, double tol, double scale,
                     const ref_row *r, const char *what)
{
    if (isnan(before)) {
        cr_expect(isnan(now), "%d %s %s %s: now %.10g, before empty",
                  r->sample, r->model, r->param, what, now);
        return;
    }
    cr_expect(fabs(now - before) <= tol * scale,
              "%d %s %s %s: now %.10g, before %.10g (tolerance %g x %g)",
              r->sample, r->model, r->param, what, now, before, tol, scale);
}

static double param_scale(double a, double b)
{
    return fmax(fmax(fabs(a), fabs(b)), PARAM_FLOOR);
}

Test(before, the_engine_gives_the_analysis_of_the_code_before_it,
     .timeout = 600)
{
    bf_dataset *ds = NULL;
    bf_target *targets = NULL;
    size_t n_targets = 0;
    bf_model_variant variants[64];
    const bf_model_type *models[64];
    size_t n_models = 0;
    bf_study_spec spec;
    bf_analysis_opts opts;
    bf_study_row *rows;
    bf_fit_stats *stats;
    bf_error err;
    size_t t;
    size_t m;
    size_t i;
    int defect_checked = 0;
    size_t n_split = 0;

    load_fixture();
    cr_assert_eq(bf_curet_load(BF_CURET_DIR, NULL, &ds, &err), BF_OK, "%s",
                 err.msg);
    cr_assert_eq(bf_study_targets(ds, NULL, 0, NULL, &targets, &n_targets,
                                  &err),
                 BF_OK);
    for (i = 0; i < bf_model_count(); i++) { /* every registry model */
        const bf_model_type *base = bf_model_get(i);
        if (strcmp(base->name, "WNO-R") == 0) {
            continue; /* new quadrature rule (doc/methods.md §7) */
        }
        if (!in_fixture(base->name)) {
            continue; /* added after the fixture */
        }
        cr_assert_lt(n_models, 64);
        bf_model_variant_init(&variants[n_models], base);
        bf_model_variant_exact(&variants[n_models], 0); /* --fit exact */
        models[n_models] = &variants[n_models].type;
        n_models++;
    }
    bf_test_study_spec(&spec, ds, targets, n_targets, models, n_models);
    spec.n_threads = 2;
    bf_analysis_opts_init(&opts);
    opts.exact = 1;
    opts.noise = BF_NOISE_OBJECTIVE; /* the fixture's interval method */
    rows = calloc(n_targets * n_models, sizeof *rows);
    stats = calloc(n_targets * n_models, sizeof *stats);
    cr_assert(rows != NULL && stats != NULL);
    cr_assert_eq(bf_study_analyse(&spec, &opts, rows, stats, &err), BF_OK,
                 "%s", err.msg);

    for (t = 0; t < n_targets; t++) {
        for (m = 0; m < n_models; m++) {
            const bf_study_row *r = &rows[t * n_models + m];
            const bf_fit_stats *s = &stats[t * n_models + m];
            const bf_model_type *type = models[m];
            size_t j;
            int any = 0;
            cr_assert_eq(r->status, BF_OK);
            for (j = 0; j <= type->p; j++) {
                const char *name;
                ref_row *b;
                if (j < type->p && !type->param[j].fitted) {
                    continue;
                }
                if (j == type->p && any) {
                    break;
                }
                name = j < type->p ? type->param[j].name : "";
                b = find(r->sample, type->name, name);
                cr_assert_not_null(b, "%d %s %s not in the fixture",
                                   r->sample, type->name, name);
                b->seen = 1;
                close_to(s->refined.lse, b->v[1], SUM_TOL, b->v[1], b,
                         "refined_lse");
                close_to(s->aic, b->v[4], IC_TOL, 1.0, b, "aic");
                close_to(s->bic, b->v[5], IC_TOL, 1.0, b, "bic");
                close_to(s->cv, b->v[6], SUM_TOL, b->v[6], b, "cv");
                if (j == type->p) {
                    break; /* a model without fitted parameters */
                }
                any = 1;
                if ((s->refined.flat >> j) & 1u) {
                    continue; /* not identified: the value is arbitrary */
                }
                close_to(s->refined.param[j], b->v[0], PARAM_TOL,
                         param_scale(s->refined.param[j], b->v[0]), b,
                         "refined_value");
                if (r->sample == 61 && strcmp(type->name, "FC-G") == 0 &&
                    strcmp(name, "n") == 0) {
                    /* defect 2: before 1.2056, now the true end 1.21954
                     * (the peer's, confirmed by a dense scan) */
                    close_to(s->ci_low[j], b->v[2], PARAM_TOL,
                             param_scale(s->ci_low[j], b->v[2]), b, "ci_low");
                    cr_expect_float_eq(b->v[3], 1.205596955, 1e-9);
                    cr_expect_float_eq(s->ci_high[j], 1.21954, 1e-5);
                    defect_checked = 1;
                    continue;
                }
                if (((s->not_identified >> j) & 1u) &&
                    !(fabs(s->ci_low[j] - b->v[2]) <=
                          PARAM_TOL * param_scale(s->ci_low[j], b->v[2]) &&
                      fabs(s->ci_high[j] - b->v[3]) <=
                          PARAM_TOL * param_scale(s->ci_high[j], b->v[3]))) {
                    /* a split set (doc/methods.md §3): the profile is
                     * below the threshold in a region apart from the
                     * estimate's too, and the interval is their hull --
                     * it holds the interval before, the estimate's region */
                    cr_expect(s->ci_low[j] <= b->v[2] + PARAM_TOL &&
                                  s->ci_high[j] >= b->v[3] - PARAM_TOL,
                              "%d %s %s: [%.10g, %.10g] does not hold "
                              "[%.10g, %.10g]", b->sample, b->model,
                              name, s->ci_low[j], s->ci_high[j], b->v[2],
                              b->v[3]);
                    n_split++;
                    continue;
                }
                close_to(s->ci_low[j], b->v[2], PARAM_TOL,
                         param_scale(s->ci_low[j], b->v[2]), b, "ci_low");
                close_to(s->ci_high[j], b->v[3], PARAM_TOL,
                         param_scale(s->ci_high[j], b->v[3]), b, "ci_high");
            }
        }
    }
    cr_expect(defect_checked);
    cr_log_info("%zu split intervals (hulls) against the fixture", n_split);
    for (i = 0; i < n_ref; i++) { /* the fixture has nothing we skipped */
        cr_expect(ref[i].seen, "fixture row %d %s %s not compared",
                  ref[i].sample, ref[i].model, ref[i].param);
    }
    free(rows);
    free(stats);
    free(targets);
    bf_dataset_free(ds);
}
