/* Embree validation (SPEC 6): winding numbers at chosen points of hand-built
 * and thesis models (inside, outside, in holes, moats and cavities, where
 * bodies overlap), rays aimed exactly through the mesh's vertices, edges and
 * face diagonals, every layer of the thesis models along x, y and z with
 * floor, middle and ceiling cuts (planes through vertices and flat faces
 * included) confirmed, a flipped label found at its layer and contour, and
 * overlapping shells: a disagreement under even-odd, confirmed under
 * non-zero.
 *
 * Expected values come from the geometry (which box a point is in), never
 * from the program's output. */
#include "contour.h"
#include "mesh.h"
#include "model.h"
#include "meshes.h"
#include "slice.h"
#include "test_hooks.h"
#include "validate.h"

#include <stdint.h>
#include <stdlib.h>

/* ---- helpers ----------------------------------------------------------------- */

static lam_rays *validator(const lam_model *m, const char *what)
{
    lam_error err;
    lam_error_clear(&err);
    lam_rays *v = NULL;
    int rc = m ? lam_rays_new(m, &v, &err) : LAM_EUSAGE;
    ok(rc == LAM_OK && v, "validator for %s", what);
    if (rc && m) diag("%s", err.msg);
    return rc ? NULL : v;
}

/* Winding at p, or -99 on an error (printed). */
static int wind(lam_rays *v, double x, double y, double z)
{
    double p[3] = { x, y, z };
    int w = -99;
    lam_error err;
    lam_error_clear(&err);
    if (!v) return -99;
    if (lam_rays_winding(v, p, &w, &err)) {
        diag("winding at (%g, %g, %g): %s", x, y, z, err.msg);
        return -99;
    }
    return w;
}

typedef struct pt {
    double p[3];
    int w;
    const char *what;
} pt;

static void windings(lam_rays *v, const pt *pts, size_t n, const char *model)
{
    for (size_t i = 0; i < n; i++)
        is_int(wind(v, pts[i].p[0], pts[i].p[1], pts[i].p[2]), pts[i].w, "%s: winding %d %s", model,
               pts[i].w, pts[i].what);
}

/* ---- layers -------------------------------------------------------------------- */

/* lam_validate_layer with the default options but the fill rule. */
static int validate_layer(lam_rays *v, const lam_layer *L, const lam_frame *f, int fill_nonzero,
                          lam_layer_check *out, lam_error *err)
{
    lam_validate_opts o;
    lam_validate_opts_init(&o);
    o.fill_nonzero = fill_nonzero;
    return lam_validate_layer(v, L, f, &o, out, err);
}

typedef struct tally {
    size_t layers, contours, checked, confirmed, disagreeing, unchecked, errors;
    size_t mislabelled;  /* contours whose label contradicts their nesting */
    size_t unexplained;  /* disagreements on other contours */
    size_t missed;       /* mislabelled contours not reported */
} tally;

/* Independent of the validator: is contour c's label wrong by its nesting,
 * counting containers in the closed sense (a contour whose bounding box
 * lies within a larger contour's box, edges allowed to touch)? The slicer
 * nests by a ray from the lowest-leftmost vertex, which misses a container
 * when that vertex lies on the container's boundary (loops that share
 * edges: a cavity touching the part's faces, cut across). */
static int mislabelled(const lam_layer *L, size_t c)
{
    const lam_contour *k = &L->contours[c];
    int depth = 0;
    for (size_t o = 0; o < L->ncontours; o++) {
        const lam_contour *q = &L->contours[o];
        if (o == c || !(fabs(q->area) > fabs(k->area))) continue;
        if (q->bbox[0] <= k->bbox[0] && q->bbox[1] <= k->bbox[1] && q->bbox[2] >= k->bbox[2] &&
            q->bbox[3] >= k->bbox[3])
            depth++;
    }
    return (depth % 2 ? LAM_HOLE : LAM_SOLID) != k->kind;
}

/* Slice m with opts and validate every layer; optionally flip the label of
 * contour flip_c of layer flip_l first. The checks of the first nkept
 * layers are kept in kept[] (zeroed first; the caller frees them).
 * Unexpected results are printed unless quiet. */
