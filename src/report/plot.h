/* plot.h: figures for the report -- a small description of charts (panels
 * of line, point and bar series, box or polar axes) and one function that
 * draws a figure to PNG, SVG or PDF. The implementation, src/report/plot.c,
 * is the only file of the project that calls PLplot (STYLE §5), and it
 * lives in the separate library target brdffit_report, so the core
 * libbrdffit does not depend on PLplot. Private: not installed. */
#ifndef BF_REPORT_PLOT_H
#define BF_REPORT_PLOT_H

#include <stddef.h>

/* Output formats; each is drawn by PLplot's cairo driver of that name. */
typedef enum {
    BF_PLOT_PNG = 0, /* pngcairo: width x height pixels */
    BF_PLOT_SVG,     /* svgcairo: width x height points (1/72 inch) */
    BF_PLOT_PDF,     /* pdfcairo: one page of width x height points */
    BF_PLOT_NFORMATS
} bf_plot_format;

/* File extension of a format ("png", "svg", "pdf"), NULL if out of range. */
const char *bf_plot_format_ext(bf_plot_format fmt);

/* How a series is drawn. */
typedef enum {
    BF_SERIES_LINE = 0, /* a polyline; non-finite points break it */
    BF_SERIES_POINTS,   /* markers */
    BF_SERIES_LINEPOINTS, /* a polyline with a marker at each point */
    BF_SERIES_BARS      /* vertical bars from 0 to y, centred on x, with
                           the value written above each bar */
} bf_series_style;

/* Number of distinct colours and markers (indices wrap around). Colours
 * 0-8: blue, vermillion, green, reddish purple, orange, sky blue, brown,
 * olive, dark red (Okabe & Ito's colour-blind-safe set first); 9: black. */
#define BF_PLOT_NCOLORS 10
#define BF_PLOT_NMARKERS 6

/* One data series of a panel. Non-finite points are skipped. */
typedef struct {
    const double *x;   /* n abscissae (radians for polar panels) */
    const double *y;   /* n ordinates (the radius for polar panels) */
    size_t n;
    bf_series_style style;
    unsigned color;    /* palette index, modulo BF_PLOT_NCOLORS */
    unsigned marker;   /* marker index for points, modulo BF_PLOT_NMARKERS */
    int dashed;        /* lines: 1 for a dashed line */
    const char *label; /* legend text (UTF-8), NULL: not in the legend */
} bf_plot_series;

/* One panel (one set of axes). Texts are UTF-8. */
typedef struct {
    const char *title;
    const char *xlabel; /* box axes: the x-axis label with its unit */
    const char *ylabel; /* box axes: the y-axis label with its unit */
    double xmin, xmax;  /* box axes: the x range */
    double ymin, ymax;  /* the y range (polar: ymax is the outer radius) */
    int logy;           /* box axes: logarithmic y axis (y > 0 only) */
    int polar;          /* 1: polar half-plane; x is the angle from the
                           vertical (the surface normal), in radians, in
                           [-pi/2, pi/2]; y is the radius */
    int square;         /* box axes: square viewport (scatter plots) */
    int diagonal;       /* box axes: draw the line y = x */
    /* box axes: labels written at x = 1, 2, ..., n_xticks instead of
     * numbers (e.g. sample numbers); NULL for numeric labels */
    const char *const *xtick_labels;
    size_t n_xticks;
    int legend;         /* 0: none, 1: inside top left, 2: inside top
                           right, 3: inside bottom right, 4: outside
                           right (the axes are narrowed to make room) */
    const bf_plot_series *series;
    size_t n_series;
} bf_plot_panel;

/* A figure: nx x ny panels filled row by row. */
typedef struct {
    unsigned width;     /* pixels (PNG) or points (SVG, PDF) */
    unsigned height;
    size_t nx, ny;      /* panel grid; n_panels <= nx * ny */
    double text_scale;  /* character size factor (1 = PLplot's default) */
    const bf_plot_panel *panels;
    size_t n_panels;
} bf_plot_figure;

/* Largest accepted width or height, pixels or points. */
#define BF_PLOT_MAX_SIZE 10000u

/* Draws fig in format fmt into the file path (created or truncated).
 * Returns BF_OK; BF_EINVAL for an invalid description (size 0 or above
 * BF_PLOT_MAX_SIZE, no panel, more panels than nx * ny, an unknown
 * format, an empty range, a log axis with ymin <= 0, a series with n > 0 and
 * NULL arrays); BF_EIO when path cannot be written or the driver produced
 * an empty file. The caller should make sure path is writable first:
 * PLplot ends the process on an error it cannot recover from. Not
 * thread-safe (PLplot keeps global state). */
int bf_plot_write(const bf_plot_figure *fig, bf_plot_format fmt,
                  const char *path);

#endif
