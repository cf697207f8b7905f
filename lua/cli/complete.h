/* Tab completion for the REPL: names that can follow what is typed. */
#ifndef LAM_COMPLETE_H
#define LAM_COMPLETE_H

#include <lua.h>

/* The completions of `word`, the text before the cursor back to the last
 * character that cannot be part of a name path (`lamina.lo`, `m:sl`,
 * `pri`): globals and keywords for a plain name; for `a.b.` the fields of
 * the table a.b (and of its __index table); for `x:` or `x.` on a userdata
 * or string, its methods (a lamina class's methods table, or an __index
 * table); after `:` only functions. Each is the whole word (`lamina.load`),
 * sorted, without repeats. Returns a malloc'd, NULL-ended array of
 * malloc'd strings (NULL when there is none or memory ran out); the
 * caller frees them. Runs no metamethod and no Lua code: tables are read
 * raw. */
char **lam_complete(lua_State *L, const char *word);

/* The characters that end a word for completion (everything but name
 * characters, `.` and `:`). */
extern const char lam_complete_breaks[];

#endif
