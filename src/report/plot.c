/* plot.c: draws report figures (plot.h) with PLplot's cairo drivers --
 * pngcairo, svgcairo and pdfcairo -- at the places plot_layout.c computed.
 * The only file of the project that calls PLplot (STYLE §5).
 *
 * Everything is drawn in points on a page of width x height points (PNG:
 * BF_PLOT_PNG_DPI / 72 pixels per point). Axes, ticks and texts are drawn
 * in page coordinates; data series in each panel's own window, so PLplot
 * clips them at the axes. Markers are polygons, not glyphs: in SVG and PDF
 * all markers of a series are one filled path (PLplot's cairo driver then
 * fills without stroking, graphics anti-aliasing being off, which vector
 * formats do not use), and dashes are drawn here, one path per dash.
 *
 * References:
 *   [1] The PLplot Plotting Library, version 5.15 reference manual
 *       (plinit/plend, plvpor, plwind, plline, plfill, plptex, plschr,
 *       plscmap0n, plsetopt and the cairo device driver options).
 *   [2] ISO 32000-1:2008 (PDF 1.7), §14.3.3: the document information
 *       dictionary's entries are optional (the creation date is blanked).
 *
 * PNG figures are drawn by the memcairo driver into an RGB buffer and
 * written by png.c as palette images (a third of pngcairo's size). */
#include "plot.h"

#include <errno.h>
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "brdffit.h"
#include "plot_internal.h"
#include "png.h"

/* PNG is drawn into memory (memcairo) and written by png.c. */
static const char *const devices[BF_PLOT_NFORMATS] = {"memcairo", "svgcairo",
                                                      "pdfcairo"};
static const char *const extensions[BF_PLOT_NFORMATS] = {"png", "svg",
                                                         "pdf"};

/* PLplot's cairo driver sets text of character height h mm in a font of
 * h * PT_PER_MM points (measured on its SVG output: 96 / 25.4). */
#define PT_PER_MM (96.0 / 25.4)

/* Colour map 0 (PLplot's indices). */
enum {
    COL_BG = 0,      /* white */
    COL_INK = 1,     /* black */
    COL_WHITE = 2,
    COL_EMPTY = 3,   /* empty heat-map cells */
    COL_SLOT = 4,    /* the BF__NSLOTS style slots */
    COL_CLASS = COL_SLOT + BF__NSLOTS,
    NCOL = COL_CLASS + BF_PLOT_NCLASSES
};

/* Line widths and marker sizes, points at print size. */
#define W_CURVE 1.0     /* data lines */
#define W_FRAME 0.6     /* axes and ticks */
#define W_GRID 0.4      /* polar rings and spokes */
#define W_FILL 0.25     /* the outline PNG fills get (anti-aliasing) */
#define MARKER_R 1.9    /* marker radius */
#define CAP 2.0         /* half-height of an interval's end ticks */
#define BAR_WIDTH 0.62  /* bars, in x units (bars sit on integers) */
#define BAR_LABEL_GAP 3.0 /* between a bar (or the axis) and its value */
#define CELL_SEP 0.4    /* white gap around heat-map cells */
#define SIMPLIFY_TOL 0.02 /* vector formats: points closer than this to the
                             line are dropped (a fiftieth of a point) */
/* Polar panels: rings at a round step giving at most POLAR_RINGS of
 * them, spokes every POLAR_STEP_DEG. */
#define POLAR_RINGS 4.5
#define POLAR_STEP_DEG 30
#define POLAR_ARC_POINTS 121

const char *bf_plot_format_ext(bf_plot_format fmt)
{
    return (unsigned)fmt < BF_PLOT_NFORMATS ? extensions[fmt] : NULL;
}

/* ==== drawing state ====================================================== */

/* One render: the figure, its layout and the device scale. */
typedef struct {
    const bf_plot_figure *fig;
    const bf__layout *L;
    bf_plot_format fmt;
    double unit;   /* device units per point */
    double *wx;    /* scratch: n + 2 window coordinates */
    double *wy;
    double *px;    /* scratch: the same in points */
    double *py;
    bf__poly poly; /* outlines joined into one polygon (vector formats) */
    int failed;    /* a drawing step ran out of memory: the figure is
                      incomplete (bf_plot_write returns BF_ENOMEM) */
} ctx_t;

/* The current panel: its axes (points) and window (data after the log or
 * polar mapping). */
typedef struct {
    const bf_plot_panel *p;
    bf__box box;
    double wx0, wx1, wy0, wy1;
} view_t;

static void color(int idx)
{
    plcol0((PLINT)idx);
}

static void width(const ctx_t *c, double w)
{
    plwidth(w * c->unit);
}

/* Copies s into buf for PLplot: its escape character '#' doubled, so
 * user text (sample names) is drawn as written, and the markup of plot.h
 * -- _{sub} and ^{sup} -- turned into PLplot's #d...#u and #u...#d. */
static const char *esc(const char *s, char *buf, size_t len)
{
    size_t j = 0;
    int level = 0; /* +1 in a subscript, -1 in a superscript */
    if (s == NULL) {
        s = "";
    }
    for (; *s != '\0' && j + 3 < len; s++) {
        if ((s[0] == '_' || s[0] == '^') && s[1] == '{' && level == 0) {
            level = s[0] == '_' ? 1 : -1;
            buf[j++] = '#';
            buf[j++] = level > 0 ? 'd' : 'u';
            s++;
            continue;
        }
        if (s[0] == '}' && level != 0) {
            buf[j++] = '#';
            buf[j++] = level > 0 ? 'u' : 'd';
            level = 0;
            continue;
        }
        if (*s == '#') {
            buf[j++] = '#';
        }
        buf[j++] = *s;
    }
    if (level != 0 && j + 2 < len) { /* an unclosed script ends here */
        buf[j++] = '#';
        buf[j++] = level > 0 ? 'u' : 'd';
    }
    buf[j] = '\0';
    return buf;
}

/* The whole page, in points. */
static void page_view(const ctx_t *c)
{
    plvpor(0.0, 1.0, 0.0, 1.0);
    plwind(0.0, (double)c->L->width, 0.0, (double)c->L->height);
}

