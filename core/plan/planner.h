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
#include "writer.h"

typedef enum lam_plan_kind { LAM_PLAN_LADRP, LAM_PLAN_SLS } lam_plan_kind;

/* Statistics of LADRP planning (lengths in the layer plane). */
typedef struct lam_ladrp_stats {
    size_t lines, deposits;
    double deposit_length, travel_length;
} lam_ladrp_stats;
typedef lam_ladrp_stats lam_ladrp_stats_out;

/* Bytes of output per item of a job (core/plan/estimate.c): measured on the
 * job's own writer (lam_out_costs_measure, lam_program_costs) or, from
 * lam_plan_opts_init, the defaults (a text program with numbers of about
 * ten characters: 16 a layer, a contour block or a hatch block, 24 a
 * contour point, 48 a hatch vector, 20 a LADRP deposit, 44 a travel with
 * the laser's commands around it: 64 a scan line). */
typedef struct lam_out_costs {
    double job;              /* begin and end (preamble, postamble) */
    double layer;            /* an empty layer */
    double contour, point;   /* a contour block, and each of its points */
    double block, vector;    /* a hatch block, and each of its vectors */
    double travel;           /* a LADRP travel with the laser off and on again around it */
    double deposit;          /* a LADRP deposit move */
} lam_out_costs;

void lam_out_costs_default(lam_out_costs *c);

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
    unsigned long long max_output; /* lam_plan_run refuses a job estimated to write
                                      more (lam_plan_check_estimate); 0: the default */
    lam_out_costs costs;         /* bytes per item of the program, for the estimate;
                                    lam_plan_opts_init sets the defaults,
                                    lam_program_costs measures them */
    lam_scan_cfg scan;           /* SLS: contour passes, hatching, skins, exposure
                                    and time (hatch.h); the planner sets
                                    scan.compensation: half the spot with
                                    beam_offset, else 0 */
    const struct lam_supports *supports; /* SLS: the run's supports (support.h), by layer
                                    index, or NULL: their walls are exposed before
                                    each layer's part (scan.support's type) */
    lam_scan_time *time;         /* SLS: if not NULL, the job's estimate is added here */
    double *layer_time;          /* SLS (lam_plan_run): if not NULL, room for every
                                    layer: each one's estimate, seconds */
    unsigned threads;            /* lam_plan_run: worker threads that slice and plan
                                    layers while the calling thread writes them in
                                    order (the same output for every number); 0 or 1:
                                    everything on the calling thread */
    size_t layer_first, layer_count; /* lam_plan_run plans only layers layer_first ..
                                    layer_first + layer_count - 1 (0-based; count 0:
                                    every layer) of the run, for part files (part.h);
                                    begin and end still describe the whole run. The
                                    layers before the range are sliced, not planned
                                    (each layer's output depends only on it; LADRP's
                                    laser is off after any layer), except LADRP
                                    islands, planned into no sink: their order starts
                                    nearest the stage the layer before left. */
} lam_plan_opts;

struct lam_supports;

/* The supports a plan of slicer s's run makes (support.h), when o is SLS,
 * its scan.support.type is not none and o->supports gives none: every
 * layer sliced on the calling thread (s is left at its start; the sweep
 * goes from the top down), then dropped. *out NULL: none asked for; the
 * caller's otherwise (lam_supports_free). Errors: the slicer's, GEOS's. */
int lam_plan_supports(lam_slicer *s, const lam_plan_opts *o, struct lam_supports **out, lam_error *err);

/* Defaults: SLS, bead 1, rates 0, model frame, edge, 0 degrees, alternate;
 * one contour pass, contours first, no hatching. */
void lam_plan_opts_init(lam_plan_opts *o);

struct lam_profile;

/* The planning values of a machine profile (process, bead or spot width,
 * rates, frame, raster and SLS options); o is initialised first. The
 * profile's strings are borrowed: it must outlive o. */
void lam_plan_opts_from_profile(lam_plan_opts *o, const struct lam_profile *p);

/* ---- the size of a job, before it runs ------------------------------------ */

/* The default output limit: 4 GiB, over ten times the largest program of
 * the bench parts, and far below what a width or bead typed wrong asks
 * (-w 1e-6 on a 100 mm cube writes about 16 GB). */
#define LAM_DEFAULT_MAX_OUTPUT (4ULL << 30)


/* What a job will do, estimated before it is planned. */
typedef struct lam_job_estimate {
    size_t layers;
    size_t sampled;          /* the layers the counts were measured on (0: the model's extent) */
    double lines;            /* LADRP scan lines: per layer, the extent across the scan
                                direction of the sections / bead, + 1 */
    double points;           /* contour points: every SLS contour pass; LADRP perimeters */
    double contours;         /* contour blocks (SLS), contour passes (LADRP perimeters) */
    double vectors, blocks;  /* SLS hatch vectors and blocks */
    double travels, deposits;/* LADRP moves */
    double bytes;            /* the output, by o->costs */
} lam_job_estimate;

/* Scan lines a layer whose sections lie in box (umin vmin umax vmax) gets
 * at raster angle `deg` with bead d (0 for an empty box). */
double lam_ladrp_lines(const double box[4], double deg, double bead);

/* Add layer L of a run of nlayers (0: unknown) to e, its counts times
 * `weight`, as planning it with o would make them: every contour pass;
 * hatch vectors from the region's area (area / hatch_distance of line),
 * its boundary (where lines start and end: its extent across the lines /
 * hatch_distance) and the strategy (a cut at every stripe_width or
 * island_size along a line, a block per stripe or island); skins by
 * position (the skin_layers at each end of the run); LADRP deposits from
 * the boundary across the scan lines. e->bytes is brought up to date. */
