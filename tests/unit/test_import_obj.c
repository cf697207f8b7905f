/* OBJ importer: the thesis cube as quads, with v/vt/vn forms, with negative
 * indices, as triangles with CRLF/comments/continuations; a concave polygon;
 * g/o names on face records; every error with its line:column; prefixes and
 * random mutations (must fail cleanly, never crash: run under SAN=1). Every
 * buffer handed to the importer is an exact-size heap copy, so ASan catches
 * any read past len. */
#include "import.h"
#include "model.h"
#include "tap.h"
#include "util.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static const char *CUBE_V =
    "v -1 -1 -1\n"
    "v 1 -1 -1\n"
    "v 1 1 -1\n"
    "v -1 1 -1\n"
    "v -1 -1 1\n"
    "v 1 -1 1\n"
    "v 1 1 1\n"
    "v -1 1 1\n";

/* Outward quads, 1-based. */
static const int Q[6][4] = {
    { 1, 4, 3, 2 }, { 5, 6, 7, 8 }, { 1, 2, 6, 5 }, { 3, 4, 8, 7 }, { 2, 3, 7, 6 }, { 4, 1, 5, 8 },
};

static const double V[8][3] = {
    { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 },
    { -1, -1, 1 },  { 1, -1, 1 },  { 1, 1, 1 },  { -1, 1, 1 },
};

/* ---- helpers ------------------------------------------------------------ */

/* Import from an exact-size heap copy of src[0..len). */
static int load(const char *src, size_t len, lam_mesh *m, lam_error *err)
{
    char *copy = heap_copy(src, len);
    lam_mesh_init(m);
    lam_error_clear(err);
    int rc = lam_import_obj_buf("t.obj", copy, len, m, err);
    free(copy);
    return rc;
}

static int load_str(const char *s, lam_mesh *m, lam_error *err) { return load(s, strlen(s), m, err); }

static double area(const lam_mesh *m)
{
    double sum = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        const double *a, *b, *c;
        tri_corners(m, t, &a, &b, &c);
        double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
        double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
        sum += sqrt(x * x + y * y + z * z) / 2;
    }
    return sum;
}

/* Every triangle of face f uses only corners of quad Q[f]. */
static int tris_follow_quads(const lam_mesh *m)
{
    if (!m->tri_face || m->nfaces != 6) return 0;
    for (size_t t = 0; t < m->ntris; t++) {
        uint32_t f = m->tri_face[t];
        for (int j = 0; j < 3; j++) {
            uint32_t v = m->tris[3 * t + j];
            if (v != (uint32_t)Q[f][0] - 1 && v != (uint32_t)Q[f][1] - 1 && v != (uint32_t)Q[f][2] - 1 &&
                v != (uint32_t)Q[f][3] - 1)
                return 0;
        }
    }
    return 1;
}

static int cube_vertices_right(const lam_mesh *m)
{
    if (m->nverts != 8) return 0;
    for (int i = 0; i < 8; i++)
        for (int k = 0; k < 3; k++)
            if (m->xyz[3 * i + k] != V[i][k]) return 0;
    return 1;
}

static uint64_t rng_state = 0x2545f4914f6cdd1dull;
static uint64_t rng(void) { return xorshift64(&rng_state); }

/* ---- tests -------------------------------------------------------------- */

static char *quad_cube(void)
{
    sbuf b = { 0 };
    sb_add(&b, "# the thesis cube\no cube\n%s", CUBE_V); /* faces from line 11 */
    for (int f = 0; f < 6; f++) sb_add(&b, "f %d %d %d %d\n", Q[f][0], Q[f][1], Q[f][2], Q[f][3]);
    return b.s;
}

static void test_quads(lam_mesh *ref)
{
    lam_error err;
    char *s = quad_cube();
    int rc = load_str(s, ref, &err);
    is_int(rc, LAM_OK, "quad cube loads (%s)", err.msg);
    is_int(ref->ntris, 12, "quad cube: 12 triangles");
    ok(cube_vertices_right(ref), "quad cube: 8 vertices with the right coordinates");
    is_int(ref->nfaces, 6, "quad cube: one face record per f line");
    ok(tris_follow_quads(ref), "quad cube: each face's triangles use its quad's corners");
    is_num(area(ref), 24.0, 1e-12, "quad cube: area 24");
    is_num(signed_volume(ref), 8.0, 1e-12, "quad cube: volume 8 (winding kept)");
    int pos_ok = ref->nfaces == 6;
    for (size_t f = 0; pos_ok && f < 6; f++)
        if (ref->faces[f].line != 11 + f || ref->faces[f].column != 1) pos_ok = 0;
    ok(pos_ok, "quad cube: face records at the f lines (11..16, column 1)");
    is_str(ref->nfaces ? lam_mesh_string(ref, ref->faces[0].name) : NULL, "cube", "face name from 'o'");
    is_str(ref->nfaces ? lam_mesh_string(ref, ref->faces[5].file) : NULL, "t.obj", "face file is the path");
    ok(ref->nfaces == 6 && ref->faces[0].name == ref->faces[5].name, "faces of one group share the name string");
    free(s);
}

