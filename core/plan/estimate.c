/* The size of a job before it is planned (planner.h): counts from a few
 * sliced layers, bytes from costs measured on the job's own writer.
 *
 * Why sample layers: a hatched layer's vectors follow its area, its
 * boundary and the strategy, none of which the model's extent tells (a
 * frame is a square's extent with a tenth of its area; an islands layer
 * is cut every island_size). Slicing LAM_ESTIMATE_SAMPLES layers on a
 * fork of the run costs one sweep's schedule and those layers, not
 * hatching anything, so a job that would write terabytes is refused in
 * the time of a few layers. */
#include "planner.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmt.h"
#include "plugin.h"
#include "profile.h"
#include "support.h"

static const double PI = 3.14159265358979323846;

void lam_out_costs_default(lam_out_costs *c)
{
    *c = (lam_out_costs){ .job = 0, .layer = 16, .contour = 16, .point = 24, .block = 16, .vector = 48,
                          .travel = 44, .deposit = 20 };
}

/* ---- one layer's counts ------------------------------------------------------ */

/* The layer's boundary seen by lines along direction deg: *cross, the sum
 * over its edges of their extent across the lines (a line spacing d meets
 * the boundary cross / d times); *along and *across, the extent of its
 * points along and across the lines. */
static void boundary(const lam_layer *L, double deg, double *cross, double *along, double *across)
{
    double a = deg * (PI / 180), c = cos(a), s = sin(a);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, sum = 0;
    for (size_t k = 0; k < L->ncontours; k++) {
        const lam_contour *ct = &L->contours[k];
        const double *uv = L->uv + 2 * ct->first;
        for (size_t i = 0; i < ct->n; i++) {
            size_t j = (i + 1) % ct->n;
            double x = uv[2 * i] * c + uv[2 * i + 1] * s, y = -uv[2 * i] * s + uv[2 * i + 1] * c;
            double yj = -uv[2 * j] * s + uv[2 * j + 1] * c;
            sum += fabs(yj - y);
            x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
        }
    }
    *cross = sum;
    *along = x1 > x0 ? x1 - x0 : 0;
    *across = y1 > y0 ? y1 - y0 : 0;
}

/* The hatch type of layer `index` of nlayers by position: the skin_layers
 * at the bottom down-skin, those at the top up-skin (down-skin first, as
 * hatch.h splits), core between: exact for a prism, and the skins' area
 * elsewhere is a fraction of the layer's. */
static int skin_type(const lam_plan_opts *o, size_t index, size_t nlayers)
{
    size_t k = o->scan.skin_layers > 0 ? (size_t)o->scan.skin_layers : 0;
    if (!k || !nlayers) return LAM_KIND_CORE;
    if (index < k) return LAM_KIND_DOWNSKIN;
    if (index + k >= nlayers) return LAM_KIND_UPSKIN;
    return LAM_KIND_CORE;
}

/* Vectors and blocks of hatching an area `area` with perimeter `perim` of
 * layer L with sc (the rules of hatch.h). A line of length l cut every w
 * (stripes, islands) gives l / w + 1 pieces on average: the vectors are
 * the lines' pieces between boundary crossings plus the length / w. */
static void hatch_counts(const lam_layer *L, const lam_scan *sc, double area, double perim, double *vec,
                         double *blk)
{
    double d = sc->distance, deg = sc->angle + (double)L->index * sc->angle_increment;
    double cross, along, across;
    boundary(L, deg, &cross, &along, &across);
    double segs = cross / d / 2, length = area / d;
    *vec = *blk = 0;
    switch (sc->strategy) {
    case LAM_HATCH_LINES:
        *vec = segs;
        *blk = 1;
        break;
    case LAM_HATCH_STRIPES: {
        double w = sc->stripe_width;
        *vec = segs + (length + segs * sc->stripe_overlap) / w;
        *blk = fmin(*vec, along / w + 1);
        break;
    }
    case LAM_HATCH_ISLANDS: {
        /* odd squares run 90 degrees more: their lines cross the boundary
         * as those of deg + 90; the squares stay on the u, v grid, so lines
         * at an angle meet a square |cos| + |sin| times as often */
        double c2, a2, x2, S = sc->island_size, a = deg * (PI / 180);
        boundary(L, deg + 90, &c2, &a2, &x2);
        segs = (cross + c2) / d / 4;
        double f = fabs(cos(a)) + fabs(sin(a));
        *vec = segs + length * f * (1 + sc->island_overlap / S) / S;
        *blk = fmin(*vec, area / (S * S) + perim / S + 1);
        break;
    }
    default: break;
    }
}

