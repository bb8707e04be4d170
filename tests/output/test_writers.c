/* test_writers.c: the library's writers of fits.csv and ranking.csv
 * (bf_fits_csv_write, bf_ranking_csv_write) and the flags of a fit
 * (bf_fit_flags_format), called as a C or Python user calls them: on a
 * study run through the API, into memory. The values written are the
 * analysis's (read back to 10 digits), ranks those of bf_study_rank. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

Test(writers, flags_name_what_the_analysis_found)
{
    const bf_model_type *on = bf_model_find("ON");
    bf_fit_stats s;
    char buf[256];
    char small[12];
    size_t len;
    memset(&s, 0, sizeof s);
    cr_assert_eq(bf_fit_flags_format(on, &s, buf, sizeof buf), 0);
    cr_assert_str_eq(buf, "");
    s.done = 1;
    cr_assert_eq(bf_fit_flags_format(on, &s, buf, sizeof buf), 0);
    s.flags = BF_STAT_REDUCED | BF_STAT_CLAMPED | BF_STAT_NOCONV |
              BF_STAT_CI_FAIL | BF_STAT_BOOT_FAIL | BF_STAT_BOOT_SPLIT;
    s.reduces_to = "LAMBERT";
    s.refined.flat = 1u;  /* rho */
    s.n_clamped = 3;
    s.boot_split = 2u;    /* sigma */
    len = bf_fit_flags_format(on, &s, buf, sizeof buf);
    cr_assert_str_eq(buf, "reduces_to=LAMBERT not_identified=rho clamped=3 "
                          "not_converged interval_failed bootstrap_failed "
                          "bootstrap_split=sigma");
    cr_assert_eq(len, strlen(buf));
    /* truncated, terminated, the full length returned (as snprintf) */
    cr_assert_eq(bf_fit_flags_format(on, &s, small, sizeof small), len);
    cr_assert_eq(strlen(small), sizeof small - 1);
    cr_assert_eq(strncmp(small, buf, sizeof small - 1), 0);
}

/* A small study through the API: samples 1, 26 of CURET; FC-E and ON with
 * the exact fit's free parameters, LAMBERT. */
typedef struct {
    bf_dataset *ds;
    bf_target *targets;
    bf_model_variant v[3];
    const bf_model_type *models[3];
    bf_study_spec spec;
    bf_analysis_opts opts;
    bf_study_row rows[6];
    bf_fit_stats stats[6];
} study;

static void run_study(study *s)
{
    static const char *const names[3] = {"FC-E", "ON", "LAMBERT"};
    size_t materials[2];
    size_t n = 0;
    bf_error err;
    size_t m;
    memset(s, 0, sizeof *s);
    cr_assert_eq(bf_curet_load(BF_CURET_DIR, NULL, &s->ds, &err), BF_OK);
    materials[0] = (size_t)bf_dataset_find(s->ds, 1);
    materials[1] = (size_t)bf_dataset_find(s->ds, 26);
    cr_assert_eq(bf_study_targets(s->ds, materials, 2, NULL, &s->targets,
                                  &n, &err),
                 BF_OK);
    for (m = 0; m < 3; m++) {
        bf_model_variant_init(&s->v[m], bf_model_find(names[m]));
        bf_model_variant_exact(&s->v[m], 0);
        s->models[m] = &s->v[m].type;
    }
    s->spec.data = s->ds;
    s->spec.targets = s->targets;
    s->spec.n_targets = n;
    bf_selection_init(&s->spec.select);
    s->spec.models = s->models;
    s->spec.n_models = 3;
    s->spec.n_default = BF_DEFAULT_N;
    bf_analysis_opts_init(&s->opts);
    s->opts.exact = 1;
    s->opts.folds = 5;
    cr_assert_eq(bf_study_analyse(&s->spec, &s->opts, s->rows, s->stats,
                                  &err),
                 BF_OK, "%s", err.msg);
}

static void free_study(study *s)
{
    free(s->targets);
    bf_dataset_free(s->ds);
}

/* The text written by writer into memory (caller frees). */
static char *written(int (*writer)(FILE *, const bf_study_spec *,
                                   const bf_study_row *,
                                   const bf_fit_stats *,
                                   const bf_analysis_opts *),
                     const study *s)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    cr_assert_not_null(fp);
    cr_assert_eq(writer(fp, &s->spec, s->rows, s->stats, &s->opts), BF_OK);
    fclose(fp);
    return text;
}

/* Field `col` (0-based) of line `line` (0 = header) of CSV text without
 * quoted fields, into buf. */
