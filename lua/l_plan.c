/* lamina.plan: a machine program, made by machine:plan(layers [, opts]).
 *
 * The layers given (one slicing run, in slicing order; any subset) are
 * planned as they are, through the core planners of the machine's process
 * (lam_plan_ladrp_layer / lam_plan_sls_layer) into the machine's writer:
 * its dialect templates, or a plugin writer (`writer:` in the profile). The
 * job header is lam_plan_run's (lam_job_init: plan_job below). The program is kept in
 * memory: plan:text() returns it, plan:write(path) writes it atomically.
 * The option `threads` plans on worker threads (core/plan/plan_drive.c); only
 * the calling thread touches Lua and the writer. */
#include "l_common.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plugin.h"
#include "tee.h"
#include "views.h"
#include "plan_layers.h"
#include "pool.h"
#include "writer.h"

#define LAM_PLANJOB "lamina.planjob"

/* Everything C that a planning run holds, released by __gc if Lua raises an
 * error half-way (an interrupt, a memory error). */
typedef struct planjob {
    unsigned tag;
    lam_writer *w;
    lam_sink sink;
    int have_sink;
    lam_error err;           /* the sink reports through it: it must not move */
    lam_plan_data rec;          /* what was planned, per layer: handed to the plan */
    lam_sink tee;            /* the program's sink and the plan data's (views.h) */
} planjob;

/* The program's sink and the plan data fed by one plan: j->tee owns both,
 * and j->sink is the tee from then on (so releasing it releases both). */
static int plan_data_tee(planjob *j)
{
    lam_views v = { .data = &j->rec };
    lam_sink both[2] = { j->sink };
    int rc = lam_views_sink(&v, &both[1], &j->err);
    if (!rc && (rc = lam_tee_sink(both, 2, &j->tee, &j->err))) both[1].destroy(both[1].ctx);
    if (!rc) j->sink = j->tee;
    return rc;
}

static void job_release(planjob *j)
{
    if (j->have_sink && j->sink.destroy) j->sink.destroy(j->sink.ctx);
    j->have_sink = 0;
    lam_writer_abort(j->w);
    j->w = NULL;
    lam_plan_data_free(&j->rec);
}

static int job_gc(lua_State *L)
{
    job_release(LAM_CHECKUD(L, 1, planjob, LAM_PLANJOB, LAM_TAG_PLANJOB));
    return 0;
}

/* Check argument 2: a non-empty sequence of live layers of one run in
 * increasing order; store their lam_layer pointers into ls (room for n,
 * the table's length) and return the run. Nothing here allocates. */
static const lrun *check_layers(lua_State *L, const lam_layer **ls, size_t n)
{
    const lrun *run = NULL;
    for (size_t i = 0; i < n; i++) {
        ls[i] = lam_lua_layeritem(L, 2, 2, i);
        const lrun *r = lam_lua_layerrun(L, -1);
        if (!run) run = r;
        else if (r != run)
            lam_lua_opterror(L, 2, "layers[%zu] comes from another slicing run (plan the layers of one model:slice)",
                             i + 1);
        if (i && !(ls[i]->index > ls[i - 1]->index))
            lam_lua_opterror(L, 2, "layers must be in slicing order (layers[%zu] is layer %zu, after layer %zu)", i + 1,
                             ls[i]->index + 1, ls[i - 1]->index + 1);
        lua_pop(L, 1); /* the table keeps the layer alive */
    }
    return run;
}

/* The estimate of planning these layers (core/plan/planner.h): each layer
 * counted as it is (lam_job_estimate_add), skins by position in the run. */
static void estimate(const lam_layer **ls, size_t n, const lam_plan_opts *o, lam_job_estimate *e)
{
    memset(e, 0, sizeof *e);
    size_t run = n ? ls[n - 1]->index + 1 : 0;
    for (size_t i = 0; i < n; i++) lam_job_estimate_add(e, o, ls[i], run, 1);
}

static size_t count_lines(const char *s, size_t len)
{
    size_t n = 0;
    for (const char *p = s; (p = memchr(p, '\n', len - (size_t)(p - s))); p++) n++;
    if (len && s[len - 1] != '\n') n++;
    return n;
}

