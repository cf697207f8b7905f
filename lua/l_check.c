/* model:validate{...} and model:check(machine [, opts]): what `lamina
 * validate` and `lamina check` test (core/check/validate.h, core/check/drc.h), with the
 * results as tables instead of a report.
 *
 * Both do every C step first (slicing aside): the layers' checks or the
 * rule check run on pointers taken once, into C memory held by a job
 * userdata (freed by its finalizer if Lua raises half-way), and only then
 * are the result tables built, from those copies: building allocates, and
 * a pending finalizer may run there (l_common.h). */
#include "l_common.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drc.h"
#include "mesh.h"
#include "pool.h"
#include "rays.h"
#include "validate.h"
#include "validate_run.h"

#define LAM_CHECKJOB "lamina.checkjob"
#define WHERE 512

typedef struct checkjob {
    lam_rays *v;
    size_t n;                /* layers */
    const lam_layer **ls;
    lam_frame *frames;
    lam_layer_check *checks;
    size_t *index;           /* each layer's 0-based index in its run */
    double *z;               /* and cut height */
    unsigned char *kinds;    /* every contour's kind, layer after layer */
    lam_drc_result drc;
    char *where;             /* WHERE bytes per violation: its source */
} checkjob;

static void job_free(checkjob *j)
{
    lam_rays_free(j->v);
    j->v = NULL;
    for (size_t i = 0; j->checks && i < j->n; i++) lam_layer_check_free(&j->checks[i]);
    free(j->checks);
    free(j->ls);
    free(j->frames);
    free(j->index);
    free(j->z);
    free(j->kinds);
    lam_drc_result_free(&j->drc);
    free(j->where);
    memset(j, 0, sizeof *j);
}

static int job_gc(lua_State *L)
{
    job_free(luaL_checkudata(L, 1, LAM_CHECKJOB));
    return 0;
}

