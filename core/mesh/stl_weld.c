/* A binary STL welded by a team of threads; see stl_weld.h.
 *
 * Corners (facet f's vertex k is corner 3 f + k) are taken a chunk at a
 * time, in passes over each chunk:
 *   A  (ranges of facets, in parallel) decode the nine floats of each
 *      facet, find the first non-finite one, keep each corner's
 *      coordinates (-0.0 made 0.0) and hash (the serial welder's,
 *      weld_hash.h), and list the range's corners by the partition of the
 *      hash table their hash falls in;
 *   B  (one task per partition) every task takes the corners listed for
 *      its partition, range by range, so in corner order: it records for
 *      each the first corner of the file at the same position (itself
 *      when new) and counts the new ones per range. A partition is a table of its own
 *      (growing on its own) of corner numbers; a corner's position is
 *      found in the chunk or, for an earlier chunk, at its vertex;
 *   C  (ranges of corners) a prefix sum of those counts numbers the new
 *      corners' vertices in corner order (first appearance, as the serial
 *      welder numbers them) and stores their positions;
 *   D  (ranges of corners, run with the next chunk's A) every other corner
 *      takes its first corner's vertex.
 * Each corner's first corner does not depend on how the table is split,
 * nor the numbering on how the ranges are: the mesh is the same for any
 * number of threads. Chunks are small enough (74,898 corners, 2 MB of
 * scratch on one huge page) that a pass finds the previous one's output
 * in cache, and the scratch is touched (page faults) once; the tables are
 * the size of the serial welder's. Both are mappings of their own
 * (lam_big_map), gone before the model's arrays are made. */
#include "stl_weld.h"

#include <stdlib.h>
#include <string.h>

#include "hugemem.h"
#include "prefetch.h"
#include "weld_hash.h"

/* Corners per chunk: a multiple of 3, so chunks hold whole facets; their
 * 28 bytes of scratch each fill a huge page. */
#define CHUNK_CORNERS ((size_t)3 * 24966)
/* Partitions per thread: pass B's tasks are claimed as threads come, so
 * one thread that the system keeps waiting holds up a quarter of a pass,
 * not half of it (or more). */
#define PARTS_PER_THREAD 4
/* Each partition's cache of recent vertices: it sees one corner in
 * (threads x PARTS_PER_THREAD), so it needs fewer slots than the serial
 * welder's 4096 for the same reach. */
#define PART_RECENT 1024

#define EMPTY UINT64_MAX
#define TAG 0xffffffff00000000ull
#define NONE SIZE_MAX

typedef struct recent {
    uint64_t h;
    uint32_t c;
} recent;

typedef struct part {
    uint64_t *table; /* hash tag << 32 | the first corner at that position */
    size_t cap, count;
    int failed;      /* out of memory growing the table */
    int own;         /* table is a block of its own (grown), not in job.tables */
    recent *rec;     /* PART_RECENT slots like the serial welder's cache of
                        recent vertices (mesh.h): a vertex comes back a few
                        facets later */
} part;

typedef struct chunk {
    size_t c0, nc, len;
} chunk;

typedef struct job {
    lam_team *team;
    const unsigned char *data;
    lam_mesh *m;
    size_t c0, nc;   /* the chunk: corners c0 .. c0 + nc - 1 of the file */
    uint64_t *h;     /* per corner of the chunk: its hash */
    uint32_t *fx;    /* 3 per corner of the chunk: its coordinates' bits (zero_bits) */
    uint32_t *first; /* per corner of the chunk: the first corner at its position */
    uint32_t *idx;   /* the chunk's corners by range, then partition (pass A) */
    size_t *ps, *pe; /* nr x np: where range r's list for partition k starts and ends in idx */
    size_t nrc;      /* ranges in this chunk */
    unsigned np;     /* partitions of the table */
    part *parts;
    size_t nr, len;  /* ranges of corners (passes A, C, D) of len corners (a multiple of 3) */
    size_t *bad;     /* per range: the offset of its first non-finite float, or NONE */
    size_t *cnt;     /* np x nr: new corners of partition k in range r */
    size_t *base;    /* per range: its first new vertex */
    chunk prev;      /* the chunk before, for pass D */
    uint64_t *tables;/* the partitions' first tables, cap0 slots each */
    size_t cap0;
    recent *recs;    /* the partitions' caches, PART_RECENT each */
} job;

static const unsigned char *corner_at(const unsigned char *data, size_t c)
{
    return data + 84 + 50 * (c / 3) + 12 + 12 * (c % 3);
}

