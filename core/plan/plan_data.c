/* The recording sink (plan_data.h). */
#include "plan_data.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

const char *lam_rec_kind_name(int kind)
{
    static const char *const names[LAM_REC_KINDS] = { "deposit", "travel", "core", "upskin", "downskin" };
    return kind >= 0 && kind < LAM_REC_KINDS ? names[kind] : "?";
}

/* Room for one more of *n items of `size` in *a (capacity *cap). */
static int grow(void **a, size_t *cap, size_t n, size_t more, size_t size)
{
    if (n + more <= *cap) return 0;
    size_t c = *cap ? *cap : 64;
    while (c < n + more) {
        if (c > SIZE_MAX / 2 / size) return -1;
        c *= 2;
    }
    void *p = realloc(*a, c * size);
    if (!p) return -1;
    *a = p;
    *cap = c;
    return 0;
}

#define GROW(r, arr, n, cap, more) grow((void **)&(r)->arr, &(r)->cap, (r)->n, (more), sizeof *(r)->arr)

static int nomem(lam_plan_data *r)
{
    return lam_error_nomem(r->err, "recording the plan");
}

/* The layer-frame (u, v) of an output-frame point. */
static void to_uv(const lam_plan_data *r, const double xyz[3], double uv[2])
{
    if (r->frame_machine) {
        uv[0] = xyz[0];
        uv[1] = xyz[1];
        return;
    }
    const double *a[2] = { r->frame.u, r->frame.v };
    for (int k = 0; k < 2; k++) {
        double s = 0; /* zero terms skipped: an axis frame gives coordinates exactly */
        for (int i = 0; i < 3; i++)
            if (a[k][i] != 0) s += xyz[i] * a[k][i];
        uv[k] = s;
    }
}

static int add_vector(lam_plan_data *r, const double uv[4], int kind)
{
    lam_rec_layer *ly = lam_plan_data_current(r);
    if (!ly) return LAM_OK; /* before the first layer (a preamble move): not part of a layer */
    if (GROW(r, vectors, nvectors, cap_vectors, 1)) return nomem(r);
    lam_rec_vector *v = &r->vectors[r->nvectors++];
    memcpy(v->uv, uv, sizeof v->uv);
    v->kind = kind;
    v->order = ++ly->ops;
    ly->nv++;
    return LAM_OK;
}

static int r_begin(void *ctx, const lam_job_info *job)
{
    lam_plan_data *r = ctx;
    to_uv(r, job->origin, r->pos);
    return r->next->begin ? r->next->begin(r->next->ctx, job) : LAM_OK;
}

static int r_layer(void *ctx, const lam_layer_info *li)
{
    lam_plan_data *r = ctx;
    if (GROW(r, layers, nlayers, cap_layers, 1)) return nomem(r);
    lam_rec_layer *ly = &r->layers[r->nlayers++];
    memset(ly, 0, sizeof *ly);
    ly->index = li->index;
    ly->z = li->z;
    ly->c0 = r->ncontours;
    ly->v0 = r->nvectors;
    return r->next->layer ? r->next->layer(r->next->ctx, li) : LAM_OK;
}

static int r_layer_end(void *ctx, const lam_layer_info *li)
{
    lam_plan_data *r = ctx;
    return r->next->layer_end ? r->next->layer_end(r->next->ctx, li) : LAM_OK;
}

static int r_feed(void *ctx, double rate)
{
    lam_plan_data *r = ctx;
    return r->next->feed ? r->next->feed(r->next->ctx, rate) : LAM_OK;
}

static int r_laser(void *ctx, int on)
{
    lam_plan_data *r = ctx;
    return r->next->laser ? r->next->laser(r->next->ctx, on) : LAM_OK;
}

static int r_move(void *ctx, const lam_move_info *m)
{
    lam_plan_data *r = ctx;
    int deposit = m->deposit;
    double uv[4] = { r->pos[0], r->pos[1], m->uv[0], m->uv[1] };
    r->pos[0] = uv[2];
    r->pos[1] = uv[3];
    int rc = add_vector(r, uv, deposit ? LAM_REC_DEPOSIT : LAM_REC_TRAVEL);
    if (rc) return rc;
    return r->next->move ? r->next->move(r->next->ctx, m) : LAM_OK;
}

static int r_contour(void *ctx, const lam_contour_info *c)
{
    lam_plan_data *r = ctx;
    lam_rec_layer *ly = lam_plan_data_current(r);
    if (ly) {
        if (GROW(r, contours, ncontours, cap_contours, 1) || c->n > SIZE_MAX / 2 ||
            grow((void **)&r->pts, &r->cap_pts, r->npts, c->n, 2 * sizeof *r->pts))
            return nomem(r);
        lam_rec_contour *rc = &r->contours[r->ncontours++];
        rc->first = r->npts;
        rc->n = c->n;
        rc->solid = c->solid;
        rc->depth = c->depth;
        rc->order = ++ly->ops;
        memcpy(r->pts + 2 * r->npts, c->uv, c->n * 2 * sizeof *r->pts);
        r->npts += c->n;
        ly->nc++;
    }
    return r->next->contour ? r->next->contour(r->next->ctx, c) : LAM_OK;
}

static int r_hatches(void *ctx, const lam_hatch_info *h)
{
    lam_plan_data *r = ctx;
    int kind = h->kind == LAM_KIND_UPSKIN ? LAM_REC_UPSKIN : h->kind == LAM_KIND_DOWNSKIN ? LAM_REC_DOWNSKIN : LAM_REC_CORE;
    if (GROW(r, vectors, nvectors, cap_vectors, h->n)) return nomem(r);
    for (size_t i = 0; i < h->n; i++) {
        int rc = add_vector(r, h->uv + 4 * i, kind);
        if (rc) return rc;
    }
    return r->next->hatches ? r->next->hatches(r->next->ctx, h) : LAM_OK;
}

static int r_end(void *ctx)
{
    lam_plan_data *r = ctx;
    return r->next->end ? r->next->end(r->next->ctx) : LAM_OK;
}

void lam_plan_data_sink(lam_plan_data *r, const lam_sink *next, const lam_frame *f, int frame_machine, lam_error *err,
                     lam_sink *out)
{
    memset(r, 0, sizeof *r);
    r->next = next;
    r->frame = *f;
    r->frame_machine = frame_machine;
    r->err = err;
    memset(out, 0, sizeof *out);
    out->ctx = r;
    out->begin = r_begin;
    out->layer = r_layer;
    out->layer_end = r_layer_end;
    out->feed = r_feed;
    out->laser = r_laser;
    out->move = r_move;
    out->contour = r_contour;
    out->end = r_end;
    /* a sink that ignores hatches still has them recorded */
    out->hatches = r_hatches;
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
