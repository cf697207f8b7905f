/* The `lamina` Lua module: luaopen_lamina, the module table, and helpers
 * every type file uses (classes, option fields, the io.open error
 * convention, the interrupt flag). Built into the executable and as the C
 * module lamina.so for a stock lua5.4 (package.cpath). See lua/API.md. */
#include "l_common.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plugin.h"
#include "pool.h"

LUAMOD_API int luaopen_lamina(lua_State *L);

volatile sig_atomic_t lam_lua_interrupt = 0;

void lam_lua_check_interrupt(lua_State *L)
{
    if (lam_lua_interrupt) luaL_error(L, "interrupted");
    lam_lua_sandbox_check_time(L);
}

int lam_lua_stopping(lua_State *L)
{
    return lam_lua_interrupt || lam_lua_sandbox_timed_out(L);
}

#define THREADS_KEY "lamina.threads"

unsigned lam_lua_threads(lua_State *L)
{
    lua_Integer n = lua_getfield(L, LUA_REGISTRYINDEX, THREADS_KEY) == LUA_TNUMBER ? lua_tointeger(L, -1) : 1;
    lua_pop(L, 1);
    return n >= 1 && n <= LAM_MAX_THREADS ? (unsigned)n : 1;
}

void lam_lua_set_threads(lua_State *L, unsigned n)
{
    lua_pushinteger(L, (lua_Integer)n);
    lua_setfield(L, LUA_REGISTRYINDEX, THREADS_KEY);
}

/* lamina.threads() -> the number of threads machine:plan uses by default */
static int l_threads(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)lam_lua_threads(L));
    return 1;
}

/* ---- classes ------------------------------------------------------------ */

/* __index: upvalue 1 the methods table, upvalue 2 the fields function. */
static int class_index(lua_State *L)
{
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
    lua_pop(L, 1);
    if (lua_type(L, 2) != LUA_TSTRING) return 0;
    lua_CFunction fields = lua_tocfunction(L, lua_upvalueindex(2));
    return fields ? fields(L) : 0;
}

void lam_lua_newclass(lua_State *L, const char *tname, const luaL_Reg *meta, const luaL_Reg *methods,
                      lua_CFunction fields)
{
    luaL_newmetatable(L, tname);
    luaL_setfuncs(L, meta, 0);
    lua_newtable(L);
    luaL_setfuncs(L, methods, 0);
    if (fields) lua_pushcfunction(L, fields);
    else lua_pushnil(L);
    lua_pushcclosure(L, class_index, 2);
    lua_setfield(L, -2, "__index");
    lua_pop(L, 1);
}

/* ---- userdata checks -------------------------------------------------------- */

void *lam_lua_testud(lua_State *L, int idx, const char *tname, size_t size, unsigned tag)
{
    unsigned *p = luaL_testudata(L, idx, tname);
    return p && lua_rawlen(L, idx) == size && *p == tag ? p : NULL;
}

void *lam_lua_checkud(lua_State *L, int idx, const char *tname, size_t size, unsigned tag)
{
    unsigned *p = luaL_checkudata(L, idx, tname);
    if (lua_rawlen(L, idx) != size || *p != tag) luaL_error(L, "corrupt %s (its metatable was replaced)", tname);
    return p;
}

/* ---- boxes ---------------------------------------------------------------- */

#define LAM_BOX "lamina.box"

typedef struct lbox {
    unsigned tag;
    void *p;
} lbox;

static int box_gc(lua_State *L)
{
    lbox *box = LAM_CHECKUD(L, 1, lbox, LAM_BOX, LAM_TAG_BOX);
    free(box->p);
    box->p = NULL;
    return 0;
}

