/* Planners against a recording sink: the thesis's LADRP sample command by
 * command, deposits that never leave the material, deposit area against
 * layer area, raster angles, and the SLS block order. */
#include "model.h"
#include "contour.h"
#include "meshes.h"
#include "planner.h"
#include "slice.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { OP_LASER, OP_FEED, OP_MOVE, OP_LAYER, OP_LAYER_END, OP_CONTOUR };

typedef struct op {
    int kind, on, deposit;
    double v[3];
    size_t n;
    int solid;
} op;

typedef struct rec {
    op *ops;
    size_t n, cap;
    lam_job_info job;
} rec;

static op *push(rec *r, int kind)
{
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 256;
        r->ops = realloc(r->ops, r->cap * sizeof *r->ops);
    }
    op *o = &r->ops[r->n++];
    memset(o, 0, sizeof *o);
    o->kind = kind;
    return o;
}

static int s_begin(void *c, const lam_job_info *j) { ((rec *)c)->job = *j; return 0; }
static int s_layer(void *c, const lam_layer_info *l) { push(c, OP_LAYER)->v[2] = l->z; return 0; }
static int s_layer_end(void *c, const lam_layer_info *l) { push(c, OP_LAYER_END)->v[2] = l->z; return 0; }
static int s_fail(void *c, const lam_layer_info *l) { (void)c; (void)l; return LAM_EIO; }
static int s_feed(void *c, double rate) { push(c, OP_FEED)->v[0] = rate; return 0; }
static int s_laser(void *c, int on) { push(c, OP_LASER)->on = on; return 0; }
static int s_move(void *c, const lam_move_info *m)
{
    op *o = push(c, OP_MOVE);
    o->deposit = m->deposit;
    memcpy(o->v, m->xyz, sizeof o->v);
    return 0;
}
static int s_contour(void *c, const lam_contour_info *ci)
{
    op *o = push(c, OP_CONTOUR);
    o->n = ci->n;
    o->solid = ci->solid;
    memcpy(o->v, ci->xyz, sizeof o->v);
    return 0;
}

static lam_sink recorder(rec *r)
{
    memset(r, 0, sizeof *r);
    lam_sink s = { r, s_begin, s_layer, s_layer_end, s_feed, s_laser, s_move, s_contour, NULL, NULL, NULL, NULL };
    return s;
}

/* material at (u, v): inside an odd number of the layer's contours */
static int material(const lam_layer *L, double u, double v)
{
    int in = 0;
    for (size_t k = 0; k < L->ncontours; k++) in ^= lam_contour_contains(L, &L->contours[k], u, v);
    return in;
}

static int check_islands;

