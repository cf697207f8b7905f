/* Arranging parts on the plate (issue 25, item 3).
 *
 * A part's footprint is its projection on the plate; arrangement works on
 * its footprint box (the box of the projection, in the part's own x, y
 * after rotation), so two boxes apart by the spacing keep the footprints
 * apart by at least as much. Parts with a fixed place (`at`: the centre of
 * the footprint box in plate coordinates) are honoured as given; the others
 * are placed automatically, in the order given, on rows across the plate
 * (a shelf packing: each row as high as its tallest box, boxes left to
 * right, rows front to back), skipping any spot a fixed part or the
 * plate's edge takes: never two boxes closer than the spacing, every box
 * inside the plate less its margin. For boxes of one size this holds as
 * many as a square grid of them does. The same input gives the same
 * placement.
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
    const char *name;        /* for messages and the layout */
} lam_arrange_item;

/* Place items[0 .. n) on plate p with `spacing` between footprint boxes.
 * Errors (LAM_EINVAL, nothing placed): a box larger than the plate ("part
 * NAME (120 x 80 mm) is larger than the plate"), a fixed part off the plate
 * or closer than the spacing to another fixed one (naming both), and "only
 * K of N parts fit on the plate (250 x 250, margin 5, spacing 5)" when the
 * automatic ones do not all fit. units names the length unit in messages. */
int lam_arrange(const lam_plate *p, double spacing, lam_arrange_item *items, size_t n, const char *units,
                lam_error *err);

/* The layout drawing (`lamina build --layout plate.svg`): the plate, its
 * margin, every item's footprint outline (outline[i]: npts[i] points x, y in
 * plate coordinates; NULL: its box) and name, and the lasers' fields (nf
 * boxes x0 y0 x1 y1), as SVG through w. Returns the writer's error. */
int lam_layout_svg(lam_writer *w, const lam_plate *p, const lam_arrange_item *items, size_t n,
                   const double *const *outline, const size_t *npts, const double (*fields)[4], size_t nf,
                   const char *units);

#endif
