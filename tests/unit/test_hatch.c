/* core/plan/hatch*.c: hatching the thesis's cube with its hole (the square
 * [-1, 1]^2 around the hole [-0.5, 0.5]^2: area 3), checked with the test's
 * own geometry (the two squares are known exactly); orders by their
 * defining property; skins against empty and full neighbours; the budget
 * error; the time of one path. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hatch.h"
#include "meshes.h"
#include "model.h"
#include "slice.h"
#include "tap.h"
#include "util.h"

static const double TOL = 1e-9;
#define PI 3.14159265358979323846

/* in the material: inside the outer square, outside the hole (or on an edge) */
static int in_ring(double x, double y)
{
    int outer = fabs(x) <= 1 + TOL && fabs(y) <= 1 + TOL;
    int hole = fabs(x) < 0.5 - TOL && fabs(y) < 0.5 - TOL;
    return outer && !hole;
}

static lam_scan_cfg cfg_lines(double h, double angle, int order)
{
    lam_scan_cfg c;
    memset(&c, 0, sizeof c);
    c.contour_count = 1;
    c.contours_first = 1;
    for (int t = 0; t < LAM_REGIONS; t++) {
        c.type[t].strategy = LAM_HATCH_LINES;
        c.type[t].distance = h;
        c.type[t].angle = angle;
        c.type[t].order = order;
        c.type[t].stripe_width = 10;
        c.type[t].island_size = 5;
    }
    return c;
}

static double len(const double *v)
{
    return hypot(v[2] - v[0], v[3] - v[1]);
}

