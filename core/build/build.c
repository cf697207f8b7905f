/* A build's description: see build.h. */
#include "build.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *dup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

int lam_region_find(const char *name)
{
    for (int r = 0; r < LAM_REGIONS; r++)
        if (!strcmp(name, lam_kind_name(r))) return r;
    return -1;
}

/* The row of short key `key` in region r, when that row lives in the
 * region's lam_scan (a number or a choice), else NULL. */
static const lam_key *region_row(int r, const char *key)
{
    char name[128];
    if (r == LAM_KIND_CORE) snprintf(name, sizeof name, "%s", key);
    else snprintf(name, sizeof name, "%s.%s", lam_kind_name(r), key);
    const lam_key *k = lam_key_find(name);
    if (!k || strcmp(k->name, name)) return NULL; /* an alias or a flat name: not this region's */
    size_t lo = offsetof(lam_profile, scan) + offsetof(lam_scan_cfg, type) + (size_t)r * sizeof(lam_scan);
    if (k->offset < lo || k->offset >= lo + sizeof(lam_scan)) return NULL;
    if (k->type == LAM_KEY_STRING || k->type == LAM_KEY_TEMPLATE) return NULL;
    return k;
}

int lam_style_key_check(const char *key, lam_error *err)
{
    for (int r = 0; r < LAM_REGIONS; r++)
        if (region_row(r, key)) return LAM_OK;
    const char *names[LAM_KEYS_MAX];
    size_t n = 0;
    for (size_t i = 0; i < lam_profile_nkeys && n < LAM_KEYS_MAX; i++) {
        const char *s = lam_key_short(&lam_profile_keys[i]);
        int ok = 0;
        for (int r = 0; r < LAM_REGIONS && !ok; r++) ok = region_row(r, s) != NULL;
        if (ok) names[n++] = s;
    }
    const char *near = lam_key_nearest(key, names, n);
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s is not a build style key%s%s%s", key,
                         near ? " (did you mean " : " (a style sets exposure and hatching keys: power, speed, "
                                                    "hatch_distance, ...", near ? near : "", near ? "?)" : ")");
}

int lam_build_new(lam_profile *p, const char *path, lam_build **out, lam_error *err)
{
    *out = NULL;
    if (p->process != LAM_PROCESS_SLS) {
        int rc = lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                               "machine %s is a %s profile: a build plans a powder-bed (sls) plate", p->name,
                               p->process == LAM_PROCESS_LADRP ? "ladrp" : "other");
        lam_profile_free(p);
        return rc;
    }
    lam_build *b = calloc(1, sizeof *b);
    if (!b || (path && !(b->path = dup(path)))) {
        free(b);
        lam_profile_free(p);
        return lam_error_nomem(err, "making a build");
    }
    b->profile = p;
    *out = b;
    return LAM_OK;
}

void lam_build_free(lam_build *b)
{
    if (!b) return;
    for (size_t i = 0; i < b->nstyles; i++) {
        free(b->styles[i].name);
        for (size_t k = 0; k < b->styles[i].nkeys; k++) {
            free(b->styles[i].keys[k].key);
            free(b->styles[i].keys[k].text);
        }
    }
    for (size_t i = 0; i < b->nparts; i++) {
        free(b->parts[i].model);
        free(b->parts[i].name);
    }
    free(b->styles);
    free(b->parts);
    free(b->path);
    lam_profile_free(b->profile);
    free(b);
}

int lam_build_style_find(const lam_build *b, const char *name)
{
    for (size_t i = 0; i < b->nstyles; i++)
        if (!strcmp(b->styles[i].name, name)) return (int)i;
    return -1;
}

static int new_style(lam_build *b, const char *name, long line, long column, lam_error *err)
{
    if (b->nstyles >= LAM_BUILD_MAX_STYLES)
        return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "more than %d build styles", LAM_BUILD_MAX_STYLES);
    lam_build_style *ns = realloc(b->styles, (b->nstyles + 1) * sizeof *ns);
    if (!ns) return lam_error_nomem(err, "adding a build style");
    b->styles = ns;
    lam_build_style *s = &ns[b->nstyles];
    memset(s, 0, sizeof *s);
    if (!(s->name = dup(name))) return lam_error_nomem(err, "adding a build style");
    s->line = line;
    s->column = column;
    b->nstyles++;
    return LAM_OK;
}

