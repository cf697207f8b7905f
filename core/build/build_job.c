/* Build job files: see build_job.h. The machine and the job's profile keys
 * go through the profile's own table and checks (lam_profile_set), the
 * styles through build.h; this file only walks the YAML and says where. */
#include "build_job.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "lexnum.h"
#include "yaml_doc.h"

#define FLOW_MAX 65536 /* a value written back as YAML flow text (lasers: 16 fields) */

typedef struct jp {
    lam_yaml_doc d;
    lam_build *b;
    lam_profile *p;          /* until the build takes it */
    char dir[4096];          /* the job's folder, "" for the current one */
    lam_error *err;
} jp;

static const char *const job_keys[] = { "machine", "parts", "styles" };
static const char *const part_keys[] = { "model", "name", "units", "scale", "rotate", "copies", "at", "z", "style" };
#define NJOB (sizeof job_keys / sizeof *job_keys)
#define NPART (sizeof part_keys / sizeof *part_keys)

/* ---- nodes --------------------------------------------------------------------- */

static const char *text_of(const yaml_node_t *n) { return (const char *)n->data.scalar.value; }

static const char *describe(const yaml_node_t *n)
{
    return n->type == YAML_MAPPING_NODE ? "a mapping" : n->type == YAML_SEQUENCE_NODE ? "a list" : "text";
}

static int want(const jp *j, const yaml_node_t *n, yaml_node_type_t type, const char *key, const char *what)
{
    if (n->type == type && !(type == YAML_SCALAR_NODE && lam_yaml_is_null(n))) return LAM_OK;
    return lam_yaml_at(&j->d, n->start_mark, LAM_EINVAL, "%s must be %s, got %s", key, what,
                       lam_yaml_is_null(n) ? "nothing" : describe(n));
}

static int number(const jp *j, const yaml_node_t *n, const char *key, double *x)
{
    int rc = want(j, n, YAML_SCALAR_NODE, key, "a number");
    if (rc) return rc;
    const char *t = text_of(n);
    if (n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE ||
        lam_parse_number((const unsigned char *)t, strlen(t), x) || !isfinite(*x))
        return lam_yaml_at(&j->d, n->start_mark, LAM_EINVAL, "%s must be a number, got '%s'", key, t);
    return LAM_OK;
}

/* The nearest of names[] and the profile's keys to word, for did-you-mean. */
static const char *nearest(const char *word, const char *const *names, size_t n, int profile_keys)
{
    const char *all[LAM_KEYS_MAX + 16];
    size_t k = 0;
    for (size_t i = 0; i < n && k < sizeof all / sizeof *all; i++) all[k++] = names[i];
    for (size_t i = 0; profile_keys && i < lam_profile_nkeys && k < sizeof all / sizeof *all; i++)
        all[k++] = lam_profile_keys[i].name;
    return lam_key_nearest(word, all, k);
}

static int unknown(const jp *j, const yaml_node_t *key, const char *where, const char *const *names, size_t n,
                   int profile_keys)
{
    const char *near = nearest(text_of(key), names, n, profile_keys);
    char hint[160] = "";
    if (near) snprintf(hint, sizeof hint, " (did you mean %s?)", near);
    return lam_yaml_at(&j->d, key->start_mark, LAM_EINVAL, "unknown key '%s' in %s%s", text_of(key), where, hint);
}

/* ---- a value as YAML flow text (for lam_profile_set) ------------------------------ */

static int put(char *buf, size_t *len, const char *s)
{
    size_t n = strlen(s);
    if (*len + n >= FLOW_MAX) return -1;
    memcpy(buf + *len, s, n + 1);
    *len += n;
    return 0;
}

static int put_scalar(char *buf, size_t *len, const yaml_node_t *n)
{
    if (n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) return put(buf, len, text_of(n));
    if (put(buf, len, "\"")) return -1;
    for (const char *s = text_of(n); *s; s++) {
        char c[3] = { *s, 0, 0 };
        if (*s == '"' || *s == '\\') c[0] = '\\', c[1] = *s;
        if (*s == '\n') c[0] = '\\', c[1] = 'n';
        if (put(buf, len, c)) return -1;
    }
    return put(buf, len, "\"");
}

