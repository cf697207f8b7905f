/* A recording lam_sink: keeps the operations a planner hands it (feed,
 * laser, move, contour, hatches) with copies of their points, to be
 * replayed later, unchanged and in the same order, onto another sink. This
 * is how worker threads plan layers while the one real sink (a text
 * dialect, a plugin writer, ...) still sees every layer in order: what it
 * writes is the same, byte for byte, whatever the number of threads. */
#ifndef LAM_PLAN_RECORD_H
#define LAM_PLAN_RECORD_H

#include <stddef.h>

#include "plan.h"

typedef struct lam_record {
    unsigned char *buf;      /* the operations, 8-byte aligned entries */
    size_t len, cap;
    int failed;              /* out of memory while recording */
} lam_record;

/* A sink recording into r (not owned; r starts empty or cleared). It has
 * exactly the callbacks `like` has among feed, laser, move, contour and
 * hatches, so a planner decides what to compute as it would for `like`;
 * begin, layer, layer_end and end are NULL (the caller sends them). A
 * callback returns LAM_ENOMEM when memory runs out. */
lam_sink lam_record_sink(lam_record *r, const lam_sink *like);

/* Forget the operations, keeping the memory for the next layer. */
void lam_record_clear(lam_record *r);

/* Send r's operations to sink in the order they came. Returns the first
 * error a callback returns. */
int lam_record_replay(const lam_record *r, const lam_sink *sink);

/* Release r's memory. */
void lam_record_free(lam_record *r);

#endif
