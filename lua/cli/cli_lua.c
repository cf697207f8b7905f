/* lamina run / lamina -e, and the host of lamina repl: a Lua 5.4 state with the lamina
 * module, in the manner of lua.c (arg table, traceback on errors, Ctrl-C
 * interrupts the running code). */
#include "cli_lua.h"
#include "cli_signal.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include <lauxlib.h>
#include <lualib.h>

#include "cli.h"
#include "cli_args.h"
#include "l_common.h"
#include "paths.h"
#include "writer.h"

LUAMOD_API int luaopen_lamina(lua_State *L);

/* ---- the state ------------------------------------------------------------- */

static int init_state(lua_State *L)
{
    luaL_openlibs(L);
    luaL_requiref(L, "lamina", luaopen_lamina, 1);
    lua_pop(L, 1);
    /* lamina's own Lua modules first (the build tree's, an installed tree's) */
    char *dirs[4];
    void **box = lam_lua_newbox(L); /* the C string below, freed even on a memory error */
    size_t n = lam_lua_dirs(dirs, 4), len = 1;
    for (size_t i = 0; i < n; i++) len += 2 * strlen(dirs[i]) + 20;
    char *path = malloc(len);
    if (path) {
        size_t k = 0;
        path[0] = '\0';
        for (size_t i = 0; i < n; i++)
            k += (size_t)snprintf(path + k, len - k, "%s/?.lua;%s/?/init.lua;", dirs[i], dirs[i]);
    }
    for (size_t i = 0; i < n; i++) free(dirs[i]);
    *box = path;
    if (!path) return luaL_error(L, "not enough memory");
    lua_getglobal(L, "package");
    lua_pushstring(L, path);
    lua_getfield(L, -2, "path");
    lua_concat(L, 2);
    lua_setfield(L, -2, "path");
    return 0;
}

lua_State *lam_cli_newstate(void)
{
    lua_State *L = luaL_newstate();
    if (!L) {
        fprintf(stderr, "lamina: cannot create a Lua state: not enough memory\n");
        return NULL;
    }
    lua_pushcfunction(L, init_state);
    if (lua_pcall(L, 0, 0, 0) != LUA_OK) {
        fprintf(stderr, "lamina: %s\n", lua_tostring(L, -1));
        lua_close(L);
        return NULL;
    }
    return L;
}

/* ---- calls, interrupts, errors -------------------------------------------- */

static lua_State *globalL;
/* Set by a Ctrl-C during any lam_cli_docall of this process: `run` and
 * `-e` end by SIGINT once the state is closed (finalizers ran, outputs
 * aborted), as every other command does, so a shell loop calling lamina
 * stops too. The recipe still sees the error first, so it may clean up. */
static volatile sig_atomic_t interrupted_once;

/* The hook set by laction. It stays armed, on Lua instructions only (a
 * count hook never runs inside C functions such as the message handler),
 * until lam_cli_docall returns: an "interrupted" raised where Lua discards
 * errors (a finalizer) or caught by the script's own pcall is raised
 * again. lam_lua_interrupt stays set as well, so the binding's loops stop. */
static void lstop(lua_State *L, lua_Debug *ar)
{
    (void)ar;
    lua_sethook(L, lstop, LUA_MASKCOUNT, 1);
    luaL_error(L, "interrupted");
}

/* SIGINT while Lua runs: stop at the next instruction or call (hook) or the
 * next layer (the binding polls lam_lua_interrupt). A second Ctrl-C before
 * the first is noticed (a long C call) ends the process as any other
 * interrupt does: temporary files removed. */
static void laction(int sig)
{
    if (lam_lua_interrupt) cli_fatal_signal(sig);
    lam_lua_interrupt = 1;
    interrupted_once = 1;
    lua_sethook(globalL, lstop, LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT, 1);
}

/* As lua.c: a string gets a traceback; an object with __tostring is a
 * message already (a recipe's option error from lamina.args): it is kept
 * as it is, so the reporter can read its exit code too. */
static int msghandler(lua_State *L)
{
    const char *msg = lua_tostring(L, 1);
    if (msg == NULL) {
        if (luaL_getmetafield(L, 1, "__tostring") != LUA_TNIL) {
            lua_pop(L, 1);
            lua_settop(L, 1);
            return 1;
        }
        msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    }
    luaL_traceback(L, L, msg, 1);
    return 1;
}

