/* figures.h: the report's figures, drawn from a finished study run --
 * Figure 2(b) (LSE against the samples sorted by FC-E slope), Figures 3-6
 * (predicted against measured normalised radiance), the count of samples
 * each model fits best, per-sample curves in the plane of incidence
 * (Cartesian and polar) and, when the analysis ran, the fitted parameters
 * with their intervals (forest plots), the profiles of the objective and
 * the samples x models overview of delta BIC. Figures are drawn to
 * temporary names, by several processes at once when asked (the same
 * bytes whatever their number), and renamed into place together by
 * bf_figures_commit, so a failed run leaves no figure behind. */
#ifndef BF_REPORT_FIGURES_H
#define BF_REPORT_FIGURES_H

#include "plot.h"
#include "study.h"

/* At most this many incidence angles in the plane-of-incidence figures. */
#define BF_FIG_MAX_INCIDENCE BF_REPORT_MAX_INCIDENCE

/* The folder, inside the output folder, that holds the figures. */
#define BF_FIG_DIR "figures"

/* What to draw. */
typedef struct {
    unsigned formats;  /* bit (1u << fmt) for each bf_plot_format wanted */
    unsigned width;    /* BF_PLOT_SINGLE_COLUMN or BF_PLOT_DOUBLE_COLUMN */
    int log_lse;       /* Figure 2(b) on a logarithmic LSE axis */
    int per_sample;    /* also one scatter figure per sample */
    double incidence[BF_FIG_MAX_INCIDENCE]; /* theta_i of the plane-of-
                                               incidence panels, radians */
    size_t n_incidence; /* 0 until given or chosen */
    int incidence_chosen; /* chosen from the data, not by --incidence */
    int jobs;          /* processes drawing at once (>= 1) */
    bf_report_progress_fn progress; /* files drawn, or NULL */
    void *progress_ctx;
} bf_fig_opts;

typedef enum {
    BF_FIG_LSE,       /* Figure 2(b) */
    BF_FIG_WINS,      /* samples won per model */
    BF_FIG_SCATTER,   /* Figures 3-6: up to six samples per figure */
    BF_FIG_DELTA_BIC, /* analysis: samples x models, delta BIC */
    BF_FIG_FOREST,    /* analysis: one model's parameters and intervals */
    BF_FIG_SAMPLE,    /* one sample's scatter panels (--per-sample) */
    BF_FIG_PLANE,     /* one sample, plane of incidence, Cartesian */
    BF_FIG_POLAR,     /* one sample, plane of incidence, polar */
    BF_FIG_PROFILE,   /* analysis: one sample's objective profiles */
    BF_FIG_CALIBRATION, /* --calibrate: one sample's simulated estimates
                          against the intervals */
    BF_FIG_DISPERSION  /* one material's n against wavelength
                          (--fresnel dielectric on spectral channels) */
} bf_fig_kind;

/* The model families the plane, polar and profile figures are split by
 * (bf_fig_entry.family): the diffuse models (SPEC §3-6) and the specular
 * ones with the composites (SPEC §9.3, §9.4). */
enum { BF_FIG_DIFFUSE = 1, BF_FIG_SPECULAR = 2 };
/* Most model curves in one plane or polar figure. */
#define BF_FIG_PLANE_CURVES 6

/* One figure: drawn in every requested format as BF_FIG_DIR/base.ext. */
typedef struct {
    bf_fig_kind kind;
    int sample;             /* per-sample figures: the sample number */
    size_t index;           /* kind-specific: the group of a scatter
                               figure, the model of a forest plot, the
                               sample index of per-sample figures */
    size_t first, count;    /* scatter groups: the sample indices
                               [first, first + count) */
    size_t parts;           /* scatter groups: how many there are */
    int family;             /* plane, polar, profile figures: the models
                               drawn, 0 all, BF_FIG_DIFFUSE or
                               BF_FIG_SPECULAR (and for plane and polar the
                               family's models [first, first + count)) */
    char base[64];          /* file name without extension */
    char title[256];        /* short heading (never drawn in the image) */
    char caption[1536];     /* what is plotted and how it is normalised */
    char alt[512];          /* alternative text of the image */
    unsigned width, height; /* points (PNG: BF_PLOT_PNG_DPI per inch) */
    char tmp[BF_PLOT_NFORMATS][4096]; /* temporary files until commit */
} bf_fig_entry;

