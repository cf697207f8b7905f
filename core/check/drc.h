/* Design-rule check (the thesis's VLSI analogy carried to SFF): rules a
 * part must meet to be built on a machine, checked on the 3D model.
 *
 * - Wall thickness: from sample points on every triangle, a ray into the
 *   material along the inward normal meets the opposite surface; a wall
 *   thinner than the machine's bead (or spot) cannot be deposited.
 * - Overhang: a downward-facing triangle whose angle from the vertical
 *   exceeds the machine's max_overhang_deg needs support (faces resting on
 *   the build plate, at the model's lowest height, are exempt).
 * Violating triangles that share an edge form one region, reported once
 * with its area and its worst value and position. */
#ifndef LAM_DRC_H
#define LAM_DRC_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "model.h"
#include "validate.h"

typedef enum lam_rule { LAM_RULE_WALL, LAM_RULE_OVERHANG } lam_rule;

typedef struct lam_violation {
    lam_rule rule;
    double pos[3];       /* the worst point of the region */
    double value;        /* wall thickness, or overhang angle in degrees */
    double limit;        /* the rule's limit */
    double area;         /* surface area of the region */
    size_t triangles;    /* triangles in the region */
    uint32_t tri;        /* the worst triangle (lam_mesh_describe_tri names its face) */
} lam_violation;

typedef struct lam_drc_opts {
    double min_wall;          /* 0: rule off */
    double max_overhang_deg;  /* 0: rule off */
    double up[3];             /* build direction, unit length */
} lam_drc_opts;

typedef struct lam_drc_result {
    lam_violation *items;     /* owned; by rule, then worst first */
    size_t n;
    size_t samples;           /* wall-thickness rays cast */
} lam_drc_result;

struct lam_profile;

/* The rules of machine profile p for building along `up` (unit length):
 * the wall at least its bead (LADRP) or spot (SLS) width, overhangs at
 * most its max_overhang_deg (0: that rule off). What `lamina check -m` and
 * Lua's model:check(machine) check. */
void lam_drc_opts_from_profile(lam_drc_opts *o, const struct lam_profile *p, const double up[3]);

/* The rule's short name: "min_wall" or "max_overhang". */
const char *lam_rule_name(lam_rule r);

/* Check model m (with a validator built on it) against o. out is
 * overwritten; free with lam_drc_result_free. Errors: LAM_ENOMEM. */
int lam_drc_run(const lam_model *m, lam_rays *v, const lam_drc_opts *o, lam_drc_result *out, lam_error *err);
void lam_drc_result_free(lam_drc_result *r);

#endif
