/* test_main_job.c: the main job (`make run`) on a machine that has only
 * the clone -- a copy of the source tree with no ../shared beside it, the
 * CURET files served from a local file:// mirror (BRDFFIT_CURET_URL) into
 * a fresh per-user cache (XDG_CACHE_HOME). The job fetches and verifies
 * them (scripts/curet-data.sh, data/curet.sha256) and writes the report
 * with the Oren-Nayar inputs shipped in data/; a corrupted mirror is
 * refused before anything is written; offline it says which files to get,
 * from where, and where to put them. The CLI is the one this build made
 * (RUN_DEPS= BRDFFIT=...): building it again is `make run`'s business, not
 * this test's. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

/* CURET's published location, as the script names it when offline. */
#define CURET_URL "https://www.cs.columbia.edu/CAVE/software/curet/data"

/* A copy of the source tree (without build and output folders) in
 * root/clone; root has nothing else, so the clone's ../shared is
 * missing. */
static void make_clone(const char *root)
{
    char cmd[4096];
    const char *out = NULL;
    snprintf(cmd, sizeof cmd,
             "mkdir '%s/clone' && tar -C '%s' --exclude=./build "
             "--exclude='./build-*' --exclude=./out --exclude='./out-*' "
             "--exclude=./.git -cf - . | tar -C '%s/clone' -xf -",
             root, BF_SOURCE_DIR, root);
    cr_assert_eq(bf_test_run_sh(cmd, &out), 0, "%s", out);
    cr_assert(!bf_test_exists(bf_test_join(root, "shared")));
    cr_assert(bf_test_exists(
        bf_test_join(root, "clone/data/oren_nayar_params.tsv")));
}

/* A mirror of CURET's two files in root/name; with corrupt, one byte of
 * abrdf.dat (the fifth) replaced by an X. */
static const char *make_mirror(const char *root, const char *name,
                               int corrupt)
{
    static char dir[1024];
    char cmd[8192];
    char table[1024];
    char brdf[1024];
    const char *out = NULL;
    /* bf_test_curet_path's buffer is static: one at a time */
    snprintf(table, sizeof table, "%s", bf_test_curet_path("table.txt"));
    snprintf(brdf, sizeof brdf, "%s", bf_test_curet_path("abrdf.dat"));
    snprintf(dir, sizeof dir, "%s/%s", root, name);
    snprintf(cmd, sizeof cmd, "mkdir '%s' && cp '%s' '%s' '%s/'%s%s%s", dir,
             table, brdf, dir,
             corrupt ? " && printf X | dd bs=1 seek=4 conv=notrunc "
                       "2>/dev/null of='"
                     : "",
             corrupt ? dir : "", corrupt ? "/abrdf.dat'" : "");
    cr_assert_eq(bf_test_run_sh(cmd, &out), 0, "%s", out);
    return dir;
}

/* Runs `make run` in root/clone with the given mirror URL and cache;
 * returns its status, its output in *out. */
static int main_job(const char *root, const char *url, const char *cache,
                    const char **out)
{
    char cmd[8192];
    snprintf(cmd, sizeof cmd,
             "cd '%s/clone' && env XDG_CACHE_HOME='%s' "
             "BRDFFIT_CURET_URL='%s' make --no-print-directory run RUN_DEPS= "
             "BRDFFIT='%s' OUT='%s/out'",
             root, cache, url, BF_CLI_PATH, root);
    return bf_test_run_sh(cmd, out);
}

/* The SHA-256 of path by the system's sha256sum, and its line in the
 * clone's data/curet.sha256. */
static void sums(const char *path, const char *clone, const char *name,
                 char *got, char *want)
{
    char cmd[4096];
    const char *out = NULL;
    snprintf(cmd, sizeof cmd, "sha256sum '%s' | cut -c1-64", path);
    cr_assert_eq(bf_test_run_sh(cmd, &out), 0);
    snprintf(got, 65, "%s", out);
    snprintf(cmd, sizeof cmd, "awk '$2 == \"%s\" { print $1 }' "
                              "'%s/data/curet.sha256'",
             name, clone);
    cr_assert_eq(bf_test_run_sh(cmd, &out), 0);
    snprintf(want, 65, "%s", out);
}

/* A fresh folder with the clone, a mirror (none when name is NULL; a
 * corrupted one with corrupt) as a file:// URL into url, and the cache
 * folder to use. Returns the folder (the caller frees it). */
