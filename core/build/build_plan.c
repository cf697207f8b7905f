/* Planning a build plate layer by layer (build_plan.h): workers plan every
 * part that reaches a layer and share the layer between the lasers; the
 * calling thread writes the layers in order through the ordered pool
 * (pool.h), so the program is the same for any number of threads. */
#include "build_plan.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "pool.h"

/* A worker's sweep over one part: a fork of its slicer and the layers
 * around the one planned (skins look 2 s + 1 layers wide). */
typedef struct part_sweep {
    lam_slicer *fork;
    size_t next;             /* the layer fork gives next */
    lam_layer **ring;
    size_t *held;            /* the local layer each ring slot holds (SIZE_MAX: none) */
} part_sweep;

typedef struct worker {
    part_sweep *sweeps;      /* one per part, made when first needed */
    lam_blayer collect;      /* the layer's blocks before the lasers */
} worker;

/* One layer planned and not yet written. */
typedef struct slot {
    lam_blayer out;          /* the blocks, shared and ordered */
    lam_scan_time lasers[LAM_LASERS_MAX];
    size_t *parts;           /* the parts planned on the layer ... */
    lam_scan_time *ptime;    /* ... and each one's estimate */
    size_t nparts;
    double cut;
    lam_layer sec;           /* the parts' sections together (the JSON's contours) */
    long long *sec_part;     /* the part of each of its contours */
    size_t sec_cap, pts_cap;
    lam_layer sup;           /* the parts' support regions together (the JSON's, region support) */
    long long *sup_part;
    size_t sup_cap, sup_pts_cap;
    lam_layer over;          /* ... and their overhangs (region overhang) */
    long long *over_part;
    size_t over_cap, over_pts_cap;
    lam_error err;
} slot;

typedef struct drive {
    lam_build_run *r;
    const lam_run_opts *o;
    const lam_sink *sink;
    size_t first, n;         /* plate layers first .. first + n - 1 */
    size_t ring;             /* 2 s + 1 */
    worker *ws;
    unsigned nws;
    slot *slots;
    size_t window;
    double *xyz;             /* the writer's scratch */
    size_t xyz_cap;
    lam_part_time *pt;       /* the layer's parts' times (nparts) */
    size_t consumed;         /* layers handed to the writer so far */
    lam_scan_cfg cfg;        /* the machine's jumps and recoating */
    lam_error *err;
} drive;

/* ---- collecting a part's operations ------------------------------------------ */

typedef struct collect_ctx {
    lam_blayer *l;
    const lam_run_part *p;
    lam_error *err;
} collect_ctx;

static void block_from(lam_bblock *b, const lam_attrs *a, int kind, const lam_run_part *p)
{
    memset(b, 0, sizeof *b);
    b->attrs = *a;
    b->attrs.style = p->style_id[kind];
    b->kind = kind;
}

static int collect_contour(void *ctx, const lam_contour_info *c)
{
    collect_ctx *cc = ctx;
    lam_bblock b;
    block_from(&b, &c->attrs, LAM_KIND_CONTOUR, cc->p);
    b.polyline = 1;
    b.solid = c->solid;
    b.depth = c->depth;
    b.exposure = (lam_exposure){ c->power, c->speed, c->point_distance, c->exposure_time };
    b.n = c->n;
    return lam_blayer_push(cc->l, &b, c->uv, c->n, cc->err);
}

static int collect_hatches(void *ctx, const lam_hatch_info *h)
{
    collect_ctx *cc = ctx;
    lam_bblock b;
    block_from(&b, &h->attrs, h->kind, cc->p);
    b.angle = h->angle;
    b.exposure = (lam_exposure){ h->power, h->speed, h->point_distance, h->exposure_time };
    b.n = h->n;
    return lam_blayer_push(cc->l, &b, h->uv, 2 * h->n, cc->err);
}

/* ---- a worker's layers ---------------------------------------------------------- */

static int sweep_layer(drive *d, part_sweep *s, const lam_run_part *p, size_t j, const lam_layer **out, lam_error *err)
{
    size_t k = j % d->ring;
    if (s->held[k] == j) {
        *out = s->ring[k];
        return LAM_OK;
    }
    int rc = s->fork ? LAM_OK : lam_slicer_fork(p->slicer, &s->fork, err);
    if (rc) return rc;
    if (s->next != j) lam_slicer_seek(s->fork, j);
    lam_layer *L = NULL;
    if ((rc = lam_slicer_next(s->fork, &L, err))) return rc;
    if (!L) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %s: layer %zu is past its end", p->name, j + 1);
    s->next = j + 1;
    lam_layer_free(s->ring[k]);
    s->ring[k] = L;
    s->held[k] = j;
    *out = L;
    return LAM_OK;
}

