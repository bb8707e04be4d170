/* targets.c: what a study fits -- targets (material x channel), their
 * configuration selections and normalised data, the groups of targets
 * that share configurations (and so model curves), and each model's fixed
 * inputs per target (SPEC §1.4-§1.6, §2, §4.2, §5, §7).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* Study errors name the material's file and line when known. */
static int target_error(bf_error *err, const bf_dataset *ds, size_t m,
                        int code, const char *what, size_t k)
{
    const char *name = bf_dataset_name(ds, m);
    const char *src = bf_dataset_source(ds, m);
    bf__error_clear(err, src != NULL && src[0] != '\0' ? src : "study");
    if (name != NULL && name[0] != '\0') {
        return bf__error_set(err, code, bf_dataset_line(ds, m),
                             "sample %d (%s): %s (K = %zu)",
                             bf_dataset_number(ds, m), name, what, k);
    }
    return bf__error_set(err, code, bf_dataset_line(ds, m),
                         "sample %d: %s (K = %zu)", bf_dataset_number(ds, m),
                         what, k);
}

int bf_study_targets(const bf_dataset *ds, const size_t *materials,
                     size_t n_materials, const char *channel,
                     bf_target **out, size_t *n_out, bf_error *err)
{
    size_t n_mat = materials != NULL ? n_materials : bf_dataset_count(ds);
    int joint = channel != NULL && strcmp(channel, "joint") == 0;
    int each = joint || (channel != NULL && strcmp(channel, "each") == 0);
    size_t cap = 0;
    size_t n = 0;
    size_t i;
    bf_target *t;

    bf__error_clear(err, "study");
    if (out == NULL || n_out == NULL || ds == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no dataset or no output");
    }
    *out = NULL;
    *n_out = 0;
    for (i = 0; i < n_mat; i++) {
        size_t m = materials != NULL ? materials[i] : i;
        if (m >= bf_dataset_count(ds)) {
            return bf__error_set(err, BF_EINVAL, 0,
                                 "material index %zu out of range", m);
        }
        cap += each ? bf_dataset_nchannels(ds, m) : 1;
    }
    t = malloc((cap + 1) * sizeof *t);
    if (t == NULL) {
        return bf__error_set(err, BF_ENOMEM, 0, "out of memory");
    }
    for (i = 0; i < n_mat; i++) {
        size_t m = materials != NULL ? materials[i] : i;
        size_t c;
        if (each) {
            for (c = 0; c < bf_dataset_nchannels(ds, m); c++) {
                t[n].material = m;
                t[n].joint = joint;
                t[n++].channel = c;
            }
            continue;
        }
        c = BF_CHANNEL_MEAN;
        if (channel != NULL &&
            bf_dataset_channel_find(ds, m, channel, &c) != BF_OK) {
            int number = bf_dataset_number(ds, m);
            free(t);
            return bf__error_set(err, BF_ENOTFOUND, 0,
                                 "sample %d (%s) has no channel '%s'",
                                 number, bf_dataset_name(ds, m), channel);
        }
        t[n].material = m;
        t[n].joint = 0;
        t[n++].channel = c;
    }
    *out = t;
    *n_out = n;
    return BF_OK;
}

int bf__study_joint_check(const bf_study_spec *spec, int analysed,
                          bf_objective obj, bf_error *err)
{
    size_t t;
    size_t m;
    size_t j;
    for (t = 0; t < spec->n_targets && !spec->targets[t].joint; t++) {
    }
    if (t == spec->n_targets) {
        return BF_OK;
    }
    bf__error_clear(err, "study");
    if (!analysed || obj != BF_OBJ_NGAN) {
        /* the paper's objectives divide the scales away (SPEC §2);
         * cuberoot and log1p have no least-squares scales to solve */
        return bf__error_set(err, BF_EINVAL, 0,
                             "--channel joint fits one shape to every "
                             "channel and each channel's scales by least "
                             "squares (SPEC §9.4): it needs --fit exact "
                             "--objective ngan%s%s",
                             analysed ? ", not " : "",
                             analysed ? bf_objective_name(obj) : "");
    }
    for (m = 0; m < spec->n_models; m++) {
        const bf_model_type *type = spec->models[m];
        for (j = 0; j < type->p; j++) {
            if (type->param[j].fitted && type->param[j].linear) {
                break;
            }
        }
        if (type->kind != BF_MODEL_SPECULAR || j == type->p) {
            return bf__error_set(err, BF_EINVAL, 0,
                                 "--channel joint: %s has no scale "
                                 "parameter to fit per channel (only the "
                                 "specular models with rho_s, A or Rd and "
                                 "the composites D+S have, SPEC §9.3, "
                                 "§9.4); fit it with --channel each",
                                 type->name);
        }
    }
    return BF_OK;
}

