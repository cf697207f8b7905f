/* The mesh's own cross-section area; see section.h. */
#include "section.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LEVEL 20

struct lam_section_index {
    const lam_model *m;
    lam_frame f;
    double *wuv;          /* per vertex: w, then u and v about the (u, v) box centre */
    double wlo, extent;
    int top;              /* deepest level */
    double size[MAX_LEVEL + 1]; /* bucket height at each level */
    uint32_t *first;      /* 2^(top+1) buckets (level L at 2^L - 1 + i) + 1 offsets into tris */
    uint32_t *tris;
    uint32_t *seen;       /* per shell: the query that last counted it */
    double *heights;      /* the vertices' w, sorted (lam_section_snap) */
    uint32_t query;
    int fork;             /* wuv, first and tris are another index's (lam_section_index_fork) */
    int shared_heights;   /* and so are heights */
};

/* Skips zero terms, as the slicer does, so heights along an axis are the
 * coordinates themselves, bit for bit. */
static double dot(const double *p, const double *a)
{
    double s = 0;
    for (int k = 0; k < 3; k++)
        if (a[k] != 0) s += p[k] * a[k];
    return s;
}

static double bucket_size(const lam_section_index *x, int level) { return x->size[level]; }

/* The bucket of a triangle spanning [a, b]: the deepest level whose buckets
 * are at least as tall as the triangle, the bucket holding its centre. */
static size_t bucket_of(const lam_section_index *x, double a, double b)
{
    int level = x->top;
    if (!(x->extent > 0)) level = 0;
    while (level > 0 && bucket_size(x, level) < b - a) level--;
    size_t n = (size_t)1 << level;
    double size = bucket_size(x, level);
    double q = size > 0 ? ((a + b) / 2 - x->wlo) / size : 0;
    size_t i = q > 0 ? (q < (double)n ? (size_t)q : n - 1) : 0;
    return n - 1 + i;
}

int lam_section_index_new(const lam_model *m, const lam_frame *f, lam_section_index **out, lam_error *err)
{
    *out = NULL;
    const lam_mesh *mesh = &m->mesh;
    lam_section_index *x = calloc(1, sizeof *x);
    if (!x) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory indexing the model's sections");
    x->m = m;
    x->f = *f;
    size_t T = mesh->ntris;
    while (x->top < MAX_LEVEL && ((size_t)1 << x->top) < T) x->top++;
    size_t nb = ((size_t)2 << x->top) - 1;
    x->wuv = malloc((3 * mesh->nverts + 1) * sizeof *x->wuv);
    x->first = calloc(nb + 1, sizeof *x->first);
    x->tris = malloc((T + 1) * sizeof *x->tris);
    x->seen = calloc(m->nshells + 1, sizeof *x->seen);
    if (!x->wuv || !x->first || !x->tris || !x->seen) {
        lam_section_index_free(x);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory indexing the model's sections");
    }
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t v = 0; v < mesh->nverts; v++) {
        const double *p = mesh->xyz + 3 * v;
        double c[3] = { dot(p, f->w), dot(p, f->u), dot(p, f->v) };
        for (int k = 0; k < 3; k++) {
            x->wuv[3 * v + k] = c[k];
            if (c[k] < lo[k]) lo[k] = c[k];
            if (c[k] > hi[k]) hi[k] = c[k];
        }
    }
    if (mesh->nverts) {
        /* (u, v) about the box centre: the cross products of Green's sum stay small */
        double cu = lo[1] + (hi[1] - lo[1]) / 2, cv = lo[2] + (hi[2] - lo[2]) / 2;
        for (size_t v = 0; v < mesh->nverts; v++) {
            x->wuv[3 * v + 1] -= cu;
            x->wuv[3 * v + 2] -= cv;
        }
        x->wlo = lo[0];
        x->extent = hi[0] - lo[0];
    }
    for (int l = 0; l <= MAX_LEVEL; l++) x->size[l] = ldexp(x->extent, -l);
    for (int pass = 0; pass < 2; pass++) {
        for (size_t t = 0; t < T; t++) {
            const uint32_t *tv = mesh->tris + 3 * t;
            double a = fmin(fmin(x->wuv[3 * tv[0]], x->wuv[3 * tv[1]]), x->wuv[3 * tv[2]]);
            double b = fmax(fmax(x->wuv[3 * tv[0]], x->wuv[3 * tv[1]]), x->wuv[3 * tv[2]]);
            size_t k = bucket_of(x, a, b);
            if (pass == 0) x->first[k + 1]++;
            else x->tris[x->first[k]++] = (uint32_t)t;
        }
        if (pass == 0) {
            for (size_t k = 0; k < nb; k++) x->first[k + 1] += x->first[k];
        } else {
            for (size_t k = nb; k > 0; k--) x->first[k] = x->first[k - 1];
            x->first[0] = 0;
        }
    }
    *out = x;
    return LAM_OK;
}

