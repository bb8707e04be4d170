/* setup.c: the CLI's options, loader, messages and progress line behind
 * the report library's study run (setup.h). */
#include <string.h>
#include <unistd.h>

#include "setup.h"

void bf_cli_message(void *ctx, int kind, const char *text)
{
    const char *cmd = ctx;
    if (kind == BF_REPORT_MSG_USAGE) {
        (void)bf_cli_usage_fail(BF_EXIT_BADVALUE, cmd, "%s", text);
    } else {
        bf_cli_err("%s", text);
    }
}

/* The load callback: the CLI's loader (its own messages and statuses). */
static int load(void *ctx, bf_report_inputs *rin)
{
    bf_cli_run *r = ctx;
    bf_cli_inputs *in = &r->in;
    size_t i;
    int rc = bf_cli_load_data(&r->opts.src, r->opts.n_file, r->opts.on_file,
                              in);
    if (rc != BF_EXIT_OK) {
        return rc;
    }
    rin->ds = in->ds;
    rin->n_file = in->n_file;
    rin->on_params = in->on_params;
    rin->curet = in->curet;
    rin->table_path = in->table_path;
    rin->brdf_path = in->brdf_path;
    rin->names_path = in->names_path;
    rin->configs_path = in->configs_path;
    rin->n_files = r->opts.src.n_inputs;
    for (i = 0; i < rin->n_files && i < BF_REPORT_MAX_FILES; i++) {
        rin->files[i] = r->opts.src.inputs[i];
    }
    return BF_EXIT_OK;
}

/* The progress callback: the CLI's progress line, one per phase. */
static void progress(void *ctx, const char *what, size_t done, size_t total)
{
    bf_cli_run *r = ctx;
    if (what == NULL) {
        bf_cli_progress_end(&r->progress);
        r->progress.what = NULL;
        return;
    }
    if (r->progress.what == NULL || strcmp(r->progress.what, what) != 0) {
        bf_cli_progress_end(&r->progress);
        bf_cli_progress_init(&r->progress, what, r->opts.quiet);
    }
    bf_cli_progress_cb(&r->progress, done, total);
}

void bf_cli_report_options(bf_cli_run *r, bf_report_options *ro,
                           bf_report_inputs *rin)
{
    const bf_cli_opts *o = &r->opts;
    bf_report_options def = BF_REPORT_OPTIONS_INIT;
    size_t i;
    *ro = def;
    ro->models = o->models;
    ro->default_models = o->defaults->models;
    ro->samples = o->samples;
    ro->channel = o->channel;
    ro->exclude = o->exclude;
    ro->cone = o->cone;
    ro->max_theta = o->max_theta;
    ro->n = o->n;
    ro->n_given = o->n_given;
    ro->n_file = o->n_file;
    ro->on_file = o->on_file;
    ro->exact = o->exact;
    ro->objective = o->objective;
    ro->fresnel = o->fresnel;
    ro->smith = o->smith;
    ro->noise = o->noise;
    ro->n_range = o->n_range;
    for (i = 0; i < o->n_range; i++) {
        ro->range[i] = o->range[i];
    }
    ro->n_boot = o->n_boot;
    ro->n_neyman = o->n_neyman;
    ro->neyman_every = o->neyman_every;
    ro->no_intervals = o->no_intervals;
    ro->folds = o->folds;
    ro->seed = o->seed;
    ro->stats = o->stats;
    ro->threads = o->threads;
    ro->echo = o->quiet ? NULL : stdout;
    ro->progress = progress;
    ro->progress_ctx = r;
    memset(rin, 0, sizeof *rin);
    rin->load = load;
    rin->load_ctx = r;
}

int bf_cli_study_setup(const char *cmd, bf_cli_run *r, bf_rep_study *st)
{
    memset(st, 0, sizeof *st);
    st->cmd = cmd;
    st->out_dir = r->opts.out_dir;
    bf_cli_report_options(r, &st->opts, &st->in);
    return bf_rep_study_prepare(st);
}

void bf_cli_run_free(bf_cli_run *r)
{
    bf_cli_free_inputs(&r->in);
}