/* The panel's axes and window (PLplot clips to them). */
static void panel_view(const ctx_t *c, const view_t *v)
{
    plvpor(v->box.x0 / c->L->width, v->box.x1 / c->L->width,
           v->box.y0 / c->L->height, v->box.y1 / c->L->height);
    plwind(v->wx0, v->wx1, v->wy0, v->wy1);
}

/* Text of size pt at (x, y) in page points, at angle deg, the reference
 * point at fraction just along the text and at its middle height. */
static void text(const ctx_t *c, double x, double y, double deg, double just,
                 double size, const char *s)
{
    char buf[512];
    double a = deg * M_PI / 180.0;
    if (s == NULL || s[0] == '\0') {
        return;
    }
    plschr(size * c->unit / PT_PER_MM, 1.0);
    plptex(x, y, cos(a), sin(a), just, esc(s, buf, sizeof buf));
}

/* ==== coordinates ======================================================== */

static void to_page(const view_t *v, double wx, double wy, double *px,
                    double *py)
{
    *px = v->box.x0 + (wx - v->wx0) / (v->wx1 - v->wx0) *
                          (v->box.x1 - v->box.x0);
    *py = v->box.y0 + (wy - v->wy0) / (v->wy1 - v->wy0) *
                          (v->box.y1 - v->box.y0);
}

static void to_window(const view_t *v, double px, double py, double *wx,
                      double *wy)
{
    *wx = v->wx0 + (px - v->box.x0) / (v->box.x1 - v->box.x0) *
                       (v->wx1 - v->wx0);
    *wy = v->wy0 + (py - v->box.y0) / (v->box.y1 - v->box.y0) *
                       (v->wy1 - v->wy0);
}

/* Data to window: log10 of y on log axes; on polar panels the angle from
 * the vertical x and the radius y (NaN beyond the outer radius). */
static void to_win(const bf_plot_panel *p, double x, double y, double *wx,
                   double *wy)
{
    if (p->polar) {
        if (!(y >= 0.0) || y > p->ymax || !isfinite(x)) {
            *wx = *wy = NAN;
        } else {
            *wx = y * sin(x);
            *wy = y * cos(x);
        }
    } else {
        *wx = x;
        *wy = p->logy ? (y > 0.0 ? log10(y) : NAN) : y;
    }
}

/* Whether the window point lies in the window (markers are drawn whole,
 * unclipped, when their centre does). */
static int in_window(const view_t *v, double wx, double wy)
{
    double ex = 1e-9 * (v->wx1 - v->wx0);
    double ey = 1e-9 * (v->wy1 - v->wy0);
    return wx >= v->wx0 - ex && wx <= v->wx1 + ex && wy >= v->wy0 - ey &&
           wy <= v->wy1 + ey;
}

static void view_make(const ctx_t *c, size_t i, view_t *v)
{
    const bf_plot_panel *p = &c->fig->panels[i];
    v->p = p;
    v->box = c->L->axes[i];
    if (p->polar) {
        /* the outer radius R of the half-disc fills the axes' width
         * less the room of the labels (plot_layout.c) */
        double Rpt = (v->box.x1 - v->box.x0) / 2 - c->L->polar_side;
        double k = p->ymax / Rpt; /* data units per point */
        double cx = (v->box.x1 - v->box.x0) / 2;
        v->wx0 = -cx * k;
        v->wx1 = cx * k;
        v->wy0 = -c->L->polar_bottom * k;
        v->wy1 = v->wy0 + (v->box.y1 - v->box.y0) * k;
    } else {
        v->wx0 = p->xmin;
        v->wx1 = p->xmax;
        v->wy0 = p->logy ? log10(p->ymin) : p->ymin;
        v->wy1 = p->logy ? log10(p->ymax) : p->ymax;
    }
}

/* ==== lines ============================================================== */

/* Fills the outline of n points in page coordinates (page view). */
static void fill_page(size_t n, const double *x, const double *y)
{
    if (n >= 3) {
        plfill((PLINT)n, x, y);
    }
}

/* Fills the joined outlines of c->poly (page view) and empties it. */
static void fill_poly(ctx_t *c)
{
    if (bf__poly_finish(&c->poly) == 0) {
        fill_page(c->poly.n, c->poly.x, c->poly.y);
    }
    bf__poly_clear(&c->poly);
}

/* Draws the polyline of n points (window coordinates of view v, all
 * finite), of width w points, dashed by d. In the vector formats points
 * closer than SIMPLIFY_TOL to the line through their neighbours are
 * dropped first (Douglas-Peucker, in points). Solid: one polyline (PLplot
 * clips it at the axes). Dashed, in SVG: clipped to the axes here, each
 * dash outlined as a polygon (butt ends) and added to c->poly, which the
 * caller fills once for the series -- one path for all its dashes (SVG
 * pays some 250 bytes a path). Dashed, in PDF and PNG: each dash a
 * polyline of at least 3 points (PLplot's cairo driver gives 2-point lines
 * round caps and longer ones butt caps: every dash gets butt caps, as the
 * outlines have). */
