/* cmd_models.c: `brdffit models` -- lists the model registry: names,
 * parameters with units, domains and grids, the equations implemented,
 * and for the specular models (SPEC §9) their NDF, masking and Fresnel
 * term, with --fresnel and --smith the parameters of those variants. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "options.h"

static void usage(void)
{
    puts("Usage: brdffit models [--fresnel schlick|dielectric|none] "
         "[--smith height|separable]\n\n"
         "Lists every model: name, parameters (unit, valid range, default, "
         "paper grid)\nand the equations it implements. The specular "
         "models (SPEC §9) name their\nnormal distribution, masking and "
         "Fresnel term; --fresnel and --smith list\nthe parameters of "
         "those variants (--fresnel dielectric replaces F0 by the\n"
         "index n; --smith applies to GGX and BECKMANN).");
}

/* The value of option name at argv[*i] ("--name VALUE" or
 * "--name=VALUE"), or NULL when argv[*i] is not that option. */
static const char *option_value(int argc, char **argv, int *i,
                                const char *name, int *missing)
{
    size_t len = strlen(name);
    const char *a = argv[*i];
    if (strncmp(a, name, len) != 0) {
        return NULL;
    }
    if (a[len] == '=') {
        return a + len + 1;
    }
    if (a[len] != '\0') {
        return NULL;
    }
    if (*i + 1 >= argc) {
        *missing = 1;
        return NULL;
    }
    return argv[++*i];
}

static void print_params(const bf_model_type *t)
{
    size_t j;
    if (t->p == 0) {
        puts("         no parameter (after normalisation)");
    }
    for (j = 0; j < t->p; j++) {
        const bf_param *p = &t->param[j];
        printf("         %-6s %-22s unit %-3s range [%g, %g]", p->name,
               p->label, p->unit, p->min, p->max);
        if (p->fitted && p->grid_n > 0) {
            printf("  fitted on %g + %g i, i = 0..%zu\n", p->grid_lo,
                   p->grid_step, p->grid_n - 1);
        } else if (p->fitted) {
            printf("  fitted%s\n", p->linear ? ", linear (a scale)" : "");
        } else {
            printf("  input, default %g\n", p->value);
        }
    }
}

int bf_cmd_models(int argc, char **argv)
{
    bf_fresnel_kind f = BF_FRESNEL_DEFAULT;
    bf_smith_kind s = BF_SMITH_DEFAULT;
    size_t i;
    int a;
    for (a = 1; a < argc; a++) {
        int missing = 0;
        const char *v;
        int rc = BF_EXIT_OK;
        if (strcmp(argv[a], "-h") == 0 || strcmp(argv[a], "--help") == 0) {
            usage();
            return BF_EXIT_OK;
        }
        if ((v = option_value(argc, argv, &a, "--fresnel", &missing))
            != NULL) {
            rc = bf_cli_parse_fresnel("models ", v, &f);
        } else if ((v = option_value(argc, argv, &a, "--smith", &missing))
                   != NULL) {
            rc = bf_cli_parse_smith("models ", v, &s);
        } else if (missing) {
            return bf_cli_usage_fail(BF_EXIT_NOVALUE, "models ",
                                     "%s needs a value", argv[a]);
        } else {
            return bf_cli_usage_error("models ", "unexpected argument '%s'",
                                      argv[a]);
        }
        if (rc != BF_EXIT_OK) {
            return rc;
        }
    }
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        const char *why = NULL;
        const bf_model_type *shown = t;
        if (t->kind == BF_MODEL_SPECULAR) {
            shown = bf_model_specular_variant(t, f, s, &why);
            if (shown == NULL) {
                shown = t;
            }
        }
        printf("%-8s %s\n         implements %s\n", t->name, t->title,
               t->reference);
        if (t->kind == BF_MODEL_SPECULAR) {
            printf("         specular, sr^-1: NDF %s; masking %s; "
                   "Fresnel %s\n",
                   shown->ndf, shown->masking, shown->fresnel_term);
        }
        if (why != NULL) {
            printf("         (the --fresnel/--smith asked for: %s %s)\n",
                   t->name, why);
        }
        print_params(shown);
    }
    return BF_EXIT_OK;
}
