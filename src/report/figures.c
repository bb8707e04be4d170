/* figures.c: the report's figures (figures.h) -- prepares what they draw
 * from (the normalised measured and predicted radiances of a finished
 * study, SPEC §2), lists the figures of the run, draws them into temporary
 * files, in parallel processes when asked, and renames them into place.
 *
 * Each figure is drawn from its own description by a fresh PLplot stream
 * (src/report/plot.c), so its bytes do not depend on which process drew it
 * or on what that process drew before: any number of processes gives the
 * same files (tested). */
#include "fig_internal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* The paper's scatter-plot models, in its order (Figures 3-6). */
static const char *const paper_scatter[] = {"ON", "LFTG", "VH-E", "FC-E"};

/* ==== shared helpers ===================================================== */

void *bf_fig_alloc(bf_fig_desc *d, size_t size)
{
    void *p;
    if (d->n_mem == BF_FIG_MAX_MEM || (p = calloc(1, size + 1)) == NULL) {
        return NULL;
    }
    d->mem[d->n_mem++] = p;
    return p;
}

void bf_fig_desc_free(bf_fig_desc *d)
{
    size_t i;
    for (i = 0; i < d->n_mem; i++) {
        free(d->mem[i]);
    }
    memset(d, 0, sizeof *d);
}

/* "TITLE (N)", or "sample N" when title is empty, into buf. */
static const char *label_of(const bf_rep_study *st, size_t s,
                            const char *title, char *buf, size_t len)
{
    if (title[0] != '\0') {
        snprintf(buf, len, "%.200s (%d)", title, st->samples[s]);
    } else {
        snprintf(buf, len, "sample %d", st->samples[s]);
    }
    return buf;
}

const char *bf_fig_sample_label(const bf_rep_study *st, size_t s, char *buf,
                                size_t len)
{
    char title[256];
    bf_rep_sample_title(st, s, title, sizeof title);
    return label_of(st, s, title, buf, len);
}

int bf_figures_choose_incidence(const bf_rep_study *st, bf_fig_opts *o)
{
    size_t total = 0;
    size_t s;
    size_t K = 0;
    bf_geom *g;
    int rc;
    /* every configuration of the study's materials, each material once
     * (targets of one material differ in channel only) */
    for (s = 0; s < st->n_samples; s++) {
        if (s == 0 || st->targets[s].material != st->targets[s - 1].material) {
            total += bf_dataset_nconf(st->in.ds, st->targets[s].material);
        }
    }
    g = malloc((total + 1) * sizeof *g);
    if (g == NULL) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    for (s = 0; s < st->n_samples; s++) {
        size_t mat = st->targets[s].material;
        if (s == 0 || mat != st->targets[s - 1].material) {
            size_t n = bf_dataset_nconf(st->in.ds, mat);
            memcpy(g + K, bf_dataset_geom(st->in.ds, mat), n * sizeof *g);
            K += n;
        }
    }
    rc = bf_geom_plane_incidences(K, g, BF_FIG_PLANE_TOL,
                                  BF_FIG_MAX_INCIDENCE, o->incidence,
                                  &o->n_incidence);
    free(g);
    if (rc != BF_OK) {
        bf_rep_err("cannot choose the incidence angles of the figures: %s",
                   bf_strerror(rc));
        return rc == BF_ENOMEM ? BF_REPORT_SOFTWARE : BF_REPORT_DATAERR;
    }
    o->incidence_chosen = 1;
    return BF_REPORT_OK;
}

/* Byte length of the first n characters of UTF-8 text t (fewer if t is
 * shorter). */
static size_t utf8_prefix(const char *t, size_t n)
{
    size_t i = 0;
    while (t[i] != '\0' && n > 0) {
        i++;
        while (((unsigned char)t[i] & 0xC0u) == 0x80u) {
            i++; /* continuation bytes */
        }
        n--;
    }
    return i;
}

