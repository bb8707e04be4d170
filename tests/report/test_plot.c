/* test_plot.c: the figure writer (src/report/plot.c, plot_layout.c,
 * plot_style.c, png.c, model_style.c) -- each format gives a valid file of
 * the size bf_plot_size reports, without title or date metadata; markers
 * are one path a series in SVG; the same description gives the same bytes
 * whatever was drawn before; the style slots tell every registry model
 * apart; invalid descriptions are refused without writing; no figure is
 * taller than BF_PLOT_MAX_TALL times its width, and panels re-flow into a
 * grid that fits; an unwritable path is an I/O error. */
#include <criterion/criterion.h>
#include <math.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "formats.h"
#include "model_style.h"
#include "plot.h"
#include "plot_internal.h"
#include "support.h"

/* A figure of two panels: a line and points with a legend entry each, and
 * a polar panel; its height comes from the width and the aspect. */
static double xs[5] = {0.1, 0.3, 0.45, 0.7, 0.9};
static double ys[5] = {0.2, NAN, 0.5, 0.65, 0.95};
static double as[5] = {-1.2, -0.5, 0.0, 0.4, 1.3};

static void describe(bf_plot_figure *fig, bf_plot_panel panel[2],
                     bf_plot_series ser[3])
{
    memset(ser, 0, 3 * sizeof *ser);
    ser[0].kind = BF_SERIES_LINE;
    ser[0].x = xs;
    ser[0].y = ys;
    ser[0].n = 5;
    ser[0].style = 1;
    ser[0].mark_every = 2;
    ser[0].label = "line # with a hash and L_{max}";
    ser[1].kind = BF_SERIES_POINTS;
    ser[1].x = xs;
    ser[1].y = xs;
    ser[1].n = 5;
    ser[1].style = BF_PLOT_INK;
    ser[1].label = "points";
    ser[2] = ser[0];
    ser[2].x = as;
    memset(panel, 0, 2 * sizeof *panel);
    panel[0].xmax = panel[0].ymax = 1.0;
    panel[0].diagonal = 1;
    panel[0].xlabel = "x (1)";
    panel[0].ylabel = "y (1)";
    panel[0].note = "a note";
    panel[0].series = ser;
    panel[0].n_series = 2;
    panel[1].polar = 1;
    panel[1].ymax = 1.0;
    panel[1].series = &ser[2];
    panel[1].n_series = 1;
    memset(fig, 0, sizeof *fig);
    fig->width = BF_PLOT_SINGLE_COLUMN + 51; /* an odd width on purpose */
    fig->aspect = 0.8;
    fig->nx = 2;
    fig->ny = 1;
    fig->legend = BF_LEGEND_TOP;
    fig->panels = panel;
    fig->n_panels = 2;
}

static const char *path_in(const char *dir, const char *name)
{
    static char path[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", dir, name);
    return path[k];
}

/* Draws the two-panel figure in format fmt into a fresh folder; returns
 * the file's path and its size in points. */
static const char *draw_in(bf_plot_format fmt, const char *name, unsigned *w,
                           unsigned *h)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[3];
    const char *path;
    describe(&fig, panel, ser);
    cr_assert_eq(bf_plot_size(&fig, w, h), BF_OK);
    path = path_in(bf_test_tmpdir(), name);
    cr_assert_eq(bf_plot_write(&fig, fmt, path), BF_OK);
    return path;
}

Test(plot, writes_a_palette_png_of_150_pixels_per_inch_without_metadata)
{
    unsigned w;
    unsigned h;
    const char *path = draw_in(BF_PLOT_PNG, "f.png", &w, &h);
    cr_assert_eq(w, BF_PLOT_SINGLE_COLUMN + 51);
    /* 303 points at 150 dpi: 303 * 150 / 72 = 631.25 -> 631 */
    fmt_check_png(path, 631, bf_plot_png_pixels(h));
    cr_expect_eq(fmt_check_png_plain(path), 3, "colour type 3: a palette");
}

