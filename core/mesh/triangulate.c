/* Triangulation of planar faces (Unigrafix faces with holes, OBJ polygons).
 *
 * Triangles and convex polygons are fanned directly; anything else (concave
 * outlines, holes) goes to GEOS's constrained Delaunay triangulation in the
 * face's own plane. GEOS adds no vertices, so every output corner is mapped
 * back to the face's vertex by its exact 2D coordinates: the mesh keeps the
 * shared vertices that the slicer chains by. */
#include "mesh.h"

#include "geos.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Project onto the coordinate plane that the face's Newell normal is most
 * perpendicular to, keeping orientation (the dropped axis' sign decides the
 * order of the two remaining axes). */
typedef struct proj {
    int ax, ay;
} proj;

static proj choose_projection(const lam_mesh *m, const uint32_t *ring, size_t n)
{
    double nx = 0, ny = 0, nz = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = m->xyz + 3 * (size_t)ring[i];
        const double *b = m->xyz + 3 * (size_t)ring[(i + 1) % n];
        nx += (a[1] - b[1]) * (a[2] + b[2]);
        ny += (a[2] - b[2]) * (a[0] + b[0]);
        nz += (a[0] - b[0]) * (a[1] + b[1]);
    }
    double ax = fabs(nx), ay = fabs(ny), az = fabs(nz);
    proj p;
    if (az >= ax && az >= ay) {
        p.ax = 0; p.ay = 1;
        if (nz < 0) { p.ax = 1; p.ay = 0; }
    } else if (ax >= ay) {
        p.ax = 1; p.ay = 2;
        if (nx < 0) { p.ax = 2; p.ay = 1; }
    } else {
        p.ax = 2; p.ay = 0;
        if (ny < 0) { p.ax = 0; p.ay = 2; }
    }
    return p;
}

static double px(const lam_mesh *m, proj p, uint32_t v) { return m->xyz[3 * (size_t)v + p.ax]; }
static double py(const lam_mesh *m, proj p, uint32_t v) { return m->xyz[3 * (size_t)v + p.ay]; }

static double cross3(const lam_mesh *m, proj p, uint32_t a, uint32_t b, uint32_t c)
{
    return (px(m, p, b) - px(m, p, a)) * (py(m, p, c) - py(m, p, a)) -
           (py(m, p, b) - py(m, p, a)) * (px(m, p, c) - px(m, p, a));
}

/* Strictly convex or with collinear runs, turning once around. */
static int is_convex(const lam_mesh *m, proj p, const uint32_t *r, size_t n)
{
    int sign = 0, xflips = 0, yflips = 0, lastsx = 0, lastsy = 0, firstsx = 0, firstsy = 0;
    for (size_t i = 0; i < n; i++) {
        double c = cross3(m, p, r[i], r[(i + 1) % n], r[(i + 2) % n]);
        int s = (c > 0) - (c < 0);
        if (s) {
            if (sign && s != sign) return 0;
            sign = s;
        }
        double dx = px(m, p, r[(i + 1) % n]) - px(m, p, r[i]);
        double dy = py(m, p, r[(i + 1) % n]) - py(m, p, r[i]);
        int sx = (dx > 0) - (dx < 0), sy = (dy > 0) - (dy < 0);
        if (sx) {
            if (lastsx && sx != lastsx) xflips++;
            if (!firstsx) firstsx = sx;
            lastsx = sx;
        }
        if (sy) {
            if (lastsy && sy != lastsy) yflips++;
            if (!firstsy) firstsy = sy;
            lastsy = sy;
        }
    }
    if (lastsx && firstsx && lastsx != firstsx) xflips++;
    if (lastsy && firstsy && lastsy != firstsy) yflips++;
    return sign != 0 && xflips <= 2 && yflips <= 2;
}

static GEOSGeometry *make_ring(lam_geos *c, const lam_mesh *m, proj p,
                               const uint32_t *r, size_t n)
{
    GEOSCoordSequence *cs = GEOSCoordSeq_create_r(c->h, (unsigned)(n + 1), 2);
    if (!cs) return NULL;
    for (size_t i = 0; i <= n; i++) {
        uint32_t v = r[i % n];
        GEOSCoordSeq_setXY_r(c->h, cs, (unsigned)i, px(m, p, v), py(m, p, v));
    }
    return GEOSGeom_createLinearRing_r(c->h, cs);
}

typedef struct key2 {
    double x, y;
    uint32_t v;
} key2;

static int cmp_key2(const void *a, const void *b)
{
    const key2 *p = a, *q = b;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    return p->v < q->v ? -1 : p->v > q->v;
}

static int lookup(const key2 *keys, size_t n, double x, double y, uint32_t *v)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (keys[mid].x < x || (keys[mid].x == x && keys[mid].y < y)) lo = mid + 1;
        else hi = mid;
    }
    if (lo < n && keys[lo].x == x && keys[lo].y == y) {
        *v = keys[lo].v;
        return 1;
    }
    return 0;
}

