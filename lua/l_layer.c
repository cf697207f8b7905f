/* lamina.layer and model:slice.
 *
 * model:slice{...} runs the core slicer to the end and returns a sequence of
 * layer userdata. Each layer owns its lam_layer and keeps the slicing run
 * (frame, options, extents: a hidden lamina.run userdata) alive through its
 * first user value; the run keeps the model alive. The second user value is
 * the layer's cache of contour userdata, so layer:contours() and
 * contour.parent give the same userdata every time (usable as table keys). */
#include "l_common.h"

#include <limits.h>
#include <math.h>
#include <string.h>

/* ---- the run -------------------------------------------------------------- */

/* End of slicing (__close of the run, a to-be-closed slot of model:slice,
 * so it also runs when slicing raises an error), and __gc: free the
 * slicer, unpin the model, and free the model if it was finalized while
 * pinned. */
static int run_close(lua_State *L)
{
    lrun *r = LAM_CHECKUD(L, 1, lrun, LAM_RUN, LAM_TAG_RUN);
    lam_slicer_free(r->s);
    r->s = NULL;
    lam_lua_discharge(L, &r->charged);
    if (r->pinned) {
        r->pinned = 0;
        lua_getiuservalue(L, 1, 1);
        lmodel *mu = LAM_TESTUD(L, -1, lmodel, LAM_MODEL, LAM_TAG_MODEL);
        if (mu && mu->busy > 0 && --mu->busy == 0 && mu->doomed) {
            lam_lua_model_free(L, mu);
            mu->doomed = 0;
        }
    }
    return 0;
}

/* ---- slicing -------------------------------------------------------------- */

/* The least a layer takes: its lam_layer, its userdata, its slot in the
 * list and its three numbers in the slicer's schedule. */
#define LAYER_LEAST (sizeof(lam_layer) + sizeof(llayer) + 64 + 3 * sizeof(double))

static size_t layer_bytes(const lam_layer *ly)
{
    return sizeof *ly + 2 * ly->npoints * sizeof *ly->uv + ly->ncontours * sizeof *ly->contours +
           ly->nopen * sizeof *ly->open;
}

/* Bring the run's charge up to what its slicer holds now. */
static void charge_slicer(lua_State *L, lrun *r, const char *path)
{
    size_t now = lam_slicer_bytes(r->s);
    if (now > r->charged && !lam_lua_charge(L, &r->charged, now - r->charged))
        lam_lua_memory_raise(L, "model:slice of %s: the slicer needs %zu bytes", path, now);
}

static const char *const slice_keys[] = { "axis", "width", "widths", "planes", "cut", "gap", "fill",
                                          "allow_open", "machine", "max_layers", NULL };
static const char *const cut_names[] = { "floor", "middle", "ceiling", NULL };
static const char *const fill_names[] = { "evenodd", "nonzero", NULL };

void lam_lua_get_axis(lua_State *L, int t, int arg, lam_frame *f)
{
    lam_error err;
    lam_error_clear(&err);
    int ty = lua_getfield(L, t, "axis");
    if (ty == LUA_TNIL) {
        lam_frame_axis('z', f, &err);
    } else if (ty == LUA_TSTRING) {
        const char *s = lua_tostring(L, -1);
        if (strlen(s) != 1 || !strchr("xyzXYZ", s[0]) || lam_frame_axis((char)(s[0] | 0x20), f, &err))
            lam_lua_opterror(L, arg, "axis must be 'x', 'y', 'z' or a direction {dx, dy, dz}, got '%s'", s);
    } else if (ty == LUA_TTABLE) {
        double d[3];
        int ok = lua_rawlen(L, -1) == 3;
        for (int j = 0; j < 3 && ok; j++) {
            ok = lua_rawgeti(L, -1, j + 1) == LUA_TNUMBER;
            d[j] = ok ? (double)lua_tonumber(L, -1) : 0;
            ok = ok && isfinite(d[j]);
            lua_pop(L, 1);
        }
        if (!ok) lam_lua_opterror(L, arg, "axis as a direction must be {dx, dy, dz}: three finite numbers");
        if (lam_frame_direction(d, f, &err)) lam_lua_opterror(L, arg, "axis: %s", err.msg);
    } else {
        char b[64];
        lam_lua_opterror(L, arg, "axis must be 'x', 'y', 'z' or a direction {dx, dy, dz}, got %s",
                         lam_lua_describe(L, -1, b, sizeof b));
    }
    lua_pop(L, 1);
}

