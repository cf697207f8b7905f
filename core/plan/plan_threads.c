/* lam_plan_run on several threads (issue 15): workers slice and plan whole
 * layers, each into a recording (plan_record.h) or, for a text dialect
 * whose text does not hang on the moves before (lam_dialect_fork) or a
 * plugin writer that allows it (lam_plugin_fork), straight into that
 * layer's bytes; the calling thread hands each layer to the callback and
 * replays its recording onto the real sink or appends its bytes
 * (lam_dialect_put, lam_plugin_put), strictly in layer order, so every sink (text dialects,
 * plugin writers) writes exactly what a run on one thread writes.
 *
 * What a layer's plan depends on besides the layer:
 *  - SLS: the layers around it (skins): a worker slices them too, and the
 *    callback still sees every layer once, in order, as far ahead of the
 *    layer being written as on one thread;
 *  - LADRP: where the stage stands when the layer starts (the nearest
 *    island first, travel lengths). A worker going on from the layer before
 *    knows it; at the start of a run of layers it plans the layer before
 *    first, unrecorded, from a guess. The writer compares the stage each
 *    recording assumed with the real one, bit for bit, and plans the layer
 *    again itself when they differ: never a different program, at worst
 *    one layer planned twice. */
#include "plan_threads.h"

#include <stdlib.h>
#include <string.h>

#include "dialect.h"
#include "plan_record.h"
#include "plugin.h"
#include "pool.h"

typedef struct result {
    lam_layer *L;            /* the layer (owned), for the callback and a plan again */
    int slice_rc, plan_rc;
    lam_error slice_err, plan_err;
    lam_record ops;          /* what planning it sent to the sink */
    lam_dialect_text text;   /* or, for a text dialect, the layer's text */
    int has_text;
    double entry[3], exit[3];/* LADRP: the stage before and after, as the worker had it */
    int entry_laser, exit_laser;
    lam_ladrp_stats stats;
    lam_scan_time time;      /* SLS: the layer's estimate */
} result;

typedef struct wstate {
    lam_slicer *sc;          /* this worker's sweep */
    lam_layer **cache;       /* layers first .. first + count - 1, owned */
    size_t first, count, cap;
    int have_exit;           /* LADRP: the stage after layer exit_layer */
    size_t exit_layer;
    double exit[3];
    lam_sls_state st;
    lam_sink text;           /* formats layers for a text dialect (run.text) */
} wstate;

enum { TEXT_DIALECT = 1, TEXT_PLUGIN };

typedef struct run {
    const lam_plan_opts *o;
    lam_plan_opts wo;        /* the workers' options: no run totals */
    const lam_frame *f;
    const lam_sink *sink;
    lam_layer_cb cb;
    void *cbctx;
    double origin[3];
    size_t S, skins, window;
    int text;                /* workers format the layers' bytes: TEXT_DIALECT, TEXT_PLUGIN, or 0 */
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

static void cache_drop_before(wstate *w, size_t lo)
{
    size_t k = 0;
    while (k < w->count && w->first + k < lo) lam_layer_free(w->cache[k++]);
    if (!k) return;
    memmove(w->cache, w->cache + k, (w->count - k) * sizeof *w->cache);
    w->count -= k;
    w->first += k;
}

static void cache_clear(wstate *w)
{
    for (size_t k = 0; k < w->count; k++) lam_layer_free(w->cache[k]);
    w->count = 0;
}

/* Layer j in w's cache, sliced now if it is not there (the cache holds
 * consecutive layers; asking for the one after them goes on sweeping). */
static int worker_layer(wstate *w, size_t j, lam_layer **out, lam_error *err)
{
    if (w->count && j >= w->first && j < w->first + w->count) {
        *out = w->cache[j - w->first];
        return LAM_OK;
    }
    if (!w->count || j != w->first + w->count || w->count == w->cap) {
        cache_clear(w);
        w->first = j;
    }
    lam_slicer_seek(w->sc, j);
    lam_layer *L = NULL;
    int rc = lam_slicer_next(w->sc, &L, err);
    if (rc || !L) {
        lam_slicer_seek(w->sc, 0); /* start afresh: a sweep that failed half way */
        cache_clear(w);
        return rc ? rc : lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "layer %zu is past the run", j + 1);
    }
    w->cache[w->count++] = L;
    *out = L;
    return LAM_OK;
}

