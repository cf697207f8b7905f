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

/* AddressSanitizer's leak check scans the thread-local blocks of libraries
 * loaded with dlopen (Embree has one) and, with this glibc, takes a block's
 * address for an older glibc's layout now and then: its tracer then
 * crashes at exit ("Tracer caught signal 11", google/sanitizers#1322), a
 * failure of the check, not of the program (test_model.t's run hit it every
 * time). Those blocks are left out of the scan; ASAN_OPTIONS overrides.
 * Weak: a program that sets its own defaults keeps them. */
#if defined(__SANITIZE_ADDRESS__)
#define LAM_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LAM_ASAN 1
#endif
#endif
#if defined(LAM_ASAN) && LAM_LAZY
const char *__asan_default_options(void) __attribute__((weak, used));
const char *__asan_default_options(void) { return "intercept_tls_get_addr=0"; }
#endif
