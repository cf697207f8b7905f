#include "contour.h"
#include "nest.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Signed area by the shoelace formula, measured from the first point (which
 * keeps the terms small) and summed with Neumaier's compensation: a thin
 * loop's terms cancel almost entirely, and its sign must not come from
 * the rounding of the sum. */
double lam_loop_area(const double *uv, size_t n)
{
    if (n < 3) return 0;
    double u0 = uv[0], v0 = uv[1], s = 0, comp = 0;
    double au = uv[2] - u0, av = uv[3] - v0;
    for (size_t i = 2; i < n; i++) {
        double bu = uv[2 * i] - u0, bv = uv[2 * i + 1] - v0;
        double d = au * bv - av * bu, t = s + d;
        comp += fabs(s) >= fabs(d) ? (s - t) + d : (d - t) + s;
        s = t;
        au = bu;
        av = bv;
    }
    return (s + comp) / 2;
}

/* The cross product of the edges a->b and b->c, or 0 when it is within
 * rounding of 0: b is then in line with a and c, on a straight run or at
 * the tip of a spike (the edges fold back onto each other). */
static double turn3(const double *a, const double *b, const double *c)
{
    double e1u = b[0] - a[0], e1v = b[1] - a[1], e2u = c[0] - b[0], e2v = c[1] - b[1];
    double x = e1u * e2v, y = e1v * e2u;
    return fabs(x - y) <= 8 * DBL_EPSILON * (fabs(x) + fabs(y)) ? 0 : x - y;
}

/* b can go: a repeat of a, or in line with a and c (a straight run or a
 * spike). */
static int removable(const double *a, const double *b, const double *c)
{
    return (a[0] == b[0] && a[1] == b[1]) || turn3(a, b, c) == 0;
}

size_t lam_loop_simplify(double *uv, size_t n)
{
    /* a stack of kept points; each new point first removes the points it
     * makes removable behind it */
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = uv + 2 * i;
        if (m && uv[2 * m - 2] == p[0] && uv[2 * m - 1] == p[1]) continue;
        while (m >= 2 && removable(uv + 2 * (m - 2), uv + 2 * (m - 1), p)) m--;
        if (m && uv[2 * m - 2] == p[0] && uv[2 * m - 1] == p[1]) continue; /* a spike's base */
        uv[2 * m] = p[0];
        uv[2 * m + 1] = p[1];
        m++;
    }
    /* the seam: the last point against the first two, the first against
     * the last and the second, until neither goes; h is the new start */
    size_t h = 0;
    while (m - h >= 3) {
        const double *first = uv + 2 * h, *second = uv + 2 * (h + 1);
        const double *last = uv + 2 * (m - 1), *before = uv + 2 * (m - 2);
        if ((last[0] == first[0] && last[1] == first[1]) || removable(before, last, first)) m--;
        else if (removable(last, first, second)) h++;
        else break;
    }
    if (h) memmove(uv, uv + 2 * h, 2 * (m - h) * sizeof *uv);
    return m - h;
}

/* Lowest, then leftmost, point. */
static size_t lowest_leftmost(const double *uv, size_t n)
{
    size_t best = 0;
    for (size_t i = 1; i < n; i++) {
        double v = uv[2 * i + 1], u = uv[2 * i];
        if (v < uv[2 * best + 1] || (v == uv[2 * best + 1] && u < uv[2 * best])) best = i;
    }
    return best;
}

static double turn_at(const double *uv, size_t n, size_t a)
{
    size_t p = (a + n - 1) % n, q = (a + 1) % n;
    double e1u = uv[2 * a] - uv[2 * p], e1v = uv[2 * a + 1] - uv[2 * p + 1];
    double e2u = uv[2 * q] - uv[2 * a], e2v = uv[2 * q + 1] - uv[2 * a + 1];
    return e1u * e2v - e1v * e2u;
}

