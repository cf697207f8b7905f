/* The interactive prompt (`lamina repl`): lua.c's read-eval-print loop with
 * lamina loaded.
 *
 * - A line is first tried as an expression (`return LINE;`) whose values
 *   are printed; `=expr` is `return expr`. Otherwise it is a statement; one
 *   that is incomplete (its syntax error ends in "<eof>") continues on the
 *   next line, as in lua.c.
 * - Line editing and history come from GNU readline or libedit, loaded at
 *   run time with dlopen (so the executable links neither, and runs
 *   without them: plain line input). $LAMINA_READLINE names the library to
 *   try ("none": no line editing). History is kept in $LAMINA_HISTORY or
 *   ~/.lamina_history.
 * - Ctrl-C while a command runs raises "interrupted" in it (lam_cli_docall);
 *   at the prompt it abandons the line (and any unfinished statement). The
 *   line editor's own signal handling is turned off (rl_catch_signals = 0,
 *   as Python does) and its character input goes through ed_getc, which
 *   ends the line when SIGINT arrives.
 *
 * - help(x) (help.h) prints lua/API.md's entry for x; Tab completes names,
 *   fields and methods (complete.h) through the editor's
 *   rl_attempted_completion_function, when the library has it.
 *
 * - A table result prints as lamina.show's summary of it (lua/lamina/show.lua:
 *   sorted keys, depth, length and size limits); one with __tostring or
 *   __name, and every other value, as print shows it.
 *
 * Without a terminal on standard input there is no prompt and no banner:
 * statements are read line by line and values printed, so the loop can be
 * driven from a pipe. */
#include "repl.h"

#include <dlfcn.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <unistd.h>

#include <lauxlib.h>

#include "cli.h"
#include "cli_lua.h"
#include "complete.h"
#include "help.h"
#include "l_common.h"

#define PROMPT1 "> "
#define PROMPT2 ">> "
#define EOFMARK "<eof>"
#define HISTORY_LINES 1000

enum { LINE_EOF = -1, LINE_INTERRUPTED = -2 };

/* ---- the line editor (dlopen) ------------------------------------------- */

typedef struct editor {
    void *lib;
    const char *name;
    char *(*readline)(const char *);
    void (*add_history)(const char *);
    int (*read_history)(const char *);
    int (*write_history)(const char *);
    int (*history_truncate_file)(const char *, int);
    void (*stifle_history)(int);
    int *catch_signals;
    int (**getc_function)(FILE *);
    const char **readline_name;
    /* completion (complete.h) */
    char **(**attempted_completion)(const char *, int, int);
    const char **word_breaks;
    int *append_character;
    int *completion_over;
} editor;

static volatile sig_atomic_t prompt_interrupted = 0;

static void prompt_action(int sig)
{
    (void)sig;
    prompt_interrupted = 1;
}

/* The editor's character input: one byte from the terminal, or a newline
 * that ends the line once SIGINT has arrived (pselect with SIGINT unblocked
 * only while waiting, so no signal slips in between test and wait). */
static int ed_getc(FILE *f)
{
    int fd = fileno(f);
    sigset_t block, orig;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    for (;;) {
        sigprocmask(SIG_BLOCK, &block, &orig);
        if (prompt_interrupted) {
            sigprocmask(SIG_SETMASK, &orig, NULL);
            return '\n';
        }
        fd_set rd;
        FD_ZERO(&rd);
        FD_SET(fd, &rd);
        int r = pselect(fd + 1, &rd, NULL, NULL, NULL, &orig);
        sigprocmask(SIG_SETMASK, &orig, NULL);
        if (r < 0) {
            if (errno == EINTR) continue;
            return EOF;
        }
        unsigned char c;
        ssize_t n = read(fd, &c, 1);
        if (n == 1) return c;
        if (n == 0 || errno != EINTR) return EOF;
    }
}

/* ---- Tab completion ------------------------------------------------------ */

static lua_State *complete_L;   /* the REPL's state, for the editor's callback */
static editor *complete_ed;

/* The editor's completion hook: lam_complete's names, in the form it
 * wants (the common prefix first, then the matches; one match alone), and
 * never file names. */
