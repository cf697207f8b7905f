/* A build's plate set up for planning (build_plan.h): the parts loaded,
 * placed and sliced, the styles and CLI labels numbered. See build_plan.h
 * for what the plate's layers are. The struct's fields are read by the
 * planner (build_plan.c) and the JSON (build_json.c); other code uses the
 * functions. */
#ifndef LAM_BUILD_RUN_H
#define LAM_BUILD_RUN_H

#include <stddef.h>

#include "arrange.h"
#include "build.h"
#include "error.h"
#include "frame.h"
#include "hatch.h"
#include "lasers.h"
#include "model.h"
#include "part.h"
#include "plan.h"
#include "planner.h"
#include "slice.h"
#include "support.h"

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
    lam_plan_opts po;        /* its planning options (po.supports: supports) */
    lam_supports *supports;  /* its supports by its own layer index, or NULL (owned) */
    int style_id[LAM_REGIONS]; /* the style number of each region */
    lam_scan_time time;      /* its share of the estimate (exposure and jumps of its own
                                blocks, as if one laser did it all), filled by planning */
} lam_run_part;

typedef struct lam_build_run lam_build_run;

struct lam_build_run {
    const lam_build *b;
    lam_run_part *parts;
    size_t nparts;
    double width;            /* layer width */
    size_t layers;           /* plate layers: up to the highest part's top */
    int cut;                 /* lam_cut */
    lam_frame frame;         /* the plate's: u, v, w = x, y, z */
    lam_plate plate;
    double spacing;
    lam_laser_set lasers;
    double *centres;         /* parts' footprint centres (lasers.h) */
    char **styles;           /* style names, number s at styles[s - 1] */
    size_t nstyles;
    /* CLI labels: label[(part - 1) * nstyles * nlasers + (style - 1) * nlasers + laser - 1]
     * is the id (0: none) of each (part, style, laser) the plate can use */
    long long *label_of;
    char **labels;           /* text of id k + 1 */
    size_t nlabels;
    lam_job_info job;
    char job_label[160];
    lam_job_exposure *exposure; /* the job's (lam_job_info.exposure): per style and region */
    char *json;              /* the job's "build" member in the JSON (build_json.c) */
};

/* Render the build's JSON description into r->json and the job's
 * json_extra. LAM_ENOMEM. */
int lam_build_run_json(lam_build_run *r, lam_error *err);

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

/* The plate's frame (u, v, w = x, y, z). */
const lam_frame *lam_build_run_frame(const lam_build_run *r);

/* The identity of the plate's run for part files (part.h): the resolved
 * profile's text, the styles, and every part's model bytes, layers
 * (lam_part_identity), place, height, scale, rotations and styles. Two
 * plates with equal identities write the same program. Errors: LAM_EIO
 * reading a model. */
int lam_build_run_identity(const lam_build_run *r, const char *profile, size_t len, uint64_t *out, lam_error *err);

/* The label id of (part, style, laser), 0 when it has none. */
long long lam_build_run_label(const lam_build_run *r, long long part, long long style, long long laser);

#endif
