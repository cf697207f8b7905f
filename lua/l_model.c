/* lamina.model: a loaded solid (lamina.load). Fields are what `lamina info`
 * reports; methods give the bounding box, shells and triangles, and slice
 * it (model:slice lives in l_layer.c). */
#include "l_common.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

lmodel *lam_lua_checkmodel(lua_State *L, int idx)
{
    lmodel *u = LAM_CHECKUD(L, idx, lmodel, LAM_MODEL, LAM_TAG_MODEL);
    if (!u->m) luaL_error(L, "attempt to use a collected " LAM_MODEL);
    return u;
}

void lam_lua_model_free(lua_State *L, lmodel *u)
{
    lam_model_free(u->m);
    u->m = NULL;
    lam_lua_discharge(L, &u->charged);
}

/* lamina.load(path) -> model | nil, message
 * In a sandbox with a memory limit the model is charged to it: a file
 * larger than the room left is refused before it is read (a model file is
 * read whole, core/base/file.h; the model then takes 0.3x an ASCII STL with
 * long numbers, 1.6x a binary STL, and up to about 2.5x while it is
 * built), and a model that turns out larger than the room is freed and
 * refused. */
int lam_lua_load(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    int n = lam_lua_denied(L, path, 0);
    if (n) return n;
    lmodel *u = lua_newuserdatauv(L, sizeof *u, 0);
    memset(u, 0, sizeof *u);
    u->tag = LAM_TAG_MODEL;
    luaL_setmetatable(L, LAM_MODEL);
    struct stat st;
    size_t room = 0;
    if (stat(path, &st) == 0 && st.st_size > 0 && !lam_lua_charge(L, &room, (size_t)st.st_size))
        lam_lua_memory_raise(L, "%s: a model file of %zu bytes", path, (size_t)st.st_size);
    lam_lua_discharge(L, &room); /* a check only: the model is charged as it is, below */
    lam_error err;
    lam_error_clear(&err);
    if (lam_model_load(path, &u->m, &err)) return lam_lua_fail(L, &err);
    size_t bytes = sizeof *u->m + lam_model_bytes(u->m, NULL);
    if (!lam_lua_charge(L, &u->charged, bytes)) {
        lam_lua_model_free(L, u);
        lam_lua_memory_raise(L, "%s: the model takes %zu bytes", path, bytes);
    }
    return 1;
}

static int m_gc(lua_State *L)
{
    lmodel *u = LAM_CHECKUD(L, 1, lmodel, LAM_MODEL, LAM_TAG_MODEL);
    if (u->busy) { /* a slicing run is reading it: that run frees it */
        u->doomed = 1;
        return 0;
    }
    lam_lua_model_free(L, u);
    return 0;
}

static int m_tostring(lua_State *L)
{
    lmodel *u = LAM_CHECKUD(L, 1, lmodel, LAM_MODEL, LAM_TAG_MODEL);
    if (!u->m) lua_pushliteral(L, LAM_MODEL " (collected)");
    else
        lua_pushfstring(L, LAM_MODEL " (%s: %I triangles, %I shell%s)", u->m->path, (lua_Integer)u->m->mesh.ntris,
                        (lua_Integer)u->m->nshells, u->m->nshells == 1 ? "" : "s");
    return 1;
}

static int m_len(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)lam_lua_checkmodel(L, 1)->m->mesh.ntris);
    return 1;
}

static int m_fields(lua_State *L)
{
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    const lam_model_stats *s = &m->stats;
    const char *k = lua_tostring(L, 2);
    static const char *const counts[] = { "ntriangles", "vertices", "edges", "shells", "cavities", "wires",
                                          "boundary_edges", "nonmanifold_edges", "degenerate_triangles",
                                          "orientation_conflicts", NULL };
    const size_t values[] = { s->triangles, s->vertices, s->edges, s->shells, s->cavities, s->wires,
                              s->boundary_edges, s->nonmanifold_edges, s->degenerate_tris,
                              s->orientation_conflicts };
    for (int i = 0; counts[i]; i++)
        if (strcmp(k, counts[i]) == 0) {
            lua_pushinteger(L, (lua_Integer)values[i]);
            return 1;
        }
    if (strcmp(k, "path") == 0) lua_pushstring(L, m->path ? m->path : "");
    else if (strcmp(k, "format") == 0) lua_pushstring(L, m->format);
    else if (strcmp(k, "area") == 0) lua_pushnumber(L, s->area);
    else if (strcmp(k, "volume") == 0) lua_pushnumber(L, s->volume);
    else if (strcmp(k, "closed") == 0) lua_pushboolean(L, s->boundary_edges == 0);
    else lua_pushnil(L);
    return 1;
}