static tally slice_validate(const lam_model *m, lam_rays *v, const lam_slice_opts *o, size_t flip_l,
                            size_t flip_c, lam_layer_check *kept, size_t nkept, int quiet, const char *what)
{
    tally t = { 0 };
    lam_error err;
    lam_error_clear(&err);
    if (kept) memset(kept, 0, nkept * sizeof *kept);
    lam_slicer *s = NULL;
    if (lam_slicer_new(m, o, &s, &err)) {
        diag("%s: %s", what, err.msg);
        t.errors++;
        return t;
    }
    int shown = 0;
    for (;;) {
        lam_layer *L = NULL;
        if (lam_slicer_next(s, &L, &err)) {
            diag("%s: %s", what, err.msg);
            t.errors++;
            break;
        }
        if (!L) break;
        if (L->index == flip_l) lam_layer_flip_label_for_test(L, flip_c);
        lam_layer_check c;
        if (validate_layer(v, L, lam_slicer_frame(s), o->fill_nonzero, &c, &err)) {
            diag("%s layer %zu: %s", what, L->index, err.msg);
            t.errors++;
        } else {
            t.layers++;
            t.contours += L->ncontours;
            t.checked += c.checked;
            t.confirmed += c.confirmed;
            t.disagreeing += c.disagreeing;
            t.unchecked += c.unchecked;
            if (c.index != L->index || c.nitems != L->ncontours) t.errors++;
            for (size_t i = 0; i < c.nitems && L->index != flip_l; i++) {
                int wrong = mislabelled(L, i);
                t.mislabelled += wrong;
                t.missed += wrong && c.items[i].ok != 0;
                t.unexplained += !wrong && c.items[i].ok == 0;
                if (c.items[i].ok != 1 && !wrong && !quiet && shown++ < 4)
                    diag("%s layer %zu (cut %.17g) contour %zu: ok %d at (%.17g, %.17g) winding %d: %s", what,
                         L->index, L->cut, i, c.items[i].ok, c.items[i].uv[0], c.items[i].uv[1],
                         c.items[i].winding_found, c.items[i].why);
            }
            if (kept && L->index < nkept) kept[L->index] = c;
            else lam_layer_check_free(&c);
        }
        lam_layer_free(L);
    }
    lam_slicer_free(s);
    return t;
}

static const char *cut_name(lam_cut c)
{
    return c == LAM_CUT_FLOOR ? "floor" : c == LAM_CUT_CEILING ? "ceiling" : "middle";
}

/* Every layer along x, y and z, with every cut and each width: all contours
 * checked, none disagreeing -- except contours the slicer mislabels (see
 * mislabelled()), which must all be reported. */
static void all_layers_confirmed(const lam_model *m, lam_rays *v, const double *widths, size_t nw,
                                 int fill_nonzero, const char *name)
{
    static const char axes[3] = { 'x', 'y', 'z' };
    static const lam_cut cuts[3] = { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING };
    if (!m || !v) {
        ok(0, "%s: layers validated", name);
        return;
    }
    for (int a = 0; a < 3; a++) {
        tally sum = { 0 };
        for (int c = 0; c < 3; c++)
            for (size_t wi = 0; wi < nw; wi++) {
                lam_slice_opts o;
                lam_slice_opts_init(&o);
                lam_error err;
                lam_frame_axis(axes[a], &o.frame, &err);
                o.cut = cuts[c];
                o.width = widths[wi];
                o.fill_nonzero = fill_nonzero;
                char what[128];
                snprintf(what, sizeof what, "%s %c %s %g", name, axes[a], cut_name(cuts[c]), widths[wi]);
                tally t = slice_validate(m, v, &o, SIZE_MAX, 0, NULL, 0, 0, what);
                sum.layers += t.layers;
                sum.contours += t.contours;
                sum.checked += t.checked;
                sum.confirmed += t.confirmed;
                sum.disagreeing += t.disagreeing;
                sum.unchecked += t.unchecked;
                sum.errors += t.errors;
                sum.mislabelled += t.mislabelled;
                sum.unexplained += t.unexplained;
                sum.missed += t.missed;
            }
        ok(sum.errors == 0 && sum.layers > 0 && sum.contours > 0 && sum.checked == sum.contours &&
               sum.unexplained == 0 && sum.missed == 0 && sum.mislabelled == 0 && sum.disagreeing == 0 &&
               sum.confirmed == sum.contours,
           "%s along %c: %zu layers, %zu contours, all checked and confirmed: zero disagreements", name,
           axes[a], sum.layers, sum.contours);
        if (sum.mislabelled)
            diag("%s along %c: %zu contours mislabelled by the slicer (touching loops), all reported", name,
                 axes[a], sum.mislabelled);
        if (sum.unexplained || sum.missed || sum.unchecked || sum.errors)
            diag("%zu checked, %zu confirmed, %zu disagreeing (%zu unexplained, %zu mislabelled missed), "
                 "%zu unchecked, %zu errors",
                 sum.checked, sum.confirmed, sum.disagreeing, sum.unexplained, sum.missed, sum.unchecked,
                 sum.errors);
    }
}

