/* Private helpers shared by the Lua binding (lua/l_aux.c, lua/l_*.c) and
 * the REPL. Not part of any public interface.
 *
 * Object graph (every arrow a user value, so a child keeps its parent
 * alive): contour -> layer -> run -> model; a derived machine -> the machine
 * that owns the loaded profile. A run is the hidden record of one slicing
 * call (frame, options, extents) shared by the layers it made.
 *
 * Every accessor goes through the parent userdata and checks that it is
 * still alive: a finalizer may have run on it already (objects collected in
 * the same cycle are finalized together, and a finalizer elsewhere can
 * resurrect a child), so a finalized object raises "attempt to use a
 * collected lamina.X" instead of touching freed memory.
 *
 * The same reason sets one rule for the C code: a raw pointer into an
 * object's C data is not used across a Lua call that may run the garbage
 * collector (anything that allocates: pushing a string, a table, a
 * userdata), because a pending finalizer of a resurrected object can run
 * there. Data is copied first, or re-checked after, or allocated before the
 * pointers are taken; model:slice, which must allocate while the slicer
 * reads the model, pins the model instead (lmodel.busy: its finalizer then
 * only marks it, and the run frees it when slicing ends). */
#ifndef LAM_L_COMMON_H
#define LAM_L_COMMON_H

#include <signal.h>
#include <stddef.h>

#include <lauxlib.h>
#include <lua.h>

#include "error.h"
#include "model.h"
#include "planner.h"
#include "profile.h"
#include "profile_keys.h"
#include "slice.h"
#include "support.h"

#include "version.h"

#define LAM_MODEL   "lamina.model"
#define LAM_RUN     "lamina.run"
#define LAM_LAYER   "lamina.layer"
#define LAM_CONTOUR "lamina.contour"
#define LAM_MACHINE "lamina.machine"
#define LAM_PLAN    "lamina.plan"
#define LAM_LAYERS  "lamina.layers"  /* the metatable of model:slice's list (a plain table) */


/* Set by the SIGINT handler of lua/cli/cli_lua.c while Lua code runs, cleared when
 * that code returns; long C loops of the binding (slicing, planning) poll
 * it between layers and raise "interrupted". Nothing sets it in a stock
 * lua5.4. */
extern volatile sig_atomic_t lam_lua_interrupt;

/* Raise "interrupted" if the flag is set, or "time limit exceeded" in a
 * sandbox whose time is up. */
void lam_lua_check_interrupt(lua_State *L);

/* Whether lam_lua_check_interrupt would raise, without raising: for C
 * loops that must stop their threads before the error is raised. */
int lam_lua_stopping(lua_State *L);

/* The number of threads machine:plan uses when its options give none
 * (lamina.threads()): what lam_lua_set_threads stored in L, else 1. May
 * allocate (a registry look-up): call it before keeping pointers. */
unsigned lam_lua_threads(lua_State *L);

/* Set that default for L (the lamina executable: `lamina run -j N`,
 * LAMINA_THREADS); n >= 1. */
void lam_lua_set_threads(lua_State *L, unsigned n);

/* ---- sandboxes (l_sandbox.c) --------------------------------------------- */

typedef struct lam_sandbox lam_sandbox;

typedef struct lam_sandbox_opts {
    const char *const *allow;   /* directories to read */
    size_t nallow;
    const char *const *out;     /* directories to read and write (created if missing) */
    size_t nout;
    double memory;              /* bytes of Lua memory and lamina's objects, 0: no limit */
    double time;                /* seconds from lam_lua_sandbox_start, 0: no limit */
    lua_CFunction open_lamina;  /* the lamina module of the state (luaopen_lamina): given by
                                   the host, so the sandbox does not call the module that
                                   opens it */
} lam_sandbox_opts;

/* A new sandboxed state (l_sandbox.c's header says what it has), or NULL
 * with a message in msg (a directory that is not one). Close it with
 * lam_lua_sandbox_close. */
