/* The planning driver (plan_drive.h): the stage protocol, written once for
 * every layer source.
 *
 * Workers make and plan whole layers, each into a recording
 * (plan_record.h) or, for a sink that can fork (lam_sink.fork: a text
 * dialect whose text does not hang on the moves before, a plugin writer
 * that allows it, a tee of one of them), straight into that layer's bytes; the calling thread
 * hands each layer to the callbacks and replays its recording onto the
 * real sink or appends its bytes, strictly in layer order, so every sink
 * writes exactly what a run on one thread writes.
 *
 * What a layer's plan depends on besides the layer:
 *  - SLS: the layers around it (skins): a worker makes them too, and the
 *    callback still sees every layer once, in order, as far ahead of the
 *    layer being written as on one thread;
 *  - LADRP: where the stage stands when the layer starts (the nearest
 *    island first, travel lengths): see lam_plan_drive. */
#include "plan_drive.h"
#include "support.h"

#include <stdlib.h>
#include <string.h>

#include "plan_record.h"
#include "pool.h"

typedef struct result {
    const lam_layer *L;      /* the layer, for the callback and a plan again */
    lam_layer *owned;        /* L when the result owns it */
    int slice_rc, plan_rc;
    lam_error slice_err, plan_err;
    lam_record ops;          /* what planning it sent to the sink */
    lam_layer_text text;     /* or, for a sink that forks, the layer's bytes */
    int has_text;
    double entry[3], exit[3];/* LADRP: the stage before and after, as the worker had it */
    int entry_laser, exit_laser;
    lam_ladrp_stats stats;
    lam_scan_time time;      /* SLS: the layer's estimate */
} result;

typedef struct wstate {
    int have_exit;           /* LADRP: the stage after layer exit_layer */
    size_t exit_layer;
    double exit[3];
    int exit_laser;
    lam_sls_state st;
    lam_sink_fork text;      /* formats layers for a sink that forks (run.text) */
} wstate;

typedef struct run {
    const lam_plan_source *src;
    const lam_plan_opts *o;
    lam_plan_opts wo;        /* the planners' options: the run's totals are the driver's */
    const lam_sink *sink;
    size_t skins, window, consumed;
    int text;                /* workers format the layers' bytes (lam_sink.fork) */
    result *res;             /* task t's result at t % window */
    wstate *ws;
    /* the writer's side */
    size_t cb_next;          /* next layer for the callback */
    double pos[3];
    int laser;
    lam_error *err;
} run;

void lam_ladrp_stats_add(lam_ladrp_stats *t, const lam_ladrp_stats *l)
{
    t->lines += l->lines;
    t->deposits += l->deposits;
    t->deposit_length += l->deposit_length;
    t->travel_length += l->travel_length;
}

static void copy_error(lam_error *to, const lam_error *from)
{
    if (to) memcpy(to, from, sizeof *to);
}

static lam_layer_info info(const run *r, const lam_layer *L)
{
    lam_layer_info li = { .index = L->index, .z = L->cut, .width = L->width, .floor = L->floor, .ceiling = L->ceiling, .section = L,
                          .support = lam_supports_region(r->o->supports, L->index),
                          .overhang = lam_supports_overhang(r->o->supports, L->index) };
    return li;
}

/* The layers a plan of layer i looks at: lo .. hi. */
static void span(const run *r, size_t i, int warm, size_t *lo, size_t *hi)
{
    size_t n = r->skins;
    *lo = warm ? i - 1 : i >= n ? i - n : 0;
    *hi = i + n < r->src->n ? i + n : r->src->n - 1;
}

/* Plan the i-th layer (near[k]: layer lo + k) into s: pos and laser are
 * LADRP's stage (updated), st SLS's state. ls and t get the layer's
 * statistics. */
