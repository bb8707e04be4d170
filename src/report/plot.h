/* plot.h: figures for the report -- a small description of charts (a grid
 * of panels holding line, point, bar and interval series, heat-map cells,
 * box or polar axes) and one function that draws a figure to PNG, SVG or
 * PDF. Texts are UTF-8; "_{...}" and "^{...}" write a subscript and a
 * superscript (L_{max}, 10^{-3}). The implementation, src/report/plot.c, is the only file of the
 * project that calls PLplot (STYLE §5); src/report/plot_layout.c places the
 * panels, labels and legend (no PLplot) and src/report/plot_style.c holds
 * the style slots. They live in the separate library target
 * brdffit_report, so the core libbrdffit does not depend on PLplot.
 * Private: not installed.
 *
 * Sizes are in points (1/72 inch): a figure is drawn at the size it is
 * meant to be printed (BF_PLOT_SINGLE_COLUMN or BF_PLOT_DOUBLE_COLUMN
 * wide), text in BF_PLOT_FONT-point type. SVG and PDF pages are that many
 * points; PNG images have BF_PLOT_PNG_DPI pixels per inch. Figures carry no
 * title: what a figure shows belongs in its caption. */
#ifndef BF_REPORT_PLOT_H
#define BF_REPORT_PLOT_H

#include <stddef.h>

/* Output formats; each is drawn by PLplot's cairo driver of that name. */
typedef enum {
    BF_PLOT_PNG = 0, /* pngcairo, BF_PLOT_PNG_DPI pixels per inch */
    BF_PLOT_SVG,     /* svgcairo, width x height points */
    BF_PLOT_PDF,     /* pdfcairo, one page of width x height points */
    BF_PLOT_NFORMATS
} bf_plot_format;

/* File extension of a format ("png", "svg", "pdf"), NULL if out of range. */
const char *bf_plot_format_ext(bf_plot_format fmt);

/* Print widths journals ask for, points: 3.5 in and 7 in. */
#define BF_PLOT_SINGLE_COLUMN 252u
#define BF_PLOT_DOUBLE_COLUMN 504u
/* Tick labels and legend text, points (axis labels are one point larger). */
#define BF_PLOT_FONT 8.0
/* PNG resolution, pixels per inch. */
#define BF_PLOT_PNG_DPI 150

/* Pixels of a PNG side of the given points. */
unsigned bf_plot_png_pixels(unsigned points);

/* ==== styles =========================================================== */

/* Style slots: each has a colour (Okabe & Ito's colour-blind-safe set), a
 * marker and a dash pattern; no two slots share both colour and dash, and
 * every slot has its own marker, so series stay apart in colour, in grey
 * print and for colour-blind readers. */
#define BF_PLOT_NSTYLES 21
#define BF_PLOT_INK 21 /* measured data: black filled circles, solid */
#define BF_PLOT_REF 22 /* reference lines (diagonal, threshold): grey */

/* The colour of a style slot as "#rrggbb" (static storage), for pages
 * that describe a figure; NULL when out of range. */
const char *bf_plot_style_hex(unsigned style);

/* Name of a style slot's marker ("filled circle", ...) and of its line
 * pattern ("solid", "dashed", ...), NULL when out of range. */
const char *bf_plot_style_marker(unsigned style);
const char *bf_plot_style_dash(unsigned style);

/* ==== figure description =============================================== */

/* How a series is drawn. */
typedef enum {
    BF_SERIES_LINE = 0, /* a polyline in the slot's dash pattern; non-finite
                           points break it; with mark_every > 0 also the
                           slot's marker at every mark_every-th point */
    BF_SERIES_POINTS,   /* the slot's markers */
    BF_SERIES_BARS,     /* vertical bars from 0 to y, centred on x, with the
                           value written above each bar */
    BF_SERIES_INTERVALS, /* horizontal segments from x to x2 at height y,
                           with end ticks (confidence intervals) */
    BF_SERIES_ERRORBARS /* vertical segments from y to y2 at x, with end
                           ticks (error bars; a POINTS series marks the
                           estimates) */
} bf_series_kind;

/* Line patterns a series may force instead of its slot's. */
enum { BF_DASH_SLOT = 0, BF_DASH_SOLID, BF_DASH_DASHED, BF_DASH_DOTTED };

/* One data series of a panel. Non-finite points are skipped. */
typedef struct {
    bf_series_kind kind;
    const double *x;    /* n abscissae (radians for polar panels) */
    const double *y;    /* n ordinates (the radius for polar panels) */
    const double *x2;   /* INTERVALS: the n right ends */
    const double *y2;   /* ERRORBARS: the n upper ends */
    const unsigned *open; /* INTERVALS (ERRORBARS): bit 0 (1) set: the left
                             (right) end -- the lower (upper) -- is open:
                             cut at a bound, drawn without its end tick;
                             NULL: all closed */
    const double *gap_lo; /* INTERVALS: the n gaps of split intervals, */
    const double *gap_hi; /* drawn as x..gap_lo and gap_hi..x2 (NaN or
                             NULL: none) */
    size_t n;
    unsigned style;     /* style slot (< BF_PLOT_NSTYLES, or BF_PLOT_INK,
                           BF_PLOT_REF) */
    int dash;           /* BF_DASH_*: the slot's pattern or a forced one */
    double weight;      /* line width factor; 0 means 1 */
    size_t mark_every;  /* LINE: a marker every mark_every points (0: no
                           marker) */
    const char *label;  /* legend text (UTF-8), NULL: not in the legend */
} bf_plot_series;

