/* Reading a run's JSON (json_sink.h) back as a program: its layers'
 * contours, for `lamina validate --program run.json`.
 *
 * A small strict recursive-descent reader (RFC 8259) rather than a library:
 * the Debian C libraries (jansson, json-c) report a position only for a
 * syntax error, never for a value that parsed, and validate must name the
 * line and column of the contour that disagrees; they also build the whole
 * document in memory, where this reader keeps only the contours (the
 * vectors, most of the file, are checked for syntax and passed over).
 * Keys it does not know are passed over too (a later version 1 may add
 * some). Columns count bytes from 1. */
#include "program_read.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "lexnum.h"
#include "json_sink.h"

#define MAX_DEPTH 64 /* nesting the reader follows before it refuses */

typedef struct jr {
    const char *path;
    const unsigned char *s;
    size_t n, pos;
    long line;
    size_t line_start;
    lam_program *p;
    size_t cap_pts, cap_contours, cap_layers;
    double origin[3];
    lam_frame plane;         /* the output frame's axes: points project on them */
    int layer_frame;         /* the job gave "layer_frame" (into p->frame) */
    double maxabs;           /* of the coordinates, for the precision */
    lam_error *err;
} jr;

static long col_of(const jr *r, size_t pos) { return (long)(pos - r->line_start) + 1; }

static int fail(jr *r, int code, size_t pos, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static int fail(jr *r, int code, size_t pos, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(r->err, code, r->path, r->line, col_of(r, pos), -1, fmt, ap);
    va_end(ap);
    return rc;
}

static int nomem(jr *r) { return lam_error_nomem(r->err, "reading the JSON"); }

static void ws(jr *r)
{
    while (r->pos < r->n) {
        unsigned char c = r->s[r->pos];
        if (c == '\n') {
            r->line++;
            r->line_start = ++r->pos;
        } else if (c == ' ' || c == '\t' || c == '\r') {
            r->pos++;
        } else {
            break;
        }
    }
}

/* What stands at the position, for messages. */
static const char *here(const jr *r)
{
    if (r->pos >= r->n) return "the end of the file";
    unsigned char c = r->s[r->pos];
    return c == '{' || c == '[' ? "an object or array" : c == '"' ? "a string" : "something else";
}

static int expect(jr *r, char c)
{
    ws(r);
    if (r->pos < r->n && r->s[r->pos] == (unsigned char)c) {
        r->pos++;
        return LAM_OK;
    }
    if (r->pos >= r->n) return fail(r, LAM_ESYNTAX, r->pos, "unexpected end of file: expected '%c'", c);
    return fail(r, LAM_ESYNTAX, r->pos, "expected '%c', found '%c'", c, r->s[r->pos]);
}

/* After a member or element: 1 for ',' (another follows), 0 for the
 * closing bracket `close`, or an error. */
static int more(jr *r, char close, int *rc)
{
    ws(r);
    if (r->pos < r->n && r->s[r->pos] == ',') return r->pos++, 1;
    if (r->pos < r->n && r->s[r->pos] == (unsigned char)close) return r->pos++, 0;
    *rc = r->pos >= r->n ? fail(r, LAM_ESYNTAX, r->pos, "unexpected end of file: expected ',' or '%c'", close)
                         : fail(r, LAM_ESYNTAX, r->pos, "expected ',' or '%c'", close);
    return -1;
}

/* Whether the container opened at the position (its bracket eaten) is
 * empty; the closing bracket is eaten too. */
static int empty(jr *r, char close)
{
    ws(r);
    if (r->pos < r->n && r->s[r->pos] == (unsigned char)close) return r->pos++, 1;
    return 0;
}

static int hex4(const unsigned char *s)
{
    int v = 0;
    for (int i = 0; i < 4; i++) {
        int c = s[i], d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                                     : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0) return -1;
        v = v * 16 + d;
    }
    return v;
}

/* A string; its first cap - 1 bytes (escapes other than \uXXXX decoded,
 * \u written as '?') into out when out is not NULL. */