static int plan_one(const run *r, size_t i, const lam_layer *const *near, size_t lo, const lam_sink *s,
                    double pos[3], int *laser, lam_sls_state *st, lam_ladrp_stats *ls, lam_scan_time *t,
                    lam_error *err)
{
    const lam_plan_source *src = r->src;
    lam_plan_opts oi = r->wo;
    if (src->layer_opts) src->layer_opts(src->user, i, &oi);
    memset(ls, 0, sizeof *ls);
    memset(t, 0, sizeof *t);
    const lam_layer *L = near[i - lo];
    if (r->o->kind == LAM_PLAN_LADRP) return lam_plan_ladrp_layer(L, src->f, &oi, s, pos, laser, ls, err);
    const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
    size_t nb = 0, na = 0;
    for (size_t k = 1; k <= r->skins && k <= i; k++) below[nb++] = near[i - k - lo];
    for (size_t k = 1; k <= r->skins && i + k < src->n; k++) above[na++] = near[i + k - lo];
    const lam_hatches *given = src->given ? src->given(src->user, i) : NULL;
    int rc = lam_plan_sls_layer(L, below, nb, above, na, src->f, &oi, s, given, st, err);
    *t = st->time;
    return rc;
}

/* A layer's figures reach the run's (on the calling thread, in order). */
static void account(const run *r, size_t i, const lam_ladrp_stats *ls, const lam_scan_time *t, lam_layer_info *li)
{
    const lam_plan_opts *o = r->o;
    if (o->kind == LAM_PLAN_LADRP) {
        if (o->totals) lam_ladrp_stats_add(o->totals, ls);
    } else {
        if (o->time) lam_scan_time_add(o->time, t);
        if (o->layer_time) o->layer_time[i] = lam_scan_time_total(t);
        if (li && lam_scan_estimates(&o->scan)) li->time = t;
    }
    if (r->src->planned) r->src->planned(r->src->user, i, ls, t);
}

/* ---- on the calling thread ------------------------------------------------ */

/* Layers lo .. hi for a layer planned on the calling thread; the callback
 * sees each new one as it is made. */
static int serial_layers(run *r, size_t lo, size_t hi, const lam_layer **near)
{
    const lam_plan_source *src = r->src;
    for (size_t j = lo; j <= hi; j++) {
        int rc = src->get(src->ctx, 0, j, lo, &near[j - lo], r->err);
        if (rc) return rc;
        if (j < r->cb_next) continue;
        r->cb_next = j + 1;
        if (src->cb && j >= src->first && j < src->end && (rc = src->cb(src->user, near[j - lo], r->err)))
            return rc;
    }
    return LAM_OK;
}

static int serial(run *r)
{
    const lam_plan_source *src = r->src;
    const lam_sink *sink = r->sink, none = { 0 };
    int ladrp = r->o->kind == LAM_PLAN_LADRP, laser = -1, rc = LAM_OK;
    double pos[3];
    memcpy(pos, src->origin, sizeof pos);
    const lam_layer **near = malloc((2 * r->skins + 1) * sizeof *near);
    lam_sls_state st;
    lam_sls_state_init(&st);
    if (!near) rc = lam_error_nomem(r->err, "planning");
    for (size_t i = 0; i < src->end && !rc; i++) {
        size_t lo, hi;
        span(r, i, 0, &lo, &hi);
        if ((rc = serial_layers(r, lo, hi, near))) break;
        if (src->stop && (rc = src->stop(src->user, i))) break;
        lam_layer_info li = info(r, near[i - lo]);
        /* before the range only LADRP's islands need planning (they go
         * nearest first from the stage); otherwise a layer leaves only
         * the laser off behind (SLS: nothing) */
        int skip = i < src->first, plan = !skip || (ladrp && r->o->islands);
        const lam_sink *to = skip ? &none : sink;
        if (!plan) laser = 0;
        if (to->layer) rc = to->layer(to->ctx, &li);
        lam_ladrp_stats ls;
        lam_scan_time t;
        if (!rc && plan) rc = plan_one(r, i, near, lo, to, pos, &laser, &st, &ls, &t, r->err);
        if (!rc && !skip) account(r, i, &ls, &t, &li);
        if (!rc && to->layer_end) rc = to->layer_end(to->ctx, &li);
    }
    free(near);
    lam_sls_state_free(&st);
    return rc;
}

/* ---- on worker threads ---------------------------------------------------- */

/* Layers lo .. hi into near for task i's result R; an error making layer i
 * is R's slice error, one making a neighbour its plan error. */