/* A list option (widths, planes) as a C array in a new userdata (pushed, so
 * it is collected on any error). Returns the count, 0 when absent. */
static size_t get_list(lua_State *L, int t, const char *key, const double **out)
{
    *out = NULL;
    int ty = lua_getfield(L, t, key);
    if (ty == LUA_TNIL) {
        lua_pop(L, 1);
        return 0;
    }
    char b[64];
    if (ty != LUA_TTABLE)
        lam_lua_opterror(L, 2, "%s must be a list of numbers, got %s", key, lam_lua_describe(L, -1, b, sizeof b));
    lua_Unsigned n = lua_rawlen(L, -1);
    if (n == 0) lam_lua_opterror(L, 2, "%s must not be empty", key);
    double *v = lua_newuserdatauv(L, (size_t)n * sizeof *v, 0);
    for (lua_Unsigned i = 0; i < n; i++) {
        if (lua_rawgeti(L, -2, (lua_Integer)i + 1) != LUA_TNUMBER)
            lam_lua_opterror(L, 2, "%s[%llu] must be a number, got %s", key, (unsigned long long)i + 1,
                             lam_lua_describe(L, -1, b, sizeof b));
        v[i] = (double)lua_tonumber(L, -1);
        if (!isfinite(v[i]))
            lam_lua_opterror(L, 2, "%s[%llu] must be a finite number, got %s", key, (unsigned long long)i + 1,
                             lam_lua_describe(L, -1, b, sizeof b));
        lua_pop(L, 1);
    }
    lua_remove(L, -2); /* the table; the array userdata stays */
    *out = v;
    return (size_t)n;
}

/* model:slice's options (table 2) into *o and *allow_open; the arrays of
 * widths and planes stay on the stack (o points into them). */
static void slice_opts(lua_State *L, lam_slice_opts *o, int *allow_open)
{
    lam_lua_checkkeys(L, 2, 2, slice_keys);
    lam_slice_opts_init(o);
    lam_lua_get_axis(L, 2, 2, &o->frame);
    if (lua_getfield(L, 2, "machine") != LUA_TNIL) {
        lmachine *mc = LAM_TESTUD(L, -1, lmachine, LAM_MACHINE, LAM_TAG_MACHINE);
        char b[64];
        if (!mc) lam_lua_opterror(L, 2, "machine must be a lamina.machine, got %s", lam_lua_describe(L, -1, b, sizeof b));
        mc = lam_lua_checkmachine(L, -1);
        if (mc->p.layer_width > 0) o->width = mc->p.layer_width;
        o->cut = (lam_cut)mc->p.cut;
        o->gap = mc->p.gap;
        o->gap_limit = lam_profile_gap_limit(&mc->p);
    }
    lua_pop(L, 1);
    int i, given = 0;
    double x;
    if (lam_lua_numfield(L, 2, 2, "width", &x)) {
        if (!(x > 0)) lam_lua_opterror(L, 2, "width must be greater than 0, got %.14g", x);
        o->width = x;
        given++;
    }
    const double *list;
    size_t n = get_list(L, 2, "widths", &list); /* pushes an array when present */
    if (n) {
        o->widths = list;
        o->nwidths = n;
        given++;
    }
    n = get_list(L, 2, "planes", &list);
    if (n) {
        o->planes = list;
        o->nplanes = n;
        given++;
    }
    if (given > 1) lam_lua_opterror(L, 2, "give one of width, widths and planes");
    if (lam_lua_choicefield(L, 2, 2, "cut", cut_names, &i)) o->cut = (lam_cut)i;
    if (lam_lua_numfield(L, 2, 2, "gap", &x)) {
        if (x < 0) lam_lua_opterror(L, 2, "gap must be 0 or more, got %.14g", x);
        o->gap = x;
    }
    if (lam_lua_choicefield(L, 2, 2, "fill", fill_names, &i)) o->fill_nonzero = i;
    *allow_open = 0;
    lam_lua_boolfield(L, 2, 2, "allow_open", allow_open);
    if (lam_lua_numfield(L, 2, 2, "max_layers", &x)) {
        if (!(x >= 1) || x != floor(x) || x > 1e15)
            lam_lua_opterror(L, 2, "max_layers must be a whole number >= 1, got %.14g", x);
        o->max_layers = (size_t)x;
    }
}