static int sweep_open(drive *d, part_sweep *s, lam_error *err)
{
    if (s->ring) return LAM_OK;
    s->ring = calloc(d->ring, sizeof *s->ring);
    s->held = malloc(d->ring * sizeof *s->held);
    if (!s->ring || !s->held) return lam_error_nomem(err, "planning a build");
    for (size_t k = 0; k < d->ring; k++) s->held[k] = SIZE_MAX;
    s->next = 0;
    return LAM_OK;
}

static void sweep_free(drive *d, part_sweep *s)
{
    for (size_t k = 0; s->ring && k < d->ring; k++) lam_layer_free(s->ring[k]);
    free(s->ring);
    free(s->held);
    lam_slicer_free(s->fork);
}

/* Part p's local layer j planned into the worker's blocks; its estimate
 * into *t. */
static int plan_part(drive *d, worker *w, size_t pi, size_t j, lam_scan_time *t, const lam_layer **sec,
                     lam_error *err)
{
    const lam_run_part *p = &d->r->parts[pi];
    part_sweep *s = &w->sweeps[pi];
    int rc = sweep_open(d, s, err);
    size_t sk = (d->ring - 1) / 2, lo = j >= sk ? j - sk : 0, hi = j + sk < p->count ? j + sk : p->count - 1;
    const lam_layer *near[2 * LAM_SKIN_MAX + 1];
    for (size_t i = lo; i <= hi && !rc; i++) rc = sweep_layer(d, s, p, i, &near[i - lo], err);
    if (rc) return rc;
    const lam_layer *below[LAM_SKIN_MAX], *above[LAM_SKIN_MAX];
    size_t nb = j - lo, na = hi - j;
    for (size_t i = 0; i < nb; i++) below[i] = near[j - lo - 1 - i];
    for (size_t i = 0; i < na; i++) above[i] = near[j - lo + 1 + i];
    lam_sls_state st;
    lam_sls_state_init(&st);
    st.attrs.part = (long long)pi + 1;
    collect_ctx cc = { &w->collect, p, err };
    lam_sink sink = { .ctx = &cc, .contour = collect_contour, .hatches = collect_hatches };
    rc = lam_plan_sls_layer(near[j - lo], below, nb, above, na, &d->r->frame, &p->po, &sink, NULL, &st, err);
    *t = st.time;
    *sec = near[j - lo];
    lam_sls_state_free(&st);
    return rc;
}

/* ---- a layer: the parts, then the lasers ------------------------------------- */

static int slot_note_part(slot *s, size_t pi, const lam_scan_time *t, lam_error *err)
{
    size_t *np = realloc(s->parts, (s->nparts + 1) * sizeof *np);
    if (np) s->parts = np;
    lam_scan_time *nt = np ? realloc(s->ptime, (s->nparts + 1) * sizeof *nt) : NULL;
    if (nt) s->ptime = nt;
    if (!np || !nt) return lam_error_nomem(err, "planning a build");
    s->parts[s->nparts] = pi;
    s->ptime[s->nparts++] = *t;
    return LAM_OK;
}

/* Part pi's contours L appended to m (with each contour's part in *part;
 * cap, pts_cap: the arrays' room). */
static int add_contours(lam_layer *m, long long **part, size_t *cap_c, size_t *cap_p, const lam_layer *L, size_t pi,
                        lam_error *err)
{
    size_t nc = m->ncontours + L->ncontours, np = m->npoints + L->npoints;
    if (nc > *cap_c) {
        size_t cap = lam_grow_cap(*cap_c, nc, 16, sizeof *m->contours);
        lam_contour *c = cap ? realloc(m->contours, cap * sizeof *c) : NULL;
        long long *pp = c ? realloc(*part, cap * sizeof *pp) : NULL;
        if (c) m->contours = c;
        if (pp) *part = pp;
        if (!pp) return lam_error_nomem(err, "planning a build");
        *cap_c = cap;
    }
    if (np > *cap_p) {
        size_t cap = lam_grow_cap(*cap_p, np, 64, 2 * sizeof *m->uv);
        double *uv = cap ? realloc(m->uv, 2 * cap * sizeof *uv) : NULL;
        if (!uv) return lam_error_nomem(err, "planning a build");
        m->uv = uv;
        *cap_p = cap;
    }
    if (L->npoints) memcpy(m->uv + 2 * m->npoints, L->uv, 2 * L->npoints * sizeof *m->uv);
    for (size_t k = 0; k < L->ncontours; k++) {
        lam_contour c = L->contours[k];
        c.first += m->npoints;
        if (c.parent >= 0) c.parent += (long)m->ncontours;
        m->contours[m->ncontours + k] = c;
        (*part)[m->ncontours + k] = (long long)pi + 1;
    }
    m->ncontours = nc;
    m->npoints = np;
    return LAM_OK;
}

