/* plot_layout.c: where everything of a figure goes (plot_internal.h) --
 * the checks of a description, axis ticks and their labels, estimated text
 * widths, and the placement in points of the axes, tick numbers, shared
 * labels, column and row labels and the one legend. No PLplot here: the
 * layout is fixed before the page is opened, so a figure's height can be
 * known (bf_plot_size) without drawing it.
 *
 * References:
 *   [1] DejaVu Sans 2.37 advance widths (units of the em), the font the
 *       report draws with (fonts-dejavu-core): the text width estimates. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "brdffit.h"
#include "plot_internal.h"

/* Lengths in points at print size. */
#define TICK 2.5        /* outward tick marks */
#define PAD 1.6         /* between a tick and its number, and similar gaps */
#define LINE 1.25       /* line height, in font sizes */
#define LABEL_LINE 1.6  /* room of an axis label or note, in font sizes:
                           a line and the depth of a subscript */
#define NUM_H 0.75      /* height of digits, in font sizes */
#define GAP 5.0         /* between neighbouring panels */
#define EDGE 2.0        /* free border of the page */
#define LABEL_SHRINK 0.75 /* the smallest x label, of the label font */
#define KEY 16.0        /* legend key line */
#define ENTRY_GAP 9.0   /* between legend entries in a row */
#define TEXT_MARGIN 1.04 /* the width estimates are raised by 4% */

/* ==== text widths ======================================================== */

/* Advance width of an ASCII character in DejaVu Sans [1], in ems (rounded
 * up to the next 0.01; classes of similar letters share a value). */
static double ascii_width(unsigned char c)
{
    static const char *const narrow = "ijlI|!'.,:;";
    if (c >= '0' && c <= '9') {
        return 0.64;
    }
    if (c == ' ') {
        return 0.32;
    }
    if (strchr(narrow, c) != NULL) {
        return 0.34;
    }
    if (strchr("frt()[]/-J", c) != NULL) {
        return 0.42;
    }
    if (c == 'm' || c == 'M' || c == 'W' || c == '%') {
        return 0.99;
    }
    if (c == 'w' || c == '+' || c == '=' || c == '<' || c == '>') {
        return 0.84;
    }
    if (c >= 'A' && c <= 'Z') {
        return 0.78;
    }
    return 0.64;
}

double bf__text_width(const char *s, double size)
{
    double em = 0.0;
    if (s == NULL) {
        return 0.0;
    }
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c < 0x80) {
            em += ascii_width(c);
        } else if ((c & 0xC0) == 0xC0) { /* first byte of a multibyte char */
            em += 0.84; /* Greek letters, the minus sign, the degree sign */
        }
    }
    return TEXT_MARGIN * em * size;
}

/* ==== ticks ============================================================== */

/* Decimals needed to write multiples of step exactly (at most 6). */
static int decimals(double step)
{
    int d;
    for (d = 0; d < 6; d++) {
        double v = step * pow(10.0, d);
        if (fabs(v - floor(v + 0.5)) < 1e-6 * fmax(1.0, v)) {
            return d;
        }
    }
    return 6;
}

/* Writes v with d decimals and a true minus sign (U+2212); -0 is 0. */
static void number(double v, int d, char *buf, size_t len)
{
    char tmp[24];
    snprintf(tmp, sizeof tmp, "%.*f", d, v);
    if (tmp[0] == '-') {
        size_t i;
        int zero = 1;
        for (i = 1; tmp[i] != '\0'; i++) {
            zero = zero && (tmp[i] == '0' || tmp[i] == '.');
        }
        snprintf(buf, len, "%s%s", zero ? "" : "\xe2\x88\x92", tmp + 1);
    } else {
        snprintf(buf, len, "%s", tmp);
    }
}

/* The smallest round step (1, 2, 2.5 or 5 times a power of ten) of at
 * least min_step giving at most 7 ticks on [lo, hi]. */
