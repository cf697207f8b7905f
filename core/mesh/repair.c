/* Repair on load: the steps of repair.h. The model build (model_build.c)
 * does the exact weld and the orientation; this file adds what a model
 * with open or non-manifold edges needs before it can be sliced: the weld
 * within a tolerance, the removal of facets without area or repeated, and
 * the filling of the holes that remain (repair_fill.c). */
#include "repair.h"
#include "repair_internal.h"
#include "rays.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int oom(lam_error *err) { return lam_error_nomem(err, "repairing the model"); }

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

/* A grid cell key for the weld: coordinates in cells of the tolerance. */
typedef struct cell_item {
    int64_t c[3];
    uint32_t v;
} cell_item;

static int cell_cmp3(const int64_t *a, const int64_t *b)
{
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    return 0;
}

static int cmp_cell(const void *x, const void *y)
{
    const cell_item *a = x, *b = y;
    int c = cell_cmp3(a->c, b->c);
    return c ? c : (a->v > b->v) - (a->v < b->v);
}

/* The first item of the sorted cells at key c, or n. */
static size_t cell_lower(const cell_item *it, size_t n, const int64_t c[3])
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (cell_cmp3(it[mid].c, c) < 0) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}


/* Join the vertices of open edges that lie within tol of each other: each
 * such vertex is looked up in the 27 grid cells around it (cells of side
 * tol, so every partner within tol is found), and partners are united;
 * every vertex of a group becomes its lowest-numbered one. Sorting the
 * cells keeps it O(b log b) for b open-edge vertices and deterministic. */
static int weld_open(const lam_model *md, double tol, uint32_t *remap, size_t *welded, lam_error *err)
{
    const lam_mesh *m = &md->mesh;
    const lam_edges *e = &md->edges;
    for (size_t v = 0; v < m->nverts; v++) remap[v] = (uint32_t)v;
    *welded = 0;
    unsigned char *open = calloc(m->nverts + 1, 1);
    if (!open) return oom(err);
    size_t nb = 0;
    for (size_t i = 0; i < e->n; i++)
        if (e->first[i + 1] - e->first[i] == 1)
            for (int k = 0; k < 2; k++) nb += !open[e->v[2 * i + k]], open[e->v[2 * i + k]] = 1;
    cell_item *it = malloc((nb + 1) * sizeof *it);
    if (!it) {
        free(open);
        return oom(err);
    }
    size_t n = 0;
    for (size_t v = 0; v < m->nverts; v++) {
        if (!open[v]) continue;
        for (int k = 0; k < 3; k++) it[n].c[k] = (int64_t)floor(m->xyz[3 * v + k] / tol);
        it[n++].v = (uint32_t)v;
    }
    free(open);
    qsort(it, n, sizeof *it, cmp_cell);
    for (size_t i = 0; i < n; i++) {
        const double *p = m->xyz + 3 * (size_t)it[i].v;
        for (int d = 0; d < 27; d++) {
            int64_t c[3] = { it[i].c[0] + d % 3 - 1, it[i].c[1] + d / 3 % 3 - 1, it[i].c[2] + d / 9 - 1 };
            for (size_t j = cell_lower(it, n, c); j < n && !cell_cmp3(it[j].c, c); j++) {
                if (it[j].v >= it[i].v || lam_dist2(p, m->xyz + 3 * (size_t)it[j].v) > tol * tol) continue;
                uint32_t a = uf_find(remap, it[i].v), b = uf_find(remap, it[j].v);
                if (a == b) continue;
                if (a < b) remap[b] = a;
                else remap[a] = b;
                (*welded)++;
            }
        }
    }
    free(it);
    for (size_t v = 0; v < m->nverts; v++) remap[v] = uf_find(remap, (uint32_t)v);
    return LAM_OK;
}

typedef struct tri_key {
    uint32_t v[3];
    uint32_t t;
} tri_key;

