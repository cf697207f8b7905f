/* The scanner's time estimate: exposure, jumps and recoats of the paths a
 * planner emits (hatch.h). */
#include "hatch.h"

#include <math.h>

int lam_scan_estimates(const lam_scan_cfg *cfg)
{
    if (lam_scan_hatches(cfg) || cfg->recoat_time > 0) return 1;
    for (int t = 0; t < LAM_REGIONS; t++)
        if (cfg->type[t].exposure.speed > 0 || cfg->type[t].exposure.exposure_time > 0) return 1;
    return 0;
}

double lam_scan_time_total(const lam_scan_time *t)
{
    return t->exposure + t->jump + t->recoat;
}

void lam_scan_time_add(lam_scan_time *a, const lam_scan_time *b)
{
    a->layers += b->layers;
    a->contours += b->contours;
    a->vectors += b->vectors;
    a->jumps += b->jumps;
    a->exposure_length += b->exposure_length;
    a->jump_length += b->jump_length;
    a->hatch_length += b->hatch_length;
    a->exposure += b->exposure;
    a->jump += b->jump;
    a->recoat += b->recoat;
}

void lam_scan_time_path(lam_scan_time *t, const lam_scan_cfg *cfg, const lam_exposure *e, const double start[2],
                        const double end[2], double length, int contour, double pos[2], int *have_pos)
{
    if (*have_pos) {
        double du = start[0] - pos[0], dv = start[1] - pos[1];
        double j = sqrt(du * du + dv * dv); /* not hypot: a jump per vector, and coordinates stay below 1e50 */
        t->jumps++;
        t->jump_length += j;
        t->jump += (cfg->jump_speed > 0 ? j / cfg->jump_speed : 0) + cfg->jump_delay;
    }
    if (contour) t->contours++;
    else t->vectors++, t->hatch_length += length;
    t->exposure_length += length;
    /* points from one end to the other; a closed contour's last is its first */
    if (e->point_distance > 0 && e->exposure_time > 0)
        t->exposure += fmax(1, floor(length / e->point_distance) + (contour ? 0 : 1)) * e->exposure_time;
    else if (e->speed > 0) t->exposure += length / e->speed;
    pos[0] = end[0];
    pos[1] = end[1];
    *have_pos = 1;
}
