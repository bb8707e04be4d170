/* plot_path.c: the geometry of drawn lines and markers (plot_internal.h),
 * in page points, without PLplot -- polylines clipped to a box, cut into
 * dashes, dashes turned into outlines (a stroke of butt-ended width as a
 * polygon), and many outlines joined into one polygon whose "bridges" the
 * path goes along and back, so that they enclose nothing under the
 * non-zero rule. plot.c fills such a polygon with one PLplot call: one
 * path in SVG and PDF for all the dashes or markers of a series.
 *
 * References:
 *   [1] Y.-D. Liang, B. A. Barsky, "A new concept and method for line
 *       clipping", ACM TOG 3(1):1-22, 1984: the segment clipping.
 *   [2] PostScript Language Reference, 3rd ed., §4.5 (stroke: butt caps,
 *       miter joins and the miter limit), which the outlines follow. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot_internal.h"

/* Joins sharper than this (the miter ratio 1 / sin(half the turn)) are
 * bevelled, as PostScript's default miter limit 10 would (ratio 10). */
#define MITER_LIMIT 10.0

/* ==== polygons =========================================================== */

static int poly_reserve(bf__poly *p, size_t extra)
{
    if (p->n + extra > p->cap) {
        size_t cap = 2 * (p->n + extra) + 64;
        double *x = realloc(p->x, cap * sizeof *x);
        double *y;
        if (x == NULL) {
            p->failed = 1;
            return -1;
        }
        p->x = x;
        y = realloc(p->y, cap * sizeof *y);
        if (y == NULL) {
            p->failed = 1;
            return -1;
        }
        p->y = y;
        p->cap = cap;
    }
    if (p->n_anchor == p->cap_anchor) {
        size_t cap = 2 * p->cap_anchor + 16;
        size_t *a = realloc(p->anchor, cap * sizeof *a);
        if (a == NULL) {
            p->failed = 1;
            return -1;
        }
        p->anchor = a;
        p->cap_anchor = cap;
    }
    return 0;
}

int bf__poly_add(bf__poly *p, size_t n, const double *x, const double *y)
{
    size_t k;
    if (n < 3) {
        return 0;
    }
    if (poly_reserve(p, n + 1) != 0) {
        return -1;
    }
    p->anchor[p->n_anchor++] = p->n;
    for (k = 0; k < n; k++) {
        p->x[p->n] = x[k];
        p->y[p->n] = y[k];
        p->n++;
    }
    if (x[n - 1] != x[0] || y[n - 1] != y[0]) { /* closed at its anchor */
        p->x[p->n] = x[0];
        p->y[p->n] = y[0];
        p->n++;
    }
    return 0;
}

int bf__poly_finish(bf__poly *p)
{
    size_t i;
    if (p->n_anchor < 2) {
        return 0;
    }
    if (poly_reserve(p, p->n_anchor) != 0) {
        return -1;
    }
    for (i = p->n_anchor - 1; i-- > 0;) { /* back along the bridges */
        p->x[p->n] = p->x[p->anchor[i]];
        p->y[p->n] = p->y[p->anchor[i]];
        p->n++;
    }
    return 0;
}

void bf__poly_clear(bf__poly *p)
{
    p->n = 0;
    p->n_anchor = 0;
}

void bf__poly_free(bf__poly *p)
{
    free(p->x);
    free(p->y);
    free(p->anchor);
    memset(p, 0, sizeof *p);
}

/* ==== clipping =========================================================== */

/* Clips the segment (x0, y0)-(x1, y1) to box b [1]: the visible part is
 * t in [*t0, *t1] of x0 + t (x1 - x0); returns 0 when none. */
static int clip_segment(const bf__box *b, double x0, double y0, double x1,
                        double y1, double *t0, double *t1)
{
    double p[4] = {-(x1 - x0), x1 - x0, -(y1 - y0), y1 - y0};
    double q[4] = {x0 - b->x0, b->x1 - x0, y0 - b->y0, b->y1 - y0};
    int k;
    *t0 = 0.0;
    *t1 = 1.0;
    for (k = 0; k < 4; k++) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) {
                return 0; /* parallel to this edge, outside */
            }
        } else {
            double r = q[k] / p[k];
            if (p[k] < 0.0) {
                *t0 = fmax(*t0, r);
            } else {
                *t1 = fmin(*t1, r);
            }
        }
    }
    return *t0 <= *t1;
}

size_t bf__clip_runs(const bf__box *b, size_t n, const double *x,
                     const double *y, double *ox, double *oy, size_t *start)
{
    size_t runs = 0;
    size_t m = 0;
    size_t k;
    int open = 0; /* a run is being built */
    for (k = 0; k + 1 < n; k++) {
        double t0;
        double t1;
        if (!clip_segment(b, x[k], y[k], x[k + 1], y[k + 1], &t0, &t1)) {
            open = 0;
            continue;
        }
        if (!open || t0 > 0.0) { /* a new run starts here */
            start[runs++] = m;
            ox[m] = x[k] + t0 * (x[k + 1] - x[k]);
            oy[m] = y[k] + t0 * (y[k + 1] - y[k]);
            m++;
        }
        ox[m] = x[k] + t1 * (x[k + 1] - x[k]);
        oy[m] = y[k] + t1 * (y[k + 1] - y[k]);
        m++;
        open = t1 >= 1.0; /* the next segment continues this run */
    }
    start[runs] = m;
    return runs;
}

/* ==== simplification ===================================================== */

