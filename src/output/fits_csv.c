/* fits_csv.c: fits.csv -- every fitted parameter of every (target, model)
 * of a study, with the analysis beyond the paper when it was run (README
 * "Output files", doc/methods.md). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "output/output.h"

#define SCALE_ROW (SIZE_MAX - 1)

/* Line l of row r for parameter j (SIZE_MAX: a model with no fitted
 * parameter; SCALE_ROW: the free scale, refined value only), with its
 * analysis columns (s: NULL or not done, empty) and its specular columns
 * (r->albedo, bf_study_row_albedo; empty for a diffuse model). */
static void fill_line(bf_fits_line *l, size_t i, const bf_study_row *r,
                      const bf_fit_stats *s, const bf_analysis_opts *opts,
                      size_t j)
{
    int has = j < BF_MAX_PARAMS;
    size_t first;
    const bf_model_type *sp = bf_model_specular_part(r->type, &first);
    size_t a;
    memset(l, 0, sizeof *l);
    l->row = i;
    l->kind = has ? BF_FITS_PARAM
                  : j == SCALE_ROW ? BF_FITS_SCALE : BF_FITS_NONE;
    l->model = r->type->name;
    l->parameter = has ? r->type->param[j].name
                       : j == SCALE_ROW ? "rho_d" : NULL;
    l->unit = has ? r->type->param[j].unit : j == SCALE_ROW ? "1" : NULL;
    l->value = has ? r->fit.param[j]
                   : j == SCALE_ROW && s != NULL ? s->scale : NAN;
    l->lse = r->fit.lse;
    l->bound_hit = has ? (r->fit.bound_hit & (1u << j)) != 0
                       : j == SCALE_ROW && s != NULL && s->scale == 0.0;
    l->k = r->k;
    l->objective =
        bf_objective_name(opts != NULL ? opts->objective : BF_OBJ_MAX);
    l->fit = opts != NULL && opts->exact ? "exact" : "paper";
    l->analysed = s != NULL && s->done;
    l->grid_value = l->grid_lse = l->refined_value = l->refined_lse = NAN;
    l->ci_low = l->ci_high = l->boot_low = l->boot_high = NAN;
    l->ml_value = NAN;
    l->ci_robust = NAN;
    l->ci_gap_low = l->ci_gap_high = NAN;
    l->aic = l->bic = l->cv = NAN;
    l->ci_open = -1;
    l->n_params = -1;
    if (l->analysed) {
        l->grid_value = has ? s->grid.param[j] : NAN;
        l->grid_lse = s->grid.lse;
        l->refined_value = has ? s->refined.param[j]
                               : j == SCALE_ROW ? s->scale : NAN;
        l->refined_lse = s->refined.lse;
        l->ci_low = has ? s->ci_low[j] : NAN;
        l->ci_high = has ? s->ci_high[j] : NAN;
        l->ml_value = has ? s->ml_param[j] : NAN;
        l->ci_method = has ? bf_ci_method_name(bf_fit_stats_ci_method(s, j))
                           : NULL;
        l->ci_open = has && s->ci_method != BF_CI_NONE
                         ? (int)((s->ci_open >> (2 * j)) & 3u)
                         : -1; /* no interval: --intervals none */
        l->ci_robust = has ? s->ci_robust[j] : NAN;
        l->ci_gap_low = has ? s->ci_gap_low[j] : NAN;
        l->ci_gap_high = has ? s->ci_gap_high[j] : NAN;
        l->boot_low = has ? s->boot_low[j] : NAN;
        l->boot_high = has ? s->boot_high[j] : NAN;
        l->n_params = (long)s->k;
        l->aic = s->aic;
        l->bic = s->bic;
        l->cv = s->cv;
        bf_fit_flags_format(r->type, s, l->flags, sizeof l->flags);
    }
    l->albedo_over_1 = -1;
    for (a = 0; a < 4; a++) {
        l->albedo[a] = sp != NULL ? r->albedo[a] : NAN;
    }
    if (sp != NULL) {
        l->ndf = sp->ndf != NULL ? sp->ndf : "";
        l->masking = sp->masking != NULL ? sp->masking : "";
        l->fresnel = sp->fresnel_term != NULL ? sp->fresnel_term : "";
        l->albedo_over_1 = bf_study_row_albedo_over_1(r);
    }
}

/* 1 when target t is a joint fit's (SPEC §9.4) first channel: its rows
 * carry the shared shape parameters. */
static int joint_first(const bf_study_spec *spec, size_t t)
{
    const bf_target *tg = &spec->targets[t];
    return tg->joint && (t == 0 || !tg[-1].joint ||
                         tg[-1].material != tg->material);
}

