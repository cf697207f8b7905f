/* Machine profiles: YAML (libyaml's document API) to lam_profile, with
 * inheritance, strict types and positions on every error. See profile.h and
 * machines/README.md.
 *
 * A profile is data only. Explicit YAML tags other than the core schema's
 * (!!str !!int !!float !!bool !!null !!map !!seq) are refused outright, so
 * `!!python/object` and friends are just errors; nothing in a profile is
 * ever evaluated: templates are parsed into literal text and fields. */
#include "profile.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml.h>

#include "yaml_doc.h"

#include "file.h"
#include "fmt.h"
#include "lexnum.h"
#include "paths.h"
#include "profile_keys.h"
#include "slice.h"

#define MAX_CHAIN 32                 /* inherits depth */
#define MAX_DIRS 16

/* The keys are the rows of profile_keys.c; the loader keeps which rows
 * some file of the chain gave. */
static size_t key_index(const lam_key *k) { return (size_t)(k - lam_profile_keys); }

/* The row named exactly `name` or by its alias (no flat short names here:
 * a YAML key is written where it lives). */
static const lam_key *exact_key(const char *name)
{
    const lam_key *k = lam_key_find(name);
    return k && (!strcmp(k->name, name) || (k->alias && !strcmp(k->alias, name))) ? k : NULL;
}

/* The loader's own row (inherits). */
static const lam_key *inherits_key(void)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (lam_profile_keys[i].flags & LAM_KEY_LOADER) return &lam_profile_keys[i];
    return NULL;
}

/* ---- one source file ---------------------------------------------------- */

/* The file being read: one YAML document (yaml_doc.h). */
typedef lam_yaml_doc src;

/* The loader's state across an inherits chain. */
typedef struct ldr {
    lam_profile *p;
    unsigned char set[LAM_KEYS_MAX]; /* rows given by some file of the chain */
    int templates_given;     /* a section of templates (dialect:) was given */
    lam_error *err;
    dev_t dev[MAX_CHAIN];    /* identity of the files being loaded */
    ino_t ino[MAX_CHAIN];
    const char *given[MAX_CHAIN];
    size_t depth;
} ldr;

#define at lam_yaml_at

static int oom_err(lam_error *err)
{
    return lam_error_nomem(err, NULL);
}
#define oom() oom_err(s->err)

static int read_all(src *s, const char *path, char **text, size_t *len)
{
    const lam_read_limit limit = { LAM_MAX_PROFILE_BYTES, "a machine profile", NULL };
    return lam_read_file(path, limit, text, len, s->err);
}

/* Byte offset where 0-based line `line` starts, or -1. */
static long line_start(const src *s, size_t line)
{
    size_t i = 0;
    if (s->len >= 3 && memcmp(s->text, "\xEF\xBB\xBF", 3) == 0) i = 3;
    for (size_t l = 0; l < line; l++) {
        const char *nl = memchr(s->text + i, '\n', s->len - i);
        if (!nl) return -1;
        i = (size_t)(nl - s->text) + 1;
    }
    return (long)i;
}

static int is_cont(unsigned char c) { return (c & 0xC0) == 0x80; }

/* Byte offset of character column col (0-based) of the line at ls, or -1. */
static long char_at(const src *s, long ls, size_t col)
{
    size_t i = (size_t)ls;
    for (size_t c = 0; c < col; c++) {
        if (i >= s->len || s->text[i] == '\n') return -1;
        i++;
        while (i < s->len && is_cont((unsigned char)s->text[i])) i++;
    }
    return (long)i;
}

/* 0-based character column of byte offset pos on the line at ls. */
static long col_of(const src *s, long ls, long pos)
{
    long c = 0;
    for (long i = ls; i < pos; i++)
        if (!is_cont((unsigned char)s->text[i])) c++;
    return c;
}

static int hexval(const char *t, size_t n, unsigned long *cp)
{
    *cp = 0;
    for (size_t i = 0; i < n; i++) {
        char c = t[i];
        int d = c >= '0' && c <= '9'   ? c - '0'
                : c >= 'a' && c <= 'f' ? c - 'a' + 10
                : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                       : -1;
        if (d < 0) return 0;
        *cp = *cp * 16 + (unsigned long)d;
    }
    return 1;
}

/* Where byte `off` of a double-quoted scalar's value v is in the text
 * t[0..L), its content starting at q: the position, -1 when the text does
 * not read back as v; *verify = 0 when off falls in (or at) an escape,
 * whose bytes are not v's. */
static long double_quoted_at(const char *t, long L, long q, const char *v, size_t off, int *verify)
{
    size_t k = 0;
    while (k < off) {
        if (q >= L) return -1;
        if (t[q] == '\\') {
            if (q + 1 >= L) return -1;
            char e = t[q + 1];
            size_t rl = 2, dl = 1;
            unsigned long cp = 0;
            if (e == 'x' || e == 'u' || e == 'U') {
                size_t h = e == 'x' ? 2 : e == 'u' ? 4 : 8;
                if (q + 2 + (long)h > L || !hexval(t + q + 2, h, &cp)) return -1;
                rl = 2 + h;
                dl = cp < 0x80 ? 1 : cp < 0x800 ? 2 : cp < 0x10000 ? 3 : 4;
            } else if (e == 'N' || e == '_') {
                dl = 2;
            } else if (e == 'L' || e == 'P') {
                dl = 3;
            }
            if (k + dl > off) {
                *verify = 0; /* inside an escape: point at it */
                break;
            }
            k += dl;
            q += (long)rl;
        } else {
            if (t[q] != v[k]) return -1;
            q++;
            k++;
        }
    }
    if (q < L && t[q] == '\\') *verify = 0;
    return q;
}

/* scalar_pos for a literal block (`|`): the value's line `li` is text
 * line m.line + 1 + li at the block's indentation. */
