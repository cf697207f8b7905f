/* help(x) in the REPL (help.h). */
#include "help.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

static const char *const classes[] = { "model", "layer", "contour", "machine", "plan", NULL };

const lam_help_entry *lam_help_find(const char *key)
{
    for (const lam_help_entry *e = lam_help_entries; e->key; e++)
        if (strcmp(e->key, key) == 0) return e;
    return NULL;
}

/* When table t (absolute index) holds the value at v (raw, by identity)
 * under a string key: push prefix .. key and return 1. */
static int find_in(lua_State *L, int t, int v, const char *prefix)
{
    lua_pushnil(L);
    while (lua_next(L, t)) {
        if (lua_type(L, -2) == LUA_TSTRING && lua_rawequal(L, -1, v)) {
            lua_pushfstring(L, "%s%s", prefix, lua_tostring(L, -2));
            lua_replace(L, -3);
            lua_pop(L, 1);
            return 1;
        }
        lua_pop(L, 1);
    }
    return 0;
}

/* Push the methods table of class tname (lam_lua_newclass keeps it as the
 * first upvalue of __index), or nil. */
static void push_methods(lua_State *L, const char *tname)
{
    int top = lua_gettop(L);
    luaL_getmetatable(L, tname);
    if (lua_istable(L, -1)) {
        lua_pushliteral(L, "__index");
        lua_rawget(L, -2);
        if (lua_iscfunction(L, -1) && lua_getupvalue(L, -1, 1) && lua_istable(L, -1)) {
            lua_replace(L, top + 1);
            lua_settop(L, top + 1);
            return;
        }
    }
    lua_settop(L, top);
    lua_pushnil(L);
}

static int function_key(lua_State *L, int v)
{
    int top = lua_gettop(L);
    if (lua_getglobal(L, "lamina") == LUA_TTABLE && find_in(L, top + 1, v, "lamina.")) goto found;
    lua_settop(L, top);
    for (int i = 0; classes[i]; i++) {
        char tname[32], prefix[32];
        snprintf(tname, sizeof tname, "lamina.%s", classes[i]);
        snprintf(prefix, sizeof prefix, "%s:", classes[i]);
        push_methods(L, tname);
        if (lua_istable(L, -1) && find_in(L, lua_gettop(L), v, prefix)) goto found;
        lua_settop(L, top);
    }
    /* the lamina.* Lua modules loaded so far */
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
    int loaded = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, loaded)) {
        const char *name = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "";
        if (strncmp(name, "lamina.", 7) == 0 && lua_istable(L, -1)) {
            char prefix[64];
            snprintf(prefix, sizeof prefix, "%s.", name + 7);
            if (find_in(L, lua_gettop(L), v, prefix)) goto found;
        }
        lua_settop(L, loaded + 1);
    }
    lua_settop(L, top);
    return 0;
found:
    lua_replace(L, top + 1);
    lua_settop(L, top + 1);
    return 1;
}

/* a table that is a loaded lamina module (or the module itself) */
static int module_key(lua_State *L, int v)
{
    int top = lua_gettop(L);
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
    lua_pushnil(L);
    while (lua_next(L, top + 1)) {
        const char *name = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "";
        if (lua_rawequal(L, -1, v) && (strcmp(name, "lamina") == 0 || strncmp(name, "lamina.", 7) == 0)) {
            lua_pushstring(L, strcmp(name, "lamina") == 0 ? "the module" : name);
            lua_replace(L, top + 1);
            lua_settop(L, top + 1);
            return 1;
        }
        lua_pop(L, 1);
    }
    lua_settop(L, top);
    return 0;
}

void lam_help_key(lua_State *L, int idx)
{
    int v = lua_absindex(L, idx);
    int top = lua_gettop(L);
    switch (lua_type(L, v)) {
    case LUA_TFUNCTION:
        if (function_key(L, v)) return;
        break;
    case LUA_TTABLE:
        if (module_key(L, v)) return;
        /* fall through - a table with a lamina metatable */
    case LUA_TUSERDATA:
        if (lua_getmetatable(L, v)) {
            lua_pushliteral(L, "__name");
            lua_rawget(L, -2);
            const char *name = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "";
            if (strcmp(name, "lamina.layers") == 0) {
                lua_pushliteral(L, "model:slice");
            } else if (strncmp(name, "lamina.", 7) == 0 && lam_help_find(name + 7)) {
                lua_pushstring(L, name + 7);
            } else {
                lua_settop(L, top);
                break;
            }
            lua_replace(L, top + 1);
            lua_settop(L, top + 1);
            return;
        }
        break;
    default:
        break;
    }
    lua_settop(L, top);
    lua_pushnil(L);
}

