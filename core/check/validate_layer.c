/* The layer check of validate.h: what a layer's contours say against the
 * model (direction, ancestry, nesting, material by rays, net area). */
#include "test_hooks.h"
#include "validate.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "section.h"

static int nomem(lam_error *err) { return lam_error_nomem(err, "while validating"); }

/* ---- a grid of the layer's edges ------------------------------------------------ */

/* Edge g of the layer runs from point g to point nxt[g]. Each edge is listed
 * in every cell its bounding box touches. */
typedef struct egrid {
    const double *uv;
    size_t *nxt;
    double u0, v0, u1, v1, cu, cv;
    size_t g;            /* g x g cells */
    size_t *first;       /* g*g + 1 offsets into items */
    size_t *items;
} egrid;

static size_t cell(double x, double x0, double c, size_t g)
{
    double q = (x - x0) / c;
    if (!(q > 0)) return 0;
    if (q >= (double)g) return g - 1;
    return (size_t)q;
}

static void edge_cells(const egrid *G, size_t e, size_t *iu0, size_t *iv0, size_t *iu1, size_t *iv1)
{
    const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
    *iu0 = cell(fmin(a[0], b[0]), G->u0, G->cu, G->g);
    *iu1 = cell(fmax(a[0], b[0]), G->u0, G->cu, G->g);
    *iv0 = cell(fmin(a[1], b[1]), G->v0, G->cv, G->g);
    *iv1 = cell(fmax(a[1], b[1]), G->v0, G->cv, G->g);
}

static void egrid_free(egrid *G)
{
    free(G->nxt);
    free(G->first);
    free(G->items);
    memset(G, 0, sizeof *G);
}

static int egrid_build(egrid *G, const lam_layer *L)
{
    memset(G, 0, sizeof *G);
    size_t P = L->npoints;
    G->uv = L->uv;
    G->nxt = malloc((P ? P : 1) * sizeof *G->nxt);
    if (!G->nxt) return -1;
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    for (size_t c = 0; c < L->ncontours; c++) {
        const lam_contour *k = &L->contours[c];
        for (size_t i = 0; i < k->n; i++) {
            size_t g = k->first + i;
            G->nxt[g] = i + 1 < k->n ? g + 1 : k->first;
            for (int j = 0; j < 2; j++) {
                if (L->uv[2 * g + j] < lo[j]) lo[j] = L->uv[2 * g + j];
                if (L->uv[2 * g + j] > hi[j]) hi[j] = L->uv[2 * g + j];
            }
        }
    }
    if (!(hi[0] >= lo[0])) lo[0] = hi[0] = lo[1] = hi[1] = 0;
    size_t g = (size_t)ceil(sqrt((double)P));
    if (g < 1) g = 1;
    if (g > 1024) g = 1024;
    G->u0 = lo[0];
    G->v0 = lo[1];
    G->u1 = hi[0];
    G->v1 = hi[1];
    size_t total;
    for (;;) {
        G->g = g;
        G->cu = hi[0] > lo[0] ? (hi[0] - lo[0]) / (double)g : 1;
        G->cv = hi[1] > lo[1] ? (hi[1] - lo[1]) / (double)g : 1;
        total = 0;
        for (size_t c = 0; c < L->ncontours; c++)
            for (size_t i = 0; i < L->contours[c].n; i++) {
                size_t iu0, iv0, iu1, iv1;
                edge_cells(G, L->contours[c].first + i, &iu0, &iv0, &iu1, &iv1);
                total += (iu1 - iu0 + 1) * (iv1 - iv0 + 1);
            }
        /* long slanted edges fill many cells: coarsen until the lists stay
         * linear in the number of edges */
        if (total <= 16 * P + 1024 || g == 1) break;
        g /= 2;
    }
    G->first = calloc(g * g + 1, sizeof *G->first);
    G->items = malloc((total ? total : 1) * sizeof *G->items);
    if (!G->first || !G->items) return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t c = 0; c < L->ncontours; c++)
            for (size_t i = 0; i < L->contours[c].n; i++) {
                size_t e = L->contours[c].first + i, iu0, iv0, iu1, iv1;
                edge_cells(G, e, &iu0, &iv0, &iu1, &iv1);
                for (size_t y = iv0; y <= iv1; y++)
                    for (size_t x = iu0; x <= iu1; x++) {
                        size_t k = y * g + x;
                        if (pass == 0) G->first[k + 1]++;
                        else G->items[G->first[k]++] = e;
                    }
            }
        if (pass == 0) {
            for (size_t k = 0; k < g * g; k++) G->first[k + 1] += G->first[k];
        } else {
            /* first[k] now holds the end of cell k: shift back */
            for (size_t k = g * g; k > 0; k--) G->first[k] = G->first[k - 1];
            G->first[0] = 0;
        }
    }
    return 0;
}

