/* The build-time summary line: see cli_estimate.h. */
#include "cli_estimate.h"

#include "fmt.h"
#include "frame.h"
#include "profile_keys.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CLI_TEXT 64 /* a length or a duration for people */

int cli_scan_timed(const lam_scan_cfg *cfg)
{
    for (int t = 0; t < LAM_REGIONS; t++)
        if (cfg->type[t].exposure.speed > 0 || cfg->type[t].exposure.exposure_time > 0) return 1;
    return 0;
}

static const char *profile_name(const lam_plan_opts *po)
{
    return po->name && *po->name ? po->name : "the profile";
}

void cli_print_estimate(const char *path, const lam_plan_opts *po, const lam_scan_time *t)
{
    double mm = lam_key_unit_mm(po->units ? po->units : "mm");
    char exposed[CLI_TEXT], jumped[CLI_TEXT], total[CLI_TEXT], ex[CLI_TEXT], jump[CLI_TEXT], recoat[CLI_TEXT];
    lam_fmt_length(t->exposure_length, mm, po->units, exposed, sizeof exposed);
    lam_fmt_length(t->jump_length, mm, po->units, jumped, sizeof jumped);
    fprintf(stderr, "lamina: %s: %zu layers, %zu contour passes, %zu hatch vectors, %s exposed, %s jumped; ", path,
            t->layers, t->contours, t->vectors, exposed, jumped);
    if (!cli_scan_timed(&po->scan)) {
        fprintf(stderr, "estimated build time unknown: %s sets no speeds\n", profile_name(po));
        return;
    }
    fprintf(stderr, "estimated build time %s (exposure %s, jumps %s, recoating %s)\n",
            lam_fmt_duration(lam_scan_time_total(t), total, sizeof total),
            lam_fmt_duration(t->exposure, ex, sizeof ex), lam_fmt_duration(t->jump, jump, sizeof jump),
            lam_fmt_duration(t->recoat, recoat, sizeof recoat));
}

void cli_print_ladrp_estimate(const char *path, const lam_plan_opts *po, size_t layers, const lam_ladrp_stats *st)
{
    double mm = lam_key_unit_mm(po->units ? po->units : "mm");
    char deposited[CLI_TEXT], travelled[CLI_TEXT], total[CLI_TEXT], dep[CLI_TEXT], trav[CLI_TEXT];
    lam_fmt_length(st->deposit_length, mm, po->units, deposited, sizeof deposited);
    lam_fmt_length(st->travel_length, mm, po->units, travelled, sizeof travelled);
    fprintf(stderr, "lamina: %s: %zu layers, %s deposited, %s travelled; ", path, layers, deposited, travelled);
    /* a rate nothing moves at does not matter */
    const char *missing = st->deposit_length > 0 && !(po->rate > 0)             ? "feed rate"
                          : st->travel_length > 0 && !(po->travel_rate > 0) ? "travel rate"
                                                                             : NULL;
    if (missing) {
        fprintf(stderr, "estimated build time unknown: %s sets no %s\n", profile_name(po), missing);
        return;
    }
    /* rates per minute, as G-code's F */
    double td = st->deposit_length > 0 ? st->deposit_length / po->rate * 60 : 0;
    double tt = st->travel_length > 0 ? st->travel_length / po->travel_rate * 60 : 0;
    fprintf(stderr, "estimated build time %s (depositing %s, travel %s)\n", lam_fmt_duration(td + tt, total, sizeof total),
            lam_fmt_duration(td, dep, sizeof dep), lam_fmt_duration(tt, trav, sizeof trav));
}

/* ---- join's meter ------------------------------------------------------------ */

static int meter_begin(void *ctx, const lam_job_info *job)
{
    cli_ladrp_meter *m = ctx;
    /* where the planner puts the stage before the first move (plan_ladrp.c) */
    const double *p = job->origin;
    if (job->frame_machine) {
        m->uv[0] = p[0];
        m->uv[1] = p[1];
    } else if (job->frame) {
        const lam_frame *f = job->frame;
        m->uv[0] = p[0] * f->u[0] + p[1] * f->u[1] + p[2] * f->u[2];
        m->uv[1] = p[0] * f->v[0] + p[1] * f->v[1] + p[2] * f->v[2];
    }
    return LAM_OK;
}

static int meter_move(void *ctx, const lam_move_info *mv)
{
    cli_ladrp_meter *m = ctx;
    double len = hypot(mv->uv[0] - m->uv[0], mv->uv[1] - m->uv[1]);
    if (mv->deposit) m->st.deposits++, m->st.deposit_length += len;
    else m->st.travel_length += len;
    m->uv[0] = mv->uv[0];
    m->uv[1] = mv->uv[1];
    return LAM_OK;
}

void cli_ladrp_meter_sink(cli_ladrp_meter *m, lam_sink *out)
{
    memset(m, 0, sizeof *m);
    memset(out, 0, sizeof *out);
    out->ctx = m;
    out->begin = meter_begin;
    out->move = meter_move;
}
