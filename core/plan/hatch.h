/* Scan strategies for powder-bed machines (SPEC 4.5): the hatch vectors
 * that fill a layer's solid region, its skin regions, and the exposure and
 * time bookkeeping of the vectors a planner emits.
 *
 * Geometry is in the layer plane (u, v). A layer's region is its material
 * under the fill rule (solids minus the holes directly inside them). The
 * hatch area is the region shrunk by the spot compensation, the contour
 * passes after the first (contour_distance each) and hatch_offset. Skins
 * (skin_layers > 0): down-skin is the region not covered by every one of
 * the skin_layers layers below, up-skin the rest not covered by every one
 * of the layers above, core what remains; a layer beyond the model counts
 * as empty, so the first layer is down-skin and the last up-skin.
 *
 * Hatch lines of one region lie at (k + 1/2) * hatch_distance from the
 * origin across the direction at angle hatch_angle + index *
 * layer_angle_increment (degrees, counter-clockwise from u), so lines of
 * neighbouring stripes and islands of one direction continue each other.
 * Where a line crosses the area's boundary is decided by the half-open
 * rule (an edge holds its lower end), so a line through a vertex is cut
 * once. Strategies:
 *  - lines: the whole area, one block;
 *  - stripes: bands stripe_width wide along the hatch direction, each grown
 *    by stripe_overlap / 2 on both sides (neighbours overlap by
 *    stripe_overlap); the band grid moves by stripe_width times the
 *    fractional part of index * 0.618034 each layer; one block per band;
 *  - islands: squares island_size wide on a grid of the layer plane, grown
 *    by island_overlap / 2 on each side, hatched at the layer's angle when
 *    i + j is even and 90 degrees more when odd; the grid moves by
 *    island_size times the fractional parts of index * 0.618034 (u) and
 *    index * 0.381966 (v) each layer; one block per island, in the order
 *    sequential (rows of increasing v, each of increasing u), checker (the
 *    even squares, then the odd ones, each sequentially) or random (a
 *    shuffle seeded by seed and the layer index: always the same).
 * Orders within a block: meander (successive lines run opposite ways),
 * unidirectional (all along the hatch direction), greedy (from the first
 * vector, always the vector with the nearest end next, entered at that
 * end). Vectors shorter than min_vector are dropped first. */
#ifndef LAM_HATCH_H
#define LAM_HATCH_H

#include "vocab.h"

#include <stddef.h>

#include "error.h"
#include "slice.h"

typedef enum lam_strategy { LAM_HATCH_NONE, LAM_HATCH_LINES, LAM_HATCH_STRIPES, LAM_HATCH_ISLANDS } lam_strategy;
typedef enum lam_hatch_order { LAM_ORDER_MEANDER, LAM_ORDER_UNIDIRECTIONAL, LAM_ORDER_GREEDY } lam_hatch_order;
typedef enum lam_island_order { LAM_ISLANDS_SEQUENTIAL, LAM_ISLANDS_CHECKER, LAM_ISLANDS_RANDOM } lam_island_order;

/* The most layers a skin may reach (skin_layers). */
#define LAM_SKIN_MAX 100

/* A region (vocab.h's first kinds: contour, core, up-skin, down-skin) has
 * its own exposure; the hatch regions also their own hatch parameters
 * (profile sections contour:, upskin:, downskin:). */

typedef struct lam_exposure {
    double power;            /* laser power (machine units, e.g. W) */
    double speed;            /* scan speed, model units per second; 0: unknown */
    double point_distance;   /* point exposure: distance between points (0: continuous) */
    double exposure_time;    /* point exposure: seconds per point */
} lam_exposure;

/* The hatch parameters of one region type. */
typedef struct lam_scan {
    int strategy;            /* lam_strategy */
    double distance;         /* hatch_distance, > 0 */
    double angle;            /* hatch_angle, degrees */
    double angle_increment;  /* layer_angle_increment, degrees per layer */
    int order;               /* lam_hatch_order */
    double min_vector;
    double stripe_width, stripe_overlap;
    double island_size, island_overlap;
    int island_order;        /* lam_island_order */
    int seed;
    lam_exposure exposure;
} lam_scan;

/* Supports (support.h): what holds a part's overhangs up. */
typedef enum lam_support_type { LAM_SUPPORT_NONE, LAM_SUPPORT_BLOCK, LAM_SUPPORT_GRID, LAM_SUPPORT_LINES } lam_support_type;

typedef struct lam_support_cfg {
    int type;                /* lam_support_type */
    double angle;            /* the steepest overhang built without support, degrees from
                                the vertical (90: none needs support) */
    double gap_xy, gap_z;    /* kept between support and the part: across, below it */
    double min_area;         /* a support region smaller than this is not made */
    double spacing;          /* between the support's walls */
    double height;           /* builds: the part raised this much above the plate */
    double teeth_height, teeth_width, teeth_spacing; /* walls reaching into the part */
    double perf_width, perf_spacing; /* square windows in the walls (0: none) */
} lam_support_cfg;