int lam_cli_docall(lua_State *L, int narg, int nres)
{
    int base = lua_gettop(L) - narg;
    lua_pushcfunction(L, msghandler);
    lua_insert(L, base);
    globalL = L;
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = laction;
    sigemptyset(&sa.sa_mask);
    lam_lua_interrupt = 0;
    /* SIGINT ignored when lamina started (nohup, a background job of a
     * script) stays ignored, as for every other command */
    int take = sigaction(SIGINT, NULL, &old) == 0 && old.sa_handler != SIG_IGN;
    if (take) sigaction(SIGINT, &sa, &old);
    int status = lua_pcall(L, narg, nres, base);
    if (take) sigaction(SIGINT, &old, NULL);
    lua_sethook(L, NULL, 0, 0);
    lam_lua_interrupt = 0;
    lua_remove(L, base);
    return status;
}

static int tostring_protected(lua_State *L)
{
    luaL_tolstring(L, 1, NULL);
    return 1;
}

int lam_cli_report(lua_State *L, int prefix)
{
    int code = EXIT_INPUT, top = lua_gettop(L);
    if (lua_type(L, -1) == LUA_TTABLE) {
        lua_getfield(L, -1, "exit");
        int isint = 0;
        lua_Integer e = lua_tointegerx(L, -1, &isint);
        if (isint && e > 0 && e < 126) code = (int)e;
        lua_pop(L, 1);
    }
    const char *msg = lua_tostring(L, -1);
    if (!msg) {
        /* __tostring runs protected: a failing one is not our crash */
        lua_pushcfunction(L, tostring_protected);
        lua_pushvalue(L, -2);
        if (lua_pcall(L, 1, 1, 0) == LUA_OK) msg = lua_tostring(L, -1);
    }
    if (!msg) msg = "(error object is not a string)";
    fprintf(stderr, "%s%s\n", prefix ? "lamina: " : "", msg);
    fflush(stderr);
    lua_settop(L, top - 1);
    return code;
}

/* arg = { [-2] = "lamina", [-1] = cmd, [0] = script, args... } as lua.c does. */
static void set_arg(lua_State *L, const char *cmd, const char *script, int argc, char **argv)
{
    lua_createtable(L, argc, 3);
    lua_pushliteral(L, "lamina");
    lua_rawseti(L, -2, -2);
    lua_pushstring(L, cmd);
    lua_rawseti(L, -2, -1);
    lua_pushstring(L, script);
    lua_rawseti(L, -2, 0);
    for (int i = 0; i < argc; i++) {
        lua_pushstring(L, argv[i]);
        lua_rawseti(L, -2, i + 1);
    }
    lua_setglobal(L, "arg");
}

/* ---- lamina run ---------------------------------------------------------- */

static const char run_usage[] =
    "usage: lamina run [--safe [--allow DIR]... [--out DIR]... [--memory SIZE] [--time SECONDS]]\n"
    "                  [-j N] RECIPE.lua [ARGS...]\n"
    "Run a Lua recipe with the lamina module loaded (global `lamina`, or\n"
    "require \"lamina\"). ARGS are in the table `arg` (arg[0] is the recipe,\n"
    "arg[1] the first argument) and in `...`, as with lua. RECIPE '-' reads\n"
    "the recipe from standard input. Exit code 1 when the recipe fails.\n"
    "  -j, --jobs N   threads machine:plan uses when the recipe gives none\n"
    "                 (lamina.threads(); default: LAMINA_THREADS, else 1)\n"
    "  --safe      run it sandboxed: no os.execute, io.popen, C modules, debug\n"
    "              library or bytecode; files only in these directories:\n"
    "  --allow DIR    may be read (any number of them)\n"
    "  --out DIR      may be read and written (created if missing)\n"
    "  --memory SIZE  memory limit of Lua and lamina's models, slicings and\n"
    "                 plans together (default 256M; 0: none)\n"
    "  --time SECONDS run time limit (default 60; 0: none)\n";

typedef struct runargs {
    const char *script;
    int argc;
    char **argv;
    int status;
    int safe;
    int (*body)(lua_State *L); /* lam_cli_host's */
    unsigned threads;          /* lamina.threads(): machine:plan's default */
} runargs;

