/* plot_style.c: the figures' style slots -- colour, marker and dash
 * pattern of each -- and the marker outlines (plot_internal.h).
 *
 * References:
 *   [1] M. Okabe, K. Ito, "Color Universal Design (CUD): how to make
 *       figures and presentations that are friendly to colorblind people"
 *       (2008): the eight-colour set; its yellow is left out (too light
 *       for lines on white) and a dark grey takes its place.
 *   [2] C. A. Brewer, ColorBrewer 2.0, "Blues" (5 classes, sequential,
 *       colour-blind safe): the heat-map classes. */
#include <math.h>
#include <stddef.h>

#include "plot_internal.h"

/* Dash patterns, on/off lengths in points at print size; dashes have
 * butt ends (a dot of a 1-point line is a 1-point square). */
const bf__dash bf__dashes[BF__NDASHES] = {
    {0, {0}},                                /* solid */
    {2, {4.0, 2.2}},                         /* dashed */
    {2, {1.1, 1.9}},                         /* dotted */
    {4, {4.0, 1.9, 1.1, 1.9}},               /* dash-dot */
    {2, {7.5, 2.5}},                         /* long dash */
    {6, {4.0, 1.7, 1.1, 1.7, 1.1, 1.7}},     /* dash-dot-dot */
};

/* Okabe & Ito [1]: blue, vermillion, bluish green, reddish purple, sky
 * blue, orange; and dark grey. */
#define BLUE {0, 114, 178}, "#0072b2"
#define VERMILLION {213, 94, 0}, "#d55e00"
#define GREEN {0, 158, 115}, "#009e73"
#define PURPLE {204, 121, 167}, "#cc79a7"
#define SKY {86, 180, 233}, "#56b4e9"
#define ORANGE {230, 159, 0}, "#e69f00"
#define GREY {85, 85, 85}, "#555555"

/* Slots 0-5 differ in colour, marker and dash from each other; every slot
 * has its own marker and its own (colour, dash) pair. */
const bf__style bf__styles[BF__NSLOTS] = {
    {BLUE, BF__MK_CIRCLE, 0},
    {VERMILLION, BF__MK_SQUARE, 1},
    {GREEN, BF__MK_TRIANGLE, 3},
    {PURPLE, BF__MK_DIAMOND, 2},
    {SKY, BF__MK_OPEN_SQUARE, 4},
    {ORANGE, BF__MK_OPEN_CIRCLE, 5},
    {GREY, BF__MK_TRIANGLE_DOWN, 0},
    {BLUE, BF__MK_OPEN_TRIANGLE, 1},
    {VERMILLION, BF__MK_OPEN_DIAMOND, 2},
    {GREEN, BF__MK_PLUS, 4},
    {PURPLE, BF__MK_CROSS, 0},
    {SKY, BF__MK_OPEN_TRIANGLE_DOWN, 3},
    /* 11-20: the specular models of SPEC §9.3 */
    {ORANGE, BF__MK_PENTAGON, 0},
    {GREY, BF__MK_HEXAGON, 1},
    {BLUE, BF__MK_TRIANGLE_RIGHT, 2},
    {VERMILLION, BF__MK_TRIANGLE_LEFT, 3},
    {GREEN, BF__MK_STAR, 5},
    {PURPLE, BF__MK_OPEN_PENTAGON, 1},
    {SKY, BF__MK_OPEN_HEXAGON, 5},
    {ORANGE, BF__MK_OPEN_TRIANGLE_RIGHT, 2},
    {GREY, BF__MK_OPEN_TRIANGLE_LEFT, 3},
    {{0, 0, 0}, "#000000", BF__MK_CIRCLE, 0},       /* BF_PLOT_INK */
    {{150, 150, 150}, "#969696", BF__MK_CIRCLE, 1}, /* BF_PLOT_REF */
};

