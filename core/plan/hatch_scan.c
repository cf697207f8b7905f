/* The scanline: where the hatch lines of one direction cross an area's
 * rings (the half-open rule of hatch.h: an edge holds its lower end), and
 * the even-odd pairs of those crossings as segments. */
#include <stdlib.h>

#include "hatch_internal.h"

static int cmp_crossing(const void *a, const void *b)
{
    const crossing *p = a, *q = b;
    if (p->k != q->k) return p->k < q->k ? -1 : 1;
    return (p->x > q->x) - (p->x < q->x);
}

static int add_crossing(hatcher *h, long k, double x)
{
    if (h->ncr == h->cap_cr) {
        size_t cap = h->cap_cr ? 2 * h->cap_cr : 256;
        crossing *n = realloc(h->cr, cap * sizeof *n);
        if (!n) return LAM_ENOMEM;
        h->cr = n;
        h->cap_cr = cap;
    }
    h->cr[h->ncr++] = (crossing){ k, x };
    return LAM_OK;
}

/* Crossings of one ring (rotated by c, s) with the lines y = (k + 1/2) d. */
static int ring_crossings(hatcher *h, const GEOSGeometry *ring, double c, double s, double d)
{
    const GEOSCoordSequence *cs = GEOSGeom_getCoordSeq_r(h->g->h, ring);
    unsigned n = 0;
    if (!cs || !GEOSCoordSeq_getSize_r(h->g->h, cs, &n)) return LAM_EGEOM;
    if (n < 4) return LAM_OK;
    if (n > h->cap_ring) {
        double *nr = realloc(h->ring, 2 * (size_t)n * sizeof *nr);
        if (!nr) return LAM_ENOMEM;
        h->ring = nr;
        h->cap_ring = n;
    }
    for (unsigned i = 0; i < n; i++) {
        double u, v;
        if (!GEOSCoordSeq_getXY_r(h->g->h, cs, i, &u, &v)) return LAM_EGEOM;
        h->ring[2 * i] = u * c + v * s;
        h->ring[2 * i + 1] = -u * s + v * c;
    }
    for (unsigned i = 0; i + 1 < n; i++) {
        double x0 = h->ring[2 * i], y0 = h->ring[2 * i + 1], x1 = h->ring[2 * i + 2], y1 = h->ring[2 * i + 3];
        if (y0 == y1) continue;
        if (y0 > y1) {
            double t = x0;
            x0 = x1, x1 = t;
            t = y0, y0 = y1, y1 = t;
        }
        /* lines with y0 <= y < y1: k from ceil(y0/d - 1/2) */
        double kl = ceil(y0 / d - 0.5), kh = ceil(y1 / d - 0.5) - 1;
        if (kh - kl > MAX_VECTORS) return LAM_EUSAGE;
        for (double kk = kl; kk <= kh; kk++) {
            double y = (kk + 0.5) * d;
            if (y < y0 || y >= y1) continue;
            double x = x0 + (x1 - x0) * (y - y0) / (y1 - y0);
            int rc = add_crossing(h, (long)kk, x);
            if (rc) return rc;
        }
    }
    return LAM_OK;
}

static int polygon_crossings(hatcher *h, const GEOSGeometry *g, double c, double s, double d)
{
    int type = GEOSGeomTypeId_r(h->g->h, g);
    if (type == GEOS_POLYGON) {
        if (GEOSisEmpty_r(h->g->h, g)) return LAM_OK;
        int rc = ring_crossings(h, GEOSGetExteriorRing_r(h->g->h, g), c, s, d);
        int nh = GEOSGetNumInteriorRings_r(h->g->h, g);
        for (int i = 0; i < nh && !rc; i++) rc = ring_crossings(h, GEOSGetInteriorRingN_r(h->g->h, g, i), c, s, d);
        return rc;
    }
    if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        int n = GEOSGetNumGeometries_r(h->g->h, g), rc = LAM_OK;
        for (int i = 0; i < n && !rc; i++) rc = polygon_crossings(h, GEOSGetGeometryN_r(h->g->h, g, i), c, s, d);
        return rc;
    }
    return LAM_OK;
}

static int add_seg(hatcher *h, long k, double x0, double x1)
{
    if (h->nsegs == h->cap_segs) {
        size_t cap = h->cap_segs ? 2 * h->cap_segs : 256;
        seg *n = realloc(h->segs, cap * sizeof *n);
        if (!n) return LAM_ENOMEM;
        h->segs = n;
        h->cap_segs = cap;
    }
    h->segs[h->nsegs++] = (seg){ k, x0, x1 };
    return LAM_OK;
}

int lam_hatch_scan(hatcher *h, const GEOSGeometry *g, double c, double s, double d)
{
    h->ncr = h->nsegs = 0;
    int rc = polygon_crossings(h, g, c, s, d);
    if (rc) return rc;
    if (h->ncr > 2 * MAX_VECTORS) return LAM_EUSAGE;
    if (h->ncr) qsort(h->cr, h->ncr, sizeof *h->cr, cmp_crossing);
    for (size_t i = 0; i + 1 < h->ncr; i++) {
        if (h->cr[i].k != h->cr[i + 1].k) continue;
        if (h->cr[i + 1].x > h->cr[i].x && (rc = add_seg(h, h->cr[i].k, h->cr[i].x, h->cr[i + 1].x))) return rc;
        i++;
    }
    return LAM_OK;
}
