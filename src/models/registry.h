/* registry.h: the registry's two lists, one line per model (SPEC §3-6 the
 * diffuse models, SPEC §9.3 the specular ones): registry.c makes the
 * table of bf_model_get from them, composite.c the composites D+S of SPEC
 * §9.4 of every pair. Private.
 *
 * Each list takes a macro X and an argument a and expands to X(a, v) for
 * each model's pointer variable v (`const bf_model_type *const
 * bf_model_x = &x_type;` in the model's file). Order is part of the API
 * (bf_model_get): the paper's six Beckmann variants, then ON, LFTG, the
 * Lambert baseline, WNO and WNO-R, then the specular models of SPEC §9.3
 * in its table's order (a new model goes at the end of its list, and a
 * new diffuse model's index shifts the specular ones: bf_model_find by
 * name is the stable way). Adding a model means one new file in
 * src/models/ (the build takes every file there) and one line here; its
 * composites come with it.
 */
#ifndef BF_MODELS_REGISTRY_H
#define BF_MODELS_REGISTRY_H

#define BF_REGISTRY_DIFFUSE(X, a)                                           \
    X(a, bf_model_bk_g)                                                     \
    X(a, bf_model_bk_e)                                                     \
    X(a, bf_model_vh_g)                                                     \
    X(a, bf_model_vh_e)                                                     \
    X(a, bf_model_fc_g)                                                     \
    X(a, bf_model_fc_e)                                                     \
    X(a, bf_model_on)                                                       \
    X(a, bf_model_lftg)                                                     \
    X(a, bf_model_lambert)                                                  \
    X(a, bf_model_wno)                                                      \
    X(a, bf_model_wno_r)

#define BF_REGISTRY_SPECULAR(X, a)                                          \
    X(a, bf_model_ggx)                                                      \
    X(a, bf_model_beckmann)                                                 \
    X(a, bf_model_ct)                                                       \
    X(a, bf_model_blinn_phong)                                              \
    X(a, bf_model_ward)                                                     \
    X(a, bf_model_ward_duer)                                                \
    X(a, bf_model_ward_gmd)                                                 \
    X(a, bf_model_as)                                                       \
    X(a, bf_model_lafortune)                                                \
    X(a, bf_model_abc)

/* Both lists with a one-argument X (X(v) per model). */
#define BF_REGISTRY_APPLY(X, v) X(v)
#define BF_REGISTRY(X)                                                      \
    BF_REGISTRY_DIFFUSE(BF_REGISTRY_APPLY, X)                               \
    BF_REGISTRY_SPECULAR(BF_REGISTRY_APPLY, X)

#define BF_REGISTRY_DECLARE(v) extern const bf_model_type *const v;

/* The composite D+S of SPEC §9.4 named name ("LAMBERT+GGX"; parts
 * case-insensitive), or NULL with *why a sentence saying why not (static
 * storage): not of the form D+S, an unknown part, S+D order, two specular
 * or two diffuse parts (composite.c). */
const bf_model_type *bf__composite_find(const char *name, const char **why);

/* ASCII case-insensitive equality of a and the first len bytes of b
 * (len SIZE_MAX: all of b) (registry.c). */
int bf__name_equal(const char *a, const char *b, size_t len);

#endif
