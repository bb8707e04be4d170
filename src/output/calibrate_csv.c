/* calibrate_csv.c: calibrate.csv -- what simulated measurements of each
 * fitted pair say about its intervals (bf_study_calibrate; README "Output
 * files", doc/methods.md §3). */
#include <math.h>

#include "output/output.h"

int bf_calibration_csv_write(FILE *fp, const bf_study_spec *spec,
                             const bf_study_row *rows,
                             const bf_fit_stats *stats,
                             const bf_analysis_opts *opts,
                             const size_t *pairs, size_t n_pairs,
                             const bf_calibration *cal)
{
    size_t i;
    int rc = bf__csv_check(fp, spec, rows, stats, 0);
    if (rc != BF_OK || opts == NULL || (n_pairs > 0 &&
                                        (pairs == NULL || cal == NULL))) {
        return rc != BF_OK ? rc : BF_EINVAL;
    }
    fputs("sample,name,channel,model,parameter,value,objective,noise_power,"
          "noise_sd,n_sim,coverage,bias,sd,ml_bias,ml_sd,width,level,"
          "not_identified,boot_coverage,boot_width,f_coverage,f_width,"
          "competing\n",
          fp);
    for (i = 0; i < n_pairs; i++) {
        const bf_study_row *r = &rows[pairs[i]];
        const bf_fit_stats *s = &stats[pairs[i]];
        const bf_calibration *c = &cal[i];
        size_t j;
        for (j = 0; j < r->type->p; j++) {
            if (!((s->free_mask >> j) & 1u)) {
                continue;
            }
            bf__csv_target(fp, spec, r->target);
            fputc(',', fp);
            bf__csv_field(fp, r->type->name);
            fprintf(fp, ",%s", r->type->param[j].name);
            bf__csv_num(fp, c->truth[j]);
            fprintf(fp, ",%s", bf_objective_name(opts->objective));
            bf__csv_num(fp, s->noise_power);
            bf__csv_num(fp, s->noise_sigma);
            fprintf(fp, ",%zu", c->n_sim);
            bf__csv_num(fp, c->coverage[j]);
            bf__csv_num(fp, c->bias[j]);
            bf__csv_num(fp, c->sd[j]);
            bf__csv_num(fp, c->ml_bias[j]);
            bf__csv_num(fp, c->ml_sd[j]);
            bf__csv_num(fp, c->width[j]);
            bf__csv_num(fp, opts->level);
            bf__csv_num(fp, c->not_identified[j]);
            bf__csv_num(fp, c->boot_coverage[j]);
            bf__csv_num(fp, c->boot_width[j]);
            bf__csv_num(fp, c->f_coverage[j]);
            bf__csv_num(fp, c->f_width[j]);
            bf__csv_num(fp, c->competing[j]);
            fputc('\n', fp);
        }
    }
    return bf__csv_status(fp);
}
