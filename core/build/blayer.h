/* One build layer's plan, held as data between the planners and the
 * lasers (lasers.h): every part's contour passes and hatch blocks in the
 * order its planner made them, each with its own copy of its points.
 * The build planner (build_plan.h) collects the operations a part's
 * planner sends (a collecting lam_sink, blayer_sink), the lasers
 * assign, cut and order them, and the blocks are then sent to the real
 * sink. Coordinates: builds plan in the plate frame, so the layer frame is
 * the output frame (u, v = x, y; w = z). */
#ifndef LAM_BLAYER_H
#define LAM_BLAYER_H

#include <stddef.h>

#include "error.h"
#include "hatch.h"
#include "plan.h"

/* One block: a closed contour pass (polyline, n points) or n vectors
 * (2 points each: a hatch block, or a contour pass cut at a laser field's
 * edge, whose vectors keep kind LAM_KIND_CONTOUR). */
typedef struct lam_bblock {
    lam_attrs attrs;         /* part, style, label, laser (0 until assigned) */
    int kind;                /* lam_vec_kind: a region */
    int polyline;            /* 1: a closed contour of n points; 0: n vectors */
    int solid, depth;        /* a contour's (lam_contour_info) */
    double angle;            /* a hatch block's direction */
    lam_exposure exposure;   /* power, speed, point distance, exposure time */
    double *uv;              /* owned: 2 doubles a point (polyline n points; vectors 2n) */
    size_t n;
} lam_bblock;

typedef struct lam_blayer {
    lam_bblock *b;
    size_t n, cap;
} lam_blayer;

/* Append a block whose points (npts points, 2 doubles each) are copied;
 * the block's uv is set to the copy. LAM_ENOMEM (err). */
int lam_blayer_push(lam_blayer *l, const lam_bblock *b, const double *uv, size_t npts, lam_error *err);

/* Drop every block (keeping the room). */
void lam_blayer_clear(lam_blayer *l);

/* Free every block and the array. */
void lam_blayer_free(lam_blayer *l);

/* The points block b has: n for a polyline, 2n for vectors. */
size_t lam_bblock_points(const lam_bblock *b);

#endif
