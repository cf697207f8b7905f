/* The plan's encoding: encoder, recording sink, decoder; see plan_record.h. */
#include "plan_record.h"

#include <stdlib.h>
#include <string.h>

#include "grow.h"

/* ---- encoding ------------------------------------------------------------- */

/* Room for n more bytes; 0 when out of memory (the record is marked failed). */
static unsigned char *room(lam_record *r, size_t n)
{
    if (r->failed) return NULL;
    if (r->len + n > r->cap) {
        unsigned char *nb = lam_grow(r->buf, &r->cap, r->len + n, 1, 4096);
        if (!nb) {
            r->failed = 1;
            return NULL;
        }
        r->buf = nb;
    }
    unsigned char *p = r->buf + r->len;
    r->len += n;
    return p;
}

void lam_record_bytes(lam_record *r, const void *p, size_t n)
{
    unsigned char *d = room(r, n);
    if (d && n) memcpy(d, p, n);
}

static unsigned char *le64(unsigned char *p, uint64_t v)
{
    for (int i = 0; i < 8; i++) p[i] = (unsigned char)(v >> (8 * i));
    return p + 8;
}

static unsigned char *real(unsigned char *p, double x)
{
    uint64_t v;
    memcpy(&v, &x, 8);
    return le64(p, v);
}

static unsigned char *reals(unsigned char *p, const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++) p = real(p, x[i]);
    return p;
}

static unsigned char *attrs(unsigned char *p, const lam_attrs *a)
{
    for (size_t i = 0; i < LAM_NATTRS; i++) p = le64(p, (uint64_t)lam_attr_get(a, i));
    return p;
}

#define ATTR_BYTES (8 * LAM_NATTRS)
#define LAYER_FIELDS 40

static unsigned char *layer_fields(unsigned char *p, const lam_layer_info *li)
{
    p = le64(p, li->index);
    p = real(p, li->z);
    p = real(p, li->width);
    p = real(p, li->floor);
    return real(p, li->ceiling);
}

int lam_record_layer(lam_record *r, const lam_layer_info *li)
{
    unsigned char *p = room(r, 1 + LAYER_FIELDS);
    if (!p) return LAM_ENOMEM;
    *p++ = 'L';
    layer_fields(p, li);
    return LAM_OK;
}

int lam_record_layer_end(lam_record *r, const lam_layer_info *li, const lam_scan_time *t)
{
    unsigned char *p = room(r, 1 + LAYER_FIELDS + 80);
    if (!p) return LAM_ENOMEM;
    *p++ = 'E';
    p = layer_fields(p, li);
    const uint64_t c[4] = { t->layers, t->contours, t->vectors, t->jumps };
    for (int i = 0; i < 4; i++) p = le64(p, c[i]);
    const double x[6] = { t->exposure_length, t->jump_length, t->hatch_length, t->exposure, t->jump, t->recoat };
    reals(p, x, 6);
    return LAM_OK;
}

static int rec_feed(void *ctx, double rate)
{
    unsigned char *p = room(ctx, 9);
    if (!p) return LAM_ENOMEM;
    *p++ = 'F';
    real(p, rate);
    return LAM_OK;
}

static int rec_laser(void *ctx, int on)
{
    unsigned char *p = room(ctx, 2);
    if (!p) return LAM_ENOMEM;
    p[0] = 'A';
    p[1] = on != 0;
    return LAM_OK;
}

static int rec_move(void *ctx, const lam_move_info *m)
{
    unsigned char *p = room(ctx, 2 + ATTR_BYTES + 40);
    if (!p) return LAM_ENOMEM;
    *p++ = 'M';
    p = attrs(p, &m->attrs);
    *p++ = m->deposit != 0;
    p = reals(p, m->xyz, 3);
    reals(p, m->uv, 2);
    return LAM_OK;
}

/* The fixed part of a contour or hatch record, and room for its n points
 * of `per` reals (xyz and, when there is uv, uv). */
