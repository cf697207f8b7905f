/* Unigrafix (.ug) importer, SPEC 2.1.
 *
 * Design
 * - Two phases. Every source file is lexed and compiled once into a small
 *   intermediate form: per scope (a file's top level or a `def` body) its
 *   vertices and an ordered list of items (faces, wires, instances,
 *   includes) whose vertex and definition names are already resolved to
 *   indices. Then the root file's top level is expanded into the mesh;
 *   instances and includes recurse with the composed transform. So every
 *   syntax and name error is reported before any geometry is emitted, and a
 *   definition instanced a thousand times is parsed once.
 * - Names must be defined before they are used: vertices before a face or
 *   wire names them, definitions before an instance names them (the thesis:
 *   "a previously defined object"). Vertex names belong to their def or
 *   file and are not seen from nested or enclosing defs; definition names
 *   are looked up from the innermost scope outward. Lookups are hash tables.
 * - A definition is registered when its `def` statement is read, so an
 *   instance of it inside its own body (directly or through a nested def)
 *   is reported as self-instantiation. Because definitions precede their
 *   instances and included files compile on their own, the instance graph
 *   has no cycles.
 * - include NAME: resolved against the including file's directory, trying
 *   NAME, then NAME.ug (a surrounding pair of double quotes is dropped).
 *   Files are identified by device and inode, so an include cycle is found
 *   however the path is spelled, and a file included several times is
 *   compiled once. The included file's top-level definitions (also those it
 *   got from its own includes) become visible in the including scope; a
 *   clash with a different definition of the same name is an error.
 * - Limits, so that no file can exhaust the stack or memory: defs nested
 *   64 deep, includes nested 64 deep, chains of instances/includes 64 deep,
 *   and one expansion of any scope emits at most 2^26 vertex references
 *   (checked while compiling, before anything is emitted).
 * - Emission: a vertex is emitted when a face or wire first names it, once
 *   per expansion of its scope (no welding here). A transform whose 3x3
 *   part has a negative determinant reverses every ring of the faces it
 *   emits. Repeated consecutive vertices in a ring (and a closing repeat of
 *   the first) are dropped; a face ring with fewer than 3 distinct vertices
 *   or a wire with fewer than 2 is an error. A face's id becomes its face
 *   record's name (instanced faces keep the def's id and position); colours,
 *   instance ids and the c, c_rgb, l and cam statements are read and
 *   ignored; an optional vertex normal is read and ignored.
 * - Lexing: tokens are `(`, `)`, `;` and words (any run of other non-space
 *   bytes except braces). Comments start only where a token could start:
 *   brace comments nest (a slash-star inside them means nothing), slash-star
 *   comments do not nest. Columns count bytes from 1. The importer keeps a
 *   private copy of the text and NUL-terminates each word in place, so
 *   names go to the mesh and to the number reader without copying. Numbers
 *   are what lexnum.h reads when it consumes the whole word (decimal, no
 *   locale), or C's hexadecimal spellings.
 * - Errors point at the offending token; an unterminated comment at its
 *   opening; a definition left open at end of file at its `def`; an include
 *   that cannot be read, or closes a cycle, at its `include`; a vertex that
 *   a transform sends to infinity at the vertex's name.
 */
#include "import.h"
#include "grow.h"
#include "lexnum.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define UG_MAX_DEF_DEPTH 64
#define UG_MAX_INCLUDE_DEPTH 64
#define UG_MAX_INSTANCE_DEPTH 64
#define UG_MAX_EXPANSION ((size_t)1 << 26)
#define UG_NONE UINT32_MAX

/* ------------------------------------------------------------------ */
/* Growable arrays and a string -> index hash map                      */

/* Make room for `need` elements of `elem` bytes in the array *arrp points
 * to (any object pointer type), doubling its capacity. 0 or -1 (no memory). */
static int reserve_(void *arrp, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    void *p;
    memcpy(&p, arrp, sizeof p);
    void *q = lam_grow(p, cap, need, elem, 8); /* grow.h: the one doubling rule */
    if (!q) return -1;
    memcpy(arrp, &q, sizeof q);
    return 0;
}
#define RESERVE(arr, cap, need) reserve_(&(arr), &(cap), (need), sizeof *(arr))

typedef struct ug_slot {
    const char *key;    /* NULL: empty slot */
    size_t len;
    uint32_t hash, val;
} ug_slot;

typedef struct ug_map {
    ug_slot *slots;
    size_t cap, n;      /* cap is 0 or a power of two */
} ug_map;

static uint32_t hash_str(const char *s, size_t n)
{
    uint32_t h = 2166136261u;   /* FNV-1a */
    for (size_t i = 0; i < n; i++) {
        h ^= (unsigned char)s[i];
        h *= 16777619u;
    }
    return h;
}

/* The slot holding key, or the empty slot where it would go. */
static size_t map_slot(const ug_map *m, const char *key, size_t len, uint32_t h)
{
    size_t mask = m->cap - 1, i = h & mask;
    for (;;) {
        const ug_slot *s = &m->slots[i];
        if (!s->key || (s->hash == h && s->len == len && memcmp(s->key, key, len) == 0))
            return i;
        i = (i + 1) & mask;
    }
}

static int map_get(const ug_map *m, const char *key, size_t len, uint32_t *val)
{
    if (!m->cap) return 0;
    const ug_slot *s = &m->slots[map_slot(m, key, len, hash_str(key, len))];
    if (!s->key) return 0;
    *val = s->val;
    return 1;
}

/* Insert a key known to be absent. 0 or -1 (no memory). */
static int map_put(ug_map *m, const char *key, size_t len, uint32_t val)
{
    if ((m->n + 1) * 4 > m->cap * 3) {
        size_t ncap = m->cap ? m->cap * 2 : 16;
        ug_slot *ns = calloc(ncap, sizeof *ns);
        if (!ns || ncap < m->cap) {
            free(ns);
            return -1;
        }
        ug_map bigger = { ns, ncap, m->n };
        for (size_t i = 0; i < m->cap; i++)
            if (m->slots[i].key)
                ns[map_slot(&bigger, m->slots[i].key, m->slots[i].len, m->slots[i].hash)] = m->slots[i];
        free(m->slots);
        *m = bigger;
    }
    uint32_t h = hash_str(key, len);
    ug_slot *s = &m->slots[map_slot(m, key, len, h)];
    s->key = key;
    s->len = len;
    s->hash = h;
    s->val = val;
    m->n++;
    return 0;
}

/* ------------------------------------------------------------------ */
/* Compiled form                                                       */

