/* The vector store a layer's hatching fills and
 * what a scan configuration does. Hatching itself is in hatch_layer.c and
 * the pieces hatch_internal.h lists; the rules are in hatch.h. */
#include "hatch.h"

#include <stdlib.h>
#include <string.h>

int lam_scan_region_used(const lam_scan_cfg *c, int k)
{
    if (k == LAM_KIND_CONTOUR) return c->contour_count > 0;
    if (k == LAM_KIND_SUPPORT) return c->support.type != LAM_SUPPORT_NONE;
    if (k != LAM_KIND_CORE && c->skin_layers == 0) return 0;
    return c->type[k].strategy != LAM_HATCH_NONE;
}

double lam_scan_region_distance(const lam_scan_cfg *c, double spot, int k)
{
    return k == LAM_KIND_CONTOUR ? spot : k == LAM_KIND_SUPPORT ? c->support.spacing : c->type[k].distance;
}

int lam_scan_hatches(const lam_scan_cfg *cfg)
{
    for (int t = LAM_KIND_CORE; t < LAM_REGIONS; t++)
        if (cfg->type[t].strategy != LAM_HATCH_NONE) return 1;
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
