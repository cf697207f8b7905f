/* Lua control of hatching in machine:plan (see l_common.h): per-layer
 * parameters, a recipe's own hatcher or its own order of the vectors.
 *
 * Every Lua function runs before planning starts (lam_lua_hatch_prepare),
 * so the planner itself never calls Lua: what the functions return is
 * copied into C arrays that a finalizer frees if Lua raises an error. */
#include "l_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LAM_HATCHCTL "lamina.hatchcontrol"

struct lhatchctl {
    size_t n;
    lam_lua_overrides *ovr;  /* per layer (NULL without a layer function) */
    lam_hatches *given;      /* per layer */
    unsigned char *has;      /* per layer: given[i] is the layer's vectors */
    lam_error err;           /* hatching a layer for `order` failed */
    size_t charged;          /* bytes charged to a sandbox (lam_lua_charge) */
};

static const char *const fn_names[] = { "layer", "hatcher", "order" };

static void ctl_free(lhatchctl *c)
{
    for (size_t i = 0; c->given && i < c->n; i++) lam_hatches_free(&c->given[i]);
    free(c->given);
    free(c->ovr);
    free(c->has);
    c->given = NULL;
    c->ovr = NULL;
    c->has = NULL;
    c->n = 0;
}

static int ctl_gc(lua_State *L)
{
    lhatchctl *c = luaL_checkudata(L, 1, LAM_HATCHCTL);
    ctl_free(c);
    lam_lua_discharge(L, &c->charged);
    return 0;
}

