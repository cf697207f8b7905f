/* The slicer (SPEC 3): exact sections of the thesis's models, the symbolic
 * perturbation rule at vertex heights and flat faces, axis frames checked
 * against rotated copies bit for bit, the floor/ceiling identity, areas and
 * volumes of a tessellated sphere against an independent brute force, open
 * meshes and gap closing, the hit-stack nesting cases, and bad options.
 *
 * Every expected value here is derived from the geometry, never copied from
 * the program's output. */
#include "contour.h"
#include "mesh.h"
#include "model.h"
#include "meshes.h"
#include "slice.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- helpers ----------------------------------------------------------------- */

static lam_model *octahedron(void)
{
    lam_mesh m;
    lam_mesh_init(&m);
    uint32_t e[4] = { vtx(&m, 1, 0, 0), vtx(&m, 0, 1, 0), vtx(&m, -1, 0, 0), vtx(&m, 0, -1, 0) };
    uint32_t top = vtx(&m, 0, 0, 1), bot = vtx(&m, 0, 0, -1);
    for (int i = 0; i < 4; i++) {
        tri(&m, e[i], e[(i + 1) % 4], top);
        tri(&m, e[(i + 1) % 4], e[i], bot);
    }
    return build_model(&m, "octahedron");
}

/* A copy of model's mesh with every vertex's coordinates permuted:
 * new[k] = old[perm[k]]. Triangles keep their order and winding. */
static lam_model *permuted(const lam_model *src, const int perm[3], const char *name)
{
    lam_mesh m;
    lam_mesh_init(&m);
    for (size_t v = 0; v < src->mesh.nverts; v++) {
        const double *p = src->mesh.xyz + 3 * v;
        vtx(&m, p[perm[0]], p[perm[1]], p[perm[2]]);
    }
    for (size_t t = 0; t < src->mesh.ntris; t++) {
        const uint32_t *tv = src->mesh.tris + 3 * t;
        tri(&m, tv[0], tv[1], tv[2]);
    }
    return build_model(&m, name);
}

/* ---- runs and the invariants every layer must keep --------------------------- */

typedef struct run {
    lam_layer **L;
    size_t n;
    int rc;
} run;

static void run_free(run *r)
{
    for (size_t i = 0; i < r->n; i++) lam_layer_free(r->L[i]);
    free(r->L);
    r->L = NULL;
    r->n = 0;
}

static int sgn(double x) { return (x > 0) - (x < 0); }

static double net_area(const lam_layer *l)
{
    double a = 0;
    for (size_t c = 0; c < l->ncontours; c++) a += l->contours[c].area;
    return a;
}

#define BAD(...) do { if (bad++ < 5) diag(__VA_ARGS__); } while (0)

/* SPEC 3.3 and 3.2 on one layer; returns the number of problems found
 * (the first few are printed). */
static int check_layer(const lam_layer *l, size_t idx, const double *planes, lam_cut cut,
                       const char *what)
{
    int bad = 0;
    if (l->index != idx) BAD("%s layer %zu: index %zu", what, idx, l->index);
    if (planes) {
        if (l->floor != planes[idx] || l->ceiling != planes[idx + 1])
            BAD("%s layer %zu: slab [%.17g, %.17g], planes say [%.17g, %.17g]", what, idx, l->floor,
                l->ceiling, planes[idx], planes[idx + 1]);
    }
    if (l->width != l->ceiling - l->floor) BAD("%s layer %zu: width %.17g", what, idx, l->width);
    double want_cut = cut == LAM_CUT_FLOOR ? l->floor : cut == LAM_CUT_CEILING ? l->ceiling : -1;
    if (cut != LAM_CUT_MIDDLE && l->cut != want_cut)
        BAD("%s layer %zu: cut %.17g, expected %.17g", what, idx, l->cut, want_cut);
    if (cut == LAM_CUT_MIDDLE && fabs(l->cut - (l->floor + l->ceiling) / 2) > 1e-12 * (1 + fabs(l->cut)))
        BAD("%s layer %zu: middle cut %.17g not in the middle", what, idx, l->cut);
    size_t total = 0;
    for (size_t ci = 0; ci < l->ncontours; ci++) {
        const lam_contour *c = &l->contours[ci];
        total += c->n;
        if (c->n < 3 || c->first + c->n > l->npoints) {
            BAD("%s layer %zu contour %zu: %zu points from %zu of %zu", what, idx, ci, c->n, c->first,
                l->npoints);
            continue;
        }
        const double *p = l->uv + 2 * c->first;
        size_t n = c->n;
        /* no zero-length segment, also across the closing edge */
        for (size_t i = 0; i < n; i++) {
            size_t j = (i + 1) % n;
            if (p[2 * i] == p[2 * j] && p[2 * i + 1] == p[2 * j + 1])
                BAD("%s layer %zu contour %zu: points %zu and %zu equal (%.17g, %.17g)", what, idx, ci, i,
                    j, p[2 * i], p[2 * i + 1]);
        }
        /* canonical start: strictly lowest, then leftmost */
        for (size_t i = 1; i < n; i++)
            if (!(p[2 * i + 1] > p[1] || (p[2 * i + 1] == p[1] && p[2 * i] > p[0]))) {
                BAD("%s layer %zu contour %zu: point %zu (%.17g, %.17g) is below/left of the start "
                    "(%.17g, %.17g)", what, idx, ci, i, p[2 * i], p[2 * i + 1], p[0], p[1]);
                break;
            }
        /* kind, depth, sign of area, the thesis's turn test */
        lam_kind want_kind = c->depth % 2 ? LAM_HOLE : LAM_SOLID;
        if (c->kind != want_kind) BAD("%s layer %zu contour %zu: kind %d at depth %d", what, idx, ci, c->kind, c->depth);
        if ((c->kind == LAM_SOLID) != (c->area > 0) || c->area == 0)
            BAD("%s layer %zu contour %zu: kind %d with area %.17g", what, idx, ci, c->kind, c->area);
        double turn = lam_contour_turn(l, c);
        if (sgn(turn) != sgn(c->area) || turn == 0)
            BAD("%s layer %zu contour %zu: turn %.17g, area %.17g", what, idx, ci, turn, c->area);
        /* measures, recomputed independently */
        double a2 = 0, mag = 0, per = 0, bb[4] = { p[0], p[1], p[0], p[1] };
        for (size_t i = 0; i < n; i++) {
            size_t j = (i + 1) % n;
            double term = p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
            a2 += term;
            mag += fabs(p[2 * i] * p[2 * j + 1]) + fabs(p[2 * j] * p[2 * i + 1]);
            per += sqrt((p[2 * j] - p[2 * i]) * (p[2 * j] - p[2 * i]) +
                        (p[2 * j + 1] - p[2 * i + 1]) * (p[2 * j + 1] - p[2 * i + 1]));
            if (p[2 * i] < bb[0]) bb[0] = p[2 * i];
            if (p[2 * i + 1] < bb[1]) bb[1] = p[2 * i + 1];
            if (p[2 * i] > bb[2]) bb[2] = p[2 * i];
            if (p[2 * i + 1] > bb[3]) bb[3] = p[2 * i + 1];
        }
        if (fabs(c->area - a2 / 2) > 1e-12 * mag + 1e-300)
            BAD("%s layer %zu contour %zu: area %.17g, shoelace %.17g", what, idx, ci, c->area, a2 / 2);
        if (fabs(c->perimeter - per) > 1e-12 * per)
            BAD("%s layer %zu contour %zu: perimeter %.17g, recomputed %.17g", what, idx, ci, c->perimeter, per);
        if (memcmp(bb, c->bbox, sizeof bb) != 0)
            BAD("%s layer %zu contour %zu: bbox %g %g %g %g, points span %g %g %g %g", what, idx, ci,
                c->bbox[0], c->bbox[1], c->bbox[2], c->bbox[3], bb[0], bb[1], bb[2], bb[3]);
        /* nesting */
        if ((c->parent == -1) != (c->depth == 0))
            BAD("%s layer %zu contour %zu: parent %ld at depth %d", what, idx, ci, c->parent, c->depth);
        if (c->parent >= 0) {
            if ((size_t)c->parent >= ci) {
                BAD("%s layer %zu contour %zu: parent %ld does not come first", what, idx, ci, c->parent);
            } else {
                const lam_contour *pc = &l->contours[c->parent];
                if (pc->depth != c->depth - 1)
                    BAD("%s layer %zu contour %zu: depth %d, parent's %d", what, idx, ci, c->depth, pc->depth);
                if (!lam_contour_contains(l, pc, p[0], p[1]))
                    BAD("%s layer %zu contour %zu: start point not inside parent %ld", what, idx, ci, c->parent);
                if (c->bbox[0] < pc->bbox[0] || c->bbox[1] < pc->bbox[1] || c->bbox[2] > pc->bbox[2] ||
                    c->bbox[3] > pc->bbox[3])
                    BAD("%s layer %zu contour %zu: bbox outside parent's", what, idx, ci);
            }
        }
        /* point in contour: just inside the start corner (convex there), and
         * outside the box */
        double au = p[2] - p[0], av = p[3] - p[1];
        double bu = p[2 * (n - 1)] - p[0], bv = p[2 * (n - 1) + 1] - p[1];
        double la = hypot(au, av), lb = hypot(bu, bv);
        double du = au / la + bu / lb, dv = av / la + bv / lb, dl = hypot(du, dv);
        if (dl < 1e-6) { /* a nearly straight corner: step off the edge to the interior side */
            du = c->area > 0 ? -av / la : av / la;
            dv = c->area > 0 ? au / la : -au / la;
            dl = 1;
        }
        double eps = 1e-6 * (la < lb ? la : lb);
        double qu = p[0] + eps * du / dl, qv = p[1] + eps * dv / dl;
        if (!lam_contour_contains(l, c, qu, qv))
            BAD("%s layer %zu contour %zu: (%.17g, %.17g) just inside the start corner is not inside", what,
                idx, ci, qu, qv);
        double span = (bb[2] - bb[0]) + (bb[3] - bb[1]);
        if (lam_contour_contains(l, c, bb[0] - span, bb[1] - span) ||
            lam_contour_contains(l, c, bb[2] + 1e-3 * span, (bb[1] + bb[3]) / 2) ||
            lam_contour_contains(l, c, (bb[0] + bb[2]) / 2, bb[3] + 1e-3 * span))
            BAD("%s layer %zu contour %zu: a point outside its box is inside", what, idx, ci);
    }
    if (total != l->npoints) BAD("%s layer %zu: contours hold %zu of %zu points", what, idx, total, l->npoints);
    return bad;
}