/* What planning's callbacks (core/plan/plan_layers.h) need. */
typedef struct planctx {
    lua_State *L;
    lplan *pl;
    planjob *j;
    const lhatchctl *ctl;
    const lam_profile *p;
    int stopped;             /* an interrupt or the sandbox's time stopped the run */
    size_t n;                /* layers planned */
    size_t room;             /* the sandbox's memory left when planning began */
    int over;                /* the plan so far passed room */
} planctx;

/* The i-th layer's options: the recipe's `layer` function's keys (copied
 * into ctl before planning: no Lua here, workers call it too). */
static void layer_opts(void *ctx, size_t i, lam_plan_opts *oi)
{
    const planctx *c = ctx;
    unsigned threads = oi->threads;
    unsigned long long max_output = oi->max_output;
    const lam_supports *sup = oi->supports;
    lam_profile pi = *c->p;
    lam_lua_hatch_profile(c->ctl, i, &pi);
    lam_lua_plan_opts(&pi, oi);
    oi->threads = threads;
    oi->max_output = max_output;
    oi->supports = sup;
}

static const lam_hatches *given(void *ctx, size_t i)
{
    return lam_lua_hatch_given(((const planctx *)ctx)->ctl, i);
}

size_t lam_lua_plan_bytes(size_t program, size_t layers, const lam_plan_data *r)
{
    return program + 1 + layers * sizeof(double) + sizeof *r + r->cap_layers * sizeof *r->layers +
           r->cap_contours * sizeof *r->contours + r->cap_vectors * sizeof *r->vectors + r->cap_pts * 2 * sizeof(double);
}

/* Between layers, on the calling thread: Ctrl-C or the sandbox's time
 * stop the run, which raises the error once every worker has stopped; so
 * does a plan grown past the sandbox's memory: what the layers so far
 * wrote and recorded, twice (the program and the record grow by doubling,
 * and the blocks they leave stay on the heap: measured, a plan peaks at
 * twice its size while it is made), checked before each layer. */
static int stop(void *ctx, size_t i)
{
    (void)i;
    planctx *c = ctx;
    c->stopped = lam_lua_stopping(c->L);
    c->over = c->room != SIZE_MAX &&
              lam_lua_plan_bytes((size_t)lam_writer_bytes(c->j->w), c->n, &c->j->rec) > c->room / 2;
    return c->stopped || c->over ? LAM_EUSAGE : LAM_OK;
}

/* In a sandbox with a memory limit: refuse a plan estimated past the room
 * left, and plan on the calling thread. Worker threads plan layers ahead
 * (up to 16 each, as recordings) before they are written, where the
 * memory cannot be looked at between layers, and the estimate cannot
 * bound them: it can be 40 times short (issue 22, item 9). */
static int sandbox_fit(const lam_job_estimate *e, size_t room, unsigned *threads)
{
    if (room == SIZE_MAX) return 1;
    *threads = 1;
    return e->bytes <= (double)room;
}

/* After a layer's operations, on the calling thread in layer order: the
 * plan's totals and the record's figures. */
static void planned(void *ctx, size_t i, const lam_ladrp_stats *ls, const lam_scan_time *t)
{
    planctx *c = ctx;
    lplan *pl = c->pl;
    lam_rec_layer *rl = lam_plan_data_current(&c->j->rec);
    if (c->p->process != LAM_PROCESS_SLS) {
        pl->travel += ls->travel_length;
        pl->deposit += ls->deposit_length;
        pl->deposits += ls->deposits;
        if (rl) {
            rl->deposit = ls->deposit_length;
            rl->travel = ls->travel_length;
        }
    } else {
        lam_scan_time_add(&pl->time, t);
        pl->layer_time[i] = lam_scan_time_total(t);
        if (rl) {
            rl->deposit = t->exposure_length;
            rl->travel = t->jump_length;
            rl->time = pl->layer_time[i];
        }
    }
}

/* The job header (lam_job_init, as lam_plan_run's): the box of the model,
 * or of the run in the layer frame for `frame: machine`; the stage starts
 * at the model origin in the plane of the first layer planned. */
