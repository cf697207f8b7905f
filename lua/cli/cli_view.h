/* The pictures of `lamina slice`: the SVG contact sheet with the scan paths
 * (--svg) and the HTML viewer (--html), both fed by the same planning run
 * as the program (their sinks join the program's in a tee). */
#ifndef CLI_VIEW_H
#define CLI_VIEW_H

#include "cli_args.h"
#include "planner.h"
#include "views.h"

typedef struct cli_view {
    lam_svg *svg;
    const char *svg_path;
    lam_writer *hw;          /* the viewer's output */
    unsigned long long limit;/* each file's most bytes (--max-output, or the default) */
} cli_view;

/* Start the pictures a asks for of slicer s's run planned with po, named
 * in *views (its svg, frame and html; the caller makes the views' sink).
 * err must outlive the run. Returns LAM_OK or an error code with err set. */
int cli_view_open(cli_view *v, const args *a, lam_slicer *s, const lam_plan_opts *po, lam_views *views,
                  lam_error *err);

/* Every layer of the run, before it is planned (the run's layer callback). */
int cli_view_layer(cli_view *v, const lam_layer *L, lam_error *err);

/* After a run that succeeded: write the sheet, commit the viewer. */
int cli_view_save(cli_view *v, lam_error *err);

/* Free; a viewer not saved is removed. */
void cli_view_free(cli_view *v);

#endif