static void line_run(ctx_t *c, const view_t *v, size_t n, const double *wx,
                     const double *wy, const bf__dash *d, double w)
{
    size_t cap;
    double *px = NULL;
    double *py = NULL;
    double *cx = NULL;
    double *cy = NULL;
    size_t *rs = NULL;
    size_t *ps = NULL;
    double *qx = NULL;
    double *qy = NULL;
    size_t runs;
    size_t base;
    size_t r;
    size_t k;
    if (n < 2) {
        return;
    }
    px = malloc(2 * n * sizeof *px);
    py = malloc(2 * n * sizeof *py);
    rs = malloc((n + 1) * sizeof *rs);
    if (px == NULL || py == NULL || rs == NULL) {
        c->failed = 1;
        goto done;
    }
    base = n; /* the page points at [n, 2n); runs are built below them */
    for (k = 0; k < n; k++) {
        to_page(v, wx[k], wy[k], &px[base + k], &py[base + k]);
    }
    if (c->fmt != BF_PLOT_PNG) {
        n = bf__simplify(n, px + base, py + base, SIMPLIFY_TOL);
        if (n == 0) {
            c->failed = 1;
            goto done;
        }
    }
    if (d->n == 0) {
        for (k = 0; k < n; k++) {
            to_window(v, px[base + k], py[base + k], &px[k], &py[k]);
        }
        plline((PLINT)n, px, py);
        goto done;
    }
    if (c->fmt != BF_PLOT_SVG) { /* one run; PLplot clips */
        memmove(px, px + base, n * sizeof *px);
        memmove(py, py + base, n * sizeof *py);
        rs[0] = 0;
        rs[1] = n;
        runs = 1;
    } else {
        runs = bf__clip_runs(&v->box, n, px + base, py + base, px, py, rs);
    }
    cap = bf__dash_capacity(d, rs[runs], px, py) + 4;
    cx = malloc(cap * sizeof *cx);
    cy = malloc(cap * sizeof *cy);
    ps = malloc(cap * sizeof *ps);
    qx = malloc(2 * cap * sizeof *qx);
    qy = malloc(2 * cap * sizeof *qy);
    if (cx == NULL || cy == NULL || ps == NULL || qx == NULL || qy == NULL) {
        c->failed = 1;
        goto done;
    }
    for (r = 0; r < runs; r++) {
        size_t pieces = bf__dash_cut(d, rs[r + 1] - rs[r], px + rs[r],
                                     py + rs[r], cx, cy, ps);
        size_t q;
        for (q = 0; q < pieces; q++) {
            size_t m = ps[q + 1] - ps[q];
            const double *x = cx + ps[q];
            const double *y = cy + ps[q];
            if (m < 2) {
                continue;
            }
            if (c->fmt == BF_PLOT_SVG) {
                size_t o = bf__stroke_outline(m, x, y, w / 2, qx, qy);
                if (bf__poly_add(&c->poly, o, qx, qy) != 0) {
                    goto done;
                }
                continue;
            }
            for (k = 0; k < m; k++) {
                to_window(v, x[k], y[k], &qx[k], &qy[k]);
            }
            if (m == 2) { /* its midpoint: a polyline, butt caps */
                qx[2] = qx[1];
                qy[2] = qy[1];
                qx[1] = (qx[0] + qx[2]) / 2;
                qy[1] = (qy[0] + qy[2]) / 2;
                m = 3;
            }
            plline((PLINT)m, qx, qy);
        }
    }
done:
    free(px);
    free(py);
    free(rs);
    free(cx);
    free(cy);
    free(ps);
    free(qx);
    free(qy);
}

/* The width of series s's lines, points. */
static double line_width(const bf_plot_series *s)
{
    return W_CURVE * (s->weight > 0.0 ? s->weight : 1.0);
}

/* Starts drawing series s's lines (panel view, its colour and width). */
static void lines_begin(ctx_t *c, const bf_plot_series *s)
{
    color(COL_SLOT + (int)s->style);
    width(c, line_width(s));
    bf__poly_clear(&c->poly);
}

/* Ends them: fills the outlines of the dashes collected (vector formats),
 * back in the panel view. */
static void lines_end(ctx_t *c, const view_t *v)
{
    if (c->poly.n_anchor > 0) {
        page_view(c);
        width(c, W_FILL);
        fill_poly(c);
        panel_view(c, v);
    }
}

/* Draws series s as lines: its finite runs. */
static void series_line(ctx_t *c, const view_t *v, const bf_plot_series *s)
{
    const bf__dash *d = bf__series_dash(s);
    double *rx = malloc((s->n + 1) * sizeof *rx);
    double *ry = malloc((s->n + 1) * sizeof *ry);
    size_t i = 0;
    if (rx == NULL || ry == NULL) {
        free(rx);
        free(ry);
        c->failed = 1;
        return;
    }
    lines_begin(c, s);
    while (i < s->n) {
        size_t m = 0;
        while (i < s->n) {
            double wx;
            double wy;
            to_win(v->p, s->x[i], s->y[i], &wx, &wy);
            i++;
            if (!isfinite(wx) || !isfinite(wy)) {
                break;
            }
            rx[m] = wx;
            ry[m] = wy;
            m++;
        }
        line_run(c, v, m, rx, ry, d, line_width(s));
    }
    lines_end(c, v);
    free(rx);
    free(ry);
}

/* ==== markers ============================================================ */

/* Draws markers mk of radius r (points) at the n page points (x, y), in
 * the current colour, page view. PNG: one filled polygon each. SVG and
 * PDF: one polygon for them all (bf__poly). */
static void markers_at(ctx_t *c, bf__marker mk, double r, size_t n,
                       const double *x, const double *y)
{
    double dx[BF__MARKER_MAX];
    double dy[BF__MARKER_MAX];
    double ox[BF__MARKER_MAX];
    double oy[BF__MARKER_MAX];
    size_t m = bf__marker_shape(mk, r, dx, dy);
    size_t i;
    size_t k;
    width(c, W_FILL);
    bf__poly_clear(&c->poly);
    for (i = 0; i < n; i++) {
        for (k = 0; k < m; k++) {
            ox[k] = x[i] + dx[k];
            oy[k] = y[i] + dy[k];
        }
        if (c->fmt == BF_PLOT_PNG) {
            fill_page(m, ox, oy);
        } else if (bf__poly_add(&c->poly, m, ox, oy) != 0) {
            break;
        }
    }
    if (c->fmt != BF_PLOT_PNG) {
        fill_poly(c);
    }
}

static double marker_r(const bf_plot_series *s)
{
    return MARKER_R * (s->weight > 0.0 ? s->weight : 1.0);
}

/* The markers of series s (every mark_every-th point of a line, starting
 * at an offset that depends on the slot, so neighbouring curves' markers
 * do not coincide). */
static void series_markers(ctx_t *c, const view_t *v,
                           const bf_plot_series *s)
{
    size_t step = s->kind == BF_SERIES_LINE ? s->mark_every : 1;
    size_t first = step > 1 ? (step / 2 + 5 * (size_t)s->style) % step : 0;
    size_t n = 0;
    size_t i;
    if (step == 0) {
        return;
    }
    for (i = first; i < s->n; i += step) {
        double wx;
        double wy;
        to_win(v->p, s->x[i], s->y[i], &wx, &wy);
        if (isfinite(wx) && isfinite(wy) && in_window(v, wx, wy)) {
            to_page(v, wx, wy, &c->px[n], &c->py[n]);
            n++;
        }
    }
    page_view(c);
    color(COL_SLOT + (int)s->style);
    markers_at(c, bf__styles[s->style].marker, marker_r(s), n, c->px, c->py);
    panel_view(c, v);
}

