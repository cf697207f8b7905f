/* lamina.contour: one closed loop of a layer (layer:contours()). A contour
 * userdata is just an index; its user value is the layer, whose data it
 * reads, so it keeps the layer (and through it the model) alive. */
#include "l_common.h"

#include <stdint.h>
#include <string.h>

#include "contour.h"

typedef struct cref {
    const lam_layer *ly;
    const lam_contour *c;
    size_t i;
} cref;

/* The contour at idx with its layer; pushes nothing. */
static cref check(lua_State *L, int idx)
{
    lcontour *u = LAM_CHECKUD(L, idx, lcontour, LAM_CONTOUR, LAM_TAG_CONTOUR);
    if (u->i == SIZE_MAX) luaL_error(L, "attempt to use a collected " LAM_CONTOUR);
    lua_getiuservalue(L, idx, 1);
    llayer *lu = LAM_TESTUD(L, -1, llayer, LAM_LAYER, LAM_TAG_LAYER);
    lua_pop(L, 1); /* the contour keeps its layer alive */
    if (!lu || !lu->L || u->i >= lu->L->ncontours) luaL_error(L, "attempt to use a collected " LAM_CONTOUR);
    cref r = { lu->L, &lu->L->contours[u->i], u->i };
    return r;
}

static int c_gc(lua_State *L)
{
    lcontour *u = LAM_CHECKUD(L, 1, lcontour, LAM_CONTOUR, LAM_TAG_CONTOUR);
    u->i = SIZE_MAX;
    return 0;
}

static int c_tostring(lua_State *L)
{
    lcontour *u = LAM_CHECKUD(L, 1, lcontour, LAM_CONTOUR, LAM_TAG_CONTOUR);
    lua_getiuservalue(L, 1, 1);
    llayer *lu = LAM_TESTUD(L, -1, llayer, LAM_LAYER, LAM_TAG_LAYER);
    if (u->i == SIZE_MAX || !lu || !lu->L || u->i >= lu->L->ncontours) {
        lua_pushliteral(L, LAM_CONTOUR " (collected)");
        return 1;
    }
    const lam_contour *c = &lu->L->contours[u->i];
    lua_pushfstring(L, LAM_CONTOUR " %I of layer %I (%s, depth %d, %I points, area %f)", (lua_Integer)u->i + 1,
                    (lua_Integer)lu->L->index + 1, c->kind == LAM_SOLID ? "solid" : "hole", c->depth,
                    (lua_Integer)c->n, c->area);
    return 1;
}

static int c_len(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)check(L, 1).c->n);
    return 1;
}

static int c_fields(lua_State *L)
{
    cref r = check(L, 1);
    const char *k = lua_tostring(L, 2);
    if (strcmp(k, "kind") == 0) lua_pushstring(L, r.c->kind == LAM_SOLID ? "solid" : "hole");
    else if (strcmp(k, "solid") == 0) lua_pushboolean(L, r.c->kind == LAM_SOLID);
    else if (strcmp(k, "depth") == 0) lua_pushinteger(L, r.c->depth);
    else if (strcmp(k, "area") == 0) lua_pushnumber(L, r.c->area);
    else if (strcmp(k, "perimeter") == 0) lua_pushnumber(L, r.c->perimeter);
    else if (strcmp(k, "index") == 0) lua_pushinteger(L, (lua_Integer)r.i + 1);
    else if (strcmp(k, "z") == 0) lua_pushnumber(L, r.ly->cut);
    else if (strcmp(k, "layer") == 0) lua_getiuservalue(L, 1, 1);
    else if (strcmp(k, "parent") == 0) {
        if (r.c->parent < 0) {
            lua_pushnil(L);
        } else {
            lua_getiuservalue(L, 1, 1);
            lam_lua_pushcontour(L, -1, (size_t)r.c->parent);
        }
    } else lua_pushnil(L);
    return 1;
}

/* contour:contains(u, v) -> boolean (this loop alone, even-odd) */
static int c_contains(lua_State *L)
{
    cref r = check(L, 1);
    double u = (double)luaL_checknumber(L, 2), v = (double)luaL_checknumber(L, 3);
    lua_pushboolean(L, lam_contour_contains(r.ly, r.c, u, v));
    return 1;
}

/* contour:bbox() -> umin, vmin, umax, vmax */
static int c_bbox(lua_State *L)
{
    cref r = check(L, 1);
    for (int j = 0; j < 4; j++) lua_pushnumber(L, r.c->bbox[j]);
    return 4;
}

/* contour:point(i) -> u, v */
static int c_point(lua_State *L)
{
    cref r = check(L, 1);
    lua_Integer i = luaL_checkinteger(L, 2);
    luaL_argcheck(L, i >= 1 && (lua_Unsigned)i <= (lua_Unsigned)r.c->n, 2, "point index out of range");
    const double *p = r.ly->uv + 2 * (r.c->first + (size_t)i - 1);
    lua_pushnumber(L, p[0]);
    lua_pushnumber(L, p[1]);
    return 2;
}

static int points_next(lua_State *L)
{
    cref r = check(L, 1);
    lua_Integer i = luaL_checkinteger(L, 2);
    if (i < 0 || (lua_Unsigned)i >= (lua_Unsigned)r.c->n) return 0;
    const double *p = r.ly->uv + 2 * (r.c->first + (size_t)i);
    lua_pushinteger(L, i + 1);
    if (lua_toboolean(L, lua_upvalueindex(1))) {
        lua_getiuservalue(L, 1, 1);
        const lrun *run = lam_lua_layerrun(L, -1);
        lua_pop(L, 1);
        double xyz[3];
        lam_frame_to_model(&run->frame, p[0], p[1], r.ly->cut, xyz);
        for (int j = 0; j < 3; j++) lua_pushnumber(L, xyz[j]);
        return 4;
    }
    lua_pushnumber(L, p[0]);
    lua_pushnumber(L, p[1]);
    return 3;
}

/* contour:points(["model"]) -> iterator: for i, u, v in c:points() or
 * for i, x, y, z in c:points("model") */
static int c_points(lua_State *L)
{
    check(L, 1);
    static const char *const frames[] = { "layer", "model", NULL };
    int model = luaL_checkoption(L, 2, "layer", frames);
    lua_pushboolean(L, model);
    lua_pushcclosure(L, points_next, 1);
    lua_pushvalue(L, 1);
    lua_pushinteger(L, 0);
    return 3;
}

/* contour:children() -> { contour, ... } directly inside this one */
static int c_children(lua_State *L)
{
    size_t self = check(L, 1).i;
    lua_newtable(L);
    lua_getiuservalue(L, 1, 1);
    lua_Integer n = 0;
    /* re-checked every time: pushing a contour may run the collector */
    for (size_t k = 0; k < check(L, 1).ly->ncontours; k++) {
        if (check(L, 1).ly->contours[k].parent != (long)self) continue;
        lam_lua_pushcontour(L, -1, k);
        lua_rawseti(L, -3, ++n);
    }
    lua_pop(L, 1);
    return 1;
}

static const luaL_Reg contour_meta[] = {
    { "__gc", c_gc },
    { "__tostring", c_tostring },
    { "__len", c_len },
    { NULL, NULL },
};

static const luaL_Reg contour_methods[] = {
    { "contains", c_contains },
    { "bbox", c_bbox },
    { "point", c_point },
    { "points", c_points },
    { "children", c_children },
    { NULL, NULL },
};

void lam_lua_open_contour(lua_State *L)
{
    lam_lua_newclass(L, LAM_CONTOUR, contour_meta, contour_methods, c_fields);
}
