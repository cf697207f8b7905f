/* Worker threads for work that must come out in order: tasks 0 .. n-1 are
 * produced on worker threads, any number at once, and consumed on the
 * calling thread strictly in task order, so what a run writes does not
 * depend on how many threads made it (issue 15).
 *
 * Workers claim runs of `chunk` consecutive tasks (a worker that keeps a
 * sweep's state goes on from where it stopped) and never start a task more
 * than `window` tasks ahead of the one being consumed: memory stays
 * bounded by window results, however long the run. Waiting is on a
 * condition variable, never a busy loop. POSIX threads.
 *
 * Teams (lam_team_*, below) are the other shape: threads started once for
 * a series of parallel loops whose tasks write disjoint parts of shared
 * arrays (the binary STL reader's passes). */
#ifndef LAM_POOL_H
#define LAM_POOL_H

#include <stddef.h>

#include "error.h"

/* Produce task `task` on worker number `worker` (0 .. threads-1; a worker
 * runs its tasks one at a time, in increasing order). Its result lives in
 * the caller's ctx until consumed. The return value is handed to consume
 * with the task, it does not stop the run: the consumer decides, in task
 * order, what a failure means. */
typedef int (*lam_produce_fn)(void *ctx, unsigned worker, size_t task);

/* Consume task `task` (produce returned `rc` for it) on the calling
 * thread, in order 0, 1, 2, ... A non-zero return stops the run: no task
 * after it is consumed, workers start nothing new, and lam_pool_ordered
 * returns that value once every worker has finished. */
typedef int (*lam_consume_fn)(void *ctx, size_t task, int rc);

/* The number of threads a run uses by default: LAMINA_THREADS when it is
 * set to a whole number >= 1, else the online processors (at least 1, at
 * most LAM_MAX_THREADS). *bad is set (when not NULL) when LAMINA_THREADS
 * is set but not a number in range. */
#define LAM_MAX_THREADS 256
unsigned lam_default_threads(int *bad);

/* The online processors: at least 1, at most LAM_MAX_THREADS. */
unsigned lam_online_cores(void);

/* Run tasks 0 .. n-1 with `threads` workers (>= 1; the calling thread only
 * consumes). Task t is consumed once tasks t .. t+ahead (those that exist)
 * are produced, so the consumer may look at the results of the `ahead`
 * tasks after it. window (raised to at least chunk and ahead + 1) bounds
 * the tasks produced and not yet consumed: a task's result may be kept in
 * slot t % window of the caller's. Returns 0 when all were consumed,
 * consume's non-zero value, or LAM_ENOMEM (message in err) when no thread
 * could be started — then nothing was produced or consumed. */
int lam_pool_ordered(unsigned threads, size_t n, size_t chunk, size_t ahead, size_t window, lam_produce_fn produce,
                     lam_consume_fn consume, void *ctx, lam_error *err);

/* The window lam_pool_ordered will use for these values. */
size_t lam_pool_window(size_t chunk, size_t ahead, size_t window);

/* A team: threads started once and kept waiting (on a condition variable)
 * for parallel loops, for work made of several short passes in a row (the
 * binary STL reader's), where starting threads per pass would cost more
 * than the pass. */
typedef struct lam_team lam_team;

/* Run task `task` of a loop on worker `worker` (0 .. lam_team_size - 1;
 * worker 0 is the calling thread). Tasks of one loop run in any order and
 * at the same time: each must write only what is its own. */
typedef void (*lam_team_fn)(void *ctx, unsigned worker, size_t task);

/* A team of `threads` (>= 2): threads - 1 are started, the caller is the
 * other. *out is NULL (and LAM_ENOMEM returned, message in err) when no
 * thread could be started; fewer started than asked makes a smaller team. */
int lam_team_new(unsigned threads, lam_team **out, lam_error *err);

/* The team's threads, the caller included (1 for a NULL team). */
unsigned lam_team_size(const lam_team *t);

/* Run fn(ctx, worker, task) for tasks 0 .. n-1 on the team's threads and
 * return once every task has returned (a parallel for: a barrier at the
 * end). A NULL team runs them in order on the calling thread. */
void lam_team_for(lam_team *t, size_t n, lam_team_fn fn, void *ctx);

/* Stop and join the team's threads and free it (NULL is fine). */
void lam_team_free(lam_team *t);

#endif
