/* Sandboxed states: `lamina run --safe` and lamina.sandbox{...} (which
 * runs a recipe in one: lua/l_sandbox_run.c).
 *
 * In the manner of Redis's scripts: the recipe runs in a Lua state of its
 * own (so nothing it does to metatables, globals or the string library
 * reaches the caller's state) that has only what cannot reach outside:
 *   - base, string, table, math, utf8, coroutine; `load`, `loadfile` and
 *     `dofile` take text only (mode "t": no bytecode, which can break the
 *     VM); no string.dump, no debug library, no package library (a
 *     `require` of its own finds Lua modules in lamina's module directories
 *     and the readable directories only: no C modules, no package.loadlib);
 *   - setmetatable refuses a metatable with a __gc field (finalizers run
 *     with hooks off, out of reach of the time limit), getmetatable answers
 *     for tables only (lamina's objects and files keep their metatables);
 *     collectgarbage does "collect", "count", "step" and "isrunning" only;
 *   - io and os without popen, tmpfile, execute, getenv, tmpname,
 *     setlocale; os.exit ends the recipe, not the process; io.open,
 *     io.lines, io.input, io.output, os.remove, os.rename, dofile and
 *     loadfile, and lamina's own functions that open files (lamina.load,
 *     lamina.machine given a path, plan:write, lamina.preview,
 *     lamina.mkdir) reach only files inside the readable directories
 *     (--allow, and --out) or, to write, the writable ones (--out). Paths
 *     are compared after realpath, so `..` and symbolic links that lead
 *     outside are outside; a link that leads nowhere is refused. No
 *     lamina.plugin (it loads machine code), no nested lamina.sandbox;
 *   - memory: one limit for Lua's memory and lamina's own objects made for
 *     the recipe (models, slicings, plans: lam_lua_charge). The state's
 *     allocator (lua_setallocf's kind) refuses to grow Lua's memory past
 *     what the objects leave ("not enough memory" in the recipe), and an
 *     object that would not fit is refused with "memory limit exceeded",
 *     before its big allocation where its size can be told in advance;
 *   - time: a count hook, and lamina's long C loops between layers, raise
 *     "time limit exceeded" once the limit has passed; from then on pcall,
 *     xpcall and coroutine.resume pass it on instead of catching it.
 * The sandbox is found from a state by its allocator (lua_getallocf), which
 * Lua code cannot change. */
/* realpath (XSI) */
#define _XOPEN_SOURCE 700
#include "l_common.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <lualib.h>

#include "file.h"
#include "paths.h"
#include "profile.h"

struct lam_sandbox {
    char **dirs;             /* realpath'd directories */
    int *writable;           /* per directory: also writable (--out) */
    size_t ndirs;
    char *mods[4];           /* lamina's Lua module directories (require only) */
    size_t nmods;
    char *machines[8];       /* the machine directories (realpath'd): profiles a
                                file may inherit from, besides --allow */
    size_t nmachines;
    size_t mem_limit, mem_used;
    size_t obj_used;         /* lamina's C objects charged (lam_lua_charge) */
    double time_limit, deadline;
    int timed_out;           /* the limit was reached: pcall cannot catch it */
    lam_file_gate old_gate;  /* the file gate before this sandbox's (file.h) */
    void *old_gate_ctx;
};

/* ---- the allocator and the clock --------------------------------------- */

static void *sb_alloc(void *ud, void *ptr, size_t osize, size_t nsize)
{
    lam_sandbox *sb = ud;
    size_t old = ptr ? osize : 0; /* without ptr, osize is a type tag */
    if (nsize == 0) {
        free(ptr);
        sb->mem_used -= old;
        return NULL;
    }
    if (sb->mem_limit && nsize > old && sb->mem_used - old + nsize > sb->mem_limit - sb->obj_used) return NULL;
    void *p = realloc(ptr, nsize);
    if (p) sb->mem_used = sb->mem_used - old + nsize;
    return p;
}

