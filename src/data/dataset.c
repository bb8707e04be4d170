/* dataset.c: the format-neutral dataset -- materials, their configuration
 * sets, channels, values and valid marks (SPEC §1.5, §2, §8). Every reader
 * produces one; the study takes one.
 *
 * [1] SPEC §1.5 (measurement frame), §2 (channels, invalid values).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* One configuration list, shared by the materials measured on it. */
typedef struct {
    size_t n;
    double *angles; /* n x 4, measurement frame (SPEC §1.5) */
    bf_geom *geom;  /* n, Beckmann's frame */
} cset_t;

typedef struct {
    char *name;
    int number;             /* > 0 explicit; 0: the position */
    bf_format format;
    char *source;           /* never NULL ("" when unknown) */
    long line;              /* where its data start in source, 0 unknown */
    size_t set;
    size_t n_channels;
    char **channel;
    double *wavelength;     /* n_channels, NaN where none */
    double *values;         /* n_conf x n_channels */
    unsigned char *valid;   /* same layout, NULL when all valid */
} material_t;

struct bf_dataset {
    cset_t *sets;
    size_t n_sets;
    size_t cap_sets;
    material_t *mat;
    size_t n_mat;
    size_t cap_mat;
};

static char *dup_str(const char *s)
{
    size_t len = strlen(s) + 1;
    char *d = malloc(len);
    if (d != NULL) {
        memcpy(d, s, len);
    }
    return d;
}

/* Grows *p (elements of size sz) to hold need, doubling. */
static int grow(void **p, size_t *cap, size_t need, size_t sz)
{
    size_t c;
    void *q;
    if (need <= *cap) {
        return BF_OK;
    }
    c = *cap == 0 ? 8 : 2 * *cap;
    while (c < need) {
        c *= 2;
    }
    if (c > SIZE_MAX / sz) {
        return BF_ENOMEM;
    }
    q = realloc(*p, c * sz);
    if (q == NULL) {
        return BF_ENOMEM;
    }
    *p = q;
    *cap = c;
    return BF_OK;
}

bf_dataset *bf_dataset_alloc(void)
{
    return calloc(1, sizeof(bf_dataset));
}

static void material_clear(material_t *m)
{
    size_t c;
    free(m->name);
    free(m->source);
    if (m->channel != NULL) {
        for (c = 0; c < m->n_channels; c++) {
            free(m->channel[c]);
        }
    }
    free(m->channel);
    free(m->wavelength);
    free(m->values);
    free(m->valid);
    memset(m, 0, sizeof *m);
}

void bf_dataset_free(bf_dataset *ds)
{
    size_t i;
    if (ds == NULL) {
        return;
    }
    for (i = 0; i < ds->n_sets; i++) {
        free(ds->sets[i].angles);
        free(ds->sets[i].geom);
    }
    for (i = 0; i < ds->n_mat; i++) {
        material_clear(&ds->mat[i]);
    }
    free(ds->sets);
    free(ds->mat);
    free(ds);
}

/* ==== building ========================================================= */

/* A zenith angle of SPEC §1.1: within [0, pi/2]. */
static int zenith_ok(double t)
{
    return t >= 0.0 && t <= BF__PI_2;
}

int bf_dataset_add_configs(bf_dataset *ds, size_t n, const double *angles,
                           size_t *set, size_t *bad)
{
    cset_t cs;
    size_t k;
    if (ds == NULL || angles == NULL || n == 0 || set == NULL ||
        n > SIZE_MAX / (4 * sizeof(double))) {
        return BF_EINVAL;
    }
    for (k = 0; k < n; k++) {
        const double *a = angles + 4 * k;
        if (!zenith_ok(a[0]) || !zenith_ok(a[2]) || !isfinite(a[1]) ||
            !isfinite(a[3])) {
            if (bad != NULL) {
                *bad = k;
            }
            return BF_EINVAL;
        }
    }
    if (grow((void **)&ds->sets, &ds->cap_sets, ds->n_sets + 1,
             sizeof *ds->sets) != BF_OK) {
        return BF_ENOMEM;
    }
    cs.n = n;
    cs.angles = malloc(n * 4 * sizeof *cs.angles);
    cs.geom = malloc(n * sizeof *cs.geom);
    if (cs.angles == NULL || cs.geom == NULL) {
        free(cs.angles);
        free(cs.geom);
        return BF_ENOMEM;
    }
    memcpy(cs.angles, angles, n * 4 * sizeof *cs.angles);
    for (k = 0; k < n; k++) {
        const double *a = angles + 4 * k;
        cs.geom[k] = bf_geom_from_measurement(a[0], a[1], a[2], a[3]);
    }
    ds->sets[ds->n_sets] = cs;
    *set = ds->n_sets++;
    return BF_OK;
}

