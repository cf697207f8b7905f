/* Planning options, job labels and the job header of a slicing run
 * (lam_plan_run itself: plan_run.c). */
#include "planner.h"
#include "repair.h"
#include "fmt.h"

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

/* A single part's run: each region's exposure, style 0 (the vectors'
 * style attribute at its default). */
static void job_exposure(lam_job_info *job, const lam_plan_opts *o)
{
    if (o->kind != LAM_PLAN_SLS) return;
    for (int k = 0; k < LAM_REGIONS; k++) {
        if (!lam_scan_region_used(&o->scan, k)) continue;
        const lam_exposure *e = &o->scan.type[k].exposure;
        job->own_exposure[job->nexposure++] = (lam_job_exposure){
            .style = 0, .region = k, .power = e->power, .speed = e->speed,
            .distance = lam_scan_region_distance(&o->scan, o->bead, k),
            .point_distance = e->point_distance, .exposure_time = e->exposure_time };
    }
}

void lam_job_init(lam_job_info *job, const lam_plan_opts *o, size_t layers, const double bbox[6], double cut0,
                  const lam_frame *f, const char *label, const char *model)
{
    memset(job, 0, sizeof *job);
    job->name = o->name;
    job->process = o->kind == LAM_PLAN_LADRP ? "ladrp" : "sls";
    job->units = o->units;
    job->layers = layers;
    job->bead = o->bead;
    job->rate = o->rate;
    job->travel_rate = o->travel_rate;
    memcpy(job->bbox, bbox, sizeof job->bbox);
    job->label = label;
    job->model = model;
    job->frame = f;
    job->frame_machine = o->frame_machine;
    /* the stage starts at the model origin of the first layer's plane */
    if (o->frame_machine) {
        job->origin[0] = job->origin[1] = 0;
        job->origin[2] = cut0;
    } else {
        lam_frame_to_model(f, 0, 0, cut0, job->origin);
    }
    job_exposure(job, o);
}

void lam_plan_job(const lam_slicer *s, const lam_model *m, const lam_plan_opts *o, lam_job_info *job,
                  char label[128])
{
    double bb[6];
    job_bbox(s, m, o, bb);
    lam_job_label(m ? m->path : NULL, label, 128);
    size_t layers = lam_slicer_count(s);
    lam_job_init(job, o, layers, bb, layers ? lam_slicer_cut(s, 0) : 0, lam_slicer_frame(s), label,
                 m ? m->path : NULL);
    if (m && m->repair.ran && lam_repair_acted(&m->repair)) job->repair = &m->repair;
}
