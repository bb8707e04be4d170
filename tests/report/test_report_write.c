/* test_report_write.c: bf_report_write without the CLI -- on a dataset
 * built in memory with a constant BRDF (a Lambertian surface), LAMBERT is
 * recovered exactly (LSE 0 in fits.csv) and beats FC-E; every figure the
 * call counts is a PNG in figures/, the page names bf_report_write, the
 * description and tables go to the echo stream only; a bad option is an
 * option error (status, bf_error, message kind) and leaves no output; an
 * interval's text (bf_rep_interval_format, the tables' one writer) marks
 * an end at the range's bound and writes a split set as two segments. */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_run.h"
#include "ranking.h"
#include "support.h"

#define DEG (M_PI / 180.0)
#define NI 4  /* incidence angles */
#define NO 8  /* viewing zeniths */
#define NP 3  /* viewing azimuths */
#define NCONF (NI * NO * NP)

static bf_dataset *lambertian(void)
{
    static double angles[NCONF * 4];
    static double values[NCONF];
    bf_material_desc d;
    bf_dataset *ds = bf_dataset_alloc();
    size_t set;
    size_t k = 0;
    int i, o, p;
    cr_assert_not_null(ds);
    for (i = 0; i < NI; i++) {
        for (o = 0; o < NO; o++) {
            for (p = 0; p < NP; p++, k++) {
                angles[4 * k] = (10.0 + 20.0 * i) * DEG;
                angles[4 * k + 1] = 0.0;
                angles[4 * k + 2] = 10.0 * o * DEG;
                angles[4 * k + 3] = 90.0 * p * DEG;
                values[k] = 0.3; /* constant BRDF */
            }
        }
    }
    cr_assert_eq(bf_dataset_add_configs(ds, NCONF, angles, &set, NULL),
                 BF_OK);
    memset(&d, 0, sizeof d);
    d.name = "flat";
    d.number = 1;
    d.format = BF_FORMAT_MEMORY;
    d.set = set;
    d.n_channels = 1;
    d.values = values;
    cr_assert_eq(bf_dataset_add_material(ds, &d, NULL), BF_OK);
    return ds;
}

typedef struct {
    int kinds[8];
    char text[8][1024];
    size_t n;
} messages;

static void collect(void *ctx, int kind, const char *text)
{
    messages *m = ctx;
    if (m->n < 8) {
        m->kinds[m->n] = kind;
        snprintf(m->text[m->n], sizeof m->text[m->n], "%s", text);
        m->n++;
    }
}

static size_t count_png(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    size_t n = 0;
    cr_assert_not_null(d, "%s missing", dir);
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        n += len > 4 && strcmp(e->d_name + len - 4, ".png") == 0;
    }
    closedir(d);
    return n;
}

Test(report_write, lambertian_data_recover_lambert_and_every_figure)
{
    bf_dataset *ds = lambertian();
    bf_report_inputs in;
    bf_report_options o = BF_REPORT_OPTIONS_INIT;
    messages msg;
    bf_error err;
    char out[128];
    char figs[160];
    char path[200];
    const char *page;
    double lse_lambert;
    char echo_text[4096] = "";
    FILE *echo = fmemopen(echo_text, sizeof echo_text - 1, "w");
    size_t n_fig = 0;

    memset(&in, 0, sizeof in);
    memset(&msg, 0, sizeof msg);
    in.ds = ds;
    o.models = "LAMBERT,FC-E";
    o.threads = 1;
    o.formats = 1u << BF_REPORT_PNG;
    o.echo = echo;
    o.message = collect;
    o.message_ctx = &msg;
    snprintf(out, sizeof out, "%s/out", bf_test_tmpdir());
    cr_assert_eq(bf_report_write(&in, &o, out, &n_fig, &err), BF_REPORT_OK,
                 "%s", err.msg);
    fclose(echo);
    cr_expect_eq(msg.n, 0, "unexpected message: %s", msg.text[0]);
    snprintf(figs, sizeof figs, "%s/figures", out);
    cr_expect_gt(n_fig, 0);
    cr_expect_eq(count_png(figs), n_fig);
    cr_expect_eq(bf_test_csv_load(out, "fits.csv"), 3); /* header, 2 */
    lse_lambert = bf_test_csv_num(bf_test_csv_find("1", "LAMBERT", NULL),
                                  "lse");
    cr_expect_leq(lse_lambert, 1e-20, "LAMBERT's LSE %g", lse_lambert);
    cr_expect_gt(bf_test_csv_num(bf_test_csv_find("1", "FC-E", NULL), "lse"),
                 1e-6);
    snprintf(path, sizeof path, "%s/report.html", out);
    page = bf_test_slurp(path, NULL);
    cr_assert_not_null(page, "%s missing", path);
    cr_expect_not_null(strstr(page, "Written by <code>bf_report_write"
                                    "</code>"));
    cr_expect_null(strstr(page, "Command:"));
    cr_expect_not_null(strstr(echo_text, "Table 2"));
    cr_expect_not_null(strstr(echo_text, "Table 3"));
    bf_dataset_free(ds);
}