static void same_as_ref(const lam_mesh *ref, const char *text, const char *what)
{
    lam_mesh m;
    lam_error err;
    int rc = load_str(text, &m, &err);
    is_int(rc, LAM_OK, "%s: loads (%s)", what, err.msg);
    ok(m.ntris == ref->ntris && m.nverts == ref->nverts &&
           memcmp(m.tris, ref->tris, 3 * ref->ntris * sizeof *m.tris) == 0 &&
           memcmp(m.xyz, ref->xyz, 3 * ref->nverts * sizeof *m.xyz) == 0,
       "%s: same vertices and triangles as the plain quad cube", what);
    lam_mesh_free(&m);
}

static void test_forms(const lam_mesh *ref)
{
    sbuf b = { 0 };
    sb_add(&b, "%svt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n", CUBE_V);
    sb_add(&b, "f %d/1/1 %d/2/1 %d/3/1 %d/4/1\n", Q[0][0], Q[0][1], Q[0][2], Q[0][3]);
    sb_add(&b, "f %d//1 %d//1 %d//1 %d//1\n", Q[1][0], Q[1][1], Q[1][2], Q[1][3]);
    sb_add(&b, "f %d/1 %d/2 %d/3 %d/4\n", Q[2][0], Q[2][1], Q[2][2], Q[2][3]);
    sb_add(&b, "f %d/-4/-1 %d/-3/-1 %d/-2/-1 %d/-1/-1\n", Q[3][0], Q[3][1], Q[3][2], Q[3][3]);
    sb_add(&b, "f %d %d/2 %d//1 %d/4/1\n", Q[4][0], Q[4][1], Q[4][2], Q[4][3]);
    sb_add(&b, "f %d/1/ %d/2/ %d/3/ %d/4/\n", Q[5][0], Q[5][1], Q[5][2], Q[5][3]);
    same_as_ref(ref, b.s, "v/vt/vn, v//vn, v/vt and mixed forms");
    free(b.s);

    /* Negative indices: all faces after the 8 vertices (-8 is vertex 1). */
    b = (sbuf){ 0 };
    sb_add(&b, "%s", CUBE_V);
    for (int f = 0; f < 6; f++)
        sb_add(&b, "f %d %d/%d %d//1 %d\n", Q[f][0] - 9, Q[f][1] - 9, -1, Q[f][2] - 9, Q[f][3] - 9);
    same_as_ref(ref, b.s, "negative (relative) indices");
    free(b.s);

    /* CRLF, comments, blank lines, w, colours, ignored statements, a
     * continuation line, leading blanks. */
    b = (sbuf){ 0 };
    sb_add(&b, "# exported\r\nmtllib cube.mtl\r\n\r\n");
    for (int i = 0; i < 8; i++)
        sb_add(&b, i & 1 ? "v %g %g %g 1.0\r\n" : "  v\t%g %g %g 0.5 0.5 0.5 # with colour\r\n", V[i][0], V[i][1], V[i][2]);
    sb_add(&b, "usemtl red\r\ns off\r\nvn 0 0 1\r\nl 1 2\r\np 1\r\n");
    for (int f = 0; f < 6; f++) {
        if (f == 2)
            sb_add(&b, "f %d %d \\\r\n   %d %d # split over two lines\r\n", Q[f][0], Q[f][1], Q[f][2], Q[f][3]);
        else
            sb_add(&b, "f %d %d %d %d\r\n", Q[f][0], Q[f][1], Q[f][2], Q[f][3]);
    }
    same_as_ref(ref, b.s, "CRLF, comments, w, colours, ignored statements, continuation");
    lam_mesh m;
    lam_error err;
    load_str(b.s, &m, &err);
    is_int(m.nfaces == 6 ? m.faces[3].line : 0, 21, "continuation: the next f is on the right line");
    is_int(m.nfaces == 6 ? m.faces[2].name : 0, LAM_NO_NAME, "no g/o: face name is NULL");
    lam_mesh_free(&m);
    free(b.s);

    /* Triangles, interleaved with their vertices, relative indices. */
    b = (sbuf){ 0 };
    for (int f = 0; f < 6; f++) {
        int q[4] = { Q[f][0] - 1, Q[f][1] - 1, Q[f][2] - 1, Q[f][3] - 1 };
        for (int j = 0; j < 4; j++) sb_add(&b, "v %g %g %g\n", V[q[j]][0], V[q[j]][1], V[q[j]][2]);
        sb_add(&b, "f -4 -3 -2\nf -4 -2 -1\n");
    }
    int rc = load_str(b.s, &m, &err);
    ok(rc == LAM_OK && m.ntris == 12 && m.nverts == 24 && m.nfaces == 12,
       "triangles with interleaved vertices: 12 triangles, 24 vertices (%s)", err.msg);
    is_num(signed_volume(&m), 8.0, 1e-12, "triangles with relative indices: volume 8");
    lam_mesh_free(&m);
    free(b.s);
}

