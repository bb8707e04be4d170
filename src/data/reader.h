/* reader.h: the private type of a data format's reader (SPEC §8) and the
 * text scanning its detection shares.
 *
 * Each format's file (src/data/<format>.c) defines, next to its code, one
 * `const bf__reader bf__<format>_reader`; the registry in format.c lists
 * them, one line each, and bf_format_name, bf_format_find,
 * bf_format_detect and bf_dataset_load are loops over it. A reader's
 * bf_format value is its position in that registry (brdffit.h). */
#ifndef BF_DATA_READER_H
#define BF_DATA_READER_H

#include <stddef.h>
#include <stdio.h>

#include "internal.h"

/* Bytes of a file that detection reads and hands to every detect. */
#define BF__DETECT_MAX 65536

/* Detection asks the readers by increasing rank (ties: registry order):
 * the strongest evidence first, the loosest guess last. */
enum {
    BF__RANK_MAGIC = 10,   /* fixed leading bytes (MERL's dimensions) */
    BF__RANK_HEADER = 20,  /* a header line naming columns (tidy CSV) */
    BF__RANK_KEYWORD = 30, /* header keywords (ASTM's NUM_POINTS, VARS) */
    BF__RANK_GUESS = 40    /* a plausible first number (pbrt's count) */
};

typedef struct bf__reader {
    const char *name;           /* bf_format_name: "pbrt" */
    const char *const *aliases; /* NULL-ended other names for
                                   bf_format_find, or NULL */
    /* How messages name the format: "tidy CSV", "MERL". */
    const char *title;
    /* A folder format: the file its folder holds ("table.txt"); detect is
     * then NULL and a folder is read by it when nothing else claims it.
     * NULL for a file format. */
    const char *folder_file;
    /* A file format: 1 when buf[0..n) -- the file's first bytes, 1 <= n <=
     * BF__DETECT_MAX -- is this format. Never called on a buffer holding a
     * NUL byte unless binary is 1. */
    int (*detect)(const char *buf, size_t n);
    int binary; /* 1: a binary format, asked before the NUL check */
    int rank;   /* BF__RANK_* */
    /* Why a file is not this format, in bf_format_detect's message. A text
     * format: "not pbrt (no wavelength count first)" (the "no format
     * recognised: ..." list names the text formats by name order, then
     * "not <title>" for each binary one); a binary format: what a binary
     * file is not, "a MERL table (it does not ...)". NULL for a folder
     * format. */
    const char *miss;
    /* Reads path into a new dataset (opts may be NULL); as bf_dataset_load.
     * NULL for a file format that needs no options: read is used. */
    int (*load)(const char *path, const bf_load_opts *opts, bf_dataset **out,
                bf_error *err);
    /* Reads a dataset from the open file fp (named name), for a reader
     * without load: bf_dataset_load opens the file (bf__load_dataset). */
    int (*read)(FILE *fp, const char *name, bf_dataset **out, bf_error *err);
} bf__reader;

/* The registry (format.c): the reader of format f, NULL for one without a
 * reader (auto, memory) or an unknown value. */
const bf__reader *bf__reader_of(bf_format f);

/* The bf_format of a registered reader (its registry position). A reader
 * stamps its datasets' materials with it (bf_material_desc.format). */
bf_format bf__reader_format(const bf__reader *r);

/* Number of bf_format values: every value below it has a name. */
size_t bf__format_count(void);

/* ==== text scanning for detect (detect.c) ==== */

/* The next line of text[0..n) from *pos: *line and *len (trailing CR,
 * blanks and tabs left out). 0 at the end. */
int bf__detect_line(const char *text, size_t n, size_t *pos,
                    const char **line, size_t *len);

/* The next line of text[0..n) from *pos that is neither blank nor a '#'
 * comment, its leading blanks left out; *pos starts past a UTF-8 byte
 * order mark (lineio.c) when it is 0. 0 at the end. */
int bf__detect_content_line(const char *text, size_t n, size_t *pos,
                            const char **line, size_t *len);

#endif
