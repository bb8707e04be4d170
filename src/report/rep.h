/* rep.h: what the report library's files share -- its messages (a sink
 * the caller sets: the CLI prints, bf_report_write keeps the error for
 * its bf_error), the atomic output files and folders, and the parsers of
 * the option lists a study takes ("1,5-9", NAME=LO:HI). Private to
 * src/report and the CLI. */
#ifndef BF_REPORT_REP_H
#define BF_REPORT_REP_H

#include <stdio.h>

#include "brdffit.h"

/* Upper limit of threads (a typo guard, not a machine limit). */
#define BF_REPORT_MAX_THREADS 1024

/* Where messages go, for the calling thread: fn (NULL: nowhere). The
 * first error since bf_rep_clear is also kept (bf_rep_last). */
void bf_rep_set_sink(bf_report_message_fn fn, void *ctx);
void bf_rep_get_sink(bf_report_message_fn *fn, void **ctx);
void bf_rep_clear(void);
/* The first error since bf_rep_clear ("" when none). */
const char *bf_rep_last(void);

/* An error message (printf format). */
void bf_rep_err(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* A note: not an error (a model left out for want of inputs). */
void bf_rep_note(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* An option's error (status BF_REPORT_CONFLICT or _BADVALUE, returned);
 * cmd ("compare ") is for the CLI's hint and otherwise unused. */
int bf_rep_usage_fail(int status, const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A library writer's failure (code, a BF_E* code) on output file name:
 * "name could not be written: out of memory" for BF_ENOMEM, else an
 * internal error; returns BF_REPORT_SOFTWARE. */
int bf_rep_write_error(const char *name, int code);

/* Parses a list "1,5,7-9" of positive integers into a new array (caller
 * frees). Returns 0 on success, -1 with a message in msg otherwise (-2
 * with "out of memory": not the user's mistake). */
int bf_rep_parse_int_list(const char *s, int **out, size_t *n, char *msg,
                          size_t msglen);
/* Parses a finite double; returns 0 on success. */
int bf_rep_parse_double(const char *s, double *out);
/* Parses --range NAME=LO:HI. Returns 0, or -1 with a message in msg. */
int bf_rep_parse_range(const char *s, char *name, size_t name_len,
                       double *lo, double *hi, char *msg, size_t msg_len);

/* The label of material m: "16 Leather" (number, name), or "16". */
void bf_rep_material_label(const bf_dataset *ds, size_t m, char *buf,
                           size_t len);

/* An output file written atomically: data go to a temporary file in the
 * same folder, renamed over the final path by bf_out_commit. */
typedef struct {
    FILE *fp;
    char path[4096];
    char tmp[4096];
} bf_out;

/* Checks, before any work, that folder dir exists and is writable, or that
 * it can be created (tried with mkdir and removed again: permission bits do
 * not stop root). Leaves nothing behind. Returns 0 or BF_REPORT_CANTCREAT
 * after the message. */
int bf_rep_check_outdir(const char *dir);
/* Creates folder dir if missing (one level). Returns 0 or a status after
 * the message. */
int bf_rep_make_outdir(const char *dir);
/* Opens dir/name for atomic writing. Returns 0 or a status. */
int bf_out_open(bf_out *o, const char *dir, const char *name);
/* Flushes, closes and renames into place. Returns 0 or a status; on
 * failure the temporary file is removed and no output is left. */
int bf_out_commit(bf_out *o);
/* Abandons the file: closes and removes the temporary. */
void bf_out_abort(bf_out *o);

#endif
