/* Wavefront OBJ importer (SPEC 2.2).
 *
 * Read: `v x y z [w]` (w and anything after z, e.g. vertex colours, ignored)
 * and `f` with `v`, `v/vt`, `v//vn` and `v/vt/vn` references (the vt/vn
 * parts are checked to be integers and otherwise ignored). Indices are
 * 1-based; negative ones count back from the last vertex read (-1 is the
 * newest). A reference is resolved when its `f` line is read, so it may only
 * name vertices defined above it (forward references are out of range).
 * Indices count from the first vertex of this file even when the mesh
 * already held vertices.
 *
 * Each `f` line becomes one face record (name = the latest `g` or `o` name,
 * the words after the keyword joined by single spaces, NULL before any or
 * after a bare `g`; file = path; position of the `f` keyword) and is
 * triangulated with lam_mesh_add_polygon (triangles directly, convex polygons
 * fanned, others through GEOS); its errors are reported at the `f`. Faces of
 * one group share one copy of the name in the mesh's string table.
 *
 * Everything else (vt, vn, vp, s, usemtl, mtllib, l, p, cstype, unknown
 * keywords) is skipped; `#` starts a comment where a token could start;
 * blank lines are fine. A `\` at the end of a line joins the next line to
 * the statement. Lines end at '\n'; '\r' counts as blank, so CRLF works.
 * Keywords are case-sensitive, as in the format. A UTF-8 BOM is skipped.
 *
 * Positions are 1-based lines and 1-based byte columns (tab = 1 column); a
 * missing token is reported just after the last token of its line. The
 * buffer is exactly len bytes: nothing past it is read, no NUL is needed.
 * Numbers: lam_parse_number (lexnum.h), as for STL; nan/inf are recognised
 * so they are reported as "not a finite number".
 *
 * Status codes: LAM_ESYNTAX malformed numbers and references; LAM_EINVAL
 * index 0, index out of range, fewer than 3 vertices, non-finite
 * coordinates; LAM_EGEOM from the triangulation. Linear time. */
#include "import.h"
#include "buf.h"
#include "grow.h"
#include "lexnum.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- lexer: tokens of one logical line ---------------------------------- */

typedef struct obj_lex {
    const unsigned char *p, *end, *line_start;
    long line;
    const unsigned char *tok; /* the token last read, n bytes (0 at end of line) */
    size_t n;
    long tline, tcol;         /* its position (just after the previous token at end of line) */
    long after_line, after_col;
    const char *path;
    lam_error *err;
} obj_lex;

/* 1: blank inside a line (' ', \t, \v, \f, \r); 2: may end a token ('\n',
 * and '\\' when a line continuation follows). A table: the inner loop. */
static const unsigned char char_tab[256] = {
    [' '] = 1, ['\t'] = 1, ['\v'] = 1, ['\f'] = 1, ['\r'] = 1, ['\n'] = 2, ['\\'] = 2,
};

static int is_blank(unsigned char c) { return char_tab[c] == 1; }

/* Length of a line continuation at p ("\\\n" or "\\\r\n"), else 0. */
static size_t continuation(const unsigned char *p, const unsigned char *end)
{
    if (p >= end || *p != '\\') return 0;
    if (end - p >= 2 && p[1] == '\n') return 2;
    if (end - p >= 3 && p[1] == '\r' && p[2] == '\n') return 3;
    return 0;
}

/* Next token of the current statement; 0 at its end (p is then at the '\n'
 * or at the end of the buffer). */
static int obj_next(obj_lex *lx)
{
    const unsigned char *p = lx->p, *end = lx->end;
    for (;;) {
        while (p < end && is_blank(*p)) p++;
        size_t c = continuation(p, end);
        if (!c) break;
        p += c;
        lx->line++;
        lx->line_start = p;
    }
    if (p < end && *p == '#') {
        const unsigned char *nl = memchr(p, '\n', (size_t)(end - p));
        p = nl ? nl : end;
    }
    if (p >= end || *p == '\n') {
        lx->p = p;
        lx->tok = p;
        lx->n = 0;
        lx->tline = lx->after_line;
        lx->tcol = lx->after_col;
        return 0;
    }
    lx->tok = p;
    lx->tline = lx->line;
    lx->tcol = (long)(p - lx->line_start) + 1;
    while (p < end && (!char_tab[*p] || (*p == '\\' && !continuation(p, end)))) p++;
    lx->n = (size_t)(p - lx->tok);
    lx->p = p;
    lx->after_line = lx->line;
    lx->after_col = (long)(p - lx->line_start) + 1;
    return 1;
}