/* A support region R's walls (support.h): lines across each direction as
 * hatch lines are counted, one block each; a block's outline a vector an
 * edge; windows cut a wall every perf_spacing. Teeth are a few layers of
 * walls inside the part: not counted. */
static void add_support(lam_job_estimate *e, const lam_support_cfg *c, const lam_layer *R, double area, double wgt)
{
    int walls = lam_support_walls(c), dirs = walls == LAM_SUPPORT_LINES ? 1 : 2;
    for (int k = 0; k < dirs; k++) {
        double cross, along, across;
        boundary(R, 90.0 * k, &cross, &along, &across);
        double vec = cross / c->spacing / 2;
        if (c->perf_width > 0 && c->perf_spacing > c->perf_width) vec += area / c->spacing / c->perf_spacing;
        e->vectors += wgt * vec;
        e->blocks += wgt;
    }
    if (walls == LAM_SUPPORT_BLOCK) {
        e->vectors += wgt * (double)R->npoints;
        e->blocks += wgt;
    }
}

static void add_sls(lam_job_estimate *e, const lam_plan_opts *o, const lam_layer *L, size_t nlayers, double wgt)
{
    const lam_layer *R = lam_supports_region(o->supports, L->index);
    if (R && o->scan.support.spacing > 0)
        add_support(e, &o->scan.support, R, lam_supports_area(o->supports, L->index), wgt);
    int passes = o->scan.contour_count > 0 ? o->scan.contour_count : 0;
    e->contours += wgt * (double)L->ncontours * passes;
    e->points += wgt * (double)L->npoints * passes;
    const lam_scan *sc = &o->scan.type[skin_type(o, L->index, nlayers)];
    if (!L->ncontours || sc->strategy == LAM_HATCH_NONE || !(sc->distance > 0)) return;
    double area = 0, perim = 0;
    for (size_t k = 0; k < L->ncontours; k++) area += L->contours[k].area, perim += L->contours[k].perimeter;
    double inset = (o->beam_offset ? o->bead / 2 : 0) + (passes > 1 ? (passes - 1) * o->scan.contour_distance : 0) +
                   o->scan.hatch_offset;
    area -= perim * inset; /* the band the inset takes off, to first order */
    if (!(area > 0)) return;
    double vec, blk;
    hatch_counts(L, sc, area, perim, &vec, &blk);
    e->vectors += wgt * vec;
    e->blocks += wgt * blk;
}

/* LADRP: per deposit a travel to its start (the laser off and on around
 * it) and the deposit; a layer's first travel; perimeter passes go round
 * every contour (a travel, then a deposit per point). */
static void add_ladrp(lam_job_estimate *e, const lam_plan_opts *o, const lam_layer *L, double wgt)
{
    if (!L->ncontours) return;
    double cross, along, across, d = o->bead;
    boundary(L, o->angle + (double)L->index * o->angle_step, &cross, &along, &across);
    double segs = cross / d / 2;
    e->lines += wgt * (floor(across / d) + 1);
    e->travels += wgt * (segs + 1);
    e->deposits += wgt * segs;
    if (o->perimeters > 0) {
        double p = (double)o->perimeters;
        e->contours += wgt * (double)L->ncontours * p;
        e->points += wgt * (double)L->npoints * p;
        e->travels += wgt * (double)L->ncontours * p;
        e->deposits += wgt * (double)L->npoints * p;
    }
}

void lam_job_estimate_bytes(lam_job_estimate *e, const lam_out_costs *c)
{
    e->bytes = c->job + c->layer * (double)e->layers + c->contour * e->contours + c->point * e->points +
               c->block * e->blocks + c->vector * e->vectors + c->travel * e->travels + c->deposit * e->deposits;
}

void lam_job_estimate_add(lam_job_estimate *e, const lam_plan_opts *o, const lam_layer *L, size_t nlayers,
                          double weight)
{
    e->layers++;
    if (o->kind == LAM_PLAN_LADRP) add_ladrp(e, o, L, weight);
    else add_sls(e, o, L, nlayers, weight);
    lam_job_estimate_bytes(e, &o->costs);
}

