/* Building a lam_model from a mesh: weld, edge table, shells, orientation,
 * cavities (enclose.h), measures. See model.h for the rules. Apart from
 * model.c (what enclose.c and the rays use of a model), so that the model
 * does not depend on the enclosure test that depends on it. */
#include "model.h"

#include "hugemem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "enclose.h"

#define NONE UINT32_MAX

static int oom(lam_error *err) { return lam_error_nomem(err, "building the model"); }

/* Drop triangles that repeat a vertex: they have no area and no edges of
 * their own, and would only confuse adjacency. Returns how many went. */
static size_t drop_collapsed(lam_mesh *m)
{
    size_t out = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        const uint32_t *v = m->tris + 3 * t;
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
        if (out != t) {
            memcpy(m->tris + 3 * out, v, 3 * sizeof *v);
            if (m->tri_face) m->tri_face[out] = m->tri_face[t];
        }
        out++;
    }
    size_t dropped = m->ntris - out;
    m->ntris = out;
    return dropped;
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

/* The edge table's triangles per edge (CSR: e->first, e->tris) from
 * e->tri_edge, and hdir[at] (may be NULL) for each: whether the triangle
 * runs along the edge from its lower vertex. */
static int edge_tris(const lam_mesh *m, lam_edges *e, unsigned char *hdir, lam_error *err)
{
    size_t n = e->n, nh = 3 * m->ntris;
    e->first = lam_big_calloc(n + 1, sizeof *e->first);
    e->tris = lam_big_malloc(nh * sizeof *e->tris + 1);
    if (!e->first || !e->tris) return oom(err);
    for (size_t i = 0; i < nh; i++) e->first[e->tri_edge[i] + 1]++;
    for (size_t i = 0; i < n; i++) e->first[i + 1] += e->first[i];
    uint32_t *fill = lam_big_malloc((n + 1) * sizeof *fill);
    if (!fill) return oom(err);
    memcpy(fill, e->first, (n + 1) * sizeof *fill);
    for (size_t i = 0; i < nh; i++) {
        uint32_t at = fill[e->tri_edge[i]]++;
        e->tris[at] = (uint32_t)(i / 3);
        /* hdir[at]: the triangle runs along the edge from its lower vertex */
        if (hdir) hdir[at] = m->tris[i] < m->tris[i % 3 == 2 ? i - 2 : i + 1];
    }
    free(fill);
    return LAM_OK;
}

/* The edge table. Half-edges are bucketed by their lower vertex (a
 * counting sort), and each vertex's few half-edges are matched by their
 * upper vertex: linear and cache-friendly, unlike a hash of all edges.
 * The bucket keeps each half-edge's upper vertex beside it, so matching
 * reads one array in order instead of jumping back into the triangles.
 * Edge ids follow the lower vertex, then first appearance. */