/* Everything hatching a layer needs. */
typedef struct lam_scan_cfg {
    lam_scan type[LAM_REGIONS];  /* [LAM_KIND_CONTOUR]: only its exposure is used */
    int contour_count;       /* contour passes */
    double contour_distance; /* between passes */
    double compensation;     /* the first pass's inset (half the spot, or 0) */
    double hatch_offset;     /* between the innermost pass and the hatches */
    int contours_first;
    int skin_layers;         /* 0: no skins (everything is core) */
    double jump_speed, jump_delay, recoat_time;
    lam_support_cfg support; /* type[LAM_KIND_SUPPORT] is its exposure */
} lam_scan_cfg;

/* Whether a plan of cfg can have vectors of region k (lam_vec_kind below
 * LAM_REGIONS): the contour with passes, the core hatched, a skin with
 * skins and its hatching, the support with a support_type. What the job's
 * exposures list (a single part's run and each part of a build). */
int lam_scan_region_used(const lam_scan_cfg *cfg, int k);

/* The distance between region k's vectors: the spot for the contour, the
 * wall spacing for the support, else the region's hatch distance. */
double lam_scan_region_distance(const lam_scan_cfg *cfg, double spot, int k);

/* Whether cfg hatches anything: some hatch type's strategy is not none. */
int lam_scan_hatches(const lam_scan_cfg *cfg);

/* Whether a build-time estimate means something for cfg: it hatches, or
 * gives a speed, a point exposure time or a recoat time. */
int lam_scan_estimates(const lam_scan_cfg *cfg);

/* A block: consecutive vectors of one type (one stripe, one island, or a
 * whole region for lines). */
typedef struct lam_hatch_block {
    int type;                /* lam_vec_kind (vocab.h): a hatch region */
    size_t first, n;         /* vectors [first, first + n) */
    double angle;            /* the block's hatch direction, degrees */
} lam_hatch_block;

typedef struct lam_hatches {
    double *v;               /* 4 per vector: u0 v0 u1 v1 (exposed from 0 to 1) */
    size_t nv, cap_v;
    lam_hatch_block *blocks;
    size_t nblocks, cap_blocks;
    double area[LAM_REGIONS];   /* the region's area per type (not shrunk) */
} lam_hatches;

/* Hatch layer L: its region split into core, up-skin and down-skin by the
 * layers below[0..nbelow) (below[0] the adjacent one) and above[0..nabove)
 * (cfg->skin_layers of each are used; missing ones count as empty), each
 * part's hatch area hatched with its type's parameters. Blocks are
 * appended to out in the order core, up-skin, down-skin; out->area is set.
 * Errors: LAM_ENOMEM, LAM_EGEOM (GEOS failed), LAM_EUSAGE (a hatch
 * distance or island size so small a layer would get over 50 million
 * vectors). */
int lam_hatch_layer(const lam_layer *L, const lam_layer *const *below, size_t nbelow, const lam_layer *const *above,
                    size_t nabove, const lam_scan_cfg *cfg, lam_hatches *out, lam_error *err);

/* Empty h for reuse (keeps its arrays). */
void lam_hatches_clear(lam_hatches *h);
void lam_hatches_free(lam_hatches *h);

/* Start a new block of `type` and `angle` in h / append vector (u0, v0) ->
 * (u1, v1) to h's last block. Return LAM_OK, LAM_ENOMEM (LAM_EUSAGE: no
 * block yet). */
int lam_hatches_add_block(lam_hatches *h, int type, double angle);
int lam_hatches_add(lam_hatches *h, double u0, double v0, double u1, double v1);

/* Time of a job or a layer, in seconds, and what it is made of. */
typedef struct lam_scan_time {
    size_t layers, contours, vectors, jumps;
    double exposure_length, jump_length;    /* model units */
    double hatch_length;                    /* of exposure_length: the hatch vectors' */
    double exposure, jump, recoat;          /* seconds */
} lam_scan_time;

/* Total of t (exposure + jump + recoat). */
double lam_scan_time_total(const lam_scan_time *t);

/* Add a with b into a. */
void lam_scan_time_add(lam_scan_time *a, const lam_scan_time *b);

/* The scanner's part of the estimate: exposing a path of `length` with e
 * (length / speed, or for point exposure floor(length / point_distance)
 * + 1 points (a closed contour: one fewer, at least one) x exposure_time;
 * 0 without a speed), and the jump from the
 * previous path's end (none before a layer's first path): distance /
 * jump_speed + jump_delay. pos/have_pos is the scanner, updated to `end`. */
void lam_scan_time_path(lam_scan_time *t, const lam_scan_cfg *cfg, const lam_exposure *e, const double start[2],
                        const double end[2], double length, int contour, double pos[2], int *have_pos);

#endif