static int flow(const jp *j, const yaml_node_t *n, char *buf, size_t *len, int depth)
{
    if (depth > LAM_YAML_MAX_NESTING) return -1;
    if (n->type == YAML_SCALAR_NODE) return put_scalar(buf, len, n);
    int map = n->type == YAML_MAPPING_NODE, rc = put(buf, len, map ? "{" : "[");
    if (map) {
        for (yaml_node_pair_t *q = n->data.mapping.pairs.start; !rc && q < n->data.mapping.pairs.top; q++) {
            if (q != n->data.mapping.pairs.start) rc = put(buf, len, ", ");
            if (!rc) rc = flow(j, lam_yaml_node(&j->d, q->key), buf, len, depth + 1);
            if (!rc) rc = put(buf, len, ": ");
            if (!rc) rc = flow(j, lam_yaml_node(&j->d, q->value), buf, len, depth + 1);
        }
    } else {
        for (yaml_node_item_t *i = n->data.sequence.items.start; !rc && i < n->data.sequence.items.top; i++) {
            if (i != n->data.sequence.items.start) rc = put(buf, len, ", ");
            if (!rc) rc = flow(j, lam_yaml_node(&j->d, *i), buf, len, depth + 1);
        }
    }
    return rc ? rc : put(buf, len, map ? "}" : "]");
}

/* ---- the machine and its keys ---------------------------------------------------------- */

static const yaml_node_t *lookup(const jp *j, const yaml_node_t *m, const char *key, const yaml_node_t **keynode)
{
    for (yaml_node_pair_t *q = m->data.mapping.pairs.start; q < m->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
        if (k->type == YAML_SCALAR_NODE && !strcmp(text_of(k), key)) {
            if (keynode) *keynode = k;
            return lam_yaml_node(&j->d, q->value);
        }
    }
    return NULL;
}

/* A path in the job: from the job's folder unless absolute. */
static void job_path(const jp *j, const char *path, char *out, size_t size)
{
    size_t n = strlen(j->dir);
    if (path[0] == '/' || !n || n + 1 >= size) n = 0;
    memcpy(out, j->dir, n);
    if (n) out[n++] = '/';
    snprintf(out + n, size - n, "%s", path);
}

static int is_path(const char *s)
{
    size_t n = strlen(s);
    return strchr(s, '/') || (n > 5 && !strcmp(s + n - 5, ".yaml")) || (n > 4 && !strcmp(s + n - 4, ".yml"));
}

static int load_machine(jp *j, const yaml_node_t *root)
{
    const yaml_node_t *v = lookup(j, root, "machine", NULL);
    if (!v)
        return lam_yaml_at(&j->d, root->start_mark, LAM_EINVAL,
                           "the job names no machine: add machine: NAME (a shipped profile, see 'lamina machines') "
                           "or a profile's path");
    int rc = want(j, v, YAML_SCALAR_NODE, "machine", "a machine profile's name or path");
    if (rc) return rc;
    char path[4096 + 512];
    if (is_path(text_of(v))) job_path(j, text_of(v), path, sizeof path);
    else snprintf(path, sizeof path, "%s", text_of(v));
    lam_error e;
    lam_error_clear(&e);
    if (!(rc = lam_profile_find(path, &j->p, &e))) return LAM_OK;
    if (e.file[0] && e.line) { /* an error inside the profile: its own position */
        if (j->err) *j->err = e;
        return rc;
    }
    return lam_yaml_at(&j->d, v->start_mark, rc, "machine %s: %s", text_of(v), e.msg);
}

/* Whether `key` is a section of profile keys (raster, contour, plate, ...). */
static int is_section(const char *key)
{
    size_t n = strlen(key);
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (!strncmp(lam_profile_keys[i].name, key, n) && lam_profile_keys[i].name[n] == '.') return 1;
    return 0;
}

/* One profile key: a scalar's value as written (quotes are YAML's, not
 * the value's), a list as YAML flow text; a key the machine's planner does
 * not read is refused, as in a profile. */
static int set_key(jp *j, const char *name, const yaml_node_t *v)
{
    static char text[FLOW_MAX];
    size_t len = 0;
    text[0] = '\0';
    if (lam_yaml_is_null(v) || (v->type == YAML_SCALAR_NODE ? put(text, &len, text_of(v)) : flow(j, v, text, &len, 0)))
        return lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "%s: %s", name,
                           lam_yaml_is_null(v) ? "no value given" : "the value is too large");
    lam_error e;
    lam_error_clear(&e);
    const lam_key *k = lam_key_find(name);
    int rc = k && !lam_key_read_by(k, j->p->process) ? lam_key_unread(k, name, j->p->process, j->p->name, &e)
                                                     : lam_profile_set(j->p, name, text, &e);
    return rc ? lam_yaml_at(&j->d, v->start_mark, rc, "%s", e.msg) : LAM_OK;
}

