/* Repair on load (repair.h) on meshes built by hand: what each step
 * counts, and that the result is closed with the volume the test works
 * out itself (boxes, a sphere's cap as a cone). */
#include "meshes.h"
#include "model.h"
#include "repair.h"

#include <math.h>
#include <stdlib.h>

static lam_model *repaired(lam_mesh *m, const char *name)
{
    lam_model *md = build_model_quiet(m, name);
    if (!md) return NULL;
    lam_error err;
    if (lam_model_repair(&md, NULL, &err)) {
        diag("%s: %s", name, err.msg);
        return NULL;
    }
    return md;
}

static void closed(const lam_model *md, const char *name)
{
    ok(md && md->stats.boundary_edges == 0 && md->stats.nonmanifold_edges == 0 &&
           md->repair.boundary_edges == 0 && md->repair.nonmanifold_edges == 0,
       "%s: closed and manifold after repair", name);
}

static void boxes(void)
{
    lam_mesh m;
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0, 0); /* -z face left out */
    lam_model *md = repaired(&m, "box without its floor");
    closed(md, "box without its floor");
    is_int(md->repair.holes, 1, "one hole");
    is_int(md->repair.hole_edges, 4, "of four edges");
    is_int(md->repair.fill_triangles, 2, "filled by two triangles");
    is_num(md->repair.fill_area, 4, 1e-12, "over the floor's 2 x 2");
    is_num(md->stats.volume, 8, 1e-12, "volume 8 again");
    lam_model_free(md);

    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0x5, -1);
    md = build_model_quiet(&m, "box");
    lam_model *before = md;
    lam_error err;
    ok(lam_model_repair(&md, NULL, &err) == LAM_OK && md == before, "a closed box is kept as it is");
    is_int(md->repair.flipped, 2, "the two facets wound against the rest are counted");
    lam_model_free(md);
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, BOX_INWARD & ~0x5u, -1);
    md = build_model_quiet(&m, "box");
    lam_model_repair(&md, NULL, &err);
    is_int(md->repair.flipped, 2, "an inward box with two facets outward: those two counted");
    ok(md->repair.ran && !md->repair.holes && !md->repair.welded, "and nothing else is done");
    lam_model_free(md);

    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, BOX_INWARD, -1);
    md = repaired(&m, "inside-out box");
    is_int(md->repair.flipped, 0, "an inside-out box: turned outward, no facet against the majority");
    is_num(md->stats.volume, 8, 0, "volume 8");
    lam_model_free(md);

    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0, -1);
    tri(&m, m.tris[0], m.tris[1], m.tris[2]);
    tri(&m, m.tris[5], m.tris[4], m.tris[3]); /* the same facet the other way round */
    md = repaired(&m, "box with facets twice");
    closed(md, "box with facets twice");
    is_int(md->repair.duplicates, 2, "two duplicate facets removed");
    is_int(md->stats.triangles, 12, "12 facets left");
    is_num(md->stats.volume, 8, 1e-12, "volume 8");
    lam_model_free(md);
}

/* A box whose top face has its own corners, 1e-9 above the walls': the
 * exact weld leaves a crack all round, the tolerance (1e-6 of the
 * diagonal) closes it. */
static void crack(void)
{
    lam_mesh m;
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0, 1);
    uint32_t v[4];
    const double eps = 1e-9;
    for (int i = 0; i < 4; i++) v[i] = vtx(&m, i & 1 ? 2 : 0, i & 2 ? 2 : 0, 2 + eps);
    tri(&m, v[0], v[1], v[3]);
    tri(&m, v[0], v[3], v[2]);
    lam_model *md = repaired(&m, "box with a cracked lid");
    closed(md, "box with a cracked lid");
    is_int(md->repair.welded, 4, "the lid's four corners welded to the walls'");
    is_int(md->repair.holes, 0, "no hole to fill");
    ok(md->repair.weld_tolerance > 1e-7 && md->repair.weld_tolerance < 1e-5, "tolerance 1e-6 of the diagonal (%g)",
       md->repair.weld_tolerance);
    is_num(md->stats.volume, 8, 1e-8, "volume 8");
    lam_model_free(md);
}

/* A UV sphere without its north fan: the hole is the first ring, filled
 * flat; the volume lost is the cone from the pole over that ring's
 * polygon. */