lhatchctl *lam_lua_hatch_split(lua_State *L, int opts)
{
    opts = lua_absindex(L, opts);
    int any = 0;
    if (lua_istable(L, opts))
        for (int f = 0; f < 3; f++) {
            int t = lua_getfield(L, opts, fn_names[f]);
            if (t != LUA_TNIL && t != LUA_TFUNCTION)
                lam_lua_opterror(L, opts, "%s must be a function, got %s", fn_names[f], luaL_typename(L, -1));
            any |= t == LUA_TFUNCTION;
            lua_pop(L, 1);
        }
    if (!any) {
        lua_pushnil(L);
        return NULL;
    }
    /* the options without the functions (the key checks see profile keys only) */
    lua_newtable(L);
    lua_pushnil(L);
    while (lua_next(L, opts)) {
        int skip = 0;
        if (lua_type(L, -2) == LUA_TSTRING)
            for (int f = 0; f < 3; f++) skip |= !strcmp(lua_tostring(L, -2), fn_names[f]);
        if (skip) {
            lua_pop(L, 1);
            continue;
        }
        lua_pushvalue(L, -2);
        lua_insert(L, -2);
        lua_rawset(L, -4);
    }
    lhatchctl *c = lua_newuserdatauv(L, sizeof *c, 1);
    memset(c, 0, sizeof *c);
    if (luaL_newmetatable(L, LAM_HATCHCTL)) {
        lua_pushcfunction(L, ctl_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    /* its user value: {layer = ..., hatcher = ..., order = ..., layers = copy} */
    lua_newtable(L);
    for (int f = 0; f < 3; f++) {
        lua_getfield(L, opts, fn_names[f]);
        lua_setfield(L, -2, fn_names[f]);
    }
    lua_setiuservalue(L, -2, 1);
    lua_insert(L, -2);         /* ... ctl copy */
    lua_replace(L, opts);      /* the copy takes the options' place */
    return c;
}

/* Charge layer i's vectors, kept until the plan is made. */
static void charge_given(lua_State *L, lhatchctl *c, size_t i)
{
    const lam_hatches *h = &c->given[i];
    lam_lua_charge_or_raise(L, &c->charged, h->cap_v * 4 * sizeof *h->v + h->cap_blocks * sizeof *h->blocks,
                            "machine:plan: the vectors of a layer's hatcher or order");
}

/* The table of layer i's parameters, as a hatcher or order function sees
 * them: every planning key of p by its Lua name, `angle` (the core hatch
 * direction of this layer, degrees) and `index` (1-based). */
static void push_params(lua_State *L, const lam_profile *p, const lam_layer *ly)
{
    lua_newtable(L);
    for (size_t k = 0; k < lam_profile_nkeys; k++) {
        const lam_key *key = &lam_profile_keys[k];
        if (!(key->flags & LAM_KEY_PLAN) || key->flags & LAM_KEY_LOADER) continue;
        lam_lua_push_key(L, p, key);
        lua_setfield(L, -2, lam_key_lua_name(key));
    }
    const lam_scan *s = &p->scan.type[LAM_KIND_CORE];
    lua_pushnumber(L, fmod(s->angle + (double)ly->index * s->angle_increment, 360.0));
    lua_setfield(L, -2, "angle");
    lua_pushinteger(L, (lua_Integer)ly->index + 1);
    lua_setfield(L, -2, "index");
}

static void push_vectors(lua_State *L, const lam_hatches *h)
{
    lua_createtable(L, (int)h->nv, 0);
    for (size_t b = 0; b < h->nblocks; b++)
        for (size_t i = 0; i < h->blocks[b].n; i++) {
            const double *v = h->v + 4 * (h->blocks[b].first + i);
            lua_createtable(L, 4, 1);
            for (int j = 0; j < 4; j++) {
                lua_pushnumber(L, v[j]);
                lua_rawseti(L, -2, j + 1);
            }
            lua_pushstring(L, lam_kind_name(h->blocks[b].type));
            lua_setfield(L, -2, "kind");
            lua_rawseti(L, -2, (lua_Integer)(h->blocks[b].first + i) + 1);
        }
}

/* The vectors a function returned (at the top) into h. */
static void read_vectors(lua_State *L, const char *who, size_t layer, lam_hatches *h)
{
    char b[64];
    if (!lua_istable(L, -1))
        luaL_error(L, "%s (layer %I) must return a table of vectors {x0, y0, x1, y1}, got %s", who,
                   (lua_Integer)layer + 1, lam_lua_describe(L, -1, b, sizeof b));
    lam_hatches_clear(h);
    lua_Unsigned n = lua_rawlen(L, -1);
    int kind = -1;
    for (lua_Unsigned i = 1; i <= n; i++) {
        lua_rawgeti(L, -1, (lua_Integer)i);
        if (!lua_istable(L, -1))
            luaL_error(L, "%s (layer %I): vector %I must be a table {x0, y0, x1, y1}, got %s", who,
                       (lua_Integer)layer + 1, (lua_Integer)i, lam_lua_describe(L, -1, b, sizeof b));
        double v[4];
        for (int j = 0; j < 4; j++) {
            lua_rawgeti(L, -1, j + 1);
            int isnum = 0;
            v[j] = lua_tonumberx(L, -1, &isnum);
            if (!isnum || !isfinite(v[j]))
                luaL_error(L, "%s (layer %I): vector %I: [%d] must be a finite number, got %s", who,
                           (lua_Integer)layer + 1, (lua_Integer)i, j + 1, lam_lua_describe(L, -1, b, sizeof b));
            lua_pop(L, 1);
        }
        int t = LAM_KIND_CORE;
        if (lua_getfield(L, -1, "kind") != LUA_TNIL) {
            size_t klen = 0;
            const char *k = lua_type(L, -1) == LUA_TSTRING ? lua_tolstring(L, -1, &klen) : NULL;
            t = k ? lam_kind_find(k, klen) : -1;
            if (t < LAM_KIND_CORE || t >= LAM_REGIONS) /* a hatch region only */
                luaL_error(L, "%s (layer %I): vector %I: kind must be core, upskin or downskin, got %s", who,
                           (lua_Integer)layer + 1, (lua_Integer)i, lam_lua_describe(L, -1, b, sizeof b));
        }
        lua_pop(L, 2);
        int rc = LAM_OK;
        if (t != kind) {
            double a = atan2(v[3] - v[1], v[2] - v[0]) * (180.0 / 3.14159265358979323846);
            rc = lam_hatches_add_block(h, t, a);
            kind = t;
        }
        if (!rc) rc = lam_hatches_add(h, v[0], v[1], v[2], v[3]);
        if (rc) luaL_error(L, "out of memory");
    }
}

/* machine:plan's order function for layer i (of the copy of the layers at
 * copy; the functions at fns): lamina's vectors for the layer (profile
 * pi), then the recipe's order of them into c->given[i]. 1 when hatching
 * failed (c->err), else 0. */
static int order_layer(lua_State *L, lhatchctl *c, int fns, int copy, size_t i, const lam_profile *pi,
                       const lam_layer *ly)
{
    lam_plan_opts oi;
    lam_lua_plan_opts(pi, &oi);
    lam_scan_cfg cfg = oi.scan;
    cfg.compensation = oi.beam_offset ? oi.bead / 2 : 0;
    size_t ns = cfg.skin_layers > 0 ? (size_t)cfg.skin_layers : 0;
    const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
    size_t nb = 0, na = 0;
    for (size_t k = 1; k <= ns && k <= i; k++) {
        lua_rawgeti(L, copy, (lua_Integer)(i - k) + 1);
        below[nb++] = lam_lua_checklayer(L, -1);
        lua_pop(L, 1);
    }
    for (size_t k = 1; k <= ns && i + k < c->n; k++) {
        lua_rawgeti(L, copy, (lua_Integer)(i + k) + 1);
        above[na++] = lam_lua_checklayer(L, -1);
        lua_pop(L, 1);
    }
    lam_error_clear(&c->err);
    if (lam_hatch_layer(ly, below, nb, above, na, &cfg, &c->given[i], &c->err)) return 1;
    lua_getfield(L, fns, "order");
    push_vectors(L, &c->given[i]);
    lua_rawgeti(L, copy, (lua_Integer)i + 1);
    push_params(L, pi, ly);
    lua_call(L, 3, 1);
    read_vectors(L, "plan: order", i, &c->given[i]);
    lua_pop(L, 1);
    c->has[i] = 1;
    return 0;
}

const lam_error *lam_lua_hatch_prepare(lua_State *L, lhatchctl *c, int layers, const lam_profile *p)
{
    if (!c) return NULL;
    layers = lua_absindex(L, layers);
    int ctl = lua_gettop(L);
    /* find the control userdata (pushed by lam_lua_hatch_split) */
    while (ctl > 0 && lua_touserdata(L, ctl) != c) ctl--;
    lua_getiuservalue(L, ctl, 1);
    int fns = lua_gettop(L);
    /* a copy of the layers: a function cannot take them away */
    size_t n = (size_t)lua_rawlen(L, layers);
    lua_createtable(L, (int)n, 0);
    for (size_t i = 1; i <= n; i++) {
        lua_rawgeti(L, layers, (lua_Integer)i);
        lua_rawseti(L, -2, (lua_Integer)i);
    }
    lua_setfield(L, fns, "layers");
    lua_getfield(L, fns, "layers");
    int copy = lua_gettop(L);
    c->n = n;
    /* a sandbox counts what the plan holds for the recipe's functions */
    lam_lua_charge_or_raise(L, &c->charged, (n ? n : 1) * (sizeof *c->given + 1 + sizeof *c->ovr),
                            "machine:plan: the layers' hatching options");
    c->given = calloc(n ? n : 1, sizeof *c->given);
    c->has = calloc(n ? n : 1, 1);
    c->ovr = calloc(n ? n : 1, sizeof *c->ovr);
    if (!c->given || !c->has || !c->ovr) luaL_error(L, "out of memory");
    int has_layer = lua_getfield(L, fns, "layer") == LUA_TFUNCTION;
    int has_hatcher = lua_getfield(L, fns, "hatcher") == LUA_TFUNCTION;
    int has_order = lua_getfield(L, fns, "order") == LUA_TFUNCTION;
    lua_pop(L, 3);
    for (size_t i = 0; i < n; i++) {
        lam_lua_check_interrupt(L);
        lam_profile pi = *p;
        if (has_layer) {
            lua_getfield(L, fns, "layer");
            lua_rawgeti(L, copy, (lua_Integer)i + 1);
            lua_pushinteger(L, (lua_Integer)i + 1);
            lua_call(L, 2, 1);
            if (lua_istable(L, -1)) {
                lam_lua_read_overrides(L, -1, 3, LAM_KEY_PLAN, NULL, &c->ovr[i]);
                lam_lua_check_readers(L, 3, &c->ovr[i], p); /* as machine:plan's own options */
            }
            else if (!lua_isnil(L, -1))
                luaL_error(L, "plan: layer (layer %I) must return a table of keys or nil, got %s", (lua_Integer)i + 1,
                           luaL_typename(L, -1));
            lua_pop(L, 1);
            lam_lua_apply_overrides(&c->ovr[i], &pi);
        }
        lua_rawgeti(L, copy, (lua_Integer)i + 1);
        const lam_layer *ly = lam_lua_checklayer(L, -1);
        lua_pop(L, 1);
        if (has_hatcher) {
            lua_getfield(L, fns, "hatcher");
            lua_rawgeti(L, copy, (lua_Integer)i + 1);
            push_params(L, &pi, ly);
            lua_call(L, 2, 1);
            read_vectors(L, "plan: hatcher", i, &c->given[i]);
            lua_pop(L, 1);
            c->has[i] = 1;
            charge_given(L, c, i);
        } else if (has_order) {
            if (order_layer(L, c, fns, copy, i, &pi, ly)) break;
            charge_given(L, c, i);
        }
    }
    lua_settop(L, fns - 1);
    return c->err.code ? &c->err : NULL;
}

void lam_lua_hatch_profile(const lhatchctl *c, size_t i, lam_profile *p)
{
    if (c && c->ovr && i < c->n) lam_lua_apply_overrides(&c->ovr[i], p);
}

const lam_hatches *lam_lua_hatch_given(const lhatchctl *c, size_t i)
{
    return c && c->has && i < c->n && c->has[i] ? &c->given[i] : NULL;
}
