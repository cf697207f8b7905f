/* Contours of a layer: assembly into lam_layer, nesting (solid/hole by
 * depth), orientation, canonical start, measures (thesis 4.2.2).
 *
 * Classification is geometric, never from the mesh's winding: from a point
 * just inside each loop at its lowest-leftmost vertex a ray goes towards
 * -u, and the loops it crosses an odd number of times contain it (nest.h:
 * a sweep over v with the active edges in a search tree, O(N log N) for a
 * layer of N points). Depth 0 is solid, 1 hole, 2 solid...
 * and the parent is the smallest containing loop, which is always larger
 * (nest.h: lam_nest_larger), so no contour is its own ancestor; that is
 * checked for every layer. Solids are then turned counter-clockwise and
 * holes clockwise, the direction decided by the signed area (compensated
 * sum) of a loop cleaned of repeated points, spikes and straight-run
 * points; on such a loop the thesis's test (the turn at the lowest-leftmost
 * vertex, lam_contour_turn) agrees, but where it does not, the area
 * decides. Each loop starts at its lowest-leftmost vertex.
 *
 * Degenerate sections (SPEC 3.3), lam_loops_tidy: a loop of (nearly) no
 * area is a sliver and is dropped; coincident loops (the same points in
 * the same cyclic order, either direction) cancel in pairs. The second is
 * the even-odd rule itself: two coincident loops bound a region of even
 * parity, no material, and they are what a plane through a ring of
 * vertices at a model's extreme (the bottom ring of a torus cut at its
 * floor) or a doubled outline gives: the two sides of a band of zero
 * width, whose exact section has no area. Of three coincident loops one
 * stays. */
#ifndef LAM_CONTOUR_H
#define LAM_CONTOUR_H

#include "error.h"
#include "layer.h"

/* Loops as input to lam_contours_assign: points back to back (2 doubles
 * each), loop l has len[l] points. */
typedef struct lam_loops {
    double *uv;
    size_t *len;
    size_t nloops, npoints;
} lam_loops;

/* Classify, orient, order and measure loops and store them in layer
 * (layer->uv, layer->contours; any previous ones are freed). Loops with fewer
 * than 3 points or no area must have been dropped by the caller
 * (lam_loops_tidy). Errors: LAM_ENOMEM; LAM_EGEOM should nesting ever break
 * its invariant (a parent not larger than its child). */
int lam_contours_assign(lam_layer *layer, const lam_loops *loops, lam_error *err);

/* Point-in-contour by the even-odd rule on this contour alone (its own
 * boundary, ignoring holes): 1 inside, 0 outside. */
int lam_contour_contains(const lam_layer *layer, const lam_contour *c, double u, double v);

/* The thesis's orientation test: at the lowest-leftmost vertex, the cross
 * product of the edges to and from it. > 0 counter-clockwise, < 0
 * clockwise; 0 only for a degenerate loop. */
double lam_contour_turn(const lam_layer *layer, const lam_contour *c);

/* Clean a loop in place: remove repeated points (also across the closing
 * edge), spikes (a point where the loop folds back along the edge it came
 * by) and points in line with their neighbours on a straight run (a mesh
 * edge crossing the middle of a flat side), "in line" up to rounding of
 * the cross product; repeated until none is left. Returns the new point
 * count (under 3: nothing with area is left). */
size_t lam_loop_simplify(double *uv, size_t n);

/* Signed area by the shoelace formula (> 0 counter-clockwise), summed with
 * compensation so that the sign of a thin loop's area is its own. */
double lam_loop_area(const double *uv, size_t n);

/* Drop the degenerate loops of a layer, in place (loops keep their order):
 * loops of under 3 points or |area| <= min_area (slivers, counted in
 * *slivers) and, with cancel_twins, coincident loops in pairs (counted in
 * *twins, two per pair). Loops must be simplified (lam_loop_simplify).
 * Errors: LAM_ENOMEM. */
int lam_loops_tidy(lam_loops *loops, double min_area, int cancel_twins, size_t *slivers, size_t *twins,
                   lam_error *err);

#endif