const char *bf_fig_sample_tick(const bf_rep_study *st, size_t s, char *buf,
                               size_t len)
{
    char title[300];
    size_t cut;
    /* the name cut, its channel (--channel each, joint) kept whole within
     * the same length */
    const char *ch = st->targets[s].channel != BF_CHANNEL_MEAN
                         ? bf_rep_channel_name(st, s)
                         : NULL;
    size_t room = BF_FIG_TICK_CHARS;
    if (ch != NULL) {
        room -= strlen(ch) + 3 < BF_FIG_TICK_CHARS / 2 ? strlen(ch) + 3
                                                       : BF_FIG_TICK_CHARS / 2;
    }
    snprintf(title, 256, "%s", bf_rep_sample_name(st, s));
    cut = utf8_prefix(title, room);
    if (title[cut] != '\0') { /* longer: cut at a space, add an ellipsis */
        size_t sp = cut;
        while (sp > cut / 2 && title[sp] != ' ') {
            sp--;
        }
        cut = title[sp] == ' ' ? sp : cut;
        while (cut > 0 && (title[cut - 1] == ' ' || title[cut - 1] == ',' ||
                           title[cut - 1] == ';')) {
            cut--;
        }
        memcpy(title + cut, "\xe2\x80\xa6", 4); /* the ellipsis and NUL */
    }
    if (ch != NULL) {
        size_t used = strlen(title);
        snprintf(title + used, sizeof title - used, " [%.32s]", ch);
    }
    return label_of(st, s, title, buf, len);
}

const char *bf_fig_target_key(const bf_rep_study *st, size_t s, char *buf,
                              size_t len)
{
    int n = snprintf(buf, len, "sample%d", st->samples[s]);
    if (st->targets[s].channel != BF_CHANNEL_MEAN && n > 0 &&
        (size_t)n + 2 < len) {
        const char *c = bf_rep_channel_name(st, s);
        size_t j = (size_t)n;
        buf[j++] = '_';
        for (; *c != '\0' && j + 1 < len; c++) {
            int ok = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                     (*c >= '0' && *c <= '9') || *c == '.' || *c == '-';
            buf[j++] = ok ? *c : '_';
        }
        buf[j] = '\0';
    }
    return buf;
}

const char *bf_fig_k_text(const bf_rep_study *st, char *buf, size_t len)
{
    if (st->n_sel > 0) {
        snprintf(buf, len, "K = %zu", st->n_sel);
    } else {
        snprintf(buf, len, "K (per sample)");
    }
    return buf;
}

const char *bf_fig_each_sample(size_t n, char *buf, size_t len)
{
    if (n == 1) {
        snprintf(buf, len, "the one sample");
    } else {
        snprintf(buf, len, "each of the %zu samples", n);
    }
    return buf;
}

const bf_study_row *bf_fig_row(const bf_rep_study *st, size_t s, size_t m)
{
    return &st->rows[s * st->n_models + m];
}

const char *bf_fig_model_list(const bf_rep_study *st, const size_t *idx,
                              size_t n, char *buf, size_t len)
{
    size_t b;
    buf[0] = '\0';
    for (b = 0; b < n; b++) {
        size_t used = strlen(buf);
        snprintf(buf + used, len - used, "%s%s", b ? ", " : "",
                 st->models[idx[b]]->name);
    }
    return buf;
}

int bf_fig_has_forest(const bf_rep_study *st, size_t m)
{
    size_t s;
    if (st->stats == NULL) {
        return 0;
    }
    for (s = 0; s < st->n_samples; s++) {
        const bf_fit_stats *f = &st->stats[s * st->n_models + m];
        if (f->done && f->free_mask != 0) {
            return 1;
        }
    }
    return 0;
}

/* ==== the data figures draw from ========================================= */

static void sample_free(bf_fig_sample *r)
{
    free(r->geom);
    free(r->data);
    free(r->pred);
    free(r->ok);
    memset(r, 0, sizeof *r);
}

/* Fills r for target s of st: its used configurations and normalised
 * measured radiance as the study fitted them (bf_rep_target_data), and
 * each model's prediction normalised by its own maximum over the same
 * configurations (SPEC §2, bf_fit_curve). Returns BF_OK or a BF_E* code. */
