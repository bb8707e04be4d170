/* abc.c: ABC, the model of Low, Kronander, Ynnerman and Unger (SPEC
 * §9.3), in sr^-1.
 *
 * References:
 *   [1] J. Low, J. Kronander, A. Ynnerman, J. Unger, "BRDF models for
 *       accurate and efficient rendering of glossy surfaces", ACM TOG
 *       31(1), 2012 (the ABC distribution, eq. 9 with the microfacet
 *       lobe of their eq. 3).
 *
 * Equations (microfacet.h has the pieces and the frame):
 *   ABC = F(cos td; ior) A / (1 + B (1 - cos th))^C G_V / (pi ci co)
 *                                                   [1], SPEC §9.3
 *   F: the dielectric reflectance of SPEC §4.1; G_V: the V-cavity G of
 *   SPEC §9.2; 1 - cos th = sin^2 th / (1 + cos th) (no cancellation).
 * A enters linearly. Limits: finite on the closed hemisphere (G_V / (ci
 * co) stays finite at one grazing zenith); 0 at the grazing corner.
 */
#include <math.h>

#include "models/microfacet.h"

/* param = {A, B, C, ior}. */
static double abc_value(const bf__mf_t *m, const double *p)
{
    double one_minus_ch;
    if (bf__mf_corner(m)) {
        return 0.0;
    }
    one_minus_ch = m->s2h / (1.0 + m->ch);
    return bf__mf_dielectric(m, p[3]) * p[0]
           / pow(1.0 + (p[1] * one_minus_ch), p[2])
           * (4.0 / BF__PI) * bf__mf_gv_over(m);
}

/* The kernel: abc_value's operations in its order, so the same bits,
 * from per-configuration factors kept in the workspace -- G_V / (ci co)
 * and 1 - cos th (the geometry's, once), the power for the last (B, C),
 * and F for each of the last ABC_F_SLOTS values of ior (a round robin;
 * one on data too large for ABC_F_CACHE bytes of them): the separable
 * fit's grid takes ior as its fastest axis (a few values, every (B, C)
 * again), its finite differences and a profile's steps change one
 * parameter at a time, so F or the power is mostly reused. */
#define ABC_F_SLOTS 8
#define ABC_F_CACHE (8u << 20)

typedef struct {
    int geo;      /* 1 once corner, omch, gv hold the geometry's */
    int p_used;   /* 1 once pw holds the power at (b, c) */
    double b;
    double c;
    size_t next;  /* the F slot filled next */
    int f_used[ABC_F_SLOTS]; /* 1 once slot s holds F at f_ior[s] */
    double f_ior[ABC_F_SLOTS];
    double v[];   /* corner, omch, gv, pw, then F per slot: n each */
} abc_work;

enum { ABC_CORNER, ABC_OMCH, ABC_GV, ABC_PW, ABC_F };

/* The F slots of a workspace for n configurations. */
static size_t abc_slots(size_t n)
{
    size_t fit = ABC_F_CACHE / (sizeof(double) * (n > 0 ? n : 1));
    return fit < 1 ? 1 : (fit > ABC_F_SLOTS ? ABC_F_SLOTS : fit);
}

static size_t abc_kwork(const bf_kernel *kr, size_t n)
{
    (void)kr;
    return sizeof(abc_work) + (ABC_F + abc_slots(n)) * n * sizeof(double);
}

static int abc_kvalues(const bf__prep *pm, const double *param, void *work,
                       double *out)
{
    abc_work *w = work;
    const double *t = pm->terms;
    size_t n = pm->n;
    size_t slots = abc_slots(n);
    double *corner = w->v + ABC_CORNER * n;
    double *omch = w->v + ABC_OMCH * n;
    double *gv = w->v + ABC_GV * n;
    double *pw = w->v + ABC_PW * n;
    double *f;
    size_t s;
    int new_f;
    int new_p = !w->p_used || w->b != param[1] || w->c != param[2];
    int rc = BF_OK;
    size_t k;
    for (s = 0; s < slots && !(w->f_used[s] && w->f_ior[s] == param[3]);
         s++) {
    }
    new_f = s == slots;
    if (new_f) { /* not held: the round robin's next slot */
        s = w->next;
        w->next = (w->next + 1) % slots;
    }
    f = w->v + (ABC_F + s) * n;
    for (k = 0; k < n && (!w->geo || new_f); k++) {
        bf__mf_t m;
        bf__mf_at(t, n, k, &m);
        if (!w->geo) {
            corner[k] = bf__mf_corner(&m) ? 1.0 : 0.0;
            omch[k] = m.s2h / (1.0 + m.ch);
            gv[k] = corner[k] != 0.0 ? 0.0 : bf__mf_gv_over(&m);
        }
        if (new_f && corner[k] == 0.0) {
            f[k] = bf__mf_dielectric(&m, param[3]);
        }
    }
    for (k = 0; k < n && new_p; k++) {
        pw[k] = corner[k] != 0.0 ? 1.0 : pow(1.0 + (param[1] * omch[k]),
                                             param[2]);
    }
    w->geo = 1;
    w->f_used[s] = 1;
    w->f_ior[s] = param[3];
    w->p_used = 1;
    w->b = param[1];
    w->c = param[2];
    for (k = 0; k < n; k++) {
        out[k] = corner[k] != 0.0
                     ? 0.0
                     : f[k] * param[0] / pw[k] * (4.0 / BF__PI) * gv[k];
        if (isnan(out[k])) {
            rc = BF_EDOM;
        }
    }
    return rc;
}

static int abc_eval(const double *param, size_t count, const bf_geom *geom,
                    double *out, void *work)
{
    (void)work;
    return bf__mf_eval(param, count, geom, out, abc_value);
}

static const bf_kernel abc_kernel = {
    .n_terms = BF__MF_NTERMS,
    .terms = bf__mf_kterms,
    .work_bytes = abc_kwork,
    .values = abc_kvalues,
    .cheap = -1,
    .columns = bf__columns_scaled,
};

static const bf_param param_abc[4] = {
    BF__PARAM_SCALE("A", "scale A"),
    {.name = "B", .label = "sharpness B", .unit = "1", .min = 0.0,
     .max = 1e6, .value = 300.0, .fitted = 1},
    {.name = "C", .label = "fall-off C", .unit = "1", .min = 0.01,
     .max = 10.0, .value = 1.0, .fitted = 1},
    BF__PARAM_INDEX("ior"),
};

static const bf_model_type abc_type = {
    .name = "ABC",
    .title = "Low et al. ABC microfacet model, sr^-1",
    .reference = "Low, Kronander, Ynnerman, Unger 2012; SPEC §9.2, §9.3",
    .p = 4,
    .param = param_abc,
    .eval = abc_eval,
    .kernel = &abc_kernel,
    .style = BF__STYLE_ABC,
    .kind = BF_MODEL_SPECULAR,
    .ndf = "ABC (A / (1 + B (1 - cos theta_h))^C)",
    .masking = BF__MASK_VCAVITY,
    .fresnel_term = "dielectric (ior, SPEC §4.1), part of the model",
};

const bf_model_type *const bf_model_abc = &abc_type;
