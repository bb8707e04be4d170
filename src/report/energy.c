/* energy.c: the report's energy table (energy.h): the albedo of each
 * specular fit (bf_study_row.albedo, fits.csv's albedo columns) one row
 * per fit. */
#include <stdlib.h>

#include "energy.h"

/* Fills the table's cells of row r (a specular fit). */
static void fill_row(bf_tt *t, const bf_study_spec *spec,
                     const bf_study_row *r, int over)
{
    const bf_target *tg = &spec->targets[r->target];
    const char *name = bf_dataset_name(spec->data, tg->material);
    const char *ch = bf_dataset_channel(spec->data, tg->material,
                                        tg->channel);
    size_t a;
    bf_tt_set(t, 0, "%d", r->sample);
    bf_tt_set(t, 1, "%s", name != NULL ? name : "");
    bf_tt_set(t, 2, "%s", ch != NULL ? ch : "");
    bf_tt_set(t, 3, "%s", r->type->name);
    for (a = 0; a < 4; a++) {
        if (r->albedo[a] == r->albedo[a]) {
            bf_tt_set(t, 4 + a, "%.4f", r->albedo[a]);
        } else {
            bf_tt_set(t, 4 + a, "-");
        }
    }
    bf_tt_set(t, 8, "%s", over ? "OVER 1" : "ok");
}

bf_tt *bf_rep_energy_table(const bf_study_spec *spec,
                           const bf_study_row *rows, size_t *n,
                           size_t *n_over)
{
    static const char *const head[9] = {
        "No.", "Sample", "Channel", "Model", "a(0)", "a(30)", "a(60)",
        "a(80)", "Check"};
    size_t n_rows = spec != NULL && rows != NULL
                        ? spec->n_targets * spec->n_models
                        : 0;
    bf_tt *t = bf_tt_alloc(9);
    size_t i;
    *n = *n_over = 0;
    if (t == NULL) {
        *n = 1;
        return NULL;
    }
    for (i = 0; i < 9; i++) {
        bf_tt_header(t, i, head[i]);
        if (i == 0 || (i >= 4 && i < 8)) {
            bf_tt_right(t, i);
        }
    }
    for (i = 0; i < n_rows; i++) {
        const bf_study_row *r = &rows[i];
        int over;
        if (r->status != BF_OK ||
            bf_model_specular_part(r->type, NULL) == NULL) {
            continue;
        }
        over = bf_study_row_albedo_over_1(r);
        (*n)++;
        *n_over += over;
        if (bf_tt_add_row(t) == 0) {
            fill_row(t, spec, r, over);
        }
    }
    if (*n == 0 || bf_tt_failed(t)) {
        bf_tt_free(t);
        return NULL;
    }
    return t;
}