/* One of the job's keys that is the machine's: on top of the profile, as
 * one more YAML file would be. */
static int override(jp *j, const yaml_node_t *k, const yaml_node_t *v)
{
    const char *key = text_of(k);
    if (v->type == YAML_MAPPING_NODE && is_section(key)) {
        for (yaml_node_pair_t *q = v->data.mapping.pairs.start; q < v->data.mapping.pairs.top; q++) {
            const yaml_node_t *k2 = lam_yaml_node(&j->d, q->key);
            if (k2->type != YAML_SCALAR_NODE) return want(j, k2, YAML_SCALAR_NODE, key, "a mapping of keys");
            char name[256];
            snprintf(name, sizeof name, "%s.%s", key, text_of(k2));
            if (!lam_key_find(name)) return unknown(j, k2, key, NULL, 0, 1);
            int rc = set_key(j, name, lam_yaml_node(&j->d, q->value));
            if (rc) return rc;
        }
        return LAM_OK;
    }
    if (!lam_key_find(key)) return unknown(j, k, "the job", job_keys, NJOB, 1);
    return set_key(j, key, v);
}

static int overrides(jp *j, const yaml_node_t *root)
{
    for (yaml_node_pair_t *q = root->data.mapping.pairs.start; q < root->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
        int rc = want(j, k, YAML_SCALAR_NODE, "a job's key", "text");
        for (size_t i = 0; !rc && i < NJOB; i++)
            if (!strcmp(text_of(k), job_keys[i])) goto next;
        if (!rc) rc = override(j, k, lam_yaml_node(&j->d, q->value));
        if (rc) return rc;
    next:;
    }
    lam_error e;
    lam_error_clear(&e);
    int rc = lam_profile_check(j->p, &e);
    return rc ? lam_yaml_at(&j->d, root->start_mark, rc, "with the job's values: %s", e.msg) : LAM_OK;
}

/* ---- styles ------------------------------------------------------------------------------ */

static int one_style(jp *j, const yaml_node_t *name, const yaml_node_t *m)
{
    int rc = want(j, m, YAML_MAPPING_NODE, text_of(name), "a mapping of exposure and hatching keys");
    for (yaml_node_pair_t *q = m->data.mapping.pairs.start; !rc && q < m->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key), *v = lam_yaml_node(&j->d, q->value);
        rc = want(j, k, YAML_SCALAR_NODE, "a style's key", "text");
        if (!rc) rc = want(j, v, YAML_SCALAR_NODE, text_of(k), "a value");
        if (rc) break;
        lam_error e;
        lam_error_clear(&e);
        rc = lam_build_style_set(j->b, text_of(name), text_of(k), text_of(v), (long)v->start_mark.line + 1,
                                 (long)v->start_mark.column + 1, &e);
        if (rc) rc = lam_yaml_at(&j->d, k->start_mark, rc, "style %s: %s", text_of(name), e.msg);
    }
    if (!rc && m->data.mapping.pairs.start == m->data.mapping.pairs.top)
        rc = lam_yaml_at(&j->d, m->start_mark, LAM_EINVAL, "style %s sets nothing", text_of(name));
    return rc;
}

static int styles(jp *j, const yaml_node_t *root)
{
    const yaml_node_t *v = lookup(j, root, "styles", NULL);
    if (!v) return LAM_OK;
    int rc = want(j, v, YAML_MAPPING_NODE, "styles", "a mapping of style names to their keys");
    for (yaml_node_pair_t *q = v->data.mapping.pairs.start; !rc && q < v->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
        rc = want(j, k, YAML_SCALAR_NODE, "a style's name", "text");
        if (!rc && lam_build_style_find(j->b, text_of(k)) >= 0)
            rc = lam_yaml_at(&j->d, k->start_mark, LAM_EINVAL, "style %s is defined twice", text_of(k));
        if (!rc) rc = one_style(j, k, lam_yaml_node(&j->d, q->value));
    }
    return rc;
}

/* ---- parts ---------------------------------------------------------------------------------- */

