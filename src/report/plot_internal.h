/* plot_internal.h: what the figure writer's files share -- the style
 * slots' colours, markers and dash patterns (plot_style.c), text width
 * estimates, axis ticks and the layout of a figure in points
 * (plot_layout.c), all without PLplot; plot.c draws them. Private to
 * src/report. */
#ifndef BF_REPORT_PLOT_INTERNAL_H
#define BF_REPORT_PLOT_INTERNAL_H

#include <stddef.h>

#include "plot.h"

/* ==== styles (plot_style.c) ============================================ */

typedef enum {
    BF__MK_CIRCLE = 0,
    BF__MK_SQUARE,
    BF__MK_TRIANGLE,      /* pointing up */
    BF__MK_DIAMOND,
    BF__MK_TRIANGLE_DOWN,
    BF__MK_PENTAGON,
    BF__MK_HEXAGON,
    BF__MK_TRIANGLE_RIGHT,
    BF__MK_TRIANGLE_LEFT,
    BF__MK_STAR,          /* five points */
    BF__MK_OPEN_CIRCLE,   /* from here on drawn after the filled ones */
    BF__MK_OPEN_SQUARE,
    BF__MK_OPEN_TRIANGLE,
    BF__MK_OPEN_DIAMOND,
    BF__MK_PLUS,
    BF__MK_CROSS,
    BF__MK_OPEN_TRIANGLE_DOWN,
    BF__MK_OPEN_PENTAGON,
    BF__MK_OPEN_HEXAGON,
    BF__MK_OPEN_TRIANGLE_RIGHT,
    BF__MK_OPEN_TRIANGLE_LEFT,
    BF__NMARKERS
} bf__marker;

/* Dash patterns: on/off lengths in points, repeated; n = 0 is solid. */
typedef struct {
    size_t n;
    double len[6];
} bf__dash;

typedef struct {
    unsigned char rgb[3];
    const char *hex;
    bf__marker marker;
    size_t dash; /* index into bf__dashes */
} bf__style;

/* BF_PLOT_NSTYLES slots, then BF_PLOT_INK and BF_PLOT_REF. */
#define BF__NSLOTS (BF_PLOT_NSTYLES + 2)
extern const bf__style bf__styles[BF__NSLOTS];
#define BF__NDASHES 6
extern const bf__dash bf__dashes[BF__NDASHES];

/* The heat-map classes, darkest first (a sequential colour-blind-safe
 * ramp), and the light grey of empty cells. */
extern const unsigned char bf__class_rgb[BF_PLOT_NCLASSES][3];
extern const unsigned char bf__empty_rgb[3];
/* Classes dark enough for white text. */
#define BF__CLASS_DARK 2

/* The dash pattern a series is drawn with (its slot's or a forced one). */
const bf__dash *bf__series_dash(const bf_plot_series *s);

/* Outline of marker mk of radius r (points) around the origin into
 * dx, dy (capacity BF__MARKER_MAX), closed (the last vertex repeats the
 * first); open markers give the outer ring then the inner ring in the
 * opposite sense, so that a non-zero fill leaves the hole. Returns the
 * vertex count. */
#define BF__MARKER_MAX 64
size_t bf__marker_shape(bf__marker mk, double r, double *dx, double *dy);

/* ==== path geometry (plot_path.c), in page points ===================== */

/* A rectangle in points, origin at the bottom left of the page. */
typedef struct {
    double x0, y0, x1, y1;
} bf__box;


/* Outlines joined into one polygon (see plot_path.c); owns its arrays. */
typedef struct {
    double *x, *y;
    size_t n, cap;
    size_t *anchor;          /* where each outline starts */
    size_t n_anchor, cap_anchor;
    int failed;              /* an append ran out of memory (kept until
                                bf__poly_free: the drawing is incomplete) */
} bf__poly;

/* Appends the closed outline of n >= 3 points (closed here if it is not)
 * and the bridge to it. Returns 0, -1 when out of memory. */
int bf__poly_add(bf__poly *p, size_t n, const double *x, const double *y);
/* Appends the way back along the bridges: the polygon is then complete.
 * Returns 0, -1 when out of memory. */
int bf__poly_finish(bf__poly *p);
void bf__poly_clear(bf__poly *p);
void bf__poly_free(bf__poly *p);

/* Clips the polyline of n points to box b: the visible runs into ox, oy
 * (capacity 2 n), run r being points start[r] .. start[r + 1] - 1
 * (start: capacity n + 1). Returns the number of runs. */
size_t bf__clip_runs(const bf__box *b, size_t n, const double *x,
                     const double *y, double *ox, double *oy, size_t *start);

