/* plot.c: draws report figures (plot.h) with PLplot's cairo drivers --
 * pngcairo, svgcairo and pdfcairo. The only file of the project that calls
 * PLplot (STYLE §5).
 *
 * References:
 *   [1] The PLplot Plotting Library, version 5.15 reference manual
 *       (plinit/plend, plssub, plvsta, plwind, plbox, plstring, pllegend,
 *       plslabelfunc, and the cairo device drivers). */
#include "plot.h"

#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "brdffit.h"

/* Colour map 0: background, ink, grid, then the series palette
 * (Okabe & Ito's colour-blind-safe colours first). */
enum { COL_BG = 0, COL_INK = 1, COL_GRID = 2, COL_SERIES = 3 };
static const unsigned char cmap0[COL_SERIES + BF_PLOT_NCOLORS][3] = {
    {255, 255, 255}, {0, 0, 0},      {190, 190, 190},
    {0, 114, 178},   {213, 94, 0},   {0, 158, 115},  {204, 121, 167},
    {230, 159, 0},   {86, 180, 233}, {140, 86, 75},  {188, 189, 34},
    {150, 30, 60},   {0, 0, 0}};

/* Marker glyphs (drawn as text: they scale with the character size). */
static const char *const markers[BF_PLOT_NMARKERS] = {"●", "■", "▲",
                                                      "◆", "▼", "×"};

static const char *const devices[BF_PLOT_NFORMATS] = {"pngcairo", "svgcairo",
                                                      "pdfcairo"};
static const char *const extensions[BF_PLOT_NFORMATS] = {"png", "svg",
                                                         "pdf"};

/* Text and marker sizes relative to PLplot's default character height. */
#define MARKER_SCALE 0.55
#define LEGEND_SCALE 0.8
#define LINE_WIDTH 1.6
/* Bar width in x units (bars are centred on integers). */
#define BAR_WIDTH 0.6
/* Polar panels: angle grid step and the radius grid divisions. */
#define POLAR_STEP_DEG 30
#define POLAR_RINGS 4
#define POLAR_ARC_POINTS 181
/* Legend outside the axes: the estimated width of a character and of
 * the sample line/marker, in character heights. */
#define CHAR_WIDTH 0.62
#define LEGEND_KEY 6.0
/* Polar panels: the window extends this far beyond the outer radius. */
#define POLAR_MARGIN 1.25

const char *bf_plot_format_ext(bf_plot_format fmt)
{
    return (unsigned)fmt < BF_PLOT_NFORMATS ? extensions[fmt] : NULL;
}

/* ==== text ================================================================ */

/* Copies s into buf doubling PLplot's escape character '#', so user text
 * (sample names) is drawn as written. */
static const char *esc(const char *s, char *buf, size_t len)
{
    size_t j = 0;
    if (s == NULL) {
        s = "";
    }
    for (; *s != '\0' && j + 2 < len; s++) {
        if (*s == '#') {
            buf[j++] = '#';
        }
        buf[j++] = *s;
    }
    buf[j] = '\0';
    return buf;
}

/* ==== checks ============================================================== */

static int range_ok(double lo, double hi)
{
    return isfinite(lo) && isfinite(hi) && lo < hi;
}

static int panel_ok(const bf_plot_panel *p)
{
    size_t i;
    if (!range_ok(p->ymin, p->ymax) || (p->series == NULL && p->n_series)) {
        return 0;
    }
    if (!p->polar && !range_ok(p->xmin, p->xmax)) {
        return 0;
    }
    if (p->logy && !(p->ymin > 0.0)) {
        return 0;
    }
    if (p->n_xticks > 0 && p->xtick_labels == NULL) {
        return 0;
    }
    for (i = 0; i < p->n_series; i++) {
        const bf_plot_series *s = &p->series[i];
        if (s->n > 0 && (s->x == NULL || s->y == NULL)) {
            return 0;
        }
    }
    return 1;
}

static int figure_ok(const bf_plot_figure *fig)
{
    size_t i;
    if (fig == NULL || fig->width == 0 || fig->height == 0 ||
        fig->width > BF_PLOT_MAX_SIZE || fig->height > BF_PLOT_MAX_SIZE ||
        fig->nx == 0 || fig->ny == 0 || fig->panels == NULL ||
        fig->n_panels == 0 || fig->n_panels > fig->nx * fig->ny ||
        !(fig->text_scale > 0.0)) {
        return 0;
    }
    for (i = 0; i < fig->n_panels; i++) {
        if (!panel_ok(&fig->panels[i])) {
            return 0;
        }
    }
    return 1;
}

