/* Embree's pointers and loader; see embree_lazy.h. */
#include "embree_lazy.h"

LAM_LAZYLIB_MODULE(lam_embree_load, "libembree3.so.3", "libembree3-3", LAM_EMBREE_FUNCS)
