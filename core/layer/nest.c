/* Nesting of a layer's loops; see nest.h for the rule and the methods. */
#include "nest.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int oom(lam_error *err) { return lam_error_nomem(err, "classifying contours"); }

/* ---- each against each other ------------------------------------------- */

/* Parity of the crossings of loop o's edges with the ray from (u, v)
 * toward -u. */
static int crossings_left(const double *uv, const lam_nest_loop *o, double u, double v)
{
    const double *p = uv + 2 * o->first;
    int par = 0;
    for (size_t i = 0; i < o->n; i++) {
        size_t j = (i + 1) % o->n;
        double vi = p[2 * i + 1], vj = p[2 * j + 1];
        double lo = vi < vj ? vi : vj, hi = vi < vj ? vj : vi;
        if (!(lo <= v && v < hi)) continue;
        double x = p[2 * i] + (v - vi) * (p[2 * j] - p[2 * i]) / (vj - vi);
        if (x < u) par ^= 1;
    }
    return par;
}

static void nest_few(const double *uv, lam_nest_loop *li, size_t nl)
{
    for (size_t l = 0; l < nl; l++) {
        const double *q = li[l].q;
        li[l].depth = 0;
        li[l].parent = -1;
        double best = INFINITY;
        for (size_t o = 0; o < nl; o++) {
            if (o == l || !lam_nest_larger(li, o, l) || !crossings_left(uv, &li[o], q[0], q[1])) continue;
            li[l].depth++;
            double a = fabs(li[o].area);
            if (a < best) {
                best = a;
                li[l].parent = (long)o;
            }
        }
    }
}

/* ---- sweep testing every active edge ------------------------------------ */

typedef struct seg {
    double vmin, vmax;
    uint32_t loop, i; /* edge from point i to i+1 of its loop */
} seg;

typedef struct query {
    double u, v;
    uint32_t loop;
} query;

static int cmp_seg(const void *a, const void *b)
{
    const seg *p = a, *q = b;
    if (p->vmin != q->vmin) return p->vmin < q->vmin ? -1 : 1;
    if (p->loop != q->loop) return p->loop < q->loop ? -1 : 1;
    return p->i < q->i ? -1 : p->i > q->i;
}

static int cmp_query(const void *a, const void *b)
{
    const query *p = a, *q = b;
    if (p->v != q->v) return p->v < q->v ? -1 : 1;
    return p->loop < q->loop ? -1 : p->loop > q->loop;
}