/* model:bbox() -> xmin, ymin, zmin, xmax, ymax, zmax */
static int m_bbox(lua_State *L)
{
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    for (int j = 0; j < 6; j++) lua_pushnumber(L, m->stats.bbox[j]);
    return 6;
}

static void push_bbox(lua_State *L, const double bb[6])
{
    lua_createtable(L, 6, 0);
    for (int j = 0; j < 6; j++) {
        lua_pushnumber(L, bb[j]);
        lua_rawseti(L, -2, j + 1);
    }
}

/* model:shell(i) -> {triangles=, volume=, area=, cavity=, enclosing=, bbox={...}} */
static int m_shell(lua_State *L)
{
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    lua_Integer i = luaL_checkinteger(L, 2);
    luaL_argcheck(L, i >= 1 && (lua_Unsigned)i <= (lua_Unsigned)m->nshells, 2, "shell index out of range");
    const lam_shell sh = m->shells[i - 1]; /* a copy: the pushes below may run the collector */
    lua_createtable(L, 0, 6);
    lua_pushinteger(L, (lua_Integer)sh.ntris);
    lua_setfield(L, -2, "triangles");
    lua_pushnumber(L, sh.volume);
    lua_setfield(L, -2, "volume");
    lua_pushnumber(L, sh.area);
    lua_setfield(L, -2, "area");
    lua_pushboolean(L, sh.cavity);
    lua_setfield(L, -2, "cavity");
    lua_pushinteger(L, sh.enclosing);
    lua_setfield(L, -2, "enclosing");
    push_bbox(L, sh.bbox);
    lua_setfield(L, -2, "bbox");
    return 1;
}

static void push_vertex(lua_State *L, const double p[3])
{
    lua_createtable(L, 3, 0);
    for (int j = 0; j < 3; j++) {
        lua_pushnumber(L, p[j]);
        lua_rawseti(L, -2, j + 1);
    }
}

/* Push triangle t (0-based) as a, b, c, shell; returns 4. The coordinates
 * are copied before anything is pushed (a push may run the collector). */
static int push_triangle(lua_State *L, const lam_model *m, size_t t)
{
    double v[3][3];
    for (int j = 0; j < 3; j++) memcpy(v[j], m->mesh.xyz + 3 * (size_t)m->mesh.tris[3 * t + (size_t)j], sizeof v[j]);
    lua_Integer shell = m->tri_shell ? (lua_Integer)m->tri_shell[t] + 1 : 0;
    for (int j = 0; j < 3; j++) push_vertex(L, v[j]);
    if (shell) lua_pushinteger(L, shell);
    else lua_pushnil(L);
    return 4;
}

/* model:triangle(i) -> a, b, c, shell (each vertex a table {x, y, z}) */
static int m_triangle(lua_State *L)
{
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    lua_Integer i = luaL_checkinteger(L, 2);
    luaL_argcheck(L, i >= 1 && (lua_Unsigned)i <= (lua_Unsigned)m->mesh.ntris, 2, "triangle index out of range");
    return push_triangle(L, m, (size_t)i - 1);
}

static int tri_next(lua_State *L)
{
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    lua_Integer i = luaL_checkinteger(L, 2);
    if (i < 0 || (lua_Unsigned)i >= (lua_Unsigned)m->mesh.ntris) return 0;
    lua_pushinteger(L, i + 1);
    return 1 + push_triangle(L, m, (size_t)i);
}

/* model:triangles() -> iterator: for i, a, b, c, shell in model:triangles() */
static int m_triangles(lua_State *L)
{
    lam_lua_checkmodel(L, 1);
    lua_pushcfunction(L, tri_next);
    lua_pushvalue(L, 1);
    lua_pushinteger(L, 0);
    return 3;
}

static const luaL_Reg model_meta[] = {
    { "__gc", m_gc },
    { "__tostring", m_tostring },
    { "__len", m_len },
    { NULL, NULL },
};

static const luaL_Reg model_methods[] = {
    { "bbox", m_bbox },
    { "shell", m_shell },
    { "triangle", m_triangle },
    { "triangles", m_triangles },
    { NULL, NULL },
};

void lam_lua_open_model(lua_State *L)
{
    lam_lua_newclass(L, LAM_MODEL, model_meta, model_methods, m_fields);
}
