/* Unigrafix importer: the thesis's parts, faces with holes, every transform
 * flag against hand-computed coordinates, includes, and every error with
 * its exact position. */
#include "import.h"
#include "tap.h"
#include "util.h"

#include <stdlib.h>
#include <string.h>

static char tests_dir[512];

static const char *model_path(const char *rel, char *buf, size_t size)
{
    snprintf(buf, size, "%s/models/%s", tests_dir, rel);
    return buf;
}

/* Import src (named `name` under tests/models/ug/, which need not exist)
 * into a fresh mesh. */
static int load(const char *src, const char *name, lam_mesh *m, lam_error *err)
{
    char path[1024];
    char rel[256];
    snprintf(rel, sizeof rel, "ug/%s", name ? name : "inline.ug");
    lam_mesh_init(m);
    lam_error_clear(err);
    return lam_import_ug_buf(model_path(rel, path, sizeof path), src, strlen(src), m, err);
}

/* Import the file tests/models/<rel> into a fresh mesh. */
static int load_file(const char *rel, lam_mesh *m, lam_error *err)
{
    char path[1024];
    lam_mesh_init(m);
    lam_error_clear(err);
    return lam_import_ug(model_path(rel, path, sizeof path), m, err);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

/* Expect an import error of `code` at line:col whose message holds `sub`. */
static void check_error(const char *label, const char *src, int code, long line, long col,
                        const char *sub)
{
    lam_mesh m;
    lam_error err;
    int rc = load(src, NULL, &m, &err);
    is_int(rc, code, "%s: status", label);
    is_int(err.code, code, "%s: err.code", label);
    is_int(err.line, line, "%s: line", label);
    is_int(err.column, col, "%s: column", label);
    ok(has(err.msg, sub), "%s: message has \"%s\"", label, sub);
    if (!has(err.msg, sub)) diag("message: %s", err.msg);
    lam_mesh_free(&m);
}

/* The instance test part: one triangle a b c. */
#define PART "def p; v a 1 2 3; v b 4 5 6; v c 7 8 10; f pf (a b c); end;\n"

/* Import PART instanced with `xf` and check where vertex a lands (exactly,
 * or within tol) and whether the triangle was turned over. */
static void check_xf(const char *xf, double x, double y, double z, double tol, int flipped)
{
    char src[512];
    snprintf(src, sizeof src, PART "i (p %s);", xf);
    lam_mesh m;
    lam_error err;
    int rc = load(src, NULL, &m, &err);
    is_int(rc, LAM_OK, "%s: loads", xf);
    if (rc) diag("%s", err.msg);
    if (rc || m.nverts != 3 || m.ntris != 1) {
        ok(0, "%s: 3 vertices, 1 triangle (got %zu, %zu)", xf, m.nverts, m.ntris);
        lam_mesh_free(&m);
        return;
    }
    /* a is emitted first (lazily, in ring order). */
    is_num(m.xyz[0], x, tol, "%s: x", xf);
    is_num(m.xyz[1], y, tol, "%s: y", xf);
    is_num(m.xyz[2], z, tol, "%s: z", xf);
    if (flipped) ok(m.tris[0] == 2 && m.tris[1] == 1 && m.tris[2] == 0, "%s: ring reversed", xf);
    else ok(m.tris[0] == 0 && m.tris[1] == 1 && m.tris[2] == 2, "%s: ring order kept", xf);
    lam_mesh_free(&m);
}

static void test_thesis_cube_hole(void)
{
    lam_mesh m;
    lam_error err;
    int rc = load_file("thesis_cube_hole.ug", &m, &err);
    load_ok(rc, &err, "thesis_cube_hole: loads");
    is_int(m.ntris, 24, "thesis_cube_hole: 12 quads -> 24 triangles");
    is_int(m.nfaces, 12, "thesis_cube_hole: 12 face records");
    is_int(m.nverts, 16, "thesis_cube_hole: 16 vertices emitted");
    if (m.nfaces == 12) {
        is_str(lam_mesh_string(&m, m.faces[0].name), "base", "first face is 'base'");
        is_int(m.faces[0].line, 26, "'base' line");
        is_int(m.faces[0].column, 1, "'base' column");
        ok(ends_with(lam_mesh_string(&m, m.faces[0].file), "thesis_cube_hole.ug"), "'base' file");
        is_str(lam_mesh_string(&m, m.faces[11].name), "tt", "last face is 'tt'");
        is_int(m.faces[11].line, 39, "'tt' line");
    }
    double lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { -1e9, -1e9, -1e9 };
    for (size_t v = 0; v < m.nverts; v++)
        for (int k = 0; k < 3; k++) {
            if (m.xyz[3 * v + k] < lo[k]) lo[k] = m.xyz[3 * v + k];
            if (m.xyz[3 * v + k] > hi[k]) hi[k] = m.xyz[3 * v + k];
        }
    ok(lo[0] == -1 && lo[1] == -1 && lo[2] == 0 && hi[0] == 1 && hi[1] == 1 && hi[2] == 2,
       "thesis_cube_hole: bounding box [-1,1]x[-1,1]x[0,2]");
    lam_mesh_free(&m);
}

static void test_frame_island(void)
{
    lam_mesh m;
    lam_error err;
    int rc = load_file("frame_island.ug", &m, &err);
    load_ok(rc, &err, "frame_island: loads");
    is_int(m.ntris, 44, "frame_island: 8 + 8 + 16 + 12 triangles");
    is_int(m.nfaces, 16, "frame_island: 10 frame faces + 6 box faces");
    /* Triangles per face record: the frame's top and bottom are annuli. */
    size_t per_face[32] = { 0 };
    for (size_t t = 0; t < m.ntris && m.tri_face; t++)
        if (m.tri_face[t] < 32) per_face[m.tri_face[t]]++;
    if (m.nfaces == 16) {
        is_str(lam_mesh_string(&m, m.faces[0].name), "frame_bottom", "face 0 is frame_bottom");
        is_int(per_face[0], 8, "frame_bottom (4 + 4 vertices, one hole) -> 8 triangles");
        is_str(lam_mesh_string(&m, m.faces[1].name), "frame_top", "face 1 is frame_top");
        is_int(per_face[1], 8, "frame_top -> 8 triangles");
        for (int f = 2; f < 16; f++)
            if (per_face[f] != 2) ok(0, "face %d has %zu triangles, not 2", f, per_face[f]);
        ok(m.faces[10].name == LAM_NO_NAME, "box faces are anonymous");
        is_int(m.faces[10].line, 7, "instanced face keeps the def's line");
        is_int(m.faces[10].column, 3, "instanced face keeps the def's column");
    }
    /* The box instance is emitted last: its 12 triangles span the island. */
    double lo[3] = { 1e9, 1e9, 1e9 }, hi[3] = { -1e9, -1e9, -1e9 };
    for (size_t t = m.ntris >= 12 ? m.ntris - 12 : 0; t < m.ntris; t++)
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) {
                double v = m.xyz[3 * (size_t)m.tris[3 * t + c] + k];
                if (v < lo[k]) lo[k] = v;
                if (v > hi[k]) hi[k] = v;
            }
    is_num(lo[0], -5, 0, "island x min");
    is_num(hi[0], 5, 0, "island x max");
    is_num(lo[1], -5, 0, "island y min");
    is_num(hi[1], 5, 0, "island y max");
    is_num(lo[2], -10, 0, "island z min");
    is_num(hi[2], 10, 0, "island z max");
    lam_mesh_free(&m);
}