static void test_polygon_and_names(void)
{
    lam_mesh m;
    lam_error err;
    /* An L-shaped hexagon (concave): 3 unit squares, 4 triangles. */
    int rc = load_str("g first group\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                      "f 1 2 3 4 5 6\n"
                      "g   second\t group  \nf 1 2 3\nf 1 3 4\ng\nf 4 5 6\no obj\nf 1 4 6\n",
                      &m, &err);
    is_int(rc, LAM_OK, "concave polygon and groups load (%s)", err.msg);
    is_int(m.ntris, 8, "concave hexagon -> 4 triangles, then 4 more");
    is_int(m.nfaces, 5, "5 f lines, 5 face records");
    double a = 0;
    if (m.ntris == 8 && m.tri_face) {
        lam_mesh first = m;
        first.ntris = 4;
        a = area(&first);
        ok(m.tri_face[0] == 0 && m.tri_face[3] == 0 && m.tri_face[4] == 1, "triangles carry their face");
    } else {
        ok(0, "triangles carry their face");
    }
    is_num(a, 3.0, 1e-12, "concave hexagon triangulated to area 3");
    if (m.nfaces == 5) {
        is_str(lam_mesh_string(&m, m.faces[0].name), "first group", "g with two words");
        is_str(lam_mesh_string(&m, m.faces[1].name), "second group", "words joined by one space");
        ok(m.faces[1].name == m.faces[2].name, "same group: one shared string");
        ok(m.faces[3].name == LAM_NO_NAME, "bare g: no name");
        is_str(lam_mesh_string(&m, m.faces[4].name), "obj", "o name");
        ok(m.faces[4].line == 15 && m.faces[4].column == 1, "face position 15:1");
    } else {
        ok(0, "face names");
    }
    lam_mesh_free(&m);

    /* A polygon without area (all points on a line) is not an error: it is
     * fanned into degenerate triangles, which the model reports. */
    rc = load_str("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 3 2 4\n", &m, &err);
    is_int(rc, LAM_OK, "degenerate polygon: loads (%s)", err.msg);
    static const uint32_t fan[6] = { 0, 2, 1, 0, 1, 3 };
    ok(m.ntris == 2 && memcmp(m.tris, fan, sizeof fan) == 0, "degenerate polygon: fanned from its first vertex");
    is_num(area(&m), 0.0, 0.0, "degenerate polygon: triangles without area");
    ok(m.nfaces == 1 && m.faces[0].line == 5 && m.faces[0].column == 1 && m.tri_face && m.tri_face[0] == 0 &&
           m.tri_face[1] == 0,
       "degenerate polygon: one face record at the f (5:1), both triangles on it");
    lam_model *model = NULL;
    rc = rc ? rc : lam_model_from_mesh(&m, "t.obj", "obj", &model, &err);
    ok(rc == LAM_OK && model && model->stats.degenerate_tris == 2,
       "degenerate polygon: the model reports both triangles as degenerate (%s)", err.msg);
    lam_model_free(model);
    lam_mesh_free(&m);

    rc = load("", 0, &m, &err);
    ok(rc == LAM_OK && m.ntris == 0, "empty OBJ: empty mesh");
    lam_mesh_free(&m);

    /* Appending: indices count from this file's first vertex. */
    lam_mesh_init(&m);
    lam_error_clear(&err);
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    rc = lam_import_obj_buf("a.obj", tri, strlen(tri), &m, &err);
    rc = rc ? rc : lam_import_obj_buf("b.obj", tri, strlen(tri), &m, &err);
    ok(rc == LAM_OK && m.ntris == 2 && m.tris[3] == 3 && m.tris[5] == 5,
       "second file's indices are relative to its own vertices");
    lam_mesh_free(&m);
}