/* Run the planner layer by layer, checking deposits against each layer. */
static void check_ladrp(const char *name, lam_model *m, char axis, double width, double bead, double angle,
                        double angle_step)
{
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    lam_error err;
    lam_error_clear(&err);
    lam_frame_axis(axis, &so.frame, &err);
    so.width = width;
    lam_slicer *s;
    lam_slicer_new(m, &so, &s, &err);
    lam_plan_opts po;
    lam_plan_opts_init(&po);
    po.kind = LAM_PLAN_LADRP;
    po.bead = bead;
    po.frame_machine = 1; /* deposits in (u, v, w): compare with the layer directly */
    po.angle = angle;
    po.angle_step = angle_step;
    po.islands = check_islands;
    int outside = 0, area_bad = 0, layers = 0;
    double pos[3] = { 0, 0, 0 };
    for (;;) {
        lam_layer *L;
        lam_slicer_next(s, &L, &err);
        if (!L) break;
        rec r;
        lam_sink sink = recorder(&r);
        int laser = -1;
        lam_ladrp_stats st;
        lam_plan_ladrp_layer(L, lam_slicer_frame(s), &po, &sink, pos, &laser, &st, &err);
        double prev[3] = { pos[0], pos[1], pos[2] }, dep = 0;
        int have_prev = 0;
        for (size_t i = 0; i < r.n; i++) {
            if (r.ops[i].kind != OP_MOVE) continue;
            if (r.ops[i].deposit && have_prev) {
                /* the planner evaluates a scan line an infinitesimal step
                 * down its sweep (a line on the top edge deposits the row
                 * below it): test the midpoint a hair down that way */
                double th = (angle + angle_step * (double)L->index) * 3.14159265358979323846 / 180;
                double mu = (prev[0] + r.ops[i].v[0]) / 2 + 1e-7 * sin(th);
                double mv = (prev[1] + r.ops[i].v[1]) / 2 - 1e-7 * cos(th);
                if (!material(L, mu, mv)) {
                    if (!outside) diag("%s layer %zu: deposit midpoint (%g, %g) outside material", name, L->index, mu, mv);
                    outside++;
                }
                dep += hypot(r.ops[i].v[0] - prev[0], r.ops[i].v[1] - prev[1]);
            }
            memcpy(prev, r.ops[i].v, sizeof prev);
            have_prev = 1;
        }
        double area = 0, perim = 0;
        for (size_t k = 0; k < L->ncontours; k++) {
            area += L->contours[k].area;
            perim += L->contours[k].perimeter;
        }
        if (fabs(dep * bead - area) > bead * perim + 1e-9) {
            if (!area_bad) diag("%s layer %zu: deposit area %g vs layer area %g (tolerance %g)", name, L->index, dep * bead, area, bead * perim);
            area_bad++;
        }
        is_num(st.deposit_length, dep, 1e-9, "%s layer %zu: stats count the deposit length", name, L->index);
        layers++;
        free(r.ops);
        lam_layer_free(L);
    }
    ok(layers > 0, "%s: %d layers planned", name, layers);
    ok(outside == 0, "%s (axis %c, angle %g + %g/layer): no deposit over a hole or outside", name, axis, angle, angle_step);
    ok(area_bad == 0, "%s: deposit length x bead within bead x perimeter of the layer area", name);
    lam_slicer_free(s);
}

