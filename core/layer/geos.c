#include "geos.h"

#include "layer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"

static void on_error(const char *message, void *userdata)
{
    lam_geos *g = userdata;
    snprintf(g->msg, sizeof g->msg, "%s", message);
}

int lam_geos_init(lam_geos *g, lam_error *err)
{
    g->msg[0] = '\0';
    g->h = NULL;
    g->grid = lam_geos_grid(1);
    int rc = lam_geos_load(err);
    if (rc) return rc;
    g->h = GEOS_init_r();
    if (!g->h) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory (GEOS)");
    GEOSContext_setErrorMessageHandler_r(g->h, on_error, g);
    return LAM_OK;
}

void lam_geos_finish(lam_geos *g)
{
    if (g->h) GEOS_finish_r(g->h);
    g->h = NULL;
}

static int add_ring(lam_geos *gc, const GEOSGeometry *ring, lam_loops_builder *b)
{
    const GEOSCoordSequence *cs = GEOSGeom_getCoordSeq_r(gc->h, ring);
    unsigned n = 0;
    if (!cs || !GEOSCoordSeq_getSize_r(gc->h, cs, &n)) return LAM_EGEOM;
    if (n < 4) return LAM_OK; /* a closed ring needs 3 points + the closing one */
    n--;
    lam_loops *L = &b->loops;
    if (L->npoints + n > b->cap_points) {
        double *nu = lam_grow(L->uv, &b->cap_points, L->npoints + n, 2 * sizeof *nu, 64);
        if (!nu) return LAM_ENOMEM;
        L->uv = nu;
    }
    if (L->nloops + 1 > b->cap_loops) {
        size_t *nl = lam_grow(L->len, &b->cap_loops, L->nloops + 1, sizeof *nl, 8);
        if (!nl) return LAM_ENOMEM;
        L->len = nl;
    }
    double *dst = L->uv + 2 * L->npoints;
    for (unsigned i = 0; i < n; i++) GEOSCoordSeq_getXY_r(gc->h, cs, i, &dst[2 * i], &dst[2 * i + 1]);
    /* GEOS keeps points of straight runs split at former crossings */
    n = (unsigned)lam_loop_simplify(dst, n);
    if (n < 3 || lam_loop_area(dst, n) == 0) return LAM_OK;
    L->npoints += n;
    L->len[L->nloops++] = n;
    return LAM_OK;
}

int lam_geos_add_polygons(lam_geos *gc, const GEOSGeometry *g, lam_loops_builder *b)
{
    int type = GEOSGeomTypeId_r(gc->h, g);
    if (type == GEOS_POLYGON) {
        if (GEOSisEmpty_r(gc->h, g)) return LAM_OK;
        int rc = add_ring(gc, GEOSGetExteriorRing_r(gc->h, g), b);
        int nh = GEOSGetNumInteriorRings_r(gc->h, g);
        for (int k = 0; k < nh && !rc; k++) rc = add_ring(gc, GEOSGetInteriorRingN_r(gc->h, g, k), b);
        return rc;
    }
    if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        int n = GEOSGetNumGeometries_r(gc->h, g), rc = LAM_OK;
        for (int i = 0; i < n && !rc; i++) rc = lam_geos_add_polygons(gc, GEOSGetGeometryN_r(gc->h, g, i), b);
        return rc;
    }
    return LAM_OK; /* points and lines have no area */
}

void lam_loops_builder_free(lam_loops_builder *b)
{
    free(b->loops.uv);
    free(b->loops.len);
    memset(b, 0, sizeof *b);
}

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

double lam_geos_grid(double magnitude)
{
    int e = 1; /* 1 = 2^0 < 2^1 */
    if (magnitude > 0 && isfinite(magnitude)) (void)frexp(magnitude, &e); /* magnitude < 2^e */
    return ldexp(1.0, e - LAM_GEOS_GRID_BITS);
}

double lam_geos_layer_magnitude(const lam_layer *L)
{
    double m = 0;
    for (size_t i = 0; i < L->ncontours; i++)
        for (int k = 0; k < 4; k++) m = fmax(m, fabs(L->contours[i].bbox[k]));
    return m;
}

