/* The stripes strategy: bands stripe_width wide along the hatch direction,
 * grown by half the overlap each side, the grid moved each layer; one block
 * per band (hatch.h). */
#include <stdlib.h>

#include "hatch_internal.h"

int lam_hatch_stripes(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, size_t index, int type,
                      lam_hatches *out)
{
    double c, s, w = sc->stripe_width, half = sc->stripe_overlap / 2;
    dir_of(angle, &c, &s);
    int rc = lam_hatch_scan(h, g, c, s, sc->distance);
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
        if (m) rc = lam_hatch_emit(h, band, m, sc, type, angle, c, s, sc->distance, out);
    }
    free(band);
    return rc;
}
