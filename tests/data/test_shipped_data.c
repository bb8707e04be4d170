/* test_shipped_data.c: what the repository ships for the main job
 * (data/README.md) -- the Oren-Nayar inputs of the study are the published
 * values of ../shared/reference, sample by sample, and data/curet.sha256
 * holds the SHA-256 of the CURET files the study reads (computed here by
 * the system's sha256sum). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

Test(shipped_data, oren_nayar_inputs_are_the_published_values)
{
    bf_sample_table *ship = NULL;
    bf_sample_table *ref = NULL;
    bf_error err;
    size_t r;
    cr_assert_eq(bf_on_params_load(BF_SOURCE_DIR "/data/oren_nayar_params.tsv",
                                   &ship, &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(bf_on_params_load(
                     bf_test_reference_path("oren_nayar_params.tsv"), &ref,
                     &err),
                 BF_OK, "%s", err.msg);
    cr_assert_eq(bf_sample_table_count(ship), bf_sample_table_count(ref));
    cr_assert_eq(bf_sample_table_count(ship), (size_t)BF_STUDY_NSAMPLES);
    for (r = 0; r < bf_sample_table_count(ref); r++) {
        int s = bf_sample_table_sample(ref, r);
        size_t c;
        for (c = 0; c < 2; c++) {
            double a;
            double b;
            cr_assert_eq(bf_sample_table_get(ship, s, c, &a), BF_OK,
                         "sample %d missing", s);
            cr_assert_eq(bf_sample_table_get(ref, s, c, &b), BF_OK);
            cr_expect_eq(a, b, "sample %d column %zu: %g shipped, %g "
                               "published",
                         s, c, a, b);
        }
    }
    bf_sample_table_free(ship);
    bf_sample_table_free(ref);
}

Test(shipped_data, curet_sums_are_those_of_the_curet_files)
{
    static const char *const files[2] = {"table.txt", "abrdf.dat"};
    size_t i;
    for (i = 0; i < 2; i++) {
        char cmd[2048];
        char path[1024];
        char got[65];
        const char *out = NULL;
        snprintf(path, sizeof path, "%s", bf_test_curet_path(files[i]));
        snprintf(cmd, sizeof cmd, "sha256sum '%s' | cut -c1-64", path);
        cr_assert_eq(bf_test_run_sh(cmd, &out), 0, "%s", out);
        snprintf(got, sizeof got, "%s", out);
        snprintf(cmd, sizeof cmd,
                 "awk '$2 == \"%s\" { print $1 }' '%s/data/curet.sha256'",
                 files[i], BF_SOURCE_DIR);
        cr_assert_eq(bf_test_run_sh(cmd, &out), 0, "%s", out);
        cr_expect(strncmp(out, got, 64) == 0 && strlen(got) == 64,
                  "%s: data/curet.sha256 says %.64s, the file is %s",
                  files[i], out, got);
    }
}
