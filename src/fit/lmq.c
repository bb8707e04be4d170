/* lmq.c: Levenberg-Marquardt for a few parameters that turns to a
 * quasi-Newton step where the residuals are large -- Madsen's hybrid
 * (K. Madsen, "A combined Gauss-Newton and quasi-Newton method for
 * non-linear least squares", DTU NI-88-10, 1988; Madsen, Nielsen &
 * Tingleff 2004, §3.5, Algorithm 3.25).
 *
 * Gauss-Newton's model JᵀJ of the Hessian of F = |r|²/2 leaves out
 * Σ r_k ∇²r_k; where the residuals at the minimum are noise and misfit,
 * not small, Levenberg-Marquardt then converges linearly, each step a
 * fixed fraction of the way (bench/RESULTS.md: 44 % of the ten specular
 * models' evaluations). Here B, a BFGS approximation of the whole
 * Hessian, is kept beside JᵀJ from the start (B₀ = JᵀJ) and updated at
 * every accepted step with Madsen's secant y = J₊ᵀJ₊ h + (J₊ − J)ᵀ r₊.
 * Levenberg-Marquardt runs (Nielsen's damping, Moré's scaling D) until
 * two accepted steps in a row end where the gradient is nearly
 * orthogonal to the residual (every column j of J: |J_jᵀr| < 0.02
 * |J_j| |r|, a large-residual neighbourhood of a minimum); then steps
 * B h = −Jᵀr in a trust region |D h| ≤ Δ, back to LM as soon as such a
 * step does not lower the scaled gradient or fails twice.
 *
 * Stops: an accepted step with every |h_j| ≤ tol (|u_j| + tol), or a
 * gradient with max_j |g_j| max(|u_j|, 1) ≤ tol max(F, 1) (GSL's xtol
 * and gtol tests); a predicted decrease below the rounding of F; 15
 * rejected trials in a row (rounding); the stall; check. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "brdffit.h"
#include "fit/lmq.h"

#define MAX_FAILS 15
#define SWITCH_COS 0.02
#define SWITCH_COUNT 2

struct bf__lmq {
    size_t n;
    size_t m;
    double *r;  /* residuals at u */
    double *rt; /* at the trial point */
    double *J;  /* Jacobian at u, column j at J + j n */
    double *Jt; /* at the accepted trial point */
};

bf__lmq *bf__lmq_alloc(size_t n, size_t m)
{
    bf__lmq *w;
    if (m == 0 || m > BF_MAX_PARAMS || n == 0) {
        return NULL;
    }
    w = calloc(1, sizeof *w);
    if (w == NULL) {
        return NULL;
    }
    w->n = n;
    w->m = m;
    w->r = malloc(n * sizeof *w->r);
    w->rt = malloc(n * sizeof *w->rt);
    w->J = malloc(n * m * sizeof *w->J);
    w->Jt = malloc(n * m * sizeof *w->Jt);
    if (w->r == NULL || w->rt == NULL || w->J == NULL || w->Jt == NULL) {
        bf__lmq_free(w);
        return NULL;
    }
    return w;
}

void bf__lmq_free(bf__lmq *w)
{
    if (w != NULL) {
        free(w->r);
        free(w->rt);
        free(w->J);
        free(w->Jt);
        free(w);
    }
}

static double dot(const double *a, const double *b, size_t n)
{
    double s = 0.0;
    size_t k;
    for (k = 0; k < n; k++) {
        s += a[k] * b[k];
    }
    return s;
}

/* The forward-difference Jacobian at u (r its residuals) into J, steps
 * sqrt(ε) max(|u_j|, typ_j) (typ NULL: 1; GSL's sqrt(ε)|u_j| is all
 * rounding where u_j is near 0 and r is not); backward where forward is
 * not defined. 0, or -1 where neither is. */
static int jacobian(bf__lmq *w, double *u, const double *r, double *J,
                    const double *typ, bf__lmq_fn fn, void *arg)
{
    size_t j;
    size_t k;
    for (j = 0; j < w->m; j++) {
        double uj = u[j];
        double t = typ != NULL ? typ[j] : 1.0;
        double h = sqrt(DBL_EPSILON) * (fabs(uj) > t ? fabs(uj) : t);
        double *col = J + j * w->n;
        int bad;
        u[j] = uj + h;
        bad = fn(u, col, arg);
        if (bad) {
            h = -h;
            u[j] = uj + h;
            bad = fn(u, col, arg);
        }
        u[j] = uj;
        if (bad) {
            return -1;
        }
        for (k = 0; k < w->n; k++) {
            col[k] = (col[k] - r[k]) / h;
        }
    }
    return 0;
}

/* A = JᵀJ (m x m, row-major), g = Jᵀr. */
static void normal(const bf__lmq *w, const double *J, const double *r,
                   double *A, double *g)
{
    size_t i;
    size_t j;
    for (i = 0; i < w->m; i++) {
        const double *ci = J + i * w->n;
        g[i] = dot(ci, r, w->n);
        for (j = 0; j <= i; j++) {
            A[i * w->m + j] = dot(ci, J + j * w->n, w->n);
            A[j * w->m + i] = A[i * w->m + j];
        }
    }
}