int lam_build_style_set(lam_build *b, const char *name, const char *key, const char *text, long line, long column,
                        lam_error *err)
{
    int rc = lam_style_key_check(key, err);
    if (rc) return rc;
    int i = lam_build_style_find(b, name);
    if (i < 0) {
        if ((rc = new_style(b, name, line, column, err))) return rc;
        i = (int)b->nstyles - 1;
    }
    lam_build_style *s = &b->styles[i];
    lam_style_key *k = NULL;
    for (size_t j = 0; j < s->nkeys && !k; j++)
        if (!strcmp(s->keys[j].key, key)) k = &s->keys[j];
    if (!k) {
        if (s->nkeys >= LAM_BUILD_MAX_KEYS)
            return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "style %s: more than %d keys", name, LAM_BUILD_MAX_KEYS);
        k = &s->keys[s->nkeys];
        if (!(k->key = dup(key))) return lam_error_nomem(err, "adding a build style");
        k->text = NULL;
        s->nkeys++;
    }
    char *t = dup(text);
    if (!t) return lam_error_nomem(err, "adding a build style");
    free(k->text);
    k->text = t;
    k->line = line;
    k->column = column;
    return LAM_OK;
}

void lam_build_part_init(lam_build_part *spec)
{
    memset(spec, 0, sizeof *spec);
    lam_xform_init(&spec->xform);
    spec->copies = 1;
    for (int r = 0; r < LAM_REGIONS; r++) spec->style[r] = -1;
}

static size_t instances(const lam_build *b)
{
    size_t n = 0;
    for (size_t i = 0; i < b->nparts; i++) n += b->parts[i].copies;
    return n;
}

int lam_build_part_add(lam_build *b, const lam_build_part *spec, lam_error *err)
{
    if (spec->copies < 1 || spec->copies > LAM_BUILD_MAX_COPIES)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "copies must be a whole number from 1 to %d, got %zu",
                             LAM_BUILD_MAX_COPIES, spec->copies);
    if (spec->has_at && spec->copies > 1)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "a part with `at` has one copy (list each placed copy as a part of its own)");
    if (!isfinite(spec->z) || spec->z < 0)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "z must be 0 or more (above the plate), got %g", spec->z);
    if (spec->has_at && !(isfinite(spec->at[0]) && isfinite(spec->at[1])))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "at must be two finite numbers");
    for (int r = 0; r < LAM_REGIONS; r++)
        if (spec->style[r] >= (int)b->nstyles)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "style %d is not one of the build's", spec->style[r]);
    if (instances(b) + spec->copies > LAM_BUILD_MAX_PARTS)
        return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "more than %d parts on one plate (copies counted)",
                             LAM_BUILD_MAX_PARTS);
    lam_build_part *np = realloc(b->parts, (b->nparts + 1) * sizeof *np);
    if (!np) return lam_error_nomem(err, "adding a part");
    b->parts = np;
    lam_build_part *p = &np[b->nparts];
    *p = *spec;
    p->model = dup(spec->model);
    p->name = dup(spec->name);
    if (!p->model || (spec->name && !p->name)) {
        free(p->model);
        free(p->name);
        return lam_error_nomem(err, "adding a part");
    }
    b->nparts++;
    return LAM_OK;
}

/* Apply one key of a style to region r of out. */
static int apply_key(lam_profile *out, int r, const lam_build_style *s, const lam_style_key *k, int whole,
                     const char *file, lam_error *err)
{
    const lam_key *row = region_row(r, k->key);
    if (!row) {
        if (whole) return LAM_OK;
        return lam_error_set(err, LAM_EINVAL, file, k->line, k->column,
                             "style %s sets %s, which the %s region does not have", s->name, k->key, lam_kind_name(r));
    }
    double x;
    lam_error e;
    lam_error_clear(&e);
    if (lam_key_scan(row, k->key, k->text, strlen(k->text), &x, &e))
        return lam_error_set(err, e.code, file, k->line, k->column, "style %s: %s", s->name, e.msg);
    lam_key_store(out, row, x);
    return LAM_OK;
}

int lam_build_styled_profile(const lam_profile *p, const lam_build_style *const style_of[LAM_REGIONS], int whole,
                             const char *file, lam_profile *out, lam_error *err)
{
    *out = *p;
    for (int r = 0; r < LAM_REGIONS; r++) {
        const lam_build_style *s = style_of[r];
        if (!s) continue;
        for (size_t k = 0; k < s->nkeys; k++) {
            int rc = apply_key(out, r, s, &s->keys[k], whole, file, err);
            if (rc) return rc;
        }
    }
    return LAM_OK;
}