/* Heat-map cells: nx x ny cells, cell (c, r) centred at x = c + 1,
 * y = r + 1, filled by colour class (a sequential colour-blind-safe
 * ramp, class 0 darkest), with an optional text. */
#define BF_PLOT_NCLASSES 5
typedef struct {
    size_t nx, ny;
    const int *cls;            /* nx * ny classes, row-major (r * nx + c);
                                  -1: an empty (light grey) cell */
    const char *const *text;   /* nx * ny texts, or NULL */
    size_t n_classes;          /* <= BF_PLOT_NCLASSES */
    const char *const *class_label; /* legend text of each class */
} bf_plot_cells;

/* One panel (one set of axes). Texts are UTF-8. */
typedef struct {
    double xmin, xmax;  /* box axes: the x range */
    double ymin, ymax;  /* the y range (polar: ymax is the outer radius) */
    double xtick, ytick;/* major tick spacing; 0: chosen from the range */
    int logy;           /* box axes: logarithmic y axis (ymin > 0) */
    int polar;          /* 1: polar half-plane; x is the angle from the
                           vertical (the surface normal), in radians, in
                           [-pi/2, pi/2], spokes every 30 degrees; y is the
                           radius */
    int diagonal;       /* box axes: draw the line y = x */
    const char *xlabel; /* the panel's own axis labels, with their units */
    const char *ylabel; /*   (NULL: the figure's shared ones) */
    const char *note;   /* short text inside the top left corner */
    /* box axes: labels written at x = 1, 2, ..., n_xticks (y = 1, ...)
     * instead of numbers; NULL for numeric labels */
    const char *const *xtick_labels;
    size_t n_xticks;
    const char *const *ytick_labels;
    size_t n_yticks;
    const bf_plot_cells *cells; /* heat map, or NULL */
    const bf_plot_series *series;
    size_t n_series;
} bf_plot_panel;

/* Where the figure's one legend goes. Its entries are the labelled series
 * of every panel (each label once) and the cell classes. */
typedef enum {
    BF_LEGEND_NONE = 0,
    BF_LEGEND_TOP,      /* above the panels, in rows */
    BF_LEGEND_BOTTOM,   /* below the shared x label, in rows */
    BF_LEGEND_RIGHT     /* right of the panels, one entry per line */
} bf_legend_place;

/* A figure: nx x ny panels filled row by row, with equal axes. */
typedef struct {
    unsigned width;     /* points */
    unsigned height;    /* points; 0: from width and aspect */
    double aspect;      /* axes height / width (1 for scatter plots; polar
                           panels need about 0.55); 0: fill the cell */
    double font;        /* text size, points; 0: BF_PLOT_FONT */
    size_t nx, ny;
    int share_x;        /* the columns share x: numbers on the bottom row */
    int share_y;        /* the rows share y: numbers on the left column */
    const char *xlabel; /* shared axis labels (written once), or NULL */
    const char *ylabel;
    const char *const *col_labels; /* nx texts above the columns, or NULL */
    const char *const *row_labels; /* ny texts right of the rows, or NULL */
    bf_legend_place legend;
    const bf_plot_panel *panels;
    size_t n_panels;
} bf_plot_figure;

/* Largest accepted width or height, points. */
#define BF_PLOT_MAX_SIZE 2000u
/* A figure fits a page: its height is at most BF_PLOT_MAX_TALL times its
 * width (a taller description is invalid). */
#define BF_PLOT_MAX_TALL 1.5

/* The size fig is drawn at, points: its width, and its height (computed
 * from the width and the aspect when fig->height is 0). BF_EINVAL for an
 * invalid description (as bf_plot_write). */
int bf_plot_size(const bf_plot_figure *fig, unsigned *width,
                 unsigned *height);

/* 1 when fig lays out (bf_plot_size gives BF_OK: within BF_PLOT_MAX_SIZE
 * and BF_PLOT_MAX_TALL) with axes at least min_axes points wide, else 0. */
int bf_plot_fits(const bf_plot_figure *fig, double min_axes);

/* Re-flows the n_panels panels of fig (filled row by row, each labelled by
 * its own note, not by column or row labels) into the grid of the fewest
 * rows whose axes are at least min_axes points wide and that fits the
 * page (bf_plot_fits); when no grid has axes that wide, into the one with
 * the widest axes that fits. Sets fig->nx and fig->ny. BF_OK, BF_EINVAL
 * when no grid fits, BF_ENOMEM. */
int bf_plot_flow(bf_plot_figure *fig, double min_axes);

/* Draws fig in format fmt into the file path (created or truncated).
 * Returns BF_OK; BF_EINVAL for an invalid description (width 0, a size
 * above BF_PLOT_MAX_SIZE, a height above BF_PLOT_MAX_TALL times the
 * width, no panel, more panels than nx * ny, an unknown
 * format or style, an empty range, a log axis with ymin <= 0, a series
 * with n > 0 and NULL arrays, cells without classes); BF_EIO when path
 * cannot be written or the driver produced an empty file; BF_ENOMEM when
 * memory ran out (the file is then incomplete: the caller drops it). The same
 * description gives the same bytes in every format (the PDF's creation
 * date, which cairo writes, is blanked). Not thread-safe (PLplot keeps
 * global state): draw in parallel from separate processes. */
int bf_plot_write(const bf_plot_figure *fig, bf_plot_format fmt,
                  const char *path);

#endif