/* Slice the whole run, check every layer, keep the layers. */
static run slice_all(const lam_model *m, const lam_slice_opts *o, const char *what)
{
    run r = { NULL, 0, 0 };
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *s = NULL;
    r.rc = lam_slicer_new(m, o, &s, &err);
    if (r.rc) {
        ok(0, "%s: slicer created", what);
        diag("%s: %s", what, err.msg);
        return r;
    }
    size_t count = lam_slicer_count(s), cap = count + 1;
    const double *planes = lam_slicer_planes(s);
    r.L = calloc(cap, sizeof *r.L);
    int bad = 0;
    for (;;) {
        lam_layer *l = NULL;
        r.rc = lam_slicer_next(s, &l, &err);
        if (r.rc) {
            diag("%s: layer %zu: %s", what, r.n, err.msg);
            break;
        }
        if (!l) break;
        if (r.n == cap) {
            cap *= 2;
            r.L = realloc(r.L, cap * sizeof *r.L);
        }
        r.L[r.n] = l;
        bad += check_layer(l, r.n, planes, o->cut, what);
        r.n++;
    }
    lam_slicer_free(s);
    ok(r.rc == LAM_OK && r.n == count, "%s: %zu layers as announced (%zu)", what, r.n, count);
    ok(bad == 0, "%s: contour invariants hold on every layer", what);
    return r;
}

static int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Two layers with the same section, bit for bit (slab bounds not compared). */
static int same_section(const lam_layer *a, const lam_layer *b, const char *what, size_t i)
{
    int bad = 0;
    if (a->ncontours != b->ncontours || a->npoints != b->npoints) {
        BAD("%s layer %zu: %zu contours/%zu points vs %zu/%zu", what, i, a->ncontours, a->npoints,
            b->ncontours, b->npoints);
        return bad;
    }
    if (a->npoints && memcmp(a->uv, b->uv, 2 * a->npoints * sizeof *a->uv) != 0)
        BAD("%s layer %zu: points differ", what, i);
    for (size_t c = 0; c < a->ncontours; c++) {
        const lam_contour *p = &a->contours[c], *q = &b->contours[c];
        if (p->first != q->first || p->n != q->n || p->depth != q->depth || p->parent != q->parent ||
            p->kind != q->kind || !same_double(p->area, q->area) || !same_double(p->perimeter, q->perimeter) ||
            memcmp(p->bbox, q->bbox, sizeof p->bbox) != 0)
            BAD("%s layer %zu contour %zu: metadata differs", what, i, c);
    }
    if (a->nopen != b->nopen || a->gaps_closed != b->gaps_closed || !same_double(a->max_gap, b->max_gap))
        BAD("%s layer %zu: gap reports differ", what, i);
    return bad;
}

static void same_runs(const run *a, const run *b, const char *what)
{
    int bad = 0;
    if (a->n != b->n) BAD("%s: %zu layers vs %zu", what, a->n, b->n);
    for (size_t i = 0; i < a->n && i < b->n; i++) {
        const lam_layer *p = a->L[i], *q = b->L[i];
        if (!same_double(p->floor, q->floor) || !same_double(p->ceiling, q->ceiling) ||
            !same_double(p->cut, q->cut) || !same_double(p->width, q->width))
            BAD("%s layer %zu: slab differs", what, i);
        bad += same_section(p, q, what, i);
    }
    ok(bad == 0 && a->n > 0, "%s: identical layers, bit for bit (%zu)", what, a->n);
}

static int points_are(const lam_layer *l, const lam_contour *c, const double *want, size_t n)
{
    return c->n == n && memcmp(l->uv + 2 * c->first, want, 2 * n * sizeof *want) == 0;
}

static void show_points(const lam_layer *l, const lam_contour *c)
{
    for (size_t i = 0; i < c->n && i < 12; i++)
        diag("  (%.17g, %.17g)", l->uv[2 * (c->first + i)], l->uv[2 * (c->first + i) + 1]);
}

static lam_slice_opts opts_axis(char axis, lam_cut cut, double width)
{
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    lam_error err;
    lam_frame_axis(axis, &o.frame, &err);
    o.cut = cut;
    o.width = width;
    return o;
}

/* ---- 1. the thesis's cube with a hole (ABBA) ---------------------------------- */

static void check_cube_hole_layer(const lam_layer *l, const char *what)
{
    static const double outer[8] = { -1, -1, 1, -1, 1, 1, -1, 1 };
    static const double hole[8] = { -.5, -.5, -.5, .5, .5, .5, .5, -.5 };
    is_int(l->ncontours, 2, "%s: two contours", what);
    if (l->ncontours != 2) return;
    const lam_contour *a = &l->contours[0], *b = &l->contours[1];
    ok(a->kind == LAM_SOLID && a->depth == 0 && a->parent == -1, "%s: contour 0 solid, depth 0, no parent", what);
    ok(points_are(l, a, outer, 4), "%s: contour 0 is (-1,-1) (1,-1) (1,1) (-1,1)", what);
    if (!points_are(l, a, outer, 4)) show_points(l, a);
    ok(a->area == 4, "%s: contour 0 area exactly +4 (%.17g)", what, a->area);
    is_num(a->perimeter, 8, 1e-12, "%s: contour 0 perimeter 8", what);
    ok(b->kind == LAM_HOLE && b->depth == 1 && b->parent == 0, "%s: contour 1 hole, depth 1, parent 0", what);
    ok(points_are(l, b, hole, 4), "%s: contour 1 is (-.5,-.5) (-.5,.5) (.5,.5) (.5,-.5)", what);
    if (!points_are(l, b, hole, 4)) show_points(l, b);
    ok(b->area == -1, "%s: contour 1 area exactly -1 (%.17g)", what, b->area);
    ok(lam_contour_contains(l, a, 0, 0) && lam_contour_contains(l, b, 0, 0),
       "%s: the centre is inside both loops (each by its own boundary)", what);
    ok(lam_contour_contains(l, a, .75, 0) && !lam_contour_contains(l, b, .75, 0),
       "%s: (.75, 0) is in the outer loop, not in the hole", what);
    ok(!lam_contour_contains(l, a, 1.5, 0) && !lam_contour_contains(l, b, 1.5, 0) &&
       !lam_contour_contains(l, a, 0, -1.25), "%s: outside points are in neither", what);
}