static void literal_pos(const src *s, const yaml_node_t *n, size_t off, long *line, long *col)
{
    yaml_mark_t m = n->start_mark;
    const char *v = (const char *)n->data.scalar.value;
    size_t vlen = n->data.scalar.length;
    const char *t = s->text;
    long L = (long)s->len;
    size_t li = 0, lstart = 0;
    for (size_t k = 0; k < off; k++)
        if (v[k] == '\n') {
            li++;
            lstart = k + 1;
        }
    /* indentation: that of the first content line that is not blank */
    long indent = -1;
    for (size_t l = m.line + 1;; l++) {
        long a = line_start(s, l);
        if (a < 0) return;
        long b = a;
        while (b < L && t[b] == ' ') b++;
        if (b < L && t[b] != '\n' && t[b] != '\r') {
            indent = b - a;
            break;
        }
    }
    size_t tline = m.line + 1 + li;
    long qline = line_start(s, tline);
    if (qline < 0 || indent < 0) return;
    long q = qline + indent + (long)(off - lstart);
    if (q > L || memcmp(t + qline + indent, v + lstart, off - lstart) != 0) return;
    *line = (long)tline + 1;
    *col = col_of(s, qline, q) + 1;
    if (off < vlen && (q >= L || t[q] != v[off])) {
        *line = (long)m.line + 1;
        *col = (long)m.column + 1;
    }
}

/* Position (1-based line, column) in the file of byte `off` of scalar n's
 * value: exact for single-line plain and quoted scalars and for literal
 * blocks, checked against the raw text; otherwise the scalar's start. */
static void scalar_pos(const src *s, const yaml_node_t *n, size_t off, long *line, long *col)
{
    yaml_mark_t m = n->start_mark;
    *line = (long)m.line + 1;
    *col = (long)m.column + 1;
    const char *v = (const char *)n->data.scalar.value;
    size_t vlen = n->data.scalar.length;
    if (off > vlen) return;
    long ls = line_start(s, m.line);
    if (ls < 0) return;
    long p = char_at(s, ls, m.column);
    if (p < 0) return;
    const char *t = s->text;
    long L = (long)s->len, q = -1, qline = ls;
    size_t tline = m.line;
    int single_line = n->end_mark.line == m.line;
    int verify = 1;
    switch (n->data.scalar.style) {
    case YAML_PLAIN_SCALAR_STYLE:
        if (!single_line || p + (long)off > L || memcmp(t + p, v, off) != 0) return;
        q = p + (long)off;
        break;
    case YAML_SINGLE_QUOTED_SCALAR_STYLE:
        if (!single_line || t[p] != '\'') return;
        q = p + 1;
        for (size_t k = 0; k < off; k++) {
            if (q >= L) return;
            if (v[k] == '\'') {
                if (q + 1 >= L || t[q] != '\'' || t[q + 1] != '\'') return;
                q += 2;
            } else {
                if (t[q] != v[k]) return;
                q++;
            }
        }
        break;
    case YAML_DOUBLE_QUOTED_SCALAR_STYLE:
        if (!single_line || t[p] != '"' || (q = double_quoted_at(t, L, p + 1, v, off, &verify)) < 0) return;
        break;
    case YAML_LITERAL_SCALAR_STYLE:
        literal_pos(s, n, off, line, col);
        return;
    default:
        return;
    }
    if (verify && off < vlen && (q >= L || (t[q] != v[off] && !(v[off] == '\'' && t[q] == '\'')))) return;
    *line = (long)tline + 1;
    *col = col_of(s, qline, q) + 1;
}

/* ---- node helpers -------------------------------------------------------- */

static yaml_node_t *node(const src *s, int id)
{
    return yaml_document_get_node((yaml_document_t *)&s->doc, id);
}

#define is_null lam_yaml_is_null

/* "a mapping", "a list", "null", "'text'" for messages. */
static const char *describe(const yaml_node_t *n, char *buf, size_t size)
{
    if (n->type == YAML_MAPPING_NODE) return "a mapping";
    if (n->type == YAML_SEQUENCE_NODE) return "a list";
    if (is_null(n)) return "null";
    lam_quote_bytes(buf, size, n->data.scalar.value, n->data.scalar.length);
    return buf;
}

/* "KEY must be WHAT, got GOT" at node n. */
static int at_key(const src *s, const yaml_node_t *n, const lam_key *k, const char *got)
{
    lam_error e;
    lam_key_expected(k, NULL, got, &e);
    return at(s, n->start_mark, LAM_EINVAL, "%s", e.msg);
}

static int want_scalar(const src *s, const yaml_node_t *n, const char *key, const char *what)
{
    char b[64];
    if (n->type != YAML_SCALAR_NODE || is_null(n))
        return at(s, n->start_mark, LAM_EINVAL, "%s must be %s, got %s", key, what, describe(n, b, sizeof b));
    return LAM_OK;
}

static int get_text(const src *s, const yaml_node_t *n, const char *key, char **out)
{
    int rc = want_scalar(s, n, key, "text");
    if (rc) return rc;
    if (strlen((const char *)n->data.scalar.value) != n->data.scalar.length)
        return at(s, n->start_mark, LAM_EINVAL, "%s contains a NUL character", key);
    char *copy = strdup((const char *)n->data.scalar.value);
    if (!copy) return oom();
    free(*out);
    *out = copy;
    return LAM_OK;
}

/* The names a mapping may hold: at the top level ("" section) the keys
 * without a section and the sections' names, in a section its keys' short
 * names; in table order. */
typedef struct keyset {
    const char *names[LAM_KEYS_MAX];
    char sections[16][32];
    size_t n, nsec;
} keyset;

static void keys_in(const char *section, keyset *ks)
{
    ks->n = ks->nsec = 0;
    size_t sl = strlen(section);
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        size_t kl = lam_key_section_len(k);
        if (sl) {
            if (kl == sl && !strncmp(k->name, section, sl)) ks->names[ks->n++] = lam_key_short(k);
        } else if (!kl) {
            ks->names[ks->n++] = k->name;
            if (k->alias) ks->names[ks->n++] = k->alias; /* the table has no alias in a section */
        } else if (!ks->nsec || strncmp(ks->sections[ks->nsec - 1], k->name, kl) != 0 ||
                   ks->sections[ks->nsec - 1][kl] != '\0') {
            if (ks->nsec == 16 || kl >= 32) continue; /* the unit test keeps the table within these */
            memcpy(ks->sections[ks->nsec], k->name, kl);
            ks->sections[ks->nsec][kl] = '\0';
            ks->names[ks->n++] = ks->sections[ks->nsec++];
        }
    }
}

/* Check the keys of mapping m: scalars, known (names[0..n)), no duplicates.
 * where: "" for the top level, else "raster" / "dialect". */
/* names, comma-separated, into out (size bytes, sized so the message
 * around it fits a lam_error): when they do not all fit, whole names only
 * and "and N more (lamina machines --keys)", never a name cut short. */
