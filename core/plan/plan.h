/* Planning: planners turn layers into machine operations and hand them to a
 * sink, which writes them in some dialect (text templates from a machine
 * profile, or a plugin writer such as binary CLI).
 *
 * Coordinates given to a sink are in the output frame: model coordinates
 * (x, y, z) by default, or the layer frame (u, v, w) when the profile says
 * `frame: machine`. Operations arrive in order: begin, then per layer
 * `layer`, its operations, `layer_end`; finally end. A sink returns LAM_OK or
 * an error code (and may fill the lam_error it was given at creation). */
#ifndef LAM_PLAN_H
#define LAM_PLAN_H

#include <stddef.h>

#include "error.h"
#include "vocab.h"

struct lam_frame;      /* slice.h */
struct lam_layer;      /* slice.h */
struct lam_scan_time;  /* hatch.h */
struct lam_sink_fork;  /* below */

/* One region's exposure in a powder-bed run (the JSON's job.exposure, for
 * a viewer's energy density: power / (speed x distance)). */
typedef struct lam_job_exposure {
    long long style;         /* the vectors' `style` attribute: 0 outside a build, else the
                                build style (core/build) the region is exposed with */
    int region;              /* lam_vec_kind: LAM_KIND_CONTOUR .. LAM_KIND_DOWNSKIN */
    double power, speed;     /* the profile's (hatch.h lam_exposure; speed 0: unknown) */
    double distance;         /* a hatch region's hatch_distance; a contour's: the spot width */
    double point_distance, exposure_time; /* point exposure (point_distance 0: continuous) */
} lam_job_exposure;

/* What a whole job looks like, for preambles and headers. */
typedef struct lam_job_info {
    const char *name;        /* machine profile name */
    const char *process;     /* "ladrp" or "sls" */
    const char *units;       /* what one model unit is, e.g. "mm" */
    size_t layers;           /* number of layers that will follow */
    double bbox[6];          /* model bounding box in the output frame: min xyz, max xyz */
    double bead;             /* bead (LADRP) or spot (SLS) width */
    double rate;             /* deposit feed rate */
    double travel_rate;      /* travel feed rate */
    double origin[3];        /* where the stage starts: the model origin in the layer
                                plane, at the first layer's build height (output frame) */
    const char *label;       /* the part's name (lam_job_label), NULL: "part" */
    const char *model;       /* the model's path as given (for headers), or NULL */
    const struct lam_frame *frame; /* the layer frame (u, v, w: w the slicing axis), or NULL */
    int frame_machine;       /* coordinates are in the layer frame (u, v, w) */
    const struct lam_repair_report *repair; /* what repair on load did to the model
                                when it did anything (lam_repair_acted), else NULL */
    /* A build (core/build): the CLI labels, labels[k] the text of id k + 1
     * (lam_attrs_id); NULL: the one label `label`, id 1. */
    const char *const *labels;
    size_t nlabels;
    const char *json_extra;  /* a build: more members of the JSON's job object, as JSON
                                text (`"build": {...}`), or NULL */
    /* SLS: the exposure of each region the plan can have vectors of,
     * nexposure entries: exposure[] when not NULL (a build's, per style and
     * region, the caller's), else own_exposure[] (lam_job_init fills it for
     * a single part's run, style 0; kept in the struct so a copy of the
     * job stays whole). LADRP: none (nexposure 0). */
    const lam_job_exposure *exposure;
    size_t nexposure;
    lam_job_exposure own_exposure[LAM_REGIONS];
} lam_job_info;

/* The part's name for a job from a model's path: the file's name without
 * directory and extension, characters other than letters, digits, `_`,
 * `-` and `.` replaced by `_` (CLI's $$LABEL text); "part" when that
 * leaves nothing. Written into buf (size > 1). */
void lam_job_label(const char *path, char *buf, size_t size);

typedef struct lam_layer_info {
    size_t index;            /* 0-based */
    double z;                /* build height of the section (the cut height) */
    double width, floor, ceiling;
    const struct lam_layer *section; /* the layer's section as sliced (its contours before
                                        any offset), or NULL; valid until layer_end returns */
    const struct lam_layer *support; /* the layer's support region (support.h), or NULL:
                                        the JSON's contours of region "support" */
    const struct lam_layer *overhang; /* what of its part needs support (support.h), or
                                         NULL: the JSON's contours of region "overhang" */
    const struct lam_scan_time *time; /* at layer_end of an SLS plan whose estimate means
                                         something (lam_scan_estimates): the layer's
                                         estimate; NULL otherwise */
    /* A build (core/build): z is the layer's top above the plate and cut
     * the height the layer was cut at; at layer_end, each laser's share
     * of the layer, lasers[k] laser k + 1's (time->exposure and jump are
     * then the busiest laser's). has_cut 0: not a build (cut unset). */
    int has_cut;
    double cut;
    const struct lam_scan_time *lasers;
    size_t nlasers;
    const struct lam_part_time *parts; /* at layer_end of a build: each part's time */
    size_t nparts;
    const long long *section_part; /* a build: the part of each of section's contours */
    const long long *support_part; /* a build: the part of each of support's contours */
    const long long *overhang_part; /* a build: the part of each of overhang's contours */
    double balance;          /* a build, at layer_end: the busiest laser over the ideal (lasers.h) */
} lam_layer_info;