static void test_cube_hole(const lam_model *m)
{
    lam_slice_opts o = opts_axis('z', LAM_CUT_FLOOR, 1);
    run r = slice_all(m, &o, "cube_hole z floor w1");
    is_int(r.n, 2, "cube_hole z floor w1: 2 layers");
    if (r.n == 2) {
        ok(r.L[0]->cut == 0 && r.L[1]->cut == 1, "cube_hole: floor cuts at 0 and 1 (%g, %g)", r.L[0]->cut,
           r.L[1]->cut);
        ok(r.L[0]->floor == 0 && r.L[0]->ceiling == 1 && r.L[1]->floor == 1 && r.L[1]->ceiling == 2,
           "cube_hole: slabs [0,1] and [1,2]");
        check_cube_hole_layer(r.L[0], "cube_hole floor layer 0 (bottom face)");
        check_cube_hole_layer(r.L[1], "cube_hole floor layer 1");
    }
    run_free(&r);

    /* the ceiling cut on the top face (z = 2) also gives the full section */
    o.cut = LAM_CUT_CEILING;
    r = slice_all(m, &o, "cube_hole z ceiling w1");
    is_int(r.n, 2, "cube_hole z ceiling w1: 2 layers");
    if (r.n == 2) {
        ok(r.L[0]->cut == 1 && r.L[1]->cut == 2, "cube_hole: ceiling cuts at 1 and 2");
        check_cube_hole_layer(r.L[0], "cube_hole ceiling layer 0");
        check_cube_hole_layer(r.L[1], "cube_hole ceiling layer 1 (top face)");
    }
    run_free(&r);

    o.cut = LAM_CUT_MIDDLE;
    o.width = 0.25;
    r = slice_all(m, &o, "cube_hole z middle w.25");
    is_int(r.n, 8, "cube_hole z middle w.25: 8 layers");
    for (size_t i = 0; i < r.n; i++) {
        char what[64];
        snprintf(what, sizeof what, "cube_hole middle layer %zu", i);
        is_num(r.L[i]->cut, 0.125 + 0.25 * (double)i, 1e-15, "%s: cut height", what);
        if (i == 3) check_cube_hole_layer(r.L[i], what);
        else ok(r.L[i]->ncontours == 2 && net_area(r.L[i]) == 3, "%s: net area 3", what);
    }
    run_free(&r);

    /* Along x, frame (u, v) = (y, z): at x = 0 the through hole splits the
     * section into two 0.5 x 2 rectangles (AABB). */
    double planes[2] = { -0.25, 0.25 };
    o = opts_axis('x', LAM_CUT_MIDDLE, 0);
    o.planes = planes;
    o.nplanes = 2;
    r = slice_all(m, &o, "cube_hole x at 0");
    if (r.n == 1) {
        const lam_layer *l = r.L[0];
        /* the model is two shells (SPEC 2.3): the box and the cavity box,
         * which reaches the box's top and bottom faces, so the section is
         * the box's rectangle with the cavity's rectangle nested in it */
        static const double outer[8] = { -1, 0, 1, 0, 1, 2, -1, 2 };
        static const double hole[8] = { -.5, 0, -.5, 2, .5, 2, .5, 0 };
        ok(l->cut == 0 && l->ncontours == 2, "cube_hole x at 0: 2 contours (%zu)", l->ncontours);
        if (l->ncontours == 2) {
            const lam_contour *c = l->contours;
            ok(points_are(l, &c[0], outer, 4) && points_are(l, &c[1], hole, 4),
               "cube_hole x at 0: rectangle (-1..1, 0..2) around the cavity (-.5..5, 0..2)");
            ok(c[0].depth == 0 && c[0].kind == LAM_SOLID && c[0].area == 4 && c[1].depth == 1 &&
               c[1].parent == 0 && c[1].kind == LAM_HOLE && c[1].area == -2,
               "cube_hole x at 0: solid 4 around hole -2 (net 2: two 0.5 x 2 strips)");
        }
    }
    run_free(&r);
}

/* ---- 2. frame with island (ABCCBA) --------------------------------------------- */

static void test_frame_island(const lam_model *m)
{
    static const lam_cut cuts[3] = { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING };
    static const char *names[3] = { "floor", "middle", "ceiling" };
    static const double outer[8] = { -20, -20, 20, -20, 20, 20, -20, 20 };
    static const double inner[8] = { -15, -15, -15, 15, 15, 15, 15, -15 };
    static const double island[8] = { -5, -5, 5, -5, 5, 5, -5, 5 };
    for (int k = 0; k < 3; k++) {
        char what[64];
        snprintf(what, sizeof what, "frame_island z %s w5", names[k]);
        lam_slice_opts o = opts_axis('z', cuts[k], 5);
        run r = slice_all(m, &o, what);
        is_int(r.n, 4, "%s: 4 layers", what);
        int bad = 0;
        for (size_t i = 0; i < r.n; i++) {
            const lam_layer *l = r.L[i];
            if (l->ncontours != 3) {
                BAD("%s layer %zu: %zu contours", what, i, l->ncontours);
                continue;
            }
            const lam_contour *c = l->contours;
            if (c[0].depth != 0 || c[1].depth != 1 || c[2].depth != 2) BAD("%s layer %zu: depths", what, i);
            if (c[0].kind != LAM_SOLID || c[1].kind != LAM_HOLE || c[2].kind != LAM_SOLID) BAD("%s layer %zu: kinds", what, i);
            if (c[0].parent != -1 || c[1].parent != 0 || c[2].parent != 1) BAD("%s layer %zu: parents", what, i);
            if (c[0].area != 1600 || c[1].area != -900 || c[2].area != 100)
                BAD("%s layer %zu: areas %.17g %.17g %.17g", what, i, c[0].area, c[1].area, c[2].area);
            if (!points_are(l, &c[0], outer, 4) || !points_are(l, &c[1], inner, 4) || !points_are(l, &c[2], island, 4))
                BAD("%s layer %zu: points", what, i);
        }
        ok(bad == 0 && r.n == 4, "%s: every layer: solid 1600 > hole -900 > solid 100, parents -1 0 1", what);
        run_free(&r);
    }
    /* Along x at x = 0 (frame u = y, v = z): the frame's two sides (5 x 20)
     * and the island (10 x 20), three siblings. */
    double planes[2] = { -1, 1 };
    lam_slice_opts o = opts_axis('x', LAM_CUT_MIDDLE, 0);
    o.planes = planes;
    o.nplanes = 2;
    run r = slice_all(m, &o, "frame_island x at 0");
    if (r.n == 1 && r.L[0]->ncontours == 3) {
        const lam_contour *c = r.L[0]->contours;
        static const double sides[3][8] = { { -20, -10, -15, -10, -15, 10, -20, 10 },
                                            { -5, -10, 5, -10, 5, 10, -5, 10 },
                                            { 15, -10, 20, -10, 20, 10, 15, 10 } };
        for (int k = 0; k < 3; k++)
            ok(c[k].depth == 0 && c[k].parent == -1 && c[k].kind == LAM_SOLID &&
               points_are(r.L[0], &c[k], sides[k], 4), "frame_island x at 0: sibling %d is the expected rectangle", k);
        ok(c[0].area == 100 && c[1].area == 200 && c[2].area == 100, "frame_island x at 0: areas 100 200 100");
    } else {
        ok(0, "frame_island x at 0: one layer with 3 contours");
    }
    run_free(&r);
    /* At x = -10 (through no vertex: they lie at x = +-20, +-15, +-5) only
     * the frame's two sides are cut: rectangles y in [-20,-15] and [15,20],
     * z in [-10,10]. The plane crosses the triangulated flat top and bottom
     * faces (z = +-10); their points must stay exactly on z = +-10, so each
     * side is exactly 4 points. */
    for (int k = 0; k < 3; k++) {
        static const double left[8] = { -20, -10, -15, -10, -15, 10, -20, 10 };
        static const double right[8] = { 15, -10, 20, -10, 20, 10, 15, 10 };
        double at[3][2] = { { -10, -5 }, { -12.5, -7.5 }, { -15 + 1e-3, -10 } };
        static const lam_cut kc[3] = { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING };
        char what[64];
        snprintf(what, sizeof what, "frame_island x at -10 (cut %d)", k);
        o = opts_axis('x', kc[k], 0);
        o.planes = at[k];
        o.nplanes = 2;
        r = slice_all(m, &o, what);
        if (r.n == 1 && r.L[0]->ncontours == 2) {
            const lam_layer *l = r.L[0];
            ok(l->cut == -10, "%s: cut at -10", what);
            ok(points_are(l, &l->contours[0], left, 4) && points_are(l, &l->contours[1], right, 4),
               "%s: two exact 4-point rectangles (-20..-15, -10..10) and (15..20, -10..10)", what);
            for (size_t c = 0; c < 2; c++)
                if (!points_are(l, &l->contours[c], c ? right : left, 4)) show_points(l, &l->contours[c]);
            ok(l->contours[0].area == 100 && l->contours[1].area == 100, "%s: areas exactly 100 (%.17g, %.17g)", what,
               l->contours[0].area, l->contours[1].area);
        } else {
            ok(0, "%s: one layer with 2 contours", what);
        }
        run_free(&r);
    }
}

