/* Which shells enclose which: the count behind the cavity rule (a shell
 * inside an odd number of others is a cavity). Internal to core/:
 * model_build.c calls it while it builds a model.
 *
 * Candidates first: shell s can only lie in shell o when s's bounding box
 * lies in o's. The pairs come from a bounding-volume tree over the shells
 * (in Morton order of their box centres, halved down to small leaves, each
 * node with the box of its shells): s descends only into nodes whose box
 * holds its own. Memory is linear in the shells however their boxes lie;
 * shells of one triangle, which cannot enclose anything, are not in the
 * tree, so a triangle soup of 200k one-triangle shells costs milliseconds
 * and 2^20 stacked triangles too. When the boxes overlap so much that the
 * pairs pass the budget below, only whether each shell has a candidate at
 * all is found, and rays decide.
 *
 * Then each candidate pair is decided. Pairwise: the generalized winding
 * number of the outer shell at up to nine sample points of the inner one
 * (triangle centroids), the decisive samples voting (a centroid on the
 * outer surface, as with the thesis's through hole, has winding 1/2 and
 * says nothing). That costs O(triangles of the outer shell) per sample;
 * when the pairs would need millions of such terms (hundreds of voids in a
 * large part) one Embree scene of all shells answers instead: a point just
 * outside a sample triangle of s (offset along its outward normal) has as
 * winding number the count of shells around it, all shells being oriented
 * outward at this stage; the samples vote again, and should any shell stay
 * undecided the pairwise test decides after all. The two agree for shells
 * wholly inside others, which is what the cavity rule is about; a body that
 * only partly overlaps another counts there by rays (the winding sees it)
 * but not pairwise (its box is not inside): such models want --fill
 * nonzero either way. */
#ifndef LAM_ENCLOSE_H
#define LAM_ENCLOSE_H

#include "model.h"
#include "rays.h"

/* Set md->shells[s].enclosing for every shell. md's triangles must be
 * oriented outward per shell, and tri_shell, shell_first/shell_tris and
 * the shells' bboxes and triangle counts set. Errors: LAM_ENOMEM. */
int lam_count_enclosing(lam_model *md, lam_error *err);

#endif
