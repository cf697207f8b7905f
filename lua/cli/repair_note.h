/* What repair on load did, said the same way by every command that loads
 * a model (slice, validate, check, info, repair). */
#ifndef LAM_CLI_REPAIR_NOTE_H
#define LAM_CLI_REPAIR_NOTE_H

#include <stdio.h>

#include "model.h"

/* On stderr: "lamina: PATH: repaired: filled 2 holes (40 boundary edges),
 * ..." when repair changed the model (not when quiet), and a warning,
 * whatever quiet says, when it is still open or non-manifold after. */
void cli_repair_note(const lam_model *m, int quiet);

/* The report as a JSON object ({"ran": false} with --no-repair). */
void cli_repair_json(FILE *o, const lam_repair_report *r);

#endif