/* ---- 3. axis frames against rotated copies ---------------------------------- */

static void test_rotation(const lam_model *src, const char *name, const double *widths, const lam_cut *cuts,
                          int nw)
{
    static const int ident[3] = { 0, 1, 2 };
    static const int to_x[3] = { 1, 2, 0 }; /* (x,y,z) -> (y,z,x) */
    static const int to_y[3] = { 2, 0, 1 }; /* (x,y,z) -> (z,x,y) */
    char what[128];
    snprintf(what, sizeof what, "%s copy", name);
    lam_model *orig = permuted(src, ident, what);
    snprintf(what, sizeof what, "%s (y,z,x)", name);
    lam_model *px = permuted(src, to_x, what);
    snprintf(what, sizeof what, "%s (z,x,y)", name);
    lam_model *py = permuted(src, to_y, what);
    if (!orig || !px || !py) goto out;
    for (int k = 0; k < nw; k++) {
        for (int a = 0; a < 2; a++) {
            char axis = a ? 'y' : 'x';
            lam_slice_opts o1 = opts_axis(axis, cuts[k], widths[k]);
            lam_slice_opts o2 = opts_axis('z', cuts[k], widths[k]);
            snprintf(what, sizeof what, "%s along %c, cut %d, w %g", name, axis, cuts[k], widths[k]);
            run r1 = slice_all(orig, &o1, what);
            snprintf(what, sizeof what, "%s permuted along z, cut %d, w %g", name, cuts[k], widths[k]);
            run r2 = slice_all(a ? py : px, &o2, what);
            snprintf(what, sizeof what, "%s: along %c == permuted copy along z (cut %d, w %g)", name, axis,
                     cuts[k], widths[k]);
            same_runs(&r1, &r2, what);
            run_free(&r1);
            run_free(&r2);
        }
    }
out:
    lam_model_free(orig);
    lam_model_free(px);
    lam_model_free(py);
}

/* ---- 4. planes through vertices and flat faces -------------------------------- */

static run slice_planes(const lam_model *m, const double *planes, size_t n, lam_cut cut, const char *what)
{
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.cut = cut;
    o.planes = planes;
    o.nplanes = n;
    return slice_all(m, &o, what);
}

static void test_vertex_planes(void)
{
    static const double square[8] = { -1, -1, 1, -1, 1, 1, -1, 1 };
    double p3[3] = { -1, 0, 1 };
    lam_model *cube = load_model("thesis_cube.ug");
    if (cube) {
        run r = slice_planes(cube, p3, 3, LAM_CUT_FLOOR, "cube planes -1 0 1 floor");
        if (r.n == 2) {
            for (size_t i = 0; i < 2; i++) {
                const lam_layer *l = r.L[i];
                ok(l->ncontours == 1 && points_are(l, &l->contours[0], square, 4) && l->contours[0].area == 4,
                   "cube floor layer %zu (cut %g): the full 2x2 square, area 4", i, l->cut);
            }
            ok(r.L[0]->cut == -1, "cube floor layer 0 is cut on the bottom face");
        }
        run_free(&r);
        r = slice_planes(cube, p3, 3, LAM_CUT_CEILING, "cube planes -1 0 1 ceiling");
        if (r.n == 2) {
            for (size_t i = 0; i < 2; i++) {
                const lam_layer *l = r.L[i];
                ok(l->ncontours == 1 && points_are(l, &l->contours[0], square, 4) && l->contours[0].area == 4,
                   "cube ceiling layer %zu (cut %g): the full 2x2 square, area 4", i, l->cut);
            }
            ok(r.L[1]->cut == 1, "cube ceiling layer 1 is cut on the top face");
        }
        run_free(&r);
        /* the whole cube along x and y too: every floor/ceiling cut is on a
         * face or through vertices and must still be the full square */
        for (int a = 0; a < 3; a++) {
            for (int cc = 0; cc < 3; cc++) {
                char what[64];
                snprintf(what, sizeof what, "cube along %c cut %d w .5", "xyz"[a], cc);
                lam_slice_opts o = opts_axis("xyz"[a], (lam_cut)cc, 0.5);
                r = slice_all(cube, &o, what);
                int bad = 0;
                for (size_t i = 0; i < r.n; i++)
                    if (r.L[i]->ncontours != 1 || !points_are(r.L[i], &r.L[i]->contours[0], square, 4))
                        BAD("%s layer %zu: not the full square", what, i);
                ok(bad == 0 && r.n == 4, "%s: 4 layers, each exactly the square", what);
                run_free(&r);
            }
        }
        lam_model_free(cube);
    }

    lam_model *oct = octahedron();
    if (!oct) return;
    static const double diamond[8] = { 0, -1, 1, 0, 0, 1, -1, 0 };
    static const double half[8] = { 0, -.5, .5, 0, 0, .5, -.5, 0 };
    double up[2] = { 0, 1 }, down[2] = { -1, 0 };
    run r = slice_planes(oct, up, 2, LAM_CUT_FLOOR, "octahedron floor at z=0");
    if (r.n == 1) {
        const lam_layer *l = r.L[0];
        ok(l->ncontours == 1 && points_are(l, &l->contours[0], diamond, 4),
           "octahedron floor z=0: one contour, exactly (0,-1) (1,0) (0,1) (-1,0)");
        if (l->ncontours && !points_are(l, &l->contours[0], diamond, 4)) show_points(l, &l->contours[0]);
        ok(l->ncontours == 1 && l->contours[0].area == 2, "octahedron floor z=0: area exactly 2");
        ok(l->nopen == 0, "octahedron floor z=0: nothing open");
    }
    run_free(&r);
    r = slice_planes(oct, down, 2, LAM_CUT_CEILING, "octahedron ceiling at z=0");
    if (r.n == 1) {
        const lam_layer *l = r.L[0];
        ok(l->ncontours == 1 && points_are(l, &l->contours[0], diamond, 4) && l->contours[0].area == 2,
           "octahedron ceiling z=0: the same diamond, area 2");
    }
    run_free(&r);
    r = slice_planes(oct, down, 2, LAM_CUT_FLOOR, "octahedron floor at the bottom apex");
    if (r.n == 1)
        ok(r.L[0]->ncontours == 0 && r.L[0]->npoints == 0 && r.L[0]->nopen == 0,
           "octahedron floor z=-1 (apex): no contour, nothing open (%zu, %zu)", r.L[0]->ncontours, r.L[0]->nopen);
    run_free(&r);
    r = slice_planes(oct, up, 2, LAM_CUT_CEILING, "octahedron ceiling at the top apex");
    if (r.n == 1)
        ok(r.L[0]->ncontours == 0 && r.L[0]->nopen == 0, "octahedron ceiling z=1 (apex): no contour");
    run_free(&r);
    r = slice_planes(oct, p3, 3, LAM_CUT_MIDDLE, "octahedron middle -1 0 1");
    if (r.n == 2)
        for (size_t i = 0; i < 2; i++)
            ok(r.L[i]->ncontours == 1 && points_are(r.L[i], &r.L[i]->contours[0], half, 4) &&
               r.L[i]->contours[0].area == 0.5, "octahedron middle layer %zu: half diamond, area .5", i);
    run_free(&r);
    /* the octahedron along x and y through its equator vertices */
    for (int a = 0; a < 2; a++) {
        char what[64];
        snprintf(what, sizeof what, "octahedron along %c floor at 0", "xy"[a]);
        lam_slice_opts o = opts_axis("xy"[a], LAM_CUT_FLOOR, 0);
        o.planes = up;
        o.nplanes = 2;
        r = slice_all(oct, &o, what);
        if (r.n == 1)
            ok(r.L[0]->ncontours == 1 && points_are(r.L[0], &r.L[0]->contours[0], diamond, 4),
               "%s: the diamond", what);
        run_free(&r);
    }
    lam_model_free(oct);

    /* A step: 4x4x1 box with a 2x2x1 box on top, one closed solid whose
     * ledge at z = 1 is a face with a hole. At z = 1 the floor (and middle)
     * cut sees the small square above, the ceiling cut the big one below. */
    lam_model *step = load_model("slice/step.ug");
    if (!step) return;
    is_num(step->stats.volume, 20, 1e-12, "step: volume 16 + 4");
    static const double big[8] = { -2, -2, 2, -2, 2, 2, -2, 2 };
    double at1[2] = { 1, 1.5 }, below1[2] = { 0.5, 1 }, mid1[2] = { 0.5, 1.5 };
    r = slice_planes(step, at1, 2, LAM_CUT_FLOOR, "step floor at the ledge");
    if (r.n == 1)
        ok(r.L[0]->ncontours == 1 && points_are(r.L[0], &r.L[0]->contours[0], square, 4),
           "step floor z=1: the 2x2 square above the ledge");
    run_free(&r);
    r = slice_planes(step, mid1, 2, LAM_CUT_MIDDLE, "step middle at the ledge");
    if (r.n == 1)
        ok(r.L[0]->cut == 1 && r.L[0]->ncontours == 1 && points_are(r.L[0], &r.L[0]->contours[0], square, 4),
           "step middle cut landing on z=1: the 2x2 square above the ledge");
    run_free(&r);
    r = slice_planes(step, below1, 2, LAM_CUT_CEILING, "step ceiling at the ledge");
    if (r.n == 1)
        ok(r.L[0]->ncontours == 1 && points_are(r.L[0], &r.L[0]->contours[0], big, 4) &&
           r.L[0]->contours[0].area == 16, "step ceiling z=1: the 4x4 square below the ledge");
    run_free(&r);
    lam_model_free(step);
}

