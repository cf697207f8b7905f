#include "vstream.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vstream {
    lam_vec_consumer c[LAM_VSTREAM_MAX];
    size_t n;
    double pos[3], puv[2];   /* the stage or the scanner, both frames */
    int have_pos;
    size_t order;
    lam_vec_stats st;
} vstream;

/* One vector from the current position to (p, uv); the position moves on.
 * `always`: even of no length (the LADRP stage's moves, as the program
 * has them); a jump of no length is no jump. */
static int emit(vstream *s, int kind, const lam_attrs *a, int always, const double p[3], const double uv[2])
{
    lam_vec v;
    memcpy(v.from, s->pos, sizeof v.from);
    memcpy(v.to, p, sizeof v.to);
    memcpy(v.fuv, s->puv, sizeof v.fuv);
    memcpy(v.tuv, uv, sizeof v.tuv);
    memcpy(s->pos, p, sizeof s->pos);
    memcpy(s->puv, uv, sizeof s->puv);
    s->have_pos = 1;
    int exposed = lam_kind_exposed(kind);
    double l2 = (v.to[0] - v.from[0]) * (v.to[0] - v.from[0]) + (v.to[1] - v.from[1]) * (v.to[1] - v.from[1]) +
                (v.to[2] - v.from[2]) * (v.to[2] - v.from[2]);
    /* the test on the square: the square root (a long wait) is not on its path */
    if (!exposed && !always && l2 == 0) return LAM_OK;
    double len = sqrt(l2);
    v.kind = kind;
    v.attrs = *a;
    v.exposed = exposed;
    v.length = len;
    v.order = ++s->order;
    s->st.vectors++;
    if (exposed) s->st.deposit_length += len;
    else s->st.travel_length += len;
    int rc = LAM_OK;
    for (size_t k = 0; k < s->n && !rc; k++)
        if (s->c[k].vector) rc = s->c[k].vector(s->c[k].ctx, &v);
    return rc;
}

/* Call member `fn` of every consumer that has it, in order, until one fails. */
#define EACH(s, fn, ...)                                                                            \
    do {                                                                                           \
        int rc_ = LAM_OK;                                                                          \
        for (size_t k_ = 0; k_ < (s)->n && !rc_; k_++)                                             \
            if ((s)->c[k_].fn) rc_ = (s)->c[k_].fn((s)->c[k_].ctx, __VA_ARGS__);                   \
        return rc_;                                                                                \
    } while (0)

/* An SLS path starts at p: a jump there from where the scanner is. */
static int start_at(vstream *s, const lam_attrs *a, const double p[3], const double uv[2])
{
    if (!s->have_pos) {
        memcpy(s->pos, p, sizeof s->pos);
        memcpy(s->puv, uv, sizeof s->puv);
        s->have_pos = 1;
        return LAM_OK;
    }
    return emit(s, LAM_KIND_JUMP, a, 0, p, uv);
}

/* The layer frame's (u, v) of the job's origin, the one point of the run
 * given in the output frame only; zero terms skipped, so an axis frame
 * gives the coordinates exactly. */
static void origin_uv(const lam_job_info *job, double uv[2])
{
    lam_frame z;
    const lam_frame *f = job->frame;
    if (job->frame_machine || !f) {
        if (!job->frame_machine) lam_frame_axis('z', &z, NULL);
        f = job->frame_machine ? NULL : &z;
    }
    for (int k = 0; k < 2; k++) {
        const double *a = k ? (f ? f->v : NULL) : (f ? f->u : NULL);
        double s = 0;
        if (!a) s = job->origin[k];
        else
            for (int i = 0; i < 3; i++)
                if (a[i] != 0) s += job->origin[i] * a[i];
        uv[k] = s;
    }
}

static int vs_begin(void *ctx, const lam_job_info *job)
{
    vstream *s = ctx;
    memcpy(s->pos, job->origin, sizeof s->pos);
    origin_uv(job, s->puv);
    s->have_pos = 1;
    EACH(s, begin, job);
}

static int vs_layer(void *ctx, const lam_layer_info *li)
{
    vstream *s = ctx;
    s->order = 0;
    memset(&s->st, 0, sizeof s->st);
    EACH(s, layer, li);
}

static int vs_layer_end(void *ctx, const lam_layer_info *li)
{
    vstream *s = ctx;
    EACH(s, layer_end, li, &s->st);
}

static int vs_move(void *ctx, const lam_move_info *m)
{
    return emit(ctx, m->deposit ? LAM_KIND_DEPOSIT : LAM_KIND_TRAVEL, &m->attrs, 1, m->xyz, m->uv);
}

static int path(vstream *s, const lam_contour_info *c)
{
    size_t order = s->order + 1;
    EACH(s, path, c, order);
}

static int vs_contour(void *ctx, const lam_contour_info *c)
{
    vstream *s = ctx;
    int prc = path(s, c);
    if (prc || c->n < 2) return prc;
    if (s->order == 0) s->have_pos = 0; /* the scanner starts a layer at its first path */
    int rc = start_at(s, &c->attrs, c->xyz, c->uv);
    for (size_t i = 1; i <= c->n && !rc; i++) {
        size_t k = i % c->n;
        rc = emit(s, LAM_KIND_CONTOUR, &c->attrs, 1, c->xyz + 3 * k, c->uv + 2 * k);
    }
    return rc;
}

static int vs_hatches(void *ctx, const lam_hatch_info *h)
{
    vstream *s = ctx;
    if (s->order == 0 && h->n) s->have_pos = 0;
    int rc = LAM_OK;
    for (size_t i = 0; i < h->n && !rc; i++) {
        rc = start_at(s, &h->attrs, h->xyz + 6 * i, h->uv + 4 * i);
        if (!rc) rc = emit(s, h->kind, &h->attrs, 1, h->xyz + 6 * i + 3, h->uv + 4 * i + 2);
    }
    return rc;
}

/* every consumer ends (each finishes what it buffered): the first error */
static int vs_end(void *ctx)
{
    vstream *s = ctx;
    int rc = LAM_OK;
    for (size_t k = 0; k < s->n; k++) {
        int r = s->c[k].end ? s->c[k].end(s->c[k].ctx) : LAM_OK;
        if (!rc) rc = r;
    }
    return rc;
}

static void destroy_all(const lam_vec_consumer *c, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (c[k].destroy) c[k].destroy(c[k].ctx);
}

static void vs_destroy(void *ctx)
{
    vstream *s = ctx;
    destroy_all(s->c, s->n);
    free(s);
}

int lam_vstream_sink(const lam_vec_consumer *c, size_t n, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (n == 0 || n > LAM_VSTREAM_MAX) {
        destroy_all(c, n > LAM_VSTREAM_MAX ? LAM_VSTREAM_MAX : n);
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "a vector stream of %zu consumers", n);
    }
    vstream *s = calloc(1, sizeof *s);
    if (!s) {
        destroy_all(c, n);
        return lam_error_nomem(err, "making a preview");
    }
    memcpy(s->c, c, n * sizeof *c);
    s->n = n;
    *out = (lam_sink){ .ctx = s, .begin = vs_begin, .layer = vs_layer, .layer_end = vs_layer_end, .move = vs_move,
                       .contour = vs_contour, .hatches = vs_hatches, .end = vs_end, .destroy = vs_destroy };
    return LAM_OK;
}
