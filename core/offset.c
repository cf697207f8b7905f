#include "offset.h"

#include <geos_c.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contour.h"

typedef struct ctx {
    GEOSContextHandle_t h;
    char msg[256];
} ctx;

static void on_error(const char *message, void *userdata)
{
    ctx *c = userdata;
    snprintf(c->msg, sizeof c->msg, "%s", message);
}

static GEOSGeometry *ring_of(ctx *c, const lam_layer *L, const lam_contour *k)
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
static GEOSGeometry *material(ctx *c, const lam_layer *L)
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

static int append_ring(ctx *c, const GEOSGeometry *ring, lam_loops *out, size_t *cap_pts, size_t *cap_loops)
{
    const GEOSCoordSequence *cs = GEOSGeom_getCoordSeq_r(c->h, ring);
    unsigned n = 0;
    if (!cs || !GEOSCoordSeq_getSize_r(c->h, cs, &n)) return LAM_EGEOM;
    if (n < 4) return LAM_OK;
    n--;
    if (out->npoints + n > *cap_pts) {
        size_t cap = *cap_pts ? *cap_pts : 64;
        while (cap < out->npoints + n) cap *= 2;
        double *nu = realloc(out->uv, 2 * cap * sizeof *nu);
        if (!nu) return LAM_ENOMEM;
        out->uv = nu;
        *cap_pts = cap;
    }
    if (out->nloops + 1 > *cap_loops) {
        size_t cap = *cap_loops ? 2 * *cap_loops : 8;
        size_t *nl = realloc(out->len, cap * sizeof *nl);
        if (!nl) return LAM_ENOMEM;
        out->len = nl;
        *cap_loops = cap;
    }
    for (unsigned i = 0; i < n; i++)
        GEOSCoordSeq_getXY_r(c->h, cs, i, &out->uv[2 * (out->npoints + i)], &out->uv[2 * (out->npoints + i) + 1]);
    n = (unsigned)lam_loop_simplify(out->uv + 2 * out->npoints, n);
    if (n < 3 || lam_loop_area(out->uv + 2 * out->npoints, n) == 0) return LAM_OK;
    out->npoints += n;
    out->len[out->nloops++] = n;
    return LAM_OK;
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
    ctx c = { GEOS_init_r(), "" };
    if (!c.h) {
        free(R);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory (GEOS)");
    }
    GEOSContext_setErrorMessageHandler_r(c.h, on_error, &c);
    int rc = LAM_OK;
    lam_loops loops = { 0 };
    size_t cap_pts = 0, cap_loops = 0;
    GEOSGeometry *mp = material(&c, L), *buf = NULL;
    if (!mp) rc = LAM_EGEOM;
    if (!rc && !(buf = GEOSBufferWithStyle_r(c.h, mp, distance, 8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 2.0)))
        rc = LAM_EGEOM;
    if (!rc) {
        int np = GEOSGetNumGeometries_r(c.h, buf);
        for (int i = 0; i < np && !rc; i++) {
            const GEOSGeometry *poly = GEOSGetGeometryN_r(c.h, buf, i);
            if (GEOSGeomTypeId_r(c.h, poly) != GEOS_POLYGON || GEOSisEmpty_r(c.h, poly)) continue;
            rc = append_ring(&c, GEOSGetExteriorRing_r(c.h, poly), &loops, &cap_pts, &cap_loops);
            int nh = GEOSGetNumInteriorRings_r(c.h, poly);
            for (int k = 0; k < nh && !rc; k++)
                rc = append_ring(&c, GEOSGetInteriorRingN_r(c.h, poly, k), &loops, &cap_pts, &cap_loops);
        }
    }
    if (buf) GEOSGeom_destroy_r(c.h, buf);
    if (mp) GEOSGeom_destroy_r(c.h, mp);
    if (!rc) rc = lam_contours_assign(R, &loops, err);
    else if (rc == LAM_ENOMEM) lam_error_set(err, rc, NULL, 0, 0, "out of memory offsetting a layer");
    else lam_error_set(err, rc, NULL, 0, 0, "offsetting layer %zu failed%s%s", L->index, c.msg[0] ? ": " : "", c.msg);
    free(loops.uv);
    free(loops.len);
    GEOS_finish_r(c.h);
    if (rc) {
        lam_layer_free(R);
        return rc;
    }
    *out = R;
    return LAM_OK;
}