/* ---- the run ------------------------------------------------------------------ */

/* Without layers: scan lines across the model's extent, contour points
 * from the crossings of every cut (the estimate before hatching counted). */
static void estimate_extent(const lam_slicer *s, const lam_plan_opts *o, lam_job_estimate *e)
{
    double box[4];
    lam_slicer_uv_bounds(s, box);
    size_t n = lam_slicer_count(s);
    memset(e, 0, sizeof *e);
    e->layers = n;
    double pts = lam_slicer_crossings(s);
    if (o->kind == LAM_PLAN_LADRP) {
        for (size_t i = 0; i < n; i++) e->lines += lam_ladrp_lines(box, o->angle + (double)i * o->angle_step, o->bead);
        e->travels = e->deposits = e->lines;
        e->points = pts * o->perimeters;
    } else {
        e->points = pts * (o->scan.contour_count > 0 ? o->scan.contour_count : 0);
    }
    lam_job_estimate_bytes(e, &o->costs);
}

void lam_plan_estimate(const lam_slicer *s, const lam_plan_opts *o, lam_job_estimate *e)
{
    memset(e, 0, sizeof *e);
    size_t n = lam_slicer_count(s);
    if (!n) {
        lam_job_estimate_bytes(e, &o->costs);
        return;
    }
    /* A mesh that is not closed is estimated from its extent: its layers
     * are open outlines, and closing their gaps is the slicer's slowest
     * work (2^18 open one-triangle shells took minutes and gigabytes per
     * sampled layer), while an estimate must cost a few layers at most. */
    const lam_model_stats *ms = &lam_slicer_model(s)->stats;
    if (ms->boundary_edges || ms->nonmanifold_edges) {
        estimate_extent(s, o, e);
        return;
    }
    size_t k = n < LAM_ESTIMATE_SAMPLES ? n : LAM_ESTIMATE_SAMPLES;
    lam_slicer *f = NULL;
    int rc = lam_slicer_fork(s, &f, NULL);
    /* sample i stands for the layers [i n / k, (i + 1) n / k): its middle */
    for (size_t i = 0; i < k && !rc; i++) {
        size_t lo = i * n / k, hi = (i + 1) * n / k, at = lo + (hi - lo) / 2;
        lam_layer *L = NULL;
        lam_slicer_seek(f, at);
        rc = lam_slicer_next(f, &L, NULL);
        if (!rc && !L) rc = LAM_EUSAGE;
        if (!rc) lam_job_estimate_add(e, o, L, n, (double)(hi - lo));
        lam_layer_free(L);
    }
    lam_slicer_free(f);
    if (rc) {
        estimate_extent(s, o, e);
        return;
    }
    e->sampled = k;
    e->layers = n;
    lam_job_estimate_bytes(e, &o->costs);
}

int lam_check_output_estimate(const lam_job_estimate *e, const lam_plan_opts *o, const char *what,
                              unsigned long long max_bytes, lam_error *err)
{
    if (!max_bytes) max_bytes = LAM_DEFAULT_MAX_OUTPUT;
    if (!(e->bytes > (double)max_bytes)) return LAM_OK;
    char a[32], b[32];
    if (!what) what = "the job";
    if (o->kind == LAM_PLAN_LADRP)
        return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0,
                             "%s would write about %s (%zu layers, %.4g scan lines of bead %g), more than the "
                             "limit of %s",
                             what, lam_fmt_bytes(a, sizeof a, e->bytes), e->layers, e->lines, o->bead,
                             lam_fmt_bytes(b, sizeof b, (double)max_bytes));
    return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0,
                         "%s would write about %s (%zu layers, %.4g contour points, %.4g hatch vectors), more than "
                         "the limit of %s",
                         what, lam_fmt_bytes(a, sizeof a, e->bytes), e->layers, e->points, e->vectors,
                         lam_fmt_bytes(b, sizeof b, (double)max_bytes));
}

int lam_plan_check_estimate(const lam_job_estimate *e, const lam_plan_opts *o, unsigned long long max_bytes,
                            lam_error *err)
{
    return lam_check_output_estimate(e, o, NULL, max_bytes, err);
}

