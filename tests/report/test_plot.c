/* test_plot.c: the figure writer (src/report/plot.c) -- each format gives
 * a valid file of the size asked for, invalid descriptions are refused
 * without writing, and an unwritable path is an I/O error. */
#include <criterion/criterion.h>
#include <math.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "formats.h"
#include "plot.h"
#include "support.h"

/* A figure of two panels: a line and points with a legend, and a polar
 * panel; width and height are odd on purpose. */
static const double xs[5] = {0.1, 0.3, 0.45, 0.7, 0.9};
static const double ys[5] = {0.2, NAN, 0.5, 0.65, 0.95};

static void describe(bf_plot_figure *fig, bf_plot_panel panel[2],
                     bf_plot_series ser[2])
{
    memset(ser, 0, 2 * sizeof *ser);
    ser[0].x = xs;
    ser[0].y = ys;
    ser[0].n = 5;
    ser[0].style = BF_SERIES_LINEPOINTS;
    ser[0].label = "line # with a hash";
    ser[1].x = xs;
    ser[1].y = xs;
    ser[1].n = 5;
    ser[1].style = BF_SERIES_POINTS;
    ser[1].color = 3;
    memset(panel, 0, 2 * sizeof *panel);
    panel[0].title = "box";
    panel[0].xlabel = "x (1)";
    panel[0].ylabel = "y (1)";
    panel[0].xmax = panel[0].ymax = 1.0;
    panel[0].diagonal = 1;
    panel[0].legend = 4;
    panel[0].series = ser;
    panel[0].n_series = 2;
    panel[1] = panel[0];
    panel[1].polar = 1;
    panel[1].legend = 0;
    memset(fig, 0, sizeof *fig);
    fig->width = 641;
    fig->height = 357;
    fig->nx = 2;
    fig->ny = 1;
    fig->text_scale = 0.9;
    fig->panels = panel;
    fig->n_panels = 2;
}

static const char *path_in(const char *dir, const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* Draws the two-panel figure in format fmt into a fresh folder; returns
 * the file's path. */
static const char *draw_in(bf_plot_format fmt, const char *name)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[2];
    const char *path;
    describe(&fig, panel, ser);
    path = path_in(bf_test_tmpdir(), name);
    cr_assert_eq(bf_plot_write(&fig, fmt, path), BF_OK);
    return path;
}

Test(plot, writes_a_png_of_the_requested_pixel_size)
{
    fmt_check_png(draw_in(BF_PLOT_PNG, "f.png"), 641, 357);
}

Test(plot, writes_a_well_formed_svg_of_the_requested_size_in_points)
{
    fmt_check_svg(draw_in(BF_PLOT_SVG, "f.svg"), 641, 357);
}

Test(plot, writes_a_one_page_pdf_of_the_requested_size_in_points)
{
    fmt_check_pdf(draw_in(BF_PLOT_PDF, "f.pdf"), 641, 357);
}

Test(plot, draws_a_log_axis_and_named_ticks)
{
    static const double lse[3] = {0.5, 4.0, 31.0};
    static const double at[3] = {1, 2, 3};
    static const char *const names[3] = {"34", "41", "23"};
    bf_plot_series s;
    bf_plot_panel p;
    bf_plot_figure fig;
    const char *dir = bf_test_tmpdir();
    memset(&s, 0, sizeof s);
    s.x = at;
    s.y = lse;
    s.n = 3;
    s.style = BF_SERIES_BARS;
    memset(&p, 0, sizeof p);
    p.xmin = 0.5;
    p.xmax = 3.5;
    p.ymin = 0.1;
    p.ymax = 100.0;
    p.logy = 1;
    p.xtick_labels = names;
    p.n_xticks = 3;
    p.series = &s;
    p.n_series = 1;
    memset(&fig, 0, sizeof fig);
    fig.width = 300;
    fig.height = 200;
    fig.nx = fig.ny = 1;
    fig.text_scale = 1.0;
    fig.panels = &p;
    fig.n_panels = 1;
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_PNG, path_in(dir, "l.png")),
                 BF_OK);
    fmt_check_png(path_in(dir, "l.png"), 300, 200);
}

Test(plot, refuses_invalid_descriptions_without_writing_a_file)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[2];
    const char *dir = bf_test_tmpdir();
    const char *path = path_in(dir, "bad.png");
    struct stat sb;

    describe(&fig, panel, ser);
    fig.width = 0;
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_PNG, path), BF_EINVAL);
    describe(&fig, panel, ser);
    fig.height = BF_PLOT_MAX_SIZE + 1;
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
    cr_expect_eq(bf_plot_write(&fig, BF_PLOT_NFORMATS, path), BF_EINVAL);
    cr_expect_eq(bf_plot_write(NULL, BF_PLOT_PNG, path), BF_EINVAL);
    cr_assert_neq(stat(path, &sb), 0, "an invalid figure left a file");
}

Test(plot, reports_an_unwritable_path_as_an_io_error)
{
    bf_plot_figure fig;
    bf_plot_panel panel[2];
    bf_plot_series ser[2];
    describe(&fig, panel, ser);
    cr_assert_eq(bf_plot_write(&fig, BF_PLOT_SVG,
                               "/nonexistent/brdffit/f.svg"),
                 BF_EIO);
}

Test(plot, names_the_format_extensions)
{
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_PNG), "png");
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_SVG), "svg");
    cr_assert_str_eq(bf_plot_format_ext(BF_PLOT_PDF), "pdf");
    cr_assert_null(bf_plot_format_ext(BF_PLOT_NFORMATS));
}