/* Distance from m along +-n (unit) to the nearest edge of the layer other
 * than `self`, looking no further than r; r when there is none. */
static double clearance(const egrid *G, size_t self, const double m[2], const double n[2], double r)
{
    double best = r;
    size_t iu0 = cell(m[0] - r * fabs(n[0]), G->u0, G->cu, G->g);
    size_t iu1 = cell(m[0] + r * fabs(n[0]), G->u0, G->cu, G->g);
    size_t iv0 = cell(m[1] - r * fabs(n[1]), G->v0, G->cv, G->g);
    size_t iv1 = cell(m[1] + r * fabs(n[1]), G->v0, G->cv, G->g);
    for (size_t y = iv0; y <= iv1; y++)
        for (size_t x = iu0; x <= iu1; x++) {
            size_t k = y * G->g + x;
            for (size_t q = G->first[k]; q < G->first[k + 1]; q++) {
                size_t e = G->items[q];
                if (e == self) continue;
                const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
                double ex = b[0] - a[0], ey = b[1] - a[1];
                double ax = a[0] - m[0], ay = a[1] - m[1];
                double den = n[0] * ey - n[1] * ex;
                if (den == 0) {
                    /* parallel to the normal line: on it, it blocks at its
                     * nearest point */
                    if (ax * n[1] - ay * n[0] != 0) continue;
                    double sa = ax * n[0] + ay * n[1];
                    double sb = (b[0] - m[0]) * n[0] + (b[1] - m[1]) * n[1];
                    double d = (sa > 0) == (sb > 0) && sa != 0 && sb != 0 ? fmin(fabs(sa), fabs(sb)) : 0;
                    if (d < best) best = d;
                    continue;
                }
                double s = (ax * ey - ay * ex) / den;  /* along the normal */
                double t = (ax * n[1] - ay * n[0]) / den; /* along the edge */
                if (t < 0 || t > 1) continue;
                if (fabs(s) < best) best = fabs(s);
            }
        }
    return best;
}

/* The smallest distance from p to an edge of the layer, looking no further
 * than r (r when none is nearer). */
static double nearest_edge(const egrid *G, const double p[2], double r)
{
    double best = r;
    size_t iu0 = cell(p[0] - r, G->u0, G->cu, G->g), iu1 = cell(p[0] + r, G->u0, G->cu, G->g);
    size_t iv0 = cell(p[1] - r, G->v0, G->cv, G->g), iv1 = cell(p[1] + r, G->v0, G->cv, G->g);
    for (size_t y = iv0; y <= iv1; y++)
        for (size_t x = iu0; x <= iu1; x++)
            for (size_t q = G->first[y * G->g + x]; q < G->first[y * G->g + x + 1]; q++) {
                size_t e = G->items[q];
                const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
                double ex = b[0] - a[0], ey = b[1] - a[1], ll = ex * ex + ey * ey;
                double t = ll > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / ll : 0;
                t = t < 0 ? 0 : t > 1 ? 1 : t;
                double dd = hypot(a[0] + t * ex - p[0], a[1] + t * ey - p[1]);
                if (dd < best) best = dd;
            }
    return best;
}

/* ---- nesting by a ray in the plane ----------------------------------------------- */

typedef struct nest_scratch {
    size_t npoints;
    size_t *loop_of;         /* per point (edge): its contour */
    uint32_t *seen;          /* per edge: the query that last looked at it */
    uint32_t query;
    unsigned char *odd;      /* per contour: bit 0 parity, bit 1 touched by this query */
    size_t *touched;
} nest_scratch;

/* The contours whose even-odd interior holds q, by a ray from q along the
 * shortest of +-u, +-v out of the layer's box (crossings by the half-open
 * rule, so a vertex on the ray counts once). *depth: how many besides self;
 * *parent: the smallest of them by |area| (-1 for none). Returns 0 when q
 * is not inside self itself (a loop that crosses itself), else 1. */