/* ==== bars, intervals, cells ============================================ */

static void series_bars(ctx_t *c, const view_t *v, const bf_plot_series *s)
{
    const bf__layout *L = c->L;
    size_t i;
    for (i = 0; i < s->n; i++) {
        double bx[4];
        double by[4];
        double wy;
        double px;
        double py;
        char label[32];
        if (!isfinite(s->x[i]) || !isfinite(s->y[i])) {
            continue;
        }
        wy = v->p->logy ? log10(s->y[i]) : s->y[i];
        bx[0] = bx[1] = s->x[i] - BAR_WIDTH / 2;
        bx[2] = bx[3] = s->x[i] + BAR_WIDTH / 2;
        by[0] = by[3] = v->wy0;
        by[1] = by[2] = wy;
        if (wy > v->wy0) {
            color(COL_SLOT + (int)s->style);
            width(c, W_FILL);
            plfill(4, bx, by);
        }
        /* the count above the bar, clear of it and of the axis */
        to_page(v, s->x[i], fmax(wy, v->wy0), &px, &py);
        snprintf(label, sizeof label, "%g", s->y[i]);
        page_view(c);
        color(COL_INK);
        text(c, px, py + BAR_LABEL_GAP + 0.5 * L->font * 0.75, 0, 0.5,
             L->font, label);
        panel_view(c, v);
    }
}

/* One segment of series_intervals from (wx[0], wy[0]) to (wx[1], wy[1])
 * (window coordinates), with an end tick at end e unless bit e of open. */
static void interval_segment(ctx_t *c, const view_t *v,
                             const bf_plot_series *s, const double *wx,
                             const double *wy, unsigned open)
{
    int vertical = s->kind == BF_SERIES_ERRORBARS;
    int e;
    double x[2] = {wx[0], wx[1]};
    double y[2] = {wy[0], wy[1]};
    line_run(c, v, 2, x, y, bf__series_dash(s), line_width(s));
    for (e = 0; e < 2; e++) { /* end ticks, where the end is shown */
        double px;
        double py;
        double tx[2];
        double ty[2];
        if (wx[e] < v->wx0 || wx[e] > v->wx1 || wy[e] < v->wy0 ||
            wy[e] > v->wy1 || ((open >> e) & 1u)) {
            continue;
        }
        to_page(v, wx[e], wy[e], &px, &py);
        to_window(v, px - (vertical ? CAP : 0.0),
                  py - (vertical ? 0.0 : CAP), &tx[0], &ty[0]);
        to_window(v, px + (vertical ? CAP : 0.0),
                  py + (vertical ? 0.0 : CAP), &tx[1], &ty[1]);
        plline(2, tx, ty);
    }
}

/* INTERVALS (horizontal, from x to x2 at y; a split one as two segments
 * either side of its gap) and ERRORBARS (vertical, from y to y2 at x):
 * segments with end ticks across them. */
static void series_intervals(ctx_t *c, const view_t *v,
                             const bf_plot_series *s)
{
    int vertical = s->kind == BF_SERIES_ERRORBARS;
    size_t i;
    lines_begin(c, s);
    for (i = 0; i < s->n; i++) {
        double wx[2];
        double wy[2];
        unsigned open = s->open != NULL ? s->open[i] & 3u : 0u;
        to_win(v->p, s->x[i], s->y[i], &wx[0], &wy[0]);
        to_win(v->p, vertical ? s->x[i] : s->x2[i],
               vertical ? s->y2[i] : s->y[i], &wx[1], &wy[1]);
        if (!isfinite(wx[0]) || !isfinite(wx[1]) || !isfinite(wy[0]) ||
            !isfinite(wy[1])) {
            continue;
        }
        if (!vertical && s->gap_lo != NULL && s->gap_hi != NULL &&
            isfinite(s->gap_lo[i]) && isfinite(s->gap_hi[i])) {
            double gx[2];
            double gy[2];
            to_win(v->p, s->gap_lo[i], s->y[i], &gx[0], &gy[0]);
            to_win(v->p, s->gap_hi[i], s->y[i], &gx[1], &gy[1]);
            if (isfinite(gx[0]) && isfinite(gx[1])) {
                double ax[2] = {wx[0], gx[0]};
                double bx[2] = {gx[1], wx[1]};
                interval_segment(c, v, s, ax, wy, open & 1u);
                interval_segment(c, v, s, bx, wy, open & 2u);
                continue;
            }
        }
        interval_segment(c, v, s, wx, wy, open);
    }
    lines_end(c, v);
}

static void draw_cells(ctx_t *c, const view_t *v)
{
    const bf_plot_cells *h = v->p->cells;
    const bf__layout *L = c->L;
    size_t r;
    size_t k;
    for (r = 0; r < h->ny; r++) {
        for (k = 0; k < h->nx; k++) {
            int cls = h->cls[r * h->nx + k];
            double x0;
            double y0;
            double x1;
            double y1;
            double bx[4];
            double by[4];
            const char *t = h->text != NULL ? h->text[r * h->nx + k] : NULL;
            to_page(v, (double)k + 0.5, (double)r + 0.5, &x0, &y0);
            to_page(v, (double)k + 1.5, (double)r + 1.5, &x1, &y1);
            bx[0] = bx[1] = x0 + CELL_SEP;
            bx[2] = bx[3] = x1 - CELL_SEP;
            by[0] = by[3] = y0 + CELL_SEP;
            by[1] = by[2] = y1 - CELL_SEP;
            page_view(c);
            color(cls >= 0 && (size_t)cls < h->n_classes ? COL_CLASS + cls
                                                          : COL_EMPTY);
            width(c, W_FILL);
            fill_page(4, bx, by);
            if (t != NULL) {
                color(cls >= 0 && cls < BF__CLASS_DARK ? COL_WHITE : COL_INK);
                text(c, (x0 + x1) / 2, (y0 + y1) / 2, 0, 0.5, L->font - 1.0,
                     t);
            }
        }
    }
    panel_view(c, v);
}

/* ==== axes =============================================================== */

/* The frame and the outward ticks of box axes as one polyline (page
 * view): along the bottom with a tick at each x tick, up the right side,
 * along the top, down the left side with a tick at each y tick. */