static int string(jr *r, char *out, size_t cap)
{
    ws(r);
    if (r->pos >= r->n || r->s[r->pos] != '"') return fail(r, LAM_ESYNTAX, r->pos, "expected a string, found %s", here(r));
    size_t k = 0;
    r->pos++;
    for (;;) {
        if (r->pos >= r->n) return fail(r, LAM_ESYNTAX, r->pos, "unexpected end of file in a string");
        unsigned char c = r->s[r->pos];
        char put = (char)c;
        if (c == '"') {
            r->pos++;
            break;
        }
        if (c < 0x20) return fail(r, LAM_ESYNTAX, r->pos, "a control character (byte %u) in a string: write it \\u%04x", c, c);
        if (c == '\\') {
            if (r->pos + 1 >= r->n) return fail(r, LAM_ESYNTAX, r->pos, "unexpected end of file in a string");
            unsigned char e = r->s[r->pos + 1];
            const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t";
            const char *at = e ? strchr(from, e) : NULL;
            if (at) {
                put = to[at - from];
                r->pos += 2;
            } else if (e == 'u') {
                if (r->pos + 6 > r->n || hex4(r->s + r->pos + 2) < 0)
                    return fail(r, LAM_ESYNTAX, r->pos, "\\u needs four hexadecimal digits");
                put = '?';
                r->pos += 6;
            } else {
                return fail(r, LAM_ESYNTAX, r->pos, "unknown escape '\\%c' in a string", e);
            }
        } else {
            r->pos++;
        }
        if (out && k + 1 < cap) out[k++] = put;
    }
    if (out && cap) out[k] = '\0';
    return LAM_OK;
}

static int is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

/* A number by JSON's grammar (no leading zeros, '+', '.5', NaN). */
static int number(jr *r, double *out)
{
    ws(r);
    size_t a = r->pos, i = a;
    const unsigned char *s = r->s;
    if (i < r->n && s[i] == '-') i++;
    if (i < r->n && s[i] == '0') i++;
    else if (i < r->n && is_digit(s[i])) while (i < r->n && is_digit(s[i])) i++;
    else return fail(r, LAM_ESYNTAX, a, "expected a number, found %s", here(r));
    if (i < r->n && s[i] == '.') {
        if (++i >= r->n || !is_digit(s[i])) return fail(r, LAM_ESYNTAX, a, "a number needs digits after its '.'");
        while (i < r->n && is_digit(s[i])) i++;
    }
    if (i < r->n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < r->n && (s[i] == '+' || s[i] == '-')) i++;
        if (i >= r->n || !is_digit(s[i])) return fail(r, LAM_ESYNTAX, a, "a number's exponent needs digits");
        while (i < r->n && is_digit(s[i])) i++;
    }
    double x = 0;
    int rc = lam_parse_number(s + a, i - a, &x);
    if (rc == LAM_ENOMEM) return nomem(r);
    if (rc || !isfinite(x)) return fail(r, LAM_EINVAL, a, "the number %.*s is out of range", (int)(i - a > 40 ? 40 : i - a), (const char *)s + a);
    r->pos = i;
    if (out) *out = x;
    return LAM_OK;
}

static int word(jr *r, const char *w)
{
    size_t k = strlen(w);
    if (r->n - r->pos < k || memcmp(r->s + r->pos, w, k)) return 0;
    r->pos += k;
    return 1;
}

static int skip(jr *r, int depth);

static int grow_points(jr *r)
{
    lam_program *p = r->p;
    if (p->npoints < r->cap_pts) return 0;
    void *a = lam_grow(p->xyz, &r->cap_pts, p->npoints + 1, 3 * sizeof *p->xyz, 256);
    if (!a) return -1;
    p->xyz = a;
    return 0;
}

/* The members of an object whose '{' was eaten, each key handed to fn
 * (which reads the value), or passed over when fn returns 1. */
typedef int (*member_fn)(jr *r, void *ctx, const char *key, size_t at, int depth);

static int members(jr *r, void *ctx, member_fn fn, int depth)
{
    if (empty(r, '}')) return LAM_OK;
    int rc = LAM_OK;
    do {
        char key[64];
        ws(r);
        size_t at = r->pos;
        if ((rc = string(r, key, sizeof key)) || (rc = expect(r, ':'))) return rc;
        ws(r);
        rc = fn ? fn(r, ctx, key, at, depth) : 1;
        if (rc == 1) rc = skip(r, depth + 1);
        if (rc) return rc;
    } while (more(r, '}', &rc) == 1);
    return rc;
}

