/* Which shells enclose which, for models with many shells inside others
 * (a part with hundreds of internal voids). Internal to core/: model.c
 * uses it while it builds a model.
 *
 * model.c's own test, pairwise, takes the generalized winding number of
 * the outer shell at sample points of the inner one: O(triangles of the
 * outer shell) per sample, which for hundreds of voids in a large part
 * runs into seconds. Here one Embree scene of all shells answers every
 * sample with a few rays: a point just outside a sample triangle of shell
 * s (offset along its outward normal) has as winding number the count of
 * the shells around it, all shells being oriented outward at this stage. */
#ifndef LAM_ENCLOSE_H
#define LAM_ENCLOSE_H

#include "model.h"

/* Set md->shells[s].enclosing for every shell s marked in candidates
 * (shells that lie in some other shell's bounding box; the others enclose
 * nothing and keep 0). md's triangles must be oriented outward per shell
 * and md->tri_shell, shell_first/shell_tris and the shells' bboxes set.
 * *done = 1 when every candidate was decided by a majority of decisive
 * samples; 0 when Embree could not be used or some shell stayed
 * undecided (then nothing is changed and the caller tests pairwise).
 * Errors: LAM_ENOMEM. */
int lam_enclosing_by_rays(lam_model *md, const unsigned char *candidates, int *done, lam_error *err);

#endif
