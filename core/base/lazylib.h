/* Shared libraries opened on first use (dlopen) instead of by the loader
 * at every start: Embree (with TBB and libstdc++) and GEOS cost a plain
 * `lamina slice` about 7 ms and 5 MB of mapped pages before main, and it
 * needs neither (README, Dependencies). One module per library
 * (embree_lazy.h, geos_lazy.h) lists the functions lamina calls in one
 * X-macro table; this module opens the library and resolves the table.
 *
 * With LAM_LAZY 0 (`make LAZY=0`) the libraries are linked as usual and
 * loading is a no-op. */
#ifndef LAM_LAZYLIB_H
#define LAM_LAZYLIB_H

#include <pthread.h>
#include <stddef.h>

#include "error.h"

#ifndef LAM_LAZY
#define LAM_LAZY 1
#endif

/* One function of a library: its symbol and the pointer it is resolved into. */
typedef struct lam_lazylib_fn {
    const char *name;
    void **slot;
} lam_lazylib_fn;

typedef struct lam_lazylib {
    const char *soname;         /* what dlopen is given: "libgeos_c.so.1" */
    const char *package;        /* the Debian package that ships it, for the message */
    const lam_lazylib_fn *fns;  /* the functions lamina calls */
    size_t nfns;
    pthread_once_t once;        /* PTHREAD_ONCE_INIT */
    char why[512];              /* "" once loaded, else why not */
} lam_lazylib;

/* Open lib and resolve every function of its table: once per process,
 * whichever thread asks first (open_once is the library's own trampoline,
 * `static void f(void) { lam_lazylib_open(&lib); }`, as pthread_once takes
 * no argument). The library stays loaded until exit. Returns LAM_OK, or
 * LAM_EIO "cannot load SONAME: <dlerror>; install PACKAGE" (also on every
 * later call); no slot is then usable. */
int lam_lazylib_load(lam_lazylib *lib, void (*open_once)(void), lam_error *err);

/* The body of open_once (the slots are all set or the library unusable). */
void lam_lazylib_open(lam_lazylib *lib);

/* A library module (geos_lazy.c, embree_lazy.c) is one line,
 * LAM_LAZYLIB_MODULE(lam_x_load, "libx.so.1", "libx1", LAM_X_FUNCS): the
 * pointers lam_dl_f of every f of the X-macro list FUNCS, their table, and
 * `int lam_x_load(lam_error *err)`, which loads the library (lam_lazylib_load).
 * Its header declares the pointers with LAM_LAZYLIB_EXTERN, after the
 * library's own header and before #defining each f to lam_dl_f (the
 * macros never expand f, so they work on either side of those #defines). */
#if LAM_LAZY
#define LAM_LAZYLIB_EXTERN(f) extern __typeof__(&f) lam_dl_##f;
#define LAM_LAZYLIB_DEFINE(f) __typeof__(lam_dl_##f) lam_dl_##f;
#define LAM_LAZYLIB_ENTRY(f) { #f, (void **)&lam_dl_##f },
#define LAM_LAZYLIB_MODULE(load, soname, package, FUNCS)                                             \
    FUNCS(LAM_LAZYLIB_DEFINE)                                                                        \
    static const lam_lazylib_fn load##_fns[] = { FUNCS(LAM_LAZYLIB_ENTRY) };                         \
    static lam_lazylib load##_lib = { soname, package, load##_fns, sizeof load##_fns / sizeof *load##_fns, \
                                      PTHREAD_ONCE_INIT, "" };                                       \
    static void load##_once(void) { lam_lazylib_open(&load##_lib); }                                 \
    int load(lam_error *err) { return lam_lazylib_load(&load##_lib, load##_once, err); }
#else
#define LAM_LAZYLIB_MODULE(load, soname, package, FUNCS)                                             \
    int load(lam_error *err) { (void)err; return LAM_OK; }
#endif

#endif