static int worker_layers(run *r, unsigned worker, size_t i, size_t lo, size_t hi, const lam_layer **near, result *R)
{
    const lam_plan_source *src = r->src;
    for (size_t j = lo; j <= hi; j++) {
        int rc = src->get(src->ctx, worker, j, lo, &near[j - lo], j == i ? &R->slice_err : &R->plan_err);
        if (rc) {
            if (j == i) R->slice_rc = rc;
            else R->plan_rc = rc;
            return rc;
        }
    }
    return LAM_OK;
}

/* Where the stage stands when worker w starts layer i (LADRP): where its
 * layer before left it, or a guess: the layer before planned into no sink
 * from the origin. */
static void entry_stage(const run *r, const wstate *w, size_t i, int warm, const lam_layer *const *near,
                        double pos[3], int *laser)
{
    memcpy(pos, r->src->origin, 3 * sizeof *pos);
    *laser = -1;
    if (i == 0) return;
    if (!warm) {
        memcpy(pos, w->exit, 3 * sizeof *pos);
        *laser = w->exit_laser;
        return;
    }
    const lam_sink none = { 0 };
    lam_ladrp_stats ls;
    lam_scan_time t;
    *laser = i - 1 == 0 ? -1 : 0;
    if (plan_one(r, i - 1, near, i - 1, &none, pos, laser, NULL, &ls, &t, NULL)) {
        memcpy(pos, r->src->origin, 3 * sizeof *pos);
        *laser = 0;
    }
}

/* Plan layer i (near from lo) into rs on worker w. */
static int worker_plan(run *r, wstate *w, size_t i, int warm, const lam_layer *const *near, size_t lo,
                       const lam_sink *rs, result *R)
{
    if (r->o->kind != LAM_PLAN_LADRP)
        return plan_one(r, i, near, lo, rs, NULL, NULL, &w->st, &R->stats, &R->time, &R->plan_err);
    double pos[3];
    int laser;
    entry_stage(r, w, i, warm, near, pos, &laser);
    memcpy(R->entry, pos, sizeof pos);
    R->entry_laser = laser;
    int rc = plan_one(r, i, near, lo, rs, pos, &laser, NULL, &R->stats, &R->time, &R->plan_err);
    memcpy(R->exit, pos, sizeof pos);
    R->exit_laser = laser;
    if (!rc) {
        w->have_exit = 1;
        w->exit_layer = i;
        memcpy(w->exit, pos, sizeof pos);
        w->exit_laser = laser;
    }
    return rc;
}

/* The writer gets the layer: the source's own, one it hands over, or a
 * copy (the skins of the next ones keep theirs). */
static void keep_layer(run *r, unsigned worker, size_t i, const lam_layer *L, result *R)
{
    const lam_plan_source *src = r->src;
    if (src->stable) {
        R->L = L;
    } else if (src->take && (R->owned = src->take(src->ctx, worker, i))) {
        R->L = R->owned;
    } else if ((R->L = R->owned = lam_layer_clone(L)) == NULL) {
        R->plan_rc = lam_error_nomem(&R->plan_err, "planning a layer");
    }
}

static void reset(result *R)
{
    R->L = R->owned = NULL;
    R->slice_rc = R->plan_rc = LAM_OK;
    lam_error_clear(&R->slice_err);
    lam_error_clear(&R->plan_err);
    lam_record_clear(&R->ops);
    memset(&R->stats, 0, sizeof R->stats);
    memset(&R->time, 0, sizeof R->time);
}