static int sample_compute(const bf_rep_study *st, size_t s, bf_fig_sample *r)
{
    size_t mat = st->targets[s].material;
    size_t nconf = bf_dataset_nconf(st->in.ds, mat);
    const bf_geom *all = bf_dataset_geom(st->in.ds, mat);
    size_t *sel = malloc((nconf + 1) * sizeof *sel);
    double *work = malloc((nconf + 1) * sizeof *work);
    size_t K = 0;
    size_t k;
    size_t m;
    int rc;

    memset(r, 0, sizeof *r);
    r->geom = malloc((nconf + 1) * sizeof *r->geom);
    r->data = malloc((nconf + 1) * sizeof *r->data);
    r->pred = malloc((nconf * st->n_models + 1) * sizeof *r->pred);
    r->ok = calloc(st->n_models + 1, sizeof *r->ok);
    if (sel == NULL || work == NULL || r->geom == NULL || r->data == NULL ||
        r->pred == NULL || r->ok == NULL) {
        free(sel);
        free(work);
        return BF_ENOMEM;
    }
    rc = bf_rep_target_data(st, s, sel, &K, r->data);
    for (k = 0; rc == BF_OK && k < K; k++) {
        r->geom[k] = all[sel[k]];
    }
    r->K = K;
    for (m = 0; m < st->n_models && rc == BF_OK; m++) {
        const bf_study_row *rm = bf_fig_row(st, s, m);
        if (rm->status != BF_OK) {
            continue;
        }
        rc = bf_fit_curve(rm->type, rm->fit.param, K, r->geom, K, r->geom,
                          work, &r->pred[m * K]);
        r->ok[m] = rc == BF_OK;
    }
    free(sel);
    free(work);
    return rc;
}

static long model_index(const bf_rep_study *st, const char *name)
{
    size_t m;
    for (m = 0; m < st->n_models; m++) {
        if (strcmp(st->models[m]->name, name) == 0) {
            return (long)m;
        }
    }
    return -1;
}

/* The models of the scatter and plane figures: those of --models when it
 * was given, else the paper's ON, LFTG, VH-E, FC-E that the run has and
 * evaluated for some sample (ON needs tabulated parameters, which data
 * other than CURET lack), or all of the run's models when none is left. */
int bf_fig_evaluated_anywhere(const bf_rep_study *st, size_t m)
{
    size_t s;
    for (s = 0; s < st->n_samples; s++) {
        if (bf_fig_row(st, s, m)->status == BF_OK) {
            return 1;
        }
    }
    return 0;
}

static size_t scatter_models(const bf_rep_study *st, size_t *idx)
{
    size_t n = 0;
    size_t i;
    if (st->opts.models == NULL) {
        for (i = 0; i < sizeof paper_scatter / sizeof *paper_scatter; i++) {
            long m = model_index(st, paper_scatter[i]);
            if (m >= 0 && bf_fig_evaluated_anywhere(st, (size_t)m)) {
                idx[n++] = (size_t)m;
            }
        }
    }
    if (n == 0) {
        for (i = 0; i < st->n_models && n < BF_FIG_MAX_MODELS; i++) {
            idx[n++] = i;
        }
    }
    return n;
}

int bf_fig_in_family(const bf_rep_study *st, size_t m, int family)
{
    int spec = st->models[m]->kind == BF_MODEL_SPECULAR;
    return family == 0 || (family == BF_FIG_SPECULAR) == spec;
}

void bf_fig_family_suffix(int family, int diffuse, size_t part, char *buf,
                          size_t len)
{
    buf[0] = '\0';
    if (family == BF_FIG_DIFFUSE && part > 1) {
        snprintf(buf, len, "_diffuse%zu", part);
    } else if (family == BF_FIG_SPECULAR && (diffuse || part > 1)) {
        snprintf(buf, len, part > 1 ? "_specular%zu" : "_specular", part);
    }
}

size_t bf_fig_family(const bf_fig_data *D, int family, size_t *out)
{
    size_t n = 0;
    size_t b;
    for (b = 0; b < D->nm; b++) {
        if (bf_fig_in_family(D->st, D->idx[b], family)) {
            out[n++] = b;
        }
    }
    return n;
}

static void data_free(bf_fig_data *D)
{
    size_t s;
    if (D->smp != NULL) {
        for (s = 0; s < D->st->n_samples; s++) {
            sample_free(&D->smp[s]);
        }
    }
    free(D->smp);
}

/* ==== the list of figures ================================================ */

/* Appends an entry; returns it, or NULL when out of memory. */
static bf_fig_entry *add_entry(bf_fig_set *set, bf_fig_kind kind,
                               size_t index, int sample)
{
    bf_fig_entry *f = realloc(set->fig, (set->n + 1) * sizeof *f);
    if (f == NULL) {
        return NULL;
    }
    set->fig = f;
    f = &set->fig[set->n++];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    f->index = index;
    f->sample = sample;
    return f;
}

/* Entries of kind for sample index s and family: n items (panels) in
 * pages of at most per, as even as can be ([first, first + count) of
 * parts; one page for n = 0). 1, or 0 when out of memory. */