static void plan_job(lam_job_info *job, const lam_plan_opts *o, const lrun *run, const lam_layer **ls, size_t n)
{
    const double uvw[6] = { run->uvbox[0], run->uvbox[1], run->wmin, run->uvbox[2], run->uvbox[3], run->wmax };
    lam_job_init(job, o, n, o->frame_machine ? uvw : run->bbox, ls[0]->cut, &run->frame, run->label, NULL);
}

/* What machine:plan's options (argument 3) say, read before any pointer
 * is kept: they may run metamethods and the recipe's functions. */
typedef struct planargs {
    lam_lua_overrides ovr;
    double max_output;
    unsigned threads;
    lhatchctl *ctl;
} planargs;

/* Read the options into a (the recipe's hatcher at 4, or nil); the
 * recipe's error, if it fails, or NULL. */
static const lam_error *read_args(lua_State *L, planargs *a)
{
    memset(a, 0, sizeof *a);
    double nthreads = 0;
    a->threads = lam_lua_threads(L); /* the script's default (lamina.threads()) */
    lua_settop(L, 3);
    if (!lua_isnoneornil(L, 3)) {
        luaL_checktype(L, 3, LUA_TTABLE);
        a->ctl = lam_lua_hatch_split(L, 3); /* at 4 (or nil) */
        static const char *const own[] = { "max_output", "threads", "supports", NULL }; /* not profile keys */
        lam_lua_read_overrides(L, 3, 3, LAM_KEY_PLAN, own, &a->ovr); /* may run metamethods: before any pointer */
        lam_lua_check_readers(L, 3, &a->ovr, &lam_lua_checkmachine(L, 1)->p);
        if (lam_lua_numfield(L, 3, 3, "max_output", &a->max_output) && !(a->max_output >= 1 && a->max_output < 1.8e19))
            lam_lua_opterror(L, 3, "max_output must be a number of bytes >= 1, got %.14g", a->max_output);
        if (lam_lua_numfield(L, 3, 3, "threads", &nthreads)) {
            if (!(nthreads >= 0 && nthreads <= LAM_MAX_THREADS && nthreads == floor(nthreads)))
                lam_lua_opterror(L, 3, "threads must be a whole number from 0 to %d (0: the online cores), got %.14g",
                                 LAM_MAX_THREADS, nthreads);
            a->threads = nthreads == 0 ? lam_online_cores() : (unsigned)nthreads;
        }
    } else {
        lua_pushnil(L);
    }
    if (!a->ctl) return NULL;
    /* the recipe's functions run now, before any pointer is kept */
    lam_profile base = lam_lua_checkmachine(L, 1)->p;
    lam_lua_apply_overrides(&a->ovr, &base);
    return lam_lua_hatch_prepare(L, a->ctl, 2, &base);
}

/* The plan (at *plan on the stack) and the job that makes it, with room
 * for n layer pointers (*ls). Everything Lua is allocated here: after
 * this, until the program is complete, no call can run the collector (and
 * a finalizer with it), so the pointers into the machine and the layers
 * stay good. */
