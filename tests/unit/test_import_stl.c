/* STL importer: the thesis cube as ASCII and binary STL (also a binary whose
 * header begins with "solid"), exact number reading, every error with its
 * position (line:column for ASCII, byte offset for binary), truncations and
 * random mutations (must fail cleanly, never crash: run under SAN=1), and
 * the openscad/admesh cube_hole.stl from tests/models. Every buffer handed
 * to the importer is an exact-size heap copy, so ASan catches any read past
 * len (the importer may not rely on a NUL terminator). */
#include "import.h"
#include "tap.h"
#include "util.h"

#include <stdint.h>
#include <stdlib.h>

/* The thesis cube, (+-1, +-1, +-1), as 12 outward triangles. */
static const double V[8][3] = {
    { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 },
    { -1, -1, 1 },  { 1, -1, 1 },  { 1, 1, 1 },  { -1, 1, 1 },
};
static const int T[12][3] = {
    { 0, 3, 2 }, { 0, 2, 1 }, { 4, 5, 6 }, { 4, 6, 7 }, { 0, 1, 5 }, { 0, 5, 4 },
    { 2, 3, 7 }, { 2, 7, 6 }, { 1, 2, 6 }, { 1, 6, 5 }, { 3, 0, 4 }, { 3, 4, 7 },
};

/* ---- helpers ------------------------------------------------------------ */

/* Import from an exact-size heap copy of src[0..len). */
static int load(const void *src, size_t len, lam_mesh *m, int *bin, lam_error *err)
{
    unsigned char *copy = heap_copy(src, len);
    lam_mesh_init(m);
    lam_error_clear(err);
    *bin = -1;
    int rc = lam_import_stl_buf("t.stl", copy, len, m, bin, err);
    free(copy);
    return rc;
}

static int load_str(const char *s, lam_mesh *m, int *bin, lam_error *err)
{
    return load(s, strlen(s), m, bin, err);
}

/* Import src[0..len) for the status, *bin and *err only (the mesh is freed). */
static int load_status(const void *src, size_t len, int *bin, lam_error *err)
{
    lam_mesh m;
    int rc = load(src, len, &m, bin, err);
    lam_mesh_free(&m);
    return rc;
}

/* Triangle t's corner j equals cube vertex T[t][j], for all 12 triangles. */
static int cube_mismatches(const lam_mesh *m)
{
    if (m->ntris != 12) return -1;
    int bad = 0;
    for (size_t t = 0; t < 12; t++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                if (m->xyz[3 * (size_t)m->tris[3 * t + j] + k] != V[T[t][j]][k]) bad++;
    return bad;
}

static int all_finite(const lam_mesh *m)
{
    for (size_t i = 0; i < 3 * m->nverts; i++)
        if (!isfinite(m->xyz[i])) return 0;
    return 1;
}

/* ASCII cube: facet i starts on line 2 + 7 i, column 3. */
static char *ascii_cube(const char *facet_kw, int crlf)
{
    sbuf b = { 0 };
    const char *nl = crlf ? "\r\n" : "\n";
    sb_add(&b, "solid cube%s", nl);
    for (int t = 0; t < 12; t++) {
        sb_add(&b, "  %s normal 0 0 0%s    outer loop%s", facet_kw, nl, nl);
        for (int j = 0; j < 3; j++)
            sb_add(&b, "      vertex %g %g %g%s", V[T[t][j]][0], V[T[t][j]][1], V[T[t][j]][2], nl);
        sb_add(&b, "    endloop%s  endfacet%s", nl, nl);
    }
    sb_add(&b, "endsolid cube%s", nl);
    return b.s;
}

static void put_u32(unsigned char *p, uint32_t u)
{
    p[0] = (unsigned char)u;
    p[1] = (unsigned char)(u >> 8);
    p[2] = (unsigned char)(u >> 16);
    p[3] = (unsigned char)(u >> 24);
}

static void put_f32(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_u32(p, u);
}

/* Byte offset in a binary STL of coordinate k (0 x, 1 y, 2 z) of vertex j
 * (0-2) of facet t (0-based). */
static size_t coord_offset(size_t t, int j, int k) { return 84 + 50 * t + 12 + 12 * (size_t)j + 4 * (size_t)k; }

/* Binary cube: 684 bytes, header text, count field as given. */
static unsigned char *binary_cube(const char *header, uint32_t count_field, size_t *len)
{
    *len = 84 + 50 * 12;
    unsigned char *b = calloc(1, *len);
    memcpy(b, header, strlen(header) < 80 ? strlen(header) : 80);
    put_u32(b + 80, count_field);
    for (int t = 0; t < 12; t++) {
        unsigned char *f = b + 84 + 50 * t;
        put_f32(f + 8, 1.0f); /* a normal, ignored */
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) put_f32(b + coord_offset((size_t)t, j, k), (float)V[T[t][j]][k]);
        f[48] = 0xaa; /* attribute bytes, ignored */
    }
    return b;
}

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static uint64_t rng(void) { return xorshift64(&rng_state); }