static void test_transforms(void)
{
    /* vertex a = (1, 2, 3) */
    check_xf("", 1, 2, 3, 0, 0);
    check_xf("red", 1, 2, 3, 0, 0);
    check_xf("-tx 1", 2, 2, 3, 0, 0);
    check_xf("-ty 2", 1, 4, 3, 0, 0);
    check_xf("-tz -3", 1, 2, 0, 0, 0);
    check_xf("-ta 1 2 3", 2, 4, 6, 0, 0);
    check_xf("-sx 2", 2, 2, 3, 0, 0);
    check_xf("-sy 3", 1, 6, 3, 0, 0);
    check_xf("-sz .5", 1, 2, 1.5, 0, 0);
    check_xf("-sa 2", 2, 4, 6, 0, 0);
    check_xf("-sa -1", -1, -2, -3, 0, 1);
    check_xf("-rx 90", 1, -3, 2, 0, 0);
    check_xf("-ry 90", 3, 2, -1, 0, 0);
    check_xf("-rz 90", -2, 1, 3, 0, 0);
    check_xf("-rz -90", 2, -1, 3, 0, 0);
    check_xf("-rz 180", -1, -2, 3, 0, 0);
    check_xf("-rz 450", -2, 1, 3, 0, 0);
    check_xf("-rz 45", -0.70710678118654757, 2.1213203435596424, 3, 1e-12, 0);
    check_xf("-rz 90 -tx 1", -1, 1, 3, 0, 0);     /* left to right: rotate, then move */
    check_xf("-tx 1 -rz 90", -2, 2, 3, 0, 0);     /* move, then rotate */
    check_xf("blue -sx 2 -ty 1", 2, 3, 3, 0, 0);
    check_xf("-mx", -1, 2, 3, 0, 1);
    check_xf("-my", 1, -2, 3, 0, 1);
    check_xf("-mz", 1, 2, -3, 0, 1);
    check_xf("-mx -my", -1, -2, 3, 0, 0);         /* two mirrors: a rotation */
    check_xf("-M3 0 -1 0 1 0 0 0 0 1", -2, 1, 3, 0, 0);
    check_xf("-M3 -1 0 0 0 1 0 0 0 1", -1, 2, 3, 0, 1);
    check_xf("-M4 1 0 0 5 0 1 0 6 0 0 1 7 0 0 0 1", 6, 8, 10, 0, 0);
    check_xf("-M4 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2", 0.5, 1, 1.5, 0, 0);

    /* The other corners, once. */
    lam_mesh m;
    lam_error err;
    int rc = load(PART "i (p -rz 90 -tx 1);", NULL, &m, &err);
    is_int(rc, LAM_OK, "b and c under -rz 90 -tx 1");
    if (!rc && m.nverts == 3) {
        ok(m.xyz[3] == -4 && m.xyz[4] == 4 && m.xyz[5] == 6, "b (4,5,6) -> (-4,4,6)");
        ok(m.xyz[6] == -7 && m.xyz[7] == 7 && m.xyz[8] == 10, "c (7,8,10) -> (-7,7,10)");
        is_str(lam_mesh_string(&m, m.faces[0].name), "pf", "instanced face keeps its id");
    }
    lam_mesh_free(&m);

    /* Nesting: the inner instance's transform applies first. */
    rc = load(PART "def q; i (p -tx 1); end;\ni (q -rz 90);", NULL, &m, &err);
    is_int(rc, LAM_OK, "nested instances load");
    if (!rc && m.nverts == 3) ok(m.xyz[0] == -2 && m.xyz[1] == 2 && m.xyz[2] == 3, "a -> tx 1 -> rz 90 = (-2,2,3)");
    lam_mesh_free(&m);

    /* A nested mirror turns the face over once; two mirrors restore it. */
    rc = load(PART "def q; i (p -mx); end;\ni (q -my);", NULL, &m, &err);
    is_int(rc, LAM_OK, "nested mirrors load");
    if (!rc && m.ntris == 1) ok(m.tris[0] == 0 && m.tris[2] == 2, "mirror of a mirror keeps the winding");
    lam_mesh_free(&m);

    /* A definition emits nothing until instanced; each instance emits. */
    rc = load(PART, NULL, &m, &err);
    is_int(rc, LAM_OK, "definition alone loads");
    is_int(m.ntris, 0, "definition alone emits nothing");
    lam_mesh_free(&m);
    rc = load(PART "i (p); i second (p -tz 1);", NULL, &m, &err);
    is_int(m.ntris, 2, "two instances, two triangles");
    is_int(m.nverts, 6, "two instances, vertices emitted per instance");
    lam_mesh_free(&m);
}

