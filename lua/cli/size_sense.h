/* Warnings before a run whose size is far beyond the part's scale: a slip
 * of the layer width or of the model's unit shows as millions of layers or
 * a part kilometres across, and it is cheaper to say so before the run than
 * after a gigabyte. Warnings only, never errors (--max-layers and
 * --max-output are the limits), printed also with -q:
 * - more than CLI_SENSE_LAYERS (100,000) layers: a 100 mm part in layers of
 *   1 µm, thinner than any layered process makes;
 * - with a machine profile (-m) whose `units` lamina knows
 *   (lam_profile_unit_mm): a model whose largest extent is more than
 *   2000 mm (larger than the build volume of any machine the profiles
 *   describe: drawn in µm, or in mm for a profile in cm or m) or less than
 *   0.5 mm (drawn in m or in inches for a profile in mm), with the option
 *   that fixes it on the same line: the --units (m, cm, in, mm or um) that
 *   brings the model nearest 100 mm within those bounds ("If it was drawn
 *   in metres, --units m makes it 150 mm"), else a --scale by a power of
 *   ten ("--scale 1e+06 makes it 100 mm"). The built-in
 *   profile stands for no machine, so its mm are no unit to check;
 * - a program estimated (lam_plan_estimate) at more than 1 GB, and within
 *   --max-output (past it the run is refused with the estimate). */
#ifndef LAM_CLI_SIZE_SENSE_H
#define LAM_CLI_SIZE_SENSE_H

#include "model.h"
#include "planner.h"
#include "profile.h"
#include "slice.h"
#include "xform.h"

#define CLI_SENSE_LAYERS 100000
#define CLI_SENSE_MAX_MM 2000.0
#define CLI_SENSE_MIN_MM 0.5
#define CLI_SENSE_AIM_MM 100.0
#define CLI_SENSE_BYTES (1024.0 * 1024 * 1024)

/* The mm one model unit was taken as when the model was loaded: --units'
 * (lam_unit_mm), or 0 when the model was taken in the machine's units.
 * cli_load_model says it, so the unit the warning suggests replaces the
 * one given (a command loads one model). */
void cli_size_sense_loaded(double unit_mm);

/* Warn on standard error about the run of slicer s over model m (file
 * path). machine: the profile of -m, or NULL for the built-in one; po: the
 * planning options to estimate the program with, or NULL (no program).
 * Returns the number of warnings printed. */
int cli_size_sense(const char *path, const lam_profile *machine, const lam_model *m, const lam_slicer *s,
                   const lam_plan_opts *po);

/* The run's other outputs held to the program's limit (--max-output, in
 * po->max_output) before planning: --json FILE and --html FILE (either
 * NULL: not asked for) estimated like the program, by their own sinks'
 * costs (lam_out_costs_measure), each refused past the limit with LAM_ELIMIT
 * and the estimate in err ("--json run.json would write about ..."). The
 * SVG sheet draws at most LAM_SVG_MAX_PANELS layers and is held to the
 * limit as it is written. */
int cli_check_outputs(const char *json, const char *html, const lam_slicer *s, const lam_model *m,
                      const lam_plan_opts *po, lam_error *err);

#endif
