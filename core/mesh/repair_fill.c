/* Filling holes (repair.h, step 3): the open edges chained into loops,
 * each loop triangulated.
 *
 * A triangle t running a -> b along an open edge leaves the hole on that
 * edge's other side; the filling must run b -> a there to agree with t's
 * winding, so the loops are walked along reversed open edges. Where
 * several loops meet at one vertex (two holes touching at a corner) the
 * walk may come back to a vertex it has passed: the part since then is a
 * loop of its own and is cut off there, so every loop visits each vertex
 * once. A walk that cannot go on (open edges whose triangles disagree in
 * winding) is counted in holes_left and left open. */
#include "repair.h"
#include "repair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX

static int oom(lam_error *err) { return lam_error_nomem(err, "filling the model's holes"); }

typedef struct loops {
    uint32_t *hs, *he;   /* per open half-edge (reversed): start and end vertex */
    uint32_t *tri;       /* and the triangle it borders */
    uint32_t *first;     /* per vertex + 1: CSR of the half-edges starting there */
    uint32_t *out;       /* half-edge ids by start vertex */
    unsigned char *used;
    uint32_t *at;        /* per vertex: its place in the walk, NONE when not in it */
    uint32_t *path;
    size_t n;
} loops;

static void loops_free(loops *L)
{
    free(L->hs);
    free(L->he);
    free(L->tri);
    free(L->first);
    free(L->out);
    free(L->used);
    free(L->at);
    free(L->path);
}

/* The reversed open half-edges of md and their index by start vertex. */
static int loops_init(const lam_model *md, loops *L, lam_error *err)
{
    const lam_mesh *m = &md->mesh;
    const lam_edges *e = &md->edges;
    memset(L, 0, sizeof *L);
    size_t n = md->stats.boundary_edges, nv = m->nverts;
    L->hs = malloc((n + 1) * sizeof *L->hs);
    L->he = malloc((n + 1) * sizeof *L->he);
    L->tri = malloc((n + 1) * sizeof *L->tri);
    L->first = calloc(nv + 2, sizeof *L->first);
    L->out = malloc((n + 1) * sizeof *L->out);
    L->used = calloc(n + 1, 1);
    L->at = malloc((nv + 1) * sizeof *L->at);
    L->path = malloc((n + 1) * sizeof *L->path);
    if (!L->hs || !L->he || !L->tri || !L->first || !L->out || !L->used || !L->at || !L->path) return oom(err);
    for (size_t i = 0; i < e->n && L->n < n; i++) {
        if (e->first[i + 1] - e->first[i] != 1) continue;
        const uint32_t *tv = m->tris + 3 * (size_t)e->tris[e->first[i]];
        uint32_t a = e->v[2 * i], b = e->v[2 * i + 1];
        int forward = (tv[0] == a && tv[1] == b) || (tv[1] == a && tv[2] == b) || (tv[2] == a && tv[0] == b);
        L->hs[L->n] = forward ? b : a;
        L->he[L->n] = forward ? a : b;
        L->tri[L->n] = e->tris[e->first[i]];
        L->n++;
    }
    for (size_t k = 0; k < L->n; k++) L->first[L->hs[k] + 1]++;
    for (size_t v = 0; v < nv; v++) L->first[v + 1] += L->first[v];
    uint32_t *fill = L->first + 0;
    for (size_t k = 0; k < L->n; k++) L->out[fill[L->hs[k]]++] = (uint32_t)k;
    for (size_t v = nv; v > 0; v--) L->first[v] = L->first[v - 1];
    L->first[0] = 0;
    for (size_t v = 0; v < nv; v++) L->at[v] = NONE;
    return LAM_OK;
}

static uint32_t next_unused(const loops *L, uint32_t v)
{
    for (uint32_t j = L->first[v]; j < L->first[v + 1]; j++)
        if (!L->used[L->out[j]]) return L->out[j];
    return NONE;
}

typedef struct filler {
    const lam_model *md; /* the model as built: its shells */
    lam_mesh *m;
    lam_repair_report *r;
    uint32_t face;       /* the face record fill triangles belong to, or LAM_NO_NAME */
    uint32_t *ring;      /* scratch: the loop's vertices */
    double *w;           /* scratch for the triangulation */
    uint16_t *k;
    lam_fill_plan *plan;
    double dp_budget;    /* triangle costs the programme may still evaluate */
    double cross_budget; /* segment pairs the crossing test may still compare */
} filler;

/* What the whole fill may spend, whatever the file: a model of a million
 * open edges in loops of LAM_REPAIR_DP_MAX would otherwise cost 1e13
 * steps. Past the budget, loops go to the planar triangulation or the fan
 * (linearithmic), and crossing is no longer tested. About a second each. */
#define DP_BUDGET 4e8
#define CROSS_BUDGET 2e8

static const double *P(const lam_mesh *m, uint32_t v) { return m->xyz + 3 * (size_t)v; }

static double tri_area(const lam_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    int zero;
    return 0.5 * lam_tri_area2(P(m, a), P(m, b), P(m, c), &zero);
}

