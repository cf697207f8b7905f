/* The SLS planner: a layer's contour passes and hatch blocks. */
#include "planner.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "offset.h"
#include "support.h"

void lam_sls_state_init(lam_sls_state *st)
{
    memset(st, 0, sizeof *st);
    st->attrs = lam_attrs_default();
}

void lam_sls_state_free(lam_sls_state *st)
{
    lam_hatches_free(&st->hatches);
    lam_hatches_free(&st->support);
}

static void to_out(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o, double u, double v, double *xyz)
{
    if (o->frame_machine) {
        xyz[0] = u;
        xyz[1] = v;
        xyz[2] = L->cut;
    } else {
        lam_frame_to_model(f, u, v, L->cut, xyz);
    }
}

static int emit_contours(const lam_layer *L, const lam_layer *C, const lam_frame *f, const lam_plan_opts *o,
                         const lam_sink *sink, lam_sls_state *st, lam_error *err)
{
    size_t maxn = 0;
    for (size_t k = 0; k < C->ncontours; k++)
        if (C->contours[k].n > maxn) maxn = C->contours[k].n;
    double *xyz = malloc((3 * maxn + 1) * sizeof *xyz);
    if (!xyz) return lam_error_nomem(err, "planning a layer");
    const lam_exposure *e = &o->scan.type[LAM_KIND_CONTOUR].exposure;
    int rc = LAM_OK;
    for (size_t k = 0; k < C->ncontours && !rc; k++) {
        const lam_contour *c = &C->contours[k];
        const double *uv = C->uv + 2 * c->first;
        double len = 0;
        for (size_t i = 0; i < c->n; i++) {
            to_out(L, f, o, uv[2 * i], uv[2 * i + 1], xyz + 3 * i);
            size_t j = (i + 1) % c->n;
            double du = uv[2 * j] - uv[2 * i], dv = uv[2 * j + 1] - uv[2 * i + 1];
            len += sqrt(du * du + dv * dv);
        }
        lam_contour_info ci = { .attrs = st->attrs, .solid = c->kind == LAM_SOLID, .depth = c->depth, .z = L->cut,
                                .xyz = xyz, .uv = uv, .n = c->n, .power = e->power, .speed = e->speed,
                                .point_distance = e->point_distance, .exposure_time = e->exposure_time };
        if (sink->contour) rc = sink->contour(sink->ctx, &ci);
        if (c->n) lam_scan_time_path(&st->time, &o->scan, e, uv, uv, len, 1, st->pos, &st->have_pos);
    }
    free(xyz);
    return rc;
}

/* contour_count passes: the first at the compensation, each next one
 * contour_distance further in */
static int contour_passes(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o, const lam_sink *sink,
                          lam_sls_state *st, lam_error *err)
{
    int rc = LAM_OK;
    for (int k = 0; k < o->scan.contour_count && !rc; k++) {
        double inset = o->scan.compensation + k * o->scan.contour_distance;
        if (inset == 0) {
            rc = emit_contours(L, L, f, o, sink, st, err);
            continue;
        }
        lam_layer *C;
        if ((rc = lam_layer_offset(L, -inset, &C, err))) break;
        rc = emit_contours(L, C, f, o, sink, st, err);
        lam_layer_free(C);
    }
    return rc;
}

/* Lengths by sqrt, not hypot: hypot's care against overflow cost a tenth
 * of a hatched run, and coordinates stay below 1e50 (LAM_COORD_MAX). */
static int emit_hatches(const lam_layer *L, const lam_hatches *h, const lam_frame *f, const lam_plan_opts *o,
                        const lam_sink *sink, lam_sls_state *st, lam_error *err)
{
    size_t maxn = 0;
    for (size_t b = 0; b < h->nblocks; b++)
        if (h->blocks[b].n > maxn) maxn = h->blocks[b].n;
    double *xyz = malloc((6 * maxn + 1) * sizeof *xyz);
    if (!xyz) return lam_error_nomem(err, "planning a layer");
    int rc = LAM_OK;
    for (size_t b = 0; b < h->nblocks && !rc; b++) {
        const lam_hatch_block *B = &h->blocks[b];
        int type = B->type >= LAM_KIND_CORE && B->type < LAM_REGIONS ? B->type : LAM_KIND_CORE;
        const lam_exposure *e = &o->scan.type[type].exposure;
        const double *uv = h->v + 4 * B->first;
        for (size_t i = 0; i < B->n; i++) {
            const double *p = uv + 4 * i;
            to_out(L, f, o, p[0], p[1], xyz + 6 * i);
            to_out(L, f, o, p[2], p[3], xyz + 6 * i + 3);
            double du = p[2] - p[0], dv = p[3] - p[1];
            lam_scan_time_path(&st->time, &o->scan, e, p, p + 2, sqrt(du * du + dv * dv), 0, st->pos,
                               &st->have_pos);
        }
        lam_hatch_info hi = { .attrs = st->attrs, .kind = type, .z = L->cut, .xyz = xyz, .uv = uv, .n = B->n,
                              .angle = B->angle, .power = e->power, .speed = e->speed,
                              .point_distance = e->point_distance, .exposure_time = e->exposure_time };
        if (sink->hatches) rc = sink->hatches(sink->ctx, &hi);
    }
    free(xyz);
    return rc;
}

int lam_plan_sls_layer(const lam_layer *L, const lam_layer *const *below, size_t nbelow,
                       const lam_layer *const *above, size_t nabove, const lam_frame *f,
                       const lam_plan_opts *opts, const lam_sink *sink, const lam_hatches *given,
                       lam_sls_state *st, lam_error *err)
{
    lam_plan_opts oc = *opts;
    const lam_plan_opts *o = &oc;
    oc.scan.compensation = opts->beam_offset ? opts->bead / 2 : 0;
    memset(&st->time, 0, sizeof st->time);
    st->have_pos = 0; /* the scanner starts each layer at its first path */
    st->time.layers = 1;
    st->time.recoat = o->scan.recoat_time;
    int rc = LAM_OK;
    const lam_hatches *h = given;
    if (!h) {
        lam_hatches_clear(&st->hatches);
        if (lam_scan_hatches(&o->scan) || o->scan.skin_layers > 0)
            rc = lam_hatch_layer(L, below, nbelow, above, nabove, &o->scan, &st->hatches, err);
        h = &st->hatches;
    }
    if (!rc && o->supports) {
        /* supports first: they stand under the part's overhangs */
        lam_hatches_clear(&st->support);
        rc = lam_support_vectors(o->supports, L->index, &o->scan.support, &st->support, err);
        if (!rc) rc = emit_hatches(L, &st->support, f, o, sink, st, err);
    }
    if (!rc && o->scan.contours_first) rc = contour_passes(L, f, o, sink, st, err);
    if (!rc) rc = emit_hatches(L, h, f, o, sink, st, err);
    if (!rc && !o->scan.contours_first) rc = contour_passes(L, f, o, sink, st, err);
    if (!rc && o->time) lam_scan_time_add(o->time, &st->time);
    return rc;
}