static int nesting(nest_scratch *S, const egrid *G, const double *area, size_t self, const double q[2], int *depth,
                   long *parent)
{
    double room[4] = { G->u1 - q[0], q[0] - G->u0, G->v1 - q[1], q[1] - G->v0 };
    int dir = 0;
    for (int k = 1; k < 4; k++)
        if (room[k] < room[dir]) dir = k;
    int along_u = dir < 2, forward = dir % 2 == 0;
    size_t iu = cell(q[0], G->u0, G->cu, G->g), iv = cell(q[1], G->v0, G->cv, G->g);
    size_t at = along_u ? iu : iv, from = forward ? at : 0, to = forward ? G->g - 1 : at;
    if (++S->query == 0) {
        memset(S->seen, 0, S->npoints * sizeof *S->seen);
        S->query = 1;
    }
    size_t nt = 0;
    const double *x = q;
    int a_ax = along_u ? 1 : 0, b_ax = along_u ? 0 : 1; /* the ray runs along b_ax at a_ax = q[a_ax] */
    for (size_t k = from; k <= to; k++) {
        size_t c = along_u ? iv * G->g + k : k * G->g + iu;
        for (size_t j = G->first[c]; j < G->first[c + 1]; j++) {
            size_t e = G->items[j];
            if (S->seen[e] == S->query) continue;
            S->seen[e] = S->query;
            const double *a = G->uv + 2 * e, *b = G->uv + 2 * G->nxt[e];
            if ((a[a_ax] > x[a_ax]) == (b[a_ax] > x[a_ax])) continue;
            double cross = a[b_ax] + (x[a_ax] - a[a_ax]) * (b[b_ax] - a[b_ax]) / (b[a_ax] - a[a_ax]);
            if (forward ? !(cross > x[b_ax]) : !(cross < x[b_ax])) continue;
            size_t lp = S->loop_of[e];
            if (!(S->odd[lp] & 2)) {
                S->odd[lp] = 2;
                S->touched[nt++] = lp;
            }
            S->odd[lp] ^= 1;
        }
    }
    int inside_self = 0;
    *depth = 0;
    *parent = -1;
    for (size_t i = 0; i < nt; i++) {
        size_t lp = S->touched[i];
        if (S->odd[lp] & 1) {
            if (lp == self) inside_self = 1;
            else {
                (*depth)++;
                if (*parent < 0 || fabs(area[lp]) < fabs(area[*parent])) *parent = (long)lp;
            }
        }
        S->odd[lp] = 0;
    }
    return inside_self;
}

/* ---- layers ------------------------------------------------------------------------ */

#define EDGES_TESTED 4
#define EDGES_TRIED 8

static const char *WHY_OK = "confirmed";
static const char *WHY_VOID = "the label says material here but the point is outside the part";
static const char *WHY_SOLID = "the label says void here but the point is inside the part";
static const char *WHY_OVERLAP =
    "the label says void here but bodies overlap here (an even winding: void under evenodd, "
    "material under nonzero)";
static const char *WHY_NOPOINT =
    "not checked: no edge is long enough or far enough from the others for a test point above "
    "float32 precision";
static const char *WHY_UNDECIDED = "not checked: the winding could not be decided at any test point";
static const char *WHY_CW_SOLID = "written clockwise but labelled solid: a machine fills it as a hole";
static const char *WHY_CCW_HOLE = "written counter-clockwise but labelled hole: a machine fills it as a solid";
static const char *WHY_NO_AREA = "its points enclose no area";
static const char *WHY_PARENT_RANGE = "its parent is not a contour of the layer";
static const char *WHY_OWN_ANCESTOR = "it is its own ancestor (its parents form a cycle)";
static const char *WHY_DEPTH_PARENT = "its depth is not its parent's depth plus one";
static const char *WHY_LABEL_DEPTH = "its label is not its depth's parity (solid at even depth, hole at odd)";
static const char *WHY_DEPTH_FOUND = "its depth is not the number of contours around it";
static const char *WHY_PARENT_FOUND = "its parent is not the smallest contour around it";
static const char *WHY_LABEL_FOUND =
    "its label is not the parity of the number of contours around it (even: solid, odd: hole)";

static const char *AREA_OPEN = "not compared: the model has boundary edges or cannot be oriented";
static const char *AREA_BOTH = "net area against the model's section";
static const char *AREA_LOSS = "net area against the model's section, allowing for gap closing";
static const char *AREA_INSET =
    "net area of the first contour pass at most the model's section (the pass lies inside it by the "
    "beam offset)";
static const char *AREA_ONE_SIDED =
    "net area at most the model's section (non-zero fill with two bodies in the plane: the section "
    "counts their overlap twice)";

void lam_validate_opts_init(lam_validate_opts *o) { memset(o, 0, sizeof *o); }

const char *lam_validate_problem_name(unsigned bit)
{
    switch (bit) {
    case LAM_VP_MATERIAL: return "material";
    case LAM_VP_DIRECTION: return "direction";
    case LAM_VP_ANCESTRY: return "ancestry";
    case LAM_VP_NESTING: return "nesting";
    }
    return "";
}