size_t bf_fits_lines(const bf_study_spec *spec, const bf_study_row *rows,
                     const bf_fit_stats *stats, const bf_analysis_opts *opts,
                     bf_fits_line *out)
{
    size_t n = 0;
    size_t i;
    if (spec == NULL || rows == NULL) {
        return 0;
    }
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
        const bf_study_row *r = &rows[i];
        const bf_fit_stats *s = stats != NULL ? &stats[i] : NULL;
        size_t j;
        size_t before = n;
        if (r->status != BF_OK) {
            continue;
        }
        if (s != NULL && s->done && bf_objective_keeps_scale(s->objective)
            && r->type->kind != BF_MODEL_SPECULAR) {
            /* SPEC §9.4: rho_d, a parameter of the fit (a specular
             * model's scales are its own parameters) */
            if (out != NULL) {
                fill_line(&out[n], i, r, s, opts, SCALE_ROW);
            }
            n++;
        }
        for (j = 0; j < r->type->p; j++) {
            /* a joint fit (SPEC §9.4): its shape once, on channel
             * "joint" at its first channel's row; the scales per channel */
            int joint = spec->targets[r->target].joint &&
                        !r->type->param[j].linear;
            if (r->type->param[j].fitted &&
                (!joint || joint_first(spec, r->target))) {
                if (out != NULL) {
                    fill_line(&out[n], i, r, s, opts, j);
                    out[n].joint = joint;
                }
                n++;
            }
        }
        if (n == before) {
            if (out != NULL) {
                fill_line(&out[n], i, r, s, opts, SIZE_MAX);
            }
            n++;
        }
    }
    return n;
}

/* Writes an integer field, or an empty one for a negative value. */
static void csv_int(FILE *fp, long v)
{
    if (v >= 0) {
        fprintf(fp, ",%ld", v);
    } else {
        fputc(',', fp);
    }
}

/* Writes text as a field after a comma (NULL: empty). */
static void csv_text(FILE *fp, const char *text)
{
    fputc(',', fp);
    bf__csv_field(fp, text != NULL ? text : "");
}

/* Writes line l of fits.csv. */
static void write_line(FILE *fp, const bf_study_spec *spec,
                       const bf_study_row *rows, const bf_fits_line *l)
{
    size_t a;
    bf__csv_target_as(fp, spec, rows[l->row].target,
                      l->joint ? "joint" : NULL);
    csv_text(fp, l->model);
    csv_text(fp, l->parameter);
    csv_text(fp, l->unit);
    if (l->kind == BF_FITS_PARAM) {
        fprintf(fp, ",%.10g", l->value);
    } else {
        bf__csv_num(fp, l->value);
    }
    fprintf(fp, ",%.10g,%d,%zu,%s,%s", l->lse, l->bound_hit, l->k,
            l->objective, l->fit);
    if (!l->analysed) {
        fputs(",,,,,,,,,,,,,,,,,,,", fp);
    } else {
        bf__csv_num(fp, l->grid_value);
        bf__csv_num(fp, l->grid_lse);
        bf__csv_num(fp, l->refined_value);
        bf__csv_num(fp, l->refined_lse);
        bf__csv_num(fp, l->ci_low);
        bf__csv_num(fp, l->ci_high);
        bf__csv_num(fp, l->ml_value);
        fprintf(fp, ",%s", l->ci_method != NULL ? l->ci_method : "");
        csv_int(fp, l->ci_open);
        bf__csv_num(fp, l->ci_robust);
        bf__csv_num(fp, l->ci_gap_low);
        bf__csv_num(fp, l->ci_gap_high);
        bf__csv_num(fp, l->boot_low);
        bf__csv_num(fp, l->boot_high);
        csv_int(fp, l->n_params);
        bf__csv_num(fp, l->aic);
        bf__csv_num(fp, l->bic);
        bf__csv_num(fp, l->cv);
        csv_text(fp, l->flags);
    }
    if (l->albedo_over_1 < 0) {
        fputs(",,,,,,,,", fp);
    } else {
        csv_text(fp, l->ndf);
        csv_text(fp, l->masking);
        csv_text(fp, l->fresnel);
        for (a = 0; a < 4; a++) {
            bf__csv_num(fp, l->albedo[a]);
        }
        fprintf(fp, ",%d", l->albedo_over_1);
    }
    fputc('\n', fp);
}

int bf_fits_csv_write(FILE *fp, const bf_study_spec *spec,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      const bf_analysis_opts *opts)
{
    size_t i;
    size_t n;
    bf_fits_line *lines;
    int rc = bf__csv_check(fp, spec, rows, stats, 0);
    if (rc != BF_OK) {
        return rc;
    }
    n = bf_fits_lines(spec, rows, stats, opts, NULL);
    lines = malloc((n + 1) * sizeof *lines);
    if (lines == NULL) {
        return BF_ENOMEM;
    }
    (void)bf_fits_lines(spec, rows, stats, opts, lines);
    fputs("sample,name,channel,model,parameter,unit,value,lse,bound_hit,k,"
          "objective,fit,grid_value,grid_lse,refined_value,refined_lse,"
          "ci_low,ci_high,ml_value,ci_method,ci_open,ci_robust,ci_gap_low,"
          "ci_gap_high,boot_low,boot_high,n_params,aic,bic,cv,flags,ndf,masking,fresnel,"
          "albedo_0,albedo_30,albedo_60,albedo_80,albedo_over_1\n",
          fp);
    for (i = 0; i < n; i++) {
        write_line(fp, spec, rows, &lines[i]);
    }
    free(lines);
    return bf__csv_status(fp);
}
