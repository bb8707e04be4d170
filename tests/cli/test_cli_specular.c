/* test_cli_specular.c: the specular models of SPEC §9 in the CLI --
 * `brdffit models` lists them with their NDF, masking, Fresnel term and
 * the parameters of the --fresnel/--smith variants; the paper's study
 * (max-normalised, SPEC §2) refuses them by name with the reason. */
#include <criterion/criterion.h>
#include <string.h>

#include "cli_run.h"
#include "support.h"

#define EXIT_BADVALUE 63

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
