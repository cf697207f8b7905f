/* Big arrays read at random (the mesh, its edge table, the welder's hash
 * table, the sweep's schedule) asked for on transparent huge pages: one
 * TLB entry and one page fault per 2 MiB instead of per 4 KiB. Debian's
 * kernels give huge pages to regions that ask (THP "madvise" mode); where
 * the kernel does not, nothing changes. A page fault costs about 12 us on
 * the virtual machines we measure on, so a run that touches its model once
 * pays mostly for faults. Measured (slice -w 0.1 -j 2, alternating with
 * Slic3r, medians of 5): the bench's sphere (160k triangles, arrays of
 * 1.9 MB) 0.129 -> 0.108 s, 3,900 -> 2,200 faults, peak 22.4 -> 25.7 MB;
 * the torus (360k) 0.207 -> 0.141 s, peak 40.7 -> 44.0 MB. Internal to
 * lamina. */
#ifndef LAM_HUGEMEM_H
#define LAM_HUGEMEM_H

#include <stddef.h>

/* Arrays smaller than this are left to ordinary pages; the huge page size. */
#define LAM_HUGE_MIN ((size_t)1 << 20)
#define LAM_HUGE_PAGE ((size_t)2 << 20)

/* Ask for huge pages for the whole pages of [p, p + bytes) when bytes is at
 * least LAM_HUGE_MIN. Changes no data; best effort (errors are ignored). */
void lam_huge_hint(void *p, size_t bytes);

/* malloc and calloc (NULL when out of memory or n * size wraps); free()
 * releases them. Blocks of LAM_HUGE_MIN or more start on a huge page and
 * are hinted; they end on one when rounding up costs at most an eighth
 * more (rounding every array up cost the torus 65 MB of peak memory
 * instead of 39). */
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