/* In a sandbox: the recipe's os.exit(n), or a memory error said plainly. */
static int report_safe(lua_State *L)
{
    int code;
    if (lam_lua_sandbox_exit(L, &code)) {
        lua_pop(L, 1);
        return code;
    }
    char buf[200];
    const char *mem = lua_type(L, -1) == LUA_TSTRING && strstr(lua_tostring(L, -1), "not enough memory")
                          ? lam_lua_sandbox_memory_error(L, buf, sizeof buf)
                          : NULL;
    if (mem) {
        lua_pop(L, 1);
        lua_pushstring(L, mem);
    }
    return lam_cli_report(L, 1);
}

static int run_main(lua_State *L)
{
    runargs *a = lua_touserdata(L, 1);
    set_arg(L, "run", a->script, a->argc, a->argv);
    lam_lua_set_threads(L, a->threads);
    const char *fname = strcmp(a->script, "-") == 0 ? NULL : a->script;
    /* sandboxed: source text only, never bytecode */
    if (luaL_loadfilex(L, fname, a->safe ? "t" : NULL) != LUA_OK) {
        lam_cli_report(L, 1);
        a->status = EXIT_INPUT;
        return 0;
    }
    luaL_checkstack(L, a->argc + 5, "too many arguments to the recipe");
    for (int i = 0; i < a->argc; i++) lua_pushstring(L, a->argv[i]);
    if (a->safe) lam_lua_sandbox_start(L);
    if (lam_cli_docall(L, a->argc, 0) != LUA_OK) a->status = a->safe ? report_safe(L) : lam_cli_report(L, 1);
    return 0;
}

/* Run f(ud) protected in L (a new plain state when L is NULL), and close L. */
static int protected_run(lua_State *L, lua_CFunction f, void *ud)
{
    int sandboxed = L != NULL;
    if (!L && !(L = lam_cli_newstate())) return EXIT_INPUT;
    runargs *a = ud;
    a->status = EXIT_OK;
    lua_pushcfunction(L, f);
    lua_pushlightuserdata(L, ud);
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) {
        lam_cli_report(L, 1);
        a->status = EXIT_INPUT;
    }
    if (sandboxed) lam_lua_sandbox_close(L);
    else lua_close(L);
    return a->status;
}

/* A command whose Lua code was interrupted ends by SIGINT (status 130 in a
 * shell) after what it printed is flushed; else it returns rc. */
static int end_run(int rc)
{
    if (!interrupted_once) return rc;
    fflush(stdout);
    cli_fatal_signal(SIGINT);
    return rc;
}

/* The last resort of --time: Lua's own C functions (a string pattern that
 * backtracks for ever) never reach the hook. Two seconds after the
 * limit, the process ends, temporary files removed. */
static void watchdog(int sig)
{
    (void)sig;
    static const char msg[] = "lamina: time limit exceeded (the recipe did not stop; ended)\n";
    ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)w;
    lam_writer_unlink_temps();
    _exit(EXIT_INPUT);
}

/* A size in bytes with an optional k, M, G or T (powers of 1024); -1 when
 * malformed. */
static double parse_bytes(const char *s)
{
    char *end;
    double x = strtod(s, &end);
    if (end == s || !(x >= 0) || !isfinite(x)) return -1;
    const char *units = "kMGT", *u = *end ? strchr(units, *end == 'K' ? 'k' : *end) : NULL;
    if (*end && (!u || end[1])) return -1;
    for (const char *p = units; u && p <= u; p++) x *= 1024;
    return x;
}