lam_sandbox *lam_lua_sandbox_of(lua_State *L)
{
    void *ud;
    return lua_getallocf(L, &ud) == sb_alloc ? ud : NULL;
}

/* ---- lamina's own objects against the same limit ------------------------- */

size_t lam_lua_mem_room(lua_State *L)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (!sb || !sb->mem_limit) return SIZE_MAX;
    size_t used = sb->mem_used + sb->obj_used;
    return used < sb->mem_limit ? sb->mem_limit - used : 0;
}

static int fits(lua_State *L, size_t bytes) { return bytes <= lam_lua_mem_room(L); }

size_t lam_lua_mem_reclaim(lua_State *L, size_t want)
{
    if (!fits(L, want)) lua_gc(L, LUA_GCCOLLECT);
    return lam_lua_mem_room(L);
}

/* A charge must leave this much room for the Lua objects that carry and
 * follow it (a userdata, a table slot): otherwise a recipe that fills its
 * memory with lamina's objects fails at some small Lua allocation just
 * after, with Lua's bare "not enough memory", instead of at the object
 * that took the room, named (which of the two came first depended on a
 * few bytes of struct size). */
static size_t headroom(const lam_sandbox *sb)
{
    size_t h = sb->mem_limit / 16;
    return h < 65536 ? h : 65536;
}

int lam_lua_charge(lua_State *L, size_t *slot, size_t bytes)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (!sb || !sb->mem_limit || !bytes) return 1;
    size_t need = bytes + headroom(sb);
    if (need < bytes) return 0;
    /* objects that are garbage hold memory until their finalizers run,
     * which Lua's emergency collection does not do: a full collection
     * first, as Lua's allocator collects before it gives up */
    if (!fits(L, need)) lua_gc(L, LUA_GCCOLLECT);
    if (!fits(L, need)) return 0;
    sb->obj_used += bytes;
    *slot += bytes;
    return 1;
}

void lam_lua_discharge(lua_State *L, size_t *slot)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (sb) sb->obj_used -= *slot < sb->obj_used ? *slot : sb->obj_used;
    *slot = 0;
}

int lam_lua_memory_raise(lua_State *L, const char *fmt, ...)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    char what[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    char msg[600];
    snprintf(msg, sizeof msg,
             "memory limit exceeded: %s (the recipe's limit is %zu bytes for Lua and lamina's models, slicings and "
             "plans together, %zu in use; raise it with --memory or the option memory)",
             what, sb ? sb->mem_limit : 0, sb ? sb->mem_used + sb->obj_used : 0);
    return luaL_error(L, "%s", msg);
}

void lam_lua_charge_or_raise(lua_State *L, size_t *slot, size_t bytes, const char *what)
{
    if (!lam_lua_charge(L, slot, bytes)) lam_lua_memory_raise(L, "%s needs %zu bytes", what, bytes);
}

/* ---- stopping: the interrupt flag and the time limit ------------------------ */

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

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

int lam_lua_sandbox_timed_out(lua_State *L)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (sb && (sb->timed_out || (sb->deadline > 0 && now() > sb->deadline))) sb->timed_out = 1;
    return sb && sb->timed_out;
}

void lam_lua_sandbox_check_time(lua_State *L)
{
    if (lam_lua_sandbox_timed_out(L))
        luaL_error(L, "time limit exceeded (%f s; raise it with --time or the option time)",
                   lam_lua_sandbox_of(L)->time_limit);
}

/* pcall, xpcall, coroutine.resume: upvalue 1 after the call, but once the
 * time limit is reached the error goes on up instead of being caught */
static int sb_catching(lua_State *L)
{
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    lam_lua_sandbox_check_time(L);
    return lua_gettop(L);
}

static void time_hook(lua_State *L, lua_Debug *ar)
{
    (void)ar;
    lam_lua_check_interrupt(L);
}

/* ---- paths ------------------------------------------------------------------ */

