/* objective.c: the objectives a fit can minimise and the fitting problem
 * that bundles model, data, weights and search ranges (doc/methods.md §1).
 *
 * [1] SPEC §2, §7.3: max-normalised curves, LSE as a sum (BF_OBJ_MAX).
 * [2] doc/methods.md §1: the scale, cos-weighted and log objectives.
 *
 * Equations (L normalised model curve, D normalised data, w weights):
 *   max    S = sum w (L - D)^2                                  SPEC §7.3
 *   scale  s* = sum w L D / sum w L^2,  S = sum w (s* L - D)^2
 *   cosw   S = sum w cos(theta_i) (L - D)^2
 *   log    S = sum w (ln max(L, f) - ln max(D, f))^2,  f = BF_LOG_FLOOR
 */
#include <math.h>
#include <string.h>

#include "fit/engine.h"

static const char *const objective_names[] = {"max", "scale", "cosw", "log"};

#define N_OBJECTIVES (sizeof objective_names / sizeof objective_names[0])

const char *bf_objective_name(bf_objective obj)
{
    if ((unsigned)obj >= N_OBJECTIVES) {
        return NULL;
    }
    return objective_names[obj];
}

int bf_objective_find(const char *name, bf_objective *obj)
{
    size_t i;
    if (name == NULL || obj == NULL) {
        return BF_EINVAL;
    }
    for (i = 0; i < N_OBJECTIVES; i++) {
        if (strcmp(name, objective_names[i]) == 0) {
            *obj = (bf_objective)i;
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}

/* ==== the problem ======================================================== */

int bf_problem_init(bf_problem *pb, const bf_model_type *type,
                    const double *fixed, size_t n, const bf_geom *geom,
                    const double *data)
{
    size_t j;
    if (pb == NULL || type == NULL || type->p > BF_MAX_PARAMS || n == 0 ||
        geom == NULL) {
        return BF_EINVAL;
    }
    memset(pb, 0, sizeof *pb);
    pb->type = type;
    pb->n = n;
    pb->geom = geom;
    pb->data = data;
    pb->objective = BF_OBJ_MAX;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        pb->fixed[j] = fixed != NULL ? fixed[j] : pj->value;
        pb->lo[j] = pj->min;
        pb->hi[j] = pj->max;
        if (pj->fitted && pj->grid_n > 0) {
            pb->free_mask |= 1u << j;
            pb->lo[j] = pj->grid_lo;
            pb->hi[j] = pj->grid_lo + pj->grid_step * (double)(pj->grid_n - 1);
        }
    }
    return BF_OK;
}

size_t bf_problem_nfree(const bf_problem *pb)
{
    size_t j;
    size_t count = 0;
    for (j = 0; j < pb->type->p; j++) {
        count += (pb->free_mask >> j) & 1u;
    }
    return count;
}

size_t bf_problem_nparams(const bf_problem *pb)
{
    return bf_problem_nfree(pb) + (pb->objective == BF_OBJ_SCALE ? 1u : 0u);
}

/* ==== objectives on a normalised curve =================================== */

/* Weight of configuration k (1 without weights). */
static double weight_of(const bf_problem *pb, size_t k)
{
    return pb->weight != NULL ? pb->weight[k] : 1.0;
}

/* The least-squares scale s* = sum w L D / sum w L^2 (0 when every weighted
 * L is 0). */
static double optimal_scale(const bf_problem *pb, const double *curve)
{
    double num = 0.0;
    double den = 0.0;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double w = weight_of(pb, k);
        num += w * curve[k] * pb->data[k];
        den += w * curve[k] * curve[k];
    }
    return den > 0.0 ? num / den : 0.0;
}

void bf__residuals(const bf_problem *pb, const double *cti,
                   const double *log_d, const double *curve, double *resid)
{
    size_t k;
    double s = pb->objective == BF_OBJ_SCALE ? optimal_scale(pb, curve) : 1.0;
    if (pb->objective == BF__OBJ_LIK) { /* src/fit/noise.c */
        bf__lik_residuals(pb, curve, resid);
        return;
    }
    for (k = 0; k < pb->n; k++) {
        double l = curve[k];
        double d = pb->data[k];
        switch (pb->objective) {
        case BF_OBJ_SCALE:
            resid[k] = s * l - d;
            break;
        case BF_OBJ_COSW:
            resid[k] = sqrt(cti[k]) * (l - d);
            break;
        case BF_OBJ_LOG:
            resid[k] = log(l > BF_LOG_FLOOR ? l : BF_LOG_FLOOR) - log_d[k];
            break;
        default:
            resid[k] = l - d; /* SPEC §7.3 */
            break;
        }
    }
}

double bf__objective(const bf_problem *pb, const double *cti,
                     const double *log_d, const double *curve,
                     double *scratch)
{
    double sum = 0.0;
    size_t k;
    /* Every objective is sum_k w_k rho_k with rho_k the rounded squared
     * residual, added in index order by one fma (w = 1: one add), exactly
     * as the grid's scoring (bf__score_weights) adds them, so a grid
     * point's S is the same number either way. */
    if (pb->objective == BF_OBJ_MAX || pb->objective == BF_OBJ_COSW) {
        return bf__sum_weighted(pb->n, curve, pb->data, pb->weight,
                                pb->objective == BF_OBJ_COSW ? cti : NULL);
    }
    if (pb->objective == BF__OBJ_LIK) { /* src/fit/noise.c */
        return bf__lik_value(pb, curve, scratch);
    }
    bf__residuals(pb, cti, log_d, curve, scratch);
    for (k = 0; k < pb->n; k++) {
        double rho = scratch[k] * scratch[k];
        sum = pb->weight != NULL ? fma(pb->weight[k], rho, sum) : sum + rho;
    }
    return sum;
}

/* ==== objectives at a parameter vector (the public entry points) ========= */

/* One evaluation of pb through the engine, with its own configuration set
 * and scratch memory (the public API's convenience; the library's fits
 * keep one engine context per problem instead). resid NULL: the value. */
static int problem_eval(const bf_problem *pb, const double *param,
                        double *value, double *resid)
{
    bf__solo so;
    size_t j;
    int rc;
    if (pb->type->p > 0 && param == NULL) {
        return BF_EINVAL;
    }
    for (j = 0; j < pb->type->p; j++) {
        const bf_param *pj = &pb->type->param[j];
        if (!isfinite(param[j]) || param[j] < pj->min || param[j] > pj->max) {
            return BF_EINVAL;
        }
    }
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    rc = resid != NULL ? bf__fit_residuals(&so.fc, param, resid)
                       : bf__fit_value(&so.fc, param, value);
    bf__solo_free(&so);
    return rc;
}

int bf_problem_value(const bf_problem *pb, const double *param, double *work,
                     double *value)
{
    (void)work;
    if (pb == NULL || pb->data == NULL || pb->type == NULL ||
        pb->geom == NULL || value == NULL) {
        return BF_EINVAL;
    }
    return problem_eval(pb, param, value, NULL);
}

int bf_problem_residuals(const bf_problem *pb, const double *param,
                         double *work, double *resid)
{
    (void)work;
    if (pb == NULL || pb->data == NULL || pb->type == NULL ||
        pb->geom == NULL || resid == NULL) {
        return BF_EINVAL;
    }
    return problem_eval(pb, param, NULL, resid);
}
