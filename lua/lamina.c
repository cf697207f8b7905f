/* The `lamina` Lua module (as Lua's linit.c): luaopen_lamina, the module
 * table and its functions; the helpers every type file uses are in
 * lua/l_aux.c. Built into the executable and as the C module lamina.so
 * for a stock lua5.4 (package.cpath). See lua/API.md. */
#include "l_common.h"

#include <string.h>

#include "plugin.h"

LUAMOD_API int luaopen_lamina(lua_State *L);

/* lamina.threads() -> the number of threads machine:plan uses by default */
static int l_threads(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)lam_lua_threads(L));
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
    { "build", lam_lua_build },
    { "machines", lam_lua_machines },
    { "machine_keys", lam_lua_machine_keys },
    { "plugin", l_plugin },
    { "writers", l_writers },
    { "preview", lam_lua_preview },
    { "threads", l_threads },
    { NULL, NULL },
};

/* Methods of a class defined in the files built on it. */
static const luaL_Reg model_methods[] = {
    { "slice", lam_lua_slice },
    { "validate", lam_lua_validate },
    { "check", lam_lua_check },
    { "supports", lam_lua_supports },
    { NULL, NULL },
};

static const luaL_Reg machine_methods[] = {
    { "plan", lam_lua_plan },
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
    lam_lua_addmethods(L, LAM_MODEL, model_methods);
    lam_lua_addmethods(L, LAM_MACHINE, machine_methods);
    luaL_newlib(L, lamina_funcs);
    lua_pushliteral(L, LAMINA_VERSION);
    lua_setfield(L, -2, "version");
    /* the sandbox's own lamina module, handed down rather than called back */
    lua_pushcfunction(L, luaopen_lamina);
    lua_pushcclosure(L, lam_lua_sandbox, 1);
    lua_setfield(L, -2, "sandbox");
    return 1;
}