/* Any value, checked and passed over. */
static int skip(jr *r, int depth)
{
    ws(r);
    if (depth > MAX_DEPTH) return fail(r, LAM_ESYNTAX, r->pos, "nested more than %d deep", MAX_DEPTH);
    if (r->pos >= r->n) return fail(r, LAM_ESYNTAX, r->pos, "unexpected end of file: expected a value");
    unsigned char c = r->s[r->pos];
    int rc = LAM_OK;
    if (c == '{') {
        r->pos++;
        return members(r, NULL, NULL, depth);
    }
    if (c == '[') {
        r->pos++;
        if (empty(r, ']')) return LAM_OK;
        do
            if ((rc = skip(r, depth + 1))) return rc;
        while (more(r, ']', &rc) == 1);
        return rc;
    }
    if (c == '"') return string(r, NULL, 0);
    if (word(r, "true") || word(r, "false") || word(r, "null")) return LAM_OK;
    if (c == '-' || is_digit(c)) return number(r, NULL);
    return fail(r, LAM_ESYNTAX, r->pos, "expected a value (object, array, string, number, true, false or null)");
}

/* [x, y, z] */
static int triple(jr *r, double v[3], const char *what)
{
    ws(r);
    size_t at = r->pos;
    if (r->pos >= r->n || r->s[r->pos] != '[') return fail(r, LAM_EINVAL, at, "%s must be an array [x, y, z]", what);
    r->pos++;
    int rc = LAM_OK;
    for (int k = 0; k < 3; k++) {
        if (k && (rc = expect(r, ','))) return fail(r, LAM_EINVAL, at, "%s must be 3 numbers [x, y, z]", what);
        if ((rc = number(r, &v[k]))) return rc;
    }
    ws(r);
    if (r->pos >= r->n || r->s[r->pos] != ']') return fail(r, LAM_EINVAL, at, "%s must be 3 numbers [x, y, z]", what);
    r->pos++;
    return LAM_OK;
}

/* ---- the run ------------------------------------------------------------------- */

typedef struct top {
    int format, version, job, layers;
    int has_plane;
} top;

static int plane_member(jr *r, void *ctx, const char *key, size_t at, int depth)
{
    (void)ctx, (void)at, (void)depth;
    lam_program *p = r->p;
    if (!ctx && !strcmp(key, "origin")) return triple(r, r->origin, "plane.origin");
    lam_frame *f = ctx ? &p->frame : &r->plane;
    if (!strcmp(key, "u")) return triple(r, f->u, "an axis u");
    if (!strcmp(key, "v")) return triple(r, f->v, "an axis v");
    if (!strcmp(key, "w")) return triple(r, f->w, "an axis w");
    return 1;
}

static int job_member(jr *r, void *ctx, const char *key, size_t at, int depth)
{
    top *t = ctx;
    if (!strcmp(key, "frame")) {
        char f[16];
        int rc = string(r, f, sizeof f);
        if (rc) return rc;
        if (strcmp(f, "model") && strcmp(f, "machine"))
            return fail(r, LAM_EINVAL, at, "job.frame must be \"model\" or \"machine\"");
        r->p->frame_machine = !strcmp(f, "machine");
        return LAM_OK;
    }
    if (!strcmp(key, "plane")) {
        if (expect(r, '{')) return fail(r, LAM_EINVAL, at, "job.plane must be an object {origin, u, v, w}");
        t->has_plane = 1;
        return members(r, NULL, plane_member, depth + 1);
    }
    if (!strcmp(key, "layer_frame")) {
        if (expect(r, '{')) return fail(r, LAM_EINVAL, at, "job.layer_frame must be an object {u, v, w}");
        r->layer_frame = 1;
        return members(r, r->p, plane_member, depth + 1);
    }
    return 1;
}

typedef struct contour_ctx {
    int have_solid, have_points;
    size_t npoints;
} contour_ctx;

