/* Support vectors (lam_support_vectors, support.h): walls on the grid of the
 * run's plane, windows cut into them, teeth, a block's outline. */
#include <stdlib.h>
#include <string.h>

#include "hatch_internal.h"
#include "support.h"

/* Segment pieces of h->segs[0..n) kept into h->segs from the start: with
 * `inside` the parts with frac(x / period) < width / period (teeth), else
 * the rest (walls with windows). period <= width with inside: whole. */
static int periodic(hatcher *h, size_t n, double period, double width, int inside, seg **out, size_t *nout)
{
    *out = NULL;
    *nout = 0;
    double pieces = 0; /* counted first: a period of 1e-9 must not run (nor allocate) a billion times */
    for (size_t i = 0; i < n; i++) pieces += (h->segs[i].x1 - h->segs[i].x0) / period + 2;
    if (!(pieces <= MAX_VECTORS)) return LAM_EUSAGE;
    size_t cap = 0;
    seg *r = NULL;
    for (size_t i = 0; i < n; i++) {
        seg s = h->segs[i];
        for (double m = floor(s.x0 / period); m * period < s.x1; m++) {
            double a = m * period, b = a + width;
            double lo = inside ? a : b, hi = inside ? b : a + period;
            lo = fmax(lo, s.x0);
            hi = fmin(hi, s.x1);
            if (hi <= lo) continue;
            if (*nout == cap) {
                cap = cap ? 2 * cap : 64;
                seg *x = realloc(r, cap * sizeof *x);
                if (!x) {
                    free(r);
                    return LAM_ENOMEM;
                }
                r = x;
            }
            if ((double)*nout >= MAX_VECTORS) {
                free(r);
                return LAM_EUSAGE;
            }
            r[(*nout)++] = (seg){ s.k, lo, hi };
        }
    }
    *out = r;
    return LAM_OK;
}

/* Whether layer L's walls have windows: in the bands of height
 * perf_width every perf_spacing upwards (by the layer's cut). */
static int windows_here(const lam_layer *L, const lam_support_cfg *c)
{
    if (!(c->perf_width > 0) || !(c->perf_spacing > c->perf_width)) return 0;
    return frac(L->cut / c->perf_spacing) < c->perf_width / c->perf_spacing;
}

/* The walls of area g at `angle` (teeth: cut into teeth) as one block. */
static int walls(hatcher *h, const GEOSGeometry *g, const lam_layer *L, const lam_support_cfg *c, double angle,
                 int teeth, lam_hatches *out)
{
    lam_scan sc;
    memset(&sc, 0, sizeof sc);
    sc.distance = c->spacing;
    sc.order = LAM_ORDER_MEANDER;
    double cs, sn;
    dir_of(angle, &cs, &sn);
    int rc = lam_hatch_scan(h, g, cs, sn, c->spacing);
    if (rc || !h->nsegs) return rc;
    seg *cut = NULL;
    size_t ncut = 0;
    if (teeth && c->teeth_spacing > c->teeth_width)
        rc = periodic(h, h->nsegs, c->teeth_spacing, c->teeth_width, 1, &cut, &ncut);
    else if (!teeth && windows_here(L, c))
        rc = periodic(h, h->nsegs, c->perf_spacing, c->perf_width, 0, &cut, &ncut);
    if (!rc && cut) rc = lam_hatch_emit(h, cut, ncut, &sc, LAM_KIND_SUPPORT, angle, cs, sn, c->spacing, out);
    else if (!rc) rc = lam_hatch_emit(h, h->segs, h->nsegs, &sc, LAM_KIND_SUPPORT, angle, cs, sn, c->spacing, out);
    free(cut);
    return rc;
}

/* A block's outline: every edge of every contour of R, one block. */
static int outline(const lam_layer *R, lam_hatches *out)
{
    int rc = lam_hatches_add_block(out, LAM_KIND_SUPPORT, 0);
    for (size_t k = 0; k < R->ncontours && !rc; k++) {
        const lam_contour *c = &R->contours[k];
        const double *uv = R->uv + 2 * c->first;
        for (size_t i = 0; i < c->n && !rc; i++) {
            size_t j = (i + 1) % c->n;
            rc = lam_hatches_add(out, uv[2 * i], uv[2 * i + 1], uv[2 * j], uv[2 * j + 1]);
        }
    }
    return rc;
}

/* The walls of layer R (and with `teeth`, of T) in each direction. */
static int all_walls(hatcher *h, const lam_layer *R, int teeth, const lam_support_cfg *c, lam_hatches *out)
{
    GEOSGeometry *g = lam_geos_layer_region(h->g, R);
    if (!g) return LAM_EGEOM;
    int rc = walls(h, g, R, c, 0, teeth, out);
    if (!rc && c->type != LAM_SUPPORT_LINES) rc = walls(h, g, R, c, 90, teeth, out);
    GEOSGeom_destroy_r(h->g->h, g);
    return rc;
}

int lam_support_walls(const lam_support_cfg *c)
{
    return c->type == LAM_SUPPORT_NONE ? LAM_SUPPORT_BLOCK : c->type;
}

int lam_support_vectors(const lam_supports *s, size_t i, const lam_support_cfg *cfg, lam_hatches *out,
                        lam_error *err)
{
    const lam_layer *R = lam_supports_region(s, i), *T = lam_supports_teeth(s, i);
    if (!R && !T) return LAM_OK;
    lam_support_cfg wc = *cfg;
    wc.type = lam_support_walls(cfg);
    const lam_support_cfg *c = &wc;
    lam_geos g;
    int rc = lam_geos_init(&g, err);
    if (rc) return rc;
    double m = fmax(R ? lam_geos_layer_magnitude(R) : 0, T ? lam_geos_layer_magnitude(T) : 0);
    g.grid = lam_geos_grid(m);
    hatcher h;
    memset(&h, 0, sizeof h);
    h.g = &g;
    h.budget = (size_t)MAX_VECTORS;
    if (R && c->type == LAM_SUPPORT_BLOCK) rc = outline(R, out);
    if (!rc && R) rc = all_walls(&h, R, 0, c, out);
    if (!rc && T) rc = all_walls(&h, T, 1, c, out);
    free(h.cr);
    free(h.segs);
    free(h.ring);
    const lam_layer *L = R ? R : T;
    if (rc == LAM_ENOMEM) lam_error_nomem(err, "making support vectors");
    else if (rc == LAM_EUSAGE)
        lam_error_set(err, rc, NULL, 0, 0, "layer %zu: support_spacing, support_teeth.spacing or "
                                           "support_perforation.spacing is too small for the layer (more than %.0f "
                                           "vectors)", L->index + 1, MAX_VECTORS);
    else if (rc)
        lam_error_set(err, rc, NULL, 0, 0, "layer %zu: support walls: GEOS: %s", L->index + 1,
                      g.msg[0] ? g.msg : "failed");
    lam_geos_finish(&g);
    return rc;
}
