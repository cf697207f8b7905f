/* Offsetting a layer's contours (GEOS buffer): solids shrink and holes grow
 * for a negative distance, so a beam or bead of width w is kept inside the
 * material by offsetting by -w/2. Sharp corners keep their shape (mitre
 * joins, limit 2: a corner sharper than about 60 degrees is bevelled). */
#ifndef LAM_OFFSET_H
#define LAM_OFFSET_H

#include "error.h"
#include "layer.h"

/* A new layer (lam_layer_free) with the same index, heights and cut, whose
 * contours are L's material region offset by `distance` (negative: inward).
 * Material that vanishes simply has no contour. Errors: LAM_ENOMEM, LAM_EGEOM. */
int lam_layer_offset(const lam_layer *L, double distance, lam_layer **out, lam_error *err);

#endif
