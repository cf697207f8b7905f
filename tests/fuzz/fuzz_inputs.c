/* Fuzz target for everything lamina reads and runs: models (Unigrafix,
 * STL, OBJ) through slicing and both planners; machine profiles (YAML)
 * through their templates and writers on a fixed part; and, with the Lua
 * binding linked in (LAMINA_FUZZ_LUA), recipe text run in a Lua state
 * with the lamina module, no io/os/package/debug, an instruction budget and a
 * memory budget. Built two ways:
 *  - with clang -fsanitize=fuzzer (make fuzz): a libFuzzer target;
 *  - in the test suite: a deterministic mutation driver that replays every
 *    seed file given on the command line and a few thousand mutants of
 *    each (bit flips, byte changes, insertions, deletions, truncations,
 *    duplicated spans), under ASan/UBSan with `make SAN=1 test`.
 * The first byte of an input picks what it is: 0 ug, 1 stl, 2 obj, 3 a
 * profile, planned on the thesis cube, 4 a Lua recipe; the files of the
 * corpus (tests/fuzz/corpus) start with that byte, as libFuzzer's do. Paths
 * in inputs (includes, recipes' models) are relative to tests/models, where
 * both runs start.
 * A first byte of 5 is a program read back (SLS, ASCII or binary CLI, or a
 * run's JSON; programs/ in the corpus) from a heap buffer of exactly its
 * length (no NUL after it: a read past the end is caught), its layers made
 * along z and x (and in its own frame when it gives one).
 * A first byte of 6 is a part file of a split run (`lamina slice --layers`,
 * parts/ in the corpus; core/plan/part.h), checked whole and joined into a
 * program through the machine profile it holds (the built-in one of its
 * process when that does not load or is a plugin's). Most mutants would
 * only meet the checksums, so three in four get both hashes made right
 * first (fix_hashes): the records' values and the writers are fuzzed.
 * A first byte of 7 is a build job (core/build/build_job.h; jobs/ in the
 * corpus, its machine tests/models/machines/plate.yaml): read, its parts
 * loaded and arranged, and a plate of at most 64 layers and 64 parts
 * planned through the machine's dialect into memory.
 * Every input must either work or fail with a message; nothing may crash,
 * leak or read out of bounds. TAP output: one test per seed. */
#include "build_job.h"
#include "plugin.h"
#include "build_plan.h"
#include "dialect.h"
#include "error.h"
#include "import.h"
#include "model.h"
#include "part.h"
#include "planner.h"
#include "profile.h"
#include "program_read.h"
#include "slice.h"
#include "writer.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifdef LAMINA_FUZZ_LUA
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
int luaopen_lamina(lua_State *L);
#endif

enum { K_UG, K_STL, K_OBJ, K_PROFILE, K_LUA, K_PROGRAM, K_PART, K_JOB, K_COUNT };

/* The thesis's cube with a through hole: the part every fuzzed profile plans. */
static const char cube_hole[] =
    "v a -1 -1 0; v b 1 -1 0; v c 1 1 0; v d -1 1 0; v e -1 -1 2; v f 1 -1 2; v g 1 1 2; v h -1 1 2;\n"
    "v i -.5 -.5 0; v j .5 -.5 0; v k .5 .5 0; v l -.5 .5 0; v m -.5 -.5 2; v n .5 -.5 2; v o .5 .5 2; v p -.5 .5 2;\n"
    "f (a b c d) (i l k j); f (e h g f) (m n o p); f (a e f b); f (b f g c); f (c g h d); f (d h e a);\n"
    "f (i j n m); f (j k o n); f (k l p o); f (l i m p);\n";

static const char ladrp_yaml[] = "name: fuzz-ladrp\nprocess: ladrp\nbead_width: 0.3\nfeed_rate: 1\n"
                                 "dialect:\n  travel: \"T {x} {y} {z}\"\n  deposit: \"D {dx} {dy} {dz}\"\n"
                                 "  laser_on: \"ON\"\n  laser_off: \"OFF\"\n  layer: \"L {n} {z}\"\n";

/* Plan md, sliced into about `layers` layers, with profile p into memory.
 * Scan lines are kept to some thousands a layer whatever the bead. */
