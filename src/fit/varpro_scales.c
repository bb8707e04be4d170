/* varpro_scales.c: the scales of the separable fit solved exactly (SPEC
 * §9.3, §10): at every point of the nonlinear parameters, the model's
 * columns once and the non-negative least-squares scales of one or two
 * of them, per block (a joint fit's channel), and the objective there
 * (varpro.c has the equations and the search).
 *
 * [1] C. L. Lawson, R. J. Hanson, "Solving Least Squares Problems", 1974,
 *     ch. 23 (non-negative least squares: the optimum is the
 *     unconstrained one on its active set).
 */
#include <math.h>
#include <string.h>

#include "fit/varpro.h"
#include "internal.h"

/* The passes over the data run at every evaluation of a separable fit
 * (the normal equations' sums, the columns' scaling, the curve, the
 * residuals): one clone per ISA (BF__CLONES, built as the kernels are),
 * so the element-wise loops vectorise; the sums stay in index order, so
 * the bits are the baseline's. */

static double weight_of(const bf_problem *pb, size_t k)
{
    return pb->weight != NULL ? pb->weight[k] : 1.0;
}

/* sum w (c0 + t1 c1 + t2 c2 - R)^2 (c0 NULL: 0; c2 NULL: one column). */
static double sse(const bf_problem *pb, const double *c0, const double *c1,
                  const double *c2, double t1, double t2)
{
    double sum = 0.0;
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double r = (c0 != NULL ? c0[k] : 0.0) + t1 * c1[k] - pb->data[k];
        if (c2 != NULL) {
            r += t2 * c2[k];
        }
        sum += weight_of(pb, k) * r * r;
    }
    return sum;
}

int bf__vp_nnls_solve(const bf__vp_normal *ne, int two, const double *hi,
                      double *t)
{
    t[0] = ne->g11 > 0.0 && ne->b1 > 0.0 ? fmin(ne->b1 / ne->g11, hi[0])
                                         : 0.0;
    if (!two) {
        return 1;
    }
    t[1] = ne->g22 > 0.0 && ne->b2 > 0.0 ? fmin(ne->b2 / ne->g22, hi[1])
                                         : 0.0;
    {
        double det = ne->g11 * ne->g22 - ne->g12 * ne->g12;
        if (det > 1e-14 * ne->g11 * ne->g22 && det > 0.0) {
            double u1 = (ne->b1 * ne->g22 - ne->b2 * ne->g12) / det;
            double u2 = (ne->b2 * ne->g11 - ne->b1 * ne->g12) / det;
            if (u1 >= 0.0 && u2 >= 0.0 && u1 <= hi[0] && u2 <= hi[1]) {
                t[0] = u1; /* both active: the unconstrained optimum */
                t[1] = u2;
                return 1;
            }
        }
    }
    return 0;
}

/* The NNLS scales of one or two columns c1, c2 for the target R - c0 (c0
 * NULL: R), each clamped into [0, hi]. */
BF__CLONES
static void nnls(const bf_problem *pb, const double *c0, const double *c1,
                 const double *c2, const double *hi, double *t)
{
    bf__vp_normal ne = {0.0, 0.0, 0.0, 0.0, 0.0};
    double a[BF__VP_MAX_LIN];
    size_t k;
    for (k = 0; k < pb->n; k++) {
        double w = weight_of(pb, k);
        double r = pb->data[k] - (c0 != NULL ? c0[k] : 0.0);
        ne.g11 += w * c1[k] * c1[k];
        ne.b1 += w * c1[k] * r;
        if (c2 != NULL) {
            ne.g12 += w * c1[k] * c2[k];
            ne.g22 += w * c2[k] * c2[k];
            ne.b2 += w * c2[k] * r;
        }
    }
    if (bf__vp_nnls_solve(&ne, c2 != NULL, hi, t)) {
        return;
    }
    a[0] = t[0];
    a[1] = t[1];
    /* one scale at 0: the better of the two one-column optima */
    if (sse(pb, c0, c1, c2, a[0], 0.0) <= sse(pb, c0, c1, c2, 0.0, a[1])) {
        t[0] = a[0];
        t[1] = 0.0;
    } else {
        t[0] = 0.0;
        t[1] = a[1];
    }
}

/* The columns of a point: c_0, then one per scale of fc->lin_mask (n_l of
 * them, their parameters lj, their bounds hi). */
typedef struct {
    double *col[BF__VP_MAX_LIN + 1];
    double hi[BF__VP_MAX_LIN];
    size_t lj[BF__VP_MAX_LIN];
    size_t n_l;
} columns_t;

/* The columns of fc's model at param into c, as bf__curve gives rho =
 * values cos ti; kept from the last evaluation when it was at the same
 * point. */
