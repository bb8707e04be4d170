/* cmd_models.c: `brdffit models` -- lists the model registry: names,
 * parameters with units, domains and grids, and the equations implemented. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

int bf_cmd_models(int argc, char **argv)
{
    size_t i;
    if (argc > 1) {
        if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
            puts("Usage: brdffit models\n\nLists every model: name, "
                 "parameters (unit, valid range, default, paper grid) and "
                 "the equations it implements.");
            return BF_EXIT_OK;
        }
        return bf_cli_usage_error("models ", "unexpected argument '%s'",
                                  argv[1]);
    }
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        size_t j;
        printf("%-8s %s\n         implements %s\n", t->name, t->title,
               t->reference);
        if (t->p == 0) {
            puts("         no parameter (after normalisation)");
        }
        for (j = 0; j < t->p; j++) {
            const bf_param *p = &t->param[j];
            printf("         %-6s %-16s unit %-3s range [%g, %g]", p->name,
                   p->label, p->unit, p->min, p->max);
            if (p->fitted) {
                printf("  fitted on %g + %g i, i = 0..%zu\n", p->grid_lo,
                       p->grid_step, p->grid_n - 1);
            } else {
                printf("  input, default %g\n", p->value);
            }
        }
    }
    return BF_EXIT_OK;
}