/* A float's bits with -0.0 made 0.0: equal bits, the same coordinate. */
static uint32_t zero_bits(uint32_t u) { return u == 0x80000000u ? 0 : u; }

static double bits_double(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The position of corner c, seen in an earlier chunk (its vertex's) or in
 * this one (fx). */
static void corner_pos(const job *j, size_t c, double xyz[3])
{
    if (c >= j->c0) {
        for (int k = 0; k < 3; k++) xyz[k] = bits_double(j->fx[3 * (c - j->c0) + (size_t)k]);
    } else {
        memcpy(xyz, j->m->xyz + 3 * (size_t)j->m->tris[c], 3 * sizeof *xyz);
    }
}

/* Is corner c (of an earlier chunk or this one) at the position fx[0..2]?
 * Compared as the serial welder compares: the floats widened to double,
 * which is one to one (they are finite), and -0.0 equal to 0.0. */
static inline int same_pos(const job *j, size_t c, const uint32_t *fx)
{
    if (c >= j->c0) {
        const uint32_t *q = j->fx + 3 * (c - j->c0);
        return q[0] == fx[0] && q[1] == fx[1] && q[2] == fx[2];
    }
    const double *q = j->m->xyz + 3 * (size_t)j->m->tris[c];
    return q[0] == bits_double(fx[0]) && q[1] == bits_double(fx[1]) && q[2] == bits_double(fx[2]);
}

static unsigned part_of(uint64_t h, unsigned np) { return (unsigned)((h >> 32) * np >> 32); }

static void pass_a(void *ctx, unsigned worker, size_t r)
{
    (void)worker;
    job *j = ctx;
    size_t lo = r * j->len, hi = lo + j->len < j->nc ? lo + j->len : j->nc;
    j->bad[r] = NONE;
    for (size_t i = lo; i < hi; i += 3) {
        const unsigned char *p = corner_at(j->data, j->c0 + i);
        double xyz[9];
        int bad = lam_stl_facet(p, xyz);
        if (bad >= 0) {
            j->bad[r] = (size_t)(p + 4 * bad - j->data);
            return;
        }
        for (int k = 0; k < 3; k++) j->h[i + (size_t)k] = lam_weld_hash(xyz + 3 * k);
        for (int k = 0; k < 9; k++) j->fx[3 * i + (size_t)k] = zero_bits(lam_rd_u32(p + 4 * k));
    }
    /* the range's corners listed by partition, each list in corner order:
     * pass B then reads only its own (a test per corner of which partition
     * it falls in is a branch mispredicted every other time) */
    size_t *ps = j->ps + r * j->np, *pe = j->pe + r * j->np;
    memset(pe, 0, j->np * sizeof *pe);
    for (size_t i = lo; i < hi; i++) pe[part_of(j->h[i], j->np)]++;
    size_t at = lo;
    for (unsigned k = 0; k < j->np; k++) {
        size_t n = pe[k];
        ps[k] = pe[k] = at;
        at += n;
    }
    for (size_t i = lo; i < hi; i++) j->idx[pe[part_of(j->h[i], j->np)]++] = (uint32_t)i;
}

static void part_put(part *pt, uint64_t h, uint64_t entry)
{
    size_t s = (size_t)h & (pt->cap - 1);
    while (pt->table[s] != EMPTY) s = (s + 1) & (pt->cap - 1);
    pt->table[s] = entry;
}

/* Partition k's first table and cache, made ready by the thread that
 * will use them (the page faults shared out). */
static void part_init(void *ctx, unsigned worker, size_t k)
{
    (void)worker;
    job *j = ctx;
    part *pt = &j->parts[k];
    pt->cap = j->cap0;
    pt->table = j->tables + k * j->cap0;
    memset(pt->table, 0xff, pt->cap * sizeof *pt->table);
    pt->rec = j->recs + k * PART_RECENT;
    for (size_t r = 0; r < PART_RECENT; r++) pt->rec[r] = (recent){ 0, UINT32_MAX };
}

static int part_grow(part *pt, const job *j, size_t cap)
{
    uint64_t *nt = lam_big_map(cap * sizeof *nt);
    if (!nt) return -1;
    memset(nt, 0xff, cap * sizeof *nt);
    uint64_t *old = pt->table;
    size_t oldcap = pt->cap;
    pt->table = nt;
    pt->cap = cap;
    for (size_t s = 0; s < oldcap; s++)
        if (old[s] != EMPTY) {
            double xyz[3];
            corner_pos(j, (uint32_t)old[s], xyz);
            part_put(pt, lam_weld_hash(xyz), old[s]);
        }
    if (pt->own) lam_big_unmap(old, oldcap * sizeof *old);
    pt->own = 1;
    return 0;
}

/* How far ahead pass B asks for a table slot. */
#define AHEAD 16

static void pass_b(void *ctx, unsigned worker, size_t k)
{
    (void)worker;
    job *j = ctx;
    part *pt = &j->parts[k];
    if (pt->failed) return;
    for (size_t r = 0; r < j->nrc; r++) {
        size_t a = j->ps[r * j->np + k], z = j->pe[r * j->np + k], fresh = 0;
        for (size_t q = a; q < z; q++) {
            if (q + AHEAD < z) LAM_PREFETCH(pt->table + ((size_t)j->h[j->idx[q + AHEAD]] & (pt->cap - 1)));
            size_t i = j->idx[q], c = j->c0 + i;
            uint64_t hv = j->h[i];
            const uint32_t *fx = j->fx + 3 * i;
            recent *rc = &pt->rec[(size_t)(hv >> 20) & (PART_RECENT - 1)];
            if (rc->h == hv && rc->c != UINT32_MAX && same_pos(j, rc->c, fx)) {
                j->first[i] = rc->c;
                continue;
            }
            uint64_t tag = hv & TAG;
            size_t s = (size_t)hv & (pt->cap - 1);
            for (;;) {
                uint64_t e = pt->table[s];
                if (e == EMPTY) {
                    pt->table[s] = tag | c;
                    *rc = (recent){ hv, (uint32_t)c };
                    j->first[i] = (uint32_t)c;
                    fresh++;
                    if (2 * ++pt->count > pt->cap && part_grow(pt, j, 2 * pt->cap)) {
                        pt->failed = 1;
                        return;
                    }
                    break;
                }
                if ((e & TAG) == tag && same_pos(j, (uint32_t)e, fx)) {
                    *rc = (recent){ hv, (uint32_t)e };
                    j->first[i] = (uint32_t)e;
                    break;
                }
                s = (s + 1) & (pt->cap - 1);
            }
        }
        j->cnt[k * j->nr + r] = fresh;
    }
}

static void pass_c(void *ctx, unsigned worker, size_t r)
{
    (void)worker;
    job *j = ctx;
    size_t lo = r * j->len, hi = lo + j->len < j->nc ? lo + j->len : j->nc;
    size_t v = j->base[r];
    uint32_t *tris = j->m->tris;
    for (size_t i = lo; i < hi; i++) {
        size_t c = j->c0 + i;
        if (j->first[i] != c) continue;
        tris[c] = (uint32_t)v;
        corner_pos(j, c, j->m->xyz + 3 * v);
        v++;
    }
}

/* Pass D of the chunk before (its c0, nc and len in j->prev), then pass A
 * of this one: the two touch different arrays. */
static void pass_da(void *ctx, unsigned worker, size_t r)
{
    job *j = ctx;
    const chunk *d = &j->prev;
    if (r * d->len < d->nc) {
        size_t lo = r * d->len, hi = lo + d->len < d->nc ? lo + d->len : d->nc;
        uint32_t *tris = j->m->tris;
        for (size_t i = lo; i < hi; i++) {
            size_t c = d->c0 + i;
            if (j->first[i] != c) tris[c] = tris[j->first[i]];
        }
    }
    if (r * j->len < j->nc) pass_a(ctx, worker, r);
}

int lam_stl_nonfinite(const char *path, const unsigned char *data, size_t off, lam_error *err)
{
    size_t facet = (off - 84) / 50, word = (off - 84 - 50 * facet - 12) / 4;
    uint32_t u = lam_rd_u32(data + off);
    float f;
    memcpy(&f, &u, sizeof f);
    return lam_error_at_offset(err, LAM_EINVAL, path, (long long)off,
                               "facet %zu, vertex %d: %c coordinate is not a finite number (%g)", facet + 1,
                               (int)(word / 3) + 1, "xyz"[word % 3], (double)f);
}

static void set_chunk(job *j, size_t c0, size_t ncorners)
{
    j->c0 = c0;
    j->nc = c0 >= ncorners ? 0 : ncorners - c0 < CHUNK_CORNERS ? ncorners - c0 : CHUNK_CORNERS;
    /* whole facets per range, every range but the last full */
    j->len = j->nc ? 3 * ((j->nc / 3 + j->nr - 1) / j->nr) : 1;
}

static int run(job *j, uint32_t count, const char *path, lam_error *err)
{
    lam_mesh *m = j->m;
    size_t ncorners = 3 * (size_t)count;
    j->prev = (chunk){ 0, 0, 1 };
    for (set_chunk(j, 0, ncorners);; set_chunk(j, j->c0 + j->nc, ncorners)) {
        lam_team_for(j->team, j->nr, pass_da, j);
        if (!j->nc) return LAM_OK;
        size_t nr = j->nrc = (j->nc + j->len - 1) / j->len;
        for (size_t r = 0; r < nr; r++)
            if (j->bad[r] != NONE) return lam_stl_nonfinite(path, j->data, j->bad[r], err);
        lam_team_for(j->team, j->np, pass_b, j);
        size_t v = m->nverts;
        for (size_t r = 0; r < nr; r++) {
            j->base[r] = v;
            for (unsigned k = 0; k < j->np; k++) v += j->cnt[k * j->nr + r];
        }
        for (unsigned k = 0; k < j->np; k++)
            if (j->parts[k].failed) return lam_error_nomem(err, "welding vertices");
        int rc = lam_mesh_reserve(m, v - m->nverts, 0, err);
        if (rc) return rc;
        lam_team_for(j->team, nr, pass_c, j);
        m->nverts = v;
        m->ntris = (j->c0 + j->nc) / 3;
        j->prev = (chunk){ j->c0, j->nc, j->len };
    }
}

int lam_stl_binary_team(const char *path, const unsigned char *data, uint32_t count, lam_mesh *m, lam_team *team,
                        lam_error *err)
{
    size_t ncorners = 3 * (size_t)count, per = ncorners < CHUNK_CORNERS ? ncorners : CHUNK_CORNERS;
    /* a closed mesh has about half as many vertices as triangles */
    size_t expect = count / 2 + 16;
    int rc = lam_mesh_reserve(m, expect, count, err);
    if (rc) return lam_error_set(err, rc, path, 0, 0, "out of memory for %lu triangles", (unsigned long)count);
    job j = { .team = team, .data = data, .m = m, .np = PARTS_PER_THREAD * lam_team_size(team) };
    j.nr = j.np; /* ranges too: a few per thread */
    /* the scratch in one block: a chunk's fills one huge page */
    size_t scratch = per * (sizeof *j.h + 3 * sizeof *j.fx + sizeof *j.first + sizeof *j.idx);
    j.h = lam_big_map(scratch);
    j.parts = calloc(j.np, sizeof *j.parts);
    j.bad = malloc(j.nr * sizeof *j.bad);
    j.base = malloc(j.nr * sizeof *j.base);
    j.cnt = malloc(j.np * j.nr * sizeof *j.cnt);
    j.ps = malloc(j.np * j.nr * sizeof *j.ps);
    j.pe = malloc(j.np * j.nr * sizeof *j.pe);
    /* each partition sized as the serial welder sizes its table, with a
     * sixteenth for the partitions' uneven shares, all in one block (huge
     * pages) until one grows */
    size_t share = expect / j.np + expect / (16 * j.np) + 16;
    j.cap0 = 1024;
    while (j.cap0 < 2 * share) j.cap0 *= 2;
    j.tables = lam_big_map(j.np * j.cap0 * sizeof *j.tables);
    j.recs = malloc(j.np * PART_RECENT * sizeof *j.recs);
    if (!j.h || !j.parts || !j.bad || !j.base || !j.cnt || !j.ps || !j.pe || !j.tables || !j.recs) {
        rc = lam_error_nomem(err, "welding vertices");
    } else {
        j.fx = (uint32_t *)(j.h + per);
        j.first = j.fx + 3 * per;
        j.idx = j.first + per;
        lam_team_for(team, j.np, part_init, &j);
        rc = run(&j, count, path, err);
    }
    if (rc == LAM_ENOMEM) lam_error_set(err, rc, path, 0, 0, "out of memory for %lu triangles", (unsigned long)count);
    for (unsigned k = 0; j.parts && k < j.np; k++)
        if (j.parts[k].own) lam_big_unmap(j.parts[k].table, j.parts[k].cap * sizeof *j.tables);
    lam_big_unmap(j.tables, j.np * j.cap0 * sizeof *j.tables);
    free(j.recs);
    lam_big_unmap(j.h, scratch);
    free(j.parts);
    free(j.bad);
    free(j.base);
    free(j.cnt);
    free(j.ps);
    free(j.pe);
    /* every vertex came through the welder and is used */
    if (!rc) m->welded = 1;
    return rc;
}
