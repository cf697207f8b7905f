/* The part-file side of `lamina slice --layers` (cli_join.c). */
#ifndef LAM_CLI_JOIN_H
#define LAM_CLI_JOIN_H

#include "cli_args.h"
#include "slice.h"
#include "writer.h"

/* For a run with --layers: check the range against the slicer's layer
 * count (usage errors for A:B past the end, K/N with more parts than
 * layers, --svg, --json, no -o), make sink a part-file sink writing to w
 * (the run's identity from the model, profile and layers) and set po's
 * layer range. Returns EXIT_OK or the exit status after printing why. */
int cli_part_setup(args *a, const lam_profile *prof, const lam_slicer *s, lam_plan_opts *po, lam_writer *w,
                   lam_sink *sink);

/* The layers first .. last (1-based) that --layers asks of a run of n
 * layers, with its usage errors (cmd names the command). Returns EXIT_OK
 * or the exit status after printing why. */
int cli_part_range(const char *cmd, const args *a, size_t n, size_t *first, size_t *last);

/* The resolved profile's text as a part file holds it (lam_profile_dump):
 * *text malloc'd. LAM_ENOMEM. */
int cli_part_profile(const lam_profile *prof, char **text, size_t *len, lam_error *err);

#endif
