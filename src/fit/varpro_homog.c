/* varpro_homog.c: the grid of a homogeneous lobe in the separable fit
 * (SPEC §9.3, §10; varpro.c has the search, doc/methods.md §2):
 * LAFORTUNE's (t Cxy dxy + t Cz ci co)^n = t^n (Cxy dxy + Cz ci co)^n
 * (bf_param.homog), so a grid point holds Cz at 1, its lobe's size s = t^n
 * is solved exactly beside the other scales (bf__varpro_magnitude), and
 * the point stands for Cz = t = s^(1/n), Cxy times t.
 *
 * [1] E. P. F. Lafortune, S.-C. Foo, K. E. Torrance, D. P. Greenberg,
 *     "Non-linear approximation of reflectance functions", SIGGRAPH 1997
 *     (eq. 5).
 */
#include <math.h>
#include <string.h>

#include "fit/varpro.h"

void bf__vp_grid_init(bf__vp_space *gs, bf__fitctx *fc, unsigned mask)
{
    const bf_model_type *t = fc->pb->type;
    unsigned lin = bf__varpro_lin(fc->pb);
    unsigned unit = 0;
    unsigned scaled = 0;
    size_t degree = t->p;
    size_t u = 0;
    size_t n_lin = 0;
    size_t j;
    for (j = 0; j < t->p; j++) {
        switch (t->param[j].homog) {
        case BF_HOMOG_UNIT:
            unit |= 1u << j;
            u = j;
            break;
        case BF_HOMOG_SCALED:
            scaled |= 1u << j;
            break;
        case BF_HOMOG_DEGREE:
            degree = j;
            break;
        default:
            break;
        }
        n_lin += (lin >> j) & 1u;
    }
    if (unit == 0 || degree == t->p || (mask & (unit | scaled)) !=
                                           (unit | scaled) ||
        fc->blocks != 1 || n_lin >= BF__VP_MAX_LIN) {
        bf__vp_space_init(gs, fc, mask);
        return;
    }
    bf__vp_space_init(gs, fc, mask & ~unit);
    gs->hg = 1;
    gs->hg_unit = u;
    gs->hg_degree = degree;
    gs->hg_scaled = scaled;
    gs->base[u] = 1.0; /* the unit parameter on the grid */
}

double bf__vp_grid_value(const bf__vp_space *gs, const double *x, double *y)
{
    const bf_problem *pb = gs->fc->pb;
    double mag = 0.0;
    double v;
    double s;
    size_t j;
    if (!gs->hg) {
        if (y != NULL) {
            memcpy(y, x, sizeof gs->base);
        }
        return bf__vp_value_at(gs->fc, x);
    }
    if (bf__varpro_magnitude(gs->fc, x, &mag, &v) != BF_OK ||
        !isfinite(v)) {
        return BF__VP_UNDEFINED;
    }
    if (y != NULL) { /* the lobe's size t^n: t on the unit parameter */
        s = pow(mag, 1.0 / x[gs->hg_degree]);
        memcpy(y, x, sizeof gs->base);
        for (j = 0; j < pb->type->p; j++) {
            if (j == gs->hg_unit || ((gs->hg_scaled >> j) & 1u)) {
                double yj = x[j] * s;
                y[j] = yj < pb->lo[j] ? pb->lo[j]
                                      : (yj > pb->hi[j] ? pb->hi[j] : yj);
            }
        }
    }
    return v;
}

int bf__vp_grid_inside(const bf__vp_space *gs, const double *x,
                       const double *y)
{
    const bf_problem *pb = gs->fc->pb;
    size_t j;
    for (j = 0; gs->hg && j < pb->type->p; j++) {
        double tol = 1e-6 * (pb->hi[j] - pb->lo[j]);
        int unit = j == gs->hg_unit;
        if (!unit && !((gs->hg_scaled >> j) & 1u)) {
            continue;
        }
        if (!(y[j] > pb->lo[j] + tol && y[j] < pb->hi[j] - tol) ||
            (!unit && !(x[j] > pb->lo[j] + tol && x[j] < pb->hi[j] - tol))) {
            return 0;
        }
    }
    return gs->hg;
}
