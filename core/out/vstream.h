/* A plan as a stream of vectors: a lam_sink that turns the planner's
 * operations (plan.h) into straight vectors, one call each, for previews
 * and interchange (svg.h, html.h).
 *
 * Kinds (vocab.h's lam_vec_kind): deposit and travel (LADRP stage moves, from
 * the stage's last position; the first layer's first move starts at the
 * job's origin); contour (each edge of an SLS contour pass, the closing
 * edge last); core, upskin, downskin (SLS hatch vectors); jump (the SLS
 * scanner between paths: from the end of one path to the start of the
 * next, within a layer; the scanner starts each layer at its first path).
 * Every stage move is a vector, as in the program; jumps of no length are
 * left out (the scanner does not move), and so are contours of fewer than
 * two points. Orders count from 1 within each layer, in the order the
 * machine runs. The vectors are those of the layer interchange JSON
 * (json_sink.h), which decodes a plan by the same rules. Both frames'
 * coordinates are the planner's (plan.h): nothing is converted back. */
#ifndef LAM_VSTREAM_H
#define LAM_VSTREAM_H

#include "plan.h"
#include "slice.h"

typedef struct lam_vec {
    int kind;                /* lam_vec_kind (vocab.h) */
    lam_attrs attrs;         /* the operation's (vocab.h); a jump: the next path's */
    double from[3], to[3];   /* output frame */
    double fuv[2], tuv[2];   /* the same in the layer frame */
    size_t order;            /* 1-based within the layer */
    int exposed;             /* 1 laser on / deposit, 0 travel or jump */
    double length;           /* |to - from|, as the layer's stats add it */
} lam_vec;

/* A layer's figures, given at its end. */
typedef struct lam_vec_stats {
    size_t vectors;          /* all kinds */
    double deposit_length;   /* exposed vectors (deposits, contours, hatches) */
    double travel_length;    /* travels and jumps */
} lam_vec_stats;

/* What a consumer of the stream implements; any may be NULL. Each returns
 * LAM_OK or an error code (the consumer fills the lam_error it was given). */
typedef struct lam_vec_consumer {
    void *ctx;
    int (*begin)(void *ctx, const lam_job_info *job);
    int (*layer)(void *ctx, const lam_layer_info *layer);
    int (*vector)(void *ctx, const lam_vec *v);
    int (*layer_end)(void *ctx, const lam_layer_info *layer, const lam_vec_stats *st);
    int (*end)(void *ctx);
    void (*destroy)(void *ctx);     /* with the sink's destroy */
    /* an SLS contour pass begins (before its edges, even one of fewer than
     * two points), order: its first edge's */
    int (*path)(void *ctx, const lam_contour_info *c, size_t order);
} lam_vec_consumer;

/* The most consumers one stream feeds. */
#define LAM_VSTREAM_MAX 8

/* Make *out a sink that decodes the plan once and feeds c[0..n), each
 * call to each consumer in that order (the first error stops the call;
 * end is given to every consumer, returning the first error). The sink
 * owns the consumers from then on: its destroy frees what it holds and
 * calls each one's destroy; on failure they are destroyed at once. Errors:
 * LAM_ENOMEM, LAM_EUSAGE (n of 0 or more than LAM_VSTREAM_MAX). */
int lam_vstream_sink(const lam_vec_consumer *c, size_t n, lam_sink *out, lam_error *err);

#endif