static unsigned char *points_room(lam_record *r, size_t fixed, size_t n, size_t per)
{
    if (n > (SIZE_MAX - fixed) / 8 / per) {
        r->failed = 1;
        return NULL;
    }
    return room(r, fixed + 8 * per * n);
}

static int rec_contour(void *ctx, const lam_contour_info *c)
{
    unsigned char *p = points_room(ctx, 1 + ATTR_BYTES + 1 + 8 * 7 + 1, c->n, c->uv ? 5 : 3);
    if (!p) return LAM_ENOMEM;
    *p++ = 'C';
    p = attrs(p, &c->attrs);
    *p++ = c->solid != 0;
    p = le64(p, (uint64_t)(int64_t)c->depth);
    p = real(p, c->z);
    p = le64(p, c->n);
    const double e[4] = { c->power, c->speed, c->point_distance, c->exposure_time };
    p = reals(p, e, 4);
    *p++ = c->uv != NULL;
    p = reals(p, c->xyz, 3 * c->n);
    if (c->uv) reals(p, c->uv, 2 * c->n);
    return LAM_OK;
}

static int rec_hatches(void *ctx, const lam_hatch_info *h)
{
    unsigned char *p = points_room(ctx, 1 + ATTR_BYTES + 8 * 8 + 1, h->n, h->uv ? 10 : 6);
    if (!p) return LAM_ENOMEM;
    *p++ = 'H';
    p = attrs(p, &h->attrs);
    p = le64(p, (uint64_t)(int64_t)h->kind);
    p = real(p, h->z);
    p = le64(p, h->n);
    const double e[5] = { h->angle, h->power, h->speed, h->point_distance, h->exposure_time };
    p = reals(p, e, 5);
    *p++ = h->uv != NULL;
    p = reals(p, h->xyz, 6 * h->n);
    if (h->uv) reals(p, h->uv, 4 * h->n);
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
    lam_rec_scratch_free(&r->sc);
    memset(r, 0, sizeof *r);
}

/* ---- decoding ------------------------------------------------------------- */

static uint64_t get64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; i--) v = (v << 8) | p[i];
    return v;
}

static double getreal(const unsigned char *p)
{
    uint64_t v = get64(p);
    double x;
    memcpy(&x, &v, 8);
    return x;
}

static const unsigned char *getattrs(const unsigned char *p, lam_attrs *a)
{
    for (size_t i = 0; i < LAM_NATTRS; i++, p += 8) lam_attr_set(a, i, (long long)get64(p));
    return p;
}

void lam_rec_scratch_free(lam_rec_scratch *sc)
{
    free(sc->d);
    memset(sc, 0, sizeof *sc);
}

/* n reals after the fixed fields, into the scratch: the count checked
 * against what is left first, so a corrupt count allocates nothing. */
static int get_points(const lam_rec_source *src, lam_rec_scratch *sc, size_t n, lam_error *err)
{
    if (n > src->left(src->ctx) / 8) return src->corrupt(src->ctx, "more points than the file holds", err);
    size_t want = n ? n : 1; /* a record of no points still gives the sink a pointer */
    if (want > sc->cap) {
        double *d = lam_realloc_n(sc->d, want, sizeof *d);
        if (!d) return lam_error_nomem(err, "reading a plan's records");
        sc->d = d;
        sc->cap = want;
    }
    if (n > SIZE_MAX / 8) return src->corrupt(src->ctx, "more points than the file holds", err);
    unsigned char buf[4096];
    for (size_t done = 0; done < n;) {
        size_t k = n - done < sizeof buf / 8 ? n - done : sizeof buf / 8;
        int rc = src->get(src->ctx, buf, 8 * k, err);
        if (rc) return rc;
        for (size_t i = 0; i < k; i++) sc->d[done + i] = getreal(buf + 8 * i);
        done += k;
    }
    return LAM_OK;
}

