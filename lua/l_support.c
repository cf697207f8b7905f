/* Supports from Lua (issue 27, core/plan/support.h): model:supports{...},
 * the support regions of a slicing run's layers for a recipe to inspect,
 * change or replace, and machine:plan's `supports` option, which plans the
 * recipe's own regions (a table, one per layer given, or a generator
 * function) instead of lamina's. A region is a layer (model:supports's, or
 * any layer of the run) or a table of loops {{u1, v1, u2, v2, ...}, ...}
 * in the layer plane, nested by the even-odd rule; nil or false: none. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "l_common.h"

#define LAM_SUPPORTS "lamina.supports" /* the box that frees a plan's supports */

typedef struct lsupports {
    lam_supports *s;
} lsupports;

static int box_gc(lua_State *L)
{
    lsupports *b = luaL_checkudata(L, 1, LAM_SUPPORTS);
    lam_supports_free(b->s);
    b->s = NULL;
    return 0;
}

static lsupports *push_box(lua_State *L)
{
    lsupports *b = lua_newuserdatauv(L, sizeof *b, 0);
    b->s = NULL;
    if (luaL_newmetatable(L, LAM_SUPPORTS)) {
        lua_pushcfunction(L, box_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    return b;
}

/* An empty layer with like's index and heights (NULL: out of memory). */
static lam_layer *empty_like(const lam_layer *like)
{
    lam_layer *R = calloc(1, sizeof *R);
    if (!R) return NULL;
    R->index = like->index;
    R->floor = like->floor;
    R->ceiling = like->ceiling;
    R->width = like->width;
    R->cut = like->cut;
    return R;
}

/* The loops table at idx read into buffers on the stack (two userdata,
 * popped by the caller): raises on a bad loop before anything is
 * allocated outside Lua. */
static lam_loops read_loops(lua_State *L, int idx, const char *what)
{
    lua_Unsigned nl = lua_rawlen(L, idx), np = 0;
    for (lua_Unsigned k = 1; k <= nl; k++) {
        lua_rawgeti(L, idx, (lua_Integer)k);
        lua_Unsigned m = lua_istable(L, -1) ? lua_rawlen(L, -1) : 0;
        if (m < 6 || m % 2) luaL_error(L, "%s[%d] must be a loop {u1, v1, u2, v2, u3, v3, ...}", what, (int)k);
        np += m / 2;
        lua_pop(L, 1);
    }
    double *uv = lua_newuserdatauv(L, (np + 1) * 2 * sizeof *uv, 0);
    size_t *len = lua_newuserdatauv(L, (nl + 1) * sizeof *len, 0);
    size_t at = 0;
    for (lua_Unsigned k = 1; k <= nl; k++) {
        lua_rawgeti(L, idx, (lua_Integer)k);
        lua_Unsigned m = lua_rawlen(L, -1);
        for (lua_Unsigned i = 1; i <= m; i++) {
            lua_rawgeti(L, -1, (lua_Integer)i);
            int isnum = 0;
            double x = lua_tonumberx(L, -1, &isnum);
            if (!isnum || !isfinite(x)) luaL_error(L, "%s[%d][%d] must be a finite number", what, (int)k, (int)i);
            uv[at++] = x;
            lua_pop(L, 1);
        }
        len[k - 1] = m / 2;
        lua_pop(L, 1);
    }
    return (lam_loops){ uv, len, nl, np };
}

/* The region at idx for plan layer `like` as a new layer (NULL: none);
 * raises on anything else. */
static lam_layer *region_at(lua_State *L, int idx, const lam_layer *like, const char *what)
{
    idx = lua_absindex(L, idx);
    if (lua_isnoneornil(L, idx) || (lua_isboolean(L, idx) && !lua_toboolean(L, idx))) return NULL;
    if (luaL_testudata(L, idx, LAM_LAYER)) {
        lam_layer *R = lam_layer_clone(lam_lua_checklayer(L, idx));
        if (!R) luaL_error(L, "out of memory");
        R->index = like->index;
        return R;
    }
    if (!lua_istable(L, idx))
        luaL_error(L, "%s must be a lamina.layer, a table of loops, nil or false, got %s", what, luaL_typename(L, idx));
    lam_loops loops = read_loops(L, idx, what);
    lam_layer *R = empty_like(like);
    lam_error err;
    lam_error_clear(&err);
    int rc = R ? lam_contours_assign(R, &loops, &err) : lam_error_nomem(&err, "reading supports");
    lua_pop(L, 2);
    if (rc) {
        lam_layer_free(R);
        luaL_error(L, "%s: %s", what, err.msg);
    }
    return R;
}

/* The largest run index of the layers in the list at `list`, plus one. */
static size_t list_room(lua_State *L, int list, lua_Unsigned n)
{
    size_t room = 0;
    for (lua_Unsigned i = 0; i < n; i++) {
        const lam_layer *ly = lam_lua_layeritem(L, list, 2, (size_t)i);
        if (ly->index + 1 > room) room = ly->index + 1;
        lua_pop(L, 1);
    }
    return room;
}

lam_supports **lam_lua_supports_option(lua_State *L, int opts, int layers)
{
    opts = lua_absindex(L, opts);
    layers = lua_absindex(L, layers);
    lsupports *b = push_box(L);
    if (lua_isnoneornil(L, opts) || lua_getfield(L, opts, "supports") == LUA_TNIL) {
        if (!lua_isnoneornil(L, opts)) lua_pop(L, 1);
        return &b->s;
    }
    int given = lua_gettop(L), fn = lua_isfunction(L, given);
    if (!fn && !lua_istable(L, given))
        lam_lua_opterror(L, 3, "supports must be a table of regions (one per layer) or a function(layer, i), got %s",
                         luaL_typename(L, given));
    lua_Unsigned n = lua_rawlen(L, layers);
    if (!(b->s = lam_supports_new(list_room(L, layers, n)))) luaL_error(L, "out of memory");
    for (lua_Unsigned i = 0; i < n; i++) {
        const lam_layer *ly = lam_lua_layeritem(L, layers, 2, (size_t)i); /* pushed */
        if (fn) {
            lua_pushvalue(L, given);
            lua_pushvalue(L, -2);
            lua_pushinteger(L, (lua_Integer)i + 1);
            lua_call(L, 2, 1);
        } else {
            lua_rawgeti(L, given, (lua_Integer)i + 1);
        }
        char what[48];
        snprintf(what, sizeof what, "supports[%llu]", (unsigned long long)i + 1);
        lam_supports_set(b->s, ly->index, region_at(L, -1, ly, what));
        lua_pop(L, 2);
    }
    lua_pop(L, 1);
    return &b->s;
}

int lam_lua_supports_auto(lam_supports **box, const lam_layer *const *ls, size_t n, const lam_profile *p,
                          lam_error *err)
{
    if (*box || p->process != LAM_PROCESS_SLS || p->scan.support.type == LAM_SUPPORT_NONE) return LAM_OK;
    return lam_supports_make(ls, n, &p->scan.support, box, err);
}

/* A table of one layer per layer of ls (the list at 4): what `get` gives
 * of s for it, or an empty layer. */
static void push_layers(lua_State *L, const lam_layer **ls, size_t n, const lam_supports *s,
                        const lam_layer *(*get)(const lam_supports *, size_t))
{
    lua_createtable(L, n < 1000000 ? (int)n : 0, 0);
    for (size_t i = 0; i < n; i++) {
        lam_lua_layeritem(L, 4, 2, i);
        const lam_layer *R = get(s, ls[i]->index);
        lam_layer *own = R ? lam_layer_clone(R) : empty_like(ls[i]);
        if (!own) luaL_error(L, "out of memory");
        lam_lua_pushlayer(L, -1, own);
        lua_rawseti(L, -3, (lua_Integer)i + 1);
        lua_pop(L, 1);
    }
}

/* model:supports{layers = , machine = [, support keys]} -> { layer, ..., overhangs = { layer, ... } } */
int lam_lua_supports(lua_State *L)
{
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    lua_getfield(L, 2, "machine");
    lam_profile p = lam_lua_checkmachine(L, 3)->p;
    if (lua_getfield(L, 2, "layers") != LUA_TTABLE) lam_lua_opterror(L, 2, "layers must be the layers of a model:slice run");
    static const char *const own[] = { "layers", "machine", NULL };
    lam_lua_overrides ovr;
    lam_lua_read_overrides(L, 2, 2, LAM_KEY_PLAN, own, &ovr);
    lam_lua_check_readers(L, 2, &ovr, &p);
    lam_lua_apply_overrides(&ovr, &p);
    if (p.process != LAM_PROCESS_SLS) lam_lua_opterror(L, 2, "supports are made for a powder-bed (sls) machine");
    lua_Unsigned n = lua_rawlen(L, 4);
    const lam_layer **ls = lua_newuserdatauv(L, (n + 1) * sizeof *ls, 0);
    for (lua_Unsigned i = 0; i < n; i++) {
        ls[i] = lam_lua_layeritem(L, 4, 2, (size_t)i);
        lua_pop(L, 1);
    }
    lsupports *b = push_box(L);
    lam_error err;
    lam_error_clear(&err);
    if (lam_supports_make(ls, (size_t)n, &p.scan.support, &b->s, &err)) return lam_lua_fail(L, &err);
    push_layers(L, ls, (size_t)n, b->s, lam_supports_region);
    push_layers(L, ls, (size_t)n, b->s, lam_supports_overhang);
    lua_setfield(L, -2, "overhangs");
    return 1;
}