/* Squared distance of (x, y) from the segment a-b. */
static double seg_dist2(double x, double y, double ax, double ay, double bx,
                        double by)
{
    double dx = bx - ax;
    double dy = by - ay;
    double l2 = dx * dx + dy * dy;
    double t = l2 > 0.0 ? ((x - ax) * dx + (y - ay) * dy) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    dx = ax + t * dx - x;
    dy = ay + t * dy - y;
    return dx * dx + dy * dy;
}

/* Marks keep[k] for the points of [lo, hi] Douglas-Peucker keeps. */
static void dp(const double *x, const double *y, size_t lo, size_t hi,
               double tol2, unsigned char *keep)
{
    while (hi > lo + 1) {
        size_t far = lo;
        double d_far = -1.0;
        size_t k;
        for (k = lo + 1; k < hi; k++) {
            double d = seg_dist2(x[k], y[k], x[lo], y[lo], x[hi], y[hi]);
            if (d > d_far) {
                d_far = d;
                far = k;
            }
        }
        if (d_far <= tol2) {
            return;
        }
        keep[far] = 1;
        dp(x, y, lo, far, tol2, keep); /* depth: log n for smooth curves */
        lo = far;
    }
}

size_t bf__simplify(size_t n, double *x, double *y, double tol)
{
    unsigned char *keep;
    size_t m = 0;
    size_t k;
    if (n < 3) {
        return n;
    }
    if ((keep = calloc(n, 1)) == NULL) {
        return 0;
    }
    keep[0] = keep[n - 1] = 1;
    dp(x, y, 0, n - 1, tol * tol, keep);
    for (k = 0; k < n; k++) {
        if (keep[k]) {
            x[m] = x[k];
            y[m] = y[k];
            m++;
        }
    }
    free(keep);
    return m;
}

/* ==== dashes ============================================================= */

size_t bf__dash_cut(const bf__dash *d, size_t n, const double *x,
                    const double *y, double *ox, double *oy, size_t *start)
{
    size_t pieces = 0;
    size_t m = 0;
    size_t phase = 0;
    double left;
    size_t k;
    if (n < 2) {
        start[0] = 0;
        return 0;
    }
    if (d->n == 0) { /* solid: the polyline itself */
        memcpy(ox, x, n * sizeof *ox);
        memcpy(oy, y, n * sizeof *oy);
        start[0] = 0;
        start[1] = n;
        return 1;
    }
    left = d->len[0];
    start[pieces++] = m;
    ox[m] = x[0];
    oy[m] = y[0];
    m++;
    for (k = 1; k < n; k++) {
        double seg = hypot(x[k] - x[k - 1], y[k] - y[k - 1]);
        double done = 0.0;
        while (seg - done > left) { /* a pattern element ends here */
            double t;
            done += left;
            t = done / seg;
            if (phase % 2 == 0) { /* the end of a dash */
                ox[m] = x[k - 1] + t * (x[k] - x[k - 1]);
                oy[m] = y[k - 1] + t * (y[k] - y[k - 1]);
                m++;
            } else { /* the start of the next */
                start[pieces++] = m;
                ox[m] = x[k - 1] + t * (x[k] - x[k - 1]);
                oy[m] = y[k - 1] + t * (y[k] - y[k - 1]);
                m++;
            }
            phase = (phase + 1) % d->n;
            left = d->len[phase];
        }
        left -= seg - done;
        if (phase % 2 == 0) {
            ox[m] = x[k];
            oy[m] = y[k];
            m++;
        }
    }
    /* the last piece ends with the polyline (or, ended in a gap, holds
     * its start only: fewer than 2 points, which callers skip) */
    start[pieces] = m;
    return pieces;
}

size_t bf__dash_capacity(const bf__dash *d, size_t n, const double *x,
                         const double *y)
{
    double len = 0.0;
    double shortest = HUGE_VAL;
    size_t k;
    for (k = 1; k < n; k++) {
        len += hypot(x[k] - x[k - 1], y[k] - y[k - 1]);
    }
    for (k = 0; k < d->n; k++) {
        shortest = fmin(shortest, d->len[k]);
    }
    /* each pattern element that ends adds a point and may start a piece */
    return n + 2 + (d->n > 0 ? (size_t)(len / shortest) + 2 : 0);
}

/* ==== outlines =========================================================== */

size_t bf__stroke_outline(size_t n, const double *x, const double *y,
                          double h, double *ox, double *oy)
{
    size_t k;
    size_t m = 0;
    if (n < 2) {
        return 0;
    }
    /* the left side forward, then the right side back: the same sense for
     * every piece, so that overlapping pieces add up under non-zero */
    for (k = 0; k < n; k++) {
        double nx;
        double ny;
        double s = 1.0;
        size_t a = k > 0 ? k - 1 : k;
        size_t b = k + 1 < n ? k + 1 : k;
        double ux = x[b] - x[a];
        double uy = y[b] - y[a];
        double len = hypot(ux, uy);
        if (len == 0.0) {
            ux = 1.0;
            uy = 0.0;
        } else {
            ux /= len;
            uy /= len;
        }
        nx = -uy;
        ny = ux;
        if (k > 0 && k + 1 < n) { /* a join: the miter of the two normals */
            double ax = x[k] - x[k - 1];
            double ay = y[k] - y[k - 1];
            double la = hypot(ax, ay);
            if (la > 0.0) {
                double c = (-ay / la) * nx + (ax / la) * ny; /* cos */
                s = c > 1.0 / MITER_LIMIT ? 1.0 / c : 1.0;   /* [2] */
            }
        }
        ox[m] = x[k] + h * s * nx;
        oy[m] = y[k] + h * s * ny;
        ox[2 * n - 1 - k] = x[k] - h * s * nx;
        oy[2 * n - 1 - k] = y[k] - h * s * ny;
        m++;
    }
    return 2 * n;
}