static void test_syntax(void)
{
    lam_mesh m;
    lam_error err;
    /* Keywords only count at the start of a statement; names may start with
     * digits and hold any punctuation but ( ) ; { }. */
    int rc = load("v v 0 0 0; v f 1 0 0; v def 0 1 0; v 2#a:b.c 0 0 1;\n"
                  "f end (v f def) red; f (v 2#a:b.c f);\n"
                  "v n 1 1 1 0 0 1; { normal ignored }\n"
                  "w edge (v f def v) green; w (n v);\n"
                  "c red 0.5 0.3; c_rgb green 0 1 0; l light 1 2 3; cam x (1 2 3);;\n",
                  NULL, &m, &err);
    load_ok(rc, &err, "keywords as names, attributes, normals, wires");
    is_int(m.ntris, 2, "two faces");
    is_int(m.nwires, 2, "two wires");
    is_int(m.nwire_segs, 4, "3 + 1 wire segments");
    if (m.nfaces == 2) is_str(lam_mesh_string(&m, m.faces[0].name), "end", "face named 'end'");
    lam_mesh_free(&m);

    /* Numbers in every spelling. */
    rc = load("v a 2 .5 -.5; v b 2.0 1e-3 -1E+2; v c 0x10 1e50 -0;\nf (a b c);", NULL, &m, &err);
    is_int(rc, LAM_OK, "number spellings");
    if (!rc && m.nverts == 3) {
        ok(m.xyz[0] == 2 && m.xyz[1] == 0.5 && m.xyz[2] == -0.5, "2 .5 -.5");
        ok(m.xyz[3] == 2 && m.xyz[4] == 1e-3 && m.xyz[5] == -100, "2.0 1e-3 -1E+2");
        ok(m.xyz[6] == 16 && m.xyz[7] == 1e50, "0x10 1e50");
    }
    lam_mesh_free(&m);

    /* Comments: nested braces, slash-star, a ring closed by repeating its
     * first vertex, a face with two holes. */
    rc = load("{ a { nested } comment } /* c { not nested */\n"
              "v a 0 0 0; v b 9 0 0; v c 9 9 0; v d 0 9 0;\n"
              "v e 1 1 0; v f 2 1 0; v g 2 2 0; v h 1 2 0;\n"
              "v i 5 5 0; v j 6 5 0; v k 6 6 0; v l 5 6 0;\n"
              "f holes (a b c d a) (e h g f) (i l k j);\n",
              NULL, &m, &err);
    load_ok(rc, &err, "face with two holes");
    is_int(m.ntris, 14, "12 vertices, two holes -> 12 + 2*2 - 2 = 14 triangles");
    lam_mesh_free(&m);

    /* An empty file and a comment-only file are empty meshes, not errors. */
    rc = load("", NULL, &m, &err);
    is_int(rc, LAM_OK, "empty file");
    ok(m.ntris == 0 && m.nverts == 0, "empty file: empty mesh");
    lam_mesh_free(&m);
    rc = load("{ nothing } /* here */ ;\n", NULL, &m, &err);
    is_int(rc, LAM_OK, "comments only");
    is_int(m.ntris, 0, "comments only: empty mesh");
    lam_mesh_free(&m);
    lam_mesh_init(&m);
    rc = lam_import_ug_buf(NULL, NULL, 0, &m, &err);
    is_int(rc, LAM_OK, "NULL path, no data");
    lam_mesh_free(&m);
}

