/* analysis.c: the analysis beyond the paper for many (target, model)
 * pairs on the engine (doc/methods.md) -- grid optimum under the
 * objective, exact refinement, profile and bootstrap intervals, AIC, BIC,
 * cross-validation and what the fit says about itself (flags) -- on
 * threads, with progress.
 *
 * [1] SPEC §2, §7 (data, configurations, grid), doc/methods.md §1-§8.
 *
 * Work is organised so that nothing is computed twice: one prepared model
 * per (configuration set, model) -- its kernel's geometry terms -- and one
 * grid of stored curves per (configuration set, model, fixed inputs),
 * shared by every target with those inputs and by all their bootstrap
 * replicates and folds (weights over the same curves). The units of work,
 * one (target, model) pair each, are independent: each reads the shared
 * grids and writes only its own result, so any thread may take any unit
 * and the results do not depend on the thread count (kernel workspaces are
 * per thread; their caches hold values that are functions of their keys).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* A group: the targets of one configuration set and model with the same
 * fixed inputs share a grid. */
typedef struct {
    size_t set;
    size_t m;
    const double *fixed; /* BF_MAX_PARAMS values (a member's) */
    size_t prep;         /* index into preps */
    bf__grid *gr;
    int status;          /* of building the grid */
} group_t;

typedef struct {
    const bf__job *job;
    bf__prep *preps;     /* n_sets x n_models */
    group_t *groups;
    size_t n_groups;
    size_t *group_of;    /* per unit, SIZE_MAX when it has no inputs */
    bf_fit_stats *stats;
    int *unit_status;
    size_t per;          /* grid optima per unit: the data and each fold */
    bf_fit_result *grids; /* per unit, per optima (phase 2), or NULL */
    unsigned char *have; /* per unit: grids computed */
    size_t done;         /* units finished (progress) */
    int status;          /* first fatal error (BF_ENOMEM) */
} run_t;

static void stats_clear(bf_fit_stats *st)
{
    size_t j;
    memset(st, 0, sizeof *st);
    for (j = 0; j < BF_MAX_PARAMS; j++) {
        st->ci_low[j] = NAN;
        st->ci_high[j] = NAN;
        st->boot_low[j] = NAN;
        st->boot_high[j] = NAN;
        st->ml_param[j] = NAN;
        st->ci_robust[j] = NAN;
        st->ci_gap_low[j] = NAN;
        st->ci_gap_high[j] = NAN;
    }
    st->noise_power = NAN;
    st->noise_sigma = NAN;
    st->aic = NAN;
    st->bic = NAN;
    st->cv = NAN;
    st->scale = NAN;
}

/* The problem of unit u (its model, inputs, data and the objective). */
static void unit_problem(const run_t *r, size_t u, bf_problem *pb)
{
    const bf__job *job = r->job;
    size_t t = u / job->n_models;
    size_t m = u % job->n_models;
    const bf__cset *cs = &job->sets[job->set_of[t]];
    bf_problem_init(pb, job->models[m], job->fixed + u * BF_MAX_PARAMS,
                    cs->n, cs->geom, job->data[t]);
    pb->objective = job->opts->objective;
}

/* ==== grouping and grids ================================================= */

static int make_groups(run_t *r)
{
    const bf__job *job = r->job;
    size_t n_units = job->n_targets * job->n_models;
    size_t u;
    size_t g;
    r->groups = calloc(n_units + 1, sizeof *r->groups);
    r->group_of = malloc((n_units + 1) * sizeof *r->group_of);
    if (r->groups == NULL || r->group_of == NULL) {
        return BF_ENOMEM;
    }
    for (u = 0; u < n_units; u++) {
        size_t t = u / job->n_models;
        size_t m = u % job->n_models;
        const double *fx = job->fixed + u * BF_MAX_PARAMS;
        r->group_of[u] = SIZE_MAX;
        if (job->status[u] != BF_OK) {
            continue;
        }
        for (g = 0; g < r->n_groups; g++) {
            const group_t *gp = &r->groups[g];
            if (gp->set == job->set_of[t] && gp->m == m &&
                memcmp(gp->fixed, fx, BF_MAX_PARAMS * sizeof *fx) == 0) {
                break;
            }
        }
        if (g == r->n_groups) {
            group_t *gp = &r->groups[r->n_groups++];
            gp->set = job->set_of[t];
            gp->m = m;
            gp->fixed = fx;
            gp->prep = gp->set * job->n_models + m;
        }
        r->group_of[u] = g;
    }
    return BF_OK;
}

