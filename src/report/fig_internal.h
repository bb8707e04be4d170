/* fig_internal.h: what the report's figure files share -- the data every
 * figure draws from (per-sample normalised radiances, the models of the
 * scatter and plane figures), a figure description with the memory it
 * points into, and one describe function per figure kind. figures.c
 * prepares the data and draws; fig_paper.c (Figures 2(b), 3-6, wins),
 * fig_plane.c (plane of incidence) and fig_analysis.c (intervals,
 * profiles, delta BIC) describe. Private to src/report. */
#ifndef BF_REPORT_FIG_INTERNAL_H
#define BF_REPORT_FIG_INTERNAL_H

#include "figures.h"

/* Most models in one figure (the complete glossy comparison has 21). */
#define BF_FIG_MAX_MODELS 32
/* One degree, radians. */
#define BF_FIG_DEG (M_PI / 180.0)
/* A measured configuration is "in the plane of incidence" of a panel when
 * its viewing direction lies within BF_FIG_PLANE_TOL of that plane and its
 * theta_i within BF_FIG_PLANE_TOL of the panel's incidence angle (CURET's
 * in-plane configurations lie exactly in it, at multiples of 11.25
 * degrees). */
#define BF_FIG_PLANE_TOL (1.0 * BF_FIG_DEG)

/* The legend of the noise model's estimate, the one the 95% interval is
 * about (bf_fit_stats.ml_param, doc/methods.md §3), in the forest plots
 * (fig_analysis.c) and the dispersion figure (fig_dispersion.c). */
#define BF_FIG_ML_LABEL "the interval's estimate (noise-weighted)"

/* One sample's (target's) normalised measured and predicted radiance on
 * its K used configurations (SPEC §2). */
typedef struct {
    size_t K;
    bf_geom *geom;       /* the K used configurations (Beckmann's frame) */
    double *data;        /* K measured values */
    double *pred;        /* n_models x K predictions (model-major) */
    int *ok;             /* model evaluated for this sample */
} bf_fig_sample;

/* Everything the figures draw from. */
typedef struct {
    const bf_rep_study *st;
    const bf_fig_opts *o;
    bf_fig_sample *smp;           /* one per sample */
    size_t idx[BF_FIG_MAX_MODELS]; /* models of the scatter and plane
                                     figures (indices into st->models) */
    size_t nm;
} bf_fig_data;

/* A figure description and the memory it points into. */
#define BF_FIG_MAX_MEM 48
typedef struct {
    bf_plot_figure fig;
    void *mem[BF_FIG_MAX_MEM];
    size_t n_mem;
} bf_fig_desc;

/* Zeroed memory owned by d (freed by bf_fig_desc_free); NULL when out of
 * memory. */
void *bf_fig_alloc(bf_fig_desc *d, size_t size);
void bf_fig_desc_free(bf_fig_desc *d);

/* What the figures and the page call a fit's value (bf_study_row.fit.lse)
 * under obj, as Table 3 does (tables.c): the paper's "LSE" under max,
 * SPEC §10's "E" under ngan, the objective's "S" under every other.
 * (fig_plane.c) */
const char *bf_fig_value_name(bf_objective obj);

/* The study row of sample index s and model index m. */
const bf_study_row *bf_fig_row(const bf_rep_study *st, size_t s, size_t m);
/* The configurations and data sample index s was fitted on: the figure
 * data's (bf_fig_sample, normalised) under the paper's objectives, the
 * fit's rho (bf_study_fit_data, SPEC §10; memory of d) under the
 * objectives that keep the scale. *abs = 1 for the latter. BF_OK or
 * BF_ENOMEM / the data's error (src/report/fig_plane.c). */
int bf_fig_fit_data(const bf_fig_data *D, size_t s, bf_fig_desc *d,
                    size_t *K, const bf_geom **geom, const double **data,
                    int *abs);
/* A parameter's label for an axis, its unit added unless dimensionless,
 * Greek names written as letters and n_d with its subscript: "σ/T (G)",
 * "σ (rad)". (fig_analysis.c) */
void bf_fig_param_label(const bf_param *p, char *buf, size_t len);
/* 1 when model m was evaluated (status BF_OK) for at least one sample of
 * st: ON without tabulated parameters is evaluated for none. */
