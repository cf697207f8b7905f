/* The area of a model's cross section, computed from the mesh alone (no
 * slicer, no contours): the validator's reference for a layer's net area.
 *
 * Each triangle that meets the plane w = h contributes one segment P -> Q,
 * P where its boundary (in the triangle's own order) goes from above the
 * plane to below it and Q where it goes back up, so the material of an
 * outward triangle lies to the segment's left seen from +w. Green's theorem
 * over all segments, A = 1/2 sum (P x Q), is then the integral of the
 * winding number over the plane: solids count +1, cavities (inward shells)
 * -1, and where two bodies overlap twice. The segments need not be chained
 * into loops, so the sum does not depend on how the slicer assembles them.
 *
 * A vertex exactly at h counts as below the plane when the section is taken
 * just above it (floor and middle cuts) and as above when it is taken just
 * below (ceiling cuts): the slicer's symbolic perturbation (SPEC 3.2), so a
 * flat face lying in the plane belongs to the side the slicer gives it.
 * Heights are the vertices' coordinates along w computed as the slicer
 * computes them (exact for the axis frames). Sums are compensated
 * (Neumaier) and taken about the centre of the model's (u, v) box.
 *
 * Queries cost O(log T + k) for T triangles and k crossing the plane: each
 * triangle is filed once in a loose bucket hierarchy over w (a bucket of
 * level L is 1/2^L of the extent and holds triangles at most that tall whose
 * centre lies in it; a query looks at two buckets per level). */
#ifndef LAM_SECTION_H
#define LAM_SECTION_H

#include <stddef.h>

#include "error.h"
#include "model.h"
#include "frame.h"

typedef struct lam_section_index lam_section_index;

/* Index the triangles of m along f's w. The model must outlive the index.
 * Errors: LAM_ENOMEM. */
int lam_section_index_new(const lam_model *m, const lam_frame *f, lam_section_index **out, lam_error *err);

void lam_section_index_free(lam_section_index *x);

/* A second index for another thread: it shares x's arrays, which no query
 * changes (and x's sorted heights when lam_section_snap has made them;
 * otherwise it sorts its own on first use), and keeps its own scratch, so
 * x and its forks can be queried at the same time from different threads.
 * x must outlive it; free it with lam_section_index_free. Errors:
 * LAM_ENOMEM. */
int lam_section_index_fork(const lam_section_index *x, lam_section_index **out, lam_error *err);

/* The frame the index was made for. */
const lam_frame *lam_section_index_frame(const lam_section_index *x);

typedef struct lam_section_measure {
    double area;          /* integral of the winding number over the plane */
    double perimeter;     /* total length of the segments */
    double rate;          /* sum of length * |n.w| / |n in the plane| over the segments: a bound on
                             |d area / d h|, for tolerances when h is known only to some precision */
    size_t segments;
    size_t solid_shells;  /* shells that are not cavities and meet the plane */
    int closed;           /* 0 when the model has boundary edges or orientation conflicts: then
                             the segments do not close and area means nothing */
} lam_section_measure;

/* The section at height h along the index's w, taken just above h (below 0)
 * or just below it (below 1). Not thread-safe for one index (it reuses a
 * scratch array of shells). Cannot fail. */
void lam_section_measure_at(lam_section_index *x, double h, int below, lam_section_measure *out);

/* The vertex height along w nearest to h when it is at most tol away (a
 * height read back from a program, written to some precision, that meant a
 * flat face's plane), else h. The sorted heights are made on first use.
 * Errors: LAM_ENOMEM (*out is then h). */
int lam_section_snap(lam_section_index *x, double h, double tol, double *out, lam_error *err);

/* Signed area of a loop of n points (2 doubles each; > 0 counter-clockwise),
 * by the shoelace formula about its first point with a compensated sum: the
 * validator's own measure, independent of the contour code's. */
double lam_section_loop_area(const double *uv, size_t n);

#endif
