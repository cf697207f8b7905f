/* Where lamina finds its data at run time (machine profiles, plugins, its
 * Lua modules): an environment variable first, then places relative to the
 * file that holds lamina's code -- the executable `lamina`, or the Lua C
 * module lamina.so when a stock lua5.4 loaded it -- so a build tree, an
 * installed tree (any PREFIX, moved or not) and a LuaRocks tree all work
 * without configuration. */
#ifndef LAM_PATHS_H
#define LAM_PATHS_H

#include <stddef.h>

/* Relative places to search, by where lamina's code was loaded from; each a
 * NULL-terminated list (or NULL). */
typedef struct lam_rel_dirs {
    const char *const *exe;    /* relative to the directory of the executable */
    const char *const *module; /* relative to the directory of the C module lamina.so */
} lam_rel_dirs;

/* Search directories: the colon-separated list in environment variable
 * `env` (if env is not NULL and it is set), then <dir>/<rel> for each
 * relative path of rel's list for the file holding lamina's code: the
 * executable (/proc/self/exe) when liblamina is linked into the program, the
 * shared object's own file (dladdr) when it is in one (lamina.so). Each
 * stored string is malloc'd (caller frees); returns how many were stored
 * (at most max). */
size_t lam_search_dirs(const char *env, const lam_rel_dirs *rel, char **dirs, size_t max);

/* The directory of the file holding lamina's code (as above), malloc'd, and
 * whether it is a shared object rather than the executable (*module, may be
 * NULL); NULL when it cannot be told. Found when the code was loaded, so a
 * module opened by a relative path stays found after a change of directory. */
char *lam_code_dir(int *module);

/* The directories of lamina's own Lua modules (lamina/adaptive.lua, ...),
 * for the executable's package.path and the sandbox's require: the build
 * tree's lua/, an installed tree's share/lua/5.4. As lam_search_dirs. */
size_t lam_lua_dirs(char **dirs, size_t max);

#endif