/* ---- tests ----------------------------------------------------------------------- */

/* Points p = q - s * d_k whose ray k passes exactly through q, a vertex, an
 * edge or a face diagonal of the unit cube, for every direction k: inside
 * points have winding 1, outside 0. Points within 1e-3 of the surface are
 * left out. */
static void rays_through_features(lam_rays *v)
{
    double feat[64][3];
    size_t nf = 0;
    for (int i = 0; i < 8; i++) { /* vertices */
        feat[nf][0] = i & 1;
        feat[nf][1] = (i >> 1) & 1;
        feat[nf][2] = (i >> 2) & 1;
        nf++;
    }
    for (int ax = 0; ax < 3; ax++) /* midpoints and a quarter of the 12 edges */
        for (int j = 0; j < 4; j++) {
            double q[3];
            q[ax] = ax == 0 ? 0.5 : 0.25;
            q[(ax + 1) % 3] = j & 1;
            q[(ax + 2) % 3] = (j >> 1) & 1;
            memcpy(feat[nf++], q, sizeof q);
        }
    for (int f = 0; f < 6; f++) { /* the diagonal every face is split along */
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = (BOX_QUADS[f][0] >> k) & 1;
            b[k] = (BOX_QUADS[f][2] >> k) & 1;
        }
        for (int k = 0; k < 3; k++) feat[nf][k] = a[k] + 0.5 * (b[k] - a[k]); /* face centre */
        nf++;
        for (int k = 0; k < 3; k++) feat[nf][k] = a[k] + 0.3 * (b[k] - a[k]);
        nf++;
    }
    static const double S[3] = { 0.3, 0.55, 0.8 };
    size_t tested = 0, wrong = 0, in = 0;
    for (size_t i = 0; i < nf; i++)
        for (size_t k = 0; lam_rays_direction(k); k++)
            for (int si = 0; si < 3; si++) {
                const double *d = lam_rays_direction(k);
                double p[3];
                int inside = 1, outside = 0;
                for (int j = 0; j < 3; j++) {
                    p[j] = feat[i][j] - S[si] * d[j];
                    if (!(p[j] > 1e-3 && p[j] < 1 - 1e-3)) inside = 0;
                    if (p[j] < -1e-3 || p[j] > 1 + 1e-3) outside = 1;
                }
                if (!inside && !outside) continue;
                tested++;
                in += inside;
                int w = wind(v, p[0], p[1], p[2]);
                if (w != inside) {
                    if (wrong++ < 5)
                        diag("ray %zu through (%g, %g, %g) from (%.17g, %.17g, %.17g): winding %d, expected %d",
                             k, feat[i][0], feat[i][1], feat[i][2], p[0], p[1], p[2], w, inside);
                }
            }
    ok(wrong == 0 && tested > 1000 && in > 100 && tested - in > 100,
       "unit cube: %zu points (%zu inside) whose rays pass exactly through vertices, edges and face "
       "diagonals: all right",
       tested, in);
}

