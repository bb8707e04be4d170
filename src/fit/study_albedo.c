/* study_albedo.c: the directional albedo of a study row's fit
 * (bf_study_row.albedo): fits.csv's albedo columns and the report's energy
 * table (issue 17 item 8, doc/methods.md §11), computed once after the fit
 * (bf_study_run, bf_study_analyse) rather than by each reader; the study's
 * rows on its threads (bf__study_rows_albedo: a sharp lobe's quadratures
 * take tens of milliseconds each). */
#include <math.h>

#include "internal.h"

/* The incidences of the albedo, degrees (fits.csv's albedo_0 ... _80). */
static const double albedo_deg[4] = {0.0, 30.0, 60.0, 80.0};

/* row->albedo[a]: NaN for a diffuse model, a failed row or quadrature. */
static void row_albedo_at(bf_study_row *row, size_t a)
{
    size_t first;
    const bf_model_type *sp =
        row->status == BF_OK && row->type != NULL
            ? bf_model_specular_part(row->type, &first)
            : NULL;
    row->albedo[a] = NAN;
    if (sp != NULL && bf_model_albedo(sp, row->fit.param + first,
                                      albedo_deg[a] * BF__PI / 180.0,
                                      &row->albedo[a]) != BF_OK) {
        row->albedo[a] = NAN;
    }
}

void bf_study_row_albedo(bf_study_row *row)
{
    size_t a;
    if (row == NULL) {
        return;
    }
    for (a = 0; a < 4; a++) {
        row_albedo_at(row, a);
    }
}

void bf__study_rows_albedo(bf_study_row *rows, size_t n, int n_threads)
{
    long q;
    n_threads = n_threads > 1 ? n_threads : 1;
    /* one quadrature per iteration: each writes its own double, so the
     * values do not depend on the thread count */
#pragma omp parallel for schedule(dynamic, 1) num_threads(n_threads)      \
    if (n_threads > 1)
    for (q = 0; q < (long)(4 * n); q++) {
        row_albedo_at(&rows[q / 4], (size_t)q % 4);
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