static int problem_index(unsigned bit)
{
    int i = 0;
    while (bit > 1) {
        bit >>= 1;
        i++;
    }
    return i;
}

static void problem(lam_contour_check *it, unsigned bit, const char *why)
{
    if (it->problems & bit) return;
    it->problems |= bit;
    it->whys[problem_index(bit)] = why;
}

/* What is written, without the model: direction against the label, and
 * the parents the layer gives (when it gives them). */
static void check_structure(const lam_layer *L, size_t ci, double area, lam_contour_check *it)
{
    const lam_contour *c = &L->contours[ci];
    if (!(area != 0)) problem(it, LAM_VP_DIRECTION, WHY_NO_AREA);
    else if (c->kind == LAM_SOLID && area < 0) problem(it, LAM_VP_DIRECTION, WHY_CW_SOLID);
    else if (c->kind == LAM_HOLE && area > 0) problem(it, LAM_VP_DIRECTION, WHY_CCW_HOLE);
    if (c->depth < 0) return;
    long K = (long)L->ncontours, p = c->parent;
    if (p < -1 || p >= K) {
        problem(it, LAM_VP_ANCESTRY, WHY_PARENT_RANGE);
        return;
    }
    /* walk up: more steps than contours means a cycle */
    for (long q = p, steps = 0; q >= 0; q = L->contours[q].parent) {
        if (q == (long)ci || ++steps > K) {
            problem(it, LAM_VP_ANCESTRY, WHY_OWN_ANCESTOR);
            return;
        }
        if (L->contours[q].parent < -1 || L->contours[q].parent >= K) break;
    }
    int want = p < 0 ? 0 : L->contours[p].depth + 1;
    if (c->depth != want) problem(it, LAM_VP_ANCESTRY, WHY_DEPTH_PARENT);
    else if (c->kind != (c->depth % 2 ? LAM_HOLE : LAM_SOLID)) problem(it, LAM_VP_ANCESTRY, WHY_LABEL_DEPTH);
}

static void check_nesting(const lam_layer *L, size_t ci, lam_contour_check *it)
{
    const lam_contour *c = &L->contours[ci];
    if (it->depth_found < 0) return;
    if (c->depth < 0) {
        /* each pass further out holds a point just inside this contour:
         * the passes around it are not its parents (validate.h) */
        if (it->pass < 0) return;
        if (c->kind != ((it->depth_found - it->pass) % 2 ? LAM_HOLE : LAM_SOLID))
            problem(it, LAM_VP_NESTING, WHY_LABEL_FOUND);
    } else if (c->depth != it->depth_found) {
        problem(it, LAM_VP_NESTING, WHY_DEPTH_FOUND);
    } else if (c->parent != it->parent_found) {
        problem(it, LAM_VP_NESTING, WHY_PARENT_FOUND);
    }
}

/* Winding at (u, v) in the cut plane, taken on the slab's side. LAM_OK,
 * LAM_ENOMEM, or LAM_EGEOM when it cannot be decided. */
static int layer_point(lam_rays *v, const lam_frame *f, double cut, int below, const double uv[2], double xyz[3],
                       int *w)
{
    lam_error scratch;
    lam_error_clear(&scratch);
    return lam_rays_winding_section(v, f, uv[0], uv[1], cut, below, xyz, w, &scratch);
}

/* The longest edges of a contour (ties: the first), at most EDGES_TRIED. */
static size_t longest_edges(const double *pts, size_t n, size_t cand[EDGES_TRIED], double clen[EDGES_TRIED])
{
    size_t ncand = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = pts + 2 * i, *b = pts + 2 * ((i + 1) % n);
        double len = hypot(b[0] - a[0], b[1] - a[1]);
        if (!(len > 0)) continue;
        size_t pos = ncand;
        while (pos > 0 && clen[pos - 1] < len) pos--;
        if (pos >= EDGES_TRIED) continue;
        size_t last = ncand < EDGES_TRIED ? ncand : EDGES_TRIED - 1;
        for (size_t q = last; q > pos; q--) {
            cand[q] = cand[q - 1];
            clen[q] = clen[q - 1];
        }
        cand[pos] = i;
        clen[pos] = len;
        if (ncand < EDGES_TRIED) ncand++;
    }
    return ncand;
}

