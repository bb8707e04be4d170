/* csv.c: the pieces the library's CSV writers share -- fields quoted as
 * RFC 4180 asks, numbers, a target's identifying fields -- and the flags
 * a fit's analysis reports (bf_fit_flags_format; doc/methods.md §2, §3,
 * §8).
 *
 * [1] RFC 4180 (comma-separated fields, double quotes).
 */
#include <math.h>
#include <stdarg.h>
#include <string.h>

#include "output/output.h"

/* 1 when text must be quoted to be read back as it is: it holds a comma,
 * a quote or a line break, starts or ends with a blank (readers trim
 * them), or starts with '#' (a comment line in a tidy CSV's first
 * column). */
static int needs_quotes(const char *text)
{
    size_t n = strlen(text);
    return strpbrk(text, ",\"\n\r") != NULL ||
           (n > 0 && (text[0] == '#' || text[0] == ' ' || text[0] == '\t' ||
                      text[n - 1] == ' ' || text[n - 1] == '\t'));
}

void bf__csv_field(FILE *fp, const char *text)
{
    if (!needs_quotes(text)) {
        fputs(text, fp);
        return;
    }
    fputc('"', fp); /* [1] */
    for (; *text != '\0'; text++) {
        if (*text == '"') {
            fputc('"', fp);
        }
        fputc(*text, fp);
    }
    fputc('"', fp);
}

void bf__csv_num(FILE *fp, double x)
{
    if (isfinite(x)) {
        fprintf(fp, ",%.10g", x);
    } else {
        fputc(',', fp);
    }
}

void bf__csv_target(FILE *fp, const bf_study_spec *spec, size_t t)
{
    bf__csv_target_as(fp, spec, t, NULL);
}

void bf__csv_target_as(FILE *fp, const bf_study_spec *spec, size_t t,
                       const char *as)
{
    const bf_target *tg = &spec->targets[t];
    const char *name = bf_dataset_name(spec->data, tg->material);
    const char *channel = as != NULL ? as
                                     : bf_dataset_channel(spec->data,
                                                          tg->material,
                                                          tg->channel);
    fprintf(fp, "%d,", bf_dataset_number(spec->data, tg->material));
    bf__csv_field(fp, name != NULL ? name : "");
    fputc(',', fp);
    bf__csv_field(fp, channel != NULL ? channel : "");
}

int bf__csv_check(FILE *fp, const bf_study_spec *spec,
                  const bf_study_row *rows, const bf_fit_stats *stats,
                  int need_stats)
{
    if (fp == NULL || spec == NULL || rows == NULL || spec->data == NULL ||
        (spec->n_targets > 0 && spec->targets == NULL) ||
        (spec->n_models > 0 && spec->models == NULL) ||
        (need_stats && stats == NULL)) {
        return BF_EINVAL;
    }
    return BF_OK;
}

int bf__csv_status(FILE *fp)
{
    return (fflush(fp) != 0 || ferror(fp)) ? BF_EIO : BF_OK;
}

/* Appends one word to buf (at *at of len), space-separated. */
static void word(char *buf, size_t len, size_t *at, const char *fmt, ...)
    BF__PRINTF(4, 5);

static void word(char *buf, size_t len, size_t *at, const char *fmt, ...)
{
    va_list ap;
    int w;
    if (*at > 0) {
        *at += (size_t)snprintf(*at < len ? buf + *at : NULL,
                                *at < len ? len - *at : 0, " ");
    }
    va_start(ap, fmt);
    w = vsnprintf(*at < len ? buf + *at : NULL, *at < len ? len - *at : 0,
                  fmt, ap);
    va_end(ap);
    *at += w > 0 ? (size_t)w : 0;
}

size_t bf_fit_flags_format(const bf_model_type *type, const bf_fit_stats *st,
                           char *buf, size_t len)
{
    size_t at = 0;
    size_t j;
    if (buf != NULL && len > 0) {
        buf[0] = '\0';
    } else {
        len = 0;
    }
    if (type == NULL || st == NULL || !st->done) {
        return 0;
    }
    if ((st->flags & BF_STAT_REDUCED) && st->reduces_to != NULL) {
        word(buf, len, &at, "reduces_to=%s", st->reduces_to);
    }
    for (j = 0; j < type->p; j++) {
        if (((st->refined.flat | st->not_identified) >> j) & 1u) {
            word(buf, len, &at, "not_identified=%s", type->param[j].name);
        }
    }
    for (j = 0; j < type->p; j++) {
        if ((st->ci_competing >> j) & 1u) {
            word(buf, len, &at, "competing=%s", type->param[j].name);
        }
    }
    if (st->flags & BF_STAT_CLAMPED) {
        word(buf, len, &at, "clamped=%zu", st->n_clamped);
    }
    if (st->flags & BF_STAT_NOCONV) {
        word(buf, len, &at, "not_converged");
    }
    if (st->ci_method == BF_CI_PROFILE_LIK || st->ci_method == BF_CI_NEYMAN) {
        if (st->noise_power == 0.0) {
            word(buf, len, &at, "noise=absolute");
        } else if (st->noise_power == 2.0) {
            word(buf, len, &at, "noise=relative");
        } else {
            word(buf, len, &at, "noise=power:%.3g", st->noise_power);
        }
    }
    if (st->flags & BF_STAT_CI_FAIL) {
        word(buf, len, &at, "interval_failed");
    }
    if (st->flags & BF_STAT_BOOT_FAIL) {
        word(buf, len, &at, "bootstrap_failed");
    }
    for (j = 0; j < type->p; j++) {
        if ((st->boot_split >> j) & 1u) {
            word(buf, len, &at, "bootstrap_split=%s", type->param[j].name);
        }
    }
    return at;
}