static void test_unit_cube(void)
{
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 1, 1, 1, 0, -1);
    lam_model *m = build_model(&mesh, "unit cube");
    lam_rays *v = validator(m, "unit cube");
    /* +1 inside proves the sign convention end to end: each crossing must
     * agree with Embree's Ng = (v1 - v0) x (v2 - v0), or every ray would be
     * discarded and no winding decided */
    static const pt P[] = {
        { { 0.5, 0.5, 0.5 }, 1, "at the centre" },
        { { 0.1, 0.9, 0.2 }, 1, "near a corner, inside" },
        { { 0.3, 0.3, 0.7 }, 1, "on the diagonal plane x = y, inside" },
        { { 0.5, 0.5, 0.5 - 0.4 }, 1, "under the centre" },
        { { 2, 0.5, 0.5 }, 0, "beyond +x" },
        { { -1, -1, -1 }, 0, "beyond the origin corner" },
        { { 0.5, 0.5, 1.5 }, 0, "above" },
        { { 1.2, 1.2, 0.5 }, 0, "on the diagonal plane x = y, outside" },
        { { 0.5, 0.5, 1 + 1e-4 }, 0, "just above the top face" },
        { { 0.5, 0.5, 1 - 1e-4 }, 1, "just under the top face" },
    };
    windings(v, P, sizeof P / sizeof P[0], "unit cube");
    if (v) {
        double p[3] = { 0.5, 0.5, 1 };
        int w = 7;
        lam_error err;
        lam_error_clear(&err);
        int rc = lam_rays_winding(v, p, &w, &err);
        ok(rc == LAM_EGEOM && strstr(err.msg, "on the surface") && w == 7,
           "a point on the top face has no winding number (LAM_EGEOM, '%s')", err.msg);
        rays_through_features(v);
        lam_rays_stats s;
        lam_rays_get_stats(v, &s);
        diag("unit cube: %zu points, %zu rays, %zu re-cast, %zu rays discarded (grazing or mixed signs), "
             "%zu on the surface, %zu undecided",
             s.points, s.rays, s.recasts, s.unreliable, s.surface, s.undecided);
        /* the same answers every time, from a second validator too */
        lam_rays *v2 = validator(m, "unit cube, again");
        int same = v2 != NULL;
        for (int i = 0; i < 200 && same; i++) {
            double q[3] = { -0.31 + 1.6 * (i % 7) / 6.0, -0.29 + 1.6 * (i % 11) / 10.0,
                            -0.27 + 1.6 * (i % 13) / 12.0 };
            int a = -1, b = -2, c = -3;
            int ra = lam_rays_winding(v, q, &a, &err), rb = lam_rays_winding(v, q, &b, &err),
                rc2 = lam_rays_winding(v2, q, &c, &err);
            same = ra == LAM_OK && rb == LAM_OK && rc2 == LAM_OK && a == b && b == c;
        }
        ok(same, "deterministic: 200 points give the same windings twice and from a second validator");
        lam_rays_free(v2);
    }
    ok(lam_rays_direction(0) && !lam_rays_direction(16), "sixteen fixed ray directions");
    lam_rays_free(v);
    lam_model_free(m);
}

