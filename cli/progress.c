/* progress.c: the progress line of long runs on stderr -- how far the
 * analysis is and about how long it still takes -- shown only when stderr
 * is a terminal, -q is not given and the run has lasted a second. */
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

/* A run shorter than this shows no line; updates at most this often. */
#define PROGRESS_AFTER 1.0
#define PROGRESS_EVERY 0.1

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void bf_cli_progress_init(bf_cli_progress *p, const char *what, int quiet)
{
    p->what = what;
    p->enabled = !quiet && isatty(STDERR_FILENO);
    p->t0 = now();
    p->last = 0.0;
    p->shown = 0;
}

void bf_cli_progress_cb(void *ctx, size_t done, size_t total)
{
    bf_cli_progress *p = ctx;
    double t;
    double left;
    if (!p->enabled || done == 0 || total == 0) {
        return;
    }
    t = now() - p->t0;
    if (t < PROGRESS_AFTER || (t - p->last < PROGRESS_EVERY && done < total)) {
        return;
    }
    p->last = t;
    left = t * (double)(total - done) / (double)done; /* at the mean rate */
    fprintf(stderr, "\rbrdffit: %s %zu/%zu (%3.0f%%), %.0f s so far, about "
                    "%.0f s left   ",
            p->what, done, total, 100.0 * (double)done / (double)total, t,
            left);
    fflush(stderr);
    p->shown = 1;
}

void bf_cli_progress_end(bf_cli_progress *p)
{
    if (p->shown) {
        fprintf(stderr, "\rbrdffit: %s done in %.1f s%40s\n", p->what,
                now() - p->t0, "");
        p->shown = 0;
    }
}