static int cmp_tri_key(const void *x, const void *y)
{
    const tri_key *a = x, *b = y;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

static void sort3(uint32_t *v)
{
    uint32_t t;
    if (v[0] > v[1]) t = v[0], v[0] = v[1], v[1] = t;
    if (v[1] > v[2]) t = v[1], v[1] = v[2], v[2] = t;
    if (v[0] > v[1]) t = v[0], v[0] = v[1], v[1] = t;
}

/* Mark (keep[t] = 0) every triangle with the same three vertices as an
 * earlier one, in any order or winding: the file said one facet twice, and
 * the copy would make each of its edges non-manifold. */
static int mark_duplicates(const lam_mesh *m, unsigned char *keep, size_t *dups, lam_error *err)
{
    tri_key *k = malloc((m->ntris + 1) * sizeof *k);
    if (!k) return oom(err);
    for (size_t t = 0; t < m->ntris; t++) {
        memcpy(k[t].v, m->tris + 3 * t, sizeof k[t].v);
        sort3(k[t].v);
        k[t].t = (uint32_t)t;
    }
    qsort(k, m->ntris, sizeof *k, cmp_tri_key);
    *dups = 0;
    for (size_t i = 1; i < m->ntris; i++)
        if (!memcmp(k[i].v, k[i - 1].v, sizeof k[i].v) && keep[k[i].t]) keep[k[i].t] = 0, (*dups)++;
    free(k);
    return LAM_OK;
}

/* Has triangle t no area (lam_tri_area2's exact test, the model's own)? */
static int no_area(const lam_mesh *m, size_t t)
{
    int zero;
    lam_tri_area2(m->xyz + 3 * (size_t)m->tris[3 * t], m->xyz + 3 * (size_t)m->tris[3 * t + 1],
                  m->xyz + 3 * (size_t)m->tris[3 * t + 2], &zero);
    return zero;
}

/* Does triangle t have an edge no other triangle shares? */
static int has_open_edge(const lam_model *md, size_t t)
{
    const lam_edges *e = &md->edges;
    for (int k = 0; k < 3; k++) {
        uint32_t id = e->tri_edge[3 * t + (size_t)k];
        if (e->first[id + 1] - e->first[id] == 1) return 1;
    }
    return 0;
}

/* Steps 1 and 2 of repair.h on md's mesh, in place: the weld within tol,
 * then facets that collapsed, that have no area and an open edge (a
 * needle at a hole's rim; one inside a closed surface is left, since
 * taking it out would open the surface), and repeats. */
static int weld_and_clean(lam_model *md, double tol, lam_repair_report *r, lam_error *err)
{
    lam_mesh *m = &md->mesh;
    uint32_t *remap = malloc((m->nverts + 1) * sizeof *remap);
    unsigned char *keep = malloc(m->ntris + 1);
    int rc = !remap || !keep ? oom(err) : weld_open(md, tol, remap, &r->welded, err);
    if (rc) goto done;
    for (size_t t = 0; t < m->ntris; t++) {
        keep[t] = !no_area(m, t) || !has_open_edge(md, t);
        for (int k = 0; k < 3; k++) m->tris[3 * t + k] = remap[m->tris[3 * t + k]];
        const uint32_t *v = m->tris + 3 * t;
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) keep[t] = 0;
        r->degenerate += !keep[t];
    }
    if ((rc = mark_duplicates(m, keep, &r->duplicates, err))) goto done;
    size_t out = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        if (!keep[t]) continue;
        memmove(m->tris + 3 * out, m->tris + 3 * t, 3 * sizeof *m->tris);
        if (m->tri_face) m->tri_face[out] = m->tri_face[t];
        out++;
    }
    m->ntris = out;
    m->welded = 0; /* vertices merged away are no longer used */
done:
    free(remap);
    free(keep);
    return rc;
}

static double diagonal(const lam_model *md)
{
    const double *b = md->stats.bbox;
    return sqrt((b[3] - b[0]) * (b[3] - b[0]) + (b[4] - b[1]) * (b[4] - b[1]) + (b[5] - b[2]) * (b[5] - b[2]));
}

/* Build a new model from md's mesh (which moves into it); md is freed
 * either way and *out is the new model or NULL. */
static int rebuild(lam_model *md, lam_model **out, lam_error *err)
{
    int rc = lam_model_from_mesh(&md->mesh, md->path, md->format, out, err);
    lam_model_free(md);
    return rc;
}

