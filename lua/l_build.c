/* lamina.build{...}: a build plate (issue 25) from Lua, the same build a
 * YAML job file describes (core/build/build_job.h) made through the same
 * calls (build.h): the machine with the build's profile keys, the styles,
 * the parts; then lam_build_run_new places them and lam_build_run_plan
 * plans the plate into the machine's writer, teed with Lua's plan data
 * (views.h), as machine:plan does. The result is a lamina.plan (l_plan.c:
 * the program, p:layer(i), p.time, ...) whose user value holds the
 * build's own fields (parts, lasers, styles, labels), which the plan
 * class's fields (l_plan.c) look at first.
 *
 * Lua tables have no order: profile keys are applied in the order of the
 * profile's key table (lamina.machine_keys()), styles are numbered after
 * the four regions' in the order of their names, and each part's units,
 * scale and rotations apply in that order (as lamina.load's do). */
#include "l_common.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "build.h"
#include "build_plan.h"
#include "build_run.h"
#include "plugin.h"
#include "pool.h"
#include "tee.h"
#include "views.h"
#include "writer.h"
#include "xform.h"

#define LAM_BUILDJOB "lamina.buildjob"
#define FLOW_MAX 65536 /* a value written as YAML flow text (lasers: 16 fields) */
#define MAX_DEPTH 8

/* Everything C that lamina.build holds while it works, released by __gc
 * when Lua raises an error half-way (a bad key, an interrupt, memory). */
typedef struct bjob {
    unsigned tag;
    lam_profile *p;          /* the machine, until the build takes it */
    lam_build *b;
    lam_build_run *run;
    lam_writer *w;
    lam_sink sink;           /* the program's sink teed with the plan data's */
    int have_sink;
    lam_plan_data rec;       /* what was planned: handed to the plan */
    lam_error err;           /* the sinks report through it: it must not move */
    size_t charged;          /* the plate's models and slicers, charged to a sandbox */
    char flow[FLOW_MAX];     /* a Lua value as text for lam_profile_set */
    size_t flen;
} bjob;

static const char *const job_keys[] = { "machine", "parts", "styles", "threads", "max_output", NULL };
static const char *const part_keys[] = { "model", "name", "units", "scale", "rotate", "copies", "at", "z", "style",
                                         NULL };

static void job_release(lua_State *L, bjob *j)
{
    if (j->have_sink && j->sink.destroy) j->sink.destroy(j->sink.ctx);
    j->have_sink = 0;
    lam_writer_abort(j->w);
    j->w = NULL;
    lam_plan_data_free(&j->rec);
    lam_build_run_free(j->run);
    j->run = NULL;
    lam_build_free(j->b);
    j->b = NULL;
    lam_profile_free(j->p);
    j->p = NULL;
    lam_lua_discharge(L, &j->charged);
}

static int job_gc(lua_State *L)
{
    job_release(L, LAM_CHECKUD(L, 1, bjob, LAM_BUILDJOB, LAM_TAG_BUILDJOB));
    return 0;
}

