/* Ordered work on POSIX threads; see pool.h. */
#include "pool.h"

#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct slot {
    int done, rc;
} slot;

typedef struct pool {
    pthread_mutex_t mu;
    pthread_cond_t work;     /* workers: room in the window, or stop */
    pthread_cond_t ready;    /* the consumer: a task finished */
    size_t n, chunk, window;
    size_t next;             /* first task no worker has claimed */
    size_t consumed;         /* tasks consumed so far */
    int stop;
    slot *ring;              /* task t's state at t % window */
    lam_produce_fn produce;
    void *ctx;
} pool;

typedef struct worker {
    pool *p;
    unsigned id;
} worker;

static void *work(void *arg)
{
    worker *w = arg;
    pool *p = w->p;
    pthread_mutex_lock(&p->mu);
    for (;;) {
        while (!p->stop && p->next < p->n && p->next >= p->consumed + p->window) pthread_cond_wait(&p->work, &p->mu);
        if (p->stop || p->next >= p->n) break;
        size_t t = p->next, end = p->n - t > p->chunk ? t + p->chunk : p->n;
        p->next = end;
        for (; t < end; t++) {
            while (!p->stop && t >= p->consumed + p->window) pthread_cond_wait(&p->work, &p->mu);
            if (p->stop) break;
            pthread_mutex_unlock(&p->mu);
            int rc = p->produce(p->ctx, w->id, t);
            pthread_mutex_lock(&p->mu);
            p->ring[t % p->window].rc = rc;
            p->ring[t % p->window].done = 1;
            pthread_cond_signal(&p->ready);
        }
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

unsigned lam_default_threads(int *bad)
{
    if (bad) *bad = 0;
    const char *env = getenv("LAMINA_THREADS");
    if (env && *env) {
        char *end;
        errno = 0;
        long v = strtol(env, &end, 10);
        if (!*end && !errno && v >= 1 && v <= LAM_MAX_THREADS) return (unsigned)v;
        if (bad) *bad = 1;
    }
    return lam_online_cores();
}

unsigned lam_online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > LAM_MAX_THREADS ? LAM_MAX_THREADS : (unsigned)n;
}

size_t lam_pool_window(size_t chunk, size_t ahead, size_t window)
{
    if (chunk < 1) chunk = 1;
    if (window < chunk) window = chunk;
    return window <= ahead ? ahead + 1 : window;
}

int lam_pool_ordered(unsigned threads, size_t n, size_t chunk, size_t ahead, size_t window, lam_produce_fn produce,
                     lam_consume_fn consume, void *ctx, lam_error *err)
{
    if (!n) return 0;
    if (chunk < 1) chunk = 1;
    window = lam_pool_window(chunk, ahead, window);
    if (threads < 1) threads = 1;
    pool p;
    memset(&p, 0, sizeof p);
    p.n = n;
    p.chunk = chunk;
    p.window = window;
    p.produce = produce;
    p.ctx = ctx;
    p.ring = calloc(window, sizeof *p.ring);
    pthread_t *tid = calloc(threads, sizeof *tid);
    worker *ws = calloc(threads, sizeof *ws);
    if (!p.ring || !tid || !ws) {
        free(p.ring);
        free(tid);
        free(ws);
        return lam_error_nomem(err, "starting threads");
    }
    pthread_mutex_init(&p.mu, NULL);
    pthread_cond_init(&p.work, NULL);
    pthread_cond_init(&p.ready, NULL);
    unsigned started = 0;
    int why = 0;
    for (; started < threads; started++) {
        ws[started] = (worker){ &p, started };
        if ((why = pthread_create(&tid[started], NULL, work, &ws[started]))) break;
    }
    /* fewer threads than asked still make the same output */
    int rc = 0;
    if (!started) {
        rc = lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "could not start a thread (%s)", strerror(why));
    } else {
        for (size_t t = 0; t < n && !rc; t++) {
            pthread_mutex_lock(&p.mu);
            for (size_t k = t; k <= t + ahead && k < n; k++)
                while (!p.ring[k % window].done) pthread_cond_wait(&p.ready, &p.mu);
            int prc = p.ring[t % window].rc;
            p.ring[t % window].done = 0;
            pthread_mutex_unlock(&p.mu);
            rc = consume(ctx, t, prc);
            pthread_mutex_lock(&p.mu);
            p.consumed = t + 1;
            if (rc) p.stop = 1;
            pthread_cond_broadcast(&p.work);
            pthread_mutex_unlock(&p.mu);
        }
    }
    pthread_mutex_lock(&p.mu);
    p.stop = 1;
    pthread_cond_broadcast(&p.work);
    pthread_mutex_unlock(&p.mu);
    for (unsigned k = 0; k < started; k++) pthread_join(tid[k], NULL);
    pthread_cond_destroy(&p.ready);
    pthread_cond_destroy(&p.work);
    pthread_mutex_destroy(&p.mu);
    free(p.ring);
    free(tid);
    free(ws);
    return rc;
}
