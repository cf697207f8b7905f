/* Several lasers on one plate: see lasers.h. The work is done on items:
 * a block one field holds whole is one item; a block no field holds is
 * cut into pieces (the walk of cut_vector), and its pieces that the walk
 * gave one laser make one item. Items are balanced, then each laser's
 * blocks are emitted in the parts' downstream order, a cut block's pieces
 * that ended on one laser merged back into one block. */
#include "lasers.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"

typedef struct piece {
    double p[4];          /* u0 v0 u1 v1 */
    size_t item;
} piece;

typedef struct item {
    size_t block;         /* in `in` */
    unsigned mask;        /* the lasers whose fields hold it whole */
    int laser;            /* 0-based once assigned */
    double work;
} item;

typedef struct binfo {
    size_t item;          /* a whole block's item; SIZE_MAX: cut */
    size_t first, n;      /* a cut block's pieces */
} binfo;

typedef struct share {
    const lam_laser_set *ls;
    const lam_scan_cfg *cfg;
    const lam_blayer *in;
    double tol;           /* how far outside a field still counts as inside */
    unsigned all;         /* every laser's bit */
    piece *pc;
    size_t npc, cap_pc;
    item *it;
    size_t nit, cap_it;
    binfo *bi;
    size_t *order;        /* the blocks in the parts' downstream order */
} share;

static int nomem(lam_error *err) { return lam_error_nomem(err, "sharing a layer between lasers"); }

/* tol: 1e-9 of the plate's size, the plate being the fields' union (the
 * set has no other plate) */
static double field_tol(const lam_laser_set *ls)
{
    double b[4] = { ls->field[0][0], ls->field[0][1], ls->field[0][2], ls->field[0][3] };
    for (size_t k = 1; k < ls->n; k++) {
        b[0] = fmin(b[0], ls->field[k][0]), b[1] = fmin(b[1], ls->field[k][1]);
        b[2] = fmax(b[2], ls->field[k][2]), b[3] = fmax(b[3], ls->field[k][3]);
    }
    return 1e-9 * fmax(b[2] - b[0], b[3] - b[1]);
}

static unsigned point_mask(const share *s, double x, double y)
{
    unsigned m = 0;
    for (size_t k = 0; k < s->ls->n; k++) {
        const double *f = s->ls->field[k];
        if (x >= f[0] - s->tol && x <= f[2] + s->tol && y >= f[1] - s->tol && y <= f[3] + s->tol) m |= 1u << k;
    }
    return m;
}

/* the fields holding every point of b (a field is convex: its edges too) */
static unsigned block_mask(const share *s, const lam_bblock *b)
{
    unsigned m = s->all;
    size_t np = lam_bblock_points(b);
    for (size_t i = 0; i < np && m; i++) m &= point_mask(s, b->uv[2 * i], b->uv[2 * i + 1]);
    return m;
}

/* The part of the segment p + t d, t in [0, 1], inside field k grown by
 * tol: [*ta, *tb]. 0 when it misses the field. */
static int clip(const share *s, size_t k, const double p[2], const double d[2], double *ta, double *tb)
{
    const double *f = s->ls->field[k];
    double a = 0, b = 1;
    for (int ax = 0; ax < 2; ax++) {
        double lo = f[ax] - s->tol, hi = f[ax + 2] + s->tol;
        if (d[ax] == 0) {
            if (p[ax] < lo || p[ax] > hi) return 0;
            continue;
        }
        double t1 = (lo - p[ax]) / d[ax], t2 = (hi - p[ax]) / d[ax];
        if (t1 > t2) {
            double x = t1;
            t1 = t2, t2 = x;
        }
        a = fmax(a, t1), b = fmin(b, t2);
    }
    *ta = a, *tb = b;
    return a <= b;
}

/* a new piece of block b from laser w's walk, in the item grp[w] (made on
 * the block's first piece for w) */
static int add_piece(share *s, size_t b, size_t grp[], size_t w, const double p[4], lam_error *err)
{
    if (grp[w] == SIZE_MAX) {
        item *ni = s->nit == s->cap_it ? lam_grow(s->it, &s->cap_it, s->nit + 1, sizeof *ni, 16) : s->it;
        if (!ni) return nomem(err);
        s->it = ni;
        s->it[s->nit] = (item){ .block = b, .mask = s->all, .laser = -1 };
        grp[w] = s->nit++;
    }
    piece *np = s->npc == s->cap_pc ? lam_grow(s->pc, &s->cap_pc, s->npc + 1, sizeof *np, 64) : s->pc;
    if (!np) return nomem(err);
    s->pc = np;
    piece *q = &s->pc[s->npc++];
    memcpy(q->p, p, sizeof q->p);
    q->item = grp[w];
    /* the walk's own field holds the piece; the bit is forced so that a cut
     * point rounded by an ulp out of it cannot leave the item no laser */
    s->it[grp[w]].mask &= (point_mask(s, p[0], p[1]) & point_mask(s, p[2], p[3])) | 1u << w;
    return LAM_OK;
}

