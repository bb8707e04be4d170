/* composite.c: the composites D+S of SPEC §9.4 -- a diffuse model D and a
 * specular model S of the registry -- for every pair of its two lists
 * (models/registry.h), so a new model's composites come with its registry
 * line; and for every variant of S (SPEC §9.2: --fresnel, --smith) the
 * composite of D and that variant, the composite's own variants
 * (bf_model_specular_variant): LAMBERT+GGX under --fresnel dielectric has
 * the parameters rho_d, rho_s, alpha, n.
 *
 * References:
 *   [1] SPEC §9.4; A. Ngan, F. Durand, W. Matusik, "Experimental analysis
 *       of BRDF models", EGSR 2005 (Lambert + one lobe).
 *
 * Equations (v_D a diffuse model's value: radiance up to scale, SPEC §2,
 * so v_D / cos ti is its BRDF up to scale):
 *   value = rho_d d(i, o) + S(i, o)                             SPEC §9.4
 *   d(i, o) = v_D(i, o) / (pi cos ti v_D(n, n))   (d(n, n) = 1/pi;
 *                                                  LAMBERT: d = 1/pi)
 *   parameters: rho_d (linear), then D's, then S's.
 * At grazing incidence (cos ti = 0) d is its limit, v_D / cos ti taken at
 * theta_i = pi/2 - 1e-7 (relative error ~1e-7 for a smooth D; the
 * objectives of SPEC §10 leave those configurations out).
 */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fit/engine.h"
#include "models/registry.h"

BF_REGISTRY(BF_REGISTRY_DECLARE)

/* Configurations of D evaluated at a time (the fixed workspace). */
#define CHUNK 64
#define GRAZING_EPS 1e-7
#define NAME_MAX_LEN 48

/* Workspace: CHUNK values and geometries of D, then D's and S's own. */
static size_t chunk_bytes(void)
{
    return bf__line_bytes(CHUNK * (sizeof(double) + sizeof(bf_geom)));
}

static int composite_eval(const bf_model_type *d, const bf_model_type *s,
                          const double *param, size_t n, const bf_geom *geom,
                          double *out, void *work)
{
    static const bf_geom normal = {0.0, BF__PI, 0.0, 0.0};
    double *dv = work;
    bf_geom *dg = (bf_geom *)(dv + CHUNK);
    void *dwork = d->work_size > 0 ? (char *)work + chunk_bytes() : NULL;
    void *swork = s->work_size > 0 ? (char *)work + chunk_bytes() : NULL;
    const double *pd = param + 1;
    const double *ps = param + 1 + d->p;
    double d0;
    double scale;
    size_t k;
    int rc;
    int rs;
    rc = d->eval(pd, 1, &normal, &d0, dwork);
    if ((rc != BF_OK) || !(d0 > 0.0) || !isfinite(d0)) {
        for (k = 0; k < n; k++) {
            out[k] = NAN;
        }
        return BF_EDOM;
    }
    scale = param[0] / (BF__PI * d0); /* SPEC §9.4: d(n, n) = 1/pi */
    rs = s->eval(ps, n, geom, out, swork);
    for (k = 0; k < n; k += CHUNK) {
        size_t m = (n - k) < CHUNK ? (n - k) : CHUNK;
        size_t q;
        memcpy(dg, geom + k, m * sizeof *dg);
        for (q = 0; q < m; q++) {
            if (dg[q].theta_i >= BF__PI_2 - GRAZING_EPS) {
                dg[q].theta_i = BF__PI_2 - GRAZING_EPS; /* the limit */
            }
        }
        if (d->eval(pd, m, dg, dv, dwork) != BF_OK) {
            rc = BF_EDOM;
        }
        for (q = 0; q < m; q++) {
            double si;
            double ci;
            bf__zenith_sincos(dg[q].theta_i, &si, &ci);
            out[k + q] += scale * dv[q] / ci;
        }
    }
    return (rc == BF_OK) && (rs == BF_OK) ? BF_OK : BF_EDOM;
}

