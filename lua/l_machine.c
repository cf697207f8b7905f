/* lamina.machine: a machine profile (YAML, core/profile.h).
 *
 * lamina.machine(name or path) loads a profile; the userdata owns it.
 * machine:override{...} makes a new machine whose values differ: it holds a
 * shallow copy of the profile (numbers its own, strings and dialect
 * templates borrowed) and keeps the owning machine alive as its user value.
 * Values are validated with the YAML loader's rules and messages. */
#include "l_common.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "writer.h"

static const char *const process_names[] = { "ladrp", "sls", NULL };
static const char *const cut_names[] = { "floor", "middle", "ceiling", NULL };
static const char *const frame_names[] = { "model", "machine", NULL };
static const char *const first_line_names[] = { "edge", "center", NULL };

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
    lua_pushfstring(L, LAM_MACHINE " %s (%s, %s %f%s)", u->p.name, process_names[sls], sls ? "spot" : "bead",
                    sls ? u->p.spot_width : u->p.bead_width, u->owner ? "" : ", overridden");
    return 1;
}

static void push_opt_number(lua_State *L, double x)
{
    if (x > 0) lua_pushnumber(L, x);
    else lua_pushnil(L);
}

static int mc_fields(lua_State *L)
{
    const lam_profile *p = &lam_lua_checkmachine(L, 1)->p;
    const char *k = lua_tostring(L, 2);
    if (strcmp(k, "name") == 0) lua_pushstring(L, p->name);
    else if (strcmp(k, "path") == 0) lua_pushstring(L, p->path);
    else if (strcmp(k, "description") == 0) lua_pushstring(L, p->description); /* nil when absent */
    else if (strcmp(k, "process") == 0) lua_pushstring(L, process_names[p->process == LAM_PROCESS_SLS]);
    else if (strcmp(k, "units") == 0) lua_pushstring(L, p->units);
    else if (strcmp(k, "writer") == 0) lua_pushstring(L, p->writer);
    else if (strcmp(k, "bead_width") == 0) push_opt_number(L, p->bead_width);
    else if (strcmp(k, "spot_width") == 0) push_opt_number(L, p->spot_width);
    else if (strcmp(k, "layer_width") == 0) push_opt_number(L, p->layer_width);
    else if (strcmp(k, "cut") == 0) lua_pushstring(L, cut_names[p->cut >= 0 && p->cut <= 2 ? p->cut : 1]);
    else if (strcmp(k, "feed_rate") == 0) lua_pushnumber(L, p->feed_rate);
    else if (strcmp(k, "travel_rate") == 0) lua_pushnumber(L, p->travel_rate);
    else if (strcmp(k, "gap") == 0) lua_pushnumber(L, p->gap);
    else if (strcmp(k, "frame") == 0) lua_pushstring(L, frame_names[p->frame_machine ? 1 : 0]);
    else if (strcmp(k, "first_line") == 0) lua_pushstring(L, first_line_names[p->first_line == LAM_FIRST_CENTER]);
    else if (strcmp(k, "angle") == 0) lua_pushnumber(L, p->angle);
    else if (strcmp(k, "angle_step") == 0) lua_pushnumber(L, p->angle_step);
    else if (strcmp(k, "alternate") == 0) lua_pushboolean(L, p->alternate);
    else if (strcmp(k, "min_deposit") == 0) lua_pushnumber(L, p->min_deposit);
    else if (strcmp(k, "perimeters") == 0) lua_pushinteger(L, p->perimeters);
    else if (strcmp(k, "beam_offset") == 0) lua_pushboolean(L, p->beam_offset);
    else if (strcmp(k, "islands") == 0) lua_pushboolean(L, p->islands);
    else if (strcmp(k, "max_overhang_deg") == 0) push_opt_number(L, p->max_overhang_deg);
    else lua_pushnil(L);
    return 1;
}

/* ---- overrides -------------------------------------------------------------- */

