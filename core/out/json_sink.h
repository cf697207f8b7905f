/* The layer interchange format (SPEC 4.6, the thesis's proposed L-SIF): a
 * planning run as JSON, `lamina slice --json FILE`. The schema ships as
 * schema/lamina-run-1.schema.json and docs/json.md describes it; in short:
 *
 *   {"format": "lamina-run", "version": 1,
 *    "job": {model, machine, process, units, frame, axis, plane, bbox, layers, bead,
 *            exposure (SLS: [{style, region, power, speed, distance}, ...])},
 *    "layers": [{index (1-based), z, floor, ceiling, width,
 *                contours: [{id, solid, depth, parent, area, points}],
 *                vectors: [{kind, from, to, order}],
 *                stats: {area, vectors, deposit_length, travel_length, time}}, ...],
 *    "totals": {layers, contours, vectors, deposit_length, travel_length, time}}
 *
 * Contours are the layer's section as sliced (before beam compensation and
 * contour passes: the part's geometry), ids 1..n in the layer's order,
 * `parent` the id of the contour directly around (null for none), `area`
 * signed in the layer plane (+ solid, - hole), points in the output frame
 * without a repeated closing point. Vectors are what the planner planned,
 * in order: LADRP moves (deposit, travel from the stage's position), SLS
 * contour passes (kind "contour", one vector per edge), hatch vectors
 * (core, upskin, downskin) and the scanner's jumps between them (non-zero
 * ones). `time` is the build-time estimate (hatch.h) of SLS plans that
 * have one, else null.
 *
 * Streaming: every layer is written as it is planned (its contours when it
 * begins, each vector as it comes, its figures when it ends); nothing of
 * earlier layers is kept, so memory does not grow with the run. Numbers
 * are written shortest round-trip (lam_dialect_number), never NaN or
 * infinite (a non-finite value is an error). One contour or vector a line,
 * so a position in the file names it. */
#ifndef LAM_JSON_SINK_H
#define LAM_JSON_SINK_H

#include "error.h"
#include "plan.h"
#include "vstream.h"
#include "writer.h"

/* The version written, and the only one read back: it changes when a
 * change would break a reader of the previous one (a key renamed, removed
 * or given another meaning); keys added keep it. */
#define LAM_JSON_VERSION 1

/* The run's JSON as a consumer of the plan's vector stream (vstream.h;
 * views.h puts it in the stream with the run's other views): written to w
 * and, when script is not NULL, the same text with every '<' as \u003c to
 * script, for JSON inside an HTML <script> element (no "</script>" can end
 * it early: in JSON text '<' is only ever a string's character), so
 * `--json` and `--html` share one text made once. Either writer may be
 * NULL; neither is owned or committed: the caller may write a document
 * around it (before begin, after end) and commits or aborts them. The
 * job's model path is written as given in lam_job_info.model. Errors go to
 * err (LAM_EIO from a writer, LAM_EINVAL for a non-finite number,
 * LAM_ENOMEM), which must outlive the consumer. */
int lam_json_consumer(lam_writer *w, lam_writer *script, lam_vec_consumer *out, lam_error *err);

/* What of the run the JSON holds (all zero: everything, as lam_json_consumer;
 * docs/json.md, "Smaller runs"):
 *   vectors SUMMARY: no "vectors" key; after the contours "summary": one
 *     {kind, <the attributes as the vectors carry them>, count, length}
 *     per (kind, attributes) group of the layer's vectors, jumps included,
 *     in the order of each group's first vector; NONE: neither key.
 *   no_contours: no "contours" key (stats.area and totals.contours stay).
 *   first, last: only layers first..last (1-based, the JSON's index) are
 *     written; 0 for first: from the first, 0 for last: to the end. The
 *     job and the totals describe the whole run (every layer is counted).
 * SLS runs' job also has "exposure" (lam_job_info's exposures: style,
 * region, power, speed, distance), whatever the options. */
enum { LAM_JSON_VECTORS_ALL, LAM_JSON_VECTORS_SUMMARY, LAM_JSON_VECTORS_NONE };
typedef struct lam_json_opts {
    int vectors;             /* LAM_JSON_VECTORS_*: every vector, a summary per layer, or none */
    int no_contours;         /* 1: leave the layers' contours out */
    size_t first, last;      /* 1-based layers written, first..last; 0, 0: all */
} lam_json_opts;

/* lam_json_consumer writing what o asks for (NULL: everything; o is
 * copied). LAM_EUSAGE for a vectors value that is none of the three or
 * first > last (last not 0). */
int lam_json_consumer_opts(lam_writer *w, lam_writer *script, const lam_json_opts *o, lam_vec_consumer *out,
                           lam_error *err);

#endif