Test(plot, takes_the_height_from_the_width_and_the_aspect)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[3];
    unsigned w;
    unsigned h1;
    unsigned h2;
    describe(&fig, panel, ser);
    cr_assert_eq(bf_plot_size(&fig, &w, &h1), BF_OK);
    fig.panels = panel; /* box axes only: the aspect decides */
    fig.n_panels = 1;
    fig.nx = 1;
    cr_assert_eq(bf_plot_size(&fig, &w, &h1), BF_OK);
    fig.aspect = 1.2;
    cr_assert_eq(bf_plot_size(&fig, &w, &h2), BF_OK);
    /* axes 1.5 times as tall, the same margins: the height grows by 0.4
     * times the axes width, which is less than the figure's */
    cr_expect_gt(h2, h1);
    cr_expect_lt(h2 - h1, (unsigned)(0.4 * w) + 1);
    fig.height = 400;
    cr_assert_eq(bf_plot_size(&fig, &w, &h2), BF_OK);
    cr_expect_eq(h2, 400u, "a given height is kept");
}

/* n scatter-like panels (aspect 1, shared axes, each named by its note)
 * of a double-column figure. */
static void panels_of(bf_plot_figure *fig, bf_plot_panel *panel, size_t n)
{
    size_t i;
    memset(panel, 0, n * sizeof *panel);
    for (i = 0; i < n; i++) {
        panel[i].xmax = panel[i].ymax = 1.0;
        panel[i].diagonal = 1;
        panel[i].note = "model: LSE 1.00";
    }
    memset(fig, 0, sizeof *fig);
    fig->width = BF_PLOT_DOUBLE_COLUMN;
    fig->aspect = 1.0;
    fig->share_x = fig->share_y = 1;
    fig->xlabel = "measured";
    fig->ylabel = "predicted";
    fig->panels = panel;
    fig->n_panels = n;
}

Test(plot, refuses_a_figure_taller_than_a_page_allows)
{
    bf_plot_figure fig;
    bf_plot_panel panel[3];
    unsigned w;
    unsigned h;
    const char *path = path_in(bf_test_tmpdir(), "tall.png");
    struct stat sb;
    panels_of(&fig, panel, 3);
    fig.nx = 1; /* three square panels in a column: about 3 widths tall */
    fig.ny = 3;
    cr_expect_eq(bf_plot_size(&fig, &w, &h), BF_EINVAL);
    cr_expect_eq(bf_plot_fits(&fig, 0.0), 0);
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    cr_expect_neq(stat(path, &sb), 0, "nothing written");
    fig.nx = 3; /* in a row: fits */
    fig.ny = 1;
    cr_assert_eq(bf_plot_size(&fig, &w, &h), BF_OK);
    cr_expect_leq((double)h, BF_PLOT_MAX_TALL * w);
    fig.nx = 1; /* a given height is held to the same bound */
    fig.ny = 1;
    fig.n_panels = 1;
    fig.height = (unsigned)(BF_PLOT_MAX_TALL * fig.width) + 1;
    cr_expect_eq(bf_plot_size(&fig, &w, &h), BF_EINVAL);
    fig.height -= 1;
    cr_expect_eq(bf_plot_size(&fig, &w, &h), BF_OK);
}

