/* test_lmq.c: the least-squares solver of the separable fits (lmq.c):
 * superlinear where Gauss-Newton is linear (a large residual at the
 * minimum), quadratic at a zero residual, the ends it reports, and
 * points where the residuals are not defined. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "fit/lmq.h"

typedef struct {
    double lambda;
    size_t evals;
    double undefined_above; /* r not defined at u[0] above this */
} prob_t;

/* Madsen, Nielsen & Tingleff 2004, Example 3.2: r = (x + 1,
 * lambda x² + x − 1). x* = 0 for lambda < 1, where r = (1, −1): the
 * Hessian of F = |r|²/2 is 2 − 2 lambda, Gauss-Newton's JᵀJ is 2, so
 * Gauss-Newton (and Levenberg-Marquardt near x*) converges linearly at
 * the ratio lambda. */
static int madsen(const double *u, double *r, void *arg)
{
    prob_t *p = arg;
    p->evals++;
    if (u[0] > p->undefined_above) {
        return 1;
    }
    r[0] = u[0] + 1.0;
    r[1] = p->lambda * u[0] * u[0] + u[0] - 1.0;
    return 0;
}

/* Rosenbrock's function as least squares: r = (10 (y − x²), 1 − x),
 * minimum 0 at (1, 1). */
static int rosenbrock(const double *u, double *r, void *arg)
{
    prob_t *p = arg;
    p->evals++;
    r[0] = 10.0 * (u[1] - u[0] * u[0]);
    r[1] = 1.0 - u[0];
    return 0;
}

static bf__lmq_opts opts(void)
{
    bf__lmq_opts o;
    memset(&o, 0, sizeof o);
    o.max_iter = 200;
    o.tol = 1e-14;
    return o;
}

Test(lmq, a_large_residual_minimum_is_reached_superlinearly)
{
    bf__lmq *w = bf__lmq_alloc(2, 1);
    bf__lmq_opts o = opts();
    prob_t p = {0.9, 0, INFINITY};
    double u = 3.0;
    double c;
    cr_assert_not_null(w);
    cr_assert_eq(bf__lmq_run(w, &u, &c, madsen, &p, &o), BF__LMQ_CONVERGED);
    /* c = 2 + (1 − lambda) x² + O(x³): x to about 1e-7 at c's rounding */
    cr_assert(fabs(u) < 1e-6, "x %g", u);
    cr_assert(fabs(c - 2.0) < 1e-14, "c %.17g", c);
    /* Gauss-Newton at the ratio 0.9 needs some 130 steps from x = 1 to
     * 1e-6, each of two evaluations (the point, the difference) */
    cr_assert(p.evals < 60, "%zu evaluations", p.evals);
    bf__lmq_free(w);
}

Test(lmq, a_zero_residual_minimum_is_found_exactly)
{
    bf__lmq *w = bf__lmq_alloc(2, 2);
    bf__lmq_opts o = opts();
    prob_t p = {0.0, 0, INFINITY};
    double u[2] = {-1.2, 1.0};
    double c;
    cr_assert_not_null(w);
    cr_assert_eq(bf__lmq_run(w, u, &c, rosenbrock, &p, &o),
                 BF__LMQ_CONVERGED);
    cr_assert(fabs(u[0] - 1.0) < 1e-9 && fabs(u[1] - 1.0) < 1e-9,
              "(%g, %g)", u[0], u[1]);
    cr_assert(c < 1e-20, "c %g", c);
    bf__lmq_free(w);
}

/* r = (e^u − 2, (u − ln 2)/10), not defined above u = 5 (an overflow):
 * from u = −3 Gauss-Newton's first step lands at u = 36. */
static int exp_fit(const double *u, double *r, void *arg)
{
    prob_t *p = arg;
    p->evals++;
    if (u[0] > p->undefined_above) {
        return 1;
    }
    r[0] = exp(u[0]) - 2.0;
    r[1] = 0.1 * (u[0] - log(2.0));
    return 0;
}

/* Steps into where r is not defined are rejected, not taken: the run
 * still ends at the minimum, which is inside. */
Test(lmq, steps_where_the_residuals_are_undefined_are_rejected)
{
    bf__lmq *w = bf__lmq_alloc(2, 1);
    bf__lmq_opts o = opts();
    prob_t p = {0.0, 0, 5.0};
    double u = -3.0;
    double c;
    cr_assert_not_null(w);
    cr_assert_eq(bf__lmq_run(w, &u, &c, exp_fit, &p, &o), BF__LMQ_CONVERGED);
    cr_assert(fabs(u - log(2.0)) < 1e-9, "u %.17g", u);
    bf__lmq_free(w);
}

Test(lmq, an_undefined_start_is_reported)
{
    bf__lmq *w = bf__lmq_alloc(2, 1);
    bf__lmq_opts o = opts();
    prob_t p = {0.5, 0, 0.0};
    double u = 1.0;
    double c;
    cr_assert_not_null(w);
    cr_assert_eq(bf__lmq_run(w, &u, &c, madsen, &p, &o), BF__LMQ_UNDEFINED);
    cr_assert_eq(u, 1.0);
    bf__lmq_free(w);
}

static int above_one(const double *u, double c, void *arg)
{
    (void)c;
    (void)arg;
    return u[0] < 1.0;
}

/* check ends the run at the first accepted iterate it names; the stall
 * at the first step that gains less than its share of c. */
Test(lmq, check_and_stall_end_a_run)
{
    bf__lmq *w = bf__lmq_alloc(2, 1);
    bf__lmq_opts o = opts();
    prob_t p = {0.9, 0, INFINITY};
    double u = 3.0;
    double c;
    cr_assert_not_null(w);
    o.check = above_one;
    cr_assert_eq(bf__lmq_run(w, &u, &c, madsen, &p, &o), BF__LMQ_JOINED);
    cr_assert(u < 1.0 && u > 1e-3, "x %g", u);
    o.check = NULL;
    o.stall = 1e-3;
    u = 3.0;
    cr_assert_eq(bf__lmq_run(w, &u, &c, madsen, &p, &o), BF__LMQ_CONVERGED);
    cr_assert(c > 2.0 && c < 2.0 * (1.0 + 1e-2), "c %.17g", c);
    cr_assert(fabs(u) > 1e-8, "x %g: stopped before the end", u);
    bf__lmq_free(w);
}

Test(lmq, sizes_are_checked)
{
    cr_assert_null(bf__lmq_alloc(2, 0));
    cr_assert_null(bf__lmq_alloc(0, 1));
    cr_assert_null(bf__lmq_alloc(20, 9));
}