static void test_includes(void)
{
    lam_mesh m;
    lam_error err;

    /* The thesis's sample #2: `include` inside a def, then instanced. */
    int rc = load_file("ug/sample2.ug", &m, &err);
    load_ok(rc, &err, "sample2 (include inside def) loads");
    is_int(m.ntris, 4, "sample2: two squares");
    if (m.nfaces == 2) {
        is_str(lam_mesh_string(&m, m.faces[0].name), "sq1", "slc1's face");
        ok(ends_with(lam_mesh_string(&m, m.faces[0].file), "ug/slc1.ug"), "face records its own file");
        is_int(m.faces[0].line, 3, "and its line there");
        is_str(lam_mesh_string(&m, m.faces[1].name), "sq2", "slc2's face");
    }
    lam_mesh_free(&m);

    /* Included geometry takes the include's transform; the library's
     * definitions become visible; a second include of it is fine. */
    rc = load("include lib -tz 1;\ni (tri -tx 10);\ninclude \"lib.ug\" -mx;", "main.ug", &m, &err);
    load_ok(rc, &err, "include with transforms, library definition");
    if (!rc && m.nverts == 9 && m.ntris == 3) {
        ok(m.xyz[0] == 0 && m.xyz[1] == 0 && m.xyz[2] == 6, "lib top triangle at z = 5 + 1");
        ok(m.xyz[3] == 1 && m.xyz[5] == 6, "its b at (1,0,6)");
        ok(m.xyz[9] == 10 && m.xyz[12] == 11, "tri instance moved by 10");
        ok(m.xyz[21] == -1 && m.xyz[23] == 5, "mirrored include: b at (-1,0,5)");
        ok(m.tris[6] == 8 && m.tris[8] == 6, "mirrored include reverses the ring");
    } else {
        ok(0, "9 vertices and 3 triangles (got %zu, %zu)", m.nverts, m.ntris);
    }
    lam_mesh_free(&m);

    /* Include inside an instanced def: transforms compose. */
    rc = load("def d; include lib -tz 1; end;\ni (d -tx 2);", "main.ug", &m, &err);
    is_int(rc, LAM_OK, "include inside a def");
    if (!rc && m.nverts == 3) ok(m.xyz[0] == 2 && m.xyz[1] == 0 && m.xyz[2] == 6, "(0,0,5) -> tz 1 -> tx 2");
    lam_mesh_free(&m);

    /* Include cycle: a.ug -> b.ug -> a.ug, reported at b's include. */
    rc = load_file("ug/a.ug", &m, &err);
    is_int(rc, LAM_EINVAL, "include cycle: status");
    ok(ends_with(err.file, "ug/b.ug"), "include cycle: in b.ug (%s)", err.file);
    is_int(err.line, 2, "include cycle: line");
    is_int(err.column, 1, "include cycle: column");
    ok(has(err.msg, "include cycle") && has(err.msg, "a.ug -> ") && has(err.msg, "b.ug -> "),
       "include cycle: names the cycle (%s)", err.msg);
    lam_mesh_free(&m);

    rc = load("v a 0 0 0;\n  include nosuchfile -tx 1;\n", "main.ug", &m, &err);
    is_int(rc, LAM_EIO, "missing include: status");
    is_int(err.line, 2, "missing include: line");
    is_int(err.column, 3, "missing include: column");
    ok(has(err.msg, "nosuchfile") && has(err.msg, "No such file"), "missing include: %s", err.msg);
    lam_mesh_free(&m);

    check_error("included definition clash", "def tri; end;\ninclude lib;", LAM_EINVAL, 2, 1,
                "included definition 'tri'");

    /* A missing root file. */
    rc = load_file("ug/does_not_exist.ug", &m, &err);
    is_int(rc, LAM_EIO, "missing root file");
    lam_mesh_free(&m);
}

