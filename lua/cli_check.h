/* Validation reports shared by `lamina validate` and `lamina slice
 * --validate`: one layer at a time, as text lines or JSON. */
#ifndef LAM_CLI_CHECK_H
#define LAM_CLI_CHECK_H

#include <stdio.h>

#include "validate.h"

typedef struct vreport {
    FILE *out;               /* where the report goes */
    int json, verbose;       /* verbose: a line for every layer, not only disagreeing ones */
    size_t layers, checked, confirmed, disagreeing, unchecked;
    int first;               /* JSON: no comma before the first layer */
} vreport;

/* Check one layer and report it. Returns LAM_OK or an error code. */
int vreport_layer(vreport *r, lam_validator *v, const lam_layer *L, const lam_frame *f, int fill_nonzero,
                  lam_error *err);

#endif