static int nest_scan(const double *uv, lam_nest_loop *li, size_t nl, lam_error *err)
{
    size_t ns = 0;
    for (size_t l = 0; l < nl; l++) ns += li[l].n;
    seg *segs = malloc(ns * sizeof *segs + 1);
    query *qs = malloc(nl * sizeof *qs + 1);
    uint32_t *active = malloc(ns * sizeof *active + 1);
    unsigned char *parity = calloc(nl, 1);
    uint32_t *touched = malloc(nl * sizeof *touched + 1);
    if (!segs || !qs || !active || !parity || !touched) {
        free(segs); free(qs); free(active); free(parity); free(touched);
        return oom(err);
    }
    for (size_t l = 0, k = 0; l < nl; l++) {
        const double *p = uv + 2 * li[l].first;
        for (size_t i = 0; i < li[l].n; i++, k++) {
            size_t j = (i + 1) % li[l].n;
            double a = p[2 * i + 1], b = p[2 * j + 1];
            segs[k].vmin = a < b ? a : b;
            segs[k].vmax = a < b ? b : a;
            segs[k].loop = (uint32_t)l;
            segs[k].i = (uint32_t)i;
        }
        qs[l].u = li[l].q[0];
        qs[l].v = li[l].q[1];
        qs[l].loop = (uint32_t)l;
    }
    qsort(segs, ns, sizeof *segs, cmp_seg);
    qsort(qs, nl, sizeof *qs, cmp_query);
    size_t ins = 0, nact = 0;
    for (size_t k = 0; k < nl; k++) {
        const query *q = &qs[k];
        /* half-open rule: an edge spans q.v when vmin <= v < vmax */
        while (ins < ns && segs[ins].vmin <= q->v) active[nact++] = (uint32_t)ins++;
        size_t keep = 0, ntouched = 0;
        for (size_t a = 0; a < nact; a++) {
            const seg *s = &segs[active[a]];
            if (s->vmax <= q->v) continue; /* below every later query too */
            active[keep++] = active[a];
            if (s->loop == q->loop || s->vmin == s->vmax) continue;
            const double *p = uv + 2 * li[s->loop].first;
            size_t i = s->i, j = (i + 1) % li[s->loop].n;
            double ui = p[2 * i], vi = p[2 * i + 1], uj = p[2 * j], vj = p[2 * j + 1];
            double x = ui + (q->v - vi) * (uj - ui) / (vj - vi);
            if (x < q->u) {
                if (!parity[s->loop]) touched[ntouched++] = s->loop;
                parity[s->loop] ^= 1;
            }
        }
        nact = keep;
        lam_nest_loop *me = &li[q->loop];
        me->depth = 0;
        me->parent = -1;
        double best = INFINITY;
        for (size_t t = 0; t < ntouched; t++) {
            uint32_t o = touched[t];
            if (parity[o] && lam_nest_larger(li, o, q->loop)) {
                me->depth++;
                double a = fabs(li[o].area);
                if (a < best || (a == best && (long)o < me->parent)) {
                    best = a;
                    me->parent = (long)o;
                }
            }
            parity[o] = 0;
        }
    }
    free(segs); free(qs); free(active); free(parity); free(touched);
    return LAM_OK;
}

/* ---- sweep with a search tree ------------------------------------------- */

/* An edge directed upward (v0 < v1); s = +1 where its loop's inside lies to
 * its +u side (the inside begins there, reading along u), -1 where it ends. */
typedef struct tedge {
    double u0, v0, u1, v1;
    uint32_t loop;
    int s;
} tedge;

/* Edge i of a loop of n points p (area: its signed area) as a tedge;
 * 0 for a horizontal edge, which never counts. */
static int make_tedge(const double *p, size_t n, size_t i, uint32_t loop, double area, tedge *t)
{
    size_t j = (i + 1) % n;
    double vi = p[2 * i + 1], vj = p[2 * j + 1];
    if (vi == vj) return 0;
    int down = vj < vi;
    t->u0 = down ? p[2 * j] : p[2 * i];
    t->v0 = down ? vj : vi;
    t->u1 = down ? p[2 * i] : p[2 * j];
    t->v1 = down ? vi : vj;
    t->loop = loop;
    /* counter-clockwise: the inside is left of the way round, so +u of an
     * edge going down */
    t->s = (down != (area < 0)) ? 1 : -1;
    return 1;
}

/* > 0: point (u, v) lies on the -u side of e's line, < 0 the +u side.
 * With `tolerant`, 0 for a point on the line up to rounding: a vertex of
 * one loop lying on another loop's edge (touching loops, collinear sides)
 * must not be put on a side by the last bit of a product. */
static double side(const tedge *e, double u, double v, int tolerant)
{
    double a = (e->u1 - e->u0) * (v - e->v0), b = (e->v1 - e->v0) * (u - e->u0);
    double c = a - b;
    return tolerant && fabs(c) <= 64 * DBL_EPSILON * (fabs(a) + fabs(b)) ? 0 : c;
}

static double side_tol(const tedge *e, double u, double v) { return side(e, u, v, 1); }

/* The active edges as a treap ordered along u (edges of a section do not
 * cross, so the order holds while both are active), each node with the sum
 * of s over its subtree. Nodes are edge indices; -1 is none. */
typedef struct treap {
    const tedge *e;
    int32_t *left, *right, *up, *sum;
    uint32_t *prio;
    int32_t root;
} treap;

