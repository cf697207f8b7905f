/* The reports of `lamina build`: see cli_build.h. */
#include "cli_build.h"

#include "cli.h"
#include "cli_args.h"
#include "cli_estimate.h"
#include "fmt.h"
#include "writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *dur(double s, char *buf, size_t size) { return lam_fmt_duration(s, buf, size); }

static const char *len(const lam_profile *p, double x, char *buf, size_t size)
{
    return lam_fmt_length(x, lam_profile_unit_mm(p), p->units, buf, size);
}

static void lasers_line(const char *path, const lam_build_run *r, const lam_scan_time *laser, double worst,
                        size_t worst_layer)
{
    const lam_laser_set *ls = lam_build_run_lasers(r);
    char a[64];
    fprintf(stderr, "lamina: %s: lasers:", path);
    for (size_t l = 0; l < ls->n; l++)
        fprintf(stderr, "%s laser %zu %s", l ? "," : "", l + 1, dur(laser[l].exposure + laser[l].jump, a, sizeof a));
    if (ls->n > 1) fprintf(stderr, "; worst balance %.3f (layer %zu)", worst, worst_layer);
    fputc('\n', stderr);
}

static void parts_line(const char *path, const lam_build_run *r)
{
    size_t n;
    const lam_run_part *parts = lam_build_run_parts(r, &n);
    char a[64];
    fprintf(stderr, "lamina: %s: parts:", path);
    for (size_t i = 0; i < n; i++)
        fprintf(stderr, "%s %s %s", i ? "," : "", parts[i].name, dur(parts[i].time.exposure + parts[i].time.jump, a, sizeof a));
    fputc('\n', stderr);
}

void cli_build_summary(const char *path, const lam_build_run *r, const lam_profile *p, const lam_scan_time *all,
                       const lam_scan_time *laser, double worst_balance, size_t worst_layer)
{
    size_t n;
    lam_build_run_parts(r, &n);
    char e[64], jl[64], t[64], x[64], rc[64];
    fprintf(stderr, "lamina: %s: %zu part%s, %zu layers, %zu laser%s, %zu contour passes, %zu hatch vectors, %s exposed, "
                    "%s jumped; ",
            path, n, n == 1 ? "" : "s", lam_build_run_layers(r), lam_build_run_lasers(r)->n,
            lam_build_run_lasers(r)->n == 1 ? "" : "s", all->contours, all->vectors,
            len(p, all->exposure_length, e, sizeof e), len(p, all->jump_length, jl, sizeof jl));
    if (!cli_scan_timed(&p->scan)) {
        fprintf(stderr, "estimated build time unknown: %s sets no speeds\n", p->name);
        return;
    }
    fprintf(stderr, "estimated build time %s (scanning %s on the busiest laser of each layer, recoating %s)\n",
            dur(lam_scan_time_total(all), t, sizeof t), dur(all->exposure + all->jump, x, sizeof x),
            dur(all->recoat, rc, sizeof rc));
    lasers_line(path, r, laser, worst_balance, worst_layer);
    parts_line(path, r);
}

/* The footprints' outlines on the plate. */
static int outlines(const lam_run_part *parts, size_t n, double **xy, size_t *npts, lam_error *err)
{
    for (size_t i = 0; i < n; i++) {
        const lam_mesh *m = &parts[i].model->mesh;
        int rc = lam_footprint_hull(m->xyz, m->nverts, &xy[i], &npts[i], err);
        if (rc) return rc;
    }
    return LAM_OK;
}

int cli_build_layout(const lam_build_run *r, const lam_profile *p, const char *path, lam_error *err)
{
    size_t n;
    const lam_run_part *parts = lam_build_run_parts(r, &n);
    lam_arrange_item *items = calloc(n ? n : 1, sizeof *items);
    double **xy = calloc(n ? n : 1, sizeof *xy);
    size_t *npts = calloc(n ? n : 1, sizeof *npts);
    int rc = items && xy && npts ? outlines(parts, n, xy, npts, err) : lam_error_nomem(err, "drawing the layout");
    for (size_t i = 0; i < n && !rc; i++) {
        memcpy(items[i].box, parts[i].box, sizeof items[i].box);
        items[i].at[0] = parts[i].at[0];
        items[i].at[1] = parts[i].at[1];
        items[i].fixed = 1;
        items[i].name = parts[i].name;
    }
    lam_writer *w = NULL;
    if (!rc) rc = cli_writer("--layout", path, &w, err);
    const lam_laser_set *ls = lam_build_run_lasers(r);
    if (!rc) rc = lam_layout_svg(w, lam_build_run_plate(r), items, n, (const double *const *)xy, npts,
                                 (const double(*)[4])ls->field, p->nlasers ? ls->n : 0, p->units);
    if (!rc) rc = lam_writer_commit(w, err);
    else lam_writer_abort(w);
    for (size_t i = 0; xy && i < n; i++) free(xy[i]);
    free(xy);
    free(npts);
    free(items);
    return rc ? cli_fail_cmd("build", err) : EXIT_OK;
}
