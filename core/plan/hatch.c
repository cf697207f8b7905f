/* Hatching a layer's region: skins by GEOS set operations, hatch lines by
 * a scanline over the area's rings, stripes and islands, orders. See
 * hatch.h for the rules. */
#include "hatch.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geos.h"

#define MAX_VECTORS 50000000.0

int lam_scan_hatches(const lam_scan_cfg *cfg)
{
    for (int t = LAM_VEC_CORE; t < LAM_VEC_TYPES; t++)
        if (cfg->type[t].strategy != LAM_HATCH_NONE) return 1;
    return 0;
}

int lam_scan_estimates(const lam_scan_cfg *cfg)
{
    if (lam_scan_hatches(cfg) || cfg->recoat_time > 0) return 1;
    for (int t = 0; t < LAM_VEC_TYPES; t++)
        if (cfg->type[t].exposure.speed > 0 || cfg->type[t].exposure.exposure_time > 0) return 1;
    return 0;
}

/* ---- the vector store ----------------------------------------------------- */

void lam_hatches_clear(lam_hatches *h)
{
    h->nv = h->nblocks = 0;
    memset(h->area, 0, sizeof h->area);
}

void lam_hatches_free(lam_hatches *h)
{
    if (!h) return;
    free(h->v);
    free(h->blocks);
    memset(h, 0, sizeof *h);
}

int lam_hatches_add_block(lam_hatches *h, int type, double angle)
{
    if (h->nblocks == h->cap_blocks) {
        size_t cap = h->cap_blocks ? 2 * h->cap_blocks : 16;
        lam_hatch_block *nb = realloc(h->blocks, cap * sizeof *nb);
        if (!nb) return LAM_ENOMEM;
        h->blocks = nb;
        h->cap_blocks = cap;
    }
    h->blocks[h->nblocks++] = (lam_hatch_block){ type, h->nv, 0, angle };
    return LAM_OK;
}

int lam_hatches_add(lam_hatches *h, double u0, double v0, double u1, double v1)
{
    if (!h->nblocks) return LAM_EUSAGE;
    if (h->nv == h->cap_v) {
        size_t cap = h->cap_v ? 2 * h->cap_v : 256;
        double *nv = realloc(h->v, 4 * cap * sizeof *nv);
        if (!nv) return LAM_ENOMEM;
        h->v = nv;
        h->cap_v = cap;
    }
    double *p = h->v + 4 * h->nv++;
    p[0] = u0, p[1] = v0, p[2] = u1, p[3] = v1;
    h->blocks[h->nblocks - 1].n++;
    return LAM_OK;
}

/* ---- scanline ------------------------------------------------------------- */

/* A piece of hatch line in the rotated frame: on line k, from x0 to x1. */
typedef struct seg {
    long k;
    double x0, x1;
} seg;

typedef struct crossing {
    long k;
    double x;
} crossing;

typedef struct hatcher {
    lam_geos *g;
    crossing *cr;
    size_t ncr, cap_cr;
    seg *segs;
    size_t nsegs, cap_segs;
    double *ring;            /* one ring, rotated */
    size_t cap_ring;
    size_t budget;           /* vectors still allowed in this layer */
} hatcher;

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

/* The hatch segments of area g at direction (c, s), sorted by line and x,
 * into h->segs (even-odd pairs of the crossings). */
static int scan(hatcher *h, const GEOSGeometry *g, double c, double s, double d)
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

/* ---- orders and output ----------------------------------------------------- */

/* Append the segments segs[0..n) (sorted by line, then x) of one block,
 * dropping short ones and ordering the rest. */