static void test_thesis_models(void)
{
    lam_model *m = load_model("thesis_cube_hole.ug");
    lam_rays *v = validator(m, "thesis_cube_hole.ug");
    static const pt H[] = {
        { { 0, 0, 1 }, 0, "in the hole" },
        { { 0.2, -0.3, 0.4 }, 0, "in the hole, off centre" },
        { { 0.75, 0, 1 }, 1, "in the wall (+x)" },
        { { 0, -0.75, 0.5 }, 1, "in the wall (-y)" },
        { { 0.75, 0.75, 1.9 }, 1, "in the wall's corner" },
        { { 2, 0, 1 }, 0, "outside" },
        { { 0, 0, -0.5 }, 0, "under the hole" },
        { { 0, 0, 2.5 }, 0, "over the hole" },
    };
    windings(v, H, sizeof H / sizeof H[0], "thesis_cube_hole");
    if (v) {
        double p[3] = { 0.5, 0.5, 1 };
        int w = 0;
        lam_error err;
        lam_error_clear(&err);
        ok(lam_rays_winding(v, p, &w, &err) == LAM_EGEOM && strstr(err.msg, "on the surface"),
           "thesis_cube_hole: a point on the hole's edge has no winding number");
    }
    static const double wh[] = { 1, 0.5, 0.25, 0.3 };
    all_layers_confirmed(m, v, wh, 4, 0, "thesis_cube_hole");

    /* a flipped label is found at its layer and contour, with its position */
    if (m && v) {
        lam_slice_opts o;
        lam_slice_opts_init(&o);
        o.width = 0.5;
        o.cut = LAM_CUT_MIDDLE;
        lam_layer_check cs[3], c;
        tally t = slice_validate(m, v, &o, 2, 1, cs, 3, 1, "hole flipped");
        c = cs[2];
        lam_layer_check_free(&cs[0]);
        lam_layer_check_free(&cs[1]);
        is_int(t.disagreeing, 1, "flipped hole: one disagreement in the run");
        int found = c.nitems == 2 && c.index == 2 && c.items[1].ok == 0 && c.items[0].ok == 1;
        ok(found, "flipped hole: reported at layer 2, contour 1");
        if (found) {
            const lam_contour_check *k = &c.items[1];
            double e = fmax(fabs(k->uv[0]), fabs(k->uv[1]));
            /* the hole's CW traversal has the wall on its left: the label
             * (solid) says that side is void, it is material */
            ok(e > 0.5 && e < 0.5 + 0.01, "flipped hole: position (%g, %g) just outside the hole's edge",
               k->uv[0], k->uv[1]);
            ok(k->xyz[0] == k->uv[0] && k->xyz[1] == k->uv[1] && k->xyz[2] == 1.25,
               "flipped hole: lifted to (%g, %g, %g) at the cut", k->xyz[0], k->xyz[1], k->xyz[2]);
            is_int(k->winding_found, 1, "flipped hole: winding 1 found");
            is_int(k->expected_material, 0, "flipped hole: the label claims void there");
            ok(k->edges == 4, "flipped hole: 4 edges tested");
        }
        lam_layer_check_free(&c);

        o.cut = LAM_CUT_FLOOR;
        t = slice_validate(m, v, &o, 0, 0, &c, 1, 1, "outer flipped");
        is_int(t.disagreeing, 1, "flipped outer square on the bottom face: one disagreement");
        found = c.nitems == 2 && c.index == 0 && c.items[0].ok == 0 && c.items[1].ok == 1;
        ok(found, "flipped outer square: reported at layer 0, contour 0");
        if (found) {
            const lam_contour_check *k = &c.items[0];
            double e = fmax(fabs(k->uv[0]), fabs(k->uv[1]));
            ok(e < 1 && e > 1 - 0.01, "flipped outer square: position (%g, %g) just inside its edge", k->uv[0],
               k->uv[1]);
            ok(k->xyz[2] == 0,
               "flipped outer square: on the bottom face, kept in the cut plane (z = %g): the symbolic step "
               "into the slab decides",
               k->xyz[2]);
            is_int(k->winding_found, 1, "flipped outer square: winding 1 found");
            is_int(k->expected_material, 0, "flipped outer square: the label claims void there");
        }
        lam_layer_check_free(&c);
    }
    lam_rays_free(v);
    lam_model_free(m);

    m = load_model("frame_island.ug");
    v = validator(m, "frame_island.ug");
    static const pt F[] = {
        { { 0, 0, 0 }, 1, "in the island" },
        { { 3, -4, 9 }, 1, "in the island, near its top" },
        { { 10, 0, 0 }, 0, "in the moat" },
        { { -7, 12, 5 }, 0, "in the moat's corner" },
        { { 17.5, 0, 0 }, 1, "in the frame" },
        { { -18, -18, -9 }, 1, "in the frame's corner" },
        { { 25, 0, 0 }, 0, "outside" },
        { { 0, 0, 15 }, 0, "above the island" },
    };
    windings(v, F, sizeof F / sizeof F[0], "frame_island");
    static const double wf[] = { 5, 2.5, 1 };
    all_layers_confirmed(m, v, wf, 3, 0, "frame_island");
    lam_rays_free(v);
    lam_model_free(m);

    m = load_model("thesis_cube.ug");
    v = validator(m, "thesis_cube.ug");
    static const double wc[] = { 1, 0.5, 0.3 };
    all_layers_confirmed(m, v, wc, 3, 0, "thesis_cube");
    lam_rays_free(v);
    lam_model_free(m);
}

/* A box with a box-shaped cavity: the model turns the inner shell inward,
 * so its inside has winding 0. And a thin-walled tube, where the test
 * points must stay closer to their edge than the wall is thick. */
