/* lam_plan_run: one slicing run through a planner into a sink. */
#include "planner.h"
#include "fmt.h"

#include "plan_threads.h"
#include "profile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void lam_plan_opts_init(lam_plan_opts *o)
{
    memset(o, 0, sizeof *o);
    o->kind = LAM_PLAN_SLS;
    o->name = "lamina";
    o->units = "mm";
    o->bead = 1;
    o->alternate = 1;
    o->scan.contour_count = 1;
    o->scan.contours_first = 1;
    lam_out_costs_default(&o->costs);
    for (int t = 0; t < LAM_REGIONS; t++) {
        o->scan.type[t].distance = 0.1;
        o->scan.type[t].stripe_width = 10;
        o->scan.type[t].island_size = 5;
    }
}

void lam_plan_opts_from_profile(lam_plan_opts *o, const lam_profile *p)
{
    lam_plan_opts_init(o);
    int sls = p->process == LAM_PROCESS_SLS;
    o->kind = sls ? LAM_PLAN_SLS : LAM_PLAN_LADRP;
    o->name = p->name;
    o->units = p->units;
    o->bead = sls ? p->spot_width : p->bead_width;
    o->rate = p->feed_rate;
    o->travel_rate = p->travel_rate;
    o->frame_machine = p->frame_machine;
    o->first_center = p->first_line == LAM_FIRST_CENTER;
    o->angle = p->angle;
    o->angle_step = p->angle_step;
    o->alternate = p->alternate;
    o->min_deposit = p->min_deposit;
    o->perimeters = p->perimeters;
    o->islands = p->islands;
    o->beam_offset = p->beam_offset;
    o->scan = p->scan;
}

void lam_job_label(const char *path, char *buf, size_t size)
{
    const char *base = path ? strrchr(path, '/') : NULL;
    base = base ? base + 1 : path ? path : "";
    const char *dot = strrchr(base, '.');
    size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    if (n >= size) n = size - 1;
    for (size_t i = 0; i < n; i++) {
        char c = base[i];
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
                 c == '.';
        buf[i] = ok ? c : '_';
    }
    buf[n] = '\0';
    if (!n) snprintf(buf, size, "part");
}

static void job_bbox(const lam_slicer *s, const lam_model *m, const lam_plan_opts *o, double bb[6])
{
    if (!o->frame_machine && m) {
        memcpy(bb, m->stats.bbox, 6 * sizeof *bb);
        return;
    }
    double box[4];
    lam_slicer_uv_bounds(s, box);
    const double *planes = lam_slicer_planes(s);
    bb[0] = box[0];
    bb[1] = box[1];
    bb[3] = box[2];
    bb[4] = box[3];
    bb[2] = planes[0];
    bb[5] = planes[lam_slicer_count(s)];
}

void lam_plan_job(const lam_slicer *s, const lam_model *m, const lam_plan_opts *o, lam_job_info *job,
                  char label[128])
{
    const lam_frame *f = lam_slicer_frame(s);
    memset(job, 0, sizeof *job);
    job->name = o->name;
    job->process = o->kind == LAM_PLAN_LADRP ? "ladrp" : "sls";
    job->units = o->units;
    job->layers = lam_slicer_count(s);
    job->bead = o->bead;
    job->rate = o->rate;
    job->travel_rate = o->travel_rate;
    job_bbox(s, m, o, job->bbox);
    lam_job_label(m ? m->path : NULL, label, 128);
    job->label = label;
    job->model = m ? m->path : NULL;
    job->frame = f;
    job->frame_machine = o->frame_machine;
    /* the stage starts at the model origin of the first layer's plane */
    double cut0 = job->layers ? lam_slicer_cut(s, 0) : 0;
    if (o->frame_machine) {
        job->origin[0] = job->origin[1] = 0;
        job->origin[2] = cut0;
    } else {
        lam_frame_to_model(f, 0, 0, cut0, job->origin);
    }
}

/* The run's layers on the calling thread: each layer as soon as it and the
 * skin window above it are sliced. */
