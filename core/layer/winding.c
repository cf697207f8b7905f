#include "winding.h"

#include "geos.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lam_loops_winding(const lam_loops *L, double u, double v)
{
    int w = 0;
    const double *p = L->uv;
    for (size_t l = 0; l < L->nloops; l++) {
        size_t n = L->len[l];
        for (size_t i = 0; i < n; i++) {
            const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n);
            double cross = (b[0] - a[0]) * (v - a[1]) - (u - a[0]) * (b[1] - a[1]);
            if (a[1] <= v) {
                if (b[1] > v && cross > 0) w++;
            } else if (b[1] <= v && cross < 0) {
                w--;
            }
        }
        p += 2 * n;
    }
    return w;
}

/* The loops as one multilinestring, each loop closed (NULL: *rc says why). */
static GEOSGeometry *loop_lines(lam_geos *c, const lam_loops *loops, int *rc)
{
    size_t nl = loops->nloops;
    GEOSGeometry **lines = calloc(nl, sizeof *lines), *mls = NULL;
    if (!lines) {
        *rc = LAM_ENOMEM;
        return NULL;
    }
    *rc = LAM_OK;
    const double *p = loops->uv;
    for (size_t l = 0; l < nl && !*rc; l++) {
        size_t n = loops->len[l];
        GEOSCoordSequence *cs = GEOSCoordSeq_create_r(c->h, (unsigned)(n + 1), 2);
        if (!cs) {
            *rc = LAM_EGEOM;
            break;
        }
        for (size_t i = 0; i <= n; i++)
            GEOSCoordSeq_setXY_r(c->h, cs, (unsigned)i, p[2 * (i % n)], p[2 * (i % n) + 1]);
        if (!(lines[l] = GEOSGeom_createLineString_r(c->h, cs))) *rc = LAM_EGEOM;
        p += 2 * n;
    }
    if (!*rc && !(mls = GEOSGeom_createCollection_r(c->h, GEOS_MULTILINESTRING, lines, (unsigned)nl))) *rc = LAM_EGEOM;
    if (mls) {
        free(lines); /* owned by mls now */
        return mls;
    }
    for (size_t l = 0; l < nl; l++)
        if (lines[l]) GEOSGeom_destroy_r(c->h, lines[l]);
    free(lines);
    return NULL;
}

/* The union of the faces of the arrangement where the loops' winding
 * number is not zero, into *uni (NULL: no such face). */
static int nonzero_union(lam_geos *c, const lam_loops *loops, const GEOSGeometry *faces, GEOSGeometry **uni)
{
    *uni = NULL;
    int nf = GEOSGetNumGeometries_r(c->h, faces), rc = LAM_OK;
    GEOSGeometry **kept = calloc(nf > 0 ? (size_t)nf : 1, sizeof *kept);
    if (!kept) return LAM_ENOMEM;
    unsigned nk = 0;
    for (int i = 0; i < nf; i++) {
        const GEOSGeometry *face = GEOSGetGeometryN_r(c->h, faces, i);
        GEOSGeometry *pt = face ? GEOSPointOnSurface_r(c->h, face) : NULL;
        double x, y;
        if (!pt || !GEOSGeomGetX_r(c->h, pt, &x) || !GEOSGeomGetY_r(c->h, pt, &y)) {
            if (pt) GEOSGeom_destroy_r(c->h, pt);
            rc = LAM_EGEOM;
            break;
        }
        GEOSGeom_destroy_r(c->h, pt);
        if (lam_loops_winding(loops, x, y) != 0) kept[nk++] = GEOSGeom_clone_r(c->h, face);
    }
    GEOSGeometry *coll = NULL;
    if (!rc && nk && !(coll = GEOSGeom_createCollection_r(c->h, GEOS_MULTIPOLYGON, kept, nk))) rc = LAM_EGEOM;
    if (coll) {
        free(kept); /* owned by coll now */
        *uni = GEOSUnaryUnionPrec_r(c->h, coll, c->grid); /* faces of one noding: valid, edge to edge */
        GEOSGeom_destroy_r(c->h, coll);
        return *uni ? LAM_OK : LAM_EGEOM;
    }
    for (int i = 0; i < nf; i++)
        if (kept[i]) GEOSGeom_destroy_r(c->h, kept[i]);
    free(kept);
    return rc;
}

int lam_fill_nonzero(lam_loops *loops, lam_error *err)
{
    if (loops->nloops == 0) return LAM_OK;
    lam_geos c;
    int rc = lam_geos_init(&c, err);
    if (rc) return rc;
    double mag = 0;
    for (size_t i = 0; i < 2 * loops->npoints; i++) mag = fmax(mag, fabs(loops->uv[i]));
    c.grid = lam_geos_grid(mag);
    GEOSGeometry *mls = loop_lines(&c, loops, &rc), *noded = NULL, *faces = NULL, *uni = NULL;
    lam_loops_builder out = { 0 };
    /* union of linework nodes it at every crossing, by snap-rounding on
     * the grid (geos.h): near-coincident edges of overlapping shells are
     * noded where a floating-point noder finds "non-noded intersections" */
    if (!rc && !(noded = GEOSUnaryUnionPrec_r(c.h, mls, c.grid))) rc = LAM_EGEOM;
    const GEOSGeometry *in[1] = { noded };
    if (!rc && !(faces = GEOSPolygonize_r(c.h, in, 1))) rc = LAM_EGEOM;
    if (!rc) rc = nonzero_union(&c, loops, faces, &uni);
    if (!rc && uni) rc = lam_geos_add_polygons(&c, uni, &out);
    if (!rc) {
        free(loops->uv);
        free(loops->len);
        *loops = out.loops;
        memset(&out, 0, sizeof out);
    }
    if (mls) GEOSGeom_destroy_r(c.h, mls);
    if (noded) GEOSGeom_destroy_r(c.h, noded);
    if (faces) GEOSGeom_destroy_r(c.h, faces);
    if (uni) GEOSGeom_destroy_r(c.h, uni);
    lam_loops_builder_free(&out);
    lam_geos_finish(&c);
    if (rc == LAM_ENOMEM) return lam_error_set(err, rc, NULL, 0, 0, "out of memory merging overlapping outlines");
    if (rc) return lam_error_set(err, rc, NULL, 0, 0, "non-zero fill (merging overlapping outlines): GEOS: %s",
                                  c.msg[0] ? c.msg : "failed");
    return LAM_OK;
}
