/* lamina.preview(layers, path [, title]): the SVG contact sheet of
 * `lamina slice --svg` (core/out/svg.c) for layers of one slicing run. */
#include "l_common.h"
#include "svg.h"

#include <string.h>

/* The sheet, released by __gc should Lua raise half-way. */
#define LAM_PREVIEWJOB "lamina.previewjob"

static int pjob_gc(lua_State *L)
{
    lam_svg **j = luaL_checkudata(L, 1, LAM_PREVIEWJOB);
    lam_svg_free(*j);
    *j = NULL;
    return 0;
}

int lam_lua_preview(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    const char *path = luaL_checkstring(L, 2);
    const char *title = luaL_optstring(L, 3, "lamina");
    int denied = lam_lua_denied(L, path, 1);
    if (denied) return denied;
    lua_Unsigned n = lua_rawlen(L, 1);
    if (n == 0) luaL_argerror(L, 1, "no layers to draw (an empty table)");
    /* check every element before anything is allocated on the C side */
    const lrun *run = NULL;
    for (lua_Unsigned i = 1; i <= n; i++) {
        lua_rawgeti(L, 1, (lua_Integer)i);
        lam_lua_checklayer(L, -1);
        const lrun *r = lam_lua_layerrun(L, -1);
        if (run && r != run)
            return luaL_argerror(L, 1, "the layers come from different slicing runs");
        run = r;
        lua_pop(L, 1);
    }
    lam_svg **j = lua_newuserdatauv(L, sizeof *j, 0);
    *j = NULL;
    if (luaL_newmetatable(L, LAM_PREVIEWJOB)) {
        lua_pushcfunction(L, pjob_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    lam_error err;
    lam_error_clear(&err);
    /* panels for the run's layer count, so the given layers keep their place */
    if (lam_svg_new(run->nlayers, run->uvbox, title, j, &err)) return lam_lua_fail(L, &err);
    for (lua_Unsigned i = 1; i <= n; i++) {
        lua_rawgeti(L, 1, (lua_Integer)i);
        int rc = lam_svg_add(*j, lam_lua_checklayer(L, -1), &err);
        lua_pop(L, 1);
        if (rc) return lam_lua_fail(L, &err);
    }
    int rc = lam_svg_save(*j, path, &err);
    lam_svg_free(*j);
    *j = NULL;
    if (rc) return lam_lua_fail(L, &err);
    lua_pushboolean(L, 1);
    return 1;
}