/* ColorBrewer "Blues" [2], darkest first. */
const unsigned char bf__class_rgb[BF_PLOT_NCLASSES][3] = {
    {8, 81, 156}, {49, 130, 189}, {107, 174, 214}, {189, 215, 231},
    {239, 243, 255}};
const unsigned char bf__empty_rgb[3] = {224, 224, 224};

static const char *const marker_names[BF__NMARKERS] = {
    "filled circle",  "filled square",  "filled triangle",
    "filled diamond", "filled inverted triangle", "filled pentagon",
    "filled hexagon", "filled right triangle", "filled left triangle",
    "filled star",    "open circle",
    "open square",    "open triangle",  "open diamond",
    "plus",           "cross",          "open inverted triangle",
    "open pentagon",  "open hexagon",   "open right triangle",
    "open left triangle"};

static const char *const dash_names[BF__NDASHES] = {
    "solid", "dashed", "dotted", "dash-dot", "long-dashed", "dash-dot-dot"};

const char *bf_plot_style_dash(unsigned style)
{
    return style < BF__NSLOTS ? dash_names[bf__styles[style].dash] : NULL;
}

const char *bf_plot_style_hex(unsigned style)
{
    return style < BF__NSLOTS ? bf__styles[style].hex : NULL;
}

const char *bf_plot_style_marker(unsigned style)
{
    return style < BF__NSLOTS ? marker_names[bf__styles[style].marker]
                              : NULL;
}

const bf__dash *bf__series_dash(const bf_plot_series *s)
{
    switch (s->dash) {
    case BF_DASH_SOLID: return &bf__dashes[0];
    case BF_DASH_DASHED: return &bf__dashes[1];
    case BF_DASH_DOTTED: return &bf__dashes[2];
    default: return &bf__dashes[bf__styles[s->style].dash];
    }
}

/* ==== marker outlines ==================================================== */

/* Marker sizes relative to r, chosen so that the shapes look equally
 * heavy: a square of the circle's area has half-side 0.886 r. */
#define SQUARE_H 0.886
#define TRIANGLE_R 1.25  /* circumradius */
#define DIAMOND_R 1.2
#define ARM_LEN 1.2      /* plus and cross: half-length of an arm */
#define ARM_HALF 0.22    /*   and its half-width */
#define RING 0.36        /* open markers: inner outline at (1 - RING) */
#define CIRCLE_SIDES 12 /* round enough at print size, few vertices */
#define PENTAGON_R 1.1
#define HEXAGON_R 1.05
#define STAR_R 1.45      /* star: outer radius, */
#define STAR_INNER 0.45  /*   inner radius over the outer */

/* A regular polygon of k sides, circumradius rad, first vertex at angle
 * a0, counter-clockwise (sense = 1) or clockwise (-1), closed. */
static size_t polygon(size_t k, double rad, double a0, int sense, double *dx,
                      double *dy)
{
    size_t i;
    for (i = 0; i <= k; i++) {
        double a = a0 + sense * 2.0 * M_PI * (double)(i % k) / (double)k;
        dx[i] = rad * cos(a);
        dy[i] = rad * sin(a);
    }
    return k + 1;
}

