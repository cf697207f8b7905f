/* Several lasers on one plate (issue 25, item 5): each layer's blocks
 * (blayer.h) are shared between the lasers whose fields reach them.
 *
 * - Every vector is exposed by one laser whose field (a box on the plate,
 *   boundary included, grown by 1e-9 of the plate's size, the plate being
 *   the fields' bounding box) holds it whole. A block that one field holds
 *   goes whole to a laser; a vector that no field holds whole is cut where
 *   it leaves a field into pieces that fields hold; a contour pass that no
 *   field holds becomes a block of contour vectors (polyline 0, its edges
 *   in order, the closing one last; kind stays LAM_KIND_CONTOUR) and is cut
 *   in the same way. The cut walks along the vector: from where it is, the
 *   field holding that point whose part of the vector reaches furthest
 *   (the lowest laser on a tie) takes the piece up to where the vector
 *   leaves it. The pieces of one block that the walk gave one laser make
 *   one block. A piece that no field reaches is an error.
 * - Balance: the blocks (and a cut block's per-laser blocks) that only one
 *   laser's field holds go to it; the others, longest first (ties: in
 *   their order), to the laser whose field holds them and has the least
 *   work so far (the lowest on a tie): longest processing time first, so
 *   the busiest laser ends at most one block's time above the ideal when
 *   fields overlap fully. A block's work is its exposure and its jumps
 *   inside it, plus one jump delay (0 for a block of nothing). Two parts of
 *   one cut block that end on one laser are one block again.
 * - Order: a laser's blocks go part by part, the part furthest downstream
 *   of the gas flow first (largest dot(part centre, gas_flow)); ties and a
 *   zero gas flow: by part number; within a part, the planner's order.
 * - Output: laser 1's blocks in its order, then laser 2's, ...; each
 *   block's attrs.laser is its laser (1-based), and the layer's per-laser
 *   times (lam_scan_time, from lam_scan_time_path over the laser's
 *   sequence, the first jump of a layer not counted as lam_scan_time_path
 *   does) are filled. Paths are timed as plan_sls.c times them, so one
 *   laser over a part's layer gives the SLS planner's time: a contour
 *   pass one closed path of its perimeter from its first point, a vector
 *   one path. A contour's vector (a cut pass) is an open path (its point
 *   count: lam_scan_time_path's for a vector) counted in `vectors` but not
 *   in hatch_length. layers is 1 for a laser that exposes anything, else
 *   0; recoat is 0. Blocks of no vectors are kept (on some laser).
 * Deterministic: the same input gives the same output. */
#ifndef LAM_LASERS_H
#define LAM_LASERS_H

#include <stddef.h>

#include "blayer.h"
#include "error.h"
#include "hatch.h"

#define LAM_LASERS_MAX 16

typedef struct lam_laser_set {
    size_t n;                         /* lasers (>= 1) */
    double field[LAM_LASERS_MAX][4];  /* x0 y0 x1 y1 on the plate, x0 < x1, y0 < y1 */
    double gas_flow[2];               /* the gas flow's direction (0 0: none) */
    const double *part_centre;        /* part p's footprint centre (x, y) at
                                         part_centre[2 * (p - 1)], parts 1 .. nparts;
                                         NULL: none (then no gas flow) */
    size_t nparts;
} lam_laser_set;

/* Share the blocks of `in` (in the planners' order, parts in turn) between
 * the lasers of ls: `out` (cleared first) gets them assigned, cut and
 * ordered as above; times[0 .. ls->n) each laser's time for the layer
 * (zeroed first; recoat not included). cfg gives the jump speed and delay
 * (lam_scan_time_path). in is not changed (out must be another layer);
 * out's blocks own copies of their points. Errors (out then empty; times
 * zeroed but on LAM_EUSAGE): LAM_EINVAL "a vector at (x, y) of part P lies
 * outside every laser's field" (where the piece no field reaches starts),
 * LAM_EINVAL "part P has no footprint centre for the gas flow" (a gas
 * flow and a block's part outside 1 .. nparts, or no part_centre),
 * LAM_EUSAGE (n outside 1 .. LAM_LASERS_MAX, an empty field), LAM_ENOMEM. */
int lam_lasers_share(const lam_laser_set *ls, const lam_scan_cfg *cfg, const lam_blayer *in, lam_blayer *out,
                     lam_scan_time *times, lam_error *err);

/* The layer's balance: the busiest laser's time (exposure + jump) over the
 * ideal, the mean time of the lasers that have any work (a time above 0);
 * 1 when no laser has work. */
double lam_lasers_balance(const lam_scan_time *times, size_t n);

#endif