static int emit_block(hatcher *h, const seg *segs, size_t n, const lam_scan *sc, int type, double angle, double c,
                      double s, double d, lam_hatches *out)
{
    int rc = lam_hatches_add_block(out, type, angle);
    if (rc) return rc;
    size_t first = out->nv;
    long line = 0, prev_k = 0;
    int have_prev = 0;
    /* meander: lines alternate (counting lines that have vectors); within a
     * reversed line its pieces run backwards too */
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && segs[j].k == segs[i].k) j++;
        size_t kept = 0;
        for (size_t q = i; q < j; q++) kept += segs[q].x1 - segs[q].x0 >= sc->min_vector;
        if (kept) {
            if (have_prev && segs[i].k != prev_k) line++;
            have_prev = 1;
            prev_k = segs[i].k;
            int back = sc->order == LAM_ORDER_MEANDER && (line & 1);
            for (size_t t = 0; t < j - i; t++) {
                const seg *p = &segs[back ? j - 1 - t : i + t];
                if (p->x1 - p->x0 < sc->min_vector) continue;
                double y = (p->k + 0.5) * d;
                double a = back ? p->x1 : p->x0, b = back ? p->x0 : p->x1;
                if (h->budget == 0) return LAM_EUSAGE;
                h->budget--;
                if ((rc = lam_hatches_add(out, a * c - y * s, a * s + y * c, b * c - y * s, b * s + y * c)))
                    return rc;
            }
        }
        i = j;
    }
    if (sc->order == LAM_ORDER_GREEDY && out->nv - first > 2) {
        /* nearest next end, from the first vector */
        double *v = out->v + 4 * first;
        size_t m = out->nv - first;
        for (size_t i = 1; i < m; i++) {
            double px = v[4 * (i - 1) + 2], py = v[4 * (i - 1) + 3];
            size_t best = i;
            int flip = 0;
            double bd = INFINITY;
            for (size_t j = i; j < m; j++) {
                double *q = v + 4 * j;
                double d0 = (q[0] - px) * (q[0] - px) + (q[1] - py) * (q[1] - py);
                double d1 = (q[2] - px) * (q[2] - px) + (q[3] - py) * (q[3] - py);
                if (d0 < bd) bd = d0, best = j, flip = 0;
                if (d1 < bd) bd = d1, best = j, flip = 1;
            }
            double t[4];
            memcpy(t, v + 4 * best, sizeof t);
            memmove(v + 4 * (i + 1), v + 4 * i, (best - i) * 4 * sizeof *v);
            if (flip) v[4 * i] = t[2], v[4 * i + 1] = t[3], v[4 * i + 2] = t[0], v[4 * i + 3] = t[1];
            else memcpy(v + 4 * i, t, sizeof t);
        }
    }
    if (out->blocks[out->nblocks - 1].n == 0) out->nblocks--; /* nothing left in it */
    return LAM_OK;
}

/* ---- strategies ------------------------------------------------------------ */

static double frac(double x)
{
    return x - floor(x);
}

static void dir_of(double deg, double *c, double *s)
{
    double r = fmod(deg, 360.0) * (3.14159265358979323846 / 180.0);
    *c = cos(r);
    *s = sin(r);
}

static int hatch_lines(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, int type, lam_hatches *out)
{
    double c, s;
    dir_of(angle, &c, &s);
    int rc = scan(h, g, c, s, sc->distance);
    return rc ? rc : emit_block(h, h->segs, h->nsegs, sc, type, angle, c, s, sc->distance, out);
}

static int hatch_stripes(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                         lam_hatches *out)
{
    double c, s, w = sc->stripe_width, half = sc->stripe_overlap / 2;
    dir_of(angle, &c, &s);
    int rc = scan(h, g, c, s, sc->distance);
    if (rc || !h->nsegs) return rc;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < h->nsegs; i++) lo = fmin(lo, h->segs[i].x0), hi = fmax(hi, h->segs[i].x1);
    double shift = w * frac((double)index * 0.618034);
    double j0 = floor((lo - half - shift) / w), j1 = floor((hi + half - shift) / w);
    if (j1 - j0 > MAX_VECTORS) return LAM_EUSAGE;
    size_t n = h->nsegs;
    seg *band = malloc((n ? n : 1) * sizeof *band);
    if (!band) return LAM_ENOMEM;
    for (double j = j0; j <= j1 && !rc; j++) {
        double b0 = j * w + shift - half, b1 = (j + 1) * w + shift + half;
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            double a = fmax(h->segs[i].x0, b0), b = fmin(h->segs[i].x1, b1);
            if (b > a) band[m++] = (seg){ h->segs[i].k, a, b };
        }
        if (m) rc = emit_block(h, band, m, sc, type, angle, c, s, sc->distance, out);
    }
    free(band);
    return rc;
}