/* the entries whose key ends in "." or ":" then `word`, or holds it
 * (contains: 1); pushes them as one string, returns how many */
static int matches(lua_State *L, const char *word, int contains, const lam_help_entry **one)
{
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    int n = 0;
    size_t wl = strlen(word);
    for (const lam_help_entry *e = lam_help_entries; e->key; e++) {
        size_t kl = strlen(e->key);
        int hit = contains ? strstr(e->key, word) != NULL
                           : kl > wl && strcmp(e->key + kl - wl, word) == 0 &&
                                 (e->key[kl - wl - 1] == '.' || e->key[kl - wl - 1] == ':');
        if (!hit) continue;
        if (n++) luaL_addstring(&b, ", ");
        luaL_addstring(&b, e->key);
        *one = e;
    }
    luaL_pushresult(&b);
    return n;
}

static void list_topics(void)
{
    fputs("help(x) prints the documentation (lua/API.md) of x: a function or method\n"
          "(help(lamina.load), help(m.slice)), an object (help(m), help(layers)), or a\n"
          "topic or name given as a string (help \"conventions\", help \"bbox\").\n"
          "Tab completes names, fields and methods. The topics:\n",
          stdout);
    int col = 0;
    for (const lam_help_entry *e = lam_help_entries; e->key; e++) {
        int w = (int)strlen(e->key) + 2;
        if (col && col + w > 78) {
            fputc('\n', stdout);
            col = 0;
        }
        printf("%s%s", col ? "  " : "  ", e->key);
        col += w;
    }
    fputc('\n', stdout);
}

/* Not finding help is an answer, not an error: print it, return nothing. */
static int say(lua_State *L, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const char *msg = lua_pushvfstring(L, fmt, ap);
    va_end(ap);
    printf("help: %s\n", msg);
    fflush(stdout);
    return 0;
}

static int l_help(lua_State *L)
{
    if (lua_gettop(L) == 0) {
        list_topics();
        fflush(stdout);
        return 0;
    }
    lua_settop(L, 1);
    const lam_help_entry *e = NULL;
    if (lua_type(L, 1) == LUA_TSTRING) {
        const char *word = lua_tostring(L, 1);
        e = lam_help_find(word);
        if (!e) {
            lua_pushfstring(L, "lamina.%s", word);
            e = lam_help_find(lua_tostring(L, -1));
        }
        if (!e) {
            const lam_help_entry *one = NULL;
            int n = matches(L, word, 0, &one);
            if (n == 0) {
                lua_pop(L, 1);
                n = matches(L, word, 1, &one);
            }
            if (n == 1) e = one;
            else if (n > 1) {
                printf("help: '%s' is in %s\n", word, lua_tostring(L, -1));
                fflush(stdout);
                return 0;
            }
        }
        if (!e) return say(L, "no help for '%s' (help() lists the topics)", word);
    } else {
        lam_help_key(L, 1);
        if (lua_isnil(L, -1))
            return say(L, "no help for this %s (not a lamina function, object or module; help() lists the topics)",
                       luaL_typename(L, 1));
        e = lam_help_find(lua_tostring(L, -1));
        if (!e) return say(L, "%s is not documented in lua/API.md", lua_tostring(L, -1));
    }
    fputs(e->text, stdout);
    /* an object type: its methods, each an entry of its own */
    size_t kl = strlen(e->key);
    int first = 1;
    for (const lam_help_entry *m = lam_help_entries; m->key; m++) {
        if (strncmp(m->key, e->key, kl) != 0 || m->key[kl] != ':') continue;
        printf("%s%s", first ? "\nMethods (help \"name\" for one): " : ", ", m->key);
        first = 0;
    }
    if (!first) fputc('\n', stdout);
    fflush(stdout);
    return 0;
}

void lam_help_open(lua_State *L)
{
    lua_pushcfunction(L, l_help);
    lua_setglobal(L, "help");
}