typedef struct layer_ctx {
    lam_rays *v;
    const lam_layer *L;
    const lam_frame *f;
    const lam_validate_opts *o;
    int below;               /* the section is taken just below the cut */
    double dmin;             /* smallest inset of a test point */
    egrid G;
    nest_scratch N;
    double *area;            /* per contour, signed, as written */
    int passes;              /* contour passes to look for (validate.h): 0 when the layer
                                is checked as the section itself */
} layer_ctx;

/* How far inside the section pass k lies. */
static double pass_inset(const lam_validate_opts *o, int k) { return o->inset + k * o->pass_distance; }

/* The void side of an edge of a contour read back as one of several
 * passes (validate.h): from m along the unit normal nv (toward the side
 * its label calls void), the section's boundary must lie at the pass's
 * inset e: material at e - s, void at e + s, s four times the smallest
 * test inset (the written precision and float32's error are well below
 * it; a smaller inset is tested at e + d only). With e = 0 (the first
 * pass, no offset) the usual point at d is the test. *k: the pass (-1: not
 * known yet, then the nearest pass that fits is looked for). Returns 1
 * when it fits, 0 when no pass does, -1 when a point could not be
 * decided, -2 when out of memory. The point tested last is put in uv, xyz
 * and *w. */
static int void_side_pass(layer_ctx *X, const double m[2], const double nv[2], double d, int *k, double uv[2],
                          double xyz[3], int *w)
{
    const lam_validate_opts *o = X->o;
    int n = o->passes > 1 ? o->passes : 1;
    double s = 4 * X->dmin;
    for (int j = *k >= 0 ? *k : 0; j < n; j++) {
        double e = pass_inset(o, j);
        if (e == 0) {
            /* the first pass is the section: the usual point at d */
            uv[0] = m[0] + d * nv[0];
            uv[1] = m[1] + d * nv[1];
            int rc = layer_point(X->v, X->f, X->L->cut, X->below, uv, xyz, w);
            if (rc == LAM_ENOMEM) return -2;
            if (rc) return -1;
            if (*w == 0) return *k = j, 1;
            if (*k >= 0) return 0;
            continue;
        }
        double out = e < 2 * s ? e + d : e + s;
        double p[2] = { m[0] + out * nv[0], m[1] + out * nv[1] };
        int rc = layer_point(X->v, X->f, X->L->cut, X->below, p, xyz, w);
        if (rc == LAM_ENOMEM) return -2;
        uv[0] = p[0], uv[1] = p[1];
        if (rc) return -1;
        if (*w != 0) {
            if (*k >= 0) return 0; /* material beyond this pass's inset */
            continue;
        }
        if (e >= 2 * s) {
            double q[2] = { m[0] + (e - s) * nv[0], m[1] + (e - s) * nv[1] }, qxyz[3];
            int wq;
            rc = layer_point(X->v, X->f, X->L->cut, X->below, q, qxyz, &wq);
            if (rc == LAM_ENOMEM) return -2;
            if (rc) return -1;
            if (wq == 0) {
                /* void already before the inset: the contour is further in than any pass */
                memcpy(uv, q, sizeof q);
                memcpy(xyz, qxyz, sizeof qxyz);
                *w = wq;
                return 0;
            }
        }
        *k = j;
        return 1;
    }
    return 0;
}

/* The two test points beside one edge of a contour, what the model has
 * there, and (read back as passes) the void side where the pass lies. */
typedef struct sides {
    double uv[2][2], xyz[2][3]; /* [0]: left of the edge, [1]: right */
    int wind[2];
    int pass_fit;               /* void_side_pass's answer; 2: no passes to look for */
    double pass_uv[2], pass_xyz[3];
    int pass_w;
} sides;

/* The test points at d either side of the midpoint m of a contour edge
 * (normal nl, length len; gi the edge's index in the layer) into uv: d as
 * the preferred inset allows, halved until no edge of the layer is nearer
 * either point than d / 2 (a vertex poking in from the side). Returns d,
 * below X->dmin when no such points were found. */
static double side_points(layer_ctx *X, size_t gi, const double m[2], const double nl[2], double len,
                          double uv[2][2])
{
    double r = fmin(lam_rays_target_inset(X->v), len / 4);
    double d = fmin(r, clearance(&X->G, gi, m, nl, 2 * r) / 2);
    for (; d >= X->dmin; d /= 2) {
        for (int sd = 0; sd < 2; sd++) {
            uv[sd][0] = m[0] + (sd ? -d : d) * nl[0];
            uv[sd][1] = m[1] + (sd ? -d : d) * nl[1];
        }
        if (nearest_edge(&X->G, uv[0], d / 2) >= d / 2 && nearest_edge(&X->G, uv[1], d / 2) >= d / 2) break;
    }
    return d;
}