/* S's variant j (bf_model_type.variants; S itself for a model without
 * options). */
static const bf_model_type *variant_of(const bf_model_type *s, size_t j)
{
    return (s->variants != NULL) && (s->variants[j] != NULL) ? s->variants[j]
                                                             : s;
}

/* One eval function per pair and variant of S (the eval has no context,
 * bf_eval_fn); those of S's absent variants are never used. */
#define VARIANT_EVAL(d, s, j)                                               \
    static int eval_##d##_##s##_##j(const double *param, size_t n,         \
                                    const bf_geom *geom, double *out,      \
                                    void *work)                            \
    {                                                                      \
        return composite_eval(d, variant_of(s, j), param, n, geom, out,    \
                              work);                                       \
    }
#define PAIR_EVAL(d, s)                                                     \
    VARIANT_EVAL(d, s, 0) VARIANT_EVAL(d, s, 1) VARIANT_EVAL(d, s, 2)      \
    VARIANT_EVAL(d, s, 3) VARIANT_EVAL(d, s, 4) VARIANT_EVAL(d, s, 5)
#define ROW_EVAL(unused, d) BF_REGISTRY_SPECULAR(PAIR_EVAL, d)
BF_REGISTRY_DIFFUSE(ROW_EVAL, 0)

/* ==== the engine's kernel ================================================ */

/* A composite's kernel: its parts' kernels on the same configurations
 * (their terms one after the other, then D's terms at the normal
 * configuration), so the geometry is taken once per configuration set. */
typedef struct {
    bf_kernel k; /* first: the engine's view */
    const bf_model_type *d;
    const bf_model_type *s;
} comp_kernel;

static const comp_kernel *comp_of(const bf_kernel *kr)
{
    return (const comp_kernel *)(const void *)kr;
}

static size_t terms_len(const bf_kernel *kr, size_t n)
{
    return kr->n_terms * n + kr->n_extra;
}

/* The normal configuration as a one-configuration set. */
static void normal_set(bf__cset *cs, bf__trig_t *trig, double *cti)
{
    static const bf_geom normal = {0.0, BF__PI, 0.0, 0.0};
    bf__geom_trig(&normal, trig);
    *cti = trig->ci;
    cs->n = 1;
    cs->geom = &normal;
    cs->trig = trig;
    cs->cti = cti;
}

/* The part which (0 D, 1 S, 2 D at the normal configuration) of pm as a
 * prepared model of its own: the composite's terms are D's on the n
 * configurations, S's on them, then D's on the normal configuration
 * (ncs, trig, cti: its one-configuration set, for which 2). */
static void part_prep(const bf__prep *pm, int which, bf__prep *out,
                      bf__cset *ncs, bf__trig_t *trig, double *cti)
{
    const comp_kernel *ck = comp_of(pm->kr);
    const bf_model_type *t = which == 1 ? ck->s : ck->d;
    memset(out, 0, sizeof *out);
    out->type = t;
    out->kr = t->kernel;
    out->cs = pm->cs;
    out->n = pm->n;
    out->geom = pm->geom;
    out->terms = pm->terms;
    if (which == 1) {
        out->terms = pm->terms + terms_len(ck->d->kernel, pm->n);
    } else if (which == 2) { /* D at the normal configuration */
        normal_set(ncs, trig, cti);
        out->cs = ncs;
        out->n = 1;
        out->geom = ncs->geom;
        out->terms = pm->terms + terms_len(ck->d->kernel, pm->n)
                     + terms_len(ck->s->kernel, pm->n);
    }
}

static void comp_terms(const bf_kernel *kr, const bf__cset *cs,
                       double *terms)
{
    const comp_kernel *ck = comp_of(kr);
    bf__cset ncs;
    bf__trig_t trig;
    double cti;
    if (ck->d->kernel->terms != NULL) {
        ck->d->kernel->terms(ck->d->kernel, cs, terms);
    }
    if (ck->s->kernel->terms != NULL) {
        ck->s->kernel->terms(ck->s->kernel, cs,
                             terms + terms_len(ck->d->kernel, cs->n));
    }
    normal_set(&ncs, &trig, &cti);
    if (ck->d->kernel->terms != NULL) {
        ck->d->kernel->terms(ck->d->kernel, &ncs,
                             terms + terms_len(ck->d->kernel, cs->n)
                                 + terms_len(ck->s->kernel, cs->n));
    }
}


