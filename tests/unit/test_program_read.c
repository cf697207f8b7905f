/* Programs read back (program_read.h): the thesis cube with its hole
 * written by each shipped contour dialect (tests/models/validate/cube_hole*),
 * hand-written programs, and malformed ones with the position of what is
 * wrong. Expected values come from the part: 4 layers of -w 0.5 at 0.25,
 * 0.75, 1.25, 1.75, each the square (-1..1) and the hole (-0.5..0.5). */
#include "meshes.h"
#include "program_read.h"

#include <stdlib.h>
#include <string.h>

static lam_program *read_model(const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/models/validate/%s", tests_dir(), name);
    lam_program *p = NULL;
    lam_error err;
    lam_error_clear(&err);
    if (lam_program_read(path, &p, &err)) diag("%s: %s", name, err.msg);
    return p;
}

/* The part as written: layer i at 0.25 + 0.5 i, contour 0 the square
 * (counter-clockwise), contour 1 the hole (clockwise), 4 corners each. */
static void cube_hole(const char *name, lam_program_format fmt, double qxy)
{
    lam_program *p = read_model(name);
    ok(p != NULL, "%s read", name);
    if (!p) return;
    ok(p->format == fmt, "%s: format %s", name, lam_program_format_name(p->format));
    int good = p->nlayers == 4 && p->ncontours == 8 && p->npoints == 32;
    for (size_t i = 0; good && i < 4; i++) {
        const lam_program_layer *L = &p->layers[i];
        good = L->z == 0.25 + 0.5 * (double)i && L->n == 2 && L->first == 2 * i;
        for (size_t k = 0; good && k < 2; k++) {
            const lam_program_contour *c = &p->contours[L->first + k];
            double h = k ? 0.5 : 1, area = 0, maxabs = 0;
            for (size_t j = 0; j < c->n; j++) {
                const double *a = p->xyz + 3 * (c->first + j), *b = p->xyz + 3 * (c->first + (j + 1) % c->n);
                area += (a[0] * b[1] - a[1] * b[0]) / 2;
                maxabs = fmax(maxabs, fmax(fabs(a[0]), fabs(a[1])));
                good = good && a[2] == L->z;
            }
            good = good && c->n == 4 && maxabs == h && fabs(area - (k ? -1 : 4)) < 1e-12 &&
                   c->dir == (fmt == LAM_PROGRAM_SLS ? -1 : k ? 0 : 1);
        }
    }
    ok(good, "%s: 4 layers at 0.25 + 0.5 i, a CCW square of area 4 and a CW hole of area 1 in each, "
             "closing points dropped, directions as written",
       name);
    ok(p->quantum_xy == qxy, "%s: coordinates good to %g (got %g)", name, qxy, p->quantum_xy);
    if (fmt != LAM_PROGRAM_CLI_BINARY) {
        const lam_program_contour *c = &p->contours[1];
        ok(c->offset == -1 && c->line == (fmt == LAM_PROGRAM_SLS ? 11 : 10) && c->column == 1,
           "%s: the second contour starts at line %ld, column %ld", name, c->line, c->column);
    } else {
        ok(p->contours[0].offset > 60 && p->contours[1].offset > p->contours[0].offset,
           "%s: contours at byte offsets (%lld, %lld)", name, p->contours[0].offset, p->contours[1].offset);
    }
    /* as layers along z: uv as written, labels from the written direction */
    lam_frame f;
    lam_frame_axis('z', &f, NULL);
    lam_layer L;
    lam_error err;
    int rc = lam_program_layer_make(p, 2, &f, 0, name, &L, &err);
    ok(rc == LAM_OK && L.ncontours == 2 && L.cut == 1.25 && L.contours[0].kind == LAM_SOLID &&
           L.contours[1].kind == LAM_HOLE && L.contours[1].depth == -1 && L.contours[1].parent == -1,
       "%s: layer 2 as a layer: cut 1.25, a solid and a hole, nesting unknown (-1)", name);
    if (rc == LAM_OK) lam_layer_clear(&L);
    lam_program_free(p);
}

static int bad(const char *text, size_t len, int code, long line, long col, long long offset, const char *msg,
               const char *what)
{
    lam_program *p = NULL;
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_program_read_buf("bad.prog", (const unsigned char *)text, len, &p, &err);
    int good = rc == code && p == NULL && err.line == line && err.column == col && err.offset == offset &&
               strstr(err.msg, msg) && !strcmp(err.file, "bad.prog");
    ok(good, "%s", what);
    if (!good) diag("got %d at %ld:%ld (byte %lld) '%s'", rc, err.line, err.column, err.offset, err.msg);
    lam_program_free(p);
    return good;
}