static int produce(void *ctx, unsigned worker, size_t i)
{
    run *r = ctx;
    wstate *w = &r->ws[worker];
    result *R = &r->res[i % r->window];
    reset(R);
    int warm = r->o->kind == LAM_PLAN_LADRP && i > 0 && !(w->have_exit && w->exit_layer == i - 1);
    size_t lo, hi;
    span(r, i, warm, &lo, &hi);
    w->have_exit = 0;
    const lam_layer *near[2 * LAM_SKIN_MAX + 1];
    int rc = worker_layers(r, worker, i, lo, hi, near, R);
    if (rc) return rc;
    /* a forked sink formats the layer here, whole; other sinks get the
     * recording replayed */
    lam_sink rs = r->text ? w->text.sink : lam_record_sink(&R->ops, r->sink);
    lam_layer_info li = info(r, near[i - lo]);
    R->has_text = r->text;
    if (r->text) {
        w->text.start(rs.ctx, &R->plan_err);
        rc = rs.layer ? rs.layer(rs.ctx, &li) : LAM_OK; /* out of memory: the error is in plan_err */
    }
    if (!rc) rc = worker_plan(r, w, i, warm, near, lo, &rs, R);
    if (!rc && r->text && rs.layer_end) rc = rs.layer_end(rs.ctx, &li);
    if (r->text) w->text.take(rs.ctx, &R->text);
    if (rc && R->plan_err.code == LAM_OK) {
        if (R->ops.failed) lam_error_nomem(&R->plan_err, "planning a layer");
        else lam_error_set(&R->plan_err, rc, NULL, 0, 0, "planning failed");
    }
    R->plan_rc = rc;
    keep_layer(r, worker, i, near[i - lo], R);
    return R->plan_rc;
}

/* The callback for the layers up to hi, as far ahead as one thread makes
 * them. */
static int callbacks(run *r, size_t hi)
{
    const lam_plan_source *src = r->src;
    for (; r->cb_next <= hi; r->cb_next++) {
        result *Q = &r->res[r->cb_next % r->window];
        if (Q->slice_rc) {
            copy_error(r->err, &Q->slice_err);
            return Q->slice_rc;
        }
        if (!Q->L) {
            copy_error(r->err, &Q->plan_err);
            return Q->plan_rc ? Q->plan_rc : LAM_ENOMEM;
        }
        int rc = src->cb ? src->cb(src->user, Q->L, r->err) : LAM_OK;
        if (rc) return rc;
    }
    return LAM_OK;
}

/* Layer i as the worker made it: its bytes, or its recording replayed, or
 * (LADRP from a wrong guess) planned again here. */
static int write_layer(run *r, size_t i, result *R)
{
    const lam_sink *sink = r->sink;
    int ladrp = r->o->kind == LAM_PLAN_LADRP;
    int same = !ladrp || (!memcmp(R->entry, r->pos, sizeof r->pos) && R->entry_laser == r->laser);
    lam_layer_info li = info(r, R->L);
    lam_ladrp_stats ls = R->stats;
    int text = R->has_text && same, rc;
    if (text) {
        /* the layer's bytes as the worker formatted them: whole, or up to
         * the error planning it */
        rc = r->ws[0].text.put(r->ws[0].text.main, &R->text);
    } else {
        rc = sink->layer ? sink->layer(sink->ctx, &li) : LAM_OK;
        if (!rc && same) {
            rc = lam_record_replay(&R->ops, sink); /* what the layer sent, then its error */
        } else if (!rc) {
            /* the worker started from a guess that was wrong: plan it here */
            lam_scan_time t;
            rc = plan_one(r, i, &R->L, i, sink, r->pos, &r->laser, NULL, &ls, &t, r->err);
        }
    }
    if (!rc && same && R->plan_rc) {
        copy_error(r->err, &R->plan_err);
        rc = R->plan_rc;
    }
    if (rc) return rc;
    if (ladrp && same) {
        memcpy(r->pos, R->exit, sizeof r->pos);
        r->laser = R->exit_laser;
    }
    account(r, i, &ls, &R->time, text ? NULL : &li);
    return !text && sink->layer_end ? sink->layer_end(sink->ctx, &li) : LAM_OK;
}

static int consume(void *ctx, size_t i, int prc)
{
    (void)prc;
    run *r = ctx;
    const lam_plan_source *src = r->src;
    result *R = &r->res[i % r->window];
    r->consumed++;
    size_t hi = i + r->skins < src->n ? i + r->skins : src->n - 1;
    int rc = callbacks(r, hi);
    if (!rc && src->stop) rc = src->stop(src->user, i);
    if (!rc) rc = write_layer(r, i, R);
    if (R->owned) lam_layer_free(R->owned);
    R->L = R->owned = NULL;
    return rc;
}

/* The workers' state; sinks that fork format the layers' bytes on the
 * workers when every worker has its formatter (otherwise the recordings
 * are replayed: the same bytes). */