static int plan_serial(lam_slicer *s, const lam_plan_opts *o, const lam_sink *sink, lam_layer_cb cb, void *cbctx,
                       const double origin[3], lam_error *err)
{
    const lam_frame *f = lam_slicer_frame(s);
    int rc = LAM_OK;
    double pos[3] = { origin[0], origin[1], origin[2] };
    int laser = -1;
    lam_sls_state st;
    lam_sls_state_init(&st);
    /* SLS skins need the layers around: a window of up to skin_layers
     * below and above the layer being planned, which is win[cur] */
    size_t n = o->kind == LAM_PLAN_SLS && o->scan.skin_layers > 0 ? (size_t)o->scan.skin_layers : 0;
    lam_layer **win = calloc(2 * n + 2, sizeof *win);
    size_t have = 0, cur = 0;
    int more = 1;
    /* a layer range (part files): the layers before it are sliced, not
     * given to the sink */
    size_t lo = o->layer_first, hi = o->layer_count ? o->layer_first + o->layer_count : (size_t)-1;
    const lam_sink none = { 0 };
    if (!win) rc = lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory planning");
    while (!rc) {
        while (!rc && more && have < cur + n + 1) {
            lam_layer *L;
            if ((rc = lam_slicer_next(s, &L, err))) break;
            if (!L) {
                more = 0;
                break;
            }
            win[have++] = L;
            if (cb && L->index >= lo && L->index < hi) rc = cb(cbctx, L, err);
        }
        if (rc || cur >= have || win[cur]->index >= hi) break;
        lam_layer *L = win[cur];
        lam_layer_info li = { L->index, L->cut, L->width, L->floor, L->ceiling, L, NULL };
        int skip = L->index < lo;
        const lam_sink *to = skip ? &none : sink;
        /* before the range only LADRP's islands need planning (they go
         * nearest first from the stage); otherwise a layer leaves only
         * the laser off behind (SLS: nothing) */
        int plan = !skip || (o->kind == LAM_PLAN_LADRP && o->islands);
        if (!plan) laser = 0;
        if (!rc && to->layer) rc = to->layer(to->ctx, &li);
        if (!rc && plan) {
            if (o->kind == LAM_PLAN_LADRP) {
                lam_ladrp_stats ls;
                rc = lam_plan_ladrp_layer(L, f, o, to, pos, &laser, &ls, err);
                if (o->totals && !skip) lam_ladrp_stats_add(o->totals, &ls);
            } else {
                const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
                size_t nb = 0, na = 0;
                for (size_t k = 1; k <= n && k <= cur; k++) below[nb++] = win[cur - k];
                for (size_t k = 1; k <= n && cur + k < have; k++) above[na++] = win[cur + k];
                rc = lam_plan_sls_layer(L, below, nb, above, na, f, o, sink, NULL, &st, err);
                if (!rc && o->layer_time) o->layer_time[L->index] = lam_scan_time_total(&st.time);
                if (lam_scan_estimates(&o->scan)) li.time = &st.time;
            }
        }
        if (!rc && to->layer_end) rc = to->layer_end(to->ctx, &li);
        if (++cur > n) {
            lam_layer_free(win[0]);
            memmove(win, win + 1, (have - 1) * sizeof *win);
            have--, cur--;
        }
    }
    for (size_t k = 0; win && k < have; k++) lam_layer_free(win[k]);
    free(win);
    lam_sls_state_free(&st);
    return rc;
}

int lam_plan_run(lam_slicer *s, const lam_model *m, const lam_plan_opts *o, const lam_sink *sink,
                 lam_layer_cb cb, void *cbctx, lam_error *err)
{
    lam_job_estimate est;
    lam_plan_estimate(s, o, &est);
    if (lam_plan_check_estimate(&est, o, o->max_output, err)) return LAM_ELIMIT;
    lam_job_info job;
    char label[128];
    lam_plan_job(s, m, o, &job, label);
    int rc = sink->begin ? sink->begin(sink->ctx, &job) : LAM_OK;
    /* a worker holds a whole layer's operations until it is written: layers
     * estimated beyond LAM_THREAD_LAYER_MAX are streamed on one thread */
    /* ... and a part (a layer range) is planned on one thread: parts are how
     * a job is spread over processes and machines already */
    int threaded = o->threads > 1 && !o->layer_count &&
                   !(est.layers && est.bytes / (double)est.layers > LAM_THREAD_LAYER_MAX);
    if (!rc) rc = threaded ? lam_plan_threaded(s, o, sink, cb, cbctx, job.origin, err)
                           : plan_serial(s, o, sink, cb, cbctx, job.origin, err);
    if (!rc && sink->end) rc = sink->end(sink->ctx);
    if (rc && err && err->code == LAM_OK) lam_error_set(err, rc, NULL, 0, 0, "planning failed");
    /* geometry that fails says which model (its message: the layer and the stage) */
    if (rc && err && err->code == LAM_EGEOM && !err->file[0] && m->path)
        lam_error_set(err, err->code, m->path, 0, 0, "%s", err->msg);
    return rc;
}
