/* study_setup.c: the parts of a study's specification every caller makes
 * the same way (the CLI's compare, rank, report, calibrate and Python's
 * compare, rank, fit): the model list under the specular options of
 * SPEC §9.2 (--fresnel, --smith), the models' variants (the exact
 * fit's freed inputs, the user's search ranges) and the check of the rows
 * a study wrote (SPEC §2, §7, §9; doc/methods.md §6). Callers word the
 * messages with their own option names.
 */
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* Appends t to out (room for cap), refusing a model listed twice and, under
 * an objective that max-normalises, a specular model (SPEC §9, §10). */
static int add_model(const bf_model_type *t, bf_objective objective,
                     const bf_model_type **out, size_t cap, size_t *n,
                     bf_error *err)
{
    size_t j;
    if (t->kind == BF_MODEL_SPECULAR && !bf_objective_keeps_scale(objective)) {
        return bf__error_set(err, BF_EDOM, 0,
                             "%s gives absolute BRDF values (SPEC §9)",
                             t->name);
    }
    for (j = 0; j < *n; j++) {
        if (out[j] == t) {
            return bf__error_set(err, BF_EINVAL, 0, "'%s' listed twice",
                                 t->name);
        }
    }
    if (*n >= cap) {
        return bf__error_set(err, BF_EINVAL, 0, "too many");
    }
    out[(*n)++] = t;
    return BF_OK;
}

/* The models' variants under the options of SPEC §9.2 (fresnel, smith),
 * in place: a specular model, or the S part of a composite D+S, becomes its
 * variant; a diffuse model is unaffected. A specular model that cannot
 * take an option given, or options that no model takes, are an error. */
static int apply_options(bf_fresnel_kind fresnel, bf_smith_kind smith,
                         bf_objective objective, const bf_model_type **out,
                         size_t n, bf_error *err)
{
    size_t taken = 0;
    size_t m;
    if ((unsigned)fresnel > BF_FRESNEL_NONE
        || (unsigned)smith > BF_SMITH_SEPARABLE) {
        return bf__error_set(err, BF_EINVAL, 0,
                             "unknown --fresnel or --smith value");
    }
    if (fresnel == BF_FRESNEL_DEFAULT && smith == BF_SMITH_DEFAULT) {
        return BF_OK;
    }
    if (!bf_objective_keeps_scale(objective)) {
        return bf__error_set(err, BF_EDOM, 0,
                             "--fresnel and --smith apply to the specular "
                             "models, which give absolute BRDF values "
                             "(SPEC §9.2, §9.3)");
    }
    for (m = 0; m < n; m++) {
        const bf_model_type *v;
        const char *why;
        if (out[m]->kind != BF_MODEL_SPECULAR) {
            continue; /* a diffuse model: unaffected */
        }
        v = bf_model_specular_variant(out[m], fresnel, smith, &why);
        if (v == NULL) {
            return bf__error_set(err, BF_EDOM, 0, "%s %s", out[m]->name,
                                 why);
        }
        out[m] = v;
        taken++;
    }
    if (taken == 0) {
        return bf__error_set(err, BF_EDOM, 0,
                             "no selected model takes --fresnel or "
                             "--smith: they apply to GGX, BECKMANN, CT "
                             "(--smith: GGX, BECKMANN) and their "
                             "composites D+S (SPEC §9.2)");
    }
    return BF_OK;
}

static int resolve_list(const char *list, bf_model_set defaults,
                        bf_objective objective, const bf_model_type **out,
                        size_t cap, size_t *n, bf_error *err);

int bf_study_models(const char *list, bf_model_set defaults,
                    bf_objective objective, bf_fresnel_kind fresnel,
                    bf_smith_kind smith, const bf_model_type **out,
                    size_t cap, size_t *n, bf_error *err)
{
    int rc;
    bf__error_clear(err, "study");
    if (out == NULL || n == NULL) {
        return bf__error_set(err, BF_EINVAL, 0, "no output");
    }
    *n = 0;
    rc = resolve_list(list, defaults, objective, out, cap, n, err);
    if (rc == BF_OK) {
        rc = apply_options(fresnel, smith, objective, out, *n, err);
    }
    return rc;
}

/* The model t enters "all" as: a diffuse model itself; a specular model
 * (SPEC §9.3) LAMBERT+t (SPEC §9.4), or t when it has its own diffuse term
 * (own_diffuse: AS), so that every model of the comparison explains the
 * whole BRDF. */
static const bf_model_type *complete_form(const bf_model_type *t)
{
    char name[64];
    if (t->kind == BF_MODEL_DIFFUSE || t->own_diffuse) {
        return t;
    }
    snprintf(name, sizeof name, "%s+%s", bf_model_lambert->name, t->name);
    return bf_model_find(name);
}

