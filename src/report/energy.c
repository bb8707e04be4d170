/* energy.c: the report's energy table (energy.h): fits.csv's albedo
 * columns (bf_fits_lines, bf_model_albedo) one row per specular fit. */
#include <stdint.h>
#include <stdlib.h>

#include "energy.h"

/* Fills the table's cells of line l. */
static void fill_row(bf_tt *t, const bf_study_spec *spec,
                     const bf_study_row *r, const bf_fits_line *l)
{
    const bf_target *tg = &spec->targets[r->target];
    const char *name = bf_dataset_name(spec->data, tg->material);
    const char *ch = bf_dataset_channel(spec->data, tg->material,
                                        tg->channel);
    size_t a;
    bf_tt_set(t, 0, "%d", r->sample);
    bf_tt_set(t, 1, "%s", name != NULL ? name : "");
    bf_tt_set(t, 2, "%s", ch != NULL ? ch : "");
    bf_tt_set(t, 3, "%s", l->model);
    for (a = 0; a < 4; a++) {
        if (l->albedo[a] == l->albedo[a]) {
            bf_tt_set(t, 4 + a, "%.4f", l->albedo[a]);
        } else {
            bf_tt_set(t, 4 + a, "-");
        }
    }
    bf_tt_set(t, 8, "%s", l->albedo_over_1 > 0 ? "OVER 1" : "ok");
}

bf_tt *bf_rep_energy_table(const bf_study_spec *spec,
                           const bf_study_row *rows, size_t *n,
                           size_t *n_over)
{
    static const char *const head[9] = {
        "No.", "Sample", "Channel", "Model", "a(0)", "a(30)", "a(60)",
        "a(80)", "Check"};
    size_t nl = bf_fits_lines(spec, rows, NULL, NULL, NULL);
    bf_fits_line *lines = malloc((nl + 1) * sizeof *lines);
    bf_tt *t = bf_tt_alloc(9);
    size_t prev = SIZE_MAX;
    size_t i;
    *n = *n_over = 0;
    if (lines == NULL || t == NULL) {
        free(lines);
        bf_tt_free(t);
        *n = 1;
        return NULL;
    }
    (void)bf_fits_lines(spec, rows, NULL, NULL, lines);
    for (i = 0; i < 9; i++) {
        bf_tt_header(t, i, head[i]);
        if (i == 0 || (i >= 4 && i < 8)) {
            bf_tt_right(t, i);
        }
    }
    for (i = 0; i < nl; i++) { /* a row's first line carries its albedo */
        const bf_fits_line *l = &lines[i];
        if (l->row == prev || l->albedo_over_1 < 0) {
            continue;
        }
        prev = l->row;
        (*n)++;
        *n_over += l->albedo_over_1 > 0;
        if (bf_tt_add_row(t) == 0) {
            fill_row(t, spec, &rows[l->row], l);
        }
    }
    free(lines);
    if (*n == 0 || bf_tt_failed(t)) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}
