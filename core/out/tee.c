/* One plan to several sinks; see tee.h. */
#include "tee.h"

#include <stdlib.h>
#include <string.h>

typedef struct tee {
    lam_sink s[LAM_TEE_MAX];
    size_t n;
} tee;

/* Each sink's operation `op` with the arguments after it, until one fails. */
#define EACH(t, op, ...)                                                                   \
    do {                                                                                   \
        for (size_t i_ = 0; i_ < (t)->n; i_++)                                             \
            if ((t)->s[i_].op) {                                                           \
                int rc_ = (t)->s[i_].op((t)->s[i_].ctx, __VA_ARGS__);                      \
                if (rc_) return rc_;                                                       \
            }                                                                              \
        return LAM_OK;                                                                     \
    } while (0)

static int t_begin(void *ctx, const lam_job_info *job) { EACH((tee *)ctx, begin, job); }
static int t_layer(void *ctx, const lam_layer_info *l) { EACH((tee *)ctx, layer, l); }
static int t_layer_end(void *ctx, const lam_layer_info *l) { EACH((tee *)ctx, layer_end, l); }
static int t_feed(void *ctx, double rate) { EACH((tee *)ctx, feed, rate); }
static int t_laser(void *ctx, int on) { EACH((tee *)ctx, laser, on); }
static int t_move(void *ctx, const lam_move_info *m) { EACH((tee *)ctx, move, m); }
static int t_contour(void *ctx, const lam_contour_info *c) { EACH((tee *)ctx, contour, c); }
static int t_hatches(void *ctx, const lam_hatch_info *h) { EACH((tee *)ctx, hatches, h); }

static int t_end(void *ctx)
{
    tee *t = ctx;
    int first = LAM_OK;
    for (size_t i = 0; i < t->n; i++)
        if (t->s[i].end) {
            int rc = t->s[i].end(t->s[i].ctx);
            if (rc && !first) first = rc;
        }
    return first;
}

/* One sink: its own fork (the bytes a worker formats are all a tee of one
 * writes). Of several, none: their layers are recorded and replayed. */
static int t_fork(void *ctx, int moves, lam_sink_fork *out, lam_error *err)
{
    tee *t = ctx;
    return t->s[0].fork(t->s[0].ctx, moves, out, err);
}

static void t_destroy(void *ctx)
{
    tee *t = ctx;
    for (size_t i = 0; i < t->n; i++)
        if (t->s[i].destroy) t->s[i].destroy(t->s[i].ctx);
    free(t);
}

int lam_tee_sink(const lam_sink *sinks, size_t n, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (n == 0 || n > LAM_TEE_MAX)
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "a tee feeds 1 to %d sinks, not %zu", LAM_TEE_MAX, n);
    tee *t = calloc(1, sizeof *t);
    if (!t) return lam_error_nomem(err, "joining sinks");
    memcpy(t->s, sinks, n * sizeof *sinks);
    t->n = n;
    int hatches = 0;
    for (size_t i = 0; i < n; i++) hatches |= sinks[i].hatches != NULL;
    *out = (lam_sink){ .ctx = t, .begin = t_begin, .layer = t_layer, .layer_end = t_layer_end, .feed = t_feed,
                       .laser = t_laser, .move = t_move, .contour = t_contour, .end = t_end, .destroy = t_destroy,
                       .hatches = hatches ? t_hatches : NULL, /* NULL: no sink wants them */
                       .fork = n == 1 && sinks[0].fork ? t_fork : NULL };
    return LAM_OK;
}