static double auto_step(double lo, double hi, double min_step)
{
    static const double mult[4] = {1.0, 2.0, 2.5, 5.0};
    double span = hi - lo;
    double mag = pow(10.0, floor(log10(span / 6.0)));
    for (;; mag *= 10.0) {
        size_t i;
        for (i = 0; i < 4; i++) {
            double step = mult[i] * mag;
            if (span / step <= 6.5 && step >= min_step * (1.0 - 1e-9)) {
                return step;
            }
        }
    }
}

static void tick_add(bf__ticks *t, double v, const char *name, int d)
{
    if (t->n == BF__MAX_TICKS) {
        return;
    }
    t->v[t->n] = v;
    if (name != NULL) {
        t->text[t->n] = name;
    } else {
        number(v, d, t->num[t->n], sizeof t->num[t->n]);
        t->text[t->n] = t->num[t->n];
    }
    t->n++;
}

/* Most decades labelled on a log axis: more are labelled every second
 * (third, ...) decade. */
#define LOG_TICKS 6
/* Ticks of a log axis [lo, hi]: the decades as numbers (0.01, 0.1, 1, 10;
 * 1e-05 and 1e+06 beyond four digits), at most LOG_TICKS of them; an axis
 * with two decades or fewer in it has 1, 2 and 5 times the decades (or
 * every digit), so that it always has numbers to read. */
