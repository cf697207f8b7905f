/* The browser viewer of a planning run: one self-contained HTML file (no
 * network, no other file) with the run's layer interchange JSON (the agreed
 * shape, "lamina-run" version 1) embedded in a <script type=
 * "application/json" id="lamina-run"> element, and the viewer's page
 * (core/viewer.html, compiled in at build time) that draws it: a layer
 * slider, zoom and pan, toggles for contours, vectors and travel, and each
 * layer's figures. The page honours a URL hash `#layer=N` (1-based) and
 * `contours=0|1`, `vectors=0|1`, `travel=0|1`, and keeps it up to date.
 *
 * Streaming: a layer is written when it has been planned and then
 * forgotten; only the sections of the layers read but not yet planned are
 * held (lam_html_section), so memory does not grow with the run.
 *
 * Use: lam_html_new; lam_html_sink gives the sink a planning run feeds
 * (lam_plan_run; with a fan-out beside the program's sink); the run's
 * layer callback hands every layer to lam_html_section; after the run,
 * commit the writer. The JSON's "</" and "<!--" can never close the
 * element: '<' in strings is written \u003c, and numbers have none. */
#ifndef LAM_HTML_H
#define LAM_HTML_H

#include "hatch.h"
#include "plan.h"
#include "slice.h"
#include "writer.h"

typedef struct lam_html lam_html;

/* A viewer written to w (borrowed; the caller commits it after the run).
 * model: the model's path as the page names it (copied). f: the run's
 * layer frame (copied); frame_machine as in the plan options. Errors:
 * LAM_ENOMEM. */
int lam_html_new(lam_writer *w, const char *model, const lam_frame *f, int frame_machine, lam_html **out,
                 lam_error *err);

/* The estimates to write, both borrowed and read as the run goes:
 * layer_time (indexed by 0-based layer index, filled by the planner before
 * each layer ends) and the job's total (complete when the run ends). NULL:
 * "time" is null. */
void lam_html_times(lam_html *h, const double *layer_time, const lam_scan_time *total);

/* Keep layer L's sections (copied) until the layer is planned. Call it
 * with every layer, in order, before the layer's planning starts (the
 * lam_plan_run layer callback). Errors: LAM_ENOMEM. */
int lam_html_section(lam_html *h, const lam_layer *L, lam_error *err);

/* Make *out the sink that writes the page as the run goes. h is borrowed
 * (it must outlive the sink); errors of the sink's calls go to err, which
 * must outlive it too. */
int lam_html_sink(lam_html *h, lam_sink *out, lam_error *err);

void lam_html_free(lam_html *h);

#endif
