#include "error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void lam_error_clear(lam_error *err)
{
    if (!err) return;
    err->code = LAM_OK;
    err->file[0] = '\0';
    err->line = err->column = 0;
    err->offset = -1;
    err->msg[0] = '\0';
}

static void set_file(lam_error *err, const char *file)
{
    if (file)
        snprintf(err->file, sizeof err->file, "%s", file);
    else
        err->file[0] = '\0';
}

int lam_error_vset(lam_error *err, int code, const char *file, long line, long column, long long offset,
                   const char *fmt, va_list ap)
{
    if (!err) return code;
    /* formatted aside first: an argument may be err's own message or file
     * (a message wrapped with its context) */
    char msg[sizeof err->msg];
    vsnprintf(msg, sizeof msg, fmt, ap);
    err->code = code;
    set_file(err, file);
    err->line = line;
    err->column = column;
    err->offset = offset;
    memcpy(err->msg, msg, sizeof msg);
    return code;
}

int lam_error_set(lam_error *err, int code, const char *file, long line,
                  long column, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(err, code, file, line, column, -1, fmt, ap);
    va_end(ap);
    return rc;
}

int lam_error_nomem(lam_error *err, const char *doing)
{
    if (doing) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory %s", doing);
    return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
}

int lam_error_at_offset(lam_error *err, int code, const char *file,
                        long long offset, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(err, code, file, 0, 0, offset, fmt, ap);
    va_end(ap);
    return rc;
}

const char *lam_error_format(const lam_error *err, char *buf, size_t size)
{
    if (!buf || size == 0) return buf;
    if (!err) {
        snprintf(buf, size, "unknown error");
        return buf;
    }
    if (err->file[0] && err->line > 0)
        snprintf(buf, size, "%s:%ld:%ld: %s", err->file, err->line,
                 err->column > 0 ? err->column : 1, err->msg);
    else if (err->file[0] && err->offset >= 0)
        snprintf(buf, size, "%s: byte %lld: %s", err->file, err->offset, err->msg);
    else if (err->file[0])
        snprintf(buf, size, "%s: %s", err->file, err->msg);
    else
        snprintf(buf, size, "%s", err->msg);
    return buf;
}

const char *lam_status_name(int code)
{
    switch (code) {
    case LAM_OK: return "ok";
    case LAM_EIO: return "I/O error";
    case LAM_ESYNTAX: return "syntax error";
    case LAM_EINVAL: return "invalid input";
    case LAM_ENOMEM: return "out of memory";
    case LAM_EFORMAT: return "unknown format";
    case LAM_EGEOM: return "geometry error";
    case LAM_EUSAGE: return "usage error";
    case LAM_ELIMIT: return "over a limit";
    }
    return "error";
}
