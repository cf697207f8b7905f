/* The GEOS glue every polygon operation shares: a context that keeps the
 * last GEOS message, the precision grid its booleans work on, valid
 * inputs, and turning polygon results back into lam_loops.
 *
 * Robustness (issue 22): GEOS's floating-point overlays throw
 * "TopologyException: found non-noded intersection" on regions whose
 * edges nearly coincide (sections of a mesh cut through many facets
 * meeting at a vertex, skins of layers that differ by a rounding). Every
 * boolean of layer regions therefore (1) gets inputs that are valid before
 * it runs (lam_geos_valid: GEOS's MakeValid where GEOSisValid says no, not
 * as a retry after a failure), and (2) runs by snap-rounding on a fixed
 * grid (GEOS's ...Prec overlays, OverlayNG with a fixed precision model),
 * which nodes every crossing on the grid and cannot meet a non-noded one.
 * The grid (lam_geos_grid) is a power of two 2^-LAM_GEOS_GRID_BITS of the
 * largest coordinate magnitude of the layers involved: 2^20 times a
 * double's rounding there, so the overlay's own arithmetic stays far inside
 * a cell, and for a part 100 mm from the origin about 3e-8 mm, far below
 * any machine's resolution (micrometres) or what a program writes (CLI:
 * 1e-5 mm): snapping moves a written coordinate by far less than its last
 * digit. It depends
 * only on the layers, never on the thread that plans them: any -j gives the
 * same program. */
#ifndef LAM_GEOS_H
#define LAM_GEOS_H

#include "contour.h"
#include "geos_lazy.h"

typedef struct lam_geos {
    GEOSContextHandle_t h;
    double grid;             /* the grid of lam_geos_intersection/_difference (> 0) */
    char msg[256];           /* GEOS's last error message, "" if none */
} lam_geos;

/* log2 of the grid's fraction of the coordinates' magnitude (see above). */
#define LAM_GEOS_GRID_BITS 32

/* Start a context, loading GEOS on the first call (geos_lazy.h) / end it
 * (also after a failed start). Errors: LAM_EIO when GEOS cannot be loaded,
 * LAM_ENOMEM when it cannot start a context. */
int lam_geos_init(lam_geos *g, lam_error *err);
void lam_geos_finish(lam_geos *g);

/* The grid for coordinates of at most `magnitude` in absolute value: the
 * power of two 2^(e - LAM_GEOS_GRID_BITS) for magnitude < 2^e (magnitude 0:
 * as for 1). */
double lam_geos_grid(double magnitude);

/* The largest |coordinate| of L's contours (their bounding boxes). */
double lam_geos_layer_magnitude(const struct lam_layer *L);

/* x made valid, taking x: x itself when GEOS finds it valid, else GEOS's
 * MakeValid (structure method: areas stay areas, collapsed parts go).
 * NULL when GEOS fails (x is destroyed). */
GEOSGeometry *lam_geos_valid(lam_geos *g, GEOSGeometry *x);

/* a intersected with / minus b by snap-rounding on g->grid (a and b
 * valid); the result is valid. NULL when GEOS fails (g->msg says why). */
GEOSGeometry *lam_geos_intersection(lam_geos *g, const GEOSGeometry *a, const GEOSGeometry *b);
GEOSGeometry *lam_geos_difference(lam_geos *g, const GEOSGeometry *a, const GEOSGeometry *b);

/* Region a (valid) offset by d (mitre joins, limit 2), made valid for the
 * booleans that follow. NULL when GEOS fails. */
GEOSGeometry *lam_geos_offset(lam_geos *g, const GEOSGeometry *a, double d);

/* Region a (valid) grown by d with round joins (16 segments a quarter
 * circle, inside the true circle: never more than d), made valid: for
 * d >= 0 the points within d of a; d < 0 shrinks it. NULL when GEOS
 * fails. */
GEOSGeometry *lam_geos_grow(lam_geos *g, const GEOSGeometry *a, double d);
/* a united with b by snap-rounding on g->grid (a and b valid). NULL when
 * GEOS fails. */
GEOSGeometry *lam_geos_union(lam_geos *g, const GEOSGeometry *a, const GEOSGeometry *b);
/* Growable lam_loops being filled from GEOS output. */
typedef struct lam_loops_builder {
    lam_loops loops;         /* owned until taken */
    size_t cap_points, cap_loops;
} lam_loops_builder;

/* Append every ring of every polygon in g (a Polygon, MultiPolygon or
 * collection) to b: exterior rings and holes alike, each without GEOS's
 * repeated closing point, simplified (lam_loop_simplify); rings left with
 * under 3 points or no area are skipped. Returns LAM_OK, LAM_ENOMEM or
 * LAM_EGEOM. */
int lam_geos_add_polygons(lam_geos *gc, const GEOSGeometry *g, lam_loops_builder *b);

struct lam_layer;

/* The layer's material as valid GEOS polygons (caller destroys): every
 * solid with the holes directly inside it (islands inside holes are solids
 * of their own), through lam_geos_valid. NULL when GEOS fails (out of
 * memory, a bad ring). */
GEOSGeometry *lam_geos_layer_region(lam_geos *g, const struct lam_layer *L);

/* Free a builder's arrays. */
void lam_loops_builder_free(lam_loops_builder *b);

#endif