typedef struct ug_vertex {
    double p[3];
    const char *name;
    long line, col;      /* of the name, for messages */
} ug_vertex;

enum { IT_FACE, IT_WIRE, IT_INST, IT_INCL };

typedef struct ug_item {
    int kind;
    const char *name;    /* face/wire/instance id; NULL when anonymous */
    long line, col;      /* the statement's keyword */
    size_t first, count; /* FACE, WIRE: vertex refs refs[first .. first+count) */
    size_t ring, nrings; /* FACE: ring lengths rings[ring .. ring+nrings) */
    uint32_t target;     /* INST, INCL: the scope expanded */
    uint32_t mat;        /* INST, INCL: its transform, index into mats */
} ug_item;

struct ug_file;

typedef struct ug_scope {
    struct ug_file *file;
    const char *name;    /* definition name; NULL for a file's top level */
    long line, col;      /* the `def` keyword */
    uint32_t parent;     /* enclosing scope of the same file, UG_NONE at top */
    int open;            /* body still being read */
    int height;          /* longest chain of instances/includes below */
    size_t cost;         /* vertex references one expansion emits, plus items */
    ug_vertex *verts;
    size_t nverts, cap_verts;
    uint32_t *vidx, *vgen; /* per vertex: mesh index / stamp (see gen) */
    size_t cap_vmark;
    uint32_t gen;        /* vgen[v] == gen: vertex v is marked in the current
                            ring (compiling) or emitted as vidx[v] (expanding) */
    ug_map vmap, dmap;   /* vertex name -> index; definition name -> scope */
    ug_item *items;
    size_t nitems, cap_items;
    uint32_t *refs;
    size_t nrefs, cap_refs;
    size_t *rings;
    size_t nrings, cap_rings;
} ug_scope;

typedef struct ug_file {
    struct ug_file *next;
    char *path;          /* for messages and face records; NULL: anonymous */
    char *buf;           /* private NUL-terminated copy of the text */
    int has_id;          /* dev/ino valid */
    dev_t dev;
    ino_t ino;
    int compiling;
    uint32_t top;        /* its top-level scope */
} ug_file;

typedef struct ug_import {
    lam_mesh *mesh;
    lam_error *err;
    ug_file *files;                         /* every file read */
    ug_file *stack[UG_MAX_INCLUDE_DEPTH + 1]; /* files being compiled */
    int depth;
    ug_scope **scopes;
    size_t nscopes, cap_scopes;
    double (*mats)[16];
    size_t nmats, cap_mats;
    uint32_t *idx;                          /* emission scratch */
    size_t cap_idx;
} ug_import;

static const char *file_name(const ug_file *f)
{
    return f && f->path ? f->path : "<buffer>";
}

static int verror(ug_import *imp, int code, const ug_file *f, long line, long col,
                  const char *fmt, va_list ap)
{
    return lam_error_vset(imp->err, code, f ? f->path : NULL, line, col, -1, fmt, ap);
}

static int error_at(ug_import *imp, int code, const ug_file *f, long line, long col,
                    const char *fmt, ...) __attribute__((format(printf, 6, 7)));
static int error_at(ug_import *imp, int code, const ug_file *f, long line, long col,
                    const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = verror(imp, code, f, line, col, fmt, ap);
    va_end(ap);
    return rc;
}

static int nomem(ug_import *imp)
{
    return lam_error_nomem(imp->err, "reading Unigrafix");
}

static void mark_next(ug_scope *s)
{
    /* A wrapped stamp would make stale marks current again. */
    if (s->gen == UINT32_MAX) {
        if (s->vgen) memset(s->vgen, 0, s->cap_vmark * sizeof *s->vgen);
        s->gen = 0;
    }
    s->gen++;
}

static int new_scope(ug_import *imp, ug_file *f, const char *name, long line,
                     long col, uint32_t parent, uint32_t *out)
{
    if (imp->nscopes >= UG_NONE || RESERVE(imp->scopes, imp->cap_scopes, imp->nscopes + 1))
        return nomem(imp);
    ug_scope *s = calloc(1, sizeof *s);
    if (!s) return nomem(imp);
    s->file = f;
    s->name = name;
    s->line = line;
    s->col = col;
    s->parent = parent;
    s->open = 1;
    *out = (uint32_t)imp->nscopes;
    imp->scopes[imp->nscopes++] = s;
    return LAM_OK;
}

static void free_scope(ug_scope *s)
{
    free(s->verts);
    free(s->vidx);
    free(s->vgen);
    free(s->vmap.slots);
    free(s->dmap.slots);
    free(s->items);
    free(s->refs);
    free(s->rings);
    free(s);
}

/* ------------------------------------------------------------------ */
/* 4x4 transforms (row-major, acting on column vectors: p' = M p)      */

static void mat_identity(double m[16])
{
    for (int i = 0; i < 16; i++) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
}

/* out = a * b; out may alias a or b. */
static void mat_mul(double out[16], const double a[16], const double b[16])
{
    double r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] +
                           a[4 * i + 2] * b[8 + j] + a[4 * i + 3] * b[12 + j];
    memcpy(out, r, sizeof r);
}

static double det3(const double m[16])
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) -
           m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* sin and cos of an angle in degrees, exact at multiples of 90 so that
 * quarter turns map grid points to grid points (tests compare exactly). */
static void sincos_deg(double deg, double *s, double *c)
{
    static const double PI = 3.14159265358979323846;
    double r = fmod(deg, 360.0);
    if (r < 0) r += 360.0;
    if (r == 0) { *s = 0; *c = 1; }
    else if (r == 90) { *s = 1; *c = 0; }
    else if (r == 180) { *s = 0; *c = -1; }
    else if (r == 270) { *s = -1; *c = 0; }
    else { *s = sin(r * PI / 180.0); *c = cos(r * PI / 180.0); }
}

typedef struct ug_flag {
    const char *name;
    int nargs;
} ug_flag;

static const ug_flag ug_flags[] = {
    { "-tx", 1 }, { "-ty", 1 }, { "-tz", 1 }, { "-ta", 3 },
    { "-sx", 1 }, { "-sy", 1 }, { "-sz", 1 }, { "-sa", 1 },
    { "-rx", 1 }, { "-ry", 1 }, { "-rz", 1 },
    { "-mx", 0 }, { "-my", 0 }, { "-mz", 0 },
    { "-M3", 9 }, { "-M4", 16 },
};

static const ug_flag *find_flag(const char *w)
{
    for (size_t i = 0; i < sizeof ug_flags / sizeof ug_flags[0]; i++)
        if (strcmp(ug_flags[i].name, w) == 0) return &ug_flags[i];
    return NULL;
}