static int list_pages(bf_fig_set *set, bf_fig_kind kind, size_t s,
                      int sample, int family, size_t n, size_t per)
{
    size_t parts = n > 0 ? (n + per - 1) / per : 1;
    size_t each = (n + parts - 1) / parts;
    size_t p;
    for (p = 0; p < parts; p++) {
        bf_fig_entry *e = add_entry(set, kind, s, sample);
        if (e == NULL) {
            return 0;
        }
        e->family = family;
        e->first = p * each;
        e->count = p + 1 < parts ? each : n - p * each;
        e->parts = parts;
    }
    return 1;
}

/* The plane and polar figures of sample index s: per family of the
 * models drawn (bf_fig_family), at most BF_FIG_PLANE_CURVES curves a
 * figure. */
static int list_plane(const bf_fig_data *D, bf_fig_set *set, size_t s)
{
    static const int fams[2] = {BF_FIG_DIFFUSE, BF_FIG_SPECULAR};
    size_t pos[BF_FIG_MAX_MODELS];
    size_t f;
    size_t k;
    int kind;
    for (kind = BF_FIG_PLANE; kind <= BF_FIG_POLAR; kind++) {
        for (f = 0; f < 2; f++) {
            size_t n = bf_fig_family(D, fams[f], pos);
            for (k = 0; k < n; k += BF_FIG_PLANE_CURVES) {
                bf_fig_entry *e = add_entry(set, (bf_fig_kind)kind, s,
                                            D->st->samples[s]);
                if (e == NULL) {
                    return BF_ENOMEM;
                }
                e->family = fams[f];
                e->first = k;
                e->count = n - k < BF_FIG_PLANE_CURVES ? n - k
                                                       : BF_FIG_PLANE_CURVES;
            }
        }
    }
    return BF_OK;
}

/* The figures of the paper's protocol: Figure 2(b), wins, Figures 3-6 and
 * per sample the plane of incidence (and the scatter panels). */
static int list_paper(const bf_fig_data *D, bf_fig_set *set)
{
    const bf_rep_study *st = D->st;
    size_t N = st->n_samples;
    size_t first_group = set->n + 2;
    size_t g;
    size_t s;
    int ok = add_entry(set, BF_FIG_LSE, 0, 0) != NULL &&
             add_entry(set, BF_FIG_WINS, 0, 0) != NULL;
    for (g = 0, s = 0; s < N && ok; g++) {
        bf_fig_entry *e = add_entry(set, BF_FIG_SCATTER, g, 0);
        ok = e != NULL;
        if (ok) {
            e->first = s;
            e->count = bf_fig_scatter_group(D, s);
            s += e->count;
        }
    }
    for (s = first_group; s < set->n && ok; s++) {
        set->fig[s].parts = g;
    }
    for (s = 0; s < N && ok; s++) {
        int sample = st->samples[s];
        ok = (!D->o->per_sample ||
              add_entry(set, BF_FIG_SAMPLE, s, sample) != NULL) &&
             (D->o->n_incidence == 0 || /* nothing in its plane */
              list_plane(D, set, s) == BF_OK);
    }
    return ok ? BF_OK : BF_ENOMEM;
}

/* The figures of the analysis (st->stats): delta BIC, a forest plot per
 * model with fitted parameters, a profile per sample, a dispersion
 * figure per material that has n(lambda) and, with --calibrate, a
 * calibration figure per sample. */
