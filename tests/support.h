/* support.h: shared helpers of the test suite -- named tolerances, checks
 * that print expected/obtained/difference/tolerance, loud access to the
 * CURET data and in-memory files for loader tests. */
#ifndef BF_TEST_SUPPORT_H
#define BF_TEST_SUPPORT_H

#include <float.h>
#include <stdio.h>

#include "brdffit.h"
#include "data/curet.h" /* the CURET reader's tables (private) */

/* Named tolerances (STYLE §7, after GSL's TEST_TOL0..6). */
#define TOL0 (2.0 * DBL_EPSILON)
#define TOL1 (16.0 * DBL_EPSILON)
#define TOL2 (256.0 * DBL_EPSILON)
#define TOL3 (2048.0 * DBL_EPSILON)
#define TOL4 (16384.0 * DBL_EPSILON)
#define TOL_FIT 1e-6

/* 1 in a build with AddressSanitizer (make test-asan), whose code runs
 * tens of times slower: the few tests whose claim needs many repetitions
 * (interval coverage) or the plain path on every sample (WNO-R's grid)
 * make it there on fewer; the plain build makes the full claim. */
#if defined(__SANITIZE_ADDRESS__)
#define BF_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BF_TEST_SANITIZED 1
#endif
#endif
#ifndef BF_TEST_SANITIZED
#define BF_TEST_SANITIZED 0
#endif

/* Asserts |obtained - expected| <= tol * max(|expected|, 1e-300) and prints
 * expected, obtained, relative difference and tolerance when it fails. */
