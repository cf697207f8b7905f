/* The helper library of the Lua binding (as Lua's lauxlib.c): classes,
 * userdata checks, boxes, the io.open error convention, option fields,
 * and the default thread count. Every file of the binding calls these;
 * they call nothing else of it. luaopen_lamina is in lua/lamina.c; the
 * interrupt flag with the sandbox's clock in lua/l_sandbox.c. */
#include "l_common.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool.h"

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

void lam_lua_addmethods(lua_State *L, const char *tname, const luaL_Reg *methods)
{
    luaL_getmetatable(L, tname);
    lua_getfield(L, -1, "__index");
    lua_getupvalue(L, -1, 1); /* class_index's methods table */
    luaL_setfuncs(L, methods, 0);
    lua_pop(L, 3);
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

/* The message whole, however long (an unknown option's error lists every
 * valid key): formatted on the C stack when it fits, else in a buffer of
 * the size it needs (in a box: freed by the collector after the error). */
int lam_lua_opterror(lua_State *L, int arg, const char *fmt, ...)
{
    void **box = lam_lua_newbox(L); /* before va_start: it may raise */
    char small[512];
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    const char *msg = n < 0 ? "(the message could not be formatted)" : small;
    if (n >= (int)sizeof small && (*box = malloc((size_t)n + 1))) {
        vsnprintf(*box, (size_t)n + 1, fmt, again);
        msg = *box;
    }
    va_end(again);
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
            char b[64], hint[80] = "";
            lam_lua_describe(L, -1, b, sizeof b);
            size_t n_allowed = 0;
            while (allowed[n_allowed]) n_allowed++;
            const char *best = lam_key_nearest(k, allowed, n_allowed);
            if (best) snprintf(hint, sizeof hint, "did you mean '%s'? ", best);
            /* every key, whatever their number (a Lua buffer: no fixed size) */
            luaL_Buffer list;
            luaL_buffinit(L, &list);
            for (size_t i = 0; allowed[i]; i++) {
                if (i) luaL_addstring(&list, ", ");
                luaL_addstring(&list, allowed[i]);
            }
            luaL_pushresult(&list);
            lam_lua_opterror(L, arg, "unknown option %s (%soptions: %s)", b, hint, lua_tostring(L, -1));
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
    char b[64];
    lam_lua_describe(L, -1, b, sizeof b);
    luaL_Buffer list; /* every name, whatever their number */
    luaL_buffinit(L, &list);
    for (int k = 0; names[k]; k++) {
        if (k) luaL_addstring(&list, names[k + 1] ? ", " : " or ");
        luaL_addstring(&list, names[k]);
    }
    luaL_pushresult(&list);
    return lam_lua_opterror(L, arg, "%s must be %s, got %s", key, lua_tostring(L, -1), b);
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
