/* lam_plan_run's threaded half (internal to the planner). */
#ifndef LAM_PLAN_THREADS_H
#define LAM_PLAN_THREADS_H

#include "planner.h"

/* The layers of the run of s (o->threads > 1 workers), from the stage at
 * origin: every layer's sink->layer, operations and sink->layer_end, and
 * cb, on the calling thread in layer order; begin and end are the
 * caller's. The output, the callbacks' order and the first error are those
 * of planning on one thread. s is left at the end of the run. */
int lam_plan_threaded(lam_slicer *s, const lam_plan_opts *o, const lam_sink *sink, lam_layer_cb cb, void *cbctx,
                      const double origin[3], lam_error *err);

/* Add a layer's LADRP statistics to a run's. */
void lam_ladrp_stats_add(lam_ladrp_stats *total, const lam_ladrp_stats *layer);

#endif
