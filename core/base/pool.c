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

/* ---- teams -------------------------------------------------------------- */

typedef struct team_worker {
    lam_team *t;
    unsigned id;
} team_worker;

struct lam_team {
    pthread_mutex_t mu;
    pthread_cond_t go;       /* workers: a new loop, or quit */
    pthread_cond_t done;     /* the caller: the loop's last task returned */
    unsigned size;           /* started threads + the caller */
    unsigned long gen;       /* loops started so far */
    int quit;
    lam_team_fn fn;
    void *ctx;
    size_t n, next, finished;
    pthread_t *tid;
    team_worker *ws;
};

/* Claim and run the current loop's tasks until none is left (mutex held
 * on entry and on return). */
static void team_tasks(lam_team *t, unsigned id)
{
    while (t->next < t->n) {
        size_t task = t->next++;
        pthread_mutex_unlock(&t->mu);
        t->fn(t->ctx, id, task);
        pthread_mutex_lock(&t->mu);
        if (++t->finished == t->n) pthread_cond_signal(&t->done);
    }
}

static void *team_work(void *arg)
{
    team_worker *w = arg;
    lam_team *t = w->t;
    unsigned long seen = 0;
    pthread_mutex_lock(&t->mu);
    for (;;) {
        while (!t->quit && t->gen == seen) pthread_cond_wait(&t->go, &t->mu);
        if (t->quit) break;
        seen = t->gen;
        team_tasks(t, w->id);
    }
    pthread_mutex_unlock(&t->mu);
    return NULL;
}

int lam_team_new(unsigned threads, lam_team **out, lam_error *err)
{
    *out = NULL;
    if (threads < 2) threads = 2;
    lam_team *t = calloc(1, sizeof *t);
    pthread_t *tid = calloc(threads - 1, sizeof *tid);
    team_worker *ws = calloc(threads - 1, sizeof *ws);
    if (!t || !tid || !ws) {
        free(t);
        free(tid);
        free(ws);
        return lam_error_nomem(err, "starting threads");
    }
    t->tid = tid;
    t->ws = ws;
    pthread_mutex_init(&t->mu, NULL);
    pthread_cond_init(&t->go, NULL);
    pthread_cond_init(&t->done, NULL);
    unsigned started = 0;
    int why = 0;
    for (; started < threads - 1; started++) {
        ws[started] = (team_worker){ t, started + 1 };
        if ((why = pthread_create(&tid[started], NULL, team_work, &ws[started]))) break;
    }
    t->size = started + 1;
    if (!started) {
        lam_team_free(t);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "could not start a thread (%s)", strerror(why));
    }
    *out = t;
    return LAM_OK;
}

unsigned lam_team_size(const lam_team *t) { return t ? t->size : 1; }

void lam_team_for(lam_team *t, size_t n, lam_team_fn fn, void *ctx)
{
    if (!t) {
        for (size_t i = 0; i < n; i++) fn(ctx, 0, i);
        return;
    }
    if (!n) return;
    pthread_mutex_lock(&t->mu);
    t->fn = fn;
    t->ctx = ctx;
    t->n = n;
    t->next = t->finished = 0;
    t->gen++;
    pthread_cond_broadcast(&t->go);
    team_tasks(t, 0);
    while (t->finished < t->n) pthread_cond_wait(&t->done, &t->mu);
    pthread_mutex_unlock(&t->mu);
}

void lam_team_free(lam_team *t)
{
    if (!t) return;
    pthread_mutex_lock(&t->mu);
    t->quit = 1;
    pthread_cond_broadcast(&t->go);
    pthread_mutex_unlock(&t->mu);
    for (unsigned k = 0; k + 1 < t->size; k++) pthread_join(t->tid[k], NULL);
    pthread_cond_destroy(&t->done);
    pthread_cond_destroy(&t->go);
    pthread_mutex_destroy(&t->mu);
    free(t->tid);
    free(t->ws);
    free(t);
}