static void frame(ctx_t *c, size_t i, const view_t *v)
{
    const bf__layout *L = c->L;
    const bf__ticks *xt = &L->xt[i];
    const bf__ticks *yt = &L->yt[i];
    double *x = c->px;
    double *y = c->py;
    size_t n = 0;
    size_t k;
    x[n] = v->box.x0;
    y[n++] = v->box.y0;
    for (k = 0; k < xt->n; k++) {
        double px;
        double py;
        to_page(v, xt->v[k], v->wy0, &px, &py);
        x[n] = px;
        y[n++] = v->box.y0;
        x[n] = px;
        y[n++] = v->box.y0 - L->tick;
        x[n] = px;
        y[n++] = v->box.y0;
    }
    x[n] = v->box.x1;
    y[n++] = v->box.y0;
    x[n] = v->box.x1;
    y[n++] = v->box.y1;
    x[n] = v->box.x0;
    y[n++] = v->box.y1;
    for (k = yt->n; k-- > 0;) {
        double px;
        double py;
        double wy = v->p->logy ? log10(yt->v[k]) : yt->v[k];
        to_page(v, v->wx0, wy, &px, &py);
        x[n] = v->box.x0;
        y[n++] = py;
        x[n] = v->box.x0 - L->tick;
        y[n++] = py;
        x[n] = v->box.x0;
        y[n++] = py;
    }
    x[n] = v->box.x0;
    y[n++] = v->box.y0;
    color(COL_INK);
    width(c, W_FRAME);
    plline((PLINT)n, x, y);
}

/* The panel's note, above its top left corner (clear of the frame by the
 * depth of a subscript); a note wider than the axes and a font's room
 * beside them smaller, down to NOTE_SHRINK of the font, so that notes of
 * neighbouring panels (long composite names, SPEC §9.4) do not meet. */
#define NOTE_SHRINK 0.6
static void note(const ctx_t *c, const view_t *v)
{
    if (v->p->note != NULL) {
        double font = c->L->font;
        double w = bf__text_width(v->p->note, font);
        double room = v->box.x1 - v->box.x0 + font;
        double size = w > room ? fmax(NOTE_SHRINK * font, font * room / w)
                               : font;
        text(c, v->box.x0, v->box.y1 + font * 1.05, 0.0, 0.0, size,
             v->p->note);
    }
}

/* The tick numbers (or names) and the panel's own labels and note. */
static void axis_texts(const ctx_t *c, size_t i, const view_t *v)
{
    const bf__layout *L = c->L;
    const bf_plot_panel *p = v->p;
    double below = v->box.y0 - L->tick;
    double left = v->box.x0 - L->tick;
    size_t k;
    color(COL_INK);
    if (L->xnum[i]) {
        for (k = 0; k < L->xt[i].n; k++) {
            double px;
            double py;
            to_page(v, L->xt[i].v[k], v->wy0, &px, &py);
            if (L->xrot[i]) {
                text(c, px, below - L->pad, 90.0, 1.0, L->font,
                     L->xt[i].text[k]);
            } else {
                text(c, px, below - L->pad - L->xnum_height[i] / 2, 0.0, 0.5,
                     L->font, L->xt[i].text[k]);
            }
        }
        below -= L->pad + L->xnum_height[i];
    }
    if (L->ynum[i]) {
        for (k = 0; k < L->yt[i].n; k++) {
            double px;
            double py;
            double wy = p->logy ? log10(L->yt[i].v[k]) : L->yt[i].v[k];
            to_page(v, v->wx0, wy, &px, &py);
            text(c, left - L->pad, py, 0.0, 1.0, L->font, L->yt[i].text[k]);
        }
        left -= L->pad + L->ynum_width[i];
    }
    if (p->xlabel != NULL) {
        text(c, L->xlabel_x[i], below - L->pad - L->label_font * 0.55, 0.0,
             0.5, L->xlabel_size[i], p->xlabel);
    }
    if (p->ylabel != NULL) {
        text(c, left - L->pad - L->label_font * 0.9,
             (v->box.y0 + v->box.y1) / 2, 90.0, 0.5, L->label_font,
             p->ylabel);
    }
    note(c, v);
}

/* A round ring step (1, 2, 2.5 or 5 times a power of ten) giving at most
 * POLAR_RINGS rings within the radius R. */
static double ring_step(double R)
{
    static const double mult[4] = {1.0, 2.0, 2.5, 5.0};
    double mag = pow(10.0, floor(log10(R / POLAR_RINGS)));
    size_t i;
    for (i = 0; i < 4; i++) {
        if (R / (mult[i] * mag) <= POLAR_RINGS) {
            return mult[i] * mag;
        }
    }
    return 10.0 * mag;
}

/* Rings, spokes every POLAR_STEP_DEG and the surface line of a polar
 * panel (panel view), then their labels (page view). */
static void polar_grid(ctx_t *c, const view_t *v)
{
    const bf__layout *L = c->L;
    double R = v->p->ymax;
    double ax[POLAR_ARC_POINTS];
    double ay[POLAR_ARC_POINTS];
    double px;
    double py;
    char t[32];
    int ring;
    int deg;
    size_t i;

    double step = ring_step(R);
    int rings = (int)floor(R / step + 1e-9);
    color(COL_SLOT + BF_PLOT_REF);
    width(c, W_GRID);
    for (ring = 1; ring <= rings + 1; ring++) {
        double r = ring <= rings ? step * ring : R; /* then the rim */
        if (ring > rings && fabs(step * rings - R) < 1e-9 * R) {
            break;
        }
        for (i = 0; i < POLAR_ARC_POINTS; i++) {
            double a = -M_PI / 2 + M_PI * (double)i / (POLAR_ARC_POINTS - 1);
            ax[i] = r * sin(a);
            ay[i] = r * cos(a);
        }
        plline(POLAR_ARC_POINTS, ax, ay);
    }
    for (deg = -90 + POLAR_STEP_DEG; deg < 90; deg += POLAR_STEP_DEG) {
        double lx[2] = {0.0, R * sin(deg * M_PI / 180.0)};
        double ly[2] = {0.0, R * cos(deg * M_PI / 180.0)};
        plline(2, lx, ly);
    }
    color(COL_INK);
    width(c, W_FRAME);
    {
        double bx[2] = {-R, R};
        double by[2] = {0.0, 0.0};
        plline(2, bx, by); /* the surface */
    }
    page_view(c);
    for (deg = -90; deg <= 90; deg += POLAR_STEP_DEG) {
        double a = deg * M_PI / 180.0;
        double gap = L->pad + 0.5 * L->font * 0.75;
        to_page(v, R * sin(a), R * cos(a), &px, &py);
        snprintf(t, sizeof t, "%s%d\xc2\xb0", deg < 0 ? "\xe2\x88\x92" : "",
                 abs(deg));
        if (deg == -90 || deg == 90) { /* beside the surface line, above
                                          it, clear of the radius numbers */
            text(c, px + (deg < 0 ? -L->pad : L->pad), py + gap, 0.0,
                 deg < 0 ? 1.0 : 0.0, L->font, t);
        } else {
            /* outside the arc, the label's near edge facing the centre */
            text(c, px + gap * sin(a), py + gap * cos(a), 0.0,
                 0.5 - 0.5 * sin(a), L->font, t);
        }
    }
    for (ring = 1; ring <= rings; ring++) {
        double r = step * ring;
        to_page(v, r, 0.0, &px, &py);
        snprintf(t, sizeof t, "%g", r);
        text(c, px, py - L->pad - 0.5 * L->font * 0.75, 0.0, 0.5, L->font,
             t);
    }
    panel_view(c, v);
}