/* D's term kept between evaluations, at the head of the kernel's
 * workspace (zeroed when allocated, bound to one configuration set): at
 * D's parameters dp, D's values dv on the configurations (n doubles
 * after this header), the cos ti each is divided by, ce (n more; at
 * grazing the limit's, below), and d0 = v_D(n, n). A fit changes S's
 * parameters at nearly every evaluation and D's (LAMBERT has none)
 * seldom. */
typedef struct {
    int held; /* 1 once dv, ce, d0 hold D's at dp */
    double d0;
    double dp[BF_MAX_PARAMS];
} diff_memo;

static size_t part_work(const bf_kernel *kr, size_t n)
{
    return kr->work_bytes != NULL ? bf__line_bytes(kr->work_bytes(kr, n))
                                   : 0;
}

/* The memo, dv and ce: the head of the workspace. */
static size_t head_bytes(size_t n)
{
    return bf__line_bytes(sizeof(diff_memo)) +
           2 * bf__line_bytes(n * sizeof(double));
}

static size_t comp_work_bytes(const bf_kernel *kr, size_t n)
{
    const comp_kernel *ck = comp_of(kr);
    return head_bytes(n) + part_work(ck->d->kernel, n)
           + part_work(ck->s->kernel, n) + part_work(ck->d->kernel, 1);
}

/* The workspace of comp_values and comp_columns: the memo with dv and ce
 * (head_bytes), then D's, S's and the normal configuration's D's, apart
 * (a part may keep a cache of its configurations' terms in its
 * workspace: FC's Fresnel factor). */
static double *dv_of(void *work)
{
    return (double *)((char *)work + bf__line_bytes(sizeof(diff_memo)));
}

static double *ce_of(const bf__prep *pm, void *work)
{
    return (double *)((char *)dv_of(work)
                      + bf__line_bytes(pm->n * sizeof(double)));
}

static char *d_work(const bf__prep *pm, void *work)
{
    return (char *)work + head_bytes(pm->n);
}

static char *s_work(const bf__prep *pm, void *work)
{
    return d_work(pm, work) + part_work(comp_of(pm->kr)->d->kernel, pm->n);
}

/* D's values, divisors and d0 at param (the composite's) into the memo
 * from D's kernel; held when all are defined. BF_OK, or BF_EDOM where
 * D(n, n) is not positive (d0 NaN, nothing else set) or a value is
 * undefined. */
static int diffuse_memo(const bf__prep *pm, const double *param, void *work)
{
    const comp_kernel *ck = comp_of(pm->kr);
    const bf_model_type *d = ck->d;
    diff_memo *mo = work;
    double *dv = dv_of(work);
    double *ce = ce_of(pm, work);
    char *nw = s_work(pm, work) + part_work(ck->s->kernel, pm->n);
    bf__prep pd;
    bf__prep pn;
    bf__cset ncs;
    bf__trig_t trig;
    double cti;
    double d0;
    size_t k;
    int rc;
    mo->held = 0;
    mo->d0 = NAN;
    part_prep(pm, 2, &pn, &ncs, &trig, &cti);
    rc = d->kernel->values(&pn, param + 1, nw, &d0);
    if ((rc != BF_OK) || !(d0 > 0.0) || !isfinite(d0)) {
        return BF_EDOM;
    }
    mo->d0 = d0;
    part_prep(pm, 0, &pd, NULL, NULL, NULL);
    rc = d->kernel->values(&pd, param + 1, d_work(pm, work), dv);
    for (k = 0; k < pm->n; k++) {
        double ci = pm->cs->cti[k];
        if (ci == 0.0) { /* grazing: the limit, as the reference path */
            bf_geom g = pm->geom[k];
            double v;
            double si;
            g.theta_i = BF__PI_2 - GRAZING_EPS;
            bf__zenith_sincos(g.theta_i, &si, &ci);
            if (d->eval(param + 1, 1, &g, &v, NULL) != BF_OK) {
                rc = BF_EDOM;
            }
            dv[k] = v;
        }
        ce[k] = ci;
    }
    if (rc == BF_OK) {
        memcpy(mo->dp, param + 1, d->p * sizeof *param);
        mo->held = 1;
    }
    return rc == BF_OK ? BF_OK : BF_EDOM;
}