int bf_fig_evaluated_anywhere(const bf_rep_study *st, size_t m);
/* The list "ON, LFTG, VH-E" of the models idx[0..n) into buf. */
const char *bf_fig_model_list(const bf_rep_study *st, const size_t *idx,
                              size_t n, char *buf, size_t len);

/* Describe functions: each fills e's base, title, caption and alt text
 * and d->fig. With full = 0 only what the texts and the figure's size need
 * (no curve is computed). Return BF_OK or a BF_E* code. */
int bf_fig_lse(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
               int full);
int bf_fig_wins(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                int full);
int bf_fig_scatter(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                   int full);
int bf_fig_plane(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                 int full);
int bf_fig_forest(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                  int full);
int bf_fig_delta_bic(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                     int full);
int bf_fig_profile(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                   int full);
/* (fig_calibration.c) One sample's calibration figure: panels [first,
 * first + count) of its bf_fig_calibration_panels, part of parts. */
int bf_fig_calibration(const bf_fig_data *D, bf_fig_entry *e,
                       bf_fig_desc *d, int full);
/* Panels of sample index s's calibration: one per fitted parameter of
 * each calibrated pair (0: no figure). */
size_t bf_fig_calibration_panels(const bf_rep_study *st, size_t s);
/* The most panels one calibration figure holds at D's width (at least
 * 1): those whose axes are still MIN_AXES wide on a page. */
size_t bf_fig_calibration_per_figure(const bf_fig_data *D);

/* (fig_dispersion.c) One material's n against wavelength: e->index its
 * first target. */
int bf_fig_dispersion(const bf_fig_data *D, bf_fig_entry *e,
                      bf_fig_desc *d, int full);
/* Whether target s is the first of its material and the material has
 * dispersion points (bf_dispersion_points): the index of its first
 * point, else SIZE_MAX. */
size_t bf_fig_dispersion_first(const bf_rep_study *st, size_t s);

/* Samples per scatter figure (Figures 3-6 hold six each, as the paper). */
#define BF_FIG_SCATTER_SAMPLES 6
/* How many samples from index s0 on the next scatter figure holds: up to
 * BF_FIG_SCATTER_SAMPLES, fewer when their grid would not fit a page
 * (many models), 1 at the least (its panels are then re-flowed). */
size_t bf_fig_scatter_group(const bf_fig_data *D, size_t s0);

/* The positions b in D->idx (into out, in order) of the models of
 * family (BF_FIG_DIFFUSE, BF_FIG_SPECULAR; 0: all); returns their count.
 * (figures.c) */
size_t bf_fig_family(const bf_fig_data *D, int family, size_t *out);
/* The file name suffix of page part (from 1) of a family's figures of a
 * sample (diffuse: 1 when the sample has figures of the diffuse models):
 * the sample's first figure none, then "_diffuse2", ..., "_specular",
 * "_specular2", ... (figures.c) */
void bf_fig_family_suffix(int family, int diffuse, size_t part, char *buf,
                          size_t len);
/* Most panels of one profile figure: more continue on a further page. */
#define BF_FIG_PROFILE_PANELS 15
/* 1 when model st->models[m] is of family (0: every model). */
int bf_fig_in_family(const bf_rep_study *st, size_t m, int family);

/* Panels of sample index s's profile figure of family (0: all): one per
 * fitted parameter of each analysed model of the family.
 * (fig_analysis.c) */
size_t bf_fig_profile_panels(const bf_rep_study *st, size_t s, int family);

/* Rows (samples) of one delta BIC or forest page at D's width: more
 * samples continue in delta_bic_2, forest_X_2, ... (fig_analysis.c) */
size_t bf_fig_rows_per_page(const bf_fig_data *D);

/* Rows (samples) of one page of model m's forest plot at D's width (its
 * panels in more rows on narrow pages): more continue in forest_X_2, ...
 * (fig_analysis.c) */
size_t bf_fig_forest_rows(const bf_fig_data *D, size_t m);

/* Whether model m has free parameters analysed for some sample (it gets
 * a forest plot). */
int bf_fig_has_forest(const bf_rep_study *st, size_t m);

#endif
