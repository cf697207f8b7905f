/* Growing arrays: the one doubling rule of core/, with the size checks
 * every hand-written copy needs (a count times an element size must not
 * wrap around). Internal to lamina (not installed). */
#ifndef LAM_GROW_H
#define LAM_GROW_H

#include <stdint.h>
#include <stdlib.h>

/* The capacity for at least need elements of size bytes: cap (min when
 * cap is 0) doubled until it reaches need. 0 when need elements would not
 * fit in size_t bytes. */
static inline size_t lam_grow_cap(size_t cap, size_t need, size_t min, size_t size)
{
    size_t c = cap ? cap : min;
    if (c == 0) c = 1;
    while (c < need) c = c > SIZE_MAX / 2 ? need : 2 * c;
    return size && c > SIZE_MAX / size ? 0 : c;
}

/* realloc(p, n * size), NULL when that fails or the product wraps around
 * (p is then untouched and still the caller's). */
static inline void *lam_realloc_n(void *p, size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size) return NULL;
    size_t bytes = n * size;
    return realloc(p, bytes ? bytes : 1);
}

/* Grow the array p of *cap elements of size bytes to hold need > *cap
 * elements (lam_grow_cap from min): the new block, *cap updated; NULL when
 * out of memory or too large, p and *cap unchanged. Typical use:
 *     if (n == cap && !(np = lam_grow(a, &cap, n + 1, sizeof *a, 16))) fail;
 */
static inline void *lam_grow(void *p, size_t *cap, size_t need, size_t size, size_t min)
{
    size_t c = lam_grow_cap(*cap, need, min, size);
    void *q = c ? lam_realloc_n(p, c, size) : NULL;
    if (q) *cap = c;
    return q;
}

#endif
