/* Plan data: a plan kept as data, per layer and in order (contour passes
 * and vectors, in the layer frame), for Lua's plan data (machine:plan,
 * lua/l_plan.c), so a recipe measures a plan without parsing its text. It
 * is a consumer of the plan's vector stream (vstream.h; views.h puts it in
 * the stream with the run's other views), so it sees the vectors the JSON
 * and the viewer see, decoded once.
 *
 * What is kept: each contour pass (SLS: solid or hole, depth, its points),
 * each hatch vector (core, up-skin, down-skin) and each stage move (LADRP:
 * deposit or travel, from the stage's previous position), each with its
 * 1-based order among the layer's operations (a contour pass is one) and
 * its attributes (vocab.h). Coordinates are (u, v) in the layer frame
 * whatever the output frame: the planner's own. */
#ifndef LAM_PLAN_DATA_H
#define LAM_PLAN_DATA_H

#include <stddef.h>

#include "error.h"
#include "plan.h"
#include "vstream.h"

typedef struct lam_rec_vector {
    double uv[4];            /* from (u, v) to (u, v) */
    size_t order;            /* 1-based among the layer's contours and vectors */
    int kind;                /* lam_vec_kind (vocab.h): deposit, travel, core, upskin, downskin */
    lam_attrs attrs;
} lam_rec_vector;

typedef struct lam_rec_contour {
    size_t first, n;         /* points first .. first+n-1 of lam_plan_data.pts (2 doubles each) */
    size_t order;
    int solid, depth;
    lam_attrs attrs;
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
    lam_error *err;          /* private */
} lam_plan_data;

/* Make *out a consumer that records into r (zeroed here). r must not move
 * while out is in use; the consumer has no destroy: release r with
 * lam_plan_data_free. Recording fails with LAM_ENOMEM (in err). */
void lam_plan_data_consumer(lam_plan_data *r, lam_error *err, lam_vec_consumer *out);

/* The layer being recorded (the last one begun), or NULL before any. */
lam_rec_layer *lam_plan_data_current(lam_plan_data *r);

/* Release what r holds and zero it (NULL is fine). */
void lam_plan_data_free(lam_plan_data *r);

#endif