static void copy_error(lam_error *to, const lam_error *from)
{
    if (to) memcpy(to, from, sizeof *to);
}

static int produce(void *ctx, unsigned worker, size_t i)
{
    run *r = ctx;
    wstate *w = &r->ws[worker];
    result *R = &r->res[i % r->window];
    const lam_plan_opts *o = &r->wo;
    R->L = NULL;
    R->slice_rc = R->plan_rc = LAM_OK;
    lam_error_clear(&R->slice_err);
    lam_error_clear(&R->plan_err);
    lam_record_clear(&R->ops);
    memset(&R->stats, 0, sizeof R->stats);
    memset(&R->time, 0, sizeof R->time);
    int ladrp = o->kind == LAM_PLAN_LADRP;
    int warm = ladrp && i > 0 && !(w->have_exit && w->exit_layer == i - 1);
    size_t n = r->skins;
    size_t lo = warm ? i - 1 : i >= n ? i - n : 0, hi = i + n < r->S ? i + n : r->S - 1;
    cache_drop_before(w, lo);
    w->have_exit = 0;
    lam_layer *L = NULL;
    for (size_t j = lo; j <= hi; j++) {
        lam_layer *Lj = NULL;
        lam_error *e = j == i ? &R->slice_err : &R->plan_err;
        int rc = worker_layer(w, j, &Lj, e);
        if (rc) {
            if (j == i) R->slice_rc = rc;
            else R->plan_rc = rc;
            return rc;
        }
        if (j == i) L = Lj;
    }
    /* a text dialect's layer is formatted here, whole; other sinks get
     * the recording replayed */
    lam_sink rs = r->text ? w->text : lam_record_sink(&R->ops, r->sink);
    lam_layer_info li = { L->index, L->cut, L->width, L->floor, L->ceiling, L, NULL };
    R->has_text = r->text;
    int rc = LAM_OK;
    if (r->text) {
        if (r->text == TEXT_PLUGIN) lam_plugin_fork_start(&rs, &R->plan_err);
        else lam_dialect_fork_start(&rs, &R->plan_err);
        rc = rs.layer(rs.ctx, &li);
    }
    if (rc) {
        /* out of memory for the layer command: the error is in plan_err */
    } else if (ladrp) {
        double pos[3];
        int laser = i == 0 ? -1 : 0;
        memcpy(pos, i == 0 || !warm ? (i == 0 ? r->origin : w->exit) : r->origin, sizeof pos);
        if (warm) {
            /* the layer before, from a guess: its end is where this one starts */
            lam_sink none = { 0 };
            lam_ladrp_stats ls;
            int prev_laser = i - 1 == 0 ? -1 : 0;
            if (lam_plan_ladrp_layer(w->cache[i - 1 - w->first], r->f, o, &none, pos, &prev_laser, &ls, NULL))
                memcpy(pos, r->origin, sizeof pos);
        }
        memcpy(R->entry, pos, sizeof pos);
        R->entry_laser = laser;
        rc = lam_plan_ladrp_layer(L, r->f, o, &rs, pos, &laser, &R->stats, &R->plan_err);
        memcpy(R->exit, pos, sizeof pos);
        R->exit_laser = laser;
        if (!rc) {
            w->have_exit = 1;
            w->exit_layer = i;
            memcpy(w->exit, pos, sizeof pos);
        }
    } else {
        const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
        size_t nb = 0, na = 0;
        for (size_t k = 1; k <= n && k <= i; k++) below[nb++] = w->cache[i - k - w->first];
        for (size_t k = 1; k <= n && i + k < r->S; k++) above[na++] = w->cache[i + k - w->first];
        rc = lam_plan_sls_layer(L, below, nb, above, na, r->f, o, &rs, NULL, &w->st, &R->plan_err);
        R->time = w->st.time;
    }
    if (!rc && r->text) rc = rs.layer_end(rs.ctx, &li);
    if (r->text == TEXT_PLUGIN) lam_plugin_fork_take(&rs, &R->text);
    else if (r->text) lam_dialect_fork_take(&rs, &R->text);
    if (rc && R->plan_err.code == LAM_OK) {
        if (R->ops.failed) lam_error_nomem(&R->plan_err, "planning a layer");
        else lam_error_set(&R->plan_err, rc, NULL, 0, 0, "planning failed");
    }
    R->plan_rc = rc;
    /* the writer gets the layer; the skins of the next ones keep a copy */
    if (n == 0 && w->count && w->first + w->count - 1 == i) {
        R->L = L;
        w->count--;
    } else if (!(R->L = lam_layer_clone(L))) {
        R->plan_rc = lam_error_nomem(&R->plan_err, "planning a layer");
    }
    return R->plan_rc;
}

