#include "paths.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

size_t lam_search_dirs(const char *env, const char *const *rel, char **dirs, size_t max)
{
    size_t n = 0;
    const char *list = env ? getenv(env) : NULL;
    while (list && *list && n < max) {
        const char *colon = strchr(list, ':');
        size_t len = colon ? (size_t)(colon - list) : strlen(list);
        if (len > 0 && (dirs[n] = malloc(len + 1))) {
            memcpy(dirs[n], list, len);
            dirs[n][len] = '\0';
            n++;
        }
        list = colon ? colon + 1 : NULL;
    }
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0) return n;
    exe[len] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash) return n;
    *slash = '\0';
    for (size_t i = 0; rel && rel[i] && n < max; i++) {
        size_t need = strlen(exe) + strlen(rel[i]) + 2;
        if ((dirs[n] = malloc(need))) {
            snprintf(dirs[n], need, "%s/%s", exe, rel[i]);
            n++;
        }
    }
    return n;
}
