#include "vstream.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vstream {
    lam_frame f;
    int machine;
    lam_vec_consumer c;
    double pos[3];           /* the stage or the scanner, output frame */
    int have_pos;
    size_t order;
    lam_vec_stats st;
} vstream;

static void to_uv(const vstream *s, const double p[3], double uv[2])
{
    if (s->machine) {
        uv[0] = p[0];
        uv[1] = p[1];
        return;
    }
    uv[0] = p[0] * s->f.u[0] + p[1] * s->f.u[1] + p[2] * s->f.u[2];
    uv[1] = p[0] * s->f.v[0] + p[1] * s->f.v[1] + p[2] * s->f.v[2];
}

/* One vector from the current position to p; the position moves on.
 * `always`: even of no length (the LADRP stage's moves, as the program
 * has them); a jump of no length is no jump. */
static int emit(vstream *s, const char *kind, int exposed, int always, const double p[3])
{
    lam_vec v;
    memcpy(v.from, s->pos, sizeof v.from);
    memcpy(v.to, p, sizeof v.to);
    memcpy(s->pos, p, sizeof s->pos);
    s->have_pos = 1;
    double len = sqrt((v.to[0] - v.from[0]) * (v.to[0] - v.from[0]) + (v.to[1] - v.from[1]) * (v.to[1] - v.from[1]) +
                      (v.to[2] - v.from[2]) * (v.to[2] - v.from[2]));
    if (!exposed && !always && len == 0) return LAM_OK;
    v.kind = kind;
    v.exposed = exposed;
    v.order = ++s->order;
    to_uv(s, v.from, v.fuv);
    to_uv(s, v.to, v.tuv);
    s->st.vectors++;
    if (exposed) s->st.deposit_length += len;
    else s->st.travel_length += len;
    return s->c.vector ? s->c.vector(s->c.ctx, &v) : LAM_OK;
}

/* An SLS path starts at p: a jump there from where the scanner is. */
static int start_at(vstream *s, const double p[3])
{
    if (!s->have_pos) {
        memcpy(s->pos, p, sizeof s->pos);
        s->have_pos = 1;
        return LAM_OK;
    }
    return emit(s, "jump", 0, 0, p);
}

static int vs_begin(void *ctx, const lam_job_info *job)
{
    vstream *s = ctx;
    if (job->frame) {
        s->f = *job->frame;
        s->machine = job->frame_machine;
    }
    memcpy(s->pos, job->origin, sizeof s->pos);
    s->have_pos = 1;
    return s->c.begin ? s->c.begin(s->c.ctx, job) : LAM_OK;
}

static int vs_layer(void *ctx, const lam_layer_info *li)
{
    vstream *s = ctx;
    s->order = 0;
    memset(&s->st, 0, sizeof s->st);
    return s->c.layer ? s->c.layer(s->c.ctx, li) : LAM_OK;
}

static int vs_layer_end(void *ctx, const lam_layer_info *li)
{
    vstream *s = ctx;
    return s->c.layer_end ? s->c.layer_end(s->c.ctx, li, &s->st) : LAM_OK;
}

static int vs_move(void *ctx, int deposit, const double xyz[3])
{
    vstream *s = ctx;
    return emit(s, deposit ? "deposit" : "travel", deposit, 1, xyz);
}

static int vs_contour(void *ctx, const lam_contour_info *c)
{
    vstream *s = ctx;
    if (c->n < 2) return LAM_OK;
    if (s->order == 0) s->have_pos = 0; /* the scanner starts a layer at its first path */
    int rc = start_at(s, c->xyz);
    for (size_t i = 1; i <= c->n && !rc; i++) rc = emit(s, "contour", 1, 1, c->xyz + 3 * (i % c->n));
    return rc;
}

static int vs_hatches(void *ctx, const lam_hatch_info *h)
{
    vstream *s = ctx;
    if (s->order == 0 && h->n) s->have_pos = 0;
    int rc = LAM_OK;
    for (size_t i = 0; i < h->n && !rc; i++) {
        rc = start_at(s, h->xyz + 6 * i);
        if (!rc) rc = emit(s, h->kind ? h->kind : "core", 1, 1, h->xyz + 6 * i + 3);
    }
    return rc;
}

static int vs_end(void *ctx)
{
    vstream *s = ctx;
    return s->c.end ? s->c.end(s->c.ctx) : LAM_OK;
}

static void vs_destroy(void *ctx)
{
    vstream *s = ctx;
    if (s->c.destroy) s->c.destroy(s->c.ctx);
    free(s);
}

int lam_vstream_sink(const lam_frame *f, int frame_machine, const lam_vec_consumer *c, lam_sink *out,
                     lam_error *err)
{
    memset(out, 0, sizeof *out);
    vstream *s = calloc(1, sizeof *s);
    if (!s) {
        if (c->destroy) c->destroy(c->ctx);
        return lam_error_nomem(err, "making a preview");
    }
    if (f) s->f = *f;
    else lam_frame_axis('z', &s->f, NULL);
    s->machine = frame_machine;
    s->c = *c;
    out->ctx = s;
    out->begin = vs_begin;
    out->layer = vs_layer;
    out->layer_end = vs_layer_end;
    out->move = vs_move;
    out->contour = vs_contour;
    out->hatches = vs_hatches;
    out->end = vs_end;
    out->destroy = vs_destroy;
    return LAM_OK;
}