static bjob *new_job(lua_State *L)
{
    bjob *j = lua_newuserdatauv(L, sizeof *j, 0);
    memset(j, 0, sizeof *j);
    j->tag = LAM_TAG_BUILDJOB;
    if (luaL_newmetatable(L, LAM_BUILDJOB)) {
        lua_pushcfunction(L, job_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    lam_error_clear(&j->err);
    return j;
}

/* ---- keys -------------------------------------------------------------------- */

static int in_list(const char *s, const char *const *list)
{
    for (size_t i = 0; list[i]; i++)
        if (!strcmp(s, list[i])) return 1;
    return 0;
}

/* The profile row `name` names (a whole name, an alias, a flat row's own
 * name), as lam_profile_set finds it; NULL for none or the loader's. */
static const lam_key *profile_key(const char *name)
{
    const lam_key *k = lam_key_find(name);
    return k && !(k->flags & LAM_KEY_LOADER) ? k : NULL;
}

/* Whether `key` is a section of profile keys (plate, contour, raster, ...). */
static int is_section(const char *key)
{
    size_t n = strlen(key);
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (!strncmp(lam_profile_keys[i].name, key, n) && lam_profile_keys[i].name[n] == '.') return 1;
    return 0;
}

/* Raise "unknown key 'KEY' in WHERE (did you mean ...?)": the nearest of
 * names and, with profile, of the profile's keys by their Lua names. */
static int unknown(lua_State *L, const char *key, const char *where, const char *const *names, int profile)
{
    const char *all[LAM_KEYS_MAX + 16];
    size_t n = 0;
    for (size_t i = 0; names[i] && n < 16; i++) all[n++] = names[i];
    for (size_t i = 0; profile && i < lam_profile_nkeys && n < LAM_KEYS_MAX + 16; i++)
        if (!(lam_profile_keys[i].flags & LAM_KEY_LOADER)) all[n++] = lam_key_lua_name(&lam_profile_keys[i]);
    const char *near = lam_key_nearest(key, all, n);
    char hint[160] = "";
    if (near) snprintf(hint, sizeof hint, " (did you mean %s?)", near);
    return lam_lua_opterror(L, 1, "unknown key '%s' in %s%s", key, where, hint);
}

/* Every key of the build table is a string this file or the profile knows. */
static void check_job_keys(lua_State *L)
{
    char b[64];
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        lua_pop(L, 1);
        if (lua_type(L, -1) != LUA_TSTRING)
            lam_lua_opterror(L, 1, "unexpected key %s (a build's keys are named)", lam_lua_describe(L, -1, b, sizeof b));
        const char *k = lua_tostring(L, -1);
        if (!in_list(k, job_keys) && !profile_key(k) && !is_section(k)) unknown(L, k, "the build", job_keys, 1);
    }
}

/* ---- a Lua value as text for lam_profile_set ------------------------------------ */

static int put(bjob *j, const char *s)
{
    size_t n = strlen(s);
    if (j->flen + n >= FLOW_MAX) return -1;
    memcpy(j->flow + j->flen, s, n + 1);
    j->flen += n;
    return 0;
}

/* A number as the YAML loader reads it back to the same double. */
static int put_number(lua_State *L, bjob *j, int idx)
{
    char t[64];
    if (lua_isinteger(L, idx)) snprintf(t, sizeof t, "%lld", (long long)lua_tointeger(L, idx));
    else if (isfinite(lua_tonumber(L, idx))) snprintf(t, sizeof t, "%.17g", (double)lua_tonumber(L, idx));
    else return -2;
    return put(j, t);
}

/* Text inside a flow value: double-quoted with YAML's escapes. */
static int put_quoted(lua_State *L, bjob *j, int idx)
{
    size_t len;
    const char *s = lua_tolstring(L, idx, &len);
    int rc = put(j, "\"");
    for (size_t i = 0; i < len && !rc; i++) {
        char c[8] = { s[i], 0 };
        if (s[i] == '"' || s[i] == '\\') snprintf(c, sizeof c, "\\%c", s[i]);
        else if ((unsigned char)s[i] < 0x20) snprintf(c, sizeof c, "\\x%02x", (unsigned char)s[i]);
        rc = put(j, c);
    }
    return rc ? rc : put(j, "\"");
}

/* A mapping's key: plain when it is a plain word (field), else quoted. */
static int put_key(lua_State *L, bjob *j, int idx)
{
    const char *s = lua_tostring(L, idx);
    int plain = s[0] != '\0';
    for (const char *c = s; *c && plain; c++)
        plain = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_';
    int rc = plain ? put(j, s) : put_quoted(L, j, idx);
    return rc ? rc : put(j, ": ");
}

/* The value at idx: 0, -1 too long, -2 not a number, text, boolean or a
 * table of them, -3 a table both list and mapping (or a key not text). */
static int flow(lua_State *L, bjob *j, int idx, int depth)
{
    idx = lua_absindex(L, idx);
    int ty = lua_type(L, idx);
    if (ty == LUA_TNUMBER) return put_number(L, j, idx);
    if (ty == LUA_TBOOLEAN) return put(j, lua_toboolean(L, idx) ? "true" : "false");
    if (ty == LUA_TSTRING) return depth ? put_quoted(L, j, idx) : put(j, lua_tostring(L, idx));
    if (ty != LUA_TTABLE || depth > MAX_DEPTH) return -2;
    lua_Unsigned n = lua_rawlen(L, idx), count = 0;
    int rc = put(j, n ? "[" : "{");
    lua_pushnil(L);
    while (!rc && lua_next(L, idx)) {
        int seq = lua_isinteger(L, -2) && lua_tointeger(L, -2) >= 1 && (lua_Unsigned)lua_tointeger(L, -2) <= n;
        if (n ? !seq : lua_type(L, -2) != LUA_TSTRING) rc = -3;
        if (!rc && !n) { /* a mapping in lua_next's order: its order means nothing */
            rc = count++ ? put(j, ", ") : 0;
            if (!rc) rc = put_key(L, j, -2);
            if (!rc) rc = flow(L, j, -1, depth + 1);
        }
        lua_pop(L, 1);
    }
    if (rc) {
        lua_pop(L, 1); /* the key lua_next left */
        return rc;
    }
    for (lua_Unsigned i = 1; i <= n && !rc; i++) { /* a list in its order */
        if (i > 1) rc = put(j, ", ");
        lua_rawgeti(L, idx, (lua_Integer)i);
        if (!rc) rc = flow(L, j, -1, depth + 1);
        lua_pop(L, 1);
    }
    return rc ? rc : put(j, n ? "]" : "}");
}

/* The value at the top as text in j->flow; a bad one raises, naming it. */
static const char *value_text(lua_State *L, bjob *j, const char *name)
{
    char b[64];
    j->flen = 0;
    j->flow[0] = '\0';
    int rc = lua_isnil(L, -1) ? -2 : flow(L, j, -1, 0);
    if (rc == -1) lam_lua_opterror(L, 1, "%s: the value is too large", name);
    if (rc == -3) lam_lua_opterror(L, 1, "%s: a table must be a list {a, b, ...} or a table of named keys", name);
    if (rc) lam_lua_opterror(L, 1, "%s must be a number, text, a boolean or a list of them, got %s", name,
                             lam_lua_describe(L, -1, b, sizeof b));
    return j->flow;
}

/* ---- the machine and its keys ------------------------------------------------------ */

static int is_path(const char *s)
{
    size_t n = strlen(s);
    return strchr(s, '/') || (n > 5 && !strcmp(s + n - 5, ".yaml")) || (n > 4 && !strcmp(s + n - 4, ".yml"));
}

/* A lamina.machine's values: its profile read again from its file, with
 * the numbers, choices and booleans machine:override may have changed. */
static int machine_copy(lua_State *L, bjob *j, int idx)
{
    const lmachine *u = lam_lua_checkmachine(L, idx);
    if (!u->root->path) lam_lua_opterror(L, 1, "machine %s was not loaded from a file", u->p.name);
    char path[4096];
    snprintf(path, sizeof path, "%s", u->root->path);
    if (lam_profile_find(path, &j->p, &j->err)) return lam_lua_fail(L, &j->err);
    u = lam_lua_checkmachine(L, idx); /* nothing in between ran Lua; taken again all the same */
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->flags & (LAM_KEY_FIXED | LAM_KEY_LOADER)) continue;
        if (k->type == LAM_KEY_NUMBER || k->type == LAM_KEY_INTEGER || k->type == LAM_KEY_BOOLEAN ||
            k->type == LAM_KEY_CHOICE)
            lam_key_store(j->p, k, lam_key_get(&u->p, k));
    }
    return 0;
}

