/* What a planned build holds (build_plan.h), shared by build_run.c (the
 * setup) and build_plan.c (the layers). Internal to core/build. */
#ifndef LAM_BUILD_INTERNAL_H
#define LAM_BUILD_INTERNAL_H

#include "build_plan.h"

struct lam_build_run {
    const lam_build *b;
    lam_run_part *parts;
    size_t nparts;
    double width;            /* layer width */
    size_t layers;           /* plate layers: up to the highest part's top */
    int cut;                 /* lam_cut */
    lam_frame frame;         /* the plate's: u, v, w = x, y, z */
    lam_plate plate;
    double spacing;
    lam_laser_set lasers;
    double *centres;         /* parts' footprint centres (lasers.h) */
    char **styles;           /* style names, number s at styles[s - 1] */
    size_t nstyles;
    /* CLI labels: label[(part - 1) * nstyles * nlasers + (style - 1) * nlasers + laser - 1]
     * is the id (0: none) of each (part, style, laser) the plate can use */
    long long *label_of;
    char **labels;           /* text of id k + 1 */
    size_t nlabels;
    lam_job_info job;
    char job_label[160];
    char *json;              /* the job's "build" member in the JSON (build_json.c) */
};

/* Render the build's JSON description into r->json and the job's
 * json_extra. LAM_ENOMEM. */
int lam_build_run_json(lam_build_run *r, lam_error *err);

/* The label id of (part, style, laser), 0 when it has none. */
long long lam_build_run_label(const lam_build_run *r, long long part, long long style, long long laser);

#endif
