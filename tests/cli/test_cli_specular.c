/* test_cli_specular.c: the specular models of SPEC §9 in the CLI --
 * `brdffit models` lists them with their NDF, masking, Fresnel term and
 * the parameters of the --fresnel/--smith variants; the paper's study
 * (max-normalised, SPEC §2) refuses them by name with the reason; data
 * with every value zero (a file, or one channel) are refused under the
 * objectives that keep the scale (SPEC §10), naming file, sample and
 * channel, with no output. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_BADVALUE 63
#define EXIT_DATAERR 65

/* The block of model name in the listing out (to the next model line). */
static const char *block(const char *out, const char *name, char *buf,
                         size_t len)
{
    char head[64];
    const char *p;
    const char *end;
    snprintf(head, sizeof head, "\n%s ", name);
    p = strstr(out, head);
    cr_assert_not_null(p, "%s not listed", name);
    p++;
    for (end = strchr(p, '\n'); end != NULL && end[1] == ' ';
         end = strchr(end + 1, '\n')) {
    }
    if (end == NULL) {
        end = p + strlen(p);
    }
    cr_assert_lt((size_t)(end - p), len);
    memcpy(buf, p, (size_t)(end - p));
    buf[end - p] = '\0';
    return buf;
}

Test(cli_specular, models_lists_the_specular_family_and_its_variants)
{
    const char *argv[] = {"models", NULL};
    const char *argv_d[] = {"models", "--fresnel", "dielectric", NULL};
    const char *argv_s[] = {"models", "--smith=separable", NULL};
    const char *out = NULL;
    char buf[4096];
    cr_assert_eq(bf_test_run_cli(argv, &out, NULL), 0);
    block(out, "GGX", buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "NDF GGX; masking Smith height-correlated"),
                       "%s", buf);
    cr_assert_not_null(strstr(buf, "F0 "), "%s", buf);
    cr_assert_not_null(strstr(buf, "linear (a scale)"), "%s", buf);
    block(out, "ABC", buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "ior "), "%s", buf);
    cr_assert_eq(bf_test_run_cli(argv_d, &out, NULL), 0);
    block(out, "GGX", buf, sizeof buf);
    cr_assert_null(strstr(buf, "F0 "), "%s", buf);
    cr_assert_not_null(strstr(buf, " n      refractive index n"), "%s", buf);
    cr_assert_not_null(strstr(buf, "Fresnel dielectric"), "%s", buf);
    block(out, "WARD", buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "WARD has no Fresnel term"), "%s", buf);
    cr_assert_eq(bf_test_run_cli(argv_s, &out, NULL), 0);
    block(out, "BECKMANN", buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "Smith separable"), "%s", buf);
    block(out, "CT", buf, sizeof buf);
    cr_assert_not_null(strstr(buf, "CT has no Smith masking"), "%s", buf);
}

Test(cli_specular, models_rejects_unknown_option_values)
{
    const char *a1[] = {"models", "--fresnel", "fresnel", NULL};
    const char *a2[] = {"models", "--smith", NULL};
    const char *err = NULL;
    cr_assert_eq(bf_test_run_cli(a1, NULL, &err), EXIT_BADVALUE);
    cr_assert_not_null(strstr(err, "--fresnel: 'fresnel' is not schlick"),
                       "%s", err);
    cr_assert_neq(bf_test_run_cli(a2, NULL, &err), 0);
    cr_assert_not_null(strstr(err, "--smith needs a value"), "%s", err);
}

/* The paper's objective max-normalises (SPEC §2): a specular model by
 * name is refused before any data is read, with what to use instead. */
Test(cli_specular, the_paper_study_refuses_a_specular_model)
{
    const char *argv[] = {"compare", "--data", "DATA", "--models",
                          "VH-G,GGX", NULL};
    const char *err = NULL;
    cr_assert_eq(bf_test_run_curet(argv), EXIT_BADVALUE);
    (void)bf_test_run_cli(argv, NULL, &err);
    cr_assert_not_null(strstr(err, "GGX gives absolute BRDF values (SPEC §9); "
                                   "fit it with --fit exact --objective ngan, "
                                   "cuberoot or log1p"),
                       "%s", err);
}

/* A tidy CSV of one material at 40 configurations in the plane of
 * incidence: channel A all zero, channel B a positive lobe. */
static const char *write_zero_csv(const char *dir)
{
    static char path[512];
    FILE *fp;
    int i;
    snprintf(path, sizeof path, "%s/zero.csv", dir);
    fp = fopen(path, "w");
    cr_assert_not_null(fp, "%s", path);
    fprintf(fp, "material,theta_i,phi_i,theta_o,phi_o,A,B\n");
    for (i = 0; i < 40; i++) {
        double ti = 10.0 + 20.0 * (i % 4);
        double to = 2.0 * (double)(i / 4) + 1.0;
        fprintf(fp, "paint,%g,0,%g,180,0,%g\n", ti, to,
                0.05 + 0.01 * (double)i);
    }
    cr_assert_eq(fclose(fp), 0);
    return path;
}

Test(cli_specular, every_value_zero_is_refused_naming_the_channel)
{
    const char *dir = bf_test_tmpdir();
    const char *csv = write_zero_csv(dir);
    char out[600];
    char fits[700];
    struct stat sb;
    const char *argv[] = {"report", "--input", csv, "--fit", "exact",
                          "--objective", "ngan", "--models",
                          "LAMBERT,LAMBERT+GGX", "--channel", "A", "--out",
                          out, "-q", NULL};
    const char *err = NULL;
    snprintf(out, sizeof out, "%s/out", dir);
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_DATAERR, "%s", err);
    cr_assert(err != NULL && strstr(err, csv) != NULL &&
                  strstr(err, "every measured value is zero") != NULL,
              "%s", err);
    snprintf(fits, sizeof fits, "%s/fits.csv", out);
    cr_assert_neq(stat(fits, &sb), 0, "no partial output");
    argv[10] = "each"; /* A among the channels: named */
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), EXIT_DATAERR, "%s", err);
    cr_assert(err != NULL && strstr(err, "channel A: every measured value "
                                         "is zero") != NULL,
              "%s", err);
    cr_assert_neq(stat(fits, &sb), 0, "no partial output");
    argv[10] = "B"; /* the other channel fits */
    cr_assert_eq(bf_test_run_cli(argv, NULL, &err), 0, "%s", err);
}
