/* Reading contour programs back; see program_read.h. */
#include "program_read.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "fmt.h"
#include "grow.h"
#include "import.h"
#include "lexnum.h"
#include "section.h"

typedef struct rd {
    const char *path;
    const unsigned char *s;
    size_t n;
    size_t pos;              /* start of the next line */
    long lineno;             /* of the line last read */
    lam_program *p;
    size_t cap_pts, cap_contours, cap_layers;
    lam_error *err;
} rd;

/* A line without its end (\n or \r\n), and a token in it. */
typedef struct line {
    const unsigned char *s;
    size_t n;
    long no;
} line;

typedef struct tok {
    const unsigned char *s;
    size_t n;
    long col;
} tok;

static int nomem(rd *r) { return lam_error_set(r->err, LAM_ENOMEM, r->path, 0, 0, "out of memory reading the program"); }

static int fail_at(rd *r, int code, long lineno, long col, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static int fail_at(rd *r, int code, long lineno, long col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(r->err, code, r->path, lineno, col, -1, fmt, ap);
    va_end(ap);
    return rc;
}

static int fail_byte(rd *r, int code, size_t at, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static int fail_byte(rd *r, int code, size_t at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(r->err, code, r->path, 0, 0, (long long)at, fmt, ap);
    va_end(ap);
    return rc;
}

/* ---- growing the program --------------------------------------------------------- */

static int grow(void **arr, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    void *a = lam_grow(*arr, cap, need, elem, 64);
    if (!a) return -1;
    *arr = a;
    return 0;
}

static int add_point(rd *r, double x, double y, double z)
{
    lam_program *p = r->p;
    if (grow((void **)&p->xyz, &r->cap_pts, p->npoints + 1, 3 * sizeof *p->xyz)) return nomem(r);
    double *q = p->xyz + 3 * p->npoints++;
    q[0] = x;
    q[1] = y;
    q[2] = z;
    return LAM_OK;
}

/* A new contour starting at the next point, in the layer at height z (a new
 * layer when the last one is at another height). */
static int add_contour(rd *r, double z, int dir, long id, long lineno, long col, long long offset)
{
    lam_program *p = r->p;
    if (!p->nlayers || p->layers[p->nlayers - 1].z != z) {
        if (grow((void **)&p->layers, &r->cap_layers, p->nlayers + 1, sizeof *p->layers)) return nomem(r);
        lam_program_layer *L = &p->layers[p->nlayers++];
        L->z = z;
        L->first = p->ncontours;
        L->n = 0;
        L->line = lineno;
        L->column = col;
        L->offset = offset;
        L->floor = L->ceiling = NAN;
    }
    if (grow((void **)&p->contours, &r->cap_contours, p->ncontours + 1, sizeof *p->contours)) return nomem(r);
    lam_program_contour *c = &p->contours[p->ncontours++];
    c->first = p->npoints;
    c->n = 0;
    c->dir = dir;
    c->id = id;
    c->line = lineno;
    c->column = col;
    c->offset = offset;
    p->layers[p->nlayers - 1].n++;
    return LAM_OK;
}

/* ---- text ------------------------------------------------------------------------ */

static int next_line(rd *r, line *l)
{
    if (r->pos >= r->n) return 0;
    size_t a = r->pos, b = a;
    while (b < r->n && r->s[b] != '\n') b++;
    r->pos = b < r->n ? b + 1 : b;
    if (b > a && r->s[b - 1] == '\r') b--;
    l->s = r->s + a;
    l->n = b - a;
    l->no = ++r->lineno;
    return 1;
}

static int is_space(unsigned char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/* The next token of l from *i, split at white space and at `sep` (0: none). */
static int next_tok(const line *l, size_t *i, unsigned char sep, tok *t)
{
    while (*i < l->n && is_space(l->s[*i])) (*i)++;
    if (*i >= l->n) return 0;
    size_t a = *i;
    while (*i < l->n && !is_space(l->s[*i]) && (!sep || l->s[*i] != sep)) (*i)++;
    t->s = l->s + a;
    t->n = *i - a;
    t->col = (long)a + 1;
    return 1;
}

static int tok_is(const tok *t, const char *w) { return t->n == strlen(w) && !memcmp(t->s, w, t->n); }

static const char *shown(char *buf, size_t size, const tok *t) { return lam_quote_bytes(buf, size, t->s, t->n); }

/* The exponent written after t->s[i] ('e' or 'E'): [+-]digits, read within
 * the token (a token is not NUL-terminated: it ends where the buffer may),
 * saturated at +-1000 (a double's range ends well before). */
static long written_exponent(const tok *t, size_t i)
{
    int neg = 0;
    long e = 0;
    if (++i < t->n && (t->s[i] == '+' || t->s[i] == '-')) neg = t->s[i++] == '-';
    for (; i < t->n && t->s[i] >= '0' && t->s[i] <= '9'; i++)
        if (e < 1000) e = e * 10 + (t->s[i] - '0');
    return neg ? -e : e;
}

/* How far the value written as t may be from the one meant: half a unit in
 * its last decimal place. */
static double written_quantum(const tok *t)
{
    long decimals = 0, exp10 = 0;
    size_t i = 0;
    while (i < t->n && t->s[i] != '.' && t->s[i] != 'e' && t->s[i] != 'E') i++;
    if (i < t->n && t->s[i] == '.')
        for (i++; i < t->n && t->s[i] >= '0' && t->s[i] <= '9'; i++) decimals++;
    if (i < t->n && (t->s[i] == 'e' || t->s[i] == 'E')) exp10 = written_exponent(t, i);
    double e = (double)exp10 - (double)decimals;
    return 0.5 * pow(10, e > 300 ? 300 : e < -300 ? -300 : e);
}

/* Token t as a finite number; *q (may be NULL) grows to its quantum. */
static int number(rd *r, const line *l, const tok *t, double *x, double *q)
{
    char b[64];
    int rc = lam_parse_number(t->s, t->n, x);
    if (rc == LAM_ENOMEM) return nomem(r);
    if (rc) return fail_at(r, LAM_ESYNTAX, l->no, t->col, "%s is not a number", shown(b, sizeof b, t));
    if (!isfinite(*x)) return fail_at(r, LAM_EINVAL, l->no, t->col, "%s is not a finite number", shown(b, sizeof b, t));
    if (q) {
        double w = written_quantum(t);
        if (w > *q) *q = w;
    }
    return LAM_OK;
}

/* Token t as a whole number in [lo, hi]. */
static int whole(rd *r, const line *l, const tok *t, double lo, double hi, const char *what, long *out)
{
    double x;
    int rc = number(r, l, t, &x, NULL);
    if (rc) return rc;
    if (x != floor(x) || x < lo || x > hi)
        return fail_at(r, LAM_EINVAL, l->no, t->col, "%s must be a whole number from %.0f to %.0f, got %s", what, lo,
                       hi, LAM_NUM_EXACT(x));
    *out = (long)x;
    return LAM_OK;
}

/* Past the end of the last line: where "the file ends" is reported. */
static void at_end(const rd *r, long *lineno, long *col)
{
    size_t a = r->n;
    while (a > 0 && r->s[a - 1] != '\n') a--;
    *lineno = r->lineno + (r->n > 0 && r->s[r->n - 1] == '\n');
    *col = r->n > 0 && r->s[r->n - 1] == '\n' ? 1 : (long)(r->n - a) + 1;
}

/* The next line that is not blank, with its first token; 0 at the end. */
static int next_statement(rd *r, line *l, tok *t, size_t *i)
{
    while (next_line(r, l)) {
        *i = 0;
        if (next_tok(l, i, 0, t)) return 1;
    }
    return 0;
}

static int no_more(rd *r, const line *l, size_t i)
{
    tok t;
    char b[64];
    if (next_tok(l, &i, 0, &t))
        return fail_at(r, LAM_ESYNTAX, l->no, t.col, "unexpected %s at the end of the line", shown(b, sizeof b, &t));
    return LAM_OK;
}

static int expect_more(rd *r, const char *what, const char *opened, long oline, long ocol)
{
    long el, ec;
    at_end(r, &el, &ec);
    return fail_at(r, LAM_ESYNTAX, el, ec, "the file ends where %s was expected (in the %s at %ld:%ld)", what, opened,
                   oline, ocol);
}

/* One SLS loop after its "loop N" line. */
static int sls_loop(rd *r, double z, const line *head, const tok *kw, long id)
{
    size_t i = (size_t)(kw->col - 1) + kw->n;
    tok t;
    long npts = 0;
    if (!next_tok(head, &i, 0, &t))
        return fail_at(r, LAM_ESYNTAX, head->no, kw->col + (long)kw->n, "'loop' needs its number of points");
    int rc = whole(r, head, &t, 3, 1e9, "a loop's number of points (at least 3)", &npts);
    if (rc || (rc = no_more(r, head, i))) return rc;
    if ((rc = add_contour(r, z, -1, id, head->no, kw->col, -1))) return rc;
    for (long k = 0; k < npts; k++) {
        line l;
        if (!next_line(r, &l)) return expect_more(r, "a vertex", "loop", head->no, kw->col);
        double c[3];
        size_t j = 0;
        for (int a = 0; a < 3; a++) {
            if (!next_tok(&l, &j, 0, &t)) {
                char b[80];
                snprintf(b, sizeof b, "vertex %ld of %ld needs 3 coordinates (x y z)", k + 1, npts);
                return fail_at(r, LAM_ESYNTAX, l.no, (long)j + 1, "%s", b);
            }
            if ((rc = number(r, &l, &t, &c[a], &r->p->quantum_xy))) return rc;
        }
        if ((rc = no_more(r, &l, j)) || (rc = add_point(r, c[0], c[1], c[2]))) return rc;
        r->p->contours[r->p->ncontours - 1].n++;
    }
    line l;
    size_t j;
    if (!next_statement(r, &l, &t, &j)) return expect_more(r, "'endloop'", "loop", head->no, kw->col);
    char b[64];
    if (!tok_is(&t, "endloop"))
        return fail_at(r, LAM_ESYNTAX, l.no, t.col, "expected 'endloop' after %ld vertices, got %s", npts,
                       shown(b, sizeof b, &t));
    return no_more(r, &l, j);
}

static int read_sls(rd *r)
{
    line l;
    tok t;
    size_t i;
    long loops = 0;
    char b[64];
    int recognised = 0; /* a first statement of the dialect was read */
    while (next_statement(r, &l, &t, &i)) {
        if (tok_is(&t, "hatches")) {
            recognised = 1;
            /* a block of hatch vectors (not contours): read over to endhatches */
            long hline = l.no, hcol = t.col;
            do {
                if (!next_statement(r, &l, &t, &i)) return expect_more(r, "'endhatches'", "hatches", hline, hcol);
            } while (!tok_is(&t, "endhatches"));
            continue;
        }
        if (!tok_is(&t, "contour") && !recognised)
            /* not the dialect at all (any other file given as --program):
             * nothing of it is quoted, it may be anything */
            return fail_at(r, LAM_ESYNTAX, l.no, t.col,
                           "not a program lamina reads: expected 'contour' (sls-contours), $$HEADERSTART (CLI) "
                           "or '{' (a run's JSON)");
        if (!tok_is(&t, "contour"))
            return fail_at(r, LAM_ESYNTAX, l.no, t.col, "expected 'contour', got %s", shown(b, sizeof b, &t));
        recognised = 1;
        long cline = l.no, ccol = t.col;
        tok zt;
        double z;
        if (!next_tok(&l, &i, 0, &zt))
            return fail_at(r, LAM_ESYNTAX, l.no, t.col + (long)t.n, "'contour' needs its height");
        int rc = number(r, &l, &zt, &z, &r->p->quantum_z);
        if (rc || (rc = no_more(r, &l, i))) return rc;
        for (;;) {
            if (!next_statement(r, &l, &t, &i)) return expect_more(r, "'loop' or 'endcontour'", "contour", cline, ccol);
            if (tok_is(&t, "endcontour")) {
                if ((rc = no_more(r, &l, i))) return rc;
                break;
            }
            if (!tok_is(&t, "loop"))
                return fail_at(r, LAM_ESYNTAX, l.no, t.col, "expected 'loop' or 'endcontour', got %s",
                               shown(b, sizeof b, &t));
            if ((rc = sls_loop(r, z, &l, &t, ++loops))) return rc;
        }
    }
    return LAM_OK;
}

/* ---- CLI header ------------------------------------------------------------------- */

typedef struct cli_header {
    long layers;             /* $$LAYERS, -1 when absent */
    long layers_line, layers_col;
    int binary;
} cli_header;

/* "$$NAME/args" or "$$NAME": the name as a token and the arguments' start. */
static int cli_command(const line *l, tok *name, size_t *args)
{
    size_t i = 0;
    while (i < l->n && is_space(l->s[i])) i++;
    if (i + 2 > l->n || l->s[i] != '$' || l->s[i + 1] != '$') return 0;
    size_t a = i;
    i += 2;
    while (i < l->n && l->s[i] != '/' && !is_space(l->s[i])) i++;
    name->s = l->s + a;
    name->n = i - a;
    name->col = (long)a + 1;
    *args = i < l->n && l->s[i] == '/' ? i + 1 : i;
    return 1;
}

static int comment_or_blank(const line *l)
{
    size_t i = 0;
    while (i < l->n && is_space(l->s[i])) i++;
    return i == l->n || (i + 1 < l->n && l->s[i] == '/' && l->s[i + 1] == '/');
}

/* Header lines up to $$HEADEREND (which ends the text in a binary file). */
static int cli_read_header(rd *r, size_t end, cli_header *h)
{
    h->layers = -1;
    line l;
    tok name;
    size_t args;
    int started = 0;
    char b[64];
    while (r->pos < end && next_line(r, &l)) {
        if (l.s + l.n > r->s + end) l.n = (size_t)(r->s + end - l.s);
        if (comment_or_blank(&l)) continue;
        if (!cli_command(&l, &name, &args))
            return fail_at(r, LAM_ESYNTAX, l.no, 1, "expected a $$ header command");
        if (!started) {
            if (!tok_is(&name, "$$HEADERSTART"))
                return fail_at(r, LAM_ESYNTAX, l.no, name.col, "expected $$HEADERSTART, got %s",
                               shown(b, sizeof b, &name));
            started = 1;
        } else if (tok_is(&name, "$$HEADEREND")) {
            return LAM_OK;
        } else if (tok_is(&name, "$$BINARY")) {
            h->binary = 1;
        } else if (tok_is(&name, "$$LAYERS")) {
            tok t;
            size_t i = args;
            if (!next_tok(&l, &i, 0, &t)) return fail_at(r, LAM_ESYNTAX, l.no, (long)args + 1, "$$LAYERS needs a count");
            int rc = whole(r, &l, &t, 0, 1e12, "$$LAYERS", &h->layers);
            if (rc) return rc;
            h->layers_line = l.no;
            h->layers_col = t.col;
        } else if (tok_is(&name, "$$UNITS")) {
            tok t;
            size_t i = args;
            double u;
            if (!next_tok(&l, &i, 0, &t)) return fail_at(r, LAM_ESYNTAX, l.no, (long)args + 1, "$$UNITS needs a value");
            int rc = number(r, &l, &t, &u, NULL);
            if (rc) return rc;
            if (!(u > 0)) return fail_at(r, LAM_EINVAL, l.no, t.col, "$$UNITS must be greater than 0, got %s",
                                           LAM_NUM_EXACT(u));
            r->p->units_mm = u;
            r->p->units_line = l.no;
            r->p->units_column = t.col;
        }
        /* $$ASCII, $$VERSION, $$DATE, $$DIMENSION, $$LABEL, $$USERDATA, ...: read over */
    }
    long el, ec;
    at_end(r, &el, &ec);
    return fail_at(r, LAM_ESYNTAX, el, ec, started ? "the file ends before $$HEADEREND" : "no $$HEADERSTART");
}

static int cli_layer_count(rd *r, const cli_header *h)
{
    if (h->layers >= 0 && (size_t)h->layers != r->p->nlayers)
        return fail_at(r, LAM_EINVAL, h->layers_line, h->layers_col, "$$LAYERS says %ld layers but the file has %zu",
                       h->layers, r->p->nlayers);
    return LAM_OK;
}

/* Drop the closing repeat of the polyline just read; an open one is not a
 * contour. */
static int close_polyline(rd *r, long lineno, long col, size_t offset)
{
    lam_program *p = r->p;
    lam_program_contour *c = &p->contours[p->ncontours - 1];
    /* (no point arithmetic before the count is known: with no points at
     * all, xyz may still be NULL) */
    const double *a = c->n ? p->xyz + 3 * c->first : NULL, *z = c->n ? a + 3 * (c->n - 1) : NULL;
    if (c->n < 4 || a[0] != z[0] || a[1] != z[1]) {
        const char *why = c->n < 4 ? "a closed polyline needs at least 4 points (3 and the first again)"
                                   : "the polyline is not closed (its last point is not its first)";
        return lineno ? fail_at(r, LAM_EINVAL, lineno, col, "%s", why) : fail_byte(r, LAM_EINVAL, offset, "%s", why);
    }
    c->n--;
    p->npoints--;
    return LAM_OK;
}

/* ---- CLI ASCII --------------------------------------------------------------------- */

/* "$$POLYLINE/id,dir,n,x1,y1,...": fields split at commas. */
static int cli_polyline(rd *r, const line *l, const tok *name, size_t args, int have_layer, double z)
{
    char b[64];
    if (!have_layer) return fail_at(r, LAM_ESYNTAX, l->no, name->col, "$$POLYLINE before the first $$LAYER");
    size_t i = args;
    long head[3] = { 0, 0, 0 };
    static const char *const what[3] = { "the polyline's id", "the polyline's direction", "the polyline's count" };
    static const double hi[3] = { 2147483647.0, 2, 1e9 };
    tok t;
    for (int k = 0; k < 3; k++) {
        if (k && (i >= l->n || l->s[i] != ','))
            return fail_at(r, LAM_ESYNTAX, l->no, (long)i + 1, "expected ',' and %s", what[k]);
        if (k) i++;
        if (!next_tok(l, &i, ',', &t)) return fail_at(r, LAM_ESYNTAX, l->no, (long)i + 1, "expected %s", what[k]);
        int rc = whole(r, l, &t, k == 0 ? -2147483648.0 : 0, hi[k], what[k], &head[k]);
        if (rc) return rc;
        while (i < l->n && is_space(l->s[i])) i++;
    }
    if (head[1] == 2)
        return fail_at(r, LAM_EINVAL, l->no, name->col, "an open polyline (direction 2) is not a contour");
    int rc = add_contour(r, z, (int)head[1], head[0], l->no, name->col, -1);
    if (rc) return rc;
    for (long k = 0; k < head[2]; k++) {
        double c[2];
        for (int a = 0; a < 2; a++) {
            if (i >= l->n || l->s[i] != ',')
                return fail_at(r, LAM_ESYNTAX, l->no, (long)i + 1, "expected %ld points, found %ld", head[2], k);
            i++;
            if (!next_tok(l, &i, ',', &t))
                return fail_at(r, LAM_ESYNTAX, l->no, (long)i + 1, "expected %ld points, found %ld", head[2], k);
            if ((rc = number(r, l, &t, &c[a], &r->p->quantum_xy))) return rc;
            while (i < l->n && is_space(l->s[i])) i++;
        }
        if ((rc = add_point(r, c[0], c[1], z))) return rc;
        r->p->contours[r->p->ncontours - 1].n++;
    }
    if (i < l->n) {
        tok extra = { l->s + i, l->n - i, (long)i + 1 };
        return fail_at(r, LAM_ESYNTAX, l->no, extra.col, "more than %ld points: %s", head[2],
                       shown(b, sizeof b, &extra));
    }
    return close_polyline(r, l->no, name->col, 0);
}

static int read_cli_ascii(rd *r)
{
    cli_header h = { 0 };
    int rc = cli_read_header(r, r->n, &h);
    if (rc) return rc;
    line l;
    tok name;
    size_t args;
    int geometry = 0, have_layer = 0, ended = 0;
    double z = 0;
    char b[64];
    while (next_line(r, &l)) {
        if (comment_or_blank(&l)) continue;
        if (ended || !cli_command(&l, &name, &args)) {
            size_t i = 0;
            tok t;
            next_tok(&l, &i, 0, &t);
            return fail_at(r, LAM_ESYNTAX, l.no, t.col, ended ? "%s after $$GEOMETRYEND" : "expected a $$ command, got %s",
                           shown(b, sizeof b, &t));
        }
        if (!geometry) {
            if (!tok_is(&name, "$$GEOMETRYSTART"))
                return fail_at(r, LAM_ESYNTAX, l.no, name.col, "expected $$GEOMETRYSTART, got %s",
                               shown(b, sizeof b, &name));
            geometry = 1;
        } else if (tok_is(&name, "$$GEOMETRYEND")) {
            ended = 1;
        } else if (tok_is(&name, "$$LAYER")) {
            tok t;
            size_t i = args;
            if (!next_tok(&l, &i, 0, &t)) return fail_at(r, LAM_ESYNTAX, l.no, (long)args + 1, "$$LAYER needs a height");
            if ((rc = number(r, &l, &t, &z, &r->p->quantum_z)) || (rc = no_more(r, &l, i))) return rc;
            have_layer = 1;
            /* a layer with no polyline is still a layer */
            lam_program *p = r->p;
            if (grow((void **)&p->layers, &r->cap_layers, p->nlayers + 1, sizeof *p->layers)) return nomem(r);
            p->layers[p->nlayers++] = (lam_program_layer){ z, p->ncontours, 0, l.no, name.col, -1, NAN, NAN };
        } else if (tok_is(&name, "$$POLYLINE")) {
            if ((rc = cli_polyline(r, &l, &name, args, have_layer, z))) return rc;
        } else if (!tok_is(&name, "$$HATCHES")) {
            return fail_at(r, LAM_ESYNTAX, l.no, name.col, "unknown command %s", shown(b, sizeof b, &name));
        }
    }
    if (!ended) {
        long el, ec;
        at_end(r, &el, &ec);
        return fail_at(r, LAM_ESYNTAX, el, ec, geometry ? "the file ends before $$GEOMETRYEND" : "no $$GEOMETRYSTART");
    }
    return cli_layer_count(r, &h);
}

/* ---- CLI binary -------------------------------------------------------------------- */

static uint32_t rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static unsigned rd_u16(const unsigned char *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }

static double rd_f32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static int32_t rd_i32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    return u <= INT32_MAX ? (int32_t)u : (int32_t)(u - INT32_MAX - 1) + INT32_MIN;
}

static int read_cli_binary(rd *r, size_t data)
{
    cli_header h = { 0 };
    int rc = cli_read_header(r, data, &h);
    if (rc) return rc;
    lam_program *p = r->p;
    size_t at = data;
    double z = 0, maxz = 0, maxxy = 0;
    int have_layer = 0;
    while (at < r->n) {
        size_t cmd_at = at;
        if (r->n - at < 2) return fail_byte(r, LAM_ESYNTAX, at, "a command id cut short by the end of the file");
        unsigned cmd = rd_u16(r->s + at);
        at += 2;
        /* CLI 2.0: 127 layer, 130 polyline, 132 hatches long (int32/float32);
         * 128, 129, 131 their short forms (uint16) */
        int longform = cmd == 127 || cmd == 130 || cmd == 132;
        size_t w = longform ? 4 : 2;
        if (cmd == 127 || cmd == 128) {
            if (r->n - at < w) return fail_byte(r, LAM_ESYNTAX, cmd_at, "a layer command cut short by the end of the file");
            z = longform ? rd_f32(r->s + at) : rd_u16(r->s + at);
            if (!isfinite(z)) return fail_byte(r, LAM_EINVAL, at, "the layer's height is not a finite number");
            at += w;
            if (fabs(z) > maxz) maxz = fabs(z);
            have_layer = 1;
            if (grow((void **)&p->layers, &r->cap_layers, p->nlayers + 1, sizeof *p->layers)) return nomem(r);
            p->layers[p->nlayers++] = (lam_program_layer){ z, p->ncontours, 0, 0, 0, (long long)cmd_at, NAN, NAN };
        } else if (cmd == 129 || cmd == 130 || cmd == 131 || cmd == 132) {
            int hatches = cmd >= 131;
            size_t nhead = hatches ? 2 : 3;
            if (r->n - at < nhead * w)
                return fail_byte(r, LAM_ESYNTAX, cmd_at, "a %s command cut short by the end of the file",
                                 hatches ? "hatches" : "polyline");
            long v[3];
            for (size_t k = 0; k < nhead; k++) v[k] = longform ? rd_i32(r->s + at + k * w) : (long)rd_u16(r->s + at + k * w);
            at += nhead * w;
            long count = v[nhead - 1];
            size_t per = (hatches ? 4 : 2) * w;
            if (count < 0 || (size_t)count > (r->n - at) / per)
                return fail_byte(r, LAM_ESYNTAX, cmd_at, "%s of %ld %s does not fit in the rest of the file",
                                 hatches ? "hatches" : "a polyline", count, hatches ? "lines" : "points");
            if (hatches) {
                at += (size_t)count * per;
                continue;
            }
            if (!have_layer) return fail_byte(r, LAM_ESYNTAX, cmd_at, "a polyline before the first layer");
            if (v[1] == 2) return fail_byte(r, LAM_EINVAL, cmd_at, "an open polyline (direction 2) is not a contour");
            if (v[1] != 0 && v[1] != 1)
                return fail_byte(r, LAM_EINVAL, cmd_at, "a polyline's direction must be 0, 1 or 2, got %ld", v[1]);
            if ((rc = add_contour(r, z, (int)v[1], v[0], 0, 0, (long long)cmd_at))) return rc;
            for (long k = 0; k < count; k++, at += 2 * w) {
                double x = longform ? rd_f32(r->s + at) : rd_u16(r->s + at);
                double y = longform ? rd_f32(r->s + at + w) : rd_u16(r->s + at + w);
                if (!isfinite(x) || !isfinite(y))
                    return fail_byte(r, LAM_EINVAL, at, "point %ld of the polyline is not finite", k + 1);
                maxxy = fmax(maxxy, fmax(fabs(x), fabs(y)));
                if ((rc = add_point(r, x, y, z))) return rc;
                p->contours[p->ncontours - 1].n++;
            }
            if ((rc = close_polyline(r, 0, 0, cmd_at))) return rc;
            if (!longform) p->quantum_xy = fmax(p->quantum_xy, 0.5);
        } else {
            return fail_byte(r, LAM_ESYNTAX, cmd_at, "unknown CLI command %u", cmd);
        }
    }
    /* float32 keeps 24 bits: half an ulp is at most 2^-24 of the value */
    p->quantum_xy = fmax(p->quantum_xy, ldexp(maxxy, -24));
    p->quantum_z = fmax(p->quantum_z, ldexp(maxz, -24));
    return cli_layer_count(r, &h);
}

/* ---- the program ------------------------------------------------------------------- */

const char *lam_program_format_name(lam_program_format f)
{
    switch (f) {
    case LAM_PROGRAM_SLS: return "sls-contours";
    case LAM_PROGRAM_CLI_ASCII: return "cli-ascii";
    case LAM_PROGRAM_CLI_BINARY: return "cli-binary";
    case LAM_PROGRAM_JSON: return "lamina-run";
    }
    return "?";
}

static const unsigned char *find(const unsigned char *s, size_t n, const char *w)
{
    size_t k = strlen(w);
    for (size_t i = 0; i + k <= n; i++)
        if (s[i] == (unsigned char)w[0] && !memcmp(s + i, w, k)) return s + i;
    return NULL;
}

int lam_program_read_buf(const char *path, const unsigned char *data, size_t len, lam_program **out, lam_error *err)
{
    *out = NULL;
    rd r;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.s = data;
    r.n = len;
    r.err = err;
    r.p = calloc(1, sizeof *r.p);
    if (!r.p) return nomem(&r);
    size_t i = 0;
    while (i < len && (is_space(data[i]) || data[i] == '\n')) i++;
    int rc;
    if (i < len && data[i] == '{') {
        rc = lam_program_read_json(path, data, len, r.p, err);
    } else if (len - i >= 13 && !memcmp(data + i, "$$HEADERSTART", 13)) {
        const unsigned char *end = find(data, len, "$$HEADEREND");
        const unsigned char *bin = end ? find(data, (size_t)(end - data), "$$BINARY") : NULL;
        if (bin) {
            r.p->format = LAM_PROGRAM_CLI_BINARY;
            rc = read_cli_binary(&r, (size_t)(end - data) + strlen("$$HEADEREND"));
        } else {
            r.p->format = LAM_PROGRAM_CLI_ASCII;
            rc = read_cli_ascii(&r);
        }
    } else {
        r.p->format = LAM_PROGRAM_SLS;
        rc = read_sls(&r);
    }
    if (rc) {
        lam_program_free(r.p);
        return rc;
    }
    *out = r.p;
    return LAM_OK;
}

int lam_program_read(const char *path, lam_program **out, lam_error *err)
{
    *out = NULL;
    char *data;
    size_t len;
    lam_read_limit limit = lam_model_limit(); /* programs are read back as large as models */
    limit.what = "a program";
    int rc = lam_read_file(path, limit, &data, &len, err);
    if (rc) return rc;
    rc = lam_program_read_buf(path, (const unsigned char *)data, len, out, err);
    free(data);
    return rc;
}

void lam_program_scale(lam_program *p, double k)
{
    for (size_t i = 0; i < 3 * p->npoints; i++) p->xyz[i] *= k;
    for (size_t i = 0; i < p->nlayers; i++) p->layers[i].z *= k;
    p->quantum_xy *= k;
    p->quantum_z *= k;
}

void lam_program_free(lam_program *p)
{
    if (!p) return;
    free(p->xyz);
    free(p->contours);
    free(p->layers);
    free(p);
}

/* ---- as layers ----------------------------------------------------------------------- */

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

int lam_program_layer_make(const lam_program *p, size_t i, const lam_frame *f, int frame_machine, const char *path,
                           lam_layer *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    const lam_program_layer *pl = &p->layers[i];
    /* a layer with no contour may come before any: contours still NULL */
    const lam_program_contour *pc = pl->n ? p->contours + pl->first : NULL;
    size_t np = 0;
    for (size_t k = 0; k < pl->n; k++) np += pc[k].n;
    out->index = i;
    out->cut = out->floor = out->ceiling = pl->z;
    out->uv = malloc((2 * np + 1) * sizeof *out->uv);
    out->contours = calloc(pl->n + 1, sizeof *out->contours);
    if (!out->uv || !out->contours) {
        lam_layer_clear(out);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory reading the program's layers");
    }
    /* a point may be off its plane by the precision of its coordinates and
     * of the height, and by the rounding of the projection */
    double slack = 4 * (p->quantum_xy + p->quantum_z) + 64 * 2.220446049250313e-16 * fabs(pl->z);
    for (size_t k = 0; k < pl->n; k++) {
        lam_contour *c = &out->contours[k];
        c->first = out->npoints;
        c->n = pc[k].n;
        c->depth = -1;
        c->parent = -1;
        for (size_t j = 0; j < pc[k].n; j++) {
            const double *q = p->xyz + 3 * (pc[k].first + j);
            double *uv = out->uv + 2 * out->npoints++;
            double w;
            if (p->format != LAM_PROGRAM_SLS || frame_machine) {
                uv[0] = q[0];
                uv[1] = q[1];
                w = q[2];
            } else {
                uv[0] = dot3(q, f->u);
                uv[1] = dot3(q, f->v);
                w = dot3(q, f->w);
            }
            if (fabs(w - pl->z) > slack) {
                /* (only SLS points can be: CLI writes the layer's height for them) */
                char a[LAM_FMT_NUM], b[LAM_FMT_NUM];
                lam_fmt_pair(a, b, w, pl->z);
                int rc = lam_error_set(err, LAM_EINVAL, path, pc[k].line, pc[k].column,
                                       "point %zu of this loop is %g from its plane (height %s along the "
                                       "slicing axis, the contour says %s): was it written along another "
                                       "axis, or in the %s frame?",
                                       j + 1, fabs(w - pl->z), a, b, frame_machine ? "model" : "machine");
                lam_layer_clear(out);
                return rc;
            }
        }
        double a = lam_section_loop_area(out->uv + 2 * c->first, c->n);
        c->area = a;
        c->kind = pc[k].dir == 0 || (pc[k].dir < 0 && a < 0) ? LAM_HOLE : LAM_SOLID;
        double *bb = c->bbox;
        bb[0] = bb[1] = INFINITY;
        bb[2] = bb[3] = -INFINITY;
        for (size_t j = 0; j < c->n; j++) {
            const double *a0 = out->uv + 2 * (c->first + j), *a1 = out->uv + 2 * (c->first + (j + 1) % c->n);
            c->perimeter += hypot(a1[0] - a0[0], a1[1] - a0[1]);
            bb[0] = fmin(bb[0], a0[0]);
            bb[1] = fmin(bb[1], a0[1]);
            bb[2] = fmax(bb[2], a0[0]);
            bb[3] = fmax(bb[3], a0[1]);
        }
    }
    out->ncontours = pl->n;
    return LAM_OK;
}

void lam_layer_clear(lam_layer *L)
{
    free(L->uv);
    free(L->contours);
    free(L->open);
    memset(L, 0, sizeof *L);
}
