/* Supports for powder-bed parts (issue 27, docs/supports.md): made in 2D,
 * layer by layer, from the run's own sections; no mesh booleans.
 *
 * The rule. A point of layer k+1 stands when the material of layer k
 * (part or support) lies within the reach r = w * tan(support_angle) of
 * it, w layer k+1's width (support_angle from the vertical: a wall leaning
 * out by r per layer builds; 90 degrees: nothing needs support). Sweeping
 * from the top down, the support of layer k is what stands on layer k+1
 * (its part and its support) and is not within r of layer k's part:
 *
 *     S[k] = ((P[k+1] u S[k+1]) - grow(P[k], r)) - grow(P[k], gap_xy)
 *
 * (grow: a round buffer, so "within r" is a distance), regions smaller than
 * support_min_area dropped. A support column so stops on the part beneath
 * and keeps r (or gap_xy) away from the walls beside it; on layer 0 it
 * stands on the plate. Then support_gap_z clears ceil(gap_z / w) layers
 * under the part; else teeth: the support's contact with the part above
 * (S[k] n P[k+1]) reaches up support_teeth.height into it (T[i]: the part
 * of layer i over the contacts of the layers below within that height).
 * Overhangs within a millionth of the reach count as standing: sections of
 * a chamfer at exactly the critical angle land on the reach itself.
 *
 * Everything is in the run's layer plane (u, v); the GEOS grid comes from
 * the largest coordinate of all the layers, so the supports depend on the
 * layers only. */
#ifndef LAM_SUPPORT_H
#define LAM_SUPPORT_H

#include <stddef.h>

#include "error.h"
#include "hatch.h"
#include "slice.h"

typedef struct lam_supports lam_supports;

/* The supports of layers[0..n) of one run (bottom to top, one frame; each
 * stands on the one before it: every layer of the run, or the subset a
 * recipe plans) under cfg (cfg->type is not looked at: regions are made
 * for any type), kept by each layer's run index (lam_layer.index). *out is
 * the caller's (lam_supports_free). Errors: LAM_ENOMEM, LAM_EGEOM (the
 * layer and the stage in err). */
int lam_supports_make(const lam_layer *const *layers, size_t n, const lam_support_cfg *cfg, lam_supports **out,
                      lam_error *err);

/* Run indices 0 .. n-1 without support, for a caller that sets its own regions
 * (lam_supports_set: Lua's support generators). NULL: out of memory. */
lam_supports *lam_supports_new(size_t n);

/* Layer i's support region becomes R (taken: freed with s, or at once on
 * an error; NULL: none). Its teeth are none. LAM_OK, LAM_EUSAGE (i out of
 * range). */
int lam_supports_set(lam_supports *s, size_t i, lam_layer *R);

/* The support region and the teeth of the layer of run index i (inside the part), or NULL when
 * it has none (i out of range: NULL). Borrowed from s. */
const lam_layer *lam_supports_region(const lam_supports *s, size_t i);
const lam_layer *lam_supports_teeth(const lam_supports *s, size_t i);

/* The overhang of the layer of run index i: its part beyond the reach of
 * the part of the layer below (what needs support), or NULL: none (and
 * for layers lam_supports_set made). Borrowed from s. */
const lam_layer *lam_supports_overhang(const lam_supports *s, size_t i);

/* The area of the support region of the layer of run index i (0 without
 * one). */
double lam_supports_area(const lam_supports *s, size_t i);

void lam_supports_free(lam_supports *s);

/* What does not stand (the rule above) on each layer of layers[0..n):
 * over[i] the area of layer i's part beyond the reach of layer i-1's part,
 * and, with s, left[i] that of layer i's part and support beyond the reach
 * of layer i-1's part and support (s NULL: left = over). Layer 0 stands on
 * the plate (0). Errors as lam_supports_make. */
int lam_supports_unsupported(const lam_layer *const *layers, size_t n, const lam_supports *s, double angle,
                             double *over, double *left, lam_error *err);

/* The walls a plan draws: cfg's support_type, block when it is none (the
 * supports were given, by a recipe: planned as blocks). */
int lam_support_walls(const lam_support_cfg *cfg);

/* The support vectors of the layer of run index i under cfg into out (appended, kind
 * LAM_KIND_SUPPORT, walls as lam_support_walls says): walls support_spacing apart on the grid of the run's
 * plane (lines: along u; grid and block: along u and v; block also the
 * region's outline), with windows where support_perforation asks, and
 * the teeth: the walls through the teeth region cut into teeth of
 * support_teeth.width every support_teeth.spacing. Nothing for a layer
 * without support. Errors: LAM_ENOMEM, LAM_EGEOM, LAM_EUSAGE
 * (a spacing so small the layer would get over 50 million vectors). */
int lam_support_vectors(const lam_supports *s, size_t i, const lam_support_cfg *cfg, lam_hatches *out,
                        lam_error *err);

#endif
