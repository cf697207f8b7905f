/* GEOS's pointers and loader; see geos_lazy.h. */
#include "geos_lazy.h"

LAM_LAZYLIB_MODULE(lam_geos_load, "libgeos_c.so.1", "libgeos-c1v5", LAM_GEOS_FUNCS)