static int build_edges(const lam_mesh *m, lam_edges *e, unsigned char *hdir, lam_error *err)
{
    size_t nt = m->ntris, nv = m->nverts, nh = 3 * nt;
    uint32_t *first = lam_big_calloc(nv + 1, sizeof *first);
    uint32_t *he = lam_big_malloc(nh * sizeof *he + 1);
    uint32_t *hh = lam_big_malloc(nh * sizeof *hh + 1);
    e->v = lam_big_malloc(nh * 2 * sizeof *e->v + 1);
    e->tri_edge = lam_big_malloc(nh * sizeof *e->tri_edge + 1);
    if (!first || !he || !hh || !e->v || !e->tri_edge) {
        free(first);
        free(he);
        free(hh);
        return oom(err);
    }
    const uint32_t *tv = m->tris;
    for (size_t t = 0; t < nt; t++, tv += 3)
        for (int k = 0; k < 3; k++) {
            uint32_t a = tv[k], b = tv[k == 2 ? 0 : k + 1];
            first[(a < b ? a : b) + 1]++;
        }
    for (size_t v = 0; v < nv; v++) first[v + 1] += first[v];
    tv = m->tris;
    for (size_t t = 0; t < nt; t++, tv += 3)
        for (int k = 0; k < 3; k++) {
            uint32_t a = tv[k], b = tv[k == 2 ? 0 : k + 1];
            uint32_t at = first[a < b ? a : b]++;
            he[at] = (uint32_t)(3 * t + (size_t)k);
            hh[at] = a < b ? b : a;
        }
    for (size_t v = nv; v > 0; v--) first[v] = first[v - 1];
    first[0] = 0;
    size_t n = 0;
    for (size_t v = 0; v < nv; v++) {
        uint32_t s = first[v], z = first[v + 1];
        if (z - s > 16) {
            /* a vertex with many edges (a fan apex): sort instead of
             * matching pairwise, so the work stays O(d log d) */
            uint64_t *key = malloc((z - s) * sizeof *key);
            if (!key) {
                free(first);
                free(he);
                free(hh);
                return oom(err);
            }
            for (uint32_t j = s; j < z; j++) key[j - s] = (uint64_t)hh[j] << 32 | he[j];
            qsort(key, z - s, sizeof *key, cmp_u64);
            for (uint32_t j = 0; j < z - s; j++) {
                if (j == 0 || key[j] >> 32 != key[j - 1] >> 32) {
                    e->v[2 * n] = (uint32_t)v;
                    e->v[2 * n + 1] = (uint32_t)(key[j] >> 32);
                    n++;
                }
                e->tri_edge[(uint32_t)key[j]] = (uint32_t)(n - 1);
            }
            free(key);
            continue;
        }
        for (uint32_t j = s; j < z; j++) {
            uint32_t hi = hh[j], id = NONE;
            for (uint32_t k = s; k < j && id == NONE; k++)
                if (hh[k] == hi) id = e->tri_edge[he[k]];
            if (id == NONE) {
                id = (uint32_t)n++;
                e->v[2 * id] = (uint32_t)v;
                e->v[2 * id + 1] = hi;
            }
            e->tri_edge[he[j]] = id;
        }
    }
    free(first);
    free(he);
    free(hh);
    e->n = n;
    uint32_t *shrunk = realloc(e->v, 2 * n * sizeof *e->v + 1); /* ~1.5 edges per triangle, not 3 */
    if (shrunk) e->v = shrunk;
    return edge_tris(m, e, hdir, err);
}

/* Does triangle t traverse edge (a -> b) in that direction? */
static int tri_has_directed(const uint32_t *tv, uint32_t a, uint32_t b)
{
    return (tv[0] == a && tv[1] == b) || (tv[1] == a && tv[2] == b) || (tv[2] == a && tv[0] == b);
}

/* Reverse triangle t, keeping slot k of tri_edge the edge (t[k], t[k+1]):
 * (t0,t1,t2) -> (t0,t2,t1) turns the edges (01, 12, 20) into (02, 21, 10),
 * that is slots 0 and 2 swap. */
static void flip_tri(lam_mesh *m, lam_edges *e, size_t t)
{
    uint32_t tmp = m->tris[3 * t + 1];
    m->tris[3 * t + 1] = m->tris[3 * t + 2];
    m->tris[3 * t + 2] = tmp;
    tmp = e->tri_edge[3 * t];
    e->tri_edge[3 * t] = e->tri_edge[3 * t + 2];
    e->tri_edge[3 * t + 2] = tmp;
}

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]]; /* path halving */
        x = parent[x];
    }
    return x;
}

/* The usual case, done without a search: when the two triangles of every
 * manifold edge already run along it in opposite directions (hdir, from
 * build_edges), nothing is flipped, and the shells are the components of
 * a union-find over the edges in order. A root is always its component's
 * lowest triangle, so shells are numbered by their first triangle, as the
 * search numbers them. Returns 0, changing nothing, when some edge is
 * inconsistent: the search then decides the flips. */
