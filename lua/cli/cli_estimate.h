/* The build-time summary of a job, as `lamina slice` and `lamina join`
 * print it (one module of its own: both commands use it, and join must
 * print what the whole run prints). Lengths and times for people
 * (fmt.h's lam_fmt_length, lam_fmt_duration): lengths in the metric unit
 * that reads best when the profile's `units` is one lamina knows, else
 * in the profile's unit. */
#ifndef LAM_CLI_ESTIMATE_H
#define LAM_CLI_ESTIMATE_H

#include "hatch.h"
#include "plan.h"
#include "planner.h"

/* The summary of powder-bed estimate t (hatch.h's lam_scan_time) for the
 * model or part set `path` on standard error, po the job's options (its
 * name, units and scan settings):
 *   lamina: part.stl: 67 layers, 134 contour passes, 1574 hatch vectors,
 *   2.93 m exposed, 335 mm jumped; estimated build time 9 min 1 s
 *   (exposure 3.8 s, jumps 0.9 s, recoating 8 min 56 s)
 * (one line). When no vector type has a scan speed or a point exposure
 * time the exposure cannot be timed, and the line ends "estimated build
 * time unknown: NAME sets no speeds". */
/* Whether some vector type of cfg can be timed: a speed or a point
 * exposure time (else the estimate is "unknown: NAME sets no speeds"). */
int cli_scan_timed(const lam_scan_cfg *cfg);

void cli_print_estimate(const char *path, const lam_plan_opts *po, const lam_scan_time *t);

/* The summary of a LADRP (DED) job of `layers` layers whose moves st
 * counts (planner.h's lam_ladrp_stats: lengths in the layer plane):
 *   lamina: part.stl: 40 layers, 2.93 m deposited, 335 mm travelled;
 *   estimated build time 5 min 0 s (depositing 4 min 53 s, travel 6.7 s)
 * po->rate (`feed_rate`) and po->travel_rate (`travel_rate`) are taken
 * as model units per minute, as G-code's F word is (machines/ded-gcode.yaml
 * writes them as F): time = length / rate x 60 s. A rate of 0 that a
 * length needs makes it "estimated build time unknown: NAME sets no feed
 * rate" (or "no travel rate"). */
void cli_print_ladrp_estimate(const char *path, const lam_plan_opts *po, size_t layers, const lam_ladrp_stats *st);

/* What `lamina join` measures of a LADRP run's replayed moves, the same
 * figures the planner counts for the whole run (lam_ladrp_stats' lengths,
 * each move from where the stage was: the first from the job's origin),
 * up to the last bits of the sums. */
typedef struct cli_ladrp_meter {
    lam_ladrp_stats st;
    double uv[2];            /* the stage, in the layer plane */
} cli_ladrp_meter;

/* A sink (no output; begin and move only) that measures into m, which
 * it zeroes; m must outlive the sink. Nothing to release. */
void cli_ladrp_meter_sink(cli_ladrp_meter *m, lam_sink *out);

#endif
