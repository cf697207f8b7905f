/* Plan data, a recording sink: keeps what a planner sends, per layer and in order
 * (contour passes and vectors, in the layer frame), and passes every call
 * on to another sink. Lua's plan data (machine:plan, lua/l_plan.c) is
 * read from it, so a recipe measures a plan without parsing its text.
 *
 * What is kept: each contour pass (SLS: solid or hole, depth, its points),
 * each hatch vector (core, up-skin, down-skin) and each stage move (LADRP:
 * deposit or travel, from the stage's previous position), each with its
 * 1-based order among the layer's operations. Coordinates are (u, v) in the
 * layer frame whatever the output frame: a model-frame position is taken
 * back to the layer frame with the run's frame (orthonormal, so a dot
 * product). */
#ifndef LAM_PLAN_DATA_H
#define LAM_PLAN_DATA_H

#include <stddef.h>

#include "error.h"
#include "plan.h"
#include "slice.h"

typedef enum lam_rec_kind {
    LAM_REC_DEPOSIT,         /* LADRP: a stage move with the laser on */
    LAM_REC_TRAVEL,          /* LADRP: a stage move with the laser off */
    LAM_REC_CORE,            /* SLS hatch vectors, by lam_vec_type */
    LAM_REC_UPSKIN,
    LAM_REC_DOWNSKIN,
    LAM_REC_KINDS
} lam_rec_kind;

/* The kind's name: "deposit", "travel", "core", "upskin", "downskin". */
const char *lam_rec_kind_name(int kind);

typedef struct lam_rec_vector {
    double uv[4];            /* from (u, v) to (u, v) */
    size_t order;            /* 1-based among the layer's contours and vectors */
    int kind;                /* lam_rec_kind */
} lam_rec_vector;

typedef struct lam_rec_contour {
    size_t first, n;         /* points first .. first+n-1 of lam_plan_data.pts (2 doubles each) */
    size_t order;
    int solid, depth;
} lam_rec_contour;

typedef struct lam_rec_layer {
    size_t index;            /* 0-based index in its slicing run */
    double z;                /* cut height */
    size_t c0, nc;           /* its contours: lam_plan_data.contours[c0 .. c0+nc) */
    size_t v0, nv;           /* its vectors */
    size_t ops;              /* contours + vectors */
    /* set by the caller after the layer is planned (the planner's figures) */
    double deposit, travel;  /* lengths with the laser (beam) on and off */
    double time;             /* SLS: the layer's estimate, seconds; LADRP: 0 */
} lam_rec_layer;

typedef struct lam_plan_data {
    lam_rec_layer *layers;
    size_t nlayers, cap_layers;
    lam_rec_contour *contours;
    size_t ncontours, cap_contours;
    lam_rec_vector *vectors;
    size_t nvectors, cap_vectors;
    double *pts;
    size_t npts, cap_pts;    /* points (2 doubles each) */
    /* private */
    lam_frame frame;
    int frame_machine;
    double pos[2];
    const lam_sink *next;
    lam_error *err;
} lam_plan_data;

/* Make *out a sink that records into r (zeroed here) and forwards every
 * call to next (which stays the caller's: destroying out does not destroy
 * next). f and frame_machine say how output coordinates go back to the
 * layer frame. r must not move while out is in use; release it with
 * lam_plan_data_free. Recording fails with LAM_ENOMEM (in err). */
void lam_plan_data_sink(lam_plan_data *r, const lam_sink *next, const lam_frame *f, int frame_machine, lam_error *err,
                     lam_sink *out);

/* The layer being recorded (the last one begun), or NULL before any. */
lam_rec_layer *lam_plan_data_current(lam_plan_data *r);

/* Release what r holds and zero it (NULL is fine). */
void lam_plan_data_free(lam_plan_data *r);

#endif
