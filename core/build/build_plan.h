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

#include "build.h"
#include "error.h"
#include "hatch.h"
#include "lasers.h"
#include "model.h"
#include "plan.h"
#include "planner.h"
#include "slice.h"
#include "arrange.h"

/* One part on the plate (a copy of a job's part). */
typedef struct lam_run_part {
    size_t spec;             /* the job's part (lam_build.parts index) */
    char name[160];          /* NAME, or NAME_k for copy k of several */
    lam_model *model;        /* in plate coordinates (owned) */
    lam_slicer *slicer;      /* on the plate's planes where the part is (owned) */
    size_t first, count;     /* plate layers first .. first + count - 1 */
    double box[4];           /* footprint box on the plate: xmin ymin xmax ymax */
    double at[2];            /* its centre */
    double zmax;             /* its top */
    lam_profile styled;      /* the machine with the part's styles (strings borrowed) */
    lam_plan_opts po;        /* its planning options */
    int style_id[LAM_REGIONS]; /* the style number of each region */
    lam_scan_time time;      /* its share of the estimate (exposure and jumps of its own
                                blocks, as if one laser did it all), filled by planning */
} lam_run_part;

typedef struct lam_build_run lam_build_run;

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
    void *user;
} lam_run_opts;

/* Load, arrange and slice build b's parts (b is borrowed and must outlive
 * the run). load: threads and repair for reading models (xform ignored).
 * Errors: a model's (file:line:col), the arrangement's (arrange.h),
 * LAM_EINVAL for a plate the profile and job do not give ("the machine
 * has no plate: give plate: {width: W, depth: D} or {diameter: D}"), a
 * layer width missing, LAM_ENOMEM. */
int lam_build_run_new(const lam_build *b, const lam_load_opts *load, lam_build_run **out, lam_error *err);

void lam_build_run_free(lam_build_run *r);

/* The parts on the plate, n of them. */
const lam_run_part *lam_build_run_parts(const lam_build_run *r, size_t *n);

/* The plate's layers and layer width, the plate and the lasers. */
size_t lam_build_run_layers(const lam_build_run *r);
double lam_build_run_width(const lam_build_run *r);
const lam_plate *lam_build_run_plate(const lam_build_run *r);
const lam_laser_set *lam_build_run_lasers(const lam_build_run *r);

/* The style names: style number s (1-based) is names[s - 1]; *n of them. */
const char *const *lam_build_run_styles(const lam_build_run *r, size_t *n);

/* The job the plate's program begins with (lam_job_info; label table
 * included); valid while r lives. */
const lam_job_info *lam_build_run_job(const lam_build_run *r);

/* Plan the plate into sink: begin, every plate layer, end (the sink is not
 * destroyed). Returns LAM_OK or the first error (a part's planner naming
 * the part and layer, the lasers', the sink's, stop's code). */
int lam_build_run_plan(lam_build_run *r, const lam_run_opts *o, const lam_sink *sink, lam_error *err);

#endif