/* The grid of group g over the free parameters' search ranges. */
static void build_grid(run_t *r, size_t g, size_t u_example)
{
    group_t *gp = &r->groups[g];
    bf__grid_layout_t lay;
    bf_problem pb;
    unit_problem(r, u_example, &pb);
    if (pb.type->kind == BF_MODEL_SPECULAR) {
        gp->status = BF_OK; /* its own search (varpro.c), no stored grid */
        return;
    }
    gp->status = bf__grid_layout_range(pb.type, pb.fixed, pb.free_mask,
                                       pb.lo, pb.hi, &lay);
    if (gp->status == BF_OK) {
        gp->gr = bf__grid_make(&r->preps[gp->prep], &lay, &gp->status);
    }
}

/* ==== one unit ============================================================ */

/* 1 when the study's grid optimum of unit u can stand for the analysis's:
 * the paper's objective on the paper's grid of the same type. */
static int study_grid_usable(const run_t *r, size_t u, const bf_problem *pb)
{
    const bf__job *job = r->job;
    bf__grid_layout_t paper;
    bf__grid_layout_t mine;
    if (job->grid == NULL || pb->objective != BF_OBJ_MAX ||
        bf__grid_layout(pb->type, pb->fixed, 0, &paper) != BF_OK ||
        bf__grid_layout_range(pb->type, pb->fixed, pb->free_mask, pb->lo,
                              pb->hi, &mine) != BF_OK ||
        paper.mask != mine.mask || paper.points != mine.points) {
        return 0;
    }
    (void)u;
    return memcmp(paper.lo, mine.lo, sizeof paper.lo) == 0 &&
           memcmp(paper.step, mine.step, sizeof paper.step) == 0;
}

/* What the optimum says about the fit: the reduced model, the clamp. */
static void fit_flags(const bf__fitctx *fc, bf_fit_stats *st)
{
    const bf_model_type *type = fc->pm->type;
    const bf_problem *pb = fc->pb;
    size_t j = type->reduces_param;
    if (type->reduces_to != NULL && j < type->p &&
        ((pb->free_mask >> j) & 1u) &&
        fabs(st->refined.param[j] - type->reduces_at) <= BF_REFINE_TOL) {
        st->flags |= BF_STAT_REDUCED;
        st->reduces_to = type->reduces_to;
    }
    if (fc->pm->kr->clamped != NULL) {
        st->n_clamped = fc->pm->kr->clamped(fc->pm, st->refined.param);
        if (st->n_clamped > 0) {
            st->flags |= BF_STAT_CLAMPED;
        }
    }
}

/* The Neyman construction's intervals in place of iv's for the
 * parameters which (bf__neyman_which; bf__neyman, on the grid gr, which
 * leaves a failed parameter's as iv's): a fit where one failed is flagged
 * BF_STAT_CI_FAIL; ci_neyman gets the parameters constructed, and
 * ci_method says "neyman" when they are every free one. */
static int neyman(bf__fitctx *fc, const bf_interval *iv, const bf__grid *gr,
                  unsigned which, const bf_analysis_opts *opts,
                  bf_fit_stats *st)
{
    const bf_problem *pb = fc->pb;
    bf_interval ny;
    unsigned failed = 0;
    size_t j;
    int rc = bf__neyman(fc, iv, gr, which, opts->n_neyman, opts->seed,
                        opts->level, &ny, &failed);
    if (rc == BF_ENOMEM) {
        return rc;
    }
    for (j = 0; j < pb->type->p; j++) {
        if ((pb->free_mask >> j) & 1u) {
            st->ci_low[j] = ny.low[j];
            st->ci_high[j] = ny.high[j];
            st->ci_gap_low[j] = ny.gap_low[j];
            st->ci_gap_high[j] = ny.gap_high[j];
            st->ci_open = (st->ci_open & ~(3u << (2 * j))) |
                          (ny.open & (3u << (2 * j)));
        }
    }
    if (failed != 0) {
        st->flags |= BF_STAT_CI_FAIL;
    }
    st->ci_neyman = ny.neyman;
    st->ci_method = ny.method;
    return BF_OK;
}