static int add_tri(filler *F, uint32_t a, uint32_t b, uint32_t c, double *area, lam_error *err)
{
    *area += tri_area(F->m, a, b, c);
    F->r->fill_triangles++;
    return lam_mesh_add_tri(F->m, a, b, c, F->face, err);
}

/* The cost of a triangle in the minimal-area fill: its area, and for a
 * needle (corners nearly in a line) a penalty as large as a small part of
 * its perimeter squared, so that a run of collinear rim vertices is joined
 * by triangles with area rather than by slivers of none. */
static double cost(const lam_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    double area = tri_area(m, a, b, c);
    double p = sqrt(lam_dist2(P(m, a), P(m, b))) + sqrt(lam_dist2(P(m, b), P(m, c))) + sqrt(lam_dist2(P(m, c), P(m, a)));
    return area < 1e-9 * p * p ? area + 1e-6 * p * p : area;
}

/* The triangulation of ring[0..n) of least total cost (Barequet and
 * Sharir's dynamic programme; planar or not). On a planar simple loop the
 * least area is the polygon's own, reached only by triangles inside it,
 * so the fill is a triangulation of the polygon. */
static int fill_dp(filler *F, size_t n, double *area, lam_error *err)
{
    double *W = F->w;
    uint16_t *K = F->k;
    const uint32_t *R = F->ring;
    for (size_t d = 2; d < n; d++)
        for (size_t i = 0; i + d < n; i++) {
            size_t j = i + d;
            double best = INFINITY;
            uint16_t bk = (uint16_t)(i + 1);
            for (size_t k = i + 1; k < j; k++) {
                double c = (k - i > 1 ? W[i * n + k] : 0) + (j - k > 1 ? W[k * n + j] : 0) +
                           cost(F->m, R[i], R[k], R[j]);
                if (c < best) best = c, bk = (uint16_t)k;
            }
            W[i * n + j] = best;
            K[i * n + j] = bk;
        }
    /* the chosen triangles, from (0, n-1) down, with an explicit stack */
    size_t *st = malloc(2 * n * sizeof *st);
    if (!st) return oom(err);
    size_t top = 0;
    st[top++] = 0;
    st[top++] = n - 1;
    int rc = LAM_OK;
    while (top && !rc) {
        size_t j = st[--top], i = st[--top];
        if (j - i < 2) continue;
        size_t k = K[i * n + j];
        rc = add_tri(F, R[i], R[(size_t)k], R[j], area, err);
        st[top++] = i;
        st[top++] = k;
        st[top++] = k;
        st[top++] = j;
    }
    free(st);
    return rc;
}

/* A fan from the loop's centroid: for loops too long for the programme
 * that GEOS could not triangulate in their plane either. */
static int fill_fan(filler *F, size_t n, double *area, lam_error *err)
{
    double c[3] = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) c[k] += P(F->m, F->ring[i])[k] / (double)n;
    uint32_t cv;
    int rc = lam_mesh_add_vertex(F->m, c[0], c[1], c[2], &cv, err);
    for (size_t i = 0; i < n && !rc; i++) rc = add_tri(F, F->ring[i], F->ring[(i + 1) % n], cv, area, err);
    return rc;
}

/* Does the loop cross itself seen along its Newell normal? O(n^2); loops
 * longer than a few thousand vertices are not checked. */