/* ---- 5, 6. the tessellated sphere ---------------------------------------------- */

typedef struct angpt {
    double a, x, y;
} angpt;

static int cmp_ang(const void *p, const void *q)
{
    const angpt *a = p, *b = q;
    return (a->a > b->a) - (a->a < b->a);
}

/* The model's section at z = c by brute force: every triangle edge that
 * crosses the plane, its point, sorted by angle around the z axis (a
 * section of a sphere mesh is convex around it), shoelace. Sets *through
 * when some vertex lies exactly at c. */
static double brute_section(const lam_model *m, double c, int *through)
{
    const lam_mesh *me = &m->mesh;
    angpt *pts = malloc((3 * me->ntris + 1) * sizeof *pts);
    size_t n = 0;
    *through = 0;
    for (size_t v = 0; v < me->nverts; v++)
        if (me->xyz[3 * v + 2] == c) *through = 1;
    for (size_t t = 0; t < me->ntris; t++)
        for (int k = 0; k < 3; k++) {
            const double *p = me->xyz + 3 * me->tris[3 * t + k];
            const double *q = me->xyz + 3 * me->tris[3 * t + (k + 1) % 3];
            if ((p[2] < c) == (q[2] < c)) continue;
            if (p[2] > q[2]) {
                const double *s = p;
                p = q;
                q = s;
            }
            double t01 = (c - p[2]) / (q[2] - p[2]);
            double x = p[0] + t01 * (q[0] - p[0]), y = p[1] + t01 * (q[1] - p[1]);
            pts[n].x = x;
            pts[n].y = y;
            pts[n].a = atan2(y, x);
            n++;
        }
    qsort(pts, n, sizeof *pts, cmp_ang);
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        a += pts[i].x * pts[j].y - pts[j].x * pts[i].y;
    }
    free(pts);
    return a / 2;
}

static void test_sphere(void)
{
    lam_model *sph = uv_sphere(10, 64, 32, 0, NULL);
    lam_model *rnd = uv_sphere(10, 64, 32, 12345, NULL);
    if (!sph || !rnd) goto out;
    const double pi = acos(-1.0);
    ok(sph->stats.volume > 0 && fabs(sph->stats.volume - 4 * pi * 1000 / 3) < 0.01 * 4 * pi * 1000 / 3,
       "sphere: mesh volume %.6g is within 1%% of 4/3 pi r^3", sph->stats.volume);
    is_num(rnd->stats.volume, sph->stats.volume, 1e-9 * sph->stats.volume,
           "sphere: random winding gives the same volume");
    is_int(rnd->stats.orientation_conflicts, 0, "sphere: random winding is repaired without conflicts");

    /* 5a. net areas against the brute force, sections through no vertex */
    lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, 0.77);
    for (int w = 0; w < 2; w++) {
        const lam_model *m = w ? rnd : sph;
        const char *name = w ? "sphere (random winding) w.77" : "sphere w.77";
        run r = slice_all(m, &o, name);
        int bad = 0, tested = 0;
        for (size_t i = 0; i < r.n; i++) {
            const lam_layer *l = r.L[i];
            int through;
            double want = brute_section(m, l->cut, &through);
            if (through) continue;
            tested++;
            double got = net_area(l);
            if (l->ncontours != 1 || l->contours[0].kind != LAM_SOLID) BAD("%s layer %zu: %zu contours", name, i, l->ncontours);
            if (!(fabs(got - want) <= 1e-9 * want))
                BAD("%s layer %zu (cut %.17g): area %.17g, brute force %.17g", name, i, l->cut, got, want);
        }
        ok(bad == 0 && tested >= 20, "%s: every section (%d) is one solid whose area matches the brute force to 1e-9",
           name, tested);
        run_free(&r);
    }

    /* 5b. volume by layers: middle cut, 100 layers */
    double zmin = sph->stats.bbox[2], zmax = sph->stats.bbox[5];
    o = opts_axis('z', LAM_CUT_MIDDLE, (zmax - zmin) / 100);
    for (int w = 0; w < 2; w++) {
        const lam_model *m = w ? rnd : sph;
        const char *name = w ? "sphere (random winding) 100 layers" : "sphere 100 layers";
        run r = slice_all(m, &o, name);
        is_int(r.n, 100, "%s: 100 layers", name);
        double vol = 0;
        for (size_t i = 0; i < r.n; i++) vol += net_area(r.L[i]) * r.L[i]->width;
        ok(fabs(vol - m->stats.volume) <= 0.005 * m->stats.volume, "%s: sum area x width %.9g within 0.5%% of %.9g",
           name, vol, m->stats.volume);
        run_free(&r);
    }

    /* winding of the input does not matter: same layers from both meshes */
    {
        lam_slice_opts o2 = opts_axis('z', LAM_CUT_MIDDLE, 0.77);
        run a = slice_all(sph, &o2, "sphere again");
        run b = slice_all(rnd, &o2, "sphere (random winding) again");
        int bad = 0;
        for (size_t i = 0; i < a.n && i < b.n; i++) {
            if (a.L[i]->ncontours != b.L[i]->ncontours) BAD("winding: layer %zu contours differ", i);
            else if (fabs(net_area(a.L[i]) - net_area(b.L[i])) > 1e-12 * fabs(net_area(a.L[i])))
                BAD("winding: layer %zu area %.17g vs %.17g", i, net_area(a.L[i]), net_area(b.L[i]));
        }
        ok(bad == 0 && a.n == b.n, "sphere: random winding slices like consistent winding");
        run_free(&a);
        run_free(&b);
    }

    /* 6. floor/ceiling identity at planes through no vertex */
    for (int w = 0; w < 2; w++) {
        const lam_model *m = w ? rnd : sph;
        const char *name = w ? "sphere (random winding)" : "sphere";
        size_t np = 0;
        double planes[80];
        /* from just above the south pole (-10) to above the north pole */
        for (int i = 0; np < 80; i++) {
            planes[np++] = -9.97 + 0.31 * i;
            if (planes[np - 1] > 10) break;
        }
        int hits = 0;
        for (size_t i = 0; i < np; i++)
            for (size_t v = 0; v < m->mesh.nverts; v++)
                if (m->mesh.xyz[3 * v + 2] == planes[i]) hits++;
        is_int(hits, 0, "%s: no vertex lies on any of the %zu planes", name, np);
        char what[96];
        snprintf(what, sizeof what, "%s floor", name);
        run f = slice_planes(m, planes, np, LAM_CUT_FLOOR, what);
        snprintf(what, sizeof what, "%s ceiling", name);
        run c = slice_planes(m, planes, np, LAM_CUT_CEILING, what);
        int bad = 0, nonempty = 0;
        for (size_t i = 0; i + 1 < f.n && i < c.n; i++) {
            snprintf(what, sizeof what, "%s ceiling(i) vs floor(i+1)", name);
            if (c.L[i]->cut != f.L[i + 1]->cut) BAD("%s: cut heights differ at %zu", what, i);
            bad += same_section(c.L[i], f.L[i + 1], what, i);
            if (c.L[i]->ncontours) nonempty++;
        }
        ok(bad == 0 && f.n == np - 1 && c.n == np - 1 && nonempty >= 60,
           "%s: ceiling of layer i == floor of layer i+1 bit for bit over the run (%d sections)", name, nonempty);
        ok(f.n && f.L[0]->ncontours == 1 && c.n && c.L[c.n - 1]->ncontours == 0,
           "%s: the first floor (just above the pole) is cut, the last ceiling (above the model) is empty", name);
        run_free(&f);
        run_free(&c);
    }

    /* 10. determinism */
    {
        lam_slice_opts o2 = opts_axis('z', LAM_CUT_MIDDLE, 0.33);
        run a = slice_all(rnd, &o2, "sphere determinism 1");
        run b = slice_all(rnd, &o2, "sphere determinism 2");
        same_runs(&a, &b, "sphere: the same run twice");
        run_free(&a);
        run_free(&b);
    }
