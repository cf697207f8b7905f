/* Contours of a layer: assembly into lam_layer, nesting (solid/hole by
 * depth), orientation, canonical start, measures (thesis 4.2.2).
 *
 * Classification is geometric, never from the mesh's winding: from a point
 * just inside each loop at its lowest-leftmost vertex a ray goes towards
 * -u, and the loops it crosses an odd number of times contain it (nest.h:
 * a sweep over v with the active edges in a search tree, O(N log N) for a
 * layer of N points). Depth 0 is solid, 1 hole, 2 solid...
 * and the parent is the smallest containing loop. Solids are then turned
 * counter-clockwise and holes clockwise, decided at the lowest-leftmost
 * vertex by the cross product of its two neighbours (the thesis's test),
 * and each loop starts at that vertex. */
#ifndef LAM_CONTOUR_H
#define LAM_CONTOUR_H

#include "slice.h"

/* Loops as input to lam_contours_assign: points back to back (2 doubles
 * each), loop l has len[l] points. */
typedef struct lam_loops {
    double *uv;
    size_t *len;
    size_t nloops, npoints;
} lam_loops;

/* Classify, orient, order and measure loops and store them in layer
 * (layer->uv, layer->contours; any previous ones are freed). Loops with fewer
 * than 3 points or no area must have been dropped by the caller.
 * Errors: LAM_ENOMEM. */
int lam_contours_assign(lam_layer *layer, const lam_loops *loops, lam_error *err);

/* Point-in-contour by the even-odd rule on this contour alone (its own
 * boundary, ignoring holes): 1 inside, 0 outside. */
int lam_contour_contains(const lam_layer *layer, const lam_contour *c, double u, double v);

/* The thesis's orientation test: at the lowest-leftmost vertex, the cross
 * product of the edges to and from it. > 0 counter-clockwise, < 0
 * clockwise; 0 only for a degenerate loop. */
double lam_contour_turn(const lam_layer *layer, const lam_contour *c);

/* Remove repeated points (also across the closing edge) and points exactly
 * in line with their neighbours on a straight run (a mesh edge crossing
 * the middle of a flat side). Returns the new point count. */
size_t lam_loop_simplify(double *uv, size_t n);

/* Signed area by the shoelace formula (> 0 counter-clockwise). */
double lam_loop_area(const double *uv, size_t n);

#endif