static void plan(const lam_model *md, const lam_profile *p, int layers, int oblique)
{
    if (p->writer && strcmp(p->writer, "text") != 0) return; /* plugins are not fuzzed here */
    lam_error err;
    lam_error_clear(&err);
    double ext = 0;
    for (int k = 0; k < 3; k++)
        if (md->stats.bbox[k + 3] - md->stats.bbox[k] > ext) ext = md->stats.bbox[k + 3] - md->stats.bbox[k];
    if (!(ext > 0)) return;
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    const double dir[3] = { 0.3, -0.2, 0.9 };
    if (oblique) lam_frame_direction(dir, &o.frame, &err);
    o.width = ext / layers;
    o.cut = (lam_cut)p->cut;
    lam_plan_opts po;
    lam_plan_opts_init(&po);
    lam_plan_opts_from_profile(&po, p);
    if (!(po.bead >= ext / 2000)) po.bead = ext / 2000;
    if (!(po.min_deposit < ext)) po.min_deposit = 0;
    if (po.perimeters > 3) po.perimeters = 3;
    lam_slicer *s = NULL;
    lam_writer *w = NULL;
    lam_sink sink;
    memset(&sink, 0, sizeof sink);
    if (lam_slicer_new(md, &o, &s, &err) == LAM_OK && lam_writer_memory(&w, &err) == LAM_OK &&
        lam_dialect_sink(&p->dialect, w, &sink, &err) == LAM_OK)
        (void)lam_plan_run(s, md, &po, &sink, NULL, NULL, &err);
    if (sink.destroy) sink.destroy(sink.ctx);
    if (w) lam_writer_abort(w);
    lam_slicer_free(s);
}

static lam_profile *builtin_sls, *builtin_ladrp;

static void init_profiles(void)
{
    if (builtin_sls) return;
    lam_error err;
    lam_profile_builtin_sls(&builtin_sls, &err);
    lam_profile_load_buf("fuzz-ladrp.yaml", ladrp_yaml, sizeof ladrp_yaml - 1, &builtin_ladrp, &err);
}

#ifdef LAMINA_FUZZ_LUA
/* A recipe may allocate 64 MB and run some millions of instructions. */
typedef struct budget {
    size_t used, limit;
} budget;

static void *alloc(void *ud, void *ptr, size_t osize, size_t nsize)
{
    budget *b = ud;
    size_t old = ptr ? osize : 0;
    if (nsize == 0) {
        free(ptr);
        b->used -= old;
        return NULL;
    }
    if (nsize > old && b->used - old + nsize > b->limit) return NULL;
    void *p = realloc(ptr, nsize);
    if (p) b->used = b->used - old + nsize;
    return p;
}

static void out_of_time(lua_State *L, lua_Debug *ar)
{
    (void)ar;
    luaL_error(L, "fuzz: instruction budget spent");
}

/* require: only "lamina" */
static int fuzz_require(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    if (strcmp(name, "lamina") != 0) return luaL_error(L, "fuzz: no module '%s'", name);
    lua_getglobal(L, "lamina");
    return 1;
}

/* print: checks its arguments' tostring like Lua's, writes nothing (the
 * driver's standard output is TAP) */
static int quiet_print(lua_State *L)
{
    int n = lua_gettop(L);
    for (int i = 1; i <= n; i++) luaL_tolstring(L, i, NULL);
    return 0;
}

static int run_lua(const char *text, size_t len)
{
    budget b = { 0, (size_t)64 << 20 };
    lua_State *L = lua_newstate(alloc, &b);
    if (!L) return 0;
    static const luaL_Reg libs[] = { { LUA_GNAME, luaopen_base },     { LUA_TABLIBNAME, luaopen_table },
                                     { LUA_STRLIBNAME, luaopen_string }, { LUA_MATHLIBNAME, luaopen_math },
                                     { LUA_UTF8LIBNAME, luaopen_utf8 }, { "lamina", luaopen_lamina },
                                     { NULL, NULL } };
    for (const luaL_Reg *l = libs; l->func; l++) {
        luaL_requiref(L, l->name, l->func, 1);
        lua_pop(L, 1);
    }
    /* no files, no bytecode: text chunks only */
    static const char *const gone[] = { "dofile", "loadfile", "load", NULL };
    for (int i = 0; gone[i]; i++) {
        lua_pushnil(L);
        lua_setglobal(L, gone[i]);
    }
    lua_pushcfunction(L, fuzz_require);
    lua_setglobal(L, "require");
    lua_pushcfunction(L, quiet_print);
    lua_setglobal(L, "print");
    /* no string.dump either: nothing to load it with, but keep it simple */
    lua_getglobal(L, "string");
    lua_pushnil(L);
    lua_setfield(L, -2, "dump");
    lua_pop(L, 1);
    lua_sethook(L, out_of_time, LUA_MASKCOUNT, 5000000);
    if (luaL_loadbufferx(L, text, len, "=fuzz.lua", "t") == LUA_OK) (void)lua_pcall(L, 0, 0, 0);
    lua_close(L);
    return 0;
}
#endif

