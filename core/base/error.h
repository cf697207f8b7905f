/* lam_error: how every core module reports a failure.
 *
 * A function that can fail returns an int status (LAM_OK == 0, else one of
 * the LAM_E* codes) and fills the caller's lam_error with a message and,
 * where there is one, a position in the user's file. core/ never prints and
 * never exits: the caller decides what to do with the error.
 *
 * The err rule, for every function of lamina's API that takes one: err is
 * the last parameter, and it may be NULL, meaning the caller wants the
 * status code only (the message is dropped). Errors are written through
 * lam_error_set / lam_error_at_offset / lam_error_clear, which accept
 * NULL; code that reads a message back (to wrap it) tests err first or
 * works on a local lam_error. Header comments do not repeat the rule. */
#ifndef LAM_ERROR_H
#define LAM_ERROR_H

#include <stdarg.h>

#include <stddef.h>

enum lam_status {
    LAM_OK = 0,
    LAM_EIO,      /* a file could not be opened, read or written */
    LAM_ESYNTAX,  /* malformed input: position says where */
    LAM_EINVAL,   /* well-formed input with an invalid value or reference */
    LAM_ENOMEM,   /* allocation failed */
    LAM_EFORMAT,  /* the file's format is not one lamina reads */
    LAM_EGEOM,    /* geometry that cannot be processed (e.g. a polygon that will not triangulate) */
    LAM_EUSAGE,   /* a caller passed options that make no sense */
    LAM_ELIMIT    /* a job larger than a limit allows (layers, output size): the
                     message gives the numbers; the caller names its option */
};

typedef struct lam_error {
    int code;            /* LAM_OK when nothing went wrong */
    char file[512];      /* file the error is in, "" when none */
    long line, column;   /* 1-based position in a text file, 0 when unknown */
    long long offset;    /* byte offset in a binary file, -1 when unknown */
    char msg[1024];      /* what is wrong, without the position prefix */
} lam_error;

/* Reset err to "no error". */
void lam_error_clear(lam_error *err);

/* Record an error at file:line:column (line/column 0 when unknown, file NULL
 * when none). Returns code so callers can write `return lam_error_set(...)`. */
int lam_error_set(lam_error *err, int code, const char *file, long line,
                  long column, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

/* The same with a va_list, and the byte offset (-1 when none): for a
 * module's own error helpers. The arguments may point into err itself. */
int lam_error_vset(lam_error *err, int code, const char *file, long line, long column, long long offset,
                   const char *fmt, va_list ap);

/* LAM_ENOMEM with the message "out of memory" followed by " " and doing
 * when given ("while slicing"). Returns LAM_ENOMEM. */
int lam_error_nomem(lam_error *err, const char *doing);

/* Record an error at a byte offset of a binary file. Returns code. */
int lam_error_at_offset(lam_error *err, int code, const char *file,
                        long long offset, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* Format as "file:line:column: msg", "file: byte N: msg", "file: msg" or
 * "msg" into buf (always NUL-terminated). Returns buf. */
const char *lam_error_format(const lam_error *err, char *buf, size_t size);

/* The status code's short name ("I/O error", "syntax error", ...). */
const char *lam_status_name(int code);

#endif