int main(void)
{
    lam_error err;
    lam_error_clear(&err);

    /* The thesis's LADRP sample: the 2-unit cube centred on the origin, bead
     * 0.08, feed 0.15, first scan line on the top edge, floor cut. */
    lam_model *cube = load_model_quiet("thesis_cube.ug");
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    so.cut = LAM_CUT_FLOOR;
    so.width = 0.08;
    lam_slicer *s;
    ok(lam_slicer_new(cube, &so, &s, &err) == LAM_OK, "slicer for the thesis cube");
    lam_plan_opts po;
    lam_plan_opts_init(&po);
    po.kind = LAM_PLAN_LADRP;
    po.bead = 0.08;
    po.rate = 0.15;
    rec r;
    lam_sink sink = recorder(&r);
    ok(lam_plan_run(s, cube, &po, &sink, NULL, NULL, &err) == LAM_OK, "planning runs (%s)", err.msg);
    is_int(r.job.layers, 25, "25 layers of 0.08 over a height of 2");
    is_num(r.job.origin[0], 0, 0, "the stage starts at the model origin (x)");
    is_num(r.job.origin[2], -1, 0, "... at the first layer's height");
    /* expected first commands, as relative moves: penup; (-1, 1.08, 0);
     * (0, -0.08, 0); pendown; feed 0.15; (2, 0, 0); penup; (0, -0.08, 0);
     * pendown; feed; (-2, 0, 0); ... */
    struct { int kind, arg; double dx, dy, dz; } want[] = {
        { OP_LAYER, 0, 0, 0, 0 },
        { OP_LASER, 0, 0, 0, 0 }, { OP_MOVE, 0, -1, 1.08, 0 }, { OP_MOVE, 0, 0, -0.08, 0 },
        { OP_LASER, 1, 0, 0, 0 }, { OP_FEED, 0, 0.15, 0, 0 }, { OP_MOVE, 1, 2, 0, 0 },
        { OP_LASER, 0, 0, 0, 0 }, { OP_MOVE, 0, 0, -0.08, 0 },
        { OP_LASER, 1, 0, 0, 0 }, { OP_FEED, 0, 0.15, 0, 0 }, { OP_MOVE, 1, -2, 0, 0 },
        { OP_LASER, 0, 0, 0, 0 }, { OP_MOVE, 0, 0, -0.08, 0 },
        { OP_LASER, 1, 0, 0, 0 }, { OP_FEED, 0, 0.15, 0, 0 }, { OP_MOVE, 1, 2, 0, 0 },
        { OP_LASER, 0, 0, 0, 0 }, { OP_MOVE, 0, 0, -0.08, 0 },
        { OP_LASER, 1, 0, 0, 0 }, { OP_FEED, 0, 0.15, 0, 0 }, { OP_MOVE, 1, -2, 0, 0 },
    };
    double at[3] = { 0, 0, -1 };
    int same = r.n >= sizeof want / sizeof *want;
    for (size_t i = 0; same && i < sizeof want / sizeof *want; i++) {
        const op *o = &r.ops[i];
        if (o->kind != want[i].kind) { diag("op %zu: kind %d, want %d", i, o->kind, want[i].kind); same = 0; break; }
        if (o->kind == OP_LASER && o->on != want[i].arg) same = 0;
        if (o->kind == OP_FEED && fabs(o->v[0] - want[i].dx) > 1e-9) same = 0;
        if (o->kind == OP_MOVE) {
            double d[3] = { o->v[0] - at[0], o->v[1] - at[1], o->v[2] - at[2] };
            if (o->deposit != want[i].arg || fabs(d[0] - want[i].dx) > 1e-9 || fabs(d[1] - want[i].dy) > 1e-9 ||
                fabs(d[2] - want[i].dz) > 1e-9) {
                diag("op %zu: move (%d, %.17g, %.17g, %.17g), want (%d, %g, %g, %g)", i, o->deposit, d[0], d[1], d[2],
                     want[i].arg, want[i].dx, want[i].dy, want[i].dz);
                same = 0;
            }
            memcpy(at, o->v, sizeof at);
        }
        if (!same) diag("mismatch at op %zu", i);
    }
    ok(same, "the thesis's LADRP sample, command by command, numbers to 1e-9");
    /* the whole first layer: 25 lines of 2 units each (y = 1.0 .. -0.92) */
    size_t deposits = 0, i = 0;
    double ymin = INFINITY;
    for (; i < r.n && r.ops[i].kind != OP_LAYER_END; i++)
        if (r.ops[i].kind == OP_MOVE && r.ops[i].deposit) {
            deposits++;
            if (r.ops[i].v[1] < ymin) ymin = r.ops[i].v[1];
        }
    is_int(deposits, 25, "first layer: 25 deposit lines (2 / 0.08)");
    is_num(ymin, -0.92, 1e-12, "the last line at y = 1 - 24 x 0.08 (the bottom edge itself deposits nothing)");
    size_t lay = 0;
    for (i = 0; i < r.n; i++) lay += r.ops[i].kind == OP_LAYER;
    is_int(lay, 25, "25 layer commands");
    free(r.ops);
    lam_slicer_free(s);

    /* first line half a bead inside: first deposit at y = 1 - 0.04 */
    lam_slicer_new(cube, &so, &s, &err);
    po.first_center = 1;
    sink = recorder(&r);
    lam_plan_run(s, cube, &po, &sink, NULL, NULL, &err);
    for (i = 0; i < r.n && !(r.ops[i].kind == OP_MOVE && r.ops[i].deposit); i++) {}
    is_num(r.ops[i].v[1], 0.96, 1e-12, "first_line center: the first deposit runs at y = 0.96");
    free(r.ops);
    lam_slicer_free(s);
    po.first_center = 0;

    /* raster angle 90: lines run along y, one bead apart in x */
    lam_slicer_new(cube, &so, &s, &err);
    po.angle = 90;
    sink = recorder(&r);
    lam_plan_run(s, cube, &po, &sink, NULL, NULL, &err);
    const op *prev = NULL;
    int along_y = 1, n90 = 0;
    for (i = 0; i < r.n && r.ops[i].kind != OP_LAYER_END; i++) {
        if (r.ops[i].kind != OP_MOVE) continue;
        if (r.ops[i].deposit && prev) {
            along_y &= r.ops[i].v[0] == prev->v[0] && fabs(fabs(r.ops[i].v[1] - prev->v[1]) - 2) < 1e-12;
            n90++;
        }
        prev = &r.ops[i];
    }
    ok(along_y && n90 == 25, "angle 90: 25 deposits along y (%d)", n90);
    free(r.ops);
    lam_slicer_free(s);
    po.angle = 0;

    /* min_deposit: a cube with a hole sliced so that lines cross the hole */
    lam_model *hole = load_model_quiet("thesis_cube_hole.ug");
    lam_slice_opts_init(&so);
    so.width = 1;
    so.cut = LAM_CUT_FLOOR;
    lam_slicer_new(hole, &so, &s, &err);
    po.bead = 0.1;
    po.min_deposit = 0.6; /* the 0.5-long pieces beside the hole go */
    sink = recorder(&r);
    lam_plan_run(s, hole, &po, &sink, NULL, NULL, &err);
    int short_ones = 0;
    at[0] = r.job.origin[0], at[1] = r.job.origin[1], at[2] = r.job.origin[2];
    for (i = 0; i < r.n; i++) {
        if (r.ops[i].kind != OP_MOVE) continue;
        if (r.ops[i].deposit && hypot(r.ops[i].v[0] - at[0], r.ops[i].v[1] - at[1]) < 0.6) short_ones++;
        memcpy(at, r.ops[i].v, sizeof at);
    }
    ok(short_ones == 0, "min_deposit drops deposits shorter than 0.6");
    free(r.ops);
    lam_slicer_free(s);
    po.min_deposit = 0;

    /* Property checks on every layer. */
    lam_model *fi = load_model_quiet("frame_island.ug");
    check_ladrp("frame_island", fi, 'z', 2, 0.5, 0, 0);
    check_ladrp("frame_island", fi, 'x', 3, 0.7, 0, 0);
    check_ladrp("frame_island", fi, 'z', 2, 0.5, 67.5, 67.5);
    check_ladrp("thesis_cube_hole", hole, 'z', 0.25, 0.08, 0, 90);
    /* a tessellated sphere built here: deposits inside, areas consistent */
    {
        lam_mesh mesh;
        lam_mesh_init(&mesh);
        add_uv_sphere(&mesh, 10, 48, 24, 0);
        lam_model *sphere = build_model_quiet(&mesh, "sphere");
        check_ladrp("sphere", sphere, 'z', 0.7, 0.3, 0, 0);
        check_ladrp("sphere", sphere, 'y', 0.9, 0.25, 30, 0);
        lam_model_free(sphere);
    }

    /* SLS: blocks in layer order, solids counter-clockwise first point lowest */
    lam_slice_opts_init(&so);
    so.width = 1;
    so.cut = LAM_CUT_FLOOR;
    lam_slicer_new(hole, &so, &s, &err);
    lam_plan_opts_init(&po);
    sink = recorder(&r);
    lam_plan_run(s, hole, &po, &sink, NULL, NULL, &err);
    int kinds_ok = 0;
    for (i = 0; i < r.n; i++)
        if (r.ops[i].kind == OP_CONTOUR) kinds_ok = kinds_ok * 2 + r.ops[i].solid;
    is_int(kinds_ok, 0xA, "SLS: per layer a solid then its hole (1010)");
    ok(r.ops[1].kind == OP_CONTOUR && r.ops[1].v[0] == -1 && r.ops[1].v[1] == -1 && r.ops[1].v[2] == 0,
       "the first block starts at (-1, -1, 0)");
    free(r.ops);
    lam_slicer_free(s);

    /* Islands one after the other: the same deposits, less travel. Two
     * cubes side by side, 6 apart: plain boustrophedon crosses the gap on
     * every line, island order once. */
    {
        lam_mesh mesh;
        lam_mesh_init(&mesh);
        for (int b = 0; b < 2; b++) add_box(&mesh, 8 * b, 0, 0, 8 * b + 2, 2, 2, 0, -1);
        lam_model *two = build_model_quiet(&mesh, "two");
        lam_slice_opts_init(&so);
        so.width = 1;
        double dep[2], trav[2];
        for (int mode = 0; mode < 2; mode++) {
            lam_slicer_new(two, &so, &s, &err);
            lam_layer *L;
            lam_slicer_next(s, &L, &err);
            lam_plan_opts_init(&po);
            po.kind = LAM_PLAN_LADRP;
            po.bead = 0.1;
            po.islands = mode;
            sink = recorder(&r);
            double p0[3] = { 0, 0, 0.5 };
            int las = -1;
            lam_ladrp_stats st;
            lam_plan_ladrp_layer(L, lam_slicer_frame(s), &po, &sink, p0, &las, &st, &err);
            dep[mode] = st.deposit_length;
            trav[mode] = st.travel_length;
            free(r.ops);
            lam_layer_free(L);
            lam_slicer_free(s);
        }
        is_num(dep[1], dep[0], 1e-9, "islands: the same deposit length (%g)", dep[0]);
        ok(trav[1] < trav[0] / 4, "islands: travel %g against %g line by line", trav[1], trav[0]);
        check_islands = 1;
        check_ladrp("two cubes by islands", two, 'z', 0.5, 0.1, 0, 0);
        check_islands = 0;
        lam_model_free(two);
    }

    /* SLS beam offset: solids move in and holes out by half the spot */
    lam_slicer_new(hole, &so, &s, &err);
    lam_plan_opts_init(&po);
    po.bead = 0.1;
    po.beam_offset = 1;
    sink = recorder(&r);
    ok(lam_plan_run(s, hole, &po, &sink, NULL, NULL, &err) == LAM_OK, "beam offset plans (%s)", err.msg);
    ok(r.ops[1].kind == OP_CONTOUR && r.ops[1].n == 4 && fabs(r.ops[1].v[0] + 0.95) < 1e-12 &&
           fabs(r.ops[1].v[1] + 0.95) < 1e-12,
       "the outer square starts at (-0.95, -0.95): inset by 0.05");
    ok(r.ops[2].kind == OP_CONTOUR && !r.ops[2].solid && fabs(r.ops[2].v[0] + 0.55) < 1e-12,
       "the hole grows to start at (-0.55, -0.55)");
    free(r.ops);
    lam_slicer_free(s);

    /* LADRP perimeters: one pass at d/2 inside, then the raster inside it */
    lam_slice_opts_init(&so);
    so.cut = LAM_CUT_FLOOR;
    so.width = 0.08;
    lam_slicer_new(cube, &so, &s, &err);
    lam_plan_opts_init(&po);
    po.kind = LAM_PLAN_LADRP;
    po.bead = 0.08;
    po.perimeters = 1;
    {
        lam_layer *L;
        lam_slicer_next(s, &L, &err);
        sink = recorder(&r);
        double p0[3] = { 0, 0, -1 };
        int las = -1;
        lam_ladrp_stats st;
        ok(lam_plan_ladrp_layer(L, lam_slicer_frame(s), &po, &sink, p0, &las, &st, &err) == LAM_OK,
           "perimeter pass plans (%s)", err.msg);
        double first[3] = { 0, 0, 0 }, ymax = -INFINITY;
        int seen = 0;
        for (i = 0; i < r.n; i++) {
            if (r.ops[i].kind != OP_MOVE) continue;
            if (!seen++) memcpy(first, r.ops[i].v, sizeof first);
            if (i > 6 && r.ops[i].deposit && r.ops[i].v[1] > ymax) ymax = r.ops[i].v[1];
        }
        ok(fabs(fabs(first[0]) - 0.96) < 1e-12 && fabs(fabs(first[1]) - 0.96) < 1e-12,
           "the perimeter starts on the square inset by d/2 (|x| = |y| = 0.96)");
        is_num(st.deposit_length, 4 * 1.92 + 23 * 1.84, 1e-9,
               "deposits: the 1.92 square's perimeter + 23 raster lines of 1.84 inside it");
        free(r.ops);
        lam_layer_free(L);
    }
    lam_slicer_free(s);

    /* err NULL (error.h): a sink that fails gives the status code alone, and
     * the planner does not read through the missing lam_error */
    {
        lam_slice_opts_init(&so);
        so.width = 0.5;
        ok(lam_slicer_new(cube, &so, &s, NULL) == LAM_OK, "a slicer with err NULL");
        lam_plan_opts_init(&po);
        po.kind = LAM_PLAN_LADRP;
        po.bead = 0.1;
        lam_sink failing = recorder(&r);
        failing.layer = s_fail;
        is_int(lam_plan_run(s, cube, &po, &failing, NULL, NULL, NULL), LAM_EIO,
               "a failing sink with err NULL: its status code");
        free(r.ops);
        lam_slicer_free(s);
    }

    lam_model_free(cube);
    lam_model_free(hole);
    lam_model_free(fi);
    return done_testing();
}