#define bf_assert_rel(obtained, expected, tol) \
    bf__assert_rel((obtained), (expected), (tol), #obtained, __FILE__, __LINE__)
/* Asserts |obtained - expected| <= tol. */
#define bf_assert_abs(obtained, expected, tol) \
    bf__assert_abs((obtained), (expected), (tol), #obtained, __FILE__, __LINE__)

void bf__assert_rel(double obtained, double expected, double tol,
                    const char *what, const char *file, int line);
void bf__assert_abs(double obtained, double expected, double tol,
                    const char *what, const char *file, int line);

/* Path of a file in the CURET data folder (BF_CURET_DIR, overridable by the
 * environment variable BRDFFIT_CURET_DIR). Fails the test loudly when the
 * file does not exist: tests never skip for missing data. Static buffer. */
const char *bf_test_curet_path(const char *file);

/* Path of a file in the reference folder (BF_REFERENCE_DIR, or
 * BRDFFIT_REFERENCE_DIR); fails loudly when missing. Static buffer. */
const char *bf_test_reference_path(const char *file);

/* Path of a file in the Cornell pbrt-v2 folder (BF_CORNELL_DIR, or
 * BRDFFIT_CORNELL_DIR); fails loudly when missing. Static buffer. */
const char *bf_test_cornell_path(const char *file);

/* The five Cornell .brdf files of shared/data/cornell-pbrt-v2/. */
#define BF_TEST_NCORNELL 5
extern const char *const bf_test_cornell[BF_TEST_NCORNELL];

/* Asserts that two datasets hold the same measurements: materials in the
 * same order with the same names, numbers and configuration counts, the
 * same angles bit for bit, the same channel names and wavelengths, the
 * same valid marks and the same valid values bit for bit, and the same
 * sharing of configuration sets. Source, format and line are not compared
 * (they say where the data came from). */
void bf_test_expect_same_dataset(const bf_dataset *a, const bf_dataset *b);

/* A dataset reader: bf_pbrt_read, bf_astm_read, bf_csv_read. */
typedef int (*bf_test_reader)(FILE *fp, const char *name, bf_dataset **out,
                              bf_error *err);

/* Reads text with rd under name; fails the test unless it succeeds. */
bf_dataset *bf_test_read_ok(bf_test_reader rd, const char *name,
                            const char *text);

/* Asserts that reading len bytes of buf with rd under name fails with
 * code at line and exactly the message msg, leaving *out NULL and err
 * naming the file. */
void bf_test_expect_read_error(bf_test_reader rd, const char *name,
                               const void *buf, size_t len, int code,
                               long line, const char *msg);

/* The parameters of type at a point of its paper grid (SPEC §7.4): each
 * fitted parameter at grid index floor(frac (grid_n - 1)), computed as the
 * grid computes it; the others at their defaults. */
void bf_test_grid_point(const bf_model_type *type, double frac,
                        double *param);

/* BRDF values whose radiance (SPEC §2: value times cos theta_i) is type's
 * at param on n configurations: out[k] = L_k / cos theta_i,k. */
void bf_test_model_brdf(const bf_model_type *type, const double *param,
                        size_t n, const bf_geom *geom, double *out);

/* The paper's grid fit (bf_study_run, format defaults: every valid
 * configuration outside the format's default cone) of material m of ds,
 * mean channel, with one model; fails the test on an error. *k gets K. */
bf_fit_result bf_test_fit_one(const bf_dataset *ds, size_t m,
                              const bf_model_type *type, size_t *k);

/* The configurations of the glossy recovery tests (measurement frame,
 * radians, 4 angles each): theta_i 5..75 deg by 10; at each, 25 directions
 * within 4 deg and 6 deg of azimuth of the mirror direction (theta_i,
 * phi_i + pi) and 25 spread over the hemisphere: half near the mirror
 * direction, all with theta <= 80 deg (SPEC §10 uses every one). */
#define BF_TEST_GLOSSY_NCONF 400
void bf_test_glossy_configs(double *at);

/* A synthetic material: type's BRDF (bf_model_eval, sr^-1) at param. */
typedef struct {
    const char *name;
    const bf_model_type *type;
    const double *param;
} bf_test_material;

/* A dataset of n materials measured at the K configurations at
 * (measurement frame, radians, 4 angles each): material i (numbered i + 1)
 * is names[i], with C channels (channel: their names, wavelength: theirs
 * in nm; either NULL for none) whose values are values + i K C (K x C,
 * row-major: configuration by configuration); fails the test on any
 * error. The caller frees it (bf_dataset_free). */
bf_dataset *bf_test_channels_dataset(size_t K, const double *at, size_t n,
                                     const char *const *names, size_t C,
                                     const char *const *channel,
                                     const double *wavelength,
                                     const double *values);

/* The same dataset written through the library's tidy CSV writer
 * (bf_csv_write) to path; fails the test on any error. */
void bf_test_write_channels_csv(const char *path, size_t K,
                                const double *at, size_t n,
                                const char *const *names, size_t C,
                                const char *const *channel,
                                const double *wavelength,
                                const double *values);

/* Writes the n materials at the K configurations at (measurement frame,
 * radians, 4 angles each) as one dataset (one channel, material i + 1 is
 * mat[i]) through bf_test_write_channels_csv to path; fails the test on
 * any error. */
void bf_test_write_model_csv(const char *path, size_t K, const double *at,
                             size_t n, const bf_test_material *mat);

/* The same with relative noise: each value times 1 + noise eps, eps
 * standard normal (GSL mt19937 seeded with seed), as radiance measured
 * with a relative error of sd noise. */
void bf_test_write_noisy_csv(const char *path, size_t K, const double *at,
                             size_t n, const bf_test_material *mat,
                             double noise, unsigned long seed);

/* The same at bf_test_glossy_configs. */
void bf_test_write_glossy_csv(const char *path, size_t n,
                              const bf_test_material *mat);

/* Path of a fixture in tests/fixtures (static buffer). */
const char *bf_test_fixture_path(const char *file);

/* Loads CURET's table.txt and abrdf.dat, failing the test loudly. */
bf_table *bf_test_load_table(void);

/* Where the coverage tests put the truth of free parameter j of pb: 37 %
 * of its search range (off every grid point); a diffuse model's
 * refractive index n at 15 % (1.395 on [1.2, 2.5]), away from n ~ 1.7,
 * where the normalised shapes of FC-E, FC-G, WNO and WNO-R fold over n:
 * there the likelihood-ratio statistic is not chi2_1 and the intervals
 * over-cover, while on either side a profile often has two minima
 * (doc/methods.md §3, "Split sets"). */
double bf_test_truth_at(const bf_problem *pb, size_t j);

/* A study of models on targets of ds as the CLI poses it: the default
 * selection, n 1.7, one thread. */
void bf_test_study_spec(bf_study_spec *spec, const bf_dataset *ds,
                        const bf_target *targets, size_t n_targets,
                        const bf_model_type *const *models, size_t n_models);
/* bf_random_geometry (random_geometry.h), asserted to succeed. */
void bf_test_random_geometry(bf_geom *geom, size_t n, unsigned long seed,
                             int mirror);
/* Every stride-th of the 198 non-specular CURET configurations into geom
 * (room for BF_CURET_NCONF); returns how many. */
size_t bf_test_curet_geometry(bf_geom *geom, size_t stride);
bf_brdf *bf_test_load_abrdf(void);

/* Opens a read-only in-memory stream over the NUL-terminated text. The
 * caller closes it with fclose. */
FILE *bf_test_memfile(const char *text);

/* Opens a read-only in-memory stream over len bytes (may contain NUL). */
FILE *bf_test_membuf(const void *buf, size_t len);

#endif
