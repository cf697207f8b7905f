/* Layers (layer.h). */
#include "layer.h"

#include <stdlib.h>
#include <string.h>

lam_layer *lam_layer_clone(const lam_layer *L)
{
    lam_layer *c = malloc(sizeof *c);
    if (!c) return NULL;
    *c = *L;
    c->uv = malloc(2 * L->npoints * sizeof *c->uv + 1);
    c->contours = malloc(L->ncontours * sizeof *c->contours + 1);
    c->open = malloc(L->nopen * sizeof *c->open + 1);
    if (!c->uv || !c->contours || !c->open) {
        lam_layer_free(c);
        return NULL;
    }
    if (L->npoints) memcpy(c->uv, L->uv, 2 * L->npoints * sizeof *c->uv);
    if (L->ncontours) memcpy(c->contours, L->contours, L->ncontours * sizeof *c->contours);
    if (L->nopen) memcpy(c->open, L->open, L->nopen * sizeof *c->open);
    return c;
}

void lam_layer_free(lam_layer *l)
{
    if (!l) return;
    free(l->uv);
    free(l->contours);
    free(l->open);
    free(l);
}
