/* The Lua side of the `lamina` command line: recipes (`lamina run`),
 * one-liners (`lamina -e`) and the interactive prompt (`lamina repl`, and
 * plain `lamina` on a terminal). */
#ifndef LAM_CLI_LUA_H
#define LAM_CLI_LUA_H

#include <lua.h>

/* lamina run RECIPE.lua|- [ARGS...]: argv[0] is "run". Exit code 0, or 1
 * when the recipe cannot be loaded or raises an error (2: usage). */
int cmd_run(int argc, char **argv);

/* lamina -e CODE [-e CODE ...]: argv[0] is "-e". */
int cmd_eval(int argc, char **argv);

/* lamina repl: argv[0] is "repl". */
int cmd_repl(int argc, char **argv);

/* Plain `lamina` without arguments: the prompt when standard input is a
 * terminal, otherwise the usual "no command given" usage error. */
int lua_main_default(void);

/* ---- shared by cli_lua.c and repl.c ---------------------------------- */

/* A new Lua state with the standard libraries, `lamina` loaded (global
 * and package.loaded) and lamina's Lua directories on package.path.
 * NULL (after a message on stderr) when that fails. */
lua_State *lam_cli_newstate(void);

/* lua_pcall with a traceback message handler, and Ctrl-C (SIGINT) turned
 * into a Lua error "interrupted" for the duration of the call (a second
 * Ctrl-C before Lua notices kills the process, as in lua.c). */
int lam_cli_docall(lua_State *L, int narg, int nres);

/* Print the error object on top of the stack to stderr (with prefix
 * "lamina: " unless prefix is 0) and pop it. Returns the exit code it
 * asks for: a table's integer field `exit` (1..125, as lamina.args sets
 * for option errors), else 1. */
int lam_cli_report(lua_State *L, int prefix);

/* The read-eval-print loop on standard input until end of file (repl.c).
 * Returns an exit code. */
int lam_repl(lua_State *L);

#endif
