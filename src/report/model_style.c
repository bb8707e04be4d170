/* model_style.c: the plot style slot of each model (model_style.h). */
#include "model_style.h"

#include <string.h>

#include "plot.h"

/* Registry names in slot order: the paper's scatter-plot models first
 * (Figures 3-6: ON, LFTG, VH-E, FC-E), then the rest of its six. */
static const char *const order[] = {"FC-E", "VH-E",    "ON",  "LFTG",
                                    "VH-G", "FC-G",    "BK-G", "BK-E",
                                    "LAMBERT", "WNO", "WNO-R"};

unsigned bf_report_model_style(const bf_model_type *type)
{
    size_t i;
    for (i = 0; i < sizeof order / sizeof *order; i++) {
        if (type != NULL && strcmp(type->name, order[i]) == 0) {
            return (unsigned)i;
        }
    }
    return BF_PLOT_NSTYLES - 1; /* a model added without a slot here */
}
