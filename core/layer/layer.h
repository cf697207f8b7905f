/* Layers: one slab of a sliced model, its contours in the layer frame
 * (frame.h) with their nesting, and what gap closing left open. The slicer
 * (slice.h) makes them; contour.h, offset.h and winding.h work on them. */
#ifndef LAM_LAYER_H
#define LAM_LAYER_H

#include <stddef.h>

typedef enum lam_kind { LAM_SOLID = 0, LAM_HOLE = 1 } lam_kind;

typedef struct lam_contour {
    size_t first, n;         /* points uv[2*first .. 2*(first+n)) of the layer */
    int depth;               /* nesting depth among the layer's contours */
    long parent;             /* index of the contour directly around it, -1 if none */
    lam_kind kind;           /* solid at even depth, hole at odd depth */
    double area;             /* signed: > 0 counter-clockwise (solids), < 0 holes */
    double perimeter;
    double bbox[4];          /* umin vmin umax vmax */
} lam_contour;

/* An open polyline that gap closing could not close. */
typedef struct lam_open_end {
    double start[2], end[2];
} lam_open_end;

typedef struct lam_layer {
    size_t index;            /* 0-based */
    double floor, ceiling, width;
    double cut;              /* height of the section along w */
    double *uv;              /* 2 per point, owned */
    size_t npoints;
    lam_contour *contours;   /* parents before children; owned */
    size_t ncontours;
    double gap;              /* the gap-closing tolerance used */
    size_t gaps_closed;      /* gaps bridged by the gap-closing pass */
    double max_gap;          /* largest bridged gap */
    size_t slivers;          /* loops dropped for (nearly) no area (contour.h) */
    size_t twins;            /* coincident loops cancelled in pairs (contour.h) */
    lam_open_end *open;      /* polylines left open (dropped from contours) */
    size_t nopen;
} lam_layer;

/* Free a layer (NULL is fine). */
void lam_layer_free(lam_layer *layer);

/* A copy of layer L with arrays of its own (NULL when out of memory). */
lam_layer *lam_layer_clone(const lam_layer *L);

#endif
