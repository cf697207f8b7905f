/* Opening a library on first use; see lazylib.h. */
#include "lazylib.h"

#include <dlfcn.h>
#include <stdio.h>

void lam_lazylib_open(lam_lazylib *lib)
{
    /* RTLD_LOCAL: the library's symbols stay out of the way of lamina's
     * and a plugin's; RTLD_NOW: the library's own dependencies are bound
     * here, where a failure is an error, not in the middle of a job */
    void *h = dlopen(lib->soname, RTLD_NOW | RTLD_LOCAL);
    const char *e = h ? NULL : dlerror();
    for (size_t i = 0; !e && i < lib->nfns; i++) {
        dlerror();
        if (!(*lib->fns[i].slot = dlsym(h, lib->fns[i].name))) e = dlerror();
        if (!*lib->fns[i].slot && !e) e = "a function it should export is NULL";
    }
    if (!e) return;
    /* the message first: dlerror's text may belong to the handle */
    snprintf(lib->why, sizeof lib->why, "cannot load %s: %s; install %s", lib->soname, e, lib->package);
    for (size_t i = 0; i < lib->nfns; i++) *lib->fns[i].slot = NULL;
    if (h) dlclose(h);
}

int lam_lazylib_load(lam_lazylib *lib, void (*open_once)(void), lam_error *err)
{
    pthread_once(&lib->once, open_once);
    if (!lib->why[0]) return LAM_OK;
    return lam_error_set(err, LAM_EIO, NULL, 0, 0, "%s", lib->why);
}