/* Skip the rest of the statement and its '\n'. */
static void obj_end_line(obj_lex *lx)
{
    while (obj_next(lx)) {}
    if (lx->p < lx->end) {
        lx->p++;
        lx->line++;
        lx->line_start = lx->p;
    }
}

static int is_tok(const obj_lex *lx, const char *kw)
{
    size_t k = strlen(kw);
    return lx->n == k && memcmp(lx->tok, kw, k) == 0;
}

static const char *found(const obj_lex *lx, char *buf, size_t size)
{
    if (!lx->n) {
        snprintf(buf, size, "end of line");
        return buf;
    }
    return lam_quote_bytes(buf, size, lx->tok, lx->n);
}

static int at_error(const obj_lex *lx, int code, long line, long col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static int at_error(const obj_lex *lx, int code, long line, long col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(lx->err, code, lx->path, line, col, -1, fmt, ap);
    va_end(ap);
    return rc;
}

/* Relocate an error from the mesh (which knows no position) to the `f`. */
static int mesh_error(const obj_lex *lx, int rc, long line, long col)
{
    if (!lx->err) return rc;
    char msg[sizeof lx->err->msg];
    snprintf(msg, sizeof msg, "%s", lx->err->msg);
    return lam_error_set(lx->err, rc, lx->path, line, col, "%s", msg);
}

/* ---- statements --------------------------------------------------------- */

typedef struct obj_state {
    size_t base;        /* mesh index of this file's vertex 1 */
    uint32_t *idx;      /* the current face's vertices */
    size_t cap;
    lam_buf name;       /* current g/o name, empty for none */
    uint32_t name_off;  /* its offset in the mesh's strings once stored */
} obj_state;

static int obj_vertex(obj_lex *lx, lam_mesh *m)
{
    double xyz[3];
    char q[96];
    for (int k = 0; k < 3; k++) {
        if (!obj_next(lx))
            return at_error(lx, LAM_ESYNTAX, lx->tline, lx->tcol,
                            "expected the vertex %c coordinate, found end of line", "xyz"[k]);
        int rc = lam_parse_number(lx->tok, lx->n, &xyz[k]);
        if (rc == LAM_ENOMEM)
            return at_error(lx, LAM_ENOMEM, lx->tline, lx->tcol, "out of memory reading a number");
        if (rc)
            return at_error(lx, LAM_ESYNTAX, lx->tline, lx->tcol,
                            "expected the vertex %c coordinate (a number), found %s",
                            "xyz"[k], found(lx, q, sizeof q));
        const char *why = lam_coord_problem(xyz[k]);
        if (why)
            return at_error(lx, LAM_EINVAL, lx->tline, lx->tcol, "vertex %c coordinate %s (%s)", "xyz"[k], why,
                            found(lx, q, sizeof q));
    }
    long line = lx->tline, col = lx->tcol;
    int rc = lam_mesh_add_vertex(m, xyz[0], xyz[1], xyz[2], NULL, lx->err);
    return rc ? mesh_error(lx, rc, line, col) : LAM_OK;
}

static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

/* [+-]digits at s[*i..n): 1 and the value (saturated) in *v, 0 if none. */
static int read_int(const unsigned char *s, size_t n, size_t *i, long long *v)
{
    size_t j = *i;
    int neg = 0;
    if (j < n && (s[j] == '+' || s[j] == '-')) neg = s[j++] == '-';
    if (j >= n || !is_digit(s[j])) return 0;
    long long x = 0;
    for (; j < n && is_digit(s[j]); j++)
        if (x < 1000000000000000LL) x = x * 10 + (s[j] - '0');
    *v = neg ? -x : x;
    *i = j;
    return 1;
}

static int obj_face(obj_lex *lx, lam_mesh *m, obj_state *st)
{
    long fline = lx->tline, fcol = lx->tcol;
    size_t nfile = m->nverts - st->base, nv = 0;
    char q[96];
    int rc;
    while (obj_next(lx)) {
        const unsigned char *s = lx->tok;
        size_t n = lx->n, i = 0;
        long long v, other;
        int okref = read_int(s, n, &i, &v);
        size_t vlen = i;
        for (int part = 0; okref && part < 2 && i < n; part++) { /* /vt, /vn (may be empty) */
            if (s[i] != '/') {
                okref = 0;
                break;
            }
            i++;
            if (i < n && s[i] != '/') okref = read_int(s, n, &i, &other);
        }
        if (!okref || i != n)
            return at_error(lx, LAM_ESYNTAX, lx->tline, lx->tcol,
                            "expected a vertex reference (v, v/vt, v//vn or v/vt/vn), found %s",
                            found(lx, q, sizeof q));
        if (v == 0)
            return at_error(lx, LAM_EINVAL, lx->tline, lx->tcol,
                            "vertex index 0 is invalid (OBJ indices start at 1)");
        if ((v > 0 && (unsigned long long)v > nfile) || (v < 0 && (unsigned long long)-v > nfile))
            return at_error(lx, LAM_EINVAL, lx->tline, lx->tcol,
                            "vertex index %.*s out of range (%zu %s defined so far)",
                            (int)(vlen < 40 ? vlen : 40), (const char *)s, nfile,
                            nfile == 1 ? "vertex" : "vertices");
        size_t one_based = v > 0 ? (size_t)v : nfile + 1 - (size_t)-v;
        if (nv == st->cap) {
            uint32_t *ni = lam_grow(st->idx, &st->cap, nv + 1, sizeof *ni, 16);
            if (!ni) return at_error(lx, LAM_ENOMEM, fline, fcol, "out of memory reading a face");
            st->idx = ni;
        }
        st->idx[nv++] = (uint32_t)(st->base + one_based - 1);
    }
    if (nv < 3)
        return at_error(lx, LAM_EINVAL, fline, fcol, "face has %zu %s, at least 3 are needed", nv,
                        nv == 1 ? "vertex" : "vertices");

    uint32_t face;
    const char *name = st->name.data && st->name.data[0] ? st->name.data : NULL;
    if (name && st->name_off != LAM_NO_NAME) {
        rc = lam_mesh_add_face(m, NULL, lx->path, fline, fcol, &face, lx->err);
        if (!rc) m->faces[face].name = st->name_off;
    } else {
        rc = lam_mesh_add_face(m, name, lx->path, fline, fcol, &face, lx->err);
        if (!rc && name) st->name_off = m->faces[face].name;
    }
    if (!rc) rc = lam_mesh_add_polygon(m, st->idx, &nv, 1, face, lx->err);
    return rc ? mesh_error(lx, rc, fline, fcol) : LAM_OK;
}

/* `g` / `o`: the words after the keyword, joined by single spaces. */
static int obj_name(obj_lex *lx, obj_state *st)
{
    long line = lx->tline, col = lx->tcol;
    st->name_off = LAM_NO_NAME;
    lam_buf_clear(&st->name);
    while (obj_next(lx)) {
        if ((st->name.len && lam_buf_append(&st->name, " ", 1)) || lam_buf_append(&st->name, lx->tok, lx->n))
            return at_error(lx, LAM_ENOMEM, line, col, "out of memory reading a name");
    }
    return LAM_OK;
}

int lam_import_obj_buf(const char *path, const char *data, size_t len,
                       lam_mesh *mesh, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    static const unsigned char empty[1];
    const unsigned char *d = data ? (const unsigned char *)data : empty;
    if (!data) len = 0;
    size_t bom = len >= 3 && d[0] == 0xef && d[1] == 0xbb && d[2] == 0xbf ? 3 : 0;
    obj_lex lx = {
        .p = d + bom, .end = d + len, .line_start = d + bom, .line = 1,
        .tok = d + bom, .n = 0, .tline = 1, .tcol = 1, .after_line = 1, .after_col = 1,
        .path = path, .err = err,
    };
    obj_state st = { .base = mesh->nverts, .name_off = LAM_NO_NAME };
    int rc = LAM_OK;
    while (!rc && lx.p < lx.end) {
        if (obj_next(&lx)) {
            if (is_tok(&lx, "v"))
                rc = obj_vertex(&lx, mesh);
            else if (is_tok(&lx, "f"))
                rc = obj_face(&lx, mesh, &st);
            else if (is_tok(&lx, "g") || is_tok(&lx, "o"))
                rc = obj_name(&lx, &st);
        }
        if (!rc) obj_end_line(&lx);
    }
    free(st.idx);
    lam_buf_free(&st.name);
    return rc;
}
