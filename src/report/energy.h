/* energy.h: the report's energy table (issue 17 item 8) -- the
 * directional albedo of every fitted specular model at theta_i = 0, 30,
 * 60 and 80 degrees (bf_study_row.albedo, fits.csv's albedo columns),
 * flagged "OVER 1" where it exceeds 1 (the white-furnace check). Printed
 * after Table 3 and shown on the page. Private to src/report. */
#ifndef BF_REPORT_ENERGY_H
#define BF_REPORT_ENERGY_H

#include "brdffit.h"
#include "texttable.h"

/* The energy table of a study's rows (spec, rows as bf_fits_lines takes
 * them, their albedo filled by bf_study_row_albedo): one row per fit of
 * a specular model or composite, columns No., Sample, Channel, Model,
 * albedo at 0, 30, 60, 80 degrees (4 decimals, "-" where the quadrature
 * failed) and Check ("OVER 1" or "ok"). NULL when no row is specular
 * (*n = 0) or out of memory (*n > 0); *n the number of specular fits,
 * *n_over those flagged. */
bf_tt *bf_rep_energy_table(const bf_study_spec *spec,
                           const bf_study_row *rows, size_t *n,
                           size_t *n_over);

/* The table's title line (for the terminal and the page). */
#define BF_REP_ENERGY_TITLE                                                   \
    "Energy: directional albedo of each specular fit at theta_i = 0, 30, "  \
    "60, 80 deg (white furnace: OVER 1 where it exceeds 1)"

#endif