/* Part pi's section L (and its support region on the part's layer j)
 * appended to the layer's. */
static int add_section(slot *s, const lam_run_part *p, size_t j, const lam_layer *L, size_t pi, lam_error *err)
{
    int rc = add_contours(&s->sec, &s->sec_part, &s->sec_cap, &s->pts_cap, L, pi, err);
    const lam_layer *R = lam_supports_region(p->supports, j), *O = lam_supports_overhang(p->supports, j);
    if (!rc && R) rc = add_contours(&s->sup, &s->sup_part, &s->sup_cap, &s->sup_pts_cap, R, pi, err);
    if (!rc && O) rc = add_contours(&s->over, &s->over_part, &s->over_cap, &s->over_pts_cap, O, pi, err);
    return rc;
}

/* Every operation's CLI id from its (part, style, laser). */
static int label_blocks(const lam_build_run *r, lam_blayer *l, lam_error *err)
{
    for (size_t i = 0; i < l->n; i++) {
        lam_attrs *a = &l->b[i].attrs;
        a->label = lam_build_run_label(r, a->part, a->style, a->laser);
        if (!a->label)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %lld: no label for style %lld and laser %lld",
                                 a->part, a->style, a->laser);
    }
    return LAM_OK;
}

static double plate_cut(const lam_build_run *r, size_t k)
{
    double a = (double)k * r->width, b = (double)(k + 1) * r->width;
    return r->cut == LAM_CUT_FLOOR ? a : r->cut == LAM_CUT_CEILING ? b : (a + b) / 2;
}

static int plan_layer(drive *d, unsigned wi, size_t k, slot *s)
{
    worker *w = &d->ws[wi];
    const lam_build_run *r = d->r;
    lam_blayer_clear(&w->collect);
    s->nparts = 0;
    s->cut = plate_cut(r, k);
    s->sec.ncontours = s->sec.npoints = 0;
    s->sup.ncontours = s->sup.npoints = 0;
    s->over.ncontours = s->over.npoints = 0;
    int rc = LAM_OK;
    for (size_t pi = 0; pi < r->nparts && !rc; pi++) {
        const lam_run_part *p = &r->parts[pi];
        if (k >= p->first + p->count && w->sweeps[pi].fork) { /* the part has ended: its sweep goes */
            sweep_free(d, &w->sweeps[pi]);
            memset(&w->sweeps[pi], 0, sizeof w->sweeps[pi]);
        }
        if (k < p->first || k >= p->first + p->count) continue;
        lam_scan_time t;
        const lam_layer *L = NULL;
        lam_error e;
        lam_error_clear(&e);
        rc = plan_part(d, w, pi, k - p->first, &t, &L, &e);
        if (rc) rc = lam_error_set(&s->err, rc, e.file[0] ? e.file : NULL, e.line, e.column, "part %s, layer %zu: %s",
                                   p->name, k + 1, e.msg);
        if (!rc) s->cut = lam_slicer_cut(p->slicer, k - p->first);
        if (!rc) rc = slot_note_part(s, pi, &t, &s->err);
        if (!rc) rc = add_section(s, p, k - p->first, L, pi, &s->err);
    }
    if (!rc) rc = lam_lasers_share(&r->lasers, &d->cfg, &w->collect, &s->out, s->lasers, &s->err);
    if (!rc) rc = label_blocks(r, &s->out, &s->err);
    return rc;
}

static int produce(void *ctx, unsigned wi, size_t t)
{
    drive *d = ctx;
    slot *s = &d->slots[t % d->window];
    lam_error_clear(&s->err);
    return plan_layer(d, wi, d->first + t, s);
}

/* ---- writing a layer ------------------------------------------------------------ */

