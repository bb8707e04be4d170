/* model_style.h: the plot style slot of each model (plot.h), the same in
 * every figure and run. Private: not installed. */
#ifndef BF_REPORT_MODEL_STYLE_H
#define BF_REPORT_MODEL_STYLE_H

#include "brdffit.h"

/* The style slot (< BF_PLOT_NSTYLES) of a model type, found by its name so
 * that variants (bf_model_variant) keep their base model's style: the
 * paper's six models get slots 0-5, which differ in colour, marker and
 * dash; every registry model gets a slot of its own. The one place that
 * maps models to styles. */
unsigned bf_report_model_style(const bf_model_type *type);

#endif
