/* The planning driver: one slicing run's layers, made by a layer source,
 * planned into a sink in layer order, on the calling thread or on worker
 * threads (issue 15) with the same output, in the pattern of
 * validate_run.h. The source makes layer i on a worker (a slicer sweeping
 * its own fork of the run, or a list of layers made already); the calling
 * thread consumes the layers in order through the ordered pool (pool.h)
 * and is the only one to touch the sink and the caller's callbacks.
 * lam_plan_run (planner.h: a slicer) and lam_plan_layers (plan_layers.h:
 * Lua's list) are its two sources. */
#ifndef LAM_PLAN_DRIVE_H
#define LAM_PLAN_DRIVE_H

#include <stddef.h>

#include "error.h"
#include "hatch.h"
#include "plan.h"
#include "planner.h"
#include "slice.h"

typedef struct lam_plan_source {
    size_t n;                /* the run's layers 0 .. n-1 (skins look at all of them) */
    size_t first, end;       /* the layers planned into the sink: first .. end-1 (end <= n).
                                The layers before are made but planned into no sink, and
                                only for LADRP islands (their order starts nearest where
                                the layer before left the stage); none after end is
                                planned. A range other than 0 .. n runs on the calling
                                thread. */
    const lam_frame *f;      /* the run's frame */
    const lam_plan_opts *o;  /* the plan; o->threads workers (0, 1: the calling thread);
                                o->totals, o->time and o->layer_time (indexed by the
                                layer's position i) are kept on the calling thread */
    double origin[3];        /* where the stage starts (output frame) */
    /* Set up the source for `workers` workers (1: the calling thread
     * only, as worker 0). Optional. Returns LAM_OK or an error (err). */
    int (*start)(void *ctx, unsigned workers, lam_error *err);
    /* Release what start made (after the run or a start that failed).
     * Optional. */
    void (*finish)(void *ctx);
    /* Layer j on worker `worker` (on that worker's thread, one call at a
     * time, mostly consecutive layers): *out is borrowed until the
     * worker's next call, and the source may drop the layers it made
     * before `keep` (the worker holds none of them). Returns LAM_OK or an
     * error (err). */
    int (*get)(void *ctx, unsigned worker, size_t j, size_t keep, const lam_layer **out, lam_error *err);
    /* Optional: hand layer j, just got by `worker`, over to the driver
     * (which frees it), or NULL; the driver clones what it keeps
     * otherwise, unless `stable`. */
    lam_layer *(*take)(void *ctx, unsigned worker, size_t j);
    int stable;              /* the source's layers outlive the run: borrowed */
    void *ctx;               /* for start, finish, get and take */
    /* The caller's callbacks, all optional, with `user`: */
    lam_layer_cb cb;         /* each layer of first .. end-1 once made, on the calling
                                thread in order, as far ahead as one thread makes them */
    /* The options of the i-th layer, starting from the plan's; may run on
     * several worker threads at once: it must only read shared data. */
    void (*layer_opts)(void *user, size_t i, lam_plan_opts *oi);
    /* Same rules: SLS vectors to plan for the i-th layer instead of
     * hatching it (NULL: lamina's own). */
    const lam_hatches *(*given)(void *user, size_t i);
    /* On the calling thread before the i-th layer is written: a non-zero
     * return stops the run with that code (an interrupt). */
    int (*stop)(void *user, size_t i);
    /* On the calling thread in layer order: the i-th layer's operations
     * have reached the sink (before its layer_end, or with it when a
     * worker formatted the layer's bytes, lam_sink.fork); ls is its LADRP
     * statistics, t its SLS estimate. */
    void (*planned)(void *user, size_t i, const lam_ladrp_stats *ls, const lam_scan_time *t);
    void *user;
} lam_plan_source;

/* Plan the layers of src into sink: for each one sink->layer, the
 * planner's operations, sink->layer_end (begin and end are the caller's).
 * With o->threads > 1 workers make and plan layers into recordings
 * (plan_record.h), or straight into the layer's bytes when the sink can
 * fork (lam_sink.fork), which the calling thread writes in layer order:
 * the output, the callbacks' order, the statistics and the first error
 * are those of one thread. LADRP (where the stage stands when a layer
 * starts): a worker going on from the layer before knows it; at the start
 * of its run of layers it plans the layer before first, unrecorded, from
 * a guess; the calling thread compares the stage each recording assumed
 * with the real one, bit for bit, and plans the layer again itself when
 * they differ: never a different program, at worst a layer planned twice.
 * When no thread can be started the run goes on the calling thread.
 * Returns LAM_OK or the first error (the source's, a planner's, the
 * sink's, a callback's code), message in err. */
int lam_plan_drive(const lam_plan_source *src, const lam_sink *sink, lam_error *err);

/* Add a layer's LADRP statistics to a run's. */
void lam_ladrp_stats_add(lam_ladrp_stats *total, const lam_ladrp_stats *layer);

#endif
