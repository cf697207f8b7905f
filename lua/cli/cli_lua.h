/* The Lua side of the `lamina` command line: recipes (`lamina run`),
 * one-liners (`lamina -e`), and the Lua state they share with the
 * interactive prompt (repl.h). */
#ifndef LAM_CLI_LUA_H
#define LAM_CLI_LUA_H

#include <lua.h>

/* lamina run RECIPE.lua|- [ARGS...]: argv[0] is "run". Exit code 0, or 1
 * when the recipe cannot be loaded or raises an error (2: usage). */
int cmd_run(int argc, char **argv);

/* lamina -e CODE [-e CODE ...]: argv[0] is "-e". */
int cmd_eval(int argc, char **argv);

/* ---- the host that `run`, `-e` and repl.c share ----------------------- */

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

/* Run body(L) protected in a new state (lam_cli_newstate) whose global
 * `arg` is set as for `lamina CMD`, then close the state. Returns body's
 * exit code, or 1 when the state cannot be made or body raises. This is
 * how repl.c runs without cli_lua.c knowing about it. */
int lam_cli_host(const char *cmd, int (*body)(lua_State *L));

#endif
