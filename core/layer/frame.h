/* Layer frames: the right-handed frame (u, v, w) a model is sliced in, w
 * the slice axis. Layer geometry (layer.h) is in (u, v) at a height along
 * w; "counter-clockwise" means seen from +w. */
#ifndef LAM_FRAME_H
#define LAM_FRAME_H

#include "error.h"

/* A right-handed layer frame: u x v = w, all unit length. */
typedef struct lam_frame {
    double u[3], v[3], w[3];
} lam_frame;

/* The thesis's frames: 'x' -> (y, z, x), 'y' -> (z, x, y), 'z' -> (x, y, z).
 * Returns LAM_EUSAGE for any other letter. */
int lam_frame_axis(char axis, lam_frame *f, lam_error *err);

/* A frame for any non-zero direction: w = d/|d|, u from the world axis least
 * aligned with w (ties: x, y, z), v = w x u. +x, +y, +z give the axis frames. */
int lam_frame_direction(const double d[3], lam_frame *f, lam_error *err);

/* Layer-frame point (u, v) at height w to model coordinates. */
void lam_frame_to_model(const lam_frame *f, double u, double v, double w, double xyz[3]);

#endif
