/* What `lamina validate` checks beyond the labels (validate.h, section.h):
 *
 * - No false alarm next to faces just above or below the cut: plates with a
 *   counterbore whose flat face lies delta from a cutting plane (delta from
 *   1e-3 to 1e-7 of the part), at three scales, sliced along x, y, z and an
 *   oblique axis, with floor, middle and ceiling cuts on that plane and on
 *   the face itself. Every contour must be confirmed and every layer's net
 *   area and the model's own section must equal the plate's area minus the
 *   holes, worked out here from the dimensions.
 * - What is written: a solid written clockwise, a contour that is its own
 *   ancestor, depths and parents against the contours around, a layer with
 *   a contour missing (its net area against the section), a layer read
 *   back without nesting (depth -1) whose label contradicts its nesting.
 * - Contour passes read back (validate.h): each found at its inset, the
 *   passes around it not taken for parents, the first pass's area; read
 *   with another inset or distance, they disagree. */
#include "meshes.h"
#include "section.h"
#include "slice.h"
#include "validate.h"

#include <stdlib.h>
#include <string.h>

/* ---- a plate with a counterbored hole ------------------------------------------- */

typedef struct rect {
    double x0, y0, x1, y1;
} rect;

typedef struct xform {
    double r[3][3];          /* rotation applied after the z flip */
    double s;                /* scale */
    int flip;                /* z -> H - z: the counterbore opens downward */
    double H;
} xform;

static uint32_t xv(lam_mesh *m, const xform *t, double x, double y, double z)
{
    if (t->flip) z = t->H - z;
    double p[3] = { t->s * x, t->s * y, t->s * z }, q[3];
    for (int i = 0; i < 3; i++) q[i] = t->r[i][0] * p[0] + t->r[i][1] * p[1] + t->r[i][2] * p[2];
    return vtx(m, q[0], q[1], q[2]);
}

static void quad(lam_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    tri(m, a, b, c);
    tri(m, a, c, d);
}

/* The ring between rectangle o and rectangle i inside it, at height z. */
static void ring(lam_mesh *m, const xform *t, const rect *o, const rect *i, double z)
{
    double ox[4] = { o->x0, o->x1, o->x1, o->x0 }, oy[4] = { o->y0, o->y0, o->y1, o->y1 };
    double ix[4] = { i->x0, i->x1, i->x1, i->x0 }, iy[4] = { i->y0, i->y0, i->y1, i->y1 };
    for (int k = 0; k < 4; k++) {
        int l = (k + 1) % 4;
        quad(m, xv(m, t, ox[k], oy[k], z), xv(m, t, ox[l], oy[l], z), xv(m, t, ix[l], iy[l], z),
             xv(m, t, ix[k], iy[k], z));
    }
}

/* The four walls of rectangle r from z0 to z1. */
static void walls(lam_mesh *m, const xform *t, const rect *r, double z0, double z1)
{
    double x[4] = { r->x0, r->x1, r->x1, r->x0 }, y[4] = { r->y0, r->y0, r->y1, r->y1 };
    for (int k = 0; k < 4; k++) {
        int l = (k + 1) % 4;
        quad(m, xv(m, t, x[k], y[k], z0), xv(m, t, x[l], y[l], z0), xv(m, t, x[l], y[l], z1),
             xv(m, t, x[k], y[k], z1));
    }
}

/* Plate O x [0, H] with through hole B and counterbore C from the top down
 * to zc (orientation is left to the model: it rebuilds it). */
static lam_model *counterbore(const xform *t, const rect *O, const rect *B, const rect *C, double zc)
{
    lam_mesh m;
    lam_mesh_init(&m);
    ring(&m, t, O, B, 0);
    ring(&m, t, O, C, t->H);
    walls(&m, t, O, 0, t->H);
    walls(&m, t, B, 0, zc);
    ring(&m, t, C, B, zc);
    walls(&m, t, C, zc, t->H);
    return build_model_quiet(&m, "counterbored plate");
}

