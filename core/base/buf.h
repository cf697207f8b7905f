/* lam_buf: the one growing byte buffer of core/ (text being built, bytes
 * being gathered): its room doubles (lam_grow_cap, grow.h) and it is
 * always NUL-terminated once it holds anything, so text in it is a C
 * string. Arrays of other elements grow with lam_grow (grow.h). Internal
 * to lamina (not installed).
 *
 *     lam_buf b;
 *     lam_buf_init(&b);
 *     if (lam_buf_printf(&b, "%d", n) || lam_buf_append(&b, s, len)) fail;
 *     char *text = lam_buf_take(&b, &len);   (the caller frees text) */
#ifndef LAM_BUF_H
#define LAM_BUF_H

#include <stdarg.h>
#include <stddef.h>

typedef struct lam_buf {
    char *data;              /* NULL until the first byte; then data[len] == '\0' */
    size_t len;              /* bytes held, not counting the NUL */
    size_t cap;              /* bytes allocated at data */
} lam_buf;

/* An empty buffer that holds no memory yet (as a zeroed lam_buf is). */
void lam_buf_init(lam_buf *b);

/* Room for n more bytes and the NUL after them (cap >= len + n + 1),
 * doubling from 64 bytes. Returns LAM_OK, or LAM_ENOMEM (out of memory or
 * more than size_t can count) with b unchanged. */
int lam_buf_reserve(lam_buf *b, size_t n);

/* Append data[0..n) (data may be NULL when n is 0). LAM_OK or LAM_ENOMEM
 * (b unchanged). */
int lam_buf_append(lam_buf *b, const void *data, size_t n);

/* Append printf-formatted text. LAM_OK, LAM_ENOMEM (b unchanged), or
 * LAM_EUSAGE when vsnprintf fails (a bad format). */
int lam_buf_printf(lam_buf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* lam_buf_printf with a va_list (ap is used once, as vsnprintf uses it). */
int lam_buf_vprintf(lam_buf *b, const char *fmt, va_list ap);

/* Append data[0..n) as base64 (RFC 4648's alphabet, '=' padding, no line
 * breaks): 4 characters for every 3 bytes. LAM_OK or LAM_ENOMEM (b unchanged). */
int lam_buf_base64(lam_buf *b, const void *data, size_t n);

/* Forget the bytes held, keeping the memory for reuse. */
void lam_buf_clear(lam_buf *b);

/* Hand the bytes to the caller: a NUL-terminated block of *len bytes
 * (len may be NULL) the caller frees; an empty buffer gives a new "".
 * NULL only when that "" cannot be allocated. b is left empty (as by
 * lam_buf_init), owning nothing. */
char *lam_buf_take(lam_buf *b, size_t *len);

/* Free b's memory and leave it empty (lam_buf_init); b may be NULL. */
void lam_buf_free(lam_buf *b);

#endif