static int32_t tsum(const treap *t, int32_t x) { return x < 0 ? 0 : t->sum[x]; }

static void refresh(treap *t, int32_t x)
{
    t->sum[x] = tsum(t, t->left[x]) + tsum(t, t->right[x]) + t->e[x].s;
}

/* Rotate x above its parent. */
static void rotate_up(treap *t, int32_t x)
{
    int32_t p = t->up[x], g = t->up[p];
    if (t->left[p] == x) {
        t->left[p] = t->right[x];
        if (t->right[x] >= 0) t->up[t->right[x]] = p;
        t->right[x] = p;
    } else {
        t->right[p] = t->left[x];
        if (t->left[x] >= 0) t->up[t->left[x]] = p;
        t->left[x] = p;
    }
    t->up[p] = x;
    t->up[x] = g;
    if (g < 0) t->root = x;
    else if (t->left[g] == p) t->left[g] = x;
    else t->right[g] = x;
    refresh(t, p);
    refresh(t, x);
}

/* Is edge a left of edge b, both active at a's lower end? Touching edges
 * are ordered by where they go above it, collinear ones by index. */
static int left_of(const treap *t, int32_t a, int32_t b)
{
    const tedge *ea = &t->e[a], *eb = &t->e[b];
    double c = side_tol(eb, ea->u0, ea->v0);
    if (c == 0) c = side_tol(eb, ea->u1, ea->v1);
    if (c == 0) return a < b;
    return c > 0;
}

static void insert(treap *t, int32_t x)
{
    t->left[x] = t->right[x] = -1;
    t->sum[x] = t->e[x].s;
    int32_t p = -1, at = t->root;
    int went_left = 0;
    while (at >= 0) {
        p = at;
        went_left = left_of(t, x, at);
        at = went_left ? t->left[at] : t->right[at];
    }
    t->up[x] = p;
    if (p < 0) t->root = x;
    else if (went_left) t->left[p] = x;
    else t->right[p] = x;
    for (int32_t a = p; a >= 0; a = t->up[a]) t->sum[a] += t->e[x].s;
    while (t->up[x] >= 0 && t->prio[x] > t->prio[t->up[x]]) rotate_up(t, x);
}

static void erase(treap *t, int32_t x)
{
    /* down to at most one child, by rotating the weightier child up */
    while (t->left[x] >= 0 && t->right[x] >= 0) {
        int32_t c = t->prio[t->left[x]] > t->prio[t->right[x]] ? t->left[x] : t->right[x];
        rotate_up(t, c);
    }
    int32_t c = t->left[x] >= 0 ? t->left[x] : t->right[x], p = t->up[x];
    if (c >= 0) t->up[c] = p;
    if (p < 0) t->root = c;
    else if (t->left[p] == x) t->left[p] = c;
    else t->right[p] = c;
    for (int32_t a = p; a >= 0; a = t->up[a]) t->sum[a] -= t->e[x].s;
}

/* In-order neighbour of x on the `near` side (left: predecessor, right:
 * successor), -1 if none. */
static int32_t neighbour(const treap *t, int32_t x, const int32_t *near, const int32_t *far)
{
    if (near[x] >= 0) {
        x = near[x];
        while (far[x] >= 0) x = far[x];
        return x;
    }
    while (t->up[x] >= 0 && near[t->up[x]] == x) x = t->up[x];
    return t->up[x];
}

static int32_t before(const treap *t, int32_t x) { return neighbour(t, x, t->left, t->right); }
static int32_t after(const treap *t, int32_t x) { return neighbour(t, x, t->right, t->left); }

/* Do edges a and b cross properly (each strictly on both sides of the
 * other)? Touching at a point or along a line is not crossing. */
static int crosses(const treap *t, int32_t a, int32_t b)
{
    const tedge *ea = &t->e[a], *eb = &t->e[b];
    double s1 = side_tol(eb, ea->u0, ea->v0), s2 = side_tol(eb, ea->u1, ea->v1);
    double s3 = side_tol(ea, eb->u0, eb->v0), s4 = side_tol(ea, eb->u1, eb->v1);
    return ((s1 < 0 && s2 > 0) || (s1 > 0 && s2 < 0)) && ((s3 < 0 && s4 > 0) || (s3 > 0 && s4 < 0));
}

