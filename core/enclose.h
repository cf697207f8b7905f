/* Which shells enclose which: the count behind the cavity rule (a shell
 * inside an odd number of others is a cavity). Internal to core/: model.c
 * calls it while it builds a model.
 *
 * Candidates first: shell s can only lie in shell o when s's bounding box
 * lies in o's. The pairs come from a grid over the model: each shell is
 * listed in the cells its box covers (a box covering many cells goes on
 * one list that every shell checks), and s looks only in the cell of its
 * box's centre, which any box containing s's box covers. A triangle soup
 * of 160k one-triangle shells thus costs milliseconds, not all 160k^2
 * pairs.
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

/* Transitional: the names enclose.c used before rays.h existed. enclose.c
 * should call lam_rays_new / lam_rays_min_inset / lam_rays_winding /
 * lam_rays_free and lam_rays_vote (its sample vote), include rays.h
 * instead of validate.h, and then these lines go. */
typedef lam_rays lam_validator;
#define lam_validator_new lam_rays_new
#define lam_validator_free lam_rays_free
#define lam_validator_min_inset lam_rays_min_inset
#define lam_validator_winding lam_rays_winding

/* Set md->shells[s].enclosing for every shell. md's triangles must be
 * oriented outward per shell, and tri_shell, shell_first/shell_tris and
 * the shells' bboxes and triangle counts set. Errors: LAM_ENOMEM. */
int lam_count_enclosing(lam_model *md, lam_error *err);

#endif
