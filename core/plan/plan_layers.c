/* lam_plan_layers: a list of layers made already, planned on the calling
 * thread or, with o->threads > 1, by workers into recordings
 * (plan_record.h) that the calling thread replays in layer order.
 *
 * A layer's plan depends on the layer, its options and, for SLS skins, the
 * layers next to it in the list: all read-only. LADRP also depends on
 * where the stage stands when the layer starts: a worker going on from the
 * layer before knows it; at the start of its run of layers it plans the
 * layer before first, unrecorded, from a guess. The writer compares the
 * stage each recording assumed with the real one, bit for bit, and plans
 * the layer again itself when they differ (as plan_threads.c does for a
 * whole run): never a different program, at worst a layer planned twice. */
#include "plan_layers.h"

#include <stdlib.h>
#include <string.h>

#include "plan_record.h"
#include "pool.h"

static size_t skins(const lam_plan_layers_job *j)
{
    return j->o->kind == LAM_PLAN_SLS && j->o->scan.skin_layers > 0 ? (size_t)j->o->scan.skin_layers : 0;
}

/* Plan the i-th layer into s: pos and laser are LADRP's stage (updated),
 * st SLS's state. ls and t get the layer's statistics. */
static int plan_one(const lam_plan_layers_job *j, size_t i, const lam_sink *s, double pos[3], int *laser,
                    lam_sls_state *st, lam_ladrp_stats *ls, lam_scan_time *t, lam_error *err)
{
    lam_plan_opts oi = *j->o;
    if (j->layer_opts) j->layer_opts(j->ctx, i, &oi);
    memset(ls, 0, sizeof *ls);
    memset(t, 0, sizeof *t);
    const lam_layer *L = j->layers[i];
    if (j->o->kind == LAM_PLAN_LADRP) return lam_plan_ladrp_layer(L, j->frame, &oi, s, pos, laser, ls, err);
    /* skins look at the neighbours in the list given */
    const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
    size_t nskin = skins(j), nb = 0, na = 0;
    for (size_t k = 1; k <= nskin && k <= i; k++) below[nb++] = j->layers[i - k];
    for (size_t k = 1; k <= nskin && i + k < j->n; k++) above[na++] = j->layers[i + k];
    int rc = lam_plan_sls_layer(L, below, nb, above, na, j->frame, &oi, s, j->given ? j->given(j->ctx, i) : NULL, st,
                                err);
    *t = st->time;
    return rc;
}

static lam_layer_info info(const lam_layer *L)
{
    lam_layer_info li = { L->index, L->cut, L->width, L->floor, L->ceiling, L, NULL };
    return li;
}

static int serial(const lam_plan_layers_job *j, const lam_sink *sink, lam_error *err)
{
    double pos[3] = { j->origin[0], j->origin[1], j->origin[2] };
    int laser = -1, rc = LAM_OK;
    lam_sls_state st;
    lam_sls_state_init(&st);
    for (size_t i = 0; i < j->n && !rc; i++) {
        if (j->stop && (rc = j->stop(j->ctx, i))) break;
        lam_layer_info li = info(j->layers[i]);
        lam_ladrp_stats ls;
        lam_scan_time t;
        if (sink->layer) rc = sink->layer(sink->ctx, &li);
        if (!rc) rc = plan_one(j, i, sink, pos, &laser, &st, &ls, &t, err);
        if (!rc && j->planned) j->planned(j->ctx, i, &ls, &t);
        if (!rc && sink->layer_end) rc = sink->layer_end(sink->ctx, &li);
    }
    lam_sls_state_free(&st);
    return rc;
}

/* ---- on worker threads ---------------------------------------------------- */

typedef struct slot {
    int rc;
    lam_error err;
    lam_record ops;          /* what planning the layer sent to the sink */
    double entry[3], exit[3];/* LADRP: the stage before and after, as the worker had it */
    int entry_laser, exit_laser;
    lam_ladrp_stats ls;
    lam_scan_time t;
} slot;

typedef struct worker {
    int have_exit;           /* LADRP: the stage after layer exit_layer */
    size_t exit_layer;
    double exit[3];
    int exit_laser;
    lam_sls_state st;
} worker;

typedef struct prun {
    const lam_plan_layers_job *j;
    const lam_sink *sink;
    slot *res;               /* task t's result at t % window */
    size_t window, consumed;
    worker *ws;
    double pos[3];           /* the writer's stage */
    int laser;
    lam_error *err;
} prun;