/* A chain of n definitions, each instancing the one before (line k+1 holds
 * def dk). */
static char *chain(int n, int twice)
{
    size_t cap = (size_t)n * 64 + 128, len = 0;
    char *s = malloc(cap);
    len += (size_t)snprintf(s, cap, "def d0; v a 0 0 0; v b 1 0 0; v c 0 1 0; f (a b c); end;\n");
    for (int k = 1; k < n; k++)
        len += (size_t)snprintf(s + len, cap - len, twice ? "def d%d; i (d%d); i (d%d -tz 1); end;\n"
                                                          : "def d%d; i (d%d); end;\n",
                                k, k - 1, k - 1);
    snprintf(s + len, cap - len, "i (d%d);\n", n - 1);
    return s;
}

static void test_limits(void)
{
    /* 64 levels of instances are allowed... */
    char *src = chain(64, 0);
    lam_mesh m;
    lam_error err;
    int rc = load(src, NULL, &m, &err);
    is_int(rc, LAM_OK, "instances 64 deep");
    is_int(m.ntris, 1, "instances 64 deep: one triangle");
    lam_mesh_free(&m);
    free(src);
    /* ...one more is an error at the instance that goes too deep. */
    src = chain(80, 0);
    check_error("instances nested too deeply", src, LAM_EINVAL, 66, 10, "nested more than 64 deep");
    free(src);
    /* Doubling 40 times: refused before anything is emitted. */
    src = chain(40, 1);
    check_error("exponential expansion", src, LAM_EINVAL, 25, 19, "expands to more than");
    free(src);

    /* Definitions nested 70 deep: refused at the 65th. */
    size_t cap = 70 * 16 + 16, len = 0;
    src = malloc(cap);
    for (int k = 0; k < 70; k++) len += (size_t)snprintf(src + len, cap - len, "def n%d;\n", k);
    for (int k = 0; k < 70; k++) len += (size_t)snprintf(src + len, cap - len, "end;");
    check_error("definitions nested too deeply", src, LAM_EINVAL, 65, 1, "definitions nested more than 64");
    free(src);

    /* Coordinates up to 1e50 in magnitude are fine, tiny ones too; beyond,
     * derived quantities (squared areas) would overflow: refused where the
     * number is, or at the vertex a transform carries too far. */
    rc = load("v a 1e50 0 0; v b -1e50 1 0; v c 0 0 1e-320;\nf (a b c);", NULL, &m, &err);
    is_int(rc, LAM_OK, "huge and tiny numbers");
    lam_mesh_free(&m);
    check_error("a coordinate of 1.5e308", "v a 0 0 0; v b 1 0 0;\nv c 0 0 1.5e308;\nf (a b c);", LAM_EINVAL, 2, 9,
                "more than a double can measure");
    check_error("a transform past 1e50", "def t; v a 0 0 0; v b 1 0 0;\nv c 0 0 1; f (a b c); end;\ni (t -sz 1e49 -sz 11);",
                LAM_EGEOM, 2, 3, "more than a double can measure");

    /* A NUL byte in the text is an error, not a truncation. */
    lam_mesh_init(&m);
    rc = lam_import_ug_buf("nul.ug", "v a 0 0 0;\n  \0 v", 16, &m, &err);
    is_int(rc, LAM_ESYNTAX, "NUL byte: status");
    ok(err.line == 2 && err.column == 3, "NUL byte: at 2:3 (got %ld:%ld)", err.line, err.column);
    lam_mesh_free(&m);
}

