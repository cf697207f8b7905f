/* What -j N rests on: the ordered pool (tasks consumed strictly in order,
 * never more than the window in flight, a consumer's error stopping the
 * run), a forked sweep that seeks (the very layers of a sweep from the
 * bottom, bit for bit, in any order of jumps), and the recording sink (a
 * replay sends the same calls with the same numbers) and a dialect's
 * layer text formatted apart (the bytes of the sink itself). */
#include "dialect.h"
#include "meshes.h"
#include "plan_record.h"
#include "pool.h"
#include "slice.h"
#include "tap.h"
#include "util.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the pool --------------------------------------------------------------- */

#define NTASK 2000
#define WINDOW 24
#define AHEAD 3

typedef struct pctx {
    pthread_mutex_t mu;
    long value[WINDOW];           /* task t's result at t % WINDOW */
    unsigned char produced[NTASK];
    size_t nproduced, nconsumed, max_flight, next_consume;
    long last_of_worker[8];
    int out_of_order, bad_value, ahead_missing, worker_backwards;
    size_t stop_at;               /* consume fails here (NTASK: never) */
} pctx;

static int p_produce(void *ctx, unsigned worker, size_t t)
{
    pctx *c = ctx;
    c->value[t % WINDOW] = (long)(t * t + 7);
    pthread_mutex_lock(&c->mu);
    if ((long)t <= c->last_of_worker[worker]) c->worker_backwards = 1;
    c->last_of_worker[worker] = (long)t;
    c->produced[t] = 1;
    c->nproduced++;
    size_t flight = c->nproduced - c->nconsumed;
    if (flight > c->max_flight) c->max_flight = flight;
    pthread_mutex_unlock(&c->mu);
    return (int)(t % 3);
}

static int p_consume(void *ctx, size_t t, int rc)
{
    pctx *c = ctx;
    pthread_mutex_lock(&c->mu);
    if (t != c->next_consume) c->out_of_order = 1;
    c->next_consume = t + 1;
    if (c->value[t % WINDOW] != (long)(t * t + 7) || rc != (int)(t % 3)) c->bad_value = 1;
    for (size_t k = t; k <= t + AHEAD && k < NTASK; k++)
        if (!c->produced[k]) c->ahead_missing = 1;
    c->nconsumed++;
    pthread_mutex_unlock(&c->mu);
    return t == c->stop_at ? 42 : 0;
}

static void pool_run(unsigned threads, size_t chunk, size_t stop_at, const char *name)
{
    pctx *c = calloc(1, sizeof *c);
    pthread_mutex_init(&c->mu, NULL);
    for (int k = 0; k < 8; k++) c->last_of_worker[k] = -1;
    c->stop_at = stop_at;
    lam_error err;
    lam_error_clear(&err);
    int rc = lam_pool_ordered(threads, NTASK, chunk, AHEAD, WINDOW, p_produce, p_consume, c, &err);
    size_t want = stop_at < NTASK ? stop_at + 1 : NTASK;
    is_int(rc, stop_at < NTASK ? 42 : 0, "%s: returns %s", name, stop_at < NTASK ? "the consumer's error" : "0");
    is_int(c->nconsumed, want, "%s: %zu tasks consumed", name, want);
    ok(!c->out_of_order && !c->bad_value, "%s: consumed in order 0, 1, 2, ... with each task's own result", name);
    ok(!c->ahead_missing, "%s: task t consumed only once t .. t+%d are produced", name, AHEAD);
    ok(c->max_flight <= WINDOW, "%s: at most %d tasks produced and not consumed (saw %zu)", name, WINDOW,
       c->max_flight);
    ok(!c->worker_backwards, "%s: each worker's tasks increase", name);
    if (stop_at < NTASK)
        ok(c->nproduced <= stop_at + 1 + WINDOW, "%s: nothing started beyond the window after the error (%zu produced)",
           name, c->nproduced);
    pthread_mutex_destroy(&c->mu);
    free(c);
}

/* ---- the sweep ------------------------------------------------------------- */

