/* The browser viewer of a planning run: one self-contained HTML file (no
 * network, no other file): the viewer's page (core/out/viewer.html,
 * compiled in at build time) with the run's data, laid out as
 * docs/viewer.md says:
 *
 *   - a head (`lamina-head`: the format, the coordinate quantum, the run's
 *     extent in the layer plane, the names of kinds and attributes),
 *   - each layer's contours and vectors as a binary block (vblock.h) in
 *     base64, in its own element, written when the layer is planned, so
 *     the page draws the first layer long before a big page is read;
 *   - the run's JSON (json_sink.h) with its vectors summarised and its
 *     contours left out (they are in the blocks): every layer's figures,
 *     the job and the totals, written at the end.
 *
 * Memory: a layer's block while it is written, and the run's summary JSON
 * (a few hundred bytes a layer) until the end. The page's only text from
 * the run is JSON with '<' as \u003c and base64, so nothing in it can end
 * an element early; the script shows the run's strings as text only. */
#ifndef LAM_HTML_H
#define LAM_HTML_H

#include "plan.h"
#include "vstream.h"
#include "writer.h"

/* The page as one consumer of the plan's vector stream (vstream.h; views.h
 * puts it in the stream), written to w as the run goes. w is borrowed (the
 * caller commits or aborts it). Errors of its calls go to err, which must
 * outlive it: LAM_EIO (w), LAM_ENOMEM, and the JSON's (json_sink.h). */
int lam_html_consumer(lam_writer *w, lam_vec_consumer *out, lam_error *err);

#endif