/* A program read back, and its layers made in the axis frames and its own. */
static int run_program(const unsigned char *buf, size_t len)
{
    lam_error err;
    lam_error_clear(&err);
    lam_program *p = NULL;
    int rc = lam_program_read_buf("fuzz.sls", buf, len, &p, &err);
    for (size_t i = 0; p && i < p->nlayers; i++)
        for (int ax = 0; ax < 3; ax++) {
            lam_frame f;
            if (ax < 2) lam_frame_axis(ax ? 'x' : 'z', &f, NULL);
            else if (p->has_frame) f = p->frame;
            else break;
            lam_layer L;
            lam_error lerr;
            lam_error_clear(&lerr);
            if (lam_program_layer_make(p, i, &f, ax == 2 && p->frame_machine, "fuzz.sls", &L, &lerr) == LAM_OK)
                lam_layer_clear(&L);
            else if (lerr.msg[0] == '\0') rc = -1;
        }
    lam_program_free(p);
    return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
}

/* ---- part files ---- */
static uint64_t fnv(const uint8_t *b, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

static uint64_t le64(const uint8_t *b)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; i--) v = v << 8 | b[i];
    return v;
}

static void put64(uint8_t *b, uint64_t v)
{
    for (int i = 0; i < 8; i++) b[i] = (uint8_t)(v >> (8 * i));
}

/* Both FNV-1a hashes of a part (part.h) made to match its bytes, where
 * its header's strings leave room for them. */
static void fix_hashes(uint8_t *b, size_t n)
{
    size_t o = 48; /* magic, version, flags, identity, first, last, layers */
    /* the job's 4 strings, its 12 reals, the profile, the model, the
     * attribute count and keys */
    for (size_t k = 0, strings = 6; k < strings; k++) {
        if (o > n || n - o < 8 || le64(b + o) > n - o - 8) return;
        o += 8 + (size_t)le64(b + o);
        if (k == 3) o += 96;
        if (k == 5) {
            if (o > n || n - o < 8 || le64(b + o) > 64) return;
            strings += (size_t)le64(b + o);
            o += 8;
        }
    }
    if (o > n || n - o < 8) return;
    put64(b + o, fnv(b, o));
    if (n - o >= 8 + 9 && b[n - 9] == 'Z') put64(b + n - 8, fnv(b, n - 8));
}

/* A part checked whole, then joined into a program. */
static int run_part(const uint8_t *buf, size_t len)
{
    lam_error err;
    lam_error_clear(&err);
    lam_part *p = NULL;
    int rc = lam_part_open_buf("fuzz.part", buf, len, &p, &err);
    lam_profile *prof = NULL;
    lam_writer *w = NULL;
    lam_sink sink, none;
    memset(&sink, 0, sizeof sink);
    memset(&none, 0, sizeof none);
    double *layer_time = NULL;
    if (rc == LAM_OK) {
        /* a part of some layers only is joined all the same: replay starts at its first */
        lam_error oerr;
        lam_error_clear(&oerr);
        if (lam_part_order(&p, 1, &oerr) != LAM_OK && oerr.msg[0] == '\0') rc = -1;
        rc = rc ? rc : lam_part_join(&p, 1, &none, NULL, NULL, &err);
    }
    if (rc == LAM_OK) {
        const lam_part_meta *meta = lam_part_get_meta(p);
        lam_error perr;
        if (lam_profile_load_buf("fuzz.part (profile)", meta->profile, meta->profile_len, &prof, &perr) != LAM_OK) {
            prof = NULL;
        } else if (prof->writer && strcmp(prof->writer, "text") != 0) {
            lam_profile_free(prof); /* plugins are not fuzzed here */
            prof = NULL;
        }
        const lam_profile *use = prof ? prof : strcmp(lam_part_job(p)->process, "ladrp") ? builtin_sls : builtin_ladrp;
        lam_scan_time est;
        memset(&est, 0, sizeof est);
        layer_time = calloc(meta->layers, sizeof *layer_time);
        if (!use || !layer_time) rc = lam_error_nomem(&err, NULL);
        if (!rc) rc = lam_writer_memory(&w, &err);
        if (!rc) rc = lam_dialect_sink(&use->dialect, w, &sink, &err);
        if (!rc) rc = lam_part_join(&p, 1, &sink, &est, layer_time, &err);
    }
    if (sink.destroy) sink.destroy(sink.ctx);
    if (w) lam_writer_abort(w);
    free(layer_time);
    lam_profile_free(prof);
    lam_part_close(p);
    return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
}

