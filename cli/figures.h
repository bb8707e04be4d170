/* figures.h: the report's figures, drawn from a finished study run --
 * Figure 2(b) (LSE against the samples sorted by FC-E slope), Figures 3-6
 * (predicted against measured normalised radiance, six samples per figure),
 * per-sample curves in the plane of incidence (Cartesian and polar) and the
 * count of samples each model fits best. Files are drawn to temporary names
 * and renamed into place together by bf_figures_commit, so a failed run
 * leaves no figure behind. */
#ifndef BF_CLI_FIGURES_H
#define BF_CLI_FIGURES_H

#include "plot.h"
#include "study.h"

/* At most this many incidence angles in the plane-of-incidence figures. */
#define BF_FIG_MAX_INCIDENCE 4

/* The folder, inside the output folder, that holds the figures. */
#define BF_FIG_DIR "figures"

/* What to draw. */
typedef struct {
    unsigned formats;  /* bit (1u << fmt) for each bf_plot_format wanted */
    int log_lse;       /* Figure 2(b) on a logarithmic LSE axis */
    int per_sample;    /* also one scatter figure per sample */
    double incidence[BF_FIG_MAX_INCIDENCE]; /* theta_i of the plane-of-
                                               incidence panels, radians */
    size_t n_incidence;
    int progress;      /* print a progress line on stderr */
} bf_fig_opts;

typedef enum {
    BF_FIG_LSE,       /* Figure 2(b) */
    BF_FIG_SCATTER,   /* Figures 3-6: six samples per figure */
    BF_FIG_SAMPLE,    /* one sample's scatter panels (--per-sample) */
    BF_FIG_PLANE,     /* one sample, plane of incidence, Cartesian */
    BF_FIG_POLAR,     /* one sample, plane of incidence, polar */
    BF_FIG_WINS       /* samples won per model */
} bf_fig_kind;

/* One figure: drawn in every requested format as BF_FIG_DIR/base.ext. */
typedef struct {
    bf_fig_kind kind;
    int sample;             /* per-sample figures: the sample; else 0 */
    char base[64];          /* file name without extension */
    char title[256];        /* short heading */
    char caption[1024];     /* what the figure shows (plain text) */
    unsigned width, height; /* pixels (PNG) or points (SVG, PDF) */
    char tmp[BF_PLOT_NFORMATS][4096]; /* temporary files until commit */
} bf_fig_entry;

/* The figures of one run. */
typedef struct {
    bf_fig_entry *fig;
    size_t n;
    unsigned formats;
    char dir[4096];         /* out_dir/BF_FIG_DIR */
} bf_fig_set;

/* Draws every figure of the study st into temporary files in
 * out_dir/BF_FIG_DIR (created if missing) and describes them in set.
 * Returns BF_EXIT_OK or an exit status after printing the error (the
 * temporaries are then removed). */
int bf_figures_render(const bf_cli_study *st, const bf_fig_opts *o,
                      const char *out_dir, bf_fig_set *set);

/* Renames every temporary file into place. Returns BF_EXIT_OK or an exit
 * status after printing the error; the files not yet renamed are removed. */
int bf_figures_commit(bf_fig_set *set);

/* Removes any temporary file left and frees set (NULL-safe fields). */
void bf_figures_free(bf_fig_set *set);

#endif