/* A section is valid by construction up to rounding: where the plane meets
 * the model at a point of two boundaries (a hole touching the outline, as
 * an oblique cut through a cube with a hole makes), the hole's vertex may
 * lie a rounding outside the outline, and GEOS's overlays refuse the
 * region ("TopologyException: ... Self-intersection"). Such a region is
 * repaired by GEOS's own MakeValid (the structure method: areas stay areas,
 * collapsed slivers go), so hatching and offsets see the material the
 * section means. */
GEOSGeometry *lam_geos_valid(lam_geos *c, GEOSGeometry *x)
{
    if (!x) return NULL;
    if (GEOSisValid_r(c->h, x) == 1) return x;
    GEOSMakeValidParams *p = GEOSMakeValidParams_create_r(c->h);
    GEOSGeometry *fixed = NULL;
    if (p && GEOSMakeValidParams_setMethod_r(c->h, p, GEOS_MAKE_VALID_STRUCTURE) &&
        GEOSMakeValidParams_setKeepCollapsed_r(c->h, p, 0))
        fixed = GEOSMakeValidWithParams_r(c->h, x, p);
    if (p) GEOSMakeValidParams_destroy_r(c->h, p);
    GEOSGeom_destroy_r(c->h, x);
    return fixed;
}

/* Snap-rounding overlays may add lower-dimension pieces (an intersection
 * of regions that touch along an edge or at a point, a sliver collapsed
 * on the grid): they hold no material, and a next overlay refuses mixed
 * dimensions, so only the polygons are kept. Takes x. */
static GEOSGeometry *polygons_of(lam_geos *c, GEOSGeometry *x)
{
    if (!x || GEOSGeomTypeId_r(c->h, x) != GEOS_GEOMETRYCOLLECTION) return x;
    int n = GEOSGetNumGeometries_r(c->h, x);
    GEOSGeometry **keep = calloc(n > 0 ? (size_t)n : 1, sizeof *keep), *out = NULL;
    unsigned k = 0;
    int bad = !keep;
    for (int i = 0; i < n && !bad; i++) {
        const GEOSGeometry *p = GEOSGetGeometryN_r(c->h, x, i);
        int t = p ? GEOSGeomTypeId_r(c->h, p) : -1;
        if (t == GEOS_POLYGON) bad = !(keep[k++] = GEOSGeom_clone_r(c->h, p));
        else if (t == GEOS_MULTIPOLYGON || t == GEOS_GEOMETRYCOLLECTION)
            bad = 1; /* overlays return flat collections */
    }
    if (!bad) out = GEOSGeom_createCollection_r(c->h, GEOS_MULTIPOLYGON, keep, k);
    if (!out)
        for (unsigned i = 0; keep && i < k; i++)
            if (keep[i]) GEOSGeom_destroy_r(c->h, keep[i]);
    free(keep);
    GEOSGeom_destroy_r(c->h, x);
    return out;
}

GEOSGeometry *lam_geos_intersection(lam_geos *c, const GEOSGeometry *a, const GEOSGeometry *b)
{
    return polygons_of(c, GEOSIntersectionPrec_r(c->h, a, b, c->grid));
}

GEOSGeometry *lam_geos_difference(lam_geos *c, const GEOSGeometry *a, const GEOSGeometry *b)
{
    return polygons_of(c, GEOSDifferencePrec_r(c->h, a, b, c->grid));
}

/* Buffer output is valid in principle, but it is built in floating point
 * from a region's near-coincident edges: it is checked like any input of a
 * boolean. */
GEOSGeometry *lam_geos_offset(lam_geos *c, const GEOSGeometry *a, double d)
{
    return lam_geos_valid(c, GEOSBufferWithStyle_r(c->h, a, d, 8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 2.0));
}

GEOSGeometry *lam_geos_grow(lam_geos *c, const GEOSGeometry *a, double d)
{
    return lam_geos_valid(c, GEOSBufferWithStyle_r(c->h, a, d, 16, GEOSBUF_CAP_ROUND, GEOSBUF_JOIN_ROUND, 2.0));
}

GEOSGeometry *lam_geos_union(lam_geos *c, const GEOSGeometry *a, const GEOSGeometry *b)
{
    return GEOSUnionPrec_r(c->h, a, b, c->grid);
}

GEOSGeometry *lam_geos_layer_region(lam_geos *c, const lam_layer *L)
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
    return lam_geos_valid(c, mp);
}