Test(plot, re_flows_panels_into_the_fewest_rows_of_wide_enough_axes)
{
    bf_plot_figure fig;
    bf_plot_panel panel[11];
    unsigned w;
    unsigned h;
    size_t n;
    for (n = 1; n <= 11; n++) {
        panels_of(&fig, panel, n);
        cr_assert_eq(bf_plot_flow(&fig, 100.0), BF_OK, "%zu panels", n);
        cr_expect_geq(fig.nx * fig.ny, n);
        cr_expect_lt(fig.nx * (fig.ny - 1), n, "%zu panels: no empty row",
                     n);
        cr_assert_eq(bf_plot_size(&fig, &w, &h), BF_OK);
        cr_expect_leq((double)h, BF_PLOT_MAX_TALL * w, "%zu panels", n);
        cr_expect(bf_plot_fits(&fig, 100.0), "%zu panels: axes >= 100 pt",
                  n);
        if (fig.ny > 1) { /* one row fewer would be too narrow */
            size_t nx = fig.nx;
            fig.nx = (n + fig.ny - 2) / (fig.ny - 1);
            fig.ny = (n + fig.nx - 1) / fig.nx;
            cr_expect(!bf_plot_fits(&fig, 100.0), "%zu panels in %zu rows",
                      n, fig.ny);
            fig.nx = nx;
        }
    }
    /* four panels fit in one row; eleven take rows of at most 4 */
    panels_of(&fig, panel, 4);
    cr_assert_eq(bf_plot_flow(&fig, 100.0), BF_OK);
    cr_expect_eq(fig.ny, 1u);
    panels_of(&fig, panel, 11);
    cr_assert_eq(bf_plot_flow(&fig, 100.0), BF_OK);
    cr_expect_leq(fig.nx, 4u);
    /* wider than any grid allows: the widest axes that fit */
    panels_of(&fig, panel, 11);
    cr_assert_eq(bf_plot_flow(&fig, 1000.0), BF_OK);
    cr_assert_eq(bf_plot_size(&fig, &w, &h), BF_OK);
    cr_expect_leq((double)h, BF_PLOT_MAX_TALL * w);
}

Test(plot, writes_a_well_formed_svg_in_points_without_a_title)
{
    unsigned w;
    unsigned h;
    const char *path = draw_in(BF_PLOT_SVG, "f.svg", &w, &h);
    fmt_check_svg(path, w, h);
    fmt_check_svg_plain(path);
}

Test(plot, writes_a_one_page_pdf_in_points_without_title_or_date)
{
    unsigned w;
    unsigned h;
    const char *path = draw_in(BF_PLOT_PDF, "f.pdf", &w, &h);
    fmt_check_pdf(path, w, h);
    fmt_check_pdf_plain(path);
}

/* The markers and the dashes of a series are one path each in SVG: 600
 * points (some 200 dashes) give as many paths as 6. */
Test(plot, draws_all_markers_and_dashes_of_a_series_as_one_svg_path)
{
    static double x[600];
    static double y[600];
    bf_plot_series s;
    bf_plot_panel p;
    bf_plot_figure fig;
    const char *dir = bf_test_tmpdir();
    size_t few;
    size_t many;
    size_t i;
    for (i = 0; i < 600; i++) {
        x[i] = 0.05 + 0.9 * (double)i / 599.0;
        y[i] = 0.5 + 0.4 * sin(7.3 * x[i]);
    }
    memset(&s, 0, sizeof s);
    s.kind = BF_SERIES_POINTS;
    s.x = x;
    s.y = y;
    s.n = 6;
    s.style = 5; /* an open marker (outer and inner outline); dash-dot-dot */
    memset(&p, 0, sizeof p);
    p.xmax = p.ymax = 1.0;
    p.series = &s;
    p.n_series = 1;
    memset(&fig, 0, sizeof fig);
    fig.width = 300;
    fig.nx = fig.ny = 1;
    fig.panels = &p;
    fig.n_panels = 1;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_SVG, path_in(dir, "a.svg")),
                 BF_OK);
    s.n = 600;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_SVG, path_in(dir, "b.svg")),
                 BF_OK);
    few = fmt_check_svg_plain(path_in(dir, "a.svg"));
    many = fmt_check_svg_plain(path_in(dir, "b.svg"));
    cr_expect_eq(many, few, "600 markers: %zu paths, 6 markers: %zu", many,
                 few);
    s.kind = BF_SERIES_LINE; /* the same points as a dashed line */
    s.n = 6;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_SVG, path_in(dir, "c.svg")),
                 BF_OK);
    s.n = 600;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_SVG, path_in(dir, "d.svg")),
                 BF_OK);
    few = fmt_check_svg_plain(path_in(dir, "c.svg"));
    many = fmt_check_svg_plain(path_in(dir, "d.svg"));
    cr_expect_eq(many, few, "dashed line of 600 points: %zu paths, of 6: %zu",
                 many, few);
}

