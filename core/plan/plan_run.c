/* lam_plan_run (planner.h): one slicing run through a planner into a sink,
 * the planning driver (plan_drive.h) over a slicer: each worker sweeps a
 * fork of the run (the calling thread, alone, the run's own slicer),
 * keeping the layers a plan looks at (skins; LADRP's layer before). */
#include "plan_drive.h"

#include <stdlib.h>
#include <string.h>

#include "planner.h"
#include "support.h"

typedef struct sweep {
    lam_slicer *sc;          /* this worker's sweep (a fork, or the run's own) */
    int forked;
    lam_layer **cache;       /* layers first .. first + count - 1, owned */
    size_t first, count, cap;
} sweep;

typedef struct slicer_src {
    lam_slicer *s;
    size_t skins;
    sweep *ws;
    unsigned workers;
} slicer_src;

static void cache_drop_before(sweep *w, size_t lo)
{
    size_t k = 0;
    while (k < w->count && w->first + k < lo) lam_layer_free(w->cache[k++]);
    if (!k) return;
    memmove(w->cache, w->cache + k, (w->count - k) * sizeof *w->cache);
    w->count -= k;
    w->first += k;
}

static void cache_clear(sweep *w)
{
    for (size_t k = 0; k < w->count; k++) lam_layer_free(w->cache[k]);
    w->count = 0;
}

static void src_finish(void *ctx)
{
    slicer_src *ss = ctx;
    for (unsigned k = 0; ss->ws && k < ss->workers; k++) {
        cache_clear(&ss->ws[k]);
        free(ss->ws[k].cache);
        if (ss->ws[k].forked) lam_slicer_free(ss->ws[k].sc);
    }
    free(ss->ws);
    ss->ws = NULL;
    ss->workers = 0;
}

static int src_start(void *ctx, unsigned workers, lam_error *err)
{
    slicer_src *ss = ctx;
    ss->ws = calloc(workers, sizeof *ss->ws);
    if (!ss->ws) return lam_error_nomem(err, "starting threads");
    ss->workers = workers;
    int rc = LAM_OK;
    for (unsigned k = 0; k < workers && !rc; k++) {
        sweep *w = &ss->ws[k];
        w->cap = 2 * ss->skins + 2;
        if (!(w->cache = calloc(w->cap, sizeof *w->cache))) rc = lam_error_nomem(err, "starting threads");
        else if (workers == 1) w->sc = ss->s;
        else if (!(rc = lam_slicer_fork(ss->s, &w->sc, err))) w->forked = 1;
    }
    if (rc) src_finish(ss);
    return rc;
}

/* Layer j in the worker's cache, sliced now if it is not there (the cache
 * holds consecutive layers; asking for the one after them goes on
 * sweeping). */
static int src_get(void *ctx, unsigned worker, size_t j, size_t keep, const lam_layer **out, lam_error *err)
{
    slicer_src *ss = ctx;
    sweep *w = &ss->ws[worker];
    cache_drop_before(w, keep);
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

/* Without skins the layer just planned is the last the worker needs. */
static lam_layer *src_take(void *ctx, unsigned worker, size_t j)
{
    slicer_src *ss = ctx;
    sweep *w = &ss->ws[worker];
    if (ss->skins || !w->count || w->first + w->count - 1 != j) return NULL;
    return w->cache[--w->count];
}

int lam_plan_supports(lam_slicer *s, const lam_plan_opts *o, lam_supports **out, lam_error *err)
{
    *out = NULL;
    if (o->kind != LAM_PLAN_SLS || o->supports || o->scan.support.type == LAM_SUPPORT_NONE) return LAM_OK;
    lam_layer **L = NULL;
    size_t n = 0;
    int rc = lam_slicer_all(s, &L, &n, err);
    if (!rc) rc = lam_supports_make((const lam_layer *const *)L, n, &o->scan.support, out, err);
    lam_layers_free(L, n);
    return rc;
}

int lam_plan_run(lam_slicer *s, const lam_model *m, const lam_plan_opts *o, const lam_sink *sink,
                 lam_layer_cb cb, void *cbctx, lam_error *err)
{
    /* the estimate before anything is sliced whole, then again with the
     * supports' walls (they need every layer: planning's cost, not the
     * estimate's) */
    lam_job_estimate est;
    lam_plan_estimate(s, o, &est);
    if (lam_plan_check_estimate(&est, o, o->max_output, err)) return LAM_ELIMIT;
    lam_supports *sup = NULL;
    int rc = lam_plan_supports(s, o, &sup, err);
    lam_plan_opts so = *o;
    so.supports = sup ? sup : o->supports;
    o = &so;
    if (!rc && sup) {
        lam_plan_estimate(s, o, &est);
        if (lam_plan_check_estimate(&est, o, o->max_output, err)) rc = LAM_ELIMIT;
    }
    lam_job_info job;
    char label[128];
    lam_plan_job(s, m, o, &job, label);
    if (!rc && sink->begin) rc = sink->begin(sink->ctx, &job);
    /* a worker holds a whole layer's operations until it is written: layers
     * estimated beyond LAM_THREAD_LAYER_MAX are streamed on one thread; a
     * part (a layer range) is planned on one thread too: parts are how a
     * job is spread over processes and machines already */
    lam_plan_opts ro = *o;
    if (o->layer_count || (est.layers && est.bytes / (double)est.layers > LAM_THREAD_LAYER_MAX)) ro.threads = 1;
    slicer_src ss = { s, o->kind == LAM_PLAN_SLS && o->scan.skin_layers > 0 ? (size_t)o->scan.skin_layers : 0,
                      NULL, 0 };
    lam_plan_source src;
    memset(&src, 0, sizeof src);
    src.n = lam_slicer_count(s);
    src.first = o->layer_first;
    src.end = o->layer_count && o->layer_first + o->layer_count < src.n ? o->layer_first + o->layer_count : src.n;
    src.f = lam_slicer_frame(s);
    src.o = &ro;
    memcpy(src.origin, job.origin, sizeof src.origin);
    src.start = src_start;
    src.finish = src_finish;
    src.get = src_get;
    src.take = src_take;
    src.ctx = &ss;
    src.cb = cb;
    src.user = cbctx;
    if (!rc) rc = lam_plan_drive(&src, sink, err);
    if (!rc && sink->end) rc = sink->end(sink->ctx);
    lam_supports_free(sup);
    if (rc && err && err->code == LAM_OK) lam_error_set(err, rc, NULL, 0, 0, "planning failed");
    /* geometry that fails says which model (its message: the layer and the stage) */
    if (rc && err && err->code == LAM_EGEOM && !err->file[0] && m && m->path)
        lam_error_set(err, err->code, m->path, 0, 0, "%s", err->msg);
    return rc;
}