double lam_contour_turn(const lam_layer *layer, const lam_contour *c)
{
    const double *uv = layer->uv + 2 * c->first;
    return turn_at(uv, c->n, lowest_leftmost(uv, c->n));
}

int lam_contour_contains(const lam_layer *layer, const lam_contour *c, double u, double v)
{
    const double *p = layer->uv + 2 * c->first;
    int in = 0;
    for (size_t i = 0, j = c->n - 1; i < c->n; j = i++) {
        double ui = p[2 * i], vi = p[2 * i + 1], uj = p[2 * j], vj = p[2 * j + 1];
        if ((vi > v) != (vj > v)) {
            double x = ui + (v - vi) * (uj - ui) / (vj - vi);
            if (x > u) in = !in;
        }
    }
    return in;
}

/* ---- degenerate loops ------------------------------------------------- */

/* A loop's box and size: coincident loops have the same of both. */
typedef struct twin_key {
    double box[4];
    size_t n, first, loop;
} twin_key;

static int cmp_twin_key(const void *a, const void *b)
{
    const twin_key *p = a, *q = b;
    if (p->n != q->n) return p->n < q->n ? -1 : 1;
    for (int k = 0; k < 4; k++)
        if (p->box[k] != q->box[k]) return p->box[k] < q->box[k] ? -1 : 1;
    return p->loop < q->loop ? -1 : p->loop > q->loop;
}

static int same_key(const twin_key *p, const twin_key *q)
{
    return p->n == q->n && !memcmp(p->box, q->box, sizeof p->box);
}

/* Do loops a and b (n points each) go through the same points in the same
 * cyclic order, forwards or backwards? */
static int coincident(const double *a, const double *b, size_t n)
{
    for (size_t j = 0; j < n; j++) {
        if (b[2 * j] != a[0] || b[2 * j + 1] != a[1]) continue;
        int fwd = 1, bwd = 1;
        for (size_t i = 1; i < n && (fwd || bwd); i++) {
            const double *p = a + 2 * i, *f = b + 2 * ((j + i) % n), *r = b + 2 * ((j + n - i) % n);
            fwd = fwd && f[0] == p[0] && f[1] == p[1];
            bwd = bwd && r[0] == p[0] && r[1] == p[1];
        }
        if (fwd || bwd) return 1;
    }
    return 0;
}

int lam_loops_tidy(lam_loops *L, double min_area, int cancel_twins, size_t *slivers, size_t *twins,
                   lam_error *err)
{
    size_t nl = L->nloops;
    if (nl == 0) return LAM_OK;
    twin_key *keys = malloc(nl * sizeof *keys);
    unsigned char *drop = calloc(nl, 1);
    if (!keys || !drop) {
        free(keys);
        free(drop);
        return lam_error_nomem(err, "assembling contours");
    }
    size_t nk = 0;
    for (size_t l = 0, off = 0; l < nl; off += L->len[l], l++) {
        const double *p = L->uv + 2 * off;
        size_t n = L->len[l];
        if (n < 3 || !(fabs(lam_loop_area(p, n)) > min_area)) {
            drop[l] = 1;
            (*slivers)++;
            continue;
        }
        if (!cancel_twins) continue;
        twin_key *k = &keys[nk++];
        k->box[0] = k->box[2] = p[0];
        k->box[1] = k->box[3] = p[1];
        for (size_t i = 1; i < n; i++) {
            if (p[2 * i] < k->box[0]) k->box[0] = p[2 * i];
            if (p[2 * i] > k->box[2]) k->box[2] = p[2 * i];
            if (p[2 * i + 1] < k->box[1]) k->box[1] = p[2 * i + 1];
            if (p[2 * i + 1] > k->box[3]) k->box[3] = p[2 * i + 1];
        }
        k->n = n;
        k->first = off;
        k->loop = l;
    }
    /* Coincident loops cancel in pairs (see contour.h): candidates share
     * their point count and box, so sorting by those brings them together */
    if (nk > 1) {
        qsort(keys, nk, sizeof *keys, cmp_twin_key);
        for (size_t g = 0, e; g < nk; g = e) {
            for (e = g + 1; e < nk && same_key(&keys[g], &keys[e]);) e++;
            for (size_t i = g; i < e; i++) {
                if (drop[keys[i].loop]) continue;
                for (size_t j = i + 1; j < e; j++) {
                    if (drop[keys[j].loop] ||
                        !coincident(L->uv + 2 * keys[i].first, L->uv + 2 * keys[j].first, keys[i].n))
                        continue;
                    drop[keys[i].loop] = drop[keys[j].loop] = 1;
                    *twins += 2;
                    break;
                }
            }
        }
    }
    /* compact: kept loops move forward */
    size_t kept = 0, at = 0;
    for (size_t l = 0, off = 0; l < nl; off += L->len[l], l++) {
        if (drop[l]) continue;
        size_t n = L->len[l];
        if (at != off) memmove(L->uv + 2 * at, L->uv + 2 * off, 2 * n * sizeof *L->uv);
        L->len[kept++] = n;
        at += n;
    }
    L->nloops = kept;
    L->npoints = at;
    free(keys);
    free(drop);
    return LAM_OK;
}

