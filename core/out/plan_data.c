/* Plan data, a consumer of the vector stream (plan_data.h). */
#include "plan_data.h"

#include <stdlib.h>
#include <string.h>

#include "grow.h"

/* Room for want items of size in *a (capacity *cap): 0 when out of memory. */
static int grow_ok(void **a, size_t *cap, size_t want, size_t size)
{
    if (want <= *cap) return 1;
    void *p = lam_grow(*a, cap, want, size, 64);
    if (!p) return 0;
    *a = p;
    return 1;
}

#define GROW(r, arr, n, cap, more) grow_ok((void **)&(r)->arr, &(r)->cap, (r)->n + (more), sizeof *(r)->arr)

static int nomem(lam_plan_data *r)
{
    return lam_error_nomem(r->err, "recording the plan");
}

static int d_layer(void *ctx, const lam_layer_info *li)
{
    lam_plan_data *r = ctx;
    if (!GROW(r, layers, nlayers, cap_layers, 1)) return nomem(r);
    lam_rec_layer *ly = &r->layers[r->nlayers++];
    memset(ly, 0, sizeof *ly);
    ly->index = li->index;
    ly->z = li->z;
    ly->c0 = r->ncontours;
    ly->v0 = r->nvectors;
    return LAM_OK;
}

static int d_path(void *ctx, const lam_contour_info *c, size_t order)
{
    (void)order; /* the stream's order counts edges and jumps: a pass is one operation here */
    lam_plan_data *r = ctx;
    lam_rec_layer *ly = lam_plan_data_current(r);
    if (!ly) return LAM_OK;
    if (!GROW(r, contours, ncontours, cap_contours, 1) || c->n > SIZE_MAX / 2 ||
        !grow_ok((void **)&r->pts, &r->cap_pts, r->npts + c->n, 2 * sizeof *r->pts))
        return nomem(r);
    lam_rec_contour *rc = &r->contours[r->ncontours++];
    rc->first = r->npts;
    rc->n = c->n;
    rc->solid = c->solid;
    rc->depth = c->depth;
    rc->attrs = c->attrs;
    rc->order = ++ly->ops;
    if (c->n) memcpy(r->pts + 2 * r->npts, c->uv, c->n * 2 * sizeof *r->pts);
    r->npts += c->n;
    ly->nc++;
    return LAM_OK;
}

static int d_vector(void *ctx, const lam_vec *v)
{
    lam_plan_data *r = ctx;
    lam_rec_layer *ly = lam_plan_data_current(r);
    /* a pass's edges are its contour; jumps are the stream's own */
    if (!ly || v->kind == LAM_KIND_CONTOUR || v->kind == LAM_KIND_JUMP) return LAM_OK;
    if (!GROW(r, vectors, nvectors, cap_vectors, 1)) return nomem(r);
    lam_rec_vector *rv = &r->vectors[r->nvectors++];
    const double uv[4] = { v->fuv[0], v->fuv[1], v->tuv[0], v->tuv[1] };
    memcpy(rv->uv, uv, sizeof rv->uv);
    rv->kind = v->kind;
    rv->attrs = v->attrs;
    rv->order = ++ly->ops;
    ly->nv++;
    return LAM_OK;
}

void lam_plan_data_consumer(lam_plan_data *r, lam_error *err, lam_vec_consumer *out)
{
    memset(r, 0, sizeof *r);
    r->err = err;
    *out = (lam_vec_consumer){ .ctx = r, .layer = d_layer, .vector = d_vector, .path = d_path };
}

lam_rec_layer *lam_plan_data_current(lam_plan_data *r)
{
    return r->nlayers ? &r->layers[r->nlayers - 1] : NULL;
}

void lam_plan_data_free(lam_plan_data *r)
{
    if (!r) return;
    free(r->layers);
    free(r->contours);
    free(r->vectors);
    free(r->pts);
    memset(r, 0, sizeof *r);
}
