/* Where lamina finds its data at run time (machine profiles, plugins):
 * an environment variable first, then places relative to the executable,
 * so a build tree and an installed tree both work without configuration. */
#ifndef LAM_PATHS_H
#define LAM_PATHS_H

#include <stddef.h>

/* Search directories: the colon-separated list in environment variable
 * `env` (if set), then <exe dir>/<rel> for each of the NULL-terminated
 * relative paths. Each stored string is malloc'd (caller frees); returns
 * how many were stored (at most max). */
size_t lam_search_dirs(const char *env, const char *const *rel, char **dirs, size_t max);

#endif