/* The layers of run r (at index run) of model m into the table at result:
 * 0, or the number of results to return (nil and a message for an open
 * outline without allow_open; lam_lua_fail's). Raises for the memory
 * limit and an interrupt. */
static int slice_layers(lua_State *L, lrun *r, const lam_model *m, int allow_open, int run, int result)
{
    lam_error err;
    lam_error_clear(&err);
    for (lua_Integer k = 1;; k++) {
        lam_lua_check_interrupt(L);
        llayer *lu = lua_newuserdatauv(L, sizeof *lu, 2);
        lu->tag = LAM_TAG_LAYER;
        lu->L = NULL;
        lu->charged = 0;
        luaL_setmetatable(L, LAM_LAYER);
        lua_pushvalue(L, run);
        lua_setiuservalue(L, -2, 1);
        if (lam_slicer_next(r->s, &lu->L, &err)) return lam_lua_fail(L, &err);
        if (!lu->L) break;
        /* made already (its size is known only now): at most one layer
         * past the limit, freed by its finalizer when this raises */
        if (!lam_lua_charge(L, &lu->charged, layer_bytes(lu->L)))
            lam_lua_memory_raise(L, "model:slice of %s: layer %lld of %zu does not fit", m->path,
                                 (long long)k, r->nlayers);
        charge_slicer(L, r, m->path); /* its scratch grows with the busiest layer */
        if (lu->L->nopen && !allow_open) {
            const lam_open_end *e = &lu->L->open[0];
            lua_pushnil(L);
            lua_pushfstring(L,
                            "%s: layer %I (z=%f): open outline from (%f, %f) to (%f, %f) could not be closed "
                            "(gap tolerance %f); raise gap or pass allow_open=true to drop open outlines",
                            m->path, k, lu->L->cut, e->start[0], e->start[1], e->end[0], e->end[1], lu->L->gap);
            return 2;
        }
        lua_rawseti(L, result, k);
    }
    return 0;
}

/* model:slice{axis=, width= | widths= | planes=, cut=, gap=, fill=,
 *             allow_open=, machine=} -> { layer, ... } | nil, message */