/* The figures of one run. */
typedef struct {
    bf_fig_entry *fig;
    size_t n;
    unsigned formats;
    char dir[4096];         /* out_dir/BF_FIG_DIR */
    struct bf_fig_run *run; /* drawing in progress (figures.c) */
} bf_fig_set;

/* Draws every figure of the study st into temporary files in
 * out_dir/BF_FIG_DIR (created if missing) and describes them in set:
 * bf_figures_start then bf_figures_finish. Returns BF_REPORT_OK or an status
 * after the message (the temporaries are then removed). */
int bf_figures_render(const bf_rep_study *st, const bf_fig_opts *o,
                      const char *out_dir, bf_fig_set *set);

/* Starts drawing the figures of the paper's protocol (and, with
 * with_analysis and st->stats, those of the analysis): with o->jobs > 1 in
 * drawing processes, and returns while they draw, so that the caller can
 * run the analysis meanwhile (st's rows must not change: the paper's
 * protocol, not --fit exact). Returns BF_REPORT_OK or a status after
 * the message (set is then freed). */
int bf_figures_start(const bf_rep_study *st, const bf_fig_opts *o,
                     const char *out_dir, bf_fig_set *set,
                     int with_analysis);

/* Draws the analysis figures if st->stats is now there and they were not
 * started, and waits for every drawing process. Returns BF_REPORT_OK or an
 * status after the message (set is then freed). */
int bf_figures_finish(const bf_rep_study *st, bf_fig_set *set);

/* Renames every temporary file into place. Returns BF_REPORT_OK or an status
 * after the message; the files not yet renamed are removed. */
int bf_figures_commit(bf_fig_set *set);

/* Stops any drawing process, removes any temporary file left and frees
 * set (NULL-safe fields). */
void bf_figures_free(bf_fig_set *set);

/* "Felt (1)", "Felt [R] (1)", or "sample 1" without a name, for target
 * s, into buf. */
const char *bf_fig_sample_label(const bf_rep_study *st, size_t s, char *buf,
                                size_t len);
/* Chooses o's incidence angles from the configurations of st's
 * materials (bf_geom_plane_incidences: those with the most views in their
 * plane of incidence, within BF_FIG_PLANE_TOL, spread over their range);
 * none when no configuration lies in its plane. BF_REPORT_OK, or an status
 * after the message. */
int bf_figures_choose_incidence(const bf_rep_study *st, bf_fig_opts *o);

/* Longest name (characters) a figure shows on an axis or above a panel. */
#define BF_FIG_TICK_CHARS 24
/* bf_fig_sample_label for text inside a figure (axis ticks, panel
 * columns): a name longer than BF_FIG_TICK_CHARS characters is cut at a
 * space and ends in an ellipsis ("Krylon spray enamel 7205... (4)"), its
 * channel kept whole ("Krylon spray enamel... [550] (4)"); the page's
 * captions and tables keep the whole name. */
const char *bf_fig_sample_tick(const bf_rep_study *st, size_t s, char *buf,
                               size_t len);
/* The key of target s in file names and page anchors: "sample16", or
 * "sample16_R" when the study fits single channels (characters other than
 * letters, digits, '.', '-' written as '_'). */
const char *bf_fig_target_key(const bf_rep_study *st, size_t s, char *buf,
                              size_t len);
/* "K = 198" when every sample has the same K, else "K (per sample)". */
const char *bf_fig_k_text(const bf_rep_study *st, char *buf, size_t len);
/* The captions' "each of the 24 samples", or "the one sample". */
const char *bf_fig_each_sample(size_t n, char *buf, size_t len);


#endif