static void test_errors(void)
{
    check_error("unterminated {", "v a 0 0 0;\n  { open { nested }\nv b 1 0 0;\n",
                LAM_ESYNTAX, 2, 3, "unterminated '{' comment");
    check_error("unterminated /*", "/* ok */ v a 0 0 0;\n\n   /* never { closed",
                LAM_ESYNTAX, 3, 4, "unterminated '/*' comment");
    check_error("stray }", "v a 0 0 0; }", LAM_ESYNTAX, 1, 12, "'}'");
    check_error("undefined vertex", "v a 0 0 0; v b 1 0 0;\nf base (a b  Q);",
                LAM_EINVAL, 2, 14, "face 'base' names undefined vertex 'Q'");
    check_error("undefined vertex, anonymous face", "v a 0 0 0;\nf (a zz a);",
                LAM_EINVAL, 2, 6, "names undefined vertex 'zz'");
    check_error("vertex of another scope", "v a 0 0 0; v b 1 0 0; v c 0 1 0;\ndef d; f (a b c); end;",
                LAM_EINVAL, 2, 11, "undefined vertex 'a'");
    check_error("undefined wire vertex", "v a 0 0 0;\nw cable (a b);",
                LAM_EINVAL, 2, 12, "wire 'cable' names undefined vertex 'b'");
    check_error("nan coordinate", "v a nan 0 0;", LAM_EINVAL, 1, 5, "coordinate is not a finite number");
    check_error("inf coordinate", "v a 0 0 -inf;", LAM_EINVAL, 1, 9, "coordinate is not a finite number");
    check_error("overflowing coordinate", "v a 0 1e999 0;", LAM_EINVAL, 1, 7, "not a finite number");
    check_error("missing ';'", "v a 0 0 0\nv b 1 0 0;", LAM_ESYNTAX, 2, 1,
                "expected ';' after vertex coordinates, got 'v'");
    check_error("bad coordinate", "v a 0 zero 0;", LAM_ESYNTAX, 1, 7, "expected y coordinate of vertex 'a', got 'zero'");
    check_error("short normal", "v a 0 0 0 1 0;", LAM_ESYNTAX, 1, 14, "normal");
    check_error("vertex redefined", "v a 0 0 0;\n  v a 1 1 1;", LAM_EINVAL, 2, 5,
                "vertex 'a' redefined (first defined at line 1, column 3)");
    check_error("face without ';'", "v a 0 0 0; v b 1 0 0; v c 0 1 0;\nf (a b c) red blue;",
                LAM_ESYNTAX, 2, 15, "expected ';' after face colour, got 'blue'");
    check_error("face ring unclosed", "v a 0 0 0; v b 1 0 0; v c 0 1 0;\nf (a b c;",
                LAM_ESYNTAX, 2, 9, "expected vertex name or ')' in face, got ';'");
    check_error("degenerate face", "v a 0 0 0; v b 1 0 0;\n f flat (a b a b);",
                LAM_EGEOM, 2, 2, "face 'flat' has fewer than 3 distinct vertices");
    check_error("degenerate hole",
                "v a 0 0 0; v b 9 0 0; v c 9 9 0; v e 1 1 0; v f 2 2 0;\nf (a b c) (e f);",
                LAM_EGEOM, 2, 1, "hole 1 has fewer than 3");
    check_error("short wire", "v a 0 0 0;\nw (a a);", LAM_EINVAL, 2, 1, "at least 2");
    check_error("unknown statement", "v a 0 0 0;\nfoo bar;", LAM_ESYNTAX, 2, 1, "unknown statement 'foo'");
    check_error("statement is '('", "v a 0 0 0;\n(a);", LAM_ESYNTAX, 2, 1, "expected a statement, got '('");
    check_error("unterminated attribute", "c red 1 2", LAM_ESYNTAX, 1, 10, "expected ';' to end 'c' statement");
    check_error("self instance", "def a;\n  v p 0 0 0;\n  i (a);\nend;",
                LAM_EINVAL, 3, 3, "definition 'a' instantiates itself");
    check_error("indirect self instance", "def a;\n def b;\n  i x (a -tx 1);\n end;\nend;",
                LAM_EINVAL, 3, 3, "definition 'a' instantiates itself");
    check_error("undefined definition", "i (nothing);", LAM_EINVAL, 1, 4,
                "instance names undefined definition 'nothing'");
    check_error("instance before def", "i (later);\ndef later; end;", LAM_EINVAL, 1, 4, "undefined definition");
    check_error("definition redefined", "def d; end;\ndef d; end;", LAM_EINVAL, 2, 5,
                "definition 'd' redefined (first defined at line 1, column 1)");
    check_error("end without def", "v a 0 0 0;\n end;", LAM_ESYNTAX, 2, 2, "'end' without 'def'");
    check_error("eof inside def", "v a 0 0 0;\n  def open;\nv b 0 0 0;", LAM_ESYNTAX, 2, 3,
                "definition 'open' is not closed by 'end'");
    check_error("unknown transform", PART "i (p -tx 1 -qq 2);", LAM_ESYNTAX, 2, 12, "unknown transform '-qq'");
    check_error("too few transform numbers", PART "i (p -ta 1 2);", LAM_ESYNTAX, 2, 6,
                "transform '-ta' takes 3 numbers, got ')'");
    check_error("too many transform numbers", PART "i (p -tx 1 2);", LAM_ESYNTAX, 2, 6,
                "transform '-tx' takes 1 number, got more");
    check_error("mirror takes no number", PART "i (p -mx 1);", LAM_ESYNTAX, 2, 6, "'-mx' takes 0 numbers");
    check_error("non-finite transform", PART "i (p -sx inf);", LAM_EINVAL, 2, 10, "not a finite number");
    check_error("M4 short", PART "i (p -M4 1 0 0 0);", LAM_ESYNTAX, 2, 6, "takes 16 numbers");
    check_error("w = 0", PART "i (p -M4 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 0);", LAM_EGEOM, 1, 10, "w = 0");
    check_error("transform overflow", PART "i (p -sa 1e300 -sa 1e300);", LAM_EGEOM, 1, 10,
                "not a finite number after");
    check_error("instance without ';'", PART "i (p) x;", LAM_ESYNTAX, 2, 7, "expected ';' after instance");
    check_error("include without name", "include ;", LAM_ESYNTAX, 1, 9, "expected file name after 'include'");
}

/* err may be NULL (error.h): a failing import still fails, and nothing
 * reads through the NULL (this crashed where a message is wrapped: an
 * include cycle, a bad number, an unknown vertex). */
static void test_null_err(void)
{
    static const char *const bad[] = { "v a 1 2 3; f (a b c);", "v a 1e400 0 0;", "include \"nowhere\";",
                                       "v a 1 2", NULL };
    for (int i = 0; bad[i]; i++) {
        lam_mesh m;
        lam_mesh_init(&m);
        int rc = lam_import_ug_buf("null.ug", bad[i], strlen(bad[i]), &m, NULL);
        ok(rc != LAM_OK, "NULL err: '%s' still fails (rc %d)", bad[i], rc);
        lam_mesh_free(&m);
    }
}

int main(void)
{
    const char *t = getenv("TESTS");
    snprintf(tests_dir, sizeof tests_dir, "%s", t && *t ? t : "tests");
    test_thesis_cube_hole();
    test_null_err();
    test_frame_island();
    test_transforms();
    test_syntax();
    test_includes();
    test_limits();
    test_errors();
    return done_testing();
}
