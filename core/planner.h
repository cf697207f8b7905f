/* Planners: from layers to machine operations on a lam_sink (plan.h).
 *
 * LADRP (thesis 4.1, SPEC 4.1): per layer, scan lines one bead width d
 * apart from the top of the layer down, at y0 - k*d (never accumulated);
 * a line through a vertex or along an edge is evaluated an infinitesimal
 * step below (the sweep direction), so a first line on the top edge
 * deposits the full width. Intersections sorted along the line pair up as
 * deposit / move by even-odd parity (the labels' nesting). Lines alternate
 * direction (boustrophedon) unless `alternate` is off. Each layer starts
 * with a travel to one bead above its first line and a step down onto it,
 * as in the thesis sample. A raster angle rotates the scan lines
 * (angle + index * angle_step degrees, counter-clockwise in the layer).
 *
 * Optional perimeter passes go round the contours before the raster,
 * offset inward with GEOS (offset.h).
 *
 * SLS (thesis 4.2, SPEC 4.2): every contour of the layer as one block,
 * solids counter-clockwise, holes clockwise, in the layer's order;
 * optionally offset by half the spot width (beam compensation). With
 * scan strategies (SPEC 4.5, hatch.h): contour_count passes (the first
 * at the compensation, each next contour_distance further in) and the
 * hatch blocks of the layer, contours first or last. */
#ifndef LAM_PLANNER_H
#define LAM_PLANNER_H

#include "hatch.h"
#include "plan.h"
#include "slice.h"

typedef enum lam_plan_kind { LAM_PLAN_LADRP, LAM_PLAN_SLS } lam_plan_kind;

/* Statistics of LADRP planning (lengths in the layer plane). */
typedef struct lam_ladrp_stats {
    size_t lines, deposits;
    double deposit_length, travel_length;
} lam_ladrp_stats;
typedef lam_ladrp_stats lam_ladrp_stats_out;

typedef struct lam_plan_opts {
    lam_plan_kind kind;
    const char *name, *units;    /* for the job header */
    double bead;                 /* LADRP bead width / SLS spot width, > 0 */
    double rate, travel_rate;    /* feed rates */
    int frame_machine;           /* output in the layer frame (u, v, w) */
    /* LADRP */
    int first_center;            /* first line half a bead inside the top edge */
    double angle, angle_step;    /* degrees */
    int alternate;               /* boustrophedon */
    double min_deposit;          /* skip deposits shorter than this */
    int islands;                 /* LADRP: raster each island (an outer contour and
                                    what it holds) on its own, nearest next, instead
                                    of whole scan lines across the layer */
    int perimeters;              /* LADRP: passes around the contours, the first
                                    offset d/2 inward, each next one d further; the
                                    raster then fills what lies inside them */
    lam_ladrp_stats_out *totals; /* if not NULL: LADRP lines, deposits and lengths of
                                    the whole run are added here */
    /* SLS */
    int beam_offset;             /* contours moved inward by half the spot (holes
                                    outward), so the beam's edge traces the part */
    lam_scan_cfg scan;           /* SLS: contour passes, hatching, skins, exposure
                                    and time (hatch.h); the planner sets
                                    scan.compensation: half the spot with
                                    beam_offset, else 0 */
    lam_scan_time *time;         /* SLS: if not NULL, the job's estimate is added here */
    double *layer_time;          /* SLS (lam_plan_run): if not NULL, room for every
                                    layer: each one's estimate, seconds */
} lam_plan_opts;

/* Defaults: SLS, bead 1, rates 0, model frame, edge, 0 degrees, alternate;
 * one contour pass, contours first, no hatching. */
void lam_plan_opts_init(lam_plan_opts *o);

struct lam_profile;

/* The planning values of a machine profile (process, bead or spot width,
 * rates, frame, raster and SLS options); o is initialised first. The
 * profile's strings are borrowed: it must outlive o. */
void lam_plan_opts_from_profile(lam_plan_opts *o, const struct lam_profile *p);

/* Called with every layer before it is planned (reports, previews). A
 * non-zero return stops the run with that code. */
typedef int (*lam_layer_cb)(void *ctx, const lam_layer *layer, lam_error *err);

/* Plan a whole slicing run into sink: begin, every layer, end. The sink is
 * not destroyed. Returns LAM_OK or the first error (from the slicer, a
 * planner, the sink or the callback). */
int lam_plan_run(lam_slicer *s, const lam_model *m, const lam_plan_opts *o, const lam_sink *sink,
                 lam_layer_cb cb, void *cbctx, lam_error *err);

/* Plan one layer (exposed for tests and Lua). pos: the stage position in
 * the output frame, updated; laser: the laser state (-1 unknown), updated. */
int lam_plan_ladrp_layer(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o,
                         const lam_sink *sink, double pos[3], int *laser, lam_ladrp_stats *st,
                         lam_error *err);

/* What SLS planning carries from layer to layer. */
typedef struct lam_sls_state {
    size_t part;             /* the part id of every contour and hatch block (1) */
    double pos[2];           /* the scanner (layer plane), for jumps */
    int have_pos;
    lam_scan_time time;      /* the last layer planned */
    lam_hatches hatches;     /* the last layer's hatch vectors (owned) */
} lam_sls_state;

void lam_sls_state_init(lam_sls_state *st);
void lam_sls_state_free(lam_sls_state *st);

/* Plan SLS layer L; below[0..nbelow) and above[0..nabove) are the layers
 * next to it, nearest first (for skins; only o->scan.skin_layers of each
 * are looked at; fewer means the model ends there). st->time is set to the
 * layer's estimate (and added to *o->time). When `given` is not NULL its
 * vectors are planned instead of hatching L (a recipe's own hatcher). */
int lam_plan_sls_layer(const lam_layer *L, const lam_layer *const *below, size_t nbelow,
                       const lam_layer *const *above, size_t nabove, const lam_frame *f,
                       const lam_plan_opts *o, const lam_sink *sink, const lam_hatches *given,
                       lam_sls_state *st, lam_error *err);

#endif