/* a count of items: no more than the bytes left */
static int count(const lam_rec_source *src, const unsigned char *p, size_t *n, lam_error *err)
{
    uint64_t x = get64(p);
    if (x > src->left(src->ctx)) return src->corrupt(src->ctx, "a count larger than the file", err);
    *n = (size_t)x;
    return LAM_OK;
}

static void read_layer_fields(const unsigned char *p, lam_rec_op *op)
{
    op->index = get64(p);
    op->layer.index = (size_t)op->index;
    op->layer.z = getreal(p + 8);
    op->layer.width = getreal(p + 16);
    op->layer.floor = getreal(p + 24);
    op->layer.ceiling = getreal(p + 32);
}

static void read_estimate(const unsigned char *p, lam_rec_op *op)
{
    for (int i = 0; i < 4; i++) op->counts[i] = get64(p + 8 * i);
    lam_scan_time *t = &op->time;
    t->layers = (size_t)op->counts[0];
    t->contours = (size_t)op->counts[1];
    t->vectors = (size_t)op->counts[2];
    t->jumps = (size_t)op->counts[3];
    double *x[6] = { &t->exposure_length, &t->jump_length, &t->hatch_length, &t->exposure, &t->jump, &t->recoat };
    for (int i = 0; i < 6; i++) *x[i] = getreal(p + 32 + 8 * i);
}

static int read_contour(const lam_rec_source *src, lam_rec_scratch *sc, lam_rec_op *op, lam_error *err)
{
    unsigned char b[ATTR_BYTES + 1 + 8 * 7 + 1];
    int rc = src->get(src->ctx, b, sizeof b, err);
    if (rc) return rc;
    lam_contour_info *c = &op->contour;
    const unsigned char *p = getattrs(b, &c->attrs);
    c->solid = *p++;
    c->depth = (int)(int64_t)get64(p);
    c->z = getreal(p + 8);
    if ((rc = count(src, p + 16, &c->n, err))) return rc;
    double *e[4] = { &c->power, &c->speed, &c->point_distance, &c->exposure_time };
    for (int i = 0; i < 4; i++) *e[i] = getreal(p + 24 + 8 * i);
    op->flag = p[56];
    if ((rc = get_points(src, sc, (op->flag ? 5 : 3) * c->n, err))) return rc;
    c->xyz = sc->d;
    c->uv = op->flag ? sc->d + 3 * c->n : NULL;
    return LAM_OK;
}

static int read_hatches(const lam_rec_source *src, lam_rec_scratch *sc, lam_rec_op *op, lam_error *err)
{
    unsigned char b[ATTR_BYTES + 8 * 8 + 1];
    int rc = src->get(src->ctx, b, sizeof b, err);
    if (rc) return rc;
    lam_hatch_info *h = &op->hatches;
    const unsigned char *p = getattrs(b, &h->attrs);
    op->kind = (int64_t)get64(p);
    h->kind = op->kind >= 0 && op->kind < LAM_KINDS ? (int)op->kind : -1;
    h->z = getreal(p + 8);
    if ((rc = count(src, p + 16, &h->n, err))) return rc;
    double *e[5] = { &h->angle, &h->power, &h->speed, &h->point_distance, &h->exposure_time };
    for (int i = 0; i < 5; i++) *e[i] = getreal(p + 24 + 8 * i);
    op->flag = p[64];
    if ((rc = get_points(src, sc, (op->flag ? 10 : 6) * h->n, err))) return rc;
    h->xyz = sc->d;
    h->uv = op->flag ? sc->d + 6 * h->n : NULL;
    return LAM_OK;
}