int lam_section_index_fork(const lam_section_index *x, lam_section_index **out, lam_error *err)
{
    *out = NULL;
    lam_section_index *y = malloc(sizeof *y);
    uint32_t *seen = calloc(x->m->nshells + 1, sizeof *seen);
    if (!y || !seen) {
        free(y);
        free(seen);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory indexing the model's sections");
    }
    *y = *x;
    y->seen = seen;
    y->query = 0;
    y->fork = 1;
    y->shared_heights = x->heights != NULL;
    *out = y;
    return LAM_OK;
}

void lam_section_index_free(lam_section_index *x)
{
    if (!x) return;
    if (!x->fork) {
        free(x->wuv);
        free(x->first);
        free(x->tris);
    }
    if (!x->shared_heights) free(x->heights);
    free(x->seen);
    free(x);
}

const lam_frame *lam_section_index_frame(const lam_section_index *x) { return &x->f; }

/* Neumaier's compensated sum: *s + *c is the running total. */
static void add(double *s, double *c, double v)
{
    double t = *s + v;
    if (fabs(*s) >= fabs(v)) *c += (*s - t) + v;
    else *c += (v - t) + *s;
    *s = t;
}

/* Where edge a-b meets the plane, computed from its lower-numbered end so
 * the two triangles of an edge get the same point. */
static void crossing(const lam_section_index *x, uint32_t a, uint32_t b, double h, double p[2])
{
    if (a > b) {
        uint32_t t = a;
        a = b;
        b = t;
    }
    const double *A = x->wuv + 3 * (size_t)a, *B = x->wuv + 3 * (size_t)b;
    double t = (h - A[0]) / (B[0] - A[0]);
    p[0] = A[1] + t * (B[1] - A[1]);
    p[1] = A[2] + t * (B[2] - A[2]);
}