/* ---- costs ---------------------------------------------------------------------- */

enum { SAMPLE = 64 };

/* What a sample job holds beyond begin and end. */
typedef struct sample {
    int layer;               /* one layer */
    size_t points;           /* a contour of this many points */
    size_t vectors;          /* a hatch block of this many vectors */
    size_t travels;          /* travel, deposits, travel, ... cycles */
    size_t deposits;         /* deposits after each travel */
} sample;

/* A coordinate inside [lo, hi] that prints with every digit, as the ends
 * of hatch vectors and scan lines do (k-th of a low-discrepancy walk). */
static double inside(double lo, double hi, size_t k)
{
    double f = fmod(0.1 + (double)k * 0.6180339887498949, 1.0);
    return lo + (hi - lo) * (0.05 + 0.9 * f);
}

static int sample_layer(const lam_sink *sk, const lam_job_info *job, const sample *q, double *buf)
{
    const double *b = job->bbox;
    double z = (b[2] + b[5]) / 2;
    /* contour points go round the box's corners: vertices of a mesh print
     * as they were drawn; the layer's section is that contour (sinks that
     * write the section, as JSON does, count its points once more) */
    double *xyz = buf, *uv = buf + 3 * q->points;
    for (size_t i = 0; i < q->points; i++) {
        int c = (int)(i % 4);
        uv[2 * i] = xyz[3 * i] = c == 1 || c == 2 ? b[3] : b[0];
        uv[2 * i + 1] = xyz[3 * i + 1] = c >= 2 ? b[4] : b[1];
        xyz[3 * i + 2] = z;
    }
    lam_contour ct = { 0, q->points, 0, -1, LAM_SOLID, (b[3] - b[0]) * (b[4] - b[1]), 0, { b[0], b[1], b[3], b[4] } };
    lam_layer sec = { .cut = z, .floor = b[2], .ceiling = b[5], .width = b[5] - b[2], .uv = uv,
                      .npoints = q->points, .contours = &ct, .ncontours = q->points ? 1 : 0 };
    lam_layer_info li = { .index = 0, .z = z, .width = b[5] - b[2], .floor = b[2], .ceiling = b[5], .section = &sec };
    int rc = sk->layer ? sk->layer(sk->ctx, &li) : LAM_OK;
    if (!rc && q->points && sk->contour) {
        lam_contour_info ci = { .attrs = lam_attrs_default(), .solid = 1, .z = z, .xyz = xyz, .uv = uv, .n = q->points };
        rc = sk->contour(sk->ctx, &ci);
    }
    if (!rc && q->vectors && sk->hatches) {
        double *hx = buf, *hu = buf + 6 * q->vectors;
        for (size_t i = 0; i < 2 * q->vectors; i++) {
            hu[2 * i] = hx[3 * i] = inside(b[0], b[3], i);
            hu[2 * i + 1] = hx[3 * i + 1] = inside(b[1], b[4], i + 7);
            hx[3 * i + 2] = z;
        }
        lam_hatch_info hi = { .attrs = lam_attrs_default(), .kind = LAM_KIND_CORE, .z = z, .xyz = hx, .uv = hu,
                              .n = q->vectors };
        rc = sk->hatches(sk->ctx, &hi);
    }
    for (size_t t = 0; t < q->travels && !rc && sk->move; t++) {
        lam_move_info m = { .attrs = lam_attrs_default(),
                            .xyz = { inside(b[0], b[3], t), inside(b[1], b[4], t + 3), z } };
        m.uv[0] = m.xyz[0];
        m.uv[1] = m.xyz[1];
        if (sk->laser) rc = sk->laser(sk->ctx, 0);
        if (!rc) rc = sk->move(sk->ctx, &m);
        if (!rc && sk->laser) rc = sk->laser(sk->ctx, 1);
        if (!rc && sk->feed) rc = sk->feed(sk->ctx, job->rate);
        for (size_t k = 0; k < q->deposits && !rc; k++) {
            m.deposit = 1;
            m.uv[0] = m.xyz[0] = inside(b[0], b[3], t + k + 11);
            rc = sk->move(sk->ctx, &m);
        }
    }
    if (!rc && sk->layer_end) rc = sk->layer_end(sk->ctx, &li);
    return rc;
}