/* ---- nesting ------------------------------------------------------------ */

/* The loop's nesting is decided at a point strictly inside it, a hair into
 * the corner at its lowest-leftmost vertex (always convex), along the sum
 * of the unit vectors to its neighbours. A vertex itself may lie on
 * another loop: a hole whose sides run along the outline around it (the
 * thesis's through hole cut lengthwise) would then miss the crossing.
 * The hair is a millionth of the loop's size, and the neighbours that set
 * the direction are the first points beyond four hairs either way: a
 * zigzag or a near-repeated point at the vertex (unwelded meshes, two
 * shells touching at a corner up to rounding) must not put the point
 * within rounding of the vertex, where a touching loop may be. */
static void inner_point(const double *uv, size_t n, size_t a, double q[2])
{
    const double *A = uv + 2 * a;
    q[0] = A[0];
    q[1] = A[1];
    double umin = A[0], umax = A[0], vmin = A[1], vmax = A[1];
    for (size_t i = 0; i < n; i++) {
        if (uv[2 * i] < umin) umin = uv[2 * i];
        if (uv[2 * i] > umax) umax = uv[2 * i];
        if (uv[2 * i + 1] < vmin) vmin = uv[2 * i + 1];
        if (uv[2 * i + 1] > vmax) vmax = uv[2 * i + 1];
    }
    double size = umax - umin > vmax - vmin ? umax - umin : vmax - vmin;
    /* small against the loop, large against rounding of its coordinates */
    double eps = 1e-6 * size, floor_eps = 1e-12 * (fabs(A[0]) + fabs(A[1]) + size);
    if (eps < floor_eps) eps = floor_eps;
    double lp = 0, ln = 0, pu = 0, pv = 0, nu = 0, nv = 0;
    for (size_t k = 1; k < n && lp <= 4 * eps; k++) {
        const double *P = uv + 2 * ((a + n - k) % n);
        pu = P[0] - A[0];
        pv = P[1] - A[1];
        lp = hypot(pu, pv);
    }
    for (size_t k = 1; k < n && ln <= 4 * eps; k++) {
        const double *N = uv + 2 * ((a + k) % n);
        nu = N[0] - A[0];
        nv = N[1] - A[1];
        ln = hypot(nu, nv);
    }
    if (!(lp > 0) || !(ln > 0)) return;
    double du = pu / lp + nu / ln, dv = pv / lp + nv / ln, dl = hypot(du, dv);
    if (!(dl > 0)) return;
    double most = (lp < ln ? lp : ln) / 4;
    if (eps > most) eps = most;
    q[0] = A[0] + eps * du / dl;
    q[1] = A[1] + eps * dv / dl;
}