/* Cut vector v of block b at the fields' edges: from t, the field holding
 * the point at t whose part of the vector reaches furthest (the lowest
 * laser on a tie) takes the piece up to where it leaves; the next piece
 * starts there. Each field takes at most one piece (its part of a line is
 * one interval), so this ends. */
static int cut_vector(share *s, size_t b, size_t grp[], const double v[4], lam_error *err)
{
    double p[2] = { v[0], v[1] }, d[2] = { v[2] - v[0], v[3] - v[1] };
    double t = 0, cur[2] = { v[0], v[1] };
    while (t < 1) {
        double best = t, ta, tb;
        size_t w = SIZE_MAX;
        for (size_t k = 0; k < s->ls->n; k++)
            if (clip(s, k, p, d, &ta, &tb) && ta <= t && tb > best) best = tb, w = k;
        if (w == SIZE_MAX)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                                 "a vector at (%.6g, %.6g) of part %lld lies outside every laser's field", cur[0],
                                 cur[1], s->in->b[b].attrs.part);
        double q[4] = { cur[0], cur[1], v[2], v[3] };
        if (best < 1) {
            /* into the field: the cut point is computed, and may round out */
            const double *f = s->ls->field[w];
            q[2] = fmin(fmax(p[0] + best * d[0], f[0] - s->tol), f[2] + s->tol);
            q[3] = fmin(fmax(p[1] + best * d[1], f[1] - s->tol), f[3] + s->tol);
        }
        int rc = add_piece(s, b, grp, w, q, err);
        if (rc) return rc;
        cur[0] = q[2], cur[1] = q[3];
        t = best;
    }
    return LAM_OK;
}

/* block b held by no field: its vectors (a polyline's edges, the closing
 * one too) cut into pieces */
static int cut_block(share *s, size_t b, lam_error *err)
{
    const lam_bblock *B = &s->in->b[b];
    size_t grp[LAM_LASERS_MAX];
    for (size_t k = 0; k < LAM_LASERS_MAX; k++) grp[k] = SIZE_MAX;
    s->bi[b] = (binfo){ .item = SIZE_MAX, .first = s->npc };
    int rc = LAM_OK;
    for (size_t i = 0; i < B->n && !rc; i++) {
        double v[4];
        if (B->polyline) {
            size_t j = (i + 1) % B->n;
            v[0] = B->uv[2 * i], v[1] = B->uv[2 * i + 1], v[2] = B->uv[2 * j], v[3] = B->uv[2 * j + 1];
        } else {
            memcpy(v, B->uv + 4 * i, sizeof v);
        }
        rc = cut_vector(s, b, grp, v, err);
    }
    s->bi[b].n = s->npc - s->bi[b].first;
    return rc;
}

/* One vector's time. A contour's vector (a cut contour pass) is timed as
 * the open path it is (its points from end to end) but its length is not
 * a hatch vector's. */
static void time_vec(lam_scan_time *t, const lam_scan_cfg *cfg, const lam_bblock *b, const double *p, double pos[2],
                     int *have)
{
    double du = p[2] - p[0], dv = p[3] - p[1], hatch = t->hatch_length;
    lam_scan_time_path(t, cfg, &b->exposure, p, p + 2, sqrt(du * du + dv * dv), 0, pos, have);
    if (b->kind == LAM_KIND_CONTOUR) t->hatch_length = hatch;
}

/* A block's paths as plan_sls.c times them: a polyline one closed path of
 * its perimeter from its first point, vectors one path each. */
static void time_block(lam_scan_time *t, const lam_scan_cfg *cfg, const lam_bblock *b, double pos[2], int *have)
{
    if (!b->polyline) {
        for (size_t i = 0; i < b->n; i++) time_vec(t, cfg, b, b->uv + 4 * i, pos, have);
        return;
    }
    if (!b->n) return;
    double len = 0;
    for (size_t i = 0; i < b->n; i++) {
        size_t j = (i + 1) % b->n;
        double du = b->uv[2 * j] - b->uv[2 * i], dv = b->uv[2 * j + 1] - b->uv[2 * i + 1];
        len += sqrt(du * du + dv * dv);
    }
    lam_scan_time_path(t, cfg, &b->exposure, b->uv, b->uv, len, 1, pos, have);
}