/* ==== panels, legend, figure ============================================ */

/* Markers that do not hide what lies under them. */
static int open_marker(bf__marker mk)
{
    return mk >= BF__MK_OPEN_CIRCLE;
}

static void draw_panel(ctx_t *c, size_t i)
{
    view_t v;
    size_t k;
    int pass;
    view_make(c, i, &v);
    panel_view(c, &v);
    if (v.p->cells != NULL) {
        draw_cells(c, &v);
    }
    if (v.p->polar) {
        polar_grid(c, &v);
    }
    if (v.p->diagonal) {
        double lo = fmax(v.p->xmin, v.p->ymin);
        double hi = fmin(v.p->xmax, v.p->ymax);
        double dx[2] = {lo, hi};
        double dy[2] = {lo, hi};
        color(COL_SLOT + BF_PLOT_REF);
        width(c, W_FRAME);
        if (lo < hi) {
            plline(2, dx, dy);
        }
    }
    for (k = 0; k < v.p->n_series; k++) { /* lines, bars, intervals */
        const bf_plot_series *s = &v.p->series[k];
        switch (s->kind) {
        case BF_SERIES_LINE: series_line(c, &v, s); break;
        case BF_SERIES_BARS: series_bars(c, &v, s); break;
        case BF_SERIES_INTERVALS:
        case BF_SERIES_ERRORBARS: series_intervals(c, &v, s); break;
        default: break;
        }
    }
    /* then the markers over them: filled ones first, so that open ones
     * drawn on top keep both visible where series coincide */
    for (pass = 0; pass < 2; pass++) {
        for (k = 0; k < v.p->n_series; k++) {
            const bf_plot_series *s = &v.p->series[k];
            if ((s->kind == BF_SERIES_POINTS || s->kind == BF_SERIES_LINE) &&
                open_marker(bf__styles[s->style].marker) == pass) {
                series_markers(c, &v, s);
            }
        }
    }
    page_view(c);
    if (!v.p->polar) {
        frame(c, i, &v);
        axis_texts(c, i, &v);
    } else {
        color(COL_INK);
        note(c, &v);
    }
}

/* A legend entry's key at (x, y) (page view): the series' line, marker
 * or box, or a cell class's box. */
static void legend_key(ctx_t *c, const bf__entry *e)
{
    const bf__layout *L = c->L;
    const bf_plot_series *s = e->series;
    double x0 = e->x;
    double x1 = e->x + L->key_width;
    double xm = (x0 + x1) / 2;
    double y = e->y;
    if (s == NULL || s->kind == BF_SERIES_BARS) {
        double h = L->font * 0.35;
        double bx[4] = {xm - 1.6 * h, xm - 1.6 * h, xm + 1.6 * h,
                        xm + 1.6 * h};
        double by[4] = {y - h, y + h, y + h, y - h};
        color(s == NULL ? COL_CLASS + e->cls : COL_SLOT + (int)s->style);
        width(c, W_FILL);
        fill_page(4, bx, by);
        if (s == NULL) { /* a thin outline: the lightest class on white */
            double ox[5] = {bx[0], bx[1], bx[2], bx[3], bx[0]};
            double oy[5] = {by[0], by[1], by[2], by[3], by[0]};
            color(COL_SLOT + BF_PLOT_REF);
            width(c, W_GRID);
            plline(5, ox, oy);
        }
        return;
    }
    if (s->kind == BF_SERIES_LINE || s->kind == BF_SERIES_INTERVALS) {
        view_t v; /* the page as a view, for the line code */
        double lx[2] = {x0, x1};
        double ly[2] = {y, y};
        v.p = NULL;
        v.box.x0 = v.wx0 = 0.0;
        v.box.y0 = v.wy0 = 0.0;
        v.box.x1 = v.wx1 = (double)L->width;
        v.box.y1 = v.wy1 = (double)L->height;
        lines_begin(c, s);
        line_run(c, &v, 2, lx, ly, bf__series_dash(s), line_width(s));
        if (c->poly.n_anchor > 0) {
            width(c, W_FILL);
            fill_poly(c);
            width(c, line_width(s));
        }
        if (s->kind == BF_SERIES_INTERVALS) {
            double tx[2] = {x0, x0};
            double ty[2] = {y - CAP, y + CAP};
            plline(2, tx, ty);
            tx[0] = tx[1] = x1;
            plline(2, tx, ty);
        }
    }
    if (s->kind == BF_SERIES_ERRORBARS) { /* a bar with its two ticks */
        double h = L->font * 0.45;
        double tx[2] = {xm, xm};
        double ty[2] = {y - h, y + h};
        color(COL_SLOT + (int)s->style);
        width(c, line_width(s));
        plline(2, tx, ty);
        tx[0] = xm - CAP;
        tx[1] = xm + CAP;
        ty[0] = ty[1] = y - h;
        plline(2, tx, ty);
        ty[0] = ty[1] = y + h;
        plline(2, tx, ty);
    }
    if (s->kind == BF_SERIES_POINTS ||
        (s->kind == BF_SERIES_LINE && s->mark_every > 0)) {
        color(COL_SLOT + (int)s->style);
        markers_at(c, bf__styles[s->style].marker, marker_r(s), 1, &xm, &y);
    }
}