static void key_list(const char *const *names, size_t nn, char *out, size_t size)
{
    static const char more[] = ", and %zu more (lamina machines --keys)";
    size_t len = 0, j = 0;
    out[0] = '\0';
    for (; j < nn; j++) {
        size_t need = strlen(names[j]) + (j ? 2 : 0), room = size - len - 1;
        /* room for this name and, unless it is the last, the tail */
        if (need > room || (j + 1 < nn && need + sizeof more + 8 > room)) break;
        len += (size_t)snprintf(out + len, size - len, "%s%s", j ? ", " : "", names[j]);
    }
    if (j < nn) snprintf(out + len, size - len, more, nn - j);
}

static int check_keys(const src *s, const yaml_node_t *m, const char *where, const char *const *names, size_t nn)
{
    for (yaml_node_pair_t *pr = m->data.mapping.pairs.start; pr < m->data.mapping.pairs.top; pr++) {
        yaml_node_t *k = node(s, pr->key);
        char b[64];
        if (k->type != YAML_SCALAR_NODE || is_null(k))
            return at(s, k->start_mark, LAM_EINVAL, "keys must be text, got %s", describe(k, b, sizeof b));
        const char *key = (const char *)k->data.scalar.value;
        size_t i = 0;
        while (i < nn && strcmp(names[i], key) != 0) i++;
        if (i == nn) {
            char allowed[900];
            key_list(names, nn, allowed, sizeof allowed);
            const char *best = lam_key_nearest(key, names, nn);
            char hint[80] = "";
            if (best) snprintf(hint, sizeof hint, "did you mean '%s'? ", best);
            return at(s, k->start_mark, LAM_EINVAL, "unknown key %s%s%s (%sallowed: %s)", describe(k, b, sizeof b),
                      *where ? " in " : "", where, hint, allowed);
        }
        const lam_key *row = *where ? NULL : exact_key(key);
        for (yaml_node_pair_t *q = m->data.mapping.pairs.start; q < pr; q++) {
            yaml_node_t *k2 = node(s, q->key);
            const char *key2 = (const char *)k2->data.scalar.value;
            if (!strcmp(key2, key))
                return at(s, k->start_mark, LAM_EINVAL, "duplicate key '%s%s%s' (first given at line %lu)", where,
                          *where ? "." : "", key, (unsigned long)k2->start_mark.line + 1);
            if (row && exact_key(key2) == row) /* a key and its alias */
                return at(s, k->start_mark, LAM_EINVAL, "duplicate key '%s': %s is another name of %s (given at line %lu)",
                          key, row->alias, row->name, (unsigned long)k2->start_mark.line + 1);
        }
    }
    return LAM_OK;
}

/* Is m the top level of a profile: has it a key of one, or a near miss?
 * Until it has, it may be any file, and messages quote none of it. */
static int recognised(const src *s, const yaml_node_t *m)
{
    /* the top-level names: keys, and the sections' names */
    char tops[LAM_KEYS_MAX][32];
    const char *names[LAM_KEYS_MAX];
    size_t n = 0;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        size_t sl = lam_key_section_len(k);
        snprintf(tops[n], sizeof tops[n], "%.*s", (int)(sl ? sl : strlen(k->name)), k->name);
        names[n] = tops[n];
        n++;
    }
    for (yaml_node_pair_t *pr = m->data.mapping.pairs.start; pr < m->data.mapping.pairs.top; pr++) {
        yaml_node_t *k = node(s, pr->key);
        if (k->type != YAML_SCALAR_NODE || k->data.scalar.length < 3) continue;
        if (lam_key_nearest((const char *)k->data.scalar.value, names, n)) return 1;
    }
    return 0;
}

static const yaml_node_t *lookup(const src *s, const yaml_node_t *m, const char *key)
{
    for (yaml_node_pair_t *pr = m->data.mapping.pairs.start; pr < m->data.mapping.pairs.top; pr++) {
        yaml_node_t *k = node(s, pr->key);
        if (k->type == YAML_SCALAR_NODE && !strcmp((const char *)k->data.scalar.value, key)) return node(s, pr->value);
    }
    return NULL;
}

static int parse(src *s)
{
    return lam_yaml_doc_parse(s, "empty profile: expected a mapping of keys (name, process, ...)");
}

/* ---- apply keys --------------------------------------------------------- */

/* A dialect command's template (null: the command writes nothing). */
static int apply_template(const src *s, const lam_key *k, const yaml_node_t *v, lam_profile *p)
{
    char b[64];
    lam_template *t = (lam_template *)(void *)((char *)p + k->offset);
    if (is_null(v)) {
        lam_template_free(t);
        return LAM_OK;
    }
    if (v->type != YAML_SCALAR_NODE) return at_key(s, v, k, describe(v, b, sizeof b));
    size_t len = v->data.scalar.length;
    if (strlen((const char *)v->data.scalar.value) != len)
        return at(s, v->start_mark, LAM_EINVAL, "%s contains a NUL character", k->name);
    char *text = strdup((const char *)v->data.scalar.value);
    if (!text) return oom();
    /* a block scalar's final line break ends the template, it is not an
     * empty last line (`|` and `|-` mean the same here) */
    yaml_scalar_style_t style = v->data.scalar.style;
    int block = style == YAML_LITERAL_SCALAR_STYLE || style == YAML_FOLDED_SCALAR_STYLE;
    if (block && len && text[len - 1] == '\n') text[len - 1] = '\0';
    lam_template nt;
    size_t off = 0;
    int rc = lam_template_parse((lam_cmd)k->cmd, text, &nt, &off, s->err);
    free(text);
    if (rc == LAM_ENOMEM) return rc;
    if (rc) {
        char msg[sizeof s->err->msg];
        snprintf(msg, sizeof msg, "%s", s->err->msg);
        long line, col;
        scalar_pos(s, v, off, &line, &col);
        return lam_error_set(s->err, LAM_EINVAL, s->path, line, col, "%s: %s", k->name, msg);
    }
    lam_template_free(t);
    *t = nt;
    return LAM_OK;
}

/* The `count` numbers of sequence v (a list row's value, a laser's field)
 * into out; `name` says what it is in messages. */