static void cap(int seg, const char *what)
{
    const int rings = 24;
    const double r = 5, pi = acos(-1.0);
    lam_mesh m;
    lam_mesh_init(&m);
    add_uv_sphere(&m, r, seg, rings, 0);
    lam_model *whole = build_model_quiet(&m, "sphere");
    double v0 = whole->stats.volume;
    lam_model_free(whole);
    lam_mesh_init(&m);
    add_uv_sphere(&m, r, seg, rings, 0);
    memmove(m.tris, m.tris + 3 * (size_t)seg, 3 * (m.ntris - (size_t)seg) * sizeof *m.tris);
    m.ntris -= (size_t)seg;
    lam_model *md = repaired(&m, what);
    closed(md, what);
    is_int(md->repair.holes, 1, "%s: one hole", what);
    is_int(md->repair.hole_edges, seg, "%s: of %d edges", what, seg);
    double th = pi / rings, rr = r * sin(th);
    double disc = 0.5 * seg * rr * rr * sin(2 * pi / seg);
    double height = r - r * cos(th);
    is_num(md->repair.fill_area, disc, 1e-9 * disc, "%s: the fill is the ring's polygon", what);
    is_num(md->stats.volume, v0 - disc * height / 3, 1e-9 * v0, "%s: volume less the cone over it", what);
    lam_model_free(md);
}

/* Two triangular holes that touch at one vertex: the walk passes that
 * vertex twice and cuts the loops apart there. */
static void pinch(void)
{
    const int seg = 12, rings = 8;
    lam_mesh m;
    lam_mesh_init(&m);
    add_uv_sphere(&m, 3, seg, rings, 0);
    lam_model *whole = build_model_quiet(&m, "sphere");
    double v0 = whole->stats.volume;
    lam_model_free(whole);
    lam_mesh_init(&m);
    add_uv_sphere(&m, 3, seg, rings, 0);
    /* quads of ring j start at seg + 2 (j - 1) seg; each is (a,d,c), (a,c,b) */
    size_t j = 2, i = 3;
    size_t t1 = (size_t)seg + 2 * ((j - 1) * seg + i) + 1;           /* (a,c,b) of quad (j, i) */
    size_t t2 = (size_t)seg + 2 * (j * seg + i + 1);                /* (a,d,c) of quad (j+1, i+1) */
    const uint32_t *a = m.tris + 3 * t1, *b = m.tris + 3 * t2;
    int shared = 0;
    for (int x = 0; x < 3; x++)
        for (int y = 0; y < 3; y++) shared += a[x] == b[y];
    is_int(shared, 1, "the two facets share one vertex");
    memmove(m.tris + 3 * t2, m.tris + 3 * (t2 + 1), 3 * (m.ntris - t2 - 1) * sizeof *m.tris);
    memmove(m.tris + 3 * t1, m.tris + 3 * (t1 + 1), 3 * (m.ntris - t1 - 1) * sizeof *m.tris);
    m.ntris -= 2;
    lam_model *md = repaired(&m, "pinched holes");
    closed(md, "pinched holes");
    is_int(md->repair.holes, 2, "two holes");
    is_int(md->repair.hole_edges, 6, "of three edges each");
    is_num(md->stats.volume, v0, 1e-12 * v0, "the same volume: each hole's fill is the facet taken");
    lam_model_free(md);
}

/* A box without its floor, a closed box pushed through that floor: the
 * fill closes the first, and the edges where the fill and the other box
 * cross are counted (the walls' own crossings are the file's: not
 * searched). */
static void crossing(void)
{
    lam_mesh m;
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0, 0);
    add_box(&m, 1, 0.5, -0.5, 3, 1.5, 1, 0, -1);
    lam_model *md = repaired(&m, "two boxes through each other");
    closed(md, "two boxes through each other");
    ok(md->repair.crossings_unknown || md->repair.crossing_edges >= 4, "edges through the fill counted (%zu)",
       md->repair.crossing_edges);
    lam_model_free(md);
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0, 0);
    md = repaired(&m, "box without its floor");
    is_int(md->repair.crossing_edges, 0, "a box alone crosses nothing");
    lam_model_free(md);
}

int main(void)
{
    crossing();
    boxes();
    crack();
    cap(32, "small cap");
    cap(LAM_REPAIR_DP_MAX + 100, "cap of a loop past the programme's length");
    pinch();
    lam_repair_report r = { .ran = 1, .holes = 37, .hole_edges = 223, .flipped = 12 };
    char buf[256];
    is_str(lam_repair_summary(&r, buf, sizeof buf), "filled 37 holes (223 boundary edges), 12 facets flipped",
           "the summary line");
    return done_testing();
}
