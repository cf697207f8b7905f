/* The recording sink; see plan_record.h. An entry is a header (the
 * operation and its scalars) followed by its point arrays, each padded to
 * 8 bytes so doubles stay aligned. */
#include "plan_record.h"

#include <stdlib.h>
#include <string.h>

#include "grow.h"

enum { OP_FEED, OP_LASER, OP_MOVE, OP_CONTOUR, OP_HATCHES };

typedef struct entry {
    int op, flag;            /* flag: laser on, deposit */
    size_t size;             /* bytes of the entry, header and arrays */
    union {
        double rate;
        lam_move_info m;
        lam_contour_info c;
        lam_hatch_info h;
    } u;
} entry;

#define PAD(n) (((n) + 7) & ~(size_t)7)

/* Room for an entry of `size` bytes at the end; NULL when out of memory. */
static entry *add(lam_record *r, int op, size_t arrays)
{
    size_t size = PAD(sizeof(entry)) + arrays;
    if (r->failed) return NULL;
    if (r->len + size > r->cap) {
        unsigned char *nb = lam_grow(r->buf, &r->cap, r->len + size, 1, 4096);
        if (!nb) {
            r->failed = 1;
            return NULL;
        }
        r->buf = nb;
    }
    entry *e = (entry *)(r->buf + r->len);
    memset(e, 0, sizeof *e);
    e->op = op;
    e->size = size;
    r->len += size;
    return e;
}

static unsigned char *arrays_of(entry *e) { return (unsigned char *)e + PAD(sizeof(entry)); }

static int rec_feed(void *ctx, double rate)
{
    entry *e = add(ctx, OP_FEED, 0);
    if (!e) return LAM_ENOMEM;
    e->u.rate = rate;
    return LAM_OK;
}

static int rec_laser(void *ctx, int on)
{
    entry *e = add(ctx, OP_LASER, 0);
    if (!e) return LAM_ENOMEM;
    e->flag = on;
    return LAM_OK;
}

static int rec_move(void *ctx, const lam_move_info *m)
{
    entry *e = add(ctx, OP_MOVE, 0);
    if (!e) return LAM_ENOMEM;
    e->u.m = *m;
    return LAM_OK;
}

/* Copy xyz (3 per point) and uv (2 per point) of n points after the header;
 * the pointers are fixed up at replay (the buffer may move). */
static entry *add_points(lam_record *r, int op, const double *xyz, const double *uv, size_t n3, size_t n2)
{
    if (n3 > SIZE_MAX / 16 || n2 > SIZE_MAX / 16) {
        r->failed = 1;
        return NULL;
    }
    size_t bx = PAD(n3 * sizeof(double)), bu = PAD(n2 * sizeof(double));
    entry *e = add(r, op, bx + bu);
    if (!e) return NULL;
    if (n3) memcpy(arrays_of(e), xyz, n3 * sizeof(double));
    if (n2) memcpy(arrays_of(e) + bx, uv, n2 * sizeof(double));
    return e;
}

static int rec_contour(void *ctx, const lam_contour_info *c)
{
    entry *e = add_points(ctx, OP_CONTOUR, c->xyz, c->uv, 3 * c->n, c->uv ? 2 * c->n : 0);
    if (!e) return LAM_ENOMEM;
    e->u.c = *c;
    e->flag = c->uv != NULL;
    return LAM_OK;
}

static int rec_hatches(void *ctx, const lam_hatch_info *h)
{
    entry *e = add_points(ctx, OP_HATCHES, h->xyz, h->uv, 6 * h->n, h->uv ? 4 * h->n : 0);
    if (!e) return LAM_ENOMEM;
    e->u.h = *h;
    e->flag = h->uv != NULL;
    return LAM_OK;
}

lam_sink lam_record_sink(lam_record *r, const lam_sink *like)
{
    lam_sink s = { 0 };
    s.ctx = r;
    if (like->feed) s.feed = rec_feed;
    if (like->laser) s.laser = rec_laser;
    if (like->move) s.move = rec_move;
    if (like->contour) s.contour = rec_contour;
    if (like->hatches) s.hatches = rec_hatches;
    return s;
}

void lam_record_clear(lam_record *r)
{
    r->len = 0;
    r->failed = 0;
}

void lam_record_free(lam_record *r)
{
    free(r->buf);
    memset(r, 0, sizeof *r);
}

int lam_record_replay(const lam_record *r, const lam_sink *sink)
{
    int rc = LAM_OK;
    for (size_t at = 0; at < r->len && !rc;) {
        entry *e = (entry *)(r->buf + at);
        at += e->size;
        switch (e->op) {
        case OP_FEED:
            rc = sink->feed(sink->ctx, e->u.rate);
            break;
        case OP_LASER:
            rc = sink->laser(sink->ctx, e->flag);
            break;
        case OP_MOVE:
            rc = sink->move(sink->ctx, &e->u.m);
            break;
        case OP_CONTOUR: {
            lam_contour_info c = e->u.c;
            c.xyz = (const double *)arrays_of(e);
            c.uv = e->flag ? (const double *)(arrays_of(e) + PAD(3 * c.n * sizeof(double))) : NULL;
            rc = sink->contour(sink->ctx, &c);
            break;
        }
        case OP_HATCHES: {
            lam_hatch_info h = e->u.h;
            h.xyz = (const double *)arrays_of(e);
            h.uv = e->flag ? (const double *)(arrays_of(e) + PAD(6 * h.n * sizeof(double))) : NULL;
            rc = sink->hatches(sink->ctx, &h);
            break;
        }
        }
    }
    return rc;
}
