/* The SLS contour planner: every contour of a layer as one block. */
#include "planner.h"

#include <stdlib.h>

#include "offset.h"

static int emit_layer(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o,
                      const lam_sink *sink, size_t *next_id, lam_error *err);

int lam_plan_sls_layer(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o,
                       const lam_sink *sink, size_t *next_id, lam_error *err)
{
    if (!o->beam_offset) return emit_layer(L, f, o, sink, next_id, err);
    lam_layer *inset;
    int rc = lam_layer_offset(L, -o->bead / 2, &inset, err);
    if (rc) return rc;
    rc = emit_layer(inset, f, o, sink, next_id, err);
    lam_layer_free(inset);
    return rc;
}

static int emit_layer(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o,
                      const lam_sink *sink, size_t *next_id, lam_error *err)
{
    size_t maxn = 0;
    for (size_t k = 0; k < L->ncontours; k++)
        if (L->contours[k].n > maxn) maxn = L->contours[k].n;
    double *xyz = malloc((3 * maxn + 1) * sizeof *xyz);
    if (!xyz) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory planning a layer");
    int rc = LAM_OK;
    for (size_t k = 0; k < L->ncontours && !rc; k++) {
        const lam_contour *c = &L->contours[k];
        const double *uv = L->uv + 2 * c->first;
        for (size_t i = 0; i < c->n; i++) {
            if (o->frame_machine) {
                xyz[3 * i] = uv[2 * i];
                xyz[3 * i + 1] = uv[2 * i + 1];
                xyz[3 * i + 2] = L->cut;
            } else {
                lam_frame_to_model(f, uv[2 * i], uv[2 * i + 1], L->cut, xyz + 3 * i);
            }
        }
        lam_contour_info ci = { (*next_id)++, c->kind == LAM_SOLID, c->depth, L->cut, xyz, uv, c->n };
        if (sink->contour) rc = sink->contour(sink->ctx, &ci);
    }
    free(xyz);
    return rc;
}
