/* rep.c: the report library's messages (a per-thread sink, the first
 * error kept for bf_report_write's bf_error), the parsers of a study's
 * option lists and the label of a material (rep.h). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "rep.h"

static _Thread_local bf_report_message_fn sink_fn;
static _Thread_local void *sink_ctx;
static _Thread_local char last[1024];

void bf_rep_set_sink(bf_report_message_fn fn, void *ctx)
{
    sink_fn = fn;
    sink_ctx = ctx;
}

void bf_rep_get_sink(bf_report_message_fn *fn, void **ctx)
{
    *fn = sink_fn;
    *ctx = sink_ctx;
}

void bf_rep_clear(void)
{
    last[0] = '\0';
}

const char *bf_rep_last(void)
{
    return last;
}

static void emit(int kind, const char *fmt, va_list ap)
{
    char buf[sizeof last];
    vsnprintf(buf, sizeof buf, fmt, ap);
    if (kind != BF_REPORT_MSG_NOTE && last[0] == '\0') {
        memcpy(last, buf, sizeof last);
    }
    if (sink_fn != NULL) {
        sink_fn(sink_ctx, kind, buf);
    }
}

void bf_rep_err(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit(BF_REPORT_MSG_ERROR, fmt, ap);
    va_end(ap);
}

void bf_rep_note(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit(BF_REPORT_MSG_NOTE, fmt, ap);
    va_end(ap);
}

int bf_rep_usage_fail(int status, const char *cmd, const char *fmt, ...)
{
    va_list ap;
    (void)cmd;
    va_start(ap, fmt);
    emit(BF_REPORT_MSG_USAGE, fmt, ap);
    va_end(ap);
    return status;
}

int bf_rep_write_error(const char *name, int code)
{
    if (code == BF_ENOMEM) {
        bf_rep_err("%s could not be written: %s", name, bf_strerror(code));
    } else {
        bf_rep_err("internal error: %s could not be written (%s)", name,
                   bf_strerror(code));
    }
    return BF_REPORT_SOFTWARE;
}

int bf_rep_parse_double(const char *s, double *out)
{
    char *end = NULL;
    double v;
    if (s == NULL || *s == '\0') {
        return -1;
    }
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) {
        return -1;
    }
    *out = v;
    return 0;
}

static int parse_pos_int(const char *s, const char **end, long *v)
{
    char *e = NULL;
    if (*s < '0' || *s > '9') {
        return -1;
    }
    errno = 0;
    *v = strtol(s, &e, 10);
    if (errno == ERANGE || *v <= 0 || *v > INT_MAX) {
        return -1;
    }
    *end = e;
    return 0;
}

int bf_rep_parse_int_list(const char *s, int **out, size_t *n, char *msg,
                          size_t msglen)
{
    int *list = NULL;
    size_t len = 0;
    size_t cap = 0;
    const char *p = s;

    *out = NULL;
    *n = 0;
    if (s == NULL || *s == '\0') {
        snprintf(msg, msglen, "empty list");
        return -1;
    }
    while (*p != '\0') {
        long lo;
        long hi;
        long v;
        const char *e;
        if (parse_pos_int(p, &e, &lo) != 0) {
            snprintf(msg, msglen, "'%s': expected a positive number at '%s'",
                     s, p);
            goto fail;
        }
        hi = lo;
        if (*e == '-') {
            p = e + 1;
            if (parse_pos_int(p, &e, &hi) != 0 || hi < lo) {
                snprintf(msg, msglen, "'%s': bad range ending at '%s'", s, p);
                goto fail;
            }
        }
        if (*e != ',' && *e != '\0') {
            snprintf(msg, msglen, "'%s': unexpected '%c'", s, *e);
            goto fail;
        }
        if (hi - lo > 1000000) {
            snprintf(msg, msglen, "'%s': range too long", s);
            goto fail;
        }
        for (v = lo; v <= hi; v++) {
            size_t i;
            for (i = 0; i < len; i++) {
                if (list[i] == (int)v) {
                    snprintf(msg, msglen, "'%s': %ld is listed twice", s, v);
                    goto fail;
                }
            }
            if (len == cap) {
                size_t ncap = cap ? 2 * cap : 16;
                int *nl = realloc(list, ncap * sizeof *nl);
                if (nl == NULL) {
                    snprintf(msg, msglen, "out of memory");
                    free(list);
                    return -2;
                }
                list = nl;
                cap = ncap;
            }
            list[len++] = (int)v;
        }
        p = (*e == ',') ? e + 1 : e;
        if (*e == ',' && *p == '\0') {
            snprintf(msg, msglen, "'%s': trailing comma", s);
            goto fail;
        }
    }
    *out = list;
    *n = len;
    return 0;
fail:
    free(list);
    return -1;
}

int bf_rep_parse_range(const char *s, char *name, size_t name_len,
                       double *lo, double *hi, char *msg, size_t msg_len)
{
    const char *eq = strchr(s, '=');
    const char *colon = eq != NULL ? strchr(eq + 1, ':') : NULL;
    char num[64];
    size_t len;
    if (eq == NULL || colon == NULL || eq == s ||
        (size_t)(eq - s) >= name_len) {
        snprintf(msg, msg_len, "'%s' is not NAME=LO:HI", s);
        return -1;
    }
    memcpy(name, s, (size_t)(eq - s));
    name[eq - s] = '\0';
    len = (size_t)(colon - eq - 1);
    if (len == 0 || len >= sizeof num) {
        snprintf(msg, msg_len, "'%s': bad lower bound", s);
        return -1;
    }
    memcpy(num, eq + 1, len);
    num[len] = '\0';
    if (bf_rep_parse_double(num, lo) != 0 ||
        bf_rep_parse_double(colon + 1, hi) != 0 || !(*lo < *hi)) {
        snprintf(msg, msg_len, "'%s': LO and HI must be numbers, LO < HI",
                 s);
        return -1;
    }
    return 0;
}

void bf_rep_material_label(const bf_dataset *ds, size_t m, char *buf,
                           size_t len)
{
    const char *name = bf_dataset_name(ds, m);
    if (name != NULL && name[0] != '\0') {
        snprintf(buf, len, "%d %s", bf_dataset_number(ds, m), name);
    } else {
        snprintf(buf, len, "%d", bf_dataset_number(ds, m));
    }
}