int lam_lua_slice(lua_State *L)
{
    lmodel *mu = lam_lua_checkmodel(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    /* the run first: it pins the model until slicing ends, however it ends */
    lrun *r = lua_newuserdatauv(L, sizeof *r, 1);
    memset(r, 0, sizeof *r);
    r->tag = LAM_TAG_RUN;
    luaL_setmetatable(L, LAM_RUN);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, 3, 1);
    lam_lua_checkmodel(L, 1); /* still alive after that allocation? */
    mu->busy++;
    r->pinned = 1;
    lua_toclose(L, 3);
    lam_slice_opts o;
    int allow_open;
    slice_opts(L, &o, &allow_open);

    const int run = 3;
    lam_error err;
    lam_error_clear(&err);
    /* in a sandbox, no more layers than the room left holds at their least
     * (the slicer's schedule, the layer and its userdata): refused before
     * the schedule is allocated */
    size_t asked = o.max_layers ? o.max_layers : LAM_DEFAULT_MAX_LAYERS;
    size_t room = lam_lua_mem_reclaim(L, asked < SIZE_MAX / LAYER_LEAST ? asked * LAYER_LEAST : SIZE_MAX);
    int clamped = room / LAYER_LEAST < asked;
    if (clamped) o.max_layers = room / LAYER_LEAST ? room / LAYER_LEAST : 1;
    const lam_model *m = mu->m; /* pinned: no finalizer frees it */
    if (lam_slicer_new(m, &o, &r->s, &err)) {
        if (err.code == LAM_EUSAGE) lam_lua_opterror(L, 2, "%s", err.msg);
        if (err.code == LAM_ELIMIT && clamped)
            lam_lua_memory_raise(L, "model:slice of %s would make more than the %zu layers that fit", m->path,
                                 o.max_layers);
        if (err.code == LAM_ELIMIT) lam_lua_opterror(L, 2, "%s (raise the limit with max_layers)", err.msg);
        return lam_lua_fail(L, &err);
    }
    charge_slicer(L, r, m->path);
    r->frame = *lam_slicer_frame(r->s);
    r->cut = o.cut;
    r->nlayers = lam_slicer_count(r->s);
    lam_slicer_uv_bounds(r->s, r->uvbox);
    r->wmin = lam_slicer_planes(r->s)[0];
    r->wmax = lam_slicer_planes(r->s)[r->nlayers];
    memcpy(r->bbox, m->stats.bbox, sizeof r->bbox);
    lam_job_label(m->path, r->label, sizeof r->label);

    lua_createtable(L, r->nlayers < INT_MAX ? (int)r->nlayers : 0, 0);
    int result = lua_gettop(L);
    int nres = slice_layers(L, r, m, allow_open, run, result);
    if (nres) return nres;
    lua_settop(L, result);   /* drop the last, empty layer userdata */
    luaL_setmetatable(L, LAM_LAYERS);
    lua_replace(L, run - 1); /* the result over the options table */
    lua_closeslot(L, run);   /* unpins the model (freeing it if it was finalized meanwhile) */
    lua_settop(L, run - 1);
    return 1;
}

/* ---- layers --------------------------------------------------------------- */

lam_layer *lam_lua_checklayer(lua_State *L, int idx)
{
    llayer *u = LAM_CHECKUD(L, idx, llayer, LAM_LAYER, LAM_TAG_LAYER);
    if (!u->L) luaL_error(L, "attempt to use a collected " LAM_LAYER);
    return u->L;
}

lam_layer *lam_lua_layeritem(lua_State *L, int list, int arg, size_t i)
{
    lua_rawgeti(L, list, (lua_Integer)i + 1);
    if (!LAM_TESTUD(L, -1, llayer, LAM_LAYER, LAM_TAG_LAYER)) {
        char b[64];
        lam_lua_opterror(L, arg, "layers[%zu] must be a lamina.layer, got %s", i + 1, lam_lua_describe(L, -1, b, sizeof b));
    }
    return lam_lua_checklayer(L, -1);
}

void lam_lua_pushlayer(lua_State *L, int like, lam_layer *taken)
{
    like = lua_absindex(L, like);
    llayer *lu = lua_newuserdatauv(L, sizeof *lu, 2);
    lu->tag = LAM_TAG_LAYER;
    lu->L = taken;
    lu->charged = 0;
    luaL_setmetatable(L, LAM_LAYER);
    lua_getiuservalue(L, like, 1);
    lua_setiuservalue(L, -2, 1);
    if (!lam_lua_charge(L, &lu->charged, layer_bytes(taken)))
        lam_lua_memory_raise(L, "a layer of %zu contours does not fit", taken->ncontours);
}

