/* A build layer's blocks: see blayer.h. */
#include "blayer.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"

size_t lam_bblock_points(const lam_bblock *b) { return b->polyline ? b->n : 2 * b->n; }

int lam_blayer_push(lam_blayer *l, const lam_bblock *b, const double *uv, size_t npts, lam_error *err)
{
    if (l->n == l->cap) {
        size_t cap = lam_grow_cap(l->cap, l->n + 1, 16, sizeof *l->b);
        lam_bblock *nb = cap ? realloc(l->b, cap * sizeof *nb) : NULL;
        if (!nb) return lam_error_nomem(err, "collecting a build layer");
        l->b = nb;
        l->cap = cap;
    }
    if (npts > SIZE_MAX / (2 * sizeof(double))) return lam_error_nomem(err, "collecting a build layer");
    double *copy = malloc((npts ? npts : 1) * 2 * sizeof *copy);
    if (!copy) return lam_error_nomem(err, "collecting a build layer");
    if (npts) memcpy(copy, uv, npts * 2 * sizeof *copy);
    l->b[l->n] = *b;
    l->b[l->n].uv = copy;
    l->n++;
    return LAM_OK;
}

void lam_blayer_clear(lam_blayer *l)
{
    for (size_t i = 0; i < l->n; i++) free(l->b[i].uv);
    l->n = 0;
}

void lam_blayer_free(lam_blayer *l)
{
    lam_blayer_clear(l);
    free(l->b);
    l->b = NULL;
    l->cap = 0;
}
