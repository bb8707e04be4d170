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
 *
 * [3] SPEC §10: the objectives that keep the scale, on rho = BRDF cos ti
 *     as measured (R) and the curve L times a free scale s >= 0:
 *   ngan      s = max(0, sum w L R / sum w L^2),  S = sum w (s L - R)^2
 *   cuberoot  t = max(0, sum w L' R' / sum w L'^2), L' = cbrt L,
 *             R' = cbrt R,  S = sum w (t L' - R')^2  (cbrt(s L) = t L')
 *   log1p     s = argmin_{s >= 0} sum w (ln(1 + s L) - ln(1 + R))^2
 *   ngan's reported value is E = sqrt(S / K).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit/engine.h"

static const char *const objective_names[] = {"max",  "scale",    "cosw",
                                               "log",  "ngan",     "cuberoot",
                                               "log1p"};

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

int bf_objective_keeps_scale(bf_objective obj)
{
    return obj == BF_OBJ_NGAN || obj == BF_OBJ_CUBEROOT ||
           obj == BF_OBJ_LOG1P;
}

double bf_objective_report(bf_objective obj, double s, double n)
{
    if (obj == BF_OBJ_NGAN) { /* SPEC §10: E = sqrt(S / K) */
        return n > 0.0 && s >= 0.0 ? sqrt(s / n) : NAN;
    }
    return s;
}

void bf__data_transform(const bf_problem *pb, double *out)
{
    size_t k;
    for (k = 0; pb->data != NULL && k < pb->n; k++) {
        double d = pb->data[k];
        switch (pb->objective) {
        case BF_OBJ_LOG: /* doc/methods.md §1: floored logs */
            out[k] = log(d > BF_LOG_FLOOR ? d : BF_LOG_FLOOR);
            break;
        case BF_OBJ_CUBEROOT: /* SPEC §10: the real cube root */
            out[k] = cbrt(d);
            break;
        case BF_OBJ_LOG1P: /* SPEC §10 */
            out[k] = log1p(d);
            break;
        default:
            return;
        }
    }
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
        } else if (pj->fitted && type->kind == BF_MODEL_SPECULAR) {
            pb->free_mask |= 1u << j; /* SPEC §9.3: its whole domain */
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
    if (pb->type->kind == BF_MODEL_SPECULAR) {
        return bf_problem_nfree(pb); /* SPEC §9: no scale beside them */
    }
    return bf_problem_nfree(pb) + (pb->objective == BF_OBJ_SCALE ||
                                           bf_objective_keeps_scale(
                                               pb->objective)
                                       ? 1u
                                       : 0u);
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

/* sum w L' R' / sum w L'^2 clamped at 0 (L' = the cube roots of the
 * curve c, or c itself when roots is 1; R' = tdata): the cube-root
 * objective's t = cbrt(s) (SPEC §10). */
static double cuberoot_scale(const bf_problem *pb, const double *tdata,
                             const double *c, int roots)
{
    double num = 0.0;
    double den = 0.0;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double w = weight_of(pb, k);
        double l = roots ? c[k] : cbrt(c[k]);
        num += w * l * tdata[k];
        den += w * l * l;
    }
    return den > 0.0 && num > 0.0 ? num / den : 0.0;
}

/* Half the derivative (*g1) and second derivative (*g2) in s of the log1p
 * objective sum w (ln(1 + s L) - R')^2, R' = tdata. */
static void log1p_slope(const bf_problem *pb, const double *tdata,
                        const double *curve, double s, double *g1,
                        double *g2)
{
    double a = 0.0;
    double b = 0.0;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double w = weight_of(pb, k);
        double l = curve[k];
        double q = l / (1.0 + s * l);
        double r = log1p(s * l) - tdata[k];
        a += w * r * q;
        b += w * q * q * (1.0 - r);
    }
    *g1 = a;
    *g2 = b;
}

/* The s >= 0 minimising the log1p objective (SPEC §10): 0 when the slope
 * at 0 is not negative, else the root of the slope in a bracket [lo, hi]
 * (hi doubled from the least-squares scale until the slope turns
 * positive, kept where 1 + s L > 0), by Newton steps from the
 * least-squares scale that bisect whenever a step leaves the bracket, to
 * a step or bracket of 1e-13 relative (S is flat to second order
 * there). */
static double log1p_scale(const bf_problem *pb, const double *tdata,
                          const double *curve)
{
    double lo = 0.0;
    double hi;
    double cap = INFINITY;
    double s;
    double g1;
    double g2;
    size_t k;
    int it;
    for (k = 0; k < pb->n; k++) { /* 1 + s L > 0 for s < cap */
        if (curve[k] < 0.0 && weight_of(pb, k) != 0.0) {
            cap = fmin(cap, -1.0 / curve[k]);
        }
    }
    log1p_slope(pb, tdata, curve, 0.0, &g1, &g2);
    if (!(g1 < 0.0)) {
        return 0.0;
    }
    hi = optimal_scale(pb, curve);
    hi = hi > 0.0 ? hi : 1.0;
    for (it = 0; it < 2100; it++) {
        if (hi >= cap) {
            hi = 0.5 * (lo + cap);
        }
        log1p_slope(pb, tdata, curve, hi, &g1, &g2);
        if (!(g1 < 0.0)) {
            break;
        }
        lo = hi;
        hi *= 2.0;
    }
    s = optimal_scale(pb, curve);
    s = s > lo && s < hi ? s : 0.5 * (lo + hi);
    for (it = 0; it < 200; it++) {
        double next;
        log1p_slope(pb, tdata, curve, s, &g1, &g2);
        if (g1 == 0.0) {
            break;
        }
        if (g1 < 0.0) {
            lo = s;
        } else {
            hi = s;
        }
        next = g2 > 0.0 ? s - g1 / g2 : NAN;
        next = next > lo && next < hi ? next : 0.5 * (lo + hi);
        if (fabs(next - s) <= 1e-13 * s || hi - lo <= 1e-13 * hi) {
            return next;
        }
        s = next;
    }
    return s;
}

