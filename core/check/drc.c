#include "drc.h"
#include "profile.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

const char *lam_rule_name(lam_rule r)
{
    return r == LAM_RULE_WALL ? "min_wall" : "max_overhang";
}

/* Worst finding per triangle, before regions are formed. */
typedef struct finding {
    double value, pos[3];
    int bad;
} finding;

static uint32_t find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void unite(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = find(parent, a);
    b = find(parent, b);
    if (a != b) parent[a > b ? a : b] = a < b ? a : b; /* smaller index wins: deterministic */
}

static int worse(lam_rule r, double a, double b)
{
    return r == LAM_RULE_WALL ? a < b : a > b;
}

/* Join violating triangles that share an edge into regions. */
static int regions(const lam_model *m, lam_rule rule, double limit, const finding *f, lam_drc_result *out)
{
    size_t nt = m->mesh.ntris;
    uint32_t *parent = malloc((nt + 1) * sizeof *parent), *slot = malloc((nt + 1) * sizeof *slot);
    if (!parent || !slot) {
        free(parent);
        free(slot);
        return LAM_ENOMEM;
    }
    for (size_t t = 0; t < nt; t++) {
        parent[t] = (uint32_t)t;
        slot[t] = UINT32_MAX;
    }
    const lam_edges *E = &m->edges;
    for (size_t e = 0; e < E->n; e++) {
        uint32_t first = UINT32_MAX;
        for (uint32_t i = E->first[e]; i < E->first[e + 1]; i++) {
            uint32_t t = E->tris[i];
            if (!f[t].bad) continue;
            if (first == UINT32_MAX) first = t;
            else unite(parent, first, t);
        }
    }
    int rc = LAM_OK;
    for (size_t t = 0; t < nt; t++) {
        if (!f[t].bad) continue;
        uint32_t root = find(parent, (uint32_t)t);
        if (slot[root] == UINT32_MAX) {
            lam_violation *nv = realloc(out->items, (out->n + 1) * sizeof *nv);
            if (!nv) {
                rc = LAM_ENOMEM;
                break;
            }
            out->items = nv;
            slot[root] = (uint32_t)out->n;
            lam_violation *v = &out->items[out->n++];
            memset(v, 0, sizeof *v);
            v->rule = rule;
            v->limit = limit;
            v->value = f[t].value;
            v->tri = (uint32_t)t;
            memcpy(v->pos, f[t].pos, sizeof v->pos);
        }
        lam_violation *v = &out->items[slot[root]];
        const uint32_t *tv = m->mesh.tris + 3 * t;
        const double *a = m->mesh.xyz + 3 * (size_t)tv[0], *b = m->mesh.xyz + 3 * (size_t)tv[1],
                     *c = m->mesh.xyz + 3 * (size_t)tv[2];
        double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
        double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
        v->area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        v->triangles++;
        /* triangles come in order, so ties keep the first: deterministic */
        if (worse(rule, f[t].value, v->value)) {
            v->value = f[t].value;
            v->tri = (uint32_t)t;
            memcpy(v->pos, f[t].pos, sizeof v->pos);
        }
    }
    free(parent);
    free(slot);
    return rc;
}

/* Is the face at p with outward normal n a boundary of the part: material
 * behind it, void in front? Coincident faces of two shells (the thesis's
 * through hole capped on the cube's own top face) bound nothing: both sides
 * are void. Undecidable points count as real, so nothing is hidden. */
static int real_surface(lam_rays *v, const double p[3], const double n[3], double tol, lam_error *err)
{
    double eps = 50 * tol, in[3], out[3];
    for (int k = 0; k < 3; k++) {
        in[k] = p[k] - eps * n[k];
        out[k] = p[k] + eps * n[k];
    }
    int wi = 1, wo = 0;
    lam_error scratch;
    (void)err;
    if (lam_rays_winding(v, in, &wi, &scratch) != LAM_OK) return 1;
    if (lam_rays_winding(v, out, &wo, &scratch) != LAM_OK) return 1;
    return wi != 0 && wo == 0;
}

static int cmp_violation(const void *a, const void *b)
{
    const lam_violation *p = a, *q = b;
    if (p->rule != q->rule) return p->rule < q->rule ? -1 : 1;
    if (p->value != q->value) return worse(p->rule, p->value, q->value) ? -1 : 1;
    return p->tri < q->tri ? -1 : p->tri > q->tri;
}

