/* model_style.h: the plot style slot of each model (plot.h), the same in
 * every figure and run. Private: not installed. */
#ifndef BF_REPORT_MODEL_STYLE_H
#define BF_REPORT_MODEL_STYLE_H

#include "brdffit.h"

/* The style slot (< BF_PLOT_NSTYLES) of a model type: its own
 * bf_model_type.style, which variants (bf_model_variant) keep from their
 * base model. The paper's six models have slots 0-5, which differ in
 * colour, marker and dash; every registry model has a slot of its own
 * (tests/report/test_plot.c). */
unsigned bf_report_model_style(const bf_model_type *type);

#endif
