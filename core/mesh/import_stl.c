/* STL importer: binary and ASCII, chosen by content (SPEC 2.2).
 *
 * Which format:
 *   - binary iff len >= 84 and 84 + 50 * count == len (count = uint32 LE at
 *     byte 80), even when the 80-byte header begins with "solid" (many
 *     exporters write that);
 *   - otherwise ASCII when the text, after leading whitespace (and a UTF-8
 *     BOM), begins with "solid". If that ASCII parse fails on a file of 84 or
 *     more bytes that contains a NUL byte, the file is a binary STL whose
 *     header says "solid" but whose count disagrees with its size (a
 *     truncated export): the count error below is reported instead of a
 *     confusing syntax error in the middle of binary data;
 *   - otherwise, 84 bytes or more: a binary STL whose count disagrees with
 *     the size: error at byte 80, "binary STL declares N triangles (needs X
 *     bytes) but the file has Y bytes" (covers truncated files);
 *   - fewer than 84 bytes: "file too short for a binary STL (N bytes)".
 *
 * Binary: no face records (tri_face stays NULL: triangle i is "facet i+1"
 * in messages), so lam_mesh_add_face is never called for a binary file and a
 * binary STL cannot be appended to a mesh that already has face records.
 * Room is reserved once for the triangles; vertices are welded exactly as
 * they are read (lam_mesh_add_vertex_welded), so a closed mesh stores about
 * half as many vertices as triangles instead of three per facet. Values are read little-endian byte by byte (no
 * alignment or host byte order assumption). A NaN/inf vertex coordinate is an
 * error at that float's byte offset; normals and the attribute word are
 * ignored, so a NaN normal (common for degenerate facets) is accepted.
 *
 * ASCII: the buffer is exactly len bytes; nothing past it is read and no NUL
 * terminator is needed. Tokens are runs of non-whitespace, keywords are
 * case-insensitive. `solid`'s name is the rest of its line, `endsolid`'s is
 * ignored; several solids may follow each other. A file that ends right after
 * a complete `endfacet` without `endsolid` is accepted. One face record per
 * facet: name NULL, file = path, position of the `facet` keyword. Positions
 * are 1-based lines (counted at '\n', so CRLF files work) and 1-based byte
 * columns (a tab is one column); an error at end of file points just past the
 * last byte.
 *
 * Numbers: lam_parse_number (lexnum.h), exact and locale-independent. It
 * reads nan, inf, infinity and MSVC's 1.#QNAN / -1.#IND / 1.#INF as
 * non-finite values, so a coordinate holding one is reported as "not a finite
 * number" rather than as malformed (a normal may hold anything numeric).
 *
 * Status codes: LAM_ESYNTAX for malformed text and a size that disagrees with
 * the count, LAM_EINVAL for non-finite coordinates, LAM_EFORMAT for a file
 * that is neither (too short for binary and not "solid"). Linear time. */
#include "import.h"
#include "lexnum.h"
#include "stl_weld.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- binary ------------------------------------------------------------- */