static int consume(void *ctx, size_t i, int prc)
{
    (void)prc;
    run *r = ctx;
    const lam_plan_opts *o = r->o;
    const lam_sink *sink = r->sink;
    lam_error *err = r->err;
    result *R = &r->res[i % r->window];
    /* the callback sees the layers as far ahead as one thread slices them */
    size_t hi = i + r->skins < r->S ? i + r->skins : r->S - 1;
    for (; r->cb_next <= hi; r->cb_next++) {
        result *Q = &r->res[r->cb_next % r->window];
        if (Q->slice_rc) {
            copy_error(err, &Q->slice_err);
            return Q->slice_rc;
        }
        if (!Q->L) {
            copy_error(err, &Q->plan_err);
            return Q->plan_rc ? Q->plan_rc : LAM_ENOMEM;
        }
        int rc = r->cb ? r->cb(r->cbctx, Q->L, err) : LAM_OK;
        if (rc) return rc;
    }
    lam_layer *L = R->L;
    lam_layer_info li = { L->index, L->cut, L->width, L->floor, L->ceiling, L, NULL };
    if (R->has_text && (R->plan_rc || o->kind != LAM_PLAN_LADRP ||
                        (!memcmp(R->entry, r->pos, sizeof r->pos) && R->entry_laser == r->laser))) {
        /* the layer's text as the worker formatted it: whole, or up to the
         * error planning it */
        int rc = R->has_text == TEXT_PLUGIN ? lam_plugin_put(sink, &R->text) : lam_dialect_put(sink, &R->text);
        if (!rc && R->plan_rc) {
            copy_error(err, &R->plan_err);
            rc = R->plan_rc;
        }
        if (!rc && o->kind == LAM_PLAN_LADRP) {
            memcpy(r->pos, R->exit, sizeof r->pos);
            r->laser = R->exit_laser;
            if (o->totals) lam_ladrp_stats_add(o->totals, &R->stats);
        }
        if (!rc && o->kind == LAM_PLAN_SLS) {
            if (o->time) lam_scan_time_add(o->time, &R->time);
            if (o->layer_time) o->layer_time[L->index] = lam_scan_time_total(&R->time);
        }
        lam_layer_free(R->L);
        R->L = NULL;
        return rc;
    }
    int rc = sink->layer ? sink->layer(sink->ctx, &li) : LAM_OK;
    if (!rc && R->plan_rc) {
        /* what the layer sent before it failed, then its error */
        rc = lam_record_replay(&R->ops, sink);
        if (!rc) {
            copy_error(err, &R->plan_err);
            rc = R->plan_rc;
        }
    } else if (!rc && o->kind == LAM_PLAN_LADRP) {
        if (!memcmp(R->entry, r->pos, sizeof r->pos) && R->entry_laser == r->laser) {
            rc = lam_record_replay(&R->ops, sink);
            memcpy(r->pos, R->exit, sizeof r->pos);
            r->laser = R->exit_laser;
            if (o->totals) lam_ladrp_stats_add(o->totals, &R->stats);
        } else {
            lam_ladrp_stats ls;
            rc = lam_plan_ladrp_layer(L, r->f, o, sink, r->pos, &r->laser, &ls, err);
            if (o->totals) lam_ladrp_stats_add(o->totals, &ls);
        }
    } else if (!rc) {
        rc = lam_record_replay(&R->ops, sink);
        if (!rc && o->time) lam_scan_time_add(o->time, &R->time);
        if (!rc && o->layer_time) o->layer_time[L->index] = lam_scan_time_total(&R->time);
        if (lam_scan_estimates(&o->scan)) li.time = &R->time;
    }
    if (!rc && sink->layer_end) rc = sink->layer_end(sink->ctx, &li);
    lam_layer_free(R->L);
    R->L = NULL;
    return rc;
}

/* A worker's formatter for sink: a text dialect's or, for contours, a
 * plugin writer's that allows it (which, in *kind); LAM_EUSAGE when
 * neither can. */