/* "all" of bf_study_models: every diffuse model of the registry, in order,
 * and under an objective that keeps the scale (SPEC §10) the complete
 * glossy comparison's form of every specular model (complete_form). */
static int resolve_all(bf_objective objective, const bf_model_type **out,
                       size_t cap, size_t *n, bf_error *err)
{
    size_t i;
    for (i = 0; i < bf_model_count(); i++) {
        const bf_model_type *t = bf_model_get(i);
        int rc = BF_OK;
        if (t->kind == BF_MODEL_DIFFUSE
            || bf_objective_keeps_scale(objective)) {
            t = complete_form(t);
            rc = t != NULL ? add_model(t, objective, out, cap, n, err)
                           : bf__error_set(err, BF_ENOTFOUND, 0,
                                           "no composite LAMBERT+%s",
                                           bf_model_get(i)->name);
        }
        if (rc != BF_OK) {
            return rc;
        }
    }
    return BF_OK;
}

/* The model list of bf_study_models, every model as the registry has it. */
static int resolve_list(const char *list, bf_model_set defaults,
                        bf_objective objective, const bf_model_type **out,
                        size_t cap, size_t *n, bf_error *err)
{
    const char *p;
    if (list != NULL && strcmp(list, "all") == 0) {
        return resolve_all(objective, out, cap, n, err);
    }
    p = list != NULL ? list : bf_model_set_names(defaults);
    if (p == NULL || *p == '\0') {
        return bf__error_set(err, BF_EINVAL, 0, "bad list '%s'",
                             p != NULL ? p : "");
    }
    while (*p != '\0') {
        char name[64];
        size_t len = strcspn(p, ",");
        const bf_model_type *t;
        const char *why;
        int rc;
        if (len == 0 || len >= sizeof name) {
            return bf__error_set(err, BF_EINVAL, 0, "bad list '%s'", list);
        }
        memcpy(name, p, len);
        name[len] = '\0';
        t = bf_model_find_why(name, &why);
        if (t == NULL && strchr(name, '+') != NULL) { /* SPEC §9.4 */
            return bf__error_set(err, BF_ENOTFOUND, 0, "'%s': %s", name,
                                 why);
        }
        if (t == NULL) {
            return bf__error_set(err, BF_ENOTFOUND, 0,
                                 "unknown model '%s'", name);
        }
        rc = add_model(t, objective, out, cap, n, err);
        if (rc != BF_OK) {
            return rc;
        }
        p += len;
        if (*p == ',' && *++p == '\0') {
            return bf__error_set(err, BF_EINVAL, 0, "trailing comma");
        }
    }
    return BF_OK;
}

int bf_study_variants(const bf_model_type *const *models, size_t n_models,
                      int exact, unsigned keep, const bf_param_range *ranges,
                      size_t n_ranges, bf_model_variant *variants,
                      const bf_model_type **out, size_t *bad_range,
                      size_t *bad_model)
{
    unsigned char used[BF_STUDY_MAX_RANGES] = {0};
    size_t m;
    size_t r;
    if (n_ranges > BF_STUDY_MAX_RANGES || models == NULL || out == NULL ||
        (n_ranges > 0 && ranges == NULL) ||
        ((exact || n_ranges > 0) && variants == NULL)) {
        return BF_EINVAL;
    }
    for (m = 0; m < n_models; m++) {
        bf_model_variant *v = &variants[m];
        out[m] = models[m];
        if (!exact && n_ranges == 0) {
            continue;
        }
        bf_model_variant_init(v, models[m]);
        if (exact) {
            bf_model_variant_exact(v, keep);
        }
        for (r = 0; r < n_ranges; r++) {
            int rc = bf_model_variant_range(v, ranges[r].name, ranges[r].lo,
                                            ranges[r].hi);
            if (rc == BF_ENOTFOUND) {
                continue;
            }
            used[r] = 1;
            if (rc != BF_OK) {
                if (bad_range != NULL) {
                    *bad_range = r;
                }
                if (bad_model != NULL) {
                    *bad_model = m;
                }
                return rc;
            }
        }
        out[m] = &v->type;
    }
    for (r = 0; r < n_ranges; r++) {
        if (!used[r]) {
            if (bad_range != NULL) {
                *bad_range = r;
            }
            return BF_ENOTFOUND;
        }
    }
    return BF_OK;
}

int bf_study_rows_check(const bf_study_row *rows, size_t n, size_t *bad)
{
    size_t i;
    for (i = 0; rows != NULL && i < n; i++) {
        if (rows[i].status != BF_OK && rows[i].status != BF_ENOTFOUND) {
            if (bad != NULL) {
                *bad = i;
            }
            return rows[i].status;
        }
    }
    return BF_OK;
}
