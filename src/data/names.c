/* names.c: sample names from samples.tsv, tab-separated rows
 * "sample<TAB>name[<TAB>flag]" after an optional header line.
 *
 * Names may contain spaces and parentheses ("Polyester (zoomed view of 2)"),
 * so fields are split at tabs only and spaces around each field are trimmed.
 * The first line is a header when its first field is not an integer. The
 * flag (CURET's in_ragheb_hancock_24 column) must be 0 or 1 when present.
 * Sample numbers are positive and unique; gaps are allowed (a partial list). */
#include "data/curet.h"
#include "internal.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int sample;
    char *name;
    long line;
} entry;

struct bf_names {
    size_t n;     /* number of entries */
    entry *entry; /* n entries in file order */
};

/* Index of sample s in nm, or -1. */
static long find(const bf_names *nm, int sample)
{
    size_t k;
    for (k = 0; k < nm->n; k++) {
        if (nm->entry[k].sample == sample) {
            return (long)k;
        }
    }
    return -1;
}

/* Parses the current line of r into nm. */
static int add_row(bf_names *nm, size_t *cap, const bf__lines *r,
                   bf_error *err)
{
    long sample = 0;
    long flag = 0;
    long dup;
    size_t len;
    char *name;
    int rc;
    if ((r->nfield < 2) || (r->nfield > 3)) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "expected 2 or 3 tab-separated fields (sample, "
                             "name, flag), found %zu",
                             r->nfield);
    }
    rc = bf__field_long(r, 0, "sample", 1, INT_MAX, &sample, err);
    if (rc != BF_OK) {
        return rc;
    }
    if (r->field[1][0] == '\0') {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "field 2 (name) is empty");
    }
    if (r->nfield == 3) {
        rc = bf__field_long(r, 2, "flag", 0, 1, &flag, err);
        if (rc != BF_OK) {
            return rc;
        }
    }
    dup = find(nm, (int)sample);
    if (dup >= 0) {
        return bf__error_set(err, BF_EPARSE, r->line,
                             "sample %ld appears twice, first at line %ld",
                             sample, nm->entry[dup].line);
    }
    if (nm->n == *cap) {
        size_t c = (*cap == 0) ? 64 : 2 * (*cap);
        entry *e = realloc(nm->entry, c * sizeof *e);
        if (e == NULL) {
            return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
        }
        nm->entry = e;
        *cap = c;
    }
    len = strlen(r->field[1]);
    name = malloc(len + 1);
    if (name == NULL) {
        return bf__error_set(err, BF_ENOMEM, r->line, "out of memory");
    }
    memcpy(name, r->field[1], len + 1);
    nm->entry[nm->n].sample = (int)sample;
    nm->entry[nm->n].name = name;
    nm->entry[nm->n].line = r->line;
    nm->n++;
    return BF_OK;
}

int bf_names_read(FILE *fp, const char *name, bf_names **out, bf_error *err)
{
    bf__lines r;
    bf_names *nm = NULL;
    size_t cap = 0;
    int have = 0;
    int header = 0;
    int rc;

    bf__error_clear(err, name);
    bf__lines_init(&r, fp);
    if (out != NULL) {
        *out = NULL;
    }
    if ((out == NULL) || (fp == NULL)) {
        return bf__error_set(err, BF_EINVAL, 0, "no stream or no output");
    }
    nm = calloc(1, sizeof *nm);
    if (nm == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    for (;;) {
        rc = bf__lines_next(&r, &have, err);
        if ((rc != BF_OK) || !have) {
            break;
        }
        rc = bf__lines_split_tab(&r, err);
        if (rc != BF_OK) {
            goto done;
        }
        if ((nm->n == 0) && !header) {
            long s;
            if (bf__parse_long(r.field[0], LONG_MIN, LONG_MAX, &s) !=
                BF__NUM_OK) {
                header = 1; /* the first line's first field is not a number */
                continue;
            }
        }
        rc = add_row(nm, &cap, &r, err);
        if (rc != BF_OK) {
            goto done;
        }
    }
    if (rc != BF_OK) {
        goto done;
    }
    if (nm->n == 0) {
        rc = bf__error_set(err, BF_EPARSE, 0,
                           header ? "header line but no rows" : "empty file");
        goto done;
    }
    *out = nm;
    nm = NULL;
done:
    bf__lines_free(&r);
    bf_names_free(nm);
    return rc;
}

int bf_names_load(const char *path, bf_names **out, bf_error *err)
{
    FILE *fp = NULL;
    int rc;
    if (out != NULL) {
        *out = NULL;
    }
    rc = bf__open(path, &fp, err);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf_names_read(fp, path, out, err);
    fclose(fp);
    return rc;
}

void bf_names_free(bf_names *nm)
{
    size_t k;
    if (nm == NULL) {
        return;
    }
    for (k = 0; k < nm->n; k++) {
        free(nm->entry[k].name);
    }
    free(nm->entry);
    free(nm);
}

const char *bf_names_get(const bf_names *nm, int sample)
{
    long k;
    if (nm == NULL) {
        return NULL;
    }
    k = find(nm, sample);
    return (k < 0) ? NULL : nm->entry[k].name;
}