/* The values a script may change, with the YAML loader's rules. */
enum okind { NUM, CHOICE, BOOL, WHOLE };
typedef struct okey {
    const char *name;
    enum okind kind;
    double lo, hi;             /* NUM: the range */
    int lo_open;               /* NUM: lo itself is excluded */
    const char *const *names;  /* CHOICE */
} okey;

enum { O_BEAD, O_SPOT, O_LAYER, O_CUT, O_FEED, O_TRAVEL, O_GAP, O_FRAME, O_FIRST, O_ANGLE, O_STEP,
       O_ALTERNATE, O_MIN_DEPOSIT, O_PERIMETERS, O_BEAM, O_OVERHANG, O_ISLANDS, O_COUNT };

static const okey okeys[O_COUNT] = {
    { "bead_width", NUM, 0, HUGE_VAL, 1, NULL },
    { "spot_width", NUM, 0, HUGE_VAL, 1, NULL },
    { "layer_width", NUM, 0, HUGE_VAL, 1, NULL },
    { "cut", CHOICE, 0, 0, 0, cut_names },
    { "feed_rate", NUM, 0, HUGE_VAL, 0, NULL },
    { "travel_rate", NUM, 0, HUGE_VAL, 0, NULL },
    { "gap", NUM, 0, HUGE_VAL, 0, NULL },
    { "frame", CHOICE, 0, 0, 0, frame_names },
    { "first_line", CHOICE, 0, 0, 0, first_line_names },
    { "angle", NUM, -HUGE_VAL, HUGE_VAL, 0, NULL },
    { "angle_step", NUM, -HUGE_VAL, HUGE_VAL, 0, NULL },
    { "alternate", BOOL, 0, 0, 0, NULL },
    { "min_deposit", NUM, 0, HUGE_VAL, 0, NULL },
    { "perimeters", WHOLE, 0, 1000, 0, NULL },
    { "beam_offset", BOOL, 0, 0, 0, NULL },
    { "max_overhang_deg", NUM, 0, 90, 0, NULL },
    { "islands", BOOL, 0, 0, 0, NULL },
};

static const char *const override_keys[O_COUNT + 1] = {
    "bead_width", "spot_width", "layer_width", "cut", "feed_rate", "travel_rate", "gap", "frame",
    "first_line", "angle", "angle_step", "alternate", "min_deposit", "perimeters", "beam_offset",
    "max_overhang_deg", "islands", NULL,
};

static const char *const fixed_keys[] = { "name", "description", "process", "units", "writer", "dialect",
                                          "inherits", "raster", NULL };

static int listed(const char *const *keys, const char *k)
{
    for (size_t i = 0; keys[i]; i++)
        if (strcmp(keys[i], k) == 0) return 1;
    return 0;
}

_Static_assert(O_COUNT <= sizeof ((lam_lua_overrides *)0)->v / sizeof(double), "lam_lua_overrides.v is too small");

static void read_one(lua_State *L, int t, int arg, const okey *k, double *v)
{
    double x = 0;
    int i = 0;
    switch (k->kind) {
    case NUM:
        lam_lua_numfield(L, t, arg, k->name, &x);
        if (k->lo_open && !(x > k->lo)) lam_lua_opterror(L, arg, "%s must be greater than %.14g, got %.14g", k->name, k->lo, x);
        if (!k->lo_open && x < k->lo && k->hi == HUGE_VAL)
            lam_lua_opterror(L, arg, "%s must be 0 or more, got %.14g", k->name, x);
        if (x < k->lo || x > k->hi)
            lam_lua_opterror(L, arg, "%s must be from %.14g to %.14g, got %.14g", k->name, k->lo, k->hi, x);
        *v = x;
        break;
    case WHOLE:
        lam_lua_numfield(L, t, arg, k->name, &x);
        if (x != floor(x) || x < k->lo || x > k->hi)
            lam_lua_opterror(L, arg, "%s must be a whole number from %.14g to %.14g, got %.14g", k->name, k->lo, k->hi, x);
        *v = x;
        break;
    case CHOICE:
        lam_lua_choicefield(L, t, arg, k->name, k->names, &i);
        *v = i;
        break;
    case BOOL:
        lam_lua_boolfield(L, t, arg, k->name, &i);
        *v = i;
        break;
    }
}