static int stl_binary(const char *path, const unsigned char *data, uint32_t count,
                      lam_mesh *m, unsigned threads, lam_error *err)
{
    if (m->nfaces || m->tri_face)
        return lam_error_set(err, LAM_EINVAL, path, 0, 0,
                             "a binary STL cannot be added to a mesh that has face records");
    if ((uint64_t)count * 3 >= UINT32_MAX - 1 - (uint64_t)m->nverts)
        return lam_error_at_offset(err, LAM_ENOMEM, path, 80,
                                   "binary STL declares %lu triangles: too many for 32-bit vertex indices",
                                   (unsigned long)count);
    if (count == 0) return LAM_OK;
    lam_team *team = NULL;
    lam_error ignored; /* no thread started: the calling thread reads it, the same mesh */
    if (threads > 1 && count >= LAM_STL_TEAM_MIN && m->nverts == 0 && m->ntris == 0 &&
        lam_team_new(threads, &team, &ignored) == LAM_OK) {
        int trc = lam_stl_binary_team(path, data, count, m, team, err);
        lam_team_free(team);
        return trc;
    }
    /* a closed mesh has about half as many vertices as triangles */
    int rc = lam_mesh_reserve(m, count / 2 + 16, count, err);
    if (rc) return lam_error_set(err, rc, path, 0, 0, "out of memory for %lu triangles", (unsigned long)count);

    int fresh = m->nverts == 0 && m->ntris == 0;
    lam_welder wd;
    lam_welder_init(&wd);
    if ((rc = lam_welder_reserve(&wd, m, count / 2 + 16, err))) return rc;
    uint32_t *t = m->tris + 3 * m->ntris;
    const unsigned char *p = data + 84 + 12; /* first vertex of facet 1 */
    for (uint32_t i = 0; i < count; i++, p += 50) {
        if (i + 4 < count) {
            /* the welder's table is big and read at random: ask for the
             * slots of a facet a few records ahead */
            const unsigned char *q = p + 4 * 50;
            for (int k = 0; k < 3; k++) {
                float c[3];
                for (int j = 0; j < 3; j++) {
                    uint32_t u = lam_rd_u32(q + 12 * k + 4 * j);
                    memcpy(&c[j], &u, sizeof c[j]);
                }
                lam_welder_prefetch(&wd, c[0], c[1], c[2]);
            }
        }
        double xyz[9];
        int bad = lam_stl_facet(p, xyz);
        if (bad >= 0) {
            lam_welder_free(&wd);
            return lam_stl_nonfinite(path, data, (size_t)(p + 4 * bad - data), err);
        }
        for (int k = 0; k < 3; k++) {
            if ((rc = lam_mesh_add_vertex_welded(m, &wd, xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2], &t[k], err))) {
                lam_welder_free(&wd);
                return lam_error_set(err, rc, path, 0, 0, "out of memory for %lu triangles", (unsigned long)count);
            }
        }
        t += 3;
        m->ntris++;
    }
    lam_welder_free(&wd);
    /* every vertex came through the welder and is used: unless the mesh
     * held something before, welding again would change nothing */
    m->welded = fresh;
    return LAM_OK;
}

static int count_error(const char *path, size_t len, uint32_t count, lam_error *err)
{
    unsigned long long need = 84 + 50ull * count;
    return lam_error_at_offset(err, LAM_ESYNTAX, path, 80,
                               "binary STL declares %lu triangles (needs %llu bytes) but the file has %llu bytes",
                               (unsigned long)count, need, (unsigned long long)len);
}

/* ---- ASCII -------------------------------------------------------------- */

typedef struct stl_lex {
    const unsigned char *p, *end, *line_start;
    long line;
    const unsigned char *tok; /* the token last read, n bytes (0 at end) */
    size_t n;
    long tline, tcol;
    const char *path;
    lam_error *err;
    lam_welder *weld;
} stl_lex;

/* Whitespace: ' ', \t, \n, \v, \f, \r (a table: the lexer's inner loop). */
static const unsigned char space_tab[256] = {
    [' '] = 1, ['\t'] = 1, ['\n'] = 1, ['\v'] = 1, ['\f'] = 1, ['\r'] = 1,
};

static int is_space(unsigned char c) { return space_tab[c]; }

/* Read the next token; 0 at end of input (position then at the end). */
static int lex_next(stl_lex *lx)
{
    const unsigned char *p = lx->p, *end = lx->end;
    while (p < end && is_space(*p)) {
        if (*p == '\n') {
            lx->line++;
            lx->line_start = p + 1;
        }
        p++;
    }
    lx->tok = p;
    lx->tline = lx->line;
    lx->tcol = (long)(p - lx->line_start) + 1;
    while (p < end && !is_space(*p)) p++;
    lx->n = (size_t)(p - lx->tok);
    lx->p = p;
    return lx->n > 0;
}

static void lex_skip_line(stl_lex *lx)
{
    const unsigned char *nl = memchr(lx->p, '\n', (size_t)(lx->end - lx->p));
    lx->p = nl ? nl : lx->end;
}

static int is_kw(const stl_lex *lx, const char *kw) { return lam_word_eq_nocase(lx->tok, lx->n, kw); }

/* "'token'" or "end of file", for messages. */
static const char *found(const stl_lex *lx, char *buf, size_t size)
{
    if (!lx->n) {
        snprintf(buf, size, "end of file");
        return buf;
    }
    return lam_quote_bytes(buf, size, lx->tok, lx->n);
}

