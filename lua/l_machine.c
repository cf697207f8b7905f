/* lamina.machine: a machine profile (YAML, core/profile/profile.h).
 *
 * lamina.machine(name or path) loads a profile; the userdata owns it.
 * machine:override{...} makes a new machine whose values differ: it holds a
 * shallow copy of the profile (numbers its own, strings and dialect
 * templates borrowed) and keeps the owning machine alive as its user value.
 * Values are validated with the YAML loader's rules and messages: the
 * fields and the keys of override are the rows of core/profile/profile_keys.c. */
#include "l_common.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "profile_keys.h"
#include "writer.h"

/* Whether the machine u (at idx) can still reach its profile: a derived
 * machine's owner may have been finalized in the same cycle. */
static int alive(lua_State *L, int idx, const lmachine *u)
{
    int ok = u->root != NULL;
    if (ok && !u->owner) {
        lua_getiuservalue(L, idx, 1);
        lmachine *owner = LAM_TESTUD(L, -1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE);
        ok = owner && owner->root == u->root;
        lua_pop(L, 1);
    }
    return ok;
}

lmachine *lam_lua_checkmachine(lua_State *L, int idx)
{
    lmachine *u = LAM_CHECKUD(L, idx, lmachine, LAM_MACHINE, LAM_TAG_MACHINE);
    if (!alive(L, idx, u)) luaL_error(L, "attempt to use a collected " LAM_MACHINE);
    return u;
}