/* The number material index i has when numbered `number` (0: position). */
static int effective_number(int number, size_t i)
{
    return number > 0 ? number : (int)(i + 1);
}

/* 1 when some material other than skip has effective number num. */
static int number_taken(const bf_dataset *ds, int num, size_t skip)
{
    size_t i;
    for (i = 0; i < ds->n_mat; i++) {
        if (i != skip && effective_number(ds->mat[i].number, i) == num) {
            return 1;
        }
    }
    return 0;
}

/* Copies desc into m (already zeroed). Checks values against valid. */
static int material_fill(material_t *m, const bf_material_desc *d,
                         size_t n_conf)
{
    size_t nv = n_conf * d->n_channels;
    size_t c;
    size_t k;
    int all_valid = 1;

    for (k = 0; k < nv; k++) {
        int ok = d->valid == NULL || d->valid[k] != 0;
        if (ok && !isfinite(d->values[k])) {
            return BF_EINVAL;
        }
        all_valid &= ok;
    }
    m->name = dup_str(d->name != NULL ? d->name : "");
    m->source = dup_str(d->source != NULL ? d->source : "");
    m->channel = calloc(d->n_channels, sizeof *m->channel);
    m->wavelength = malloc(d->n_channels * sizeof *m->wavelength);
    m->values = malloc(nv * sizeof *m->values);
    if (m->name == NULL || m->source == NULL || m->channel == NULL ||
        m->wavelength == NULL || m->values == NULL) {
        return BF_ENOMEM;
    }
    m->n_channels = d->n_channels;
    for (c = 0; c < d->n_channels; c++) {
        char num[32];
        const char *nm = d->channel != NULL ? d->channel[c] : NULL;
        if (nm == NULL) {
            snprintf(num, sizeof num, "%zu", c + 1);
            nm = num;
        }
        m->channel[c] = dup_str(nm);
        if (m->channel[c] == NULL) {
            return BF_ENOMEM;
        }
        m->wavelength[c] = d->wavelength != NULL ? d->wavelength[c] : NAN;
    }
    memcpy(m->values, d->values, nv * sizeof *m->values);
    if (!all_valid) {
        m->valid = malloc(nv);
        if (m->valid == NULL) {
            return BF_ENOMEM;
        }
        for (k = 0; k < nv; k++) {
            m->valid[k] = d->valid[k] != 0;
        }
    }
    m->number = d->number;
    m->format = d->format;
    m->line = d->line;
    m->set = d->set;
    return BF_OK;
}

int bf_dataset_add_material(bf_dataset *ds, const bf_material_desc *desc,
                            size_t *index)
{
    material_t m;
    size_t c;
    int rc;
    if (ds == NULL || desc == NULL || desc->values == NULL ||
        desc->n_channels == 0 || desc->set >= ds->n_sets ||
        desc->number < 0 ||
        desc->n_channels > SIZE_MAX / sizeof(double) /
                               ds->sets[desc->set].n) {
        return BF_EINVAL;
    }
    for (c = 0; desc->channel != NULL && c < desc->n_channels; c++) {
        if (desc->channel[c] == NULL || desc->channel[c][0] == '\0') {
            return BF_EINVAL;
        }
    }
    if (number_taken(ds, effective_number(desc->number, ds->n_mat),
                     SIZE_MAX)) {
        return BF_EINVAL;
    }
    if (grow((void **)&ds->mat, &ds->cap_mat, ds->n_mat + 1,
             sizeof *ds->mat) != BF_OK) {
        return BF_ENOMEM;
    }
    memset(&m, 0, sizeof m);
    rc = material_fill(&m, desc, ds->sets[desc->set].n);
    if (rc != BF_OK) {
        material_clear(&m);
        return rc;
    }
    ds->mat[ds->n_mat] = m;
    if (index != NULL) {
        *index = ds->n_mat;
    }
    ds->n_mat++;
    return BF_OK;
}