BF__CLONES
static int columns(bf__fitctx *fc, const double *param, columns_t *c)
{
    const bf_problem *pb = fc->pb;
    const size_t n = fc->pm->n;
    size_t j;
    size_t q;
    int rc;
    c->n_l = 0;
    for (j = 0; j < pb->type->p; j++) {
        if ((fc->lin_mask >> j) & 1u) {
            if (c->n_l == BF__VP_MAX_LIN || fc->cols == NULL) {
                return BF_EINVAL;
            }
            c->hi[c->n_l] = pb->hi[j];
            c->lj[c->n_l++] = j;
        }
    }
    for (q = 0; q <= c->n_l; q++) {
        c->col[q] = fc->cols + q * n;
    }
    /* c_0 and the c_j, each part of the model evaluated once (the
     * kernel's columns) */
    fc->n_eval++;
    if (!fc->cols_ok || fc->cols_lin != fc->lin_mask ||
        memcmp(fc->cols_at, param, pb->type->p * sizeof *param) != 0) {
        fc->cols_ok = 0;
        rc = (fc->pm->kr->columns != NULL ? fc->pm->kr->columns
                                          : bf__columns_values)(
            fc->pm, param, fc->lin_mask, fc->work, c->col[0], c->col + 1);
        if (rc != BF_OK) {
            return BF_EDOM;
        }
        for (q = 0; q <= c->n_l; q++) {
            const double *cti = fc->pm->cs->cti;
            double *cq = c->col[q];
            double nf = 0.0;
            size_t k;
#pragma omp simd reduction(+ : nf)
            for (k = 0; k < n; k++) {
                cq[k] *= cti[k];
                nf += cq[k] - cq[k]; /* NaN once a value is not finite */
            }
            if (nf != 0.0) {
                return BF_EDOM;
            }
        }
        memcpy(fc->cols_at, param, pb->type->p * sizeof *param);
        fc->cols_lin = fc->lin_mask;
        fc->cols_ok = 1;
    }
    return BF_OK;
}

BF__CLONES
int bf__varpro_value(bf__fitctx *fc, const double *param, double *value)
{
    const bf_problem *pb = fc->pb;
    const size_t n = fc->pm->n;
    columns_t c;
    double **col = c.col;
    size_t q;
    size_t b;
    double t[BF__VP_MAX_LIN] = {0.0, 0.0};
    int rc = columns(fc, param, &c);
    if (rc != BF_OK) {
        return rc;
    }
    /* per block (a joint fit's channel, SPEC §9.4; one block otherwise):
     * its scales by NNLS on the shared columns, its curve, its S; the
     * blocks' S summed */
    *value = 0.0;
    for (b = 0; b < fc->blocks; b++) {
        bf_problem sub = *pb;
        double *curve = fc->curve + b * n;
        size_t k;
        sub.data = pb->data + b * n;
        nnls(&sub, col[0], col[1], c.n_l > 1 ? col[2] : NULL, c.hi, t);
        for (k = 0; k < n; k++) { /* the curve at the solved scales */
            double v = col[0][k];
            for (q = 0; q < c.n_l; q++) {
                v += t[q] * col[q + 1][k];
            }
            curve[k] = v;
        }
        for (q = 0; q < c.n_l; q++) {
            fc->block_lin[b * BF_MAX_PARAMS + c.lj[q]] = t[q];
            if (b == 0) {
                fc->lin[c.lj[q]] = t[q];
            }
        }
        *value += bf__objective(&sub, fc->pm->cs->cti, NULL, curve,
                                fc->scratch);
    }
    return isfinite(*value) ? BF_OK : BF_EDOM;
}

int bf__varpro_magnitude(bf__fitctx *fc, const double *param, double *mag,
                         double *value)
{
    const bf_problem *pb = fc->pb;
    columns_t c;
    double *lobe;
    size_t k;
    double t[BF__VP_MAX_LIN] = {0.0, 0.0};
    int rc;
    if (fc->blocks != 1) {
        return BF_EINVAL; /* the lobe's size is a shape parameter */
    }
    rc = columns(fc, param, &c);
    if (rc == BF_OK && c.n_l == BF__VP_MAX_LIN) {
        rc = BF_EINVAL; /* the size would be a third scale */
    }
    if (rc != BF_OK) {
        return rc;
    }
    /* c_0 (the lobe, the only part without a scale) as one more column,
     * its scale the size t^n, unbounded (Cz's bound is checked after) */
    lobe = c.col[0];
    c.hi[c.n_l] = HUGE_VAL;
    nnls(pb, NULL, c.n_l > 0 ? c.col[1] : lobe, c.n_l > 0 ? lobe : NULL, c.hi,
         t);
    for (k = 0; k < fc->pm->n; k++) {
        fc->curve[k] = c.n_l > 0 ? t[0] * c.col[1][k] + t[1] * lobe[k]
                                 : t[0] * lobe[k];
    }
    if (c.n_l > 0) {
        fc->lin[c.lj[0]] = t[0];
        fc->block_lin[c.lj[0]] = t[0];
    }
    *mag = t[c.n_l];
    *value = bf__objective(pb, fc->pm->cs->cti, NULL, fc->curve, fc->scratch);
    return isfinite(*value) ? BF_OK : BF_EDOM;
}

BF__CLONES
void bf__vp_residuals(const bf__fitctx *fc, const double *sw, double *f)
{
    const size_t n = fc->pb->n;
    const double *c = fc->curve;
    const double *d = fc->pb->data;
    size_t b;
    size_t k;
    for (b = 0; b < fc->blocks; b++, c += n, d += n, f += n) {
        if (sw == NULL) {
            for (k = 0; k < n; k++) {
                f[k] = c[k] - d[k];
            }
            continue;
        }
        for (k = 0; k < n; k++) {
            f[k] = sw[k] * (c[k] - d[k]);
        }
    }
}
