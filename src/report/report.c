/* report.c: bf_report_write (brdffit.h) -- the run of `brdffit report`:
 * the study of SPEC §7 on the caller's data, its tables (fits.csv,
 * table2.md, table3.md), every figure (figures/) and report.html, each
 * drawn or written to a temporary file first and renamed into place
 * together, so that a failed run leaves no partial output. */
#include <string.h>

#include "figures.h"
#include "report_html.h"
#include "tables.h"

/* Most processes drawing figures at once. */
#define MAX_JOBS 64

/* The figure options of o. */
static void figure_options(const bf_report_options *o, bf_fig_opts *fo)
{
    size_t i;
    memset(fo, 0, sizeof *fo);
    fo->formats = o->formats;
    fo->width = o->single_column ? BF_PLOT_SINGLE_COLUMN
                                 : BF_PLOT_DOUBLE_COLUMN;
    fo->log_lse = o->log_lse;
    fo->per_sample = o->per_sample;
    fo->n_incidence = o->n_incidence < BF_FIG_MAX_INCIDENCE
                          ? o->n_incidence
                          : BF_FIG_MAX_INCIDENCE;
    for (i = 0; i < fo->n_incidence; i++) {
        fo->incidence[i] = o->incidence[i];
    }
    fo->progress = o->progress;
    fo->progress_ctx = o->progress_ctx;
}

/* Writes report.html into the output folder's temporary file page. */
static int write_page(const bf_rep_study *st, const bf_fig_set *figs,
                      const bf_report_meta *meta, bf_out *page)
{
    int rc = bf_out_open(page, st->out_dir, "report.html");
    if (rc != BF_REPORT_OK) {
        return rc;
    }
    rc = bf_report_html(st, figs, meta, page->fp);
    if (rc != 0) {
        bf_rep_err("%s: %s", page->path,
                   rc == -2 ? "out of memory" : "write failed");
        bf_out_abort(page);
        return rc == -2 ? BF_REPORT_SOFTWARE : BF_REPORT_IOERR;
    }
    return BF_REPORT_OK;
}

/* The study, then everything drawn and written to temporary files, then
 * renamed into place. The paper's figures are drawn while the analysis
 * runs (with the exact fit the analysis is the study: they wait for it). */
static int run(bf_rep_study *st, bf_fig_opts *fo, bf_fig_set *figs,
               bf_report_meta *meta)
{
    bf_out page;
    int page_open = 0;
    int started = 0;
    int rc = bf_rep_study_prepare(st);
    if (rc == BF_REPORT_OK && fo->n_incidence == 0) {
        rc = bf_figures_choose_incidence(st, fo);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_report_checksums(st, meta);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_study_run_protocol(st);
    }
    fo->jobs = st->spec.n_threads > 1 ? st->spec.n_threads : 1;
    fo->jobs = fo->jobs > MAX_JOBS ? MAX_JOBS : fo->jobs;
    if (rc == BF_REPORT_OK && !st->opts.exact) {
        rc = bf_figures_start(st, fo, st->out_dir, figs, 0);
        started = rc == BF_REPORT_OK;
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_study_run_analysis(st);
    }
    if (rc == BF_REPORT_OK && !started) {
        rc = bf_figures_start(st, fo, st->out_dir, figs, 1);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_figures_finish(st, figs);
    }
    if (rc == BF_REPORT_OK) {
        rc = write_page(st, figs, meta, &page);
        page_open = rc == BF_REPORT_OK;
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_study_write_tables(st);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_figures_commit(figs);
    }
    if (rc == BF_REPORT_OK) {
        page_open = 0;
        rc = bf_out_commit(&page);
    }
    if (page_open) {
        bf_out_abort(&page);
    }
    return rc;
}

/* The bf_error of a failed run: its first message, a BF_E* code. */
static void fill_error(int status, bf_error *err)
{
    const char *msg = bf_rep_last();
    memset(err, 0, sizeof *err);
    switch (status) {
    case BF_REPORT_CONFLICT:
    case BF_REPORT_BADVALUE: err->code = BF_EINVAL; break;
    case BF_REPORT_DATAERR: err->code = BF_EDOM; break;
    case BF_REPORT_SOFTWARE: err->code = BF_ENOMEM; break;
    default: err->code = BF_EIO; break;
    }
    snprintf(err->file, sizeof err->file, "report");
    snprintf(err->msg, sizeof err->msg, "%s",
             msg[0] != '\0' ? msg : bf_strerror(err->code));
}

int bf_report_write(bf_report_inputs *in, const bf_report_options *o,
                    const char *out_dir, size_t *n_figures, bf_error *err)
{
    bf_report_message_fn old_fn;
    void *old_ctx;
    bf_rep_study st;
    bf_fig_opts fo;
    bf_fig_set figs;
    bf_report_meta meta;
    int rc;

    if (n_figures != NULL) {
        *n_figures = 0;
    }
    if (in == NULL || o == NULL || out_dir == NULL) {
        if (err != NULL) {
            memset(err, 0, sizeof *err);
            err->code = BF_EINVAL;
            snprintf(err->msg, sizeof err->msg, "bf_report_write: NULL "
                                                "argument");
        }
        return BF_REPORT_SOFTWARE;
    }
    bf_rep_get_sink(&old_fn, &old_ctx);
    bf_rep_set_sink(o->message, o->message_ctx);
    bf_rep_clear();
    memset(&st, 0, sizeof st);
    memset(&figs, 0, sizeof figs);
    memset(&meta, 0, sizeof meta);
    st.cmd = "report";
    st.opts = *o;
    st.in = *in;
    st.out_dir = out_dir;
    figure_options(o, &fo);
    meta.argc = o->argv != NULL ? o->argc : 0;
    meta.argv = o->argv;
    meta.fig = &fo;
    rc = run(&st, &fo, &figs, &meta);
    if (rc == BF_REPORT_OK && n_figures != NULL) {
        *n_figures = figs.n;
    }
    if (rc != BF_REPORT_OK && err != NULL) {
        fill_error(rc, err);
    }
    *in = st.in; /* what load filled, for the caller to free */
    bf_figures_free(&figs);
    bf_rep_study_free(&st);
    bf_rep_set_sink(old_fn, old_ctx);
    return rc;
}