/* Drops, in place, the points of the polyline that lie within tol of the
 * simplified line (Douglas-Peucker; the ends are kept). Returns the
 * number of points left (n when n < 3), 0 when out of memory. */
size_t bf__simplify(size_t n, double *x, double *y, double tol);

/* Cuts the polyline of n points into the dashes of pattern d (solid: one
 * piece, the polyline): pieces into ox, oy, piece r being points start[r]
 * .. start[r + 1] - 1 (pieces of fewer than 2 points are to be skipped).
 * Capacities from bf__dash_capacity (points; pieces need half as many
 * plus one). Returns the number of pieces. */
size_t bf__dash_cut(const bf__dash *d, size_t n, const double *x,
                    const double *y, double *ox, double *oy, size_t *start);
size_t bf__dash_capacity(const bf__dash *d, size_t n, const double *x,
                         const double *y);

/* The outline of the polyline of n >= 2 points stroked with half-width h
 * and butt ends (mitred joins [PostScript §4.5]): 2 n points into ox, oy,
 * the left side forward then the right side back. Returns 2 n (0 for
 * n < 2). */
size_t bf__stroke_outline(size_t n, const double *x, const double *y,
                          double h, double *ox, double *oy);

/* ==== text and ticks (plot_layout.c) ================================== */

/* Estimated width of UTF-8 text in DejaVu Sans at size points (advance
 * widths by character class, rounded up). */
double bf__text_width(const char *s, double size);

/* Ticks of an axis: positions and their labels. */
#define BF__MAX_TICKS 72
typedef struct {
    size_t n;
    double v[BF__MAX_TICKS];
    char num[BF__MAX_TICKS][32];        /* numeric labels */
    const char *text[BF__MAX_TICKS];    /* the label: num, or a name */
} bf__ticks;

/* Ticks of [lo, hi]: every step (0: a round step giving 4 to 7 ticks), or
 * on a log axis the decades; with names, the n names at 1, 2, ..., n that
 * lie in the range. */
void bf__ticks_make(double lo, double hi, double step, int logy,
                    const char *const *names, size_t n_names,
                    bf__ticks *t);

/* ==== layout (plot_layout.c) =========================================== */

#define BF__MAX_PANELS 128
#define BF__MAX_ENTRIES 48

/* A legend entry: a series' key, or a cell class's box. */
typedef struct {
    const bf_plot_series *series; /* NULL for a cell class */
    int cls;                      /* the class, or -1 */
    const char *text;
    double x, y;                  /* the key's left end, text baseline
                                     centre height */
} bf__entry;

typedef struct {
    unsigned width, height;  /* page, points */
    double font;             /* tick and legend text, points */
    double label_font;       /* axis labels, points */
    double tick;             /* tick length, points */
    double pad;              /* gap between a tick and its number */
    bf__box axes[BF__MAX_PANELS];
    int xnum[BF__MAX_PANELS];    /* panel writes its x numbers */
    int ynum[BF__MAX_PANELS];
    bf__ticks xt[BF__MAX_PANELS];
    bf__ticks yt[BF__MAX_PANELS];
    double ynum_width[BF__MAX_PANELS]; /* widest y number, points */
    int xrot[BF__MAX_PANELS];  /* x names written upwards (too many to fit
                                  side by side) */
    double xnum_height[BF__MAX_PANELS]; /* height of the x numbers */
    double xlabel_x[BF__MAX_PANELS]; /* centre of the panel's x label:
                                        under its axes, moved to stay
                                        in its span (below) */
    double xlabel_size[BF__MAX_PANELS]; /* its size, points: label_font,
                                           smaller where it is wider than
                                           its span -- from half way to the
                                           axes on its left (the page's
                                           edge) to half way to those on
                                           its right */
    double polar_side;       /* polar panels: room beside the half-disc, */
    double polar_top;        /*   above it and below the surface line, */
    double polar_bottom;     /*   points */
    bf__box grid;            /* the union of the axes */
    double xlabel_y;         /* baseline-centre height of the shared x
                                label */
    double ylabel_x;         /* centre of the shared (rotated) y label */
    double col_label_y;      /* centre height of the column labels */
    int col_lines;           /* their lines: 0 (none), 1, or 2 (a label is
                                wider than the axes) */
    double row_label_x;      /* centre of the (rotated) row labels */
    bf__entry entry[BF__MAX_ENTRIES];
    size_t n_entries;
    double key_width;        /* length of a legend key line, points */
} bf__layout;

/* Checks fig (BF_EINVAL when invalid) and places everything. L is large
 * (allocate it). */
int bf__layout_make(const bf_plot_figure *fig, bf__layout *L);

#endif
