/* readers_stub.c: TEMPORARY (branch `dataset` only, never merged): the
 * entry points of the format readers until src/data/format.c, pbrt.c,
 * astm.c, csv.c and merl.c land. Only CURET folders load. */
#include <string.h>
#include <sys/stat.h>

#include "internal.h"

const char *bf_format_name(bf_format f)
{
    static const char *const names[] = {"auto", "curet", "pbrt", "astm",
                                        "merl", "csv",   "memory"};
    return (f >= 0 && (size_t)f < sizeof names / sizeof *names) ? names[f]
                                                                 : NULL;
}

int bf_format_find(const char *name, bf_format *f)
{
    int i;
    for (i = 0; i <= BF_FORMAT_MEMORY; i++) {
        if (strcmp(name, bf_format_name((bf_format)i)) == 0) {
            *f = (bf_format)i;
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}

int bf_dataset_load(const char *path, const bf_load_opts *opts,
                    bf_dataset **out, bf_error *err)
{
    struct stat sb;
    (void)opts;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        return bf_curet_load(path, NULL, out, err);
    }
    *out = NULL;
    bf__error_clear(err, path);
    return bf__error_set(err, BF_EPARSE, 0, "format readers not built yet");
}

int bf_csv_write(const bf_dataset *ds, FILE *fp)
{
    (void)ds;
    (void)fp;
    return BF_EINVAL;
}

int bf_configs_load(const char *path, double **angles, size_t *n,
                    bf_error *err)
{
    (void)angles;
    (void)n;
    bf__error_clear(err, path);
    return bf__error_set(err, BF_EPARSE, 0, "format readers not built yet");
}

int bf_format_detect(const char *path, bf_format *f, bf_error *err)
{
    (void)f;
    bf__error_clear(err, path);
    return bf__error_set(err, BF_EPARSE, 0, "format readers not built yet");
}
