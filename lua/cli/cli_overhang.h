/* `lamina check`'s overhang analysis for a powder-bed machine (issue 27):
 * the machine's layers, the supports its profile makes (support.h), and
 * per layer the overhang area that stands on nothing within the reach of
 * the layer below. */
#ifndef LAM_CLI_OVERHANG_H
#define LAM_CLI_OVERHANG_H

#include <stddef.h>

#include "cli_args.h"
#include "lamina.h"

typedef struct cli_overhangs {
    int ran;                 /* 0: not a powder-bed profile (nothing below is set) */
    const char *type;        /* the profile's support_type */
    const char *units;       /* the profile's units */
    double angle;            /* its support_angle */
    size_t n;                /* layers */
    double *z;               /* each layer's cut */
    double *over;            /* each layer's overhang without supports */
    double *left;            /* ... and with the profile's (= over without) */
    double *support;         /* each layer's support area */
    size_t bad;              /* layers with left > 0 */
} cli_overhangs;

/* The analysis of model m with the slicing of a and profile prof into o
 * (zeroed first; o->ran 0 for a LADRP profile). Errors: the slicer's,
 * GEOS's, out of memory (err). */
int cli_overhangs_run(const args *a, lam_model *m, const lam_profile *prof, cli_overhangs *o, lam_error *err);

/* The text lines (a line per unsupported layer and a summary) or the
 * JSON member `,"overhangs":{...}` of o on standard output. */
void cli_overhangs_print(const cli_overhangs *o, const char *path, int json);

void cli_overhangs_free(cli_overhangs *o);

#endif