static int read_numbers(const src *s, const yaml_node_t *v, const char *name, size_t count, double *out)
{
    char b[64];
    if (v->type != YAML_SEQUENCE_NODE)
        return at(s, v->start_mark, LAM_EINVAL, "%s must be a list of %zu numbers, got %s", name, count,
                  describe(v, b, sizeof b));
    size_t n = (size_t)(v->data.sequence.items.top - v->data.sequence.items.start);
    if (n != count)
        return at(s, v->start_mark, LAM_EINVAL, "%s must be a list of %zu numbers, got a list of %zu", name, count, n);
    for (size_t i = 0; i < n; i++) {
        const yaml_node_t *e = node(s, v->data.sequence.items.start[i]);
        int rc = LAM_EINVAL;
        /* "1" in quotes is text, as for a number key */
        if (e->type == YAML_SCALAR_NODE && !is_null(e) && e->data.scalar.style == YAML_PLAIN_SCALAR_STYLE)
            rc = lam_parse_number(e->data.scalar.value, e->data.scalar.length, &out[i]);
        if (rc == LAM_ENOMEM) return oom();
        if (rc)
            return at(s, e->start_mark, LAM_EINVAL, "%s must be a list of %zu numbers, got %s in it", name, count,
                      describe(e, b, sizeof b));
        if (!isfinite(out[i]))
            return at(s, e->start_mark, LAM_EINVAL, "%s must be finite numbers, got %s", name, describe(e, b, sizeof b));
    }
    return LAM_OK;
}

/* One laser of `lasers:`, a mapping {field: [x0, y0, x1, y1]}, into f. */
static int read_laser(const src *s, const yaml_node_t *m, double f[4])
{
    static const char *const names[] = { "field" };
    char b[64];
    if (m->type != YAML_MAPPING_NODE)
        return at(s, m->start_mark, LAM_EINVAL, "a laser must be a mapping {field: [x0, y0, x1, y1]}, got %s",
                  describe(m, b, sizeof b));
    int rc = check_keys(s, m, "lasers", names, 1);
    if (rc) return rc;
    const yaml_node_t *fv = lookup(s, m, "field");
    if (!fv) return at(s, m->start_mark, LAM_EINVAL, "a laser needs its field: {field: [x0, y0, x1, y1]}");
    if ((rc = read_numbers(s, fv, "a laser's field", 4, f))) return rc;
    lam_error e;
    if (lam_key_check_field(f, &e)) return at(s, fv->start_mark, LAM_EINVAL, "%s", e.msg);
    return LAM_OK;
}

/* A list row's value v (numbers, lasers) into p; p is unchanged on error. */
static int read_list(const src *s, const lam_key *k, const yaml_node_t *v, lam_profile *p)
{
    char b[64];
    double f[LAM_PROFILE_LASERS_MAX][4];
    if (k->type == LAM_KEY_NUMBERS) {
        if (k->count > 4 * LAM_PROFILE_LASERS_MAX) return at(s, v->start_mark, LAM_EINVAL, "%s: too many", k->name);
        int rc = read_numbers(s, v, k->name, k->count, f[0]);
        lam_error e;
        if (!rc && lam_key_check_numbers(k, NULL, f[0], k->count, &e)) rc = at(s, v->start_mark, LAM_EINVAL, "%s", e.msg);
        if (!rc) memcpy((char *)p + k->offset, f[0], k->count * sizeof f[0][0]);
        return rc;
    }
    if (v->type != YAML_SEQUENCE_NODE) return at_key(s, v, k, describe(v, b, sizeof b));
    size_t n = (size_t)(v->data.sequence.items.top - v->data.sequence.items.start);
    if (n < 1 || n > LAM_PROFILE_LASERS_MAX) {
        snprintf(b, sizeof b, n ? "a list of %zu" : "an empty list", n);
        return at_key(s, v, k, b);
    }
    for (size_t i = 0; i < n; i++) {
        int rc = read_laser(s, node(s, v->data.sequence.items.start[i]), f[i]);
        if (rc) return rc;
    }
    memcpy(p->laser_field, f, n * sizeof f[0]);
    p->nlasers = n;
    return LAM_OK;
}

/* The value v of row k into L's profile, with the row's checks. */
static int apply_value(ldr *L, const src *s, const lam_key *k, const yaml_node_t *v)
{
    lam_profile *p = L->p;
    char b[128];
    int rc;
    lam_error e;
    lam_error_clear(&e);
    if (k->type == LAM_KEY_NUMBERS || k->type == LAM_KEY_LASERS) {
        rc = read_list(s, k, v, p);
    } else if (k->type == LAM_KEY_TEMPLATE) {
        rc = apply_template(s, k, v, p);
    } else if (k->type == LAM_KEY_STRING) {
        char **field = (char **)(void *)((char *)p + k->offset);
        if (v->type != YAML_SCALAR_NODE || is_null(v)) return at_key(s, v, k, describe(v, b, sizeof b));
        if (!(rc = get_text(s, v, k->name, field)) && lam_key_check_text(k, *field, &e))
            rc = at(s, v->start_mark, LAM_EINVAL, "%s", e.msg);
    } else {
        if (v->type != YAML_SCALAR_NODE || is_null(v)) return at_key(s, v, k, describe(v, b, sizeof b));
        if (v->data.scalar.style != YAML_PLAIN_SCALAR_STYLE && k->type != LAM_KEY_CHOICE) {
            /* "0.08" and "true" in quotes are text, not a number or a boolean */
            char q[64];
            snprintf(b, sizeof b, "%s%s", k->type == LAM_KEY_BOOLEAN ? "" : "the quoted string ",
                     describe(v, q, sizeof q));
            return at_key(s, v, k, b);
        }
        double x;
        rc = lam_key_scan(k, NULL, (const char *)v->data.scalar.value, v->data.scalar.length, &x, &e);
        if (rc) return e.code == LAM_ENOMEM ? oom() : at(s, v->start_mark, e.code, "%s", e.msg);
        lam_key_store(p, k, x);
    }
    if (!rc) L->set[key_index(k)] = 1;
    return rc;
}

/* plate: (before its values, then after them) a file that gives a shape
 * replaces the shape it inherits, a round plate over a rectangular one or
 * the other way round; the plate it leaves must be one shape, whole. */