lua_State *lam_lua_sandbox_open(const lam_sandbox_opts *o, char *msg, size_t size);
void lam_lua_sandbox_close(lua_State *L);

/* Start the clock and the time hook, right before the recipe runs. */
void lam_lua_sandbox_start(lua_State *L);

/* The sandbox of state L, NULL when L is not sandboxed. */
lam_sandbox *lam_lua_sandbox_of(lua_State *L);

/* Raise "time limit exceeded" when L's sandbox is out of time. */
void lam_lua_sandbox_check_time(lua_State *L);

/* Whether L is a sandbox whose time is up (marks it so), without raising. */
int lam_lua_sandbox_timed_out(lua_State *L);

/* When L is sandboxed and path is outside what it may read (write 0) or
 * write (write 1): push nil, a message and EACCES, as io.open fails, and
 * return 3. Otherwise 0. For every lamina function that opens a file. */
int lam_lua_denied(lua_State *L, const char *path, int write);

/* Whether the error object on top of L is a sandbox's os.exit; *code gets
 * its code. The object stays. */
int lam_lua_sandbox_exit(lua_State *L, int *code);

/* The message for a memory error in a sandbox with a memory limit (in
 * buf), NULL otherwise. */
const char *lam_lua_sandbox_memory_error(lua_State *L, char *buf, size_t size);

/* lamina's own memory against a sandbox's memory limit: the C memory of
 * the models, slicings and plans a sandboxed recipe makes shares the one
 * limit with Lua's memory. Outside a sandbox, or with no limit, nothing is
 * counted and everything fits. */

/* Bytes left under the limit now (SIZE_MAX without one). Never collects. */
size_t lam_lua_mem_room(lua_State *L);

/* The same, after a full collection when fewer than want bytes are left
 * (objects that are garbage give theirs back in their finalizers). Runs
 * the collector: the rule of lam_lua_charge holds. */
size_t lam_lua_mem_reclaim(lua_State *L, size_t want);

/* Charge bytes to the object whose charge is *slot (added to it): 1 when
 * they fit, 0 when they do not even after a full collection (nothing
 * charged). Runs the collector (finalizers included): call it only where
 * no raw pointer into an object's C data is kept across it. */
int lam_lua_charge(lua_State *L, size_t *slot, size_t bytes);

/* Give back all of *slot (set to 0): in the object's finalizer, or when
 * its memory is freed. Never raises or allocates. */
void lam_lua_discharge(lua_State *L, size_t *slot);

/* Raise "memory limit exceeded: WHAT (the limit, what is in use; how to
 * raise it)", WHAT formatted from fmt. A Lua error like any other: pcall
 * catches it, and the recipe may go on once it has let objects go. */