/* machine = NAME | PATH | lamina.machine into j->p: 0, or the results of
 * a failure (nil, message) to return. */
static int open_machine(lua_State *L, bjob *j)
{
    char b[64];
    int ty = lua_getfield(L, 1, "machine"), n = 0;
    if (ty == LUA_TSTRING) {
        const char *name = lua_tostring(L, -1);
        if (is_path(name) && (n = lam_lua_denied(L, name, 0))) return n;
        if (lam_profile_find(name, &j->p, &j->err)) return lam_lua_fail(L, &j->err);
    } else if (LAM_TESTUD(L, -1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE)) {
        if ((n = machine_copy(L, j, lua_gettop(L)))) return n;
    } else if (ty == LUA_TNIL) {
        lam_lua_opterror(L, 1, "machine is missing: give a shipped machine's name (lamina.machines()), "
                               "a profile's path or a lamina.machine");
    } else {
        lam_lua_opterror(L, 1, "machine must be a machine's name, a profile's path or a lamina.machine, got %s",
                         lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
    return 0;
}

/* Set row k from the value at the top, named `as` in messages; *first
 * keeps the name it was first given by (two names of one row raise). */
static void set_row(lua_State *L, bjob *j, const lam_key *k, const char *as, char *first, size_t size)
{
    if (first[0]) { /* the names in their order: lua_next's is the table's hashing */
        int less = strcmp(first, as) < 0;
        lam_lua_opterror(L, 1, "%s is given twice (as %s and as %s)", k->name, less ? first : as, less ? as : first);
    }
    snprintf(first, size, "%s", as);
    const char *text = value_text(L, j, as);
    lam_error e;
    lam_error_clear(&e);
    if (lam_profile_set(j->p, k->name, text, &e)) lam_lua_opterror(L, 1, "%s", e.msg);
}

/* Row k from the build table, given at the top level or in its section's
 * table (plate = {width = ...}). */
static void apply_row(lua_State *L, bjob *j, const lam_key *k)
{
    char name[256], first[256] = "";
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        const char *top = lua_tostring(L, -2);
        if (in_list(top, job_keys)) { /* read elsewhere */
        } else if (profile_key(top) == k) {
            set_row(L, j, k, top, first, sizeof first);
        } else if (!profile_key(top) && lua_type(L, -1) == LUA_TTABLE) {
            lua_pushnil(L);
            while (lua_next(L, -2)) {
                snprintf(name, sizeof name, "%s.%s", top, lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "?");
                if (lua_type(L, -2) == LUA_TSTRING && profile_key(name) == k) set_row(L, j, k, name, first, sizeof first);
                lua_pop(L, 1);
            }
        }
        lua_pop(L, 1);
    }
    lam_error e;
    if (first[0] && !lam_key_read_by(k, j->p->process)) { /* it would do nothing: as machine:override */
        lam_key_unread(k, first, j->p->process, j->p->name, &e);
        lam_lua_opterror(L, 1, "%s", e.msg);
    }
}

/* A section's table holds keys of that section only; a section is a table. */
static void check_sections(lua_State *L)
{
    char name[256], b[64];
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        const char *top = lua_tostring(L, -2);
        if (!in_list(top, job_keys) && !profile_key(top)) {
            if (lua_type(L, -1) != LUA_TTABLE)
                lam_lua_opterror(L, 1, "%s must be a table of its keys (%s = {...}), got %s", top, top,
                                 lam_lua_describe(L, -1, b, sizeof b));
            lua_pushnil(L);
            while (lua_next(L, -2)) {
                lua_pop(L, 1);
                if (lua_type(L, -1) != LUA_TSTRING)
                    lam_lua_opterror(L, 1, "%s: unexpected key %s", top, lam_lua_describe(L, -1, b, sizeof b));
                snprintf(name, sizeof name, "%s.%s", top, lua_tostring(L, -1));
                const lam_key *k = profile_key(name);
                if (!k || lam_key_section_len(k) != strlen(top)) {
                    const char *none[] = { NULL };
                    unknown(L, name, top, none, 1);
                }
            }
        }
        lua_pop(L, 1);
    }
}

static void apply_profile_keys(lua_State *L, bjob *j)
{
    check_sections(L);
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (!(lam_profile_keys[i].flags & LAM_KEY_LOADER)) apply_row(L, j, &lam_profile_keys[i]);
    lam_error e;
    lam_error_clear(&e);
    if (lam_profile_check(j->p, &e)) lam_lua_opterror(L, 1, "with the build's values: %s", e.msg);
}

/* ---- styles -------------------------------------------------------------------------- */

