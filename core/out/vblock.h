/* The viewer's layer blocks (docs/viewer.md, "A layer's block"): one
 * layer's section contours and vectors as bytes the page's script decodes
 * when the layer is shown. Coordinates are the layer frame's (u, v) in
 * whole quanta, each point the difference from the one before it in the
 * block, every number a LEB128 varint (signed ones zigzag); vectors go in
 * runs of one kind and one attribute row; jumps are a flag on the vector
 * after them. A hatch vector takes 4 to 8 bytes where binary CLI takes 16.
 *
 *     lam_vblock b;
 *     lam_vblock_init(&b, quantum);
 *     per layer: lam_vblock_contour(&b, ...)...; lam_vblock_vector(&b, v)...;
 *                lam_vblock_finish(&b, &out); write out; lam_vblock_reset(&b);
 *     lam_vblock_free(&b); */
#ifndef LAM_VBLOCK_H
#define LAM_VBLOCK_H

#include <stddef.h>

#include "buf.h"
#include "vocab.h"
#include "vstream.h"

/* The largest coordinate in quanta a block holds: points beyond are put at
 * this bound (a difference of two stays below 2^31, what the page's
 * 32-bit arithmetic reads). */
#define LAM_VBLOCK_MAX_Q (1LL << 29)

typedef struct lam_vblock {
    double quantum;          /* one step, in the job's units */
    long long cu, cv;        /* the cursor: the last point written */
    lam_attrs *rows;         /* the layer's attribute rows */
    size_t nrows, cap_rows, last_row;
    lam_buf contours, runs, run; /* encoded parts; run: the open run's vectors */
    size_t ncontours, nruns, run_n;
    lam_buf marks;           /* the marked regions (support, overhang), their own cursor */
    size_t nmarks;
    long long mu, mv;
    int run_kind;
    size_t run_row;
    int jump;                /* a jump came: the next vector has the flag */
    int failed;              /* out of memory: sticky */
} lam_vblock;

/* A block encoder with coordinate step quantum (> 0), holding nothing. */
void lam_vblock_init(lam_vblock *b, double quantum);

/* The quantum for a run: 0.1 µm in the job's units (1e-4 when the units are
 * not known), or more when box (u0 v0 u1 v1, the run's extent in the layer
 * plane) would not fit LAM_VBLOCK_MAX_Q / 4 steps from the origin. */
double lam_vblock_quantum(const char *units, const double box[4]);

/* Add a section contour of n points uv (2 doubles each, no repeated
 * closing point): solid or hole, at nesting depth. */
void lam_vblock_contour(lam_vblock *b, const double *uv, size_t n, int solid, int depth);

/* The regions a block may mark (docs/viewer.md): numbers in the page. */
enum { LAM_VBLOCK_SUPPORT = 1, LAM_VBLOCK_OVERHANG = 2 };

/* Add a contour of a marked region (LAM_VBLOCK_SUPPORT, _OVERHANG), as
 * lam_vblock_contour: written after the vectors, a block without marks
 * ends at its vectors as before. */
void lam_vblock_mark(lam_vblock *b, int region, const double *uv, size_t n, int solid, int depth);

/* Add the stream's next vector (vstream.h), in order. Jumps are not
 * written as vectors: they become the flag of the vector after them. */
void lam_vblock_vector(lam_vblock *b, const lam_vec *v);

/* Append the layer's block to out. LAM_OK, or LAM_ENOMEM when this or any
 * call since the reset ran out of memory. */
int lam_vblock_finish(lam_vblock *b, lam_buf *out);

/* Start the next layer: forget the layer's contents, keep the memory. */
void lam_vblock_reset(lam_vblock *b);

/* Free what b holds (b may be NULL). */
void lam_vblock_free(lam_vblock *b);

#endif
