/* dispersion_csv.c: dispersion.csv -- n against wavelength, with its
 * interval, for every fit that gives one (bf_dispersion_points; README
 * "Output files", doc/methods.md "Dispersion"). */
#include <stdlib.h>

#include "output/output.h"

int bf_dispersion_csv_write(FILE *fp, const bf_study_spec *spec,
                            const bf_study_row *rows,
                            const bf_fit_stats *stats)
{
    size_t i;
    size_t n;
    bf_dispersion_point *pt;
    int rc = bf__csv_check(fp, spec, rows, stats, 0);
    if (rc != BF_OK) {
        return rc;
    }
    n = bf_dispersion_points(spec, rows, stats, NULL);
    pt = malloc((n + 1) * sizeof *pt);
    if (pt == NULL) {
        return BF_ENOMEM;
    }
    (void)bf_dispersion_points(spec, rows, stats, pt);
    fputs("sample,name,channel,model,wavelength_nm,n,ci_low,ci_high,n_ml\n",
          fp);
    for (i = 0; i < n; i++) {
        bf__csv_target_as(fp, spec, rows[pt[i].row].target,
                          pt[i].joint ? "joint" : NULL);
        fputc(',', fp);
        bf__csv_field(fp, pt[i].model);
        bf__csv_num(fp, pt[i].wavelength);
        fprintf(fp, ",%.10g", pt[i].n);
        bf__csv_num(fp, pt[i].ci_low);
        bf__csv_num(fp, pt[i].ci_high);
        bf__csv_num(fp, pt[i].n_ml);
        fputc('\n', fp);
    }
    free(pt);
    return bf__csv_status(fp);
}