/* ---- tests -------------------------------------------------------------- */

static void test_ascii_cube(void)
{
    lam_mesh m;
    lam_error err;
    int bin;
    char *s = ascii_cube("facet", 0);
    int rc = load_str(s, &m, &bin, &err);
    is_int(rc, LAM_OK, "ASCII cube loads (%s)", err.msg);
    is_int(bin, 0, "ASCII cube: *binary = 0");
    is_int(m.ntris, 12, "ASCII cube: 12 triangles");
    is_int(m.nverts, 8, "ASCII cube: 36 corners welded exactly to 8 vertices");
    is_int(cube_mismatches(&m), 0, "ASCII cube: every corner has the right coordinates");
    is_num(signed_volume(&m), 8.0, 1e-12, "ASCII cube: volume 8");
    is_int(m.nfaces, 12, "ASCII cube: one face record per facet");
    ok(m.tri_face != NULL, "ASCII cube: triangles carry face ids");
    int pos_ok = 1;
    for (size_t i = 0; i < m.nfaces && i < 12; i++)
        if (m.faces[i].line != 2 + 7 * i || m.faces[i].column != 3 || m.tri_face[i] != i ||
            m.faces[i].name != LAM_NO_NAME)
            pos_ok = 0;
    ok(pos_ok, "ASCII cube: face i is at line 2+7i, column 3 of 'facet', no name");
    is_str(lam_mesh_string(&m, m.faces[11].file), "t.stl", "ASCII cube: face file is the path");
    lam_mesh_free(&m);
    free(s);

    /* Keywords in any case, CRLF line ends. */
    s = ascii_cube("FaCeT", 1);
    for (char *p = s; (p = strstr(p, "vertex")); p += 6) memcpy(p, "VERTEX", 6);
    for (char *p = s; (p = strstr(p, "endloop")); p += 7) memcpy(p, "EndLoop", 7);
    memcpy(s, "SOLID", 5);
    rc = load_str(s, &m, &bin, &err);
    is_int(rc, LAM_OK, "mixed-case keywords and CRLF load (%s)", err.msg);
    is_int(cube_mismatches(&m), 0, "mixed-case CRLF cube: coordinates right");
    is_int(m.nfaces ? m.faces[5].line : 0, 2 + 7 * 5, "CRLF: lines counted once per CRLF");
    lam_mesh_free(&m);
    free(s);
}