out:
    lam_model_free(sph);
    lam_model_free(rnd);
}

/* ---- 7. open mesh and gap closing ------------------------------------------------ */

static void test_open(void)
{
    lam_mesh me;
    lam_mesh_init(&me);
    add_box(&me, -1, -1, -1, 1, 1, 1, 0, 5); /* no x = +1 face */
    lam_model *m = build_model(&me, "open cube");
    if (!m) return;
    is_int(m->stats.boundary_edges, 4, "open cube: 4 boundary edges");
    static const double square[8] = { -1, -1, 1, -1, 1, 1, -1, 1 };
    double gaps[3] = { LAM_GAP_AUTO, 0, 1.99 }; /* auto: 5e-4 of the diagonal, 0.0017 */
    for (int g = 0; g < 3; g++) {
        lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, 0.5);
        o.gap = gaps[g];
        char what[64];
        snprintf(what, sizeof what, "open cube gap %g", gaps[g]);
        run r = slice_all(m, &o, what);
        int bad = 0;
        for (size_t i = 0; i < r.n; i++) {
            const lam_layer *l = r.L[i];
            if (l->ncontours != 0 || l->nopen != 1 || l->gaps_closed != 0) {
                BAD("%s layer %zu: %zu contours, %zu open, %zu closed", what, i, l->ncontours, l->nopen, l->gaps_closed);
                continue;
            }
            const lam_open_end *e = &l->open[0];
            /* the polyline runs between (1,-1) and (1,1), in either direction */
            int fwd = e->start[0] == 1 && e->start[1] == -1 && e->end[0] == 1 && e->end[1] == 1;
            int bwd = e->start[0] == 1 && e->start[1] == 1 && e->end[0] == 1 && e->end[1] == -1;
            if (!fwd && !bwd)
                BAD("%s layer %zu: open from (%g,%g) to (%g,%g)", what, i, e->start[0], e->start[1], e->end[0], e->end[1]);
        }
        ok(bad == 0 && r.n == 4, "%s: each layer reports 1 open polyline (1,+-1)..(1,-+1), no contour", what);
        run_free(&r);
    }
    lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, 0.5);
    o.gap = 3;
    run r = slice_all(m, &o, "open cube gap 3");
    int bad = 0;
    for (size_t i = 0; i < r.n; i++) {
        const lam_layer *l = r.L[i];
        if (l->ncontours != 1 || l->nopen != 0 || l->gaps_closed != 1 || l->max_gap != 2) {
            BAD("open cube gap 3 layer %zu: %zu contours, %zu open, %zu closed, max gap %.17g", i, l->ncontours,
                l->nopen, l->gaps_closed, l->max_gap);
            continue;
        }
        if (!points_are(l, &l->contours[0], square, 4) || l->contours[0].area != 4)
            BAD("open cube gap 3 layer %zu: not the 2x2 square", i);
    }
    ok(bad == 0 && r.n == 4, "open cube gap 3: each layer 1 contour of area 4, 1 gap closed, max gap exactly 2");
    run_free(&r);
    /* a floor cut on the bottom face (z = -1) is taken just above it and
     * meets the same open sides: reported open, not dropped */
    double pl[2] = { -1, 0 };
    o.planes = pl;
    o.nplanes = 2;
    o.cut = LAM_CUT_FLOOR;
    o.gap = 0.05;
    r = slice_all(m, &o, "open cube floor on the bottom face");
    if (r.n == 1) ok(r.L[0]->ncontours == 0 && r.L[0]->nopen == 1, "open cube floor z=-1: reported open, not dropped");
    run_free(&r);
    lam_model_free(m);
}

/* ---- 8. hit-stack cases with shells --------------------------------------------- */

static void test_shells(void)
{
    /* AABB: two disjoint cubes side by side, the same v range */
    lam_mesh me;
    lam_mesh_init(&me);
    add_box(&me, -3, -1, -1, -1, 1, 1, 0, -1);
    add_box(&me, 1, -1, -1, 3, 1, 1, 0, -1);
    lam_model *m = build_model(&me, "two cubes");
    if (m) {
        is_int(m->stats.shells, 2, "two cubes: 2 shells");
        lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, 0.5);
        run r = slice_all(m, &o, "two cubes (AABB)");
        static const double left[8] = { -3, -1, -1, -1, -1, 1, -3, 1 };
        static const double right[8] = { 1, -1, 3, -1, 3, 1, 1, 1 };
        int bad = 0;
        for (size_t i = 0; i < r.n; i++) {
            const lam_layer *l = r.L[i];
            if (l->ncontours != 2) {
                BAD("AABB layer %zu: %zu contours", i, l->ncontours);
                continue;
            }
            for (int c = 0; c < 2; c++)
                if (l->contours[c].depth != 0 || l->contours[c].parent != -1 || l->contours[c].kind != LAM_SOLID ||
                    l->contours[c].area != 4)
                    BAD("AABB layer %zu contour %d: depth %d parent %ld area %g", i, c, l->contours[c].depth,
                        l->contours[c].parent, l->contours[c].area);
            if (!points_are(l, &l->contours[0], left, 4) || !points_are(l, &l->contours[1], right, 4))
                BAD("AABB layer %zu: points", i);
        }
        ok(bad == 0 && r.n == 4, "AABB: 2 solids of area 4, depth 0, no parent, left then right");
        run_free(&r);
        lam_model_free(m);
    }

    /* ABBA and ABCCBA with shells: nested cubes (cavity, island in it);
     * all wound outward in the input, the model turns the cavity inward */
    for (int depth = 2; depth <= 3; depth++) {
        lam_mesh_init(&me);
        for (int k = 0; k < depth; k++) add_box(&me, -3 + k, -3 + k, -3 + k, 3 - k, 3 - k, 3 - k, 0, -1);
        char name[64];
        snprintf(name, sizeof name, "%d nested cubes", depth);
        m = build_model(&me, name);
        if (!m) continue;
        double want_vol = depth == 2 ? 216 - 64 : 216 - 64 + 8;
        is_num(m->stats.volume, want_vol, 1e-9, "%s: volume %g", name, want_vol);
        lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, 1.5);
        run r = slice_all(m, &o, name);
        int bad = 0;
        for (size_t i = 0; i < r.n; i++) {
            const lam_layer *l = r.L[i];
            double c = l->cut;
            /* shells crossed by this cut: |c| < 3 - k */
            size_t want = 0;
            for (int k = 0; k < depth; k++)
                if (fabs(c) < 3 - k) want++;
            if (l->ncontours != want) {
                BAD("%s layer %zu (cut %g): %zu contours, expected %zu", name, i, c, l->ncontours, want);
                continue;
            }
            for (size_t k = 0; k < want; k++) {
                const lam_contour *ct = &l->contours[k];
                double side = 6 - 2.0 * (double)k;
                double area = k % 2 ? -side * side : side * side;
                if (ct->depth != (int)k || ct->parent != (long)k - 1 || ct->area != area)
                    BAD("%s layer %zu contour %zu: depth %d parent %ld area %g (expected %g)", name, i, k, ct->depth,
                        ct->parent, ct->area, area);
            }
        }
        ok(bad == 0 && r.n == 4, "%s: nesting depth, parent and signed area of every contour", name);
        run_free(&r);
        lam_model_free(m);
    }
}

/* ---- layers outside the model ---------------------------------------------------- */

/* Cuts where the model is not give empty layers: planes all below the
 * cube, all above it, and sphere planes starting below it and ending above. */