void lam_job_estimate_add(lam_job_estimate *e, const lam_plan_opts *o, const lam_layer *L, size_t nlayers,
                          double weight);

/* e->bytes from e's counts and costs c. */
void lam_job_estimate_bytes(lam_job_estimate *e, const lam_out_costs *c);

/* The estimate of planning slicer s's whole run with o: up to
 * LAM_ESTIMATE_SAMPLES layers evenly spread over the run are sliced (on a
 * fork of s: s is not moved) and counted (lam_job_estimate_add), each
 * standing for its share of the run. When slicing them fails, from the
 * model's extent and lam_slicer_crossings (contour points only). */
#define LAM_ESTIMATE_SAMPLES 32
void lam_plan_estimate(const lam_slicer *s, const lam_plan_opts *o, lam_job_estimate *e);

/* The bytes per item of the output a sink writes: sample jobs (an empty
 * one, a layer, contours, hatch blocks and LADRP moves of two sizes, with
 * coordinates inside job->bbox) are written through fresh sinks from
 * open(arg, ...) into memory and their sizes compared. A sample the sink
 * refuses (a writer without hatches) costs 0. Returns LAM_OK, or the error
 * of open or out of memory. */
typedef int (*lam_sink_open)(void *arg, lam_writer *w, lam_sink *out, lam_error *err);
int lam_out_costs_measure(lam_sink_open open, void *arg, const lam_job_info *job, lam_out_costs *c,
                          lam_error *err);

/* The costs of profile p's program (its writer: lam_program_sink) for a
 * job like `job` (lam_plan_job); on error c is left as it was. */
int lam_program_costs(const struct lam_profile *p, const lam_job_info *job, lam_out_costs *c, lam_error *err);

/* The one builder of a job header (lam_plan_job, Lua's machine:plan): a
 * plan with options o of `layers` layers whose box in the output frame is
 * bbox (the model's, or the run's (u, v, w) box when o->frame_machine),
 * the stage starting at the model origin in the plane of the first layer
 * planned, cut height cut0. f (the run's frame: always set), label (NULL:
 * "part") and model (the model's path, or NULL) are borrowed, as o's
 * strings. SLS: also the exposures of the regions the plan can make (the
 * JSON's job.exposure), from o's scan settings. */
void lam_job_init(lam_job_info *job, const lam_plan_opts *o, size_t layers, const double bbox[6], double cut0,
                  const lam_frame *f, const char *label, const char *model);

/* The job lam_plan_run describes to its sink's begin for slicer s and
 * model m (NULL: the job's box from the slicer; label: room for 128
 * bytes, the job's label). */
void lam_plan_job(const lam_slicer *s, const lam_model *m, const lam_plan_opts *o, lam_job_info *job,
                  char label[128]);

/* LAM_ELIMIT when e->bytes passes max_bytes (0: LAM_DEFAULT_MAX_OUTPUT),
 * with a message that gives the estimate and what it comes from:
 * "the job would write about 16 GB (100000000 layers, 400000000 contour
 * points, 0 hatch vectors), more than the limit of 4 GB". what: the output
 * ("the job" when NULL: the program). */
int lam_plan_check_estimate(const lam_job_estimate *e, const lam_plan_opts *o, unsigned long long max_bytes,
                            lam_error *err);
int lam_check_output_estimate(const lam_job_estimate *e, const lam_plan_opts *o, const char *what,
                              unsigned long long max_bytes, lam_error *err);

/* Output per layer above which lam_plan_run does not use threads: 16 MB,
 * a hundred times a layer of the bench's hatching job. */
#define LAM_THREAD_LAYER_MAX (16.0 * 1024 * 1024)

/* Called with every layer before it is planned (reports, previews). A
 * non-zero return stops the run with that code. */
typedef int (*lam_layer_cb)(void *ctx, const lam_layer *layer, lam_error *err);

/* Plan a whole slicing run into sink: begin, every layer, end. The sink is
 * not destroyed. With o->threads > 1, workers slice and plan layers into
 * recordings (plan_record.h) that the calling thread replays onto sink and
 * hands to cb in layer order: sink and cb run on the calling thread only,
 * and the run's output, messages and first error are the ones of a run on
 * one thread. A job whose layers are estimated (lam_plan_estimate) at more
 * than LAM_THREAD_LAYER_MAX bytes of output each runs on the calling thread,
 * which streams a layer instead of holding it. Returns LAM_OK or the first error (from the slicer, a
 * planner, the sink or the callback); LAM_ELIMIT, before anything is
 * planned or written, when the run's estimate passes o->max_output. */
int lam_plan_run(lam_slicer *s, const lam_model *m, const lam_plan_opts *o, const lam_sink *sink,
                 lam_layer_cb cb, void *cbctx, lam_error *err);

/* Plan one layer (exposed for tests and Lua). pos: the stage position in
 * the output frame, updated; laser: the laser state (-1 unknown), updated. */
int lam_plan_ladrp_layer(const lam_layer *L, const lam_frame *f, const lam_plan_opts *o,
                         const lam_sink *sink, double pos[3], int *laser, lam_ladrp_stats *st,
                         lam_error *err);

/* What SLS planning carries from layer to layer. */
typedef struct lam_sls_state {
    lam_attrs attrs;         /* of every contour and hatch block (vocab.h's defaults) */
    double pos[2];           /* the scanner (layer plane), for jumps */
    int have_pos;
    lam_scan_time time;      /* the last layer planned */
    lam_hatches hatches;     /* the last layer's hatch vectors (owned) */
    lam_hatches support;     /* the last layer's support vectors (owned) */
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