/* A key given twice in mapping m (at pair q). */
static int twice(const jp *j, const yaml_node_t *m, const yaml_node_pair_t *q)
{
    const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
    for (yaml_node_pair_t *o = m->data.mapping.pairs.start; o < q; o++) {
        const yaml_node_t *ok = lam_yaml_node(&j->d, o->key);
        if (ok->type == YAML_SCALAR_NODE && k->type == YAML_SCALAR_NODE && !strcmp(text_of(ok), text_of(k)))
            return lam_yaml_at(&j->d, k->start_mark, LAM_EINVAL, "duplicate key '%s'", text_of(k));
    }
    return LAM_OK;
}

static int style_ref(jp *j, const yaml_node_t *v, int *index)
{
    int rc = want(j, v, YAML_SCALAR_NODE, "style", "a style's name");
    if (rc) return rc;
    *index = lam_build_style_find(j->b, text_of(v));
    if (*index >= 0) return LAM_OK;
    const char *names[LAM_BUILD_MAX_STYLES];
    for (size_t i = 0; i < j->b->nstyles; i++) names[i] = j->b->styles[i].name;
    const char *near = lam_key_nearest(text_of(v), names, j->b->nstyles);
    return lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "style %s is not defined under styles:%s%s%s", text_of(v),
                       near ? " (did you mean " : "", near ? near : "", near ? "?)" : "");
}

static int part_style(jp *j, const yaml_node_t *v, lam_build_part *p)
{
    if (v->type == YAML_SCALAR_NODE) {
        int s, rc = style_ref(j, v, &s);
        for (int r = 0; r < LAM_REGIONS && !rc; r++) p->style[r] = s;
        p->style_whole = 1;
        return rc;
    }
    int rc = want(j, v, YAML_MAPPING_NODE, "style", "a style's name or a mapping of regions to styles");
    for (yaml_node_pair_t *q = v->data.mapping.pairs.start; !rc && q < v->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
        rc = want(j, k, YAML_SCALAR_NODE, "a region", "contour, core, upskin or downskin");
        int r = rc ? -1 : lam_region_find(text_of(k));
        if (!rc && r < 0)
            rc = lam_yaml_at(&j->d, k->start_mark, LAM_EINVAL,
                             "%s is not a region: a style is given for contour, core, upskin or downskin", text_of(k));
        if (!rc) rc = style_ref(j, lam_yaml_node(&j->d, q->value), &p->style[r]);
    }
    return rc;
}

/* A list of n numbers (or one number when one_ok, for every axis). */
static int numbers(jp *j, const yaml_node_t *v, const char *key, double *x, size_t n, int one_ok)
{
    if (one_ok && v->type == YAML_SCALAR_NODE) {
        int rc = number(j, v, key, &x[0]);
        for (size_t i = 1; i < n; i++) x[i] = x[0];
        return rc;
    }
    char what[64];
    snprintf(what, sizeof what, "a list of %zu numbers", n);
    int rc = want(j, v, YAML_SEQUENCE_NODE, key, what);
    size_t got = rc ? 0 : (size_t)(v->data.sequence.items.top - v->data.sequence.items.start);
    if (!rc && got != n) return lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "%s must be %s, got %zu", key, what, got);
    for (size_t i = 0; i < n && !rc; i++) rc = number(j, lam_yaml_node(&j->d, v->data.sequence.items.start[i]), key, &x[i]);
    return rc;
}

static int xform_text(jp *j, const yaml_node_t *v, const char *key, lam_xform *x, const char *text)
{
    lam_error e;
    lam_error_clear(&e);
    int rc = !strcmp(key, "rotate") ? lam_xform_parse_rotate(x, text, &e) : lam_xform_parse_scale(x, text, &e);
    return rc ? lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "%s '%s': %s", key, text, e.msg) : LAM_OK;
}

static int rotate(jp *j, const yaml_node_t *v, lam_build_part *p)
{
    if (v->type == YAML_SCALAR_NODE && !lam_yaml_is_null(v)) return xform_text(j, v, "rotate", &p->xform, text_of(v));
    int rc = want(j, v, YAML_SEQUENCE_NODE, "rotate", "AXIS:DEG (x:90) or a list of them");
    for (yaml_node_item_t *i = v->data.sequence.items.start; !rc && i < v->data.sequence.items.top; i++) {
        const yaml_node_t *r = lam_yaml_node(&j->d, *i);
        rc = want(j, r, YAML_SCALAR_NODE, "rotate", "AXIS:DEG (x:90)");
        if (!rc) rc = xform_text(j, r, "rotate", &p->xform, text_of(r));
    }
    return rc;
}