#define BAD(text, code, line, col, msg, what) bad(text, sizeof text - 1, code, line, col, -1, msg, what)

static void malformed(void)
{
    BAD("contour 1\nloop 3\n0 0 1\n1 0 1\nendloop\n", LAM_ESYNTAX, 5, 1, "not a number",
        "SLS: a loop one vertex short reads 'endloop' as a coordinate");
    BAD("contour 1\nloop 3\n0 0 1\n1 0 1\n1 1 1\n", LAM_ESYNTAX, 6, 1, "'endloop'",
        "SLS: the file ends inside a loop");
    BAD("contour 1\nloop 2\n", LAM_EINVAL, 2, 6, "at least 3", "SLS: a loop of 2 points");
    BAD("contour 1\nloop 3\n0 0 1\n1 0\n", LAM_ESYNTAX, 4, 4, "3 coordinates", "SLS: a vertex with 2 coordinates");
    BAD("contour 1\nloop 3\n0 0 1\n1 0 1 7\n", LAM_ESYNTAX, 4, 7, "unexpected '7'", "SLS: a vertex with 4 numbers");
    BAD("contour 1\nloop 3\n0 0 1\n1 nan 1\n", LAM_EINVAL, 4, 3, "not a finite number", "SLS: nan");
    BAD("\n\nsolid x\n", LAM_ESYNTAX, 3, 1, "not a program lamina reads", "SLS: another file");
    {
        /* nothing of a file not recognised is quoted */
        static const char secret[] = "hunter2 is the password\n";
        lam_program *p = NULL;
        lam_error err;
        lam_error_clear(&err);
        int rc = lam_program_read_buf("secret.txt", (const unsigned char *)secret, sizeof secret - 1, &p, &err);
        ok(rc == LAM_ESYNTAX && !strstr(err.msg, "hunter") && !strstr(err.msg, "password"),
           "another file: its content is not quoted ('%s')", err.msg);
        static const char js[] = "{\"format\": \"hunter2\"}";
        rc = lam_program_read_buf("secret.json", (const unsigned char *)js, sizeof js - 1, &p, &err);
        ok(rc == LAM_EFORMAT && !strstr(err.msg, "hunter"), "another JSON: its format is not quoted ('%s')", err.msg);
    }
    BAD("$$HEADERSTART\n$$ASCII\n$$LAYERS/2\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$GEOMETRYEND\n",
        LAM_EINVAL, 3, 10, "says 2 layers but the file has 1", "CLI: $$LAYERS against the layers");
    BAD("$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$POLYLINE/1,2,4,0,0,1,0,1,1,0,0\n$$GEOMETRYEND\n",
        LAM_EINVAL, 5, 1, "open polyline", "CLI: direction 2 (an open line) is not a contour");
    BAD("$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$POLYLINE/1,1,4,0,0,1,0,1,1,0,0,5\n"
        "$$GEOMETRYEND\n",
        LAM_ESYNTAX, 5, 33, "more than 4 points", "CLI: a polyline with a coordinate too many");
    BAD("$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$POLYLINE/1,1,4,0,0,1,0,1,1,0,0\n", LAM_ESYNTAX, 4, 1,
        "before the first $$LAYER", "CLI: a polyline before any layer");
    BAD("$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$FOO/2\n", LAM_ESYNTAX, 5, 1,
        "unknown command '$$FOO'", "CLI: an unknown command");
    BAD("$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n", LAM_ESYNTAX, 5, 1, "before $$GEOMETRYEND",
        "CLI: no $$GEOMETRYEND");
    /* binary: a layer, then a polyline whose count runs past the end */
    static const unsigned char bin[] = "$$HEADERSTART\n$$BINARY\n$$HEADEREND"
                                       "\x7f\x00\x00\x00\x80\x3f"
                                       "\x82\x00\x01\x00\x00\x00\x01\x00\x00\x00\x09\x00\x00\x00";
    size_t head = strlen("$$HEADERSTART\n$$BINARY\n$$HEADEREND");
    bad((const char *)bin, sizeof bin - 1, LAM_ESYNTAX, 0, 0, (long long)head + 6, "does not fit",
        "CLI binary: a polyline of 9 points in 12 bytes, at its command's byte offset");
    static const unsigned char unk[] = "$$HEADERSTART\n$$BINARY\n$$HEADEREND\x7f\x00\x00\x00\x80\x3f\x99\x00";
    bad((const char *)unk, sizeof unk - 1, LAM_ESYNTAX, 0, 0, (long long)head + 6, "unknown CLI command 153",
        "CLI binary: an unknown command");
}