/* an item's work: its exposure and inner jumps, and one jump delay to
 * reach it (none for an item with nothing to expose) */
static double item_work(const share *s, size_t ix)
{
    const item *I = &s->it[ix];
    const lam_bblock *B = &s->in->b[I->block];
    lam_scan_time t;
    memset(&t, 0, sizeof t);
    double pos[2] = { 0, 0 };
    int have = 0;
    if (s->bi[I->block].item == ix) {
        time_block(&t, s->cfg, B, pos, &have);
    } else {
        const binfo *bi = &s->bi[I->block];
        for (size_t i = bi->first; i < bi->first + bi->n; i++)
            if (s->pc[i].item == ix) time_vec(&t, s->cfg, B, s->pc[i].p, pos, &have);
    }
    return have ? t.exposure + t.jump + s->cfg->jump_delay : 0;
}

/* every block to items: whole, or cut */
static int make_items(share *s, lam_error *err)
{
    for (size_t b = 0; b < s->in->n; b++) {
        unsigned m = block_mask(s, &s->in->b[b]);
        if (!m) {
            int rc = cut_block(s, b, err);
            if (rc) return rc;
            continue;
        }
        item *ni = s->nit == s->cap_it ? lam_grow(s->it, &s->cap_it, s->nit + 1, sizeof *ni, 16) : s->it;
        if (!ni) return nomem(err);
        s->it = ni;
        s->it[s->nit] = (item){ .block = b, .mask = m, .laser = -1 };
        s->bi[b] = (binfo){ .item = s->nit++ };
    }
    for (size_t i = 0; i < s->nit; i++) s->it[i].work = item_work(s, i);
    return LAM_OK;
}

typedef struct lpt_key {
    double work;
    size_t ix;
} lpt_key;

/* longest first; ties by position (items are made in the blocks' order) */
static int lpt_cmp(const void *a, const void *b)
{
    const lpt_key *x = a, *y = b;
    if (x->work != y->work) return x->work > y->work ? -1 : 1;
    return (x->ix > y->ix) - (x->ix < y->ix);
}

/* Items one laser can take go to it; the others, longest first, to the
 * laser that can take them with the least work so far (the lowest on a
 * tie). */
static int assign(share *s, lam_error *err)
{
    double load[LAM_LASERS_MAX] = { 0 };
    lpt_key *keys = malloc((s->nit ? s->nit : 1) * sizeof *keys);
    if (!keys) return nomem(err);
    size_t nk = 0;
    for (size_t i = 0; i < s->nit; i++) {
        unsigned m = s->it[i].mask;
        if (m & (m - 1)) {
            keys[nk++] = (lpt_key){ s->it[i].work, i };
            continue;
        }
        for (size_t k = 0; k < s->ls->n; k++)
            if (m == 1u << k) s->it[i].laser = (int)k, load[k] += s->it[i].work;
    }
    qsort(keys, nk, sizeof *keys, lpt_cmp);
    for (size_t j = 0; j < nk; j++) {
        item *I = &s->it[keys[j].ix];
        size_t best = SIZE_MAX;
        for (size_t k = 0; k < s->ls->n; k++)
            if ((I->mask >> k & 1) && (best == SIZE_MAX || load[k] < load[best])) best = k;
        I->laser = (int)best;
        load[best] += I->work;
    }
    free(keys);
    return LAM_OK;
}

typedef struct part_key {
    double dot;
    long long part;
    size_t block;
} part_key;

/* downstream first, then part number, then the planners' order */
static int part_cmp(const void *a, const void *b)
{
    const part_key *x = a, *y = b;
    if (x->dot != y->dot) return x->dot > y->dot ? -1 : 1;
    if (x->part != y->part) return x->part < y->part ? -1 : 1;
    return (x->block > y->block) - (x->block < y->block);
}

/* s->order: the blocks part by part downstream first. A gas flow needs
 * every block's part to have a centre. */
static int part_order(share *s, lam_error *err)
{
    const lam_laser_set *ls = s->ls;
    int gas = ls->gas_flow[0] != 0 || ls->gas_flow[1] != 0;
    part_key *keys = malloc((s->in->n ? s->in->n : 1) * sizeof *keys);
    if (!keys) return nomem(err);
    for (size_t b = 0; b < s->in->n; b++) {
        long long p = s->in->b[b].attrs.part;
        keys[b] = (part_key){ 0, p, b };
        if (!gas) continue;
        if (p < 1 || (unsigned long long)p > ls->nparts || !ls->part_centre) {
            free(keys);
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %lld has no footprint centre for the gas flow",
                                 p);
        }
        const double *c = ls->part_centre + 2 * (p - 1);
        keys[b].dot = c[0] * ls->gas_flow[0] + c[1] * ls->gas_flow[1];
    }
    qsort(keys, s->in->n, sizeof *keys, part_cmp);
    for (size_t b = 0; b < s->in->n; b++) s->order[b] = keys[b].block;
    free(keys);
    return LAM_OK;
}