/* 1 when some v[0..n) is positive. */
static int any_positive(size_t n, const double *v)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (v[i] > 0.0) {
            return 1;
        }
    }
    return 0;
}

/* bf_study_target_data, with rho as measured when raw is 1 (SPEC §10). */
static int target_data(const bf_study_spec *spec, size_t t, int raw,
                       size_t *sel, size_t *k, double *data, bf_error *err);

int bf_study_target_data(const bf_study_spec *spec, size_t t, size_t *sel,
                         size_t *k, double *data, bf_error *err)
{
    return target_data(spec, t, 0, sel, k, data, err);
}

int bf_study_fit_data(const bf_study_spec *spec, bf_objective obj, size_t t,
                      size_t *sel, size_t *k, double *data, bf_error *err)
{
    bf_study_spec keep;
    if (spec == NULL || !bf_objective_keeps_scale(obj)) {
        return target_data(spec, t, 0, sel, k, data, err);
    }
    keep = *spec; /* SPEC §10: theta_i, theta_o <= 80 deg, as bf_analyse */
    if (keep.select.max_theta > BF_KEEP_SCALE_THETA) {
        keep.select.max_theta = BF_KEEP_SCALE_THETA;
    }
    return target_data(&keep, t, 1, sel, k, data, err);
}

static int target_data(const bf_study_spec *spec, size_t t, int raw,
                       size_t *sel, size_t *k, double *data, bf_error *err)
{
    const bf_target *tg;
    int rc;
    bf__error_clear(err, "study");
    if (spec == NULL || spec->data == NULL || t >= spec->n_targets ||
        spec->targets == NULL || sel == NULL || k == NULL || data == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "invalid study target");
    }
    tg = &spec->targets[t];
    /* a joint fit's channels share one set of configurations: those
     * valid on every channel, the mean's (SPEC §9.4) */
    rc = bf_dataset_select(spec->data, tg->material,
                           tg->joint ? BF_CHANNEL_MEAN : tg->channel,
                           &spec->select, sel, k, NULL);
    if (rc == BF_ENOTFOUND) {
        return target_error(err, spec->data, tg->material, rc,
                            "an excluded configuration number does not "
                            "exist", bf_dataset_nconf(spec->data,
                                                      tg->material));
    }
    if (rc != BF_OK) {
        return bf__error_set(err, rc, 0, "invalid study target");
    }
    if (*k == 0) {
        return target_error(err, spec->data, tg->material, BF_EDOM,
                            "no configuration is left to fit", 0);
    }
    rc = raw ? bf__dataset_rho(spec->data, tg->material, tg->channel, *k,
                               sel, data)
             : bf_dataset_radiance(spec->data, tg->material, tg->channel, *k,
                                   sel, data);
    if (rc != BF_OK) { /* SPEC §2 */
        return target_error(err, spec->data, tg->material, rc,
                            "the measured radiance has no positive maximum "
                            "over the used configurations",
                            *k);
    }
    if (raw && !any_positive(*k, data)) { /* SPEC §10: every scale 0 */
        char why[160];
        const char *ch = tg->channel != BF_CHANNEL_MEAN
                             ? bf_dataset_channel(spec->data, tg->material,
                                                  tg->channel)
                             : NULL;
        snprintf(why, sizeof why, "%s%s%severy measured value is zero over "
                 "the used configurations (theta_i, theta_o <= 80 deg): "
                 "nothing to fit", ch != NULL ? "channel " : "",
                 ch != NULL ? ch : "", ch != NULL ? ": " : "");
        return target_error(err, spec->data, tg->material, BF_EDOM, why, *k);
    }
    return BF_OK;
}

/* The fixed parameter values of type for target t: defaults, with n from
 * the n file or spec->n_default (SPEC §4.2) and rho, sigma from the ON
 * parameter file (SPEC §5), both looked up by the material's number.
 * Returns BF_ENOTFOUND when a needed input is absent. */
int bf__study_inputs(const bf_study_spec *spec, const bf_model_type *type,
                     size_t t, double *fixed)
{
    int sample = bf_dataset_number(spec->data, spec->targets[t].material);
    size_t j;
    for (j = 0; j < type->p; j++) {
        const bf_param *pj = &type->param[j];
        fixed[j] = pj->value;
        if (pj->fitted) {
            continue;
        }
        if (pj->input == BF_INPUT_INDEX) { /* SPEC §4.2 */
            fixed[j] = spec->n_default;
            if (spec->n_file != NULL &&
                bf_sample_table_get(spec->n_file, sample, 0, &fixed[j]) !=
                    BF_OK) {
                return BF_ENOTFOUND;
            }
        } else if (pj->input == BF_INPUT_ON) { /* SPEC §5 */
            if (spec->on_params == NULL ||
                bf_sample_table_get(spec->on_params, sample, pj->input_col,
                                    &fixed[j]) != BF_OK) {
                return BF_ENOTFOUND;
            }
        }
    }
    return BF_OK;
}