static int by_name(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Style `name` from the table at the top: each key a style key with a
 * number, text or boolean. */
static void one_style(lua_State *L, bjob *j, const char *name)
{
    char b[64], what[300];
    int t = lua_gettop(L), any = 0;
    if (lua_type(L, t) != LUA_TTABLE)
        lam_lua_opterror(L, 1, "styles.%s must be a table of exposure and hatching keys, got %s", name,
                         lam_lua_describe(L, t, b, sizeof b));
    lua_pushnil(L);
    while (lua_next(L, t)) {
        if (lua_type(L, -2) != LUA_TSTRING)
            lam_lua_opterror(L, 1, "styles.%s: unexpected key %s", name, lam_lua_describe(L, -2, b, sizeof b));
        snprintf(what, sizeof what, "styles.%s.%s", name, lua_tostring(L, -2));
        if (lua_type(L, -1) == LUA_TTABLE) lam_lua_opterror(L, 1, "%s must be a value, got a table", what);
        const char *text = value_text(L, j, what);
        lam_error e;
        lam_error_clear(&e);
        if (lam_build_style_set(j->b, name, lua_tostring(L, -2), text, 0, 0, &e))
            lam_lua_opterror(L, 1, "styles.%s: %s", name, e.msg);
        any = 1;
        lua_pop(L, 1);
    }
    if (!any) lam_lua_opterror(L, 1, "styles.%s sets nothing", name);
}

/* styles = {NAME = {key = value, ...}, ...}, defined in the order of
 * their names (the numbers and labels they get). */
static void read_styles(lua_State *L, bjob *j)
{
    char b[64];
    int ty = lua_getfield(L, 1, "styles");
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return;
    }
    if (ty != LUA_TTABLE)
        lam_lua_opterror(L, 1, "styles must be a table of named styles, got %s", lam_lua_describe(L, -1, b, sizeof b));
    int t = lua_gettop(L);
    lua_Integer n = 0;
    lua_newtable(L); /* the names, held here: a finalizer cannot take them from the recipe's table */
    lua_pushnil(L);
    while (lua_next(L, t)) {
        if (lua_type(L, -2) != LUA_TSTRING || !lua_tostring(L, -2)[0])
            lam_lua_opterror(L, 1, "styles: a style's name must be text, got %s", lam_lua_describe(L, -2, b, sizeof b));
        if (++n > LAM_BUILD_MAX_STYLES) lam_lua_opterror(L, 1, "styles: more than %d styles", LAM_BUILD_MAX_STYLES);
        lua_pop(L, 1);
        lua_pushvalue(L, -1);
        lua_rawseti(L, t + 1, n);
    }
    const char **names = lua_newuserdatauv(L, (size_t)(n ? n : 1) * sizeof *names, 0);
    for (lua_Integer k = 1; k <= n; k++) {
        lua_rawgeti(L, t + 1, k);
        names[k - 1] = lua_tostring(L, -1);
        lua_pop(L, 1);
    }
    qsort(names, (size_t)n, sizeof *names, by_name);
    for (lua_Integer i = 0; i < n; i++) {
        lua_getfield(L, t, names[i]);
        one_style(L, j, names[i]);
        lua_settop(L, t + 2);
    }
    lua_settop(L, t - 1);
}

/* ---- parts ------------------------------------------------------------------------------ */

/* Raise "parts[I]MSG" (MSG begins with ".key ..." or ": ..."). */
static int part_error(lua_State *L, int i, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return lam_lua_opterror(L, 1, "parts[%d]%s", i, msg);
}