static char **ed_complete(const char *text, int start, int end)
{
    (void)start;
    (void)end;
    if (complete_ed->append_character) *complete_ed->append_character = 0;
    if (complete_ed->completion_over) *complete_ed->completion_over = 1;
    char **m = complete_L ? lam_complete(complete_L, text) : NULL;
    if (!m) return NULL;
    size_t n = 0;
    while (m[n]) n++;
    char **out = malloc((n + 2) * sizeof *out);
    size_t common = strlen(m[0]);
    for (size_t i = 1; i < n; i++) {
        size_t k = 0;
        while (k < common && m[i][k] == m[0][k]) k++;
        common = k;
    }
    char *prefix = n > 1 ? strndup(m[0], common) : NULL;
    if (!out || (n > 1 && !prefix)) {
        for (size_t i = 0; i < n; i++) free(m[i]);
        free(m);
        free(out);
        free(prefix);
        return NULL;
    }
    if (n == 1) {
        out[0] = m[0];
        out[1] = NULL;
    } else {
        out[0] = prefix;
        memcpy(out + 1, m, n * sizeof *m);
        out[n + 1] = NULL;
    }
    free(m);
    return out;
}

#define SYM(field, name) (*(void **)(&ed->field) = dlsym(ed->lib, name))

static int try_editor(editor *ed, const char *lib)
{
    ed->lib = dlopen(lib, RTLD_NOW | RTLD_LOCAL);
    if (!ed->lib) return 0;
    SYM(readline, "readline");
    SYM(add_history, "add_history");
    if (!ed->readline || !ed->add_history) {
        dlclose(ed->lib);
        memset(ed, 0, sizeof *ed);
        return 0;
    }
    SYM(read_history, "read_history");
    SYM(write_history, "write_history");
    SYM(history_truncate_file, "history_truncate_file");
    SYM(stifle_history, "stifle_history");
    ed->catch_signals = dlsym(ed->lib, "rl_catch_signals");
    ed->getc_function = dlsym(ed->lib, "rl_getc_function");
    ed->readline_name = dlsym(ed->lib, "rl_readline_name");
    ed->attempted_completion = dlsym(ed->lib, "rl_attempted_completion_function");
    ed->word_breaks = dlsym(ed->lib, "rl_completer_word_break_characters");
    ed->append_character = dlsym(ed->lib, "rl_completion_append_character");
    ed->completion_over = dlsym(ed->lib, "rl_attempted_completion_over");
    ed->name = lib;
    if (ed->catch_signals) *ed->catch_signals = 0;
    if (ed->getc_function) *ed->getc_function = ed_getc;
    if (ed->readline_name) *ed->readline_name = "lamina";
    if (ed->attempted_completion && ed->word_breaks) {
        complete_ed = ed;
        *ed->attempted_completion = ed_complete;
        *ed->word_breaks = lam_complete_breaks;
    }
    if (ed->stifle_history) ed->stifle_history(HISTORY_LINES);
    return 1;
}

static void load_editor(editor *ed)
{
    memset(ed, 0, sizeof *ed);
    const char *want = getenv("LAMINA_READLINE");
    if (want && *want) {
        if (strcmp(want, "none") != 0) try_editor(ed, want);
        return;
    }
    static const char *const libs[] = { "libreadline.so.8", "libreadline.so", "libedit.so.2", NULL };
    for (int i = 0; libs[i] && !try_editor(ed, libs[i]); i++) {
    }
}

/* The history file (malloc'd), or NULL when disabled. */
static char *history_path(void)
{
    const char *p = getenv("LAMINA_HISTORY");
    if (p) return *p ? strdup(p) : NULL;
    const char *home = getenv("HOME");
    if (!home || !*home) return NULL;
    size_t n = strlen(home) + 32;
    char *path = malloc(n);
    if (path) snprintf(path, n, "%s/.lamina_history", home);
    return path;
}

/* ---- reading statements (lua.c's pushline / addreturn / multiline) ------ */

typedef struct repl {
    lua_State *L;
    int base;                /* stack slot of the current statement */
    int tty;
    editor ed;
    int first_eq;            /* the statement was typed as "=expr" */
} repl;

static const char *get_prompt(lua_State *L, int firstline)
{
    if (lua_getglobal(L, firstline ? "_PROMPT" : "_PROMPT2") == LUA_TNIL) {
        lua_pop(L, 1);
        lua_pushstring(L, firstline ? PROMPT1 : PROMPT2);
    } else {
        luaL_tolstring(L, -1, NULL); /* the prompt may be any value */
        lua_remove(L, -2);
    }
    return lua_tostring(L, -1);
}

/* Read one line and push it (with `=` turned into `return`). Returns 1, or
 * LINE_EOF, or LINE_INTERRUPTED (Ctrl-C at the prompt). */
