/* The LADRP raster planner; see planner.h for the rules. */
#include "planner.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "offset.h"

typedef struct xedge {
    double vlo, vhi;       /* v of the lower and upper end (rotated frame) */
    double ulo, uhi;       /* u of the same ends */
} xedge;

static int cmp_vhi_desc(const void *a, const void *b)
{
    const xedge *p = a, *q = b;
    if (p->vhi != q->vhi) return p->vhi > q->vhi ? -1 : 1;
    if (p->vlo != q->vlo) return p->vlo > q->vlo ? -1 : 1;
    if (p->ulo != q->ulo) return p->ulo < q->ulo ? -1 : 1;
    return (p->uhi > q->uhi) - (p->uhi < q->uhi);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Exact cosine and sine for multiples of 90 degrees. */
static void rotation(double deg, double *c, double *s)
{
    double r = fmod(deg, 360.0);
    if (r < 0) r += 360.0;
    if (r == 0) { *c = 1; *s = 0; }
    else if (r == 90) { *c = 0; *s = 1; }
    else if (r == 180) { *c = -1; *s = 0; }
    else if (r == 270) { *c = 0; *s = -1; }
    else {
        double a = r * 3.14159265358979323846 / 180.0;
        *c = cos(a);
        *s = sin(a);
    }
}

double lam_ladrp_lines(const double box[4], double deg, double bead)
{
    if (!(box[2] >= box[0]) || !(box[3] >= box[1])) return 0;
    /* lines run along (c, s), spaced across (-s, c), over which the box
     * spans |w s| + |h c| */
    double c, s;
    rotation(deg, &c, &s);
    return floor((fabs((box[2] - box[0]) * s) + fabs((box[3] - box[1]) * c)) / bead) + 1;
}

typedef struct emitter {
    const lam_sink *sink;
    const lam_frame *f;
    const lam_plan_opts *o;
    double c, s, w;        /* rotation of the scan frame; layer height */
    double *pos;           /* stage, output frame */
    double ur, vr;         /* stage in the scan frame */
    int *laser;
    lam_ladrp_stats *st;
} emitter;

/* The layer frame's (u, v) of a scan-frame point, and the output frame's. */
static void to_output(const emitter *e, double ur, double vr, double uv[2], double out[3])
{
    double u = e->s == 0 ? ur * e->c : ur * e->c - vr * e->s;
    double v = e->s == 0 ? vr * e->c : ur * e->s + vr * e->c;
    uv[0] = u;
    uv[1] = v;
    if (e->o->frame_machine) {
        out[0] = u;
        out[1] = v;
        out[2] = e->w;
    } else {
        lam_frame_to_model(e->f, u, v, e->w, out);
    }
}

static int laser(emitter *e, int on)
{
    if (*e->laser == on) return LAM_OK;
    int rc = e->sink->laser ? e->sink->laser(e->sink->ctx, on) : LAM_OK;
    if (!rc && on && e->sink->feed) rc = e->sink->feed(e->sink->ctx, e->o->rate);
    *e->laser = on;
    return rc;
}

static int move(emitter *e, int deposit, double ur, double vr)
{
    int rc = laser(e, deposit);
    if (rc) return rc;
    lam_move_info m = { .attrs = lam_attrs_default(), .deposit = deposit };
    to_output(e, ur, vr, m.uv, m.xyz);
    double len = hypot(ur - e->ur, vr - e->vr);
    if (deposit) e->st->deposit_length += len;
    else e->st->travel_length += len;
    e->ur = ur;
    e->vr = vr;
    memcpy(e->pos, m.xyz, sizeof m.xyz);
    return e->sink->move ? e->sink->move(e->sink->ctx, &m) : LAM_OK;
}

/* Perimeter passes: each contour of each inset, travel to its start, then
 * deposit round it and back to the start. */
static int perimeters(emitter *e, const lam_layer *L, lam_layer **inner, lam_error *err)
{
    *inner = NULL;
    double d = e->o->bead;
    int rc = LAM_OK;
    double c = e->c, s = e->s;
    e->c = 1; /* perimeters follow the contours: no raster rotation */
    e->s = 0;
    for (int k = 0; k < e->o->perimeters && !rc; k++) {
        lam_layer *P;
        if ((rc = lam_layer_offset(L, -(d / 2 + k * d), &P, err))) break;
        for (size_t i = 0; i < P->ncontours && !rc; i++) {
            const lam_contour *ct = &P->contours[i];
            const double *uv = P->uv + 2 * ct->first;
            rc = move(e, 0, uv[0], uv[1]);
            for (size_t j = 1; j <= ct->n && !rc; j++) rc = move(e, 1, uv[2 * (j % ct->n)], uv[2 * (j % ct->n) + 1]);
            e->st->deposits++;
        }
        lam_layer_free(P);
    }
    e->c = c;
    e->s = s;
    if (!rc) rc = lam_layer_offset(L, -(e->o->perimeters * d), inner, err);
    /* the raster continues from the stage in its own (rotated) frame */
    double u = e->ur, v = e->vr;
    e->ur = s == 0 ? u * c : u * c + v * s;
    e->vr = s == 0 ? v * c : -u * s + v * c;
    return rc;
}

/* The region's edges in the scan frame (rotated by -angle) into edges,
 * sorted by their top, and the region's extent across the lines; returns
 * how many (edges along the scan direction are never crossed: left out). */
static size_t scan_edges(const emitter *e, const lam_layer *L, xedge *edges, double *vmin, double *vmax)
{
    size_t ne = 0;
    *vmin = INFINITY, *vmax = -INFINITY;
    for (size_t k = 0; k < L->ncontours; k++) {
        const lam_contour *c = &L->contours[k];
        for (size_t i = 0; i < c->n; i++) {
            size_t j = (i + 1) % c->n;
            const double *p = L->uv + 2 * (c->first + i), *q = L->uv + 2 * (c->first + j);
            double pu = e->s == 0 ? p[0] * e->c : p[0] * e->c + p[1] * e->s;
            double pv = e->s == 0 ? p[1] * e->c : -p[0] * e->s + p[1] * e->c;
            double qu = e->s == 0 ? q[0] * e->c : q[0] * e->c + q[1] * e->s;
            double qv = e->s == 0 ? q[1] * e->c : -q[0] * e->s + q[1] * e->c;
            if (pv < *vmin) *vmin = pv;
            if (pv > *vmax) *vmax = pv;
            if (pv == qv) continue; /* along the scan direction: never crossed */
            xedge *x = &edges[ne++];
            if (pv < qv) { x->vlo = pv; x->ulo = pu; x->vhi = qv; x->uhi = qu; }
            else { x->vlo = qv; x->ulo = qu; x->vhi = pv; x->uhi = pu; }
        }
    }
    if (ne) qsort(edges, ne, sizeof *edges, cmp_vhi_desc);
    return ne;
}

/* The raster of one region (a layer, or one island of it). */
static int raster(emitter *e, const lam_layer *L, int approach, lam_error *err)
{
    const lam_plan_opts *o = e->o;
    lam_ladrp_stats *st = e->st;
    xedge *edges = malloc((L->npoints + 1) * sizeof *edges);
    double *xs = malloc((L->npoints + 1) * sizeof *xs);
    uint32_t *active = malloc((L->npoints + 1) * sizeof *active);
    if (!edges || !xs || !active) {
        free(edges);
        free(xs);
        free(active);
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory planning a layer");
    }
    double vmin, vmax;
    size_t ne = scan_edges(e, L, edges, &vmin, &vmax);

    int rc = LAM_OK;
    double d = o->bead;
    double y0 = o->first_center ? vmax - d / 2 : vmax;
    size_t ins = 0, nact = 0, emitted = 0;
    for (size_t k = 0; ne && rc == LAM_OK; k++) {
        double y = y0 - (double)k * d; /* never accumulated */
        if (!(y > vmin)) break;
        /* the line is evaluated just below y: an edge counts when vlo < y <= vhi */
        while (ins < ne && edges[ins].vhi >= y) active[nact++] = (uint32_t)ins++;
        size_t keep = 0, nx = 0;
        for (size_t a = 0; a < nact; a++) {
            const xedge *x = &edges[active[a]];
            if (!(x->vlo < y)) continue; /* passed: lines only go down */
            active[keep++] = active[a];
            double t = (y - x->vlo) / (x->vhi - x->vlo);
            xs[nx++] = x->ulo == x->uhi ? x->ulo : (1 - t) * x->ulo + t * x->uhi;
        }
        nact = keep;
        nx &= ~(size_t)1; /* an odd count only comes from a degenerate layer */
        if (nx == 0) continue;
        qsort(xs, nx, sizeof *xs, cmp_double);
        int backward = o->alternate && emitted % 2 == 1;
        size_t ndep = 0;
        for (size_t i = 0; i < nx / 2 && !rc; i++) {
            size_t pi = backward ? nx / 2 - 1 - i : i;
            double a = xs[2 * pi], b = xs[2 * pi + 1];
            if (b - a < o->min_deposit || !(b > a)) continue;
            double from = backward ? b : a, to = backward ? a : b;
            if (approach && emitted == 0 && ndep == 0) {
                /* the thesis's approach: one bead above the first line, then down */
                rc = move(e, 0, from, y + d);
                if (!rc) rc = move(e, 0, from, y);
            } else if (e->ur != from || e->vr != y) {
                rc = move(e, 0, from, y);
            }
            if (!rc) rc = move(e, 1, to, y);
            ndep++;
            st->deposits++;
        }
        if (ndep) {
            emitted++;
            st->lines++;
        }
    }
    free(edges);
    free(xs);
    free(active);
    return rc;
}

/* The island of root contour r: it and every contour nested in it, as a
 * layer of its own. */
static lam_layer *island(const lam_layer *L, size_t r)
{
    lam_layer *I = calloc(1, sizeof *I);
    size_t n = 0, pts = 0;
    long *map = malloc((L->ncontours + 1) * sizeof *map);
    if (!I || !map) goto fail;
    for (size_t k = 0; k < L->ncontours; k++) {
        long p = (long)k;
        while (p >= 0 && (size_t)p != r) p = L->contours[p].parent;
        map[k] = p < 0 ? -1 : (long)n++;
        if (map[k] >= 0) pts += L->contours[k].n;
    }
    I->contours = calloc(n + 1, sizeof *I->contours);
    I->uv = malloc((2 * pts + 1) * sizeof *I->uv);
    if (!I->contours || !I->uv) goto fail;
    *I = (lam_layer){ .index = L->index, .floor = L->floor, .ceiling = L->ceiling, .width = L->width,
                      .cut = L->cut, .uv = I->uv, .contours = I->contours, .ncontours = n, .gap = L->gap };
    for (size_t k = 0; k < L->ncontours; k++) {
        if (map[k] < 0) continue;
        lam_contour *c = &I->contours[map[k]];
        *c = L->contours[k];
        c->first = I->npoints;
        c->parent = c->parent >= 0 ? map[c->parent] : -1;
        memcpy(I->uv + 2 * I->npoints, L->uv + 2 * L->contours[k].first, 2 * c->n * sizeof *I->uv);
        I->npoints += c->n;
    }
    free(map);
    return I;
fail:
    free(map);
    lam_layer_free(I);
    return NULL;
}

/* Islands one after the other, each next one the nearest to the stage (by
 * the corner where its raster starts), so the stage crosses the gaps
 * between islands once instead of on every scan line. */
static int raster_islands(emitter *e, const lam_layer *L, lam_error *err)
{
    size_t nroots = 0;
    for (size_t k = 0; k < L->ncontours; k++) nroots += L->contours[k].parent < 0;
    lam_layer **isl = calloc(nroots + 1, sizeof *isl);
    double *corner = malloc((2 * nroots + 1) * sizeof *corner);
    int rc = isl && corner ? LAM_OK : LAM_ENOMEM;
    size_t ni = 0;
    for (size_t k = 0; k < L->ncontours && !rc; k++) {
        if (L->contours[k].parent >= 0) continue;
        if (!(isl[ni] = island(L, k))) {
            rc = LAM_ENOMEM;
            break;
        }
        /* the top-left corner of its bounding box in the scan frame */
        const lam_contour *c = &L->contours[k];
        double umin = INFINITY, vmax = -INFINITY;
        for (size_t i = 0; i < c->n; i++) {
            const double *p = L->uv + 2 * (c->first + i);
            double pu = e->s == 0 ? p[0] * e->c : p[0] * e->c + p[1] * e->s;
            double pv = e->s == 0 ? p[1] * e->c : -p[0] * e->s + p[1] * e->c;
            if (pu < umin) umin = pu;
            if (pv > vmax) vmax = pv;
        }
        corner[2 * ni] = umin;
        corner[2 * ni + 1] = vmax;
        ni++;
    }
    if (rc) lam_error_set(err, rc, NULL, 0, 0, "out of memory planning a layer");
    for (size_t done = 0; done < ni && !rc; done++) {
        size_t best = ni;
        double bd = INFINITY;
        for (size_t i = 0; i < ni; i++) {
            if (!isl[i]) continue;
            double dd = hypot(corner[2 * i] - e->ur, corner[2 * i + 1] - e->vr);
            if (dd < bd) {
                bd = dd;
                best = i;
            }
        }
        rc = raster(e, isl[best], 1, err);
        lam_layer_free(isl[best]);
        isl[best] = NULL;
    }
    for (size_t i = 0; i < ni; i++) lam_layer_free(isl[i]);
    free(isl);
    free(corner);
    return rc;
}

int lam_plan_ladrp_layer(const lam_layer *L0, const lam_frame *f, const lam_plan_opts *o,
                         const lam_sink *sink, double pos[3], int *laser_state, lam_ladrp_stats *st,
                         lam_error *err)
{
    memset(st, 0, sizeof *st);
    if (!(o->bead > 0) || !isfinite(o->bead))
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "bead width must be positive");
    emitter e = { sink, f, o, 1, 0, L0->cut, pos, 0, 0, laser_state, st };
    rotation(o->angle + (double)L0->index * o->angle_step, &e.c, &e.s);
    /* the stage in the scan frame, for travel lengths and island order */
    {
        double u, v;
        if (o->frame_machine) {
            u = pos[0];
            v = pos[1];
        } else {
            u = pos[0] * f->u[0] + pos[1] * f->u[1] + pos[2] * f->u[2];
            v = pos[0] * f->v[0] + pos[1] * f->v[1] + pos[2] * f->v[2];
        }
        e.ur = e.s == 0 ? u * e.c : u * e.c + v * e.s;
        e.vr = e.s == 0 ? v * e.c : -u * e.s + v * e.c;
    }
    const lam_layer *L = L0;
    lam_layer *inner = NULL;
    int rc = LAM_OK;
    if (o->perimeters > 0) {
        rc = perimeters(&e, L0, &inner, err);
        L = inner;
    }
    if (!rc) rc = o->islands ? raster_islands(&e, L, err) : raster(&e, L, o->perimeters <= 0, err);
    if (!rc) rc = laser(&e, 0);
    lam_layer_free(inner);
    return rc;
}