/* Figures are drawn in any order by any process: a figure's bytes must
 * not depend on what was drawn before. */
Test(plot, gives_the_same_bytes_whatever_was_drawn_before)
{
    static const bf_plot_format fmts[3] = {BF_PLOT_PNG, BF_PLOT_SVG,
                                           BF_PLOT_PDF};
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[3];
    const char *dir = bf_test_tmpdir();
    size_t f;
    for (f = 0; f < 3; f++) {
        char a[64];
        char b[64];
        char other[64];
        size_t la;
        size_t lb;
        char *da;
        char *db;
        snprintf(a, sizeof a, "a.%s", bf_plot_format_ext(fmts[f]));
        snprintf(b, sizeof b, "b.%s", bf_plot_format_ext(fmts[f]));
        snprintf(other, sizeof other, "o.%s", bf_plot_format_ext(fmts[f]));
        describe(&fig, panel, ser);
        cr_assert_eq(bf_plot_write(&fig, fmts[f], path_in(dir, a)), BF_OK);
        fig.legend = BF_LEGEND_RIGHT; /* something else in between */
        panel[0].logy = 1;
        panel[0].ymin = 0.01;
        cr_assert_eq(bf_plot_write(&fig, fmts[(f + 1) % 3],
                                   path_in(dir, other)),
                     BF_OK);
        describe(&fig, panel, ser);
        cr_assert_eq(bf_plot_write(&fig, fmts[f], path_in(dir, b)), BF_OK);
        da = fmt_read(path_in(dir, a), &la);
        db = fmt_read(path_in(dir, b), &lb);
        cr_expect(la == lb && memcmp(da, db, la) == 0,
                  "%s differs when drawn after another figure", a);
        free(da);
        free(db);
    }
}

/* Every model of the registry gets its own slot, and the slots differ:
 * each has its own marker, and no two share both colour and dash; the
 * paper's six (slots 0-5) differ in all three. */
Test(plot, gives_every_registry_model_a_style_of_its_own)
{
    unsigned used = 0;
    size_t i;
    size_t j;
    for (i = 0; i < bf_model_count(); i++) {
        unsigned s = bf_report_model_style(bf_model_get(i));
        cr_assert_lt(s, BF_PLOT_NSTYLES, "%s", bf_model_get(i)->name);
        cr_expect(!((used >> s) & 1u), "%s shares slot %u",
                  bf_model_get(i)->name, s);
        used |= 1u << s;
    }
    for (i = 0; i < BF_PLOT_NSTYLES; i++) {
        for (j = i + 1; j < BF_PLOT_NSTYLES; j++) {
            unsigned a = (unsigned)i;
            unsigned b = (unsigned)j;
            cr_expect_str_neq(bf_plot_style_marker(a),
                              bf_plot_style_marker(b),
                              "slots %u and %u share a marker", a, b);
            cr_expect(strcmp(bf_plot_style_hex(a), bf_plot_style_hex(b)) ||
                          strcmp(bf_plot_style_dash(a),
                                 bf_plot_style_dash(b)),
                      "slots %u and %u share colour and dash", a, b);
            if (j < 6) {
                cr_expect_str_neq(bf_plot_style_hex(a), bf_plot_style_hex(b));
                cr_expect_str_neq(bf_plot_style_dash(a),
                                  bf_plot_style_dash(b));
            }
        }
    }
    cr_expect_null(bf_plot_style_hex(BF_PLOT_REF + 1));
}