/* Judge both sides of one edge against what the contour's label expects:
 * the first point tested (or the first disagreeing one) goes into it, the
 * first disagreement is the problem. */
static void judge_sides(layer_ctx *X, lam_contour_check *it, sides *S, int interior_left, int interior_material,
                        int *have_first, int *disagree)
{
    for (int sd = 0; sd < 2; sd++) {
        int interior = sd == 0 ? interior_left : !interior_left;
        int expect = interior ? interior_material : !interior_material;
        int truth = S->wind[sd] != 0;
        if (!expect && S->pass_fit != 2) {
            /* the void side as the pass found it */
            memcpy(S->uv[sd], S->pass_uv, sizeof S->pass_uv);
            memcpy(S->xyz[sd], S->pass_xyz, sizeof S->pass_xyz);
            S->wind[sd] = S->pass_w;
            truth = S->pass_fit != 1;
        }
        int bad = truth != expect;
        if (!*have_first || (bad && !*disagree)) {
            memcpy(it->uv, S->uv[sd], sizeof it->uv);
            memcpy(it->xyz, S->xyz[sd], sizeof it->xyz);
            it->winding_found = S->wind[sd];
            it->expected_material = expect;
            *have_first = 1;
        }
        if (bad && !*disagree) {
            *disagree = 1;
            const char *why = expect ? WHY_VOID
                              : !X->o->fill_nonzero && S->wind[sd] % 2 == 0 ? WHY_OVERLAP
                                                                             : WHY_SOLID;
            problem(it, LAM_VP_MATERIAL, why);
        }
    }
}

/* Test points beside the contour's longest edges: the material check, and
 * the nesting found at the first point inside it. LAM_OK or LAM_ENOMEM. */
static int check_material(layer_ctx *X, size_t ci, lam_contour_check *it)
{
    const lam_layer *L = X->L;
    const lam_contour *c = &L->contours[ci];
    const double *pts = L->uv + 2 * c->first;
    int interior_left = X->area[ci] > 0;
    int interior_material = c->kind == LAM_SOLID;
    size_t cand[EDGES_TRIED];
    double clen[EDGES_TRIED];
    size_t ncand = longest_edges(pts, c->n, cand, clen);
    int have_first = 0, disagree = 0, undecided = 0, nested = 0;
    for (size_t q = 0; q < ncand && it->edges < EDGES_TESTED; q++) {
        size_t i = cand[q];
        const double *a = pts + 2 * i, *b = pts + 2 * ((i + 1) % c->n);
        double len = clen[q];
        double m[2] = { a[0] + (b[0] - a[0]) / 2, a[1] + (b[1] - a[1]) / 2 };
        double nl[2] = { -(b[1] - a[1]) / len, (b[0] - a[0]) / len };
        sides S;
        double d = side_points(X, c->first + i, m, nl, len, S.uv);
        if (!(d >= X->dmin)) continue;
        if (!nested) {
            nested = 1;
            if (!nesting(&X->N, &X->G, X->area, ci, S.uv[interior_left ? 0 : 1], &it->depth_found,
                         &it->parent_found)) {
                it->depth_found = -1;
                it->parent_found = -1;
            }
        }
        S.wind[0] = S.wind[1] = 0;
        int r0 = LAM_OK;
        /* read back as passes, the label's void side is tested where the
         * pass lies (void_side_pass), not at d: a point d off an inset
         * contour may sit on the model's face */
        int passes = X->passes && c->depth < 0;
        int vs = (interior_left ? interior_material : !interior_material) ? 1 : 0; /* the label's void side */
        for (int sd = 0; sd < 2 && r0 == LAM_OK; sd++) {
            if (passes && sd == vs) continue;
            r0 = layer_point(X->v, X->f, L->cut, X->below, S.uv[sd], S.xyz[sd], &S.wind[sd]);
            if (r0 == LAM_ENOMEM) return LAM_ENOMEM;
        }
        if (r0 != LAM_OK) {
            undecided = 1;
            continue;
        }
        /* read back as passes: the void side where the pass says */
        S.pass_fit = 2;
        S.pass_w = 0;
        if (passes) {
            double nv[2] = { vs ? -nl[0] : nl[0], vs ? -nl[1] : nl[1] };
            int k = it->pass;
            S.pass_fit = void_side_pass(X, m, nv, d, &k, S.pass_uv, S.pass_xyz, &S.pass_w);
            if (S.pass_fit == -2) return LAM_ENOMEM;
            if (S.pass_fit < 0) {
                undecided = 1;
                continue;
            }
            if (S.pass_fit == 1) it->pass = k;
        }
        it->edges++;
        judge_sides(X, it, &S, interior_left, interior_material, &have_first, &disagree);
    }
    if (!it->edges) it->why = undecided ? WHY_UNDECIDED : WHY_NOPOINT;
    return LAM_OK;
}