/* splitmix64: a fixed, portable generator for the random island order */
static uint64_t mix(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

typedef struct cell {
    long i, j;
} cell;

/* The hatch segments of one angle over the whole area, sorted by line and
 * x (a copy of scan's result: the two angles of the islands live side by
 * side). */
typedef struct lineset {
    double c, s;
    seg *segs;
    size_t n;
} lineset;

static int lineset_scan(hatcher *h, const GEOSGeometry *g, double angle, double d, lineset *ls)
{
    dir_of(angle, &ls->c, &ls->s);
    int rc = scan(h, g, ls->c, ls->s, d);
    if (rc) return rc;
    ls->segs = malloc((h->nsegs ? h->nsegs : 1) * sizeof *ls->segs);
    if (!ls->segs) return LAM_ENOMEM;
    if (h->nsegs) memcpy(ls->segs, h->segs, h->nsegs * sizeof *ls->segs);
    ls->n = h->nsegs;
    return LAM_OK;
}

/* Where line y (rotated frame) runs inside the square whose corners, in
 * ring order, are q[0..3] (rotated): x in [*lo, *hi], empty when *hi <=
 * *lo. Its crossings with the square's sides, by ring_crossings' rule (a
 * side from y0 to y1 counts y0 <= y < y1): a line through the lowest
 * corner counts, one through the highest does not. */
static void square_span(const double q[8], double y, double *lo, double *hi)
{
    double a = INFINITY, b = -INFINITY;
    for (int i = 0; i < 4; i++) {
        double x0 = q[2 * i], y0 = q[2 * i + 1], x1 = q[(2 * i + 2) % 8], y1 = q[(2 * i + 3) % 8];
        if (y0 == y1) continue;
        if (y0 > y1) {
            double t = x0;
            x0 = x1, x1 = t;
            t = y0, y0 = y1, y1 = t;
        }
        if (y < y0 || y >= y1) continue;
        double x = x0 + (x1 - x0) * (y - y0) / (y1 - y0);
        if (x < a) a = x;
        if (x > b) b = x;
    }
    *lo = a;
    *hi = b;
}

/* Islands: squares of island_size (grown by half the overlap on each
 * side) shifted per layer, each hatched at the layer's angle or 90 degrees
 * to it, checkerwise. Each angle's lines are scanned once over the whole
 * area and each square takes the pieces of them inside it: the pieces a
 * scan of area and square together would give (a line counts for a square
 * from the square's lowest corner up to, not including, its highest, as a
 * scan counts a crossing), without clipping the area once per square.
 * (Clipping with GEOS per square was three quarters of a hatched run.) */
static int hatch_islands(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                         lam_hatches *out)
{
    double bb[4];
    if (GEOSisEmpty_r(h->g->h, g)) return LAM_OK;
    if (!GEOSGeom_getXMin_r(h->g->h, g, &bb[0]) || !GEOSGeom_getYMin_r(h->g->h, g, &bb[1]) ||
        !GEOSGeom_getXMax_r(h->g->h, g, &bb[2]) || !GEOSGeom_getYMax_r(h->g->h, g, &bb[3]))
        return LAM_EGEOM;
    double S = sc->island_size, half = sc->island_overlap / 2, d = sc->distance;
    double su = S * frac((double)index * 0.618034), sv = S * frac((double)index * 0.381966);
    double i0 = floor((bb[0] - half - su) / S), i1 = floor((bb[2] + half - su) / S);
    double j0 = floor((bb[1] - half - sv) / S), j1 = floor((bb[3] + half - sv) / S);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > MAX_VECTORS) return LAM_EUSAGE;
    size_t ni = (size_t)(i1 - i0 + 1), nj = (size_t)(j1 - j0 + 1), n = ni * nj;
    cell *cells = malloc(n * sizeof *cells);
    if (!cells) return LAM_ENOMEM;
    size_t m = 0;
    for (int pass = 0; pass < (sc->island_order == LAM_ISLANDS_CHECKER ? 2 : 1); pass++)
        for (size_t b = 0; b < nj; b++)
            for (size_t a = 0; a < ni; a++) {
                long i = (long)i0 + (long)a, j = (long)j0 + (long)b;
                if (sc->island_order == LAM_ISLANDS_CHECKER && (int)((i + j) & 1) != pass) continue;
                cells[m++] = (cell){ i, j };
            }
    if (sc->island_order == LAM_ISLANDS_RANDOM) {
        uint64_t st = ((uint64_t)(unsigned)sc->seed << 32) ^ (uint64_t)index;
        for (size_t k = m; k > 1; k--) {
            size_t r = (size_t)(mix(&st) % k);
            cell t = cells[k - 1];
            cells[k - 1] = cells[r];
            cells[r] = t;
        }
    }
    lineset set[2];
    memset(set, 0, sizeof set); /* segs NULL until scanned */
    seg *piece = NULL;
    size_t cap = 0;
    int rc = LAM_OK;
    for (size_t k = 0; k < m && !rc; k++) {
        double u0 = (double)cells[k].i * S + su - half, v0 = (double)cells[k].j * S + sv - half;
        double u1 = u0 + S + 2 * half, v1 = v0 + S + 2 * half;
        int odd = (int)((cells[k].i + cells[k].j) & 1);
        double a = angle + (odd ? 90.0 : 0.0);
        lineset *ls = &set[odd];
        if (!ls->segs && (rc = lineset_scan(h, g, a, d, ls))) break; /* scanned on first use */
        /* the square, rotated as ring_crossings rotates a ring; its lines
         * from its lowest corner up to its highest */
        double ylo = INFINITY, yhi = -INFINITY, sq[8];
        const double cu[4] = { u0, u1, u1, u0 }, cv[4] = { v0, v0, v1, v1 };
        for (int q = 0; q < 4; q++) {
            sq[2 * q] = cu[q] * ls->c + cv[q] * ls->s;
            sq[2 * q + 1] = -cu[q] * ls->s + cv[q] * ls->c;
            ylo = fmin(ylo, sq[2 * q + 1]), yhi = fmax(yhi, sq[2 * q + 1]);
        }
        long klo = (long)ceil(ylo / d - 0.5);
        size_t lo = 0, hi = ls->n; /* the first segment on line klo or after */
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (ls->segs[mid].k < klo) lo = mid + 1;
            else hi = mid;
        }
        size_t np = 0;
        for (size_t q = lo; q < ls->n; q++) {
            const seg *p = &ls->segs[q];
            double y = (p->k + 0.5) * d;
            if (y >= yhi) break;
            if (y < ylo) continue;
            double xa, xb;
            square_span(sq, y, &xa, &xb);
            if (p->x0 > xa) xa = p->x0;
            if (p->x1 < xb) xb = p->x1;
            /* a line along a side shared by the square and the area (a hole
             * filling a square) leaves a sliver of rounding: rotating the
             * area and the square moves their common side apart by an ulp */
            if (!(xb - xa > 1e-12 * (fabs(xa) + fabs(xb) + d))) continue;
            if (np == cap) {
                size_t nc = cap ? 2 * cap : 64;
                seg *g2 = realloc(piece, nc * sizeof *g2);
                if (!g2) {
                    rc = LAM_ENOMEM;
                    break;
                }
                piece = g2;
                cap = nc;
            }
            piece[np++] = (seg){ p->k, xa, xb };
        }
        if (!rc && np) rc = emit_block(h, piece, np, sc, type, a, ls->c, ls->s, d, out);
    }
    free(piece);
    free(set[0].segs);
    free(set[1].segs);
    free(cells);
    return rc;
}

