/* The slicer: a plane sweep through a lam_model (thesis chapter 3).
 *
 * Layer i is the slab [a(i-1), a(i)] along the slice axis w; its contours
 * are the model's cross section at the cut height (floor, middle or ceiling
 * of the slab), in the layer frame (u, v, w), which is right-handed so
 * "counter-clockwise" means seen from +w.
 *
 * Sweep: each edge that crosses a cut is scheduled into the bucket of the
 * first layer whose cut it crosses (a binary search over the cut heights),
 * inserted into an active set when the sweep reaches that layer and
 * dropped lazily once below the plane, so a run costs O(E log S + S + K)
 * for E edges, S layers and K segments out — never a sort of all edges,
 * nor a pass over all triangles per layer. Layers come out one at a time
 * (lam_slicer_next), so memory is the model plus the layers in flight.
 *
 * Robustness (SPEC 3.2): a vertex exactly on a cutting plane is treated as
 * an infinitesimal step below the plane for floor and middle cuts and above
 * it for ceiling cuts (symbolic perturbation), so every intersection lies on
 * an edge interior, each edge's point is computed once from its lower and
 * upper ends as (1-t)*lo + t*hi (bitwise identical from both triangles and
 * exact at the ends), and segments are chained by edge identity. */
#ifndef LAM_SLICE_H
#define LAM_SLICE_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "frame.h"
#include "layer.h"
#include "model.h"

typedef enum lam_cut { LAM_CUT_FLOOR, LAM_CUT_MIDDLE, LAM_CUT_CEILING } lam_cut;

/* The default gap-closing tolerance scales with the model: gap < 0
 * (LAM_GAP_AUTO) means LAM_GAP_REL times the model's size, the diagonal of
 * its bounding box (0.05 for a part of 100 units across, PrusaSlicer's
 * closing radius in millimetres), so the same open scan in metres and in
 * millimetres gives the same sections; at most gap_limit when that is > 0
 * (a machine's 0.05 mm in its own units, lam_profile_gap_limit). */
#define LAM_GAP_AUTO (-1.0)
#define LAM_GAP_REL 5e-4
#define LAM_GAP_MM 0.05

/* A loop whose |area| is at most (LAM_SLIVER_REL * the model's size)^2 is a
 * sliver (SPEC 3.3: dropped and counted): far above the rounding of an
 * area (DBL_EPSILON * size^2), far below any feature a machine builds. */
#define LAM_SLIVER_REL 1e-6

typedef struct lam_slice_opts {
    lam_frame frame;
    lam_cut cut;
    double gap;              /* close open polylines whose ends are this close; 0 disables;
                                LAM_GAP_AUTO (< 0): lam_default_gap of the model.
                                Polylines still open are dropped from the layer and listed
                                in lam_layer.open: the caller decides whether that fails. */
    double gap_limit;        /* > 0: the automatic gap is at most this */
    int fill_nonzero;        /* 0: even-odd (the thesis's nesting parity); 1: non-zero
                                winding, overlapping shells merge (winding.h) */
    /* Layer boundaries, one of: */
    double width;            /* > 0: uniform layers from the model's minimum;
                                0: lam_default_width of the extent */
    const double *widths;    /* a(i) = a(i-1) + widths[i-1], from the minimum */
    size_t nwidths;
    const double *planes;    /* explicit increasing boundaries a(0) .. a(S) */
    size_t nplanes;
    size_t max_layers;       /* most layers a run may make; 0: LAM_DEFAULT_MAX_LAYERS */
} lam_slice_opts;

/* The default of max_layers: a metre at a micrometre, far above any real
 * build, far below a width typed wrong (-w 1e-6 on a 100 mm part is 10^8). */
#define LAM_DEFAULT_MAX_LAYERS 1000000

/* Fill opts with the defaults: axis z, middle cut, default gap, width 0
 * (meaning: lam_default_width of the model). */
void lam_slice_opts_init(lam_slice_opts *o);

/* 1/100 of the extent, rounded down to 1, 2, 2.5 or 5 times a power of ten. */
double lam_default_width(double extent);

/* The automatic gap-closing tolerance for a model of this size (the
 * diagonal of its bounding box): LAM_GAP_REL * size, at most limit when
 * limit > 0. */
double lam_default_gap(double size, double limit);

typedef struct lam_slicer lam_slicer;

/* Prepare a sweep over model with opts (copied). The model must outlive the
 * slicer. Errors: LAM_EUSAGE for a negative or non-finite width, a width
 * in the list <= 0, widths that do not cover the model, planes not strictly
 * increasing or fewer than two; LAM_ELIMIT for more layers than
 * max_layers (the message gives both numbers), found before anything the
 * size of the run is allocated. */
int lam_slicer_new(const lam_model *model, const lam_slice_opts *opts, lam_slicer **out,
                   lam_error *err);

/* Number of layers the run will produce. */
size_t lam_slicer_count(const lam_slicer *s);

/* Layer boundaries a(0) .. a(S) (S + 1 values). */
const double *lam_slicer_planes(const lam_slicer *s);

/* Points of all the run's sections before points in line are merged (one
 * per edge crossing a cut): an upper bound on the contour points of the
 * run, known before slicing. */
double lam_slicer_crossings(const lam_slicer *s);

/* The model s slices (borrowed: owned by the caller of lam_slicer_new). */
const lam_model *lam_slicer_model(const lam_slicer *s);

/* Cut height of layer i (0 <= i < count). */
double lam_slicer_cut(const lam_slicer *s, size_t i);

/* The model's extent in the layer frame: umin vmin umax vmax. */
void lam_slicer_uv_bounds(const lam_slicer *s, double box[4]);

/* The gap-closing tolerance of the run (the automatic one resolved). */
double lam_slicer_gap(const lam_slicer *s);

/* The slicer's frame. */
const lam_frame *lam_slicer_frame(const lam_slicer *s);

/* Next layer in increasing order: *out is a new layer the caller frees with
 * lam_layer_free, or NULL when the run is over. */
int lam_slicer_next(lam_slicer *s, lam_layer **out, lam_error *err);

void lam_slicer_free(lam_slicer *s);

/* The bytes slicer s holds now: its schedule and its scratch (as grown so
 * far), not the model's nor the layers'. For a budget (the Lua sandbox). */
size_t lam_slicer_bytes(const lam_slicer *s);

/* A second sweep over the same run: it shares s's model, layers and
 * schedule (s must outlive it and not be freed first) and keeps its own
 * position and scratch, so threads can slice different layers at once.
 * It starts at layer 0; free it with lam_slicer_free. */
int lam_slicer_fork(const lam_slicer *s, lam_slicer **out, lam_error *err);

/* Every layer of s's run, sliced on the calling thread from the first
 * (s is left at its start): *out holds *n layers, the caller's
 * (lam_layers_free). Errors: those of lam_slicer_next, LAM_ENOMEM. */
int lam_slicer_all(lam_slicer *s, lam_layer ***out, size_t *n, lam_error *err);

/* Free layers[0..n) and the array. */
void lam_layers_free(lam_layer **layers, size_t n);

/* Make layer i (<= count) the next lam_slicer_next returns. Forward it
 * costs the edges scheduled in between, backward a sweep from the start;
 * the layers come out bit for bit as from a sweep that never jumped. */
void lam_slicer_seek(lam_slicer *s, size_t i);

#endif