/* A part's share of a build layer (lam_layer_info.parts): exposure and
 * jumps of its own blocks, seconds. */
typedef struct lam_part_time {
    long long part;          /* attrs.part */
    double time;
} lam_part_time;

/* Every operation carries both frames' coordinates, computed once by the
 * planner: a consumer takes the frame it needs and never converts back. */

/* One stage move (LADRP): from where the stage is to xyz. */
typedef struct lam_move_info {
    lam_attrs attrs;         /* vocab.h */
    int deposit;             /* 1 laser on (LAM_KIND_DEPOSIT), 0 travel (LAM_KIND_TRAVEL) */
    double xyz[3];           /* where the stage goes, output frame */
    double uv[2];            /* the same in the layer frame */
} lam_move_info;

/* One closed contour for contour-based processes (SLS, CLI). */
typedef struct lam_contour_info {
    lam_attrs attrs;         /* vocab.h; attrs.part is CLI's $$LABEL id (1: one model a job) */
    int solid;               /* 1 solid (counter-clockwise), 0 hole (clockwise) */
    int depth;
    double z;                /* build height */
    const double *xyz;       /* n points, 3 doubles each, output frame, no repeated closing point */
    const double *uv;        /* the same points in the layer frame (2 doubles each) */
    size_t n;
    double power, speed, point_distance, exposure_time;   /* the contour's exposure */
} lam_contour_info;

/* One block of hatch vectors (a region, a stripe or an island). */
typedef struct lam_hatch_info {
    lam_attrs attrs;         /* as lam_contour_info's */
    int kind;                /* lam_vec_kind (vocab.h): core, up-skin or down-skin */
    double z;                /* build height */
    const double *xyz;       /* 2 points per vector (start, end), 3 doubles each, output frame */
    const double *uv;        /* the same in the layer frame, 4 doubles per vector */
    size_t n;                /* vectors */
    double angle;            /* hatch direction, degrees in the layer plane */
    double power, speed, point_distance, exposure_time;
} lam_hatch_info;

typedef struct lam_sink {
    void *ctx;
    int (*begin)(void *ctx, const lam_job_info *job);
    int (*layer)(void *ctx, const lam_layer_info *layer);
    int (*layer_end)(void *ctx, const lam_layer_info *layer);
    int (*feed)(void *ctx, double rate);
    int (*laser)(void *ctx, int on);
    /* move the stage (absolute); m->deposit: laser on */
    int (*move)(void *ctx, const lam_move_info *m);
    int (*contour)(void *ctx, const lam_contour_info *c);
    /* a sink may buffer its output: it is complete (and write errors are
     * reported) only when end returns */
    int (*end)(void *ctx);
    /* release ctx; called exactly once, after end or instead of it */
    void (*destroy)(void *ctx);
    /* a block of hatch vectors (NULL: the sink ignores hatches) */
    int (*hatches)(void *ctx, const lam_hatch_info *h);
    /* Optional (NULL: the sink cannot; a planner on threads then records
     * each layer and replays it, plan_record.h): a formatter of this
     * sink's layers for a worker thread, so a worker writes a whole
     * layer's bytes itself and the sink appends them in layer order
     * (issue 15). Called on the calling thread after begin; `moves`: the
     * plan sends moves (LADRP). Fills *out and returns LAM_OK, LAM_EUSAGE
     * (making nothing) when the sink cannot for such a plan (a text
     * dialect's relative moves hang on the moves before), or LAM_ENOMEM
     * (err). The sink must outlive the fork. A tee forwards it (tee.h). */
    int (*fork)(void *ctx, int moves, struct lam_sink_fork *out, lam_error *err);
} lam_sink;

/* A layer's bytes formatted by a worker's fork of a sink (lam_sink.fork). */
typedef struct lam_layer_text {
    char *s;                 /* the bytes (owned: free) */
    size_t len, cap;
    int complete;            /* the layer's layer_end was formatted */
    int has_sep;             /* the first separator of the layer is s[sep_at .. +sep_len) */
    size_t sep_at, sep_len;
    size_t blocks;           /* contour and hatch blocks in it */
    size_t layer;            /* the layer's index (plugin writers, plugin.h) */
} lam_layer_text;

/* A worker's fork of a sink (lam_sink.fork). */
typedef struct lam_sink_fork {
    lam_sink sink;           /* on the worker's thread: layer, the operations, layer_end
                                (no begin, end or fork); sink.destroy releases the fork */
    /* Start a layer (ctx: sink.ctx); its errors (out of memory) go to err
     * until the next start. */
    void (*start)(void *ctx, lam_error *err);
    /* Move the bytes formatted since the start into t, and t's old buffer
     * into the worker for reuse (ctx: sink.ctx). */
    void (*take)(void *ctx, lam_layer_text *t);
    /* On the calling thread, in layer order: write t through the forked
     * sink (ctx: main) as if its layer had been sent to it. Returns the
     * sink's error. */
    int (*put)(void *main, const lam_layer_text *t);
    void *main;              /* the forked sink's ctx */
} lam_sink_fork;

#endif
