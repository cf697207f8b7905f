/* The binary STL reader's threaded half (issue 15): a large binary STL is
 * decoded, checked and welded by a team of threads, into the mesh the
 * serial reader (import_stl.c) makes, bit for bit: the same vertices,
 * numbered by first appearance in corner order, the same triangles, the
 * same error for the same bad file. Internal to lamina. */
#ifndef LAM_STL_WELD_H
#define LAM_STL_WELD_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "error.h"
#include "mesh.h"
#include "pool.h"

/* Fewer facets than this are read by the calling thread alone. Measured
 * (the "reading the model" phase of `slice -v`, -j 1 against -j 2 in
 * ABBA order, medians of 16-24, at nice -20 on a 2-core VM with other
 * work running): 30k facets 36 -> 44 ms, 100k 56 -> 79 ms, 160k (the
 * bench's sphere) 76 -> 80 ms, 361k (its torus) 156 -> 160 ms, 1M 568 ->
 * 454 ms, 5M 2.33 -> 1.66 s. Below some hundreds of thousands of facets
 * the first reads of the mapped file (page faults, which two threads do
 * no faster than one on these VMs) and the passes' hand-overs outweigh
 * the shared hashing and lookups. */
#define LAM_STL_TEAM_MIN (1u << 19)

/* A little-endian uint32 read byte by byte (no alignment or byte order
 * assumption). */
static inline uint32_t lam_rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The nine vertex coordinates of the facet record whose first vertex is
 * at p, as doubles; returns -1, or the index (0..8) of the first that is
 * not finite (both readers report it by its byte offset). */
static inline int lam_stl_facet(const unsigned char *p, double xyz[9])
{
    uint32_t bad = 0;
    for (int k = 0; k < 9; k++) {
        uint32_t u = lam_rd_u32(p + 4 * k);
        float f;
        memcpy(&f, &u, sizeof f);
        xyz[k] = f;
        bad |= (u & 0x7f800000u) == 0x7f800000u;
    }
    if (!bad) return -1;
    int k = 0;
    while ((lam_rd_u32(p + 4 * k) & 0x7f800000u) != 0x7f800000u) k++;
    return k;
}

/* The error for the non-finite vertex coordinate at byte offset off of a
 * binary STL (data: the whole file): "facet F, vertex V: x coordinate is
 * not a finite number (nan)" at that offset. Returns LAM_EINVAL. */
int lam_stl_nonfinite(const char *path, const unsigned char *data, size_t off, lam_error *err);

/* Read the `count` facets of the binary STL data (the whole file, its size
 * already checked against count, count * 3 < UINT32_MAX - 1) into the
 * empty mesh m, welded, with the team's threads. Errors as the serial
 * reader's: the first non-finite coordinate by offset, LAM_ENOMEM. */
int lam_stl_binary_team(const char *path, const unsigned char *data, uint32_t count, lam_mesh *m, lam_team *team,
                        lam_error *err);

/* lam_import_stl_buf (import.h) with up to `threads` threads: a team is
 * started for a binary STL of LAM_STL_TEAM_MIN facets or more read into an
 * empty mesh, and stopped before returning; anything else is read by the
 * calling thread. (import_stl.c) */
int lam_import_stl_threads(const char *path, const unsigned char *data, size_t len, lam_mesh *mesh, int *binary,
                           unsigned threads, lam_error *err);

#endif
