/* The directory lamina's code was loaded from: the main program, or a shared
 * object (the Lua C module). dladdr names the object that holds a function
 * of ours; for the main program it gives argv[0], which need not be a path,
 * so the main program is told apart by its load address (that of its own
 * program headers, AT_PHDR) and read from /proc/self/exe instead. */
#define _GNU_SOURCE
#include "paths.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/auxv.h>
#include <unistd.h>

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

static char *find_code_dir(int *module);

/* Found once when the code is loaded: dladdr names a module by the path it
 * was opened with, which may be relative ("./lamina.so" from a package.cpath
 * of "./?.so") and so holds only until the process changes directory. Freed
 * when the module is unloaded (lua_close dlcloses it). */
static char *loaded_dir;
static int loaded_module;

__attribute__((constructor)) static void code_dir_init(void)
{
    loaded_dir = find_code_dir(&loaded_module);
}

__attribute__((destructor)) static void code_dir_fini(void)
{
    free(loaded_dir);
    loaded_dir = NULL;
}

char *lam_code_dir(int *module)
{
    if (!loaded_dir) return find_code_dir(module);
    if (module) *module = loaded_module;
    return strdup(loaded_dir);
}

static char *find_code_dir(int *module)
{
    Dl_info self, prog;
    int in_so = 0;
    char *path = NULL;
    unsigned long phdr = getauxval(AT_PHDR);
    if (dladdr((void *)(size_t)find_code_dir, &self) && self.dli_fname && phdr && dladdr((void *)phdr, &prog) &&
        self.dli_fbase != prog.dli_fbase)
        in_so = 1;
    if (in_so) {
        path = realpath(self.dli_fname, NULL);
    } else {
        char exe[PATH_MAX];
        ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
        if (len > 0) {
            exe[len] = '\0';
            path = strdup(exe);
        }
    }
    if (!path) return NULL;
    char *slash = strrchr(path, '/');
    if (!slash) {
        free(path);
        return NULL;
    }
    slash[slash == path] = '\0'; /* "/lamina" -> "/" */
    if (module) *module = in_so;
    return path;
}

size_t lam_search_dirs(const char *env, const lam_rel_dirs *rel, char **dirs, size_t max)
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
    int module = 0;
    char *base = rel ? lam_code_dir(&module) : NULL;
    if (!base) return n;
    const char *const *r = module ? rel->module : rel->exe;
    for (size_t i = 0; r && r[i] && n < max; i++) {
        size_t need = strlen(base) + strlen(r[i]) + 2;
        if ((dirs[n] = malloc(need))) {
            snprintf(dirs[n], need, "%s/%s", base, r[i]);
            n++;
        }
    }
    free(base);
    return n;
}

size_t lam_lua_dirs(char **dirs, size_t max)
{
    static const char *const exe[] = { "../lua", "../share/lua/5.4", NULL };
    static const char *const module[] = { "../lua", "../../../share/lua/5.4", NULL };
    static const lam_rel_dirs rel = { exe, module };
    return lam_search_dirs(NULL, &rel, dirs, max);
}