static int hatch_area(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, size_t index, int type,
                      lam_hatches *out)
{
    double angle = fmod(sc->angle + (double)index * sc->angle_increment, 360.0);
    switch (sc->strategy) {
    case LAM_HATCH_LINES: return hatch_lines(h, g, sc, angle, type, out);
    case LAM_HATCH_STRIPES: return hatch_stripes(h, g, sc, angle, index, type, out);
    case LAM_HATCH_ISLANDS: return hatch_islands(h, g, sc, angle, index, type, out);
    default: return LAM_OK;
    }
}

/* ---- skins and the layer ----------------------------------------------------- */

/* The intersection of the regions of layers[0..n) (NULL when n is 0 or
 * a layer is missing: nothing covers). */
static int covered(lam_geos *g, const lam_layer *const *layers, size_t have, size_t n, GEOSGeometry **out)
{
    *out = NULL;
    if (n == 0 || have < n) return LAM_OK;
    GEOSGeometry *acc = NULL;
    for (size_t i = 0; i < n; i++) {
        if (!layers[i]) {
            if (acc) GEOSGeom_destroy_r(g->h, acc);
            return LAM_OK;
        }
        GEOSGeometry *r = lam_geos_layer_region(g, layers[i]);
        if (!r) {
            if (acc) GEOSGeom_destroy_r(g->h, acc);
            return LAM_EGEOM;
        }
        if (!acc) {
            acc = r;
            continue;
        }
        GEOSGeometry *x = lam_geos_intersection(g, acc, r);
        GEOSGeom_destroy_r(g->h, acc);
        GEOSGeom_destroy_r(g->h, r);
        if (!x) return LAM_EGEOM;
        acc = x;
    }
    *out = acc;
    return LAM_OK;
}

