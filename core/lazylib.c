#include "lazylib.h"

#include <dlfcn.h>
#include <stdio.h>

void lam_lazylib_open(lam_lazylib *lib)
{
    /* RTLD_LOCAL: lamina's own symbols, and a plugin's, stay apart from
     * the library's; RTLD_NOW: a missing symbol fails here, not mid-job */
    void *h = dlopen(lib->soname, RTLD_NOW | RTLD_LOCAL);
    const char *e = h ? NULL : dlerror();
    for (size_t i = 0; h && !e && i < lib->nfns; i++) {
        dlerror();
        *lib->fns[i].slot = dlsym(h, lib->fns[i].name);
        if (!*lib->fns[i].slot) e = dlerror();
        if (!*lib->fns[i].slot && !e) e = "a function resolved to NULL";
    }
    if (!e) return;
    /* never dlclose: dlerror's text may live in the handle, and a half
     * resolved table must stay unused anyway */
    snprintf(lib->why, sizeof lib->why, "cannot load %s: %s; install %s", lib->soname, e, lib->package);
}

int lam_lazylib_load(lam_lazylib *lib, void (*open_once)(void), lam_error *err)
{
    pthread_once(&lib->once, open_once);
    if (!lib->why[0]) return LAM_OK;
    return lam_error_set(err, LAM_EIO, NULL, 0, 0, "%s", lib->why);
}
