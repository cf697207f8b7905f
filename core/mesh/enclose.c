/* Which shells enclose which; see enclose.h. */
#include "enclose.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rays.h"

/* Samples per inner shell. */
#define SAMPLES 9

/* Past this many winding-number terms (samples times triangles of the
 * shells around them) the pairwise test gives way to rays: some tens of
 * milliseconds. */
#define PAIRWISE_WORK 4e6

static int bbox_inside(const double *in, const double *out)
{
    for (int j = 0; j < 3; j++)
        if (in[j] < out[j] || in[j + 3] > out[j + 3]) return 0;
    return 1;
}

/* ---- candidate pairs ------------------------------------------------------ */

/* A bounding-volume tree over the shells that can enclose another: shells
 * in the order of their box centres along a Morton curve, cut in halves
 * down to leaves of at most LEAF shells, each node holding the box of its
 * shells. Memory is linear in the shells whatever their boxes (a grid
 * listing each box in every cell it covers is not: 2^20 stacked triangles
 * over 64x64 cells each made 2^32 entries), and a query visits only nodes
 * whose box holds the query box. A shell of one triangle is left out: the
 * solid angle of a triangle is below 2 pi, so its winding number stays
 * under 1/2 and it encloses nothing (a triangle soup thus costs nothing
 * here). */
#define LEAF 4

typedef struct node {
    double box[6];
    size_t first, count; /* a leaf: order[first .. first + count) */
    size_t right;        /* an inner node: its right child (the left is next) */
} node;

typedef struct tree {
    size_t *order;
    node *nodes;
    size_t nnodes;
} tree;

typedef struct keyed {
    uint64_t key;
    size_t shell;
} keyed;

static int by_key(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->key != y->key) return x->key < y->key ? -1 : 1;
    return x->shell < y->shell ? -1 : x->shell > y->shell;
}

/* 21 bits of x spread to every third bit. */
static uint64_t spread3(uint64_t x)
{
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

static void box_union(double *to, const double *b)
{
    for (int k = 0; k < 3; k++) {
        if (b[k] < to[k]) to[k] = b[k];
        if (b[k + 3] > to[k + 3]) to[k + 3] = b[k + 3];
    }
}

static size_t build(const lam_model *md, tree *t, size_t lo, size_t hi)
{
    size_t at = t->nnodes++;
    node *n = &t->nodes[at];
    memcpy(n->box, md->shells[t->order[lo]].bbox, sizeof n->box);
    if (hi - lo <= LEAF) {
        n->first = lo;
        n->count = hi - lo;
        for (size_t i = lo + 1; i < hi; i++) box_union(n->box, md->shells[t->order[i]].bbox);
        return at;
    }
    n->count = 0;
    size_t mid = lo + (hi - lo) / 2;
    build(md, t, lo, mid);
    size_t right = build(md, t, mid, hi);
    n = &t->nodes[at];
    n->right = right;
    box_union(n->box, t->nodes[at + 1].box);
    box_union(n->box, t->nodes[right].box);
    return at;
}

static void tree_free(tree *t)
{
    free(t->order);
    free(t->nodes);
}

static int tree_build(const lam_model *md, tree *t)
{
    memset(t, 0, sizeof *t);
    size_t ns = md->nshells, n = 0;
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t s = 0; s < ns; s++) {
        if (md->shells[s].ntris < 2) continue;
        n++;
        for (int k = 0; k < 3; k++) {
            double c = md->shells[s].bbox[k] / 2 + md->shells[s].bbox[k + 3] / 2;
            if (c < lo[k]) lo[k] = c;
            if (c > hi[k]) hi[k] = c;
        }
    }
    keyed *keys = malloc(n * sizeof *keys + 1);
    t->order = malloc(n * sizeof *t->order + 1);
    /* leaves hold at least LEAF / 2 shells once there is more than one, so
     * n + 1 nodes are enough */
    t->nodes = malloc((n + 1) * sizeof *t->nodes);
    if (!keys || !t->order || !t->nodes) {
        free(keys);
        tree_free(t);
        return LAM_ENOMEM;
    }
    n = 0;
    for (size_t s = 0; s < ns; s++) {
        if (md->shells[s].ntris < 2) continue;
        uint64_t key = 0;
        for (int k = 0; k < 3; k++) {
            double c = md->shells[s].bbox[k] / 2 + md->shells[s].bbox[k + 3] / 2;
            double f = hi[k] > lo[k] ? (c - lo[k]) / (hi[k] - lo[k]) * 2097151.0 : 0;
            key |= spread3(f > 0 ? f < 2097151.0 ? (uint64_t)f : 2097151 : 0) << k;
        }
        keys[n].key = key;
        keys[n++].shell = s;
    }
    qsort(keys, n, sizeof *keys, by_key);
    for (size_t i = 0; i < n; i++) t->order[i] = keys[i].shell;
    free(keys);
    if (n) build(md, t, 0, n);
    return LAM_OK;
}

/* The shells whose box holds shell s's box, one by one: init_query, then
 * next_candidate until it returns -1. */
typedef struct query {
    size_t stack[128]; /* the tree is balanced: its depth is log2 of the shells */
    size_t sp, leaf, in_leaf;
    int in;
} query;

static void init_query(const tree *t, query *q)
{
    q->sp = 0;
    q->in = 0;
    if (t->nnodes) q->stack[q->sp++] = 0;
}