static int pushline(repl *r, int firstline)
{
    lua_State *L = r->L;
    const char *prompt = get_prompt(L, firstline);
    void **box = lam_lua_newbox(L); /* the line, freed whatever happens */
    prompt_interrupted = 0;
    char *line;
    if (r->ed.readline) {
        line = r->ed.readline(prompt);
        *box = line;
    } else {
        if (r->tty) {
            fputs(prompt, stdout);
            fflush(stdout);
        }
        size_t cap = 0;
        line = NULL;
        ssize_t n = getline(&line, &cap, stdin);
        *box = line;
        if (n < 0) {
            line = NULL;
            if (prompt_interrupted) clearerr(stdin);
        }
    }
    int result = 1;
    if (prompt_interrupted) {
        if (!r->ed.readline && r->tty) fputc('\n', stdout);
        result = LINE_INTERRUPTED;
    } else if (!line) {
        result = LINE_EOF;
    } else {
        size_t len = strlen(line);
        if (len > 0 && line[len - 1] == '\n') line[--len] = '\0';
        if (firstline) r->first_eq = line[0] == '=';
        if (firstline && line[0] == '=') lua_pushfstring(L, "return %s", line + 1);
        else lua_pushlstring(L, line, len);
        lua_replace(L, -3); /* over the prompt */
    }
    free(*box);
    *box = NULL;
    lua_pop(L, result == 1 ? 1 : 2);
    return result;
}

static void saveline(repl *r, const char *line)
{
    if (!r->ed.add_history || !line[0]) return;
    if (r->first_eq && strncmp(line, "return ", 7) == 0) {
        lua_pushfstring(r->L, "=%s", line + 7);
        r->ed.add_history(lua_tostring(r->L, -1));
        lua_pop(r->L, 1);
    } else {
        r->ed.add_history(line);
    }
}

/* The statement at base as an expression: pushes the compiled chunk and
 * returns LUA_OK, or pushes nothing and returns an error status. */
static int addreturn(repl *r)
{
    lua_State *L = r->L;
    const char *line = lua_tostring(L, -1);
    const char *retline = lua_pushfstring(L, "return %s;", line);
    int status = luaL_loadbuffer(L, retline, strlen(retline), "=stdin");
    if (status == LUA_OK) {
        lua_remove(L, -2);
        saveline(r, line);
    } else {
        lua_pop(L, 2);
    }
    return status;
}

static int incomplete(lua_State *L, int status)
{
    if (status == LUA_ERRSYNTAX) {
        size_t lmsg;
        const char *msg = lua_tolstring(L, -1, &lmsg);
        size_t mark = sizeof EOFMARK - 1;
        if (lmsg >= mark && strcmp(msg + lmsg - mark, EOFMARK) == 0) {
            lua_pop(L, 1);
            return 1;
        }
    }
    return 0;
}

/* The statement at base, with continuation lines while it is incomplete. */
static int multiline(repl *r)
{
    lua_State *L = r->L;
    for (;;) {
        size_t len;
        const char *line = lua_tolstring(L, r->base, &len);
        int status = luaL_loadbuffer(L, line, len, "=stdin");
        if (!incomplete(L, status)) {
            saveline(r, line);
            return status;
        }
        int got = pushline(r, 0);
        if (got == LINE_INTERRUPTED) return LINE_INTERRUPTED;
        if (got == LINE_EOF) { /* report the unfinished statement */
            saveline(r, line);
            return luaL_loadbuffer(L, line, len, "=stdin");
        }
        lua_pushliteral(L, "\n");
        lua_insert(L, -2);
        lua_concat(L, 3);
    }
}

/* Read and compile one statement: LUA_OK with the chunk on the stack, an
 * error status with the message, LINE_EOF or LINE_INTERRUPTED. */
static int loadline(repl *r)
{
    lua_State *L = r->L;
    lua_settop(L, r->base - 1);
    int got = pushline(r, 1);
    if (got != 1) return got;
    int status = addreturn(r);
    if (status != LUA_OK) status = multiline(r);
    lua_remove(L, r->base);
    if (status == LINE_INTERRUPTED) lua_settop(L, r->base - 1);
    return status;
}

/* ---- printing results ---------------------------------------------------- */

#define SHOW_KEY "lamina.repl.show" /* registry: lamina.show's value function */

/* Keep lamina.show.value for printing tables (lua/lamina/show.lua),
 * required once when the prompt starts, so a script that changes require
 * or package.path later does not change how results print. */
static int load_show(lua_State *L)
{
    lua_getglobal(L, "require");
    lua_pushliteral(L, "lamina.show");
    lua_call(L, 1, 1);
    lua_getfield(L, -1, "value");
    luaL_checktype(L, -1, LUA_TFUNCTION);
    lua_setfield(L, LUA_REGISTRYINDEX, SHOW_KEY);
    return 0;
}

/* A table that has no text of its own: no __tostring, no __name (a layer
 * list has both, and prints its summary through __tostring). */
