/* error.c: the library's version, error texts and loader error reports
 * (bf_version, bf_strerror, bf_error_format; bf__error_* of internal.h). */
#include "internal.h"

#include <errno.h>
#include <stdarg.h>
#include <string.h>

const char *bf_version(void)
{
    return BF_VERSION_STRING;
}

const char *bf_strerror(int code)
{
    switch (code) {
    case BF_OK:
        return "success";
    case BF_EINVAL:
        return "invalid argument";
    case BF_EDOM:
        return "outside the domain of the model or function";
    case BF_ENOMEM:
        return "out of memory";
    case BF_EIO:
        return "input/output error";
    case BF_EPARSE:
        return "malformed input file";
    case BF_ENOCONV:
        return "iterative method did not converge";
    case BF_ENOTFOUND:
        return "no such item";
    default:
        return "unknown error code";
    }
}

char *bf_error_format(const bf_error *err, char *buf, size_t len)
{
    const char *file;
    if (buf == NULL || len == 0) {
        return buf;
    }
    if (err == NULL) {
        snprintf(buf, len, "(no error report)");
        return buf;
    }
    file = err->file[0] != '\0' ? err->file : BF__NONAME;
    if (err->line > 0) {
        snprintf(buf, len, "%s:%ld: %s", file, err->line, err->msg);
    } else {
        snprintf(buf, len, "%s: %s", file, err->msg);
    }
    return buf;
}

/* ==== private helpers shared by the loaders ==== */

/* Copies src into dst of size n, truncating; dst is always terminated. */
static void copy_truncated(char *dst, size_t n, const char *src)
{
    size_t len = strlen(src);
    if (len >= n) {
        len = n - 1;
    }
    memcpy(dst, src, len);
    dst[len] = '\0';
}

void bf__error_clear(bf_error *err, const char *name)
{
    if (err == NULL) {
        return;
    }
    err->code = BF_OK;
    err->line = 0;
    copy_truncated(err->file, sizeof err->file,
                   name != NULL ? name : BF__NONAME);
    err->msg[0] = '\0';
}

int bf__errno_code(int e)
{
    return e == ENOMEM ? BF_ENOMEM : BF_EIO;
}

int bf__error_set(bf_error *err, int code, long line, const char *fmt, ...)
{
    va_list ap;
    if (err == NULL) {
        return code;
    }
    err->code = code;
    err->line = line;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return code;
}
