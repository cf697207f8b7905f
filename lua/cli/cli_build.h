/* `lamina build` (cli_build.c) and its reports (cli_build_report.c): the
 * summary on standard error and the plate's layout drawing. */
#ifndef LAM_CLI_BUILD_H
#define LAM_CLI_BUILD_H

#include <stddef.h>

#include "build_run.h"
#include "hatch.h"
#include "profile.h"

int cmd_build(int argc, char **argv);

/* The summary of a planned plate on standard error: parts, layers, lasers,
 * vectors and lengths, the build time (the layers' busiest lasers plus
 * recoating; "unknown: NAME sets no speeds" when nothing can be timed),
 * each laser's time and the worst layer's balance, each part's time.
 * all: the layers' estimates summed; laser: each laser's summed. */
void cli_build_summary(const char *path, const lam_build_run *r, const lam_profile *p, const lam_scan_time *all,
                       const lam_scan_time *laser, double worst_balance, size_t worst_layer);

/* --layout FILE: the plate, the parts' footprints (convex hulls) and names,
 * the lasers' fields, as SVG (arrange.h's lam_layout_svg) through an atomic
 * writer. Returns an exit status (cli.h), the error printed. */
int cli_build_layout(const lam_build_run *r, const lam_profile *p, const char *path, lam_error *err);

#endif
