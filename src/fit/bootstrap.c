/* bootstrap.c: the percentile bootstrap over configurations
 * (doc/methods.md §3): resamples as weights over the same curves.
 *
 * [1] B. Efron, R. J. Tibshirani, "An Introduction to the Bootstrap",
 *     Chapman & Hall 1993, ch. 9 (bootstrapping regression by resampling
 *     pairs) and ch. 13 (percentile intervals).
 *
 * Equations: replicate b weights w_bk = the number of times configuration
 * k is drawn in n draws with replacement; the estimate of replicate b
 * minimises S_b = sum_k w_bk r_k^2; the interval is the (1 -+ level)/2
 * quantiles of the B estimates [1].
 *
 * A resample changes only the weights, never the configurations: the grid
 * optimum of every replicate comes from the one set of stored curves,
 * scored against many weight vectors at once (bf__grid_optima), and the
 * refinement reuses the engine's prepared model.
 */
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

/* Replicates whose grid optima are found together: for the objectives
 * whose optima need no stored scores (max, cosw: bf__grid_weights_argmin)
 * BATCH, so each super-block's squared residuals serve them all; for the
 * others BATCH_STORED (their scores: BATCH_STORED x grid columns
 * doubles). */
#define BATCH 1024
#define BATCH_STORED 64
/* A gap between replicate estimates wider than this share of the interval
 * splits it (is_split). */
#define SPLIT_GAP 0.25

/* 1 when the sorted estimates e[0..m) fall into separate groups inside
 * the interval [low, high]: a gap wider than SPLIT_GAP of it with at least
 * the interval's tail share (1 - level)/2 of the replicates on either
 * side -- replicates whose optima lie in different basins of the
 * objective, so the percentile interval spans both (doc/methods.md §3). */
static int is_split(const double *e, size_t m, double low, double high,
                    double level)
{
    size_t tail = (size_t)ceil(0.5 * (1.0 - level) * (double)m);
    size_t i;
    for (i = 1; i < m; i++) {
        if (e[i - 1] >= low && e[i] <= high && i >= tail && m - i >= tail &&
            e[i] - e[i - 1] > SPLIT_GAP * (high - low)) {
            return 1;
        }
    }
    return 0;
}

int bf__bootstrap(bf__fitctx *fc, const bf_grid *gr, size_t n_boot,
                  unsigned long seed, double level, double *est,
                  size_t *n_est, double *low, double *high, unsigned *split)
{
    const bf_problem *pb = fc->pb;
    size_t n = pb->n;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    size_t batch = (pb->objective == BF_OBJ_MAX ||
                    pb->objective == BF_OBJ_COSW)
                       ? BATCH
                       : BATCH_STORED;
    double *w = malloc(batch * n * sizeof *w);
    const double **wp = malloc(batch * sizeof *wp);
    bf_fit_result *g = malloc(batch * sizeof *g);
    double *own = est == NULL ? malloc(n_boot * BF_MAX_PARAMS * sizeof *own)
                              : NULL;
    double *e = est != NULL ? est : own;
    size_t used = 0;
    size_t b0;
    size_t j;
    int rc = BF_OK;

    if (split != NULL) {
        *split = 0;
    }
    if (rng == NULL || w == NULL || wp == NULL || g == NULL || e == NULL) {
        rc = BF_ENOMEM;
        goto done;
    }
    gsl_rng_set(rng, seed);
    for (b0 = 0; b0 < n_boot && rc == BF_OK; b0 += batch) {
        size_t nb = n_boot - b0 < batch ? n_boot - b0 : batch;
        size_t b;
        size_t k;
        for (b = 0; b < nb; b++) { /* resample configurations [1] */
            double *wb = w + b * n;
            memset(wb, 0, n * sizeof *wb);
            for (k = 0; k < n; k++) {
                wb[gsl_rng_uniform_int(rng, n)] += 1.0;
            }
            wp[b] = wb;
        }
        rc = bf__grid_optima(gr, pb, fc->pm->cs->cti, nb, wp, g);
        for (b = 0; rc == BF_OK && b < nb; b++) {
            bf_problem rep = *pb;
            bf_fit_result r;
            int st = BF_EDOM;
            rep.weight = wp[b];
            if (isfinite(g[b].lse)) {
                bf__fitctx_use(fc, &rep);
                st = bf__refine(fc, &g[b], &r);
                st = st == BF_ENOCONV ? BF_OK : st; /* the best point */
            }
            if (st == BF_ENOMEM) {
                rc = st;
                break;
            }
            if (st != BF_OK) {
                continue; /* a replicate the model cannot fit: left out */
            }
            for (j = 0; j < BF_MAX_PARAMS; j++) {
                e[j * n_boot + used] = r.param[j];
            }
            used++;
        }
        bf__fitctx_use(fc, pb);
    }
    for (j = 0; rc == BF_OK && j < BF_MAX_PARAMS; j++) {
        double *ej = e + j * n_boot;
        low[j] = NAN;
        high[j] = NAN;
        if (j >= pb->type->p || !((pb->free_mask >> j) & 1u) || used < 2) {
            continue;
        }
        gsl_sort(ej, 1, used);
        low[j] = gsl_stats_quantile_from_sorted_data(ej, 1, used,
                                                     0.5 * (1.0 - level));
        high[j] = gsl_stats_quantile_from_sorted_data(ej, 1, used,
                                                      0.5 * (1.0 + level));
        if (split != NULL && is_split(ej, used, low[j], high[j], level)) {
            *split |= 1u << j;
        }
    }
    if (rc == BF_OK && used < 2) {
        rc = BF_EDOM;
    }
    if (n_est != NULL) {
        *n_est = used;
    }
done:
    gsl_rng_free(rng);
    free(w);
    free(wp);
    free(g);
    free(own);
    return rc;
}

int bf_fit_bootstrap(const bf_problem *pb, const bf_curves *curves,
                     size_t n_boot, unsigned long seed, double level,
                     double *low, double *high)
{
    bf__solo so;
    int rc;
    if (bf__curves_check(curves, pb) != BF_OK || low == NULL ||
        high == NULL || pb->weight != NULL || n_boot < 2 ||
        !(level > 0.0 && level < 1.0)) {
        return BF_EINVAL;
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = bf__bootstrap(&so.fc, bf__curves_grid(curves), n_boot, seed, level,
                       NULL, NULL, low, high, NULL);
    bf__solo_free(&so);
    return rc;
}
