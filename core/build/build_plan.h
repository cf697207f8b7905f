/* Planning a build plate (issue 25, items 2, 4 and 5).
 *
 * lam_build_run_new places a build (build.h): each part's model is loaded
 * once (units, scale, rotations), dropped onto the plate (its lowest point
 * at the part's z, 0 unless it says) with its footprint box centred on the
 * origin, and every copy arranged (arrange.h) and moved to its place.
 *
 * The plate's layers are counted from the plate: layer k (0-based) is the
 * slab [k w, (k + 1) w] of the layer width w (the profile's), cut where the
 * profile says (middle by default). Each part is sliced on those planes
 * only where it is, so a part on the plate has exactly the layers, and the
 * program, it has planned alone at the same place. A plate layer holds
 * every part that reaches it, part by part through the powder-bed planner
 * (with the part's styled profile), then shared between the lasers
 * (lasers.h); the sink gets the layer's top height as z (CLI's $$LAYER)
 * and the cut height in lam_layer_info.cut.
 *
 * Ids: part i (1-based, in the job's order, copies in turn) is attrs.part;
 * styles are numbered 1 contour, 2 core, 3 upskin, 4 downskin (the
 * regions' own), then the job's other styles in their order; every
 * operation's attrs.label is the CLI id of its (part, style, laser), and
 * the job's label table (lam_job_info.labels) names them
 * "PART:STYLE:LASER" (e.g. "bracket_2:core:1").
 *
 * Memory: the models, their slicers, and per worker the layers around the
 * one planned (skins); the plate's layers stream through the sink one at a
 * time (at most a window of layers per thread ahead), however many parts. */
#ifndef LAM_BUILD_PLAN_H
#define LAM_BUILD_PLAN_H

#include <stddef.h>

#include "build_run.h"
#include "error.h"
#include "hatch.h"
#include "plan.h"

/* How a plate is planned. */
typedef struct lam_run_opts {
    unsigned threads;        /* workers (0, 1: the calling thread); the same output for any */
    size_t layer_first, layer_count; /* plan only these plate layers (count 0: all), for
                                part files; begin and end still describe the whole plate */
    /* Optional, on the calling thread before layer k is written: non-zero stops the run
     * with that code (an interrupt). */
    int (*stop)(void *user, size_t k);
    /* Optional, on the calling thread in layer order once layer k is written: its
     * estimate (exposure and jump of the busiest laser), each laser's. */
    void (*planned)(void *user, size_t k, const lam_scan_time *layer, const lam_scan_time *lasers, size_t nlasers);
    /* Optional, on the calling thread in layer order before layer k is written: its
     * sections, every part's (a contact sheet's panel); non-zero stops the run. */
    int (*section)(void *user, const lam_layer *sec, lam_error *err);
    void *user;
} lam_run_opts;

/* Plan the plate into sink: begin, every plate layer, end (the sink is not
 * destroyed). Returns LAM_OK or the first error (a part's planner naming
 * the part and layer, the lasers', the sink's, stop's code). */
int lam_build_run_plan(lam_build_run *r, const lam_run_opts *o, const lam_sink *sink, lam_error *err);

#endif