/* What every fit gets after its optimum st->refined (fc->pb = pb): the
 * intervals under the noise model (unless opts->no_intervals), the
 * bootstrap, AIC and BIC, the cross-validation (gr, fold_grid: the grid
 * and the folds' grid optima; NULL for a specular model, whose folds have
 * their own fits, from what its whole fit left them, whole; NULL for the
 * others). */
static int analyse_rest(bf__fitctx *fc, const bf_problem *pb,
                        const bf_analysis_opts *opts, const size_t *fold,
                        const bf__grid *gr, const bf_fit_result *fold_grid,
                        const bf__vp_whole *whole, bf_fit_stats *st)
{
    bf_interval iv;
    unsigned which; /* the parameters the construction makes */
    size_t j;
    int rc;
    memset(&iv, 0, sizeof iv);
    if (pb->free_mask != 0 && !opts->no_intervals) {
        rc = bf__intervals(fc, &st->refined, opts->noise, opts->level,
                           &iv);
        if (rc == BF_ENOMEM) {
            return rc;
        }
        if (rc != BF_OK) {
            st->flags |= BF_STAT_CI_FAIL;
        }
        for (j = 0; j < pb->type->p; j++) {
            if ((pb->free_mask >> j) & 1u) {
                st->ci_low[j] = iv.low[j];
                st->ci_high[j] = iv.high[j];
                st->ml_param[j] = iv.ml.param[j];
                st->ci_robust[j] = iv.robust[j];
                st->ci_gap_low[j] = iv.gap_low[j];
                st->ci_gap_high[j] = iv.gap_high[j];
            }
        }
        st->ci_open = iv.open;
        st->ci_method = iv.method;
        st->noise_power = iv.noise_power;
        st->noise_sigma = iv.sigma;
        st->not_identified = iv.not_identified;
        st->ci_competing = iv.competing;
        which = rc == BF_OK ? bf__neyman_which(pb, &iv, opts->n_neyman,
                                               opts->neyman_every)
                            : 0;
        if (which != 0) {
            rc = neyman(fc, &iv, gr, which, opts, st);
            if (rc == BF_ENOMEM) {
                return rc;
            }
        }
    }
    if (opts->n_boot >= 2 && pb->free_mask != 0) {
        unsigned split = 0;
        rc = bf__bootstrap(fc, &iv, opts->n_boot, opts->seed, opts->level,
                           NULL, NULL, st->boot_low, st->boot_high, &split);
        st->boot_split = split;
        if (split != 0) {
            st->flags |= BF_STAT_BOOT_SPLIT;
        }
        if (rc == BF_ENOMEM) {
            return rc;
        }
        if (rc != BF_OK) {
            st->flags |= BF_STAT_BOOT_FAIL;
        } else {
            st->boot_method = BF_CI_RESIDUAL_BOOTSTRAP;
        }
    }
    if (st->refined.lse > 0.0) {
        st->aic = bf_criterion_aic(st->refined.lse, pb->n, st->k);
        st->bic = bf_criterion_bic(st->refined.lse, pb->n, st->k);
    }
    if (opts->folds >= 2 && opts->folds <= pb->n) {
        if (pb->free_mask == 0) {
            st->cv = st->refined.lse; /* nothing to fit: CV = LSE */
        } else {
            rc = bf__cv(fc, gr, fold, opts->folds, fold_grid, whole,
                        &st->cv);
            if (rc == BF_ENOMEM) {
                return rc;
            }
        }
    }
    st->done = 1;
    return BF_OK;
}

/* The joint fit (--channel joint, SPEC §9.4) led by unit u: the n_ch
 * channels' data on the same configurations, one shape, each channel's
 * scales solved exactly (varpro.c, ngan), S summed over the channels; its
 * AIC and BIC on the K C values with the shape's and every channel's
 * scales counted. Every channel's unit gets the fit with its own scales
 * (the shape, S, AIC and BIC the same). */
