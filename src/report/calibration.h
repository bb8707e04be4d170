/* calibration.h: the check of a study's intervals on simulated
 * measurements, in `brdffit report --calibrate N` and `brdffit calibrate`
 * (doc/methods.md §3) -- the run (the library's bf_study_calibrate_all,
 * with a progress line), calibrate.csv (the library's writer), and its
 * table, printed as text or on report.html. The figures are
 * fig_calibration.c's. */
#ifndef BF_REPORT_CALIBRATION_H
#define BF_REPORT_CALIBRATION_H

#include <stdio.h>

#include "study.h"
#include "texttable.h"

/* The options' checks before any work: --calibrate N with 0 < N <
 * BF_CALIBRATE_MIN_SIM (BF_REPORT_BADVALUE), or with --channel joint
 * (BF_REPORT_CONFLICT: a joint fit is not simulated). BF_REPORT_OK or the
 * status after the message. */
int bf_rep_calibrate_check(const char *hint, const bf_report_options *o);

/* With st->opts.calibrate > 0 (after the analysis): simulates
 * st->opts.calibrate measurements of every analysed pair with free
 * parameters (seed st->opts.seed, st->spec.n_threads threads, the
 * progress line "calibrating: simulated measurements refitted", one
 * tick a simulation) into st->cal.
 * BF_REPORT_OK (also when not asked) or a status after the message. */
int bf_rep_study_calibrate(bf_rep_study *st);

/* The table of st->cal: one row per pair and fitted parameter -- sample,
 * model, parameter, the value simulated, the fit's 95% interval, the
 * simulations fitted, their coverage +- its binomial sd, the band of
 * BF_CALIBRATION_BAND, the verdict (low, ok, high), bias / sd, width /
 * spread and the share not identified (bf_calibration_summarise). NULL
 * when out of memory. */
bf_tt *bf_rep_calibration_table(const bf_rep_study *st);

/* Prints what was simulated, the table and what its columns mean to fp.
 * BF_REPORT_OK, or BF_REPORT_SOFTWARE after the message when out of
 * memory. */
int bf_rep_calibration_print(const bf_rep_study *st, FILE *fp);

/* Writes calibrate.csv atomically into the output folder
 * (bf_calibration_csv_write). BF_REPORT_OK or a status after the
 * message. */
int bf_rep_calibration_write(const bf_rep_study *st);

/* The calibration's part of report.html: what was simulated, how to read
 * the table, and the table (id "calibration"). 0, or -2 when the table
 * could not be formed for want of memory. */
int bf_report_calibration(FILE *fp, const bf_rep_study *st);

#endif
