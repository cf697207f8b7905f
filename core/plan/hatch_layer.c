/* Hatching one layer (lam_hatch_layer): its region, the skins, the hatch
 * inset, and each type's part hatched by its strategy. */
#include <stdlib.h>
#include <string.h>

#include "hatch_internal.h"

static int hatch_area(hatcher *h, const GEOSGeometry *g, const lam_scan *sc, size_t index, int type,
                      lam_hatches *out)
{
    double angle = fmod(sc->angle + (double)index * sc->angle_increment, 360.0);
    switch (sc->strategy) {
    case LAM_HATCH_LINES: return lam_hatch_lines(h, g, sc, angle, type, out);
    case LAM_HATCH_STRIPES: return lam_hatch_stripes(h, g, sc, angle, index, type, out);
    case LAM_HATCH_ISLANDS: return lam_hatch_islands(h, g, sc, angle, index, type, out);
    default: return LAM_OK;
    }
}

static double area_of(lam_geos *g, const GEOSGeometry *x)
{
    double a = 0;
    return x && GEOSArea_r(g->h, x, &a) ? a : 0;
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
    g.grid = lam_skins_grid(L, below, nbelow, above, nabove, n);
    GEOSGeometry *region = NULL, *hatch = NULL;
    GEOSGeometry *part[LAM_REGIONS] = { NULL };
    const char *stage = "region";
    if (!(region = lam_geos_layer_region(&g, L))) rc = LAM_EGEOM;
    if (!rc && n) {
        stage = "skins";
        rc = lam_skins_split(&g, region, below, nbelow, above, nabove, n, part);
    } else if (!rc) {
        if (!(part[LAM_KIND_CORE] = GEOSGeom_clone_r(g.h, region))) rc = LAM_EGEOM;
    }
    for (int t = LAM_KIND_CORE; t < LAM_REGIONS && !rc; t++) out->area[t] = area_of(&g, part[t]);
    double inset = cfg->compensation + (cfg->contour_count > 1 ? (cfg->contour_count - 1) * cfg->contour_distance : 0) +
                   cfg->hatch_offset;
    if (!rc && lam_scan_hatches(cfg)) {
        stage = "hatch inset";
        hatch = inset > 0 ? lam_geos_offset(&g, region, -inset) : GEOSGeom_clone_r(g.h, region);
        if (!hatch) rc = LAM_EGEOM;
    }
    for (int t = LAM_KIND_CORE; t < LAM_REGIONS && !rc && hatch; t++) {
        if (!part[t] || GEOSisEmpty_r(g.h, part[t]) || cfg->type[t].strategy == LAM_HATCH_NONE) continue;
        stage = lam_kind_name(t);
        GEOSGeometry *a = n ? lam_geos_intersection(&g, hatch, part[t]) : GEOSGeom_clone_r(g.h, hatch);
        if (!a) {
            rc = LAM_EGEOM;
            break;
        }
        rc = hatch_area(&h, a, &cfg->type[t], L->index, t, out);
        GEOSGeom_destroy_r(g.h, a);
    }
    for (int t = 0; t < LAM_REGIONS; t++)
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
