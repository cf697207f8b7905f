#include "offset.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"
#include "geos.h"

static GEOSGeometry *ring_of(lam_geos *c, const lam_layer *L, const lam_contour *k)
{
    GEOSCoordSequence *cs = GEOSCoordSeq_create_r(c->h, (unsigned)(k->n + 1), 2);
    if (!cs) return NULL;
    for (size_t i = 0; i <= k->n; i++) {
        const double *p = L->uv + 2 * (k->first + i % k->n);
        GEOSCoordSeq_setXY_r(c->h, cs, (unsigned)i, p[0], p[1]);
    }
    return GEOSGeom_createLinearRing_r(c->h, cs);
}

/* The layer's material as GEOS polygons: every solid with the holes directly
 * inside it (islands inside holes are solids of their own). */
static GEOSGeometry *material(lam_geos *c, const lam_layer *L)
{
    size_t n = L->ncontours;
    GEOSGeometry **polys = calloc(n + 1, sizeof *polys);
    GEOSGeometry **holes = calloc(n + 1, sizeof *holes);
    if (!polys || !holes) {
        free(polys);
        free(holes);
        return NULL;
    }
    unsigned np = 0;
    int bad = 0;
    for (size_t i = 0; i < n && !bad; i++) {
        if (L->contours[i].kind != LAM_SOLID) continue;
        unsigned nh = 0;
        for (size_t j = 0; j < n && !bad; j++)
            if (L->contours[j].parent == (long)i && L->contours[j].kind == LAM_HOLE)
                bad = !(holes[nh++] = ring_of(c, L, &L->contours[j]));
        GEOSGeometry *shell = bad ? NULL : ring_of(c, L, &L->contours[i]);
        GEOSGeometry *p = shell ? GEOSGeom_createPolygon_r(c->h, shell, holes, nh) : NULL;
        if (!p) {
            for (unsigned k = 0; k < nh; k++)
                if (holes[k]) GEOSGeom_destroy_r(c->h, holes[k]);
            if (shell) GEOSGeom_destroy_r(c->h, shell);
            bad = 1;
            break;
        }
        polys[np++] = p;
    }
    free(holes);
    GEOSGeometry *mp = NULL;
    if (!bad) mp = GEOSGeom_createCollection_r(c->h, GEOS_MULTIPOLYGON, polys, np);
    if (!mp)
        for (unsigned k = 0; k < np; k++) GEOSGeom_destroy_r(c->h, polys[k]);
    free(polys);
    return mp;
}

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
    if (lam_geos_init(&c)) {
        free(R);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory (GEOS)");
    }
    int rc = LAM_OK;
    lam_loops_builder loops = { 0 };
    GEOSGeometry *mp = material(&c, L), *buf = NULL;
    if (!mp) rc = LAM_EGEOM;
    if (!rc && !(buf = GEOSBufferWithStyle_r(c.h, mp, distance, 8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 2.0)))
        rc = LAM_EGEOM;
    if (!rc) rc = lam_geos_add_polygons(&c, buf, &loops);
    if (buf) GEOSGeom_destroy_r(c.h, buf);
    if (mp) GEOSGeom_destroy_r(c.h, mp);
    if (!rc) rc = lam_contours_assign(R, &loops.loops, err);
    else if (rc == LAM_ENOMEM) lam_error_set(err, rc, NULL, 0, 0, "out of memory offsetting a layer");
    else lam_error_set(err, rc, NULL, 0, 0, "offsetting layer %zu failed%s%s", L->index, c.msg[0] ? ": " : "", c.msg);
    lam_loops_builder_free(&loops);
    lam_geos_finish(&c);
    if (rc) {
        lam_layer_free(R);
        return rc;
    }
    *out = R;
    return LAM_OK;
}
