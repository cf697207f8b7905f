/* Nesting of a layer's loops: for each loop, how many other loops contain
 * it (its depth: 0 solid, 1 hole, 2 solid...) and the smallest of them
 * (its parent). Internal to core/ (contour.c is the user).
 *
 * The question is asked at a point just inside each loop (next to its
 * lowest-leftmost vertex, so that a vertex lying on another loop does not
 * decide it): a loop contains the point when a ray from it towards -u
 * crosses the loop's edges an odd number of times, an edge counting when
 * the ray's height v lies in [its lower v, its upper v) (horizontal edges
 * never count). Loops of a section do not cross, though they may touch.
 *
 * Three methods, the same answers:
 *   - a few loops (at most LAM_NEST_FEW): each against each other;
 *   - otherwise a sweep over v with the active edges in a balanced search
 *     tree ordered along u, O(N log N) for N points: the depth is a sum
 *     over the edges left of the point (+1 where a loop's inside begins,
 *     -1 where it ends), the parent follows from the nearest edge of
 *     another loop to the left;
 *   - should the sweep's answers not agree with each other (a depth that
 *     is not its parent's plus one: rounding at touching loops; or a
 *     parent that is not larger, lam_nest_larger), the layer
 *     is done again by a sweep that tests every active edge, as exact as
 *     the few-loops method but O(N) per loop in the worst case. */
#ifndef LAM_NEST_H
#define LAM_NEST_H

#include <math.h>
#include <stddef.h>

#include "error.h"

#define LAM_NEST_FEW 8

typedef struct lam_nest_loop {
    size_t first, n;  /* its points: uv[2 * first] ... (n points, n >= 3) */
    double q[2];      /* a point just inside it */
    double area;      /* signed (> 0 counter-clockwise), not 0 */
    int depth;        /* out */
    long parent;      /* out: index of the smallest containing loop, -1 */
} lam_nest_loop;

/* Containment is an order: a loop can only lie inside a larger one, larger
 * meaning a greater |area|, or the same |area| and a lower index. Loops of
 * equal area that take each other's inner point (overlapping, or nearly
 * coincident) then nest one way, never both: no loop is its own ancestor.
 * Every method counts only larger loops. */
static inline int lam_nest_larger(const lam_nest_loop *loops, size_t a, size_t b)
{
    double x = fabs(loops[a].area), y = fabs(loops[b].area);
    return x > y || (x == y && a < b);
}

/* Set depth and parent of loops[0 .. nloops) whose points are in uv.
 * Errors: LAM_ENOMEM. */
int lam_nest(const double *uv, lam_nest_loop *loops, size_t nloops, lam_error *err);

/* The same with a chosen method, for tests: 0 each against each other,
 * 1 the tree sweep (*agreed set to 0 when it had to fall back, else 1),
 * 2 the sweep testing every active edge. */
int lam_nest_method(const double *uv, lam_nest_loop *loops, size_t nloops, int method, int *agreed,
                    lam_error *err);

#endif
