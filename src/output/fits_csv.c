/* fits_csv.c: fits.csv -- every fitted parameter of every (target, model)
 * of a study, with the analysis beyond the paper when it was run (README
 * "Output files", doc/methods.md). */
#include <math.h>
#include <stdint.h>

#include "output/output.h"

/* j of the row of the free scale rho_d (SPEC §9.4). */
#define SCALE_ROW (SIZE_MAX - 1)

/* The analysis columns of row i and parameter j (SIZE_MAX: a model with
 * no fitted parameter; SCALE_ROW: the free scale, refined value only). */
static void analysis_cols(FILE *fp, const bf_study_row *r,
                          const bf_fit_stats *s, const bf_analysis_opts *opts,
                          size_t j)
{
    int has = j < BF_MAX_PARAMS;
    char flags[512];
    fprintf(fp, ",%s,%s",
            bf_objective_name(opts != NULL ? opts->objective : BF_OBJ_MAX),
            opts != NULL && opts->exact ? "exact" : "paper");
    if (s == NULL || !s->done) {
        fputs(",,,,,,,,,,,,,,,", fp);
        return;
    }
    bf__csv_num(fp, has ? s->grid.param[j] : NAN);
    bf__csv_num(fp, s->grid.lse);
    bf__csv_num(fp, has ? s->refined.param[j]
                        : j == SCALE_ROW ? s->scale : NAN);
    bf__csv_num(fp, s->refined.lse);
    bf__csv_num(fp, has ? s->ci_low[j] : NAN);
    bf__csv_num(fp, has ? s->ci_high[j] : NAN);
    fprintf(fp, ",%s", has ? bf_ci_method_name(s->ci_method) : "");
    if (has) {
        fprintf(fp, ",%u", (s->ci_open >> (2 * j)) & 3u);
    } else {
        fputc(',', fp);
    }
    bf__csv_num(fp, has ? s->boot_low[j] : NAN);
    bf__csv_num(fp, has ? s->boot_high[j] : NAN);
    fprintf(fp, ",%zu", s->k);
    bf__csv_num(fp, s->aic);
    bf__csv_num(fp, s->bic);
    bf__csv_num(fp, s->cv);
    bf_fit_flags_format(r->type, s, flags, sizeof flags);
    fputc(',', fp);
    bf__csv_field(fp, flags);
}

/* The incidences of the energy columns (issue 17 item 8), degrees. */
static const double albedo_deg[4] = {0.0, 30.0, 60.0, 80.0};

/* The specular columns of row r (empty for a diffuse model): the NDF,
 * masking and Fresnel term of its specular part (SPEC §9.2: every output
 * names them), and that part's directional albedo at the fitted
 * parameters (bf_model_albedo) at the incidences above, with 1 where one
 * exceeds 1 (the white-furnace check). */
static void specular_cols(FILE *fp, const bf_study_row *r,
                          const double *albedo)
{
    size_t first;
    const bf_model_type *sp = bf_model_specular_part(r->type, &first);
    size_t a;
    int over = 0;
    if (sp == NULL) {
        fputs(",,,,,,,,", fp);
        return;
    }
    fputc(',', fp);
    bf__csv_field(fp, sp->ndf != NULL ? sp->ndf : "");
    fputc(',', fp);
    bf__csv_field(fp, sp->masking != NULL ? sp->masking : "");
    fputc(',', fp);
    bf__csv_field(fp, sp->fresnel_term != NULL ? sp->fresnel_term : "");
    for (a = 0; a < 4; a++) {
        bf__csv_num(fp, albedo[a]);
        over |= albedo[a] > 1.0;
    }
    fprintf(fp, ",%d", over);
}

/* The albedos of specular_cols for row r (NaN where the quadrature fails
 * or the model is diffuse). */
static void row_albedo(const bf_study_row *r, double *albedo)
{
    size_t first;
    const bf_model_type *sp = bf_model_specular_part(r->type, &first);
    size_t a;
    for (a = 0; a < 4; a++) {
        albedo[a] = NAN;
        if (sp != NULL &&
            bf_model_albedo(sp, r->fit.param + first,
                            albedo_deg[a] * 3.14159265358979323846 / 180.0,
                            &albedo[a]) != BF_OK) {
            albedo[a] = NAN;
        }
    }
}

int bf_fits_csv_write(FILE *fp, const bf_study_spec *spec,
                      const bf_study_row *rows, const bf_fit_stats *stats,
                      const bf_analysis_opts *opts)
{
    size_t i;
    int rc = bf__csv_check(fp, spec, rows, stats, 0);
    if (rc != BF_OK) {
        return rc;
    }
    fputs("sample,name,channel,model,parameter,unit,value,lse,bound_hit,k,"
          "objective,fit,grid_value,grid_lse,refined_value,refined_lse,"
          "ci_low,ci_high,ci_method,ci_open,boot_low,boot_high,n_params,aic,"
          "bic,cv,flags,ndf,masking,fresnel,albedo_0,albedo_30,albedo_60,"
          "albedo_80,albedo_over_1\n",
          fp);
    for (i = 0; i < spec->n_targets * spec->n_models; i++) {
        const bf_study_row *r = &rows[i];
        const bf_fit_stats *s = stats != NULL ? &stats[i] : NULL;
        size_t j;
        int any = 0;
        double albedo[4];
        if (r->status != BF_OK) {
            continue;
        }
        row_albedo(r, albedo);
        if (s != NULL && s->done && bf_objective_keeps_scale(s->objective)
            && r->type->kind != BF_MODEL_SPECULAR) {
            /* SPEC §9.4: rho_d, a parameter of the fit (a specular
             * model's scales are its own parameters) */
            any = 1;
            bf__csv_target(fp, spec, r->target);
            fputc(',', fp);
            bf__csv_field(fp, r->type->name);
            fputs(",rho_d,1", fp);
            bf__csv_num(fp, s->scale);
            fprintf(fp, ",%.10g,%d,%zu", r->fit.lse, s->scale == 0.0,
                    r->k);
            analysis_cols(fp, r, s, opts, SCALE_ROW);
            specular_cols(fp, r, albedo);
            fputc('\n', fp);
        }
        for (j = 0; j < r->type->p; j++) {
            if (!r->type->param[j].fitted) {
                continue;
            }
            any = 1;
            bf__csv_target(fp, spec, r->target);
            fputc(',', fp);
            bf__csv_field(fp, r->type->name);
            fprintf(fp, ",%s,%s,%.10g,%.10g,%d,%zu", r->type->param[j].name,
                    r->type->param[j].unit, r->fit.param[j], r->fit.lse,
                    (r->fit.bound_hit & (1u << j)) ? 1 : 0, r->k);
            analysis_cols(fp, r, s, opts, j);
            specular_cols(fp, r, albedo);
            fputc('\n', fp);
        }
        if (!any) {
            bf__csv_target(fp, spec, r->target);
            fputc(',', fp);
            bf__csv_field(fp, r->type->name);
            fprintf(fp, ",,,,%.10g,0,%zu", r->fit.lse, r->k);
            analysis_cols(fp, r, s, opts, SIZE_MAX);
            specular_cols(fp, r, albedo);
            fputc('\n', fp);
        }
    }
    return bf__csv_status(fp);
}
