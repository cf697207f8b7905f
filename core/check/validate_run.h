/* The layer check of validate.h over many layers, on several threads
 * (issue 15), with the results handed back strictly in layer order, so a
 * report made from them does not depend on the number of threads.
 *
 * Workers make a layer (slice it, read it from a program, or take it from
 * a list: the caller's lam_vlayer_fn) and check it (lam_validate_layer)
 * with a lam_rays of their own (forks of the caller's, lam_rays_fork:
 * Embree's committed scene is shared read-only); the
 * calling thread only hands each result to the caller's lam_vreport_fn, in
 * order 0, 1, 2, ..., through the ordered pool (pool.h). With one thread
 * (or one layer) everything runs on the calling thread, one layer after
 * the other, through the same two functions. The first error in layer
 * order is the run's, as on one thread: the layers before it are
 * reported, none after it. */
#ifndef LAM_VALIDATE_RUN_H
#define LAM_VALIDATE_RUN_H

#include <stddef.h>

#include "error.h"
#include "rays.h"
#include "slice.h"
#include "validate.h"

/* A layer to check, as a source made it. */
typedef struct lam_vlayer {
    const lam_layer *L;     /* the layer */
    lam_layer *owned;       /* freed with lam_layer_free once reported (or the run
                               stops); NULL when the source keeps L */
    const lam_frame *f;     /* the frame it was made with */
    lam_validate_opts o;    /* how to check it */
} lam_vlayer;

/* Make layer i on worker `worker` (0 .. threads-1; called on that worker's
 * thread, one layer at a time, in increasing order, usually runs of
 * consecutive layers), whose rays are v (for its section index,
 * lam_rays_section). It may touch what is the worker's, and read what no
 * thread changes during the run. out is zeroed before; on failure nothing
 * must be left in it to free. Returns LAM_OK or an error code (err). */
typedef int (*lam_vlayer_fn)(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err);

/* Layer i and its check, on the calling thread in layer order. The run
 * frees chk afterwards unless report takes it (moves it out and zeroes
 * *chk). A non-zero return stops the run and is its result. */
typedef int (*lam_vreport_fn)(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err);

/* Check layers 0 .. n-1 on `threads` threads (1 .. LAM_MAX_THREADS; no
 * more are started than there are layers). f: the frame most layers have
 * (v's section index is made for it first, and the workers share it), or
 * NULL. Returns LAM_OK when every layer was reported, the first error in
 * layer order (making or checking a layer: message in err), report's
 * non-zero value, or LAM_ENOMEM when the workers could not be set up
 * (then nothing was reported). */
int lam_validate_layers(lam_rays *v, size_t n, unsigned threads, const lam_frame *f, lam_vlayer_fn make,
                        lam_vreport_fn report, void *ctx, lam_error *err);

/* The same for every layer of s's run, sliced by the workers (with forks
 * of s, lam_slicer_fork; on one thread with s), each checked with o (NULL:
 * the defaults). The layers are the run's (lam_vlayer.owned). Where s
 * stands afterwards is unspecified: seek it before slicing again. */
int lam_validate_slicer(lam_slicer *s, lam_rays *v, const lam_validate_opts *o, unsigned threads,
                        lam_vreport_fn report, void *ctx, lam_error *err);

#endif