Test(plot, refuses_invalid_descriptions_without_writing_a_file)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[3];
    const char *dir = bf_test_tmpdir();
    const char *path = path_in(dir, "bad.png");
    struct stat sb;

    describe(&fig, panel, ser);
    fig.width = 0;
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    fig.width = BF_PLOT_MAX_SIZE + 1;
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    fig.width = 20; /* no room for the axes */
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    fig.nx = 1; /* two panels in a 1 x 1 grid */
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    panel[0].ymax = panel[0].ymin; /* empty range */
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    panel[0].logy = 1; /* log axis from 0 */
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    ser[1].y = NULL;
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    ser[1].style = BF_PLOT_REF + 1; /* no such slot */
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_NFORMATS, path), BF_EINVAL);
    cr_expect_eq(bf_plot_write(NULL, BF_PLOT_PNG, path), BF_EINVAL);
    cr_assert_neq(stat(path, &sb), 0, "an invalid figure left a file");
}

/* Error bars (BF_SERIES_ERRORBARS): vertical segments from y to y2 are
 * drawn (the figure changes), a bar with a non-finite end is skipped (the
 * same bytes as no bar), and a series without y2 is refused. */
static int same_bytes(const char *a, const char *b)
{
    size_t la;
    size_t lb;
    char *da = fmt_read(a, &la);
    char *db = fmt_read(b, &lb);
    int same = la == lb && memcmp(da, db, la) == 0;
    free(da);
    free(db);
    return same;
}

Test(plot, draws_error_bars_from_y_to_y2)
{
    static double x[3] = {0.2, 0.5, 0.8};
    static double lo[3] = {0.3, 0.4, 0.2};
    static double hi[3] = {0.6, 0.7, NAN};
    bf_plot_series s;
    bf_plot_panel p;
    bf_plot_figure fig;
    const char *dir = bf_test_tmpdir();
    memset(&s, 0, sizeof s);
    s.kind = BF_SERIES_ERRORBARS;
    s.x = x;
    s.y = lo;
    s.y2 = hi;
    s.style = 2;
    s.label = "interval";
    memset(&p, 0, sizeof p);
    p.xmax = p.ymax = 1.0;
    p.series = &s;
    p.n_series = 1;
    memset(&fig, 0, sizeof fig);
    fig.width = 300;
    fig.nx = fig.ny = 1;
    fig.legend = BF_LEGEND_TOP;
    fig.panels = &p;
    fig.n_panels = 1;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_PNG, path_in(dir, "e0.png")),
                 BF_OK);
    s.n = 2;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_PNG, path_in(dir, "e2.png")),
                 BF_OK);
    s.n = 3; /* the third has no upper end */
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_PNG, path_in(dir, "e3.png")),
                 BF_OK);
    cr_expect(!same_bytes(path_in(dir, "e0.png"), path_in(dir, "e2.png")),
              "two error bars drew nothing");
    cr_expect(same_bytes(path_in(dir, "e2.png"), path_in(dir, "e3.png")),
              "a bar without its upper end was drawn");
    s.y2 = NULL;
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path_in(dir, "bad.png")),
                 BF_EINVAL);
}

Test(plot, reports_an_unwritable_path_as_an_io_error)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[3];
    int f;
    describe(&fig, panel, ser);
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        cr_expect_eq(bf_plot_write(&fig, (bf_plot_format)f,
                                   "/nonexistent/brdffit/f"),
                     BF_EIO, "%s", bf_plot_format_ext((bf_plot_format)f));
    }
}

Test(plot, names_the_format_extensions_and_the_column_widths)
{
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_PNG), "png");
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_SVG), "svg");
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_PDF), "pdf");
    cr_assert_null(bf_plot_format_ext(BF_PLOT_NFORMATS));
    /* 3.5 in and 7 in at 72 points per inch; 150 pixels per inch */
    cr_assert_eq(BF_PLOT_SINGLE_COLUMN, 252u);
    cr_assert_eq(BF_PLOT_DOUBLE_COLUMN, 504u);
    cr_assert_eq(bf_plot_png_pixels(BF_PLOT_DOUBLE_COLUMN), 1050u);
}

/* A panel's x label wider than its column stays inside the page and off
 * its neighbours' (the last column's used to run off the right edge: ABC's
 * "refractive index ior" in a forest plot), set smaller where it must;
 * one that fits stays centred under its axes at the label font. */
