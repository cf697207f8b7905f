/* Validation of sliced layers against the solid with Embree (SPEC 6).
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
 *   other, by the winding number of rays (rays.h).
 * Per layer, the net area (solids minus holes, by the label) must match the
 * model's own section at the cut (section.h: Green's theorem over the
 * mesh's triangles), within a tolerance from the precision the points and
 * the height were written with, and from how far the model's vertices may
 * lie from those of the mesh the layer was made from (lam_validate_opts.
 * moved: the repair's weld when the layers come from the mesh before
 * repair and the model is the repaired one).
 *
 * Layers whose outlines were closed across gaps or left open (dropped), or
 * may have been (lam_validate_opts.gaps_unknown), are compared too, with a
 * tolerance that allows for the gap closing (the loss check): a bridge of
 * length at most gap stands where the closed model's section runs between
 * the same two ends (across the filled hole); taking that section to stay
 * within gap / 2 of the bridge, the area between them is at most gap / 2 x
 * the bridge's length, so the layer may differ by gap / 2 x the length
 * bridged (gaps_closed x gap when the slicer counted its bridges, else the
 * layer's perimeter); at least LAM_VALIDATE_LOSS_REL of the section (for
 * fills that are not flat) and the precision tolerance. An outline dropped
 * whole is not allowed for: losing it (a solid) or filling it (a hole) is
 * what the check is for. area_lost says how much, signed.
 *
 * Not compared, and said so (area_open): models with boundary edges or
 * orientation conflicts, whose section does not close. One-sided (net at
 * most the section) under the non-zero fill rule when two bodies meet the
 * plane, where the section counts their overlap twice.
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
#include "rays.h"
#include "section.h"
#include "slice.h"

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
    int pass;                /* read back with contour passes (lam_validate_opts):
                                the pass it was found at (0 the outermost), -1 when
                                no edge told; 0 otherwise */
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
    double area_lost;        /* when compared: section_area - net_area (> 0 the program
                                lacks area, < 0 it holds area the model has not) */
    int area_loose;          /* 1 when compared with the loss check's tolerance (above) */
    int area_open;           /* 1 when not compared because the model's section does not
                                close (boundary edges or orientation conflicts) */
    const char *area_why;    /* static text: why not compared, or what the comparison was */
} lam_layer_check;

/* The least a layer compared by the loss check may differ from the section
 * without failing, as a fraction of the section (validate.h, above): a
 * thousandth, well above the difference a filled hole's triangles make
 * against a bridge across it (a sagitta of a gap's width), well below a
 * dropped outline of any feature a machine builds. */
#define LAM_VALIDATE_LOSS_REL 1e-3

/* How a layer is checked. */
typedef struct lam_validate_opts {
    int fill_nonzero;        /* the fill rule it was made with: 0 even-odd, 1 non-zero */
    double quantum_uv;       /* how far a written coordinate may be from the true one
                                (half a unit in its last printed place); 0 for layers
                                straight from the slicer */
    double quantum_h;        /* the same for the written height */
    /* Contour passes of a layer read back (depth < 0), as the SLS planner
     * writes them (planner.h): `passes` of them (0 or 1: one), the first
     * `inset` inside the section (beam_offset: half the spot), each next
     * `pass_distance` further in. A contour of pass k lies inset + k *
     * pass_distance inside the section: its label's material side is
     * tested as usual, its void side just before and just beyond that
     * distance (material, then void), the pass found from the first edge
     * decided (the nearest k that fits); its label against the nesting
     * counts the k passes around it; the net area compared is the first
     * pass's (at most the section when inset > 0: an inset region is
     * smaller). */
    int passes;
    double inset, pass_distance;
    /* The mesh the layers were made from against the model the check uses
     * (validate.h): `moved`, how far the model's vertices may lie from the
     * mesh's (the repair's weld tolerance when the model is a repaired copy
     * of it; 0: the same mesh); `gap`, the gap-closing tolerance the layers
     * were made with (0: none); `gaps_unknown`, 1 when a layer may have had
     * gaps closed or outlines dropped without saying so (a program read
     * back that was sliced from the mesh before repair): every layer is
     * then compared by the loss check. */
    double moved, gap;
    int gaps_unknown;
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
int lam_validate_layer(lam_rays *v, const lam_layer *L, const lam_frame *f, const lam_validate_opts *o,
                       lam_layer_check *out, lam_error *err);

/* Static text naming one LAM_VP_* bit ("material", "direction", ...). */
const char *lam_validate_problem_name(unsigned bit);

/* Release out->items and zero *out (NULL is fine). */
void lam_layer_check_free(lam_layer_check *c);

#endif