static void test_outside(void)
{
    lam_model *cube = load_model("thesis_cube.ug");
    lam_model *sph = uv_sphere(10, 16, 8, 0, NULL);
    double below[2] = { -3, -2 }, above[2] = { 2, 3 }, through[5] = { -10.5, -10.25, 0.1, 10.25, 10.5 };
    for (int which = 0; which < 3; which++) {
        const lam_model *m = which < 2 ? cube : sph;
        if (!m) continue;
        const double *pl = which == 0 ? below : which == 1 ? above : through;
        size_t np = which == 2 ? 5 : 2;
        for (int cut = 0; cut < 3; cut++) {
            char what[64];
            snprintf(what, sizeof what, "%s, cut %d",
                     which == 0 ? "planes below the cube" : which == 1 ? "planes above the cube"
                                                          : "sphere planes from below to above", cut);
            run r = slice_planes(m, pl, np, (lam_cut)cut, what);
            int bad = 0;
            for (size_t i = 0; i < r.n; i++) {
                double c = r.L[i]->cut;
                size_t want = (which == 2 && c > -10 && c < 10) ? 1 : 0;
                if (r.L[i]->ncontours != want || r.L[i]->nopen)
                    BAD("%s layer %zu (cut %g): %zu contours, expected %zu", what, i, c, r.L[i]->ncontours, want);
            }
            ok(bad == 0 && r.n == np - 1, "%s: empty layers where the model is not", what);
            run_free(&r);
        }
    }
    lam_model_free(cube);
    lam_model_free(sph);
}

/* ---- 11. bad options and general directions ------------------------------------- */

static void expect_usage(const lam_model *m, const lam_slice_opts *o, const char *what)
{
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *s = (lam_slicer *)&err; /* must be reset to NULL */
    int rc = lam_slicer_new(m, o, &s, &err);
    ok(rc == LAM_EUSAGE && s == NULL && err.code == LAM_EUSAGE && err.msg[0],
       "%s: LAM_EUSAGE with a message (rc %d: %s)", what, rc, err.msg);
    if (rc == LAM_OK && s != (lam_slicer *)&err) lam_slicer_free(s);
}

static void test_options(const lam_model *m)
{
    lam_slice_opts o = opts_axis('z', LAM_CUT_MIDDLE, -1);
    expect_usage(m, &o, "width -1");
    o.width = NAN;
    expect_usage(m, &o, "width NaN");
    o.width = INFINITY;
    expect_usage(m, &o, "width infinity");

    /* width 0 is the documented default: lam_default_width of the extent
     * (2 -> 0.02, so 100 layers) */
    o.width = 0;
    {
        lam_error err;
        lam_slicer *s = NULL;
        int rc = lam_slicer_new(m, &o, &s, &err);
        ok(rc == LAM_OK && s && lam_slicer_count(s) == 100, "width 0: the default width 0.02, 100 layers");
        lam_slicer_free(s);
    }
    is_num(lam_default_width(2), 0.02, 1e-17, "default width of extent 2 is 0.02");
    is_num(lam_default_width(300), 2.5, 0, "default width of extent 300 is 2.5");
    is_num(lam_default_width(730), 5, 0, "default width of extent 730 is 5");

    double short_w[2] = { 0.5, 0.5 }, exact_w[2] = { 1, 1 }, zero_w[3] = { 1, 0, 1 }, neg_w[3] = { 1, -1, 2 };
    o = opts_axis('z', LAM_CUT_MIDDLE, 0);
    o.widths = short_w;
    o.nwidths = 2;
    expect_usage(m, &o, "widths 0.5 0.5 do not cover 0..2");
    o.widths = zero_w;
    o.nwidths = 3;
    expect_usage(m, &o, "widths 1 0 1");
    o.widths = neg_w;
    expect_usage(m, &o, "widths 1 -1 2");
    o.widths = exact_w;
    o.nwidths = 0;
    expect_usage(m, &o, "an empty widths list");
    o.nwidths = 2;
    run r = slice_all(m, &o, "widths 1 1");
    ok(r.n == 2 && r.L[0]->floor == 0 && r.L[1]->ceiling == 2, "widths 1 1: slabs from the model's minimum 0 to 2");
    run_free(&r);

    double eq[4] = { 0, 1, 1, 2 }, dec[3] = { 0, 2, 1 }, one[1] = { 0 }, nan_p[2] = { 0, NAN };
    o = opts_axis('z', LAM_CUT_MIDDLE, 0);
    o.planes = eq;
    o.nplanes = 4;
    expect_usage(m, &o, "planes 0 1 1 2 (repeated)");
    o.planes = dec;
    o.nplanes = 3;
    expect_usage(m, &o, "planes 0 2 1 (decreasing)");
    o.planes = one;
    o.nplanes = 1;
    expect_usage(m, &o, "a single plane");
    o.planes = nan_p;
    o.nplanes = 2;
    expect_usage(m, &o, "planes 0 NaN");

    lam_frame f;
    lam_error err;
    lam_error_clear(&err);
    is_int(lam_frame_axis('q', &f, &err), LAM_EUSAGE, "axis 'q' is a usage error");
    double zero[3] = { 0, 0, 0 };
    is_int(lam_frame_direction(zero, &f, &err), LAM_EUSAGE, "direction (0,0,0) is a usage error");
    for (int a = 0; a < 3; a++) {
        double d[3] = { 0, 0, 0 };
        d[a] = 2.5;
        lam_frame fa, fd;
        lam_frame_axis("xyz"[a], &fa, &err);
        int rc = lam_frame_direction(d, &fd, &err);
        ok(rc == LAM_OK && memcmp(&fa, &fd, sizeof fa) == 0, "direction +%c is the %c axis frame", "xyz"[a], "xyz"[a]);
    }
    lam_frame fx;
    lam_frame_axis('x', &fx, &err);
    ok(fx.u[1] == 1 && fx.v[2] == 1 && fx.w[0] == 1, "axis x frame is (u, v, w) = (y, z, x)");
    lam_frame_axis('y', &fx, &err);
    ok(fx.u[2] == 1 && fx.v[0] == 1 && fx.w[1] == 1, "axis y frame is (u, v, w) = (z, x, y)");

    /* a general direction: (1, 1, 1) through the cube [-1,1]^3 */
    lam_model *cube = load_model("thesis_cube.ug");
    if (!cube) return;
    double d[3] = { 1, 1, 1 };
    o = opts_axis('z', LAM_CUT_MIDDLE, 0);
    int rc = lam_frame_direction(d, &o.frame, &err);
    ok(rc == LAM_OK, "direction (1,1,1) gives a frame");
    const lam_frame *F = &o.frame;
    double cr[3] = { F->u[1] * F->v[2] - F->u[2] * F->v[1], F->u[2] * F->v[0] - F->u[0] * F->v[2],
                     F->u[0] * F->v[1] - F->u[1] * F->v[0] };
    double s3 = 1 / sqrt(3.0), e = 0;
    for (int k = 0; k < 3; k++) {
        e += fabs(F->w[k] - s3) + fabs(cr[k] - F->w[k]);
        e += fabs(F->u[0] * F->u[0] + F->u[1] * F->u[1] + F->u[2] * F->u[2] - 1) / 3;
        e += fabs(F->u[0] * F->v[0] + F->u[1] * F->v[1] + F->u[2] * F->v[2]) / 3;
    }
    ok(e < 1e-14, "direction (1,1,1): w = d/|d|, u unit, u . v = 0, u x v = w (err %g)", e);
    double wmin = INFINITY, wmax = -INFINITY;
    for (size_t v = 0; v < cube->mesh.nverts; v++) {
        const double *p = cube->mesh.xyz + 3 * v;
        double w = p[0] * F->w[0] + p[1] * F->w[1] + p[2] * F->w[2];
        if (w < wmin) wmin = w;
        if (w > wmax) wmax = w;
    }
    o.width = (wmax - wmin) / 200;
    r = slice_all(cube, &o, "cube along (1,1,1), 200 layers");
    is_int(r.n, 200, "cube along (1,1,1): 200 layers");
    double vol = 0;
    int nonpos = 0;
    for (size_t i = 0; i < r.n; i++) {
        double a = net_area(r.L[i]);
        if (!(a > 0)) nonpos++;
        vol += a * r.L[i]->width;
    }
    is_int(nonpos, 0, "cube along (1,1,1): every layer's net area is positive");
    ok(fabs(vol - 8) < 0.02 * 8, "cube along (1,1,1): sum area x width %.9g within 2%% of 8", vol);
    run_free(&r);
    /* the middle section, w = 0, is the regular hexagon of side sqrt 2 */
    double mid[2] = { -0.1, 0.1 };
    o.width = 0;
    o.planes = mid;
    o.nplanes = 2;
    r = slice_all(cube, &o, "cube along (1,1,1) at 0");
    if (r.n == 1) {
        /* 6 corners; in a rotated frame the points where face diagonals
         * cross the sides are in line only up to rounding, so simplification
         * (exact by design) may keep some of them: up to 12 points */
        ok(r.L[0]->ncontours == 1 && r.L[0]->contours[0].n >= 6 && r.L[0]->contours[0].n <= 12,
           "cube along (1,1,1) at 0: one hexagon (6 corners + at most 6 side points)");
        is_num(net_area(r.L[0]), 3 * sqrt(3.0), 1e-9, "cube along (1,1,1) at 0: area 3 sqrt 3");
        if (r.L[0]->ncontours == 1) is_num(r.L[0]->contours[0].perimeter, 6 * sqrt(2.0), 1e-9, "hexagon perimeter 6 sqrt 2");
    }
    run_free(&r);
    lam_model_free(cube);
}

