/* Big arrays read at random (the mesh, its edge table, the welder's hash
 * table, the sweep's schedule) asked for on transparent huge pages: one
 * TLB entry and one page fault per 2 MiB instead of per 4 KiB. Debian's
 * kernels give huge pages to regions that ask (THP "madvise" mode); where
 * the kernel does not, nothing changes. Measured (slice -w 0.1 -j 1, CPU
 * time medians of 3): a 1M-triangle binary STL sphere 22,400 -> 4,100 page
 * faults, 790 -> 680 ms; the bench's torus (360k) 8,400 -> 3,700 faults,
 * 294 -> 222 ms; peak memory +1.5 MB. Arrays under 4 MB (the 160k sphere's)
 * are unchanged. Internal to lamina. */
#ifndef LAM_HUGEMEM_H
#define LAM_HUGEMEM_H

#include <stddef.h>

/* Arrays smaller than this are left to ordinary pages. */
#define LAM_HUGE_MIN ((size_t)4 << 20)
#define LAM_HUGE_PAGE ((size_t)2 << 20) /* the huge page size */

/* Ask for huge pages for the whole pages of [p, p + bytes) when bytes is at
 * least LAM_HUGE_MIN. Changes no data; best effort (errors are ignored). */
void lam_huge_hint(void *p, size_t bytes);

/* malloc and calloc, hinted (NULL when out of memory or n * size wraps).
 * Not aligned to huge pages: rounding every array up to whole 2 MiB pages
 * cost the torus 65 MB of peak memory instead of 39 for little more
 * speed; a hint leaves the memory as it was. */
void *lam_big_malloc(size_t bytes);
void *lam_big_calloc(size_t n, size_t size);

/* A block of its own (an anonymous mapping starting on a huge page,
 * hinted), for scratch freed before the arrays that outlive it are made:
 * lam_big_unmap hands it back to the kernel, where a block of the heap
 * would leave a hole (the CLI's heap is never trimmed, main.c) that later
 * arrays fit around, not into: the 5M-triangle run's peak was 72 MB higher
 * with the threaded STL reader's tables on the heap. NULL when out of
 * memory. Its pages read as zero. */
void *lam_big_map(size_t bytes);

/* Release a block of lam_big_map(bytes) (NULL is fine). */
void lam_big_unmap(void *p, size_t bytes);

#endif