/* A build job: read, placed and (when small) planned into memory. */
static int run_job(const char *buf, size_t len)
{
    lam_error err;
    lam_error_clear(&err);
    lam_build *b = NULL;
    lam_build_run *r = NULL;
    lam_writer *w = NULL;
    lam_sink sink = { 0 };
    int rc = lam_build_load_buf("fuzz.job", buf, len, &b, &err);
    if (!rc) rc = lam_build_run_new(b, NULL, &r, &err);
    size_t nparts = 0;
    if (!rc) lam_build_run_parts(r, &nparts);
    if (!rc && lam_build_run_layers(r) <= 64 && nparts <= 64) {
        rc = lam_writer_memory(&w, &err);
        if (!rc) rc = lam_program_sink(b->profile->writer, &b->profile->dialect, w, &sink, &err);
        lam_run_opts o = { .threads = 1 + (unsigned)(len & 1) };
        if (!rc) rc = lam_build_run_plan(r, &o, &sink, &err);
    }
    if (sink.destroy) sink.destroy(sink.ctx);
    lam_writer_abort(w);
    lam_build_run_free(r);
    lam_build_free(b);
    return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
}

/* The first byte picks the reader, the rest is the input. */
static int one(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    int kind = data[0] % K_COUNT;
    const char *buf = (const char *)data + 1;
    size_t len = size - 1;
    lam_error err;
    lam_error_clear(&err);
    lam_mesh m;
    lam_mesh_init(&m);
    int rc = LAM_OK;
    init_profiles();
    switch (kind) {
    case K_UG: rc = lam_import_ug_buf("fuzz.ug", buf, len, &m, &err); break;
    case K_STL: rc = lam_import_stl_buf("fuzz.stl", (const unsigned char *)buf, len, &m, NULL, &err); break;
    case K_OBJ: rc = lam_import_obj_buf("fuzz.obj", buf, len, &m, &err); break;
    case K_PROFILE: {
        lam_profile *p = NULL;
        rc = lam_profile_load_buf("fuzz.yaml", buf, len, &p, &err);
        if (rc == LAM_OK) {
            /* its templates and raster settings, on the thesis's part */
            lam_mesh cm;
            lam_mesh_init(&cm);
            lam_model *md = NULL;
            lam_error cerr;
            if (lam_import_ug_buf("cube.ug", cube_hole, sizeof cube_hole - 1, &cm, &cerr) == LAM_OK &&
                lam_model_from_mesh(&cm, "cube", "unigrafix", &md, &cerr) == LAM_OK)
                plan(md, p, 5, (int)(size & 1));
            lam_mesh_free(&cm);
            lam_model_free(md);
        }
        lam_profile_free(p);
        return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
    }
    case K_JOB: return run_job(buf, len);
    case K_PROGRAM:
    case K_PART: {
        /* a heap copy of exactly the input: a read past it is caught */
        uint8_t *copy = malloc(len ? len : 1);
        if (!copy) return 0;
        memcpy(copy, buf, len);
        if (kind == K_PART && size % 4 != 0) fix_hashes(copy, len);
        rc = kind == K_PART ? run_part(copy, len) : run_program(copy, len);
        free(copy);
        return rc;
    }
    default:
#ifdef LAMINA_FUZZ_LUA
        return run_lua(buf, len);
#else
        return 0;
#endif
    }
    if (rc == LAM_OK && m.ntris) {
        /* what loads must also build: weld, edges, shells, orientation */
        lam_model *md = NULL;
        rc = lam_model_from_mesh(&m, "fuzz", "fuzz", &md, &err);
        /* ... and slice, straight and oblique, whatever shape it has */
        for (int axis = 0; md && axis < 2; axis++) {
            lam_slice_opts o;
            lam_slice_opts_init(&o);
            const double oblique[3] = { 0.3, -0.2, 0.9 };
            if (axis) lam_frame_direction(oblique, &o.frame, &err);
            o.fill_nonzero = (int)(size & 1);
            double ext = 0;
            for (int k = 0; k < 3; k++)
                if (md->stats.bbox[k + 3] - md->stats.bbox[k] > ext) ext = md->stats.bbox[k + 3] - md->stats.bbox[k];
            o.width = ext > 0 && ext < 1e300 ? ext / 7 : 1;
            lam_slicer *s = NULL;
            lam_error serr;
            if (lam_slicer_new(md, &o, &s, &serr) == LAM_OK) {
                lam_layer *L;
                while (lam_slicer_next(s, &L, &serr) == LAM_OK && L) lam_layer_free(L);
            }
            lam_slicer_free(s);
        }
        /* ... and plan, both processes */
        if (md && builtin_sls) plan(md, builtin_sls, 3, 0);
        if (md && builtin_ladrp) plan(md, builtin_ladrp, 3, (int)(size & 1));
        lam_model_free(md);
    }
    lam_mesh_free(&m);
    /* a failure always says what went wrong */
    return rc != LAM_OK && err.msg[0] == '\0' ? -1 : 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)one(data, size);
    return 0;
}