/* ---- groups, each in a child process ------------------------------------------- */

static void group_cube_hole(void)
{
    lam_model *ch = load_model("thesis_cube_hole.ug");
    if (!ch) return;
    test_cube_hole(ch);
    static const double w1[4] = { 0.3, 0.5, 0.5, 0.5 };
    static const lam_cut c1[4] = { LAM_CUT_MIDDLE, LAM_CUT_FLOOR, LAM_CUT_CEILING, LAM_CUT_MIDDLE };
    test_rotation(ch, "cube_hole", w1, c1, 4);
    /* 10. determinism on a loaded model */
    lam_slice_opts o = opts_axis('x', LAM_CUT_FLOOR, 0.125);
    run a = slice_all(ch, &o, "cube_hole x determinism 1");
    run b = slice_all(ch, &o, "cube_hole x determinism 2");
    same_runs(&a, &b, "cube_hole along x: the same run twice");
    run_free(&a);
    run_free(&b);
    lam_model_free(ch);
}

static void group_frame_island(void)
{
    lam_model *fi = load_model("frame_island.ug");
    if (!fi) return;
    test_frame_island(fi);
    static const double w2[3] = { 2.5, 3, 2.5 };
    static const lam_cut c2[3] = { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING };
    test_rotation(fi, "frame_island", w2, c2, 3);
    lam_model_free(fi);
}

static void group_options(void)
{
    lam_model *ch = load_model("thesis_cube_hole.ug");
    if (!ch) return;
    test_options(ch);
    lam_model_free(ch);
}

/* Run one group of tests in a child process and relay its TAP lines with
 * our numbering, so that a crash (or a sanitizer abort) in the slicer is a
 * failed test and the other groups still run. */
static void group(const char *name, void (*fn)(void))
{
    int fd[2];
    fflush(stdout);
    if (pipe(fd) != 0) {
        ok(0, "%s: pipe", name);
        return;
    }
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        ok(0, "%s: fork", name);
        return;
    }
    if (pid == 0) {
        close(fd[0]);
        if (dup2(fd[1], 1) < 0) _exit(3);
        close(fd[1]);
        tap_n = tap_failed = 0; /* the child counts its own */
        fn();
        fflush(stdout);
        exit(tap_failed ? 1 : 0); /* exit, not _exit: LeakSanitizer runs at exit */
    }
    close(fd[1]);
    FILE *in = fdopen(fd[0], "r");
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int failed_here = 0;
    while (in && (len = getline(&line, &cap, in)) > 0) {
        int pass = strncmp(line, "ok ", 3) == 0, fail = strncmp(line, "not ok ", 7) == 0;
        if (pass || fail) {
            const char *rest = line + (pass ? 3 : 7);
            while (*rest >= '0' && *rest <= '9') rest++;
            ++tap_n;
            if (fail) {
                ++tap_failed;
                failed_here++;
            }
            printf("%s %d%s", pass ? "ok" : "not ok", tap_n, rest);
        } else {
            fputs(line, stdout);
        }
        fflush(stdout);
    }
    free(line);
    if (in) fclose(in);
    int st = 0;
    if (waitpid(pid, &st, 0) != pid) st = -1;
    if (WIFSIGNALED(st))
        ok(0, "%s: the group ran to its end (killed by signal %d)", name, WTERMSIG(st));
    else if (!WIFEXITED(st) || (WEXITSTATUS(st) != 0 && !failed_here))
        ok(0, "%s: the group exited cleanly (status %d: a sanitizer report?)", name, WIFEXITED(st) ? WEXITSTATUS(st) : -1);
}

/* A plane that misses a flat face by rounding is put on it. A 4 nm cube
 * with a cavity whose top face is at 3 * 1e-9 = 3.0000000000000004e-09;
 * floor cuts every 0.3 nm put plane 10 at 10 * 3e-10 = 3e-09, an ulp under
 * that face. Put on the face (plane and cut), the cut gives the section
 * just above it, the solid square alone, as a cut exactly on the face
 * would. */
static void test_snapped_planes(void)
{
    const double k = 1e-9;
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 4 * k, 4 * k, 4 * k, 0, -1);
    add_box(&mesh, 1 * k, 1 * k, 1 * k, 3 * k, 3 * k, 3 * k, BOX_INWARD, -1);
    lam_model *m = build_model_quiet(&mesh, "nanometre box with a cavity");
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.width = 3e-10;
    o.cut = LAM_CUT_FLOOR;
    run r = slice_all(m, &o, "nanometre box, floor cuts every 0.3 nm");
    ok(10 * 3e-10 < 3 * k, "(plane 10 as computed, %.17g, lies under the face at %.17g)", 10 * 3e-10, 3 * k);
    if (r.n > 10) {
        ok(r.L[10]->cut == 3 * k, "the cut of layer 10 is put on the face: %.17g", r.L[10]->cut);
        ok(r.L[10]->ncontours == 1 && r.L[9]->ncontours == 2,
           "layer 10 is the solid square alone (%zu contours), layer 9 still has the hole (%zu)",
           r.L[10]->ncontours, r.L[9]->ncontours);
        ok(r.L[10]->floor == 3 * k && r.L[9]->ceiling == r.L[10]->floor,
           "the plane moves with the cut: floor of layer 10 and ceiling of layer 9, bit for bit");
    }
    run_free(&r);
    lam_model_free(m);
}

/* lam_slicer_bytes: what a slicer holds, for a memory budget (the Lua
 * sandbox): at least its schedule (S + 1 planes, S cuts, S + 2 offsets for
 * S layers), the scratch once slicing has grown it, and the vertices'
 * layer-frame copy of an oblique frame. */
static void test_bytes(void)
{
    lam_model *m = octahedron(); /* z from -1 to 1 */
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.width = 0.01;
    lam_slicer *s = NULL;
    int rc = lam_slicer_new(m, &o, &s, NULL);
    size_t S = s ? lam_slicer_count(s) : 0, b0 = s ? lam_slicer_bytes(s) : 0;
    ok(rc == LAM_OK && S == 200 && b0 >= (3 * S + 3) * sizeof(double), "bytes: 200 layers, at least their schedule");
    lam_layer *L = NULL;
    while (s && lam_slicer_next(s, &L, NULL) == LAM_OK && L) lam_layer_free(L);
    size_t b1 = s ? lam_slicer_bytes(s) : 0;
    ok(b1 >= b0 + 64 * (3 * sizeof(uint32_t) + 2 * sizeof(double)), "bytes: the scratch slicing grew is counted");
    lam_slicer_free(s);
    const double d[3] = { 1, 1, 1 };
    lam_slice_opts_init(&o);
    o.width = 0.01;
    lam_frame_direction(d, &o.frame, NULL);
    s = NULL;
    rc = lam_slicer_new(m, &o, &s, NULL);
    size_t S2 = s ? lam_slicer_count(s) : 0, b2 = s ? lam_slicer_bytes(s) : 0;
    ok(rc == LAM_OK && b2 >= (3 * S2 + 3) * sizeof(double) + 3 * m->mesh.nverts * sizeof(double),
       "bytes: an oblique frame's copy of the vertices is counted");
    lam_slicer_free(s);
    lam_model_free(m);
}

int main(void)
{
    group("cube with hole", group_cube_hole);
    group("frame with island", group_frame_island);
    group("vertex planes and flat faces", test_vertex_planes);
    group("sphere", test_sphere);
    group("open cube", test_open);
    group("shells", test_shells);
    group("layers outside the model", test_outside);
    group("options and frames", group_options);
    group("planes put on faces they miss by rounding", test_snapped_planes);
    group("bytes held", test_bytes);
    return done_testing();
}