int cmd_run(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        fputs(run_usage, stdout);
        return EXIT_OK;
    }
    lam_sandbox_opts so;
    memset(&so, 0, sizeof so);
    so.memory = 256.0 * 1024 * 1024;
    so.time = 60;
    so.open_lamina = luaopen_lamina;
    const char *allow[64], *out[64];
    so.allow = allow;
    so.out = out;
    int i = 1, safe = 0, limits = 0;
    unsigned threads = 0;
    for (; i < argc && argv[i][0] == '-' && argv[i][1]; i++) {
        const char *o = argv[i];
        if (!strcmp(o, "--safe")) {
            safe = 1;
            continue;
        }
        if (!strcmp(o, "-j") || !strcmp(o, "--jobs")) {
            if (i + 1 >= argc) return cli_usage("run", "option %s needs a value", o);
            int rc = cli_threads_arg("run", o, argv[++i], &threads);
            if (rc) return rc;
            continue;
        }
        if (strcmp(o, "--allow") && strcmp(o, "--out") && strcmp(o, "--memory") && strcmp(o, "--time"))
            return cli_usage("run", "unknown option '%s' (options go before the recipe)", o);
        if (i + 1 >= argc) return cli_usage("run", "option %s needs a value", o);
        const char *v = argv[++i];
        limits = 1;
        if (!strcmp(o, "--allow") || !strcmp(o, "--out")) {
            size_t *n = o[2] == 'a' ? &so.nallow : &so.nout;
            if (*n == 64) return cli_usage("run", "at most 64 %s directories", o);
            (o[2] == 'a' ? allow : out)[(*n)++] = v;
        } else if (!strcmp(o, "--memory")) {
            if ((so.memory = parse_bytes(v)) < 0)
                return cli_usage("run", "--memory takes a size in bytes, such as 512M (got '%s')", v);
        } else {
            char *end;
            so.time = strtod(v, &end);
            if (end == v || *end || !(so.time >= 0) || !isfinite(so.time) || so.time > 1e6)
                return cli_usage("run", "--time takes a number of seconds (got '%s')", v);
        }
    }
    if (limits && !safe) return cli_usage("run", "--allow, --out, --memory and --time go with --safe");
    if (i >= argc) return cli_usage("run", "no recipe given");
    int rc = threads ? 0 : cli_threads_env("run", 1, &threads);
    if (rc) return rc;
    runargs a = { argv[i], argc - i - 1, argv + i + 1, EXIT_OK, safe, NULL, threads };
    if (!safe) return end_run(protected_run(NULL, run_main, &a));
    char msg[1024];
    lua_State *L = lam_lua_sandbox_open(&so, msg, sizeof msg);
    if (!L) return cli_usage("run", "%s", msg);
    struct itimerval t;
    memset(&t, 0, sizeof t);
    if (so.time > 0) {
        double at = so.time + 2;
        t.it_value.tv_sec = (time_t)at;
        t.it_value.tv_usec = (suseconds_t)((at - floor(at)) * 1e6);
        signal(SIGALRM, watchdog);
        setitimer(ITIMER_REAL, &t, NULL);
    }
    rc = protected_run(L, run_main, &a);
    memset(&t, 0, sizeof t);
    setitimer(ITIMER_REAL, &t, NULL);
    return end_run(rc);
}

/* ---- lamina -e ------------------------------------------------------------- */

static int eval_main(lua_State *L)
{
    runargs *a = lua_touserdata(L, 1);
    set_arg(L, "-e", "", 0, NULL);
    lam_lua_set_threads(L, a->threads);
    for (int i = 1; i < a->argc; i += 2) {
        const char *code = a->argv[i];
        if (luaL_loadbuffer(L, code, strlen(code), "=(command line)") != LUA_OK ||
            lam_cli_docall(L, 0, 0) != LUA_OK) {
            a->status = lam_cli_report(L, 1);
            return 0;
        }
    }
    return 0;
}

int cmd_eval(int argc, char **argv)
{
    for (int i = 0; i < argc; i += 2) {
        if (strcmp(argv[i], "-e") != 0) return cli_usage(NULL, "unexpected '%s' after -e CODE (give -e CODE ...)", argv[i]);
        if (i + 1 >= argc) return cli_usage(NULL, "-e needs Lua code");
    }
    runargs a = { "", argc, argv, EXIT_OK, 0, NULL, 1 };
    int rc = cli_threads_env(NULL, 1, &a.threads);
    return rc ? rc : end_run(protected_run(NULL, eval_main, &a));
}

/* ---- the host of other Lua commands (lamina repl) ------------------------- */

static int host_main(lua_State *L)
{
    runargs *a = lua_touserdata(L, 1);
    set_arg(L, a->script, "", 0, NULL);
    lam_lua_set_threads(L, a->threads);
    a->status = a->body(L);
    return 0;
}

int lam_cli_host(const char *cmd, int (*body)(lua_State *L))
{
    runargs a = { cmd, 0, NULL, EXIT_OK, 0, body, 1 };
    int rc = cli_threads_env(cmd, 1, &a.threads);
    return rc ? rc : protected_run(NULL, host_main, &a);
}
