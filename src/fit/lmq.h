/* lmq.h: nonlinear least squares for a few parameters --
 * Levenberg-Marquardt that turns to a quasi-Newton step where the
 * residuals are large (Madsen 1988; Madsen, Nielsen & Tingleff,
 * "Methods for non-linear least squares problems", 2nd ed., IMM DTU
 * 2004, §3.5), finite-difference Jacobians. Internal to src/fit, never
 * installed. */
#ifndef BF_FIT_LMQ_H
#define BF_FIT_LMQ_H

#include <stddef.h>

/* The residuals at u (m values) into r (n values): 0, or nonzero where
 * the function is not defined there. */
typedef int (*bf__lmq_fn)(const double *u, double *r, void *arg);
/* After every accepted step, the iterate u and its cost c = |r|²: 1 ends
 * the run (BF__LMQ_JOINED). */
typedef int (*bf__lmq_check)(const double *u, double c, void *arg);

typedef struct bf__lmq bf__lmq;

typedef struct {
    size_t max_iter; /* accepted steps */
    double tol;      /* step and gradient tolerances (GSL's xtol, gtol) */
    double stall;    /* > 0: a step lowering c by less than stall c ends */
    bf__lmq_check check; /* NULL: none */
    /* m typical magnitudes: the finite differences' steps are sqrt(ε)
     * max(|u_j|, typ_j); NULL: 1 */
    const double *typ;
} bf__lmq_opts;

enum {
    BF__LMQ_CONVERGED = 0, /* a tolerance, the stall, or rounding */
    BF__LMQ_JOINED,        /* check said so */
    BF__LMQ_MAXITER,
    BF__LMQ_NOPROG,        /* no step from the start lowers c */
    BF__LMQ_UNDEFINED      /* the function or its Jacobian at the start */
};

/* A workspace for n residuals and m <= BF_MAX_PARAMS parameters; NULL
 * when out of memory. */
bf__lmq *bf__lmq_alloc(size_t n, size_t m);
void bf__lmq_free(bf__lmq *w);

/* Minimises |r(u)|² from u (replaced by the last accepted iterate);
 * *c its cost. One of BF__LMQ_*. */
int bf__lmq_run(bf__lmq *w, double *u, double *c, bf__lmq_fn fn, void *arg,
                const bf__lmq_opts *o);

#endif