static int analyse_joint(run_t *r, size_t u, bf__fitctx *fc, size_t n_ch)
{
    const bf__job *job = r->job;
    size_t t = u / job->n_models;
    size_t n = fc->pm->n;
    bf_fit_stats *st = &r->stats[u];
    double *data = malloc((n * n_ch + 1) * sizeof *data);
    double *grid_p = malloc((2 * n_ch + 1) * BF_MAX_PARAMS * sizeof *grid_p);
    double *ref_p = grid_p != NULL ? grid_p + n_ch * BF_MAX_PARAMS : NULL;
    bf__fitctx jc;
    bf_problem pb;
    unsigned lin = 0;
    size_t n_lin = 0;
    size_t c;
    size_t j;
    int rc = data != NULL && grid_p != NULL ? BF_OK : BF_ENOMEM;
    memset(&jc, 0, sizeof jc);
    if (rc == BF_OK) {
        rc = bf__fitctx_init_blocks(&jc, fc->pm, n_ch);
    }
    if (rc != BF_OK) {
        free(data);
        free(grid_p);
        return rc;
    }
    unit_problem(r, u, &pb);
    for (c = 0; c < n_ch; c++) {
        memcpy(data + c * n, job->data[t + c], n * sizeof *data);
    }
    pb.data = data;
    bf__fitctx_use(&jc, &pb);
    for (j = 0; j < pb.type->p; j++) {
        if (((pb.free_mask >> j) & 1u) && pb.type->param[j].linear) {
            lin |= 1u << j;
            n_lin++;
        }
    }
    st->objective = pb.objective;
    st->free_mask = pb.free_mask;
    st->n = n * n_ch;
    st->k = bf_problem_nparams(&pb) + (n_ch - 1) * n_lin;
    rc = bf__varpro_fit(&jc, &st->grid, &st->refined, NULL);
    if (rc == BF_OK) {
        rc = bf__varpro_scales(&jc, st->grid.param, grid_p);
    }
    if (rc == BF_OK) {
        rc = bf__varpro_scales(&jc, st->refined.param, ref_p);
    }
    if (rc == BF_OK && st->refined.lse > 0.0) {
        st->aic = bf_criterion_aic(st->refined.lse, st->n, st->k);
        st->bic = bf_criterion_bic(st->refined.lse, st->n, st->k);
    }
    for (c = n_ch; rc == BF_OK && c-- > 0;) { /* the first channel last */
        bf_fit_stats *sc = &r->stats[u + c * job->n_models];
        if (c > 0) {
            *sc = *st;
        }
        memcpy(sc->grid.param, grid_p + c * BF_MAX_PARAMS,
               sizeof sc->grid.param);
        memcpy(sc->refined.param, ref_p + c * BF_MAX_PARAMS,
               sizeof sc->refined.param);
        for (j = 0; j < pb.type->p; j++) { /* each channel's own scales */
            if ((lin >> j) & 1u) {
                unsigned bit = 1u << j;
                sc->refined.bound_hit &= ~bit;
                if (sc->refined.param[j] <= pb.lo[j] + BF_REFINE_TOL ||
                    sc->refined.param[j] >= pb.hi[j] - BF_REFINE_TOL) {
                    sc->refined.bound_hit |= bit;
                }
            }
        }
        sc->done = 1;
    }
    bf__fitctx_free(&jc);
    free(data);
    free(grid_p);
    return rc;
}

/* Analyses unit u with the thread's context fc (pointed at the unit's
 * problem here). Returns BF_OK, a code for the row (BF_EDOM: the model
 * cannot fit these data), or BF_ENOMEM. */