static void count_left(const lam_model *md, lam_repair_report *r)
{
    r->boundary_edges = md->stats.boundary_edges;
    r->nonmanifold_edges = md->stats.nonmanifold_edges;
}

/* The self-intersections that remain, counted as the edges crossing a
 * facet where one of the two is from `first` on (the fills; rays.h), and
 * (crossed, may be NULL) the triangles involved.
 * Without Embree (it could not be loaded) the count is unknown and said
 * so; only running out of memory is an error. */
static int crossings(const lam_model *md, size_t first, lam_repair_report *r, unsigned char *crossed,
                     lam_error *err)
{
    lam_rays *v;
    lam_error e2;
    r->crossing_edges = 0;
    if (first >= md->mesh.ntris) return LAM_OK; /* nothing filled: nothing to look for */
    int rc = lam_rays_new(md, &v, &e2);
    if (rc) {
        r->crossings_unknown = 1;
        return rc == LAM_ENOMEM ? lam_error_nomem(err, "repairing the model") : LAM_OK;
    }
    rc = lam_rays_crossed_edges(v, first, &r->crossing_edges, crossed, &e2);
    lam_rays_free(v);
    if (rc == LAM_ELIMIT) r->crossings_unknown = 1; /* a part counted: said, not an error */
    else if (rc) return lam_error_nomem(err, "repairing the model");
    return LAM_OK;
}

/* One fill of md (which is kept: its mesh is truncated back after) into
 * the model *out, with the crossings counted and, per loop, whether its
 * fill crosses the surface (bad[k]). */
static int fill_once(lam_model *md, lam_fill_plan *plan, lam_repair_report *r, unsigned char **badp,
                     lam_model **out, lam_error *err)
{
    lam_mesh *m = &md->mesh;
    size_t nv = m->nverts, nt = m->ntris, nf = m->nfaces, ns = m->strings_len;
    int rc = lam_repair_fill(md, plan, r, err);
    lam_mesh filled;
    if (!rc) rc = lam_mesh_copy(m, &filled, err);
    m->nverts = nv, m->ntris = nt, m->nfaces = nf, m->strings_len = ns;
    if (rc) return rc;
    if ((rc = lam_model_from_mesh(&filled, md->path, md->format, out, err))) return rc;
    unsigned char *crossed = calloc((*out)->mesh.ntris + 1, 1);
    unsigned char *bad = realloc(*badp, plan->nloops + 1);
    if (bad) *badp = bad;
    if (!crossed || !bad) {
        free(crossed);
        return lam_error_nomem(err, "repairing the model");
    }
    rc = crossings(*out, plan->nloops ? plan->first[0] : (*out)->mesh.ntris, r, crossed, err);
    /* the build keeps the triangles' order (nothing in a fill collapses):
     * the plan's ranges are the model's */
    int same = plan->nloops && (*out)->mesh.ntris == plan->first[plan->nloops]; /* no loop closed: no plan */
    for (size_t k = 0; k < plan->nloops; k++) {
        bad[k] = 0;
        for (size_t t = plan->first[k]; same && t < plan->first[k + 1] && !bad[k]; t++) bad[k] = crossed[t];
    }
    free(crossed);
    return rc;
}

/* Step 3 with its check: fill every loop; where a loop's fill crosses the
 * surface (the least-area fill of a scan's hole can fold through the rim's
 * other side), fill that loop again the next way (LAM_FILL_PLANE, then
 * LAM_FILL_FAN), at most twice. The fill kept is the last one, its
 * crossings counted. */
static int fill_checked(lam_model *md, lam_repair_report *r, lam_model **out, lam_error *err)
{
    lam_fill_plan plan;
    memset(&plan, 0, sizeof plan);
    lam_repair_report r0 = *r;
    unsigned char *bad = NULL;
    int rc = LAM_OK;
    *out = NULL;
    for (int round = 0; round < 3 && !rc; round++) {
        *r = r0;
        lam_model_free(*out);
        *out = NULL;
        if ((rc = fill_once(md, &plan, r, &bad, out, err))) break;
        int again = 0;
        if (!plan.method) {
            plan.method = calloc(plan.nloops + 1, 1);
            plan.nmethod = plan.method ? plan.nloops : 0;
        }
        for (size_t k = 0; k < plan.nloops && k < plan.nmethod; k++)
            if (bad[k] && plan.method[k] < LAM_FILL_FAN) plan.method[k]++, again = 1;
        if (!again) break;
    }
    free(bad);
    free(plan.method);
    free(plan.first);
    if (rc) {
        lam_model_free(*out);
        *out = NULL;
    }
    return rc;
}