static long next_candidate(const lam_model *md, const tree *t, size_t s, query *q)
{
    const double *b = md->shells[s].bbox;
    for (;;) {
        if (q->in) {
            const node *n = &t->nodes[q->leaf];
            while (q->in_leaf < n->count) {
                size_t o = t->order[n->first + q->in_leaf++];
                if (o != s && bbox_inside(b, md->shells[o].bbox)) return (long)o;
            }
            q->in = 0;
        }
        if (!q->sp) return -1;
        size_t at = q->stack[--q->sp];
        const node *n = &t->nodes[at];
        if (!bbox_inside(b, n->box)) continue;
        if (n->count) {
            q->leaf = at;
            q->in_leaf = 0;
            q->in = 1;
        } else {
            q->stack[q->sp++] = n->right;
            q->stack[q->sp++] = at + 1;
        }
    }
}

/* ---- pairwise ---------------------------------------------------------------- */

/* The sample triangles of shell s: up to SAMPLES, spread evenly over its
 * triangles. Returns how many. */
static int samples(const lam_model *md, size_t s, uint32_t tri[SAMPLES])
{
    size_t n = md->shell_first[s + 1] - md->shell_first[s], want = n < SAMPLES ? n : SAMPLES;
    size_t step = want ? n / want : 1;
    for (size_t k = 0; k < want; k++) tri[k] = md->shell_tris[md->shell_first[s] + k * step];
    return (int)want;
}

/* Does shell `outer` enclose shell `inner`? (See enclose.h.) */
static int shell_encloses(const lam_model *md, size_t outer, size_t inner)
{
    const lam_mesh *m = &md->mesh;
    uint32_t tri[SAMPLES];
    int ns = samples(md, inner, tri), in = 0, out = 0;
    for (int k = 0; k < ns; k++) {
        const uint32_t *tv = m->tris + 3 * (size_t)tri[k];
        double c[3];
        for (int j = 0; j < 3; j++)
            c[j] = (m->xyz[3 * (size_t)tv[0] + j] + m->xyz[3 * (size_t)tv[1] + j] + m->xyz[3 * (size_t)tv[2] + j]) / 3.0;
        double w = fabs(lam_model_shell_winding(md, outer, c));
        if (w > 0.75) in++;
        else if (w < 0.25) out++;
    }
    return in > out;
}

/* ---- by rays ------------------------------------------------------------------- */

/* Set enclosing for the shells marked in cand that the rays decide, and
 * unmark them; the pairwise test decides the rest (all of them without
 * Embree). */
static void by_rays(lam_model *md, unsigned char *cand)
{
    const lam_mesh *m = &md->mesh;
    lam_rays *v = NULL;
    lam_error verr;
    lam_error_clear(&verr);
    if (lam_rays_new(md, &v, &verr)) return;
    /* the offset: the rays' own inset for its test points, well clear
     * of its float32 tolerance and tiny against the model */
    double delta = lam_rays_min_inset(v);
    for (size_t s = 0; s < md->nshells; s++) {
        if (!cand[s]) continue;
        uint32_t tri[SAMPLES];
        int ns = samples(md, s, tri), w[SAMPLES], nw = 0;
        for (int k = 0; k < ns; k++) {
            const uint32_t *t = m->tris + 3 * (size_t)tri[k];
            const double *a = m->xyz + 3 * (size_t)t[0], *b = m->xyz + 3 * (size_t)t[1], *c = m->xyz + 3 * (size_t)t[2];
            double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, q[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
            double nrm[3] = { u[1] * q[2] - u[2] * q[1], u[2] * q[0] - u[0] * q[2], u[0] * q[1] - u[1] * q[0] };
            double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            if (!(len > 0)) continue;
            double pt[3];
            for (int j = 0; j < 3; j++) pt[j] = (a[j] + b[j] + c[j]) / 3 + delta * nrm[j] / len;
            int wind;
            lam_error_clear(&verr);
            if (lam_rays_winding(v, pt, &wind, &verr) == LAM_OK) w[nw++] = wind;
        }
        /* the most frequent answer, with a strict majority of the decisive
         * samples (a sample on another shell's surface says nothing) */
        size_t best_count = 0;
        int best = nw ? lam_rays_vote(w, (size_t)nw, &best_count) : -1;
        if (best >= 0 && 2 * best_count > (size_t)nw) {
            md->shells[s].enclosing = best;
            cand[s] = 0;
        }
    }
    lam_rays_free(v);
}

int lam_count_enclosing(lam_model *md, lam_error *err)
{
    size_t ns = md->nshells;
    for (size_t s = 0; s < ns; s++) md->shells[s].enclosing = 0;
    if (ns < 2) return LAM_OK;
    tree t;
    unsigned char *cand = calloc(ns, 1);
    if (!cand || tree_build(md, &t)) {
        free(cand);
        return lam_error_nomem(err, "building the model");
    }
    /* the work the pairwise test would do, and who has a candidate at all;
     * past the budget only the first candidate of each shell is looked
     * for (many overlapping boxes make a quadratic number of pairs) */
    double work = 0;
    query q;
    for (size_t s = 0; s < ns; s++) {
        size_t n = md->shells[s].ntris;
        init_query(&t, &q);
        for (long o; (o = next_candidate(md, &t, s, &q)) >= 0;) {
            cand[s] = 1;
            if (work > PAIRWISE_WORK) break;
            work += (double)(n < SAMPLES ? n : SAMPLES) * (double)md->shells[o].ntris;
        }
    }
    if (work > PAIRWISE_WORK) by_rays(md, cand);
    for (size_t s = 0; s < ns; s++) {
        if (!cand[s]) continue;
        init_query(&t, &q);
        for (long o; (o = next_candidate(md, &t, s, &q)) >= 0;)
            if (shell_encloses(md, (size_t)o, s)) md->shells[s].enclosing++;
    }
    tree_free(&t);
    free(cand);
    return LAM_OK;
}