static void test_cavity_and_thin_wall(void)
{
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 4, 4, 4, 0, -1);
    add_box(&mesh, 1, 1, 1, 3, 3, 3, 0, -1);
    lam_model *m = build_model(&mesh, "box with a cavity");
    lam_rays *v = validator(m, "box with a cavity");
    static const pt C[] = {
        { { 2, 2, 2 }, 0, "in the cavity" },
        { { 0.5, 2, 2 }, 1, "in the wall" },
        { { 2, 2, 3.5 }, 1, "over the cavity" },
        { { 5, 2, 2 }, 0, "outside" },
    };
    windings(v, C, sizeof C / sizeof C[0], "box with a cavity");
    static const double w[] = { 1, 0.5 };
    all_layers_confirmed(m, v, w, 2, 0, "box with a cavity");
    lam_rays_free(v);
    lam_model_free(m);

    /* a square tube, one shell, wall 0.01 thick on a model 10 across: the
     * preferred inset (1e-3 of the size) equals the thickness, so the test
     * points must be pulled in toward their edge */
    lam_mesh_init(&mesh);
    uint32_t o[8], in[8];
    for (int i = 0; i < 8; i++) {
        o[i] = vtx(&mesh, i & 1 ? 10 : 0, i & 2 ? 10 : 0, i & 4 ? 10 : 0);
        in[i] = vtx(&mesh, i & 1 ? 9.99 : 0.01, i & 2 ? 9.99 : 0.01, i & 4 ? 10 : 0);
    }
    /* side faces of the outer box (outward) and the inner one (inward):
     * BOX_QUADS 2..5 are the sides */
    for (int f = 2; f < 6; f++) {
        const int *q = BOX_QUADS[f];
        tri(&mesh, o[q[0]], o[q[1]], o[q[2]]);
        tri(&mesh, o[q[0]], o[q[2]], o[q[3]]);
        tri(&mesh, in[q[0]], in[q[2]], in[q[1]]);
        tri(&mesh, in[q[0]], in[q[3]], in[q[2]]);
    }
    /* caps: ring between the outer and inner square at z = 0 and z = 10 */
    static const int ring[4] = { 0, 1, 3, 2 }; /* corners in CCW order seen from +z */
    for (int z = 0; z < 2; z++)
        for (int i = 0; i < 4; i++) {
            int a = ring[i] | (z << 2), b = ring[(i + 1) % 4] | (z << 2);
            if (z) {
                tri(&mesh, o[a], o[b], in[b]);
                tri(&mesh, o[a], in[b], in[a]);
            } else {
                tri(&mesh, o[a], in[b], o[b]);
                tri(&mesh, o[a], in[a], in[b]);
            }
        }
    m = build_model(&mesh, "thin-walled tube");
    v = validator(m, "thin-walled tube");
    static const pt T[] = {
        { { 0.005, 5, 5 }, 1, "in the wall" },
        { { 5, 5, 5 }, 0, "in the bore" },
        { { 5, 9.995, 1 }, 1, "in the far wall" },
    };
    windings(v, T, sizeof T / sizeof T[0], "thin-walled tube");
    static const double wt[] = { 2.5, 1 };
    all_layers_confirmed(m, v, wt, 2, 0, "thin-walled tube");
    lam_rays_free(v);
    lam_model_free(m);
}

/* Two cubes [0,2]^3 and [1,3]^3 as separate shells, built here and read
 * from the fixture validate/overlap_cubes.ug. */