void bf__study_groups_free(bf__groups_t *gs)
{
    size_t i;
    for (i = 0; gs->g != NULL && i < gs->n; i++) {
        free(gs->g[i].sel);
        free(gs->g[i].geom);
        free(gs->g[i].members);
        free(gs->g[i].data);
    }
    free(gs->g);
    gs->g = NULL;
    gs->n = 0;
}

/* 1 when target t's selection (k, sel) equals group g's on the same set. */
static int same_group(const bf__group_t *g, size_t set, size_t k,
                      const size_t *sel)
{
    return g->set == set && g->n_sel == k &&
           memcmp(g->sel, sel, k * sizeof *sel) == 0;
}

/* One pass over the targets: each one's selection and data, computed
 * once into per-target storage, find (or open) its group; then every group
 * gets its members' data. */
int bf__study_groups(const bf_study_spec *spec, bf__groups_t *gs,
                     bf_error *err)
{
    return bf__study_groups_data(spec, 0, gs, err);
}

int bf__study_groups_fit(const bf_study_spec *spec, bf_objective obj,
                         bf__groups_t *gs, bf_error *err)
{
    bf_study_spec keep = *spec;
    int raw = bf_objective_keeps_scale(obj);
    if (raw && keep.select.max_theta > BF_KEEP_SCALE_THETA) {
        keep.select.max_theta = BF_KEEP_SCALE_THETA; /* SPEC §10 */
    }
    return bf__study_groups_data(&keep, raw, gs, err);
}

int bf__study_groups_data(const bf_study_spec *spec, int raw,
                          bf__groups_t *gs, bf_error *err)
{
    size_t nt = spec->n_targets;
    size_t *group_of = malloc((nt + 1) * sizeof *group_of);
    size_t *k_of = malloc((nt + 1) * sizeof *k_of);
    size_t *at = malloc((nt + 1) * sizeof *at);
    size_t *sel = NULL;
    double *data = NULL;
    size_t total = 0;
    size_t t;
    size_t i;
    int rc = BF_OK;

    gs->g = calloc(nt + 1, sizeof *gs->g);
    gs->n = 0;
    if (gs->g == NULL || group_of == NULL || k_of == NULL || at == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto fail;
    }
    for (t = 0; t < nt; t++) { /* where each target's values go */
        at[t] = total;
        total += bf_dataset_nconf(spec->data, spec->targets[t].material);
    }
    sel = malloc((total + 1) * sizeof *sel);
    data = malloc((total + 1) * sizeof *data);
    if (sel == NULL || data == NULL) {
        rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
        goto fail;
    }
    for (t = 0; t < nt; t++) {
        size_t m = spec->targets[t].material;
        size_t set = bf_dataset_set(spec->data, m);
        size_t *ts = sel + at[t];
        bf__group_t *g = NULL;
        rc = target_data(spec, t, raw, ts, &k_of[t], data + at[t], err);
        if (rc != BF_OK) {
            goto fail;
        }
        for (i = 0; i < gs->n && g == NULL; i++) {
            if (same_group(&gs->g[i], set, k_of[t], ts)) {
                g = &gs->g[i];
            }
        }
        if (g == NULL) { /* a new group: its configurations, once */
            const bf_geom *geom = bf_dataset_geom(spec->data, m);
            size_t k = k_of[t];
            g = &gs->g[gs->n++];
            g->set = set;
            g->n_sel = k;
            g->sel = malloc(k * sizeof *g->sel);
            g->geom = malloc(k * sizeof *g->geom);
            if (g->sel == NULL || g->geom == NULL) {
                rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
                goto fail;
            }
            memcpy(g->sel, ts, k * sizeof *ts);
            for (i = 0; i < k; i++) {
                g->geom[i] = geom[ts[i]];
            }
        }
        group_of[t] = (size_t)(g - gs->g);
        g->n_members++;
    }
    for (i = 0; i < gs->n; i++) {
        bf__group_t *g = &gs->g[i];
        g->members = malloc(g->n_members * sizeof *g->members);
        g->data = malloc(g->n_members * g->n_sel * sizeof *g->data);
        if (g->members == NULL || g->data == NULL) {
            rc = bf__error_set(err, BF_ENOMEM, 0, "out of memory");
            goto fail;
        }
        g->n_members = 0;
    }
    for (t = 0; t < nt; t++) {
        bf__group_t *g = &gs->g[group_of[t]];
        memcpy(g->data + g->n_members * g->n_sel, data + at[t],
               g->n_sel * sizeof *data);
        g->members[g->n_members++] = t;
    }
    free(group_of);
    free(k_of);
    free(at);
    free(sel);
    free(data);
    return BF_OK;
fail:
    free(group_of);
    free(k_of);
    free(at);
    free(sel);
    free(data);
    bf__study_groups_free(gs);
    return rc;
}
