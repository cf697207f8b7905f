/* The build-time summary of a powder-bed job, as `lamina slice` and
 * `lamina join` print it (one module of its own: both commands use it). */
#ifndef LAM_CLI_ESTIMATE_H
#define LAM_CLI_ESTIMATE_H

#include "hatch.h"

/* The summary of estimate t (hatch.h's lam_scan_time) for the model or
 * part set `path`, on standard error. */
void cli_print_estimate(const char *path, const lam_scan_time *t);

#endif
