/* cli_run.h: runs the brdffit binary from tests and captures its outputs. */
#ifndef BF_TEST_CLI_RUN_H
#define BF_TEST_CLI_RUN_H

#include <stddef.h>

/* Runs BF_CLI_PATH with argv (NULL-terminated, argv[0] excluded), standard
 * output and error captured into the static buffers returned through out and
 * err (may be NULL). Returns the exit status, or -1 if it did not exit
 * normally (a crash fails the calling test). */
int bf_test_run_cli(const char *const *argv, const char **out,
                    const char **err);

/* bf_test_run_cli with every argument "DATA" replaced by the CURET
 * folder (bf_test_curet_path): argv is changed in place. */
int bf_test_run_curet(const char **argv);

/* Runs the shell command cmd (/bin/sh -c) with standard output and error
 * captured together into the static buffer returned through out (may be
 * NULL; shared with bf_test_run_cli's stdout buffer). Returns the exit
 * status, or -1 if it did not exit normally. */
int bf_test_run_sh(const char *cmd, const char **out);

/* Creates a fresh temporary folder (static buffer); it and what it holds
 * are removed when the process exits (kept when BF_TEST_KEEP is set). */
const char *bf_test_tmpdir(void);

/* Reads a whole file into a static buffer; NULL when it does not exist. */
const char *bf_test_slurp(const char *path, size_t *len);

/* A heap copy of a whole file (the caller frees it), *len its bytes;
 * fails the test when it does not exist. */
char *bf_test_copy(const char *path, size_t *len);

/* "dir/name" in one of four static buffers used in turn (so that up to
 * four paths are alive at once). */
const char *bf_test_join(const char *dir, const char *name);

/* 1 when path exists. */
int bf_test_exists(const char *path);

/* A CSV output of the CLI (dir/name), read whole into static storage
 * (quoted fields unquoted); returns its number of lines (header included). Its
 * cells are found by header name: bf_test_csv_cell (borrowed until the
 * next load), bf_test_csv_num (NaN for an empty cell); bf_test_csv_find
 * gives the row of (sample, model, parameter), NULL matching any. */
size_t bf_test_csv_load(const char *dir, const char *name);
size_t bf_test_csv_col(const char *name);
const char *bf_test_csv_cell(size_t row, const char *name);
double bf_test_csv_num(size_t row, const char *name);
size_t bf_test_csv_find(const char *sample, const char *model,
                        const char *param);

#endif