lrun *lam_lua_layerrun(lua_State *L, int idx)
{
    lua_getiuservalue(L, idx, 1);
    lrun *r = LAM_TESTUD(L, -1, lrun, LAM_RUN, LAM_TAG_RUN);
    lua_pop(L, 1); /* the layer keeps it alive */
    if (!r) luaL_error(L, "attempt to use a collected " LAM_LAYER);
    return r;
}

void lam_lua_pushcontour(lua_State *L, int idx, size_t k)
{
    idx = lua_absindex(L, idx);
    const lam_layer *ly = lam_lua_checklayer(L, idx);
    if (k >= ly->ncontours) {
        lua_pushnil(L);
        return;
    }
    if (lua_getiuservalue(L, idx, 2) != LUA_TTABLE) {
        lua_pop(L, 1);
        lua_createtable(L, ly->ncontours < 1000000 ? (int)ly->ncontours : 0, 0);
        lua_pushvalue(L, -1);
        lua_setiuservalue(L, idx, 2);
    }
    if (lua_rawgeti(L, -1, (lua_Integer)k + 1) == LUA_TNIL) {
        lua_pop(L, 1);
        lcontour *c = lua_newuserdatauv(L, sizeof *c, 1);
        c->tag = LAM_TAG_CONTOUR;
        c->i = k;
        luaL_setmetatable(L, LAM_CONTOUR);
        lua_pushvalue(L, idx);
        lua_setiuservalue(L, -2, 1);
        lua_pushvalue(L, -1);
        lua_rawseti(L, -3, (lua_Integer)k + 1);
    }
    lua_remove(L, -2); /* the cache */
}

static int l_gc(lua_State *L)
{
    llayer *u = LAM_CHECKUD(L, 1, llayer, LAM_LAYER, LAM_TAG_LAYER);
    lam_layer_free(u->L);
    u->L = NULL;
    lam_lua_discharge(L, &u->charged);
    return 0;
}

static int l_tostring(lua_State *L)
{
    llayer *u = LAM_CHECKUD(L, 1, llayer, LAM_LAYER, LAM_TAG_LAYER);
    if (!u->L) lua_pushliteral(L, LAM_LAYER " (collected)");
    else
        lua_pushfstring(L, LAM_LAYER " %I (z=%f, width %f, %I contour%s)", (lua_Integer)u->L->index + 1, u->L->cut,
                        u->L->width, (lua_Integer)u->L->ncontours, u->L->ncontours == 1 ? "" : "s");
    return 1;
}

static int l_len(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)lam_lua_checklayer(L, 1)->ncontours);
    return 1;
}

static int l_fields(lua_State *L)
{
    const lam_layer *ly = lam_lua_checklayer(L, 1);
    const char *k = lua_tostring(L, 2);
    if (strcmp(k, "index") == 0) lua_pushinteger(L, (lua_Integer)ly->index + 1);
    else if (strcmp(k, "z") == 0) lua_pushnumber(L, ly->cut);
    else if (strcmp(k, "floor") == 0) lua_pushnumber(L, ly->floor);
    else if (strcmp(k, "ceiling") == 0) lua_pushnumber(L, ly->ceiling);
    else if (strcmp(k, "width") == 0) lua_pushnumber(L, ly->width);
    else if (strcmp(k, "points") == 0) lua_pushinteger(L, (lua_Integer)ly->npoints);
    else if (strcmp(k, "gaps_closed") == 0) lua_pushinteger(L, (lua_Integer)ly->gaps_closed);
    else if (strcmp(k, "max_gap") == 0) lua_pushnumber(L, ly->max_gap);
    else if (strcmp(k, "gap") == 0) lua_pushnumber(L, ly->gap);
    else if (strcmp(k, "slivers") == 0) lua_pushinteger(L, (lua_Integer)ly->slivers);
    else if (strcmp(k, "twins") == 0) lua_pushinteger(L, (lua_Integer)ly->twins);
    else if (strcmp(k, "open") == 0) lua_pushinteger(L, (lua_Integer)ly->nopen);
    else if (strcmp(k, "area") == 0) {
        double a = 0;
        for (size_t i = 0; i < ly->ncontours; i++) a += ly->contours[i].area;
        lua_pushnumber(L, a);
    } else if (strcmp(k, "cut") == 0) {
        lua_pushstring(L, cut_names[lam_lua_layerrun(L, 1)->cut]);
    } else if (strcmp(k, "layers") == 0) {
        lua_pushinteger(L, (lua_Integer)lam_lua_layerrun(L, 1)->nlayers);
    } else if (strcmp(k, "model") == 0) {
        lua_getiuservalue(L, 1, 1);
        if (LAM_TESTUD(L, -1, lrun, LAM_RUN, LAM_TAG_RUN)) lua_getiuservalue(L, -1, 1);
        else lua_pushnil(L);
    } else {
        lua_pushnil(L);
    }
    return 1;
}

