/* Model core: welding, edge table, shells, orientation from adjacency,
 * cavities, volume, defect counts — on meshes built by hand. */
#include "meshes.h"
#include "model.h"

#include <stdlib.h>

int main(void)
{
    lam_mesh m;
    lam_model *md;

    /* A unit cube, every other triangle flipped: orientation is rebuilt. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 2, 2, 2, 0x555, -1);
    md = build_model_quiet(&m, "test");
    ok(md != NULL, "cube builds");
    is_int(md->stats.vertices, 8, "8 welded vertices from 8 per box");
    is_int(md->stats.triangles, 12, "12 triangles");
    is_int(md->stats.edges, 18, "18 edges (12 box edges + 6 diagonals)");
    is_int(md->stats.shells, 1, "one shell");
    is_int(md->stats.cavities, 0, "no cavity");
    is_num(md->stats.volume, 8, 0, "volume 8 exactly despite flipped input triangles");
    is_num(signed_volume(&md->mesh), 8, 0, "triangles themselves now face outward");
    is_num(md->stats.area, 24, 1e-12, "surface area 24");
    is_int(md->stats.boundary_edges, 0, "closed");
    is_int(md->stats.orientation_conflicts, 0, "orientable");
    for (size_t e = 0; e < md->edges.n; e++) {
        if (md->edges.first[e + 1] - md->edges.first[e] != 2) { ok(0, "edge %zu not manifold", e); break; }
    }
    /* every edge is used once in each direction after orientation */
    int consistent = 1;
    for (size_t e = 0; e < md->edges.n && consistent; e++) {
        uint32_t a = md->edges.v[2 * e], b = md->edges.v[2 * e + 1];
        int fwd = 0, back = 0;
        for (uint32_t i = md->edges.first[e]; i < md->edges.first[e + 1]; i++) {
            const uint32_t *t = md->mesh.tris + 3 * md->edges.tris[i];
            for (int k = 0; k < 3; k++) {
                if (t[k] == a && t[(k + 1) % 3] == b) fwd++;
                if (t[k] == b && t[(k + 1) % 3] == a) back++;
            }
        }
        consistent = fwd == 1 && back == 1;
    }
    ok(consistent, "each edge traversed once each way");
    /* tri_edge matches the final vertex order */
    int slots = 1;
    for (size_t t = 0; t < md->mesh.ntris; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = md->mesh.tris[3 * t + k], b = md->mesh.tris[3 * t + (k + 1) % 3];
            uint32_t e = md->edges.tri_edge[3 * t + k];
            uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
            if (md->edges.v[2 * e] != lo || md->edges.v[2 * e + 1] != hi) slots = 0;
        }
    ok(slots, "tri_edge slot k is the edge (t[k], t[k+1])");
    lam_model_free(md);

    /* The whole cube wound inward: turned outward by its volume. */
    lam_mesh_init(&m);
    add_box(&m, -1, -1, -1, 1, 1, 1, 0xfff, -1);
    md = build_model_quiet(&m, "test");
    is_num(md->stats.volume, 8, 0, "inside-out cube is turned outward");
    lam_model_free(md);

    /* Box with a cavity: inner shell inside outer -> cavity, volume 64 - 8. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 4, 4, 4, 0, -1);
    add_box(&m, 1, 1, 1, 3, 3, 3, 0x0f0, -1);
    md = build_model_quiet(&m, "test");
    is_int(md->stats.shells, 2, "two shells");
    is_int(md->stats.cavities, 1, "one cavity");
    is_num(md->stats.volume, 56, 0, "volume 64 - 8");
    is_num(signed_volume(&md->mesh), 56, 0, "cavity triangles face into the void");
    ok(md->shells[1].cavity && md->shells[1].volume == -8, "the inner shell is the cavity, volume -8");
    double inside[3] = { 2, 2, 2 }, outside[3] = { 10, 0, 0 };
    is_num(lam_model_shell_winding(md, 0, inside), 1, 1e-9, "winding 1 inside the outer shell");
    is_num(lam_model_shell_winding(md, 0, outside), 0, 1e-9, "winding 0 outside");
    lam_model_free(md);

    /* An island inside a cavity inside a solid: depths 0, 1, 2. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 10, 10, 10, 0, -1);
    add_box(&m, 2, 2, 2, 8, 8, 8, 0, -1);
    add_box(&m, 4, 4, 4, 6, 6, 6, 0xfff, -1);
    md = build_model_quiet(&m, "test");
    is_int(md->stats.cavities, 1, "only the middle shell is a cavity");
    is_int(md->shells[2].enclosing, 2, "the island is enclosed twice");
    is_num(md->stats.volume, 1000 - 216 + 8, 0, "volume 1000 - 216 + 8");
    lam_model_free(md);

    /* Two disjoint cubes: two solids, volumes add. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 1, 1, 1, 0, -1);
    add_box(&m, 5, 0, 0, 6, 1, 1, 0x3, -1);
    md = build_model_quiet(&m, "test");
    is_int(md->stats.shells, 2, "two shells");
    is_int(md->stats.cavities, 0, "side by side: no cavity");
    is_num(md->stats.volume, 2, 0, "volume 1 + 1");
    lam_model_free(md);

    /* Two cubes sharing one edge: a non-manifold edge, still two shells. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 1, 1, 1, 0, -1);
    add_box(&m, 1, 1, 0, 2, 2, 1, 0, -1);
    md = build_model_quiet(&m, "test");
    is_int(md->stats.nonmanifold_edges, 1, "the shared edge has four triangles");
    is_int(md->stats.shells, 2, "shells split at the non-manifold edge");
    is_int(md->stats.vertices, 14, "two shared vertices welded");
    is_num(md->stats.volume, 2, 0, "volume 2");
    lam_model_free(md);

    /* A cube without its top: open, boundary edges counted. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 1, 1, 1, 0, 1);
    md = build_model_quiet(&m, "test");
    is_int(md->stats.boundary_edges, 4, "four boundary edges around the missing face");
    is_int(md->stats.triangles, 10, "10 triangles");
    lam_model_free(md);

    /* Degenerate triangles: collinear is kept and counted, a repeated
     * vertex is dropped and counted. */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 1, 1, 1, 0, -1);
    {
        lam_error err;
        uint32_t a, b, c;
        lam_mesh_add_vertex(&m, 0, 0, 0, &a, &err);
        lam_mesh_add_vertex(&m, 1, 0, 0, &b, &err);
        lam_mesh_add_vertex(&m, 0.5, 0, 0, &c, &err);
        lam_mesh_add_tri(&m, a, b, c, LAM_NO_NAME, &err);
        lam_mesh_add_tri(&m, a, a, b, LAM_NO_NAME, &err);
    }
    md = build_model_quiet(&m, "test");
    is_int(md->stats.degenerate_tris, 2, "two degenerate triangles reported");
    is_int(md->stats.triangles, 13, "the collapsed one is dropped, the collinear one kept");
    lam_model_free(md);

    /* Welding is bitwise: -0.0 and 0.0 weld, 1e-300 apart does not. */
    lam_mesh_init(&m);
    {
        lam_error err;
        uint32_t a, b, c, d, e, f;
        lam_mesh_add_vertex(&m, 0.0, 0, 0, &a, &err);
        lam_mesh_add_vertex(&m, 1, 0, 0, &b, &err);
        lam_mesh_add_vertex(&m, 0, 1, 0, &c, &err);
        lam_mesh_add_vertex(&m, -0.0, 0, 0, &d, &err);
        lam_mesh_add_vertex(&m, 0, 1, 0, &e, &err);
        lam_mesh_add_vertex(&m, 1e-300, 1, 1, &f, &err);
        lam_mesh_add_tri(&m, a, b, c, LAM_NO_NAME, &err);
        lam_mesh_add_tri(&m, d, e, f, LAM_NO_NAME, &err);
        ok(lam_mesh_weld(&m, &err) == LAM_OK, "weld succeeds");
        is_int(m.nverts, 4, "-0.0 welds with 0.0, duplicates merge");
        is_int(m.tris[3], m.tris[0], "second triangle uses the first's vertex");
        lam_mesh_free(&m);
    }

    /* An empty mesh is an error, not a crash. */
    lam_mesh_init(&m);
    {
        lam_error err;
        lam_error_clear(&err);
        md = NULL;
        int rc = lam_model_from_mesh(&m, "empty.stl", "mesh", &md, &err);
        ok(rc != LAM_OK && md == NULL, "an empty mesh is refused");
        ok(strstr(err.msg, "no triangles") != NULL, "with a message: %s", err.msg);
    }

    /* A translated cube far from the origin keeps an exact volume. */
    lam_mesh_init(&m);
    add_box(&m, 1e6, 1e6, 1e6, 1e6 + 2, 1e6 + 2, 1e6 + 2, 0, -1);
    md = build_model_quiet(&m, "test");
    is_num(md->stats.volume, 8, 0, "volume exact far from the origin");
    lam_model_free(md);
    /* Shells by union-find (consistent input) and by the search (input
     * with flipped triangles) must agree: three boxes as separate shells,
     * the middle one a cavity of the first, the third apart; once wound
     * consistently (inward cavity included, as a file would have it), once
     * with triangles flipped in each box, the first one in the very first
     * triangle (the search's seed). Same shells, labels, cavities, volume
     * and, triangle by triangle, the same winding. */
    {
        lam_mesh a, b;
        lam_mesh_init(&a);
        lam_mesh_init(&b);
        add_box(&a, 0, 0, 0, 4, 4, 4, 0, -1);
        add_box(&a, 1, 1, 1, 2, 2, 2, BOX_INWARD, -1);
        add_box(&a, 10, 0, 0, 11, 1, 1, 0, -1);
        add_box(&b, 0, 0, 0, 4, 4, 4, 0x001, -1);
        add_box(&b, 1, 1, 1, 2, 2, 2, BOX_INWARD ^ 0x0f0, -1);
        add_box(&b, 10, 0, 0, 11, 1, 1, 0xa00, -1);
        lam_model *ma = build_model_quiet(&a, "consistent"), *mb = build_model_quiet(&b, "flipped");
        ok(ma && mb, "three boxes build, consistent and with flipped triangles");
        if (ma && mb) {
            is_int(ma->stats.shells, 3, "three shells");
            is_int(ma->stats.cavities, 1, "one cavity");
            is_num(ma->stats.volume, 64 - 1 + 1, 0, "volume 64 - 1 + 1");
            is_int(mb->stats.shells, ma->stats.shells, "flipped input: the same shells");
            is_int(mb->stats.cavities, ma->stats.cavities, "flipped input: the same cavity");
            is_num(mb->stats.volume, ma->stats.volume, 0, "flipped input: the same volume");
            int same = ma->mesh.ntris == mb->mesh.ntris;
            for (size_t t = 0; same && t < ma->mesh.ntris; t++)
                same = ma->tri_shell[t] == mb->tri_shell[t] &&
                       memcmp(ma->mesh.tris + 3 * t, mb->mesh.tris + 3 * t, 3 * sizeof(uint32_t)) == 0;
            ok(same, "flipped input: every triangle in the same shell, wound the same way");
            ok(ma->tri_shell[0] == 0 && ma->tri_shell[12] == 1 && ma->tri_shell[24] == 2,
               "shells numbered by their first triangle");
        }
        lam_model_free(ma);
        lam_model_free(mb);
    }
    /* Voids in a part, many of them: 27 cubes inside a sphere, every
     * third holding a smaller solid cube (an island in the void). With a
     * fine sphere the pairwise winding-number test would do millions of
     * terms and Embree rays decide instead; with a coarse one the pairwise
     * test decides. Both must find the same cavities and volume. */
    for (int fine = 0; fine < 2; fine++) {
        lam_mesh mesh, alone;
        lam_mesh_init(&mesh);
        lam_mesh_init(&alone);
        int seg = fine ? 240 : 24, rings = fine ? 120 : 12;
        add_uv_sphere(&mesh, 20, seg, rings, 0);
        add_uv_sphere(&alone, 20, seg, rings, 0);
        int voids = 0, islands = 0;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++) {
                    double x = -6 + 6 * i, y = -6 + 6 * j, z = -6 + 6 * k;
                    /* as a file would have it: voids wound inward */
                    add_box(&mesh, x, y, z, x + 2, y + 2, z + 2, BOX_INWARD, -1);
                    voids++;
                    if ((i + j + k) % 3 == 0) {
                        add_box(&mesh, x + 0.5, y + 0.5, z + 0.5, x + 1.5, y + 1.5, z + 1.5, 0, -1);
                        islands++;
                    }
                }
        lam_model *ms = build_model_quiet(&alone, "sphere alone");
        lam_model *mp = build_model_quiet(&mesh, "porous sphere");
        ok(ms && mp, "%s sphere with %d voids and %d islands builds", fine ? "fine" : "coarse", voids, islands);
        if (ms && mp) {
            is_int(mp->stats.shells, 1 + voids + islands, "%s: every body a shell", fine ? "fine" : "coarse");
            is_int(mp->stats.cavities, voids, "%s: every void a cavity, no island one", fine ? "fine" : "coarse");
            is_num(mp->stats.volume, ms->stats.volume - 8.0 * voids + 1.0 * islands, 1e-9 * ms->stats.volume,
                   "%s: volume = sphere - voids + islands", fine ? "fine" : "coarse");
            int right = 1;
            for (size_t s = 1; s < mp->nshells; s++)
                right &= mp->shells[s].enclosing == (mp->shells[s].cavity ? 1 : 2);
            ok(right && mp->shells[0].enclosing == 0, "%s: voids enclosed once, islands twice, the sphere never",
               fine ? "fine" : "coarse");
        }
        lam_model_free(ms);
        lam_model_free(mp);
    }
    return done_testing();
}