/* The canonical absolute form of path, malloc'd: realpath for what exists,
 * the canonical parent and the last name for what does not (a name that
 * is empty, "." or ".." has none). NULL when there is none, or when path
 * is a symbolic link that leads nowhere (opening it to write would create
 * whatever it names). */
static char *resolve(const char *path)
{
    struct stat st;
    if (lstat(path, &st) == 0) return realpath(path, NULL);
    if (errno != ENOENT) return NULL;
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/') n--;
    const char *slash = NULL;
    for (size_t i = n; i > 0; i--)
        if (path[i - 1] == '/') {
            slash = path + i - 1;
            break;
        }
    const char *base = slash ? slash + 1 : path;
    size_t nbase = n - (size_t)(base - path);
    if (nbase == 0 || (nbase == 1 && base[0] == '.') || (nbase == 2 && base[0] == '.' && base[1] == '.'))
        return NULL;
    char *dir = slash ? strndup(path, slash == path ? 1 : (size_t)(slash - path)) : strdup(".");
    char *rd = dir ? resolve(dir) : NULL;
    free(dir);
    if (!rd) return NULL;
    size_t nrd = strlen(rd);
    char *out = malloc(nrd + nbase + 2);
    if (out) snprintf(out, nrd + nbase + 2, "%s%s%.*s", rd, strcmp(rd, "/") ? "/" : "", (int)nbase, base);
    free(rd);
    return out;
}

static int inside(const char *real, const char *dir)
{
    size_t n = strlen(dir);
    return strcmp(dir, "/") == 0 || (strncmp(real, dir, n) == 0 && (real[n] == '/' || real[n] == '\0'));
}

/* 1 when sb lets path be read (write 0) or written (write 1). */
static int allowed(const lam_sandbox *sb, const char *path, int write)
{
    char *real = resolve(path);
    int ok = 0;
    for (size_t i = 0; real && i < sb->ndirs && !ok; i++) ok = (!write || sb->writable[i]) && inside(real, sb->dirs[i]);
    free(real);
    return ok;
}

static const char *denied_text(int write)
{
    return write ? "outside the sandbox's writable directories (--out)"
                 : "outside the sandbox's readable directories (--allow, --out)";
}

/* The file gate while a sandbox lives: what core reads by itself (a
 * Unigrafix include, a profile's inherits) stays inside the readable
 * directories too. */
static int gate(void *ctx, const char *path, lam_error *err)
{
    const lam_sandbox *sb = ctx;
    if (allowed(sb, path, 0)) return LAM_OK;
    char *real = resolve(path);
    int shipped = 0;
    for (size_t i = 0; real && i < sb->nmachines && !shipped; i++) shipped = inside(real, sb->machines[i]);
    free(real);
    if (shipped) return LAM_OK;
    return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot read: %s", denied_text(0));
}

int lam_lua_denied(lua_State *L, const char *path, int write)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (!sb || allowed(sb, path, write)) return 0;
    luaL_pushfail(L);
    lua_pushfstring(L, "%s: %s", path, denied_text(write));
    lua_pushinteger(L, EACCES);
    return 3;
}

/* ---- the restricted libraries ------------------------------------------ */

/* A C function wrapping upvalue 1 after a path check of argument `arg`
 * (when it is a string). */