/* Sum of s over the edges strictly left of (u, v) (an edge through the
 * point does not count, as in the scan), and the nearest such edge. */
static int32_t left_sum(const treap *t, double u, double v, int32_t *nearest)
{
    int32_t acc = 0, at = t->root;
    *nearest = -1;
    while (at >= 0) {
        if (side(&t->e[at], u, v, 0) >= 0) {
            at = t->left[at];
        } else {
            acc += tsum(t, t->left[at]) + t->e[at].s;
            *nearest = at;
            at = t->right[at];
        }
    }
    return acc;
}

typedef struct event {
    double v;
    uint32_t what; /* kind << 30 | index: 0 erase edge, 1 insert edge, 2 query loop */
} event;

static int cmp_event(const void *a, const void *b)
{
    const event *p = a, *q = b;
    if (p->v != q->v) return p->v < q->v ? -1 : 1;
    return p->what < q->what ? -1 : p->what > q->what;
}

static uint32_t mix(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* The tree sweep's parents, from each loop's link (the nearest other loop
 * to its left) and whether its inside begins there (opens): the loop whose
 * inside begins just left of the point, or a loop beside it whose parent
 * it shares; then the depths must agree. state and stack are scratch
 * (state zeroed, stack nl long). 0 when the answers do not hold together. */
static int tree_parents(lam_nest_loop *li, size_t nl, const long *link, const unsigned char *opens,
                        unsigned char *state, long *stack)
{
    int good = 1;
    for (size_t l = 0; l < nl && good; l++) {
        size_t sp = 0;
        long at = (long)l;
        while (state[at] == 0 && link[at] >= 0 && !opens[at]) {
            state[at] = 1;
            stack[sp++] = at;
            at = link[at];
        }
        if (state[at] == 1) {
            good = 0; /* a cycle of loops beside each other */
            break;
        }
        if (state[at] == 0) { /* a root, or inside the loop it links to */
            li[at].parent = link[at];
            state[at] = 2;
        }
        long parent = li[at].parent;
        while (sp) {
            long x = stack[--sp];
            li[x].parent = parent;
            state[x] = 2;
        }
    }
    for (size_t l = 0; l < nl && good; l++) {
        long p = li[l].parent;
        good = p < 0 ? li[l].depth == 0 : li[l].depth == li[p].depth + 1 && lam_nest_larger(li, (size_t)p, l);
    }
    return good;
}

/* The tree sweep; *agreed = 0 when its answers do not hold together (the
 * caller then uses the scan). */
static int nest_tree(const double *uv, lam_nest_loop *li, size_t nl, int *agreed, lam_error *err)
{
    *agreed = 0;
    size_t np = 0;
    for (size_t l = 0; l < nl; l++) np += li[l].n;
    if (np >= (1u << 30) || nl >= (1u << 30)) return LAM_OK; /* event packing: leave it to the scan */
    tedge *e = malloc(np * sizeof *e + 1);
    event *ev = malloc((2 * np + nl) * sizeof *ev + 1);
    int32_t *arr = malloc(4 * np * sizeof *arr + 1);
    uint32_t *prio = malloc(np * sizeof *prio + 1);
    long *link = malloc(nl * sizeof *link + 1);         /* the nearest other loop to the left */
    unsigned char *opens = malloc(nl + 1);              /* ... whose inside begins there */
    unsigned char *state = calloc(nl + 1, 1);
    long *stack = malloc(nl * sizeof *stack + 1);
    size_t *efirst = malloc((nl + 1) * sizeof *efirst); /* loop l's edges: e[efirst[l] .. efirst[l + 1]) */
    if (!e || !ev || !arr || !prio || !link || !opens || !state || !stack || !efirst) {
        free(e); free(ev); free(arr); free(prio); free(link); free(opens); free(state); free(stack); free(efirst);
        return oom(err);
    }
    size_t ne = 0, nev = 0;
    for (size_t l = 0; l < nl; l++) {
        efirst[l] = ne;
        const double *p = uv + 2 * li[l].first;
        for (size_t i = 0; i < li[l].n; i++) {
            tedge *t = &e[ne];
            if (!make_tedge(p, li[l].n, i, (uint32_t)l, li[l].area, t)) continue;
            ev[nev++] = (event){ t->v1, (uint32_t)ne };
            ev[nev++] = (event){ t->v0, 1u << 30 | (uint32_t)ne };
            ne++;
        }
        ev[nev++] = (event){ li[l].q[1], 2u << 30 | (uint32_t)l };
    }
    efirst[nl] = ne;
    qsort(ev, nev, sizeof *ev, cmp_event);
    treap t = { e, arr, arr + np, arr + 2 * np, arr + 3 * np, prio, -1 };
    for (size_t k = 0; k < ne; k++) prio[k] = mix((uint32_t)k + 1);
    int good = 1;
    for (size_t k = 0; k < nev && good; k++) {
        uint32_t kind = ev[k].what >> 30, id = ev[k].what & ((1u << 30) - 1);
        /* The order along u holds only while no two edges cross: loops of
         * overlapping bodies (even-odd fill) do. Edges that cross are next
         * to each other just before they do (Shamos and Hoey), so every
         * pair made neighbours is tested; a crossing hands the layer to
         * the scan, which needs no order. */
        if (kind == 0) {
            int32_t p = before(&t, (int32_t)id), n = after(&t, (int32_t)id);
            erase(&t, (int32_t)id);
            if (p >= 0 && n >= 0 && crosses(&t, p, n)) good = 0;
        } else if (kind == 1) {
            insert(&t, (int32_t)id);
            int32_t p = before(&t, (int32_t)id), n = after(&t, (int32_t)id);
            if ((p >= 0 && crosses(&t, p, (int32_t)id)) || (n >= 0 && crosses(&t, (int32_t)id, n))) good = 0;
        } else {
            lam_nest_loop *me = &li[id];
            int32_t nearest;
            int32_t all = left_sum(&t, me->q[0], me->q[1], &nearest);
            /* its own edges left of the point, counted the same way */
            int32_t own = 0;
            for (size_t x = efirst[id]; x < efirst[id + 1]; x++)
                if (e[x].v0 <= me->q[1] && me->q[1] < e[x].v1 && side(&e[x], me->q[0], me->q[1], 0) < 0) own += e[x].s;
            me->depth = all - own;
            while (nearest >= 0 && e[nearest].loop == id) nearest = before(&t, nearest);
            link[id] = nearest >= 0 ? (long)e[nearest].loop : -1;
            opens[id] = nearest >= 0 && e[nearest].s > 0;
            if (me->depth < 0) good = 0;
        }
    }
    if (good) good = tree_parents(li, nl, link, opens, state, stack);
    *agreed = good;
    free(e); free(ev); free(arr); free(prio); free(link); free(opens); free(state); free(stack); free(efirst);
    return LAM_OK;
}

int lam_nest_method(const double *uv, lam_nest_loop *loops, size_t nloops, int method, int *agreed,
                    lam_error *err)
{
    if (agreed) *agreed = 1;
    if (method == 0) {
        nest_few(uv, loops, nloops);
        return LAM_OK;
    }
    if (method == 1) {
        int ok = 0, rc = nest_tree(uv, loops, nloops, &ok, err);
        if (agreed) *agreed = ok;
        if (rc || ok) return rc;
    }
    return nest_scan(uv, loops, nloops, err);
}

int lam_nest(const double *uv, lam_nest_loop *loops, size_t nloops, lam_error *err)
{
    return lam_nest_method(uv, loops, nloops, nloops <= LAM_NEST_FEW ? 0 : 1, NULL, err);
}