void lam_section_measure_at(lam_section_index *x, double h, int below, lam_section_measure *out)
{
    memset(out, 0, sizeof *out);
    const lam_model *m = x->m;
    out->closed = m->stats.boundary_edges == 0 && m->stats.orientation_conflicts == 0;
    if (++x->query == 0) {
        memset(x->seen, 0, m->nshells * sizeof *x->seen);
        x->query = 1;
    }
    double area = 0, area_c = 0, per = 0, per_c = 0, rate = 0, rate_c = 0;
    for (int level = 0; level <= x->top; level++) {
        size_t n = (size_t)1 << level;
        double size = bucket_size(x, level);
        double q = size > 0 ? (h - x->wlo) / size : 0;
        /* bucket i holds triangles within [i - 1/2, i + 3/2] buckets */
        double qlo = ceil(q - 1.501), qhi = floor(q + 0.501);
        if (!(qhi >= 0) || qlo >= (double)n) continue;
        size_t i0 = qlo > 0 ? (size_t)qlo : 0, i1 = qhi < (double)n - 1 ? (size_t)qhi : n - 1;
        for (size_t k = n - 1 + i0; k <= n - 1 + i1; k++)
            for (uint32_t j = x->first[k]; j < x->first[k + 1]; j++) {
                uint32_t t = x->tris[j];
                const uint32_t *tv = m->mesh.tris + 3 * (size_t)t;
                int up[3], nup = 0;
                for (int c = 0; c < 3; c++) {
                    double w = x->wuv[3 * (size_t)tv[c]];
                    up[c] = w > h || (w == h && below);
                    nup += up[c];
                }
                if (nup == 0 || nup == 3) continue;
                double P[2] = { 0, 0 }, Q[2] = { 0, 0 };
                for (int c = 0; c < 3; c++) {
                    int d = (c + 1) % 3;
                    if (up[c] && !up[d]) crossing(x, tv[c], tv[d], h, P);
                    else if (!up[c] && up[d]) crossing(x, tv[c], tv[d], h, Q);
                }
                add(&area, &area_c, (P[0] * Q[1] - P[1] * Q[0]) / 2);
                double len = sqrt((Q[0] - P[0]) * (Q[0] - P[0]) + (Q[1] - P[1]) * (Q[1] - P[1]));
                add(&per, &per_c, len);
                const double *A = x->wuv + 3 * (size_t)tv[0], *B = x->wuv + 3 * (size_t)tv[1],
                             *C = x->wuv + 3 * (size_t)tv[2];
                double e1[3] = { B[0] - A[0], B[1] - A[1], B[2] - A[2] };
                double e2[3] = { C[0] - A[0], C[1] - A[1], C[2] - A[2] };
                /* the normal in (w, u, v) order: n_w = e1u e2v - e1v e2u, ... */
                double nw = e1[1] * e2[2] - e1[2] * e2[1];
                double nu = e1[2] * e2[0] - e1[0] * e2[2];
                double nv = e1[0] * e2[1] - e1[1] * e2[0];
                double side = sqrt(nu * nu + nv * nv);
                if (side > 0) add(&rate, &rate_c, len * fabs(nw) / side);
                out->segments++;
                uint32_t s = m->tri_shell ? m->tri_shell[t] : 0;
                if (s < m->nshells && x->seen[s] != x->query) {
                    x->seen[s] = x->query;
                    if (!m->shells[s].cavity) out->solid_shells++;
                }
            }
    }
    out->area = area + area_c;
    out->perimeter = per + per_c;
    out->rate = rate + rate_c;
}

double lam_section_loop_area(const double *uv, size_t n)
{
    double s = 0, c = 0;
    for (size_t i = 1; i + 1 < n; i++) {
        double ax = uv[2 * i] - uv[0], ay = uv[2 * i + 1] - uv[1];
        double bx = uv[2 * i + 2] - uv[0], by = uv[2 * i + 3] - uv[1];
        add(&s, &c, ax * by - ay * bx);
    }
    return (s + c) / 2;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int lam_section_snap(lam_section_index *x, double h, double tol, double *out, lam_error *err)
{
    *out = h;
    size_t n = x->m->mesh.nverts;
    if (!n) return LAM_OK;
    if (!x->heights) {
        x->heights = malloc(n * sizeof *x->heights);
        if (!x->heights) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory indexing the model's heights");
        for (size_t v = 0; v < n; v++) x->heights[v] = x->wuv[3 * v];
        qsort(x->heights, n, sizeof *x->heights, by_value);
    }
    /* the first height >= h, and the one before it */
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (x->heights[mid] < h) lo = mid + 1;
        else hi = mid;
    }
    double best = h, gap = tol;
    if (lo < n && x->heights[lo] - h <= gap) best = x->heights[lo], gap = x->heights[lo] - h;
    if (lo > 0 && h - x->heights[lo - 1] < gap) best = x->heights[lo - 1];
    *out = best;
    return LAM_OK;
}
