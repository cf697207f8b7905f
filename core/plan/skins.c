/* Skins: a layer's region split into core, up-skin and down-skin by GEOS
 * set operations with the regions of the layers below and above (hatch.h). */
#include "hatch_internal.h"

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

double lam_skins_grid(const lam_layer *L, const lam_layer *const *below, size_t nbelow, const lam_layer *const *above,
                      size_t nabove, size_t n)
{
    double m = lam_geos_layer_magnitude(L);
    for (size_t i = 0; i < n && i < nbelow; i++)
        if (below[i]) m = fmax(m, lam_geos_layer_magnitude(below[i]));
    for (size_t i = 0; i < n && i < nabove; i++)
        if (above[i]) m = fmax(m, lam_geos_layer_magnitude(above[i]));
    return lam_geos_grid(m);
}

int lam_skins_split(lam_geos *g, const GEOSGeometry *region, const lam_layer *const *below, size_t nbelow,
                    const lam_layer *const *above, size_t nabove, size_t n, GEOSGeometry **part)
{
    GEOSGeometry *down_cov = NULL, *up_cov = NULL, *rest = NULL;
    int rc = covered(g, below, nbelow, n, &down_cov);
    if (!rc) rc = covered(g, above, nabove, n, &up_cov);
    if (!rc) {
        /* down-skin first: a region open both below and above is down-skin */
        part[LAM_KIND_DOWNSKIN] = minus(g, region, down_cov);
        rest = part[LAM_KIND_DOWNSKIN] ? lam_geos_difference(g, region, part[LAM_KIND_DOWNSKIN]) : NULL;
        part[LAM_KIND_UPSKIN] = rest ? minus(g, rest, up_cov) : NULL;
        part[LAM_KIND_CORE] = rest && part[LAM_KIND_UPSKIN] ? lam_geos_difference(g, rest, part[LAM_KIND_UPSKIN]) : NULL;
        if (!part[LAM_KIND_DOWNSKIN] || !part[LAM_KIND_UPSKIN] || !part[LAM_KIND_CORE]) rc = LAM_EGEOM;
    }
    if (rest) GEOSGeom_destroy_r(g->h, rest);
    if (down_cov) GEOSGeom_destroy_r(g->h, down_cov);
    if (up_cov) GEOSGeom_destroy_r(g->h, up_cov);
    return rc;
}