static int plate_shape(ldr *L, const src *s, const yaml_node_t *m, int after)
{
    const yaml_node_t *d = lookup(s, m, "diameter"), *w = lookup(s, m, "width"), *h = lookup(s, m, "depth");
    if (!after) {
        if (d) L->p->plate_width = L->p->plate_depth = 0;
        if (w || h) L->p->plate_diameter = 0;
        return LAM_OK;
    }
    lam_error e;
    if (!lam_profile_check_plate(L->p, &e)) return LAM_OK;
    return at(s, d && (w || h) ? d->start_mark : m->start_mark, LAM_EINVAL, "%s", e.msg);
}

/* A section's mapping (raster:, dialect:): its keys merge into the profile. */
static int apply_section(ldr *L, const src *s, const char *section, const yaml_node_t *m)
{
    keyset ks;
    keys_in(section, &ks);
    char b[64];
    if (m->type != YAML_MAPPING_NODE)
        return at(s, m->start_mark, LAM_EINVAL, "%s must be a mapping (%s, %s, ...), got %s", section, ks.names[0],
                  ks.n > 1 ? ks.names[1] : "", describe(m, b, sizeof b));
    int rc = check_keys(s, m, section, ks.names, ks.n);
    int plate = !strcmp(section, "plate");
    if (!rc && plate) plate_shape(L, s, m, 0);
    for (yaml_node_pair_t *pr = m->data.mapping.pairs.start; !rc && pr < m->data.mapping.pairs.top; pr++) {
        char full[128];
        snprintf(full, sizeof full, "%s.%s", section, (const char *)node(s, pr->key)->data.scalar.value);
        rc = apply_value(L, s, exact_key(full), node(s, pr->value));
    }
    /* `dialect: {}` gives a dialect that writes nothing */
    for (size_t i = 0; i < ks.n; i++) {
        char full[128];
        snprintf(full, sizeof full, "%s.%s", section, ks.names[i]);
        if (exact_key(full)->type == LAM_KEY_TEMPLATE) L->templates_given = 1;
    }
    if (!rc && plate) rc = plate_shape(L, s, m, 1);
    return rc;
}

static int apply(ldr *L, const src *s, const yaml_node_t *root)
{
    int rc = LAM_OK;
    for (yaml_node_pair_t *pr = root->data.mapping.pairs.start; !rc && pr < root->data.mapping.pairs.top; pr++) {
        const char *key = (const char *)node(s, pr->key)->data.scalar.value;
        const yaml_node_t *v = node(s, pr->value);
        const lam_key *k = exact_key(key);
        if (!k) rc = apply_section(L, s, key, v); /* check_keys let only rows and sections through */
        else if (!(k->flags & LAM_KEY_LOADER)) rc = apply_value(L, s, k, v); /* inherits: resolved before */
    }
    return rc;
}

/* ---- inherits ------------------------------------------------------------ */

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

static int is_path(const char *s)
{
    return strchr(s, '/') || ends_with(s, ".yaml") || ends_with(s, ".yml");
}

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

size_t lam_machine_dirs(char **dirs, size_t max)
{
    /* the build tree, then an installed tree: bin/lamina, lib/lua/5.4/lamina.so,
     * and a LuaRocks tree's lib/lua/5.4/lamina.so (its data goes with the Lua
     * modules, the only place a rock's files other than C modules are deployed) */
    static const char *const exe[] = { "../machines", "../share/lamina/machines", NULL };
    static const char *const module[] = { "../machines", "../../../share/lamina/machines",
                                          "../../../share/lua/5.4/lamina/machines", NULL };
    static const lam_rel_dirs rel = { exe, module };
    return lam_search_dirs("LAMINA_MACHINES", &rel, dirs, max);
}

/* NAME.yaml in the machine directories: a malloc'd path, or NULL with the
 * searched directories listed in `searched`. */
static char *find_shipped(const char *name, char *searched, size_t size)
{
    char *dirs[MAX_DIRS];
    size_t n = lam_machine_dirs(dirs, MAX_DIRS);
    char *found = NULL;
    size_t k = 0;
    searched[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        if (!found) {
            size_t need = strlen(dirs[i]) + strlen(name) + 7;
            char *path = malloc(need);
            if (path) {
                snprintf(path, need, "%s/%s.yaml", dirs[i], name);
                if (is_file(path)) found = path;
                else free(path);
            }
            if (k + 1 < size) {
                int w = snprintf(searched + k, size - k, "%s%s", k ? ", " : "", dirs[i]);
                if (w > 0) k += (size_t)w < size - k ? (size_t)w : size - k - 1;
            }
        }
        free(dirs[i]);
    }
    if (!n) snprintf(searched, size, "(no directories: set LAMINA_MACHINES)");
    return found;
}

/* A name is looked up in the machine directories only, never in the current
 * directory (a file there must not stand in for a shipped profile by
 * accident). When dir[0..dl) (a prefix ending in '/', or empty) holds
 * NAME.yaml (or .yml), hint[0..size) says how to name it: "; NAME.yaml HERE
 * is not searched: write ./NAME.yaml"; else it is "". */
static void local_hint(const char *dir, size_t dl, const char *name, const char *here, char *hint, size_t size)
{
    hint[0] = '\0';
    static const char *const ext[] = { ".yaml", ".yml" };
    for (int e = 0; e < 2 && !hint[0]; e++) {
        size_t need = dl + strlen(name) + 6;
        char *path = malloc(need);
        if (!path) return;
        snprintf(path, need, "%.*s%s%s", (int)dl, dir, name, ext[e]);
        if (is_file(path)) snprintf(hint, size, "; %s%s %s is not searched: write ./%s%s", name, ext[e], here, name, ext[e]);
        free(path);
    }
}

static int load_file(ldr *L, const char *path, int top);

