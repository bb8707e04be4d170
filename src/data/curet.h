/* curet.h: the CURET reader's own tables (private; src/data/): the
 * configuration table (table.txt), the BRDF rows (abrdf.dat and its
 * channels) and the sample names (samples.tsv), read by bf_curet_load
 * into a bf_dataset -- the public data model. The file syntax is that of
 * every reader (brdffit.h, "load"; src/data/lineio.c). Tests, benchmarks
 * and fuzz targets of these readers include this header. */
#ifndef BF_DATA_CURET_H
#define BF_DATA_CURET_H

#include <stddef.h>
#include <stdio.h>

#include "brdffit.h"

/* A configuration table: rows "index theta_v phi_v theta_i phi_i" in CURET's
 * sample frame (SPEC §1.3). Opaque; owns memory. */
typedef struct bf_table bf_table;

/* Reads a configuration table from fp (name is used in messages). Indices
 * must run 1..N in order. Returns BF_OK and *out (free with bf_table_free),
 * or BF_EPARSE/BF_EIO/BF_ENOMEM with err filled. Each row has exactly 5
 * numbers; zeniths must lie in [0, pi/2] and azimuths in [-2 pi, 2 pi], up
 * to 1e-9 rad (a zenith within that tolerance outside [0, pi/2] is clamped
 * onto it). An empty file is BF_EPARSE "empty file" at line 0. */
int bf_table_read(FILE *fp, const char *name, bf_table **out, bf_error *err);

/* Opens path and calls bf_table_read. */
int bf_table_load(const char *path, bf_table **out, bf_error *err);

/* Frees t; NULL does nothing. */
void bf_table_free(bf_table *t);

/* Number of configurations. */
size_t bf_table_size(const bf_table *t);

/* Configuration k (0-based) in Beckmann's frame (bf_geom_from_curet).
 * All fields are NaN when k >= bf_table_size(t). */
bf_geom bf_table_geom(const bf_table *t, size_t k);

/* Configuration k's raw CURET angles: theta_v, phi_v, theta_i, phi_i (NaN
 * when k is out of range). */
void bf_table_raw(const bf_table *t, size_t k, double raw[4]);

/* Writes the 0-based indices of the configurations that are used by the
 * study into sel (capacity bf_table_size(t)): every configuration that is
 * not specular (SPEC §1.4) and whose theta_i and theta_v are both
 * <= max_theta (pass a value >= pi/2 to keep all). Returns the count. */
size_t bf_table_select(const bf_table *t, double max_theta, size_t *sel);

/* A BRDF file with rows "sample v1 ... vN" (CURET abrdf/rbrdf/gbrdf/bbrdf
 * layout). Opaque; owns memory. */
typedef struct bf_brdf bf_brdf;

/* Reads BRDF rows with exactly n_conf values each (n_conf = 0: as many as
 * the first row has, at least one). Sample numbers must be
 * positive, unique and run 1, 2, 3, ... without gaps. Values must be finite.
 * Returns BF_OK and *out (free with bf_brdf_free) or an error with err.
 * Rows may come in any order; they are stored sorted by sample number, so
 * row r holds sample r + 1. Negative values are kept as measured. Errors
 * (BF_EPARSE): wrong value count, bad number (field named), duplicate
 * sample (at its second line, naming the first), missing sample (line 0,
 * naming the smallest missing number), empty file. */
int bf_brdf_read(FILE *fp, const char *name, size_t n_conf, bf_brdf **out,
                 bf_error *err);
int bf_brdf_load(const char *path, size_t n_conf, bf_brdf **out,
                 bf_error *err);
void bf_brdf_free(bf_brdf *b);

size_t bf_brdf_count(const bf_brdf *b);      /* number of samples */
size_t bf_brdf_nconf(const bf_brdf *b);      /* values per sample */
int bf_brdf_sample(const bf_brdf *b, size_t row);  /* sample number, -1 if
                                                      row is out of range */
/* Line of the file that row came from (0 if out of range). */
long bf_brdf_line(const bf_brdf *b, size_t row);
/* Values of a row (borrowed until bf_brdf_free); NULL if out of range. */
const double *bf_brdf_values(const bf_brdf *b, size_t row);
/* Row of sample number s, or -1. */
long bf_brdf_find(const bf_brdf *b, int sample);

/* Sample names: rows "sample name [flag]" of samples.tsv (tab-separated,
 * header line). Opaque; owns memory. Fields are split at tabs only (names
 * contain spaces), spaces around fields are trimmed; the first line is a
 * header when its first field is not an integer; flag, when present, is 0
 * or 1; sample numbers are unique, gaps allowed. */
typedef struct bf_names bf_names;
int bf_names_read(FILE *fp, const char *name, bf_names **out, bf_error *err);
int bf_names_load(const char *path, bf_names **out, bf_error *err);
void bf_names_free(bf_names *nm);
/* Name of sample s (borrowed), or NULL when unknown or nm is NULL. */
const char *bf_names_get(const bf_names *nm, int sample);

/* CURET's configurations in the measurement frame (SPEC §1.3, §1.5):
 * angles (capacity 4 bf_table_size(t)) gets rows theta_i, phi_i,
 * theta_o = theta_v, phi_o = phi_v (bf_curet_configs_load). */
void bf_table_angles(const bf_table *t, double *angles);

/* The dataset of bf_curet_load from tables already read (names may be
 * NULL); copies them. */
int bf_curet_dataset(const bf_table *t, const bf_brdf *b,
                     const bf_names *names, const char *source,
                     const char *channel, bf_dataset **out, bf_error *err);

/* Measured radiance of SPEC §2: out[j] = v[sel[j]] * cos(theta_i of
 * configuration sel[j]), then normalised over the n selected values.
 * Returns BF_EDOM when the maximum is not positive. */
int bf_data_radiance(const bf_table *t, const double *v, size_t n,
                     const size_t *sel, double *out);

#endif