static int contour_member(jr *r, void *ctx, const char *key, size_t at, int depth)
{
    (void)depth;
    contour_ctx *c = ctx;
    lam_program *p = r->p;
    lam_program_contour *pc = &p->contours[p->ncontours - 1];
    if (!strcmp(key, "solid")) {
        if (word(r, "true")) pc->dir = 1;
        else if (word(r, "false")) pc->dir = 0;
        else return fail(r, LAM_EINVAL, r->pos, "\"solid\" must be true or false");
        c->have_solid = 1;
        return LAM_OK;
    }
    if (!strcmp(key, "id")) {
        double id;
        int rc = number(r, &id);
        if (rc) return rc;
        if (id < 1 || id != floor(id) || id > 1e15)
            return fail(r, LAM_EINVAL, at, "a contour's id must be a whole number from 1, got %g", id);
        pc->id = (long)id;
        return LAM_OK;
    }
    if (!strcmp(key, "points")) {
        if (expect(r, '[')) return fail(r, LAM_EINVAL, at, "\"points\" must be an array of [x, y, z]");
        c->have_points = 1;
        if (empty(r, ']')) return LAM_OK;
        int rc = LAM_OK;
        do {
            if (grow_points(r)) return nomem(r);
            double *q = p->xyz + 3 * p->npoints;
            if ((rc = triple(r, q, "a point"))) return rc;
            for (int k = 0; k < 3; k++) r->maxabs = fmax(r->maxabs, fabs(q[k]));
            p->npoints++;
            pc->n++;
        } while (more(r, ']', &rc) == 1);
        return rc;
    }
    return 1;
}

typedef struct layer_ctx {
    int have_z;
    double z;
    double floor, ceiling;   /* NAN when not given */
    size_t first;            /* its first contour */
    size_t index;            /* 1-based, for messages */
} layer_ctx;

static int contour(jr *r, layer_ctx *L, int depth)
{
    lam_program *p = r->p;
    ws(r);
    size_t at = r->pos;
    long line = r->line, col = col_of(r, at);
    if (r->pos >= r->n || r->s[r->pos] != '{') return fail(r, LAM_EINVAL, at, "a contour must be an object");
    r->pos++;
    if (p->ncontours >= r->cap_contours) {
        void *a = lam_grow(p->contours, &r->cap_contours, p->ncontours + 1, sizeof *p->contours, 64);
        if (!a) return nomem(r);
        p->contours = a;
    }
    lam_program_contour *pc = &p->contours[p->ncontours++];
    memset(pc, 0, sizeof *pc);
    pc->first = p->npoints;
    pc->dir = -1;
    pc->id = (long)(p->ncontours - L->first);
    pc->line = line;
    pc->column = col;
    pc->offset = -1;
    contour_ctx c = { 0, 0, 0 };
    int rc = members(r, &c, contour_member, depth);
    if (rc) return rc;
    r->line = line; /* messages about the whole contour point at its start */
    size_t ls = r->line_start;
    r->line_start = at - (size_t)(col - 1);
    if (!c.have_solid) rc = fail(r, LAM_EINVAL, at, "contour %ld of layer %zu has no \"solid\"", pc->id, L->index);
    else if (!c.have_points) rc = fail(r, LAM_EINVAL, at, "contour %ld of layer %zu has no \"points\"", pc->id, L->index);
    else if (pc->n < 3)
        rc = fail(r, LAM_EINVAL, at, "contour %ld of layer %zu has %zu point%s: a contour needs 3", pc->id, L->index, pc->n,
                  pc->n == 1 ? "" : "s");
    r->line_start = ls;
    return rc;
}

static int layer_member(jr *r, void *ctx, const char *key, size_t at, int depth)
{
    (void)at;
    layer_ctx *L = ctx;
    if (!strcmp(key, "z")) {
        L->have_z = 1;
        return number(r, &L->z);
    }
    if (!strcmp(key, "floor")) return number(r, &L->floor);
    if (!strcmp(key, "ceiling")) return number(r, &L->ceiling);
    if (!strcmp(key, "contours")) {
        if (expect(r, '[')) return fail(r, LAM_EINVAL, at, "\"contours\" must be an array");
        if (empty(r, ']')) return LAM_OK;
        int rc = LAM_OK;
        do
            if ((rc = contour(r, L, depth + 1))) return rc;
        while (more(r, ']', &rc) == 1);
        return rc;
    }
    return 1;
}