/* The records of fixed size: their fields after the tag. */
static int read_fixed(const lam_rec_source *src, lam_rec_op *op, lam_error *err)
{
    unsigned char b[LAYER_FIELDS + 80];
    size_t n = op->tag == 'L' ? LAYER_FIELDS : op->tag == 'E' ? LAYER_FIELDS + 80 : op->tag == 'F' ? 8
             : op->tag == 'A' ? 1 : ATTR_BYTES + 41;
    int rc = src->get(src->ctx, b, n, err);
    if (rc) return rc;
    if (op->tag == 'L' || op->tag == 'E') read_layer_fields(b, op);
    if (op->tag == 'E') read_estimate(b + LAYER_FIELDS, op);
    if (op->tag == 'F') op->rate = getreal(b);
    if (op->tag == 'A') op->flag = b[0];
    if (op->tag == 'M') {
        const unsigned char *p = getattrs(b, &op->move.attrs);
        op->flag = op->move.deposit = *p++;
        for (int i = 0; i < 3; i++) op->move.xyz[i] = getreal(p + 8 * i);
        for (int i = 0; i < 2; i++) op->move.uv[i] = getreal(p + 24 + 8 * i);
    }
    return LAM_OK;
}

int lam_rec_read(const lam_rec_source *src, lam_rec_scratch *sc, lam_rec_op *op, lam_error *err)
{
    unsigned char tag = 0;
    int rc = src->get(src->ctx, &tag, 1, err);
    if (rc) return rc;
    memset(&op->layer, 0, sizeof op->layer);
    op->tag = tag;
    switch (tag) {
    case 'Z': return LAM_OK;
    case 'C': return read_contour(src, sc, op, err);
    case 'H': return read_hatches(src, sc, op, err);
    case 'L': case 'E': case 'F': case 'A': case 'M': return read_fixed(src, op, err);
    default: return src->corrupt(src->ctx, "an unknown record", err);
    }
}

int lam_rec_send(const lam_rec_op *op, const lam_sink *s)
{
    switch (op->tag) {
    case 'L': return s->layer ? s->layer(s->ctx, &op->layer) : LAM_OK;
    case 'E': return s->layer_end ? s->layer_end(s->ctx, &op->layer) : LAM_OK;
    case 'F': return s->feed ? s->feed(s->ctx, op->rate) : LAM_OK;
    case 'A': return s->laser ? s->laser(s->ctx, op->flag) : LAM_OK;
    case 'M': return s->move ? s->move(s->ctx, &op->move) : LAM_OK;
    case 'C': return s->contour ? s->contour(s->ctx, &op->contour) : LAM_OK;
    case 'H': return s->hatches ? s->hatches(s->ctx, &op->hatches) : LAM_OK;
    default: return LAM_OK;
    }
}

/* ---- replaying a recording ---------------------------------------------- */

typedef struct mem {
    const unsigned char *b;
    size_t len, off;
} mem;

static int mem_get(void *ctx, void *dst, size_t n, lam_error *err)
{
    mem *m = ctx;
    if (n > m->len - m->off) return lam_error_set(err, LAM_EFORMAT, NULL, 0, 0, "a recording ends inside a record");
    memcpy(dst, m->b + m->off, n);
    m->off += n;
    return LAM_OK;
}

static unsigned long long mem_left(void *ctx)
{
    const mem *m = ctx;
    return m->len - m->off;
}

static int mem_corrupt(void *ctx, const char *what, lam_error *err)
{
    const mem *m = ctx;
    return lam_error_set(err, LAM_EFORMAT, NULL, 0, 0, "a recording's byte %zu: %s", m->off, what);
}

int lam_record_replay(lam_record *r, const lam_sink *sink)
{
    mem m = { r->buf, r->len, 0 };
    lam_rec_source src = { &m, mem_get, mem_left, mem_corrupt };
    lam_rec_op op;
    int rc = LAM_OK;
    while (!rc && m.off < m.len) {
        rc = lam_rec_read(&src, &r->sc, &op, NULL);
        if (!rc) rc = lam_rec_send(&op, sink);
    }
    return rc;
}