static int setup(run *r, unsigned threads)
{
    int rc = LAM_OK;
    for (unsigned k = 0; k < threads; k++) lam_sls_state_init(&r->ws[k].st);
    r->text = r->sink->fork != NULL;
    for (unsigned k = 0; k < threads && r->text; k++) {
        int frc = r->sink->fork(r->sink->ctx, r->o->kind == LAM_PLAN_LADRP, &r->ws[k].text, r->err);
        r->text = !frc;
        if (frc == LAM_ENOMEM) rc = frc;
    }
    return rc;
}

static void teardown(run *r, unsigned threads)
{
    for (unsigned k = 0; r->ws && k < threads; k++) {
        lam_sls_state_free(&r->ws[k].st);
        if (r->ws[k].text.sink.destroy) r->ws[k].text.sink.destroy(r->ws[k].text.sink.ctx);
    }
    for (size_t t = 0; r->res && t < r->window; t++) {
        lam_layer_free(r->res[t].owned);
        lam_record_free(&r->res[t].ops);
        free(r->res[t].text.s);
    }
    free(r->res);
    free(r->ws);
    r->res = NULL;
    r->ws = NULL;
}

static int threaded(run *r, unsigned threads)
{
    const lam_plan_source *src = r->src;
    /* Runs of consecutive layers a worker makes on its own: a new run
     * costs a slicer's sweep only the edges scheduled in between, but a
     * LADRP worker plans one layer more (where the stage stands) and skins
     * make 2 * skins more: runs of 16 there, of 4 for plain SLS, whose
     * layers are independent. Every worker busy while the writer catches
     * up: a window of a run more than there are workers, which bounds
     * memory. */
    size_t most = r->o->kind == LAM_PLAN_LADRP ? 16 : r->skins ? 4 * r->skins + 4 : 4;
    if (most > 16) most = 16;
    size_t chunk = src->n / (4 * (size_t)threads);
    chunk = chunk < 1 ? 1 : chunk > most ? most : chunk;
    size_t window = chunk * (threads + 1) + r->skins;
    if (window < 4 * (size_t)threads) window = 4 * (size_t)threads;
    r->window = window = lam_pool_window(chunk, r->skins, window);
    r->res = calloc(window, sizeof *r->res);
    r->ws = calloc(threads, sizeof *r->ws);
    int rc = r->res && r->ws ? LAM_OK : lam_error_nomem(r->err, "starting threads");
    if (!rc && src->start) rc = src->start(src->ctx, threads, r->err);
    if (!rc) rc = setup(r, threads);
    if (!rc) rc = lam_pool_ordered(threads, src->n, chunk, r->skins, window, produce, consume, r, r->err);
    teardown(r, threads);
    if (src->finish) src->finish(src->ctx);
    return rc;
}

int lam_plan_drive(const lam_plan_source *src, const lam_sink *sink, lam_error *err)
{
    const lam_plan_opts *o = src->o;
    run r;
    memset(&r, 0, sizeof r);
    r.src = src;
    r.o = o;
    r.wo = *o;
    r.wo.totals = NULL;
    r.wo.time = NULL;
    r.wo.layer_time = NULL;
    r.sink = sink;
    r.err = err;
    r.skins = o->kind == LAM_PLAN_SLS && o->scan.skin_layers > 0 ? (size_t)o->scan.skin_layers : 0;
    memcpy(r.pos, src->origin, sizeof r.pos);
    r.laser = -1;
    size_t threads = o->threads > LAM_MAX_THREADS ? LAM_MAX_THREADS : o->threads;
    if (threads > src->n) threads = src->n;
    int rc = LAM_ENOMEM;
    if (threads > 1 && src->first == 0 && src->end == src->n) {
        rc = threaded(&r, (unsigned)threads);
        if (rc != LAM_ENOMEM || r.consumed) return rc;
        /* no threads to be had: the sink has seen nothing yet */
        lam_error_clear(err);
    }
    r.cb_next = 0;
    if (src->start && (rc = src->start(src->ctx, 1, err))) return rc;
    rc = serial(&r);
    if (src->finish) src->finish(src->ctx);
    return rc;
}