static int resolve_parent(ldr *L, const src *s, const yaml_node_t *v)
{
    char *name = NULL;
    int rc = get_text(s, v, inherits_key()->name, &name);
    if (rc) return rc;
    char *parent = NULL;
    if (!*name) {
        rc = at(s, v->start_mark, LAM_EINVAL, "inherits must name a profile");
    } else if (is_path(name)) {
        if (name[0] == '/') {
            parent = strdup(name);
        } else {
            const char *slash = strrchr(s->path, '/');
            size_t dl = slash ? (size_t)(slash - s->path) + 1 : 0;
            parent = malloc(dl + strlen(name) + 1);
            if (parent) {
                memcpy(parent, s->path, dl);
                strcpy(parent + dl, name);
            }
        }
        struct stat st;
        if (!parent) rc = oom();
        else if (stat(parent, &st) != 0)
            rc = at(s, v->start_mark, LAM_EINVAL, "inherits '%s': cannot open %s: %s", name, parent, strerror(errno));
        else if (!S_ISREG(st.st_mode))
            rc = at(s, v->start_mark, LAM_EINVAL, "inherits '%s': %s is not a file", name, parent);
    } else {
        char searched[1024], hint[300];
        parent = find_shipped(name, searched, sizeof searched);
        const char *slash = strrchr(s->path, '/');
        if (!parent)
            local_hint(s->path, slash ? (size_t)(slash - s->path) + 1 : 0, name, "beside this profile", hint, sizeof hint);
        if (!parent)
            rc = at(s, v->start_mark, LAM_EINVAL, "inherits '%s': no machine profile %s.yaml in %s%s", name, name,
                    searched, hint);
    }
    if (!rc) {
        struct stat st;
        if (stat(parent, &st) != 0) {
            rc = at(s, v->start_mark, LAM_EINVAL, "inherits '%s': cannot open %s: %s", name, parent, strerror(errno));
        } else {
            for (size_t i = 0; i < L->depth && !rc; i++) {
                if (L->dev[i] != st.st_dev || L->ino[i] != st.st_ino) continue;
                char cycle[700] = "";
                for (size_t j = i; j < L->depth; j++) {
                    strncat(cycle, L->given[j], sizeof cycle - strlen(cycle) - 1);
                    strncat(cycle, " -> ", sizeof cycle - strlen(cycle) - 1);
                }
                strncat(cycle, parent, sizeof cycle - strlen(cycle) - 1);
                rc = at(s, v->start_mark, LAM_EINVAL, "inherits cycle: %s", cycle);
            }
            if (!rc && L->depth >= MAX_CHAIN)
                rc = at(s, v->start_mark, LAM_EINVAL, "inherits chain longer than %d profiles", MAX_CHAIN);
        }
    }
    if (!rc) rc = load_file(L, parent, 0);
    free(parent);
    free(name);
    return rc;
}

/* Required keys, and the values that follow others, once the whole chain
 * is read. */
static int finish(ldr *L, const src *s, const yaml_node_t *root)
{
    lam_profile *p = L->p;
    int sls = p->process == LAM_PROCESS_SLS;
    const char *missing = NULL, *why = "";
    char section[32];
    for (size_t i = 0; i < lam_profile_nkeys && !missing; i++)
        if (lam_profile_keys[i].flags & LAM_KEY_NEED && !L->set[i])
            missing = lam_profile_keys[i].name, why = "every profile needs it";
    for (size_t i = 0; i < lam_profile_nkeys && !missing && !L->templates_given && !strcmp(p->writer, "text"); i++)
        if (lam_profile_keys[i].type == LAM_KEY_TEMPLATE) {
            snprintf(section, sizeof section, "%.*s", (int)lam_key_section_len(&lam_profile_keys[i]),
                     lam_profile_keys[i].name);
            missing = section, why = "the command templates, unless a plugin writer writes the program";
        }
    for (size_t i = 0; i < lam_profile_nkeys && !missing; i++)
        if (lam_profile_keys[i].flags & (sls ? LAM_KEY_NEED_SLS : LAM_KEY_NEED_LADRP) && !L->set[i])
            missing = lam_profile_keys[i].name, why = sls ? "an sls profile needs it" : "a ladrp profile needs it";
    if (missing) return at(s, root->start_mark, LAM_EINVAL, "missing key '%s' (%s)", missing, why);
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->follows && !L->set[i]) lam_key_store(p, k, lam_key_get(p, lam_key_find(k->follows)));
    }
    if (sls) p->bead_width = p->spot_width;
    return LAM_OK;
}

/* A key the file given gives itself that its planner does not read is an
 * error at the key (it would do nothing); a parent's are not: a base may
 * serve profiles of both processes (machines/README.md, "Keys"). */
static int unread_key(const src *s, const yaml_node_t *key, const lam_key *k, int process)
{
    lam_error e;
    if (!k || k->flags & LAM_KEY_LOADER || lam_key_read_by(k, process)) return LAM_OK;
    lam_key_unread(k, NULL, process, NULL, &e);
    return at(s, key->start_mark, LAM_EINVAL, "%s", e.msg);
}

static int check_readers(const ldr *L, const src *s, const yaml_node_t *root)
{
    int rc = LAM_OK;
    for (yaml_node_pair_t *pr = root->data.mapping.pairs.start; !rc && pr < root->data.mapping.pairs.top; pr++) {
        const yaml_node_t *key = node(s, pr->key), *v = node(s, pr->value);
        const char *name = (const char *)key->data.scalar.value;
        const lam_key *k = exact_key(name);
        if (k || v->type != YAML_MAPPING_NODE) {
            rc = unread_key(s, key, k, L->p->process);
            continue;
        }
        for (yaml_node_pair_t *q = v->data.mapping.pairs.start; !rc && q < v->data.mapping.pairs.top; q++) {
            char full[128];
            snprintf(full, sizeof full, "%s.%s", name, (const char *)node(s, q->key)->data.scalar.value);
            rc = unread_key(s, node(s, q->key), exact_key(full), L->p->process);
        }
    }
    return rc;
}

static int load_text(ldr *L, src *s, const char *path, int top);

static int load_file(ldr *L, const char *path, int top)
{
    src file;
    memset(&file, 0, sizeof file);
    src *s = &file;
    s->path = path;
    s->err = L->err;
    int rc = read_all(s, path, &s->text, &s->len);
    if (rc) return rc;
    return load_text(L, s, path, top);
}