/* Solves (M + mu diag(d²)) h = −g by Cholesky in the scaled variables
 * d h (M m x m, symmetric). 0, or -1 when not positive definite. */
static int solve(size_t m, const double *M, const double *d, double mu,
                 const double *g, double *h)
{
    double L[BF_MAX_PARAMS * BF_MAX_PARAMS];
    double z[BF_MAX_PARAMS];
    size_t i;
    size_t j;
    size_t k;
    for (i = 0; i < m; i++) {
        for (j = 0; j <= i; j++) {
            double s = M[i * m + j] / (d[i] * d[j]) + (i == j ? mu : 0.0);
            for (k = 0; k < j; k++) {
                s -= L[i * m + k] * L[j * m + k];
            }
            if (i == j) {
                if (!(s > 0.0)) {
                    return -1;
                }
                L[i * m + i] = sqrt(s);
            } else {
                L[i * m + j] = s / L[j * m + j];
            }
        }
    }
    for (i = 0; i < m; i++) { /* L z = −g/d */
        double s = -g[i] / d[i];
        for (k = 0; k < i; k++) {
            s -= L[i * m + k] * z[k];
        }
        z[i] = s / L[i * m + i];
    }
    for (i = m; i-- > 0;) { /* Lᵀ (d h) = z */
        double s = z[i];
        for (k = i + 1; k < m; k++) {
            s -= L[k * m + i] * z[k];
        }
        z[i] = s / L[i * m + i];
    }
    for (i = 0; i < m; i++) {
        h[i] = z[i] / d[i];
    }
    return 0;
}

/* hᵀ M h (M m x m). */
static double quad(size_t m, const double *M, const double *h)
{
    double s = 0.0;
    size_t i;
    size_t j;
    for (i = 0; i < m; i++) {
        for (j = 0; j < m; j++) {
            s += h[i] * M[i * m + j] * h[j];
        }
    }
    return s;
}

/* |D h|. */
static double scaled_norm(size_t m, const double *d, const double *h)
{
    double s = 0.0;
    size_t i;
    for (i = 0; i < m; i++) {
        s += d[i] * h[i] * d[i] * h[i];
    }
    return sqrt(s);
}

/* max_j |g_j| / d_j: the gradient in the scaled variables. */
static double scaled_grad(size_t m, const double *d, const double *g)
{
    double s = 0.0;
    size_t i;
    for (i = 0; i < m; i++) {
        double v = fabs(g[i]) / d[i];
        s = v > s ? v : s;
    }
    return s;
}

/* 1 when every column of J is nearly orthogonal to r (A = JᵀJ, g = Jᵀr,
 * c = |r|²): the large-residual neighbourhood of a minimum. */
static int large_residual(size_t m, const double *A, const double *g,
                          double c)
{
    size_t i;
    for (i = 0; i < m; i++) {
        double nj = sqrt(A[i * m + i] * c);
        if (!(fabs(g[i]) < SWITCH_COS * nj)) {
            return 0;
        }
    }
    return 1;
}

/* BFGS: B += y yᵀ/(hᵀy) − (B h)(B h)ᵀ/(hᵀ B h), when hᵀy > 0. */
static void bfgs(size_t m, double *B, const double *h, const double *y)
{
    double v[BF_MAX_PARAMS];
    double hy = dot(h, y, m);
    double hv;
    size_t i;
    size_t j;
    for (i = 0; i < m; i++) {
        v[i] = dot(B + i * m, h, m);
    }
    hv = dot(h, v, m);
    if (!(hy > 0.0) || !(hv > 0.0)) {
        return;
    }
    for (i = 0; i < m; i++) {
        for (j = 0; j < m; j++) {
            B[i * m + j] += y[i] * y[j] / hy - v[i] * v[j] / hv;
        }
    }
}

/* GSL's xtol and gtol tests after an accepted step h to u (gradient g,
 * cost c): every |h_j| <= tol (|u_j| + tol), or max_j |g_j| max(|u_j|, 1)
 * <= tol max(c / 2, 1). */
static int tolerances_met(size_t m, const double *u, const double *h,
                          const double *g, double c, double tol)
{
    int small = 1;
    double gs = 0.0;
    size_t k;
    for (k = 0; k < m; k++) {
        double au = fabs(u[k]);
        double gk = fabs(g[k]) * (au > 1.0 ? au : 1.0);
        small = small && fabs(h[k]) <= tol * (au + tol);
        gs = gk > gs ? gk : gs;
    }
    return small || gs <= tol * (0.5 * c > 1.0 ? 0.5 * c : 1.0);
}

static void swap(double **a, double **b)
{
    double *t = *a;
    *a = *b;
    *b = t;
}

