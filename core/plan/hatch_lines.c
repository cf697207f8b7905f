/* The lines strategy: the whole area, one block. */
#include "hatch_internal.h"

int lam_hatch_lines(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, double angle, int type, lam_hatches *out)
{
    double c, s;
    dir_of(angle, &c, &s);
    int rc = lam_hatch_scan(h, g, c, s, sc->distance);
    return rc ? rc : lam_hatch_emit(h, h->segs, h->nsegs, sc, type, angle, c, s, sc->distance, out);
}