static void obj_error(const char *text, int code, long line, long col, const char *msg, const char *what)
{
    lam_mesh m;
    lam_error err;
    int rc = load_str(text, &m, &err);
    error_is(rc, &err, code, line, col, msg, what);
    lam_mesh_free(&m);
}

#define TRI_V "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

static void test_errors(void)
{
    obj_error(TRI_V "f 1 2 4\n", LAM_EINVAL, 4, 7, "vertex index 4 out of range (3 vertices defined so far)",
              "index out of range at 4:7");
    obj_error(TRI_V "f 1 2 -4\n", LAM_EINVAL, 4, 7, "vertex index -4 out of range (3 vertices defined so far)",
              "relative index out of range at 4:7");
    obj_error("v 0 0 0\nf 1 1 2//3\n", LAM_EINVAL, 2, 7, "vertex index 2 out of range (1 vertex defined so far)",
              "index out of range with v//vn");
    obj_error(TRI_V "f 1 0 3\n", LAM_EINVAL, 4, 5, "vertex index 0 is invalid", "index 0 at 4:5");
    obj_error(TRI_V "f 1/1/1 2/1/1 0/1/1\n", LAM_EINVAL, 4, 15, "vertex index 0 is invalid", "index 0 as 0/1/1");
    obj_error(TRI_V "  f 1 2\n", LAM_EINVAL, 4, 3, "face has 2 vertices, at least 3 are needed",
              "face with 2 vertices: at the 'f' 4:3");
    obj_error(TRI_V "f\n", LAM_EINVAL, 4, 1, "face has 0 vertices", "face with no vertices");
    obj_error(TRI_V "f 1 2 a\n", LAM_ESYNTAX, 4, 7, "expected a vertex reference (v, v/vt, v//vn or v/vt/vn), found 'a'",
              "non-numeric reference");
    obj_error(TRI_V "f 1 2/x 3\n", LAM_ESYNTAX, 4, 5, "found '2/x'", "malformed vt part");
    obj_error(TRI_V "f 1 2 3/1/1/1\n", LAM_ESYNTAX, 4, 7, "found '3/1/1/1'", "too many slashes");
    obj_error(TRI_V "f 1 2 3.0\n", LAM_ESYNTAX, 4, 7, "found '3.0'", "fractional index");
    obj_error("v 0 0 0\nv 1 2x 3\n", LAM_ESYNTAX, 2, 5, "expected the vertex y coordinate (a number), found '2x'",
              "malformed number at 2:5");
    obj_error("v 0 0 0\nv 1 2\n", LAM_ESYNTAX, 2, 6, "expected the vertex z coordinate, found end of line",
              "missing z: just after the last token");
    obj_error("v 0 0 0\nv 1 2 # z is missing\n", LAM_ESYNTAX, 2, 6, "found end of line", "missing z before a comment");
    obj_error("v 0 0 0\nv 1 2", LAM_ESYNTAX, 2, 6, "found end of line", "missing z at end of buffer");
    obj_error("v 0 nan 0\n", LAM_EINVAL, 1, 5, "vertex y coordinate is not a finite number ('nan')", "NaN at 1:5");
    obj_error("v 0 0 -inf\n", LAM_EINVAL, 1, 7, "vertex z coordinate is not a finite number ('-inf')", "-inf at 1:7");
    obj_error("v 1e400 0 0\n", LAM_EINVAL, 1, 3, "not a finite number ('1e400')", "overflow is not finite");
    obj_error("v 0 0 0\r\nv 1 0 0\r\nf 1 2 9\r\n", LAM_EINVAL, 3, 7, "vertex index 9 out of range", "CRLF: position right");
    obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n  2 \\\n 7\n", LAM_EINVAL, 6, 2, "vertex index 7 out of range",
              "continuation: error on the continued line");
    obj_error("v 1 2 3\nf 1 1 1 99999999999999999999999\n", LAM_EINVAL, 2, 9, "out of range", "huge index");

    lam_mesh m;
    lam_error err;
    load_str(TRI_V "f 1 2 4\n", &m, &err);
    char buf[1200];
    is_str(lam_error_format(&err, buf, sizeof buf), "t.obj:4:7: vertex index 4 out of range (3 vertices defined so far)",
           "error formats as file:line:column");
    lam_mesh_free(&m);
}