/* lamina.machine(name_or_path) -> machine | nil, message */
int lam_lua_machine(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    /* a name is looked up in the machine directories; a path is the user's */
    size_t len = strlen(name);
    int path = strchr(name, '/') || (len > 5 && strcmp(name + len - 5, ".yaml") == 0);
    int n = path ? lam_lua_denied(L, name, 0) : 0;
    if (n) return n;
    lmachine *u = lua_newuserdatauv(L, sizeof *u, 1);
    memset(u, 0, sizeof *u);
    u->tag = LAM_TAG_MACHINE;
    u->owner = 1;
    luaL_setmetatable(L, LAM_MACHINE);
    lam_error err;
    lam_error_clear(&err);
    if (lam_profile_find(name, &u->root, &err)) return lam_lua_fail(L, &err);
    u->p = *u->root;
    return 1;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a > b && strcmp(s + a - b, suffix) == 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* lamina.machines() -> sorted names of the profiles in the machine directories */
int lam_lua_machines(lua_State *L)
{
    char *dirs[16];
    size_t nd = lam_machine_dirs(dirs, 16);
    lua_newtable(L); /* set of names */
    for (size_t d = 0; d < nd; d++) {
        DIR *dir = opendir(dirs[d]);
        struct dirent *de;
        while (dir && (de = readdir(dir))) {
            if (de->d_name[0] == '.' || !ends_with(de->d_name, ".yaml")) continue;
            lua_pushlstring(L, de->d_name, strlen(de->d_name) - 5);
            lua_pushboolean(L, 1);
            lua_rawset(L, -3);
        }
        if (dir) closedir(dir);
        free(dirs[d]);
    }
    lua_newtable(L);
    lua_Integer n = 0;
    lua_pushnil(L);
    while (lua_next(L, -3)) {
        lua_pop(L, 1);
        lua_pushvalue(L, -1);
        lua_rawseti(L, -3, ++n);
    }
    /* sort in C: the names are strings in the sequence */
    if (n > 1) {
        const char **names = lua_newuserdatauv(L, (size_t)n * sizeof *names, 0);
        for (lua_Integer i = 1; i <= n; i++) {
            lua_rawgeti(L, -2, i);
            names[i - 1] = lua_tostring(L, -1);
            lua_pop(L, 1); /* still referenced by the set table */
        }
        qsort(names, (size_t)n, sizeof *names, by_name);
        for (lua_Integer i = 1; i <= n; i++) {
            lua_pushstring(L, names[i - 1]);
            lua_rawseti(L, -3, i);
        }
        lua_pop(L, 1);
    }
    return 1;
}

/* lamina.machine_keys() -> { {name=, lua=, type=, ...}, ... }: the rows of
 * the profile key table, in its order */
int lam_lua_machine_keys(lua_State *L)
{
    static const char *const types[] = { "number", "integer", "boolean", "choice", "string", "template", "numbers",
                                         "lasers" };
    _Static_assert(sizeof types / sizeof types[0] == LAM_KEY_LASERS + 1, "a name for every key type");
    lua_createtable(L, (int)lam_profile_nkeys, 0);
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        lua_createtable(L, 0, 16);
        lua_pushstring(L, k->name);
        lua_setfield(L, -2, "name");
        lua_pushstring(L, lam_key_lua_name(k));
        lua_setfield(L, -2, "lua");
        lua_pushstring(L, types[k->type]);
        lua_setfield(L, -2, "type");
        if (k->type == LAM_KEY_NUMBERS) {
            lua_pushinteger(L, (lua_Integer)k->count);
            lua_setfield(L, -2, "count");
        }
        if (k->type == LAM_KEY_NUMBER || k->type == LAM_KEY_INTEGER || k->type == LAM_KEY_NUMBERS) {
            lua_pushnumber(L, k->lo);
            lua_setfield(L, -2, "min");
            lua_pushnumber(L, k->hi);
            lua_setfield(L, -2, "max");
            lua_pushboolean(L, k->flags & LAM_KEY_ABOVE);
            lua_setfield(L, -2, "above_min");
        }
        if (k->choices) {
            lua_newtable(L);
            for (int c = 0; k->choices[c]; c++) {
                lua_pushstring(L, k->choices[c]);
                lua_rawseti(L, -2, c + 1);
            }
            lua_setfield(L, -2, "choices");
        }
        const char *text[][2] = { { "default", k->def }, { "follows", k->follows }, { "option", k->option },
                                  { "doc", k->doc } };
        for (size_t t = 0; t < sizeof text / sizeof text[0]; t++)
            if (text[t][1]) {
                lua_pushstring(L, text[t][1]);
                lua_setfield(L, -2, text[t][0]);
            }
        const struct { const char *field; unsigned flag; } flags[] = {
            { "optional", LAM_KEY_OPTIONAL }, { "fixed", LAM_KEY_FIXED | LAM_KEY_LOADER }, { "plan", LAM_KEY_PLAN },
            { "loader", LAM_KEY_LOADER },
        };
        for (size_t f = 0; f < sizeof flags / sizeof flags[0]; f++) {
            lua_pushboolean(L, (k->flags & flags[f].flag) != 0);
            lua_setfield(L, -2, flags[f].field);
        }
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

static int mc_gc(lua_State *L)
{
    lmachine *u = LAM_CHECKUD(L, 1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE);
    if (u->owner) lam_profile_free(u->root);
    u->root = NULL;
    return 0;
}

static int mc_tostring(lua_State *L)
{
    lmachine *u = LAM_CHECKUD(L, 1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE);
    if (!alive(L, 1, u)) {
        lua_pushliteral(L, LAM_MACHINE " (collected)");
        return 1;
    }
    int sls = u->p.process == LAM_PROCESS_SLS;
    const lam_key *process = lam_key_at(offsetof(lam_profile, process));
    lua_pushfstring(L, LAM_MACHINE " %s (%s, %s %f%s)", u->p.name, process->choices[sls], sls ? "spot" : "bead",
                    sls ? u->p.spot_width : u->p.bead_width, u->owner ? "" : ", overridden");
    return 1;
}

/* {a, b, ...} of v[0..n) */
static void push_numbers(lua_State *L, const double *v, size_t n)
{
    lua_createtable(L, (int)n, 0);
    for (size_t i = 0; i < n; i++) {
        lua_pushnumber(L, v[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
}

/* A list row's value: {dx, dy}; { {field = {x0, y0, x1, y1}}, ... }; nil
 * when not given. */
static void push_list(lua_State *L, const lam_profile *p, const lam_key *k)
{
    if (!lam_key_given(p, k)) {
        lua_pushnil(L);
        return;
    }
    if (k->type == LAM_KEY_NUMBERS) {
        push_numbers(L, (const double *)(const void *)((const char *)p + k->offset), k->count);
        return;
    }
    lua_createtable(L, (int)p->nlasers, 0);
    for (size_t i = 0; i < p->nlasers; i++) {
        lua_createtable(L, 0, 1);
        push_numbers(L, p->laser_field[i], 4);
        lua_setfield(L, -2, "field");
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
}

void lam_lua_push_key(lua_State *L, const lam_profile *p, const lam_key *k)
{
    const char *at = (const char *)p + k->offset;
    double x = lam_key_get(p, k);
    switch (k->type) {
    case LAM_KEY_NUMBER:
        /* an optional value with a default (spacing: 0) is that number */
        if (k->flags & LAM_KEY_OPTIONAL && x == 0 && !k->def) lua_pushnil(L);
        else if (k->flags & LAM_KEY_AUTO && x < 0) lua_pushliteral(L, "auto");
        else lua_pushnumber(L, x);
        break;
    case LAM_KEY_INTEGER: lua_pushinteger(L, (lua_Integer)x); break;
    case LAM_KEY_BOOLEAN: lua_pushboolean(L, x != 0); break;
    case LAM_KEY_CHOICE: lua_pushstring(L, k->choices[(int)x]); break;
    case LAM_KEY_STRING: lua_pushstring(L, *(char *const *)(const void *)at); break; /* nil when absent */
    case LAM_KEY_TEMPLATE: {
        const lam_template *t = (const lam_template *)(const void *)at;
        if (t->present) lua_pushstring(L, t->source);
        else lua_pushnil(L);
        break;
    }
    case LAM_KEY_NUMBERS:
    case LAM_KEY_LASERS: push_list(L, p, k); break;
    }
}

/* The row Lua knows by `name`: a flat row by its short name, any other by
 * its whole name. */
static const lam_key *lua_key(const char *name)
{
    const lam_key *k = name ? lam_key_find(name) : NULL;
    return k && !(k->flags & LAM_KEY_LOADER) && !strcmp(lam_key_lua_name(k), name) ? k : NULL;
}

static int mc_fields(lua_State *L)
{
    const lam_profile *p = &lam_lua_checkmachine(L, 1)->p;
    const char *name = lua_tostring(L, 2);
    const lam_key *k = lua_key(name);
    if (k) lam_lua_push_key(L, p, k);
    else if (name && strcmp(name, "path") == 0) lua_pushstring(L, p->path);
    else lua_pushnil(L);
    return 1;
}

/* ---- overrides -------------------------------------------------------------- */

/* A list row (gas_flow, lasers): its value does not fit the one number
 * per row that lam_lua_overrides keeps. */
static int is_list(const lam_key *k)
{
    return k->type == LAM_KEY_NUMBERS || k->type == LAM_KEY_LASERS;
}

/* Whether row k may be given in a table whose rows must have `need`. */
static int allowed(const lam_key *k, unsigned need)
{
    return !(k->flags & (LAM_KEY_FIXED | LAM_KEY_LOADER)) && (k->flags & need) == need && !is_list(k);
}

static void read_one(lua_State *L, int t, int arg, const lam_key *k, double *v)
{
    const char *name = lam_key_lua_name(k);
    double x = 0;
    int i = 0;
    lam_error err;
    char shown[64];
    switch (k->type) {
    case LAM_KEY_NUMBER:
    case LAM_KEY_INTEGER:
        if (k->flags & LAM_KEY_AUTO) {
            int is_auto = lua_getfield(L, t, name) == LUA_TSTRING && !strcmp(lua_tostring(L, -1), "auto");
            lua_pop(L, 1);
            if (is_auto) {
                *v = -1;
                break;
            }
        }
        lam_lua_numfield(L, t, arg, name, &x);
        snprintf(shown, sizeof shown, "%.14g", x);
        if (lam_key_check(k, name, x, shown, &err)) lam_lua_opterror(L, arg, "%s", err.msg);
        *v = x;
        break;
    case LAM_KEY_CHOICE:
        lam_lua_choicefield(L, t, arg, name, k->choices, &i);
        *v = i;
        break;
    case LAM_KEY_BOOLEAN:
        lam_lua_boolfield(L, t, arg, name, &i);
        *v = i;
        break;
    default:
        break; /* strings and templates are FIXED */
    }
}

void lam_lua_read_overrides(lua_State *L, int t, int arg, unsigned need, const char *const *extra,
                            lam_lua_overrides *o)
{
    t = lua_absindex(L, t);
    memset(o, 0, sizeof *o);
    const char *names[LAM_KEYS_MAX + 9];
    size_t n = 0;
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (allowed(&lam_profile_keys[i], need)) names[n++] = lam_key_lua_name(&lam_profile_keys[i]);
    for (size_t i = 0; extra && extra[i] && n < LAM_KEYS_MAX + 8; i++) names[n++] = extra[i];
    names[n] = NULL;
    /* keys of the profile that cannot be given here get their own message */
    lua_pushnil(L);
    while (lua_next(L, t)) {
        lua_pop(L, 1);
        const char *name = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
        const lam_key *k = lua_key(name);
        if (!name || (k && allowed(k, need))) continue;
        if (k && is_list(k) && !(need & LAM_KEY_PLAN))
            lam_lua_opterror(L, arg, "%s cannot be changed here (give it in the profile, or with --set)", name);
        if (k && k->flags & LAM_KEY_FIXED)
            lam_lua_opterror(L, arg, "%s cannot be changed here (load another machine profile)", name);
        if (k) lam_lua_opterror(L, arg, "%s cannot be changed here (it is not a planning option)", name);
        for (size_t i = 0; i < lam_profile_nkeys; i++) {
            const lam_key *f = &lam_profile_keys[i];
            size_t sl = lam_key_section_len(f);
            if (f->flags & LAM_KEY_FLAT && strlen(name) == sl && !strncmp(f->name, name, sl))
                lam_lua_opterror(L, arg, "give the %s keys directly (%s = ..., not %s = {%s = ...})", name,
                                 lam_key_short(f), name, lam_key_short(f));
        }
    }
    lam_lua_checkkeys(L, t, arg, names);
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (!allowed(k, need)) continue;
        int present = lua_getfield(L, t, lam_key_lua_name(k)) != LUA_TNIL;
        lua_pop(L, 1);
        if (!present) continue;
        read_one(L, t, arg, k, &o->v[i]);
        o->set[i] = 1;
    }
}

void lam_lua_apply_overrides(const lam_lua_overrides *o, lam_profile *p)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (o->set[i]) lam_key_put(p, &lam_profile_keys[i], o->v[i]);
}

void lam_lua_check_readers(lua_State *L, int arg, const lam_lua_overrides *o, const lam_profile *p)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        lam_error err;
        if (!o->set[i] || lam_key_read_by(k, p->process)) continue;
        lam_key_unread(k, lam_key_lua_name(k), p->process, p->name, &err);
        lam_lua_opterror(L, arg, "%s", err.msg);
    }
}

/* machine:override{key = value, ...} -> a new machine */
static int mc_override(lua_State *L)
{
    lam_lua_checkmachine(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    lam_lua_overrides ovr;
    lam_lua_read_overrides(L, 2, 2, 0, NULL, &ovr); /* may run metamethods: no pointers held yet */
    lam_lua_check_readers(L, 2, &ovr, &lam_lua_checkmachine(L, 1)->p);
    /* the plate the values leave is one shape, whole (a width needs a depth) */
    lam_profile trial = lam_lua_checkmachine(L, 1)->p;
    lam_lua_apply_overrides(&ovr, &trial);
    lam_error err;
    if (lam_profile_check_plate(&trial, &err)) lam_lua_opterror(L, 2, "%s", err.msg);
    lmachine *u = lua_newuserdatauv(L, sizeof *u, 1);
    memset(u, 0, sizeof *u);
    u->tag = LAM_TAG_MACHINE;
    luaL_setmetatable(L, LAM_MACHINE);
    const lmachine *base = lam_lua_checkmachine(L, 1); /* nothing allocates from here on */
    u->root = base->root;
    u->p = base->p;
    lam_lua_apply_overrides(&ovr, &u->p);
    if (base->owner) lua_pushvalue(L, 1);
    else lua_getiuservalue(L, 1, 1);
    lua_setiuservalue(L, -2, 1);
    return 1;
}

/* machine:yaml() -> the profile as YAML with the current values */
static int mc_yaml(lua_State *L)
{
    lmachine *u = lam_lua_checkmachine(L, 1);
    lam_writer *w;
    lam_error err;
    lam_error_clear(&err);
    size_t len = 0;
    void **box = lam_lua_newbox(L); /* frees the text even if pushing it fails */
    if (lam_writer_memory(&w, &err)) return lam_lua_fail(L, &err);
    lam_profile_dump(&u->p, w);
    if (lam_writer_take(w, (char **)box, &len, &err)) return lam_lua_fail(L, &err);
    lua_pushlstring(L, *box, len);
    free(*box);
    *box = NULL;
    return 1;
}

void lam_lua_plan_opts(const lam_profile *p, lam_plan_opts *o)
{
    lam_plan_opts_from_profile(o, p);
}

static const luaL_Reg machine_meta[] = {
    { "__gc", mc_gc },
    { "__tostring", mc_tostring },
    { NULL, NULL },
};

static const luaL_Reg machine_methods[] = {
    { "override", mc_override },
    { "yaml", mc_yaml },
    { NULL, NULL },
};

void lam_lua_open_machine(lua_State *L)
{
    lam_lua_newclass(L, LAM_MACHINE, machine_meta, machine_methods, mc_fields);
}