int main(void)
{
    lam_model *m = load_model("thesis_cube_hole.ug");
    if (!m) return done_testing();
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    so.width = 1;
    so.cut = LAM_CUT_FLOOR;
    lam_slicer *s;
    lam_error err;
    lam_error_clear(&err);
    lam_slicer_new(m, &so, &s, &err);
    lam_layer *L;
    lam_slicer_next(s, &L, &err);
    ok(L && L->ncontours == 2, "the cube's first layer: a square and its hole");

    /* lines at 30 degrees, 0.05 apart: inside, the right direction, area 3 */
    lam_hatches h;
    memset(&h, 0, sizeof h);
    lam_scan_cfg c = cfg_lines(0.05, 30, LAM_ORDER_MEANDER);
    int rc = lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h, &err);
    is_int(rc, LAM_OK, "lines hatch (%s)", err.msg);
    int inside = 1, dir = 1;
    double total = 0;
    for (size_t i = 0; i < h.nv; i++) {
        const double *v = h.v + 4 * i;
        for (int k = 0; k <= 8; k++)
            inside &= in_ring(v[0] + (v[2] - v[0]) * k / 8, v[1] + (v[3] - v[1]) * k / 8);
        double cross = (v[2] - v[0]) * sin(30 * PI / 180) - (v[3] - v[1]) * cos(30 * PI / 180);
        dir &= fabs(cross) < 1e-9 * (1 + len(v));
        total += len(v);
    }
    /* 55 lines across (2.73 / 0.05), those through the hole in two */
    ok(h.nv > 55 && inside, "%zu vectors, every one inside the square and outside the hole", h.nv);
    ok(dir, "every vector at 30 degrees");
    is_num(total * 0.05, 3, 0.03, "length x distance is the area 3 (%g)", total * 0.05);
    is_num(h.area[LAM_KIND_CORE], 3, 1e-9, "the region's area, all core without skins");
    /* meander: successive lines run opposite ways; a line cut by the hole
     * runs both its pieces the same way */
    int alternate = 1;
    double c30 = cos(30 * PI / 180), s30 = sin(30 * PI / 180);
    for (size_t i = 1; i < h.nv; i++) {
        const double *a = h.v + 4 * (i - 1), *b = h.v + 4 * i;
        double ya = -a[0] * s30 + a[1] * c30, yb = -b[0] * s30 + b[1] * c30;
        double da = (a[2] - a[0]) * c30 + (a[3] - a[1]) * s30, db = (b[2] - b[0]) * c30 + (b[3] - b[1]) * s30;
        if (fabs(ya - yb) > 1e-9) alternate &= (da > 0) != (db > 0);
        else alternate &= (da > 0) == (db > 0);
    }
    ok(alternate, "meander: lines alternate, pieces of one line keep its way");

    /* unidirectional: every vector along +30 degrees */
    c = cfg_lines(0.05, 30, LAM_ORDER_UNIDIRECTIONAL);
    lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h, &err);
    int forward = 1;
    for (size_t i = 0; i < h.nv; i++) forward &= (h.v[4 * i + 2] - h.v[4 * i]) * c30 + (h.v[4 * i + 3] - h.v[4 * i + 1]) * s30 > 0;
    ok(forward, "unidirectional: every vector along the hatch direction");

    /* greedy: each next vector starts at the nearest end left */
    c = cfg_lines(0.1, 0, LAM_ORDER_GREEDY);
    lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h, &err);
    int nearest = 1;
    for (size_t i = 1; i < h.nv; i++) {
        const double *p = h.v + 4 * (i - 1) + 2;
        double d = hypot(h.v[4 * i] - p[0], h.v[4 * i + 1] - p[1]);
        for (size_t j = i; j < h.nv; j++)
            for (int e = 0; e < 2; e++)
                nearest &= d <= hypot(h.v[4 * j + 2 * e] - p[0], h.v[4 * j + 2 * e + 1] - p[1]) + 1e-12;
    }
    ok(nearest, "greedy: every next vector starts at the nearest end of those left (%zu)", h.nv);

    /* islands, random order: the same seed the same vectors; another seed
     * the same islands in another order */
    c = cfg_lines(0.1, 0, LAM_ORDER_MEANDER);
    for (int t = 0; t < LAM_REGIONS; t++) {
        c.type[t].strategy = LAM_HATCH_ISLANDS;
        c.type[t].island_size = 0.5;
        c.type[t].island_order = LAM_ISLANDS_RANDOM;
        c.type[t].seed = 11;
    }
    lam_hatches h2;
    memset(&h2, 0, sizeof h2);
    lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h, &err);
    lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h2, &err);
    ok(h.nv == h2.nv && h.nv && !memcmp(h.v, h2.v, 4 * h.nv * sizeof *h.v), "random islands: deterministic");
    for (int t = 0; t < LAM_REGIONS; t++) c.type[t].seed = 12;
    lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h2, &err);
    double s1 = 0, s2 = 0;
    for (size_t i = 0; i < h.nv; i++) s1 += len(h.v + 4 * i);
    for (size_t i = 0; i < h2.nv; i++) s2 += len(h2.v + 4 * i);
    ok(h.nv == h2.nv && fabs(s1 - s2) < 1e-9 && memcmp(h.v, h2.v, 4 * h.nv * sizeof *h.v),
       "random islands: another seed, the same vectors in another order");
    is_int(h.nblocks, 12, "islands of 0.5: 16 squares over the cube less the 4 of the hole");

    /* skins: nothing below, the layer itself above -> all down-skin; the
     * layer itself on both sides -> all core */
    c = cfg_lines(0.1, 0, LAM_ORDER_MEANDER);
    c.skin_layers = 1;
    const lam_layer *same[1] = { L };
    lam_hatch_layer(L, NULL, 0, same, 1, &c, &h, &err);
    is_num(h.area[LAM_KIND_DOWNSKIN], 3, 1e-9, "skins: nothing below, all down-skin");
    is_num(h.area[LAM_KIND_CORE] + h.area[LAM_KIND_UPSKIN], 0, 1e-9, "... no core, no up-skin");
    lam_hatch_layer(L, same, 1, NULL, 0, &c, &h, &err);
    is_num(h.area[LAM_KIND_UPSKIN], 3, 1e-9, "skins: covered below, nothing above: all up-skin");
    lam_hatch_layer(L, same, 1, same, 1, &c, &h, &err);
    is_num(h.area[LAM_KIND_CORE], 3, 1e-9, "skins: covered on both sides: all core");
    int kinds = 1;
    for (size_t b = 0; b < h.nblocks; b++) kinds &= h.blocks[b].type == LAM_KIND_CORE;
    ok(h.nblocks && kinds, "... and every block is core");

    /* a hatch distance that would make too many vectors */
    c = cfg_lines(1e-8, 0, LAM_ORDER_MEANDER);
    lam_error_clear(&err);
    rc = lam_hatch_layer(L, NULL, 0, NULL, 0, &c, &h, &err);
    is_int(rc, LAM_EUSAGE, "hatch distance 1e-8: LAM_EUSAGE");
    ok(has(err.msg, "too small"), "... saying so (%s)", err.msg);

    /* the time of paths: 3 long at speed 2 (1.5 s); a jump of 5 at 10/s
     * plus 0.1 s; point exposure 3 / 0.5 + 1 = 7 points x 0.2 s */
    lam_scan_cfg tc;
    memset(&tc, 0, sizeof tc);
    tc.jump_speed = 10;
    tc.jump_delay = 0.1;
    lam_exposure e = { 100, 2, 0, 0 }, pe = { 100, 0, 0.5, 0.2 };
    lam_scan_time t;
    memset(&t, 0, sizeof t);
    double pos[2] = { 0, 0 };
    int have = 0;
    const double a0[2] = { 0, 0 }, a1[2] = { 3, 0 }, b0[2] = { 3, 5 }, b1[2] = { 0, 5 };
    lam_scan_time_path(&t, &tc, &e, a0, a1, 3, 0, pos, &have);
    is_num(t.exposure, 1.5, 1e-12, "time: 3 at speed 2 is 1.5 s, no jump before the first path");
    lam_scan_time_path(&t, &tc, &pe, b0, b1, 3, 0, pos, &have);
    is_num(t.jump, 0.6, 1e-12, "time: a jump of 5 at 10/s plus 0.1 s delay");
    is_num(t.exposure, 1.5 + 1.4, 1e-12, "time: point exposure, 7 points of 0.2 s");
    ok(t.vectors == 2 && t.jumps == 1 && t.hatch_length == 6, "time: counts and lengths");

    lam_hatches_free(&h);
    lam_hatches_free(&h2);
    lam_layer_free(L);
    lam_slicer_free(s);
    lam_model_free(m);
    return done_testing();
}
