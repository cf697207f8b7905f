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
 * the call fails. Hits near the point (within a few float32 tolerances
 * along the ray, where Embree's float geometry cannot tell which side the
 * point is on) are placed again in double precision from the model's own
 * vertices: the signed distance of the point from the triangle's plane
 * decides whether the crossing is ahead or behind. A point in the plane of
 * a triangle it hits (to double rounding) is on the surface and has no
 * winding number, unless the query gives a direction to perturb it in (the
 * layer check does: the slicer's symbolic step toward the inside of its
 * slab), which then decides. The same point always gets the same answer.
 *
 * Layer check. Per contour, what is written is checked, not only its label:
 * - direction: a solid is counter-clockwise and a hole clockwise by its
 *   signed area (computed here, compensated), since a machine takes a
 *   clockwise loop for a hole whatever the label says;
 * - ancestry: the parent is a contour of the layer, no contour is its own
 *   ancestor, depth is the parent's plus one (0 without one) and the label
 *   is the depth's parity;
 * - nesting: the contours around a point just inside it, counted by an
 *   even-odd ray in the plane (this module's own crossing test, not the
 *   slicer's), give its depth and its parent (the smallest around it); a
 *   layer read back from a program (depth < 0: unknown) must have each
 *   label agree with that depth's parity;
 * - material: test points beside its edges, lifted to 3D at the cut
 *   height, must be material on the side the label claims and void on the
 *   other, by the winding number of rays (below).
 * Per layer, the net area (solids minus holes, by the label) must match the
 * model's own section at the cut (section.h: Green's theorem over the
 * mesh's triangles), within a tolerance from the precision the points and
 * the height were written with. Not compared, and said so: layers whose
 * outlines were closed across gaps or left open, models with boundary
 * edges; one-sided (net at most the section) under the non-zero fill rule
 * when two bodies meet the plane, where the section counts their overlap
 * twice.
 *
 * Test points: on both sides of up to four of the contour's longest edges,
 * at the edge's midpoint, offset along its normal by d. d is tied to the
 * local geometry: at most a quarter of the edge, half the distance along
 * the normal to any other edge of the layer, 1e-3 * model size, and halved
 * until no edge of the layer comes nearer to the point than d / 2; at
 * least an inset well above float32 error (max(1e-5 * model size, 1000 *
 * FLT_EPSILON * largest |coordinate|)) and, for a program read back, ten
 * times the precision its points were written with. The points stay in the
 * cut plane: the winding is the one at the section itself, and a face lying
 * in the plane (a cut on a flat face) is resolved by the slicer's symbolic
 * step toward the inside of the slab (up for floor and middle cuts, down
 * for ceiling cuts), never by moving the point off the plane, where a face
 * just above or below the cut would be crossed.
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
#include "section.h"
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
 * (in the plane of a triangle a ray hits, to double rounding), LAM_ENOMEM. Not thread-safe for one
 * validator (each call reuses its hit buffer). */
int lam_validator_winding(lam_validator *v, const double p[3], int *winding, lam_error *err);

/* The winding at the section point (u, v) at height h of frame f (its
 * model coordinates into xyz), taken just above the plane (below 0) or just
 * below it (below 1), as the slicer takes sections (SPEC 3.2): a triangle
 * in whose plane the point lies, to double rounding, is above or below it
 * as the slicer sees it from its vertices' heights (a face lying in the
 * plane is on the far side of that step). On the surface (LAM_EGEOM) only
 * when a triangle passes through the point itself or stands on edge there. */
int lam_validator_winding_section(lam_validator *v, const lam_frame *f, double u, double w, double h, int below,
                                  double xyz[3], int *winding, lam_error *err);

/* Embree's float32 tolerance (hits this close along a ray are placed again
 * in double precision), and the smallest inset of a layer test point from
 * its edge (model units). */
double lam_validator_tolerance(const lam_validator *v);
double lam_validator_min_inset(const lam_validator *v);

/* The preferred inset of a test point (1e-3 of the model's size, at least
 * four smallest insets) and the model's largest extent. */
double lam_validator_target_inset(const lam_validator *v);
double lam_validator_scale(const lam_validator *v);

/* The model's sections along f (section.h), indexed on first use and kept
 * for the next layers of the same frame; owned by the validator. Errors:
 * LAM_ENOMEM. */
int lam_validator_section(lam_validator *v, const lam_frame *f, lam_section_index **out, lam_error *err);

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

/* What a contour check found wrong (bits of lam_contour_check.problems). */
enum {
    LAM_VP_MATERIAL = 1 << 0,   /* a test point contradicts the label (rays) */
    LAM_VP_DIRECTION = 1 << 1,  /* written clockwise and labelled solid, or the reverse, or no area */
    LAM_VP_ANCESTRY = 1 << 2,   /* parent out of range, its own ancestor, depth or label against the parent */
    LAM_VP_NESTING = 1 << 3     /* depth or parent (or, read back, the label) against the contours around it */
};

/* The result for one contour. */
typedef struct lam_contour_check {
    size_t contour;          /* index in the layer */
    int ok;                  /* 1 confirmed, 0 disagrees, -1 not checked (no test point
                                could be placed or decided and nothing else is wrong;
                                why says which) */
    unsigned problems;       /* LAM_VP_* bits, 0 when confirmed or not checked */
    size_t edges;            /* edges tested (both sides decided) */
    double uv[2], xyz[3];    /* the first disagreeing test point; for a confirmed
                                contour, the first point tested */
    int winding_found;       /* the winding number there */
    int expected_material;   /* what the label claims there: 1 material, 0 void */
    double area;             /* signed area of the points as written (> 0 counter-clockwise) */
    int depth_found;         /* contours around it by the plane ray; -1 when not found */
    long parent_found;       /* the smallest of them, -1 for none */
    const char *why;         /* static text: "confirmed", why not checked, or the first problem */
    const char *whys[4];     /* per LAM_VP_* bit (bit k at k): what is wrong, NULL if nothing */
} lam_contour_check;

typedef struct lam_layer_check {
    size_t index;            /* the layer's index */
    size_t checked;          /* contours with at least one edge tested or a problem found */
    size_t confirmed, disagreeing;  /* confirmed + disagreeing == checked */
    size_t unchecked;        /* contours with no test point (ok == -1) */
    lam_contour_check *items;  /* one per contour, in the layer's order; owned */
    size_t nitems;
    /* the layer's net area against the model's section */
    int area_checked;        /* 1 compared, 0 not (area_why says why) */
    int area_ok;             /* 1 when compared and within tolerance (or not compared) */
    double net_area;         /* solids minus holes, by the label, of the points as written */
    double section_area;     /* the model's section at the cut (section.h) */
    double area_tolerance;
    const char *area_why;    /* static text: why not compared, or what the comparison was */
} lam_layer_check;

/* How a layer is checked. */
typedef struct lam_validate_opts {
    int fill_nonzero;        /* the fill rule it was made with: 0 even-odd, 1 non-zero */
    double quantum_uv;       /* how far a written coordinate may be from the true one
                                (half a unit in its last printed place); 0 for layers
                                straight from the slicer */
    double quantum_h;        /* the same for the written height */
} lam_validate_opts;

/* Defaults: even-odd, exact coordinates. */
void lam_validate_opts_init(lam_validate_opts *o);

/* Check every contour of layer L (made with frame f) as the header says.
 * The section is taken just below the cut when L is a ceiling cut (cut ==
 * ceiling > floor), else just above. Contours with depth < 0 have no
 * nesting to check (a program read back): their depth and parent are found
 * and their labels must agree with it. out is overwritten (not freed
 * first) and must be released with lam_layer_check_free. Errors:
 * LAM_ENOMEM (out is then empty). Undecidable points are not errors: the
 * edge is replaced by the next longest one, and a contour with no decided
 * edge and no other problem is reported unchecked. */
int lam_validate_layer(lam_validator *v, const lam_layer *L, const lam_frame *f, const lam_validate_opts *o,
                       lam_layer_check *out, lam_error *err);

/* Static text naming one LAM_VP_* bit ("material", "direction", ...). */
const char *lam_validate_problem_name(unsigned bit);

/* Release out->items and zero *out (NULL is fine). */
void lam_layer_check_free(lam_layer_check *c);

/* Tests only: flip the label of one contour (solid <-> hole) without
 * touching its points, depth or parent. Out of range does nothing. */
void lam_layer_flip_label_for_test(lam_layer *L, size_t contour);

#endif