static int list_analysis(const bf_fig_data *D, bf_fig_set *set)
{
    const bf_rep_study *st = D->st;
    size_t per = st->cal.n > 0 ? bf_fig_calibration_per_figure(D) : 1;
    size_t m;
    size_t s;
    /* delta BIC in pages of rows (samples) */
    int ok = list_pages(set, BF_FIG_DELTA_BIC, 0, 0, 0, st->n_samples,
                        bf_fig_rows_per_page(D));
    for (m = 0; m < st->n_models && ok; m++) {
        if (bf_fig_has_forest(st, m)) {
            ok = list_pages(set, BF_FIG_FOREST, m, 0, 0, st->n_samples,
                            bf_fig_forest_rows(D, m));
        }
    }
    for (s = 0; s < st->n_samples && ok; s++) {
        /* the diffuse models' profiles, then the specular ones' (none for
         * a joint fit: it has no profile interval, and its profile is the
         * channels' together) */
        int none = bf_fig_profile_panels(st, s, 0) == 0;
        int f;
        if (st->targets[s].joint) {
            continue;
        }
        for (f = none ? 0 : BF_FIG_DIFFUSE; f <= BF_FIG_SPECULAR && ok;
             f++) {
            if (!none && bf_fig_profile_panels(st, s, f) == 0) {
                continue; /* (none: one figure saying so) */
            }
            ok = list_pages(set, BF_FIG_PROFILE, s, st->samples[s], f,
                            bf_fig_profile_panels(st, s, f),
                            BF_FIG_PROFILE_PANELS);
            f = none ? BF_FIG_SPECULAR : f;
        }
    }
    for (s = 0; s < st->n_samples && ok; s++) { /* n(lambda) */
        if (bf_fig_dispersion_first(st, s) != SIZE_MAX) {
            ok = add_entry(set, BF_FIG_DISPERSION, s, st->samples[s]) !=
                 NULL;
        }
    }
    for (s = 0; s < st->n_samples && ok && st->cal.n > 0; s++) {
        /* a sample's panels in parts of at most per */
        size_t np = bf_fig_calibration_panels(st, s);
        ok = np == 0 || list_pages(set, BF_FIG_CALIBRATION, s,
                                   st->samples[s], 0, np, per);
    }
    return ok ? BF_OK : BF_ENOMEM;
}

static int describe(const bf_fig_data *D, bf_fig_entry *e, bf_fig_desc *d,
                    int full)
{
    memset(d, 0, sizeof *d);
    switch (e->kind) {
    case BF_FIG_LSE: return bf_fig_lse(D, e, d, full);
    case BF_FIG_WINS: return bf_fig_wins(D, e, d, full);
    case BF_FIG_SCATTER:
    case BF_FIG_SAMPLE: return bf_fig_scatter(D, e, d, full);
    case BF_FIG_DELTA_BIC: return bf_fig_delta_bic(D, e, d, full);
    case BF_FIG_FOREST: return bf_fig_forest(D, e, d, full);
    case BF_FIG_PLANE:
    case BF_FIG_POLAR: return bf_fig_plane(D, e, d, full);
    case BF_FIG_PROFILE: return bf_fig_profile(D, e, d, full);
    case BF_FIG_CALIBRATION: return bf_fig_calibration(D, e, d, full);
    case BF_FIG_DISPERSION: return bf_fig_dispersion(D, e, d, full);
    }
    return BF_EINVAL;
}

/* ==== temporary files ==================================================== */

/* Creates an empty temporary file for e in format fmt. */
static int make_tmp(const bf_fig_set *set, bf_fig_entry *e,
                    bf_plot_format fmt)
{
    int fd;
    int len = snprintf(e->tmp[fmt], sizeof e->tmp[fmt], "%s/.%s.%s.XXXXXX",
                       set->dir, e->base, bf_plot_format_ext(fmt));
    if (len < 0 || (size_t)len >= sizeof e->tmp[fmt]) {
        bf_rep_err("%s: output path too long", set->dir);
        e->tmp[fmt][0] = '\0';
        return BF_REPORT_CANTCREAT;
    }
    fd = mkstemp(e->tmp[fmt]);
    if (fd < 0) {
        bf_rep_err("%s/%s.%s: cannot create: %s", set->dir, e->base,
                   bf_plot_format_ext(fmt), strerror(errno));
        e->tmp[fmt][0] = '\0';
        return BF_REPORT_CANTCREAT;
    }
    (void)fchmod(fd, 0644);
    close(fd);
    return BF_REPORT_OK;
}

/* ==== drawing ============================================================ */

static int n_formats(unsigned formats)
{
    int n = 0;
    int f;
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        n += (int)((formats >> f) & 1u);
    }
    return n;
}

/* Draws entry e in every format of the set; calls tick after each file.
 * Returns BF_REPORT_OK or a status after the message. */