static int crosses_itself(const lam_mesh *m, const uint32_t *R, size_t n)
{
    if (n < 4) return 0;
    double nn[3] = { 0, 0, 0 };
    for (size_t i = 0; i < n; i++) {
        const double *a = P(m, R[i]), *b = P(m, R[(i + 1) % n]);
        nn[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nn[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nn[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    int ax = fabs(nn[0]) >= fabs(nn[1]) && fabs(nn[0]) >= fabs(nn[2]) ? 0 : fabs(nn[1]) >= fabs(nn[2]) ? 1 : 2;
    int u = (ax + 1) % 3, v = (ax + 2) % 3;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1) continue;
            const double *a = P(m, R[i]), *b = P(m, R[(i + 1) % n]), *c = P(m, R[j]), *d = P(m, R[(j + 1) % n]);
            double d1 = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
            double d2 = (b[u] - a[u]) * (d[v] - a[v]) - (b[v] - a[v]) * (d[u] - a[u]);
            double d3 = (d[u] - c[u]) * (a[v] - c[v]) - (d[v] - c[v]) * (a[u] - c[u]);
            double d4 = (d[u] - c[u]) * (b[v] - c[v]) - (d[v] - c[v]) * (b[u] - c[u]);
            if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 1;
        }
    return 0;
}

/* The loop's polygon in its plane (GEOS), else the fan. */
static int fill_plane(filler *F, size_t n, double *area, lam_error *err)
{
    size_t before = F->m->ntris, rl = n;
    int rc = lam_mesh_add_polygon(F->m, F->ring, &rl, 1, F->face, NULL);
    if (rc) {
        F->m->ntris = before;
        return rc == LAM_ENOMEM ? oom(err) : fill_fan(F, n, area, err);
    }
    for (size_t t = before; t < F->m->ntris; t++) {
        const uint32_t *v = F->m->tris + 3 * t;
        *area += tri_area(F->m, v[0], v[1], v[2]);
    }
    F->r->fill_triangles += F->m->ntris - before;
    return LAM_OK;
}

/* Note loop k's first triangle (the plan's record of what it made). */
static int plan_loop(lam_fill_plan *P, size_t first, lam_error *err)
{
    if (P->nloops + 2 > P->cap) {
        size_t cap = P->cap ? 2 * P->cap : 64;
        size_t *g = realloc(P->first, cap * sizeof *g);
        if (!g) return oom(err);
        P->first = g;
        P->cap = cap;
    }
    P->first[P->nloops++] = first;
    P->first[P->nloops] = first;
    return LAM_OK;
}

/* Fill the loop of the walk's half-edges path[j..len). */
static int fill_loop(filler *F, const loops *L, size_t j, size_t len, lam_error *err)
{
    size_t k = F->plan->nloops;
    int rc = plan_loop(F->plan, F->m->ntris, err);
    if (rc) return rc;
    int method = k < F->plan->nmethod ? F->plan->method[k] : LAM_FILL_DP;
    size_t n = len - j;
    uint32_t t0 = L->tri[L->path[j]];
    if (n == 3 && F->md->shells[F->md->tri_shell[t0]].ntris == 1) {
        /* a lone facet: filled, it would be a two-sided sliver of no
         * volume (a triangle soup would double); it stays open */
        F->r->holes_left++;
        return LAM_OK;
    }
    for (size_t i = 0; i < n; i++) F->ring[i] = L->hs[L->path[j + i]];
    F->r->holes++;
    F->r->hole_edges += n;
    double pairs = 0.5 * (double)n * (double)n, work = (double)n * (double)n * (double)n / 6;
    if (pairs <= F->cross_budget) {
        F->cross_budget -= pairs;
        F->r->crossing_loops += (size_t)crosses_itself(F->m, F->ring, n);
    }
    double area = 0;
    if (method == LAM_FILL_DP && n <= LAM_REPAIR_DP_MAX && work <= F->dp_budget) {
        F->dp_budget -= work;
        rc = fill_dp(F, n, &area, err);
    } else if (method != LAM_FILL_FAN) {
        rc = fill_plane(F, n, &area, err);
    } else {
        rc = fill_fan(F, n, &area, err);
    }
    F->plan->first[F->plan->nloops] = F->m->ntris;
    F->r->fill_area += area;
    if (area > F->r->largest_hole) F->r->largest_hole = area;
    return rc;
}

/* Walk from half-edge k, cutting off and filling every loop it closes. */
static int walk(filler *F, loops *L, uint32_t k, lam_error *err)
{
    size_t len = 0;
    uint32_t cur;
    L->at[L->hs[k]] = 0;
    L->path[len++] = k;
    L->used[k] = 1;
    cur = L->he[k];
    while (len) {
        if (L->at[cur] != NONE) {
            size_t j = L->at[cur];
            int rc = fill_loop(F, L, j, len, err);
            for (size_t i = j; i < len; i++) L->at[L->hs[L->path[i]]] = NONE;
            len = j;
            if (rc) return rc;
            if (!len) break;
        }
        uint32_t h = next_unused(L, cur);
        if (h == NONE) { /* a chain that does not close */
            F->r->holes_left++;
            for (size_t i = 0; i < len; i++) L->at[L->hs[L->path[i]]] = NONE;
            break;
        }
        L->at[cur] = (uint32_t)len;
        L->path[len++] = h;
        L->used[h] = 1;
        cur = L->he[h];
    }
    return LAM_OK;
}

int lam_repair_fill(lam_model *md, lam_fill_plan *plan, lam_repair_report *r, lam_error *err)
{
    loops L;
    plan->nloops = 0;
    filler F = { .md = md, .plan = plan, .m = &md->mesh, .r = r, .face = LAM_NO_NAME, .dp_budget = DP_BUDGET, .cross_budget = CROSS_BUDGET };
    int rc = loops_init(md, &L, err);
    size_t dp = L.n < LAM_REPAIR_DP_MAX ? L.n : LAM_REPAIR_DP_MAX;
    if (!rc) {
        F.ring = malloc((L.n + 1) * sizeof *F.ring);
        F.w = malloc((dp * dp + 1) * sizeof *F.w);
        F.k = malloc((dp * dp + 1) * sizeof *F.k);
        if (!F.ring || !F.w || !F.k) rc = oom(err);
    }
    if (!rc && md->mesh.tri_face) rc = lam_mesh_add_face(&md->mesh, "hole filled by repair", NULL, 0, 0, &F.face, err);
    for (size_t k = 0; k < L.n && !rc; k++)
        if (!L.used[k]) rc = walk(&F, &L, (uint32_t)k, err);
    loops_free(&L);
    free(F.ring);
    free(F.w);
    free(F.k);
    return rc;
}