static int units(jp *j, const yaml_node_t *v, lam_build_part *p)
{
    int rc = want(j, v, YAML_SCALAR_NODE, "units", "a unit (mm, cm, m, um, in, ft)");
    double mm = rc ? 0 : lam_unit_mm(text_of(v)), machine = lam_profile_unit_mm(j->b->profile);
    if (!rc && !(mm > 0))
        rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "units must be mm, cm, m, um, in, inch or ft, got '%s'",
                         text_of(v));
    if (!rc && !(machine > 0))
        rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "units %s: the machine's units (%s) are unknown", text_of(v),
                         j->b->profile->units);
    if (!rc) lam_xform_scale_by(&p->xform, mm / machine);
    return rc;
}

static int copies(jp *j, const yaml_node_t *v, lam_build_part *p)
{
    double x;
    int rc = number(j, v, "copies", &x);
    if (!rc && !(x >= 1 && x <= LAM_BUILD_MAX_COPIES && x == floor(x)))
        rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "copies must be a whole number from 1 to %d, got '%s'",
                         LAM_BUILD_MAX_COPIES, text_of(v));
    if (!rc) p->copies = (size_t)x;
    return rc;
}

static int scale(jp *j, const yaml_node_t *v, lam_build_part *p)
{
    double s[3];
    int rc = numbers(j, v, "scale", s, 3, 1);
    char text[128];
    snprintf(text, sizeof text, "%.17g,%.17g,%.17g", s[0], s[1], s[2]);
    return rc ? rc : xform_text(j, v, "scale", &p->xform, text);
}

static int text_key(jp *j, const yaml_node_t *v, const char *key, char *out, size_t size)
{
    int rc = want(j, v, YAML_SCALAR_NODE, key, key[0] == 'm' ? "a model's path" : "text");
    if (!rc && !text_of(v)[0]) rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "%s must not be empty", key);
    if (!rc && strlen(text_of(v)) >= size) rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "%s is too long", key);
    if (!rc && key[0] == 'm') job_path(j, text_of(v), out, size);
    else if (!rc) snprintf(out, size, "%s", text_of(v));
    return rc;
}

/* One key of a part. */
static int part_key(jp *j, const yaml_node_t *k, const yaml_node_t *v, lam_build_part *p, char *model, char *name)
{
    const char *key = text_of(k);
    if (!strcmp(key, "model")) return text_key(j, v, key, model, 4096);
    if (!strcmp(key, "name")) return text_key(j, v, key, name, 128);
    if (!strcmp(key, "units")) return units(j, v, p);
    if (!strcmp(key, "scale")) return scale(j, v, p);
    if (!strcmp(key, "rotate")) return rotate(j, v, p);
    if (!strcmp(key, "copies")) return copies(j, v, p);
    if (!strcmp(key, "style")) return part_style(j, v, p);
    if (!strcmp(key, "z")) {
        int rc = number(j, v, key, &p->z);
        if (!rc && p->z < 0)
            rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "z must be 0 or more (above the plate), got '%s'",
                             text_of(v));
        return rc;
    }
    if (!strcmp(key, "at")) {
        p->has_at = 1;
        return numbers(j, v, key, p->at, 2, 0);
    }
    return unknown(j, k, "a part", part_keys, NPART, 0);
}

static int one_part(jp *j, const yaml_node_t *m)
{
    int rc = want(j, m, YAML_MAPPING_NODE, "a part", "a mapping (model: PATH, copies: N, ...)");
    lam_build_part p;
    lam_build_part_init(&p);
    static char model[4096], name[128];
    model[0] = name[0] = '\0';
    const yaml_node_t *at = NULL;
    for (yaml_node_pair_t *q = rc ? NULL : m->data.mapping.pairs.start; !rc && q < m->data.mapping.pairs.top; q++) {
        const yaml_node_t *k = lam_yaml_node(&j->d, q->key);
        rc = want(j, k, YAML_SCALAR_NODE, "a part's key", "text");
        if (!rc) rc = twice(j, m, q);
        if (!rc && !strcmp(text_of(k), "at")) at = k;
        if (!rc) rc = part_key(j, k, lam_yaml_node(&j->d, q->value), &p, model, name);
    }
    if (rc) return rc;
    if (!model[0]) return lam_yaml_at(&j->d, m->start_mark, LAM_EINVAL, "the part names no model: add model: PATH");
    if (at && p.copies > 1)
        return lam_yaml_at(&j->d, at->start_mark, LAM_EINVAL,
                           "a part with at has one copy: list each placed copy as a part of its own");
    p.model = model;
    p.name = name[0] ? name : NULL;
    p.line = (long)m->start_mark.line + 1;
    p.column = (long)m->start_mark.column + 1;
    lam_error e;
    lam_error_clear(&e);
    rc = lam_build_part_add(j->b, &p, &e);
    return rc ? lam_yaml_at(&j->d, m->start_mark, rc, "%s", e.msg) : LAM_OK;
}

