/* A sink that hands one plan to several sinks (a program and its JSON,
 * say), so that they are fed by one planning run. */
#ifndef LAM_TEE_H
#define LAM_TEE_H

#include <stddef.h>

#include "error.h"
#include "plan.h"

/* The largest number of sinks one tee feeds. */
#define LAM_TEE_MAX 8

/* A sink calling each of sinks[0..n) in turn, in that order, for every
 * operation (an operation a sink leaves NULL is skipped for it); the first
 * error stops the operation and is returned. `end` is called on every sink
 * even after one fails (each finishes what it buffered), returning the
 * first error. The tee copies the sink structs and owns them from then on:
 * its destroy destroys each. On failure (LAM_EUSAGE for n of 0 or more
 * than LAM_TEE_MAX, LAM_ENOMEM) nothing is taken: the caller still owns
 * the sinks. The tee forwards fork (plan.h) when it feeds one sink; a tee
 * of several cannot be forked (their layers are recorded and replayed). */
int lam_tee_sink(const lam_sink *sinks, size_t n, lam_sink *out, lam_error *err);

#endif
