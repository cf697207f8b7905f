/* Non-zero fill: overlapping shells merge; holes stay where the winding is
 * zero; even-odd (the default) keeps the nesting parity. */
#include "winding.h"
#include "meshes.h"
#include "model.h"
#include "slice.h"

#include <math.h>

/* Slice at one plane (middle of [z0, z1]) and return the layer. */
static lam_layer *section(lam_model *m, double z0, double z1, int nonzero)
{
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    double planes[2] = { z0, z1 };
    o.planes = planes;
    o.nplanes = 2;
    o.fill_nonzero = nonzero;
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *s;
    lam_layer *L = NULL;
    if (lam_slicer_new(m, &o, &s, &err) || lam_slicer_next(s, &L, &err)) diag("slice: %s", err.msg);
    lam_slicer_free(s);
    return L;
}

static double net_area(const lam_layer *L)
{
    double a = 0;
    for (size_t k = 0; k < L->ncontours; k++) a += L->contours[k].area;
    return a;
}

int main(void)
{
    lam_mesh mesh;
    lam_model *m;

    /* Two overlapping cubes as separate shells: [0,2]^3 and [1,3]^3. */
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 2, 2, 2, 0, -1);
    add_box(&mesh, 1, 1, 1, 3, 3, 3, 0, -1);
    m = build_model_quiet(&mesh, "two");
    is_int(m->stats.shells, 2, "two shells");

    lam_layer *L = section(m, 1.25, 1.75, 0);
    is_int(L->ncontours, 2, "even-odd: two crossing squares");
    ok(L->contours[1].kind == LAM_HOLE, "even-odd: the second square is nested inside the first: a hole");
    lam_layer_free(L);

    L = section(m, 1.25, 1.75, 1);
    is_int(L->ncontours, 1, "non-zero: one merged outline");
    if (L->ncontours == 1) {
        ok(L->contours[0].kind == LAM_SOLID && L->contours[0].area > 0, "merged outline is a CCW solid");
        is_num(L->contours[0].area, 7, 1e-12, "its area is 4 + 4 - 1");
        is_int(L->contours[0].n, 8, "an L-shaped octagon: 8 corners");
    }
    lam_layer_free(L);

    /* Below the overlap: only the first cube, unchanged by the rule. */
    L = section(m, 0.25, 0.75, 1);
    is_int(L->ncontours, 1, "non-zero below the overlap: one square");
    is_num(net_area(L), 4, 0, "area 4, exactly");
    lam_layer_free(L);
    lam_model_free(m);

    /* A box with a cavity, and a second body inside the cavity: winding is
     * 1 in the wall, 0 in the cavity, 1 in the inner body. Non-zero keeps
     * all three outlines: solid, hole, solid. */
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 10, 10, 10, 0, -1);
    add_box(&mesh, 2, 2, 2, 8, 8, 8, BOX_INWARD, -1);
    add_box(&mesh, 4, 4, 4, 6, 6, 6, 0, -1);
    m = build_model_quiet(&mesh, "nested");
    L = section(m, 4.5, 5.5, 1);
    is_int(L->ncontours, 3, "non-zero keeps the cavity and the island");
    if (L->ncontours == 3) {
        ok(L->contours[0].kind == LAM_SOLID && L->contours[1].kind == LAM_HOLE && L->contours[2].kind == LAM_SOLID,
           "solid, hole, solid");
        is_num(net_area(L), 100 - 36 + 4, 1e-9, "net area 100 - 36 + 4");
    }
    lam_layer_free(L);
    lam_model_free(m);

    /* A bar through the cavity's wall and out of the box: winding 1 where it
     * crosses the cavity, 2 in the wall, 1 outside. (A body entirely inside
     * the box would count as enclosed and so as a cavity: SPEC 2.3.) */
    lam_mesh_init(&mesh);
    add_box(&mesh, 0, 0, 0, 10, 10, 10, 0, -1);
    add_box(&mesh, 2, 2, 2, 8, 8, 8, BOX_INWARD, -1);
    add_box(&mesh, 5, 4, 4, 12, 6, 6, 0, -1);
    m = build_model_quiet(&mesh, "bar");
    is_int(m->stats.cavities, 1, "the bar is not enclosed: one cavity only");
    L = section(m, 4.5, 5.5, 1);
    is_num(net_area(L), 100 - 36 + 3 * 2 + 2 * 2, 1e-9, "non-zero: the bar fills 3 x 2 of the cavity and adds 2 x 2 outside");
    is_int(L->ncontours, 2, "the outline with a tab, and one notched hole");
    lam_layer_free(L);
    L = section(m, 4.5, 5.5, 0);
    is_int(L->ncontours, 3, "even-odd keeps three crossing outlines");
    lam_layer_free(L);
    lam_model_free(m);

    /* lam_loops_winding directly */
    double sq[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    size_t len[1] = { 4 };
    lam_loops lp = { sq, len, 1, 4 };
    is_int(lam_loops_winding(&lp, 0.5, 0.5), 1, "winding 1 inside a CCW square");
    is_int(lam_loops_winding(&lp, 1.5, 0.5), 0, "winding 0 outside");
    return done_testing();
}
