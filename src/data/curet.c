/* curet.c: CURET as a dataset -- table.txt (the configurations), one BRDF
 * file (abrdf.dat or a channel file) and samples.tsv (names), one material
 * per sample, numbered by its sample number and named from samples.tsv
 * (no name without it) (SPEC §1.3, §2, §8).
 *
 * [1] K. J. Dana et al., ACM TOG 18(1), 1999 (CURET); layout in
 *     shared/data/curet/SOURCES.md.
 */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "data/curet.h"
#include "data/reader.h"
#include "internal.h"

/* The channel a CURET BRDF file holds, from its base name: abrdf.dat is
 * the mean of R, G, B (SPEC §2), r/g/bbrdf.dat one colour each. */
static const char *channel_of(const char *path)
{
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    if (strcmp(base, "abrdf.dat") == 0) {
        return "mean";
    }
    if (strcmp(base, "rbrdf.dat") == 0) {
        return "R";
    }
    if (strcmp(base, "gbrdf.dat") == 0) {
        return "G";
    }
    if (strcmp(base, "bbrdf.dat") == 0) {
        return "B";
    }
    return base;
}

void bf_table_angles(const bf_table *t, double *angles)
{
    size_t k;
    for (k = 0; k < bf_table_size(t); k++) {
        double raw[4]; /* theta_v, phi_v, theta_i, phi_i (SPEC §1.3) */
        bf_table_raw(t, k, raw);
        angles[4 * k + 0] = raw[2];
        angles[4 * k + 1] = raw[3];
        angles[4 * k + 2] = raw[0]; /* o = v */
        angles[4 * k + 3] = raw[1];
    }
}

int bf_curet_configs_load(const char *path, double **angles, size_t *n,
                          bf_error *err)
{
    bf_table *t = NULL;
    int rc;
    if (angles == NULL || n == NULL) {
        return BF_EINVAL;
    }
    *angles = NULL;
    *n = 0;
    rc = bf_table_load(path, &t, err);
    if (rc != BF_OK) {
        return rc;
    }
    *angles = malloc(4 * bf_table_size(t) * sizeof **angles);
    if (*angles == NULL) {
        bf_table_free(t);
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    bf_table_angles(t, *angles);
    *n = bf_table_size(t);
    bf_table_free(t);
    return BF_OK;
}

int bf_curet_dataset(const bf_table *t, const bf_brdf *b,
                     const bf_names *names, const char *source,
                     const char *channel, bf_dataset **out, bf_error *err)
{
    size_t n = bf_table_size(t);
    double *angles = NULL;
    bf_dataset *ds = NULL;
    size_t set;
    size_t r;
    int rc;

    bf__error_clear(err, source);
    if (out != NULL) {
        *out = NULL;
    }
    if (t == NULL || b == NULL || out == NULL || n == 0 ||
        bf_brdf_nconf(b) != n) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "the table and the BRDF rows do not match");
    }
    angles = malloc(n * 4 * sizeof *angles);
    ds = bf_dataset_alloc();
    if (angles == NULL || ds == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto done;
    }
    bf_table_angles(t, angles);
    rc = bf_dataset_add_configs(ds, n, angles, &set, NULL);
    for (r = 0; rc == BF_OK && r < bf_brdf_count(b); r++) {
        bf_material_desc d;
        const char *ch = channel;
        int sample = bf_brdf_sample(b, r);
        memset(&d, 0, sizeof d);
        d.name = bf_names_get(names, sample); /* NULL: no name */
        d.number = sample;
        d.format = BF_FORMAT_CURET;
        d.source = source;
        d.line = bf_brdf_line(b, r);
        d.set = set;
        d.n_channels = 1;
        d.channel = &ch;
        d.values = bf_brdf_values(b, r);
        rc = bf_dataset_add_material(ds, &d, NULL);
    }
    if (rc != BF_OK) {
        rc = bf__error_set(err, rc, 0, "%s",
                           rc == BF_ENOMEM ? "out of memory"
                                           : "invalid CURET tables");
        goto done;
    }
    *out = ds;
    ds = NULL;
done:
    free(angles);
    bf_dataset_free(ds);
    return rc;
}

int bf_curet_load(const char *dir, const char *brdf_path, bf_dataset **out,
                  bf_error *err)
{
    char table_path[BF_ERROR_FILE_MAX];
    char path[BF_ERROR_FILE_MAX];
    char names_path[BF_ERROR_FILE_MAX];
    bf_table *t = NULL;
    bf_brdf *b = NULL;
    bf_names *names = NULL;
    struct stat sb;
    int rc;

    if (out != NULL) {
        *out = NULL;
    }
    bf__error_clear(err, dir);
    if (dir == NULL || out == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no folder or no output");
    }
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        return bf__error_set(err, BF_EIO, 0,
                             "CURET data folder not found (it must hold "
                             "table.txt and abrdf.dat)");
    }
    snprintf(table_path, sizeof table_path, "%s/table.txt", dir);
    if (brdf_path != NULL) {
        snprintf(path, sizeof path, "%s", brdf_path);
    } else {
        snprintf(path, sizeof path, "%s/abrdf.dat", dir);
    }
    snprintf(names_path, sizeof names_path, "%s/samples.tsv", dir);

    rc = bf_table_load(table_path, &t, err);
    if (rc == BF_OK) {
        rc = bf_brdf_load(path, bf_table_size(t), &b, err);
    }
    if (rc == BF_EPARSE && t != NULL && stat(path, &sb) == 0 &&
        S_ISREG(sb.st_mode)) {
        /* Rows that agree with each other but not with the table: say so,
         * naming both files (the first error otherwise stands). A pipe
         * cannot be read twice, so only a regular file is. */
        bf_error again;
        if (bf_brdf_load(path, 0, &b, &again) == BF_OK &&
            bf_brdf_nconf(b) != bf_table_size(t)) {
            bf__error_clear(err, path);
            bf__error_set(err, BF_EPARSE, bf_brdf_line(b, 0),
                          "the BRDF rows have %zu values but %s has %zu "
                          "configurations",
                          bf_brdf_nconf(b), table_path, bf_table_size(t));
        }
    }
    if (rc == BF_OK && stat(names_path, &sb) == 0) {
        rc = bf_names_load(names_path, &names, err);
    }
    if (rc == BF_OK) {
        rc = bf_curet_dataset(t, b, names, path, channel_of(path), out, err);
    }
    bf_table_free(t);
    bf_brdf_free(b);
    bf_names_free(names);
    return rc;
}

/* ==== the reader (reader.h) ==== */

static int load(const char *path, const bf_load_opts *opts, bf_dataset **out,
                bf_error *err)
{
    (void)opts;
    return bf_curet_load(path, NULL, out, err);
}

const bf__reader bf__curet_reader = {
    .name = "curet",
    .title = "CURET",
    .folder_file = "table.txt",
    .load = load,
};