/* The matrix of one transform flag with its arguments a[]. */
static void flag_matrix(const ug_flag *f, const double *a, double t[16])
{
    mat_identity(t);
    char op = f->name[1], ax = f->name[2];
    int k = ax == 'x' ? 0 : ax == 'y' ? 1 : ax == 'z' ? 2 : -1; /* -1: a, 3, 4 */
    if (op == 't') {
        if (k >= 0) t[4 * k + 3] = a[0];
        else { t[3] = a[0]; t[7] = a[1]; t[11] = a[2]; }
    } else if (op == 's') {
        if (k >= 0) t[5 * k] = a[0];
        else t[0] = t[5] = t[10] = a[0];
    } else if (op == 'm') {
        t[5 * k] = -1.0;
    } else if (op == 'r') {
        /* Rotation about axis k by the right-hand rule: the other two axes
         * (i, j) in cyclic order turn i -> j. */
        int i = (k + 1) % 3, j = (k + 2) % 3;
        double s, c;
        sincos_deg(a[0], &s, &c);
        t[5 * i] = c;
        t[4 * i + j] = -s;
        t[4 * j + i] = s;
        t[5 * j] = c;
    } else if (ax == '3') {
        for (int r = 0; r < 3; r++)
            for (int col = 0; col < 3; col++) t[4 * r + col] = a[3 * r + col];
    } else {
        memcpy(t, a, 16 * sizeof *t);
    }
}

