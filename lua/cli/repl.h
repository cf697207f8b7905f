/* lamina repl: the interactive Lua prompt, on the host of cli_lua.h. */
#ifndef LAM_REPL_H
#define LAM_REPL_H

/* lamina repl: argv[0] is "repl". Returns an exit code. */
int cmd_repl(int argc, char **argv);

/* Plain `lamina` without arguments: the prompt when standard input is a
 * terminal, otherwise the usual "no command given" usage error. */
int lua_main_default(void);

#endif