static int analyse_unit(run_t *r, size_t u, bf__fitctx *fc, size_t *fold,
                        bf_fit_result *grids)
{
    const bf__job *job = r->job;
    const bf_analysis_opts *opts = job->opts;
    const group_t *gp = &r->groups[r->group_of[u]];
    bf_fit_stats *st = &r->stats[u];
    bf_problem pb;
    int cv;
    int rc;

    if (job->joint_n != NULL && job->joint_n[u / job->n_models] > 0) {
        size_t n_ch = job->joint_n[u / job->n_models];
        /* a joint fit's other channels: its first channel's unit */
        return n_ch == SIZE_MAX ? BF_OK : analyse_joint(r, u, fc, n_ch);
    }
    unit_problem(r, u, &pb);
    bf__fitctx_use(fc, &pb);
    st->objective = pb.objective;
    st->free_mask = pb.free_mask;
    st->n = pb.n;
    st->k = bf_problem_nparams(&pb);
    cv = opts->folds >= 2 && opts->folds <= pb.n && pb.free_mask != 0;
    rc = cv ? bf_fit_cv_folds(pb.n, opts->folds, opts->seed, fold) : BF_OK;
    if (rc != BF_OK) {
        return rc;
    }
    if (pb.type->kind == BF_MODEL_SPECULAR) {
        /* SPEC §9.3, §9.4 under an objective that keeps the scale: the
         * separable fit (varpro.c), its own grid; then as every model */
        bf__vp_whole whole;
        memset(&whole, 0, sizeof whole);
        whole.fold = cv ? fold : NULL; /* its folds' grid values too */
        whole.folds = opts->folds;
        rc = bf__varpro_fit(fc, &st->grid, &st->refined, &whole);
        if (rc == BF_OK) {
            rc = analyse_rest(fc, &pb, opts, fold, NULL, NULL, &whole, st);
        }
        bf__vp_whole_free(&whole);
        return rc;
    }
    if (gp->gr == NULL) {
        return gp->status;
    }
    /* the grid optima of the data and of every fold's training set: from
     * the group's pass (phase 2), else one pass for this unit */
    if (r->have[u]) {
        memcpy(grids, r->grids + u * r->per, r->per * sizeof *grids);
    } else if (cv) {
        rc = bf__grid_optima_folds(gp->gr, &pb, fc->pm->cs->cti, fold,
                                   opts->folds, grids);
    } else {
        const double *w[1] = {NULL};
        rc = bf__grid_optima(gp->gr, &pb, fc->pm->cs->cti, 1, w, grids);
    }
    if (rc != BF_OK) {
        return rc;
    }
    st->grid = grids[0];
    if (study_grid_usable(r, u, &pb) && job->grid[u].n_eval > 0) {
        st->grid = job->grid[u]; /* the study's grid optimum stands */
    }
    if (!isfinite(st->grid.lse)) {
        return BF_EDOM;
    }
    rc = bf__refine(fc, &st->grid, &st->refined);
    if (rc == BF_ENOCONV) {
        st->flags |= BF_STAT_NOCONV;
    } else if (rc != BF_OK) {
        return rc;
    }
    if (!(st->refined.lse < st->grid.lse)) {
        /* never worse than the grid (the study's sums round differently) */
        size_t n_eval = st->refined.n_eval;
        unsigned flat = st->refined.flat;
        st->refined = st->grid;
        st->refined.n_eval = n_eval;
        st->refined.flat = flat;
    }
    fit_flags(fc, st);
    if (bf_objective_keeps_scale(pb.objective)) { /* SPEC §9.4: rho_d */
        rc = bf_fit_scale(&pb, st->refined.param, &st->scale);
        if (rc == BF_ENOMEM) {
            return rc;
        }
    }
    return analyse_rest(fc, &pb, opts, fold, gp->gr, grids + 1, NULL, st);
}

/* ==== the grid optima of a group, one pass (phase 2) ===================== */

/* The grid optima of every member of group g (data and folds) from one
 * pass over the group's curves (the max and cosw objectives; the others
 * are scored per unit). */
static void group_optima(run_t *r, size_t g)
{
    const bf__job *job = r->job;
    const group_t *gp = &r->groups[g];
    const bf_analysis_opts *opts = job->opts;
    const bf__cset *cs = &job->sets[gp->set];
    size_t n_units = job->n_targets * job->n_models;
    size_t folds = opts->folds >= 2 && opts->folds <= cs->n ? opts->folds : 0;
    const double **data = malloc((job->n_targets + 1) * sizeof *data);
    size_t *members = malloc((job->n_targets + 1) * sizeof *members);
    size_t *fold = malloc((cs->n + 1) * sizeof *fold);
    bf_fit_result *res = NULL;
    size_t n_members = 0;
    size_t u;
    size_t q;
    size_t b;
    if (gp->gr == NULL || data == NULL || members == NULL || fold == NULL ||
        (opts->objective != BF_OBJ_MAX && opts->objective != BF_OBJ_COSW) ||
        (folds > 0 &&
         bf_fit_cv_folds(cs->n, folds, opts->seed, fold) != BF_OK)) {
        goto done; /* the units score themselves */
    }
    for (u = 0; u < n_units; u++) {
        if (r->group_of[u] == g) {
            members[n_members] = u;
            data[n_members++] = job->data[u / job->n_models];
        }
    }
    res = malloc((n_members * (folds + 1) + 1) * sizeof *res);
    if (res == NULL ||
        bf__grid_folds_argmin(gp->gr, n_members, data,
                              opts->objective == BF_OBJ_COSW ? cs->cti : NULL,
                              fold, folds, res) != BF_OK) {
        goto done;
    }
    for (q = 0; q < n_members; q++) {
        u = members[q];
        for (b = 0; b < r->per; b++) { /* without folds: the data only */
            r->grids[u * r->per + b] = res[q * (folds + 1) +
                                           (b <= folds ? b : 0)];
        }
        r->have[u] = folds + 1 == r->per || folds == 0;
    }
done:
    free(data);
    free(members);
    free(fold);
    free(res);
}