int bf__lmq_run(bf__lmq *w, double *u, double *c, bf__lmq_fn fn, void *arg,
                const bf__lmq_opts *o)
{
    const size_t m = w->m;
    const size_t n = w->n;
    double A[BF_MAX_PARAMS * BF_MAX_PARAMS];
    double An[BF_MAX_PARAMS * BF_MAX_PARAMS];
    double B[BF_MAX_PARAMS * BF_MAX_PARAMS];
    double g[BF_MAX_PARAMS], gn[BF_MAX_PARAMS], d[BF_MAX_PARAMS];
    double h[BF_MAX_PARAMS], ut[BF_MAX_PARAMS], y[BF_MAX_PARAMS];
    double mu = 1e-3;
    double nu = 2.0;
    double delta = 0.0;
    size_t iter = 0;
    size_t fails = 0;
    int qn = 0;
    int qn_fails = 0;
    int near = 0;
    size_t i;
    if (fn(u, w->r, arg)) {
        return BF__LMQ_UNDEFINED;
    }
    *c = dot(w->r, w->r, n);
    if (!isfinite(*c) || jacobian(w, u, w->r, w->J, o->typ, fn, arg)) {
        return BF__LMQ_UNDEFINED;
    }
    normal(w, w->J, w->r, A, g);
    memcpy(B, A, sizeof B);
    for (i = 0; i < m; i++) {
        d[i] = sqrt(A[i * m + i]);
        if (!(d[i] > 0.0)) {
            d[i] = 1.0;
        }
    }
    while (iter < o->max_iter) {
        double pred;
        double ct;
        double c0;
        double F = 0.5 * *c;
        double rho;
        int ok;
        if (qn && solve(m, B, d, 0.0, g, h) != 0) {
            qn = 0; /* B not positive definite: back to LM */
        }
        if (qn) {
            double s = scaled_norm(m, d, h);
            if (s > delta) {
                for (i = 0; i < m; i++) {
                    h[i] *= delta / s;
                }
            }
            pred = -(dot(h, g, m) + 0.5 * quad(m, B, h));
        } else {
            if (solve(m, A, d, mu, g, h) != 0) {
                return iter == 0 ? BF__LMQ_NOPROG : BF__LMQ_CONVERGED;
            }
            pred = -(dot(h, g, m) + 0.5 * quad(m, A, h));
        }
        if (!(pred > 4.0 * DBL_EPSILON * F)) {
            if (!qn) {
                /* nothing left above F's rounding */
                return iter == 0 ? BF__LMQ_NOPROG : BF__LMQ_CONVERGED;
            }
            qn = 0;
            continue;
        }
        for (i = 0; i < m; i++) {
            ut[i] = u[i] + h[i];
        }
        ok = fn(ut, w->rt, arg) == 0;
        ct = ok ? dot(w->rt, w->rt, n) : INFINITY;
        if (ok && ct < *c) {
            ok = jacobian(w, ut, w->rt, w->Jt, o->typ, fn, arg) == 0;
        } else {
            ok = 0;
        }
        if (!ok) {
            if (++fails >= MAX_FAILS) {
                return iter == 0 ? BF__LMQ_NOPROG : BF__LMQ_CONVERGED;
            }
            if (qn) {
                delta *= 0.5;
                if (++qn_fails >= 2) {
                    qn = 0;
                }
            } else {
                mu *= nu;
                nu *= 2.0;
            }
            continue;
        }
        /* accepted */
        rho = 0.5 * (*c - ct) / pred;
        normal(w, w->Jt, w->rt, An, gn);
        for (i = 0; i < m; i++) { /* y = An h + gn − Jᵀ r₊ */
            y[i] = dot(An + i * m, h, m) + gn[i] -
                   dot(w->J + i * n, w->rt, n);
        }
        bfgs(m, B, h, y);
        if (qn) {
            double sd = scaled_norm(m, d, h);
            if (rho < 0.25) {
                delta *= 0.5;
            } else if (rho > 0.75 && 3.0 * sd > delta) {
                delta = 3.0 * sd;
            }
            if (scaled_grad(m, d, gn) >= scaled_grad(m, d, g)) {
                qn = 0;
                near = 0;
            }
            qn_fails = 0;
        } else {
            double t = 2.0 * rho - 1.0;
            t = 1.0 - t * t * t;
            mu *= t > 1.0 / 3.0 ? t : 1.0 / 3.0;
            nu = 2.0;
            near = large_residual(m, An, gn, ct) ? near + 1 : 0;
            if (near >= SWITCH_COUNT) {
                qn = 1;
                qn_fails = 0;
                delta = scaled_norm(m, d, h);
            }
        }
        for (i = 0; i < m; i++) {
            double dn = sqrt(An[i * m + i]);
            d[i] = dn > d[i] ? dn : d[i];
        }
        memcpy(u, ut, m * sizeof *u);
        memcpy(A, An, sizeof A);
        memcpy(g, gn, sizeof g);
        swap(&w->r, &w->rt);
        swap(&w->J, &w->Jt);
        fails = 0;
        iter++;
        c0 = *c;
        *c = ct;
        if (o->check != NULL && o->check(u, ct, arg)) {
            return BF__LMQ_JOINED;
        }
        if ((o->stall > 0.0 && c0 - ct < o->stall * ct) ||
            tolerances_met(m, u, h, g, ct, o->tol)) {
            return BF__LMQ_CONVERGED;
        }
    }
    return BF__LMQ_MAXITER;
}