static int draw_entry(const bf_fig_data *D, const bf_fig_set *set,
                      bf_fig_entry *e, void (*tick)(void *), void *arg)
{
    bf_fig_desc d;
    int rc = describe(D, e, &d, 1);
    int f;
    if (rc != BF_OK) {
        bf_rep_err("%s: cannot describe the figure: %s", e->base,
                   bf_strerror(rc));
        bf_fig_desc_free(&d);
        return rc == BF_ENOMEM ? BF_REPORT_SOFTWARE : BF_REPORT_DATAERR;
    }
    for (f = 0; f < BF_PLOT_NFORMATS; f++) {
        if (!((set->formats >> f) & 1u)) {
            continue;
        }
        rc = bf_plot_write(&d.fig, (bf_plot_format)f, e->tmp[f]);
        if (rc != BF_OK) {
            bf_rep_err("%s/%s.%s: cannot draw the figure: %s", set->dir,
                       e->base, bf_plot_format_ext((bf_plot_format)f),
                       bf_strerror(rc));
            bf_fig_desc_free(&d);
            return rc == BF_EIO ? BF_REPORT_IOERR : BF_REPORT_SOFTWARE;
        }
        tick(arg);
    }
    bf_fig_desc_free(&d);
    return BF_REPORT_OK;
}

/* Progress (the options' callback): files drawn of the total. */
typedef struct {
    size_t done;
    size_t total;
    bf_report_progress_fn show; /* NULL: none */
    void *show_ctx;
    int fd; /* workers: the pipe to the parent, else -1 */
} progress_t;

static void progress_tick(void *arg)
{
    progress_t *p = arg;
    if (p->fd >= 0) {
        char c = 'x';
        (void)!write(p->fd, &c, 1);
        return;
    }
    p->done++;
    if (p->show != NULL) {
        p->show(p->show_ctx, "drawing figures", p->done, p->total);
    }
}

/* Reads one figure index from the work pipe; 0 at its end. */
static int next_index(int fd, size_t *i)
{
    unsigned char b[4];
    size_t got = 0;
    while (got < sizeof b) {
        ssize_t r = read(fd, b + got, sizeof b - got);
        if (r < 0 && errno == EINTR) {
            continue;
        }
        if (r <= 0) {
            return 0;
        }
        got += (size_t)r;
    }
    *i = (size_t)b[0] | ((size_t)b[1] << 8) | ((size_t)b[2] << 16) |
         ((size_t)b[3] << 24);
    return 1;
}

/* The drawing processes of one batch of figures. */
#define MAX_WORKERS 64
typedef struct {
    pid_t pid[MAX_WORKERS];
    int n;    /* processes started */
    int prog; /* read end of their progress pipe, -1 when none */
} pool_t;

/* What a render keeps from bf_figures_start to bf_figures_finish. */
struct bf_fig_run {
    bf_fig_data D;
    const bf_fig_opts *o;
    pool_t pool[2];   /* the paper's figures, the analysis figures */
    size_t n_pools;
    progress_t pr;
    int analysis;     /* the analysis figures are listed */
};

/* Draws figures [from, set->n) with jobs processes: the parent writes
 * their indices into a work pipe (4 bytes each: atomic pipe writes and
 * reads) before any worker starts reading, each worker draws the figures
 * it reads, reports each file drawn on the progress pipe and exits with
 * its status. With jobs = 1 the figures are drawn here. Returns
 * BF_REPORT_OK or a status (after the message). */
static int pool_start(const bf_fig_data *D, bf_fig_set *set, size_t from,
                      int jobs, pool_t *p, progress_t *pr)
{
    int work[2];
    int prog[2];
    int w;
    size_t i;
    p->n = 0;
    p->prog = -1;
    if (jobs <= 1 || set->n - from <= 1) {
        int rc = BF_REPORT_OK;
        for (i = from; i < set->n && rc == BF_REPORT_OK; i++) {
            rc = draw_entry(D, set, &set->fig[i], progress_tick, pr);
        }
        return rc;
    }
    if (pipe(work) != 0) {
        bf_rep_err("cannot start the drawing processes: %s", strerror(errno));
        return BF_REPORT_SOFTWARE;
    }
    for (i = from; i < set->n; i++) { /* a few bytes a figure: fits */
        unsigned char b[4] = {(unsigned char)(i & 0xFF),
                              (unsigned char)((i >> 8) & 0xFF),
                              (unsigned char)((i >> 16) & 0xFF),
                              (unsigned char)((i >> 24) & 0xFF)};
        if (write(work[1], b, sizeof b) != (ssize_t)sizeof b) {
            bf_rep_err("cannot hand out the figures: %s", strerror(errno));
            close(work[0]);
            close(work[1]);
            return BF_REPORT_SOFTWARE;
        }
    }
    close(work[1]);
    if (pipe(prog) != 0) {
        bf_rep_err("cannot start the drawing processes: %s", strerror(errno));
        close(work[0]);
        return BF_REPORT_SOFTWARE;
    }
    fflush(stdout);
    fflush(stderr);
    for (w = 0; w < jobs && w < MAX_WORKERS; w++) {
        pid_t pid = fork();
        if (pid < 0) {
            bf_rep_err("cannot start a drawing process: %s", strerror(errno));
            break;
        }
        if (pid == 0) { /* a worker */
            progress_t mine = *pr;
            int status = BF_REPORT_OK;
            close(prog[0]);
            mine.fd = prog[1];
            while (status == BF_REPORT_OK && next_index(work[0], &i) &&
                   i < set->n) {
                status = draw_entry(D, set, &set->fig[i], progress_tick,
                                    &mine);
            }
            _exit(status);
        }
        p->pid[p->n++] = pid;
    }
    close(work[0]);
    close(prog[1]);
    p->prog = prog[0];
    return p->n > 0 ? BF_REPORT_OK : BF_REPORT_SOFTWARE;
}