void **lam_lua_newbox(lua_State *L)
{
    lbox *box = lua_newuserdatauv(L, sizeof *box, 0);
    box->tag = LAM_TAG_BOX;
    box->p = NULL;
    if (luaL_newmetatable(L, LAM_BOX)) {
        lua_pushcfunction(L, box_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    return &box->p;
}

/* ---- errors and options ------------------------------------------------ */

int lam_lua_fail(lua_State *L, const lam_error *err)
{
    char buf[2048];
    luaL_pushfail(L);
    lua_pushstring(L, lam_error_format(err, buf, sizeof buf));
    return 2;
}

int lam_lua_opterror(lua_State *L, int arg, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return luaL_argerror(L, arg, msg);
}

const char *lam_lua_describe(lua_State *L, int idx, char *buf, size_t size)
{
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
        if (lua_isinteger(L, idx)) snprintf(buf, size, "%lld", (long long)lua_tointeger(L, idx));
        else snprintf(buf, size, "%.14g", (double)lua_tonumber(L, idx));
        break;
    case LUA_TSTRING: {
        size_t len, k = 0, i = 0;
        const char *s = lua_tolstring(L, idx, &len);
        if (size < 16) {
            snprintf(buf, size, "a string");
            break;
        }
        buf[k++] = '\'';
        for (; i < len && k + 6 < size; i++) buf[k++] = (s[i] >= 0x20 && s[i] < 0x7f) ? s[i] : '?';
        if (i < len) {
            memcpy(buf + k, "...", 3);
            k += 3;
        }
        buf[k++] = '\'';
        buf[k] = '\0';
        break;
    }
    case LUA_TBOOLEAN:
        snprintf(buf, size, "%s", lua_toboolean(L, idx) ? "true" : "false");
        break;
    case LUA_TNIL:
        snprintf(buf, size, "nil");
        break;
    default: {
        int t = luaL_getmetafield(L, idx, "__name"); /* pushes nothing when absent */
        snprintf(buf, size, "a %s", t == LUA_TSTRING ? lua_tostring(L, -1) : luaL_typename(L, idx));
        if (t != LUA_TNIL) lua_pop(L, 1);
    }
    }
    return buf;
}

void lam_lua_checkkeys(lua_State *L, int t, int arg, const char *const *allowed)
{
    t = lua_absindex(L, t);
    lua_pushnil(L);
    while (lua_next(L, t)) {
        lua_pop(L, 1); /* the value */
        if (lua_type(L, -1) != LUA_TSTRING) {
            char b[64];
            lam_lua_opterror(L, arg, "unexpected key %s (options are named)", lam_lua_describe(L, -1, b, sizeof b));
        }
        const char *k = lua_tostring(L, -1);
        int found = 0;
        for (size_t i = 0; allowed[i] && !found; i++) found = strcmp(allowed[i], k) == 0;
        if (!found) {
            char list[400];
            size_t n = 0;
            list[0] = '\0';
            for (size_t i = 0; allowed[i] && n + 1 < sizeof list; i++) {
                int w = snprintf(list + n, sizeof list - n, "%s%s", i ? ", " : "", allowed[i]);
                if (w < 0) break;
                n += (size_t)w;
            }
            char b[64], hint[80] = "";
            size_t n_allowed = 0;
            while (allowed[n_allowed]) n_allowed++;
            const char *best = lam_key_nearest(k, allowed, n_allowed);
            if (best) snprintf(hint, sizeof hint, "did you mean '%s'? ", best);
            lam_lua_opterror(L, arg, "unknown option %s (%soptions: %s)", lam_lua_describe(L, -1, b, sizeof b), hint,
                             list);
        }
    }
}

int lam_lua_numfield(lua_State *L, int t, int arg, const char *key, double *x)
{
    int ty = lua_getfield(L, t, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    char b[64];
    if (ty != LUA_TNUMBER)
        lam_lua_opterror(L, arg, "%s must be a number, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    double v = (double)lua_tonumber(L, -1);
    if (!isfinite(v))
        lam_lua_opterror(L, arg, "%s must be a finite number, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    lua_pop(L, 1);
    *x = v;
    return 1;
}

int lam_lua_choicefield(lua_State *L, int t, int arg, const char *key, const char *const *names, int *i)
{
    int ty = lua_getfield(L, t, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    if (ty == LUA_TSTRING) {
        const char *s = lua_tostring(L, -1);
        for (int k = 0; names[k]; k++)
            if (strcmp(names[k], s) == 0) {
                lua_pop(L, 1);
                *i = k;
                return 1;
            }
    }
    char list[200], b[64];
    size_t n = 0;
    list[0] = '\0';
    for (int k = 0; names[k] && n + 1 < sizeof list; k++) {
        int w = snprintf(list + n, sizeof list - n, "%s%s", k ? (names[k + 1] ? ", " : " or ") : "", names[k]);
        if (w < 0) break;
        n += (size_t)w;
    }
    return lam_lua_opterror(L, arg, "%s must be %s, got %s", key, list, lam_lua_describe(L, -1, b, sizeof b));
}

int lam_lua_boolfield(lua_State *L, int t, int arg, const char *key, int *v)
{
    int ty = lua_getfield(L, t, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    char b[64];
    if (ty != LUA_TBOOLEAN)
        lam_lua_opterror(L, arg, "%s must be true or false, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    *v = lua_toboolean(L, -1);
    lua_pop(L, 1);
    return 1;
}

/* ---- module functions ---------------------------------------------------- */

/* lamina.plugin(path) -> true | nil, message */
static int l_plugin(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    if (lam_lua_sandbox_of(L)) return luaL_error(L, "lamina.plugin is not available in the sandbox");
    lam_error err;
    lam_error_clear(&err);
    if (lam_plugin_load(path, &err)) return lam_lua_fail(L, &err);
    lua_pushboolean(L, 1);
    return 1;
}

/* lamina.writers() -> sorted table of the plugin writers registered */
static int l_writers(lua_State *L)
{
    size_t n = lam_plugin_writers(NULL, 0);
    const char **names = lua_newuserdatauv(L, (n + 1) * sizeof *names, 0);
    n = lam_plugin_writers(names, n);
    lua_createtable(L, (int)n, 0);
    for (size_t i = 0; i < n; i++) {
        lua_pushstring(L, names[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* lamina.mkdir(path) -> true | nil, message: the directory and any
 * parents missing (mkdir -p) */
static int l_mkdir(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    int n = lam_lua_denied(L, path, 1);
    if (n) return n;
    int e = lam_lua_mkdirs(path);
    if (e) {
        luaL_pushfail(L);
        lua_pushfstring(L, "%s: cannot create the directory: %s", path, strerror(e));
        return 2;
    }
    lua_pushboolean(L, 1);
    return 1;
}

static const luaL_Reg lamina_funcs[] = {
    { "mkdir", l_mkdir },
    { "load", lam_lua_load },
    { "machine", lam_lua_machine },
    { "machines", lam_lua_machines },
    { "machine_keys", lam_lua_machine_keys },
    { "plugin", l_plugin },
    { "writers", l_writers },
    { "preview", lam_lua_preview },
    { "threads", l_threads },
    { NULL, NULL },
};

LUAMOD_API int luaopen_lamina(lua_State *L)
{
    luaL_checkversion(L);
    lam_lua_open_model(L);
    lam_lua_open_layer(L);
    lam_lua_open_contour(L);
    lam_lua_open_machine(L);
    lam_lua_open_plan(L);
    luaL_newlib(L, lamina_funcs);
    lua_pushliteral(L, LAMINA_VERSION);
    lua_setfield(L, -2, "version");
    lam_lua_open_sandbox(L);
    return 1;
}
