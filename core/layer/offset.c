#include "offset.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "geos.h"

int lam_layer_offset(const lam_layer *L, double distance, lam_layer **out, lam_error *err)
{
    *out = NULL;
    lam_layer *R = calloc(1, sizeof *R);
    if (!R) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory offsetting a layer");
    R->index = L->index;
    R->floor = L->floor;
    R->ceiling = L->ceiling;
    R->width = L->width;
    R->cut = L->cut;
    if (L->ncontours == 0) {
        *out = R;
        return LAM_OK;
    }
    lam_geos c;
    int rc = lam_geos_init(&c, err);
    if (rc) {
        free(R);
        return rc;
    }
    lam_loops_builder loops = { 0 };
    c.grid = lam_geos_grid(lam_geos_layer_magnitude(L));
    GEOSGeometry *mp = lam_geos_layer_region(&c, L), *buf = NULL;
    const char *stage = "region";
    if (!mp) rc = LAM_EGEOM;
    if (!rc && (stage = "offset", !(buf = lam_geos_offset(&c, mp, distance)))) rc = LAM_EGEOM;
    if (!rc) rc = lam_geos_add_polygons(&c, buf, &loops);
    if (buf) GEOSGeom_destroy_r(c.h, buf);
    if (mp) GEOSGeom_destroy_r(c.h, mp);
    if (!rc) rc = lam_contours_assign(R, &loops.loops, err);
    else if (rc == LAM_ENOMEM) lam_error_set(err, rc, NULL, 0, 0, "out of memory offsetting a layer");
    else lam_error_set(err, rc, NULL, 0, 0, "layer %zu: %s by %g: GEOS: %s", L->index + 1, stage, distance,
                       c.msg[0] ? c.msg : "failed");
    lam_loops_builder_free(&loops);
    lam_geos_finish(&c);
    if (rc) {
        lam_layer_free(R);
        return rc;
    }
    *out = R;
    return LAM_OK;
}