/* The tolerance of the precision the layer was written and computed with:
 * rounding of the areas, coordinates and height written to a quantum
 * (each point up to quantum_uv off moves the area by at most that times
 * the perimeters), and the model's vertices up to `moved` from the mesh
 * the layer was made from (the section's segments move by at most that). */
static double precision_tolerance(const layer_ctx *X, double sum_abs, double per, const lam_section_measure *sm)
{
    double both = per + sm->perimeter;
    return 1e-9 * (sum_abs + fabs(sm->area)) + 2 * X->o->quantum_uv * both + X->o->quantum_h * sm->rate +
           1e-12 * lam_rays_scale(X->v) * both + X->o->moved * both;
}

/* The loss check's tolerance (validate.h): a bridge of length at most gap
 * differs from the closed section across the hole by at most gap / 2 times
 * its length; the length bridged is gaps_closed x gap when the slicer
 * counted them, else at most the layer's perimeter (the bridges are part of
 * its outlines). */
static double loss_tolerance(const layer_ctx *X, double precision, double per, double section)
{
    const lam_layer *L = X->L;
    double g = X->o->gap > 0 ? X->o->gap : 0;
    double bridged = X->o->gaps_unknown ? per : fmin(per, (double)L->gaps_closed * g);
    return fmax(precision, fmax(LAM_VALIDATE_LOSS_REL * fabs(section), g / 2 * bridged));
}

/* The layer's net area against the model's own section at the cut. */
static int check_area(layer_ctx *X, int below, lam_layer_check *out, lam_error *err)
{
    const lam_layer *L = X->L;
    double sum_abs = 0, per = 0;
    out->net_area = 0;
    for (size_t ci = 0; ci < L->ncontours; ci++) {
        const lam_contour *c = &L->contours[ci];
        if (out->items[ci].pass > 0) continue; /* the first pass is the section's (validate.h) */
        double a = fabs(X->area[ci]);
        out->net_area += c->kind == LAM_SOLID ? a : -a;
        sum_abs += a;
        const double *pts = L->uv + 2 * c->first;
        for (size_t i = 0; i < c->n; i++) {
            const double *p = pts + 2 * i, *q = pts + 2 * ((i + 1) % c->n);
            per += hypot(q[0] - p[0], q[1] - p[1]);
        }
    }
    out->area_ok = 1;
    lam_section_index *sec;
    int rc = lam_rays_section(X->v, X->f, &sec, err);
    if (rc) return rc;
    lam_section_measure sm;
    lam_section_measure_at(sec, L->cut, below, &sm);
    out->section_area = sm.area;
    if (!sm.closed) {
        out->area_why = AREA_OPEN;
        out->area_open = 1;
        return LAM_OK;
    }
    out->area_tolerance = precision_tolerance(X, sum_abs, per, &sm);
    out->area_loose = L->gaps_closed || L->nopen || X->o->gaps_unknown;
    if (out->area_loose) out->area_tolerance = loss_tolerance(X, out->area_tolerance, per, sm.area);
    out->area_checked = 1;
    out->area_lost = sm.area - out->net_area;
    if (X->passes && X->o->inset > 0) {
        out->area_why = AREA_INSET;
        out->area_ok = out->net_area <= sm.area + out->area_tolerance;
    } else if (X->o->fill_nonzero && sm.solid_shells >= 2) {
        out->area_why = AREA_ONE_SIDED;
        out->area_ok = out->net_area <= sm.area + out->area_tolerance;
    } else {
        out->area_why = out->area_loose ? AREA_LOSS : AREA_BOTH;
        out->area_ok = fabs(out->area_lost) <= out->area_tolerance;
    }
    return LAM_OK;
}

static void layer_ctx_free(layer_ctx *X)
{
    egrid_free(&X->G);
    free(X->N.loop_of);
    free(X->N.seen);
    free(X->N.odd);
    free(X->N.touched);
    free(X->area);
}

/* The first problem in the order a reader wants them: what the machine
 * would do wrong first. */
static const unsigned PROBLEM_ORDER[] = { LAM_VP_ANCESTRY, LAM_VP_DIRECTION, LAM_VP_MATERIAL, LAM_VP_NESTING };

/* The per-layer scratch of X (areas, point owners, nesting marks, the
 * edge grid) and out's items, and each contour's signed area. 0, or -1
 * when out of memory (then nothing is left to free in out). */
