/* The winding rule: fill rules for a layer's loops (even-odd, non-zero).
 *
 * The slicer's raw loops are oriented by the mesh (material on the left).
 * Even-odd (the thesis's nesting parity) keeps them as they are. Non-zero
 * keeps the region where their winding number is not zero, so overlapping
 * shells of a multi-body mesh merge into one outline: the loops are noded
 * with GEOS, the faces of the arrangement polygonised, each face kept when
 * the winding number at an interior point is non-zero, and the kept faces
 * united. */
#ifndef LAM_WINDING_H
#define LAM_WINDING_H

#include "contour.h"

/* Replace *loops (arrays malloc'd; replaced in place) by the outlines of the
 * non-zero region. Errors: LAM_ENOMEM, LAM_EGEOM (GEOS failed). */
int lam_fill_nonzero(lam_loops *loops, lam_error *err);

/* Winding number of the loops around (u, v) (points exactly on a loop count
 * by the usual half-open rule). */
int lam_loops_winding(const lam_loops *loops, double u, double v);

#endif