/* The bytes of one sample job through a fresh sink; -1 when the sink
 * refuses it. */
static double sample_bytes(lam_sink_open open, void *arg, const lam_job_info *job, const sample *q, double *buf,
                           int *fatal, lam_error *err)
{
    lam_writer *w = NULL;
    lam_sink sk = { 0 };
    lam_error e;
    lam_error_clear(&e);
    int rc = lam_writer_memory(&w, &e);
    if (!rc) rc = open(arg, w, &sk, &e);
    if (rc) {
        *fatal = rc;
        lam_error_set(err, e.code ? e.code : rc, NULL, 0, 0, "%s", e.msg[0] ? e.msg : "out of memory");
        lam_writer_abort(w);
        return -1;
    }
    lam_job_info j = *job;
    j.layers = (size_t)q->layer; /* a writer may check the count it announced */
    rc = sk.begin ? sk.begin(sk.ctx, &j) : LAM_OK;
    if (!rc && q->layer) rc = sample_layer(&sk, &j, q, buf);
    if (!rc && sk.end) rc = sk.end(sk.ctx);
    double n = rc ? -1 : (double)lam_writer_bytes(w);
    if (sk.destroy) sk.destroy(sk.ctx);
    lam_writer_abort(w);
    return n;
}

int lam_out_costs_measure(lam_sink_open open, void *arg, const lam_job_info *job, lam_out_costs *c, lam_error *err)
{
    memset(c, 0, sizeof *c);
    double *buf = malloc(2 * SAMPLE * 10 * sizeof *buf);
    if (!buf) return lam_error_nomem(err, "estimating the output");
    const sample q[] = {
        { 0, 0, 0, 0, 0 },                  /* the job */
        { 1, 0, 0, 0, 0 },                  /* an empty layer */
        { 1, SAMPLE, 0, 0, 0 }, { 1, 2 * SAMPLE, 0, 0, 0 },
        { 1, 0, SAMPLE, 0, 0 }, { 1, 0, 2 * SAMPLE, 0, 0 },
        { 1, 0, 0, SAMPLE, 1 }, { 1, 0, 0, SAMPLE, 2 }, { 1, 0, 0, 2 * SAMPLE, 2 },
    };
    double n[sizeof q / sizeof *q];
    int fatal = 0;
    for (size_t i = 0; i < sizeof q / sizeof *q && !fatal; i++) n[i] = sample_bytes(open, arg, job, &q[i], buf, &fatal, err);
    free(buf);
    if (fatal) return fatal;
    if (n[0] < 0 || n[1] < 0) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "the writer refuses an empty job");
    /* differences of two sizes: a block's own bytes and its items' */
    c->job = n[0];
    c->layer = n[1] - n[0];
    if (n[2] >= 0 && n[3] >= 0) c->point = (n[3] - n[2]) / SAMPLE, c->contour = n[2] - n[1] - SAMPLE * c->point;
    if (n[4] >= 0 && n[5] >= 0) c->vector = (n[5] - n[4]) / SAMPLE, c->block = n[4] - n[1] - SAMPLE * c->vector;
    if (n[6] >= 0 && n[7] >= 0 && n[8] >= 0) {
        c->deposit = (n[7] - n[6]) / SAMPLE;
        c->travel = (n[8] - n[7]) / SAMPLE - 2 * c->deposit;
    }
    /* a header or trailer that counts its items is not below zero */
    double *all[] = { &c->layer, &c->contour, &c->point, &c->block, &c->vector, &c->travel, &c->deposit };
    for (size_t i = 0; i < sizeof all / sizeof *all; i++)
        if (*all[i] < 0) *all[i] = 0;
    return LAM_OK;
}

typedef struct program_arg {
    const lam_profile *p;
} program_arg;

static int open_program(void *arg, lam_writer *w, lam_sink *out, lam_error *err)
{
    const lam_profile *p = ((program_arg *)arg)->p;
    return lam_program_sink(p->writer, &p->dialect, w, out, err);
}

int lam_program_costs(const lam_profile *p, const lam_job_info *job, lam_out_costs *c, lam_error *err)
{
    program_arg a = { p };
    lam_out_costs m;
    int rc = lam_out_costs_measure(open_program, &a, job, &m, err);
    if (!rc) *c = m; /* else c stays as it was */
    return rc;
}