static void log_ticks(double lo, double hi, bf__ticks *t)
{
    static const double mant[2][9] = {{1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
    static const size_t n_mant[2] = {3, 9};
    double k0 = ceil(log10(lo) - 1e-9);
    double k1 = floor(log10(hi) + 1e-9);
    double stride = k1 - k0 + 1 > LOG_TICKS
                        ? ceil((k1 - k0 + 1) / LOG_TICKS)
                        : 1.0;
    double k;
    size_t j;
    int pass;
    if (k1 - k0 + 1 >= 3) { /* decades */
        for (k = k0; k <= k1; k += stride) {
            tick_add(t, pow(10.0, k), NULL, k < 0 ? (int)-k : 0);
            if (fabs(k) > 4) {
                snprintf(t->num[t->n - 1], sizeof t->num[t->n - 1], "1e%+.0f",
                         k);
            }
        }
        return;
    }
    for (pass = 0; pass < 2 && t->n < 2; pass++) {
        t->n = 0;
        for (k = floor(log10(lo)); k <= k1 + 1; k += 1.0) {
            for (j = 0; j < n_mant[pass]; j++) {
                double v = mant[pass][j] * pow(10.0, k);
                if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) {
                    tick_add(t, v, NULL, k < 0 ? (int)-k : 0);
                }
            }
        }
    }
}

void bf__ticks_make(double lo, double hi, double step, int logy,
                    const char *const *names, size_t n_names, bf__ticks *t)
{
    double eps = 1e-9 * (hi - lo);
    double k;
    size_t i;
    t->n = 0;
    if (names != NULL) {
        for (i = 1; i <= n_names; i++) {
            if ((double)i >= lo - eps && (double)i <= hi + eps) {
                tick_add(t, (double)i, names[i - 1], 0);
            }
        }
        return;
    }
    if (logy) {
        log_ticks(lo, hi, t);
        return;
    }
    if (!(step > 0.0)) {
        step = auto_step(lo, hi, 0.0);
    }
    for (k = ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0) {
        tick_add(t, k * step, NULL, decimals(step));
    }
}

/* ==== checks ============================================================= */

static int range_ok(double lo, double hi)
{
    return isfinite(lo) && isfinite(hi) && lo < hi;
}

static int series_ok(const bf_plot_series *s)
{
    if (s->n > 0 && (s->x == NULL || s->y == NULL ||
                     (s->kind == BF_SERIES_INTERVALS && s->x2 == NULL) ||
                     (s->kind == BF_SERIES_ERRORBARS && s->y2 == NULL))) {
        return 0;
    }
    return s->style < BF__NSLOTS && (unsigned)s->kind <= BF_SERIES_ERRORBARS;
}

static int panel_ok(const bf_plot_panel *p)
{
    size_t i;
    if (!range_ok(p->ymin, p->ymax) || (p->series == NULL && p->n_series) ||
        (!p->polar && !range_ok(p->xmin, p->xmax)) ||
        (p->logy && !(p->ymin > 0.0)) ||
        (p->n_xticks > 0 && p->xtick_labels == NULL) ||
        (p->n_yticks > 0 && p->ytick_labels == NULL)) {
        return 0;
    }
    if (p->cells != NULL &&
        (p->cells->cls == NULL || p->cells->n_classes == 0 ||
         p->cells->n_classes > BF_PLOT_NCLASSES ||
         p->cells->class_label == NULL)) {
        return 0;
    }
    for (i = 0; i < p->n_series; i++) {
        if (!series_ok(&p->series[i])) {
            return 0;
        }
    }
    return 1;
}

static int figure_ok(const bf_plot_figure *fig)
{
    size_t i;
    if (fig == NULL || fig->width == 0 || fig->width > BF_PLOT_MAX_SIZE ||
        fig->height > BF_PLOT_MAX_SIZE || fig->nx == 0 || fig->ny == 0 ||
        fig->panels == NULL || fig->n_panels == 0 ||
        fig->n_panels > fig->nx * fig->ny ||
        fig->n_panels > BF__MAX_PANELS || fig->font < 0.0 ||
        !(fig->aspect >= 0.0)) {
        return 0;
    }
    for (i = 0; i < fig->n_panels; i++) {
        if (!panel_ok(&fig->panels[i])) {
            return 0;
        }
    }
    return 1;
}

/* ==== legend ============================================================= */

/* Collects the legend entries: every labelled series once (by its text),
 * then the cell classes. */
static void collect_entries(const bf_plot_figure *fig, bf__layout *L)
{
    size_t i;
    size_t j;
    size_t k;
    L->n_entries = 0;
    for (i = 0; i < fig->n_panels; i++) {
        const bf_plot_panel *p = &fig->panels[i];
        for (j = 0; j < p->n_series; j++) {
            const bf_plot_series *s = &p->series[j];
            int dup = 0;
            if (s->label == NULL) {
                continue;
            }
            for (k = 0; k < L->n_entries && !dup; k++) {
                dup = strcmp(L->entry[k].text, s->label) == 0;
            }
            if (!dup && L->n_entries < BF__MAX_ENTRIES) {
                L->entry[L->n_entries].series = s;
                L->entry[L->n_entries].cls = -1;
                L->entry[L->n_entries].text = s->label;
                L->n_entries++;
            }
        }
        if (p->cells != NULL) {
            for (k = 0; k < p->cells->n_classes; k++) {
                if (L->n_entries < BF__MAX_ENTRIES) {
                    L->entry[L->n_entries].series = NULL;
                    L->entry[L->n_entries].cls = (int)k;
                    L->entry[L->n_entries].text = p->cells->class_label[k];
                    L->n_entries++;
                }
            }
        }
    }
}

static double entry_width(const bf__layout *L, const bf__entry *e)
{
    return L->key_width + PAD * 2 + bf__text_width(e->text, L->font);
}

/* Places the entries in rows of at most width points, starting at the
 * top row's centre height y, centred on cx; returns the number of rows.
 * With place = 0 only counts. */
static size_t flow_entries(bf__layout *L, double width, double cx, double y,
                           int place)
{
    size_t rows = 0;
    size_t i = 0;
    double row_h = L->font * 1.45;
    while (i < L->n_entries) {
        size_t j = i;
        double w = entry_width(L, &L->entry[j]);
        while (j + 1 < L->n_entries &&
               w + ENTRY_GAP + entry_width(L, &L->entry[j + 1]) <= width) {
            j++;
            w += ENTRY_GAP + entry_width(L, &L->entry[j]);
        }
        if (place) {
            double x = cx - w / 2;
            size_t k;
            for (k = i; k <= j; k++) {
                L->entry[k].x = x;
                L->entry[k].y = y - (double)rows * row_h;
                x += entry_width(L, &L->entry[k]) + ENTRY_GAP;
            }
        }
        rows++;
        i = j + 1;
    }
    return rows;
}

/* ==== the layout ========================================================= */

/* The widest y number (or name) of panel i. */
static double ynum_width(const bf__layout *L, size_t i)
{
    double w = 0.0;
    size_t k;
    for (k = 0; k < L->yt[i].n; k++) {
        w = fmax(w, bf__text_width(L->yt[i].text[k], L->font));
    }
    return w;
}

/* Whether the x numbers of t fit side by side on width points. */
static int ticks_fit(const bf__layout *L, const bf__ticks *t, double width)
{
    double total = 0.0;
    size_t k;
    for (k = 0; k < t->n; k++) {
        total += bf__text_width(t->text[k], L->font) + 3 * PAD;
    }
    return total <= width;
}

/* Whether the names of t stand side by side on an axis [lo, hi] of width
 * points, each centred on its tick: no two neighbours closer than half
 * their widths and two gaps. */
static int names_fit(const bf__layout *L, const bf__ticks *t, double lo,
                     double hi, double width)
{
    size_t k;
    for (k = 1; k < t->n; k++) {
        double room = (t->v[k] - t->v[k - 1]) / (hi - lo) * width;
        double need = 0.5 * (bf__text_width(t->text[k - 1], L->font) +
                             bf__text_width(t->text[k], L->font)) +
                      2 * PAD;
        if (need > room) {
            return 0;
        }
    }
    return 1;
}

/* Whether panel i is the lowest one of its column (it writes the x
 * numbers of a shared axis). */
static int lowest_in_column(const bf_plot_figure *fig, size_t i)
{
    return i + fig->nx >= fig->n_panels;
}

/* Room of the polar panels' labels, points: beside the half-disc (the
 * 90-degree labels), above it (the 0-degree label) and below the
 * surface line (the radius numbers). */
static void polar_room(const bf__layout *L, double *side, double *top,
                       double *bottom)
{
    *side = bf__text_width("\xe2\x88\x92" "90\xc2\xb0", L->font) + 2 * PAD;
    *top = L->font * 1.2 + PAD;
    *bottom = L->font * NUM_H + 2 * PAD;
}

/* Panel i's x label (axes placed): centred under its axes within its
 * span, from half way to the axes on its left (the page's edge) to half
 * way to those on its right; a label wider than the span is set smaller,
 * down to LABEL_SHRINK of the label font. */
static void xlabel_place(const bf_plot_figure *fig, bf__layout *L, size_t i)
{
    size_t c = i % fig->nx;
    const bf__box *a = &L->axes[i];
    double lo = c > 0 ? (L->axes[i - 1].x1 + a->x0) / 2 : EDGE;
    double hi = c + 1 < fig->nx && i + 1 < fig->n_panels
                    ? (a->x1 + L->axes[i + 1].x0) / 2
                    : (double)fig->width - EDGE;
    double w = fig->panels[i].xlabel != NULL
                   ? bf__text_width(fig->panels[i].xlabel, L->label_font)
                   : 0.0;
    double size = L->label_font;
    double half;
    if (w > hi - lo) {
        size = fmax(LABEL_SHRINK, (hi - lo) / w) * L->label_font;
        w *= size / L->label_font;
    }
    half = w / 2;
    L->xlabel_size[i] = size;
    L->xlabel_x[i] = 2 * half > hi - lo
                         ? (lo + hi) / 2
                         : fmax(lo + half, fmin((a->x0 + a->x1) / 2,
                                                hi - half));
}

int bf__layout_make(const bf_plot_figure *fig, bf__layout *L)
{
    double colL[BF__MAX_PANELS] = {0};
    double colR[BF__MAX_PANELS] = {0};
    double rowT[BF__MAX_PANELS] = {0};
    double rowB[BF__MAX_PANELS] = {0};
    double bot[BF__MAX_PANELS] = {0};
    double out_l;
    double out_r;
    double out_t;
    double out_b;
    double leg_t = 0.0;
    double leg_b = 0.0;
    double leg_r = 0.0;
    double aw;
    double ah;
    double sum_w = 0.0;
    double sum_h = 0.0;
    double x;
    double y;
    double side;
    double ptop;
    double pbot;
    int polar = 1;
    size_t i;
    size_t c;
    size_t r;

    if (!figure_ok(fig)) {
        return BF_EINVAL;
    }
    memset(L, 0, sizeof *L);
    L->font = fig->font > 0.0 ? fig->font : BF_PLOT_FONT;
    L->label_font = L->font + 1.0;
    L->tick = TICK;
    L->pad = PAD;
    L->key_width = KEY;
    L->width = fig->width;
    polar_room(L, &side, &ptop, &pbot);

    /* ticks, and the margins each panel needs inside its cell */
    for (i = 0; i < fig->n_panels; i++) {
        const bf_plot_panel *p = &fig->panels[i];
        double left = TICK;
        double bottom = TICK;
        double top = EDGE;
        double right = EDGE;
        c = i % fig->nx;
        r = i / fig->nx;
        polar = polar && p->polar;
        if (p->polar) {
            colL[c] = fmax(colL[c], EDGE);
            colR[c] = fmax(colR[c], EDGE);
            rowT[r] = fmax(rowT[r],
                           p->note != NULL ? L->font * LABEL_LINE : EDGE);
            continue;
        }
        bf__ticks_make(p->xmin, p->xmax, p->xtick, 0, p->xtick_labels,
                       p->n_xticks, &L->xt[i]);
        bf__ticks_make(p->ymin, p->ymax, p->ytick,
                       p->logy, p->ytick_labels, p->n_yticks, &L->yt[i]);
        L->xnum[i] = !fig->share_x || lowest_in_column(fig, i);
        L->ynum[i] = !fig->share_y || c == 0;
        L->ynum_width[i] = ynum_width(L, i);
        if (L->ynum[i]) {
            left += PAD + L->ynum_width[i];
            top = fmax(top, 0.5 * L->font);
        }
        if (p->ylabel != NULL) {
            left += PAD + L->label_font * LABEL_LINE;
        }
        if (L->xnum[i]) {
            L->xnum_height[i] = L->font * NUM_H;
            bottom += PAD + L->font * NUM_H;
            if (L->xt[i].n > 0) { /* the end numbers stick out by half */
                right = fmax(right, 0.5 * bf__text_width(
                                              L->xt[i].text[L->xt[i].n - 1],
                                              L->font));
                left = fmax(left, 0.5 * bf__text_width(L->xt[i].text[0],
                                                       L->font));
            }
        }
        if (p->xlabel != NULL) {
            bottom += PAD + L->label_font * LABEL_LINE;
        }
        if (p->note != NULL) {
            top = fmax(top, L->font * LABEL_LINE);
        }
        colL[c] = fmax(colL[c], left);
        colR[c] = fmax(colR[c], right);
        rowT[r] = fmax(rowT[r], top);
        bot[i] = bottom;
    }
    for (c = 0; c + 1 < fig->nx; c++) {
        colR[c] += GAP;
    }
    for (c = 0; c < fig->nx; c++) {
        sum_w += colL[c] + colR[c];
    }

    /* outer margins: shared labels, column and row labels, the legend */
    collect_entries(fig, L);
    if (fig->legend == BF_LEGEND_RIGHT && L->n_entries > 0) {
        for (i = 0; i < L->n_entries; i++) {
            leg_r = fmax(leg_r, entry_width(L, &L->entry[i]));
        }
        leg_r += 2 * GAP;
    } else if (fig->legend != BF_LEGEND_NONE && L->n_entries > 0) {
        double h = (double)flow_entries(L, fig->width - 2 * EDGE, 0, 0, 0) *
                   L->font * 1.45;
        if (fig->legend == BF_LEGEND_TOP) {
            leg_t = h + PAD;
        } else {
            leg_b = h + PAD;
        }
    }
    out_l = EDGE +
            (fig->ylabel != NULL ? L->label_font * LABEL_LINE + PAD : 0.0);
    out_b = EDGE + leg_b +
            (fig->xlabel != NULL ? L->label_font * LABEL_LINE + PAD : 0.0);
    out_t = EDGE + leg_t;
    out_r = EDGE + leg_r +
            (fig->row_labels != NULL ? L->label_font * LINE + PAD : 0.0);

    /* the axes: all the same size */
    aw = ((double)fig->width - out_l - out_r - sum_w) / (double)fig->nx;
    if (!(aw > 10.0)) {
        return BF_EINVAL; /* no room left for the axes */
    }
    /* column labels wider than the axes take two lines */
    L->col_lines = fig->col_labels != NULL ? 1 : 0;
    for (c = 0; fig->col_labels != NULL && c < fig->nx; c++) {
        if (bf__text_width(fig->col_labels[c], L->label_font) > aw + GAP) {
            L->col_lines = 2;
        }
    }
    out_t += (double)L->col_lines * L->label_font * LINE;
    /* numbers that do not fit side by side get a larger step */
    for (i = 0; i < fig->n_panels; i++) {
        const bf_plot_panel *p = &fig->panels[i];
        double step = p->xtick;
        int tries;
        for (tries = 0; !p->polar && L->xnum[i] && p->xtick_labels == NULL &&
                        !ticks_fit(L, &L->xt[i], aw) && tries < 8;
             tries++) {
            step = auto_step(p->xmin, p->xmax,
                             (L->xt[i].n > 1 ? L->xt[i].v[1] - L->xt[i].v[0]
                                             : step) *
                                 1.5);
            bf__ticks_make(p->xmin, p->xmax, step, 0, NULL, 0, &L->xt[i]);
        }
    }
    /* x names that do not fit side by side are written upwards */
    for (i = 0; i < fig->n_panels; i++) {
        const bf_plot_panel *p = &fig->panels[i];
        double widest = 0.0;
        size_t k;
        if (p->polar || !L->xnum[i] || p->xtick_labels == NULL) {
            continue;
        }
        for (k = 0; k < L->xt[i].n; k++) {
            widest = fmax(widest, bf__text_width(L->xt[i].text[k], L->font));
        }
        if (!names_fit(L, &L->xt[i], p->xmin, p->xmax, aw)) {
            L->xrot[i] = 1;
            bot[i] += widest - L->xnum_height[i];
            L->xnum_height[i] = widest;
        }
    }
    for (i = 0; i < fig->n_panels; i++) {
        r = i / fig->nx;
        rowB[r] = fmax(rowB[r], fig->panels[i].polar ? EDGE : bot[i]);
    }
    for (r = 0; r + 1 < fig->ny; r++) {
        rowB[r] += GAP;
    }
    for (r = 0; r < fig->ny; r++) {
        sum_h += rowT[r] + rowB[r];
    }
    if (polar) { /* the half-disc fills the width */
        double R = aw / 2 - side;
        ah = R + ptop + pbot;
    } else {
        ah = fig->aspect > 0.0 ? fig->aspect * aw : 0.62 * aw;
    }
    if (fig->height == 0) {
        L->height = (unsigned)ceil(out_t + out_b + sum_h +
                                   (double)fig->ny * ah);
        if (L->height > BF_PLOT_MAX_SIZE) {
            return BF_EINVAL;
        }
    } else {
        double room = (double)fig->height - out_t - out_b - sum_h;
        L->height = fig->height;
        if (!(room / (double)fig->ny > 10.0)) {
            return BF_EINVAL;
        }
        if (fig->aspect > 0.0 || polar) { /* keep the shape, centred */
            double want = ah;
            ah = fmin(want, room / (double)fig->ny);
            out_t += (room - (double)fig->ny * ah) / 2;
        } else {
            ah = room / (double)fig->ny;
        }
    }

    if ((double)L->height > BF_PLOT_MAX_TALL * (double)fig->width) {
        return BF_EINVAL; /* taller than a page allows */
    }

    /* place the axes, row by row from the top */
    L->polar_side = side;
    L->polar_top = ptop;
    L->polar_bottom = pbot;
    y = (double)L->height - out_t;
    for (r = 0; r < fig->ny; r++) {
        y -= rowT[r];
        x = out_l;
        for (c = 0; c < fig->nx; c++) {
            x += colL[c];
            i = r * fig->nx + c;
            if (i < fig->n_panels) {
                L->axes[i].x0 = x;
                L->axes[i].x1 = x + aw;
                L->axes[i].y0 = y - ah;
                L->axes[i].y1 = y;
            }
            x += aw + colR[c];
        }
        y -= ah + rowB[r];
    }
    for (i = 0; i < fig->n_panels; i++) {
        xlabel_place(fig, L, i);
    }
    L->grid = L->axes[0];
    for (i = 1; i < fig->n_panels; i++) {
        L->grid.x0 = fmin(L->grid.x0, L->axes[i].x0);
        L->grid.x1 = fmax(L->grid.x1, L->axes[i].x1);
        L->grid.y0 = fmin(L->grid.y0, L->axes[i].y0);
        L->grid.y1 = fmax(L->grid.y1, L->axes[i].y1);
    }
    L->xlabel_y = EDGE + leg_b + L->label_font * 0.9;
    L->ylabel_x = EDGE + L->label_font * 0.9;
    L->col_label_y = L->grid.y1 + rowT[0] +
                     (double)L->col_lines * L->label_font * LINE / 2;
    L->row_label_x = L->grid.x1 + colR[fig->nx - 1] + PAD +
                     L->label_font * 0.55;

    /* the legend */
    if (fig->legend == BF_LEGEND_RIGHT) {
        double ly = L->grid.y1 - L->font * 0.6;
        for (i = 0; i < L->n_entries; i++) {
            L->entry[i].x = (double)fig->width - EDGE - leg_r + GAP;
            L->entry[i].y = ly - (double)i * L->font * 1.45;
        }
    } else if (fig->legend == BF_LEGEND_TOP) {
        flow_entries(L, fig->width - 2 * EDGE, (double)fig->width / 2,
                     (double)L->height - EDGE - L->font * 0.7, 1);
    } else if (fig->legend == BF_LEGEND_BOTTOM) {
        size_t rows = flow_entries(L, fig->width - 2 * EDGE, 0, 0, 0);
        flow_entries(L, fig->width - 2 * EDGE, (double)fig->width / 2,
                     EDGE + (double)rows * L->font * 1.45 - L->font * 0.7,
                     1);
    } else {
        L->n_entries = 0;
    }
    return BF_OK;
}

int bf_plot_size(const bf_plot_figure *fig, unsigned *width,
                 unsigned *height)
{
    bf__layout *L = malloc(sizeof *L);
    int rc = L != NULL ? bf__layout_make(fig, L) : BF_ENOMEM;
    if (rc == BF_OK) {
        *width = L->width;
        *height = L->height;
    }
    free(L);
    return rc;
}

int bf_plot_fits(const bf_plot_figure *fig, double min_axes)
{
    bf__layout *L = malloc(sizeof *L);
    int fits = L != NULL && bf__layout_make(fig, L) == BF_OK &&
               L->axes[0].x1 - L->axes[0].x0 >= min_axes;
    free(L);
    return fits;
}

int bf_plot_flow(bf_plot_figure *fig, double min_axes)
{
    bf__layout *L = malloc(sizeof *L);
    size_t n = fig->n_panels;
    size_t rows;
    size_t best_nx = 0;
    double best_aw = 0.0;
    if (L == NULL) {
        return BF_ENOMEM;
    }
    /* from one row down to one column: the first grid whose axes are
     * min_axes wide; else the one with the widest axes that fits */
    for (rows = 1; rows <= n; rows++) {
        size_t nx = (n + rows - 1) / rows;
        double aw;
        if (rows > 1 && nx == (n + rows - 2) / (rows - 1)) {
            continue; /* the same grid as one row fewer */
        }
        fig->nx = nx;
        fig->ny = (n + nx - 1) / nx;
        if (bf__layout_make(fig, L) != BF_OK) {
            continue;
        }
        aw = L->axes[0].x1 - L->axes[0].x0;
        if (aw >= min_axes) {
            free(L);
            return BF_OK;
        }
        if (aw > best_aw) {
            best_aw = aw;
            best_nx = nx;
        }
    }
    free(L);
    if (best_nx == 0) {
        return BF_EINVAL;
    }
    fig->nx = best_nx;
    fig->ny = (n + best_nx - 1) / best_nx;
    return BF_OK;
}

unsigned bf_plot_png_pixels(unsigned points)
{
    return (unsigned)((double)points * BF_PLOT_PNG_DPI / 72.0 + 0.5);
}