static int same_layer(const lam_layer *a, const lam_layer *b)
{
    if (a->index != b->index || a->npoints != b->npoints || a->ncontours != b->ncontours || a->nopen != b->nopen ||
        memcmp(&a->cut, &b->cut, sizeof a->cut) || a->gaps_closed != b->gaps_closed || a->slivers != b->slivers)
        return 0;
    if (a->npoints && memcmp(a->uv, b->uv, 2 * a->npoints * sizeof *a->uv)) return 0;
    for (size_t k = 0; k < a->ncontours; k++) {
        const lam_contour *p = &a->contours[k], *q = &b->contours[k];
        if (p->first != q->first || p->n != q->n || p->depth != q->depth || p->parent != q->parent ||
            p->kind != q->kind || memcmp(&p->area, &q->area, sizeof p->area))
            return 0;
    }
    return 1;
}

static void sweep_seek(const lam_model *m, lam_cut cut, double width, const char *name)
{
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    o.cut = cut;
    o.width = width;
    double d[3] = { 1, 2, 3 };
    lam_frame_direction(d, &o.frame, NULL);
    lam_slicer *s = NULL;
    if (lam_slicer_new(m, &o, &s, NULL)) {
        ok(0, "%s: slicer", name);
        return;
    }
    size_t n = lam_slicer_count(s);
    lam_layer **ref = calloc(n, sizeof *ref);
    for (size_t i = 0; i < n; i++) lam_slicer_next(s, &ref[i], NULL);
    /* a fork jumping forward by varying steps, then back, then every layer */
    lam_slicer *f = NULL;
    int good = !lam_slicer_fork(s, &f, NULL), tried = 0;
    uint64_t rng = 0x9e3779b97f4a7c15ull;
    for (size_t i = 0; good && i < n; i += 1 + xorshift64(&rng) % 7, tried++) {
        lam_slicer_seek(f, i);
        lam_layer *L = NULL;
        good = !lam_slicer_next(f, &L, NULL) && L && same_layer(L, ref[i]);
        if (!good) diag("%s: layer %zu after a jump differs", name, i);
        lam_layer_free(L);
    }
    for (size_t i = n; good && i-- > 0;) { /* backward: a sweep again from the bottom */
        lam_slicer_seek(f, i);
        lam_layer *L = NULL;
        good = !lam_slicer_next(f, &L, NULL) && L && same_layer(L, ref[i]);
        if (!good) diag("%s: layer %zu after a jump back differs", name, i);
        lam_layer_free(L);
        if (i + 10 < n) break; /* a few are enough: each is a full sweep */
    }
    ok(good && tried > 5 && n > 20, "%s: a forked sweep that jumps (%d jumps over %zu layers) gives the same layers, bit for bit",
       name, tried, n);
    lam_layer *c = n ? lam_layer_clone(ref[n / 2]) : NULL;
    ok(c && c->uv != ref[n / 2]->uv && same_layer(c, ref[n / 2]), "%s: a cloned layer is an equal copy", name);
    lam_layer_free(c);
    lam_slicer_free(f); /* before its parent */
    for (size_t i = 0; i < n; i++) lam_layer_free(ref[i]);
    free(ref);
    lam_slicer_free(s);
}

/* ---- the recording sink ----------------------------------------------------- */

typedef struct calls {
    char text[4096];
    size_t len;
} calls;

