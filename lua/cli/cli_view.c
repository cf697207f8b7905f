#include "cli_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- a fan-out sink: every call to each of up to three sinks -------------- */

typedef struct fan {
    lam_sink s[3];
    size_t n;
} fan;

#define FAN_CALL(call, ...)                                                                                       \
    fan *f = ctx;                                                                                                 \
    int rc = LAM_OK;                                                                                              \
    for (size_t k = 0; k < f->n && !rc; k++)                                                                      \
        if (f->s[k].call) rc = f->s[k].call(f->s[k].ctx, __VA_ARGS__);                                            \
    return rc;

static int fan_begin(void *ctx, const lam_job_info *j) { FAN_CALL(begin, j) }
static int fan_layer(void *ctx, const lam_layer_info *l) { FAN_CALL(layer, l) }
static int fan_layer_end(void *ctx, const lam_layer_info *l) { FAN_CALL(layer_end, l) }
static int fan_feed(void *ctx, double r) { FAN_CALL(feed, r) }
static int fan_laser(void *ctx, int on) { FAN_CALL(laser, on) }
static int fan_move(void *ctx, int d, const double p[3]) { FAN_CALL(move, d, p) }
static int fan_contour(void *ctx, const lam_contour_info *c) { FAN_CALL(contour, c) }
static int fan_hatches(void *ctx, const lam_hatch_info *h) { FAN_CALL(hatches, h) }

static int fan_end(void *ctx)
{
    fan *f = ctx;
    int rc = LAM_OK;
    for (size_t k = 0; k < f->n && !rc; k++)
        if (f->s[k].end) rc = f->s[k].end(f->s[k].ctx);
    return rc;
}

static void fan_destroy(void *ctx)
{
    fan *f = ctx;
    for (size_t k = 0; k < f->n; k++)
        if (f->s[k].destroy) f->s[k].destroy(f->s[k].ctx);
    free(f);
}

/* ---- the pictures --------------------------------------------------------- */

int cli_view_open(cli_view *v, const args *a, lam_slicer *s, const lam_plan_opts *po, lam_sink *sink,
                  lam_error *err)
{
    memset(v, 0, sizeof *v);
    if (!a->svg && !a->html) return LAM_OK;
    fan *f = calloc(1, sizeof *f);
    if (!f) return lam_error_nomem(err, "making the pictures");
    f->s[f->n++] = *sink;
    *sink = (lam_sink){ f, fan_begin, fan_layer, fan_layer_end, fan_feed, fan_laser, fan_move, fan_contour,
                        fan_end, fan_destroy, fan_hatches };
    const lam_frame *fr = lam_slicer_frame(s);
    int rc = LAM_OK;
    if (a->svg) {
        double box[4];
        lam_slicer_uv_bounds(s, box);
        char title[600];
        snprintf(title, sizeof title, "lamina: %s", a->path);
        v->svg_path = a->svg;
        rc = lam_svg_new(lam_slicer_count(s), box, title, &v->svg, err);
        if (!rc) rc = lam_svg_sink(v->svg, fr, po->frame_machine, &f->s[f->n], err);
        if (!rc) f->n++;
    }
    if (!rc && a->html) {
        rc = strcmp(a->html, "-") ? lam_writer_file(a->html, &v->hw, err)
                                  : lam_writer_stream(stdout, "stdout", &v->hw, err);
        if (!rc) rc = lam_html_new(v->hw, a->path, fr, po->frame_machine, &v->html, err);
        if (!rc) {
            lam_html_times(v->html, po->layer_time, po->layer_time ? po->time : NULL);
            rc = lam_html_sink(v->html, &f->s[f->n], err);
        }
        if (!rc) f->n++;
    }
    return rc;
}

int cli_view_layer(cli_view *v, const lam_layer *L, lam_error *err)
{
    int rc = v->svg ? lam_svg_add(v->svg, L, err) : LAM_OK;
    if (!rc && v->html) rc = lam_html_section(v->html, L, err);
    return rc;
}

int cli_view_save(cli_view *v, lam_error *err)
{
    if (v->svg && lam_svg_save(v->svg, v->svg_path, err)) return err->code;
    if (v->hw) {
        lam_writer *w = v->hw;
        v->hw = NULL;
        if (lam_writer_commit(w, err)) return err->code;
    }
    return LAM_OK;
}

void cli_view_free(cli_view *v)
{
    lam_writer_abort(v->hw);
    lam_html_free(v->html);
    lam_svg_free(v->svg);
    memset(v, 0, sizeof *v);
}
