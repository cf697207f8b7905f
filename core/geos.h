/* The GEOS glue every polygon operation shares: a context that keeps the
 * last GEOS message, and turning polygon results back into lam_loops. */
#ifndef LAM_GEOS_H
#define LAM_GEOS_H

#include "contour.h"
#include "geos_lazy.h"

typedef struct lam_geos {
    GEOSContextHandle_t h;
    char msg[256];           /* GEOS's last error message, "" if none */
} lam_geos;

/* Start a context, loading GEOS on the first call (geos_lazy.h) / end it
 * (also after a failed start). Errors: LAM_EIO when GEOS cannot be loaded,
 * LAM_ENOMEM when it cannot start a context. */
int lam_geos_init(lam_geos *g, lam_error *err);
void lam_geos_finish(lam_geos *g);

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

/* The layer's material as a GEOS MultiPolygon (caller destroys): every
 * solid with the holes directly inside it (islands inside holes are solids
 * of their own). NULL when GEOS fails (out of memory, a bad ring). */
GEOSGeometry *lam_geos_layer_region(lam_geos *g, const struct lam_layer *L);

/* Free a builder's arrays. */
void lam_loops_builder_free(lam_loops_builder *b);

#endif
