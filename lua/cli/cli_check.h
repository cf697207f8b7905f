/* Validation reports shared by `lamina validate` and `lamina slice
 * --validate`: one layer at a time, as text lines or JSON. */
#ifndef LAM_CLI_CHECK_H
#define LAM_CLI_CHECK_H

#include <stdio.h>

#include "validate.h"

#include "program_read.h"
#include "progress.h"

typedef struct vreport {
    FILE *out;               /* where the report goes */
    int json, verbose;       /* verbose: a line for every layer, not only disagreeing ones */
    size_t layers, checked, confirmed, disagreeing, unchecked;
    size_t areas_compared, areas_differ;
    int first;               /* JSON: no comma before the first layer */
    cli_progress *progress;  /* the line to erase before a text line (NULL: none) */
} vreport;

/* Where a layer's contours stand in a program read back (NULL for a layer
 * straight from the slicer). */
typedef struct vsource {
    const char *path;
    const lam_program_contour *contours;  /* the layer's, in its order */
} vsource;

/* Check one layer and report it. Returns LAM_OK or an error code. */
int vreport_layer(vreport *r, lam_rays *v, const lam_layer *L, const lam_frame *f, const lam_validate_opts *o,
                  const vsource *src, lam_error *err);

/* Report layer L's check (made elsewhere: lam_validate_layer, or a worker
 * of validate_run.h) and count it. Cannot fail. */
void vreport_check(vreport *r, const lam_layer *L, const lam_layer_check *chk, const vsource *src);

/* The report's last line (text) or closing fields (JSON), and the exit
 * status the checks call for: EXIT_CHECK when a contour or an area
 * disagrees, else EXIT_OK. */
int vreport_finish(vreport *r, const char *what);

#endif
