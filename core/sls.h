/* The thesis's SLS contour dialect (SPEC 4.2), written straight from
 * layers: per contour `contour Z`, `loop P`, P lines `X Y Z`, `endloop`,
 * `endcontour`, six decimals, model coordinates, blocks separated by a blank
 * line. Solids come out counter-clockwise and holes clockwise because the
 * layer's contours already are. */
#ifndef LAM_SLS_H
#define LAM_SLS_H

#include "slice.h"
#include "writer.h"

/* Write one layer's contours; *blocks counts blocks written so far (start
 * at 0) so blank lines go between blocks only. */
int lam_sls_write_layer(lam_writer *w, const lam_layer *layer, const lam_frame *frame, size_t *blocks);

#endif