/* Waits for the processes of p, counting the files they report; returns
 * the first failing status (BF_REPORT_OK when all succeeded). With kill_them,
 * stops them first (the run failed elsewhere). */
static int pool_wait(pool_t *p, progress_t *pr, int kill_them)
{
    char buf[256];
    ssize_t got;
    int rc = BF_REPORT_OK;
    int w;
    for (w = 0; kill_them && w < p->n; w++) {
        kill(p->pid[w], SIGTERM);
    }
    while (p->prog >= 0 && ((got = read(p->prog, buf, sizeof buf)) > 0 ||
                            (got < 0 && errno == EINTR))) {
        ssize_t k;
        for (k = 0; k < got; k++) {
            progress_tick(pr);
        }
    }
    if (p->prog >= 0) {
        close(p->prog);
        p->prog = -1;
    }
    for (w = 0; w < p->n; w++) {
        int status = 0;
        while (waitpid(p->pid[w], &status, 0) < 0 && errno == EINTR) {
        }
        if (rc == BF_REPORT_OK) {
            rc = WIFEXITED(status) ? WEXITSTATUS(status) : BF_REPORT_SOFTWARE;
        }
    }
    p->n = 0;
    return rc;
}

/* ==== the render ========================================================= */

/* Names, texts and sizes of figures [from, set->n) (the page needs them),
 * then their temporary files. */
static int prepare(const bf_fig_data *D, bf_fig_set *set, size_t from)
{
    size_t i;
    int f;
    for (i = from; i < set->n; i++) {
        bf_fig_desc d;
        int e = describe(D, &set->fig[i], &d, 0);
        if (e == BF_OK) {
            e = bf_plot_size(&d.fig, &set->fig[i].width,
                             &set->fig[i].height);
        }
        bf_fig_desc_free(&d);
        if (e != BF_OK) {
            bf_rep_err("%s: cannot lay out the figure: %s",
                       set->fig[i].base, bf_strerror(e));
            return BF_REPORT_SOFTWARE;
        }
    }
    for (i = from; i < set->n; i++) {
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            if ((set->formats >> f) & 1u) {
                int rc = make_tmp(set, &set->fig[i], (bf_plot_format)f);
                if (rc != BF_REPORT_OK) {
                    return rc;
                }
            }
        }
    }
    return BF_REPORT_OK;
}