/* Parse and apply s->text (owned: freed here). */
static int load_text(ldr *L, src *s, const char *path, int top)
{
    int rc;
    s->what = "a machine profile";
    if ((rc = parse(s))) goto out;
    const yaml_node_t *root = yaml_document_get_root_node(&s->doc);
    if (root->type != YAML_MAPPING_NODE) {
        /* nothing of a file that is not a profile is quoted */
        rc = at(s, root->start_mark, LAM_EINVAL, "a machine profile is a mapping of keys (name, process, ...), got %s",
                root->type == YAML_SEQUENCE_NODE ? "a list" : "text");
        goto out;
    }
    if (!recognised(s, root)) {
        rc = at(s, root->start_mark, LAM_EINVAL,
                "not a machine profile: none of its keys is a profile key (name, process, dialect, ...)");
        goto out;
    }
    keyset ks;
    keys_in("", &ks);
    if ((rc = check_keys(s, root, "", ks.names, ks.n))) goto out;
    const yaml_node_t *inh = lookup(s, root, inherits_key()->name);
    if (inh) {
        struct stat st;
        if (stat(path, &st) != 0) {
            rc = lam_error_set(s->err, LAM_EIO, path, 0, 0, "cannot open: %s", strerror(errno));
            goto out;
        }
        L->dev[L->depth] = st.st_dev;
        L->ino[L->depth] = st.st_ino;
        L->given[L->depth] = path;
        L->depth++;
        rc = resolve_parent(L, s, inh);
        L->depth--;
        if (rc) goto out;
    }
    if ((rc = apply(L, s, root))) goto out;
    if (top && !(rc = finish(L, s, root))) rc = check_readers(L, s, root);
out:
    lam_yaml_doc_free(s);
    free(s->text);
    return rc;
}

/* ---- public ---------------------------------------------------------------- */

double lam_profile_unit_mm(const lam_profile *p)
{
    return lam_key_unit_mm(p->units ? p->units : "mm");
}

double lam_profile_gap_limit(const lam_profile *p)
{
    double mm = lam_profile_unit_mm(p);
    return mm > 0 ? LAM_GAP_MM / mm : 0;
}

static char **string_at(lam_profile *p, const lam_key *k)
{
    return (char **)(void *)((char *)p + k->offset);
}

/* A profile holding every row's default. */
static lam_profile *new_profile(void)
{
    lam_profile *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        double x;
        if (!k->def) continue;
        if (k->type == LAM_KEY_STRING) {
            if (!(*string_at(p, k) = strdup(k->def))) {
                lam_profile_free(p);
                return NULL;
            }
        } else if (lam_key_scan(k, NULL, k->def, strlen(k->def), &x, NULL) == LAM_OK) {
            lam_key_store(p, k, x); /* test_profile checks that every default reads */
        }
    }
    return p;
}

void lam_profile_free(lam_profile *p)
{
    if (!p) return;
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (lam_profile_keys[i].type == LAM_KEY_STRING && !(lam_profile_keys[i].flags & LAM_KEY_LOADER))
            free(*string_at(p, &lam_profile_keys[i]));
    free(p->path);
    lam_dialect_free(&p->dialect);
    free(p);
}

/* A loader of a new profile: LAM_ENOMEM when there is no room for one. */
static int loader_start(ldr *L, lam_error *err)
{
    lam_error_clear(err);
    memset(L, 0, sizeof *L);
    L->err = err;
    return (L->p = new_profile()) ? LAM_OK : oom_err(err);
}

/* The loader's profile, named `path`, into *out after a load that gave rc. */
static int loader_finish(ldr *L, int rc, const char *path, lam_profile **out, lam_error *err)
{
    if (!rc && !(L->p->path = strdup(path))) rc = oom_err(err);
    if (rc) {
        lam_profile_free(L->p);
        return rc;
    }
    *out = L->p;
    return LAM_OK;
}

int lam_profile_load(const char *path, lam_profile **out, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    *out = NULL;
    ldr L;
    int rc = loader_start(&L, err);
    if (rc) return rc;
    return loader_finish(&L, load_file(&L, path, 1), path, out, err);
}

int lam_profile_load_buf(const char *name, const char *text, size_t len, lam_profile **out, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    *out = NULL;
    ldr L;
    int rc = loader_start(&L, err);
    if (rc) return rc;
    src buf;
    memset(&buf, 0, sizeof buf);
    buf.path = name;
    buf.err = err;
    buf.len = len;
    rc = (buf.text = malloc(len + 1)) ? LAM_OK : oom_err(err);
    if (!rc) {
        memcpy(buf.text, text, len);
        buf.text[len] = '\0';
        rc = load_text(&L, &buf, name, 1);
    }
    return loader_finish(&L, rc, name, out, err);
}

int lam_profile_find(const char *name_or_path, lam_profile **out, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    *out = NULL;
    if (is_path(name_or_path)) return lam_profile_load(name_or_path, out, err);
    if (!*name_or_path) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "empty machine profile name");
    char searched[1024], hint[300];
    char *path = find_shipped(name_or_path, searched, sizeof searched);
    if (!path) {
        local_hint("", 0, name_or_path, "in the current directory", hint, sizeof hint);
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "unknown machine '%s': no %s.yaml in %s ('lamina machines' lists them)%s", name_or_path,
                             name_or_path, searched, hint);
    }
    int rc = lam_profile_load(path, out, err);
    free(path);
    return rc;
}

/* ---- --set ---------------------------------------------------------------- */

/* Set a list row (numbers, lasers) of p from text, YAML in flow style
 * ("[1, 0]", "[{field: [0, 0, 125, 250]}]"), with the loader's checks and
 * messages, without a position; p is unchanged on error. */
static int set_list(lam_profile *p, const lam_key *k, const char *text, lam_error *err)
{
    if (!text[strspn(text, " \t")]) return lam_key_expected(k, NULL, "nothing", err);
    src s;
    memset(&s, 0, sizeof s);
    s.path = "--set";
    s.what = "a profile value";
    s.err = err;
    s.len = strlen(text);
    if (!(s.text = strdup(text))) return oom_err(err);
    int rc = parse(&s);
    if (!rc) rc = read_list(&s, k, yaml_document_get_root_node(&s.doc), p);
    lam_yaml_doc_free(&s);
    free(s.text);
    if (rc && rc != LAM_ENOMEM) {
        /* the loader's message, without a position in the value's text */
        char msg[sizeof err->msg];
        snprintf(msg, sizeof msg, "%s", err->msg);
        lam_error_set(err, rc, NULL, 0, 0, "%s", msg);
    }
    return rc;
}

static const lam_key *find_or_fail(const char *name, lam_error *err)
{
    const lam_key *k = lam_key_find(name);
    if (k) return k;
    const char *names[LAM_KEYS_MAX];
    size_t n = 0;
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (!(lam_profile_keys[i].flags & LAM_KEY_LOADER)) names[n++] = lam_profile_keys[i].name;
    const char *best = lam_key_nearest(name, names, n);
    char shown[64];
    lam_quote_bytes(shown, sizeof shown, (const unsigned char *)name, strlen(name));
    if (best)
        lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "unknown key %s (did you mean '%s'?)", shown, best);
    else
        lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "unknown key %s", shown);
    return NULL;
}

