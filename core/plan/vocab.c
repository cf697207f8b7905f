/* The plan's vocabulary; see vocab.h. */
#include "vocab.h"

#include <string.h>

static const char *const kind_names[LAM_KINDS] = { "contour", "core", "upskin", "downskin",
                                                   "support", "deposit", "travel", "jump" };

const char *lam_kind_name(int kind)
{
    return kind >= 0 && kind < LAM_KINDS ? kind_names[kind] : "?";
}

int lam_kind_find(const char *name, size_t len)
{
    for (int k = 0; k < LAM_KINDS; k++)
        if (strlen(kind_names[k]) == len && !memcmp(kind_names[k], name, len)) return k;
    return -1;
}

int lam_kind_exposed(int kind)
{
    return kind != LAM_KIND_TRAVEL && kind != LAM_KIND_JUMP;
}

static const struct {
    const char *key;
    long long def;
} rows[] = {
#define LAM_ATTR_ROW(field, key, def, doc) { key, def },
    LAM_ATTRS(LAM_ATTR_ROW)
#undef LAM_ATTR_ROW
};

lam_attrs lam_attrs_default(void)
{
    lam_attrs a;
    for (size_t i = 0; i < LAM_NATTRS; i++) lam_attr_set(&a, i, rows[i].def);
    return a;
}

const char *lam_attr_key(size_t i) { return rows[i].key; }

long long lam_attr_default(size_t i) { return rows[i].def; }

/* lam_attrs is LAM_NATTRS long longs in row order (vocab.h), so an
 * attribute is its index into them. */
long long lam_attr_get(const lam_attrs *a, size_t i)
{
    long long v;
    memcpy(&v, (const char *)a + i * sizeof v, sizeof v);
    return v;
}

void lam_attr_set(lam_attrs *a, size_t i, long long v)
{
    memcpy((char *)a + i * sizeof v, &v, sizeof v);
}

long long lam_attrs_id(const lam_attrs *a) { return a->label ? a->label : a->part; }