static char *setup(const char *name, int corrupt, char *url, size_t url_len,
                   char *cache, size_t cache_len)
{
    char *root = strdup(bf_test_tmpdir());
    cr_assert_not_null(root);
    make_clone(root);
    if (name != NULL) {
        snprintf(url, url_len, "file://%s", make_mirror(root, name, corrupt));
    } else {
        snprintf(url, url_len, "file:///nonexistent/brdffit-mirror");
    }
    snprintf(cache, cache_len, "%s/cache", root);
    return root;
}

Test(main_job, runs_from_a_bare_clone_with_the_curet_files_fetched_and_verified,
     .timeout = 900)
{
    char url[1200];
    char cache[1200];
    char *root = setup("mirror", 0, url, sizeof url, cache, sizeof cache);
    char got[65];
    char want[65];
    const char *out = NULL;
    const char *page;
    int rc;

    rc = main_job(root, url, cache, &out);
    cr_assert_eq(rc, 0, "make run failed:\n%s", out);
    cr_expect_not_null(strstr(out, "downloading"), "%s", out);
    /* the cache holds both files, as the repository's sums say */
    sums(bf_test_join(cache, "brdffit/curet/abrdf.dat"),
         bf_test_join(root, "clone"), "abrdf.dat", got, want);
    cr_expect_str_eq(got, want);
    cr_expect_eq(strlen(want), 64u);
    sums(bf_test_join(cache, "brdffit/curet/table.txt"),
         bf_test_join(root, "clone"), "table.txt", got, want);
    cr_expect_str_eq(got, want);
    /* the report: from the cached data and the shipped ON parameters */
    page = bf_test_slurp(bf_test_join(root, "out/report.html"), NULL);
    cr_assert_not_null(page, "no report.html:\n%s", out);
    cr_expect_not_null(strstr(page, "brdffit/curet/abrdf.dat"));
    cr_expect_not_null(strstr(page, "data/oren_nayar_params.tsv"));
    cr_expect_not_null(strstr(page, "24 samples"));
    cr_expect(bf_test_exists(bf_test_join(root, "out/figures/fig2b.png")));
    cr_expect(bf_test_exists(bf_test_join(root, "out/figures/delta_bic.pdf")));

    /* again, with the mirror gone: the cache is used as it is */
    {
        char cmd[4096];
        snprintf(cmd, sizeof cmd,
                 "env XDG_CACHE_HOME='%s' BRDFFIT_CURET_URL=file:///nonexistent "
                 "'%s/clone/scripts/curet-data.sh'",
                 cache, root);
        rc = bf_test_run_sh(cmd, &out);
        cr_expect_eq(rc, 0, "the cache was not used:\n%s", out);
        cr_expect_null(strstr(out, "downloading"), "fetched again:\n%s", out);
        cr_expect_not_null(strstr(out, "/brdffit/curet"), "%s", out);
    }
    free(root);
}

Test(main_job, refuses_a_mirror_whose_files_do_not_match_their_sums,
     .timeout = 300)
{
    char url[1200];
    char cache[1200];
    char *root = setup("bad", 1, url, sizeof url, cache, sizeof cache);
    const char *out = NULL;
    cr_expect_neq(main_job(root, url, cache, &out), 0);
    cr_expect_not_null(strstr(out, "abrdf.dat is not CURET's abrdf.dat"),
                       "%s", out);
    cr_expect_not_null(strstr(out, "refused"), "%s", out);
    cr_expect(!bf_test_exists(bf_test_join(cache, "brdffit/curet/abrdf.dat")),
              "the bad file was kept");
    cr_expect(!bf_test_exists(
        bf_test_join(cache, "brdffit/curet/.abrdf.dat.part")));
    cr_expect(!bf_test_exists(bf_test_join(root, "out")),
              "output written from bad data");
    free(root);
}

Test(main_job, says_which_files_to_get_and_where_to_put_them_when_offline,
     .timeout = 300)
{
    char url[1200];
    char cache[1200];
    char *root = setup(NULL, 0, url, sizeof url, cache, sizeof cache);
    char where[1300];
    const char *out = NULL;
    cr_expect_neq(main_job(root, url, cache, &out), 0);
    cr_expect_not_null(strstr(out, CURET_URL "/table.txt"), "%s", out);
    cr_expect_not_null(strstr(out, CURET_URL "/abrdf.dat"), "%s", out);
    snprintf(where, sizeof where, "%s/brdffit/curet/", cache);
    cr_expect_not_null(strstr(out, where), "%s", out);
    cr_expect_not_null(strstr(out, "data/curet.sha256"), "%s", out);
    cr_expect(!bf_test_exists(bf_test_join(root, "out")));
    free(root);
}