/* Adds D's term rho d(i, o) of SPEC §9.4 at param (the composite's) to
 * out, D's part from the memo (diffuse_memo where it does not hold D's
 * parameters); NaN everywhere and BF_EDOM where D(n, n) is not
 * positive. */
BF__CLONES
static int add_diffuse(const bf__prep *pm, const double *param, double rho,
                       void *work, double *out)
{
    const bf_model_type *d = comp_of(pm->kr)->d;
    const diff_memo *mo = work;
    const double *dv = dv_of(work);
    const double *ce = ce_of(pm, work);
    double scale;
    size_t k;
    int rc = BF_OK;
    if (!mo->held || memcmp(mo->dp, param + 1, d->p * sizeof *param) != 0) {
        rc = diffuse_memo(pm, param, work);
        if (rc != BF_OK && !(mo->d0 > 0.0)) {
            for (k = 0; k < pm->n; k++) {
                out[k] = NAN;
            }
            return BF_EDOM;
        }
    }
    scale = rho / (BF__PI * mo->d0); /* SPEC §9.4: d(n, n) = 1/pi */
    for (k = 0; k < pm->n; k++) {
        out[k] += scale * dv[k] / ce[k];
    }
    return rc;
}

/* Values of the composite from its parts' kernels (the reference path's
 * formula, SPEC §9.4). */
static int comp_values(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    const comp_kernel *ck = comp_of(pm->kr);
    bf__prep ps;
    int rc;
    part_prep(pm, 1, &ps, NULL, NULL, NULL);
    rc = ck->s->kernel->values(&ps, param + 1 + ck->d->p, s_work(pm, work),
                               out);
    if (add_diffuse(pm, param, param[0], work, out) != BF_OK) {
        rc = BF_EDOM;
    }
    return rc == BF_OK ? BF_OK : BF_EDOM;
}

/* The separable fit's columns (bf_kernel.columns): rho_d's is D's term at
 * rho_d = 1 alone, S's from S's own columns, so each part is evaluated
 * once (not the whole composite n_lin + 1 times). A fixed rho_d adds D's
 * term to c0. */
static int comp_columns(const bf__prep *pm, const double *param, unsigned lin,
                        void *work, double *c0, double *const *col)
{
    const comp_kernel *ck = comp_of(pm->kr);
    const bf_kernel *skr = ck->s->kernel;
    const size_t off = 1 + ck->d->p;
    bf__prep ps;
    int rc;
    if (((lin >> 1) & ((1u << ck->d->p) - 1u)) != 0) {
        return BF_EINVAL; /* D's own parameters are not scales */
    }
    part_prep(pm, 1, &ps, NULL, NULL, NULL);
    rc = (skr->columns != NULL ? skr->columns : bf__columns_values)(
        &ps, param + off, lin >> off, s_work(pm, work), c0,
        col + (lin & 1u));
    if (rc != BF_OK) {
        return BF_EDOM;
    }
    if (lin & 1u) {
        memset(col[0], 0, pm->n * sizeof *col[0]);
        return add_diffuse(pm, param, 1.0, work, col[0]);
    }
    return add_diffuse(pm, param, param[0], work, c0);
}

/* 1 when a part's kernel can serve inside the composite's: it has terms
 * and values, no tables of its own (prepare) and no eval workspace (the
 * grazing fallback calls its eval without one). */