#ifndef LAMINA_LIBFUZZER
static uint64_t rng = 0x9e3779b97f4a7c15ull;
static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static size_t mutate(uint8_t *b, size_t n, size_t cap)
{
    int ops = 1 + (int)(next() % 4);
    for (int k = 0; k < ops; k++) {
        size_t body = n > 1 ? n - 1 : 1; /* keep byte 0: the reader */
        size_t at = 1 + (size_t)(next() % body);
        switch (next() % 7) {
        case 0: if (at < n) b[at] ^= (uint8_t)(1u << (next() % 8)); break;
        case 1: if (at < n) b[at] = (uint8_t)next(); break;
        case 2: /* insert a byte from a small alphabet of troublemakers */
            if (n < cap && at <= n) {
                static const char alpha[] = " ;(){}/*\n-.0123456789eEnaif:#\"'[]";
                memmove(b + at + 1, b + at, n - at);
                b[at] = (uint8_t)alpha[next() % (sizeof alpha - 1)];
                n++;
            }
            break;
        case 3: /* delete a span */
            if (at < n) {
                size_t len = 1 + (size_t)(next() % 16);
                if (at + len > n) len = n - at;
                memmove(b + at, b + at + len, n - at - len);
                n -= len;
            }
            break;
        case 4: if (at < n) n = at; break; /* truncate */
        case 5: /* duplicate a span */
            if (at < n) {
                size_t len = 1 + (size_t)(next() % 64);
                if (at + len > n) len = n - at;
                if (n + len <= cap) {
                    memmove(b + at + len, b + at, n - at);
                    n += len;
                }
            }
            break;
        default: /* overwrite 4 bytes: counts in binary STL, huge numbers in text */
            for (int i = 0; i < 4 && at + i < n; i++) b[at + i] = (uint8_t)next();
        }
    }
    return n;
}

int main(int argc, char **argv)
{
    int mutants = 2000, failed = 0, t = 0;
    const char *env = getenv("LAMINA_FUZZ_MUTANTS");
    if (env) mutants = atoi(env);
    for (int i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        if (!f) {
            printf("not ok %d - cannot open %s\n", ++t, argv[i]);
            failed++;
            continue;
        }
        uint8_t *seed = malloc(1 << 20);
        size_t n = fread(seed, 1, 1 << 20, f);
        fclose(f);
        size_t cap = n + 4096;
        uint8_t *b = malloc(cap);
        /* a seed's mutants depend on it alone (not on the seeds before it) */
        rng = fnv(seed, n) | 1;
        /* the seed itself from an exact-size copy too */
        uint8_t *whole = malloc(n ? n : 1);
        memcpy(whole, seed, n);
        int bad = one(whole, n) != 0;
        free(whole);
        for (int k = 0; k < mutants && !bad; k++) {
            memcpy(b, seed, n);
            size_t m = mutate(b, n, cap);
            /* exact-size heap copy: ASan sees any read past the end */
            uint8_t *exact = malloc(m ? m : 1);
            memcpy(exact, b, m);
            bad = one(exact, m) != 0;
            free(exact);
        }
        printf("%s %d - %s and %d mutants: loaded or refused with a message\n", bad ? "not ok" : "ok", ++t, argv[i],
               mutants);
        fflush(stdout); /* what passed shows even if a sanitizer stops the next */
        failed += bad;
        free(seed);
        free(b);
    }
    printf("1..%d\n", t);
    return failed ? 1 : 0;
}
#endif