/* An SLS program sliced along x in the model frame: points (x y z) with x
 * the height; projected on the x frame's (u, v) = (y, z). Read in the wrong
 * frame, the contour's position is the error's. */
static void frames(void)
{
    static const char text[] = "contour 0.500\nloop 3\n0.500 0.000 0.000\n0.500 1.000 0.000\n0.500 0.000 1.000\n"
                               "endloop\nendcontour\n";
    lam_program *p = NULL;
    lam_error err;
    ok(lam_program_read_buf("x.sls", (const unsigned char *)text, sizeof text - 1, &p, &err) == LAM_OK && p,
       "an SLS program along x");
    if (!p) return;
    lam_frame f;
    lam_frame_axis('x', &f, NULL);
    lam_layer L;
    int rc = lam_program_layer_make(p, 0, &f, 0, "x.sls", &L, &err);
    ok(rc == LAM_OK && L.npoints == 3 && L.uv[2] == 1 && L.uv[3] == 0 && L.uv[4] == 0 && L.uv[5] == 1 &&
           L.contours[0].kind == LAM_SOLID,
       "model frame along x: (y, z) as (u, v), counter-clockwise seen from +x: a solid");
    if (rc == LAM_OK) lam_layer_clear(&L);
    lam_frame_axis('z', &f, NULL);
    rc = lam_program_layer_make(p, 0, &f, 0, "x.sls", &L, &err);
    ok(rc == LAM_EINVAL && err.line == 2 && err.column == 1 && strstr(err.msg, "from its plane"),
       "read along z instead: the loop at 2:1 is not in its plane ('%s')", err.msg);
    lam_program_free(p);
}


/* Read text[0..n) from a heap buffer of exactly n bytes, no NUL after it:
 * under AddressSanitizer (make SAN=1) any read past the end aborts the
 * test. Returns the reader's code; *p_out (may be NULL) gets the program. */
static int read_exact(const char *text, size_t n, lam_program **p_out, lam_error *err)
{
    unsigned char *buf = malloc(n ? n : 1);
    if (!buf) return LAM_ENOMEM;
    memcpy(buf, text, n);
    lam_program *p = NULL;
    lam_error_clear(err);
    int rc = lam_program_read_buf("exact.prog", n ? buf : buf + 1, n, &p, err);
    /* the layers made from it read only the program, not the buffer */
    lam_frame f;
    lam_frame_axis('z', &f, NULL);
    for (size_t i = 0; p && i < p->nlayers; i++) {
        lam_layer L;
        lam_error e2;
        if (lam_program_layer_make(p, i, &f, 0, "exact.prog", &L, &e2) == LAM_OK) lam_layer_clear(&L);
    }
    free(buf);
    if (p_out) *p_out = p;
    else lam_program_free(p);
    return rc;
}

/* Every prefix of a program, each in a buffer of its exact length: each
 * one is read or refused with a message naming the file, none reads past
 * its end, and the whole is read. */
static void prefixes(const char *text, size_t n, const char *what)
{
    size_t refused = 0, silent = 0;
    for (size_t k = 0; k < n; k++) {
        lam_error err;
        int rc = read_exact(text, k, NULL, &err);
        if (rc) {
            refused++;
            if (!err.msg[0] || strcmp(err.file, "exact.prog")) silent++;
        }
    }
    lam_error err;
    ok(read_exact(text, n, NULL, &err) == LAM_OK, "%s: read whole from an exact-length buffer", what);
    ok(silent == 0 && refused > 0, "%s: its %zu prefixes read within their length, %zu refused, each with a "
                                   "message (%zu without)", what, n, refused, silent);
}