static void draw_legend(ctx_t *c)
{
    const bf__layout *L = c->L;
    size_t i;
    page_view(c);
    for (i = 0; i < L->n_entries; i++) {
        legend_key(c, &L->entry[i]);
        color(COL_INK);
        text(c, L->entry[i].x + L->key_width + 2 * L->pad, L->entry[i].y, 0.0,
             0.0, L->font, L->entry[i].text);
    }
}

/* A column label centred at x: on one line, or when wider than the axes
 * (width w) and the layout has two lines, split at the space nearest its
 * middle. */
static void col_label(const ctx_t *c, double x, double w, const char *s)
{
    const bf__layout *L = c->L;
    double line = L->label_font * 1.25;
    const char *cut = NULL;
    const char *p;
    char first[256];
    size_t mid = strlen(s) / 2;
    if (L->col_lines < 2 || bf__text_width(s, L->label_font) <= w) {
        text(c, x, L->col_label_y, 0.0, 0.5, L->label_font, s);
        return;
    }
    for (p = s; *p != '\0'; p++) {
        if (*p == ' ' &&
            (cut == NULL || labs((long)(p - s) - (long)mid) <
                                labs((long)(cut - s) - (long)mid))) {
            cut = p;
        }
    }
    if (cut == NULL || (size_t)(cut - s) >= sizeof first) {
        text(c, x, L->col_label_y, 0.0, 0.5, L->label_font, s);
        return;
    }
    memcpy(first, s, (size_t)(cut - s));
    first[cut - s] = '\0';
    text(c, x, L->col_label_y + line / 2, 0.0, 0.5, L->label_font, first);
    text(c, x, L->col_label_y - line / 2, 0.0, 0.5, L->label_font, cut + 1);
}

/* Shared labels, column and row labels (page view). */
static void figure_texts(const ctx_t *c)
{
    const bf_plot_figure *fig = c->fig;
    const bf__layout *L = c->L;
    size_t k;
    color(COL_INK);
    text(c, (L->grid.x0 + L->grid.x1) / 2, L->xlabel_y, 0.0, 0.5,
         L->label_font, fig->xlabel);
    text(c, L->ylabel_x, (L->grid.y0 + L->grid.y1) / 2, 90.0, 0.5,
         L->label_font, fig->ylabel);
    for (k = 0; fig->col_labels != NULL && k < fig->nx; k++) {
        const bf__box *b = &L->axes[k < fig->n_panels ? k : 0];
        col_label(c, (b->x0 + b->x1) / 2, b->x1 - b->x0, fig->col_labels[k]);
    }
    for (k = 0; fig->row_labels != NULL && k < fig->ny; k++) {
        const bf__box *b = &L->axes[k * fig->nx];
        text(c, L->row_label_x, (b->y0 + b->y1) / 2, -90.0, 0.5,
             L->label_font, fig->row_labels[k]);
    }
}

/* The code of a failed fopen: BF_ENOMEM for want of memory, else BF_EIO. */
static int open_error(void)
{
    return errno == ENOMEM ? BF_ENOMEM : BF_EIO;
}

/* Reads the whole file at path into a new buffer *out (NUL-terminated;
 * the caller frees). Returns BF_OK, BF_ENOMEM or BF_EIO (*out NULL). */
static int slurp(const char *path, char **out, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    char *buf = NULL;
    long n;
    int rc = BF_EIO;
    *out = NULL;
    if (fp == NULL) {
        return open_error();
    }
    if (fseek(fp, 0, SEEK_END) == 0 && (n = ftell(fp)) > 0 &&
        fseek(fp, 0, SEEK_SET) == 0) {
        buf = malloc((size_t)n + 1);
        rc = buf == NULL ? BF_ENOMEM : BF_EIO;
        if (buf != NULL && fread(buf, 1, (size_t)n, fp) == (size_t)n) {
            buf[n] = '\0';
            *len = (size_t)n;
            *out = buf;
            rc = BF_OK;
        } else {
            free(buf);
        }
    }
    fclose(fp);
    return rc;
}

/* Blanks the PDF's /CreationDate entry (cairo writes the clock time) with
 * spaces of the same length, so byte offsets stay valid and the same
 * figure gives the same bytes [2]. Returns BF_OK, BF_ENOMEM or BF_EIO. */
static int blank_pdf_date(const char *path)
{
    static const char key[] = "/CreationDate (";
    size_t len = 0;
    char *buf;
    char *p;
    int rc = slurp(path, &buf, &len);
    if (rc != BF_OK) {
        return rc;
    }
    for (p = buf; p + sizeof key - 1 < buf + len; p++) {
        if (memcmp(p, key, sizeof key - 1) == 0) {
            char *end = memchr(p, ')', (size_t)(buf + len - p));
            FILE *fp;
            if (end == NULL) {
                break;
            }
            memset(p, ' ', (size_t)(end - p + 1));
            fp = fopen(path, "wb");
            if (fp == NULL) {
                rc = open_error();
            } else if (fwrite(buf, 1, len, fp) != len) {
                rc = BF_EIO;
            }
            if (fp != NULL && fclose(fp) != 0) {
                rc = BF_EIO;
            }
            break;
        }
    }
    free(buf);
    return rc;
}

/* cairo numbers its surfaces in the process and writes the number into
 * the SVG's top group, id="surfaceN": renumbered 1 here, so the file does
 * not depend on what the process drew before. Returns BF_OK, BF_ENOMEM
 * or BF_EIO. */