static int kernel_usable(const bf_model_type *t)
{
    const bf_kernel *kr = t->kernel;
    return (kr != NULL) && (kr->values != NULL) && (kr->prepare == NULL)
           && (t->work_size == 0)
           && ((kr->terms != NULL) || (kr->n_terms + kr->n_extra == 0));
}

typedef struct {
    const bf_model_type *const *d;
    const bf_model_type *const *s;
    bf_eval_fn eval[BF_SPECULAR_VARIANTS];
} pair_t;

#define PAIR_ENTRY(d, s)                                                    \
    {&d, &s, {eval_##d##_##s##_0, eval_##d##_##s##_1, eval_##d##_##s##_2,  \
              eval_##d##_##s##_3, eval_##d##_##s##_4, eval_##d##_##s##_5}},
#define ROW_ENTRY(unused, d) BF_REGISTRY_SPECULAR(PAIR_ENTRY, d)
static const pair_t pairs[] = {BF_REGISTRY_DIFFUSE(ROW_ENTRY, 0)};
#define N_PAIRS (sizeof pairs / sizeof pairs[0])

_Static_assert(BF_SPECULAR_VARIANTS == 6, "PAIR_EVAL makes six variants");

/* The type objects, made once (their parts' fields are not constant
 * expressions): for each pair, one per variant of S (SPEC §9.2: --fresnel,
 * --smith), at S's index in its table (BF_VARIANT_INDEX; a model without
 * options at 0); name NULL where S has no such variant. */
static bf_model_type types[N_PAIRS][BF_SPECULAR_VARIANTS];
static bf_param params[N_PAIRS][BF_SPECULAR_VARIANTS][BF_MAX_PARAMS];
static const bf_model_type *tables[N_PAIRS][BF_SPECULAR_VARIANTS];
static char names[N_PAIRS][NAME_MAX_LEN];
static char titles[N_PAIRS][2 * NAME_MAX_LEN];
static comp_kernel kernels[N_PAIRS][BF_SPECULAR_VARIANTS];
static pthread_once_t once = PTHREAD_ONCE_INIT;

static const bf_param rho_d_param = {
    .name = "rho_d", .label = "diffuse albedo rho_d", .unit = "1",
    .min = 0.0, .max = 1e6, .value = 0.5, .fitted = 1, .linear = 1};

/* The composite of D and S (pair i, variant j) into t. */
static void make_type(size_t i, size_t j, const bf_model_type *d,
                      const bf_model_type *s)
{
    bf_model_type *t = &types[i][j];
    bf_param *pp = params[i][j];
    pp[0] = rho_d_param;
    if (d->p > 0) { /* LAMBERT has no parameters: param NULL */
        memcpy(&pp[1], d->param, d->p * sizeof *d->param);
    }
    if (s->p > 0) {
        memcpy(&pp[1 + d->p], s->param, s->p * sizeof *s->param);
    }
    t->name = names[i];
    t->title = titles[i];
    t->reference = "SPEC §9.4";
    t->p = 1 + d->p + s->p;
    t->param = pp;
    t->eval = pairs[i].eval[j];
    t->work_size = chunk_bytes()
                   + (d->work_size > s->work_size ? d->work_size
                                                  : s->work_size);
    t->style = s->style;
    if (kernel_usable(d) && kernel_usable(s)) {
        comp_kernel *ck = &kernels[i][j];
        ck->d = d;
        ck->s = s;
        ck->k.n_terms = d->kernel->n_terms + s->kernel->n_terms;
        ck->k.n_extra = d->kernel->n_extra + s->kernel->n_extra
                        + terms_len(d->kernel, 1);
        ck->k.terms = comp_terms;
        ck->k.work_bytes = comp_work_bytes;
        ck->k.values = comp_values;
        ck->k.columns = comp_columns;
        ck->k.cheap = -1;
        t->kernel = &ck->k;
    }
    t->kind = BF_MODEL_SPECULAR;
    t->ndf = s->ndf;
    t->masking = s->masking;
    t->fresnel_term = s->fresnel_term;
    /* the composite's options are S's (bf_model_specular_variant) */
    t->variants = s->variants != NULL ? tables[i] : NULL;
    tables[i][j] = t;
}

static void make_types(void)
{
    size_t i;
    size_t j;
    for (i = 0; i < N_PAIRS; i++) {
        const bf_model_type *d = *pairs[i].d;
        const bf_model_type *s = *pairs[i].s;
        snprintf(names[i], sizeof names[i], "%s+%s", d->name, s->name);
        snprintf(titles[i], sizeof titles[i], "%s diffuse + %s specular",
                 d->name, s->name);
        for (j = 0; j < BF_SPECULAR_VARIANTS; j++) {
            const bf_model_type *sj = s->variants != NULL ? s->variants[j]
                                      : j == 0            ? s
                                                          : NULL;
            if ((sj != NULL) && (1 + d->p + sj->p <= BF_MAX_PARAMS)) {
                make_type(i, j, d, sj); /* else name NULL: too many */
            }
        }
    }
}

/* The index of S's registry type in its table of variants (0 for a model
 * without options). */
static size_t registry_variant(const bf_model_type *s)
{
    size_t j;
    for (j = 0; (s->variants != NULL) && (j < BF_SPECULAR_VARIANTS); j++) {
        if (s->variants[j] == s) {
            return j;
        }
    }
    return 0;
}

/* The registry model named by the len bytes at name, or NULL. */
static const bf_model_type *part(const char *name, size_t len)
{
    size_t i;
    for (i = 0; i < bf_model_count(); i++) {
        if (bf__name_equal(bf_model_get(i)->name, name, len)) {
            return bf_model_get(i);
        }
    }
    return NULL;
}

const bf_model_type *bf__composite_find(const char *name, const char **why)
{
    const char *plus = strchr(name, '+');
    const bf_model_type *d;
    const bf_model_type *s;
    size_t i;
    if ((plus == NULL) || (strchr(plus + 1, '+') != NULL)) {
        *why = "a composite is D+S: one diffuse and one specular model "
               "(SPEC §9.4)";
        return NULL;
    }
    d = part(name, (size_t)(plus - name));
    s = part(plus + 1, SIZE_MAX);
    if ((d == NULL) || (s == NULL)) {
        *why = "unknown model in the composite D+S (see 'brdffit models')";
        return NULL;
    }
    if ((d->kind == BF_MODEL_SPECULAR) && (s->kind != BF_MODEL_SPECULAR)) {
        *why = "a composite is D+S, the diffuse model first (SPEC §9.4)";
        return NULL;
    }
    if (d->kind == BF_MODEL_SPECULAR) {
        *why = "a composite D+S has one specular part, not two (SPEC §9.4)";
        return NULL;
    }
    if (s->kind != BF_MODEL_SPECULAR) {
        *why = "a composite D+S needs a specular model of SPEC §9.3 after "
               "the '+', not a second diffuse one";
        return NULL;
    }
    pthread_once(&once, make_types);
    for (i = 0; i < N_PAIRS; i++) {
        if ((*pairs[i].d == d) && (*pairs[i].s == s)) {
            const bf_model_type *t = &types[i][registry_variant(s)];
            if (t->name == NULL) {
                break;
            }
            *why = NULL;
            return t;
        }
    }
    *why = "the composite has more parameters than BF_MAX_PARAMS";
    return NULL;
}

const bf_model_type *bf_model_specular_part(const bf_model_type *type,
                                            size_t *first)
{
    size_t i;
    size_t ignored;
    if (first == NULL) {
        first = &ignored;
    }
    *first = 0;
    if ((type == NULL) || (type->kind != BF_MODEL_SPECULAR)) {
        return NULL;
    }
    for (i = 0; i < N_PAIRS; i++) {
        size_t j;
        for (j = 0; j < BF_SPECULAR_VARIANTS; j++) {
            /* a composite, or a copy of one (bf_model_variant): by its
             * eval */
            if ((types[i][j].name != NULL)
                && (type->eval == types[i][j].eval)) {
                *first = 1 + (*pairs[i].d)->p;
                return variant_of(*pairs[i].s, j);
            }
        }
    }
    return type;
}
