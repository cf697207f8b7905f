/* The build-time summary line: see cli_estimate.h. */
#include "cli_estimate.h"

#include <stdio.h>

void cli_print_estimate(const char *path, const lam_scan_time *t)
{
    fprintf(stderr,
            "lamina: %s: %zu layers, %zu contour passes, %zu hatch vectors, %.6g exposed, %.6g jumped; "
            "estimated build time %.6g s (exposure %.6g s, jumps %.6g s, recoating %.6g s)\n",
            path, t->layers, t->contours, t->vectors, t->exposure_length, t->jump_length, lam_scan_time_total(t),
            t->exposure, t->jump, t->recoat);
}