static int renumber_svg(const char *path)
{
    static const char key[] = "<g id=\"surface";
    size_t len = 0;
    char *buf;
    char *p;
    FILE *fp;
    int ok;
    int rc = slurp(path, &buf, &len);
    if (rc != BF_OK) {
        return rc;
    }
    p = strstr(buf, key);
    if (p == NULL) {
        free(buf);
        return BF_OK;
    }
    p += sizeof key - 1;
    fp = fopen(path, "wb");
    if (fp == NULL) {
        rc = open_error();
        free(buf);
        return rc;
    }
    ok = fwrite(buf, 1, (size_t)(p - buf), fp) ==
                           (size_t)(p - buf);
    if (ok) {
        char *q = p;
        while (*q >= '0' && *q <= '9') {
            q++;
        }
        ok = fputc('1', fp) != EOF &&
             fwrite(q, 1, len - (size_t)(q - buf), fp) ==
                 len - (size_t)(q - buf);
    }
    if (fclose(fp) != 0) {
        ok = 0;
    }
    free(buf);
    return ok ? BF_OK : BF_EIO;
}

/* The colour map: background, ink, white, empty cells, the style slots and
 * the heat-map classes. */
static void colormap(unsigned char (*rgb)[3])
{
    size_t i;
    memset(rgb, 255, 3 * sizeof *rgb); /* background, (ink), white */
    memset(rgb[COL_INK], 0, sizeof rgb[COL_INK]);
    memcpy(rgb[COL_EMPTY], bf__empty_rgb, 3);
    for (i = 0; i < BF__NSLOTS; i++) {
        memcpy(rgb[COL_SLOT + i], bf__styles[i].rgb, 3);
    }
    for (i = 0; i < BF_PLOT_NCLASSES; i++) {
        memcpy(rgb[COL_CLASS + i], bf__class_rgb[i], 3);
    }
}

static void set_colors(void)
{
    unsigned char rgb[NCOL][3];
    size_t i;
    colormap(rgb);
    plscmap0n(NCOL);
    for (i = 0; i < NCOL; i++) {
        plscol0((PLINT)i, rgb[i][0], rgb[i][1], rgb[i][2]);
    }
}

/* Scratch arrays for the largest series and the frame of the figure. */
static int ctx_alloc(ctx_t *c)
{
    size_t n = 4 * BF__MAX_TICKS + 16;
    size_t i;
    size_t j;
    for (i = 0; i < c->fig->n_panels; i++) {
        for (j = 0; j < c->fig->panels[i].n_series; j++) {
            n = c->fig->panels[i].series[j].n + 2 > n
                    ? c->fig->panels[i].series[j].n + 2
                    : n;
        }
    }
    c->wx = malloc(n * sizeof *c->wx);
    c->wy = malloc(n * sizeof *c->wy);
    c->px = malloc(n * sizeof *c->px);
    c->py = malloc(n * sizeof *c->py);
    memset(&c->poly, 0, sizeof c->poly);
    return c->wx != NULL && c->wy != NULL && c->px != NULL && c->py != NULL;
}

static void ctx_free(ctx_t *c)
{
    free(c->wx);
    free(c->wy);
    free(c->px);
    free(c->py);
    bf__poly_free(&c->poly);
}

int bf_plot_write(const bf_plot_figure *fig, bf_plot_format fmt,
                  const char *path)
{
    struct stat st;
    bf__layout *L;
    ctx_t c;
    FILE *probe;
    unsigned char *image = NULL;
    unsigned pw = 0;
    unsigned ph = 0;
    size_t i;
    int rc;
    int failed;

    if ((unsigned)fmt >= BF_PLOT_NFORMATS || path == NULL) {
        return BF_EINVAL;
    }
    L = malloc(sizeof *L);
    if (L == NULL) {
        return BF_ENOMEM;
    }
    rc = bf__layout_make(fig, L);
    if (rc != BF_OK) {
        free(L);
        return rc;
    }
    memset(&c, 0, sizeof c);
    c.fig = fig;
    c.L = L;
    c.fmt = fmt;
    c.unit = fmt == BF_PLOT_PNG ? BF_PLOT_PNG_DPI / 72.0 : 1.0;
    if (!ctx_alloc(&c)) {
        ctx_free(&c);
        free(L);
        return BF_ENOMEM;
    }
    /* PLplot exits the process when it cannot open its output: check
     * first that the file can be written. */
    probe = fopen(path, "wb");
    if (probe == NULL) {
        rc = open_error();
        ctx_free(&c);
        free(L);
        return rc;
    }
    fclose(probe);
    if (fmt == BF_PLOT_PNG) { /* drawn on white, in memory */
        pw = bf_plot_png_pixels(L->width);
        ph = bf_plot_png_pixels(L->height);
        image = malloc((size_t)pw * ph * 3);
        if (image == NULL) {
            ctx_free(&c);
            free(L);
            return BF_ENOMEM;
        }
        memset(image, 255, (size_t)pw * ph * 3);
    }

    plsdev(devices[fmt]);
    if (fmt == BF_PLOT_PNG) {
        plsmem((PLINT)pw, (PLINT)ph, image);
    } else {
        plsfnam(path);
    }
    /* graphics anti-aliasing off in the vector formats (1: cairo's
     * ANTIALIAS_NONE) makes the driver fill polygons without stroking
     * their outline, which the joined markers need; on in PNG (0: the
     * default) */
    plsetopt("drvopt", fmt == BF_PLOT_PNG ? "graphics_anti_aliasing=0"
                                          : "graphics_anti_aliasing=1");
    if (fmt != BF_PLOT_PNG) {
        plspage(0.0, 0.0, (PLINT)L->width, (PLINT)L->height, 0, 0);
    }
    set_colors();
    plinit();
    pladv(0);
    for (i = 0; i < fig->n_panels; i++) {
        draw_panel(&c, i);
    }
    page_view(&c);
    figure_texts(&c);
    draw_legend(&c);
    plend();
    failed = c.failed || c.poly.failed;
    ctx_free(&c);
    free(L);
    if (failed) {
        free(image);
        return BF_ENOMEM;
    }
    if (fmt == BF_PLOT_PNG) {
        unsigned char rgb[NCOL][3];
        colormap(rgb);
        rc = bf__png_write(path, pw, ph, image,
                           (const unsigned char(*)[3])rgb, NCOL);
        free(image);
        if (rc != BF_OK) {
            return rc;
        }
    }
    rc = fmt == BF_PLOT_PDF   ? blank_pdf_date(path)
         : fmt == BF_PLOT_SVG ? renumber_svg(path)
                              : BF_OK;
    if (rc != BF_OK) {
        return rc;
    }
    if (stat(path, &st) != 0 || st.st_size == 0) {
        return BF_EIO;
    }
    return BF_OK;
}