static void say(calls *l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(calls *l, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(l->text + l->len, sizeof l->text - l->len, fmt, ap);
    va_end(ap);
    if (n > 0 && l->len + (size_t)n < sizeof l->text) l->len += (size_t)n;
}

static int l_feed(void *ctx, double r)
{
    say(ctx, "feed %.17g;", r);
    return 0;
}
static int l_laser(void *ctx, int on)
{
    say(ctx, "laser %d;", on);
    return 0;
}
static int l_move(void *ctx, const lam_move_info *m)
{
    say(ctx, "%s %.17g %.17g %.17g %.17g %.17g part %lld;", m->deposit ? "dep" : "trav", m->xyz[0], m->xyz[1], m->xyz[2],
        m->uv[0], m->uv[1], m->attrs.part);
    return 0;
}
static int l_contour(void *ctx, const lam_contour_info *c)
{
    say(ctx, "contour n %zu solid %d z %.17g:", c->n, c->solid, c->z);
    for (size_t i = 0; i < c->n; i++) say(ctx, " %.17g,%.17g,%.17g", c->xyz[3 * i], c->xyz[3 * i + 1], c->uv[2 * i]);
    return 0;
}
static int l_hatches(void *ctx, const lam_hatch_info *h)
{
    say(ctx, "hatches n %zu kind %s angle %.17g part %lld:", h->n, lam_kind_name(h->kind), h->angle, h->attrs.part);
    for (size_t i = 0; i < 6 * h->n; i++) say(ctx, " %.17g", h->xyz[i]);
    for (size_t i = 0; i < 4 * h->n; i++) say(ctx, " %.17g", h->uv[i]);
    return 0;
}

static int drive(const lam_sink *s)
{
    const double xyz[9] = { 0.1, 0.2, 0.3, 1e-300, -2.5, 3, 7, 8, 9 }, uv[6] = { 0.1, 0.2, -2.5, 3, 7, 8 };
    const double hx[12] = { 1, 2, 3, 4, 5, 6, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5 }, hu[8] = { 1, 2, 4, 5, 1.5, 2.5, 4.5, 5.5 };
    lam_contour_info c = { { .part = 1 }, 1, 0, 0.3, xyz, uv, 3, 100, 200, 0, 0 };
    lam_hatch_info h = { .attrs = { 3 }, .kind = LAM_KIND_UPSKIN, .z = 0.3, .xyz = hx, .uv = hu, .n = 2, .angle = 67,
                         .power = 100, .speed = 200 };
    lam_move_info m1 = { .attrs = { 2 }, .deposit = 1, .xyz = { xyz[3], xyz[4], xyz[5] }, .uv = { -2.5, 3 } };
    lam_move_info m2 = { .attrs = { 1 }, .deposit = 0, .xyz = { xyz[6], xyz[7], xyz[8] }, .uv = { 7, 8 } };
    int rc = s->feed(s->ctx, 1234.5);
    if (!rc) rc = s->laser(s->ctx, 1);
    if (!rc) rc = s->move(s->ctx, &m1);
    if (!rc) rc = s->contour(s->ctx, &c);
    if (!rc) rc = s->hatches(s->ctx, &h);
    if (!rc) rc = s->move(s->ctx, &m2);
    if (!rc) rc = s->laser(s->ctx, 0);
    return rc;
}

static void record_replay(void)
{
    calls direct = { .len = 0 }, replayed = { .len = 0 };
    lam_sink d = { .ctx = &direct, .feed = l_feed, .laser = l_laser, .move = l_move, .contour = l_contour,
                   .hatches = l_hatches };
    drive(&d);
    lam_record r = { 0 };
    lam_sink rs = lam_record_sink(&r, &d);
    int rc = drive(&rs);
    d.ctx = &replayed;
    if (!rc) rc = lam_record_replay(&r, &d);
    is_int(rc, 0, "record: recording and replaying succeed");
    ok(direct.len > 100 && direct.len == replayed.len && !memcmp(direct.text, replayed.text, direct.len),
       "record: the replay makes the very calls, numbers bit for bit (%zu bytes of calls)", direct.len);
    lam_sink partial = { .ctx = &replayed, .move = l_move };
    lam_sink ps = lam_record_sink(&r, &partial);
    ok(ps.move && !ps.feed && !ps.laser && !ps.contour && !ps.hatches,
       "record: the recording sink has the callbacks of the sink it stands for");
    lam_record_free(&r);
}

/* ---- a dialect's layer text formatted apart ------------------------------- */

static int put_tpl(lam_dialect *d, lam_cmd c, const char *text)
{
    size_t off;
    lam_error err;
    return lam_template_parse(c, text, &d->cmd[c], &off, &err);
}

/* Two layers, the first with no blocks, the second with two contours,
 * sent to a dialect sink directly and through its fork (plan.h): the
 * same text. */
static void dialect_fork(void)
{
    lam_dialect d;
    memset(&d, 0, sizeof d);
    int rc = put_tpl(&d, LAM_CMD_LAYER, "layer {number} {z:%.2f}") | put_tpl(&d, LAM_CMD_LAYER_END, "end {index}") |
             put_tpl(&d, LAM_CMD_CONTOUR_BEGIN, "contour {index} {n} {points:%.1f}") |
             put_tpl(&d, LAM_CMD_SEPARATOR, "--") | put_tpl(&d, LAM_CMD_PREAMBLE, "begin {layers}");
    ok(rc == LAM_OK, "dialect: templates parse");
    double xyz[9] = { 0, 0, 1, 1, 0, 1, 0, 1, 1 }, uv[6] = { 0, 0, 1, 0, 0, 1 };
    lam_contour_info ci = { { .part = 1 }, 1, 0, 1, xyz, uv, 3, 0, 0, 0, 0 };
    lam_layer_info li[2] = { { .index = 0, .z = 0.5, .width = 0.5, .floor = 0, .ceiling = 0.5 }, { .index = 1, .z = 1, .width = 0.5, .floor = 0.5, .ceiling = 1 } };
    lam_job_info job;
    memset(&job, 0, sizeof job);
    job.layers = 2;
    char *text[2] = { NULL, NULL };
    for (int way = 0; way < 2; way++) {
        lam_writer *w;
        lam_error err;
        lam_sink s;
        lam_writer_memory(&w, &err);
        lam_dialect_sink(&d, w, &s, &err);
        s.begin(s.ctx, &job);
        if (way == 0) {
            for (int l = 0; l < 2; l++) {
                s.layer(s.ctx, &li[l]);
                for (int c = 0; c < 2 * l; c++) s.contour(s.ctx, &ci);
                s.layer_end(s.ctx, &li[l]);
            }
        } else {
            lam_sink_fork fk;
            lam_dialect_text t;
            memset(&t, 0, sizeof t);
            ok(s.fork && s.fork(s.ctx, 1, &fk, &err) == LAM_OK, "dialect: a worker's formatter (its fork)");
            lam_sink ws = fk.sink;
            for (int l = 0; l < 2; l++) {
                fk.start(ws.ctx, &err);
                ws.layer(ws.ctx, &li[l]);
                for (int c = 0; c < 2 * l; c++) ws.contour(ws.ctx, &ci);
                ws.layer_end(ws.ctx, &li[l]);
                fk.take(ws.ctx, &t);
                fk.put(fk.main, &t);
            }
            lam_dialect_text_free(&t);
            ws.destroy(ws.ctx);
        }
        s.end(s.ctx);
        s.destroy(s.ctx);
        size_t n;
        lam_writer_take(w, &text[way], &n, &err);
    }
    const char *want = "begin 2\nlayer 1 0.50\nend 0\nlayer 2 1.00\ncontour 0 3 0.0,0.0,1.0,0.0,0.0,1.0\n--\n"
                       "contour 1 3 0.0,0.0,1.0,0.0,0.0,1.0\nend 1\n";
    is_str(text[0], want, "dialect: the sink's own text");
    is_str(text[1], want, "dialect: layers formatted apart and put in order: the same text, no separator first");
    /* relative moves depend on every move before: no worker formatter */
    put_tpl(&d, LAM_CMD_TRAVEL, "G0 X{dx}");
    lam_writer *w;
    lam_error err;
    lam_sink s;
    lam_sink_fork fk;
    lam_writer_memory(&w, &err);
    lam_dialect_sink(&d, w, &s, &err);
    s.begin(s.ctx, &job);
    ok(s.fork(s.ctx, 1, &fk, &err) == LAM_EUSAGE && s.fork(s.ctx, 0, &fk, &err) == LAM_OK,
       "dialect: relative moves are formatted in order, unless the plan has no moves");
    fk.sink.destroy(fk.sink.ctx);
    s.destroy(s.ctx);
    lam_writer_abort(w);
    free(text[0]);
    free(text[1]);
    lam_dialect_free(&d);
}

int main(void)
{
    pool_run(1, 1, NTASK, "pool, 1 worker, runs of 1");
    pool_run(3, 5, NTASK, "pool, 3 workers, runs of 5");
    pool_run(8, 3, NTASK, "pool, 8 workers, runs of 3");
    pool_run(4, 4, 500, "pool, 4 workers, the consumer fails at task 500");
    pool_run(2, 7, 0, "pool, 2 workers, the consumer fails at the first task");

    lam_model *sph = uv_sphere(10, 48, 24, 7, "sphere");
    if (sph) {
        sweep_seek(sph, LAM_CUT_MIDDLE, 0.37, "sphere, oblique axis, middle cuts");
        sweep_seek(sph, LAM_CUT_CEILING, 0.37, "sphere, oblique axis, ceiling cuts");
        lam_model_free(sph);
    }
    lam_model *cube = load_model("thesis_cube_hole.ug");
    if (cube) {
        sweep_seek(cube, LAM_CUT_FLOOR, 0.05, "cube with a hole, floor cuts");
        lam_model_free(cube);
    }
    record_replay();
    dialect_fork();
    return done_testing();
}