/* a - b; b NULL: nothing covers, a copy of a */
static GEOSGeometry *minus(lam_geos *g, const GEOSGeometry *a, const GEOSGeometry *b)
{
    return b ? lam_geos_difference(g, a, b) : GEOSGeom_clone_r(g->h, a);
}

static double area_of(lam_geos *g, const GEOSGeometry *x)
{
    double a = 0;
    return x && GEOSArea_r(g->h, x, &a) ? a : 0;
}

/* The grid of a layer's booleans: from the largest coordinate of the layer
 * and the skin layers it is compared with (geos.h), so that it depends on
 * the layers only. */
static double skin_grid(const lam_layer *L, const lam_layer *const *below, size_t nbelow,
                        const lam_layer *const *above, size_t nabove, size_t n)
{
    double m = lam_geos_layer_magnitude(L);
    for (size_t i = 0; i < n && i < nbelow; i++)
        if (below[i]) m = fmax(m, lam_geos_layer_magnitude(below[i]));
    for (size_t i = 0; i < n && i < nabove; i++)
        if (above[i]) m = fmax(m, lam_geos_layer_magnitude(above[i]));
    return lam_geos_grid(m);
}

/* Core, up-skin and down-skin of region into part[] (see hatch.h). */
static int split_skins(lam_geos *g, const GEOSGeometry *region, const lam_layer *const *below, size_t nbelow,
                       const lam_layer *const *above, size_t nabove, size_t n, GEOSGeometry **part)
{
    GEOSGeometry *down_cov = NULL, *up_cov = NULL, *rest = NULL;
    int rc = covered(g, below, nbelow, n, &down_cov);
    if (!rc) rc = covered(g, above, nabove, n, &up_cov);
    if (!rc) {
        /* down-skin first: a region open both below and above is down-skin */
        part[LAM_VEC_DOWNSKIN] = minus(g, region, down_cov);
        rest = part[LAM_VEC_DOWNSKIN] ? lam_geos_difference(g, region, part[LAM_VEC_DOWNSKIN]) : NULL;
        part[LAM_VEC_UPSKIN] = rest ? minus(g, rest, up_cov) : NULL;
        part[LAM_VEC_CORE] = rest && part[LAM_VEC_UPSKIN] ? lam_geos_difference(g, rest, part[LAM_VEC_UPSKIN]) : NULL;
        if (!part[LAM_VEC_DOWNSKIN] || !part[LAM_VEC_UPSKIN] || !part[LAM_VEC_CORE]) rc = LAM_EGEOM;
    }
    if (rest) GEOSGeom_destroy_r(g->h, rest);
    if (down_cov) GEOSGeom_destroy_r(g->h, down_cov);
    if (up_cov) GEOSGeom_destroy_r(g->h, up_cov);
    return rc;
}

static void hatch_error(lam_error *err, int rc, const lam_layer *L, const char *stage, const lam_geos *g)
{
    if (rc == LAM_ENOMEM) lam_error_set(err, rc, NULL, 0, 0, "out of memory hatching layer %zu", L->index + 1);
    else if (rc == LAM_EUSAGE)
        lam_error_set(err, rc, NULL, 0, 0, "layer %zu: the hatch distance, stripe width or island size is too small "
                                           "for the layer (more than %.0f vectors)", L->index + 1, MAX_VECTORS);
    else
        lam_error_set(err, rc, NULL, 0, 0, "layer %zu: %s: GEOS: %s", L->index + 1, stage,
                      g->msg[0] ? g->msg : "failed");
}