static planjob *new_job(lua_State *L, size_t n, const lam_layer ***ls, lplan **pl, int *plan)
{
    *ls = lua_newuserdatauv(L, n * sizeof **ls, 0);
    *pl = lua_newuserdatauv(L, sizeof **pl, 0);
    memset(*pl, 0, sizeof **pl);
    (*pl)->tag = LAM_TAG_PLAN;
    luaL_setmetatable(L, LAM_PLAN);
    *plan = lua_gettop(L);
    planjob *j = lua_newuserdatauv(L, sizeof *j, 0);
    memset(j, 0, sizeof *j);
    j->tag = LAM_TAG_PLANJOB;
    if (luaL_newmetatable(L, LAM_PLANJOB)) {
        lua_pushcfunction(L, job_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_setmetatable(L, -2);
    return j;
}

/* Plan the layers into the job's writer (at most limit bytes) through the
 * machine's sink and the plan's record: begin, the layers (the planning
 * driver, lam_plan_layers). Returns LAM_OK or an error (j->err). */
static int plan_into(planjob *j, planctx *pc, const lam_plan_opts *o, const lam_job_info *job, const lrun *run,
                     const lam_layer **ls, size_t n, unsigned long long limit)
{
    if (lam_writer_memory(&j->w, &j->err)) return j->err.code;
    lam_writer_set_limit(j->w, limit);
    int rc = lam_program_sink(pc->p->writer, &pc->p->dialect, j->w, &j->sink, &j->err);
    if (rc) return rc;
    j->have_sink = 1;
    if ((rc = plan_data_tee(j))) return rc;
    const lam_sink *s = &j->tee;
    rc = s->begin ? s->begin(s->ctx, job) : LAM_OK;
    lam_plan_layers_job lj;
    memset(&lj, 0, sizeof lj);
    lj.layers = ls;
    lj.n = n;
    lj.frame = &run->frame;
    lj.o = o;
    memcpy(lj.origin, job->origin, sizeof lj.origin);
    if (pc->ctl) {
        lj.layer_opts = layer_opts;
        lj.given = given;
    }
    lj.stop = stop;
    lj.planned = planned;
    lj.ctx = pc;
    return rc ? rc : lam_plan_layers(&lj, s, &j->err);
}

/* The program made: into the plan (at `plan`), which owns it and the
 * record from now on. Returns lua's result count. */
static int plan_done(lua_State *L, planjob *j, lplan *pl, int plan, const lam_profile *p, size_t n,
                     const char *process)
{
    int rc = lam_writer_take(j->w, &pl->data, &pl->len, &j->err);
    j->w = NULL;
    if (rc) return lam_lua_fail(L, &j->err);
    char *fit = realloc(pl->data, pl->len + 1); /* the buffer grew by doubling: give back its slack */
    if (fit) pl->data = fit;
    pl->lines = count_lines(pl->data, pl->len);
    pl->layers = n;
    pl->binary = !lam_program_text(p->writer);
    snprintf(pl->name, sizeof pl->name, "%s", p->name ? p->name : "");
    snprintf(pl->process, sizeof pl->process, "%s", process);
    pl->rec = malloc(sizeof *pl->rec);
    if (!pl->rec) return luaL_error(L, "out of memory");
    *pl->rec = j->rec; /* the plan owns the record now */
    memset(&j->rec, 0, sizeof j->rec);
    lua_settop(L, plan);
    size_t bytes = lam_lua_plan_bytes(pl->len, n, pl->rec);
    if (!lam_lua_charge(L, &pl->charged, bytes))
        return lam_lua_memory_raise(L, "machine:plan: the plan takes %zu bytes", bytes); /* p_gc frees it */
    return 1;
}

/* machine:plan(layers [, opts]) -> plan | nil, message */
int lam_lua_plan(lua_State *L)
{
    lam_lua_checkmachine(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    planargs a;
    const lam_error *e = read_args(L, &a);
    if (e) return lam_lua_fail(L, e);
    lua_settop(L, 4);
    lam_supports **sup = lam_lua_supports_option(L, 3, 2); /* at 5: the recipe's regions, or lamina's below */
    int collected = 0;
again:;
    lua_Unsigned nl = lua_rawlen(L, 2);
    if (nl == 0) luaL_argerror(L, 2, "no layers to plan (an empty table)");
    if (nl > SIZE_MAX / sizeof(void *)) luaL_argerror(L, 2, "too many layers");
    size_t n = (size_t)nl;
    const lam_layer **ls;
    lplan *pl;
    int plan;
    planjob *j = new_job(L, n, &ls, &pl, &plan);
    lam_profile p = lam_lua_checkmachine(L, 1)->p;
    lam_lua_apply_overrides(&a.ovr, &p);
    const lrun *run = check_layers(L, ls, n);
    lam_plan_opts o;
    lam_lua_plan_opts(&p, &o);
    if (lam_lua_supports_auto(sup, ls, n, &p, &j->err)) return lam_lua_fail(L, &j->err);
    o.supports = *sup;
    o.max_output = (unsigned long long)a.max_output;
    lam_job_info job;
    plan_job(&job, &o, run, ls, n);
    lam_program_costs(&p, &job, &o.costs, NULL); /* the estimate in the writer's own bytes (planner.h) */
    lam_job_estimate est;
    estimate(ls, n, &o, &est);
    if (lam_plan_check_estimate(&est, &o, o.max_output, &j->err))
        luaL_error(L, "plan: %s (raise the limit with the option max_output)", j->err.msg);
    /* a worker holds a layer's operations until it is written: layers
     * estimated beyond LAM_THREAD_LAYER_MAX are planned on this thread, as
     * lam_plan_run does */
    o.threads = est.layers && est.bytes / (double)est.layers > LAM_THREAD_LAYER_MAX ? 1 : a.threads;
    size_t room = lam_lua_mem_room(L);
    if (!sandbox_fit(&est, room, &o.threads)) {
        if (collected)
            return lam_lua_memory_raise(L, "machine:plan: the program is estimated at %.0f bytes, %zu are left",
                                        est.bytes, room);
        /* garbage objects may hold the room: collect (no pointer is kept
         * across it: everything is taken again) and try once more; so does
         * a plan stopped for memory below, once */
        lua_settop(L, 5);
        lua_gc(L, LUA_GCCOLLECT);
        collected = 1;
        goto again;
    }
    lam_error_clear(&j->err);
    if (!(pl->layer_time = calloc(n, sizeof *pl->layer_time))) return luaL_error(L, "out of memory");
    unsigned long long limit = o.max_output ? o.max_output : LAM_DEFAULT_MAX_OUTPUT;
    planctx pc = { L, pl, j, a.ctl, &p, 0, n, room, 0 };
    /* the sandbox's room (see stop), if less; at least 1 (0 is no limit) */
    int rc = plan_into(j, &pc, &o, &job, run, ls, n, room / 2 < limit ? (room / 2 ? room / 2 : 1) : limit);
    if (pc.stopped) {
        lam_lua_check_interrupt(L); /* raises: the job's __gc cleans up */
        return luaL_error(L, "interrupted");
    }
    if (pc.over || (room / 2 < limit && j->w && lam_writer_over_limit(j->w))) {
        if (collected)
            return lam_lua_memory_raise(L, "machine:plan: the plan, which takes twice its size while it is made, "
                                           "passed the %zu bytes left", room);
        /* garbage objects may hold the room: drop this attempt (the job's
         * and the plan's finalizers free it), collect, plan once more */
        lua_settop(L, 5);
        lua_gc(L, LUA_GCCOLLECT);
        collected = 1;
        goto again;
    }
    if (!rc && j->tee.end) rc = j->tee.end(j->tee.ctx);
    if (j->have_sink && j->sink.destroy) j->sink.destroy(j->sink.ctx);
    j->have_sink = 0;
    if (rc) {
        if (j->err.code == LAM_OK) lam_error_set(&j->err, rc, NULL, 0, 0, "planning failed");
        return lam_lua_fail(L, &j->err);
    }
    return plan_done(L, j, pl, plan, &p, n, job.process);
}

/* ---- the plan userdata -------------------------------------------------- */

static lplan *check(lua_State *L, int idx)
{
    lplan *pl = LAM_CHECKUD(L, idx, lplan, LAM_PLAN, LAM_TAG_PLAN);
    if (!pl->data) luaL_error(L, "attempt to use a collected " LAM_PLAN);
    return pl;
}

static int p_gc(lua_State *L)
{
    lplan *pl = LAM_CHECKUD(L, 1, lplan, LAM_PLAN, LAM_TAG_PLAN);
    free(pl->data);
    pl->data = NULL;
    free(pl->layer_time);
    pl->layer_time = NULL;
    lam_plan_data_free(pl->rec);
    free(pl->rec);
    pl->rec = NULL;
    lam_lua_discharge(L, &pl->charged);
    return 0;
}

static int p_tostring(lua_State *L)
{
    lplan *pl = LAM_CHECKUD(L, 1, lplan, LAM_PLAN, LAM_TAG_PLAN);
    if (!pl->data) lua_pushliteral(L, LAM_PLAN " (collected)");
    else if (pl->binary)
        lua_pushfstring(L, LAM_PLAN " (%s, %s, %I layers, %I bytes)", pl->name, pl->process, (lua_Integer)pl->layers,
                        (lua_Integer)pl->len);
    else
        lua_pushfstring(L, LAM_PLAN " (%s, %s, %I layers, %I lines)", pl->name, pl->process, (lua_Integer)pl->layers,
                        (lua_Integer)pl->lines);
    return 1;
}

static int p_len(lua_State *L)
{
    lplan *pl = check(L, 1);
    lua_pushinteger(L, (lua_Integer)(pl->binary ? pl->len : pl->lines));
    return 1;
}

static int p_fields(lua_State *L)
{
    lplan *pl = check(L, 1);
    /* a build's plan (lamina.build, l_build.c) holds its own fields in its
     * user value: parts, lasers, styles, labels */
    if (lua_getiuservalue(L, 1, 1) == LUA_TTABLE) {
        lua_pushvalue(L, 2);
        if (lua_rawget(L, -2) != LUA_TNIL) return 1;
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    const char *k = lua_tostring(L, 2);
    if (strcmp(k, "bytes") == 0) lua_pushinteger(L, (lua_Integer)pl->len);
    else if (strcmp(k, "lines") == 0) lua_pushinteger(L, (lua_Integer)pl->lines);
    else if (strcmp(k, "layers") == 0) lua_pushinteger(L, (lua_Integer)pl->layers);
    else if (strcmp(k, "machine") == 0) lua_pushstring(L, pl->name);
    else if (strcmp(k, "process") == 0) lua_pushstring(L, pl->process);
    else if (strcmp(k, "binary") == 0) lua_pushboolean(L, pl->binary);
    else if (strcmp(k, "travel") == 0) lua_pushnumber(L, pl->travel);
    else if (strcmp(k, "deposit") == 0) lua_pushnumber(L, pl->deposit);
    else if (strcmp(k, "deposits") == 0) lua_pushinteger(L, (lua_Integer)pl->deposits);
    else if (strcmp(k, "time") == 0) {
        const lam_scan_time *t = &pl->time;
        lua_createtable(L, 0, 9);
        lua_pushnumber(L, lam_scan_time_total(t));
        lua_setfield(L, -2, "total");
        lua_pushnumber(L, t->exposure);
        lua_setfield(L, -2, "exposure");
        lua_pushnumber(L, t->jump);
        lua_setfield(L, -2, "jumps");
        lua_pushnumber(L, t->recoat);
        lua_setfield(L, -2, "recoat");
        lua_pushinteger(L, (lua_Integer)t->vectors);
        lua_setfield(L, -2, "vectors");
        lua_pushinteger(L, (lua_Integer)t->contours);
        lua_setfield(L, -2, "contours");
        lua_pushnumber(L, t->exposure_length);
        lua_setfield(L, -2, "exposed");
        lua_pushnumber(L, t->jump_length);
        lua_setfield(L, -2, "jumped");
        lua_pushnumber(L, t->hatch_length);
        lua_setfield(L, -2, "hatched");
        lua_createtable(L, (int)pl->layers, 0);
        for (size_t i = 0; i < pl->layers && pl->layer_time; i++) {
            lua_pushnumber(L, pl->layer_time[i]);
            lua_rawseti(L, -2, (lua_Integer)i + 1);
        }
        lua_setfield(L, -2, "layers");
    } else lua_pushnil(L);
    return 1;
}

/* plan:text() -> the program (bytes, for a binary writer) */
static int p_text(lua_State *L)
{
    lplan *pl = check(L, 1);
    lua_pushlstring(L, pl->data, pl->len);
    return 1;
}

/* plan:write(path) -> true | nil, message (atomic: all or nothing) */
static int p_write(lua_State *L)
{
    lplan *pl = check(L, 1);
    const char *path = luaL_checkstring(L, 2);
    int n = lam_lua_denied(L, path, 1);
    if (n) return n;
    lam_writer *w;
    lam_error err;
    lam_error_clear(&err);
    if (lam_writer_file(path, &w, &err)) return lam_lua_fail(L, &err);
    lam_writer_write(w, pl->data, pl->len);
    if (lam_writer_commit(w, &err)) return lam_lua_fail(L, &err);
    lua_pushboolean(L, 1);
    return 1;
}

/* The attributes (vocab.h) that are not at their default, as fields of
 * the table on top. */
static void push_attrs(lua_State *L, const lam_attrs *a)
{
    for (size_t i = 0; i < LAM_NATTRS; i++)
        if (lam_attr_get(a, i) != lam_attr_default(i)) {
            lua_pushinteger(L, (lua_Integer)lam_attr_get(a, i));
            lua_setfield(L, -2, lam_attr_key(i));
        }
}

/* plan:layer(i) -> { index, z, deposit, travel, time, contours, vectors } | nil
 * (tables made now from the record: nothing refers back to the plan) */
static int p_layer(lua_State *L)
{
    lplan *pl = check(L, 1);
    lua_Integer i = luaL_checkinteger(L, 2);
    if (!pl->rec || i < 1 || (lua_Unsigned)i > pl->rec->nlayers) {
        lua_pushnil(L);
        return 1;
    }
    /* copied out first: building tables may run a finalizer */
    lam_rec_layer ly = pl->rec->layers[i - 1];
    lua_createtable(L, 0, 8);
    lua_pushinteger(L, (lua_Integer)ly.index + 1);
    lua_setfield(L, -2, "index");
    lua_pushnumber(L, ly.z);
    lua_setfield(L, -2, "z");
    lua_pushnumber(L, ly.deposit);
    lua_setfield(L, -2, "deposit");
    lua_pushnumber(L, ly.travel);
    lua_setfield(L, -2, "travel");
    lua_pushnumber(L, ly.time);
    lua_setfield(L, -2, "time");
    lua_createtable(L, (int)(ly.nc < INT_MAX ? ly.nc : 0), 0);
    for (size_t k = 0; k < ly.nc; k++) {
        pl = check(L, 1);
        lam_rec_contour c = pl->rec->contours[ly.c0 + k];
        lua_createtable(L, c.n < INT_MAX / 2 ? (int)(2 * c.n) : 0, 3);
        lua_pushstring(L, c.solid ? "solid" : "hole");
        lua_setfield(L, -2, "kind");
        lua_pushinteger(L, c.depth);
        lua_setfield(L, -2, "depth");
        lua_pushinteger(L, (lua_Integer)c.order);
        lua_setfield(L, -2, "order");
        push_attrs(L, &c.attrs);
        for (size_t q = 0; q < 2 * c.n; q++) {
            pl = check(L, 1);
            lua_pushnumber(L, pl->rec->pts[2 * c.first + q]);
            lua_rawseti(L, -2, (lua_Integer)q + 1);
        }
        lua_rawseti(L, -2, (lua_Integer)k + 1);
    }
    lua_setfield(L, -2, "contours");
    lua_createtable(L, (int)(ly.nv < INT_MAX ? ly.nv : 0), 0);
    for (size_t k = 0; k < ly.nv; k++) {
        pl = check(L, 1);
        lam_rec_vector v = pl->rec->vectors[ly.v0 + k];
        lua_createtable(L, 4, 2);
        for (int q = 0; q < 4; q++) {
            lua_pushnumber(L, v.uv[q]);
            lua_rawseti(L, -2, q + 1);
        }
        lua_pushstring(L, lam_kind_name(v.kind));
        lua_setfield(L, -2, "kind");
        push_attrs(L, &v.attrs);
        lua_pushinteger(L, (lua_Integer)v.order);
        lua_setfield(L, -2, "order");
        lua_rawseti(L, -2, (lua_Integer)k + 1);
    }
    lua_setfield(L, -2, "vectors");
    return 1;
}

static const luaL_Reg plan_meta[] = {
    { "__gc", p_gc },
    { "__tostring", p_tostring },
    { "__len", p_len },
    { NULL, NULL },
};

static const luaL_Reg plan_methods[] = {
    { "text", p_text },
    { "write", p_write },
    { "layer", p_layer },
    { NULL, NULL },
};

void lam_lua_open_plan(lua_State *L)
{
    lam_lua_newclass(L, LAM_PLAN, plan_meta, plan_methods, p_fields);
}