static const char *field(const char *text, size_t line, size_t col,
                         char *buf, size_t len)
{
    const char *p = text;
    size_t n;
    for (; line > 0; line--) {
        p = strchr(p, '\n');
        cr_assert_not_null(p);
        p++;
    }
    for (; col > 0; col--) {
        p += strcspn(p, ",\n");
        cr_assert_eq(*p, ',');
        p++;
    }
    n = strcspn(p, ",\n");
    cr_assert_lt(n, len);
    memcpy(buf, p, n);
    buf[n] = '\0';
    return buf;
}

static size_t column(const char *text, const char *name)
{
    char buf[64];
    size_t c;
    for (c = 0; c < 200; c++) {
        if (strcmp(field(text, 0, c, buf, sizeof buf), name) == 0) {
            return c;
        }
    }
    cr_assert_fail("no column %s", name);
    return 0;
}

static size_t count_lines(const char *text)
{
    size_t n = 0;
    for (; *text != '\0'; text++) {
        n += *text == '\n';
    }
    return n;
}

Test(writers, fits_csv_has_a_line_per_fitted_parameter_with_its_analysis)
{
    study s;
    char *text;
    char buf[128];
    size_t line = 1;
    size_t t;
    size_t m;
    run_study(&s);
    text = written(bf_fits_csv_write, &s);
    cr_assert_eq(strncmp(text, "sample,name,channel,model,parameter,unit,"
                               "value,lse,bound_hit,k,objective,fit,",
                         62),
                 0);
    /* FC-E: m, n; ON: rho, sigma; LAMBERT: one line; two samples */
    cr_assert_eq(count_lines(text), 1 + 2 * 5);
    for (t = 0; t < 2; t++) {
        for (m = 0; m < 3; m++) {
            const bf_study_row *r = &s.rows[t * 3 + m];
            const bf_fit_stats *st = &s.stats[t * 3 + m];
            size_t j;
            for (j = 0; j < r->type->p || (r->type->p == 0 && j == 0); j++) {
                if (r->type->p > 0 && !r->type->param[j].fitted) {
                    continue;
                }
                cr_assert_eq(atoi(field(text, line, 0, buf, sizeof buf)),
                             r->sample);
                cr_assert_str_eq(field(text, line, 3, buf, sizeof buf),
                                 r->type->name);
                bf_assert_rel(strtod(field(text, line,
                                           column(text, "refined_lse"), buf,
                                           sizeof buf),
                                     NULL),
                              st->refined.lse, 1e-9);
                bf_assert_rel(strtod(field(text, line, column(text, "cv"),
                                           buf, sizeof buf),
                                     NULL),
                              st->cv, 1e-9);
                if (r->type->p > 0) {
                    bf_assert_rel(strtod(field(text, line,
                                               column(text, "ci_high"), buf,
                                               sizeof buf),
                                         NULL),
                                  st->ci_high[j], 1e-9);
                }
                cr_assert_str_eq(field(text, line, column(text, "fit"), buf,
                                       sizeof buf),
                                 "exact");
                line++;
            }
        }
    }
    free(text);
    free_study(&s);
}

/* bf_fits_lines: the structs behind fits.csv, one per line, the values
 * the study's rows and stats hold (not read back from text). */
Test(writers, fits_lines_are_the_lines_of_fits_csv)
{
    study s;
    bf_fits_line lines[16];
    char *text;
    size_t n;
    size_t i;
    run_study(&s);
    text = written(bf_fits_csv_write, &s);
    n = bf_fits_lines(&s.spec, s.rows, s.stats, &s.opts, NULL);
    cr_assert_eq(n, count_lines(text) - 1);
    cr_assert_eq(bf_fits_lines(&s.spec, s.rows, s.stats, &s.opts, lines), n);
    cr_assert_eq(bf_fits_lines(NULL, s.rows, NULL, NULL, NULL), 0);
    for (i = 0; i < n; i++) {
        const bf_fits_line *l = &lines[i];
        const bf_study_row *r = &s.rows[l->row];
        const bf_fit_stats *st = &s.stats[l->row];
        cr_assert_str_eq(l->model, r->type->name);
        cr_assert_str_eq(l->fit, "exact");
        cr_assert(l->analysed);
        cr_assert_eq(l->lse, r->fit.lse);
        cr_assert_eq(l->refined_lse, st->refined.lse);
        cr_assert_eq(l->n_params, (long)st->k);
        cr_assert_eq(l->albedo_over_1, -1); /* diffuse: empty */
        cr_assert(isnan(l->albedo[0]) && l->ndf == NULL);
        if (l->kind == BF_FITS_PARAM) {
            int j = bf_model_param_index(r->type, l->parameter);
            cr_assert(j >= 0 && r->type->param[j].fitted);
            cr_assert_eq(l->value, r->fit.param[j]);
            cr_assert_eq(l->ci_high, st->ci_high[j]);
            cr_assert_eq(l->ml_value, st->ml_param[j]);
            /* the interval is about ml_value: it holds it */
            cr_assert(isfinite(l->ml_value));
            cr_assert(!(l->ci_low > l->ml_value) &&
                      !(l->ci_high < l->ml_value),
                      "%s %s: ml_value %g outside [%g, %g]", l->model,
                      l->parameter, l->ml_value, l->ci_low, l->ci_high);
            cr_assert_not_null(l->ci_method);
            cr_assert(isnan(l->ci_robust)); /* diffuse: no robust factor */
        } else {
            cr_assert_eq(l->kind, BF_FITS_NONE);
            cr_assert_str_eq(r->type->name, "LAMBERT");
            cr_assert(l->parameter == NULL && isnan(l->value));
            cr_assert(l->ci_method == NULL && l->ci_open == -1);
        }
    }
    cr_assert_eq(lines[n - 1].row, 5); /* the last row, LAMBERT on 26 */
    free(text);
    free_study(&s);
}