/* Field key of part i (table t) as a finite number: 0 when absent. */
static int part_number(lua_State *L, int t, int i, const char *key, double *x)
{
    char b[64];
    int ty = lua_getfield(L, t, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    if (ty != LUA_TNUMBER || !isfinite(lua_tonumber(L, -1)))
        part_error(L, i, ".%s must be a number, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    *x = (double)lua_tonumber(L, -1);
    lua_pop(L, 1);
    return 1;
}

/* {a, b, ...}: n numbers of the list at the top, for part i's key. */
static void part_numbers(lua_State *L, int i, const char *key, double *x, size_t n)
{
    char b[64];
    if (lua_type(L, -1) != LUA_TTABLE || lua_rawlen(L, -1) != n)
        part_error(L, i, ".%s must be a list of %zu numbers, got %s", key, n, lam_lua_describe(L, -1, b, sizeof b));
    for (size_t k = 0; k < n; k++) {
        if (lua_rawgeti(L, -1, (lua_Integer)k + 1) != LUA_TNUMBER || !isfinite(lua_tonumber(L, -1)))
            part_error(L, i, ".%s[%zu] must be a number, got %s", key, k + 1, lam_lua_describe(L, -1, b, sizeof b));
        x[k] = (double)lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
}

/* Text through one of xform.h's parsers; a bad one raises. */
static void part_xform(lua_State *L, int i, const char *key, lam_xform *x, const char *text)
{
    lam_error e;
    lam_error_clear(&e);
    int rc = !strcmp(key, "rotate") ? lam_xform_parse_rotate(x, text, &e) : lam_xform_parse_scale(x, text, &e);
    if (rc) part_error(L, i, ".%s '%s': %s", key, text, e.msg);
}

/* units, then scale, then rotate (lamina.load's order). */
static void part_shape(lua_State *L, bjob *j, int t, int i, lam_build_part *p)
{
    char b[64], text[128];
    if (lua_getfield(L, t, "units") != LUA_TNIL) {
        double mm = lua_type(L, -1) == LUA_TSTRING ? lam_unit_mm(lua_tostring(L, -1)) : 0;
        double machine = lam_profile_unit_mm(j->b->profile);
        if (!(mm > 0))
            part_error(L, i, ".units must be mm, cm, m, um, in, inch or ft, got %s", lam_lua_describe(L, -1, b, sizeof b));
        if (!(machine > 0)) part_error(L, i, ".units: the machine's units (%s) are unknown", j->b->profile->units);
        lam_xform_scale_by(&p->xform, mm / machine);
    }
    lua_pop(L, 1);
    int ty = lua_getfield(L, t, "scale");
    if (ty != LUA_TNIL) {
        double s[3];
        if (ty == LUA_TNUMBER) s[0] = s[1] = s[2] = (double)lua_tonumber(L, -1);
        else part_numbers(L, i, "scale", s, 3);
        snprintf(text, sizeof text, "%.17g,%.17g,%.17g", s[0], s[1], s[2]);
        part_xform(L, i, "scale", &p->xform, text);
    }
    lua_pop(L, 1);
    ty = lua_getfield(L, t, "rotate");
    if (ty == LUA_TSTRING) {
        part_xform(L, i, "rotate", &p->xform, lua_tostring(L, -1));
    } else if (ty == LUA_TTABLE) {
        for (lua_Integer k = 1; k <= (lua_Integer)lua_rawlen(L, -1); k++) {
            if (lua_rawgeti(L, -1, k) != LUA_TSTRING)
                part_error(L, i, ".rotate[%d] must be text such as \"x:90\", got %s", (int)k,
                           lam_lua_describe(L, -1, b, sizeof b));
            part_xform(L, i, "rotate", &p->xform, lua_tostring(L, -1));
            lua_pop(L, 1);
        }
    } else if (ty != LUA_TNIL) {
        part_error(L, i, ".rotate must be text such as \"x:90\" or a list of them, got %s",
                   lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
}

/* The style named by the string at the top, for part i (did you mean). */
static int style_ref(lua_State *L, bjob *j, int i, const char *where)
{
    char b[64];
    if (lua_type(L, -1) != LUA_TSTRING)
        part_error(L, i, ".%s must be a style's name, got %s", where, lam_lua_describe(L, -1, b, sizeof b));
    int s = lam_build_style_find(j->b, lua_tostring(L, -1));
    if (s >= 0) return s;
    const char *names[LAM_BUILD_MAX_STYLES];
    for (size_t k = 0; k < j->b->nstyles; k++) names[k] = j->b->styles[k].name;
    const char *near = lam_key_nearest(lua_tostring(L, -1), names, j->b->nstyles);
    return part_error(L, i, ".%s: style %s is not defined in styles%s%s%s", where, lua_tostring(L, -1),
                      near ? " (did you mean " : "", near ? near : "", near ? "?)" : "");
}

/* style = NAME (every region) or {REGION = NAME, ...}. */
static void part_style(lua_State *L, bjob *j, int t, int i, lam_build_part *p)
{
    char b[64], where[64];
    int ty = lua_getfield(L, t, "style");
    if (ty == LUA_TSTRING) {
        int s = style_ref(L, j, i, "style");
        for (int r = 0; r < LAM_REGIONS; r++) p->style[r] = s;
        p->style_whole = 1;
    } else if (ty == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            int r = lua_type(L, -2) == LUA_TSTRING ? lam_region_find(lua_tostring(L, -2)) : -1;
            if (r < 0)
                part_error(L, i, ".style: %s is not a region (contour, core, upskin or downskin)",
                           lam_lua_describe(L, -2, b, sizeof b));
            snprintf(where, sizeof where, "style.%s", lua_tostring(L, -2));
            p->style[r] = style_ref(L, j, i, where);
            lua_pop(L, 1);
        }
    } else if (ty != LUA_TNIL) {
        part_error(L, i, ".style must be a style's name or a table of regions to styles, got %s",
                   lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
}

/* model and name: text copied into out (size bytes). */
static int part_text(lua_State *L, int t, int i, const char *key, char *out, size_t size)
{
    char b[64];
    int ty = lua_getfield(L, t, key);
    out[0] = '\0';
    if (ty != LUA_TNIL && (ty != LUA_TSTRING || !lua_tostring(L, -1)[0]))
        part_error(L, i, ".%s must be %s, got %s", key, key[0] == 'm' ? "a model's path" : "text (not empty)",
                   lam_lua_describe(L, -1, b, sizeof b));
    if (ty != LUA_TNIL && strlen(lua_tostring(L, -1)) >= size) part_error(L, i, ".%s is too long", key);
    if (ty != LUA_TNIL) snprintf(out, size, "%s", lua_tostring(L, -1));
    lua_pop(L, 1);
    return ty != LUA_TNIL;
}

/* copies, at and z of part i. */
static void part_place(lua_State *L, int t, int i, lam_build_part *p)
{
    double x = 1;
    if (part_number(L, t, i, "copies", &x) && !(x >= 1 && x <= LAM_BUILD_MAX_COPIES && x == floor(x)))
        part_error(L, i, ".copies must be a whole number from 1 to %d, got %.14g", LAM_BUILD_MAX_COPIES, x);
    p->copies = (size_t)x;
    if (part_number(L, t, i, "z", &p->z) && p->z < 0)
        part_error(L, i, ".z must be 0 or more (above the plate), got %.14g", p->z);
    if (lua_getfield(L, t, "at") != LUA_TNIL) {
        part_numbers(L, i, "at", p->at, 2);
        p->has_at = 1;
        if (p->copies > 1) part_error(L, i, ".at: a part with at has one copy: list each placed copy as a part");
    }
    lua_pop(L, 1);
}

/* Part i (the table at t) into the build. */
static void one_part(lua_State *L, bjob *j, int t, int i)
{
    char b[64], where[32];
    if (lua_type(L, t) != LUA_TTABLE)
        part_error(L, i, " must be a table {model = PATH, ...}, got %s", lam_lua_describe(L, t, b, sizeof b));
    snprintf(where, sizeof where, "parts[%d]", i);
    lua_pushnil(L);
    while (lua_next(L, t)) {
        lua_pop(L, 1);
        if (lua_type(L, -1) != LUA_TSTRING)
            part_error(L, i, ": unexpected key %s (a part's keys are named)", lam_lua_describe(L, -1, b, sizeof b));
        if (!in_list(lua_tostring(L, -1), part_keys)) unknown(L, lua_tostring(L, -1), where, part_keys, 0);
    }
    lam_build_part p;
    lam_build_part_init(&p);
    char model[4096], name[128];
    if (!part_text(L, t, i, "model", model, sizeof model)) part_error(L, i, " names no model: add model = PATH");
    part_text(L, t, i, "name", name, sizeof name);
    part_shape(L, j, t, i, &p);
    part_place(L, t, i, &p);
    part_style(L, j, t, i, &p);
    p.model = model;
    p.name = name[0] ? name : NULL;
    lam_error e;
    lam_error_clear(&e);
    if (lam_build_part_add(j->b, &p, &e)) part_error(L, i, ": %s", e.msg);
}

static void read_parts(lua_State *L, bjob *j)
{
    char b[64];
    int ty = lua_getfield(L, 1, "parts");
    if (ty != LUA_TTABLE)
        lam_lua_opterror(L, 1, "parts must be a list of parts {{model = PATH, ...}, ...}, got %s",
                         lam_lua_describe(L, -1, b, sizeof b));
    int t = lua_gettop(L);
    lua_Unsigned n = lua_rawlen(L, t);
    if (n == 0) lam_lua_opterror(L, 1, "parts is empty: list at least one part");
    for (lua_Unsigned i = 1; i <= n; i++) {
        lua_rawgeti(L, t, (lua_Integer)i);
        one_part(L, j, t + 1, (int)i);
        lua_settop(L, t);
    }
    lua_pop(L, 1);
}

/* ---- the plate ----------------------------------------------------------------------------- */

/* What lamina.build reads for itself (not profile keys). */
typedef struct bopts {
    unsigned threads;
    double max_output;       /* 0: LAM_DEFAULT_MAX_OUTPUT */
} bopts;

static void read_opts(lua_State *L, bopts *o)
{
    double n = 0;
    o->threads = lam_lua_threads(L); /* the script's default (lamina.threads()) */
    o->max_output = 0;
    if (lam_lua_numfield(L, 1, 1, "threads", &n)) {
        if (!(n >= 0 && n <= LAM_MAX_THREADS && n == floor(n)))
            lam_lua_opterror(L, 1, "threads must be a whole number from 0 to %d (0: the online cores), got %.14g",
                             LAM_MAX_THREADS, n);
        o->threads = n == 0 ? lam_online_cores() : (unsigned)n;
    }
    if (lam_lua_numfield(L, 1, 1, "max_output", &o->max_output) && !(o->max_output >= 1 && o->max_output < 1.8e19))
        lam_lua_opterror(L, 1, "max_output must be a number of bytes >= 1, got %.14g", o->max_output);
}

/* Load and place the parts: 0, or the results of a failure to return. In
 * a sandbox the models must be readable, their files must fit the memory
 * left before they are read (a model file is read whole), and the plate's
 * models and their slicers (one per copy) are charged once made. */
static int place(lua_State *L, bjob *j, unsigned threads)
{
    size_t files = 0, check = 0, np, bytes = 0;
    for (size_t i = 0; i < j->b->nparts; i++) {
        int n = lam_lua_denied(L, j->b->parts[i].model, 0);
        if (n) return n;
        struct stat st;
        if (stat(j->b->parts[i].model, &st) == 0 && st.st_size > 0) files += (size_t)st.st_size;
    }
    if (!lam_lua_charge(L, &check, files)) lam_lua_memory_raise(L, "lamina.build: model files of %zu bytes", files);
    lam_lua_discharge(L, &check);
    lam_load_opts lo = { .threads = threads };
    if (lam_build_run_new(j->b, &lo, &j->run, &j->err)) return lam_lua_fail(L, &j->err);
    const lam_run_part *rp = lam_build_run_parts(j->run, &np);
    for (size_t i = 0; i < np; i++)
        bytes += sizeof *rp[i].model + lam_model_bytes(rp[i].model, NULL) + lam_slicer_bytes(rp[i].slicer);
    if (!lam_lua_charge(L, &j->charged, bytes))
        lam_lua_memory_raise(L, "lamina.build: the plate's %zu parts (models and slicers) take %zu bytes", np, bytes);
    lam_lua_check_interrupt(L); /* loading may have taken the time that was left */
    return 0;
}

/* What planning's callbacks need. */
typedef struct bctx {
    lua_State *L;
    bjob *j;
    lplan *pl;
    size_t room;             /* the sandbox's memory left when planning began */
    size_t n;                /* layers written */
    int stopped, over;
    lam_scan_time lasers[LAM_LASERS_MAX];
} bctx;

/* Before each layer, as machine:plan: Ctrl-C or the sandbox's time stop
 * the run; so does a plan grown past half the sandbox's room (a plan takes
 * twice its size while it is made). */
static int on_stop(void *user, size_t k)
{
    (void)k;
    bctx *c = user;
    c->stopped = lam_lua_stopping(c->L);
    c->over = c->room != SIZE_MAX && lam_lua_plan_bytes((size_t)lam_writer_bytes(c->j->w), c->n, &c->j->rec) > c->room / 2;
    return c->stopped || c->over ? LAM_EUSAGE : LAM_OK;
}

/* Once layer k is written: the plan's totals, the record's figures. */
static void on_planned(void *user, size_t k, const lam_scan_time *t, const lam_scan_time *lasers, size_t nl)
{
    bctx *c = user;
    lam_scan_time_add(&c->pl->time, t);
    c->pl->layer_time[k] = lam_scan_time_total(t);
    lam_rec_layer *rl = lam_plan_data_current(&c->j->rec);
    if (rl) {
        rl->deposit = t->exposure_length;
        rl->travel = t->jump_length;
        rl->time = c->pl->layer_time[k];
    }
    for (size_t l = 0; l < nl && l < LAM_LASERS_MAX; l++) lam_scan_time_add(&c->lasers[l], &lasers[l]);
    c->n = k + 1;
}

/* The machine's program sink into a memory writer, teed with the plan data. */
static int open_sink(bjob *j, unsigned long long limit)
{
    const lam_profile *p = j->b->profile;
    if (lam_writer_memory(&j->w, &j->err)) return j->err.code;
    lam_writer_set_limit(j->w, limit);
    int rc = lam_program_sink(p->writer, &p->dialect, j->w, &j->sink, &j->err);
    if (rc) return rc;
    j->have_sink = 1;
    lam_views v = { .data = &j->rec };
    lam_sink both[2] = { j->sink }, tee;
    if ((rc = lam_views_sink(&v, &both[1], &j->err))) return rc;
    if ((rc = lam_tee_sink(both, 2, &tee, &j->err))) {
        both[1].destroy(both[1].ctx);
        return rc;
    }
    j->sink = tee; /* it owns both now */
    return LAM_OK;
}

/* Plan the plate into the plan pl; c->lasers gets each laser's time.
 * LAM_OK or a failure in j->err; an interrupt, the time limit and the
 * memory limit raise. */
static int plan_plate(lua_State *L, bjob *j, lplan *pl, const bopts *o, bctx *c)
{
    size_t layers = lam_build_run_layers(j->run), room = lam_lua_mem_room(L);
    unsigned threads = o->threads;
    if (room != SIZE_MAX) { /* as machine:plan: one thread, garbage collected first */
        threads = 1;
        lua_gc(L, LUA_GCCOLLECT);
        room = lam_lua_mem_room(L);
    }
    if (!(pl->layer_time = calloc(layers ? layers : 1, sizeof *pl->layer_time))) return luaL_error(L, "out of memory");
    unsigned long long limit = o->max_output > 0 ? (unsigned long long)o->max_output : LAM_DEFAULT_MAX_OUTPUT;
    int by_room = room != SIZE_MAX && room / 2 < limit;
    if (by_room) limit = room / 2 ? room / 2 : 1;
    *c = (bctx){ .L = L, .j = j, .pl = pl, .room = room };
    lam_run_opts ro = { .threads = threads, .stop = on_stop, .planned = on_planned, .user = c };
    int rc = open_sink(j, limit);
    if (!rc) rc = lam_build_run_plan(j->run, &ro, &j->sink, &j->err);
    if (c->stopped) {
        lam_lua_check_interrupt(L); /* raises: the job's __gc cleans up */
        return luaL_error(L, "interrupted");
    }
    int full = j->w && lam_writer_over_limit(j->w);
    if (c->over || (by_room && full))
        return lam_lua_memory_raise(L, "lamina.build: the plan, which takes twice its size while it is made, "
                                       "passed the %zu bytes left",
                                    room);
    if (j->have_sink && j->sink.destroy) j->sink.destroy(j->sink.ctx);
    j->have_sink = 0;
    if (rc && full) {
        char msg[sizeof j->err.msg];
        snprintf(msg, sizeof msg, "%s", j->err.msg);
        lam_error_set(&j->err, rc, NULL, 0, 0, "%s (raise the limit with the option max_output)", msg);
    }
    return rc;
}

static size_t count_lines(const char *s, size_t len)
{
    size_t n = 0;
    for (const char *p = s; (p = memchr(p, '\n', len - (size_t)(p - s))); p++) n++;
    if (len && s[len - 1] != '\n') n++;
    return n;
}

/* The program and the record into the plan, which owns them from now on. */
static int take_program(bjob *j, lplan *pl)
{
    int rc = lam_writer_take(j->w, &pl->data, &pl->len, &j->err);
    j->w = NULL;
    if (rc) return rc;
    char *fit = realloc(pl->data, pl->len + 1); /* the buffer grew by doubling: give back its slack */
    if (fit) pl->data = fit;
    const lam_profile *p = j->b->profile;
    pl->lines = count_lines(pl->data, pl->len);
    pl->layers = lam_build_run_layers(j->run);
    pl->binary = !lam_program_text(p->writer);
    snprintf(pl->name, sizeof pl->name, "%s", p->name ? p->name : "");
    snprintf(pl->process, sizeof pl->process, "%s", lam_build_run_job(j->run)->process);
    if (!(pl->rec = malloc(sizeof *pl->rec))) return lam_error_nomem(&j->err, "lamina.build");
    *pl->rec = j->rec;
    memset(&j->rec, 0, sizeof j->rec);
    return LAM_OK;
}

/* ---- the build's fields ---------------------------------------------------------------------- */

static void push_numbers(lua_State *L, const double *v, size_t n)
{
    lua_createtable(L, (int)n, 0);
    for (size_t i = 0; i < n; i++) {
        lua_pushnumber(L, v[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
}

static void push_texts(lua_State *L, const char *const *s, size_t n)
{
    lua_createtable(L, (int)n, 0);
    for (size_t i = 0; i < n; i++) {
        lua_pushstring(L, s[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
}

/* {part, entry, name, at, box, layers = {first, last}, time} of each part on
 * the plate (the run is the job's, anchored: no collection frees it). */
static void push_parts(lua_State *L, const lam_build_run *r)
{
    size_t np;
    const lam_run_part *rp = lam_build_run_parts(r, &np);
    lua_createtable(L, (int)np, 0);
    for (size_t i = 0; i < np; i++) {
        lua_createtable(L, 0, 7);
        lua_pushinteger(L, (lua_Integer)i + 1);
        lua_setfield(L, -2, "part");
        lua_pushinteger(L, (lua_Integer)rp[i].spec + 1);
        lua_setfield(L, -2, "entry");
        lua_pushstring(L, rp[i].name);
        lua_setfield(L, -2, "name");
        push_numbers(L, rp[i].at, 2);
        lua_setfield(L, -2, "at");
        push_numbers(L, rp[i].box, 4);
        lua_setfield(L, -2, "box");
        lua_createtable(L, 2, 0);
        lua_pushinteger(L, (lua_Integer)rp[i].first + 1);
        lua_rawseti(L, -2, 1);
        lua_pushinteger(L, (lua_Integer)(rp[i].first + rp[i].count));
        lua_rawseti(L, -2, 2);
        lua_setfield(L, -2, "layers");
        lua_pushnumber(L, rp[i].time.exposure + rp[i].time.jump);
        lua_setfield(L, -2, "time");
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
}

/* The table of the build's fields (the plan's user value). */
static void push_info(lua_State *L, const lam_build_run *r, const lam_scan_time *times)
{
    lua_createtable(L, 0, 4);
    push_parts(L, r);
    lua_setfield(L, -2, "parts");
    const lam_laser_set *ls = lam_build_run_lasers(r);
    lua_createtable(L, (int)ls->n, 0);
    for (size_t k = 0; k < ls->n; k++) {
        lua_createtable(L, 0, 3);
        lua_pushinteger(L, (lua_Integer)k + 1);
        lua_setfield(L, -2, "laser");
        push_numbers(L, ls->field[k], 4);
        lua_setfield(L, -2, "field");
        lua_pushnumber(L, times[k].exposure + times[k].jump);
        lua_setfield(L, -2, "time");
        lua_rawseti(L, -2, (lua_Integer)k + 1);
    }
    lua_setfield(L, -2, "lasers");
    size_t ns;
    const char *const *styles = lam_build_run_styles(r, &ns);
    push_texts(L, styles, ns);
    lua_setfield(L, -2, "styles");
    const lam_job_info *job = lam_build_run_job(r);
    push_texts(L, job->labels, job->labels ? job->nlabels : 0);
    lua_setfield(L, -2, "labels");
}

static lplan *new_plan(lua_State *L)
{
    lplan *pl = lua_newuserdatauv(L, sizeof *pl, 1);
    memset(pl, 0, sizeof *pl);
    pl->tag = LAM_TAG_PLAN;
    luaL_setmetatable(L, LAM_PLAN);
    return pl;
}

/* lamina.build{...} -> plan | nil, message */
int lam_lua_build(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_settop(L, 1);
    check_job_keys(L);
    bopts o;
    read_opts(L, &o);
    bjob *j = new_job(L); /* at 2 */
    int n = open_machine(L, j);
    if (n) return n;
    apply_profile_keys(L, j);
    lam_error e;
    lam_error_clear(&e);
    int rc = lam_build_new(j->p, NULL, &j->b, &e);
    j->p = NULL; /* the build's now, or freed */
    if (rc) lam_lua_opterror(L, 1, "%s", e.msg);
    read_styles(L, j);
    read_parts(L, j);
    if ((n = place(L, j, o.threads))) return n;
    lplan *pl = new_plan(L); /* at 3 */
    bctx c;
    rc = plan_plate(L, j, pl, &o, &c);
    if (!rc) rc = take_program(j, pl);
    if (rc) return lam_lua_fail(L, &j->err);
    push_info(L, j->run, c.lasers);
    lua_setiuservalue(L, 3, 1);
    size_t bytes = lam_lua_plan_bytes(pl->len, pl->layers, pl->rec);
    job_release(L, j); /* the models, the slicers: the plan keeps what it needs */
    lua_settop(L, 3);
    if (!lam_lua_charge(L, &pl->charged, bytes))
        return lam_lua_memory_raise(L, "lamina.build: the plan takes %zu bytes", bytes); /* its __gc frees it */
    return 1;
}