/* ---- assembly ----------------------------------------------------------- */

typedef struct order_key {
    long parent;
    double v, u;
    uint32_t loop;
} order_key;

static int cmp_order(const void *a, const void *b)
{
    const order_key *p = a, *q = b;
    if (p->parent != q->parent) return p->parent < q->parent ? -1 : 1;
    if (p->v != q->v) return p->v < q->v ? -1 : 1;
    if (p->u != q->u) return p->u < q->u ? -1 : 1;
    return p->loop < q->loop ? -1 : p->loop > q->loop;
}

/* The nesting invariant: a parent is larger than its child
 * (lam_nest_larger), so following parents always ends, and no contour is
 * its own ancestor. Checked for every loop, whichever method nested. */
static int check_parents(const lam_nest_loop *li, size_t nl, lam_error *err)
{
    for (size_t l = 0; l < nl; l++) {
        long p = li[l].parent;
        if (p < -1 || p >= (long)nl || (p >= 0 && !lam_nest_larger(li, (size_t)p, l)))
            return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                                 "contour %zu of %zu has contour %ld as its parent, which is not larger "
                                 "(nesting would loop)", l, nl, p);
    }
    return LAM_OK;
}

/* Depth-first order into order[0..nl): each parent followed by its
 * children, siblings by their start point (lowest, then leftmost). keys
 * and stack are the caller's scratch of nl entries. */
static int tree_order(const lam_loops *L, const lam_nest_loop *li, const size_t *start, size_t nl, order_key *keys,
                      size_t *stack, size_t *order, lam_error *err)
{
    for (size_t l = 0; l < nl; l++) {
        keys[l].parent = li[l].parent;
        keys[l].v = L->uv[2 * (li[l].first + start[l]) + 1];
        keys[l].u = L->uv[2 * (li[l].first + start[l])];
        keys[l].loop = (uint32_t)l;
    }
    qsort(keys, nl, sizeof *keys, cmp_order);
    /* children of p occupy a contiguous run of keys; find runs by parent */
    size_t *run_first = calloc(nl + 1, sizeof *run_first), *run_len = calloc(nl + 1, sizeof *run_len);
    if (!run_first || !run_len) {
        free(run_first);
        free(run_len);
        return lam_error_nomem(err, "assembling contours");
    }
    for (size_t k = 0; k < nl; k++) {
        size_t slot = (size_t)(keys[k].parent + 1); /* 0: roots */
        if (run_len[slot]++ == 0) run_first[slot] = k;
    }
    size_t nout = 0, sp = 0;
    for (size_t k = run_len[0]; k-- > 0;) stack[sp++] = keys[run_first[0] + k].loop;
    while (sp) {
        size_t l = stack[--sp];
        order[nout++] = l;
        size_t slot = l + 1;
        for (size_t k = run_len[slot]; k-- > 0;) stack[sp++] = keys[run_first[slot] + k].loop;
    }
    free(run_first);
    free(run_len);
    return LAM_OK;
}

/* Write loop `in` (points src, lowest-leftmost at in_start) as contour c
 * at dst: from that point, in the direction its kind wants, with its
 * signed area, perimeter and bounding box. */