void lam_lua_read_overrides(lua_State *L, int t, int arg, const char *const *keys, lam_lua_overrides *o)
{
    if (!keys) keys = override_keys;
    t = lua_absindex(L, t);
    memset(o, 0, sizeof *o);
    /* keys of the profile that cannot be given here get their own message */
    lua_pushnil(L);
    while (lua_next(L, t)) {
        lua_pop(L, 1);
        const char *k = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
        if (!k || listed(keys, k)) continue;
        if (strcmp(k, "raster") == 0)
            lam_lua_opterror(L, arg, "give the raster keys directly (angle = 90, not raster = {angle = 90})");
        if (listed(fixed_keys, k))
            lam_lua_opterror(L, arg, "%s cannot be changed here (load another machine profile)", k);
        if (listed(override_keys, k))
            lam_lua_opterror(L, arg, "%s cannot be changed here (it is not a planning option)", k);
    }
    lam_lua_checkkeys(L, t, arg, keys);
    for (int k = 0; k < O_COUNT; k++) {
        if (!listed(keys, okeys[k].name)) continue;
        int present = lua_getfield(L, t, okeys[k].name) != LUA_TNIL;
        lua_pop(L, 1);
        if (!present) continue;
        read_one(L, t, arg, &okeys[k], &o->v[k]);
        o->set |= 1u << k;
    }
}

void lam_lua_apply_overrides(const lam_lua_overrides *o, lam_profile *p)
{
#define SET(k) (o->set & (1u << (k)))
    int sls = p->process == LAM_PROCESS_SLS;
    int travel_follows = p->travel_rate == p->feed_rate;
    if (SET(O_BEAD)) p->bead_width = o->v[O_BEAD];
    if (SET(O_SPOT)) p->spot_width = o->v[O_SPOT];
    if (sls && SET(O_BEAD)) p->spot_width = p->bead_width; /* one width for SLS */
    if (sls && SET(O_SPOT)) p->bead_width = p->spot_width;
    if (SET(O_LAYER)) p->layer_width = o->v[O_LAYER];
    if (SET(O_CUT)) p->cut = (int)o->v[O_CUT];
    if (SET(O_FEED)) {
        p->feed_rate = o->v[O_FEED];
        if (travel_follows) p->travel_rate = p->feed_rate;
    }
    if (SET(O_TRAVEL)) p->travel_rate = o->v[O_TRAVEL];
    if (SET(O_GAP)) p->gap = o->v[O_GAP];
    if (SET(O_FRAME)) p->frame_machine = (int)o->v[O_FRAME];
    if (SET(O_FIRST)) p->first_line = (lam_first_line)(int)o->v[O_FIRST];
    if (SET(O_ANGLE)) p->angle = o->v[O_ANGLE];
    if (SET(O_STEP)) p->angle_step = o->v[O_STEP];
    if (SET(O_ALTERNATE)) p->alternate = (int)o->v[O_ALTERNATE];
    if (SET(O_MIN_DEPOSIT)) p->min_deposit = o->v[O_MIN_DEPOSIT];
    if (SET(O_PERIMETERS)) p->perimeters = (int)o->v[O_PERIMETERS];
    if (SET(O_BEAM)) p->beam_offset = (int)o->v[O_BEAM];
    if (SET(O_OVERHANG)) p->max_overhang_deg = o->v[O_OVERHANG];
    if (SET(O_ISLANDS)) p->islands = (int)o->v[O_ISLANDS];
#undef SET
}

/* machine:override{key = value, ...} -> a new machine */
static int mc_override(lua_State *L)
{
    lam_lua_checkmachine(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    lam_lua_overrides ovr;
    lam_lua_read_overrides(L, 2, 2, NULL, &ovr); /* may run metamethods: no pointers held yet */
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
    { "plan", lam_lua_plan },
    { "yaml", mc_yaml },
    { NULL, NULL },
};

void lam_lua_open_machine(lua_State *L)
{
    lam_lua_newclass(L, LAM_MACHINE, machine_meta, machine_methods, mc_fields);
}