static int plain_table(lua_State *L, int i)
{
    if (lua_type(L, i) != LUA_TTABLE) return 0;
    for (int k = 0; k < 2; k++) {
        if (luaL_getmetafield(L, i, k ? "__name" : "__tostring") != LUA_TNIL) {
            lua_pop(L, 1);
            return 0;
        }
    }
    return 1;
}

/* The results (the arguments) through the global print, as lua.c does,
 * each plain table first turned into lamina.show's summary of it. */
static int print_values(lua_State *L)
{
    int n = lua_gettop(L);
    int show = lua_getfield(L, LUA_REGISTRYINDEX, SHOW_KEY) == LUA_TFUNCTION;
    for (int i = 1; show && i <= n; i++) {
        if (!plain_table(L, i)) continue;
        lua_pushvalue(L, n + 1);
        lua_pushvalue(L, i);
        lua_call(L, 1, 1);
        lua_replace(L, i);
    }
    lua_settop(L, n);
    lua_getglobal(L, "print");
    lua_insert(L, 1);
    lua_call(L, n, 0);
    return 0;
}

/* Print the values from base on; Ctrl-C interrupts it (a huge table). */
static void print_results(repl *r)
{
    lua_State *L = r->L;
    int n = lua_gettop(L) - r->base + 1;
    if (n <= 0) return;
    luaL_checkstack(L, LUA_MINSTACK, "too many results to print");
    lua_pushcfunction(L, print_values);
    lua_insert(L, r->base);
    if (lam_cli_docall(L, n, 0) != LUA_OK) lam_cli_report(L, 0);
    fflush(stdout);
}

/* The loop on standard input until end of file; returns an exit code. */
static int repl_loop(lua_State *L)
{
    repl r;
    memset(&r, 0, sizeof r);
    r.L = L;
    r.base = lua_gettop(L) + 1;
    r.tty = isatty(STDIN_FILENO);
    lam_help_open(L);
    lua_pushcfunction(L, load_show);
    if (lua_pcall(L, 0, 0, 0) != LUA_OK) { /* tables then print as print shows them */
        fprintf(stderr, "lamina repl: lamina.show did not load (%s)\n", lua_tostring(L, -1));
        lua_pop(L, 1);
    }
    complete_L = L;
    if (r.tty) load_editor(&r.ed);
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = prompt_action; /* no SA_RESTART: a read in progress returns EINTR */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old);
    void **hist = lam_lua_newbox(L); /* the history path */
    r.base++;
    if (r.ed.readline) *hist = history_path();
    if (*hist && r.ed.read_history) r.ed.read_history(*hist);
    if (r.tty) {
        printf("lamina %s (%s): the lamina module is loaded; Ctrl-D quits, Ctrl-C interrupts.\n", LAMINA_VERSION,
               LUA_RELEASE);
        if (!r.ed.readline) printf("(no line editing: install GNU readline or libedit)\n");
        fflush(stdout);
    }
    int status;
    while ((status = loadline(&r)) != LINE_EOF) {
        if (status == LINE_INTERRUPTED) continue;
        if (status == LUA_OK) status = lam_cli_docall(L, 0, LUA_MULTRET);
        if (status == LUA_OK) print_results(&r);
        else lam_cli_report(L, 0);
    }
    lua_settop(L, r.base - 1);
    if (r.tty) {
        fputc('\n', stdout);
        fflush(stdout);
    }
    if (*hist && r.ed.write_history && r.ed.write_history(*hist) == 0 && r.ed.history_truncate_file)
        r.ed.history_truncate_file(*hist, HISTORY_LINES);
    sigaction(SIGINT, &old, NULL);
    complete_L = NULL;
    return 0;
}

static const char repl_usage[] =
    "usage: lamina repl\n"
    "An interactive Lua 5.4 prompt with the lamina module loaded (also plain\n"
    "`lamina` on a terminal). Expressions and `=expr` print their values;\n"
    "an incomplete statement continues on the next line; Ctrl-C interrupts a\n"
    "running command (or abandons the line being typed), Ctrl-D quits.\n"
    "Line editing, Tab completion and history (~/.lamina_history, or\n"
    "$LAMINA_HISTORY) come from GNU readline or libedit when installed.\n"
    "help() lists the topics of lua/API.md; help(x) prints the entry of a\n"
    "function, method or object (help(lamina.load), help(m)).\n";

int cmd_repl(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        fputs(repl_usage, stdout);
        return EXIT_OK;
    }
    if (argc >= 2) return cli_usage("repl", "unexpected argument '%s'", argv[1]);
    return lam_cli_host("repl", repl_loop);
}

int lua_main_default(void)
{
    if (!isatty(STDIN_FILENO)) return cli_usage(NULL, "no command given");
    char *argv[] = { "repl", NULL };
    return cmd_repl(1, argv);
}