/* ==== the run ============================================================= */

/* Per thread: one context per prepared model, made on first use. */
typedef struct {
    bf__fitctx *fc;
    unsigned char *made;
} thread_t;

static bf__fitctx *context(run_t *r, thread_t *th, size_t prep)
{
    if (!th->made[prep]) {
        if (bf__fitctx_init(&th->fc[prep], &r->preps[prep]) != BF_OK) {
            return NULL;
        }
        th->made[prep] = 1;
    }
    return &th->fc[prep];
}

static void run_units(run_t *r)
{
    const bf__job *job = r->job;
    size_t n_units = job->n_targets * job->n_models;
    size_t n_preps = job->n_sets * job->n_models;
    int n_threads = job->n_threads > 1 ? job->n_threads : 1;
    long n_groups = (long)r->n_groups;
    long g;
    long u;

    /* the grids, one per group, shared afterwards */
#pragma omp parallel for schedule(dynamic, 1) num_threads(n_threads)      \
    if (n_threads > 1)
    for (g = 0; g < n_groups; g++) {
        size_t v;
        for (v = 0; v < n_units; v++) {
            if (r->group_of[v] == (size_t)g) {
                build_grid(r, (size_t)g, v);
                break;
            }
        }
    }
    for (g = 0; g < n_groups; g++) {
        if (r->groups[g].status == BF_ENOMEM) {
            r->status = BF_ENOMEM;
            return;
        }
    }
    /* every member's grid optima, one pass over each group's curves */
#pragma omp parallel for schedule(dynamic, 1) num_threads(n_threads)      \
    if (n_threads > 1)
    for (g = 0; g < n_groups; g++) {
        group_optima(r, (size_t)g);
    }

#pragma omp parallel num_threads(n_threads) if (n_threads > 1)
    {
        thread_t th;
        size_t p;
        size_t max_n = 0;
        size_t *fold;
        bf_fit_result *grids = malloc((job->opts->folds + 2) * sizeof *grids);
        for (p = 0; p < job->n_sets; p++) {
            max_n = job->sets[p].n > max_n ? job->sets[p].n : max_n;
        }
        fold = malloc((max_n + 1) * sizeof *fold);
        th.fc = calloc(n_preps + 1, sizeof *th.fc);
        th.made = calloc(n_preps + 1, 1);
#pragma omp for schedule(dynamic, 1)
        for (u = 0; u < (long)n_units; u++) {
            size_t uu = (size_t)u;
            int rc = BF_OK;
            int fatal;
#pragma omp atomic read
            fatal = r->status;
            if (r->group_of[uu] == SIZE_MAX || fatal != BF_OK) {
                rc = r->job->status[uu];
            } else {
                bf__fitctx *fc = th.fc == NULL || th.made == NULL ||
                                         fold == NULL || grids == NULL
                                     ? NULL
                                     : context(r, &th,
                                               r->groups[r->group_of[uu]]
                                                   .prep);
                rc = fc == NULL ? BF_ENOMEM
                                : analyse_unit(r, uu, fc, fold, grids);
            }
            r->unit_status[uu] = rc;
#pragma omp critical(bf_analysis_progress)
            {
                if (rc == BF_ENOMEM) {
#pragma omp atomic write
                    r->status = BF_ENOMEM;
                }
                r->done++;
                if (job->opts->progress != NULL) {
                    job->opts->progress(job->opts->progress_ctx, r->done,
                                        n_units);
                }
            }
        }
        for (p = 0; th.made != NULL && p < n_preps; p++) {
            if (th.made[p]) {
                bf__fitctx_free(&th.fc[p]);
            }
        }
        free(th.fc);
        free(th.made);
        free(fold);
        free(grids);
    }
}