static int scratch(drive *d, size_t npts)
{
    if (npts <= d->xyz_cap) return LAM_OK;
    double *x = npts < SIZE_MAX / (3 * sizeof *x) ? realloc(d->xyz, 3 * npts * sizeof *x) : NULL;
    if (!x) return lam_error_nomem(d->err, "writing a build layer");
    d->xyz = x;
    d->xyz_cap = npts;
    return LAM_OK;
}

static int write_block(drive *d, const lam_bblock *b, double top)
{
    size_t np = lam_bblock_points(b);
    int rc = scratch(d, np ? np : 1);
    if (rc) return rc;
    for (size_t i = 0; i < np; i++) {
        d->xyz[3 * i] = b->uv[2 * i];
        d->xyz[3 * i + 1] = b->uv[2 * i + 1];
        d->xyz[3 * i + 2] = top;
    }
    const lam_exposure *e = &b->exposure;
    const lam_sink *k = d->sink;
    if (b->polyline) {
        lam_contour_info c = { .attrs = b->attrs, .solid = b->solid, .depth = b->depth, .z = top, .xyz = d->xyz,
                               .uv = b->uv, .n = b->n, .power = e->power, .speed = e->speed,
                               .point_distance = e->point_distance, .exposure_time = e->exposure_time };
        return k->contour ? k->contour(k->ctx, &c) : LAM_OK;
    }
    lam_hatch_info h = { .attrs = b->attrs, .kind = b->kind, .z = top, .xyz = d->xyz, .uv = b->uv, .n = b->n,
                         .angle = b->angle, .power = e->power, .speed = e->speed,
                         .point_distance = e->point_distance, .exposure_time = e->exposure_time };
    return k->hatches ? k->hatches(k->ctx, &h) : LAM_OK;
}

/* The layer's estimate: every laser's counts and lengths, the busiest
 * laser's exposure and jumps, one recoating. */
static lam_scan_time layer_time(const drive *d, const slot *s)
{
    lam_scan_time t;
    memset(&t, 0, sizeof t);
    size_t busiest = 0;
    for (size_t l = 0; l < d->r->lasers.n; l++) {
        const lam_scan_time *x = &s->lasers[l];
        t.contours += x->contours;
        t.vectors += x->vectors;
        t.jumps += x->jumps;
        t.exposure_length += x->exposure_length;
        t.jump_length += x->jump_length;
        t.hatch_length += x->hatch_length;
        const lam_scan_time *b = &s->lasers[busiest];
        if (x->exposure + x->jump > b->exposure + b->jump) busiest = l;
    }
    t.layers = 1;
    t.exposure = s->lasers[busiest].exposure;
    t.jump = s->lasers[busiest].jump;
    t.recoat = d->cfg.recoat_time;
    return t;
}

static int write_layer(drive *d, size_t k, const slot *s)
{
    const lam_build_run *r = d->r;
    double top = (double)(k + 1) * r->width;
    lam_layer sec = s->sec;
    sec.index = k;
    sec.cut = s->cut;
    sec.floor = (double)k * r->width;
    sec.ceiling = top;
    sec.width = r->width;
    lam_layer_info li = { .index = k, .z = top, .width = r->width, .floor = sec.floor, .ceiling = top,
                          .section = &sec, .has_cut = 1, .cut = s->cut, .section_part = s->sec_part,
                          .support = s->sup.ncontours ? &s->sup : NULL, .support_part = s->sup_part,
                          .overhang = s->over.ncontours ? &s->over : NULL, .overhang_part = s->over_part };
    const lam_sink *sk = d->sink;
    int rc = d->o->section ? d->o->section(d->o->user, &sec, d->err) : LAM_OK;
    if (!rc && sk->layer) rc = sk->layer(sk->ctx, &li);
    for (size_t i = 0; i < s->out.n && !rc; i++) rc = write_block(d, &s->out.b[i], top);
    lam_scan_time t = layer_time(d, s);
    li.time = &t;
    li.lasers = s->lasers;
    li.nlasers = r->lasers.n;
    li.balance = lam_lasers_balance(s->lasers, r->lasers.n);
    for (size_t i = 0; i < s->nparts; i++)
        d->pt[i] = (lam_part_time){ (long long)s->parts[i] + 1, s->ptime[i].exposure + s->ptime[i].jump };
    li.parts = d->pt;
    li.nparts = s->nparts;
    if (!rc && sk->layer_end) rc = sk->layer_end(sk->ctx, &li);
    for (size_t i = 0; i < s->nparts && !rc; i++) lam_scan_time_add(&d->r->parts[s->parts[i]].time, &s->ptime[i]);
    if (!rc && d->o->planned) d->o->planned(d->o->user, k, &t, s->lasers, r->lasers.n);
    return rc;
}