/* ==== drawing helpers ===================================================== */

static void set_color(unsigned color)
{
    plcol0((PLINT)(COL_SERIES + color % BF_PLOT_NCOLORS));
}

static void set_dashed(int dashed)
{
    static const PLINT mark[1] = {1500};
    static const PLINT space[1] = {1000};
    if (dashed) {
        plstyl(1, mark, space);
    } else {
        plstyl(0, NULL, NULL);
    }
}

/* Draws the finite runs of (x, y) as polylines (a NaN breaks the line). */
static void polyline(size_t n, const double *x, const double *y)
{
    size_t i = 0;
    while (i < n) {
        size_t j = i;
        while (j < n && isfinite(x[j]) && isfinite(y[j])) {
            j++;
        }
        if (j - i >= 2) {
            plline((PLINT)(j - i), &x[i], &y[i]);
        }
        i = j + 1;
    }
}

/* Draws the finite points of (x, y) as markers. */
static void points(size_t n, const double *x, const double *y,
                   unsigned marker, double text_scale)
{
    size_t i;
    plschr(0.0, MARKER_SCALE * text_scale);
    for (i = 0; i < n; i++) {
        if (isfinite(x[i]) && isfinite(y[i])) {
            plstring(1, &x[i], &y[i], markers[marker % BF_PLOT_NMARKERS]);
        }
    }
    plschr(0.0, text_scale);
}

/* Vertical bars centred on x from 0 to y, the value written above each. */
static void bars(size_t n, const double *x, const double *y, double ytop,
                 unsigned color, double text_scale)
{
    size_t i;
    for (i = 0; i < n; i++) {
        PLFLT bx[4];
        PLFLT by[4];
        char label[32];
        if (!isfinite(x[i]) || !isfinite(y[i])) {
            continue;
        }
        bx[0] = bx[1] = x[i] - BAR_WIDTH / 2;
        bx[2] = bx[3] = x[i] + BAR_WIDTH / 2;
        by[0] = by[3] = 0.0;
        by[1] = by[2] = y[i];
        set_color(color);
        if (y[i] > 0.0) {
            plfill(4, bx, by);
        }
        plcol0(COL_INK);
        snprintf(label, sizeof label, "%g", y[i]);
        plschr(0.0, 0.9 * text_scale);
        plptex(x[i], y[i] + 0.02 * ytop, 1.0, 0.0, 0.5, label);
        plschr(0.0, text_scale);
    }
}

/* The x-axis label callback of box panels with named ticks. */
typedef struct {
    const char *const *labels;
    size_t n;
} tick_labels;

static void tick_label(PLINT axis, PLFLT value, char *label, PLINT length,
                       PLPointer data)
{
    const tick_labels *t = data;
    double r = floor(value + 0.5);
    label[0] = '\0';
    if (axis == PL_X_AXIS && fabs(value - r) < 1e-6 && r >= 1.0 &&
        r <= (double)t->n) {
        char buf[128];
        snprintf(label, (size_t)length, "%s",
                 esc(t->labels[(size_t)r - 1], buf, sizeof buf));
    }
}

/* Maps data y to the drawn coordinate (log10 on log axes). */
static double ymap(const bf_plot_panel *p, double y)
{
    if (!p->logy) {
        return y;
    }
    return y > 0.0 ? log10(y) : NAN;
}

/* ==== legend ============================================================== */

