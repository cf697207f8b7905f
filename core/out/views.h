/* The run's views: its JSON (--json), its viewer (--html, the same JSON
 * inside the page), its contact sheet's scan paths (--svg) and Lua's plan
 * data, all consumers of one vector stream (vstream.h): a planning run's
 * operations are decoded into vectors once, whatever views are asked for
 * (the page carries its own summary of the JSON, html.h). The
 * views' sink goes beside the program's in a tee (tee.h). */
#ifndef LAM_VIEWS_H
#define LAM_VIEWS_H

#include "error.h"
#include "plan.h"
#include "plan_data.h"
#include "svg.h"
#include "writer.h"

typedef struct lam_views {
    lam_writer *json;        /* the layer interchange JSON (json_sink.h), or NULL */
    const struct lam_json_opts *json_opts; /* what the JSON holds (json_sink.h), NULL: everything */
    lam_writer *html;        /* the viewer page (html.h), or NULL */
    lam_svg *svg;            /* a sheet to draw the plan on (svg.h), or NULL */
    const lam_frame *frame;  /* with svg: the run's frame (names the axes) */
    int frame_machine;       /* with svg: the output frame is the layer frame */
    lam_plan_data *data;     /* plan data to fill (plan_data.h, zeroed here), or NULL */
} lam_views;

/* Make *out a sink that feeds every view v names (at least one). The
 * writers, the sheet and the data stay the caller's (the writers to commit
 * or abort after the run); err must outlive the sink. Errors: LAM_ENOMEM,
 * LAM_EUSAGE when v names no view. */
int lam_views_sink(const lam_views *v, lam_sink *out, lam_error *err);

#endif