static void test_overlap(void)
{
    lam_model *fm = load_model("validate/overlap_cubes.ug");
    lam_rays *fv = validator(fm, "validate/overlap_cubes.ug");
    if (fm) is_int(fm->nshells, 2, "overlap_cubes.ug: two shells");
    is_int(wind(fv, 1.5, 1.5, 1.5), 2, "overlap_cubes.ug: winding 2 where the cubes overlap");
    is_int(wind(fv, 2.5, 1.5, 2.5), 1, "overlap_cubes.ug: winding 1 in the second only");
    lam_rays_free(fv);
    lam_model_free(fm);

    lam_mesh mesh;
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 2, 2, 2, 0, -1);
    add_box(&mesh, 1, 1, 1, 3, 3, 3, 0, -1);
    lam_model *m = build_model(&mesh, "overlapping cubes");
    lam_rays *v = validator(m, "overlapping cubes");
    static const pt P[] = {
        { { 1.5, 1.5, 1.5 }, 2, "where they overlap" },
        { { 0.5, 0.5, 0.5 }, 1, "in the first only" },
        { { 2.5, 2.5, 2.5 }, 1, "in the second only" },
        { { 0.5, 2.5, 1.5 }, 0, "in neither" },
    };
    windings(v, P, sizeof P / sizeof P[0], "overlapping cubes");
    if (!m || !v) {
        ok(0, "overlapping cubes: layers");
        lam_rays_free(v);
        lam_model_free(m);
        return;
    }

    /* even-odd: layers 2 and 3 (cuts 1.25 and 1.75) have the second square
     * labelled a hole inside the first; validation disagrees there only */
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.width = 0.5;
    o.cut = LAM_CUT_MIDDLE;
    o.fill_nonzero = 0;
    lam_layer_check cs[6];
    tally t = slice_validate(m, v, &o, SIZE_MAX, 0, cs, 6, 1, "overlap evenodd");
    ok(t.errors == 0 && t.layers == 6 && t.disagreeing == 2, "evenodd: 6 layers, 2 disagreeing contours");
    for (size_t li = 0; li < 6; li++) {
        const lam_layer_check *c = &cs[li];
        if (li == 2 || li == 3) {
            int at_hole = c->nitems == 2 && c->items[0].ok == 1 && c->items[1].ok == 0 && c->disagreeing == 1;
            ok(at_hole, "evenodd layer %zu: the overlap's hole contour disagrees (at %g, %g: winding %d, %s)", li,
               c->nitems > 1 ? c->items[1].uv[0] : 0, c->nitems > 1 ? c->items[1].uv[1] : 0,
               c->nitems > 1 ? c->items[1].winding_found : 0, c->nitems > 1 ? c->items[1].why : "");
        } else {
            ok(c->nitems == 1 && c->confirmed == 1, "evenodd layer %zu: one square, confirmed", li);
        }
        lam_layer_check_free(&cs[li]);
    }

    /* non-zero: one merged outline per layer, confirmed */
    o.fill_nonzero = 1;
    t = slice_validate(m, v, &o, SIZE_MAX, 0, cs, 3, 0, "overlap nonzero");
    lam_layer_check c = cs[2];
    lam_layer_check_free(&cs[0]);
    lam_layer_check_free(&cs[1]);
    ok(t.errors == 0 && t.layers == 6 && t.disagreeing == 0 && t.confirmed == t.contours && t.contours == 6,
       "nonzero: 6 layers, one contour each, all confirmed");
    ok(c.nitems == 1 && c.items[0].ok == 1 && c.items[0].edges == 4,
       "nonzero layer 2: the merged outline confirmed on 4 edges");
    lam_layer_check_free(&c);
    static const double w[] = { 1, 0.5, 0.3 };
    all_layers_confirmed(m, v, w, 3, 1, "overlapping cubes, nonzero");

    /* the same merged outline built by hand (independent of the fill code) */
    lam_layer L;
    memset(&L, 0, sizeof L);
    L.index = 7;
    L.floor = 1;
    L.ceiling = 2;
    L.width = 1;
    L.cut = 1.5;
    double outline[16] = { 0, 0, 2, 0, 2, 1, 3, 1, 3, 3, 1, 3, 1, 2, 0, 2 };
    size_t len[1] = { 8 };
    lam_loops loops = { outline, len, 1, 8 };
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_contours_assign(&L, &loops, &err);
    ok(rc == LAM_OK && L.ncontours == 1, "hand-made merged layer");
    if (rc == LAM_OK) {
        lam_frame f;
        lam_frame_axis('z', &f, &err);
        rc = validate_layer(v, &L, &f, 1, &c, &err);
        ok(rc == LAM_OK && c.index == 7 && c.confirmed == 1 && c.disagreeing == 0,
           "hand-made merged layer: confirmed");
        lam_layer_check_free(&c);
        /* and the even-odd pair, square in square, by hand: disagrees */
        double pair[16] = { 0, 0, 2, 0, 2, 2, 0, 2, 1, 1, 3, 1, 3, 3, 1, 3 };
        size_t plen[2] = { 4, 4 };
        lam_loops pl = { pair, plen, 2, 8 };
        rc = lam_contours_assign(&L, &pl, &err);
        ok(rc == LAM_OK && L.ncontours == 2 && L.contours[1].kind == LAM_HOLE,
           "hand-made even-odd layer: the second square is a hole");
        if (rc == LAM_OK) {
            rc = validate_layer(v, &L, &f, 0, &c, &err);
            ok(rc == LAM_OK && c.disagreeing == 1 && c.items[1].ok == 0, "hand-made even-odd layer: disagrees");
            lam_layer_check_free(&c);
        }
        /* a hole drawn inside the overlap, where the winding is 2: under
         * even-odd the disagreement is explained as overlapping bodies */
        double inner[16] = { 0, 0, 2, 0, 2, 2, 0, 2, 1.2, 1.2, 1.8, 1.2, 1.8, 1.8, 1.2, 1.8 };
        lam_loops il = { inner, plen, 2, 8 };
        rc = lam_contours_assign(&L, &il, &err);
        if (rc == LAM_OK) {
            rc = validate_layer(v, &L, &f, 0, &c, &err);
            int seen = rc == LAM_OK && c.nitems == 2 && c.items[1].ok == 0;
            ok(seen && c.items[1].winding_found == 2 && c.items[1].expected_material == 0 &&
                   strstr(c.items[1].why, "overlap"),
               "a hole inside the overlap: winding 2 where the label says void, explained as overlap ('%s')",
               seen ? c.items[1].why : "");
            ok(seen && c.items[0].ok == 1, "a hole inside the overlap: the outer square confirmed");
            lam_layer_check_free(&c);
            rc = validate_layer(v, &L, &f, 1, &c, &err);
            ok(rc == LAM_OK && c.nitems == 2 && c.items[1].ok == 0 && !strstr(c.items[1].why, "overlap"),
               "the same layer said to be non-zero: a plain disagreement");
            lam_layer_check_free(&c);
        }
    }
    free(L.uv);
    free(L.contours);
    lam_rays_free(v);
    lam_model_free(m);
}