static int consistent_shells(lam_model *md, const unsigned char *hdir, uint32_t *parent)
{
    const lam_edges *e = &md->edges;
    size_t nt = md->mesh.ntris;
    for (size_t t = 0; t < nt; t++) parent[t] = (uint32_t)t;
    for (size_t i = 0; i < e->n; i++) {
        uint32_t f = e->first[i];
        if (e->first[i + 1] - f != 2) continue;
        if (hdir[f] == hdir[f + 1]) return 0;
        uint32_t a = uf_find(parent, e->tris[f]), b = uf_find(parent, e->tris[f + 1]);
        if (a < b) parent[b] = a;
        else if (b < a) parent[a] = b;
    }
    /* parent[t] <= t throughout, so one pass upward flattens every path
     * (a parent below t already points at its root) and labels */
    size_t nshells = 0;
    for (size_t t = 0; t < nt; t++) {
        uint32_t r = parent[parent[t]];
        parent[t] = r;
        md->tri_shell[t] = r == t ? (uint32_t)nshells++ : md->tri_shell[r];
    }
    md->nshells = nshells;
    md->stats.orientation_conflicts = 0;
    return 1;
}

/* Shells are the components through manifold edges (exactly two triangles):
 * two solids that only touch along a non-manifold edge stay two shells, each
 * with its own orientation. Unless the file's orientation is already
 * consistent (consistent_shells), one breadth-first pass both labels the
 * shell and makes its winding consistent. */
static int build_shells(lam_model *md, const unsigned char *hdir, lam_error *err)
{
    lam_mesh *m = &md->mesh;
    lam_edges *e = &md->edges;
    size_t nt = m->ntris;
    md->tri_shell = malloc(nt * sizeof *md->tri_shell + 1);
    uint32_t *queue = malloc(nt * sizeof *queue + 1);
    if (!md->tri_shell || !queue) {
        free(queue);
        return oom(err);
    }
    if (hdir && consistent_shells(md, hdir, queue)) {
        free(queue);
        md->shells = calloc(md->nshells ? md->nshells : 1, sizeof *md->shells);
        return md->shells ? LAM_OK : oom(err);
    }
    for (size_t t = 0; t < nt; t++) md->tri_shell[t] = NONE;
    size_t nshells = 0, conflicts = 0, cap = 0, *flips = NULL;
    for (size_t seed = 0; seed < nt; seed++) {
        if (md->tri_shell[seed] != NONE) continue;
        if (nshells == cap) {
            size_t *g = realloc(flips, (cap = cap ? 2 * cap : 64) * sizeof *g);
            if (!g) {
                free(flips);
                free(queue);
                return oom(err);
            }
            flips = g;
        }
        flips[nshells] = 0;
        size_t head = 0, tail = 0;
        queue[tail++] = (uint32_t)seed;
        md->tri_shell[seed] = (uint32_t)nshells;
        while (head < tail) {
            uint32_t t = queue[head++];
            for (int k = 0; k < 3; k++) {
                /* Recompute the directed edge from the current (possibly
                 * flipped) vertex order. */
                const uint32_t *tv = m->tris + 3 * (size_t)t;
                uint32_t a = tv[k], b = tv[(k + 1) % 3];
                uint32_t eid = e->tri_edge[3 * (size_t)t + k];
                if (e->first[eid + 1] - e->first[eid] != 2) continue;
                uint32_t u = e->tris[e->first[eid]];
                if (u == t) u = e->tris[e->first[eid] + 1];
                const uint32_t *uv = m->tris + 3 * (size_t)u;
                int same_dir = tri_has_directed(uv, a, b);
                if (md->tri_shell[u] == NONE) {
                    if (same_dir) flip_tri(m, e, u), flips[nshells]++;
                    md->tri_shell[u] = (uint32_t)nshells;
                    queue[tail++] = u;
                } else if (same_dir && md->tri_shell[u] == md->tri_shell[t]) {
                    conflicts++;
                }
            }
        }
        nshells++;
    }
    free(queue);
    /* Each inconsistent edge was seen from both sides. */
    md->stats.orientation_conflicts = conflicts / 2;
    md->nshells = nshells;
    md->shells = calloc(nshells ? nshells : 1, sizeof *md->shells);
    if (!md->shells) {
        free(flips);
        return oom(err);
    }
    /* the search flips against the seed; the count against the shell's
     * majority is the smaller of that and the rest (outward_shells) */
    for (size_t s = 0; s < nshells; s++) md->shells[s].flipped = flips[s];
    free(flips);
    return LAM_OK;
}

/* Per shell: bbox, area and signed volume measured from a point of the
 * shell (keeps the sum well conditioned far from the origin). Returns how
 * many triangles have zero area. */
