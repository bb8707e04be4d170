/* study_albedo.c: the directional albedo of a study row's fit
 * (bf_study_row.albedo): fits.csv's albedo columns and the report's energy
 * table (issue 17 item 8, doc/methods.md §11), computed once after the fit
 * (bf_study_run, bf_study_analyse) rather than by each reader. */
#include <math.h>

#include "internal.h"

/* The incidences of the albedo, degrees (fits.csv's albedo_0 ... _80). */
static const double albedo_deg[4] = {0.0, 30.0, 60.0, 80.0};

void bf_study_row_albedo(bf_study_row *row)
{
    size_t first;
    const bf_model_type *sp;
    size_t a;
    if (row == NULL) {
        return;
    }
    sp = row->status == BF_OK && row->type != NULL
             ? bf_model_specular_part(row->type, &first)
             : NULL;
    for (a = 0; a < 4; a++) {
        row->albedo[a] = NAN;
        if (sp != NULL &&
            bf_model_albedo(sp, row->fit.param + first,
                            albedo_deg[a] * BF__PI / 180.0,
                            &row->albedo[a]) != BF_OK) {
            row->albedo[a] = NAN;
        }
    }
}

int bf_study_row_albedo_over_1(const bf_study_row *row)
{
    int over = 0;
    size_t a;
    if (row == NULL) {
        return 0;
    }
    for (a = 0; a < 4; a++) {
        over |= row->albedo[a] > 1.0; /* NaN: false */
    }
    return over;
}