static int parts(jp *j, const yaml_node_t *root)
{
    const yaml_node_t *v = lookup(j, root, "parts", NULL);
    if (!v)
        return lam_yaml_at(&j->d, root->start_mark, LAM_EINVAL, "the job lists no parts: add parts: [{model: PATH}]");
    int rc = want(j, v, YAML_SEQUENCE_NODE, "parts", "a list of parts");
    if (!rc && v->data.sequence.items.start == v->data.sequence.items.top)
        rc = lam_yaml_at(&j->d, v->start_mark, LAM_EINVAL, "parts is empty: list at least one part");
    for (yaml_node_item_t *i = rc ? NULL : v->data.sequence.items.start; !rc && i < v->data.sequence.items.top; i++)
        rc = one_part(j, lam_yaml_node(&j->d, *i));
    return rc;
}

/* ---- the job ------------------------------------------------------------------------------- */

static int no_duplicates(const jp *j, const yaml_node_t *m)
{
    for (yaml_node_pair_t *q = m->data.mapping.pairs.start; q < m->data.mapping.pairs.top; q++) {
        int rc = twice(j, m, q);
        if (rc) return rc;
    }
    return LAM_OK;
}

static int read_job(jp *j)
{
    int rc = lam_yaml_doc_parse(&j->d, "empty build job: expected a mapping (machine: NAME, parts: [...])");
    const yaml_node_t *root = rc ? NULL : yaml_document_get_root_node(&j->d.doc);
    if (!rc && root->type != YAML_MAPPING_NODE)
        rc = lam_yaml_at(&j->d, root->start_mark, LAM_EINVAL, "a build job is a mapping (machine: NAME, parts: [...]), got %s",
                         describe(root));
    if (!rc) rc = no_duplicates(j, root);
    if (!rc) rc = load_machine(j, root);
    if (!rc) rc = overrides(j, root);
    if (!rc) {
        lam_error e;
        lam_error_clear(&e);
        rc = lam_build_new(j->p, j->d.path, &j->b, &e);
        j->p = NULL;
        if (rc) { /* a machine that cannot build a plate: said where it is named */
            const yaml_node_t *m = lookup(j, root, "machine", NULL);
            rc = lam_yaml_at(&j->d, (m ? m : root)->start_mark, rc, "%s", e.msg);
        }
    }
    if (!rc) rc = styles(j, root);
    if (!rc) rc = parts(j, root);
    return rc;
}

int lam_build_load_buf(const char *path, const char *text, size_t len, lam_build **out, lam_error *err)
{
    *out = NULL;
    jp *j = calloc(1, sizeof *j);
    if (!j) return lam_error_nomem(err, "reading a build job");
    j->err = err;
    j->d.path = path ? path : "<job>";
    j->d.text = (char *)text;
    j->d.len = len;
    j->d.what = "a build job";
    j->d.err = err;
    const char *slash = path ? strrchr(path, '/') : NULL;
    if (slash) snprintf(j->dir, sizeof j->dir, "%.*s", (int)(slash - path), path);
    if (slash && slash == path) snprintf(j->dir, sizeof j->dir, "/");
    int rc = read_job(j);
    lam_yaml_doc_free(&j->d);
    lam_profile_free(j->p);
    if (rc) lam_build_free(j->b);
    else *out = j->b;
    free(j);
    return rc;
}

int lam_build_load(const char *path, lam_build **out, lam_error *err)
{
    *out = NULL;
    char *text = NULL;
    size_t len = 0;
    const lam_read_limit limit = { LAM_MAX_PROFILE_BYTES, "a build job", NULL };
    int rc = lam_read_file(path, limit, &text, &len, err);
    if (!rc) rc = lam_build_load_buf(path, text, len, out, err);
    free(text);
    return rc;
}
