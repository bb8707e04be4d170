/* output.h: what the writers of the library's CSV files share (private;
 * src/output/). */
#ifndef BF_OUTPUT_H
#define BF_OUTPUT_H

#include <stdio.h>

#include "internal.h"

/* Writes text as one CSV field, quoted (RFC 4180, "" for a quote) when it
 * holds a comma, a quote or a line break, starts or ends with a blank, or
 * starts with '#'; the empty text as nothing (an empty field). Every CSV
 * the library writes (fits.csv, ranking.csv, tidy CSV) quotes with it. */
void bf__csv_field(FILE *fp, const char *text);

/* Writes ",x" with %.10g, or "," alone when x is not finite. */
void bf__csv_num(FILE *fp, double x);

/* Writes "sample,name,channel" of target t of spec (no trailing comma). */
void bf__csv_target(FILE *fp, const bf_study_spec *spec, size_t t);
/* The same with the channel field channel (NULL: the target's): a joint
 * fit's shared parameters are on channel "joint" (SPEC §9.4). */
void bf__csv_target_as(FILE *fp, const bf_study_spec *spec, size_t t,
                       const char *channel);

/* The common check of the writers: BF_EINVAL for a NULL fp, spec or rows
 * (or stats when need_stats). */
int bf__csv_check(FILE *fp, const bf_study_spec *spec,
                  const bf_study_row *rows, const bf_fit_stats *stats,
                  int need_stats);

/* Flushes fp: BF_OK, or BF_EIO when it reports a write error. */
int bf__csv_status(FILE *fp);

#endif