int bf__analyse(const bf__job *job, bf_fit_stats *stats, int *unit_status)
{
    run_t r;
    size_t n_units = job->n_targets * job->n_models;
    size_t u;
    size_t s;
    size_t m;
    size_t g;
    int rc;

    memset(&r, 0, sizeof r);
    r.job = job;
    r.stats = stats;
    r.unit_status = unit_status;
    for (u = 0; u < n_units; u++) {
        stats_clear(&stats[u]);
        unit_status[u] = job->status[u];
    }
    r.per = job->opts->folds >= 2 ? job->opts->folds + 1 : 1;
    r.grids = malloc((n_units * r.per + 1) * sizeof *r.grids);
    r.have = calloc(n_units + 1, 1);
    r.preps = calloc(job->n_sets * job->n_models + 1, sizeof *r.preps);
    rc = r.preps == NULL || r.grids == NULL || r.have == NULL
             ? BF_ENOMEM
             : make_groups(&r);
    for (s = 0; rc == BF_OK && s < job->n_sets; s++) {
        for (m = 0; rc == BF_OK && m < job->n_models; m++) {
            rc = bf__prep_init(&r.preps[s * job->n_models + m],
                               job->models[m], &job->sets[s]);
        }
    }
    if (rc == BF_OK) {
        run_units(&r);
        rc = r.status;
    }
    for (u = 0; rc == BF_OK && job->joint_n != NULL && u < n_units; u++) {
        size_t n_ch = job->joint_n[u / job->n_models];
        size_t c;
        for (c = 1; n_ch != SIZE_MAX && c < n_ch; c++) { /* its channels */
            unit_status[u + c * job->n_models] = unit_status[u];
        }
    }
    for (g = 0; g < r.n_groups; g++) {
        bf__grid_free(r.groups[g].gr);
    }
    for (s = 0; r.preps != NULL && s < job->n_sets * job->n_models; s++) {
        bf__prep_free(&r.preps[s]);
    }
    free(r.preps);
    free(r.groups);
    free(r.group_of);
    free(r.grids);
    free(r.have);
    return rc;
}

/* A macro's value as a string literal. */
#define NY_STR_(x) #x
#define NY_STR(x) NY_STR_(x)

int bf_analysis_opts_check(const bf_analysis_opts *o, bf_error *err)
{
    const char *why = NULL;
    if (o == NULL) {
        why = "no analysis options";
    } else if (bf_objective_name(o->objective) == NULL) {
        why = "unknown objective";
    } else if (bf_noise_name(o->noise) == NULL) {
        why = "unknown noise model";
    } else if (!(o->level > 0.0 && o->level < 1.0)) {
        why = "the interval level must be in (0, 1)";
    } else if (o->no_intervals && o->n_boot > 0) {
        why = "no_intervals is set: a bootstrap interval is an interval "
              "too; drop the bootstrap or keep the intervals";
    } else if (o->no_intervals && o->n_neyman > 0 && o->neyman_every) {
        why = "no_intervals is set: the Neyman construction is an interval "
              "too; drop it or keep the intervals";
    } else if (o->n_neyman > 0 && o->n_neyman < BF_NEYMAN_MIN_SIM) {
        why = "the Neyman construction needs at least " NY_STR(
            BF_NEYMAN_MIN_SIM) " simulations per threshold";
    } else if (o->n_neyman > 0 && o->neyman_every &&
               o->noise == BF_NOISE_OBJECTIVE) {
        why = "the Neyman construction simulates a noise model: not with "
              "the objective's own (noise 'objective')";
    }
    if (why == NULL) {
        return BF_OK;
    }
    bf__error_clear(err, "analysis");
    return bf__error_set(err, BF_EINVAL, 0, "%s", why);
}

void bf_analysis_opts_init(bf_analysis_opts *o)
{
    memset(o, 0, sizeof *o);
    o->objective = BF_OBJ_MAX; /* the paper's (SPEC §2) */
    o->level = 0.95;
    o->folds = 10;
    o->seed = 1;
    o->noise = BF_NOISE_AUTO;
    o->n_neyman = BF_NEYMAN_AUTO_SIM; /* where a second minimum competes */
}