static int layer_ctx_init(layer_ctx *X, const lam_layer *L, lam_layer_check *out)
{
    size_t K = L->ncontours, P = L->npoints;
    if (!K) return 0;
    out->items = calloc(K, sizeof *out->items);
    X->area = malloc(K * sizeof *X->area);
    X->N.npoints = P;
    X->N.loop_of = malloc(P * sizeof *X->N.loop_of);
    X->N.seen = calloc(P, sizeof *X->N.seen);
    X->N.odd = calloc(K, 1);
    X->N.touched = malloc(K * sizeof *X->N.touched);
    if (!out->items || !X->area || !X->N.loop_of || !X->N.seen || !X->N.odd || !X->N.touched ||
        egrid_build(&X->G, L)) {
        lam_layer_check_free(out);
        return -1;
    }
    out->nitems = K;
    for (size_t ci = 0; ci < K; ci++) {
        const lam_contour *c = &L->contours[ci];
        X->area[ci] = c->n >= 3 ? lam_section_loop_area(L->uv + 2 * c->first, c->n) : 0;
        for (size_t i = 0; i < c->n; i++) X->N.loop_of[c->first + i] = ci;
    }
    return 0;
}

/* Check contour ci into out->items[ci] and count it. 0, or -1 when out of
 * memory. */
static int check_contour(layer_ctx *X, size_t ci, lam_layer_check *out)
{
    const lam_layer *L = X->L;
    const lam_contour *c = &L->contours[ci];
    lam_contour_check *it = &out->items[ci];
    it->contour = ci;
    it->area = X->area[ci];
    it->depth_found = -1;
    it->parent_found = -1;
    it->pass = X->passes && c->depth < 0 ? -1 : 0;
    it->why = WHY_NOPOINT;
    check_structure(L, ci, X->area[ci], it);
    int rc = c->n >= 3 ? check_material(X, ci, it) : 0;
    check_nesting(L, ci, it);
    if (it->problems) {
        for (size_t k = 0; k < sizeof PROBLEM_ORDER / sizeof *PROBLEM_ORDER; k++)
            if (it->problems & PROBLEM_ORDER[k]) {
                it->why = it->whys[problem_index(PROBLEM_ORDER[k])];
                break;
            }
        it->ok = 0;
        out->checked++;
        out->disagreeing++;
    } else if (it->edges) {
        it->ok = 1;
        it->why = WHY_OK;
        out->checked++;
        out->confirmed++;
    } else {
        it->ok = -1;
        out->unchecked++;
    }
    return rc;
}

int lam_validate_layer(lam_rays *v, const lam_layer *L, const lam_frame *f, const lam_validate_opts *o,
                       lam_layer_check *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    out->index = L->index;
    lam_validate_opts defaults;
    if (!o) {
        lam_validate_opts_init(&defaults);
        o = &defaults;
    }
    layer_ctx X;
    memset(&X, 0, sizeof X);
    X.v = v;
    X.L = L;
    X.f = f;
    X.o = o;
    int below = L->cut >= L->ceiling && L->ceiling > L->floor;
    X.below = below;
    X.dmin = fmax(lam_rays_min_inset(v), 10 * o->quantum_uv);
    if (layer_ctx_init(&X, L, out)) {
        layer_ctx_free(&X);
        return nomem(err);
    }
    X.passes = o->passes > 1 || o->inset > 0 ? (o->passes > 1 ? o->passes : 1) : 0;
    int rc = LAM_OK;
    for (size_t ci = 0; ci < L->ncontours && !rc; ci++) rc = check_contour(&X, ci, out);
    /* a contour whose pass no edge told is taken to be in the pass written
     * before it (the planner writes the passes one after the other) */
    for (size_t ci = 0; ci < out->nitems; ci++)
        if (out->items[ci].pass < 0) out->items[ci].pass = ci ? out->items[ci - 1].pass : 0;
    if (!rc) rc = check_area(&X, below, out, err);
    else rc = nomem(err);
    layer_ctx_free(&X);
    if (rc) lam_layer_check_free(out);
    return rc;
}

void lam_layer_check_free(lam_layer_check *c)
{
    if (!c) return;
    free(c->items);
    memset(c, 0, sizeof *c);
}

void lam_layer_flip_label_for_test(lam_layer *L, size_t contour)
{
    if (!L || contour >= L->ncontours) return;
    lam_contour *c = &L->contours[contour];
    c->kind = c->kind == LAM_SOLID ? LAM_HOLE : LAM_SOLID;
}