int lam_lua_memory_raise(lua_State *L, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* lam_lua_charge, raising "memory limit exceeded: WHAT needs N bytes"
 * when they do not fit. */
void lam_lua_charge_or_raise(lua_State *L, size_t *slot, size_t bytes, const char *what);

/* mkdir -p: 0 or an errno. No sandbox check. */
int lam_lua_mkdirs(const char *path);

/* lamina.sandbox{...} (l_sandbox_run.c): upvalue 1 the opener of the
 * sandbox's lamina module (luaopen_lamina). */
int lam_lua_sandbox(lua_State *L);

/* ---- userdata --------------------------------------------------------- */

/* Every lamina userdata starts with its type's tag, and is looked up with
 * lam_lua_checkud / lam_lua_testud: luaL_checkudata / luaL_testudata that
 * also check the block's size and tag, so a userdata given another type's
 * metatable (debug.setmetatable) is refused instead of misread. */
enum { LAM_TAG_MODEL = 0x1a4d0001, LAM_TAG_RUN, LAM_TAG_LAYER, LAM_TAG_CONTOUR, LAM_TAG_MACHINE, LAM_TAG_PLAN,
       LAM_TAG_BOX, LAM_TAG_PLANJOB, LAM_TAG_BUILDJOB };

void *lam_lua_checkud(lua_State *L, int idx, const char *tname, size_t size, unsigned tag);
void *lam_lua_testud(lua_State *L, int idx, const char *tname, size_t size, unsigned tag);
#define LAM_CHECKUD(L, idx, type, tname, tag) ((type *)lam_lua_checkud((L), (idx), (tname), sizeof(type), (tag)))
#define LAM_TESTUD(L, idx, type, tname, tag) ((type *)lam_lua_testud((L), (idx), (tname), sizeof(type), (tag)))

typedef struct lmodel {
    unsigned tag;
    lam_model *m;            /* NULL once finalized */
    int busy;                /* slicing runs reading m right now */
    int doomed;              /* finalized while busy: freed when the last run ends */
    size_t charged;          /* bytes charged to a sandbox (lam_lua_charge) */
} lmodel;

typedef struct lrun {
    unsigned tag;
    lam_slicer *s;           /* only while slicing; the layers own their data */
    int pinned;              /* holds one lmodel.busy count (while slicing) */
    lam_frame frame;
    lam_cut cut;
    size_t nlayers;          /* layers the run made */
    double uvbox[4];         /* the model's extent in the layer frame */
    double wmin, wmax;       /* first and last plane */
    double bbox[6];          /* the model's bounding box (model frame) */
    char label[128];         /* the part's name for programs (lam_job_label) */
    size_t charged;          /* the slicer's bytes charged to a sandbox (while slicing) */
} lrun;

typedef struct llayer {
    unsigned tag;
    lam_layer *L;            /* NULL once finalized */
    size_t charged;          /* bytes charged to a sandbox */
} llayer;

typedef struct lcontour {
    unsigned tag;
    size_t i;                /* index in the layer; SIZE_MAX once finalized */
} lcontour;

typedef struct lmachine {
    unsigned tag;
    lam_profile *root;       /* the loaded profile; owned when owner, NULL once freed */
    int owner;               /* 1: loaded by lamina.machine; 0: made by override */
    lam_profile p;           /* effective values; strings and dialect borrowed from root */
} lmachine;

typedef struct lplan {
    unsigned tag;
    char *data;              /* the program (NUL-terminated), NULL once finalized */
    size_t len, lines, layers;
    int binary;              /* written by a plugin writer: #plan counts bytes */
    char name[128], process[8];
    double travel, deposit;  /* LADRP: stage travel and deposit lengths (layer plane) */
    size_t deposits;         /* LADRP: deposit moves */
    lam_scan_time time;      /* SLS: the build-time estimate (hatch.h) */
    double *layer_time;      /* SLS: each layer's estimate, seconds (owned) */
    struct lam_plan_data *rec;  /* what was planned, per layer (plan_data.h; owned) */
    size_t charged;          /* bytes charged to a sandbox */
} lplan;

/* Checked accessors: raise the usual "bad argument" error for a wrong type
 * and "attempt to use a collected ..." for a finalized object. */
lmodel *lam_lua_checkmodel(lua_State *L, int idx);
/* Free u's model and give back its charge (its finalizer, or the run that
 * pinned it). */
void lam_lua_model_free(lua_State *L, lmodel *u);
lam_layer *lam_lua_checklayer(lua_State *L, int idx);
lrun *lam_lua_layerrun(lua_State *L, int idx);   /* run of the layer at idx */
/* Push a layer of the run of the layer at `like`, holding `taken` (its
 * finalizer frees it); charged to a sandbox (raises past its memory). */
void lam_lua_pushlayer(lua_State *L, int like, lam_layer *taken);
/* Item i (0-based) of the list at index `list` as a live layer: pushed and
 * its lam_layer returned; anything else raises an error on argument `arg`
 * ("layers[3] must be a lamina.layer, got string"). */
lam_layer *lam_lua_layeritem(lua_State *L, int list, int arg, size_t i);
lmachine *lam_lua_checkmachine(lua_State *L, int idx);

/* Push the contour userdata k of the layer at idx (cached: the same
 * userdata every time), or nil when k is out of range. */
void lam_lua_pushcontour(lua_State *L, int layer_idx, size_t k);

/* ---- classes and modules --------------------------------------------- */

/* Create metatable tname with metamethods `meta` and an __index that looks
 * in `methods` first, then calls `fields` (self, key) for anything else. */
void lam_lua_newclass(lua_State *L, const char *tname, const luaL_Reg *meta, const luaL_Reg *methods,
                      lua_CFunction fields);

/* Add methods to class tname (made by lam_lua_newclass): luaopen_lamina
 * gives a class the methods other files define (model:slice in l_layer.c,
 * machine:plan in l_plan.c), so a type file does not call the files
 * built on it. */
void lam_lua_addmethods(lua_State *L, const char *tname, const luaL_Reg *methods);

void lam_lua_open_model(lua_State *L);
void lam_lua_open_layer(lua_State *L);
void lam_lua_open_contour(lua_State *L);
void lam_lua_open_machine(lua_State *L);
void lam_lua_open_plan(lua_State *L);

/* Module-level functions and methods defined in one file, used in another. */
int lam_lua_load(lua_State *L);            /* lamina.load (l_model.c) */
int lam_lua_slice(lua_State *L);           /* model:slice (l_layer.c) */
int lam_lua_machine(lua_State *L);         /* lamina.machine (l_machine.c) */
int lam_lua_machines(lua_State *L);        /* lamina.machines (l_machine.c) */
int lam_lua_machine_keys(lua_State *L);    /* lamina.machine_keys (l_machine.c) */
int lam_lua_plan(lua_State *L);            /* machine:plan (l_plan.c) */

/* The C memory of a plan (l_plan.c): its program, per-layer times and its
 * record, for the sandbox's budget; machine:plan's and lamina.build's. */
size_t lam_lua_plan_bytes(size_t program, size_t layers, const struct lam_plan_data *r);
int lam_lua_build(lua_State *L);           /* lamina.build (l_build.c) */

/* The option `axis` of table t (argument arg): "x", "y", "z" or a
 * direction {dx, dy, dz}, as model:slice takes it (z when absent); a bad
 * value raises. */
void lam_lua_get_axis(lua_State *L, int t, int arg, lam_frame *f);

/* model:validate{...} and model:check(machine [, opts]) (l_check.c) */
int lam_lua_validate(lua_State *L);
int lam_lua_check(lua_State *L);

/* Fill plan options from a machine profile's values. */
void lam_lua_plan_opts(const lam_profile *p, lam_plan_opts *o);

/* Values of a machine profile given in a Lua table (machine:override,
 * the options of machine:plan), read and checked as the YAML loader checks
 * them before being applied: reading may run the table's metamethods, so
 * it happens before any pointer into a profile is taken. */
typedef struct lam_lua_overrides {
    unsigned char set[LAM_KEYS_MAX]; /* set[i]: row i of lam_profile_keys was given */
    double v[LAM_KEYS_MAX];
} lam_lua_overrides;

/* Read table t (argument number arg, as luaL_argerror counts): the rows a
 * machine may change (not LAM_KEY_FIXED) that have the flags `need`
 * (LAM_KEY_PLAN: machine:plan's options; 0: every one), by their Lua names;
 * `extra` (NULL-ended, or NULL) names the other keys the caller reads
 * itself, so that only keys in neither are refused as unknown. */
void lam_lua_read_overrides(lua_State *L, int t, int arg, unsigned need, const char *const *extra,
                            lam_lua_overrides *o);
void lam_lua_apply_overrides(const lam_lua_overrides *o, lam_profile *p);

/* Refuse (argument error at arg) a value in o that machine p's planner does
 * not read, as the command line and the YAML loader do (lam_key_unread). */
void lam_lua_check_readers(lua_State *L, int arg, const lam_lua_overrides *o, const lam_profile *p);

/* Push the value of row k in p, as Lua sees it: nil for an optional value
 * not given. */
void lam_lua_push_key(lua_State *L, const lam_profile *p, const lam_key *k);

/* Supports (l_support.c). machine:plan's `supports` option of the options
 * table at opts for the layers at `layers`: the recipe's regions read (its
 * generator called, on this thread, before planning), kept in a box pushed
 * on the stack (its finalizer frees them); *box NULL when the option is
 * absent. lam_lua_supports_auto then makes lamina's own into an empty box
 * when machine p asks for them. model:supports{layers =, machine =, ...}. */
lam_supports **lam_lua_supports_option(lua_State *L, int opts, int layers);
int lam_lua_supports_auto(lam_supports **box, const lam_layer *const *ls, size_t n, const lam_profile *p,
                          lam_error *err);
int lam_lua_supports(lua_State *L);

/* Lua control of an SLS plan's hatching (l_hatch.c), from machine:plan's
 * options `layer` (function(layer, i) -> the keys to change for that
 * layer), `hatcher` (function(layer, params) -> vectors) and `order`
 * (function(vectors, layer, params) -> vectors). Vectors are a sequence
 * of {x0, y0, x1, y1 [, kind = "core"|"upskin"|"downskin"]} in the layer
 * plane; consecutive vectors of one kind make a block. */
typedef struct lhatchctl lhatchctl;

/* Take the three functions out of the options table at index opts
 * (replaced in place by a copy without them, so the key checks see only
 * profile keys); pushes a control object (or nil when none is given) and
 * returns it, NULL for none. */
lhatchctl *lam_lua_hatch_split(lua_State *L, int opts);

/* Run the functions for every layer of the table at index layers (checked
 * layers, in order), with the machine's profile p and its plan options
 * base: called before any pointer is taken that a collection could free.
 * Returns NULL, or the error of hatching a layer for `order` (the layers
 * after it are not looked at): the plan fails with it as planning would. */
const lam_error *lam_lua_hatch_prepare(lua_State *L, lhatchctl *c, int layers, const lam_profile *p);

/* Layer i's profile (p with the layer's overrides) and hatch vectors
 * (NULL: the planner hatches). */
void lam_lua_hatch_profile(const lhatchctl *c, size_t i, lam_profile *p);
const lam_hatches *lam_lua_hatch_given(const lhatchctl *c, size_t i);

/* ---- errors and options ----------------------------------------------- */

/* Push a userdata holding one malloc'd pointer (initially NULL) that its
 * finalizer frees: C memory that must not leak if Lua raises an error
 * before the C code frees it itself (then set *box = NULL). */
void **lam_lua_newbox(lua_State *L);

/* The expected-failure convention of io.open: push nil and the formatted
 * error; returns 2. */
int lam_lua_fail(lua_State *L, const lam_error *err);

/* lamina.preview(layers, path [, title]) (l_preview.c) */
int lam_lua_preview(lua_State *L);

/* Raise an error of an option: "bad argument #arg to 'fn' (msg)". */
int lam_lua_opterror(lua_State *L, int arg, const char *fmt, ...);

/* Check that every key of table t is a string in `allowed` (NULL-ended);
 * otherwise raise a bad-argument error naming the unknown key. */
void lam_lua_checkkeys(lua_State *L, int t, int arg, const char *const *allowed);

/* Field `key` of table t: 0 when absent (nil), 1 with *x set when a finite
 * number; anything else raises "KEY must be a number, got TYPE". */
int lam_lua_numfield(lua_State *L, int t, int arg, const char *key, double *x);

/* Field `key` of table t when it is a string among `names` (NULL-ended):
 * 0 when absent, 1 with *i its index; anything else raises an error that
 * lists the names. */
int lam_lua_choicefield(lua_State *L, int t, int arg, const char *key, const char *const *names, int *i);

/* Field `key` as a boolean: 0 absent, 1 with *b set; other types raise. */
int lam_lua_boolfield(lua_State *L, int t, int arg, const char *key, int *b);

/* A short description of the value at idx for messages: "-1", "'top'",
 * "a table". Pushes nothing; the text lives in buf. */
const char *lam_lua_describe(lua_State *L, int idx, char *buf, size_t size);

#endif