static int consume(void *ctx, size_t t, int rc)
{
    drive *d = ctx;
    const slot *s = &d->slots[t % d->window];
    size_t k = d->first + t;
    d->consumed++;
    if (rc) {
        if (d->err) *d->err = s->err;
        return rc;
    }
    if (d->o->stop && (rc = d->o->stop(d->o->user, k))) return rc;
    return write_layer(d, k, s);
}

/* ---- the run ---------------------------------------------------------------------- */

static int drive_open(drive *d, unsigned threads, lam_error *err)
{
    const lam_build_run *r = d->r;
    size_t skins = r->nparts ? (size_t)r->parts[0].po.scan.skin_layers : 0;
    d->ring = 2 * skins + 1;
    d->nws = threads;
    d->window = threads > 1 ? lam_pool_window(4, 0, 4 * ((size_t)threads + 1)) : 1;
    d->ws = calloc(threads, sizeof *d->ws);
    d->slots = calloc(d->window, sizeof *d->slots);
    d->pt = calloc(r->nparts ? r->nparts : 1, sizeof *d->pt);
    if (!d->ws || !d->slots || !d->pt) return lam_error_nomem(err, "planning a build");
    for (unsigned i = 0; i < threads; i++)
        if (!(d->ws[i].sweeps = calloc(r->nparts ? r->nparts : 1, sizeof *d->ws[i].sweeps)))
            return lam_error_nomem(err, "planning a build");
    d->cfg = r->b->profile->scan;
    return LAM_OK;
}

static void drive_close(drive *d)
{
    for (unsigned i = 0; d->ws && i < d->nws; i++) {
        for (size_t p = 0; d->ws[i].sweeps && p < d->r->nparts; p++) sweep_free(d, &d->ws[i].sweeps[p]);
        free(d->ws[i].sweeps);
        lam_blayer_free(&d->ws[i].collect);
    }
    for (size_t k = 0; d->slots && k < d->window; k++) {
        lam_blayer_free(&d->slots[k].out);
        free(d->slots[k].parts);
        free(d->slots[k].ptime);
        free(d->slots[k].sec.uv);
        free(d->slots[k].sec.contours);
        free(d->slots[k].sec_part);
        free(d->slots[k].sup.uv);
        free(d->slots[k].sup.contours);
        free(d->slots[k].sup_part);
        free(d->slots[k].over.uv);
        free(d->slots[k].over.contours);
        free(d->slots[k].over_part);
    }
    free(d->ws);
    free(d->slots);
    free(d->xyz);
    free(d->pt);
}

/* The layers on the calling thread, one after the other. */
static int run_here(drive *d)
{
    for (size_t t = 0; t < d->n; t++) {
        int rc = consume(d, t, produce(d, 0, t));
        if (rc) return rc;
    }
    return LAM_OK;
}

int lam_build_run_plan(lam_build_run *r, const lam_run_opts *o, const lam_sink *sink, lam_error *err)
{
    static const lam_run_opts none;
    if (!o) o = &none;
    drive d = { .r = r, .o = o, .sink = sink, .err = err };
    d.first = o->layer_count ? o->layer_first : 0;
    d.n = o->layer_count ? o->layer_count : r->layers;
    if (d.first > r->layers || d.n > r->layers - d.first)
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "layers %zu to %zu of a plate of %zu", d.first + 1,
                             d.first + d.n, r->layers);
    for (size_t i = 0; i < r->nparts; i++) memset(&r->parts[i].time, 0, sizeof r->parts[i].time);
    unsigned threads = o->threads > 1 ? o->threads : 1;
    int rc = drive_open(&d, threads, err);
    if (!rc && sink->begin) rc = sink->begin(sink->ctx, &r->job);
    if (!rc && threads > 1) {
        rc = lam_pool_ordered(threads, d.n, 4, 0, d.window, produce, consume, &d, err);
        /* no thread could start (then nothing reached the sink): on this one */
        if (rc == LAM_ENOMEM && !d.consumed) rc = run_here(&d);
    } else if (!rc) {
        rc = run_here(&d);
    }
    if (!rc && sink->end) rc = sink->end(sink->ctx);
    drive_close(&d);
    return rc;
}