static void write_contour(lam_contour *c, const lam_nest_loop *in, size_t in_start, const double *src, double *dst)
{
    size_t n = in->n;
    /* The signed area decides the direction (SPEC 3.3). The thesis's
     * turn at the lowest-leftmost vertex agrees on a clean simple loop,
     * but one vertex sees only its two neighbours: a zigzag or
     * near-repeated point there turns the wrong way. */
    int ccw = in->area > 0;
    int want_ccw = c->kind == LAM_SOLID;
    for (size_t i = 0; i < n; i++) {
        /* start at the lowest-leftmost point, walk forward or backward */
        size_t j = ccw == want_ccw ? (in_start + i) % n : (in_start + n - i) % n;
        dst[2 * i] = src[2 * j];
        dst[2 * i + 1] = src[2 * j + 1];
    }
    c->area = ccw == want_ccw ? in->area : -in->area;
    c->perimeter = 0;
    c->bbox[0] = c->bbox[2] = dst[0];
    c->bbox[1] = c->bbox[3] = dst[1];
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        /* sqrt, not hypot: side lengths are nowhere near overflow, and
         * hypot's care costs a tenth of a layer's assembly */
        double du = dst[2 * j] - dst[2 * i], dv = dst[2 * j + 1] - dst[2 * i + 1];
        c->perimeter += sqrt(du * du + dv * dv);
        if (dst[2 * i] < c->bbox[0]) c->bbox[0] = dst[2 * i];
        if (dst[2 * i] > c->bbox[2]) c->bbox[2] = dst[2 * i];
        if (dst[2 * i + 1] < c->bbox[1]) c->bbox[1] = dst[2 * i + 1];
        if (dst[2 * i + 1] > c->bbox[3]) c->bbox[3] = dst[2 * i + 1];
    }
}

int lam_contours_assign(lam_layer *layer, const lam_loops *L, lam_error *err)
{
    free(layer->uv);
    free(layer->contours);
    layer->uv = NULL;
    layer->contours = NULL;
    layer->npoints = layer->ncontours = 0;
    size_t nl = L->nloops;
    if (nl == 0) return LAM_OK;

    lam_nest_loop *li = malloc(nl * sizeof *li);
    size_t *start = malloc(nl * sizeof *start);
    order_key *keys = malloc(nl * sizeof *keys);
    size_t *order = malloc(nl * sizeof *order);
    long *newidx = malloc(nl * sizeof *newidx);
    size_t *stack = malloc(nl * sizeof *stack);
    layer->uv = malloc(2 * L->npoints * sizeof *layer->uv);
    layer->contours = calloc(nl, sizeof *layer->contours);
    int rc = LAM_OK;
    if (!li || !start || !keys || !order || !newidx || !stack || !layer->uv || !layer->contours) {
        rc = lam_error_nomem(err, "assembling contours");
        goto done;
    }
    size_t off = 0;
    for (size_t l = 0; l < nl; l++) {
        li[l].first = off;
        li[l].n = L->len[l];
        start[l] = lowest_leftmost(L->uv + 2 * off, L->len[l]);
        li[l].area = lam_loop_area(L->uv + 2 * off, L->len[l]);
        inner_point(L->uv + 2 * off, L->len[l], start[l], li[l].q);
        off += L->len[l];
    }
    if ((rc = lam_nest(L->uv, li, nl, err)) || (rc = check_parents(li, nl, err)) ||
        (rc = tree_order(L, li, start, nl, keys, stack, order, err)))
        goto done;
    for (size_t k = 0; k < nl; k++) newidx[order[k]] = (long)k;

    size_t pos = 0;
    for (size_t k = 0; k < nl; k++) {
        const lam_nest_loop *in = &li[order[k]];
        lam_contour *c = &layer->contours[k];
        c->first = pos;
        c->n = in->n;
        c->depth = in->depth;
        c->kind = in->depth % 2 ? LAM_HOLE : LAM_SOLID;
        c->parent = in->parent >= 0 ? newidx[in->parent] : -1;
        write_contour(c, in, start[order[k]], L->uv + 2 * in->first, layer->uv + 2 * pos);
        pos += in->n;
    }
    layer->npoints = pos;
    layer->ncontours = nl;
done:
    free(li);
    free(start);
    free(keys);
    free(order);
    free(newidx);
    free(stack);
    if (rc) {
        free(layer->uv);
        free(layer->contours);
        layer->uv = NULL;
        layer->contours = NULL;
    }
    return rc;
}