static int lex_error(const stl_lex *lx, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* An error at the token last read. */
static int lex_error(const stl_lex *lx, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(lx->err, code, lx->path, lx->tline, lx->tcol, -1, fmt, ap);
    va_end(ap);
    return rc;
}

static int expect_kw(stl_lex *lx, const char *kw, const char *what)
{
    char q[96];
    if (lex_next(lx) && is_kw(lx, kw)) return LAM_OK;
    return lex_error(lx, LAM_ESYNTAX, "expected '%s'%s, found %s", kw, what, found(lx, q, sizeof q));
}

/* Three numbers; `finite` demands finite values (vertex coordinates). */
static int read_xyz(stl_lex *lx, double out[3], int finite, const char *what)
{
    char q[96];
    for (int k = 0; k < 3; k++) {
        if (!lex_next(lx))
            return lex_error(lx, LAM_ESYNTAX, "expected the %s %c coordinate, found end of file",
                             what, "xyz"[k]);
        int rc = lam_parse_number(lx->tok, lx->n, &out[k]);
        if (rc == LAM_ENOMEM) return lex_error(lx, LAM_ENOMEM, "out of memory reading a number");
        if (rc)
            return lex_error(lx, LAM_ESYNTAX, "expected the %s %c coordinate (a number), found %s",
                             what, "xyz"[k], found(lx, q, sizeof q));
        const char *why = finite ? lam_coord_problem(out[k]) : NULL;
        if (why) return lex_error(lx, LAM_EINVAL, "%s %c coordinate %s (%s)", what, "xyz"[k], why, found(lx, q, sizeof q));
    }
    return LAM_OK;
}

/* Relocate an error from the mesh (which knows no position) to the facet. */
static int mesh_error(const stl_lex *lx, int rc, long line, long col)
{
    if (!lx->err) return rc;
    char msg[sizeof lx->err->msg];
    snprintf(msg, sizeof msg, "%s", lx->err->msg);
    return lam_error_set(lx->err, rc, lx->path, line, col, "%s", msg);
}

/* After `facet`: normal, loop of exactly three vertices, endfacet. */
static int stl_facet(stl_lex *lx, lam_mesh *m)
{
    long fline = lx->tline, fcol = lx->tcol;
    char q[96];
    double normal[3], v[9];
    int rc;
    if ((rc = expect_kw(lx, "normal", " after 'facet'"))) return rc;
    if ((rc = read_xyz(lx, normal, 0, "normal"))) return rc;
    if ((rc = expect_kw(lx, "outer", " (of 'outer loop')"))) return rc;
    if ((rc = expect_kw(lx, "loop", " after 'outer'"))) return rc;
    int nv = 0;
    for (;;) {
        if (!lex_next(lx))
            return lex_error(lx, LAM_ESYNTAX, "expected %s, found end of file",
                             nv < 3 ? "'vertex' or 'endloop'" : "'endloop'");
        if (is_kw(lx, "vertex")) {
            if (nv == 3) return lex_error(lx, LAM_ESYNTAX, "facet has more than 3 vertices");
            if ((rc = read_xyz(lx, v + 3 * nv, 1, "vertex"))) return rc;
            nv++;
        } else if (is_kw(lx, "endloop")) {
            if (nv != 3)
                return lex_error(lx, LAM_ESYNTAX, "facet has %d %s, expected 3", nv,
                                 nv == 1 ? "vertex" : "vertices");
            break;
        } else {
            return lex_error(lx, LAM_ESYNTAX, "expected %s, found %s",
                             nv < 3 ? "'vertex' or 'endloop'" : "'endloop'", found(lx, q, sizeof q));
        }
    }
    if ((rc = expect_kw(lx, "endfacet", " after 'endloop'"))) return rc;

    uint32_t face, a, b, c;
    if ((rc = lam_mesh_add_face(m, NULL, lx->path, fline, fcol, &face, lx->err)) ||
        (rc = lam_mesh_add_vertex_welded(m, lx->weld, v[0], v[1], v[2], &a, lx->err)) ||
        (rc = lam_mesh_add_vertex_welded(m, lx->weld, v[3], v[4], v[5], &b, lx->err)) ||
        (rc = lam_mesh_add_vertex_welded(m, lx->weld, v[6], v[7], v[8], &c, lx->err)) ||
        (rc = lam_mesh_add_tri(m, a, b, c, face, lx->err)))
        return mesh_error(lx, rc, fline, fcol);
    return LAM_OK;
}

static size_t skip_bom(const unsigned char *data, size_t len)
{
    return len >= 3 && data[0] == 0xef && data[1] == 0xbb && data[2] == 0xbf ? 3 : 0;
}

static int stl_ascii_body(const char *path, const unsigned char *data, size_t len,
                          lam_mesh *m, lam_welder *wd, lam_error *err)
{
    size_t bom = skip_bom(data, len);
    stl_lex lx = {
        .p = data + bom, .end = data + len, .line_start = data + bom, .line = 1,
        .tok = data + bom, .n = 0, .tline = 1, .tcol = 1, .path = path, .err = err, .weld = wd,
    };
    char q[96];
    /* A facet takes 150-300 bytes of text: reserve for the short end. */
    int rc = lam_mesh_reserve(m, len / 300, len / 150, err);
    if (rc) return rc;
    int solids = 0;
    for (;;) {
        if (!lex_next(&lx)) {
            if (solids) return LAM_OK;
            return lex_error(&lx, LAM_ESYNTAX, "expected 'solid', found end of file");
        }
        if (!is_kw(&lx, "solid"))
            return lex_error(&lx, LAM_ESYNTAX, "expected %s, found %s",
                             solids ? "'solid' or end of file" : "'solid'", found(&lx, q, sizeof q));
        lex_skip_line(&lx); /* the solid's name */
        solids++;
        size_t facets = 0;
        for (;;) {
            if (!lex_next(&lx)) {
                if (facets) return LAM_OK; /* lenient: EOF after endfacet, no endsolid */
                return lex_error(&lx, LAM_ESYNTAX, "expected 'facet' or 'endsolid', found end of file");
            }
            if (is_kw(&lx, "endsolid")) {
                lex_skip_line(&lx);
                break;
            }
            if (!is_kw(&lx, "facet"))
                return lex_error(&lx, LAM_ESYNTAX, "expected 'facet' or 'endsolid', found %s",
                                 found(&lx, q, sizeof q));
            if ((rc = stl_facet(&lx, m))) return rc;
            facets++;
        }
    }
}

/* Leading whitespace (and a UTF-8 BOM), then "solid", any case. */
static int looks_ascii(const unsigned char *data, size_t len)
{
    size_t i = skip_bom(data, len);
    while (i < len && is_space(data[i])) i++;
    return len - i >= 5 && lam_word_eq_nocase(data + i, 5, "solid");
}

/* ---- entry -------------------------------------------------------------- */

static int stl_ascii(const char *path, const unsigned char *data, size_t len,
                     lam_mesh *m, lam_error *err)
{
    lam_welder wd;
    lam_welder_init(&wd);
    int rc = stl_ascii_body(path, data, len, m, &wd, err);
    lam_welder_free(&wd);
    return rc;
}

int lam_import_stl_buf(const char *path, const unsigned char *data, size_t len,
                       lam_mesh *mesh, int *binary, lam_error *err)
{
    return lam_import_stl_threads(path, data, len, mesh, binary, 1, err);
}

int lam_import_stl_threads(const char *path, const unsigned char *data, size_t len, lam_mesh *mesh, int *binary,
                           unsigned threads, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    if (binary) *binary = 0;
    if (!data) len = 0;
    uint32_t count = len >= 84 ? lam_rd_u32(data + 80) : 0;
    if (len >= 84 && 84 + 50ull * count == (unsigned long long)len) {
        if (binary) *binary = 1;
        return stl_binary(path, data, count, mesh, threads, err);
    }
    if (len && looks_ascii(data, len)) {
        int rc = stl_ascii(path, data, len, mesh, err);
        if (rc && rc != LAM_ENOMEM && len >= 84 && memchr(data, 0, len)) {
            if (binary) *binary = 1;
            return count_error(path, len, count, err);
        }
        return rc;
    }
    if (len >= 84) {
        if (binary) *binary = 1;
        return count_error(path, len, count, err);
    }
    return lam_error_set(err, LAM_EFORMAT, path, 0, 0, "file too short for a binary STL (%zu bytes)%s",
                         len, len ? " and not an ASCII STL (no leading 'solid')" : "");
}