/* Prefixes and random mutations: success, or an error with a message and a
 * line:column. */
static void test_robustness(void)
{
    char *s = quad_cube();
    size_t n = strlen(s), bad = 0;
    for (size_t len = 0; len <= n; len++) {
        lam_mesh m;
        lam_error err;
        int rc = load(s, len, &m, &err);
        if (rc != LAM_OK && (!err.msg[0] || err.line < 1 || err.column < 1)) bad++;
        if (len == n && (rc != LAM_OK || m.ntris != 12)) bad++;
        lam_mesh_free(&m);
    }
    is_int(bad, 0, "every prefix of the quad cube: success or a positioned error");

    static const char alphabet[] = "0123456789.-+/eE \n\r\t\\#vfgo\0\xff";
    char *work = malloc(n);
    size_t oks = 0, runs = 3000;
    bad = 0;
    for (size_t r = 0; r < runs; r++) {
        memcpy(work, s, n);
        int k = 1 + (int)(rng() % 4);
        for (int i = 0; i < k; i++) work[rng() % n] = alphabet[rng() % (sizeof alphabet - 1)];
        size_t len = rng() % 3 == 0 ? rng() % n : n;
        lam_mesh m;
        lam_error err;
        int rc = load(work, len, &m, &err);
        if (rc == LAM_OK) {
            oks++;
            for (size_t i = 0; i < 3 * m.nverts; i++)
                if (!isfinite(m.xyz[i])) {
                    bad++;
                    break;
                }
            for (size_t i = 0; i < 3 * m.ntris; i++)
                if (m.tris[i] >= m.nverts) {
                    bad++;
                    break;
                }
        } else if (!err.msg[0] || err.code != rc || err.line < 1 || err.column < 1) {
            if (bad++ < 3) diag("mutation %zu: rc %d at %ld:%ld '%s'", r, rc, err.line, err.column, err.msg);
        }
        lam_mesh_free(&m);
    }
    is_int(bad, 0, "%zu random mutations: valid mesh or a positioned error (%zu ok)", runs, oks);
    free(work);
    free(s);
}

/* lam_model_load maps a file whose size is not a multiple of the page size
 * and reads any other: the same cube (its last face line without a newline,
 * so a reader that runs past the end would see it) loads the same way at
 * one byte under, exactly at and one byte over a page. */
static void test_file_sizes(void)
{
    long page = sysconf(_SC_PAGESIZE);
    if (page <= 0) page = 4096;
    for (long delta = -1; delta <= 1; delta++) {
        sbuf b = { 0 };
        sb_add(&b, "%s", CUBE_V);
        char faces[256] = "";
        size_t fl = 0;
        for (int i = 0; i < 6; i++)
            fl += (size_t)snprintf(faces + fl, sizeof faces - fl, "f %d %d %d %d%s", Q[i][0], Q[i][1], Q[i][2],
                                   Q[i][3], i < 5 ? "\n" : "");
        /* pad with a comment line so the file has exactly page + delta bytes */
        long pad = page + delta - (long)b.n - (long)fl - 2;
        sb_add(&b, "#");
        for (long k = 0; k < pad; k++) sb_add(&b, "x");
        sb_add(&b, "\n%s", faces);
        char dir[] = "/tmp/lamina-obj-size-XXXXXX", path[64];
        FILE *f = NULL;
        if (mkdtemp(dir)) {
            snprintf(path, sizeof path, "%s/cube.obj", dir);
            f = fopen(path, "wb");
        }
        if (!f) {
            ok(0, "temporary file");
            free(b.s);
            return;
        }
        fwrite(b.s, 1, b.n, f);
        fclose(f);
        lam_model *m = NULL;
        lam_error err;
        lam_error_clear(&err);
        int rc = lam_model_load(path, &m, &err);
        ok(rc == LAM_OK && (long)b.n == page + delta && m && m->stats.triangles == 12 && m->stats.volume == 8 &&
               m->stats.boundary_edges == 0,
           "a %ld-byte OBJ (page %+ld) loads the whole cube: %s", (long)b.n, delta, rc ? err.msg : "ok");
        lam_model_free(m);
        unlink(path);
        rmdir(dir);
        free(b.s);
    }
}

int main(void)
{
    lam_mesh ref;
    test_quads(&ref);
    test_forms(&ref);
    lam_mesh_free(&ref);
    test_polygon_and_names();
    test_errors();
    test_robustness();
    test_file_sizes();
    return done_testing();
}