static int fork_text(const lam_sink *sink, int ladrp, lam_sink *out, int *kind, lam_error *err)
{
    int rc = lam_dialect_fork(sink, ladrp, out, err);
    if (rc != LAM_EUSAGE) {
        *kind = TEXT_DIALECT;
        return rc;
    }
    if (ladrp) return LAM_EUSAGE;
    *kind = TEXT_PLUGIN;
    return lam_plugin_fork(sink, out, err);
}

int lam_plan_threaded(lam_slicer *s, const lam_plan_opts *o, const lam_sink *sink, lam_layer_cb cb, void *cbctx,
                      const double origin[3], lam_error *err)
{
    unsigned threads = o->threads > LAM_MAX_THREADS ? LAM_MAX_THREADS : o->threads;
    run r;
    memset(&r, 0, sizeof r);
    r.o = o;
    r.wo = *o;
    r.wo.totals = NULL;
    r.wo.time = NULL;
    r.wo.layer_time = NULL;
    r.f = lam_slicer_frame(s);
    r.sink = sink;
    r.cb = cb;
    r.cbctx = cbctx;
    memcpy(r.origin, origin, sizeof r.origin);
    memcpy(r.pos, origin, sizeof r.pos);
    r.laser = -1;
    r.err = err;
    r.S = lam_slicer_count(s);
    r.skins = o->kind == LAM_PLAN_SLS && o->scan.skin_layers > 0 ? (size_t)o->scan.skin_layers : 0;
    if (!r.S) return LAM_OK;
    /* Runs of consecutive layers a worker sweeps on its own: a new run
     * costs the sweep only the edges scheduled in between, but a LADRP
     * worker plans one layer more (where the stage stands) and skins slice
     * 2 * skins more: runs of 16 there, of 4 for plain SLS, whose layers
     * are independent. Every worker busy while the writer catches up: a
     * window of a run more than there are workers, which bounds memory. */
    size_t most = o->kind == LAM_PLAN_LADRP ? 16 : r.skins ? 4 * r.skins + 4 : 4;
    if (most > 16) most = 16;
    size_t chunk = r.S / (4 * (size_t)threads);
    chunk = chunk < 1 ? 1 : chunk > most ? most : chunk;
    size_t window = chunk * (threads + 1) + r.skins;
    if (window < 4 * (size_t)threads) window = 4 * (size_t)threads;
    r.window = window = lam_pool_window(chunk, r.skins, window);
    r.res = calloc(window, sizeof *r.res);
    r.ws = calloc(threads, sizeof *r.ws);
    int rc = r.res && r.ws ? LAM_OK : lam_error_nomem(err, "starting threads");
    for (unsigned k = 0; k < threads && !rc; k++) {
        wstate *w = &r.ws[k];
        lam_sls_state_init(&w->st);
        w->cap = 2 * r.skins + 2;
        if (!(w->cache = calloc(w->cap, sizeof *w->cache))) rc = lam_error_nomem(err, "starting threads");
        else rc = lam_slicer_fork(s, &w->sc, err);
    }
    /* text dialects and plugin writers that allow it are formatted by the
     * workers when every worker has its formatter (otherwise the
     * recordings are replayed: the same bytes) */
    r.text = !rc;
    for (unsigned k = 0; k < threads && r.text; k++) {
        int kind = 0, frc = fork_text(sink, o->kind == LAM_PLAN_LADRP, &r.ws[k].text, &kind, err);
        r.text = frc ? 0 : kind;
        if (frc == LAM_ENOMEM) rc = frc;
    }
    if (!rc) rc = lam_pool_ordered(threads, r.S, chunk, r.skins, window, produce, consume, &r, err);
    for (unsigned k = 0; r.ws && k < threads; k++) {
        cache_clear(&r.ws[k]);
        free(r.ws[k].cache);
        lam_slicer_free(r.ws[k].sc);
        lam_sls_state_free(&r.ws[k].st);
        if (r.ws[k].text.destroy) r.ws[k].text.destroy(r.ws[k].text.ctx);
    }
    for (size_t t = 0; r.res && t < window; t++) {
        lam_layer_free(r.res[t].L);
        lam_record_free(&r.res[t].ops);
        lam_dialect_text_free(&r.res[t].text);
    }
    free(r.res);
    free(r.ws);
    return rc;
}