static void legend(const bf_plot_panel *p, double text_scale)
{
    PLINT opt[BF_PLOT_NCOLORS * 4];
    const char *text[BF_PLOT_NCOLORS * 4];
    char esc_text[BF_PLOT_NCOLORS * 4][128];
    PLINT color[BF_PLOT_NCOLORS * 4];
    PLINT lstyle[BF_PLOT_NCOLORS * 4];
    PLFLT lwidth[BF_PLOT_NCOLORS * 4];
    PLFLT sscale[BF_PLOT_NCOLORS * 4];
    PLINT snum[BF_PLOT_NCOLORS * 4];
    PLINT pattern[BF_PLOT_NCOLORS * 4];
    PLFLT bscale[BF_PLOT_NCOLORS * 4];
    PLFLT bwidth[BF_PLOT_NCOLORS * 4];
    const char *sym[BF_PLOT_NCOLORS * 4];
    PLINT ink[BF_PLOT_NCOLORS * 4];
    PLFLT w;
    PLFLT h;
    PLINT pos;
    size_t n = 0;
    size_t i;

    for (i = 0; i < p->n_series && n < sizeof opt / sizeof *opt; i++) {
        const bf_plot_series *s = &p->series[i];
        if (s->label == NULL) {
            continue;
        }
        opt[n] = s->style == BF_SERIES_LINE     ? PL_LEGEND_LINE
                 : s->style == BF_SERIES_POINTS ? PL_LEGEND_SYMBOL
                 : s->style == BF_SERIES_LINEPOINTS
                     ? (PL_LEGEND_LINE | PL_LEGEND_SYMBOL)
                     : PL_LEGEND_COLOR_BOX;
        text[n] = esc(s->label, esc_text[n], sizeof esc_text[n]);
        color[n] = (PLINT)(COL_SERIES + s->color % BF_PLOT_NCOLORS);
        lstyle[n] = s->dashed ? 2 : 1;
        lwidth[n] = LINE_WIDTH;
        sscale[n] = MARKER_SCALE / LEGEND_SCALE;
        snum[n] = 1;
        sym[n] = markers[s->marker % BF_PLOT_NMARKERS];
        pattern[n] = 0;
        bscale[n] = 0.8;
        bwidth[n] = 1.0;
        ink[n] = COL_INK;
        n++;
    }
    if (n == 0 || p->legend == 0) {
        return;
    }
    pos = PL_POSITION_INSIDE | PL_POSITION_TOP | PL_POSITION_LEFT;
    if (p->legend == 2) {
        pos = PL_POSITION_INSIDE | PL_POSITION_TOP | PL_POSITION_RIGHT;
    } else if (p->legend == 3) {
        pos = PL_POSITION_INSIDE | PL_POSITION_BOTTOM | PL_POSITION_RIGHT;
    } else if (p->legend == 4) {
        pos = PL_POSITION_OUTSIDE | PL_POSITION_RIGHT;
    }
    plschr(0.0, text_scale);
    pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, pos,
             0.02, 0.02, 0.06, COL_BG, COL_GRID, 1, 0, 0, (PLINT)n, opt, 0.8,
             LEGEND_SCALE, 1.8, 0.0, ink, text, color, pattern, bscale,
             bwidth, color, lstyle, lwidth, color, sscale, snum, sym);
}

/* ==== panels ============================================================== */

/* Where the current panel sits: its column and row in the figure's grid,
 * to convert the page coordinates PLplot reports (plgvpd) back to the
 * subpage coordinates plvpor takes (subpages tile the page exactly). */
typedef struct {
    size_t col, row, nx, ny;
} cell;

/* Number of characters (not bytes) of UTF-8 text. */
static size_t utf8_len(const char *s)
{
    size_t n = 0;
    for (; *s != '\0'; s++) {
        n += (*s & 0xC0) != 0x80;
    }
    return n;
}

/* Width to keep free for a legend outside the axes, as a fraction of the
 * subpage width, estimated from the longest label (PLplot cannot measure
 * a legend before drawing it). */
static double legend_room(const bf_plot_panel *p)
{
    PLFLT def;
    PLFLT ht;
    PLFLT x0;
    PLFLT x1;
    PLFLT y0;
    PLFLT y1;
    size_t longest = 0;
    size_t i;
    for (i = 0; i < p->n_series; i++) {
        if (p->series[i].label != NULL) {
            size_t n = utf8_len(p->series[i].label);
            longest = n > longest ? n : longest;
        }
    }
    plgchr(&def, &ht);       /* character height, mm */
    plgspa(&x0, &x1, &y0, &y1); /* subpage, mm */
    return (LEGEND_SCALE * (CHAR_WIDTH * (double)longest + LEGEND_KEY) * ht) /
           (x1 - x0);
}

/* Sets the panel's viewport: PLplot's standard one (room for the labels),
 * narrowed for a legend outside on the right, with the given aspect ratio
 * (height / width of the axes) when aspect > 0. */
static void viewport(const bf_plot_panel *p, const cell *c, double aspect)
{
    PLFLT x0;
    PLFLT x1;
    PLFLT y0;
    PLFLT y1;
    double sx0 = (double)c->col / (double)c->nx;
    double sy0 = 1.0 - (double)(c->row + 1) / (double)c->ny;
    plvsta();
    plgvpd(&x0, &x1, &y0, &y1); /* page coordinates */
    x0 = (x0 - sx0) * (double)c->nx;
    x1 = (x1 - sx0) * (double)c->nx;
    y0 = (y0 - sy0) * (double)c->ny;
    y1 = (y1 - sy0) * (double)c->ny;
    if (p->legend == 4) {
        x1 -= legend_room(p);
    }
    if (aspect > 0.0) {
        plvpas(x0, x1, y0, y1, aspect);
    } else {
        plvpor(x0, x1, y0, y1);
    }
}