static size_t measure_shells(lam_model *md, double *ref, double *comp)
{
    size_t degenerate = 0;
    lam_mesh *m = &md->mesh;
    for (size_t s = 0; s < md->nshells; s++) {
        lam_shell *sh = &md->shells[s];
        for (int k = 0; k < 3; k++) {
            sh->bbox[k] = INFINITY;
            sh->bbox[k + 3] = -INFINITY;
        }
        ref[3 * s] = NAN;
    }
    for (size_t t = 0; t < m->ntris; t++) {
        lam_shell *sh = &md->shells[md->tri_shell[t]];
        double *r = ref + 3 * (size_t)md->tri_shell[t];
        const double *p[3];
        for (int k = 0; k < 3; k++) p[k] = m->xyz + 3 * (size_t)m->tris[3 * t + k];
        if (isnan(r[0])) memcpy(r, p[0], 3 * sizeof *r);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) {
                if (p[k][j] < sh->bbox[j]) sh->bbox[j] = p[k][j];
                if (p[k][j] > sh->bbox[j + 3]) sh->bbox[j + 3] = p[k][j];
            }
        double a[3], b[3], c[3];
        for (int j = 0; j < 3; j++) {
            a[j] = p[0][j] - r[j];
            b[j] = p[1][j] - r[j];
            c[j] = p[2][j] - r[j];
        }
        /* six times the volume, summed with Neumaier's compensation and
         * divided once at the end: exact for the usual grid coordinates */
        double d = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]);
        double s6 = sh->volume + d;
        comp[md->tri_shell[t]] += fabs(sh->volume) >= fabs(d) ? (sh->volume - s6) + d : (d - s6) + sh->volume;
        sh->volume = s6;
        int zero;
        sh->area += 0.5 * lam_tri_area2(p[0], p[1], p[2], &zero);
        degenerate += (size_t)zero;
        sh->ntris++;
    }
    for (size_t s = 0; s < md->nshells; s++)
        md->shells[s].volume = (md->shells[s].volume + comp[s]) / 6.0;
    return degenerate;
}

static void flip_shell(lam_model *md, size_t s)
{
    for (uint32_t i = md->shell_first[s]; i < md->shell_first[s + 1]; i++)
        flip_tri(&md->mesh, &md->edges, md->shell_tris[i]);
    md->shells[s].volume = -md->shells[s].volume;
}

static int index_shells(lam_model *md, lam_error *err)
{
    md->shell_first = calloc(md->nshells + 1, sizeof *md->shell_first);
    md->shell_tris = malloc(md->mesh.ntris * sizeof *md->shell_tris + 1);
    if (!md->shell_first || !md->shell_tris) return oom(err);
    for (size_t t = 0; t < md->mesh.ntris; t++) md->shell_first[md->tri_shell[t] + 1]++;
    for (size_t s = 0; s < md->nshells; s++) md->shell_first[s + 1] += md->shell_first[s];
    for (size_t t = 0; t < md->mesh.ntris; t++) {
        /* triangles are visited in order and shells are numbered by their
         * first triangle, so a running cursor per shell keeps them sorted */
        md->shell_tris[md->shell_first[md->tri_shell[t]]++] = (uint32_t)t;
    }
    for (size_t s = md->nshells; s > 0; s--) md->shell_first[s] = md->shell_first[s - 1];
    md->shell_first[0] = 0;
    return LAM_OK;
}

/* Measure the shells (volume, area; *zero_area: triangles without area)
 * and turn each outward by its signed volume. Errors: LAM_ENOMEM. */
static int outward_shells(lam_model *md, size_t *zero_area, lam_error *err)
{
    double *ref = malloc(3 * md->nshells * sizeof *ref);
    double *comp = calloc(md->nshells, sizeof *comp);
    if (!ref || !comp) {
        free(ref);
        free(comp);
        return oom(err);
    }
    *zero_area = measure_shells(md, ref, comp);
    free(ref);
    free(comp);
    for (size_t s = 0; s < md->nshells; s++)
        if (md->shells[s].volume < 0) flip_shell(md, s);
    return LAM_OK;
}

