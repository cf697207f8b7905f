/* Models for the unit tests that load or build them (slice, validate, fill,
 * model, planner): files under TESTS/models, meshes built vertex by vertex,
 * boxes and UV spheres. All static inline, so a test program pays nothing
 * for the helpers it does not use (and -Wunused-function stays quiet). It
 * includes tap.h (for ok and diag) and util.h itself. */
#ifndef LAM_TEST_MESHES_H
#define LAM_TEST_MESHES_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "error.h"
#include "mesh.h"
#include "model.h"
#include "tap.h"
#include "util.h"

/* The tests folder: $TESTS when set and not empty, otherwise "tests". */
static inline const char *tests_dir(void)
{
    const char *t = getenv("TESTS");
    return t && *t ? t : "tests";
}

/* The model file TESTS/models/NAME, or NULL with a diag; with check, also the test point "load NAME". */
static inline lam_model *model_file(const char *name, int check)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/models/%s", tests_dir(), name);
    lam_error err;
    lam_error_clear(&err);
    lam_model *m = NULL;
    int rc = lam_model_load(path, &m, &err);
    if (check) ok(rc == LAM_OK && m, "load %s", name);
    if (rc) diag("%s: %s", path, err.msg);
    return rc ? NULL : m;
}

/* The model file TESTS/models/NAME as one test point, "load NAME" (NULL on failure). */
static inline lam_model *load_model(const char *name) { return model_file(name, 1); }

/* The model file TESTS/models/NAME without a test point (NULL and a diag on failure). */
static inline lam_model *load_model_quiet(const char *name) { return model_file(name, 0); }

/* The model of mesh (emptied) called name, or NULL with a diag; with check, also the test point "build NAME". */
static inline lam_model *mesh_model(lam_mesh *mesh, const char *name, int check)
{
    lam_error err;
    lam_error_clear(&err);
    lam_model *m = NULL;
    int rc = lam_model_from_mesh(mesh, name, "mesh", &m, &err);
    if (check) ok(rc == LAM_OK && m, "build %s", name);
    if (rc) diag("%s: %s", name, err.msg);
    return rc ? NULL : m;
}

/* The model of mesh (emptied) called name as one test point, "build NAME" (NULL on failure). */
static inline lam_model *build_model(lam_mesh *mesh, const char *name) { return mesh_model(mesh, name, 1); }

/* The model of mesh (emptied) called name without a test point (NULL and a diag on failure). */
static inline lam_model *build_model_quiet(lam_mesh *mesh, const char *name) { return mesh_model(mesh, name, 0); }

/* Adds vertex (x, y, z) to m and returns its index (a diag on failure). */
static inline uint32_t vtx(lam_mesh *m, double x, double y, double z)
{
    uint32_t i = 0;
    lam_error err;
    if (lam_mesh_add_vertex(m, x, y, z, &i, &err)) diag("add_vertex: %s", err.msg);
    return i;
}

/* Adds triangle (a, b, c) to m, unnamed (a diag on failure). */
static inline void tri(lam_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    lam_error err;
    if (lam_mesh_add_tri(m, a, b, c, LAM_NO_NAME, &err)) diag("add_tri: %s", err.msg);
}

/* A box's faces -z +z -y +y -x +x as quads of corners (bit 0 x, bit 1 y, bit 2 z), wound outward. */
static const int BOX_QUADS[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
                                     { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };

/* add_box's flip mask that winds the whole box inward. */
enum { BOX_INWARD = 0xfff };

/* Adds box (x0,y0,z0)-(x1,y1,z1) with own 8 vertices; flip bit k flips triangle k; face skip (-1: none) left out. */
static inline void add_box(lam_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1,
                           unsigned flip, int skip)
{
    uint32_t v[8];
    for (int i = 0; i < 8; i++) v[i] = vtx(m, i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
    /* each quad split along its corner 0 - corner 2 diagonal; triangle k is
     * 2f and 2f + 1 of face f whether or not an earlier face is skipped */
    for (int f = 0; f < 6; f++) {
        if (f == skip) continue;
        uint32_t a = v[BOX_QUADS[f][0]], b = v[BOX_QUADS[f][1]], c = v[BOX_QUADS[f][2]], d = v[BOX_QUADS[f][3]];
        if (flip >> (2 * f) & 1) tri(m, a, c, b);
        else tri(m, a, b, c);
        if (flip >> (2 * f + 1) & 1) tri(m, a, d, c);
        else tri(m, a, c, d);
    }
}

/* Deterministic pseudo-random bits from *s (no libc rand: the same on every platform). */
static inline uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 16;
}

/* Adds a UV sphere of radius r at 0: poles, rings-1 rings of seg points; seed != 0 flips triangles at random. */
static inline void add_uv_sphere(lam_mesh *m, double r, int seg, int rings, uint32_t seed)
{
    const double pi = acos(-1.0);
    uint32_t north = vtx(m, 0, 0, r);
    uint32_t first = north + 1;
    for (int j = 1; j < rings; j++) {
        double th = pi * j / rings;
        for (int i = 0; i < seg; i++) {
            double ph = 2 * pi * i / seg;
            vtx(m, r * sin(th) * cos(ph), r * sin(th) * sin(ph), r * cos(th));
        }
    }
    uint32_t south = vtx(m, 0, 0, -r);
#define RV(j, i) (first + (uint32_t)(((j) - 1) * seg + ((i) % seg)))
    uint32_t s = seed;
#define TRI(a, b, c) do { if (seed && (lcg(&s) & 1)) tri(m, a, c, b); else tri(m, a, b, c); } while (0)
    for (int i = 0; i < seg; i++) TRI(north, RV(1, i), RV(1, i + 1));
    for (int j = 1; j + 1 < rings; j++)
        for (int i = 0; i < seg; i++) {
            uint32_t a = RV(j, i), b = RV(j, i + 1), c = RV(j + 1, i + 1), d = RV(j + 1, i);
            TRI(a, d, c);
            TRI(a, c, b);
        }
    for (int i = 0; i < seg; i++) TRI(RV(rings - 1, i + 1), RV(rings - 1, i), south);
#undef TRI
#undef RV
}

/* add_uv_sphere as a model, one test point "build NAME" (name NULL: "sphere SEGxRINGS seed SEED"). */
static inline lam_model *uv_sphere(double r, int seg, int rings, uint32_t seed, const char *name)
{
    lam_mesh m;
    lam_mesh_init(&m);
    add_uv_sphere(&m, r, seg, rings, seed);
    char buf[64];
    if (!name) snprintf(buf, sizeof buf, "sphere %dx%d seed %u", seg, rings, (unsigned)seed);
    return build_model(&m, name ? name : buf);
}

#endif