/* block b's share for laser k (0-based) onto out: the whole block, or its
 * pieces that went to k as one block of vectors (scratch: room for the
 * block's pieces) */
static int emit_block(const share *s, size_t b, size_t k, double *scratch, lam_blayer *out, lam_error *err)
{
    const lam_bblock *B = &s->in->b[b];
    const binfo *bi = &s->bi[b];
    lam_bblock nb = *B;
    nb.attrs.laser = (long long)k + 1;
    if (bi->item != SIZE_MAX) {
        if (s->it[bi->item].laser != (int)k) return LAM_OK;
        return lam_blayer_push(out, &nb, B->uv, lam_bblock_points(B), err);
    }
    size_t n = 0;
    for (size_t i = bi->first; i < bi->first + bi->n; i++)
        if (s->it[s->pc[i].item].laser == (int)k) memcpy(scratch + 4 * n++, s->pc[i].p, 4 * sizeof *scratch);
    if (!n) return LAM_OK;
    nb.polyline = 0;
    nb.n = n;
    return lam_blayer_push(out, &nb, scratch, 2 * n, err);
}

/* each laser's blocks in order onto out, and its time */
static int emit(const share *s, lam_blayer *out, lam_scan_time *times, lam_error *err)
{
    size_t most = 0;
    for (size_t b = 0; b < s->in->n; b++)
        if (s->bi[b].item == SIZE_MAX && s->bi[b].n > most) most = s->bi[b].n;
    double *scratch = lam_realloc_n(NULL, most ? most : 1, 4 * sizeof *scratch);
    if (!scratch) return nomem(err);
    int rc = LAM_OK;
    for (size_t k = 0; k < s->ls->n && !rc; k++) {
        size_t first = out->n;
        for (size_t j = 0; j < s->in->n && !rc; j++) rc = emit_block(s, s->order[j], k, scratch, out, err);
        double pos[2] = { 0, 0 };
        int have = 0;
        for (size_t j = first; j < out->n && !rc; j++) time_block(&times[k], s->cfg, &out->b[j], pos, &have);
        times[k].layers = have ? 1 : 0;
    }
    free(scratch);
    return rc;
}

static int check_set(const lam_laser_set *ls, lam_error *err)
{
    if (ls->n < 1 || ls->n > LAM_LASERS_MAX)
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "%zu lasers: a build has 1 to %d", ls->n, LAM_LASERS_MAX);
    for (size_t k = 0; k < ls->n; k++) {
        const double *f = ls->field[k];
        if (!(f[0] < f[2] && f[1] < f[3]))
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "laser %zu's field is empty", k + 1);
    }
    return LAM_OK;
}

int lam_lasers_share(const lam_laser_set *ls, const lam_scan_cfg *cfg, const lam_blayer *in, lam_blayer *out,
                     lam_scan_time *times, lam_error *err)
{
    lam_blayer_clear(out);
    int rc = check_set(ls, err);
    if (rc) return rc;
    memset(times, 0, ls->n * sizeof *times);
    share s = { .ls = ls, .cfg = cfg, .in = in, .tol = field_tol(ls) };
    s.all = (1u << ls->n) - 1;
    s.bi = lam_realloc_n(NULL, in->n ? in->n : 1, sizeof *s.bi);
    s.order = lam_realloc_n(NULL, in->n ? in->n : 1, sizeof *s.order);
    rc = !s.bi || !s.order ? nomem(err) : LAM_OK;
    if (!rc) rc = make_items(&s, err);
    if (!rc) rc = assign(&s, err);
    if (!rc) rc = part_order(&s, err);
    if (!rc) rc = emit(&s, out, times, err);
    if (rc) {
        lam_blayer_clear(out);
        memset(times, 0, ls->n * sizeof *times);
    }
    free(s.pc);
    free(s.it);
    free(s.bi);
    free(s.order);
    return rc;
}

double lam_lasers_balance(const lam_scan_time *times, size_t n)
{
    double most = 0, sum = 0;
    size_t busy = 0;
    for (size_t k = 0; k < n; k++) {
        double t = times[k].exposure + times[k].jump;
        if (t > 0) busy++, sum += t, most = fmax(most, t);
    }
    return busy ? most / (sum / (double)busy) : 1;
}
