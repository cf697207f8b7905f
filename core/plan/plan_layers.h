/* Planning a list of layers made already (Lua's machine:plan): any subset
 * of one slicing run, in increasing order, each planned as it is, on the
 * calling thread or on worker threads (issue 15) with the same output. */
#ifndef LAM_PLAN_LAYERS_H
#define LAM_PLAN_LAYERS_H

#include "planner.h"

typedef struct lam_plan_layers_job {
    const lam_layer *const *layers; /* n layers of one run, increasing index (borrowed) */
    size_t n;
    const lam_frame *frame;          /* the run's frame */
    const lam_plan_opts *o;          /* the plan's options; o->threads workers (0, 1: none) */
    double origin[3];                /* LADRP: where the stage starts */
    /* Optional. The options of the i-th layer given, starting from *o; may
     * run on several worker threads at once: it must only read shared
     * data (no Lua). */
    void (*layer_opts)(void *ctx, size_t i, lam_plan_opts *oi);
    /* Optional, same rules: SLS vectors to plan for the i-th layer instead
     * of hatching it (NULL: lamina's own). */
    const lam_hatches *(*given)(void *ctx, size_t i);
    /* Optional, on the calling thread before the i-th layer is written: a
     * non-zero return stops the run with that code (an interrupt). */
    int (*stop)(void *ctx, size_t i);
    /* Optional, on the calling thread in layer order: the i-th layer's
     * operations have reached the sink (before its layer_end); ls is its
     * LADRP statistics, t its SLS estimate. */
    void (*planned)(void *ctx, size_t i, const lam_ladrp_stats *ls, const lam_scan_time *t);
    void *ctx;
} lam_plan_layers_job;

/* Plan the layers of j into sink: for each one sink->layer, the planner's
 * operations, sink->layer_end (begin and end are the caller's). With
 * o->threads > 1, workers plan layers into recordings (plan_record.h) that
 * the calling thread replays in layer order, so the sink, stop and planned
 * run on the calling thread only and the output, the statistics and the
 * first error are those of one thread. Returns LAM_OK or the first error
 * (a planner's, the sink's, stop's code), message in err. */
int lam_plan_layers(const lam_plan_layers_job *j, const lam_sink *sink, lam_error *err);

#endif
