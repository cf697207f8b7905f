/* Validation of sliced layers against the solid with Embree (SPEC 6).
 *
 * A lam_validator holds one Embree device and one robust scene of the
 * model's triangles (float32, as Embree stores them) in the model's
 * orientation: outward for solids, inward for cavities.
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
 * the call fails. A point within the tolerance of the surface has no winding
 * number (the call fails and says so). The same point always gets the same
 * answer.
 *
 * Layer check. For each contour, test points are placed on both sides of
 * up to four of its longest edges, at the edge's midpoint, offset along its
 * normal by an inset well above float32 error (at least max(1e-5 * model
 * size, 1000 * FLT_EPSILON * largest |coordinate|)) and well below the
 * feature size (at most a quarter of the edge, half the distance to any
 * other edge of the layer along that normal, 1e-3 * model size), and
 * lifted to 3D at the cut height. A point that falls on the surface (a cut
 * through a flat face) is moved a tiny step toward the inside of its slab,
 * as the slicer's symbolic perturbation does (SPEC 3.2): up for floor and
 * middle cuts, down for ceiling cuts.
 *
 * What the label claims: a solid's interior is material and its exterior
 * void; a hole's interior is void and its exterior material. The interior
 * side of an edge comes from the contour's actual orientation (signed area),
 * not from the label, so a contour whose label is wrong (solid <-> hole)
 * disagrees on both sides of every edge.
 *
 * The truth: material where the winding number is non-zero. Bodies that
 * overlap are material (winding 2), cavities are not (their inward faces
 * cancel the solid around them), whatever the fill rule. Under even-odd,
 * the slicer labels the square where two shells overlap a hole: validation
 * reports that disagreement, which the non-zero fill rule (one merged
 * outline) resolves. The fill rule the layer was made with changes only the
 * explanation given for a disagreement. */
#ifndef LAM_VALIDATE_H
#define LAM_VALIDATE_H

#include <stddef.h>

#include "error.h"
#include "model.h"
#include "slice.h"

typedef struct lam_validator lam_validator;

/* Build the Embree scene of model's triangles. The model must outlive the
 * validator. Errors: LAM_EGEOM with Embree's message when Embree fails
 * (no device, a buffer or build error), LAM_ENOMEM. */
int lam_validator_new(const lam_model *m, lam_validator **out, lam_error *err);

void lam_validator_free(lam_validator *v);

/* Winding number of the model's solid around p (model coordinates).
 * Errors: LAM_EGEOM "cannot decide the winding at (x, y, z)" when the
 * directions do not reach a majority, LAM_EGEOM when p is on the surface
 * (within the validator's tolerance), LAM_ENOMEM. Not thread-safe for one
 * validator (each call reuses its hit buffer). */
int lam_validator_winding(lam_validator *v, const double p[3], int *winding, lam_error *err);

/* Distance within which a point counts as on the surface, and the smallest
 * inset of a layer test point from its edge (model units). */
double lam_validator_tolerance(const lam_validator *v);
double lam_validator_min_inset(const lam_validator *v);

/* Ray direction k of the fixed set (unit length in double precision; Embree
 * gets it rounded to float), NULL when k is past the last. The first five
 * are cast for every point, the others when those do not agree. For tests
 * and diagnostics. */
const double *lam_validator_direction(size_t k);

/* The nearest surface along the ray from p in direction d (unit length)
 * beyond distance tmin (nearer hits are ignored: a ray leaving a surface
 * must not see that surface). *t is INFINITY when nothing is hit; *tri (may
 * be NULL) the triangle hit. Errors: LAM_ENOMEM. The scene is float32, so
 * distances are good to about lam_validator_tolerance. */
int lam_validator_ray(lam_validator *v, const double p[3], const double d[3], double tmin, double *t, uint32_t *tri,
                      lam_error *err);

typedef struct lam_validator_stats {
    size_t points;      /* winding queries (including surface retries) */
    size_t rays;        /* rays cast */
    size_t recasts;     /* queries that needed the further directions */
    size_t unreliable;  /* rays discarded (grazing or mixed-sign hits) */
    size_t surface;     /* queries that found the point on the surface */
    size_t undecided;   /* queries without a majority */
} lam_validator_stats;

void lam_validator_get_stats(const lam_validator *v, lam_validator_stats *st);

/* The result for one contour. */
typedef struct lam_contour_check {
    size_t contour;          /* index in the layer */
    int ok;                  /* 1 confirmed, 0 disagrees, -1 not checked (no test point
                                could be placed or decided; why says which) */
    size_t edges;            /* edges tested (both sides decided) */
    double uv[2], xyz[3];    /* the first disagreeing test point; for a confirmed
                                contour, the first point tested */
    int winding_found;       /* the winding number there */
    int expected_material;   /* what the label claims there: 1 material, 0 void */
    const char *why;         /* static text: "confirmed" or what disagrees */
} lam_contour_check;

typedef struct lam_layer_check {
    size_t index;            /* the layer's index */
    size_t checked;          /* contours with at least one edge tested */
    size_t confirmed, disagreeing;  /* confirmed + disagreeing == checked */
    size_t unchecked;        /* contours with no test point (ok == -1) */
    lam_contour_check *items;  /* one per contour, in the layer's order; owned */
    size_t nitems;
} lam_layer_check;

/* Check every contour of layer L (made with frame f; fill_nonzero: the fill
 * rule it was made with, 0 even-odd, 1 non-zero). out is overwritten (not
 * freed first) and must be released with lam_layer_check_free. Errors:
 * LAM_ENOMEM (out is then empty). Undecidable points are not errors: the
 * edge is replaced by the next longest one, and a contour with no decided
 * edge is reported unchecked. */
int lam_validate_layer(lam_validator *v, const lam_layer *L, const lam_frame *f, int fill_nonzero,
                       lam_layer_check *out, lam_error *err);

/* Release out->items and zero *out (NULL is fine). */
void lam_layer_check_free(lam_layer_check *c);

/* Tests only: flip the label of one contour (solid <-> hole) without
 * touching its points, depth or parent. Out of range does nothing. */
void lam_layer_flip_label_for_test(lam_layer *L, size_t contour);

#endif