static void bounded(void)
{
    /* found by the fuzzer: the exponent's digits run to the buffer's end
     * (the quantum read them with strtol, past it) */
    char num[64];
    int k = snprintf(num, sizeof num, "contour 0.E4111");
    for (int i = 0; i < 27; i++) num[k++] = '4';
    lam_error err;
    int rc = read_exact(num, (size_t)k, NULL, &err);
    ok(rc == LAM_ESYNTAX && err.line == 1 && strstr(err.msg, "'loop' or 'endcontour'"),
       "'contour 0.E4111' and 27 more 4s, no newline: a height (0, its exponent saturated), then the "
       "file ends where a loop was expected (%d '%s')", rc, err.msg);
    static const char *const ends[] = { "contour 1e", "contour 1e+", "contour 1.5E-", "contour -.", "contour 1e-99999999999999999999" };
    for (size_t i = 0; i < sizeof ends / sizeof *ends; i++) {
        rc = read_exact(ends[i], strlen(ends[i]), NULL, &err);
        ok(rc != LAM_OK && err.line == 1, "'%s' at the buffer's end: refused at line 1 (%d '%s')", ends[i], rc, err.msg);
    }
    /* a polyline of no points, cut by the end of the buffer: refused, no
     * pointer arithmetic on the points not yet allocated */
    static const char poly0[] = "$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$POLYLINE/1,1,0";
    rc = read_exact(poly0, sizeof poly0 - 1, NULL, &err);
    ok(rc == LAM_EINVAL && err.line == 5 && strstr(err.msg, "at least 4 points"),
       "$$POLYLINE/1,1,0 (no points) at the end: at least 4 points needed, at 5:1 (%d '%s')", rc, err.msg);
    /* a layer with no polyline before any contour: made into a layer with
     * none (the program's contour list still empty) */
    static const char empty[] = "$$HEADERSTART\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/1\n$$GEOMETRYEND";
    lam_program *p = NULL;
    rc = read_exact(empty, sizeof empty - 1, &p, &err);
    ok(rc == LAM_OK && p && p->nlayers == 1 && p->ncontours == 0 && p->layers[0].n == 0,
       "a CLI layer with no polyline: one layer of no contour");
    lam_program_free(p);
    static const char sls[] = "contour 0.25\nloop 4\n-1 -1 0.25\n1 -1 0.25\n1 1 0.25\n-1 1 0.25\nendloop\n"
                              "endcontour\n\nhatches core 1 0.25\n0 0 0.25 1 0 0.25\nendhatches\n"
                              "contour 0.75\nloop 3\n0 0 0.75\n1 0 0.75\n0 1.5e-0 0.75\nendloop\nendcontour";
    prefixes(sls, sizeof sls - 1, "SLS");
    static const char cli[] = "$$HEADERSTART\n$$ASCII\n$$UNITS/1\n$$LAYERS/2\n$$HEADEREND\n$$GEOMETRYSTART\n"
                              "$$LAYER/0.25\n$$POLYLINE/1,1,5,-1,-1,1,-1,1,1,-1,1,-1,-1\n$$HATCHES/1,1,0,0,1,0\n"
                              "$$LAYER/0.75\n$$POLYLINE/1,0,4,0,0,0,1.5E0,1,0,0,0\n$$GEOMETRYEND";
    prefixes(cli, sizeof cli - 1, "CLI ASCII");
    static const char json[] =
        "{\"format\": \"lamina-run\", \"version\": 1, \"job\": {\"frame\": \"model\", \"plane\": "
        "{\"origin\": [0, 0, 0], \"u\": [1, 0, 0], \"v\": [0, 1, 0], \"w\": [0, 0, 1]}},\n"
        "\"layers\": [{\"z\": 0.25, \"contours\": [{\"solid\": true, \"id\": 1, \"points\": "
        "[[-1, -1, 0.25], [1, -1, 0.25], [1, 1, 0.25e0], [-1, 1, 2.5E-1]]}]}], \"x\": \"\\u00e9\\n\"}";
    prefixes(json, sizeof json - 1, "JSON");
    static const unsigned char bin[] = "$$HEADERSTART\n$$BINARY\n$$LAYERS/1\n$$HEADEREND"
                                       "\x7f\x00\x00\x00\x80\x3e"
                                       "\x82\x00\x01\x00\x00\x00\x01\x00\x00\x00\x04\x00\x00\x00"
                                       "\x00\x00\x00\x00\x00\x00\x00\x00"
                                       "\x00\x00\x80\x3f\x00\x00\x00\x00"
                                       "\x00\x00\x00\x00\x00\x00\x80\x3f"
                                       "\x00\x00\x00\x00\x00\x00\x00\x00";
    prefixes((const char *)bin, sizeof bin - 1, "CLI binary");
}

int main(void)
{
    cube_hole("cube_hole.sls", LAM_PROGRAM_SLS, 5e-7);
    cube_hole("cube_hole_ascii.cli", LAM_PROGRAM_CLI_ASCII, 5e-6);
    /* float32 at the largest coordinate, 1: 2^-24 */
    cube_hole("cube_hole_binary.cli", LAM_PROGRAM_CLI_BINARY, 5.9604644775390625e-08);
    malformed();
    frames();
    bounded();
    return done_testing();
}
