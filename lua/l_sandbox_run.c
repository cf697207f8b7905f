/* lamina.sandbox{...}: a recipe run in a sandboxed state of its own
 * (lua/l_sandbox.c makes the state and keeps its limits), its arguments
 * copied in and its results copied back. */
#include "l_common.h"

#include <stdlib.h>
#include <string.h>

/* A directory or a list of them, options[key], as a C array (in a box on
 * the stack); the strings stay in the options table. */
static size_t string_list(lua_State *L, const char *key, const char *const **out)
{
    *out = NULL;
    int ty = lua_getfield(L, 1, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    char b[64];
    if (ty != LUA_TSTRING && ty != LUA_TTABLE)
        lam_lua_opterror(L, 1, "%s must be a directory or a list of directories, got %s", key,
                         lam_lua_describe(L, -1, b, sizeof b));
    size_t n = ty == LUA_TSTRING ? 1 : (size_t)lua_rawlen(L, -1);
    void **box = lam_lua_newbox(L);
    const char **arr = malloc((n + 1) * sizeof *arr);
    if (!arr) luaL_error(L, "not enough memory");
    *box = (void *)arr;
    if (ty == LUA_TSTRING) arr[0] = lua_tostring(L, -2);
    for (size_t i = 0; ty == LUA_TTABLE && i < n; i++) {
        if (lua_rawgeti(L, -2, (lua_Integer)i + 1) != LUA_TSTRING)
            lam_lua_opterror(L, 1, "%s[%zu] must be a string, got %s", key, i + 1,
                             lam_lua_describe(L, -1, b, sizeof b));
        arr[i] = lua_tostring(L, -1);
        lua_pop(L, 1);
    }
    lua_remove(L, -2);
    *out = arr;
    return n;
}

static int sandbox_msgh(lua_State *L)
{
    if (lua_type(L, 1) != LUA_TSTRING) return 1;
    luaL_traceback(L, L, lua_tostring(L, 1), 1);
    return 1;
}

/* Copy value idx of S onto L: nil, booleans, numbers and strings. */
static int copy_value(lua_State *S, int idx, lua_State *L)
{
    switch (lua_type(S, idx)) {
    case LUA_TNIL: lua_pushnil(L); return 1;
    case LUA_TBOOLEAN: lua_pushboolean(L, lua_toboolean(S, idx)); return 1;
    case LUA_TNUMBER:
        if (lua_isinteger(S, idx)) lua_pushinteger(L, lua_tointeger(S, idx));
        else lua_pushnumber(L, lua_tonumber(S, idx));
        return 1;
    case LUA_TSTRING: {
        size_t len;
        const char *s = lua_tolstring(S, idx, &len);
        lua_pushlstring(L, s, len);
        return 1;
    }
    }
    return 0;
}

/* The sandboxed state, closed by __gc / __close should the caller's state
 * raise an error (out of memory) while it is open. */
#define LAM_SANDBOXJOB "lamina.sandboxjob"

static int job_close(lua_State *L)
{
    lua_State **S = luaL_checkudata(L, 1, LAM_SANDBOXJOB);
    if (*S) lam_lua_sandbox_close(*S);
    *S = NULL;
    return 0;
}

/* The options of lamina.sandbox{...} (argument 1) into *o, the code or
 * the file into *code, *clen, *file; pushes the list boxes, the code, the
 * file and the args (or nothing for them); returns the args' index or 0. */
static int sandbox_opts(lua_State *L, lam_sandbox_opts *o, const char **code, size_t *clen, const char **file)
{
    static const char *const keys[] = { "code", "file", "args", "allow", "out", "memory", "time", NULL };
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_settop(L, 1);
    lam_lua_checkkeys(L, 1, 1, keys);
    memset(o, 0, sizeof *o);
    o->memory = 256.0 * 1024 * 1024;
    o->time = 60;
    o->open_lamina = lua_tocfunction(L, lua_upvalueindex(1));
    if (lam_lua_numfield(L, 1, 1, "memory", &o->memory) && o->memory < 0)
        lam_lua_opterror(L, 1, "memory must be a number of bytes >= 0 (0: no limit), got %.14g", o->memory);
    if (lam_lua_numfield(L, 1, 1, "time", &o->time) && o->time < 0)
        lam_lua_opterror(L, 1, "time must be a number of seconds >= 0 (0: no limit), got %.14g", o->time);
    lua_getfield(L, 1, "code");
    lua_getfield(L, 1, "file");
    *clen = 0;
    *code = lua_type(L, 2) == LUA_TSTRING ? lua_tolstring(L, 2, clen) : NULL;
    *file = lua_type(L, 3) == LUA_TSTRING ? lua_tostring(L, 3) : NULL;
    if ((*code != NULL) == (*file != NULL) || (!*code && !lua_isnil(L, 2)) || (!*file && !lua_isnil(L, 3)))
        lam_lua_opterror(L, 1, "give the recipe as one string: code = TEXT or file = PATH");
    o->nallow = string_list(L, "allow", &o->allow);
    o->nout = string_list(L, "out", &o->out);
    int args = lua_getfield(L, 1, "args") == LUA_TNIL ? 0 : lua_gettop(L);
    if (args && !lua_istable(L, args)) lam_lua_opterror(L, 1, "args must be a list");
    return args;
}

/* Load and run the recipe in s with the caller's args (a list at index args
 * of L, or 0), results above base: the status of lua_pcall. */
static int sandbox_call(lua_State *L, int args, lua_State *s, int base, const char *code, size_t clen,
                        const char *file)
{
    size_t nargs = args ? (size_t)lua_rawlen(L, args) : 0;
    int st = code ? luaL_loadbufferx(s, code, clen, "=(sandbox)", "t") : luaL_loadfilex(s, file, "t");
    if (st != LUA_OK) return st;
    /* arg as `lamina run` sets it, and the same values as ... */
    lua_createtable(s, (int)nargs, 1);
    int t = lua_gettop(s);
    lua_pushstring(s, file ? file : "(sandbox)");
    lua_rawseti(s, t, 0);
    for (size_t i = 0; i < nargs; i++) {
        lua_rawgeti(L, args, (lua_Integer)i + 1);
        if (!copy_value(L, -1, s)) lua_pushnil(s);
        lua_pop(L, 1);
        lua_rawseti(s, t, (lua_Integer)i + 1);
    }
    lua_pushvalue(s, t);
    lua_setglobal(s, "arg");
    for (size_t i = 0; i < nargs; i++) lua_rawgeti(s, t, (lua_Integer)i + 1);
    lua_remove(s, t);
    lam_lua_sandbox_start(s);
    st = lua_pcall(s, (int)nargs, LUA_MULTRET, base);
    lua_sethook(s, NULL, 0, 0);
    return st;
}

/* What lamina.sandbox returns for the recipe's status st in s (results
 * above base; job the index of the state's box in L). */
static int sandbox_results(lua_State *L, int job, lua_State *s, int base, int st)
{
    int code_out = 0;
    if (st != LUA_OK && lam_lua_sandbox_exit(s, &code_out)) {
        if (code_out == 0) {
            lua_pushboolean(L, 1);
            return 1;
        }
        luaL_pushfail(L);
        lua_pushfstring(L, "the recipe called os.exit(%d)", code_out);
        lua_pushinteger(L, code_out);
        return 3;
    }
    if (st != LUA_OK) {
        char mb[200];
        const char *mm = st == LUA_ERRMEM ? lam_lua_sandbox_memory_error(s, mb, sizeof mb) : NULL;
        luaL_pushfail(L);
        if (mm) lua_pushstring(L, mm);
        else if (lua_type(s, -1) == LUA_TSTRING) lua_pushstring(L, lua_tostring(s, -1));
        else lua_pushfstring(L, "(error object is a %s value)", luaL_typename(s, -1));
        lua_pushinteger(L, 1);
        return 3;
    }
    int nres = lua_gettop(s) - base;
    luaL_checkstack(L, nres + 2, "too many results from the sandbox");
    lua_pushboolean(L, 1);
    for (int i = 1; i <= nres; i++)
        if (!copy_value(s, base + i, L)) {
            lua_settop(L, job);
            luaL_pushfail(L);
            lua_pushfstring(L, "result %d of the recipe is a %s (nil, booleans, numbers and strings come back)", i,
                            luaL_typename(s, base + i));
            lua_pushinteger(L, 1);
            return 3;
        }
    return nres + 1;
}

int lam_lua_sandbox(lua_State *L)
{
    lam_sandbox_opts o;
    const char *code, *file;
    size_t clen;
    int args = sandbox_opts(L, &o, &code, &clen, &file);
    unsigned threads = lam_lua_threads(L); /* the sandbox plans as its host does */

    lua_State **S = lua_newuserdatauv(L, sizeof *S, 0);
    *S = NULL;
    if (luaL_newmetatable(L, LAM_SANDBOXJOB)) {
        lua_pushcfunction(L, job_close);
        lua_setfield(L, -2, "__gc");
        lua_pushcfunction(L, job_close);
        lua_setfield(L, -2, "__close");
    }
    lua_setmetatable(L, -2);
    int job = lua_gettop(L);
    lua_toclose(L, job);
    char msg[1024];
    if (!(*S = lam_lua_sandbox_open(&o, msg, sizeof msg))) {
        luaL_pushfail(L);
        lua_pushstring(L, msg);
        return 2;
    }
    lua_State *s = *S;
    lam_lua_set_threads(s, threads);
    size_t nargs = args ? (size_t)lua_rawlen(L, args) : 0;
    if (!lua_checkstack(s, (int)nargs + 8)) return luaL_error(L, "too many arguments to the sandbox");
    lua_pushcfunction(s, sandbox_msgh);
    int base = lua_gettop(s);
    int st = sandbox_call(L, args, s, base, code, clen, file);
    return sandbox_results(L, job, s, base, st);
}
