/* Arranging parts on the plate (issue 25, item 3).
 *
 * A part's footprint is its projection on the plate; arrangement works on
 * its footprint box (the box of the projection, in the part's own x, y
 * after rotation), so two boxes apart by the spacing keep the footprints
 * apart by at least as much. Parts with a fixed place (`at`: the centre of
 * the footprint box in plate coordinates) are honoured as given; the others
 * are placed automatically on rows across the plate, a shelf packing
 * (first fit, decreasing height):
 * - order: by box depth (y extent), deepest first, ties by index (stable),
 *   so each row is as deep as its first box and the shallower ones after
 *   it fill the gaps;
 * - each box goes into the first row, front to back, that has room for it
 *   at the row's front edge, as far left as the plate, the boxes before it
 *   and the fixed parts allow; failing that it opens a new row behind the
 *   last one (spacing behind it), or further back if fixed parts or a round
 *   plate's edge leave it no room there;
 * - never two boxes closer than the spacing (their gap in x or in y is at
 *   least the spacing), every box inside the plate less its margin.
 * Rectangular plates are filled from the front-left corner (margin,
 * margin), not centred. Round plates: a box is inside when its four
 * corners are within diameter / 2 - margin of the centre; rows run across
 * the circle and start at its left edge, and the rows' front-to-back
 * offset is the best (most parts placed, the first of equals) of a few:
 * the centred stacks of rows of the deepest box, the front edge, and 16
 * steps through one row pitch. For boxes of one size this holds as many
 * as a square grid of them (pitch: box + spacing) does: a rectangle's
 * grid from its corner, a circle's centred grid. Comparisons allow 1e-9
 * of the plate's size in the "fits" direction only, so a row that exactly
 * fills the width fits; a box's edge never passes the margin by more than
 * that (a box that would is moved back inside, so it may come that much
 * closer to its neighbour than the spacing). The same input gives the
 * same placement.
 *
 * Plate coordinates: from the front-left corner of a rectangular plate
 * (x across its width, y across its depth), from the centre of a round
 * one. */
#ifndef LAM_ARRANGE_H
#define LAM_ARRANGE_H

#include <stddef.h>

#include "error.h"
#include "writer.h"

typedef struct lam_plate {
    int round;               /* 1: a round plate of `diameter`; 0: width x depth */
    double width, depth, diameter;
    double margin;           /* kept free along the edge */
} lam_plate;

typedef struct lam_arrange_item {
    double box[4];           /* the footprint box, part coordinates: xmin ymin xmax ymax */
    int fixed;               /* 1: placed at `at` */
    double at[2];            /* in: fixed place; out: where the box's centre is on the plate */
    double shift[2];         /* out: what to add to the part's x, y to place it */
    const char *name;        /* for messages and the layout (NULL: "#" and its 1-based index) */
} lam_arrange_item;

/* Place items[0 .. n) on plate p with `spacing` between footprint boxes:
 * fills every item's at (the box's centre on the plate) and shift (at less
 * the box's centre), a fixed item's at left as given. units (NULL or "":
 * none) names the length unit in messages. Errors, LAM_EINVAL, with no
 * item changed (a failed call reports nothing as placed):
 * - a plate, margin, spacing, box or fixed place that is negative or not
 *   finite, a box with xmax < xmin or ymax < ymin, a margin that leaves
 *   no room;
 * - "part NAME (120 x 80 mm) is larger than the plate (100 x 100 mm,
 *   margin 5)": no place on the plate holds it (the first such part);
 * - "fixed part NAME at (300, 20) is off the plate (250 x 250 mm, margin
 *   5)": its box passes the margin;
 * - "fixed parts A and B are closer than the spacing (5 mm)" (or "...
 *   overlap"): the first such pair by index;
 * - "only K of N parts fit on the plate (250 x 250 mm, margin 5, spacing
 *   5); not placed: NAME and M more": K counts the fixed parts and the
 *   automatic ones the packing placed, N all parts; NAME is the first by
 *   index left out.
 * LAM_ENOMEM. */
int lam_arrange(const lam_plate *p, double spacing, lam_arrange_item *items, size_t n, const char *units,
                lam_error *err);

/* A part's footprint outline from its mesh: the convex hull of the
 * vertices' (x, y) (xyz: nverts points x, y, z), by Andrew's monotone
 * chain. *out_xy (malloc'd, the caller frees) gets *out_n points x, y
 * counter-clockwise from the lowest x (lowest y among equal x), without
 * repeated or collinear points: 1 point when every vertex projects to the
 * same one, 2 when they project onto a segment. Errors: LAM_EINVAL (no
 * vertices, a coordinate not finite), LAM_ENOMEM; *out_xy NULL and
 * *out_n 0 then. */
int lam_footprint_hull(const double *xyz, size_t nverts, double **out_xy, size_t *out_n, lam_error *err);

/* The footprint box of the same vertices: box = xmin ymin xmax ymax of
 * their (x, y). Errors: LAM_EINVAL (no vertices, a coordinate not
 * finite; box untouched). */
int lam_footprint_box(const double *xyz, size_t nverts, double box[4], lam_error *err);

/* The layout drawing (`lamina build --layout plate.svg`): the plate, its
 * margin (dashed, when there is one), every item's footprint outline (outline[i]: npts[i]
 * points x, y in plate coordinates; outline NULL or outline[i] NULL: its
 * box placed by shift) and name (escaped) at its at, and the lasers'
 * fields (nf boxes x0 y0 x1 y1, drawn as translucent rectangles labelled
 * "laser 1", ...), a scale bar in units (NULL: none named), y up (the
 * plate's front at the bottom), as SVG through w. Elements carry a class
 * (plate, margin, part, name, field, field-label, scalebar), one part and
 * one name per item, one field and one label per field. Returns the
 * writer's error code (lam_writer_error tells it). */
int lam_layout_svg(lam_writer *w, const lam_plate *p, const lam_arrange_item *items, size_t n,
                   const double *const *outline, const size_t *npts, const double (*fields)[4], size_t nf,
                   const char *units);

#endif