/* Lists figures from `from` on with list, prepares and starts them. */
static int batch(struct bf_fig_run *run, bf_fig_set *set,
                 int (*list)(const bf_fig_data *, bf_fig_set *))
{
    size_t from = set->n;
    int rc;
    if (list(&run->D, set) != BF_OK) {
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    rc = prepare(&run->D, set, from);
    run->pr.total += (set->n - from) * (size_t)n_formats(set->formats);
    if (rc == BF_REPORT_OK) {
        rc = pool_start(&run->D, set, from, run->o->jobs,
                        &run->pool[run->n_pools++], &run->pr);
    }
    return rc;
}

int bf_figures_start(const bf_rep_study *st, const bf_fig_opts *o,
                     const char *out_dir, bf_fig_set *set,
                     int with_analysis)
{
    struct bf_fig_run *run = calloc(1, sizeof *run);
    size_t s;
    int rc = BF_REPORT_OK;

    memset(set, 0, sizeof *set);
    set->formats = o->formats;
    snprintf(set->dir, sizeof set->dir, "%s/%s", out_dir, BF_FIG_DIR);
    if (run == NULL || (run->D.smp = calloc(st->n_samples + 1,
                                            sizeof *run->D.smp)) == NULL) {
        free(run);
        bf_rep_err("out of memory");
        return BF_REPORT_SOFTWARE;
    }
    set->run = run;
    run->o = o;
    run->D.st = st;
    run->D.o = o;
    run->pr.show = o->progress;
    run->pr.show_ctx = o->progress_ctx;
    run->pr.fd = -1;
    for (s = 0; s < st->n_samples && rc == BF_REPORT_OK; s++) {
        int e = sample_compute(st, s, &run->D.smp[s]);
        if (e != BF_OK) {
            bf_rep_err("sample %d: cannot compute the radiances to plot: %s",
                       st->samples[s], bf_strerror(e));
            rc = e == BF_ENOMEM ? BF_REPORT_SOFTWARE : BF_REPORT_DATAERR;
        }
    }
    run->D.nm = scatter_models(st, run->D.idx);
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_make_outdir(out_dir);
    }
    if (rc == BF_REPORT_OK) {
        rc = bf_rep_make_outdir(set->dir);
    }
    if (rc == BF_REPORT_OK) {
        rc = batch(run, set, list_paper);
    }
    if (rc == BF_REPORT_OK && with_analysis && st->stats != NULL) {
        run->analysis = 1;
        rc = batch(run, set, list_analysis);
    }
    if (rc != BF_REPORT_OK) {
        bf_figures_free(set);
    }
    return rc;
}

int bf_figures_finish(const bf_rep_study *st, bf_fig_set *set)
{
    struct bf_fig_run *run = set->run;
    int rc = BF_REPORT_OK;
    size_t p;
    if (run == NULL) {
        return BF_REPORT_SOFTWARE;
    }
    if (!run->analysis && st->stats != NULL) {
        run->analysis = 1;
        rc = batch(run, set, list_analysis);
    }
    for (p = 0; p < run->n_pools; p++) {
        int w = pool_wait(&run->pool[p], &run->pr, rc != BF_REPORT_OK);
        rc = rc == BF_REPORT_OK ? w : rc;
    }
    if (run->pr.show != NULL && run->pr.done > 0) {
        run->pr.show(run->pr.show_ctx, NULL, 0, 0);
    }
    if (rc != BF_REPORT_OK) {
        bf_figures_free(set);
    }
    return rc;
}

int bf_figures_render(const bf_rep_study *st, const bf_fig_opts *o,
                      const char *out_dir, bf_fig_set *set)
{
    int rc = bf_figures_start(st, o, out_dir, set, 1);
    return rc == BF_REPORT_OK ? bf_figures_finish(st, set) : rc;
}

int bf_figures_commit(bf_fig_set *set)
{
    size_t i;
    int f;
    for (i = 0; i < set->n; i++) {
        bf_fig_entry *e = &set->fig[i];
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            char path[4200];
            if (e->tmp[f][0] == '\0') {
                continue;
            }
            snprintf(path, sizeof path, "%s/%s.%s", set->dir, e->base,
                     bf_plot_format_ext((bf_plot_format)f));
            if (rename(e->tmp[f], path) != 0) {
                bf_rep_err("%s: cannot rename into place: %s", path,
                           strerror(errno));
                return BF_REPORT_IOERR; /* bf_figures_free removes the rest */
            }
            e->tmp[f][0] = '\0';
        }
    }
    return BF_REPORT_OK;
}

void bf_figures_free(bf_fig_set *set)
{
    struct bf_fig_run *run = set->run;
    size_t i;
    int f;
    if (run != NULL) { /* processes still drawing: stop them first */
        for (i = 0; i < run->n_pools; i++) {
            (void)pool_wait(&run->pool[i], &run->pr, 1);
        }
    }
    for (i = 0; i < set->n; i++) {
        for (f = 0; f < BF_PLOT_NFORMATS; f++) {
            if (set->fig[i].tmp[f][0] != '\0') {
                unlink(set->fig[i].tmp[f]);
                set->fig[i].tmp[f][0] = '\0';
            }
        }
    }
    free(set->fig);
    set->fig = NULL;
    set->n = 0;
    if (run != NULL) {
        data_free(&run->D);
        free(run);
        set->run = NULL;
        (void)rmdir(set->dir); /* only when empty: nothing else is lost */
    }
}