/* A tessellated sphere: random points against the geometry (inside the
 * inscribed sphere of the polyhedron: 1; outside the circumscribed one: 0),
 * and every layer along x, y and z, shallow facets near the poles included. */
static void test_sphere(void)
{
    const double pi = acos(-1.0);
    int seg = 48, rings = 24;
    lam_model *m = uv_sphere(10, seg, rings, 0, "uv sphere");
    lam_rays *v = validator(m, "uv sphere");
    if (!m || !v) {
        lam_rays_free(v);
        lam_model_free(m);
        return;
    }
    /* every facet is at least this far from the centre */
    double rin = 10 * cos(pi / seg) * cos(pi / rings);
    uint64_t st = 0x9e3779b97f4a7c15u;
    size_t tested = 0, wrong = 0;
    for (int i = 0; i < 2000; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = -12 + 24 * (double)(xorshift64(&st) >> 11) / 9007199254740992.0;
        double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        int want = r < rin - 1e-3 ? 1 : r > 10 + 1e-3 ? 0 : -1;
        if (want < 0) continue;
        tested++;
        int w = wind(v, p[0], p[1], p[2]);
        if (w != want && wrong++ < 5) diag("sphere: winding %d at r = %.17g, expected %d", w, r, want);
    }
    ok(wrong == 0 && tested > 1000, "uv sphere: %zu random points, windings right", tested);
    static const double w[] = { 0.5, 0.35 };
    all_layers_confirmed(m, v, w, 2, 0, "uv sphere");
    lam_rays_stats s;
    lam_rays_get_stats(v, &s);
    diag("uv sphere: %zu points, %zu rays, %zu re-cast, %zu rays discarded, %zu on the surface, %zu undecided",
         s.points, s.rays, s.recasts, s.unreliable, s.surface, s.undecided);
    lam_rays_free(v);
    lam_model_free(m);
}

/* A box with a box-shaped hole through it, at scales and places float32
 * alone could not hold: kilometres and nanometres, 1e7 from the origin
 * with millimetre walls, 1e30 away. The validator centres and scales the
 * model before Embree sees it, so every layer is confirmed everywhere. */
static void test_scales(void)
{
    static const struct { double scale, offset; const char *name; } cases[] = {
        { 1e6, 0, "kilometre box" }, { 1e-9, 0, "nanometre box" },
        { 1e-2, 1e7, "centimetre box 1e7 from the origin" }, { 1e23, 1e30, "box 1e30 away" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        double k = cases[i].scale, o = cases[i].offset;
        lam_mesh mesh;
        lam_mesh_init(&mesh);
        add_box(&mesh, o, o, o, o + 4 * k, o + 4 * k, o + 4 * k, 0, -1);
        add_box(&mesh, o + k, o + k, o + k, o + 3 * k, o + 3 * k, o + 3 * k, BOX_INWARD, -1);
        lam_model *m = build_model_quiet(&mesh, cases[i].name);
        lam_rays *v = validator(m, cases[i].name);
        /* 0.3 nm: plane 10 rounds an ulp below the hole's top face, and
         * is put on it (slice.c, snap_cuts) */
        double widths[] = { 0.5 * k, 0.35 * k, 0.3 * k };
        all_layers_confirmed(m, v, widths, 3, 0, cases[i].name);
        lam_rays_free(v);
        lam_model_free(m);
    }
}

int main(void)
{
    test_unit_cube();
    test_thesis_models();
    test_cavity_and_thin_wall();
    test_overlap();
    test_sphere();
    test_scales();
    return done_testing();
}