int lam_hatch_layer(const lam_layer *L, const lam_layer *const *below, size_t nbelow, const lam_layer *const *above,
                    size_t nabove, const lam_scan_cfg *cfg, lam_hatches *out, lam_error *err)
{
    lam_hatches_clear(out);
    if (!L->ncontours) return LAM_OK;
    lam_geos g;
    int rc = lam_geos_init(&g, err);
    if (rc) return rc;
    hatcher h;
    memset(&h, 0, sizeof h);
    h.g = &g;
    h.budget = (size_t)MAX_VECTORS;
    size_t n = cfg->skin_layers > 0 ? (size_t)cfg->skin_layers : 0;
    g.grid = skin_grid(L, below, nbelow, above, nabove, n);
    GEOSGeometry *region = NULL, *hatch = NULL;
    GEOSGeometry *part[LAM_VEC_TYPES] = { NULL };
    const char *stage = "region";
    if (!(region = lam_geos_layer_region(&g, L))) rc = LAM_EGEOM;
    if (!rc && n) {
        stage = "skins";
        rc = split_skins(&g, region, below, nbelow, above, nabove, n, part);
    } else if (!rc) {
        if (!(part[LAM_VEC_CORE] = GEOSGeom_clone_r(g.h, region))) rc = LAM_EGEOM;
    }
    for (int t = LAM_VEC_CORE; t < LAM_VEC_TYPES && !rc; t++) out->area[t] = area_of(&g, part[t]);
    double inset = cfg->compensation + (cfg->contour_count > 1 ? (cfg->contour_count - 1) * cfg->contour_distance : 0) +
                   cfg->hatch_offset;
    if (!rc && lam_scan_hatches(cfg)) {
        stage = "hatch inset";
        hatch = inset > 0 ? lam_geos_offset(&g, region, -inset) : GEOSGeom_clone_r(g.h, region);
        if (!hatch) rc = LAM_EGEOM;
    }
    for (int t = LAM_VEC_CORE; t < LAM_VEC_TYPES && !rc && hatch; t++) {
        if (!part[t] || GEOSisEmpty_r(g.h, part[t]) || cfg->type[t].strategy == LAM_HATCH_NONE) continue;
        stage = lam_vec_type_name(t);
        GEOSGeometry *a = n ? lam_geos_intersection(&g, hatch, part[t]) : GEOSGeom_clone_r(g.h, hatch);
        if (!a) {
            rc = LAM_EGEOM;
            break;
        }
        rc = hatch_area(&h, a, &cfg->type[t], L->index, t, out);
        GEOSGeom_destroy_r(g.h, a);
    }
    for (int t = 0; t < LAM_VEC_TYPES; t++)
        if (part[t]) GEOSGeom_destroy_r(g.h, part[t]);
    if (hatch) GEOSGeom_destroy_r(g.h, hatch);
    if (region) GEOSGeom_destroy_r(g.h, region);
    free(h.cr);
    free(h.segs);
    free(h.ring);
    if (rc) hatch_error(err, rc, L, stage, &g);
    lam_geos_finish(&g);
    return rc;
}

/* ---- time ------------------------------------------------------------------ */

double lam_scan_time_total(const lam_scan_time *t)
{
    return t->exposure + t->jump + t->recoat;
}

void lam_scan_time_add(lam_scan_time *a, const lam_scan_time *b)
{
    a->layers += b->layers;
    a->contours += b->contours;
    a->vectors += b->vectors;
    a->jumps += b->jumps;
    a->exposure_length += b->exposure_length;
    a->jump_length += b->jump_length;
    a->hatch_length += b->hatch_length;
    a->exposure += b->exposure;
    a->jump += b->jump;
    a->recoat += b->recoat;
}

void lam_scan_time_path(lam_scan_time *t, const lam_scan_cfg *cfg, const lam_exposure *e, const double start[2],
                        const double end[2], double length, int contour, double pos[2], int *have_pos)
{
    if (*have_pos) {
        double du = start[0] - pos[0], dv = start[1] - pos[1];
        double j = sqrt(du * du + dv * dv); /* not hypot: a jump per vector, and coordinates stay below 1e50 */
        t->jumps++;
        t->jump_length += j;
        t->jump += (cfg->jump_speed > 0 ? j / cfg->jump_speed : 0) + cfg->jump_delay;
    }
    if (contour) t->contours++;
    else t->vectors++, t->hatch_length += length;
    t->exposure_length += length;
    /* points from one end to the other; a closed contour's last is its first */
    if (e->point_distance > 0 && e->exposure_time > 0)
        t->exposure += fmax(1, floor(length / e->point_distance) + (contour ? 0 : 1)) * e->exposure_time;
    else if (e->speed > 0) t->exposure += length / e->speed;
    pos[0] = end[0];
    pos[1] = end[1];
    *have_pos = 1;
}