int lam_profile_set(lam_profile *p, const char *name, const char *text, lam_error *err)
{
    lam_error own; /* err may be NULL (error.h); messages are wrapped below */
    if (!err) err = &own;
    const lam_key *k = find_or_fail(name, err);
    if (!k) return LAM_EINVAL;
    if (k->flags & LAM_KEY_LOADER)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s is only read while a profile loads", k->name);
    if (k->type == LAM_KEY_STRING) {
        int rc = lam_key_check_text(k, text, err);
        if (rc) return rc;
        char *copy = strdup(text);
        if (!copy) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
        char **at = (char **)(void *)((char *)p + k->offset);
        free(*at);
        *at = copy;
        return LAM_OK;
    }
    if (k->type == LAM_KEY_TEMPLATE) {
        lam_template t;
        size_t off = 0;
        int rc = lam_template_parse((lam_cmd)k->cmd, text, &t, &off, err);
        if (rc == LAM_ENOMEM) return rc;
        if (rc) {
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s: %s (at character %zu)", k->name, msg, off + 1);
        }
        lam_template *at = (lam_template *)(void *)((char *)p + k->offset);
        lam_template_free(at);
        *at = t;
        return LAM_OK;
    }
    if (k->type == LAM_KEY_NUMBERS || k->type == LAM_KEY_LASERS) return set_list(p, k, text, err);
    double x;
    int rc = lam_key_scan(k, NULL, text, strlen(text), &x, err);
    if (!rc) lam_key_put(p, k, x);
    return rc;
}

/* ---- dump --------------------------------------------------------------- */

static void put_string(lam_writer *w, const char *s)
{
    lam_writer_write(w, "\"", 1);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        switch (*c) {
        case '"': lam_writer_write(w, "\\\"", 2); break;
        case '\\': lam_writer_write(w, "\\\\", 2); break;
        case '\n': lam_writer_write(w, "\\n", 2); break;
        case '\t': lam_writer_write(w, "\\t", 2); break;
        case '\r': lam_writer_write(w, "\\r", 2); break;
        default:
            if (*c < 0x20 || *c == 0x7f) lam_writer_printf(w, "\\x%02x", *c);
            else lam_writer_write(w, c, 1);
        }
    }
    lam_writer_write(w, "\"", 1);
}

/* A comment line: control characters shown as '?'. */
static void put_comment(lam_writer *w, const char *label, const char *text)
{
    lam_writer_printf(w, "# %s", label);
    for (const unsigned char *c = (const unsigned char *)text; *c; c++)
        lam_writer_write(w, *c < 0x20 ? "?" : (const char *)c, 1);
    lam_writer_write(w, "\n", 1);
}

/* A list row's value in YAML flow style: "[-1, 0]", "[{field: [0, 0, 125,
 * 250]}, ...]". */
static void put_list(lam_writer *w, const lam_profile *p, const lam_key *k)
{
    char buf[LAM_FMT_MAX];
    size_t n = k->type == LAM_KEY_LASERS ? p->nlasers : k->count;
    const double *v = (const double *)(const void *)((const char *)p + k->offset);
    lam_writer_write(w, "[", 1);
    for (size_t i = 0; i < n; i++) {
        if (i) lam_writer_write(w, ", ", 2);
        if (k->type == LAM_KEY_NUMBERS) {
            lam_writer_write(w, buf, lam_dialect_number(buf, v[i]));
            continue;
        }
        lam_writer_write(w, "{field: [", 9);
        for (int j = 0; j < 4; j++) {
            if (j) lam_writer_write(w, ", ", 2);
            lam_writer_write(w, buf, lam_dialect_number(buf, p->laser_field[i][j]));
        }
        lam_writer_write(w, "]}", 2);
    }
    lam_writer_write(w, "]", 1);
}

void lam_profile_plate_centre(const lam_profile *p, double c[2])
{
    int rect = p && !(p->plate_diameter > 0) && p->plate_width > 0 && p->plate_depth > 0;
    c[0] = rect ? p->plate_width / 2 : 0;
    c[1] = rect ? p->plate_depth / 2 : 0;
}

int lam_profile_dump(const lam_profile *p, lam_writer *w)
{
    put_comment(w, "lamina machine profile ", p->name ? p->name : "");
    if (p->path) put_comment(w, "resolved from ", p->path);
    const char *section = "";
    size_t sl = 0;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        const char *at = (const char *)p + k->offset;
        const lam_template *t = (const lam_template *)(const void *)at;
        const char *str = k->type == LAM_KEY_STRING ? *(char *const *)(const void *)at : NULL;
        /* not the other planner's keys (an sls profile's bead width is its
         * spot width): the dump loads again (check_readers) */
        if (k->flags & LAM_KEY_LOADER || !lam_key_read_by(k, p->process) || !lam_key_given(p, k)) continue;
        size_t kl = lam_key_section_len(k);
        if (kl && (kl != sl || strncmp(k->name, section, kl) != 0)) {
            lam_writer_printf(w, "%.*s:\n", (int)kl, k->name);
            section = k->name;
            sl = kl;
        }
        lam_writer_printf(w, "%s%s: ", kl ? "  " : "", lam_key_short(k));
        char buf[LAM_FMT_MAX];
        double x = lam_key_get(p, k);
        switch (k->type) {
        case LAM_KEY_NUMBER:
            if (k->flags & LAM_KEY_AUTO && x < 0) lam_writer_printf(w, "auto");
            else lam_writer_write(w, buf, lam_dialect_number(buf, x));
            break;
        case LAM_KEY_INTEGER: lam_writer_printf(w, "%d", (int)x); break;
        case LAM_KEY_BOOLEAN: lam_writer_printf(w, "%s", x ? "true" : "false"); break;
        case LAM_KEY_CHOICE: {
            int n = 0;
            while (k->choices[n]) n++;
            lam_writer_printf(w, "%s", k->choices[x >= 0 && x < n ? (int)x : 0]);
            break;
        }
        case LAM_KEY_STRING: put_string(w, str ? str : ""); break;
        case LAM_KEY_TEMPLATE: put_string(w, t->source); break;
        case LAM_KEY_NUMBERS:
        case LAM_KEY_LASERS: put_list(w, p, k); break;
        }
        lam_writer_write(w, "\n", 1);
    }
    return lam_writer_write(w, "", 0);
}