/* The counts and the bounding box of md's stats (volume, area and
 * cavities are counted as the shells are settled). */
static void count_stats(lam_model *md, size_t degenerate)
{
    lam_model_stats *st = &md->stats;
    const lam_mesh *m = &md->mesh;
    st->triangles = m->ntris;
    st->vertices = m->nverts;
    st->edges = md->edges.n;
    st->shells = md->nshells;
    st->wires = m->nwires;
    st->degenerate_tris = degenerate;
    for (size_t i = 0; i < md->edges.n; i++) {
        uint32_t k = md->edges.first[i + 1] - md->edges.first[i];
        if (k == 1) st->boundary_edges++;
        else if (k > 2) st->nonmanifold_edges++;
    }
    for (int j = 0; j < 3; j++) {
        st->bbox[j] = INFINITY;
        st->bbox[j + 3] = -INFINITY;
    }
    for (size_t v = 0; v < m->nverts; v++)
        for (int j = 0; j < 3; j++) {
            double x = m->xyz[3 * v + j];
            if (x < st->bbox[j]) st->bbox[j] = x;
            if (x > st->bbox[j + 3]) st->bbox[j + 3] = x;
        }
}

int lam_model_from_mesh(lam_mesh *mesh, const char *path, const char *format,
                        lam_model **out, lam_error *err)
{
    *out = NULL;
    lam_model *md = calloc(1, sizeof *md);
    if (!md) {
        lam_mesh_free(mesh);
        return oom(err);
    }
    md->mesh = *mesh;
    lam_mesh_init(mesh);
    md->format = format ? format : "mesh";
    md->path = strdup(path ? path : "");
    int rc;
    if (!md->path) {
        rc = oom(err);
        goto fail;
    }
    lam_mesh *m = &md->mesh;
    size_t collapsed = drop_collapsed(m);
    if (collapsed) m->welded = 0; /* their vertices may now be unused */
    if (m->ntris == 0) {
        rc = lam_error_set(err, LAM_EGEOM, path, 0, 0, "the model has no triangles (nothing to slice)");
        goto fail;
    }
    if ((rc = lam_mesh_weld(m, err))) goto fail;
    size_t welded_away = drop_collapsed(m); /* welding can make triangles collapse */
    collapsed += welded_away;
    if (m->ntris == 0) {
        rc = lam_error_set(err, LAM_EGEOM, path, 0, 0, "the model has no triangles with area");
        goto fail;
    }
    if (welded_away) {
        m->welded = 0;
        if ((rc = lam_mesh_weld(m, err))) goto fail; /* drop vertices only they used */
    }
    /* hdir is only a shortcut: without the memory for it the search runs */
    unsigned char *hdir = malloc(3 * m->ntris + 1);
    if ((rc = build_edges(m, &md->edges, hdir, err)) || (rc = build_shells(md, hdir, err))) {
        free(hdir);
        goto fail;
    }
    free(hdir);
    if ((rc = index_shells(md, err))) goto fail;

    size_t zero_area = 0;
    if ((rc = outward_shells(md, &zero_area, err)) || (rc = lam_count_enclosing(md, err))) goto fail;
    lam_model_stats *st = &md->stats;
    for (size_t s = 0; s < md->nshells; s++) {
        lam_shell *sh = &md->shells[s];
        sh->cavity = sh->enclosing % 2;
        if (sh->cavity) {
            flip_shell(md, s);
            st->cavities++;
        }
        st->volume += sh->volume;
        st->area += sh->area;
        if (sh->flipped > sh->ntris - sh->flipped) sh->flipped = sh->ntris - sh->flipped;
        st->flipped_tris += sh->flipped;
    }
    /* each coordinate is within LAM_COORD_MAX, but a sum over billions of
     * such triangles could still overflow */
    if (!isfinite(st->area) || !isfinite(st->volume)) {
        rc = lam_error_set(err, LAM_EGEOM, path, 0, 0,
                           "the model spans more than a double can measure (its %s overflows)",
                           isfinite(st->area) ? "volume" : "surface area");
        goto fail;
    }

    count_stats(md, collapsed + zero_area);
    *out = md;
    return LAM_OK;
fail:
    lam_model_free(md);
    return rc;
}