/* q = M p. 0, or 1 when w is 0, or 2 when the result is not finite. */
static int transform_point(const double m[16], const double p[3], double q[3])
{
    for (int i = 0; i < 3; i++)
        q[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
    double w = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
    if (w == 0) return 1;
    if (w != 1)
        for (int i = 0; i < 3; i++) q[i] /= w;
    for (int i = 0; i < 3; i++)
        if (!isfinite(q[i])) return 2;
    return 0;
}

/* ------------------------------------------------------------------ */
/* Lexer                                                               */

enum { TK_EOF, TK_WORD, TK_LPAREN, TK_RPAREN, TK_SEMI };

typedef struct ug_token {
    int kind;
    char *s;             /* TK_WORD: NUL-terminated in the file's buffer */
    size_t len;
    long line, col;
} ug_token;

typedef struct ug_parser {
    ug_import *imp;
    ug_file *file;
    char *buf;
    size_t len, pos;
    size_t held_pos;     /* the delimiter after the last word was replaced */
    char held;           /* by a NUL; this is what it was */
    long line, col;      /* position of buf[pos] */
    ug_token peeked;
    int has_peek;
    uint32_t scope;      /* scope statements go into */
    int def_depth;
    int known;           /* a Unigrafix statement was seen: until then the
                            file may be anything, and messages quote none of it */
} ug_parser;

static int char_at(const ug_parser *p, size_t i)
{
    if (i >= p->len) return -1;
    return (unsigned char)(i == p->held_pos ? p->held : p->buf[i]);
}

static void advance(ug_parser *p)
{
    if (char_at(p, p->pos) == '\n') {
        p->line++;
        p->col = 1;
    } else {
        p->col++;
    }
    p->pos++;
}

static int is_space(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static int ends_word(int c)
{
    return c < 0 || is_space(c) || c == '(' || c == ')' || c == ';' || c == '{' ||
           c == '}' || c == '\0';
}

static int perr(ug_parser *p, int code, long line, long col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
static int perr(ug_parser *p, int code, long line, long col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = verror(p->imp, code, p->file, line, col, fmt, ap);
    va_end(ap);
    return rc;
}

/* Skip whitespace and comments up to the next token. */
static int skip_blank(ug_parser *p)
{
    for (;;) {
        int c = char_at(p, p->pos);
        if (c < 0) return LAM_OK;
        if (is_space(c)) {
            advance(p);
        } else if (c == '{') {
            long line = p->line, col = p->col;
            size_t depth = 0;
            do {
                c = char_at(p, p->pos);
                if (c < 0)
                    return perr(p, LAM_ESYNTAX, line, col, "unterminated '{' comment");
                if (c == '{') depth++;
                else if (c == '}') depth--;
                advance(p);
            } while (depth > 0);
        } else if (c == '/' && char_at(p, p->pos + 1) == '*') {
            long line = p->line, col = p->col;
            advance(p);
            advance(p);
            while (!(char_at(p, p->pos) == '*' && char_at(p, p->pos + 1) == '/')) {
                if (char_at(p, p->pos) < 0)
                    return perr(p, LAM_ESYNTAX, line, col, "unterminated '/*' comment");
                advance(p);
            }
            advance(p);
            advance(p);
        } else {
            return LAM_OK;
        }
    }
}

static int lex(ug_parser *p, ug_token *t)
{
    int rc = skip_blank(p);
    if (rc) return rc;
    t->line = p->line;
    t->col = p->col;
    t->s = NULL;
    t->len = 0;
    int c = char_at(p, p->pos);
    switch (c) {
    case -1: t->kind = TK_EOF; return LAM_OK;
    case '(': t->kind = TK_LPAREN; advance(p); return LAM_OK;
    case ')': t->kind = TK_RPAREN; advance(p); return LAM_OK;
    case ';': t->kind = TK_SEMI; advance(p); return LAM_OK;
    case '}': return perr(p, LAM_ESYNTAX, t->line, t->col, "'}' outside a comment");
    case '\0': return perr(p, LAM_ESYNTAX, t->line, t->col, "unexpected NUL byte");
    default: break;
    }
    size_t start = p->pos;
    while (!ends_word(char_at(p, p->pos))) advance(p);
    t->kind = TK_WORD;
    t->s = p->buf + start;
    t->len = p->pos - start;
    /* Terminate the word in place; remember the delimiter it overwrote. */
    p->held = p->buf[p->pos];
    p->held_pos = p->pos;
    p->buf[p->pos] = '\0';
    return LAM_OK;
}

static int next(ug_parser *p, ug_token *t)
{
    if (p->has_peek) {
        *t = p->peeked;
        p->has_peek = 0;
        return LAM_OK;
    }
    return lex(p, t);
}

static int peek(ug_parser *p, const ug_token **t)
{
    if (!p->has_peek) {
        int rc = lex(p, &p->peeked);
        if (rc) return rc;
        p->has_peek = 1;
    }
    *t = &p->peeked;
    return LAM_OK;
}

/* A token as quoted in messages (long words are cut). */
static const char *tokstr(const ug_parser *p, const ug_token *t, char *buf, size_t size)
{
    switch (t->kind) {
    case TK_EOF: return "end of file";
    case TK_LPAREN: return "'('";
    case TK_RPAREN: return "')'";
    case TK_SEMI: return "';'";
    default: return p->known ? lam_quote_bytes(buf, size, (const unsigned char *)t->s, t->len) : "a word";
    }
}

/* "expected X, got <token>" at the token. */
static int expected(ug_parser *p, const ug_token *t, const char *what)
{
    char b[64];
    return perr(p, LAM_ESYNTAX, t->line, t->col, "expected %s, got %s", what, tokstr(p, t, b, sizeof b));
}

static int expect_semi(ug_parser *p, const char *after)
{
    ug_token t;
    int rc = next(p, &t);
    if (rc) return rc;
    if (t.kind == TK_SEMI) return LAM_OK;
    char what[96];
    snprintf(what, sizeof what, "';' after %s", after);
    return expected(p, &t, what);
}

/* The whole word is a number: decimals by lexnum.h (whatever the C
 * locale's decimal separator; nan and inf read as such so that the caller
 * can say "not a finite number"), and C's hexadecimal spellings (0x10),
 * which Unigrafix files have always been read with, by strtod. */
static int parse_number(const ug_token *t, double *out)
{
    if (t->kind != TK_WORD) return 0;
    if (lam_parse_number((const unsigned char *)t->s, t->len, out) == LAM_OK) return 1;
    const char *h = t->s + (t->s[0] == '-' || t->s[0] == '+');
    if (h[0] != '0' || (h[1] != 'x' && h[1] != 'X')) return 0;
    char *end;
    double v = strtod(t->s, &end);
    if (end != t->s + t->len) return 0;
    *out = v;
    return 1;
}

static int is_number(const ug_token *t)
{
    double v;
    return parse_number(t, &v);
}

/* ------------------------------------------------------------------ */
/* Statements                                                          */

static ug_scope *cur_scope(const ug_parser *p)
{
    return p->imp->scopes[p->scope];
}

/* Where a definition was made, for "first defined at" messages. */
static void def_where(const ug_parser *p, const ug_scope *d, char *buf, size_t size)
{
    if (d->file == p->file) snprintf(buf, size, "line %ld, column %ld", d->line, d->col);
    else snprintf(buf, size, "%s:%ld:%ld", file_name(d->file), d->line, d->col);
}

static int st_vertex(ug_parser *p)
{
    static const char axis[3] = { 'x', 'y', 'z' };
    ug_scope *s = cur_scope(p);
    ug_token name, t;
    int rc = next(p, &name);
    if (rc) return rc;
    if (name.kind != TK_WORD) return expected(p, &name, "vertex name after 'v'");
    uint32_t old;
    if (map_get(&s->vmap, name.s, name.len, &old))
        return perr(p, LAM_EINVAL, name.line, name.col,
                    "vertex '%s' redefined (first defined at line %ld, column %ld)",
                    name.s, s->verts[old].line, s->verts[old].col);
    double xyz[3];
    for (int k = 0; k < 3; k++) {
        if ((rc = next(p, &t))) return rc;
        char what[96];
        snprintf(what, sizeof what, "%c coordinate of vertex '%.40s'", axis[k], name.s);
        if (!parse_number(&t, &xyz[k])) return expected(p, &t, what);
        if (lam_coord_problem(xyz[k]))
            return perr(p, LAM_EINVAL, t.line, t.col, "coordinate %s", lam_coord_problem(xyz[k]));
    }
    /* An optional normal (three more numbers) is read and ignored. */
    if ((rc = next(p, &t))) return rc;
    if (is_number(&t)) {
        for (int k = 1; k < 3; k++) {
            if ((rc = next(p, &t))) return rc;
            if (!is_number(&t)) return expected(p, &t, "3 numbers for the vertex normal");
        }
        if ((rc = expect_semi(p, "vertex normal"))) return rc;
    } else if (t.kind != TK_SEMI) {
        return expected(p, &t, "';' after vertex coordinates");
    }
    if (s->nverts >= UG_NONE - 1) return perr(p, LAM_EINVAL, name.line, name.col, "too many vertices");
    if (RESERVE(s->verts, s->cap_verts, s->nverts + 1) ||
        RESERVE(s->vgen, s->cap_vmark, s->nverts + 1) ||
        map_put(&s->vmap, name.s, name.len, (uint32_t)s->nverts))
        return nomem(p->imp);
    s->vgen[s->nverts] = 0;
    ug_vertex *v = &s->verts[s->nverts++];
    memcpy(v->p, xyz, sizeof xyz);
    v->name = name.s;
    v->line = name.line;
    v->col = name.col;
    return LAM_OK;
}

/* Read vertex names up to ')' (the '(' is consumed) into s->refs, dropping
 * a vertex that repeats the one before it. *count: refs appended. */
static int read_ring(ug_parser *p, ug_scope *s, const char *what, const char *name,
                     size_t *count)
{
    size_t start = s->nrefs;
    for (;;) {
        ug_token t;
        int rc = next(p, &t);
        if (rc) return rc;
        if (t.kind == TK_RPAREN) break;
        if (t.kind != TK_WORD) {
            char w[64];
            snprintf(w, sizeof w, "vertex name or ')' in %s", what);
            return expected(p, &t, w);
        }
        uint32_t v;
        if (!map_get(&s->vmap, t.s, t.len, &v)) {
            if (name)
                return perr(p, LAM_EINVAL, t.line, t.col, "%s '%s' names undefined vertex '%s'",
                            what, name, t.s);
            return perr(p, LAM_EINVAL, t.line, t.col, "%s names undefined vertex '%s'", what, t.s);
        }
        if (s->nrefs > start && s->refs[s->nrefs - 1] == v) continue;
        if (RESERVE(s->refs, s->cap_refs, s->nrefs + 1)) return nomem(p->imp);
        s->refs[s->nrefs++] = v;
    }
    *count = s->nrefs - start;
    return LAM_OK;
}

static size_t distinct(ug_scope *s, size_t first, size_t n)
{
    size_t d = 0;
    mark_next(s);
    for (size_t i = first; i < first + n; i++)
        if (s->vgen[s->refs[i]] != s->gen) {
            s->vgen[s->refs[i]] = s->gen;
            d++;
        }
    return d;
}

/* Append an item, keeping the scope's expansion cost and instance height
 * within the limits. */
static int add_item(ug_parser *p, ug_scope *s, const ug_item *it)
{
    ug_import *imp = p->imp;
    size_t cost = 1;
    if (it->kind == IT_FACE || it->kind == IT_WIRE) {
        cost += it->count;
    } else {
        const ug_scope *tg = imp->scopes[it->target];
        if (tg->height + 1 > UG_MAX_INSTANCE_DEPTH)
            return perr(p, LAM_EINVAL, it->line, it->col,
                        "instances and includes nested more than %d deep", UG_MAX_INSTANCE_DEPTH);
        if (tg->height + 1 > s->height) s->height = tg->height + 1;
        cost += tg->cost;
    }
    if (cost > UG_MAX_EXPANSION - s->cost)
        return perr(p, LAM_EINVAL, it->line, it->col,
                    "%s expands to more than %zu vertex references",
                    s->name ? "definition" : "the model", UG_MAX_EXPANSION);
    s->cost += cost;
    if (RESERVE(s->items, s->cap_items, s->nitems + 1)) return nomem(imp);
    s->items[s->nitems++] = *it;
    return LAM_OK;
}

/* The optional ID and the '(' after the keyword of a face, wire or instance
 * (`what`): the ID, if any, into it->name; the '(' is consumed. */
static int read_id_paren(ug_parser *p, const ug_token *kw, const char *what, ug_item *it)
{
    ug_token t;
    int rc = next(p, &t);
    if (rc) return rc;
    char w[64];
    if (t.kind == TK_WORD) {
        it->name = t.s;
        if ((rc = next(p, &t))) return rc;
        if (t.kind == TK_LPAREN) return LAM_OK;
        snprintf(w, sizeof w, "'(' after %s name", what);
    } else {
        if (t.kind == TK_LPAREN) return LAM_OK;
        snprintf(w, sizeof w, "%s name or '(' after '%s'", what, kw->s);
    }
    return expected(p, &t, w);
}

/* The optional colour and the ';' that end a face or wire (`what`). */
static int end_colour_semi(ug_parser *p, const char *what)
{
    const ug_token *nt;
    int rc = peek(p, &nt);
    if (rc) return rc;
    if (nt->kind != TK_WORD) return expect_semi(p, what);
    ug_token t;
    if ((rc = next(p, &t))) return rc;
    char after[32];
    snprintf(after, sizeof after, "%s colour", what);
    return expect_semi(p, after);
}

/* f [ID] (v1 ... vn) [(h1 ...) ...] [color]; */
static int st_face(ug_parser *p, const ug_token *kw)
{
    ug_scope *s = cur_scope(p);
    ug_item it = { .kind = IT_FACE, .line = kw->line, .col = kw->col };
    ug_token t;
    int rc = read_id_paren(p, kw, "face", &it);
    if (rc) return rc;
    it.first = s->nrefs;
    it.ring = s->nrings;
    for (;;) {
        size_t start = s->nrefs, n;
        if ((rc = read_ring(p, s, "face", it.name, &n))) return rc;
        /* A ring written closed (last == first) is the same ring. */
        while (n > 1 && s->refs[start + n - 1] == s->refs[start]) {
            n--;
            s->nrefs--;
        }
        if (distinct(s, start, n) < 3) {
            char hole[32] = "";
            if (s->nrings > it.ring) snprintf(hole, sizeof hole, " hole %zu", s->nrings - it.ring);
            return perr(p, LAM_EGEOM, kw->line, kw->col,
                        "face%s%s%s%s has fewer than 3 distinct vertices",
                        it.name ? " '" : "", it.name ? it.name : "", it.name ? "'" : "", hole);
        }
        if (RESERVE(s->rings, s->cap_rings, s->nrings + 1)) return nomem(p->imp);
        s->rings[s->nrings++] = n;
        const ug_token *nt;
        if ((rc = peek(p, &nt))) return rc;
        if (nt->kind != TK_LPAREN) break;
        if ((rc = next(p, &t))) return rc;
    }
    it.count = s->nrefs - it.first;
    it.nrings = s->nrings - it.ring;
    if ((rc = end_colour_semi(p, "face"))) return rc;
    return add_item(p, s, &it);
}

/* w [ID] (v1 v2 ...) [color]; */
static int st_wire(ug_parser *p, const ug_token *kw)
{
    ug_scope *s = cur_scope(p);
    ug_item it = { .kind = IT_WIRE, .line = kw->line, .col = kw->col };
    int rc = read_id_paren(p, kw, "wire", &it);
    if (rc) return rc;
    it.first = s->nrefs;
    if ((rc = read_ring(p, s, "wire", it.name, &it.count))) return rc;
    if (it.count < 2)
        return perr(p, LAM_EINVAL, kw->line, kw->col, "wire%s%s%s needs at least 2 distinct vertices",
                    it.name ? " '" : "", it.name ? it.name : "", it.name ? "'" : "");
    if ((rc = end_colour_semi(p, "wire"))) return rc;
    return add_item(p, s, &it);
}

/* Transform flags up to a token of kind `end` (consumed), composed left to
 * right into a new matrix; *mat receives its index. */
static int parse_transforms(ug_parser *p, int end, uint32_t *mat)
{
    double m[16];
    mat_identity(m);
    const ug_flag *last = NULL;
    ug_token last_tok = { 0 };
    const char *endname = end == TK_RPAREN ? "')'" : "';'";
    for (;;) {
        ug_token t;
        int rc = next(p, &t);
        if (rc) return rc;
        if (t.kind == end) break;
        const ug_flag *f = t.kind == TK_WORD ? find_flag(t.s) : NULL;
        if (!f) {
            if (last && is_number(&t))
                return perr(p, LAM_ESYNTAX, last_tok.line, last_tok.col,
                            "transform '%s' takes %d number%s, got more", last->name,
                            last->nargs, last->nargs == 1 ? "" : "s");
            if (t.kind == TK_WORD && t.s[0] == '-')
                return perr(p, LAM_ESYNTAX, t.line, t.col, "unknown transform '%s'", t.s);
            char what[64];
            snprintf(what, sizeof what, "a transform or %s", endname);
            return expected(p, &t, what);
        }
        double a[16], tm[16];
        for (int k = 0; k < f->nargs; k++) {
            ug_token at;
            if ((rc = next(p, &at))) return rc;
            if (!parse_number(&at, &a[k])) {
                char b[64];
                return perr(p, LAM_ESYNTAX, t.line, t.col, "transform '%s' takes %d number%s, got %s",
                            f->name, f->nargs, f->nargs == 1 ? "" : "s", tokstr(p, &at, b, sizeof b));
            }
            if (!isfinite(a[k]))
                return perr(p, LAM_EINVAL, at.line, at.col, "transform argument is not a finite number");
        }
        flag_matrix(f, a, tm);
        mat_mul(m, tm, m);
        last = f;
        last_tok = t;
    }
    ug_import *imp = p->imp;
    if (imp->nmats >= UG_NONE || RESERVE(imp->mats, imp->cap_mats, imp->nmats + 1))
        return nomem(imp);
    memcpy(imp->mats[imp->nmats], m, sizeof m);
    *mat = (uint32_t)imp->nmats++;
    return LAM_OK;
}

/* A definition visible from scope si: innermost scope outward. */
static int find_def(const ug_import *imp, uint32_t si, const char *name, size_t len, uint32_t *out)
{
    for (; si != UG_NONE; si = imp->scopes[si]->parent)
        if (map_get(&imp->scopes[si]->dmap, name, len, out)) return 1;
    return 0;
}

/* i [ID] (defname [color] [transforms]); */
static int st_instance(ug_parser *p, const ug_token *kw)
{
    ug_import *imp = p->imp;
    ug_item it = { .kind = IT_INST, .line = kw->line, .col = kw->col };
    ug_token t;
    int rc = read_id_paren(p, kw, "instance", &it);
    if (rc) return rc;
    if ((rc = next(p, &t))) return rc;
    if (t.kind != TK_WORD) return expected(p, &t, "definition name after '('");
    if (!find_def(imp, p->scope, t.s, t.len, &it.target))
        return perr(p, LAM_EINVAL, t.line, t.col, "instance names undefined definition '%s'", t.s);
    const ug_scope *d = imp->scopes[it.target];
    if (d->open)
        return perr(p, LAM_EINVAL, kw->line, kw->col, "definition '%s' instantiates itself", d->name);
    /* A word that is not a transform flag is the colour: skip it. */
    const ug_token *nt;
    if ((rc = peek(p, &nt))) return rc;
    if (nt->kind == TK_WORD && nt->s[0] != '-' && (rc = next(p, &t))) return rc;
    if ((rc = parse_transforms(p, TK_RPAREN, &it.mat))) return rc;
    if ((rc = expect_semi(p, "instance"))) return rc;
    return add_item(p, cur_scope(p), &it);
}

/* def NAME; */
static int st_def(ug_parser *p, const ug_token *kw)
{
    ug_import *imp = p->imp;
    ug_token name;
    int rc = next(p, &name);
    if (rc) return rc;
    if (name.kind != TK_WORD) return expected(p, &name, "definition name after 'def'");
    uint32_t old;
    if (map_get(&cur_scope(p)->dmap, name.s, name.len, &old)) {
        char where[600];
        def_where(p, imp->scopes[old], where, sizeof where);
        return perr(p, LAM_EINVAL, name.line, name.col,
                    "definition '%s' redefined (first defined at %s)", name.s, where);
    }
    if ((rc = expect_semi(p, "definition name"))) return rc;
    if (p->def_depth >= UG_MAX_DEF_DEPTH)
        return perr(p, LAM_EINVAL, kw->line, kw->col, "definitions nested more than %d deep",
                    UG_MAX_DEF_DEPTH);
    uint32_t si = 0;
    if ((rc = new_scope(imp, p->file, name.s, kw->line, kw->col, p->scope, &si))) return rc;
    if (map_put(&cur_scope(p)->dmap, name.s, name.len, si)) return nomem(imp);
    p->scope = si;
    p->def_depth++;
    return LAM_OK;
}

static int st_end(ug_parser *p, const ug_token *kw)
{
    ug_scope *s = cur_scope(p);
    if (s->parent == UG_NONE) return perr(p, LAM_ESYNTAX, kw->line, kw->col, "'end' without 'def'");
    int rc = expect_semi(p, "'end'");
    if (rc) return rc;
    s->open = 0;
    p->scope = s->parent;
    p->def_depth--;
    return LAM_OK;
}

/* c, c_rgb, l, cam: attributes lamina does not use. */
static int skip_statement(ug_parser *p, const ug_token *kw)
{
    for (;;) {
        ug_token t;
        int rc = next(p, &t);
        if (rc) return rc;
        if (t.kind == TK_SEMI) return LAM_OK;
        if (t.kind == TK_EOF)
            return perr(p, LAM_ESYNTAX, t.line, t.col, "expected ';' to end '%s' statement, got end of file",
                        kw->s);
    }
}

static int compile_file(ug_import *imp, char *path, char *buf, size_t len,
                        const struct stat *st, uint32_t *top);

/* The including file's directory joined with name, plus suffix. */
static char *include_path(const ug_file *f, const char *name, const char *suffix)
{
    size_t dlen = 0;
    if (name[0] != '/' && f->path) {
        const char *slash = strrchr(f->path, '/');
        if (slash) dlen = (size_t)(slash - f->path) + 1;
    }
    size_t n = dlen + strlen(name) + strlen(suffix) + 1;
    char *s = malloc(n);
    if (s) snprintf(s, n, "%.*s%s%s", (int)dlen, f ? f->path : "", name, suffix);
    return s;
}

static int cycle_error(ug_parser *p, const ug_token *kw, const ug_file *again)
{
    ug_import *imp = p->imp;
    char msg[sizeof imp->err->msg];
    int k = 0;
    while (k < imp->depth && imp->stack[k] != again) k++;
    size_t n = (size_t)snprintf(msg, sizeof msg, "include cycle: ");
    for (; k < imp->depth && n < sizeof msg; k++)
        n += (size_t)snprintf(msg + n, sizeof msg - n, "%s -> ", file_name(imp->stack[k]));
    if (n < sizeof msg) snprintf(msg + n, sizeof msg - n, "%s", file_name(again));
    return perr(p, LAM_EINVAL, kw->line, kw->col, "%s", msg);
}

/* Find, read and compile the file `include name` names. */
static int include_file(ug_parser *p, const ug_token *kw, const char *name, uint32_t *top)
{
    ug_import *imp = p->imp;
    char *path = include_path(p->file, name, "");
    char *alt = include_path(p->file, name, ".ug");
    struct stat st;
    int rc = LAM_OK;
    if (!path || !alt) {
        rc = nomem(imp);
        goto out;
    }
    /* NAME as written, else NAME.ug; a directory counts as missing. */
    int e = stat(path, &st) != 0 ? errno : S_ISDIR(st.st_mode) ? EISDIR : 0;
    if (e) {
        if (stat(alt, &st) != 0 || S_ISDIR(st.st_mode)) {
            rc = perr(p, LAM_EIO, kw->line, kw->col, "cannot include '%s' (tried %s and %s): %s",
                      name, path, alt, strerror(e));
            goto out;
        }
        char *tmp = path;
        path = alt;
        alt = tmp;
    }
    for (ug_file *f = imp->files; f; f = f->next) {
        if (!f->has_id || f->dev != st.st_dev || f->ino != st.st_ino) continue;
        if (f->compiling) rc = cycle_error(p, kw, f);
        else *top = f->top;
        goto out;
    }
    if (imp->depth >= UG_MAX_INCLUDE_DEPTH) {
        rc = perr(p, LAM_EINVAL, kw->line, kw->col, "includes nested more than %d deep",
                  UG_MAX_INCLUDE_DEPTH);
        goto out;
    }
    char *data;
    size_t len;
    lam_error rerr;
    lam_error_clear(&rerr);
    if ((rc = lam_read_file(path, lam_model_limit(), &data, &len, &rerr))) {
        rc = perr(p, rc, kw->line, kw->col, "cannot include '%s': %s: %s", name, path, rerr.msg);
        goto out;
    }
    rc = compile_file(imp, path, data, len, &st, top);
    path = NULL;              /* compile_file took it */
out:
    free(path);
    free(alt);
    return rc;
}

/* Make the included file's top-level definitions visible in scope s. */
static int import_defs(ug_parser *p, const ug_token *kw, ug_scope *s, const ug_scope *from)
{
    ug_import *imp = p->imp;
    for (size_t i = 0; i < from->dmap.cap; i++) {
        const ug_slot *sl = &from->dmap.slots[i];
        if (!sl->key) continue;
        uint32_t old;
        if (map_get(&s->dmap, sl->key, sl->len, &old)) {
            if (old == sl->val) continue;   /* the same file included twice */
            char where[600];
            def_where(p, imp->scopes[old], where, sizeof where);
            return perr(p, LAM_EINVAL, kw->line, kw->col,
                        "included definition '%s' (%s:%ld:%ld) clashes with the one at %s",
                        sl->key, file_name(imp->scopes[sl->val]->file),
                        imp->scopes[sl->val]->line, imp->scopes[sl->val]->col, where);
        }
        if (map_put(&s->dmap, sl->key, sl->len, sl->val)) return nomem(imp);
    }
    return LAM_OK;
}

/* include filename [transforms]; */
static int st_include(ug_parser *p, const ug_token *kw)
{
    ug_item it = { .kind = IT_INCL, .line = kw->line, .col = kw->col };
    ug_token t;
    int rc = next(p, &t);
    if (rc) return rc;
    if (t.kind != TK_WORD) return expected(p, &t, "file name after 'include'");
    char *name = t.s;
    if (t.len >= 2 && name[0] == '"' && name[t.len - 1] == '"') {
        name[t.len - 1] = '\0';
        name++;
    }
    if ((rc = parse_transforms(p, TK_SEMI, &it.mat))) return rc;
    if ((rc = include_file(p, kw, name, &it.target))) return rc;
    ug_scope *s = cur_scope(p);
    if ((rc = import_defs(p, kw, s, p->imp->scopes[it.target]))) return rc;
    return add_item(p, s, &it);
}

static int statement(ug_parser *p, const ug_token *kw)
{
    static const char *const skipped[] = { "c", "c_rgb", "l", "cam", NULL };
    const char *k = kw->s;
    int skip = 0;
    for (int i = 0; skipped[i]; i++) skip |= strcmp(k, skipped[i]) == 0;
    int known = skip || !strcmp(k, "v") || !strcmp(k, "f") || !strcmp(k, "w") || !strcmp(k, "i") ||
                !strcmp(k, "def") || !strcmp(k, "end") || !strcmp(k, "include");
    if (!known && !p->known)
        return perr(p, LAM_EFORMAT, kw->line, kw->col,
                    "not a Unigrafix file: it does not start with a statement (v, f, w, i, def, include, ...)");
    if (!known) {
        char b[64];
        return perr(p, LAM_ESYNTAX, kw->line, kw->col, "unknown statement %s",
                    lam_quote_bytes(b, sizeof b, (const unsigned char *)k, kw->len));
    }
    p->known = 1;
    if (skip) return skip_statement(p, kw);
    if (strcmp(k, "v") == 0) return st_vertex(p);
    if (strcmp(k, "f") == 0) return st_face(p, kw);
    if (strcmp(k, "w") == 0) return st_wire(p, kw);
    if (strcmp(k, "i") == 0) return st_instance(p, kw);
    if (strcmp(k, "def") == 0) return st_def(p, kw);
    if (strcmp(k, "end") == 0) return st_end(p, kw);
    return st_include(p, kw);
}

static int parse_file(ug_parser *p)
{
    for (;;) {
        ug_token t;
        int rc = next(p, &t);
        if (rc) return rc;
        if (t.kind == TK_SEMI) continue;        /* empty statement */
        if (t.kind == TK_EOF) break;
        if (t.kind != TK_WORD) return expected(p, &t, "a statement");
        if ((rc = statement(p, &t))) return rc;
    }
    const ug_scope *s = cur_scope(p);
    if (s->parent != UG_NONE)
        return perr(p, LAM_ESYNTAX, s->line, s->col, "definition '%s' is not closed by 'end'", s->name);
    return LAM_OK;
}

/* Compile one file. Takes ownership of path and buf (NUL-terminated, len
 * bytes); st (may be NULL) identifies the file for cycles and reuse. */
static int compile_file(ug_import *imp, char *path, char *buf, size_t len,
                        const struct stat *st, uint32_t *top)
{
    ug_file *f = calloc(1, sizeof *f);
    if (!f) {
        free(path);
        free(buf);
        return nomem(imp);
    }
    f->path = path;
    f->buf = buf;
    if (st) {
        f->has_id = 1;
        f->dev = st->st_dev;
        f->ino = st->st_ino;
    }
    f->next = imp->files;
    imp->files = f;
    int rc = new_scope(imp, f, NULL, 0, 0, UG_NONE, &f->top);
    if (rc) return rc;
    ug_parser p = { .imp = imp, .file = f, .buf = buf, .len = len, .held_pos = SIZE_MAX,
                    .line = 1, .col = 1, .scope = f->top };
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) p.pos = 3;   /* UTF-8 BOM */
    f->compiling = 1;
    imp->stack[imp->depth++] = f;
    rc = parse_file(&p);
    imp->depth--;
    f->compiling = 0;
    imp->scopes[f->top]->open = 0;
    *top = f->top;
    return rc;
}

/* ------------------------------------------------------------------ */
/* Expansion                                                           */

/* The mesh index of vertex v of scope s under transform m, emitting it on
 * first use in this expansion. */
static int emit_vertex(ug_import *imp, ug_scope *s, uint32_t v, const double m[16], uint32_t *out)
{
    if (s->vgen[v] == s->gen) {
        *out = s->vidx[v];
        return LAM_OK;
    }
    const ug_vertex *vx = &s->verts[v];
    double q[3];
    switch (transform_point(m, vx->p, q)) {
    case 1:
        return error_at(imp, LAM_EGEOM, s->file, vx->line, vx->col,
                        "vertex '%s' has w = 0 under the instance transform", vx->name);
    case 2:
        return error_at(imp, LAM_EGEOM, s->file, vx->line, vx->col,
                        "vertex '%s' is not a finite number after the instance transform", vx->name);
    default:
        break;
    }
    for (int k = 0; k < 3; k++)
        if (lam_coord_problem(q[k]))
            return error_at(imp, LAM_EGEOM, s->file, vx->line, vx->col, "vertex '%s' after the instance transform: %c coordinate %g %s",
                            vx->name, "xyz"[k], q[k], lam_coord_problem(q[k]));
    int rc = lam_mesh_add_vertex(imp->mesh, q[0], q[1], q[2], out, imp->err);
    if (rc) return rc;
    s->vgen[v] = s->gen;
    s->vidx[v] = *out;
    return LAM_OK;
}

static int emit_face(ug_import *imp, ug_scope *s, const ug_item *it, const double m[16], int flip)
{
    if (RESERVE(imp->idx, imp->cap_idx, it->count)) return nomem(imp);
    for (size_t k = 0; k < it->count; k++) {
        int rc = emit_vertex(imp, s, s->refs[it->first + k], m, &imp->idx[k]);
        if (rc) return rc;
    }
    const size_t *rl = s->rings + it->ring;
    if (flip) {
        /* A mirroring transform turns the face over: reverse every ring. */
        for (size_t r = 0, off = 0; r < it->nrings; off += rl[r], r++)
            for (size_t a = off, b = off + rl[r] - 1; a < b; a++, b--) {
                uint32_t tmp = imp->idx[a];
                imp->idx[a] = imp->idx[b];
                imp->idx[b] = tmp;
            }
    }
    uint32_t face;
    int rc = lam_mesh_add_face(imp->mesh, it->name, s->file->path, it->line, it->col, &face, imp->err);
    if (rc) return rc;
    rc = lam_mesh_add_polygon(imp->mesh, imp->idx, rl, it->nrings, face, imp->err);
    if (rc && imp->err && imp->err->line == 0 && !imp->err->file[0]) {
        /* The triangulator does not know where the face came from. */
        char msg[sizeof imp->err->msg];
        snprintf(msg, sizeof msg, "%s", imp->err->msg);
        error_at(imp, rc, s->file, it->line, it->col, "%s", msg);
    }
    return rc;
}

static int emit_wire(ug_import *imp, ug_scope *s, const ug_item *it, const double m[16])
{
    uint32_t prev = 0;
    for (size_t k = 0; k < it->count; k++) {
        uint32_t v;
        int rc = emit_vertex(imp, s, s->refs[it->first + k], m, &v);
        if (rc) return rc;
        if (k > 0 && (rc = lam_mesh_add_wire_seg(imp->mesh, prev, v, imp->err))) return rc;
        prev = v;
    }
    imp->mesh->nwires++;
    return LAM_OK;
}

static int expand(ug_import *imp, uint32_t si, const double m[16], int depth)
{
    ug_scope *s = imp->scopes[si];
    /* add_item bounds the height; this guards the recursion regardless. */
    if (depth > UG_MAX_INSTANCE_DEPTH)
        return error_at(imp, LAM_EINVAL, s->file, s->line, s->col, "instances nested too deeply");
    if (s->nverts && !s->vidx) {
        s->vidx = malloc(s->cap_vmark * sizeof *s->vidx);
        if (!s->vidx) return nomem(imp);
    }
    mark_next(s);
    int flip = det3(m) < 0;
    for (size_t i = 0; i < s->nitems; i++) {
        const ug_item *it = &s->items[i];
        int rc;
        if (it->kind == IT_FACE) {
            rc = emit_face(imp, s, it, m, flip);
        } else if (it->kind == IT_WIRE) {
            rc = emit_wire(imp, s, it, m);
        } else {
            double cm[16];
            mat_mul(cm, m, imp->mats[it->mat]);
            rc = expand(imp, it->target, cm, depth + 1);
        }
        if (rc) return rc;
    }
    return LAM_OK;
}

/* ------------------------------------------------------------------ */
/* Entry points                                                        */

static void free_import(ug_import *imp)
{
    for (ug_file *f = imp->files, *nf; f; f = nf) {
        nf = f->next;
        free(f->path);
        free(f->buf);
        free(f);
    }
    for (size_t i = 0; i < imp->nscopes; i++) free_scope(imp->scopes[i]);
    free(imp->scopes);
    free(imp->mats);
    free(imp->idx);
}

/* Compile the root text (taking ownership of buf) and expand it. */
static int import_text(const char *path, char *buf, size_t len, lam_mesh *mesh, lam_error *err)
{
    ug_import imp = { .mesh = mesh, .err = err };
    char *pcopy = NULL;
    if (path && !(pcopy = strdup(path))) {
        free(buf);
        return nomem(&imp);
    }
    struct stat st;
    int have_st = path && stat(path, &st) == 0;
    uint32_t top;
    int rc = compile_file(&imp, pcopy, buf, len, have_st ? &st : NULL, &top);
    if (!rc) {
        double m[16];
        mat_identity(m);
        rc = expand(&imp, top, m, 0);
    }
    free_import(&imp);
    return rc;
}

int lam_import_ug(const char *path, lam_mesh *mesh, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    lam_error_clear(err);
    if (!path || !mesh) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "lam_import_ug: no path or mesh");
    char *data;
    size_t len;
    int rc = lam_read_file(path, lam_model_limit(), &data, &len, err);
    if (rc) return rc;
    return import_text(path, data, len, mesh, err);
}

int lam_import_ug_buf(const char *path, const char *data, size_t len,
                      lam_mesh *mesh, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    lam_error_clear(err);
    if (!mesh || (!data && len))
        return lam_error_set(err, LAM_EUSAGE, path, 0, 0, "lam_import_ug_buf: no data or mesh");
    if (len == SIZE_MAX) return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "input too large");
    char *buf = malloc(len + 1);
    if (!buf) return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory reading Unigrafix");
    if (len) memcpy(buf, data, len);
    buf[len] = '\0';
    return import_text(path, buf, len, mesh, err);
}