static int geos_triangulate(lam_mesh *m, proj p, const uint32_t *idx, const size_t *ring_len,
                            size_t nrings, size_t total, double outer_area, uint32_t face,
                            lam_error *err)
{
    lam_geos c;
    int rc = lam_geos_init(&c, err);
    GEOSGeometry **holes = NULL, *shell = NULL, *poly = NULL, *tris = NULL;
    key2 *keys = rc ? NULL : malloc(total * sizeof *keys);
    if (rc) goto done;
    if (!keys) {
        rc = lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory triangulating a face");
        goto done;
    }
    for (size_t i = 0; i < total; i++) {
        keys[i].x = px(m, p, idx[i]);
        keys[i].y = py(m, p, idx[i]);
        keys[i].v = idx[i];
    }
    qsort(keys, total, sizeof *keys, cmp_key2);

    shell = make_ring(&c, m, p, idx, ring_len[0]);
    if (nrings > 1) holes = calloc(nrings - 1, sizeof *holes);
    if (!shell || (nrings > 1 && !holes)) goto geos_fail;
    size_t off = ring_len[0];
    for (size_t r = 1; r < nrings; r++) {
        holes[r - 1] = make_ring(&c, m, p, idx + off, ring_len[r]);
        if (!holes[r - 1]) goto geos_fail;
        off += ring_len[r];
    }
    poly = GEOSGeom_createPolygon_r(c.h, shell, holes, (unsigned)(nrings - 1));
    if (!poly) goto geos_fail;
    shell = NULL; /* owned by poly now */
    for (size_t r = 1; r < nrings; r++) holes[r - 1] = NULL;
    tris = GEOSConstrainedDelaunayTriangulation_r(c.h, poly);
    if (!tris) goto geos_fail;

    int ng = GEOSGetNumGeometries_r(c.h, tris);
    if (ng <= 0) {
        rc = lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                           "face could not be triangulated (degenerate or self-intersecting outline)");
        goto done;
    }
    for (int g = 0; g < ng; g++) {
        const GEOSGeometry *t = GEOSGetGeometryN_r(c.h, tris, g);
        const GEOSGeometry *ring = t ? GEOSGetExteriorRing_r(c.h, t) : NULL;
        const GEOSCoordSequence *cs = ring ? GEOSGeom_getCoordSeq_r(c.h, ring) : NULL;
        if (!cs) goto geos_fail;
        uint32_t v[3];
        for (unsigned k = 0; k < 3; k++) {
            double x, y;
            if (!GEOSCoordSeq_getXY_r(c.h, cs, k, &x, &y) || !lookup(keys, total, x, y, &v[k])) {
                rc = lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                                   "face triangulation produced a point that is not a vertex of the face");
                goto done;
            }
        }
        double a = cross3(m, p, v[0], v[1], v[2]);
        if ((a < 0) != (outer_area < 0)) {
            uint32_t tmp = v[1];
            v[1] = v[2];
            v[2] = tmp;
        }
        if ((rc = lam_mesh_add_tri(m, v[0], v[1], v[2], face, err))) goto done;
    }
    goto done;

geos_fail:
    rc = lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "face could not be triangulated%s%s",
                       c.msg[0] ? ": " : "", c.msg);
done:
    if (tris) GEOSGeom_destroy_r(c.h, tris);
    if (poly) GEOSGeom_destroy_r(c.h, poly);
    if (shell) GEOSGeom_destroy_r(c.h, shell);
    if (holes) {
        for (size_t r = 1; r < nrings; r++)
            if (holes[r - 1]) GEOSGeom_destroy_r(c.h, holes[r - 1]);
        free(holes);
    }
    free(keys);
    lam_geos_finish(&c);
    return rc;
}

int lam_mesh_add_polygon(lam_mesh *m, const uint32_t *idx, const size_t *ring_len,
                         size_t nrings, uint32_t face, lam_error *err)
{
    if (nrings == 0)
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "face has no vertices");
    size_t total = 0;
    for (size_t r = 0; r < nrings; r++) {
        if (ring_len[r] < 3)
            return lam_error_set(err, LAM_EGEOM, NULL, 0, 0,
                                 "%s has %zu vertices, at least 3 are needed",
                                 r ? "a hole of the face" : "face", ring_len[r]);
        total += ring_len[r];
    }
    for (size_t i = 0; i < total; i++)
        if (idx[i] >= m->nverts)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "face names a vertex that does not exist");
    if (nrings == 1 && total == 3)
        return lam_mesh_add_tri(m, idx[0], idx[1], idx[2], face, err);

    proj p = choose_projection(m, idx, ring_len[0]);
    double area2 = 0;
    for (size_t i = 0; i < ring_len[0]; i++)
        area2 += px(m, p, idx[i]) * py(m, p, idx[(i + 1) % ring_len[0]]) -
                 px(m, p, idx[(i + 1) % ring_len[0]]) * py(m, p, idx[i]);
    /* Convex faces fan directly. So do faces without area (all points in
     * a line): their triangles are degenerate, which the model reports and
     * the slicer survives, where refusing them would stop the whole import. */
    if (nrings == 1 && (area2 == 0 || is_convex(m, p, idx, total))) {
        for (size_t i = 1; i + 1 < total; i++) {
            int rc = lam_mesh_add_tri(m, idx[0], idx[i], idx[i + 1], face, err);
            if (rc) return rc;
        }
        return LAM_OK;
    }
    if (area2 == 0)
        return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "face with holes has an outline of zero area");
    return geos_triangulate(m, p, idx, ring_len, nrings, total, area2, face, err);
}
