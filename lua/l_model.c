/* lamina.model: a loaded solid (lamina.load). Fields are what `lamina info`
 * reports; methods give the bounding box, shells and triangles, and slice
 * it (model:slice lives in l_layer.c). */
#include "repair.h"
#include "l_common.h"

#include "xform.h"

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

/* ---- lamina.load's options: the command line's load options ------------- */

static const char *const load_keys[] = { "units", "scale", "rotate", "translate", "place", "repair", "machine", NULL };

/* text through one of xform.h's parsers; a bad one raises, naming key and text */
static void parse_text(lua_State *L, lam_xform *x, const char *key, const char *text,
                       int (*parse)(lam_xform *, const char *, lam_error *))
{
    lam_error err;
    lam_error_clear(&err);
    char b[64];
    lua_pushstring(L, text);
    if (parse(x, text, &err)) lam_lua_opterror(L, 2, "%s %s: %s", key, lam_lua_describe(L, -1, b, sizeof b), err.msg);
    lua_pop(L, 1);
}

/* A number (or text of numbers) at the top: appended to buf as "a,b,c" */
static void add_number(lua_State *L, const char *key, char *buf, size_t size)
{
    char b[64];
    if (lua_type(L, -1) != LUA_TNUMBER)
        lam_lua_opterror(L, 2, "%s must hold numbers, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    size_t n = strlen(buf);
    snprintf(buf + n, size - n, "%s%.17g", n ? "," : "", (double)lua_tonumber(L, -1));
}

/* scale (a number, {fx, fy, fz} or text) and translate ({x, y, z} or text) */
static void numbers_opt(lua_State *L, lam_xform *x, const char *key, int one,
                        int (*parse)(lam_xform *, const char *, lam_error *))
{
    char text[256] = "", b[64];
    int ty = lua_getfield(L, 2, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return;
    }
    if (ty == LUA_TSTRING) {
        parse_text(L, x, key, lua_tostring(L, -1), parse);
    } else if (ty == LUA_TNUMBER && one) {
        add_number(L, key, text, sizeof text);
        parse_text(L, x, key, text, parse);
    } else if (ty == LUA_TTABLE) {
        lua_Integer n = (lua_Integer)lua_rawlen(L, -1);
        if (n != 3) lam_lua_opterror(L, 2, "%s must be a list of 3 numbers, got %d", key, (int)n);
        for (int k = 1; k <= 3; k++) {
            lua_rawgeti(L, -1, k);
            add_number(L, key, text, sizeof text);
            lua_pop(L, 1);
        }
        parse_text(L, x, key, text, parse);
    } else {
        lam_lua_opterror(L, 2, "%s must be %s, got %s", key, one ? "a number, {fx, fy, fz} or text" : "{x, y, z} or text",
                         lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
}

/* rotate: "x:90" (or "x:90,z:45") or a list of them, applied in order */
static void rotate_opt(lua_State *L, lam_xform *x)
{
    char b[64];
    int ty = lua_getfield(L, 2, "rotate");
    if (ty == LUA_TSTRING) {
        parse_text(L, x, "rotate", lua_tostring(L, -1), lam_xform_parse_rotate);
    } else if (ty == LUA_TTABLE) {
        lua_Integer n = (lua_Integer)lua_rawlen(L, -1);
        for (lua_Integer i = 1; i <= n; i++) {
            if (lua_rawgeti(L, -1, i) != LUA_TSTRING)
                lam_lua_opterror(L, 2, "rotate[%d] must be text such as \"x:90\", got %s", (int)i,
                                 lam_lua_describe(L, -1, b, sizeof b));
            parse_text(L, x, "rotate", lua_tostring(L, -1), lam_xform_parse_rotate);
            lua_pop(L, 1);
        }
    } else if (ty != LUA_TNIL) {
        lam_lua_opterror(L, 2, "rotate must be text such as \"x:90\" or a list of them, got %s",
                         lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
}

/* The mm of the target machine's unit: machine= (an object or a name, as
 * lamina.machine takes it), else mm; centre: its plate's (place="plate") */
static double machine_mm(lua_State *L, double centre[2])
{
    centre[0] = centre[1] = 0;
    char b[64];
    int ty = lua_getfield(L, 2, "machine");
    double mm = 1;
    if (ty == LUA_TSTRING) {
        lua_pushcfunction(L, lam_lua_machine);
        lua_pushvalue(L, -2);
        lua_call(L, 1, 2);
        if (lua_isnil(L, -2)) lam_lua_opterror(L, 2, "machine: %s", lua_tostring(L, -1));
        lua_pop(L, 1);
        mm = lam_profile_unit_mm(&lam_lua_checkmachine(L, -1)->p);
        lam_profile_plate_centre(&lam_lua_checkmachine(L, -1)->p, centre);
        lua_pop(L, 1);
    } else if (ty != LUA_TNIL) {
        if (!LAM_TESTUD(L, -1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE))
            lam_lua_opterror(L, 2, "machine must be a lamina.machine or a machine's name, got %s",
                             lam_lua_describe(L, -1, b, sizeof b));
        mm = lam_profile_unit_mm(&lam_lua_checkmachine(L, -1)->p);
        lam_profile_plate_centre(&lam_lua_checkmachine(L, -1)->p, centre);
    }
    lua_pop(L, 1);
    return mm;
}

/* The options table at argument 2 (absent or nil: the defaults) into x */
static void load_opts(lua_State *L, lam_xform *x, int *no_repair)
{
    lam_xform_init(x);
    *no_repair = 0;
    if (lua_isnoneornil(L, 2)) return;
    luaL_checktype(L, 2, LUA_TTABLE);
    lam_lua_checkkeys(L, 2, 2, load_keys);
    char b[64];
    const char *units = NULL;
    if (lua_getfield(L, 2, "units") != LUA_TNIL) {
        units = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
        if (!units || !(lam_unit_mm(units) > 0))
            lam_lua_opterror(L, 2, "units must be mm, cm, m, um, in or ft, got %s", lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
    double mm = machine_mm(L, x->plate_centre);
    if (units) {
        if (!(mm > 0)) lam_lua_opterror(L, 2, "units: the machine's units are unknown");
        lam_xform_scale_by(x, lam_unit_mm(units) / mm);
    }
    numbers_opt(L, x, "scale", 1, lam_xform_parse_scale);
    rotate_opt(L, x);
    numbers_opt(L, x, "translate", 0, lam_xform_parse_translate);
    if (lua_getfield(L, 2, "place") != LUA_TNIL) {
        if (lua_type(L, -1) != LUA_TSTRING)
            lam_lua_opterror(L, 2, "place must be \"plate\" or \"none\", got %s", lam_lua_describe(L, -1, b, sizeof b));
        parse_text(L, x, "place", lua_tostring(L, -1), lam_xform_parse_place);
    }
    lua_pop(L, 1);
    int repair = 1;
    lam_lua_boolfield(L, 2, 2, "repair", &repair);
    *no_repair = !repair;
}

/* lamina.load(path [, opts]) -> model | nil, message
 * opts: the command line's load options (units=, scale=, rotate=,
 * translate=, place=, repair=false for --no-repair, machine= for the units
 * to convert into); a bad option raises, a file that does not load
 * returns nil and the message.
 * In a sandbox with a memory limit the model is charged to it: a file
 * larger than the room left is refused before it is read (a model file is
 * read whole, core/base/file.h; the model then takes 0.3x an ASCII STL with
 * long numbers, 1.6x a binary STL, and up to about 2.5x while it is
 * built), and a model that turns out larger than the room is freed and
 * refused. */
int lam_lua_load(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    lam_xform x;
    int no_repair;
    load_opts(L, &x, &no_repair); /* before anything is allocated: it may raise */
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
    lam_load_opts o = { .xform = &x, .no_repair = no_repair };
    if (lam_model_load_opts(path, &o, &u->m, &err)) return lam_lua_fail(L, &err);
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

/* model.repair: what repair on load did (repair.h's rows, and ran). */
static void push_repair(lua_State *L, const lam_repair_report *r)
{
    lua_createtable(L, 0, 20);
    lua_pushboolean(L, r->ran);
    lua_setfield(L, -2, "ran");
#define COUNT(f) lua_pushinteger(L, (lua_Integer)r->f), lua_setfield(L, -2, #f);
    LAM_REPAIR_COUNTS(COUNT)
#undef COUNT
#define MEASURE(f) lua_pushnumber(L, r->f), lua_setfield(L, -2, #f);
    LAM_REPAIR_MEASURES(MEASURE)
#undef MEASURE
    lua_pushboolean(L, r->crossings_unknown);
    lua_setfield(L, -2, "crossings_unknown");
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
    else if (strcmp(k, "repair") == 0) push_repair(L, &m->repair);
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
