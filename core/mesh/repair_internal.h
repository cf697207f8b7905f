/* Between repair.c and repair_fill.c; internal to core/mesh. */
#ifndef LAM_REPAIR_INTERNAL_H
#define LAM_REPAIR_INTERNAL_H

#include "model.h"

/* How a loop is filled: the least-area programme (when short enough and
 * within budget), the loop's polygon triangulated in its plane (GEOS), a
 * fan from its centroid. Each is tried after the one before when the fill
 * crossed the surface (repair.c). */
enum { LAM_FILL_DP, LAM_FILL_PLANE, LAM_FILL_FAN };

/* The fill's choices and what it made, per loop in the walk's order
 * (which depends only on the model, so a second fill of the same model
 * walks the same loops). */
typedef struct lam_fill_plan {
    unsigned char *method;  /* per loop; loops past nmethod: LAM_FILL_DP */
    size_t nmethod;
    size_t *first;          /* per loop + 1: its triangles [first[k], first[k+1]) in the filled mesh */
    size_t nloops, cap;
} lam_fill_plan;

/* Step 3 of repair.h: chain md's open edges into loops and append
 * triangles filling each to md->mesh (md's edges and shells are then
 * stale: the caller rebuilds the model from the mesh, or truncates the
 * mesh back). Counts go into r, the loops into plan. Errors: LAM_ENOMEM. */
int lam_repair_fill(lam_model *md, lam_fill_plan *plan, lam_repair_report *r, lam_error *err);

#endif