/* The description of material i of ds (pointers borrowed from ds). */
static void describe(const bf_dataset *ds, size_t i, size_t set,
                     bf_material_desc *d)
{
    const material_t *m = &ds->mat[i];
    memset(d, 0, sizeof *d);
    d->name = m->name;
    d->number = m->number;
    d->format = m->format;
    d->source = m->source;
    d->line = m->line;
    d->set = set;
    d->n_channels = m->n_channels;
    d->channel = (const char *const *)m->channel;
    d->wavelength = m->wavelength;
    d->values = m->values;
    d->valid = m->valid;
}

int bf_dataset_append(bf_dataset *dst, const bf_dataset *src)
{
    size_t n_mat0;
    size_t n_sets0;
    size_t i;
    int rc = BF_OK;
    if (dst == NULL || src == NULL || dst == src) {
        return BF_EINVAL;
    }
    n_mat0 = dst->n_mat;
    n_sets0 = dst->n_sets;
    for (i = 0; i < src->n_sets && rc == BF_OK; i++) {
        size_t set;
        rc = bf_dataset_add_configs(dst, src->sets[i].n, src->sets[i].angles,
                                    &set, NULL);
    }
    for (i = 0; i < src->n_mat && rc == BF_OK; i++) {
        bf_material_desc d;
        describe(src, i, n_sets0 + src->mat[i].set, &d);
        rc = bf_dataset_add_material(dst, &d, NULL);
    }
    if (rc != BF_OK) { /* leave dst as it was */
        while (dst->n_mat > n_mat0) {
            material_clear(&dst->mat[--dst->n_mat]);
        }
        while (dst->n_sets > n_sets0) {
            dst->n_sets--;
            free(dst->sets[dst->n_sets].angles);
            free(dst->sets[dst->n_sets].geom);
        }
    }
    return rc;
}

/* ==== reading ========================================================== */

size_t bf_dataset_count(const bf_dataset *ds)
{
    return ds != NULL ? ds->n_mat : 0;
}

/* Material m, or NULL when out of range. */
static const material_t *mat(const bf_dataset *ds, size_t m)
{
    return (ds != NULL && m < ds->n_mat) ? &ds->mat[m] : NULL;
}

const char *bf_dataset_name(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->name : NULL;
}

int bf_dataset_number(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? effective_number(p->number, m) : -1;
}

long bf_dataset_find(const bf_dataset *ds, int number)
{
    size_t i;
    for (i = 0; i < bf_dataset_count(ds); i++) {
        if (effective_number(ds->mat[i].number, i) == number) {
            return (long)i;
        }
    }
    return -1;
}

bf_format bf_dataset_format(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->format : BF_FORMAT_AUTO;
}

const char *bf_dataset_source(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->source : NULL;
}

long bf_dataset_line(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->line : 0;
}

size_t bf_dataset_nconf(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? ds->sets[p->set].n : 0;
}

size_t bf_dataset_set(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->set : SIZE_MAX;
}

const bf_geom *bf_dataset_geom(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? ds->sets[p->set].geom : NULL;
}

const double *bf_dataset_angles(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? ds->sets[p->set].angles : NULL;
}

size_t bf_dataset_nchannels(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->n_channels : 0;
}

const char *bf_dataset_channel(const bf_dataset *ds, size_t m, size_t c)
{
    const material_t *p = mat(ds, m);
    if (p != NULL && c == BF_CHANNEL_MEAN) {
        return "mean";
    }
    return (p != NULL && c < p->n_channels) ? p->channel[c] : NULL;
}

double bf_dataset_wavelength(const bf_dataset *ds, size_t m, size_t c)
{
    const material_t *p = mat(ds, m);
    return (p != NULL && c < p->n_channels) ? p->wavelength[c] : NAN;
}

const double *bf_dataset_values(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->values : NULL;
}

const unsigned char *bf_dataset_valid(const bf_dataset *ds, size_t m)
{
    const material_t *p = mat(ds, m);
    return p != NULL ? p->valid : NULL;
}
