/* Repair on load (issue 24): a mesh as users have it (a scan with holes, a
 * CAD export with cracks, facets written twice or the wrong way round)
 * made into closed shells before it is sliced, in 3D, once, instead of
 * each layer closing its own gaps differently.
 *
 * lam_model_repair takes a built model (model_build.c: exact weld, edges,
 * shells oriented by adjacency and volume) and, only when it has open or
 * non-manifold edges, rebuilds it from a repaired copy of its mesh:
 *   1. weld within a tolerance: vertices of open edges that lie within
 *      weld_tolerance of another open edge's vertex become one (cracks
 *      between unwelded copies); the tolerance is relative to the model's
 *      size (1e-6 of its bounding box diagonal unless given);
 *   2. facets that lost their area (a repeated vertex after the weld, or
 *      three collinear vertices) and facets with the same three vertices
 *      as an earlier one go;
 *   3. the model is rebuilt (orientation per shell), and each boundary
 *      loop (the open edges chained, walked so that the fill runs against
 *      the shell's winding) is filled with triangles: a minimal-area
 *      triangulation of the loop for loops of up to LAM_REPAIR_DP_MAX
 *      vertices (planar or not: on a planar simple loop that is a
 *      triangulation of the polygon itself), otherwise its polygon
 *      triangulated in its plane (GEOS) or a fan from its centroid (a lone facet's loop is left open and counted in
 *      holes_left: filled, it would be a two-sided sliver of no volume);
 *      a loop that crosses itself in its best-fit plane is
 *      filled the same way and counted. The programme and the crossing
 *      test have a budget for the whole model (repair_fill.c), so that no
 *      file makes the fill run unbounded: past it, loops are triangulated
 *      in their plane (GEOS) or fanned;
 *      A loop whose fill crosses the rest of the surface (the least-area
 *      fill of a scan's hole can fold through the rim's far side: one of
 *      the Stanford bunny's five) is filled again the next way, in its
 *      plane, then as a fan (at most two more fills of the model);
 *   4. the model is rebuilt again, and what remains is counted: open and
 *      non-manifold edges, and edges that pass through a facet not their
 *      own where one of the two is a fill's (self-intersections a fill
 *      made; Embree segment queries, rays.h; the file's own crossings are
 *      not searched: --fill nonzero is what slices overlapping bodies).
 * Facets the file wound against the majority of their shell (which the
 * model build turns to agree) are counted in `flipped`, for every STL and
 * OBJ model repaired (a Unigrafix file's winding means nothing, SPEC 2.1:
 * not counted); a shell wound inward throughout is turned outward silently,
 * as the model build always has (SPEC: the file's winding is never
 * trusted).
 *
 * Closed, manifold models are never changed, so their slices stay the
 * same bit for bit. */
#ifndef LAM_REPAIR_H
#define LAM_REPAIR_H

#include "error.h"
#include "model.h"

/* Loops longer than this are triangulated in their plane, or fanned from
 * their centroid (the minimal-area triangulation is cubic in the loop's
 * length). */
#define LAM_REPAIR_DP_MAX 400

typedef struct lam_repair_opts {
    double weld_tolerance; /* model units; <= 0: 1e-6 of the bounding box diagonal */
} lam_repair_opts;

/* Repair *md in place (o may be NULL: defaults): *md may be replaced by a
 * new model (the old one is freed); (*md)->repair says what was done.
 * Errors: LAM_ENOMEM, LAM_EGEOM when nothing with area is left; on error
 * the model is freed and *md is NULL. */
int lam_model_repair(lam_model **md, const lam_repair_opts *o, lam_error *err);

/* The report's fields, one row each, for every writer of it (the run's
 * JSON, `lamina info --json`, `lamina repair --json`): X(name) with the
 * field's name in lam_repair_report, which is also its JSON key. */
#define LAM_REPAIR_COUNTS(X)                                                                        \
    X(welded) X(degenerate) X(duplicates) X(flipped) X(holes) X(hole_edges) X(fill_triangles)     \
    X(crossing_loops) X(holes_left) X(boundary_edges) X(nonmanifold_edges) X(crossing_edges)
#define LAM_REPAIR_MEASURES(X) X(weld_tolerance) X(fill_area) X(largest_hole)

/* 1 when repair changed the model (anything but `ran` and the tolerance
 * non-zero), or left it open or non-manifold. */
int lam_repair_acted(const lam_repair_report *r);

/* One line for messages: "filled 37 holes (223 boundary edges), 12 facets
 * flipped" (only the actions taken; "" when none). Returns buf. */
const char *lam_repair_summary(const lam_repair_report *r, char *buf, size_t size);

#endif
