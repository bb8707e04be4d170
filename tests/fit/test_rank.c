/* test_rank.c: model selection in the library (doc/methods.md §5) -- the
 * tie of two criterion values, ranks that ties share, the best model
 * after the tie-break (fewer parameters, then the first listed), and the
 * wins over targets with fits that reduce to a smaller model counted for
 * that model. Synthetic analyses: the values are chosen, not computed. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "support.h"

/* An analysed pair with BIC = AIC = CV = v, k parameters, n = 100. */
static bf_fit_stats stat(double v, size_t k)
{
    bf_fit_stats s;
    memset(&s, 0, sizeof s);
    s.done = 1;
    s.n = 100;
    s.k = k;
    s.aic = v;
    s.bic = v;
    s.cv = v;
    return s;
}

Test(rank, a_tie_is_a_relative_difference_of_the_residual_sums)
{
    /* CV: relative to the larger magnitude */
    cr_assert(bf_criterion_tied(10.0, 10.0 * (1.0 + 0.5 * BF_TIE_REL),
                                BF_CRIT_CV, 100));
    cr_assert(!bf_criterion_tied(10.0, 10.0 * (1.0 + 2.0 * BF_TIE_REL),
                                 BF_CRIT_CV, 100));
    /* BIC = n ln(RSS/n) + const: a relative change e of RSS moves it by
     * n e, whatever its own size (here near 0) */
    cr_assert(bf_criterion_tied(0.0, 100 * 0.5 * BF_TIE_REL, BF_CRIT_BIC,
                                100));
    cr_assert(!bf_criterion_tied(0.0, 100 * 2.0 * BF_TIE_REL, BF_CRIT_BIC,
                                 100));
    cr_assert(!bf_criterion_tied(NAN, NAN, BF_CRIT_CV, 100));
}

Test(rank, ties_share_a_rank_and_fewer_parameters_win)
{
    bf_fit_stats s[4];
    size_t rank[4];
    size_t best;
    s[0] = stat(-500.0, 2);
    s[1] = stat(-500.0 + 1e-9, 1); /* tied with 0 (n e = 1e-9 < 1e-7) */
    s[2] = stat(-400.0, 0);
    s[3] = stat(NAN, 1);           /* not computed */
    bf_criterion_rank(s, 4, BF_CRIT_BIC, rank, &best);
    cr_assert_eq(rank[0], 1);
    cr_assert_eq(rank[1], 1);
    cr_assert_eq(rank[2], 3);
    cr_assert_eq(rank[3], 0);
    cr_assert_eq(best, 1, "the tie goes to the model with fewer parameters");
    s[1].k = 2; /* equal counts: the first listed */
    bf_criterion_rank(s, 4, BF_CRIT_BIC, rank, &best);
    cr_assert_eq(best, 0);
    s[0] = stat(NAN, 1);
    s[1] = stat(NAN, 1);
    s[2] = stat(NAN, 1);
    bf_criterion_rank(s, 4, BF_CRIT_BIC, rank, &best);
    cr_assert_eq(best, SIZE_MAX);
}

Test(rank, wins_count_for_the_model_a_fit_reduces_to)
{
    /* models ON (2 parameters, reduces to LAMBERT), VH-E (1); three
     * targets: ON best on 0 (a true ON fit), ON best on 1 but at sigma = 0
     * (LAMBERT), VH-E best on 2 */
    const bf_model_type *models[2];
    bf_fit_stats s[6];
    bf_study_spec spec;
    size_t rank[6];
    size_t best[3];
    const char *names[4];
    size_t wins[4];
    size_t n = 0;
    models[0] = bf_model_find("ON");
    models[1] = bf_model_find("VH-E");
    cr_assert(models[0] != NULL && models[1] != NULL);
    s[0] = stat(-10.0, 2);
    s[1] = stat(-5.0, 1);
    s[2] = stat(-10.0, 2);
    s[2].flags = BF_STAT_REDUCED;
    s[2].reduces_to = "LAMBERT";
    s[3] = stat(-5.0, 1);
    s[4] = stat(-1.0, 2);
    s[5] = stat(-5.0, 1);
    memset(&spec, 0, sizeof spec);
    spec.models = models;
    spec.n_models = 2;
    spec.n_targets = 3;
    cr_assert_eq(bf_study_rank(&spec, s, BF_CRIT_BIC, rank, best), BF_OK);
    cr_assert_eq(best[0], 0);
    cr_assert_eq(best[1], 0);
    cr_assert_eq(best[2], 1);
    cr_assert_eq(rank[4], 2);
    cr_assert_str_eq(bf_criterion_winner(models, s + 2, 0), "LAMBERT");
    cr_assert_eq(bf_study_wins(&spec, s, BF_CRIT_BIC, names, wins, &n),
                 BF_OK);
    cr_assert_eq(n, 3);
    /* one win each, in the order of the first win */
    cr_assert_str_eq(names[0], "ON");
    cr_assert_str_eq(names[1], "LAMBERT");
    cr_assert_str_eq(names[2], "VH-E");
    cr_assert(wins[0] == 1 && wins[1] == 1 && wins[2] == 1);
    s[4] = stat(-20.0, 2); /* ON now best on target 2 too */
    cr_assert_eq(bf_study_wins(&spec, s, BF_CRIT_BIC, names, wins, &n),
                 BF_OK);
    cr_assert_eq(n, 2);
    cr_assert_str_eq(names[0], "ON");
    cr_assert_eq(wins[0], 2);
    cr_assert_str_eq(names[1], "LAMBERT");
    cr_assert_eq(bf_study_wins(NULL, s, BF_CRIT_BIC, names, wins, &n),
                 BF_EINVAL);
}
