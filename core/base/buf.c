/* The growing byte buffer: see buf.h. */
#include "buf.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "grow.h"

void lam_buf_init(lam_buf *b)
{
    b->data = NULL;
    b->len = b->cap = 0;
}

int lam_buf_reserve(lam_buf *b, size_t n)
{
    if (n > SIZE_MAX - 1 - b->len) return LAM_ENOMEM;
    size_t need = b->len + n + 1;
    if (need <= b->cap) return LAM_OK;
    char *p = lam_grow(b->data, &b->cap, need, 1, 64);
    if (!p) return LAM_ENOMEM;
    b->data = p;
    return LAM_OK;
}

int lam_buf_append(lam_buf *b, const void *data, size_t n)
{
    int rc = lam_buf_reserve(b, n);
    if (rc) return rc;
    if (n) memcpy(b->data + b->len, data, n);
    b->len += n;
    b->data[b->len] = '\0';
    return LAM_OK;
}

int lam_buf_base64(lam_buf *b, const void *data, size_t n)
{
    static const char A[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    if (n / 3 >= ((size_t)-1 - 8) / 4) return LAM_ENOMEM;
    size_t out = (n + 2) / 3 * 4;
    int rc = lam_buf_reserve(b, out);
    if (rc) return rc;
    const unsigned char *p = data;
    char *q = b->data + b->len;
    size_t i = 0;
    for (; i + 3 <= n; i += 3, q += 4) {
        unsigned long t = (unsigned long)p[i] << 16 | (unsigned long)p[i + 1] << 8 | p[i + 2];
        q[0] = A[t >> 18];
        q[1] = A[t >> 12 & 63];
        q[2] = A[t >> 6 & 63];
        q[3] = A[t & 63];
    }
    if (i < n) {
        unsigned long t = (unsigned long)p[i] << 16 | (i + 1 < n ? (unsigned long)p[i + 1] << 8 : 0);
        q[0] = A[t >> 18];
        q[1] = A[t >> 12 & 63];
        q[2] = i + 1 < n ? A[t >> 6 & 63] : '=';
        q[3] = '=';
    }
    b->len += out;
    b->data[b->len] = '\0';
    return LAM_OK;
}

int lam_buf_vprintf(lam_buf *b, const char *fmt, va_list ap)
{
    va_list again;
    va_copy(again, ap);
    /* first into the room there is (often enough), then into the room the
     * first pass measured */
    size_t room = b->cap > b->len ? b->cap - b->len : 0;
    int n = vsnprintf(room ? b->data + b->len : NULL, room, fmt, ap);
    int rc = n < 0 ? LAM_EUSAGE : LAM_OK;
    if (!rc && (size_t)n >= room) {
        rc = lam_buf_reserve(b, (size_t)n);
        if (!rc) vsnprintf(b->data + b->len, (size_t)n + 1, fmt, again);
    }
    va_end(again);
    if (rc) {
        if (b->data) b->data[b->len] = '\0'; /* a first pass may have written past it */
        return rc;
    }
    b->len += (size_t)n;
    return LAM_OK;
}

int lam_buf_printf(lam_buf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_buf_vprintf(b, fmt, ap);
    va_end(ap);
    return rc;
}

void lam_buf_clear(lam_buf *b)
{
    b->len = 0;
    if (b->data) b->data[0] = '\0';
}

char *lam_buf_take(lam_buf *b, size_t *len)
{
    char *p = b->data ? b->data : calloc(1, 1);
    if (len) *len = p ? b->len : 0;
    lam_buf_init(b);
    return p;
}

void lam_buf_free(lam_buf *b)
{
    if (!b) return;
    free(b->data);
    lam_buf_init(b);
}
