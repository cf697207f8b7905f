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

void *lam_big_map(size_t bytes)
{
    size_t size = (bytes + 4095) & ~(size_t)4095, pad = size >= LAM_HUGE_MIN ? LAM_HUGE_PAGE : 0;
    if (!bytes || size < bytes || size + pad < size) return NULL;
    unsigned char *p = mmap(NULL, size + pad, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    /* keep the part that starts on a huge page */
    size_t head = pad ? (LAM_HUGE_PAGE - ((uintptr_t)p & (LAM_HUGE_PAGE - 1))) & (LAM_HUGE_PAGE - 1) : 0;
    if (head) munmap(p, head);
    if (pad - head) munmap(p + head + size, pad - head);
    lam_huge_hint(p + head, size);
    return p + head;
}

void lam_big_unmap(void *p, size_t bytes)
{
    if (p) munmap(p, (bytes + 4095) & ~(size_t)4095);
}
