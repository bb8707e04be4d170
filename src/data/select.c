/* select.c: channels, the configurations a study uses and the measured
 * radiance of a dataset's material (SPEC §1.4, §1.6, §2).
 *
 * [1] SPEC §1.4 (CURET's specular configurations), §1.6 (the specular cone
 *     of other data), §2 (radiance = BRDF x cos theta_i, normalised by its
 *     maximum over the used configurations; channels; invalid values).
 */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* Case-insensitive ASCII comparison. */
static int same_text(const char *a, const char *b)
{
    for (; *a != '\0' && *b != '\0'; a++, b++) {
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) {
            return 0;
        }
    }
    return *a == *b;
}

int bf_dataset_channel_find(const bf_dataset *ds, size_t m,
                            const char *name, size_t *c)
{
    size_t n = bf_dataset_nchannels(ds, m);
    size_t i;
    double wl;
    if (name == NULL || c == NULL || n == 0) {
        return BF_EINVAL;
    }
    if (same_text(name, "mean")) {
        *c = BF_CHANNEL_MEAN;
        return BF_OK;
    }
    for (i = 0; i < n; i++) {
        if (same_text(name, bf_dataset_channel(ds, m, i))) {
            *c = i;
            return BF_OK;
        }
    }
    /* a wavelength in nm: "550" matches a channel at 550 nm */
    if (bf__parse_double(name, &wl) == BF__NUM_OK) {
        for (i = 0; i < n; i++) {
            if (bf_dataset_wavelength(ds, m, i) == wl) {
                *c = i;
                return BF_OK;
            }
        }
    }
    return BF_ENOTFOUND;
}

int bf_dataset_value(const bf_dataset *ds, size_t m, size_t k, size_t c,
                     double *value)
{
    size_t nc = bf_dataset_nchannels(ds, m);
    const double *v = bf_dataset_values(ds, m);
    const unsigned char *ok = bf_dataset_valid(ds, m);
    size_t i;
    double sum = 0.0;
    if (v == NULL || k >= bf_dataset_nconf(ds, m) ||
        (c != BF_CHANNEL_MEAN && c >= nc)) {
        *value = NAN;
        return 0;
    }
    v += k * nc;
    ok = ok != NULL ? ok + k * nc : NULL;
    if (c != BF_CHANNEL_MEAN || nc == 1) { /* one channel: its value */
        size_t j = c == BF_CHANNEL_MEAN ? 0 : c;
        *value = v[j];
        return ok == NULL || ok[j];
    }
    for (i = 0; i < nc; i++) { /* SPEC §2: the mean over the channels */
        if (ok != NULL && !ok[i]) {
            *value = NAN;
            return 0;
        }
        sum += v[i];
    }
    *value = sum / (double)nc;
    return 1;
}

void bf_selection_init(bf_selection *s)
{
    memset(s, 0, sizeof *s);
    s->cone = BF_CONE_DEFAULT;
    s->max_theta = BF__PI_2;
}

/* Whether configuration g is left out as specular: by CURET's test of SPEC
 * §1.4 (cone = BF_CONE_DEFAULT on CURET data), or by the cone of SPEC §1.6
 * (delta < cone). */
static int in_cone(const bf_geom *g, double cone, int curet)
{
    if (cone < 0.0) {
        return curet && bf_geom_is_specular(g);
    }
    return cone > 0.0 && bf_geom_mirror_angle(g) < cone;
}

int bf_dataset_select(const bf_dataset *ds, size_t m, size_t c,
                      const bf_selection *s, size_t *sel, size_t *n,
                      size_t *cone_out)
{
    size_t nconf = bf_dataset_nconf(ds, m);
    const bf_geom *geom = bf_dataset_geom(ds, m);
    unsigned char *ex = NULL;
    size_t n_cone = 0;
    size_t k;
    size_t j;
    int curet;

    if (geom == NULL || s == NULL || sel == NULL || n == NULL ||
        (c != BF_CHANNEL_MEAN && c >= bf_dataset_nchannels(ds, m)) ||
        isnan(s->cone) || isnan(s->max_theta) ||
        (s->n_exclude > 0 && s->exclude == NULL)) {
        return BF_EINVAL;
    }
    for (j = 0; j < s->n_exclude; j++) {
        if (s->exclude[j] == 0 || s->exclude[j] > nconf) {
            return BF_ENOTFOUND;
        }
    }
    if (s->n_exclude > 0) {
        ex = calloc(nconf, 1);
        if (ex == NULL) {
            return BF_ENOMEM;
        }
        for (j = 0; j < s->n_exclude; j++) {
            ex[s->exclude[j] - 1] = 1;
        }
    }
    curet = bf_dataset_format(ds, m) == BF_FORMAT_CURET;
    *n = 0;
    for (k = 0; k < nconf; k++) {
        const bf_geom *g = &geom[k];
        double v;
        if (!bf_dataset_value(ds, m, k, c, &v)) {
            continue; /* SPEC §2: an invalid value leaves it out */
        }
        if (in_cone(g, s->cone, curet)) {
            n_cone++;
            continue;
        }
        if (g->theta_i > s->max_theta || g->theta_s > s->max_theta) {
            continue;
        }
        if (ex != NULL && ex[k]) {
            continue;
        }
        sel[(*n)++] = k;
    }
    free(ex);
    if (cone_out != NULL) {
        *cone_out = n_cone;
    }
    return BF_OK;
}

int bf_dataset_radiance(const bf_dataset *ds, size_t m, size_t c, size_t n,
                        const size_t *sel, double *out)
{
    int rc = bf__dataset_rho(ds, m, c, n, sel, out);
    return rc != BF_OK ? rc : bf_normalise(n, out, out);
}

int bf__dataset_rho(const bf_dataset *ds, size_t m, size_t c, size_t n,
                    const size_t *sel, double *out)
{
    const bf_geom *geom = bf_dataset_geom(ds, m);
    size_t nconf = bf_dataset_nconf(ds, m);
    size_t j;
    if (geom == NULL || sel == NULL || out == NULL || n == 0 ||
        (c != BF_CHANNEL_MEAN && c >= bf_dataset_nchannels(ds, m))) {
        return BF_EINVAL;
    }
    for (j = 0; j < n; j++) {
        double v;
        if (sel[j] >= nconf) {
            return BF_EINVAL;
        }
        if (!bf_dataset_value(ds, m, sel[j], c, &v)) {
            return BF_EDOM;
        }
        /* SPEC §2: BRDF x cos(theta_i) */
        out[j] = v * cos(geom[sel[j]].theta_i);
    }
    return BF_OK;
}