static void rotation(double r[3][3], double ax, double ay)
{
    double cx = cos(ax), sx = sin(ax), cy = cos(ay), sy = sin(ay);
    /* Ry(ay) * Rx(ax) */
    double R[3][3] = { { cy, sy * sx, sy * cx }, { 0, cx, -sx }, { -sy, cy * sx, cy * cx } };
    memcpy(r, R, sizeof R);
}

/* Along the model's z after the transform: the slicing direction. */
static void axis_of(const xform *t, double d[3])
{
    for (int i = 0; i < 3; i++) d[i] = t->r[i][2];
}

typedef struct run_tally {
    size_t layers, contours, confirmed, disagreeing, unchecked, areas, area_bad, wrong_expected;
} run_tally;

/* Slice m along d with the given planes and cut, validate every layer, and
 * compare each layer's net area and section with want(cut height). */
static run_tally run(lam_model *m, const double d[3], const double *planes, size_t np, lam_cut cut,
                     double (*want)(double h, void *), void *ctx, double tol, const char *what)
{
    run_tally t = { 0 };
    lam_error err;
    lam_error_clear(&err);
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    lam_frame_direction(d, &o.frame, &err);
    o.planes = planes;
    o.nplanes = np;
    o.cut = cut;
    lam_slicer *s = NULL;
    lam_rays *v = NULL;
    if (lam_slicer_new(m, &o, &s, &err) || lam_rays_new(m, &v, &err)) {
        diag("%s: %s", what, err.msg);
        t.disagreeing = 1000;
        lam_slicer_free(s);
        return t;
    }
    int shown = 0;
    for (lam_layer *L; lam_slicer_next(s, &L, &err) == LAM_OK && L; lam_layer_free(L)) {
        lam_layer_check c;
        lam_validate_opts vo;
        lam_validate_opts_init(&vo);
        if (lam_validate_layer(v, L, lam_slicer_frame(s), &vo, &c, &err)) {
            diag("%s: %s", what, err.msg);
            t.disagreeing++;
            continue;
        }
        t.layers++;
        t.contours += L->ncontours;
        t.confirmed += c.confirmed;
        t.disagreeing += c.disagreeing;
        t.unchecked += c.unchecked;
        t.areas += c.area_checked;
        t.area_bad += !c.area_ok;
        double w = want ? want(L->cut, ctx) : c.section_area;
        int bad = !(fabs(c.net_area - w) <= tol && fabs(c.section_area - w) <= tol);
        t.wrong_expected += bad;
        if ((bad || c.disagreeing || !c.area_ok) && shown++ < 3) {
            diag("%s: layer %zu (cut %.17g): net %.17g, section %.17g, expected %.17g, %zu disagreeing", what,
                 L->index, L->cut, c.net_area, c.section_area, w, c.disagreeing);
            for (size_t i = 0; i < c.nitems; i++)
                if (c.items[i].ok == 0)
                    diag("  contour %zu at (%g, %g, %g): %s", i, c.items[i].xyz[0], c.items[i].xyz[1], c.items[i].xyz[2],
                         c.items[i].why);
        }
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_slicer_free(s);
    return t;
}

typedef struct plate_areas {
    double hf, top;          /* heights along the slicing axis: the face, the plate's far side */
    int flip;                /* the counterbore is below hf (else above) */
    int below;               /* the section is taken just below the cut */
    double full, bored;      /* areas: plain holes, and where the counterbore is cut */
} plate_areas;

/* The plate's section at h, taken just above h (or below), worked out
 * from the dimensions: nothing outside [0, top], the counterbore's area
 * beyond the face. A cut on the face itself (equal heights, which the
 * oblique axis does not give exactly) goes by the step's side. */
static double plate_want(double h, void *ctx)
{
    const plate_areas *p = ctx;
    if (h < 0 || h > p->top || (h == 0 && p->below) || (h == p->top && !p->below)) return 0;
    int beyond = p->flip ? h < p->hf || (h == p->hf && p->below) : h > p->hf || (h == p->hf && !p->below);
    return beyond ? p->bored : p->full;
}

static void test_faces_near_the_cut(void)
{
    static const double scales[] = { 1, 200, 1e4 };
    static const double deltas[] = { 1e-3, 1e-4, 1e-5, 1e-6, 1e-7 };
    /* (ax, ay) rotations: z, x (z -> x), y, an oblique axis */
    static const double rots[][2] = { { 0, 0 }, { 0, 1.5707963267948966 }, { -1.5707963267948966, 0 }, { 0.4, 0.7 } };
    static const char *const rot_names[] = { "z", "x", "y", "oblique" };
    static const lam_cut cuts[] = { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING };
    static const char *const cut_names[] = { "floor", "middle", "ceiling" };
    rect O = { 0, 0, 1, 1 }, B = { 0.45, 0.45, 0.55, 0.55 }, C = { 0.4, 0.4, 0.6, 0.6 };
    double H = 0.05, c = 0.045; /* the cut: the counterbore's floor is delta above it */
    size_t runs = 0, bad_runs = 0, layers = 0, contours = 0, confirmed = 0, areas = 0;
    for (size_t si = 0; si < sizeof scales / sizeof *scales; si++)
        for (size_t di = 0; di < sizeof deltas / sizeof *deltas; di++)
            for (size_t ri = 0; ri < sizeof rots / sizeof *rots; ri++)
                for (int flip = 0; flip < 2; flip++) {
                    xform t = { .s = scales[si], .flip = flip, .H = H };
                    rotation(t.r, rots[ri][0], rots[ri][1]);
                    double zc = c + deltas[di];
                    lam_model *m = counterbore(&t, &O, &B, &C, zc);
                    if (!m) {
                        bad_runs++;
                        continue;
                    }
                    double d[3];
                    axis_of(&t, d);
                    /* flipped, the face is delta below H - c: cut there */
                    double cut = (flip ? H - c : c) * t.s;
                    double lo = -1e-3 * t.s, hi = (H + 1e-3) * t.s;
                    /* the face's plane itself as a boundary too */
                    double face = (flip ? H - zc : zc) * t.s;
                    plate_areas pa = { face, H * t.s, flip, 0, (1 - 0.01) * t.s * t.s, (1 - 0.04) * t.s * t.s };
                    double tol = 1e-9 * t.s * t.s;
                    for (size_t ci = 0; ci < 3; ci++)
                        for (int on_face = 0; on_face < 2; on_face++) {
                            double at = on_face ? face : cut;
                            /* floor and ceiling cuts on the plane itself; a
                             * middle cut between two planes around it */
                            double w = 0.002 * t.s;
                            double planes[4] = { lo, at - w, at, hi };
                            if (cuts[ci] == LAM_CUT_MIDDLE) planes[1] = at - w, planes[2] = at + w;
                            if (cuts[ci] == LAM_CUT_FLOOR) planes[1] = at, planes[2] = at + w;
                            if (planes[1] <= lo || planes[2] >= hi) continue;
                            pa.below = cuts[ci] == LAM_CUT_CEILING;
                            /* the oblique axis puts the face's corners a few
                             * ulps apart: the area there is the slicer's
                             * business, the check's is only to agree */
                            int exact = ri < 3 || !on_face;
                            char what[160];
                            snprintf(what, sizeof what, "scale %g, delta %g, axis %s, %s, %s cut %s", scales[si],
                                     deltas[di], rot_names[ri], flip ? "face below" : "face above",
                                     cut_names[ci], on_face ? "on the face" : "beside it");
                            run_tally r = run(m, d, planes, 4, cuts[ci], exact ? plate_want : NULL, &pa, tol, what);
                            runs++;
                            if (r.disagreeing || r.area_bad || r.wrong_expected || r.areas != r.layers ||
                                r.confirmed != r.contours)
                                bad_runs++;
                            layers += r.layers;
                            contours += r.contours;
                            confirmed += r.confirmed;
                            areas += r.areas;
                        }
                    lam_model_free(m);
                }
    ok(runs >= 700 && bad_runs == 0,
       "faces 1e-3 .. 1e-7 of the part above or below the cut, 3 scales, 4 axes, 3 cuts, beside and on the "
       "face: %zu runs, %zu with a disagreement, an unconfirmed contour or an area off",
       runs, bad_runs);
    ok(layers > 2000 && contours == confirmed && areas == layers,
       "... %zu layers, %zu contours all confirmed, %zu areas compared (net area and section = plate minus holes)",
       layers, confirmed, areas);
}

/* ---- what is written ----------------------------------------------------------------- */

/* thesis_cube_hole.ug at z = 1: the square (-1..1) and the hole (-0.5..0.5). */
static void square(double *uv, double h, int ccw)
{
    double p[8] = { -h, -h, h, -h, h, h, -h, h };
    for (int i = 0; i < 4; i++) {
        int j = ccw ? i : 3 - i;
        uv[2 * i] = p[2 * j];
        uv[2 * i + 1] = p[2 * j + 1];
    }
}

typedef struct hand {
    lam_layer L;
    double uv[16];
    lam_contour c[2];
} hand;

/* outer: CCW solid depth 0; inner: CW hole depth 1 inside it (as written
 * by a correct slicer), then modified by the caller. */
static void hand_layer(hand *h)
{
    memset(h, 0, sizeof *h);
    square(h->uv, 1, 1);
    square(h->uv + 8, 0.5, 0);
    h->c[0] = (lam_contour){ .first = 0, .n = 4, .depth = 0, .parent = -1, .kind = LAM_SOLID };
    h->c[1] = (lam_contour){ .first = 4, .n = 4, .depth = 1, .parent = 0, .kind = LAM_HOLE };
    h->L.index = 3;
    h->L.floor = 0.75;
    h->L.ceiling = 1.25;
    h->L.cut = 1;
    h->L.uv = h->uv;
    h->L.npoints = 8;
    h->L.contours = h->c;
    h->L.ncontours = 2;
}

/* Validate L along z with the options o (NULL: the defaults). */
static int check_layer(lam_rays *v, const lam_layer *L, const lam_validate_opts *o, lam_layer_check *c)
{
    lam_frame f;
    lam_error err;
    lam_frame_axis('z', &f, &err);
    lam_validate_opts dflt;
    lam_validate_opts_init(&dflt);
    int rc = lam_validate_layer(v, L, &f, o ? o : &dflt, c, &err);
    if (rc) diag("validate: %s", err.msg);
    return rc;
}

static int check(lam_rays *v, hand *h, lam_layer_check *c)
{
    return check_layer(v, &h->L, NULL, c);
}

/* The thesis cube with a hole and its validator: 0, or 1 after a failed test. */
static int open_validator(lam_model **m, lam_rays **v)
{
    lam_error err;
    *m = load_model("thesis_cube_hole.ug");
    *v = NULL;
    if (*m && !lam_rays_new(*m, v, &err)) return 0;
    ok(0, "validator for thesis_cube_hole.ug");
    lam_model_free(*m);
    return 1;
}

static void test_what_is_written(void)
{
    lam_model *m;
    lam_rays *v;
    if (open_validator(&m, &v)) return;
    hand h;
    lam_layer_check c;

    hand_layer(&h);
    if (!check(v, &h, &c)) {
        ok(c.confirmed == 2 && c.disagreeing == 0 && c.area_checked && c.area_ok,
           "as a slicer writes it: both confirmed, net area 3 = the section (%g, %g)", c.net_area, c.section_area);
        is_num(c.section_area, 3, 1e-12, "the model's own section at z = 1: 4 - 1");
        ok(c.items[1].depth_found == 1 && c.items[1].parent_found == 0 && c.items[0].depth_found == 0,
           "nesting found in the plane: the hole inside the square");
        lam_layer_check_free(&c);
    }

    /* a solid written clockwise with the right label: the rays agree, the
     * direction does not */
    hand_layer(&h);
    square(h.uv, 1, 0);
    if (!check(v, &h, &c)) {
        lam_contour_check *k = &c.items[0];
        ok(c.disagreeing == 1 && k->ok == 0 && k->problems == LAM_VP_DIRECTION && strstr(k->why, "clockwise"),
           "a solid written clockwise, labelled solid: a direction disagreement only ('%s')", k->why);
        is_num(k->area, -4, 1e-12, "... its signed area as written: -4");
        lam_layer_check_free(&c);
    }

    /* a contour its own parent, and two that are each other's */
    hand_layer(&h);
    h.c[1].parent = 1;
    if (!check(v, &h, &c)) {
        ok(c.items[1].ok == 0 && (c.items[1].problems & LAM_VP_ANCESTRY) && strstr(c.items[1].why, "own ancestor"),
           "a contour that is its own parent: '%s'", c.items[1].why);
        lam_layer_check_free(&c);
    }
    hand_layer(&h);
    h.c[0].parent = 1;
    h.c[0].depth = 2;
    if (!check(v, &h, &c)) {
        ok(c.items[0].ok == 0 && c.items[1].ok == 0 && strstr(c.items[0].why, "own ancestor") &&
               strstr(c.items[1].why, "own ancestor"),
           "two contours each other's parent: both their own ancestors");
        lam_layer_check_free(&c);
    }

    /* the hole said to stand alone (depth 0, no parent) but labelled hole */
    hand_layer(&h);
    h.c[1].depth = 0;
    h.c[1].parent = -1;
    if (!check(v, &h, &c)) {
        lam_contour_check *k = &c.items[1];
        ok(k->ok == 0 && (k->problems & LAM_VP_ANCESTRY) && (k->problems & LAM_VP_NESTING) &&
               !(k->problems & LAM_VP_MATERIAL),
           "a hole at depth 0: its label against its depth, and its depth against the one contour around it");
        lam_layer_check_free(&c);
    }
    /* a parent that exists but is not the one around it */
    hand_layer(&h);
    for (int i = 0; i < 4; i++) h.uv[8 + 2 * i] += 3; /* the hole moved out of the square, beside it */
    if (!check(v, &h, &c)) {
        lam_contour_check *k = &c.items[1];
        ok(k->ok == 0 && (k->problems & LAM_VP_NESTING) && k->depth_found == 0,
           "a hole outside its parent: no contour around it ('%s')", k->whys[3] ? k->whys[3] : "");
        lam_layer_check_free(&c);
    }

    /* the hole left out: each contour right, the layer's area wrong */
    hand_layer(&h);
    h.L.ncontours = 1;
    h.L.npoints = 4;
    if (!check(v, &h, &c)) {
        ok(c.confirmed == 1 && c.disagreeing == 0 && c.area_checked && !c.area_ok,
           "a layer with its hole missing: the square confirmed, the net area %g against the section's %g",
           c.net_area, c.section_area);
        lam_layer_check_free(&c);
    }

    /* read back from a program: no depth, the label from the file */
    hand_layer(&h);
    h.c[0].depth = h.c[1].depth = -1;
    h.c[0].parent = h.c[1].parent = -1;
    if (!check(v, &h, &c)) {
        ok(c.confirmed == 2 && c.area_ok && c.items[1].depth_found == 1,
           "read back (depth unknown): confirmed, the hole found inside the square");
        lam_layer_check_free(&c);
    }
    h.c[1].kind = LAM_SOLID;
    square(h.uv + 8, 0.5, 1);
    if (!check(v, &h, &c)) {
        lam_contour_check *k = &c.items[1];
        ok(k->ok == 0 && (k->problems & LAM_VP_NESTING) && (k->problems & LAM_VP_MATERIAL) &&
               !(k->problems & LAM_VP_DIRECTION) && !c.area_ok,
           "read back: the hole written as a solid (counter-clockwise): material, nesting and area disagree");
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_model_free(m);
}

/* ---- the loss check (validate.h) -------------------------------------------------- */

/* Layers whose outlines were closed across gaps or dropped are compared
 * with the gap's allowance, not skipped; the vertices moved by repair's
 * weld widen the exact comparison by that much; a model whose section does
 * not close is said so (area_open) instead. */
static void test_loss_check(void)
{
    lam_model *m;
    lam_rays *v;
    if (open_validator(&m, &v)) return;
    hand h;
    lam_layer_check c;
    lam_validate_opts o;
    lam_validate_opts_init(&o);
    o.gap = 0.5;

    /* the square's side at x = 1 bridged 0.04 inside (as a bridge across a
     * hole in the surface might be): 2 x 0.04 = 0.08 of area gone */
    hand_layer(&h);
    h.uv[2] = h.uv[4] = 0.96;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_checked && !c.area_ok && !c.area_loose && strstr(c.area_why, "against"),
           "no gap closed: 0.08 off the section is a difference (tolerance %g)", c.area_tolerance);
        lam_layer_check_free(&c);
    }
    h.L.gaps_closed = 1;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_checked && c.area_ok && c.area_loose && strstr(c.area_why, "gap closing"),
           "one gap of 0.5 bridged: within its allowance (gap / 2 x gap = %g)", c.area_tolerance);
        is_num(c.area_tolerance, 0.125, 1e-12, "... the allowance is gap^2 / 2 for one bridge");
        is_num(c.area_lost, 0.08, 1e-12, "... and the area lost is said: 3 - 2.92");
        lam_layer_check_free(&c);
    }
    o.gap = 0.2;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_checked && !c.area_ok && c.area_loose, "... with a gap of 0.2 (allowance %g) it differs",
           c.area_tolerance);
        lam_layer_check_free(&c);
    }
    /* read back, the bridges unknown: the allowance is gap / 2 x the layer's
     * perimeter (the square 7.92, the hole 4) */
    h.L.gaps_closed = 0;
    o.gaps_unknown = 1;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_ok && c.area_loose, "gaps unknown (a program read back): within gap / 2 x perimeter");
        is_num(c.area_tolerance, 0.1 * 11.92, 1e-9, "... 0.1 x 11.92");
        lam_layer_check_free(&c);
    }
    o.gaps_unknown = 0;

    /* an outline dropped open: the hole gone, so the layer holds 1 more
     * than the model; the least allowance is 1e-3 of the section */
    hand_layer(&h);
    h.L.ncontours = 1;
    h.L.npoints = 4;
    h.L.nopen = 1;
    o.gap = 0;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_checked && !c.area_ok && c.area_loose, "the hole dropped open: the layer differs");
        is_num(c.area_lost, -1, 1e-12, "... by 1 more than the model has (area_lost -1)");
        is_num(c.area_tolerance, LAM_VALIDATE_LOSS_REL * 3, 1e-12, "... against 1e-3 of the section");
        lam_layer_check_free(&c);
    }

    /* the square's corner 1e-4 off, as repair's weld may move a vertex: a
     * difference unless the check is told the vertices moved that much */
    hand_layer(&h);
    h.uv[4] = 1 + 1e-4;
    o.gap = 0.05;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(!c.area_ok && !c.area_loose, "a vertex 1e-4 off: the area differs exactly compared");
        lam_layer_check_free(&c);
    }
    o.moved = 1e-4;
    if (!check_layer(v, &h.L, &o, &c)) {
        ok(c.area_ok && !c.area_loose, "... and agrees with moved = 1e-4 (tolerance %g)", c.area_tolerance);
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_model_free(m);

    /* a box without its top: its section means nothing, and says so */
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    add_box(&mesh, -1, -1, 0, 1, 1, 2, 0, 1);
    lam_error err;
    m = build_model_quiet(&mesh, "open box");
    if (!m || lam_rays_new(m, &v, &err)) {
        ok(0, "validator for a box without its top");
        lam_model_free(m);
        return;
    }
    hand_layer(&h);
    h.L.ncontours = 1;
    h.L.npoints = 4;
    if (!check_layer(v, &h.L, NULL, &c)) {
        ok(!c.area_checked && c.area_ok && c.area_open && strstr(c.area_why, "boundary edges"),
           "an open box: the area not compared, area_open ('%s')", c.area_why);
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_model_free(m);
}

/* ---- the model's own section ----------------------------------------------------------- */

/* A closed UV sphere's sections against the polygon each ring makes: the
 * plane through a ring's vertices, taken just above and just below, and
 * between rings the area of the polygon cut from the facets, worked out here
 * from the ring radii by linear interpolation along each meridian. */
static void test_section_area(void)
{
    const double pi = acos(-1.0);
    int seg = 24, rings = 12;
    double r = 5;
    lam_model *m = uv_sphere(r, seg, rings, 7, NULL);
    if (!m) return;
    lam_frame f;
    lam_error err;
    lam_frame_axis('z', &f, &err);
    lam_section_index *x = NULL;
    if (lam_section_index_new(m, &f, &x, &err)) {
        ok(0, "section index: %s", err.msg);
        lam_model_free(m);
        return;
    }
    /* a regular seg-gon of circumradius rho has area seg/2 rho^2 sin(2 pi/seg) */
    double k = seg / 2.0 * sin(2 * pi / seg);
    int bad = 0;
    for (int j = 0; j < rings; j++) {
        double z0 = r * cos(pi * j / rings), z1 = r * cos(pi * (j + 1) / rings);
        double r0 = r * sin(pi * j / rings), r1 = r * sin(pi * (j + 1) / rings);
        for (int q = 1; q < 4; q++) {
            double t = q / 4.0, z = z0 + t * (z1 - z0), rho = r0 + t * (r1 - r0);
            lam_section_measure sm;
            lam_section_measure_at(x, z, 0, &sm);
            if (!(fabs(sm.area - k * rho * rho) <= 1e-9 * r * r) || !sm.closed || sm.solid_shells != 1) {
                if (bad++ < 3) diag("z = %g: %.17g, expected %.17g", z, sm.area, k * rho * rho);
            }
        }
        if (j == 0) continue;
        /* on ring j: just above and just below give the ring's polygon */
        lam_section_measure up, down;
        lam_section_measure_at(x, z0, 0, &up);
        lam_section_measure_at(x, z0, 1, &down);
        if (!(fabs(up.area - k * r0 * r0) <= 1e-9 * r * r) || !(fabs(down.area - k * r0 * r0) <= 1e-9 * r * r))
            if (bad++ < 3) diag("ring %d: %.17g / %.17g, expected %.17g", j, up.area, down.area, k * r0 * r0);
    }
    ok(bad == 0, "sphere sections (randomly flipped triangles, re-oriented by the model) between and on rings");
    lam_section_measure sm;
    lam_section_measure_at(x, r, 0, &sm);
    ok(sm.area == 0 && sm.segments == 0, "just above the north pole: nothing");
    lam_section_measure_at(x, -r, 0, &sm);
    ok(sm.area == 0 && sm.perimeter == 0,
       "just above the south pole (a vertex on the plane counts below): segments of no length, no area");
    /* a height read back near ring 3's plane snaps to it within the tolerance only */
    double ring3 = 0, snapped = 0, kept = 0;
    for (size_t i = 0; i < m->mesh.nverts; i++)
        if (fabs(m->mesh.xyz[3 * i + 2] - r * cos(pi * 3 / rings)) < 1e-9) ring3 = m->mesh.xyz[3 * i + 2];
    lam_section_snap(x, ring3 + 4e-7, 5e-7, &snapped, &err);
    lam_section_snap(x, ring3 + 4e-7, 1e-7, &kept, &err);
    ok(ring3 != 0 && snapped == ring3 && kept == ring3 + 4e-7, "snap: to the ring's height within 5e-7, not within 1e-7");
    lam_section_index_free(x);
    lam_model_free(m);
}


/* ---- contour passes read back ------------------------------------------------------------ */

/* thesis_cube_hole.ug at z = 1 as an SLS planner writes it with two passes,
 * the first `c` inside the section (beam offset), the next `d` further in:
 * squares 1 - c and 1 - c - d (solids, counter-clockwise), holes 0.5 + c
 * and 0.5 + c + d (clockwise), pass 0 first; read back (depth -1). */
typedef struct passes_layer {
    lam_layer L;
    double uv[32];
    lam_contour c[4];
} passes_layer;

static void passes_make(passes_layer *h, double c, double d)
{
    memset(h, 0, sizeof *h);
    for (int k = 0; k < 2; k++) {
        double e = c + k * d;
        square(h->uv + 16 * k, 1 - e, 1);
        square(h->uv + 16 * k + 8, 0.5 + e, 0);
        h->c[2 * k] = (lam_contour){ .first = 8 * (size_t)k, .n = 4, .depth = -1, .parent = -1, .kind = LAM_SOLID };
        h->c[2 * k + 1] = (lam_contour){ .first = 8 * (size_t)k + 4, .n = 4, .depth = -1, .parent = -1, .kind = LAM_HOLE };
    }
    h->L.index = 3;
    h->L.floor = 0.75;
    h->L.ceiling = 1.25;
    h->L.cut = 1;
    h->L.uv = h->uv;
    h->L.npoints = 16;
    h->L.contours = h->c;
    h->L.ncontours = 4;
}

static int passes_check(lam_rays *v, passes_layer *h, int n, double inset, double dist, lam_layer_check *c)
{
    lam_validate_opts o;
    lam_validate_opts_init(&o);
    o.passes = n;
    o.inset = inset;
    o.pass_distance = dist;
    return check_layer(v, &h->L, &o, c);
}

static void test_passes(void)
{
    lam_model *m;
    lam_rays *v;
    if (open_validator(&m, &v)) return;
    passes_layer h;
    lam_layer_check c;
    /* beam offset 0.05, passes 0.1 apart: right */
    passes_make(&h, 0.05, 0.1);
    if (!passes_check(v, &h, 2, 0.05, 0.1, &c)) {
        ok(c.confirmed == 4 && c.disagreeing == 0, "two passes, the first 0.05 in, read as such: 4 confirmed");
        ok(c.items[0].pass == 0 && c.items[1].pass == 0 && c.items[2].pass == 1 && c.items[3].pass == 1,
           "... the square and hole at 0.05 found as pass 0, those at 0.15 as pass 1");
        /* pass 0's net area: 1.9^2 - 1.1^2 = 2.4, at most the section's 3 */
        ok(c.area_checked && c.area_ok && fabs(c.net_area - 2.4) < 1e-9 && strstr(c.area_why, "at most"),
           "... the first pass's net area (%g = 1.9^2 - 1.1^2) at most the section's (%g)", c.net_area, c.section_area);
        lam_layer_check_free(&c);
    }
    /* the same program checked as if the passes had no beam offset, or
     * were 0.2 apart: the contours are not where the passes would be */
    if (!passes_check(v, &h, 2, 0, 0.1, &c)) {
        ok(c.disagreeing == 4, "read without the beam offset: all 4 disagree (%zu)", c.disagreeing);
        lam_layer_check_free(&c);
    }
    if (!passes_check(v, &h, 2, 0.05, 0.2, &c)) {
        ok(c.confirmed == 2 && c.items[2].ok == 0 && c.items[3].ok == 0,
           "read as 0.2 apart: pass 0 confirmed, the inner pass disagrees");
        lam_layer_check_free(&c);
    }
    /* no beam offset, two passes: the first is the section itself */
    passes_make(&h, 0, 0.1);
    if (!passes_check(v, &h, 2, 0, 0.1, &c)) {
        ok(c.confirmed == 4 && c.area_ok && fabs(c.net_area - 3) < 1e-9 && strstr(c.area_why, "against"),
           "two passes, the first the section: 4 confirmed, its net area 3 = the section");
        lam_layer_check_free(&c);
    }
    /* ... and read as one pass (the old reading): the inner pass's labels
     * contradict the nesting */
    if (!passes_check(v, &h, 1, 0, 0, &c)) {
        ok(c.disagreeing >= 2 && !c.area_ok, "the same read as one pass: the inner pass disagrees (%zu), the area too",
           c.disagreeing);
        lam_layer_check_free(&c);
    }
    /* a hole labelled solid in the inner pass (written counter-clockwise) */
    passes_make(&h, 0.05, 0.1);
    h.c[3].kind = LAM_SOLID;
    square(h.uv + 24, 0.65, 1);
    if (!passes_check(v, &h, 2, 0.05, 0.1, &c)) {
        ok(c.items[3].ok == 0 && c.confirmed == 3, "an inner-pass hole written as a solid: it disagrees, the rest confirmed");
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_model_free(m);
}

int main(void)
{
    test_faces_near_the_cut();
    test_what_is_written();
    test_loss_check();
    test_section_area();
    test_passes();
    return done_testing();
}
