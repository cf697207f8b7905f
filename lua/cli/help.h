/* The REPL's help(x): lua/API.md's entries, made into a C table at build
 * time (lua/cli/help.awk, a Makefile rule), so help and the document
 * cannot drift apart. */
#ifndef LAM_HELP_H
#define LAM_HELP_H

#include <lua.h>

typedef struct lam_help_entry {
    const char *key;         /* "lamina.load", "model:slice", "layer", "conventions" */
    const char *text;        /* the entry: its heading, then its text (examples too) */
} lam_help_entry;

/* Every entry of API.md in its order, ended by { NULL, NULL }
 * (the generated file). */
extern const lam_help_entry lam_help_entries[];

/* The entry with this key, or NULL. */
const lam_help_entry *lam_help_find(const char *key);

/* Push the help key of the value at idx, or nil when it has none: a
 * lamina function or method by identity (lamina.NAME, CLASS:NAME, and
 * MODULE.NAME for the loaded lamina.MODULE modules), an object by its
 * metatable's name (a layer: "layer"; model:slice's list: "model:slice"),
 * the lamina table ("the module") and a loaded module table
 * ("lamina.axes"). Runs no metamethod. */
void lam_help_key(lua_State *L, int idx);

/* Set the global help(x) in L: help() lists the topics, help(x) prints
 * x's entry (x a value, or a key or part of one as a string). */
void lam_help_open(lua_State *L);

#endif
