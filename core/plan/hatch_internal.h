/* What the pieces of hatching share (not installed): the scanline's
 * segments and working arrays, the block output, the strategies and the
 * skins. The pieces, one job each:
 *   hatch.c          the vector store, vector-type names, lam_scan_hatches
 *   hatch_layer.c    lam_hatch_layer: region, skins, inset, one strategy per type
 *   hatch_scan.c     the scanline: an area's hatch segments at one direction
 *   hatch_order.c    a block's segments to vectors, ordered
 *   hatch_lines.c, hatch_stripes.c, hatch_islands.c   one file per strategy
 *   skins.c          core, up-skin and down-skin by GEOS set operations
 *   scan_time.c      the scanner's time estimate
 * The rules are in hatch.h. */
#ifndef LAM_HATCH_INTERNAL_H
#define LAM_HATCH_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "geos.h"
#include "hatch.h"

/* The most vectors (and squares, stripes, crossings per edge) of one layer. */
#define MAX_VECTORS 50000000.0

/* A piece of hatch line in the rotated frame: on line k, from x0 to x1. */
typedef struct seg {
    long k;
    double x0, x1;
} seg;

typedef struct crossing {
    long k;
    double x;
} crossing;

/* The working state of hatching one layer: GEOS, the scanline's arrays
 * (kept between scans), the vector budget. */
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

static inline double frac(double x)
{
    return x - floor(x);
}

/* The unit direction at deg degrees. */
static inline void dir_of(double deg, double *c, double *s)
{
    double r = fmod(deg, 360.0) * (3.14159265358979323846 / 180.0);
    *c = cos(r);
    *s = sin(r);
}

/* The hatch segments of area g at direction (c, s) and line distance d,
 * sorted by line and x, into h->segs (even-odd pairs of the crossings of
 * the lines y = (k + 1/2) d with g's rings, rotated by (c, s)). Errors:
 * LAM_ENOMEM, LAM_EGEOM, LAM_EUSAGE (too many crossings). */
int lam_hatch_scan(hatcher *h, const GEOSGeometry *g, double c, double s, double d);

/* Append the segments segs[0..n) (sorted by line, then x) of one block of
 * `type` at `angle` to out, dropping those shorter than sc->min_vector and
 * ordering the rest by sc->order; (c, s) and d as for lam_hatch_scan. An
 * empty block is not kept. Errors: LAM_ENOMEM, LAM_EUSAGE (h's budget
 * spent). */
int lam_hatch_emit(hatcher *h, const seg *segs, size_t n, const lam_scan *sc, int type, double angle, double c,
                   double s, double d, lam_hatches *out);

/* The strategies: hatch area g with sc at `angle` (the layer's, index
 * the layer's index) as blocks of `type` appended to out. Errors as
 * lam_hatch_scan and lam_hatch_emit. */
int lam_hatch_lines(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, int type, lam_hatches *out);
int lam_hatch_stripes(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                      lam_hatches *out);
int lam_hatch_islands(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                      lam_hatches *out);

/* The grid of a layer's booleans: from the largest coordinate of the layer
 * and the n skin layers each side it is compared with (geos.h), so that it
 * depends on the layers only. */
double lam_skins_grid(const lam_layer *L, const lam_layer *const *below, size_t nbelow, const lam_layer *const *above,
                      size_t nabove, size_t n);

/* Core, up-skin and down-skin of region into part[LAM_KIND_CORE..] (see
 * hatch.h; n skin layers each side), new geometries the caller destroys.
 * Errors: LAM_EGEOM (the parts made so far are left in part[]). */
int lam_skins_split(lam_geos *g, const GEOSGeometry *region, const lam_layer *const *below, size_t nbelow,
                    const lam_layer *const *above, size_t nabove, size_t n, GEOSGeometry **part);

#endif
