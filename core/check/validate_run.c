/* Layers checked on several threads, reported in order; see validate_run.h. */
#include "validate_run.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pool.h"

typedef struct slot {
    lam_vlayer l;
    lam_layer_check chk;
    int rc;
    lam_error err;
} slot;

typedef struct vrun {
    lam_rays **rays;         /* per worker: the caller's alone, or forks */
    slot *res;               /* task t's result at t % window */
    size_t window;
    lam_vlayer_fn make;
    lam_vreport_fn report;
    void *ctx;
    lam_error *err;
} vrun;

static void slot_clear(slot *S)
{
    lam_layer_check_free(&S->chk);
    lam_layer_free(S->l.owned);
    memset(&S->l, 0, sizeof S->l);
}

static int check(vrun *r, unsigned worker, size_t i, slot *S)
{
    memset(S, 0, sizeof *S);
    lam_error_clear(&S->err);
    lam_rays *v = r->rays[worker];
    int rc = r->make(r->ctx, worker, v, i, &S->l, &S->err);
    if (!rc) rc = lam_validate_layer(v, S->l.L, S->l.f, &S->l.o, &S->chk, &S->err);
    return S->rc = rc;
}

static int deliver(vrun *r, size_t i, slot *S)
{
    int rc = S->rc;
    if (rc) {
        if (r->err) *r->err = S->err;
    } else {
        rc = r->report(r->ctx, i, &S->l, &S->chk, r->err);
    }
    slot_clear(S);
    return rc;
}

static int produce(void *ctx, unsigned worker, size_t i)
{
    vrun *r = ctx;
    return check(r, worker, i, &r->res[i % r->window]);
}

static int consume(void *ctx, size_t i, int rc)
{
    (void)rc;
    vrun *r = ctx;
    return deliver(r, i, &r->res[i % r->window]);
}

int lam_validate_layers(lam_rays *v, size_t n, unsigned threads, const lam_frame *f, lam_vlayer_fn make,
                        lam_vreport_fn report, void *ctx, lam_error *err)
{
    if (!n) return LAM_OK;
    if (threads > LAM_MAX_THREADS) threads = LAM_MAX_THREADS;
    if (threads > n) threads = (unsigned)n;
    if (threads < 1) threads = 1;
    vrun r = { 0 };
    r.make = make;
    r.report = report;
    r.ctx = ctx;
    r.err = err;
    lam_rays *one[1] = { v };
    int rc = LAM_OK;
    if (threads == 1) {
        r.rays = one;
        slot S;
        for (size_t i = 0; i < n && !rc; i++) {
            check(&r, 0, i, &S);
            rc = deliver(&r, i, &S);
        }
        return rc;
    }
    lam_section_index *sec;
    if (f && (rc = lam_rays_section(v, f, &sec, err))) return rc;
    /* runs of consecutive layers keep a worker's sweep going; a window of a
     * run more than there are workers keeps them busy while the reports
     * catch up, and bounds the layers held */
    size_t chunk = n / (4 * (size_t)threads);
    chunk = chunk < 1 ? 1 : chunk > 8 ? 8 : chunk;
    size_t window = chunk * (threads + 1);
    if (window < 4 * (size_t)threads) window = 4 * (size_t)threads;
    r.window = window = lam_pool_window(chunk, 0, window);
    r.rays = calloc(threads, sizeof *r.rays);
    r.res = calloc(window, sizeof *r.res);
    if (!r.rays || !r.res) rc = lam_error_nomem(err, "starting threads");
    /* every worker a fork: v itself stays as it is (a worker replacing its
     * section index for another frame must not free what forks share) */
    for (unsigned k = 0; k < threads && !rc; k++) rc = lam_rays_fork(v, &r.rays[k], err);
    if (!rc) rc = lam_pool_ordered(threads, n, chunk, 0, window, produce, consume, &r, err);
    /* what was checked and not reported (the run stopped before it) */
    for (size_t t = 0; r.res && t < window; t++) slot_clear(&r.res[t]);
    for (unsigned k = 0; r.rays && k < threads; k++) lam_rays_free(r.rays[k]);
    free(r.rays);
    free(r.res);
    return rc;
}

/* ---- the layers of a slicer's run ------------------------------------------------ */

typedef struct sweep {
    lam_slicer **sc;         /* per worker: the caller's alone, or forks */
    size_t *next;            /* the layer each one's next lam_slicer_next returns (SIZE_MAX: unknown) */
    const lam_frame *f;
    lam_validate_opts o;
    lam_vreport_fn report;
    void *ctx;
} sweep;

static int slice_layer(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err)
{
    (void)v;
    sweep *x = ctx;
    lam_slicer *sc = x->sc[worker];
    if (x->next[worker] != i) lam_slicer_seek(sc, i);
    lam_layer *L = NULL;
    int rc = lam_slicer_next(sc, &L, err);
    if (rc || !L) {
        /* a sweep that failed half way starts afresh */
        x->next[worker] = SIZE_MAX;
        lam_slicer_seek(sc, 0);
        return rc ? rc : lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "layer %zu is past the run", i + 1);
    }
    x->next[worker] = i + 1;
    out->L = out->owned = L;
    out->f = x->f;
    out->o = x->o;
    return LAM_OK;
}

static int slice_report(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    sweep *x = ctx;
    return x->report(x->ctx, i, l, chk, err);
}

int lam_validate_slicer(lam_slicer *s, lam_rays *v, const lam_validate_opts *o, unsigned threads,
                        lam_vreport_fn report, void *ctx, lam_error *err)
{
    size_t n = lam_slicer_count(s);
    if (threads > LAM_MAX_THREADS) threads = LAM_MAX_THREADS;
    if (threads > n) threads = (unsigned)n;
    if (threads < 1) threads = 1;
    sweep x = { 0 };
    x.f = lam_slicer_frame(s);
    if (o) x.o = *o;
    else lam_validate_opts_init(&x.o);
    x.report = report;
    x.ctx = ctx;
    x.sc = calloc(threads, sizeof *x.sc);
    x.next = malloc(threads * sizeof *x.next);
    int rc = x.sc && x.next ? LAM_OK : lam_error_nomem(err, "starting threads");
    for (unsigned k = 0; k < threads && !rc; k++) {
        x.next[k] = SIZE_MAX;
        if (threads == 1) x.sc[k] = s;
        else rc = lam_slicer_fork(s, &x.sc[k], err);
    }
    if (!rc) rc = lam_validate_layers(v, n, threads, x.f, slice_layer, slice_report, &x, err);
    for (unsigned k = 0; x.sc && threads > 1 && k < threads; k++) lam_slicer_free(x.sc[k]);
    free(x.sc);
    free(x.next);
    return rc;
}