static void box_panel(const bf_plot_panel *p, const cell *c,
                      double text_scale)
{
    char t[512];
    tick_labels ticks;
    double y0 = ymap(p, p->ymin);
    double y1 = ymap(p, p->ymax);
    size_t i;

    viewport(p, c, p->square ? 1.0 : 0.0);
    plwind(p->xmin, p->xmax, y0, y1);
    plcol0(COL_INK);
    plwidth(1.0);
    if (p->n_xticks > 0) {
        ticks.labels = p->xtick_labels;
        ticks.n = p->n_xticks;
        plslabelfunc(tick_label, &ticks);
        plbox("bcnsto", 1.0, 1, p->logy ? "bcnstlv" : "bcnstv", 0.0, 0);
        plslabelfunc(NULL, NULL);
    } else {
        plbox("bcnst", 0.0, 0, p->logy ? "bcnstlv" : "bcnstv", 0.0, 0);
    }
    plmtex("t", 1.2, 0.5, 0.5, esc(p->title, t, sizeof t));
    plmtex("b", 3.0, 0.5, 0.5, esc(p->xlabel, t, sizeof t));
    plmtex("l", p->logy ? 4.5 : 4.0, 0.5, 0.5, esc(p->ylabel, t, sizeof t));
    if (p->diagonal) {
        double lo = fmax(p->xmin, p->ymin);
        double hi = fmin(p->xmax, p->ymax);
        PLFLT dx[2] = {lo, hi};
        PLFLT dy[2] = {lo, hi};
        plcol0(COL_GRID);
        plwidth(LINE_WIDTH);
        if (lo < hi) {
            plline(2, dx, dy);
        }
    }
    for (i = 0; i < p->n_series; i++) {
        const bf_plot_series *s = &p->series[i];
        size_t k;
        size_t chunk;
        set_color(s->color);
        plwidth(LINE_WIDTH);
        set_dashed(s->dashed);
        /* map y in chunks (no allocation) */
        for (k = 0; k < s->n; k += chunk) {
            PLFLT ym[256];
            size_t j;
            chunk = s->n - k < 256 ? s->n - k : 256;
            for (j = 0; j < chunk; j++) {
                ym[j] = ymap(p, s->y[k + j]);
            }
            if (s->style == BF_SERIES_LINE ||
                s->style == BF_SERIES_LINEPOINTS) {
                /* overlap chunks by one point so the line is continuous */
                size_t m = chunk + (k + chunk < s->n ? 1 : 0);
                PLFLT yl[257];
                memcpy(yl, ym, chunk * sizeof *ym);
                if (m > chunk) {
                    yl[chunk] = ymap(p, s->y[k + chunk]);
                }
                polyline(m, &s->x[k], yl);
                if (s->style == BF_SERIES_LINEPOINTS) {
                    points(chunk, &s->x[k], ym, s->marker, text_scale);
                }
            } else if (s->style == BF_SERIES_POINTS) {
                points(chunk, &s->x[k], ym, s->marker, text_scale);
            } else {
                bars(chunk, &s->x[k], ym, y1, s->color, text_scale);
            }
        }
        set_dashed(0);
    }
    legend(p, text_scale);
}

/* Polar coordinates (angle from the vertical, radius) -> page. */
static void to_xy(double a, double r, double *x, double *y)
{
    *x = r * sin(a);
    *y = r * cos(a);
}

