/* Ray queries on a model's triangles with Embree: the one place lamina
 * builds an Embree scene, casts rays and votes on a winding number. Used
 * by the layer validator (validate.h), the design-rule check (drc.h) and
 * the shell enclosure test (enclose.h).
 *
 * A lam_rays holds one Embree device and one robust scene of the model's
 * triangles (float32, as Embree stores them) in the model's orientation:
 * outward for solids, inward for cavities.
 *
 * Winding number. From a point p, rays are cast in fixed, deterministic,
 * non-axis directions, and every hit along each ray is gathered (an
 * intersection filter records the hit and rejects it, so traversal goes on;
 * a primitive reported twice -- spatial splits -- counts once). A crossing
 * counts sign(dir . n): +1 leaving through an outward face, -1 entering, so
 * the sum is the winding number of the solid around p (1 inside a solid, 0
 * outside and inside a cavity, 2 where two bodies overlap). The sign is taken
 * from the triangle's normal in double precision and must agree with
 * Embree's geometric normal, Ng = (v1 - v0) x (v2 - v0). Hits of one shell
 * at nearly the same distance (a ray through a shared edge or vertex, which
 * Embree may report on several triangles) count once when their signs agree;
 * mixed signs (grazing an edge or a silhouette) make that direction
 * unreliable. Five directions vote first; unless at least three are reliable
 * and all agree, eleven more are cast and a strict majority (of at least
 * three) of the reliable ones decides. Otherwise the winding is not guessed:
 * the call fails. Hits near the point (within a few float32 tolerances
 * along the ray, where Embree's float geometry cannot tell which side the
 * point is on) are placed again in double precision from the model's own
 * vertices: the signed distance of the point from the triangle's plane
 * decides whether the crossing is ahead or behind. A point in the plane of
 * a triangle it hits (to double rounding) is on the surface and has no
 * winding number, unless the query gives a direction to perturb it in (the
 * layer check does: the slicer's symbolic step toward the inside of its
 * slab), which then decides. The same point always gets the same answer. */
#ifndef LAM_RAYS_H
#define LAM_RAYS_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "model.h"
#include "section.h"

typedef struct lam_rays lam_rays;

/* Build the Embree scene of model's triangles, loading Embree on the first
 * call (embree_lazy.h). The model must outlive the lam_rays. Errors:
 * LAM_EIO when Embree cannot be loaded, LAM_EGEOM with Embree's message
 * when Embree fails (no device, a buffer or build error), LAM_ENOMEM. */
int lam_rays_new(const lam_model *m, lam_rays **out, lam_error *err);

/* Free v; a fork's statistics are added to its parent's (so free forks on
 * the parent's thread, after their last query). */
void lam_rays_free(lam_rays *v);

/* A second handle on v's scene for another thread. Embree's committed
 * scene is only read by queries, so v and its forks may be queried at the
 * same time from different threads; each keeps its own hit buffer,
 * statistics and section index (a fork of v's index for the frame v last
 * indexed, lam_section_index_fork, else its own on first use). The answers
 * are v's, bit for bit. v must outlive it. Errors: LAM_ENOMEM. */
int lam_rays_fork(lam_rays *v, lam_rays **out, lam_error *err);

/* Winding number of the model's solid around p (model coordinates).
 * Errors: LAM_EGEOM "cannot decide the winding at (x, y, z)" when the
 * directions do not reach a majority, LAM_EGEOM when p is on the surface
 * (in the plane of a triangle a ray hits, to double rounding), LAM_ENOMEM. Not thread-safe for one
 * lam_rays (each call reuses its hit buffer): one fork per thread (lam_rays_fork). */
int lam_rays_winding(lam_rays *v, const double p[3], int *winding, lam_error *err);

/* The winding at the section point (u, v) at height h of frame f (its
 * model coordinates into xyz), taken just above the plane (below 0) or just
 * below it (below 1), as the slicer takes sections (SPEC 3.2): a triangle
 * in whose plane the point lies, to double rounding, is above or below it
 * as the slicer sees it from its vertices' heights (a face lying in the
 * plane is on the far side of that step). On the surface (LAM_EGEOM) only
 * when a triangle passes through the point itself or stands on edge there. */
int lam_rays_winding_section(lam_rays *v, const lam_frame *f, double u, double w, double h, int below,
                                  double xyz[3], int *winding, lam_error *err);

/* Embree's float32 tolerance (hits this close along a ray are placed again
 * in double precision), and the smallest inset of a layer test point from
 * its edge (model units). */
double lam_rays_tolerance(const lam_rays *v);
double lam_rays_min_inset(const lam_rays *v);

/* The preferred inset of a test point (1e-3 of the model's size, at least
 * four smallest insets) and the model's largest extent. */
double lam_rays_target_inset(const lam_rays *v);
double lam_rays_scale(const lam_rays *v);

/* The model's sections along f (section.h), indexed on first use and kept
 * for the next layers of the same frame; owned by the validator. Errors:
 * LAM_ENOMEM. */
int lam_rays_section(lam_rays *v, const lam_frame *f, lam_section_index **out, lam_error *err);

/* Ray direction k of the fixed set (unit length in double precision; Embree
 * gets it rounded to float), NULL when k is past the last. The first five
 * are cast for every point, the others when those do not agree. For tests
 * and diagnostics. */
const double *lam_rays_direction(size_t k);

/* The nearest surface along the ray from p in direction d (unit length)
 * beyond distance tmin (nearer hits are ignored: a ray leaving a surface
 * must not see that surface). *t is INFINITY when nothing is hit; *tri (may
 * be NULL) the triangle hit. Errors: LAM_ENOMEM. The scene is float32, so
 * distances are good to about lam_rays_tolerance. */
int lam_rays_cast(lam_rays *v, const double p[3], const double d[3], double tmin, double *t, uint32_t *tri,
                  lam_error *err);

/* How many edges pass through a triangle that has neither of their ends
 * (the surface intersects itself there) where the edge or the triangle is
 * one of the model's triangles from `first` on (a repair's fill: the
 * file's own crossings are not searched, which on a stack of overlapping
 * facets would cost each edge a walk past thousands of them), in *count.
 * One segment query an edge near those triangles, in float32: an edge that
 * only grazes a triangle within lam_rays_tolerance may count or not.
 * crossed (may be NULL; one byte a triangle, zeroed by the caller): set
 * for the triangles of each such edge and the triangle it passes through.
 * Errors: LAM_ENOMEM, LAM_ELIMIT past a budget of work (fills by the
 * million among overlapping facets): then *count is a part. */
int lam_rays_crossed_edges(lam_rays *v, size_t first, size_t *count, unsigned char *crossed, lam_error *err);

typedef struct lam_rays_stats {
    size_t points;      /* winding queries (including surface retries) */
    size_t rays;        /* rays cast */
    size_t recasts;     /* queries that needed the further directions */
    size_t unreliable;  /* rays discarded (grazing or mixed-sign hits) */
    size_t surface;     /* queries that found the point on the surface */
    size_t undecided;   /* queries without a majority */
} lam_rays_stats;

void lam_rays_get_stats(const lam_rays *v, lam_rays_stats *st);

/* The most frequent of the n values w[0..n-1] (the first to reach that
 * count on a tie), its count in *count; n > 0. The vote of the winding
 * queries above, and of callers that sample several points (a strict
 * majority is 2 * count > n). */
int lam_rays_vote(const int *w, size_t n, size_t *count);

#endif