/* layer:contours() -> { contour, ... } (parents before children) */
static int l_contours(lua_State *L)
{
    const lam_layer *ly = lam_lua_checklayer(L, 1);
    size_t n = ly->ncontours;
    lua_createtable(L, n < 1000000 ? (int)n : 0, 0);
    for (size_t k = 0; k < n; k++) {
        lam_lua_pushcontour(L, 1, k);
        lua_rawseti(L, -2, (lua_Integer)k + 1);
    }
    return 1;
}

/* layer:contour(i) -> contour | nil */
static int l_contour(lua_State *L)
{
    lam_lua_checklayer(L, 1);
    lua_Integer i = luaL_checkinteger(L, 2);
    if (i < 1) lua_pushnil(L);
    else lam_lua_pushcontour(L, 1, (size_t)((lua_Unsigned)i - 1));
    return 1;
}

/* layer:bbox() -> umin, vmin, umax, vmax of its contours (nil when empty) */
static int l_bbox(lua_State *L)
{
    const lam_layer *ly = lam_lua_checklayer(L, 1);
    if (!ly->ncontours) {
        lua_pushnil(L);
        return 1;
    }
    double b[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < ly->ncontours; i++) {
        const double *c = ly->contours[i].bbox;
        if (c[0] < b[0]) b[0] = c[0];
        if (c[1] < b[1]) b[1] = c[1];
        if (c[2] > b[2]) b[2] = c[2];
        if (c[3] > b[3]) b[3] = c[3];
    }
    for (int j = 0; j < 4; j++) lua_pushnumber(L, b[j]);
    return 4;
}