Test(report_write, a_bad_option_is_an_option_error_and_writes_nothing)
{
    bf_dataset *ds = lambertian();
    bf_report_inputs in;
    bf_report_options o = BF_REPORT_OPTIONS_INIT;
    messages msg;
    bf_error err;
    char out[128];
    struct stat sb;

    memset(&in, 0, sizeof in);
    memset(&msg, 0, sizeof msg);
    in.ds = ds;
    o.models = "LAMBERT,NOPE";
    o.message = collect;
    o.message_ctx = &msg;
    snprintf(out, sizeof out, "%s/out", bf_test_tmpdir());
    cr_assert_eq(bf_report_write(&in, &o, out, NULL, &err),
                 BF_REPORT_BADVALUE);
    cr_expect_eq(err.code, BF_EINVAL);
    cr_expect_not_null(strstr(err.msg, "NOPE"), "%s", err.msg);
    cr_assert_eq(msg.n, 1);
    cr_expect_eq(msg.kinds[0], BF_REPORT_MSG_USAGE);
    cr_expect_str_eq(msg.text[0], err.msg);
    cr_expect_neq(stat(out, &sb), 0, "%s was created", out);
    o.models = NULL;
    o.samples = "paper"; /* CURET's samples, on other data */
    cr_expect_eq(bf_report_write(&in, &o, out, NULL, &err),
                 BF_REPORT_BADVALUE);
    cr_expect_neq(stat(out, &sb), 0, "%s was created", out);
    bf_dataset_free(ds);
}

Test(report_write, an_interval_s_text_marks_bounds_and_segments)
{
    char buf[160];
    bf_fit_stats f;
    bf_rep_interval_format(buf, sizeof buf, 0.1, 0.2349, NAN, NAN, 1u);
    cr_assert_str_eq(buf, "[0.1 (bound), 0.2349]");
    bf_rep_interval_format(buf, sizeof buf, 3.373, 5.1, NAN, NAN, 2u);
    cr_assert_str_eq(buf, "[3.373, 5.1 (bound)]");
    bf_rep_interval_format(buf, sizeof buf, 1.2, 2.5, 1.311, 2.351, 3u);
    cr_assert_str_eq(buf, "[1.2 (bound), 1.311] \xe2\x88\xaa [2.351, "
                          "2.5 (bound)]");
    /* a gap needs both ends */
    bf_rep_interval_format(buf, sizeof buf, 1.2, 2.5, 1.311, NAN, 0u);
    cr_assert_str_eq(buf, "[1.2, 2.5]");
    /* a fit's interval: no bound marks */
    memset(&f, 0, sizeof f);
    f.ci_low[1] = 1.115296386;
    f.ci_high[1] = 1.374602173;
    f.ci_gap_low[1] = 1.156592411;
    f.ci_gap_high[1] = 1.205522113;
    bf_rep_interval_text(buf, sizeof buf, &f, 1);
    cr_assert_str_eq(buf, "[1.115, 1.157] \xe2\x88\xaa [1.206, 1.375]");
    f.ci_gap_low[1] = f.ci_gap_high[1] = NAN;
    bf_rep_interval_text(buf, sizeof buf, &f, 1);
    cr_assert_str_eq(buf, "[1.115, 1.375]");
    /* a short buffer is cut, terminated */
    cr_assert_eq(bf_rep_interval_format(buf, 6, 0.1, 0.2349, NAN, NAN, 0u),
                 (int)strlen("[0.1, 0.2349]"));
    cr_assert_str_eq(buf, "[0.1,");
}
