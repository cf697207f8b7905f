#include "cli_view.h"

#include "cli.h"


#include <stdio.h>
#include <string.h>

int cli_view_open(cli_view *v, const args *a, lam_slicer *s, const lam_plan_opts *po, lam_views *views,
                  lam_error *err)
{
    memset(v, 0, sizeof *v);
    v->limit = a->max_output ? a->max_output : LAM_DEFAULT_MAX_OUTPUT;
    int rc = LAM_OK;
    if (a->svg) {
        double box[4];
        lam_slicer_uv_bounds(s, box);
        char title[600];
        snprintf(title, sizeof title, "lamina: %s", a->path);
        v->svg_path = a->svg;
        rc = lam_svg_new(lam_slicer_count(s), box, title, &v->svg, err);
        views->svg = v->svg;
        views->frame = lam_slicer_frame(s);
        views->frame_machine = po->frame_machine;
    }
    if (!rc && a->html && !(rc = cli_writer("--html", a->html, &v->hw, err))) lam_writer_set_limit(v->hw, v->limit);
    views->html = v->hw;
    return rc;
}

int cli_view_layer(cli_view *v, const lam_layer *L, lam_error *err)
{
    return v->svg ? lam_svg_add(v->svg, L, err) : LAM_OK;
}

int cli_view_save(cli_view *v, lam_error *err)
{
    if (v->svg) {
        lam_writer *w;
        if (cli_writer("--svg", v->svg_path, &w, err)) return err->code;
        lam_writer_set_limit(w, v->limit);
        lam_svg_write(v->svg, w);
        if (lam_writer_commit(w, err)) return err->code;
    }
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
    lam_svg_free(v->svg);
    memset(v, 0, sizeof *v);
}