static void test_ascii_variants(void)
{
    lam_mesh m;
    lam_error err;
    int bin;
    /* Two solids, tabs, leading blank lines and a BOM, no final endsolid. */
    sbuf b = { 0 };
    sb_add(&b, "\xef\xbb\xbf\n\n  solid first part\n");
    for (int t = 0; t < 12; t++) {
        if (t == 6) sb_add(&b, "endsolid first part\nsolid\n");
        sb_add(&b, "facet\tnormal 0 0 1 outer loop");
        for (int j = 0; j < 3; j++) sb_add(&b, "\tvertex %g %g %g", V[T[t][j]][0], V[T[t][j]][1], V[T[t][j]][2]);
        sb_add(&b, " endloop endfacet\n");
    }
    int rc = load_str(b.s, &m, &bin, &err);
    is_int(rc, LAM_OK, "two solids, tabs, one facet per line, BOM, no endsolid at EOF (%s)", err.msg);
    is_int(cube_mismatches(&m), 0, "two solids: coordinates right");
    is_int(m.nfaces ? m.faces[6].line : 0, 12, "two solids: facet 7 on line 12");
    is_int(m.nfaces ? m.faces[0].column : 0, 1, "BOM is not counted as columns");
    lam_mesh_free(&m);
    free(b.s);

    /* Empty solid, then a solid: fine. NaN normals are fine too. */
    rc = load_str("solid a\nendsolid a\nsolid b\nfacet normal nan NaN -inf\nouter loop\n"
                  "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid b\n",
                  &m, &bin, &err);
    is_int(rc, LAM_OK, "empty solid and a non-finite normal are accepted (%s)", err.msg);
    is_int(m.ntris, 1, "one triangle");
    lam_mesh_free(&m);

    /* Exact number reading: fast path, slow path, extremes. */
    rc = load_str("solid n\nfacet normal 0 0 0\nouter loop\n"
                  "vertex 0.1 -2.5e-3 +3\n"
                  "vertex 1e50 4.9406564584124654e-324 123456789012345678901234567890\n"
                  "vertex .5 5. -0\n"
                  "endloop\nendfacet\nendsolid n\n", &m, &bin, &err);
    is_int(rc, LAM_OK, "number forms load (%s)", err.msg);
    if (m.nverts == 3) {
        ok(m.xyz[0] == 0.1 && m.xyz[1] == -2.5e-3 && m.xyz[2] == 3.0, "0.1 -2.5e-3 +3 read exactly");
        ok(m.xyz[3] == 1e50, "1e50, the largest coordinate, read exactly");
        ok(m.xyz[4] == 4.9406564584124654e-324, "smallest subnormal read exactly");
        ok(m.xyz[5] == 123456789012345678901234567890.0, "30-digit integer read exactly");
        ok(m.xyz[6] == 0.5 && m.xyz[7] == 5.0 && m.xyz[8] == 0.0 && !signbit(m.xyz[8]),
           ".5 5. -0 read (-0 welds as +0)");
    } else {
        ok(0, "number forms: 3 vertices");
    }
    lam_mesh_free(&m);
    /* DBL_MAX reads, but a model that far out would overflow its areas */
    rc = load_str("solid n\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                  "vertex 0 1.7976931348623157e308 0\nendloop\nendfacet\nendsolid n\n", &m, &bin, &err);
    ok(rc == LAM_EINVAL && err.line == 6 && err.column == 10 && strstr(err.msg, "more than a double can measure"),
       "DBL_MAX refused at its position (%ld:%ld %s)", err.line, err.column, err.msg);
    lam_mesh_free(&m);
}

static void test_binary_cube(void)
{
    lam_mesh m;
    lam_error err;
    int bin;
    size_t len;
    unsigned char *b = binary_cube("binary cube from a test", 12, &len);
    int rc = load(b, len, &m, &bin, &err);
    is_int(rc, LAM_OK, "binary cube loads (%s)", err.msg);
    is_int(bin, 1, "binary cube: *binary = 1");
    is_int(m.ntris, 12, "binary cube: 12 triangles");
    is_int(m.nverts, 8, "binary cube: 36 corners welded exactly to 8 vertices");
    is_int(cube_mismatches(&m), 0, "binary cube: every corner has the right coordinates");
    is_num(signed_volume(&m), 8.0, 1e-12, "binary cube: volume 8");
    ok(m.tri_face == NULL && m.nfaces == 0, "binary cube: no face records (triangle i is facet i+1)");
    lam_mesh_free(&m);
    free(b);

    b = binary_cube("solid cube exported by a CAD system", 12, &len);
    rc = load(b, len, &m, &bin, &err);
    is_int(rc, LAM_OK, "binary cube whose header begins with 'solid' loads (%s)", err.msg);
    is_int(bin, 1, "'solid' header, size matches: binary");
    is_int(cube_mismatches(&m), 0, "'solid' header: coordinates right");
    lam_mesh_free(&m);

    /* A NaN normal is not an error. */
    put_f32(b + 84 + 50 * 3, NAN);
    rc = load_status(b, len, &bin, &err);
    is_int(rc, LAM_OK, "binary: NaN normal accepted");
    free(b);

    /* No triangles at all: valid, empty. */
    b = binary_cube("empty", 0, &len);
    rc = load(b, 84, &m, &bin, &err);
    ok(rc == LAM_OK && m.ntris == 0 && bin == 1, "84-byte binary with count 0: empty mesh");
    lam_mesh_free(&m);
    free(b);
}

static void test_binary_errors(void)
{
    lam_error err;
    int bin;
    size_t len;
    unsigned char *b;
    int rc = load_status("", 0, &bin, &err);
    ok(rc != LAM_OK, "empty buffer fails");
    is_str(err.msg, "file too short for a binary STL (0 bytes)", "empty buffer: message");

    rc = load_status("not an stl", 10, &bin, &err);
    ok(rc == LAM_EFORMAT && has(err.msg, "file too short for a binary STL (10 bytes)"),
       "10 bytes of text: too short (%s)", err.msg);

    b = binary_cube("cube", 12, &len);
    rc = load_status(b, len - 10, &bin, &err);
    ok(rc != LAM_OK, "truncated binary fails");
    is_int(err.offset, 80, "truncated binary: error at byte 80");
    is_str(err.msg, "binary STL declares 12 triangles (needs 684 bytes) but the file has 674 bytes",
           "truncated binary: message");
    is_int(bin, 1, "truncated binary: *binary = 1");

    put_u32(b + 80, 13);
    rc = load_status(b, len, &bin, &err);
    ok(rc != LAM_OK && err.offset == 80, "count too large: error at byte 80");
    is_str(err.msg, "binary STL declares 13 triangles (needs 734 bytes) but the file has 684 bytes",
           "count too large: message");

    put_u32(b + 80, 0xffffffffu);
    rc = load_status(b, len, &bin, &err);
    ok(rc != LAM_OK && err.offset == 80 && has(err.msg, "declares 4294967295 triangles"),
       "count 2^32-1: clean error (%s)", err.msg);
    free(b);

    /* Truncated binary whose header begins with "solid": the count error,
     * not a syntax error inside binary data. */
    b = binary_cube("solid cube", 12, &len);
    rc = load_status(b, len - 50, &bin, &err);
    ok(rc != LAM_OK && err.offset == 80 && has(err.msg, "declares 12 triangles"),
       "truncated binary with 'solid' header: count error at byte 80 (%s)", err.msg);
    free(b);

    /* Non-finite coordinates: error at the float's own byte offset. */
    b = binary_cube("cube", 12, &len);
    put_f32(b + coord_offset(5, 1, 1), NAN); /* facet 6, vertex 2, y */
    rc = load_status(b, len, &bin, &err);
    is_int(rc, LAM_EINVAL, "binary NaN coordinate fails");
    is_int(err.offset, 362, "binary NaN: offset of that float (362)");
    ok(has(err.msg, "facet 6, vertex 2: y coordinate is not a finite number"), "binary NaN: message (%s)",
       err.msg);
    free(b);

    b = binary_cube("solid", 12, &len);
    put_f32(b + coord_offset(11, 2, 2), -INFINITY); /* last facet, vertex 3, z */
    rc = load_status(b, len, &bin, &err);
    is_int(rc, LAM_EINVAL, "binary -inf coordinate fails");
    is_int(err.offset, 678, "binary -inf: offset of that float (678)");
    ok(has(err.msg, "facet 12, vertex 3: z coordinate is not a finite number (-inf)"),
       "binary -inf: message (%s)", err.msg);
    char buf[1200];
    is_str(lam_error_format(&err, buf, sizeof buf),
           "t.stl: byte 678: facet 12, vertex 3: z coordinate is not a finite number (-inf)",
           "binary error formats with the byte offset");
    free(b);

    /* Binary facets cannot join a mesh with face records. */
    b = binary_cube("cube", 12, &len);
    lam_mesh m;
    lam_mesh_init(&m);
    lam_error_clear(&err);
    char *s = ascii_cube("facet", 0);
    rc = lam_import_stl_buf("a.stl", (const unsigned char *)s, strlen(s), &m, &bin, &err);
    rc = rc ? rc : lam_import_stl_buf("b.stl", b, len, &m, &bin, &err);
    is_int(rc, LAM_EINVAL, "binary after ASCII in one mesh: refused");
    lam_mesh_free(&m);
    free(s);
    free(b);
}

/* One ASCII case: must fail with code at line:col and a message containing msg. */
static void ascii_error(const char *text, int code, long line, long col, const char *msg, const char *what)
{
    lam_error err;
    int bin;
    int rc = load_status(text, strlen(text), &bin, &err);
    error_is(rc, &err, code, line, col, msg, what);
}

/* A facet's opening on lines 1-3 (vertices from line 4), and its three
 * vertices on lines 4-6, for error cases. */
#define FACET_HEAD "solid t\nfacet normal 0 0 1\nouter loop\n"
#define FACET_VERTICES "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"

static void test_ascii_errors(void)
{
    ascii_error(FACET_HEAD "  vertex 0 0 0\n  vertex 1 0 0\n endloop\nendfacet\nendsolid t\n", LAM_ESYNTAX, 6, 2,
                "facet has 2 vertices, expected 3", "facet with 2 vertices: at 'endloop' 6:2");
    ascii_error(FACET_HEAD FACET_VERTICES "   vertex 0 1 0\n endloop\nendfacet\nendsolid t\n", LAM_ESYNTAX, 7, 4,
                "facet has more than 3 vertices", "facet with 4 vertices: at the 4th 'vertex' 7:4");
    ascii_error(FACET_HEAD "endloop\n", LAM_ESYNTAX, 4, 1,
                "facet has 0 vertices, expected 3", "facet with no vertices");
    ascii_error(FACET_HEAD "vertex 0 0 0\nvertex 1 nan 0\n", LAM_EINVAL, 5, 10,
                "vertex y coordinate is not a finite number ('nan')", "ASCII NaN coordinate at 5:10");
    ascii_error(FACET_HEAD "vertex 0 0 -Infinity\n", LAM_EINVAL, 4, 12,
                "coordinate is not a finite number", "ASCII -Infinity coordinate at 4:12");
    ascii_error(FACET_HEAD "vertex 1e999 0 0\n", LAM_EINVAL, 4, 8,
                "coordinate is not a finite number ('1e999')", "ASCII overflowing coordinate");
    ascii_error(FACET_HEAD "vertex 0 1.#QNAN 0\n", LAM_EINVAL, 4, 10,
                "coordinate is not a finite number", "ASCII MSVC 1.#QNAN coordinate");
    ascii_error(FACET_HEAD "vertex 0 1.0.0 0\n", LAM_ESYNTAX, 4, 10,
                "expected the vertex y coordinate (a number), found '1.0.0'", "malformed number");
    ascii_error(FACET_HEAD "vertex 0 1e 0\n", LAM_ESYNTAX, 4, 10,
                "found '1e'", "exponent without digits");
    ascii_error("solid t\nfacet normal 0 x 1\n", LAM_ESYNTAX, 2, 16,
                "expected the normal y coordinate (a number), found 'x'", "malformed normal");
    ascii_error("solid t\nfacet normal 0 0 1\n  outer lop\n", LAM_ESYNTAX, 3, 9,
                "expected 'loop' after 'outer', found 'lop'", "'outer lop'");
    ascii_error("solid t\nfacet 0 0 1\n", LAM_ESYNTAX, 2, 7, "expected 'normal' after 'facet', found '0'",
                "facet without normal");
    ascii_error(FACET_HEAD "vertex 0 0 0\n", LAM_ESYNTAX, 5, 1,
                "expected 'vertex' or 'endloop', found end of file", "EOF inside a facet: position at EOF");
    ascii_error(FACET_HEAD "vertex 0 0 0\nvertex 0 0", LAM_ESYNTAX, 5, 11,
                "expected the vertex z coordinate, found end of file", "EOF inside a vertex");
    ascii_error(FACET_HEAD FACET_VERTICES "endloop\nendfacet\nfoo\n", LAM_ESYNTAX, 9, 1,
                "expected 'facet' or 'endsolid', found 'foo'", "unexpected token between facets");
    ascii_error(FACET_HEAD FACET_VERTICES "endloop\n", LAM_ESYNTAX, 8, 1,
                "expected 'endfacet' after 'endloop', found end of file", "EOF before endfacet");
    ascii_error("solid t\nendsolid t\n garbage\n", LAM_ESYNTAX, 3, 2,
                "expected 'solid' or end of file, found 'garbage'", "garbage after endsolid");
    ascii_error("solid", LAM_ESYNTAX, 1, 6, "expected 'facet' or 'endsolid', found end of file",
                "'solid' alone: EOF error just past it");
    ascii_error("solidworks part\n", LAM_ESYNTAX, 1, 1, "expected 'solid', found 'solidworks'",
                "'solidworks' is not 'solid'");
    ascii_error("solid t\r\nfacet normal 0 0 1\r\n\touter loop\r\n\tvertex 0 0 0\r\n\tendloop\r\n", LAM_ESYNTAX, 5, 2,
                "facet has 1 vertex, expected 3", "CRLF and tabs: columns in bytes");
    ascii_error(FACET_HEAD "vertex 0 0 \x01\xff\n", LAM_ESYNTAX, 4, 12,
                "found '\\x01\\xff'", "binary bytes are quoted as \\xNN in messages");

    lam_error err;
    int bin;
    const char *text = FACET_HEAD "endloop\n";
    load_status(text, strlen(text), &bin, &err);
    char buf[1200];
    is_str(lam_error_format(&err, buf, sizeof buf), "t.stl:4:1: facet has 0 vertices, expected 3",
           "ASCII error formats as file:line:column");
}

/* Every prefix of the ASCII cube: succeeds exactly when it ends after a
 * complete 'endfacet' (or once 'endsolid' is complete), with as many
 * triangles as complete facets; never reads past the prefix. */
static void test_ascii_prefixes(void)
{
    char *s = ascii_cube("facet", 0);
    size_t n = strlen(s);
    const char *endsolid = strstr(s, "endsolid");
    size_t bad = 0;
    for (size_t len = 0; len <= n; len++) {
        lam_mesh m;
        lam_error err;
        int bin;
        int rc = load(s, len, &m, &bin, &err);
        size_t trim = len;
        while (trim && (s[trim - 1] == ' ' || s[trim - 1] == '\n')) trim--;
        size_t facets = 0;
        for (const char *p = s; (p = strstr(p, "endfacet")) && (size_t)(p - s) + 8 <= len; p += 8) facets++;
        int expect_ok = (trim >= 8 && memcmp(s + trim - 8, "endfacet", 8) == 0) ||
                        len >= (size_t)(endsolid - s) + 8;
        if (expect_ok ? rc != LAM_OK || m.ntris != facets : rc == LAM_OK || !err.msg[0] || (err.line < 1 && rc != LAM_EFORMAT)) {
            if (bad++ < 3) diag("prefix %zu: rc %d, %zu triangles, '%s'", len, rc, m.ntris, err.msg);
        }
        lam_mesh_free(&m);
    }
    is_int(bad, 0, "all %zu prefixes of the ASCII cube: ok exactly after complete facets", n + 1);
    free(s);

    size_t blen;
    unsigned char *b = binary_cube("solid cube", 12, &blen);
    bad = 0;
    for (size_t len = 0; len < blen; len++) {
        lam_error err;
        int bin;
        int rc = load_status(b, len, &bin, &err);
        if (rc == LAM_OK || !err.msg[0] || (len >= 84 && err.offset != 80)) bad++;
    }
    is_int(bad, 0, "every truncation of the binary cube fails cleanly (count error at byte 80)");
    free(b);
}

/* Random byte mutations: each result is success with finite coordinates or
 * an error with a message and a position. */
static void test_mutations(void)
{
    static const char alphabet[] = "0123456789.-+eE \n\r\tsolidfacetnormalvertexendloop#\0\xff";
    char *s = ascii_cube("facet", 0);
    size_t n = strlen(s), blen;
    unsigned char *b = binary_cube("solid x", 12, &blen);
    unsigned char *work = malloc(n > blen ? n : blen);
    size_t bad = 0, oks = 0, runs = 4000;
    for (size_t r = 0; r < runs; r++) {
        int binary = r & 1;
        size_t len = binary ? blen : n;
        memcpy(work, binary ? (const void *)b : (const void *)s, len);
        int k = 1 + (int)(rng() % 4);
        for (int i = 0; i < k; i++) {
            size_t at = rng() % len;
            work[at] = binary ? (unsigned char)rng() : (unsigned char)alphabet[rng() % (sizeof alphabet - 1)];
        }
        if (rng() % 4 == 0) len = rng() % len;
        lam_mesh m;
        lam_error err;
        int bin;
        int rc = load(work, len, &m, &bin, &err);
        if (rc == LAM_OK) {
            oks++;
            if (!all_finite(&m) || m.ntris > 12) bad++;
        } else if (!err.msg[0] || err.code != rc ||
                   !((err.line >= 1 && err.column >= 1) || err.offset >= 0 || rc == LAM_EFORMAT)) {
            if (bad++ < 3) diag("mutation %zu: rc %d, '%s'", r, rc, err.msg);
        }
        lam_mesh_free(&m);
    }
    is_int(bad, 0, "%zu random mutations: success with finite coordinates or a positioned error (%zu ok)",
           runs, oks);
    free(work);
    free(b);
    free(s);
}

static void test_cube_hole_file(void)
{
    const char *dir = getenv("TESTS");
    char path[1024];
    snprintf(path, sizeof path, "%s/models/cube_hole.stl", dir ? dir : "tests");
    FILE *f = fopen(path, "rb");
    ok(f != NULL, "open %s", path);
    if (!f) return;
    unsigned char *data = malloc(1 << 20);
    size_t size = fread(data, 1, 1 << 20, f);
    fclose(f);
    lam_mesh m;
    lam_error err;
    int bin;
    int rc = load(data, size, &m, &bin, &err);
    is_int(rc, LAM_OK, "cube_hole.stl loads (%s)", err.msg);
    is_int(bin, 1, "cube_hole.stl is binary");
    is_int(m.ntris, (size - 84) / 50, "cube_hole.stl: triangle count = (size - 84) / 50");
    ok(all_finite(&m), "cube_hole.stl: finite coordinates");
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < m.nverts; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m.xyz[3 * i + k]);
            hi[k] = fmax(hi[k], m.xyz[3 * i + k]);
        }
    ok(lo[0] == -1 && lo[1] == -1 && lo[2] == 0 && hi[0] == 1 && hi[1] == 1 && hi[2] == 2,
       "cube_hole.stl: bounding box [-1,1]x[-1,1]x[0,2]");
    is_num(fabs(signed_volume(&m)), 6.0, 1e-9, "cube_hole.stl: |volume| = 8 - 2 = 6");
    lam_mesh_free(&m);
    free(data);
}

int main(void)
{
    test_ascii_cube();
    test_ascii_variants();
    test_binary_cube();
    test_binary_errors();
    test_ascii_errors();
    test_ascii_prefixes();
    test_mutations();
    test_cube_hole_file();
    return done_testing();
}