/* Whether the file's facet order says which side is out: STL's and OBJ's
 * does (counter-clockwise seen from outside); Unigrafix's does not (SPEC
 * 2.1: the thesis's own sample mixes both), so its facets turned to agree
 * are the import's ordinary work, not a repair to report. */
static int winding_means(const char *format) { return !format || strcmp(format, "unigrafix") != 0; }

int lam_model_repair(lam_model **mdp, const lam_repair_opts *o, lam_error *err)
{
    lam_model *md = *mdp;
    lam_repair_report r;
    memset(&r, 0, sizeof r);
    r.ran = 1;
    int winding = winding_means(md->format);
    r.flipped = winding ? md->stats.flipped_tris : 0;
    if (md->stats.boundary_edges == 0 && md->stats.nonmanifold_edges == 0) {
        md->repair = r;
        return LAM_OK;
    }
    double size = diagonal(md);
    r.weld_tolerance = o && o->weld_tolerance > 0 ? o->weld_tolerance : 1e-6 * size;
    int rc = LAM_OK;
    if (r.weld_tolerance > 0 && isfinite(r.weld_tolerance)) rc = weld_and_clean(md, r.weld_tolerance, &r, err);
    if (!rc) rc = rebuild(md, mdp, err);
    else lam_model_free(md), *mdp = NULL;
    if (rc) return rc;
    md = *mdp;
    lam_model *filled = NULL;
    if (md->stats.boundary_edges) rc = fill_checked(md, &r, &filled, err);
    if (rc || filled) {
        lam_model_free(md);
        *mdp = md = filled;
    }
    if (rc) return rc;
    /* flips the second build made count too: a facet the weld joined to
     * its shell the other way round */
    r.flipped += winding ? md->stats.flipped_tris : 0;
    count_left(md, &r);
    md->repair = r;
    return LAM_OK;
}

static void add(char *buf, size_t size, size_t *at, const char *fmt, size_t n, const char *one, const char *many)
{
    if (!n || *at >= size) return;
    int k = snprintf(buf + *at, size - *at, "%s", *at ? ", " : "");
    if (k > 0) *at += (size_t)k;
    if (*at >= size) return;
    k = snprintf(buf + *at, size - *at, fmt, n, n == 1 ? one : many);
    if (k > 0) *at += (size_t)k;
}

int lam_repair_acted(const lam_repair_report *r)
{
#define NONZERO(f) || r->f
    return 0 LAM_REPAIR_COUNTS(NONZERO);
#undef NONZERO
}

const char *lam_repair_summary(const lam_repair_report *r, char *buf, size_t size)
{
    size_t at = 0;
    if (!size) return buf;
    buf[0] = 0;
    if (r->holes && at < size) {
        int k = snprintf(buf, size, "filled %zu hole%s (%zu boundary edge%s)", r->holes, r->holes == 1 ? "" : "s",
                         r->hole_edges, r->hole_edges == 1 ? "" : "s");
        if (k > 0) at = (size_t)k;
    }
    add(buf, size, &at, "%zu vert%s welded", r->welded, "ex", "ices");
    add(buf, size, &at, "%zu facet%s flipped", r->flipped, "", "s");
    add(buf, size, &at, "%zu degenerate facet%s removed", r->degenerate, "", "s");
    add(buf, size, &at, "%zu duplicate facet%s removed", r->duplicates, "", "s");
    add(buf, size, &at, "%zu hole%s crossing itself", r->crossing_loops, "", "s");
    add(buf, size, &at, "%zu hole%s left open", r->holes_left, "", "s");
    if (at >= size) at = size - 1;
    buf[at] = 0;
    return buf;
}
