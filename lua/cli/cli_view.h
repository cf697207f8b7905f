/* The pictures of `lamina slice`: the SVG contact sheet (--svg) and the
 * HTML viewer (--html), both drawn from the same planning run as the
 * program, through a fan-out of the program's sink. */
#ifndef CLI_VIEW_H
#define CLI_VIEW_H

#include "cli_args.h"
#include "html.h"
#include "planner.h"
#include "svg.h"

typedef struct cli_view {
    lam_svg *svg;
    lam_html *html;
    lam_writer *hw;          /* the viewer's file */
    const char *svg_path;
} cli_view;

/* Start the pictures a asks for of slicer s's run planned with po (whose
 * layer_time and time, when set, the viewer reads as the run goes), and
 * make *sink a fan-out to the program's sink (taken over: the fan-out's
 * destroy destroys it) and theirs. err must outlive the run. Returns
 * LAM_OK or an error code with err set. */
int cli_view_open(cli_view *v, const args *a, lam_slicer *s, const lam_plan_opts *po, lam_sink *sink,
                  lam_error *err);

/* Every layer of the run, before it is planned (the run's layer callback). */
int cli_view_layer(cli_view *v, const lam_layer *L, lam_error *err);

/* After a run that succeeded: write the sheet, commit the viewer. */
int cli_view_save(cli_view *v, lam_error *err);

/* Free; a viewer not saved is removed. */
void cli_view_free(cli_view *v);

#endif
