/* Huge-page hints; see hugemem.h. madvise and MADV_HUGEPAGE are Linux's. */
#define _DEFAULT_SOURCE
#include "hugemem.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

void lam_huge_hint(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    if (!p || bytes < LAM_HUGE_MIN) return;
    uintptr_t page = 4096, a = ((uintptr_t)p + page - 1) & ~(page - 1), z = ((uintptr_t)p + bytes) & ~(page - 1);
    if (z > a) (void)madvise((void *)a, z - a, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

void *lam_big_malloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    lam_huge_hint(p, bytes);
    return p;
}

void *lam_big_calloc(size_t n, size_t size)
{
    if (size && n > SIZE_MAX / size) return NULL;
    void *p = calloc(n ? n : 1, size ? size : 1);
    lam_huge_hint(p, n * size);
    return p;
}