Test(writers, ranking_csv_has_ranks_best_models_and_parameters)
{
    study s;
    char *text;
    char buf[128];
    size_t rank[6];
    size_t best[2];
    size_t t;
    size_t m;
    run_study(&s);
    text = written(bf_ranking_csv_write, &s);
    cr_assert_eq(count_lines(text), 1 + 2 * 3);
    cr_assert_eq(bf_study_rank(&s.spec, s.stats, BF_CRIT_BIC, rank, best),
                 BF_OK);
    /* two fitted-parameter slots (FC-E and ON fit two) */
    cr_assert_str_eq(field(text, 0, column(text, "p2_boot_high"), buf,
                           sizeof buf),
                     "p2_boot_high");
    for (t = 0; t < 2; t++) {
        for (m = 0; m < 3; m++) {
            size_t line = 1 + t * 3 + m;
            size_t i = t * 3 + m;
            cr_assert_eq((size_t)atoi(field(text, line,
                                             column(text, "rank_bic"), buf,
                                             sizeof buf)),
                         rank[i]);
            cr_assert_eq(atoi(field(text, line, column(text, "best_bic"),
                                    buf, sizeof buf)),
                         best[t] == m);
            if (m == 1) { /* ON: rho in slot 1, with its interval */
                cr_assert_str_eq(field(text, line, column(text, "p1"), buf,
                                       sizeof buf),
                                 "rho");
                bf_assert_rel(strtod(field(text, line,
                                           column(text, "p2_ci_high"), buf,
                                           sizeof buf),
                                     NULL),
                              s.stats[i].ci_high[1], 1e-9);
            }
            if (m == 2) { /* LAMBERT: no parameter, empty slots */
                cr_assert_str_eq(field(text, line, column(text, "p1"), buf,
                                       sizeof buf),
                                 "");
            }
        }
    }
    /* Loofa (26): ON's sigma is 0, so ON is LAMBERT */
    cr_assert_str_eq(field(text, 5, column(text, "counts_as"), buf,
                           sizeof buf),
                     "LAMBERT");
    cr_assert_not_null(strstr(field(text, 5, column(text, "flags"), buf,
                                    sizeof buf),
                              "reduces_to=LAMBERT"));
    free(text);
    free_study(&s);
}

Test(writers, bad_arguments_and_write_errors_are_reported)
{
    study s;
    FILE *full;
    run_study(&s);
    cr_assert_eq(bf_fits_csv_write(NULL, &s.spec, s.rows, NULL, NULL),
                 BF_EINVAL);
    cr_assert_eq(bf_fits_csv_write(stdout, NULL, s.rows, NULL, NULL),
                 BF_EINVAL);
    cr_assert_eq(bf_ranking_csv_write(stdout, &s.spec, s.rows, NULL,
                                      &s.opts),
                 BF_EINVAL, "ranking.csv needs the analysis");
    full = fopen("/dev/full", "w");
    cr_assert_not_null(full);
    cr_assert_eq(bf_fits_csv_write(full, &s.spec, s.rows, s.stats, &s.opts),
                 BF_EIO);
    cr_assert_eq(bf_ranking_csv_write(full, &s.spec, s.rows, s.stats,
                                      &s.opts),
                 BF_EIO);
    fclose(full);
    free_study(&s);
}
