/* Command templates of a machine dialect, and the sink that writes a plan
 * through them.
 *
 * A template is literal text with fields: `{field}` or `{field:%.5f}`
 * (a printf-style conversion, restricted to one of d i f F e E g G with
 * optional flags "-+ 0#", width and precision up to 40; %s for text fields).
 * `{{` and `}}` stand for literal braces. Each command has a fixed set of
 * fields; naming any other is an error when the profile loads. A template
 * may span several lines; each emitted command ends with a newline. An
 * absent command emits nothing; an empty string emits an empty line.
 *
 * Fields by command:
 *   preamble, postamble   name process units layers dimension bead rate travel_rate
 *                         xmin ymin zmin xmax ymax zmax label id
 *   layer, layer_end      index number z width floor ceiling
 *   feed                  rate
 *   laser_on, laser_off   rate
 *   travel, deposit       dx dy dz x y z rate
 *   contour_begin, contour_end, polyline
 *                         index id dir kind depth n z points
 *                         power speed point_distance exposure_time
 *   hatches_begin, hatches_end, hatches
 *                         index id kind n z angle points
 *                         power speed point_distance exposure_time
 *   hatch                 x0 y0 z0 x1 y1 z1 i power speed
 *   loop_begin, loop_end  n z
 *   vertex                x y z i
 *   separator             (none: written between two contour blocks)
 * `dir` is 1 for solids (counter-clockwise) and 0 for holes; `kind` is the
 * text "solid" or "hole" (hatch commands: "core", "upskin" or "downskin");
 * `id` is a block's CLI label id (lam_attrs_id: 1 for the one model of a
 * job, a build's label otherwise) and `label` the part's name (the model
 * file's name without directory and extension, characters other than
 * letters, digits, `_`, `-` and `.` made `_`); a hatch block's `n`
 * counts its vectors and its `points` are x0,y0,x1,y1 per vector;
 * `power speed point_distance exposure_time` are the exposure of the
 * vector type (profile keys, sections contour:, upskin:, downskin:); `number` is index + 1; `points` expands to
 * x,y,x,y,... (layer-plane coordinates in the output frame, each number with
 * the field's format, default %.6f), repeating the first point when the
 * dialect says `close_polylines: true`; `n` counts the points written.
 *
 * Labels: a line of the preamble or postamble that uses {id} is written
 * once per label of the job (lam_job_info.labels; a job without a table
 * has one, id 1, its label), with {id} and {label} that label's id and
 * text: `$$LABEL/{id},{label}` lists a build plate's labels. Copies of the
 * template's last line are still one a line. Elsewhere {label} is the
 * job's label; a fixed `$$LABEL/1,{label}` names only that one (a build's
 * other ids are then missing from the header).
 *
 * Details fixed by the implementation (machines/README.md says the same):
 * - `index` is the layer's 0-based index in layer commands and the contour's
 *   0-based index within its layer in contour commands. `points` are the
 *   contour's uv (the layer plane; x,y when slicing along z), or the output
 *   x,y when a planner gives no uv. close_polylines also repeats the first
 *   point as a last `vertex` command.
 * - Default formats: integer fields (index number layers dimension n id dir
 *   depth i) as integers; other numbers as lam_dialect_number (shortest
 *   exact); text as is. %d/%i on a non-integer field rounds half away from
 *   zero. Exactly %.Nf (or %f) renders with lam_fmt_fixed.
 * - No negative zeros: under f/F a value that would print as "-0.000" prints
 *   as "0.000", as the thesis's SLS programs have it; -0.0 is positive
 *   under every conversion.
 * - Relative moves: the stage position after a written move is the previous
 *   position plus the dx dy dz as written (read back from the text), so
 *   rounding never accumulates; an axis without its relative field in the
 *   template is taken as reached. An absent travel/deposit command writes
 *   nothing and leaves the stage where it was.
 * - The sink copies the job's strings, its labels too, at begin. */
#ifndef LAM_DIALECT_H
#define LAM_DIALECT_H

#include <stddef.h>

#include "dialect_template.h"
#include "error.h"
#include "plan.h"
#include "writer.h"

/* A sink that writes through the dialect's templates to w (not owned;
 * the caller commits or aborts it). Relative moves (dx dy dz) are measured
 * from the stage position, which starts at job->origin. The `rate` field of
 * travel/deposit/laser commands is the job's travel_rate or rate. Errors go
 * to err, which must outlive the sink. */
int lam_dialect_sink(const lam_dialect *d, lam_writer *w, lam_sink *out, lam_error *err);

/* Layer text formatted by worker threads (issue 15): the sink's fork
 * member (plan.h) makes a worker's sink that formats a whole layer (layer,
 * its operations, layer_end) into its own buffer, and the writer thread
 * appends the buffers in layer order through the fork's put; the bytes are
 * those the sink writes on one thread. A dialect that writes relative
 * moves (dx dy dz) does not fork when the planner sends moves: each move's
 * text hangs on the rounding of every move before. */
typedef lam_layer_text lam_dialect_text; /* plan.h */

/* Free a layer's text (the buffer a fork's take filled). */
void lam_dialect_text_free(lam_dialect_text *t);

#endif