static void polar_grid(const bf_plot_panel *p)
{
    double R = p->ymax;
    PLFLT ax[POLAR_ARC_POINTS];
    PLFLT ay[POLAR_ARC_POINTS];
    char t[64];
    int ring;
    int deg;
    size_t i;

    plcol0(COL_GRID);
    plwidth(1.0);
    for (ring = 1; ring <= POLAR_RINGS; ring++) {
        double r = R * ring / POLAR_RINGS;
        for (i = 0; i < POLAR_ARC_POINTS; i++) {
            double a = -M_PI / 2 + M_PI * (double)i / (POLAR_ARC_POINTS - 1);
            to_xy(a, r, &ax[i], &ay[i]);
        }
        plline(POLAR_ARC_POINTS, ax, ay);
        snprintf(t, sizeof t, "%.3g", r);
        plcol0(COL_INK);
        plptex(r, -0.06 * R, 1.0, 0.0, 0.5, t);
        plcol0(COL_GRID);
    }
    for (deg = -90; deg <= 90; deg += POLAR_STEP_DEG) {
        double a = deg * M_PI / 180.0;
        PLFLT lx[2] = {0.0, 0.0};
        PLFLT ly[2] = {0.0, 0.0};
        double tx;
        double ty;
        to_xy(a, R, &lx[1], &ly[1]);
        plcol0(COL_GRID);
        plline(2, lx, ly);
        to_xy(a, 1.07 * R, &tx, &ty);
        if (deg == -90 || deg == 90) {
            ty += 0.04 * R; /* above the surface line and radius labels */
        }
        snprintf(t, sizeof t, "%d°", deg);
        plcol0(COL_INK);
        plptex(tx, ty, 1.0, 0.0, 0.5, t);
    }
    plcol0(COL_INK);
    plwidth(LINE_WIDTH);
    {
        PLFLT bx[2] = {-R, R};
        PLFLT by[2] = {0.0, 0.0};
        plline(2, bx, by); /* the surface */
    }
}

static void polar_panel(const bf_plot_panel *p, const cell *c,
                        double text_scale)
{
    char t[512];
    double R = p->ymax;
    size_t i;

    viewport(p, c, (1.15 + 0.1) / (2 * POLAR_MARGIN));
    plwind(-POLAR_MARGIN * R, POLAR_MARGIN * R, -0.1 * R, 1.15 * R);
    plcol0(COL_INK);
    plmtex("t", 1.2, 0.5, 0.5, esc(p->title, t, sizeof t));
    plmtex("b", 1.0, 0.5, 0.5, esc(p->xlabel, t, sizeof t));
    polar_grid(p);
    for (i = 0; i < p->n_series; i++) {
        const bf_plot_series *s = &p->series[i];
        size_t k;
        set_color(s->color);
        plwidth(LINE_WIDTH);
        set_dashed(s->dashed);
        for (k = 0; k < s->n;) {
            PLFLT px[256];
            PLFLT py[256];
            size_t j;
            size_t chunk = s->n - k < 255 ? s->n - k : 255;
            size_t m = chunk + (s->style == BF_SERIES_LINE && k + chunk < s->n);
            for (j = 0; j < m; j++) {
                double r = s->y[k + j];
                if (!(r >= 0.0) || r > R) {
                    px[j] = NAN; /* outside the plotted radius: break */
                    py[j] = NAN;
                } else {
                    to_xy(s->x[k + j], r, &px[j], &py[j]);
                }
            }
            if (s->style == BF_SERIES_LINE) {
                polyline(m, px, py);
            } else {
                points(chunk, px, py, s->marker, text_scale);
            }
            k += chunk;
        }
        set_dashed(0);
    }
    legend(p, text_scale);
}

/* ==== the figure ========================================================== */

int bf_plot_write(const bf_plot_figure *fig, bf_plot_format fmt,
                  const char *path)
{
    struct stat st;
    FILE *probe;
    size_t i;

    if (!figure_ok(fig) || (unsigned)fmt >= BF_PLOT_NFORMATS ||
        path == NULL) {
        return BF_EINVAL;
    }
    /* PLplot exits the process when it cannot open its output: check
     * first that the file can be written. */
    probe = fopen(path, "wb");
    if (probe == NULL) {
        return BF_EIO;
    }
    fclose(probe);

    plsdev(devices[fmt]);
    plsfnam(path);
    plspage(0.0, 0.0, (PLINT)fig->width, (PLINT)fig->height, 0, 0);
    for (i = 0; i < sizeof cmap0 / sizeof *cmap0; i++) {
        plscol0((PLINT)i, cmap0[i][0], cmap0[i][1], cmap0[i][2]);
    }
    plssub((PLINT)fig->nx, (PLINT)fig->ny);
    plinit();
    plschr(0.0, fig->text_scale);
    for (i = 0; i < fig->n_panels; i++) {
        cell c;
        c.col = i % fig->nx;
        c.row = i / fig->nx;
        c.nx = fig->nx;
        c.ny = fig->ny;
        pladv(0);
        if (fig->panels[i].polar) {
            polar_panel(&fig->panels[i], &c, fig->text_scale);
        } else {
            box_panel(&fig->panels[i], &c, fig->text_scale);
        }
    }
    plend();
    if (stat(path, &st) != 0 || st.st_size == 0) {
        return BF_EIO;
    }
    return BF_OK;
}