static int checked_call(lua_State *L, int arg, int write)
{
    if (lua_type(L, arg) == LUA_TSTRING) {
        int n = lam_lua_denied(L, lua_tostring(L, arg), write);
        if (n) return n;
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

/* io.open(path [, mode]): writing for any mode but plain reading */
static int sb_open(lua_State *L)
{
    const char *mode = luaL_optstring(L, 2, "r");
    return checked_call(L, 1, strpbrk(mode, "wa+") != NULL);
}
static int sb_write1(lua_State *L) { return checked_call(L, 1, 1); }

/* a path check that raises, for functions that raise on a missing file */
static int sb_raise_read1(lua_State *L)
{
    if (lua_type(L, 1) == LUA_TSTRING && lam_lua_denied(L, lua_tostring(L, 1), 0))
        return luaL_error(L, "%s", lua_tostring(L, -2));
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

static int sb_rename(lua_State *L)
{
    const char *from = luaL_checkstring(L, 1), *to = luaL_checkstring(L, 2);
    int n = lam_lua_denied(L, from, 1);
    if (!n) n = lam_lua_denied(L, to, 1);
    if (n) return n;
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

/* os.exit([code]): raises the exit object, which ends the recipe with
 * that code (lam_lua_sandbox_exit reads it) */
static const char exit_key = 0;

static int sb_exit(lua_State *L)
{
    int code = lua_isnoneornil(L, 1) ? 0
               : lua_isboolean(L, 1) ? !lua_toboolean(L, 1)
                                     : (int)luaL_checkinteger(L, 1);
    lua_newtable(L);
    lua_pushinteger(L, code);
    lua_setfield(L, -2, "exit");
    lua_rawgetp(L, LUA_REGISTRYINDEX, &exit_key);
    lua_setmetatable(L, -2);
    return lua_error(L);
}

static int exit_tostring(lua_State *L)
{
    lua_getfield(L, 1, "exit");
    lua_pushfstring(L, "os.exit(%d)", (int)lua_tointeger(L, -1));
    return 1;
}

int lam_lua_sandbox_exit(lua_State *L, int *code)
{
    if (!lua_istable(L, -1) || !lua_getmetatable(L, -1)) return 0;
    lua_rawgetp(L, LUA_REGISTRYINDEX, &exit_key);
    int is = lua_rawequal(L, -1, -2);
    lua_pop(L, 2);
    if (is) {
        lua_getfield(L, -1, "exit");
        *code = (int)lua_tointeger(L, -1);
        lua_pop(L, 2);
    }
    return is;
}

/* load(chunk [, name [, mode [, env]]]): text only */
static int sb_load(lua_State *L)
{
    const char *mode = luaL_optstring(L, 3, "t");
    if (strchr(mode, 'b')) {
        luaL_pushfail(L);
        lua_pushliteral(L, "binary chunks cannot be loaded in the sandbox");
        return 2;
    }
    int n = lua_gettop(L) < 3 ? 3 : lua_gettop(L);
    lua_settop(L, n);
    lua_pushliteral(L, "t");
    lua_replace(L, 3);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, n, LUA_MULTRET);
    return lua_gettop(L);
}

/* loadfile([path [, mode [, env]]]): checked, text only */
static int sb_loadfile(lua_State *L)
{
    const char *path = luaL_optstring(L, 1, NULL);
    if (path && lam_lua_denied(L, path, 0)) {
        lua_pop(L, 1); /* nil, message: as loadfile fails */
        return 2;
    }
    const char *mode = luaL_optstring(L, 2, "t");
    if (strchr(mode, 'b')) {
        luaL_pushfail(L);
        lua_pushliteral(L, "binary chunks cannot be loaded in the sandbox");
        return 2;
    }
    int env = !lua_isnone(L, 3);
    if (luaL_loadfilex(L, path, "t") != LUA_OK) {
        luaL_pushfail(L);
        lua_insert(L, -2);
        return 2;
    }
    if (env) {
        lua_pushvalue(L, 3);
        if (!lua_setupvalue(L, -2, 1)) lua_pop(L, 1);
    }
    return 1;
}

static int sb_dofile(lua_State *L)
{
    const char *path = luaL_optstring(L, 1, NULL);
    if (path && lam_lua_denied(L, path, 0)) return luaL_error(L, "%s", lua_tostring(L, -2));
    lua_settop(L, 1);
    if (luaL_loadfilex(L, path, "t") != LUA_OK) return lua_error(L);
    lua_call(L, 0, LUA_MULTRET);
    return lua_gettop(L) - 1;
}

static int sb_setmetatable(lua_State *L)
{
    if (lua_istable(L, 2)) {
        lua_pushliteral(L, "__gc");
        int gc = lua_rawget(L, 2) != LUA_TNIL;
        lua_pop(L, 1);
        if (gc) return luaL_error(L, "setmetatable: __gc metamethods are not allowed in the sandbox");
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, 1);
    return 1;
}

static int sb_getmetatable(lua_State *L)
{
    if (!lua_istable(L, 1)) {
        luaL_checkany(L, 1);
        lua_pushnil(L);
        return 1;
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, 1);
    return 1;
}

static int sb_collectgarbage(lua_State *L)
{
    static const char *const ok[] = { "collect", "count", "step", "isrunning", NULL };
    const char *opt = luaL_optstring(L, 1, "collect");
    int found = 0;
    for (int i = 0; ok[i] && !found; i++) found = strcmp(ok[i], opt) == 0;
    if (!found) return luaL_error(L, "collectgarbage('%s') is not allowed in the sandbox", opt);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

/* require(name): loaded modules, else NAME.lua or NAME/init.lua (dots as
 * slashes) in lamina's module directories (lamina.* only: installed, they
 * are the Lua tree share/lua/5.4 that other packages' modules share), then
 * the readable directories; text only. */
static int sb_require(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    lua_settop(L, 1);
    lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
    if (lua_getfield(L, 2, name) != LUA_TNIL) return 1;
    lua_pop(L, 1);
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    int good = name[0] != '\0' && name[0] != '.' && strstr(name, "..") == NULL;
    for (const char *c = name; *c && good; c++)
        good = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_' ||
               *c == '.' || *c == '-';
    if (!good || !sb) return luaL_error(L, "module '%s' not found in the sandbox", name);
    char rel[256];
    snprintf(rel, sizeof rel, "%s", name);
    for (char *c = rel; *c; c++)
        if (*c == '.') *c = '/';
    static const char *const forms[] = { "%s/%s.lua", "%s/%s/init.lua" };
    for (size_t d = 0; d < sb->nmods + sb->ndirs; d++) {
        const char *dir = d < sb->nmods ? sb->mods[d] : sb->dirs[d - sb->nmods];
        if (d < sb->nmods && strncmp(name, "lamina.", 7) != 0) continue;
        for (int k = 0; k < 2; k++) {
            char path[PATH_MAX];
            snprintf(path, sizeof path, forms[k], dir, rel);
            struct stat st;
            if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) continue;
            if (d >= sb->nmods && !allowed(sb, path, 0)) continue; /* a link out of the directory */
            if (luaL_loadfilex(L, path, "t") != LUA_OK)
                return luaL_error(L, "error loading module '%s' from %s:\n\t%s", name, path, lua_tostring(L, -1));
            lua_pushvalue(L, 1);
            lua_pushstring(L, path);
            lua_call(L, 2, 1);
            if (lua_isnil(L, -1)) {
                lua_pop(L, 1);
                lua_pushboolean(L, 1);
            }
            lua_pushvalue(L, -1);
            lua_setfield(L, 2, name);
            return 1;
        }
    }
    return luaL_error(L, "module '%s' not found in the sandbox (lamina's modules and the --allow directories)", name);
}

/* Replace t[name] with a closure of f over its old value. */
static void wrap(lua_State *L, int t, const char *name, lua_CFunction f)
{
    t = lua_absindex(L, t);
    lua_getfield(L, t, name);
    lua_pushcclosure(L, f, 1);
    lua_setfield(L, t, name);
}

static void drop(lua_State *L, int t, const char *const *names)
{
    t = lua_absindex(L, t);
    for (; *names; names++) {
        lua_pushnil(L);
        lua_setfield(L, t, *names);
    }
}

/* The state's libraries; argument 1 the lamina module's opener
 * (lam_sandbox_opts.open_lamina). */
static int open_libs(lua_State *L)
{
    const luaL_Reg libs[] = {
        { LUA_GNAME, luaopen_base },          { LUA_COLIBNAME, luaopen_coroutine },
        { LUA_TABLIBNAME, luaopen_table },    { LUA_IOLIBNAME, luaopen_io },
        { LUA_OSLIBNAME, luaopen_os },        { LUA_STRLIBNAME, luaopen_string },
        { LUA_MATHLIBNAME, luaopen_math },    { LUA_UTF8LIBNAME, luaopen_utf8 },
        { "lamina", lua_tocfunction(L, 1) },  { NULL, NULL },
    };
    for (const luaL_Reg *lib = libs; lib->func; lib++) {
        luaL_requiref(L, lib->name, lib->func, 1);
        lua_pop(L, 1);
    }
    lua_pushglobaltable(L);
    int g = lua_gettop(L);
    wrap(L, g, "load", sb_load);
    wrap(L, g, "setmetatable", sb_setmetatable);
    wrap(L, g, "getmetatable", sb_getmetatable);
    wrap(L, g, "collectgarbage", sb_collectgarbage);
    wrap(L, g, "pcall", sb_catching);
    wrap(L, g, "xpcall", sb_catching);
    lua_getglobal(L, LUA_COLIBNAME);
    wrap(L, -1, "resume", sb_catching);
    lua_pop(L, 1);
    lua_pushcfunction(L, sb_loadfile);
    lua_setfield(L, g, "loadfile");
    lua_pushcfunction(L, sb_dofile);
    lua_setfield(L, g, "dofile");
    lua_pushcfunction(L, sb_require);
    lua_setfield(L, g, "require");

    lua_getglobal(L, LUA_STRLIBNAME);
    drop(L, -1, (const char *const[]){ "dump", NULL });
    lua_getglobal(L, LUA_IOLIBNAME);
    int io = lua_gettop(L);
    drop(L, io, (const char *const[]){ "popen", "tmpfile", NULL });
    wrap(L, io, "open", sb_open);
    wrap(L, io, "lines", sb_raise_read1);
    wrap(L, io, "input", sb_raise_read1);
    wrap(L, io, "output", sb_write1);
    lua_getglobal(L, LUA_OSLIBNAME);
    int os = lua_gettop(L);
    drop(L, os, (const char *const[]){ "execute", "getenv", "tmpname", "setlocale", NULL });
    wrap(L, os, "remove", sb_write1);
    wrap(L, os, "rename", sb_rename);
    lua_pushcfunction(L, sb_exit);
    lua_setfield(L, os, "exit");
    lua_getglobal(L, "lamina");
    drop(L, -1, (const char *const[]){ "plugin", "sandbox", NULL });

    lua_newtable(L); /* the exit object's metatable */
    lua_pushcfunction(L, exit_tostring);
    lua_setfield(L, -2, "__tostring");
    lua_rawsetp(L, LUA_REGISTRYINDEX, &exit_key);
    return 0;
}

/* ---- making and closing ---------------------------------------------------- */

static void sandbox_free(lam_sandbox *sb)
{
    if (!sb) return;
    for (size_t i = 0; i < sb->ndirs; i++) free(sb->dirs[i]);
    for (size_t i = 0; i < sb->nmods; i++) free(sb->mods[i]);
    for (size_t i = 0; i < sb->nmachines; i++) free(sb->machines[i]);
    free(sb->dirs);
    free(sb->writable);
    free(sb);
}

/* mkdir -p, without checks (the caller's own directories) */
int lam_lua_mkdirs(const char *path)
{
    if (!*path) return ENOENT;
    char *p = strdup(path);
    if (!p) return ENOMEM;
    int e = 0;
    for (char *c = p + 1;; c++) {
        if (*c != '/' && *c != '\0') continue;
        char keep = *c;
        *c = '\0';
        struct stat st;
        if (mkdir(p, 0777) != 0 && (errno != EEXIST || stat(p, &st) != 0 || !S_ISDIR(st.st_mode))) e = errno ? errno : EEXIST;
        *c = keep;
        if (e || keep == '\0') break;
    }
    free(p);
    return e;
}

static int add_dir(lam_sandbox *sb, const char *dir, int writable, char *msg, size_t size)
{
    if (writable && lam_lua_mkdirs(dir) != 0) {
        snprintf(msg, size, "--out %s: cannot create the directory: %s", dir, strerror(errno ? errno : EIO));
        return -1;
    }
    char *real = realpath(dir, NULL);
    struct stat st;
    if (!real || stat(real, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(msg, size, "%s %s: not a directory", writable ? "--out" : "--allow", dir);
        free(real);
        return -1;
    }
    sb->dirs[sb->ndirs] = real;
    sb->writable[sb->ndirs++] = writable;
    return 0;
}

lua_State *lam_lua_sandbox_open(const lam_sandbox_opts *o, char *msg, size_t size)
{
    lam_sandbox *sb = calloc(1, sizeof *sb);
    size_t n = o->nallow + o->nout;
    if (sb) {
        sb->dirs = calloc(n + 1, sizeof *sb->dirs);
        sb->writable = calloc(n + 1, sizeof *sb->writable);
    }
    if (!sb || !sb->dirs || !sb->writable) {
        snprintf(msg, size, "not enough memory");
        sandbox_free(sb);
        return NULL;
    }
    for (size_t i = 0; i < o->nallow; i++)
        if (add_dir(sb, o->allow[i], 0, msg, size)) {
            sandbox_free(sb);
            return NULL;
        }
    for (size_t i = 0; i < o->nout; i++)
        if (add_dir(sb, o->out[i], 1, msg, size)) {
            sandbox_free(sb);
            return NULL;
        }
    sb->nmods = lam_lua_dirs(sb->mods, 4);
    char *md[8];
    size_t nmd = lam_machine_dirs(md, 8);
    for (size_t i = 0; i < nmd; i++) {
        char *real = realpath(md[i], NULL);
        if (real) sb->machines[sb->nmachines++] = real;
        free(md[i]);
    }
    sb->mem_limit = o->memory > 0 && o->memory < (double)SIZE_MAX ? (size_t)o->memory : 0;
    sb->time_limit = o->time > 0 ? o->time : 0;
    lua_State *L = lua_newstate(sb_alloc, sb);
    if (!L) {
        snprintf(msg, size, "cannot create a Lua state: not enough memory");
        sandbox_free(sb);
        return NULL;
    }
    lam_file_set_gate(gate, sb, &sb->old_gate, &sb->old_gate_ctx);
    lua_pushcfunction(L, open_libs);
    lua_pushcfunction(L, o->open_lamina);
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
        snprintf(msg, size, "%s", lua_tostring(L, -1));
        lam_lua_sandbox_close(L);
        return NULL;
    }
    return L;
}

void lam_lua_sandbox_start(lua_State *L)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (!sb) return;
    sb->deadline = sb->time_limit > 0 ? now() + sb->time_limit : 0;
    lua_sethook(L, time_hook, LUA_MASKCOUNT, 1000);
}

const char *lam_lua_sandbox_memory_error(lua_State *L, char *buf, size_t size)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    if (!sb || !sb->mem_limit) return NULL;
    snprintf(buf, size,
             "memory limit exceeded (%zu bytes for Lua and lamina's models, slicings and plans together; raise it "
             "with --memory or the option memory)",
             sb->mem_limit);
    return buf;
}

void lam_lua_sandbox_close(lua_State *L)
{
    lam_sandbox *sb = lam_lua_sandbox_of(L);
    lua_close(L);
    if (sb) lam_file_set_gate(sb->old_gate, sb->old_gate_ctx, NULL, NULL);
    sandbox_free(sb);
}
