/* The islands strategy: squares on a grid of the layer plane, checkerwise
 * at two angles, in sequential, checker or random order (hatch.h). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hatch_internal.h"

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
    int rc = lam_hatch_scan(h, g, ls->c, ls->s, d);
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

/* The squares of the layer's grid over area g (su, sv: the grid's shift)
 * into a new array *cells[0..*m) in sc's island order. Errors: LAM_EGEOM,
 * LAM_ENOMEM, LAM_EUSAGE (too many squares). */
static int island_cells(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, size_t index, double su, double sv,
                        cell **cells, size_t *m)
{
    double bb[4];
    if (!GEOSGeom_getXMin_r(h->g->h, g, &bb[0]) || !GEOSGeom_getYMin_r(h->g->h, g, &bb[1]) ||
        !GEOSGeom_getXMax_r(h->g->h, g, &bb[2]) || !GEOSGeom_getYMax_r(h->g->h, g, &bb[3]))
        return LAM_EGEOM;
    double S = sc->island_size, half = sc->island_overlap / 2;
    double i0 = floor((bb[0] - half - su) / S), i1 = floor((bb[2] + half - su) / S);
    double j0 = floor((bb[1] - half - sv) / S), j1 = floor((bb[3] + half - sv) / S);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > MAX_VECTORS) return LAM_EUSAGE;
    size_t ni = (size_t)(i1 - i0 + 1), nj = (size_t)(j1 - j0 + 1), n = ni * nj;
    cell *c = *cells = malloc(n * sizeof *c);
    if (!c) return LAM_ENOMEM;
    size_t k = 0;
    for (int pass = 0; pass < (sc->island_order == LAM_ISLANDS_CHECKER ? 2 : 1); pass++)
        for (size_t b = 0; b < nj; b++)
            for (size_t a = 0; a < ni; a++) {
                long i = (long)i0 + (long)a, j = (long)j0 + (long)b;
                if (sc->island_order == LAM_ISLANDS_CHECKER && (int)((i + j) & 1) != pass) continue;
                c[k++] = (cell){ i, j };
            }
    if (sc->island_order == LAM_ISLANDS_RANDOM) {
        uint64_t st = ((uint64_t)(unsigned)sc->seed << 32) ^ (uint64_t)index;
        for (size_t q = k; q > 1; q--) {
            size_t r = (size_t)(mix(&st) % q);
            cell t = c[q - 1];
            c[q - 1] = c[r];
            c[r] = t;
        }
    }
    *m = k;
    return LAM_OK;
}

/* The pieces of ls's segments inside the square [u0, u1] x [v0, v1] into
 * *piece[0..*np) (grown as needed, *cap its room). Errors: LAM_ENOMEM. */
static int square_pieces(const lineset *ls, double u0, double v0, double u1, double v1, double d, seg **piece,
                         size_t *cap, size_t *np)
{
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
    *np = 0;
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
        if (*np == *cap) {
            size_t nc = *cap ? 2 * *cap : 64;
            seg *g2 = realloc(*piece, nc * sizeof *g2);
            if (!g2) return LAM_ENOMEM;
            *piece = g2;
            *cap = nc;
        }
        (*piece)[(*np)++] = (seg){ p->k, xa, xb };
    }
    return LAM_OK;
}

/* Islands: squares of island_size (grown by half the overlap on each
 * side) shifted per layer, each hatched at the layer's angle or 90 degrees
 * to it, checkerwise. Each angle's lines are scanned once over the whole
 * area and each square takes the pieces of them inside it: the pieces a
 * scan of area and square together would give (a line counts for a square
 * from the square's lowest corner up to, not including, its highest, as a
 * scan counts a crossing), without clipping the area once per square.
 * (Clipping with GEOS per square was three quarters of a hatched run.) */
int lam_hatch_islands(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                      lam_hatches *out)
{
    if (GEOSisEmpty_r(h->g->h, g)) return LAM_OK;
    double S = sc->island_size, half = sc->island_overlap / 2, d = sc->distance;
    double su = S * frac((double)index * 0.618034), sv = S * frac((double)index * 0.381966);
    cell *cells = NULL;
    size_t m = 0;
    int rc = island_cells(h, g, sc, index, su, sv, &cells, &m);
    if (rc) return rc;
    lineset set[2];
    memset(set, 0, sizeof set); /* segs NULL until scanned */
    seg *piece = NULL;
    size_t cap = 0;
    for (size_t k = 0; k < m && !rc; k++) {
        double u0 = (double)cells[k].i * S + su - half, v0 = (double)cells[k].j * S + sv - half;
        double u1 = u0 + S + 2 * half, v1 = v0 + S + 2 * half;
        int odd = (int)((cells[k].i + cells[k].j) & 1);
        double a = angle + (odd ? 90.0 : 0.0);
        lineset *ls = &set[odd];
        if (!ls->segs && (rc = lineset_scan(h, g, a, d, ls))) break; /* scanned on first use */
        size_t np = 0;
        rc = square_pieces(ls, u0, v0, u1, v1, d, &piece, &cap, &np);
        if (!rc && np) rc = lam_hatch_emit(h, piece, np, sc, type, a, ls->c, ls->s, d, out);
    }
    free(piece);
    free(set[0].segs);
    free(set[1].segs);
    free(cells);
    return rc;
}
