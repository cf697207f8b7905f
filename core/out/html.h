/* The browser viewer of a planning run: one self-contained HTML file (no
 * network, no other file): the viewer's page (core/out/viewer.html, compiled
 * in at build time) with the run's layer interchange JSON (json_sink.h,
 * "lamina-run" version 1) in its <script type="application/json"
 * id="lamina-run"> element. The page draws it: a layer slider, zoom and
 * pan, toggles for contours, vectors and travel, each layer's figures. It
 * honours a URL hash `#layer=N` (1-based) with `contours=0|1`,
 * `vectors=0|1`, `travel=0|1`, and keeps it up to date.
 *
 * The JSON is streamed as the run goes (the JSON sink writes each layer
 * when it is planned and forgets it), so memory does not grow with the
 * run; it is the page's only text from the run, and its strings write '<'
 * as \u003c (lam_json_consumer's script text: escape.h's LAM_ESC_JSON_SCRIPT), so no
 * "</script>" or "<!--" can end or change the element. The page's script
 * shows the run's strings (model path, machine, units) as text only
 * (textContent, document.title, canvas text), never as markup. */
#ifndef LAM_HTML_H
#define LAM_HTML_H

#include "plan.h"
#include "vstream.h"
#include "writer.h"

/* The page around the run's JSON as two consumers of the plan's vector
 * stream (vstream.h; views.h puts them in the stream): head writes the
 * page up to the data when the job begins, tail the rest when it ends;
 * between them the JSON consumer (json_sink.h) writes the data to w with
 * its script escaping. w is borrowed (the caller commits or aborts it);
 * head's destroy frees both. Errors of their calls go to err, which must
 * outlive them. Errors: LAM_ENOMEM. */
int lam_html_page(lam_writer *w, lam_vec_consumer *head, lam_vec_consumer *tail, lam_error *err);

#endif