static checkjob *newjob(lua_State *L)
{
    checkjob *j = lua_newuserdatauv(L, sizeof *j, 0);
    memset(j, 0, sizeof *j);
    if (luaL_newmetatable(L, LAM_CHECKJOB)) {
        lua_pushcfunction(L, job_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    return j;
}

static void setnum(lua_State *L, const char *k, double x)
{
    lua_pushnumber(L, x);
    lua_setfield(L, -2, k);
}

static void setint(lua_State *L, const char *k, size_t x)
{
    lua_pushinteger(L, (lua_Integer)x);
    lua_setfield(L, -2, k);
}

static void setbool(lua_State *L, const char *k, int b)
{
    lua_pushboolean(L, b);
    lua_setfield(L, -2, k);
}

static void setstr(lua_State *L, const char *k, const char *s)
{
    lua_pushstring(L, s);
    lua_setfield(L, -2, k);
}

static void setvec(lua_State *L, const char *k, const double *x, int n)
{
    lua_createtable(L, n, 0);
    for (int i = 0; i < n; i++) {
        lua_pushnumber(L, x[i]);
        lua_rawseti(L, -2, i + 1);
    }
    lua_setfield(L, -2, k);
}

/* One contour's result. */
static void push_contour(lua_State *L, const lam_contour_check *c, int kind)
{
    lua_createtable(L, 0, 12);
    setint(L, "index", c->contour + 1);
    setstr(L, "kind", kind == LAM_SOLID ? "solid" : "hole");
    setstr(L, "status", c->ok > 0 ? "confirmed" : c->ok == 0 ? "disagrees" : "unchecked");
    setbool(L, "ok", c->ok > 0);
    setstr(L, "why", c->why ? c->why : "");
    lua_createtable(L, 0, 4);
    for (unsigned k = 0; k < 4; k++)
        if (c->problems & (1u << k)) setstr(L, lam_validate_problem_name(1u << k), c->whys[k] ? c->whys[k] : "");
    lua_setfield(L, -2, "problems");
    setint(L, "edges", c->edges);
    setnum(L, "area", c->area);
    if (c->edges || c->ok == 0) {
        setvec(L, "point", c->uv, 2);
        setvec(L, "position", c->xyz, 3);
        lua_pushinteger(L, c->winding_found);
        lua_setfield(L, -2, "winding");
    }
    if (c->depth_found >= 0) {
        lua_pushinteger(L, c->depth_found);
        lua_setfield(L, -2, "depth_found");
    }
    if (c->parent_found >= 0) setint(L, "parent_found", (size_t)c->parent_found + 1);
}

static const char *const fill_names[] = { "evenodd", "nonzero", NULL };

/* threads = N of the options at t, as machine:plan reads it (0: the
 * online cores; not given: the script's default, lamina.threads()) */
static unsigned get_threads(lua_State *L, int t)
{
    double x;
    if (!lam_lua_numfield(L, t, 2, "threads", &x)) return lam_lua_threads(L);
    if (!(x >= 0 && x <= LAM_MAX_THREADS) || x != floor(x))
        lam_lua_opterror(L, 2, "threads must be a whole number from 0 to %d (0: the online cores), got %.14g",
                         LAM_MAX_THREADS, x);
    return x == 0 ? lam_online_cores() : (unsigned)x;
}

/* The options at t without threads, at t (model:slice's key check sees
 * its own keys only). */
static void drop_threads(lua_State *L, int t)
{
    lua_newtable(L);
    lua_pushnil(L);
    while (lua_next(L, t)) {
        if (lua_type(L, -2) == LUA_TSTRING && !strcmp(lua_tostring(L, -2), "threads")) {
            lua_pop(L, 1);
            continue;
        }
        lua_pushvalue(L, -2);
        lua_insert(L, -2);
        lua_rawset(L, -4);
    }
    lua_replace(L, t);
}

/* The layers' checks on the workers (validate_run.h): the layers are the
 * list's, read only; the results are kept in layer order on this thread,
 * which runs no Lua until every worker has stopped. */
typedef struct vctx {
    lua_State *L;
    checkjob *j;
    lam_validate_opts vo;
    size_t k;                /* kinds filled so far */
} vctx;

#define STOPPED (-1)         /* interrupted, or out of time: raised once the workers stop */

static int list_layer(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err)
{
    (void)worker, (void)v, (void)err;
    const vctx *c = ctx;
    out->L = c->j->ls[i];
    out->f = &c->j->frames[i];
    out->o = c->vo;
    return LAM_OK;
}

static int keep_check(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    (void)err;
    vctx *c = ctx;
    checkjob *j = c->j;
    j->checks[i] = *chk;
    memset(chk, 0, sizeof *chk);
    for (size_t q = 0; q < l->L->ncontours; q++) j->kinds[c->k++] = (unsigned char)l->L->contours[q].kind;
    return lam_lua_stopping(c->L) ? STOPPED : LAM_OK;
}

/* model:validate's report, from the copies the job keeps. */
static void push_report(lua_State *L, const checkjob *j)
{
    size_t n = j->n;
    size_t checked = 0, confirmed = 0, disagreeing = 0, unchecked = 0, compared = 0, differ = 0;
    lua_createtable(L, n < INT_MAX ? (int)n : 0, 8);
    for (size_t i = 0, k = 0; i < n; i++) {
        const lam_layer_check *c = &j->checks[i];
        checked += c->checked;
        confirmed += c->confirmed;
        disagreeing += c->disagreeing;
        unchecked += c->unchecked;
        compared += c->area_checked != 0;
        differ += !c->area_ok;
        lua_createtable(L, c->nitems < INT_MAX ? (int)c->nitems : 0, 12);
        setint(L, "index", j->index[i] + 1);
        setnum(L, "z", j->z[i]);
        setbool(L, "ok", c->disagreeing == 0 && c->area_ok);
        setint(L, "checked", c->checked);
        setint(L, "confirmed", c->confirmed);
        setint(L, "disagreeing", c->disagreeing);
        setint(L, "unchecked", c->unchecked);
        setnum(L, "net_area", c->net_area);
        if (c->area_checked) {
            setnum(L, "section_area", c->section_area);
            setnum(L, "area_tolerance", c->area_tolerance);
        }
        setbool(L, "area_ok", c->area_ok);
        setstr(L, "area_why", c->area_why ? c->area_why : "");
        for (size_t q = 0; q < c->nitems; q++) {
            push_contour(L, &c->items[q], j->kinds[k + c->items[q].contour]);
            lua_rawseti(L, -2, (lua_Integer)q + 1);
        }
        k += c->nitems;
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    setbool(L, "ok", disagreeing == 0 && differ == 0);
    setint(L, "checked", checked);
    setint(L, "confirmed", confirmed);
    setint(L, "disagreeing", disagreeing);
    setint(L, "unchecked", unchecked);
    setint(L, "areas_compared", compared);
    setint(L, "areas_differing", differ);
}

/* model:validate{slice options | layers = {...} [, fill =]} -> report | nil, message */
int lam_lua_validate(lua_State *L)
{
    lam_lua_checkmodel(L, 1);
    if (lua_isnoneornil(L, 2)) {
        lua_settop(L, 1);
        lua_newtable(L);
    }
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    int fill = 0;
    unsigned threads = get_threads(L, 2);
    if (lua_getfield(L, 2, "layers") != LUA_TNIL) {
        static const char *const keys[] = { "layers", "fill", "threads", NULL };
        lam_lua_checkkeys(L, 2, 2, keys);
        char b[64];
        if (!lua_istable(L, 3))
            lam_lua_opterror(L, 2, "layers must be a list of lamina.layer, got %s", lam_lua_describe(L, 3, b, sizeof b));
        lam_lua_choicefield(L, 2, 2, "fill", fill_names, &fill);
        lua_replace(L, 2); /* the layers at 2 */
    } else {
        lua_pop(L, 1);
        lam_lua_choicefield(L, 2, 2, "fill", fill_names, &fill);
        drop_threads(L, 2);
        /* sliced as model:slice slices, in this call (its errors name validate) */
        int nr = lam_lua_slice(L); /* the layers replace the options at 2 */
        if (nr == 2) return 2;     /* nil, message */
    }
    lua_settop(L, 2);
    lua_Unsigned nl = lua_rawlen(L, 2);
    if (nl > SIZE_MAX / sizeof(lam_layer_check)) luaL_argerror(L, 2, "too many layers");
    size_t n = (size_t)nl;
    checkjob *j = newjob(L); /* at 3 */
    j->ls = calloc(n + 1, sizeof *j->ls);
    j->frames = calloc(n + 1, sizeof *j->frames);
    j->checks = calloc(n + 1, sizeof *j->checks);
    j->index = calloc(n + 1, sizeof *j->index);
    j->z = calloc(n + 1, sizeof *j->z);
    if (!j->ls || !j->frames || !j->checks || !j->index || !j->z) return luaL_error(L, "out of memory");
    j->n = n;
    size_t total = 0;
    /* the layers' pointers: nothing allocates from here to the tables */
    for (size_t i = 0; i < n; i++) {
        j->ls[i] = lam_lua_layeritem(L, 2, 2, i);
        j->frames[i] = lam_lua_layerrun(L, -1)->frame;
        lua_getiuservalue(L, -1, 1); /* the run */
        lua_getiuservalue(L, -1, 1); /* its model */
        if (!lua_rawequal(L, -1, 1)) lam_lua_opterror(L, 2, "layers[%zu] is a layer of another model", i + 1);
        lua_pop(L, 3); /* the list keeps the layer alive */
        j->index[i] = j->ls[i]->index;
        j->z[i] = j->ls[i]->cut;
        total += j->ls[i]->ncontours;
    }
    j->kinds = malloc(total + 1);
    if (!j->kinds) return luaL_error(L, "out of memory");
    lam_error err;
    lam_error_clear(&err);
    if (lam_rays_new(lam_lua_checkmodel(L, 1)->m, &j->v, &err)) return lam_lua_fail(L, &err);
    vctx vc = { L, j, { 0 }, 0 };
    lam_validate_opts_init(&vc.vo);
    vc.vo.fill_nonzero = fill;
    for (size_t i = 0; i < n; i++) /* the loss check's allowance for bridged gaps */
        if (j->ls[i]->gap > vc.vo.gap) vc.vo.gap = j->ls[i]->gap;
    lam_lua_check_interrupt(L);
    int rc = lam_validate_layers(j->v, n, threads, n ? &j->frames[0] : NULL, list_layer, keep_check, &vc, &err);
    lam_rays_free(j->v);
    j->v = NULL;
    lam_lua_check_interrupt(L);
    if (rc == STOPPED) return luaL_error(L, "interrupted");
    if (rc) return lam_lua_fail(L, &err);

    push_report(L, j);
    return 1;
}

/* model:check(machine [, {axis = ...}]) -> report | nil, message */
int lam_lua_check(lua_State *L)
{
    lam_lua_checkmodel(L, 1);
    lam_lua_checkmachine(L, 2);
    lua_settop(L, 3);
    lam_frame f;
    if (lua_isnil(L, 3)) {
        lam_error e;
        lam_frame_axis('z', &f, &e);
    } else {
        luaL_checktype(L, 3, LUA_TTABLE);
        static const char *const keys[] = { "axis", NULL };
        lam_lua_checkkeys(L, 3, 3, keys);
        lam_lua_get_axis(L, 3, 3, &f);
    }
    checkjob *j = newjob(L);
    char machine[128];
    const lam_profile *p = &lam_lua_checkmachine(L, 2)->p;
    snprintf(machine, sizeof machine, "%s", p->name ? p->name : "");
    lam_drc_opts o;
    lam_drc_opts_from_profile(&o, p, f.w);
    const lam_model *m = lam_lua_checkmodel(L, 1)->m;
    lam_error err;
    lam_error_clear(&err);
    if (lam_rays_new(m, &j->v, &err) || lam_drc_run(m, j->v, &o, &j->drc, &err)) return lam_lua_fail(L, &err);
    lam_rays_free(j->v);
    j->v = NULL;
    size_t n = j->drc.n;
    if (!(j->where = calloc(n + 1, WHERE))) return luaL_error(L, "out of memory");
    for (size_t i = 0; i < n; i++) lam_mesh_describe_tri(&m->mesh, j->drc.items[i].tri, j->where + i * WHERE, WHERE);

    lua_createtable(L, n < INT_MAX ? (int)n : 0, 6);
    setbool(L, "ok", n == 0);
    setstr(L, "machine", machine);
    setnum(L, "min_wall", o.min_wall);
    if (o.max_overhang_deg > 0) setnum(L, "max_overhang_deg", o.max_overhang_deg);
    setint(L, "samples", j->drc.samples);
    for (size_t i = 0; i < n; i++) {
        const lam_violation *x = &j->drc.items[i];
        lua_createtable(L, 0, 7);
        setstr(L, "rule", lam_rule_name(x->rule));
        setvec(L, "position", x->pos, 3);
        setnum(L, "value", x->value);
        setnum(L, "limit", x->limit);
        setnum(L, "area", x->area);
        setint(L, "triangles", x->triangles);
        setstr(L, "source", j->where + i * WHERE);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}
