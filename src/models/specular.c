/* specular.c: the options of the specular models (SPEC §9.2: --fresnel,
 * --smith) as variant type objects, and their names.
 *
 * References: SPEC §9.2, §9.3 (which option applies to which model).
 *
 * Equations: none here; each model file defines its variants' type
 * objects and their table (bf_model_type.variants).
 */
#include <string.h>

#include "models/microfacet.h"

static const char *const why_diffuse =
    "is not a specular model (SPEC §9.3): --fresnel and --smith apply to "
    "GGX, BECKMANN and CT (--smith to GGX and BECKMANN)";
static const char *const why_no_fresnel =
    "has no Fresnel term (SPEC §9.3): --fresnel applies to GGX, BECKMANN "
    "and CT";
static const char *const why_own_fresnel =
    "has its own Fresnel term, part of the model (SPEC §9.3): --fresnel "
    "applies to GGX, BECKMANN and CT";
static const char *const why_no_smith =
    "has no Smith masking (SPEC §9.2): --smith applies to GGX and BECKMANN";
static const char *const why_unknown = "unknown --fresnel or --smith value";

/* Whether table has an entry with separable Smith masking. */
static int has_smith(const bf_model_type *const *tab)
{
    size_t j;
    for (j = 0; j < BF_SPECULAR_VARIANTS; j++) {
        if ((tab[j] != NULL) && (j % 2 == 1)) {
            return 1;
        }
    }
    return 0;
}

static const bf_model_type *fail(const char **why, const char *reason)
{
    *why = reason;
    return NULL;
}

const bf_model_type *bf_model_specular_variant(const bf_model_type *base,
                                               bf_fresnel_kind f,
                                               bf_smith_kind s,
                                               const char **why)
{
    const bf_model_type *const *tab;
    const char *ignored;
    size_t pos;
    if (why == NULL) {
        why = &ignored;
    }
    *why = NULL;
    if ((base == NULL) || ((unsigned)f > BF_FRESNEL_NONE)
        || ((unsigned)s > BF_SMITH_SEPARABLE)) {
        return fail(why, why_unknown);
    }
    if ((f == BF_FRESNEL_DEFAULT) && (s == BF_SMITH_DEFAULT)) {
        return base;
    }
    if (base->kind != BF_MODEL_SPECULAR) {
        return fail(why, why_diffuse);
    }
    tab = base->variants;
    if ((s != BF_SMITH_DEFAULT) && ((tab == NULL) || !has_smith(tab))) {
        return fail(why, why_no_smith);
    }
    if (tab == NULL) {
        return fail(why, (base->fresnel_term != NULL
                          && strcmp(base->fresnel_term, BF__FRES_ABSENT) == 0)
                             ? why_no_fresnel
                             : why_own_fresnel);
    }
    /* base's own entry: by its eval, so that a copy (bf_model_variant)
     * is found too */
    for (pos = 0; (pos < BF_SPECULAR_VARIANTS)
                  && ((tab[pos] == NULL) || (tab[pos]->eval != base->eval));
         pos++) {
    }
    if (pos == BF_SPECULAR_VARIANTS) {
        return fail(why, why_unknown);
    }
    if (f == BF_FRESNEL_DEFAULT) {
        f = (bf_fresnel_kind)(pos / 2 + 1);
    }
    if (s == BF_SMITH_DEFAULT) {
        s = (bf_smith_kind)(pos % 2 + 1);
    }
    if (tab[BF_VARIANT_INDEX(f, s)] == NULL) {
        return fail(why, why_own_fresnel);
    }
    return tab[BF_VARIANT_INDEX(f, s)];
}

int bf_fresnel_find(const char *name, bf_fresnel_kind *out)
{
    static const char *const names[] = {"schlick", "dielectric", "none"};
    size_t j;
    for (j = 0; (name != NULL) && (j < 3); j++) {
        if (strcmp(name, names[j]) == 0) {
            *out = (bf_fresnel_kind)(BF_FRESNEL_SCHLICK + (int)j);
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}

int bf_smith_find(const char *name, bf_smith_kind *out)
{
    static const char *const names[] = {"height", "separable"};
    size_t j;
    for (j = 0; (name != NULL) && (j < 2); j++) {
        if (strcmp(name, names[j]) == 0) {
            *out = (bf_smith_kind)(BF_SMITH_HEIGHT + (int)j);
            return BF_OK;
        }
    }
    return BF_ENOTFOUND;
}