double bf__fit_scale_of(const bf_problem *pb, const double *tdata,
                        const double *curve)
{
    if (pb->type->kind == BF_MODEL_SPECULAR) {
        return 1.0; /* SPEC §9: its scales are parameters */
    }
    switch (pb->objective) {
    case BF_OBJ_SCALE:
        return optimal_scale(pb, curve);
    case BF_OBJ_NGAN: {
        double s = optimal_scale(pb, curve);
        return s > 0.0 ? s : 0.0; /* non-negative (SPEC §9.3 domains) */
    }
    case BF_OBJ_CUBEROOT: {
        double t = cuberoot_scale(pb, tdata, curve, 0);
        return t * t * t;
    }
    case BF_OBJ_LOG1P:
        return log1p_scale(pb, tdata, curve);
    default:
        return 1.0;
    }
}

/* The residuals and the sum run at every evaluation of every fit: one
 * clone per ISA (BF__CLONES, built as the kernels are), so the
 * element-wise loops vectorise and fma() is one instruction, not a call;
 * the bits are the baseline's (no contraction; the sum in index order). */
BF__CLONES
void bf__residuals(const bf_problem *pb, const double *cti,
                   const double *log_d, const double *curve, double *resid)
{
    size_t k;
    double s;
    if (pb->objective == BF__OBJ_LIK) { /* src/fit/noise.c */
        bf__lik_residuals(pb, curve, resid);
        return;
    }
    if (pb->objective == BF_OBJ_CUBEROOT) { /* t cbrt(L) - cbrt(rho) */
        double t;
        for (k = 0; k < pb->n; k++) {
            resid[k] = cbrt(curve[k]);
        }
        t = pb->type->kind == BF_MODEL_SPECULAR
                ? 1.0 /* SPEC §9: its scales are parameters */
                : cuberoot_scale(pb, log_d, resid, 1);
        for (k = 0; k < pb->n; k++) {
            resid[k] = t * resid[k] - log_d[k];
        }
        return;
    }
    s = bf__fit_scale_of(pb, log_d, curve);
    if (pb->objective == BF_OBJ_NGAN || pb->objective == BF_OBJ_SCALE) {
        /* SPEC §10 (the separable fits' every evaluation): a loop of its
         * own, which the clones vectorise */
        for (k = 0; k < pb->n; k++) {
            resid[k] = s * curve[k] - pb->data[k];
        }
        return;
    }
    for (k = 0; k < pb->n; k++) {
        double l = curve[k];
        double d = pb->data[k];
        switch (pb->objective) {
        case BF_OBJ_LOG1P:
            resid[k] = log1p(s * l) - log_d[k];
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

BF__CLONES
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

/* ==== the free scale as rho_d (SPEC §9.4) ================================ */

int bf_fit_scale(const bf_problem *pb, const double *param, double *rho_d)
{
    static const bf_geom normal = {0.0, 3.14159265358979323846, 0.0, 0.0};
    bf__solo so;
    double *v;
    double vmax = -INFINITY;
    double s = 0.0;
    size_t k;
    int rc;
    if (pb == NULL || rho_d == NULL || pb->data == NULL ||
        !bf_objective_keeps_scale(pb->objective) ||
        (pb->type != NULL && pb->type->kind == BF_MODEL_SPECULAR) ||
        (pb->type != NULL && pb->type->p > 0 && param == NULL)) {
        return BF_EINVAL;
    }
    *rho_d = NAN;
    rc = bf__solo_init(&so, pb);
    if (rc != BF_OK) {
        return rc;
    }
    v = malloc((pb->n + 1) * sizeof *v);
    rc = v == NULL ? BF_ENOMEM
                   : bf__curve(&so.pm, param, so.fc.work, so.fc.curve);
    if (rc == BF_OK) { /* s L_k, L the curve normalised by its maximum */
        s = bf__fit_scale_of(pb, so.fc.log_d, so.fc.curve);
        rc = bf_model_eval(pb->type, param, pb->n, pb->geom, v);
    }
    if (rc == BF_OK) {
        rc = bf_model_eval(pb->type, param, 1, &normal, v + pb->n);
    }
    for (k = 0; rc == BF_OK && k < pb->n; k++) {
        vmax = v[k] > vmax ? v[k] : vmax;
    }
    /* s L_k = s v_k / max v = rho_d v_k / (pi v_normal), SPEC §9.4 */
    if (rc == BF_OK && !(vmax > 0.0 && v[pb->n] > 0.0 && isfinite(vmax) &&
                         isfinite(v[pb->n]))) {
        rc = BF_EDOM;
    }
    if (rc == BF_OK) {
        *rho_d = s * 3.14159265358979323846 * (v[pb->n] / vmax);
    }
    free(v);
    bf__solo_free(&so);
    return rc;
}