int lam_drc_run(const lam_model *m, lam_rays *val, const lam_drc_opts *o, lam_drc_result *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    size_t nt = m->mesh.ntris;
    finding *f = calloc(nt + 1, sizeof *f);
    if (!f) return lam_error_nomem(err, "checking design rules");
    double wmin = INFINITY;
    for (size_t v = 0; v < m->mesh.nverts; v++) {
        const double *p = m->mesh.xyz + 3 * v;
        double w = p[0] * o->up[0] + p[1] * o->up[1] + p[2] * o->up[2];
        if (w < wmin) wmin = w;
    }
    double tol = lam_rays_tolerance(val);
    int rc = LAM_OK;
    for (int pass = 0; pass < 2 && !rc; pass++) {
        lam_rule rule = pass == 0 ? LAM_RULE_WALL : LAM_RULE_OVERHANG;
        double limit = pass == 0 ? o->min_wall : o->max_overhang_deg;
        if (!(limit > 0)) continue;
        memset(f, 0, nt * sizeof *f);
        for (size_t t = 0; t < nt && !rc; t++) {
            const uint32_t *tv = m->mesh.tris + 3 * t;
            const double *a = m->mesh.xyz + 3 * (size_t)tv[0], *b = m->mesh.xyz + 3 * (size_t)tv[1],
                         *c = m->mesh.xyz + 3 * (size_t)tv[2];
            double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
            double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(len > 0)) continue; /* degenerate: no side, no rule */
            for (int k = 0; k < 3; k++) n[k] /= len;
            double cen[3] = { (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3 };
            if (rule == LAM_RULE_OVERHANG) {
                double down = -(n[0] * o->up[0] + n[1] * o->up[1] + n[2] * o->up[2]);
                if (down <= 0) continue;
                double top = -INFINITY;
                for (int k = 0; k < 3; k++) {
                    const double *p = m->mesh.xyz + 3 * (size_t)tv[k];
                    double hw = p[0] * o->up[0] + p[1] * o->up[1] + p[2] * o->up[2];
                    if (hw > top) top = hw;
                }
                if (top - wmin <= tol) continue; /* resting on the build plate */
                double angle = asin(down > 1 ? 1 : down) * 180 / PI;
                /* a hair of slack so a face meant to be exactly at the limit passes */
                if (angle > limit + 1e-9 && !real_surface(val, cen, n, tol, err)) continue;
                if (angle > limit + 1e-9) {
                    f[t].bad = 1;
                    f[t].value = angle;
                    memcpy(f[t].pos, cen, sizeof cen);
                }
                continue;
            }
            /* wall thickness from the centroid and three points toward the corners */
            double best = INFINITY, bpos[3] = { 0, 0, 0 };
            for (int s = 0; s < 4 && !rc; s++) {
                double p[3];
                for (int k = 0; k < 3; k++) {
                    const double *corner = s == 0 ? cen : m->mesh.xyz + 3 * (size_t)tv[s - 1];
                    p[k] = s == 0 ? cen[k] : (cen[k] + corner[k]) / 2;
                }
                double in[3] = { -n[0], -n[1], -n[2] }, dist = INFINITY;
                uint32_t hit;
                rc = lam_rays_cast(val, p, in, 4 * tol, &dist, &hit, err);
                out->samples++;
                if (!rc && dist < best) {
                    best = dist;
                    memcpy(bpos, p, sizeof p);
                }
            }
            if (!rc && best < limit) {
                f[t].bad = 1;
                f[t].value = best;
                memcpy(f[t].pos, bpos, sizeof bpos);
            }
        }
        if (!rc && regions(m, rule, limit, f, out)) rc = lam_error_nomem(err, NULL);
    }
    free(f);
    if (rc) {
        lam_drc_result_free(out);
        return rc;
    }
    if (out->n > 1) qsort(out->items, out->n, sizeof *out->items, cmp_violation);
    return LAM_OK;
}

void lam_drc_result_free(lam_drc_result *r)
{
    free(r->items);
    memset(r, 0, sizeof *r);
}

void lam_drc_opts_from_profile(lam_drc_opts *o, const lam_profile *p, const double up[3])
{
    memset(o, 0, sizeof *o);
    o->min_wall = p->process == LAM_PROCESS_LADRP ? p->bead_width : p->spot_width;
    o->max_overhang_deg = p->max_overhang_deg;
    memcpy(o->up, up, sizeof o->up);
}
