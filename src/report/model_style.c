/* model_style.c: the plot style slot of each model (model_style.h). */
#include "model_style.h"

#include "plot.h"

unsigned bf_report_model_style(const bf_model_type *type)
{
    /* The slot is the model type's own (bf_model_type.style), which a
     * variant (bf_model_variant) copies from its base model; a type made
     * outside the library with a slot out of range gets the last one. */
    if (type == NULL || type->style >= BF_PLOT_NSTYLES) {
        return BF_PLOT_NSTYLES - 1;
    }
    return type->style;
}