Test(plot, keeps_every_x_label_inside_the_page_and_apart)
{
    static const char *const labels[3] = {"x", "fall-off C",
                                          "refractive index ior"};
    bf_plot_figure fig;
    bf_plot_panel panel[3];
    bf_plot_series ser;
    bf__layout *L = malloc(sizeof *L);
    double right = 0.0;
    size_t i;
    cr_assert_not_null(L);
    memset(&ser, 0, sizeof ser);
    ser.kind = BF_SERIES_POINTS;
    ser.x = xs;
    ser.y = xs;
    ser.n = 5;
    ser.style = BF_PLOT_INK;
    memset(panel, 0, sizeof panel);
    for (i = 0; i < 3; i++) {
        panel[i].xmax = panel[i].ymax = 1.0;
        panel[i].xlabel = labels[i];
        panel[i].series = &ser;
        panel[i].n_series = 1;
    }
    memset(&fig, 0, sizeof fig);
    fig.width = BF_PLOT_SINGLE_COLUMN;
    fig.nx = 3;
    fig.ny = 1;
    fig.panels = panel;
    fig.n_panels = 3;
    cr_assert_eq(bf__layout_make(&fig, L), BF_OK);
    for (i = 0; i < 3; i++) {
        double half = bf__text_width(labels[i], L->xlabel_size[i]) / 2;
        cr_expect_geq(L->xlabel_x[i] - half, right, "label %zu", i);
        right = L->xlabel_x[i] + half;
        cr_expect_leq(right, (double)fig.width, "label %zu", i);
    }
    /* the last label is wider than its span: smaller, and moved left */
    cr_expect_lt(L->xlabel_size[2], L->label_font);
    cr_expect_lt(L->xlabel_x[2], (L->axes[2].x0 + L->axes[2].x1) / 2);
    /* the first fits: the label font, centred under its axes */
    cr_expect_float_eq(L->xlabel_size[0], L->label_font, 1e-12);
    cr_expect_float_eq(L->xlabel_x[0], (L->axes[0].x0 + L->axes[0].x1) / 2,
                       1e-12);
    free(L);
}

/* x names (a bar or heat-map axis) are written upwards when two
 * neighbours would touch, though all of them together fit the axis: four
 * models where two long composite names sit side by side (the ΔBIC
 * figure wrote "LAMBERT+GGXLAMBERT+WARD"); short ones stay upright. */
Test(plot, writes_x_names_upwards_where_neighbours_would_touch)
{
    static const char *const longer[4] = {"FC-E", "VH-E", "LAMBERT+GGX",
                                          "LAMBERT+WARD"};
    static const char *const shorter[4] = {"FC-E", "VH-E", "GGX", "WARD"};
    const char *const *names[2] = {shorter, longer};
    bf__layout *L = malloc(sizeof *L);
    int c;
    cr_assert_not_null(L);
    for (c = 0; c < 2; c++) {
        bf_plot_figure fig;
        bf_plot_panel panel;
        double aw;
        double total = 0.0;
        size_t k;
        memset(&panel, 0, sizeof panel);
        panel.xmin = 0.5;
        panel.xmax = 4.5;
        panel.ymax = 1.0;
        panel.xtick_labels = names[c];
        panel.n_xticks = 4;
        memset(&fig, 0, sizeof fig);
        fig.width = 382; /* the ΔBIC figure's width for four models */
        fig.nx = fig.ny = 1;
        fig.panels = &panel;
        fig.n_panels = 1;
        cr_assert_eq(bf__layout_make(&fig, L), BF_OK);
        aw = L->axes[0].x1 - L->axes[0].x0;
        for (k = 0; k < 4; k++) {
            total += bf__text_width(names[c][k], L->font) + 2.0 * 1.6;
        }
        cr_assert_lt(total, aw, "case %d: all the names fit the axis", c);
        cr_expect_eq(L->xrot[0], c, "case %d", c);
    }
    free(L);
}