static int layers(jr *r, int depth)
{
    lam_program *p = r->p;
    if (expect(r, '[')) return fail(r, LAM_EINVAL, r->pos, "\"layers\" must be an array");
    if (empty(r, ']')) return LAM_OK;
    int rc = LAM_OK;
    size_t index = 0;
    do {
        ws(r);
        size_t at = r->pos;
        long line = r->line, col = col_of(r, at);
        if (r->pos >= r->n || r->s[r->pos] != '{') return fail(r, LAM_EINVAL, at, "a layer must be an object");
        r->pos++;
        layer_ctx L = { 0, 0, NAN, NAN, p->ncontours, ++index };
        if ((rc = members(r, &L, layer_member, depth + 1))) return rc;
        if (!L.have_z) return fail(r, LAM_EINVAL, at, "layer %zu has no \"z\"", index);
        /* (a layer of no contour is kept: the caller tells whether the
         * model has material there) */
        if (p->nlayers >= r->cap_layers) {
            void *a = lam_grow(p->layers, &r->cap_layers, p->nlayers + 1, sizeof *p->layers, 64);
            if (!a) return nomem(r);
            p->layers = a;
        }
        lam_program_layer *pl = &p->layers[p->nlayers++];
        pl->z = L.z;
        pl->first = L.first;
        pl->n = p->ncontours - L.first;
        pl->line = line;
        pl->column = col;
        pl->offset = -1;
        pl->floor = L.floor;
        pl->ceiling = L.ceiling;
    } while (more(r, ']', &rc) == 1);
    return rc;
}

static int top_member(jr *r, void *ctx, const char *key, size_t at, int depth)
{
    top *t = ctx;
    if (!strcmp(key, "format")) {
        char f[32];
        int rc = string(r, f, sizeof f);
        if (rc) return rc;
        /* another JSON document: nothing of it is quoted */
        if (strcmp(f, "lamina-run")) return fail(r, LAM_EFORMAT, at, "\"format\" is not \"lamina-run\": not a lamina run");
        t->format = 1;
        return LAM_OK;
    }
    if (!strcmp(key, "version")) {
        double v;
        int rc = number(r, &v);
        if (rc) return rc;
        if (v != LAM_JSON_VERSION)
            return fail(r, LAM_EFORMAT, at, "version %g of the lamina-run format: this lamina reads version %d", v,
                        LAM_JSON_VERSION);
        t->version = 1;
        return LAM_OK;
    }
    if (!strcmp(key, "job")) {
        if (expect(r, '{')) return fail(r, LAM_EINVAL, at, "\"job\" must be an object");
        t->job = 1;
        return members(r, t, job_member, depth + 1);
    }
    if (!strcmp(key, "layers")) {
        t->layers = 1;
        return layers(r, depth + 1);
    }
    return 1;
}

int lam_program_read_json(const char *path, const unsigned char *data, size_t len, lam_program *p, lam_error *err)
{
    jr r;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.s = data;
    r.n = len;
    r.line = 1;
    r.p = p;
    r.err = err;
    p->format = LAM_PROGRAM_JSON;
    p->has_frame = 1;
    lam_frame_axis('z', &p->frame, NULL);
    lam_frame_axis('z', &r.plane, NULL);
    top t;
    memset(&t, 0, sizeof t);
    int rc = expect(&r, '{');
    if (!rc) rc = members(&r, &t, top_member, 0);
    if (rc) return rc;
    ws(&r);
    if (r.pos < r.n) return fail(&r, LAM_ESYNTAX, r.pos, "more after the end of the JSON value");
    const char *missing = !t.format ? "format" : !t.version ? "version" : !t.job ? "job" : !t.layers ? "layers" : NULL;
    r.line = 1, r.line_start = 0;
    if (missing) return fail(&r, LAM_EINVAL, 0, "not a lamina run: no \"%s\"", missing);
    if (!t.has_plane) return fail(&r, LAM_EINVAL, 0, "the job has no \"plane\": how the points were written is unknown");
    if (!r.layer_frame) {
        /* before layer_frame, a model-frame run's plane was its layer frame */
        if (p->frame_machine) return fail(&r, LAM_EINVAL, 0, "a machine-frame run without \"layer_frame\": where its layers lie in the model is unknown");
        p->frame = r.plane;
    }
    /* each point in the layer frame: (u, v, w) on the plane, so the
     * program's points are read as the machine frame's */
    const lam_frame *f = &r.plane;
    for (size_t i = 0; i < p->npoints; i++) {
        double *q = p->xyz + 3 * i, d[3] = { q[0] - r.origin[0], q[1] - r.origin[1], q[2] - r.origin[2] };
        for (int k = 0; k < 3; k++) {
            const double *axis = k == 0 ? f->u : k == 1 ? f->v : f->w;
            q[k] = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
        }
    }
    /* every number is exact (shortest round-trip): what is left is the
     * rounding of projecting a point on the plane */
    p->quantum_xy = p->quantum_z = 8 * 2.220446049250313e-16 * r.maxabs;
    return LAM_OK;
}