/* layer:open_ends() -> { {u1, v1, u2, v2}, ... } of outlines left open */
static int l_open_ends(lua_State *L)
{
    size_t n = lam_lua_checklayer(L, 1)->nopen;
    lua_createtable(L, n < 1000000 ? (int)n : 0, 0);
    for (size_t i = 0; i < n; i++) {
        /* a copy, re-checked every time: creating a table may run the collector */
        const lam_layer *ly = lam_lua_checklayer(L, 1);
        if (i >= ly->nopen) break;
        const lam_open_end e = ly->open[i];
        const double v[4] = { e.start[0], e.start[1], e.end[0], e.end[1] };
        lua_createtable(L, 4, 0);
        for (int j = 0; j < 4; j++) {
            lua_pushnumber(L, v[j]);
            lua_rawseti(L, -2, j + 1);
        }
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

static void push_vec(lua_State *L, const double v[3])
{
    lua_createtable(L, 3, 0);
    for (int j = 0; j < 3; j++) {
        lua_pushnumber(L, v[j]);
        lua_rawseti(L, -2, j + 1);
    }
}

/* layer:frame() -> u, v, w (unit vectors as {x, y, z}) */
static int l_frame(lua_State *L)
{
    lam_lua_checklayer(L, 1);
    const lrun *r = lam_lua_layerrun(L, 1);
    push_vec(L, r->frame.u);
    push_vec(L, r->frame.v);
    push_vec(L, r->frame.w);
    return 3;
}

/* layer:to_model(u, v [, w]) -> x, y, z (w defaults to the layer's z) */
static int l_to_model(lua_State *L)
{
    const lam_layer *ly = lam_lua_checklayer(L, 1);
    double u = (double)luaL_checknumber(L, 2), v = (double)luaL_checknumber(L, 3);
    double w = (double)luaL_optnumber(L, 4, ly->cut);
    const lrun *r = lam_lua_layerrun(L, 1);
    double xyz[3];
    lam_frame_to_model(&r->frame, u, v, w, xyz);
    for (int j = 0; j < 3; j++) lua_pushnumber(L, xyz[j]);
    return 3;
}

static const luaL_Reg layer_meta[] = {
    { "__gc", l_gc },
    { "__tostring", l_tostring },
    { "__len", l_len },
    { NULL, NULL },
};

static const luaL_Reg layer_methods[] = {
    { "contours", l_contours },
    { "contour", l_contour },
    { "bbox", l_bbox },
    { "open_ends", l_open_ends },
    { "frame", l_frame },
    { "to_model", l_to_model },
    { NULL, NULL },
};

static const luaL_Reg run_meta[] = {
    { "__gc", run_close },
    { "__close", run_close },
    { NULL, NULL },
};

/* A list of layers (what model:slice returns) prints as a summary: "12
 * layers of thesis_cube_hole.ug, z 0 .. 2" (the first layer's floor to the
 * last one's ceiling, from what the table holds now; the file's name
 * without its directory). It stays a plain table otherwise. */
static int layers_tostring(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_Integer n = (lua_Integer)lua_rawlen(L, 1);
    lua_rawgeti(L, 1, 1);
    lua_rawgeti(L, 1, n);
    /* printing never raises: a finalized layer or model just says less */
    llayer *first = LAM_TESTUD(L, -2, llayer, LAM_LAYER, LAM_TAG_LAYER);
    llayer *last = LAM_TESTUD(L, -1, llayer, LAM_LAYER, LAM_TAG_LAYER);
    if (n == 0 || !first || !first->L || !last || !last->L) {
        lua_pushfstring(L, "%I layer%s", n, n == 1 ? "" : "s");
        return 1;
    }
    char lo[32], hi[32], name[256] = "";
    snprintf(lo, sizeof lo, LUA_NUMBER_FMT, (LUAI_UACNUMBER)first->L->floor);
    snprintf(hi, sizeof hi, LUA_NUMBER_FMT, (LUAI_UACNUMBER)last->L->ceiling);
    lua_getiuservalue(L, -2, 1); /* the run */
    if (LAM_TESTUD(L, -1, lrun, LAM_RUN, LAM_TAG_RUN)) {
        lua_getiuservalue(L, -1, 1); /* its model */
        lmodel *mu = LAM_TESTUD(L, -1, lmodel, LAM_MODEL, LAM_TAG_MODEL);
        if (mu && mu->m && mu->m->path) {
            const char *base = strrchr(mu->m->path, '/');
            snprintf(name, sizeof name, " of %s", base ? base + 1 : mu->m->path);
        }
    }
    lua_pushfstring(L, "%I layer%s%s, z %s .. %s", n, n == 1 ? "" : "s", name, lo, hi);
    return 1;
}

static const luaL_Reg layers_meta[] = {
    { "__tostring", layers_tostring },
    { NULL, NULL },
};

void lam_lua_open_layer(lua_State *L)
{
    luaL_newmetatable(L, LAM_LAYERS);
    luaL_setfuncs(L, layers_meta, 0);
    lua_pop(L, 1);
    luaL_newmetatable(L, LAM_RUN);
    luaL_setfuncs(L, run_meta, 0);
    lua_pop(L, 1);
    lam_lua_newclass(L, LAM_LAYER, layer_meta, layer_methods, l_fields);
}
