/* Between repair.c and repair_fill.c; internal to core/mesh. */
#ifndef LAM_REPAIR_INTERNAL_H
#define LAM_REPAIR_INTERNAL_H

#include "model.h"

/* Step 3 of repair.h: chain md's open edges into loops and append
 * triangles filling each to md->mesh (md's edges and shells are then
 * stale: the caller rebuilds the model from the mesh). Counts go into r.
 * Errors: LAM_ENOMEM. */
int lam_repair_fill(lam_model *md, lam_repair_report *r, lam_error *err);

#endif