/* The outline of a basic (filled) shape of radius r and sense. */
static size_t shape(bf__marker mk, double r, int sense, double *dx,
                    double *dy)
{
    switch (mk) {
    case BF__MK_SQUARE:
    case BF__MK_OPEN_SQUARE:
        return polygon(4, SQUARE_H * r * M_SQRT2, M_PI / 4, sense, dx, dy);
    case BF__MK_TRIANGLE:
    case BF__MK_OPEN_TRIANGLE:
        return polygon(3, TRIANGLE_R * r, M_PI / 2, sense, dx, dy);
    case BF__MK_TRIANGLE_DOWN:
    case BF__MK_OPEN_TRIANGLE_DOWN:
        return polygon(3, TRIANGLE_R * r, -M_PI / 2, sense, dx, dy);
    case BF__MK_DIAMOND:
    case BF__MK_OPEN_DIAMOND:
        return polygon(4, DIAMOND_R * r, M_PI / 2, sense, dx, dy);
    case BF__MK_TRIANGLE_RIGHT:
    case BF__MK_OPEN_TRIANGLE_RIGHT:
        return polygon(3, TRIANGLE_R * r, 0.0, sense, dx, dy);
    case BF__MK_TRIANGLE_LEFT:
    case BF__MK_OPEN_TRIANGLE_LEFT:
        return polygon(3, TRIANGLE_R * r, M_PI, sense, dx, dy);
    case BF__MK_PENTAGON:
    case BF__MK_OPEN_PENTAGON:
        return polygon(5, PENTAGON_R * r, M_PI / 2, sense, dx, dy);
    case BF__MK_HEXAGON:
    case BF__MK_OPEN_HEXAGON:
        return polygon(6, HEXAGON_R * r, 0.0, sense, dx, dy);
    default:
        return polygon(CIRCLE_SIDES, r, 0.0, sense, dx, dy);
    }
}

/* A five-pointed star of outer radius rad, counter-clockwise, closed:
 * outer and inner vertices alternate. */
static size_t star(double rad, double *dx, double *dy)
{
    size_t i;
    for (i = 0; i <= 10; i++) {
        double a = M_PI / 2 + M_PI * (double)(i % 10) / 5.0;
        double q = (i % 2 == 0) ? rad : rad * STAR_INNER;
        dx[i] = q * cos(a);
        dy[i] = q * sin(a);
    }
    return 11;
}

/* A plus (rot = 0) or a cross (rot = pi/4): the outline of two crossed
 * bars, counter-clockwise from the top of the right arm. */
static size_t plus(double r, double rot, double *dx, double *dy)
{
    static const double u[12] = {1, 0, 0, 0, 0, -1, -1, 0, 0, 0, 0, 1};
    static const double v[12] = {0, 0, 1, 1, 0, 0, 0, 0, -1, -1, 0, 0};
    static const double su[12] = {0, 1, 1, -1, -1, 0, 0, -1, -1, 1, 1, 0};
    static const double sv[12] = {1, 1, 0, 0, 1, 1, -1, -1, 0, 0, -1, -1};
    double c = cos(rot);
    double s = sin(rot);
    size_t i;
    for (i = 0; i < 12; i++) {
        /* vertex = ARM_LEN * (u, v) + ARM_HALF * (su, sv) */
        double px = ARM_LEN * u[i] + ARM_HALF * su[i];
        double py = ARM_LEN * v[i] + ARM_HALF * sv[i];
        dx[i] = r * (c * px - s * py);
        dy[i] = r * (s * px + c * py);
    }
    dx[12] = dx[0];
    dy[12] = dy[0];
    return 13;
}

size_t bf__marker_shape(bf__marker mk, double r, double *dx, double *dy)
{
    size_t n;
    switch (mk) {
    case BF__MK_PLUS: return plus(r, 0.0, dx, dy);
    case BF__MK_CROSS: return plus(r, M_PI / 4, dx, dy);
    case BF__MK_STAR: return star(STAR_R * r, dx, dy);
    case BF__MK_OPEN_PENTAGON:
    case BF__MK_OPEN_HEXAGON:
    case BF__MK_OPEN_TRIANGLE_RIGHT:
    case BF__MK_OPEN_TRIANGLE_LEFT:
    case BF__MK_OPEN_CIRCLE:
    case BF__MK_OPEN_SQUARE:
    case BF__MK_OPEN_TRIANGLE:
    case BF__MK_OPEN_DIAMOND:
    case BF__MK_OPEN_TRIANGLE_DOWN:
        n = shape(mk, r, 1, dx, dy);
        return n + shape(mk, r * (1.0 - RING), -1, dx + n, dy + n);
    default: return shape(mk, r, 1, dx, dy);
    }
}