static int produce(void *ctx, unsigned wk, size_t i)
{
    prun *r = ctx;
    const lam_plan_layers_job *j = r->j;
    worker *w = &r->ws[wk];
    slot *R = &r->res[i % r->window];
    lam_record_clear(&R->ops);
    lam_error_clear(&R->err);
    lam_sink rs = lam_record_sink(&R->ops, r->sink);
    double pos[3];
    int laser = -1;
    memcpy(pos, j->origin, sizeof pos);
    if (j->o->kind == LAM_PLAN_LADRP && i > 0) {
        if (w->have_exit && w->exit_layer == i - 1) {
            memcpy(pos, w->exit, sizeof pos);
            laser = w->exit_laser;
        } else {
            /* the layer before, from a guess: its end is where this one starts */
            lam_sink none = { 0 };
            lam_ladrp_stats ls;
            lam_scan_time t;
            laser = i - 1 == 0 ? -1 : 0;
            if (plan_one(j, i - 1, &none, pos, &laser, NULL, &ls, &t, NULL)) {
                memcpy(pos, j->origin, sizeof pos);
                laser = 0;
            }
        }
    }
    w->have_exit = 0;
    memcpy(R->entry, pos, sizeof pos);
    R->entry_laser = laser;
    int rc = plan_one(j, i, &rs, pos, &laser, &w->st, &R->ls, &R->t, &R->err);
    memcpy(R->exit, pos, sizeof pos);
    R->exit_laser = laser;
    if (!rc) {
        w->have_exit = 1;
        w->exit_layer = i;
        memcpy(w->exit, pos, sizeof pos);
        w->exit_laser = laser;
    } else if (R->err.code == LAM_OK) {
        if (R->ops.failed) lam_error_nomem(&R->err, "planning a layer");
        else lam_error_set(&R->err, rc, NULL, 0, 0, "planning failed");
    }
    return R->rc = rc;
}

static int consume(void *ctx, size_t i, int prc)
{
    (void)prc;
    prun *r = ctx;
    const lam_plan_layers_job *j = r->j;
    const lam_sink *sink = r->sink;
    slot *R = &r->res[i % r->window];
    r->consumed++;
    int rc = j->stop ? j->stop(j->ctx, i) : LAM_OK;
    if (rc) return rc;
    lam_layer_info li = info(j->layers[i]);
    if (sink->layer && (rc = sink->layer(sink->ctx, &li))) return rc;
    lam_ladrp_stats ls = R->ls;
    lam_scan_time t = R->t;
    if (j->o->kind == LAM_PLAN_LADRP && (memcmp(R->entry, r->pos, sizeof r->pos) || R->entry_laser != r->laser)) {
        /* the worker started from a guess that was wrong: plan it here */
        rc = plan_one(j, i, sink, r->pos, &r->laser, NULL, &ls, &t, r->err);
    } else {
        /* what the layer sent, and its error if planning it failed */
        rc = lam_record_replay(&R->ops, sink);
        if (!rc && R->rc) {
            memcpy(r->err, &R->err, sizeof *r->err);
            rc = R->rc;
        }
        if (!rc) {
            memcpy(r->pos, R->exit, sizeof r->pos);
            r->laser = R->exit_laser;
        }
    }
    if (!rc && j->planned) j->planned(j->ctx, i, &ls, &t);
    if (!rc && sink->layer_end) rc = sink->layer_end(sink->ctx, &li);
    return rc;
}

int lam_plan_layers(const lam_plan_layers_job *j, const lam_sink *sink, lam_error *err)
{
    size_t threads = j->o->threads > LAM_MAX_THREADS ? LAM_MAX_THREADS : j->o->threads;
    if (threads > j->n) threads = j->n;
    if (threads <= 1) return serial(j, sink, err);
    prun r;
    memset(&r, 0, sizeof r);
    r.j = j;
    r.sink = sink;
    r.err = err;
    memcpy(r.pos, j->origin, sizeof r.pos);
    r.laser = -1;
    /* runs of consecutive layers: a LADRP worker going on from its layer
     * before knows where the stage stands */
    size_t most = j->o->kind == LAM_PLAN_LADRP ? 16 : 4;
    size_t chunk = j->n / (4 * threads);
    chunk = chunk < 1 ? 1 : chunk > most ? most : chunk;
    size_t window = chunk * (threads + 1);
    if (window < 4 * threads) window = 4 * threads;
    r.window = window = lam_pool_window(chunk, 0, window);
    r.res = calloc(window, sizeof *r.res);
    r.ws = calloc(threads, sizeof *r.ws);
    int rc = r.res && r.ws ? LAM_OK : lam_error_nomem(err, "starting threads");
    for (size_t k = 0; r.ws && k < threads; k++) lam_sls_state_init(&r.ws[k].st);
    if (!rc) rc = lam_pool_ordered((unsigned)threads, j->n, chunk, 0, window, produce, consume, &r, err);
    for (size_t k = 0; r.ws && k < threads; k++) lam_sls_state_free(&r.ws[k].st);
    for (size_t t = 0; r.res && t < window; t++) lam_record_free(&r.res[t].ops);
    free(r.res);
    free(r.ws);
    if (rc == LAM_ENOMEM && !r.consumed) {
        /* no threads to be had: the sink has seen nothing yet */
        lam_error_clear(err);
        return serial(j, sink, err);
    }
    return rc;
}
