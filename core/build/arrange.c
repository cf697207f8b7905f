#include "arrange.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmt.h"

/* The plate less its margin. */
typedef struct area {
    int round;
    double x0, y0, x1, y1; /* rectangle: the room inside the margin; round: the box of the circle */
    double r;              /* round: the room's radius */
    double tol;            /* 1e-9 of the plate's size: the slack of "fits" */
} area;

/* A box on the plate. */
typedef struct pbox {
    double x0, y0, x1, y1;
    size_t i; /* the item */
} pbox;

typedef struct row {
    double y, h, cursor; /* front edge, depth, where the next box may start */
} row;

typedef struct packer {
    const area *a;
    double s;
    const pbox *fixed;  /* sorted by x0 */
    size_t nfixed;
    double wmax;        /* the widest fixed part's x1 - x0 */
    const double *tops; /* the fixed parts' y1 + spacing, ascending */
    const double *w, *h; /* the automatic boxes in packing order */
    size_t nauto;
    row *rows;
    double *x, *y;      /* out: each box's front-left corner */
    unsigned char *placed;
} packer;

static const char *unit_sp(const char *units)
{
    return units && *units ? " " : "";
}

static const char *unit_of(const char *units)
{
    return units ? units : "";
}

/* An item's name for messages: its name, or "#" and its 1-based index. */
static const char *name_of(const lam_arrange_item *it, size_t i, char buf[32])
{
    if (it->name) return it->name;
    snprintf(buf, 32, "#%zu", i + 1);
    return buf;
}

/* "250 x 250 mm, margin 5" or "diameter 300 mm, margin 5". */
static const char *plate_text(const lam_plate *p, const char *units, char *buf, size_t size)
{
    if (p->round)
        snprintf(buf, size, "diameter %s%s%s, margin %s", LAM_NUM(p->diameter), unit_sp(units), unit_of(units),
                 LAM_NUM(p->margin));
    else
        snprintf(buf, size, "%s x %s%s%s, margin %s", LAM_NUM(p->width), LAM_NUM(p->depth), unit_sp(units),
                 unit_of(units), LAM_NUM(p->margin));
    return buf;
}

static int bad(double v)
{
    return !isfinite(v) || v < 0;
}

static int make_area(const lam_plate *p, double spacing, area *a, lam_error *err)
{
    if (!p) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "no plate to arrange the parts on");
    if (bad(spacing)) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "the spacing must be a number >= 0");
    if (bad(p->margin)) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "the plate's margin must be a number >= 0");
    memset(a, 0, sizeof *a);
    a->round = p->round != 0;
    if (a->round) {
        if (bad(p->diameter) || p->diameter == 0)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "the plate's diameter must be a number > 0");
        a->r = p->diameter / 2 - p->margin;
        a->x0 = a->y0 = -a->r;
        a->x1 = a->y1 = a->r;
        a->tol = 1e-9 * p->diameter;
    } else {
        if (bad(p->width) || bad(p->depth) || p->width == 0 || p->depth == 0)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "the plate's width and depth must be numbers > 0");
        a->x0 = a->y0 = p->margin;
        a->x1 = p->width - p->margin;
        a->y1 = p->depth - p->margin;
        a->tol = 1e-9 * fmax(p->width, p->depth);
    }
    if (a->x1 <= a->x0 || a->y1 <= a->y0)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "the plate's margin (%s) leaves no room for parts",
                             LAM_NUM(p->margin));
    return LAM_OK;
}

/* The room across the plate for a box spanning [ya, yb] in y: its x from
 * *xl to *xr (round: the chord at the box's corner furthest from the
 * centre). 0 when the span leaves the plate. */
static int span(const area *a, double ya, double yb, double *xl, double *xr)
{
    if (!a->round) {
        if (ya < a->y0 - a->tol || yb > a->y1 + a->tol) return 0;
        *xl = a->x0;
        *xr = a->x1;
        return 1;
    }
    double ym = fmax(fabs(ya), fabs(yb));
    if (ym > a->r + a->tol) return 0;
    double half = ym >= a->r ? 0 : sqrt((a->r - ym) * (a->r + ym));
    *xl = -half;
    *xr = half;
    return 1;
}

/* Whether box b lies inside the room (round: its 4 corners). */
static int inside(const area *a, const pbox *b)
{
    if (!a->round)
        return b->x0 >= a->x0 - a->tol && b->x1 <= a->x1 + a->tol && b->y0 >= a->y0 - a->tol &&
               b->y1 <= a->y1 + a->tol;
    double xm = fmax(fabs(b->x0), fabs(b->x1)), ym = fmax(fabs(b->y0), fabs(b->y1));
    double rr = a->r + a->tol;
    return hypot(xm, ym) <= rr;
}

/* Gaps between two boxes along x and along y (negative: they overlap). */
static double gap_x(const pbox *a, const pbox *b)
{
    return fmax(b->x0 - a->x1, a->x0 - b->x1);
}

static double gap_y(const pbox *a, const pbox *b)
{
    return fmax(b->y0 - a->y1, a->y0 - b->y1);
}

/* The first x >= x where a box w x h at y keeps the spacing from every
 * fixed part. The fixed parts are sorted by x0: one that starts the
 * spacing or more past the box's right edge ends the search (so do all
 * after it), and x only grows, so a part passed once never comes back. */
static double clear_of_fixed(const packer *pk, double x, double y, double w, double h)
{
    double lim = pk->s - pk->a->tol;
    /* the parts that start before x - wmax - lim end before x - lim (the
     * tol covers the rounding of x0 + wmax): they are clear on the left */
    double from = x - pk->wmax - lim - pk->a->tol;
    size_t lo = 0, hi = pk->nfixed;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (pk->fixed[mid].x0 < from)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (size_t k = lo; k < pk->nfixed; k++) {
        const pbox *f = &pk->fixed[k];
        if (f->x0 - (x + w) >= lim) break;
        if (fmax(f->y0 - (y + h), y - f->y1) >= lim) continue;
        if (x - f->x1 < lim) x = f->x1 + pk->s;
    }
    return x;
}

/* Place a box w x h in row r: its front-left corner in *x, *y; 0 when the
 * row has no room left for it. A box that passes the room's edge by no
 * more than the slack is moved back inside it. */
static int try_row(const packer *pk, const row *r, double w, double h, double *x, double *y)
{
    const area *a = pk->a;
    double yy = r->y, xl, xr;
    if (!a->round && yy + h > a->y1) {
        if (yy + h > a->y1 + a->tol) return 0;
        yy = a->y1 - h;
    }
    if (!span(a, yy, yy + h, &xl, &xr)) return 0;
    double xx = clear_of_fixed(pk, r->cursor > xl ? r->cursor : xl, yy, w, h);
    if (xx + w > xr) {
        if (xx + w > xr + a->tol) return 0;
        xx = xr - w;
    }
    *x = xx;
    *y = yy;
    return 1;
}

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Open a row for a box w x h at ycur or, when it has no room there, at
 * the first place further back where something changes: a fixed part
 * left behind. On a round plate nothing in front of the place where the
 * chord is as wide as the box can hold it, so the search starts there. */
static int open_row(packer *pk, double ycur, double w, double h, row *r, double *x, double *y)
{
    const area *a = pk->a;
    double c = ycur;
    if (a->round && w / 2 < a->r) c = fmax(c, -sqrt((a->r - w / 2) * (a->r + w / 2)));
    size_t k = 0;
    while (k < pk->nfixed && pk->tops[k] <= c) k++;
    for (;;) {
        if (c + h > a->y1 + a->tol) return 0;
        row t = { c, h, -INFINITY };
        if (try_row(pk, &t, w, h, x, y)) {
            *r = t;
            return 1;
        }
        while (k < pk->nfixed && pk->tops[k] <= c) k++;
        if (k == pk->nfixed) return 0;
        c = pk->tops[k++];
    }
}

/* The shelf packing from front edge ystart: first fit into the rows in
 * turn, else a new row. Returns how many boxes it placed. */
static size_t pack(packer *pk, double ystart)
{
    size_t nrows = 0, count = 0;
    double ycur = ystart;
    for (size_t k = 0; k < pk->nauto; k++) {
        double w = pk->w[k], h = pk->h[k], x = 0, y = 0;
        row *r = NULL;
        pk->placed[k] = 0;
        for (size_t j = 0; j < nrows && !r; j++)
            if (try_row(pk, &pk->rows[j], w, h, &x, &y)) r = &pk->rows[j];
        if (!r && open_row(pk, ycur, w, h, &pk->rows[nrows], &x, &y)) {
            r = &pk->rows[nrows++];
            ycur = r->y + r->h + pk->s;
        }
        if (!r) continue;
        r->cursor = x + w + pk->s;
        pk->x[k] = x;
        pk->y[k] = y;
        pk->placed[k] = 1;
        count++;
    }
    return count;
}

/* The front edges a round plate's packing tries, best first among equals:
 * the two centred stacks of rows as deep as the first box (a row or a gap
 * on the centre line), the first place its chord holds it, and 16 steps
 * through one row pitch from there. Returns how many. */
static size_t round_starts(const packer *pk, double starts[20])
{
    const area *a = pk->a;
    double w = pk->w[0], h = pk->h[0], pitch = h + pk->s;
    double front = w / 2 < a->r ? -sqrt((a->r - w / 2) * (a->r + w / 2)) : 0;
    size_t ns = 0;
    /* the most rows of that pitch from the front place to its mirror */
    double kmax = floor((2 * -front + pk->s) / pitch);
    if ((kmax + 1) * pitch - pk->s <= 2 * -front + a->tol) kmax++;
    for (double k = kmax; k >= 1 && k > kmax - 2; k--) starts[ns++] = -(k * pitch - pk->s) / 2;
    starts[ns++] = front;
    for (int j = 1; j < 16; j++) starts[ns++] = front + pitch * j / 16;
    return ns;
}

/* Pack the automatic boxes: on a round plate the best of round_starts
 * (kept in bx, by, bp), else from the room's front edge. Returns how many
 * it placed; the placement is left in pk's x, y, placed. */
static size_t pack_best(packer *pk, double *bx, double *by, unsigned char *bp)
{
    if (!pk->nauto) return 0;
    if (!pk->a->round) return pack(pk, pk->a->y0);
    double starts[20];
    size_t ns = round_starts(pk, starts), best = 0;
    int any = 0;
    for (size_t k = 0; k < ns; k++) {
        size_t c = pack(pk, starts[k]);
        if (!any || c > best) {
            any = 1;
            best = c;
            memcpy(bx, pk->x, pk->nauto * sizeof *bx);
            memcpy(by, pk->y, pk->nauto * sizeof *by);
            memcpy(bp, pk->placed, pk->nauto);
        }
        if (best == pk->nauto) break;
    }
    memcpy(pk->x, bx, pk->nauto * sizeof *bx);
    memcpy(pk->y, by, pk->nauto * sizeof *by);
    memcpy(pk->placed, bp, pk->nauto);
    return best;
}

/* An item's own checks: its numbers, its size against the plate, and a
 * fixed one's place. */
static int check_item(const lam_plate *p, const area *a, const lam_arrange_item *it, size_t i, const char *units,
                      lam_error *err)
{
    char nb[32], pb[160];
    const char *nm = name_of(it, i, nb);
    const double *b = it->box;
    for (int k = 0; k < 4; k++)
        if (!isfinite(b[k]))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %s has a footprint box that is not finite", nm);
    if (b[2] < b[0] || b[3] < b[1])
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %s has an empty footprint box", nm);
    double w = b[2] - b[0], h = b[3] - b[1];
    pbox c = { -w / 2, -h / 2, w / 2, h / 2, i };
    if (!a->round) c = (pbox){ a->x0, a->y0, a->x0 + w, a->y0 + h, i };
    if (!inside(a, &c))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "part %s (%s x %s%s%s) is larger than the plate (%s)", nm,
                             LAM_NUM(w), LAM_NUM(h), unit_sp(units), unit_of(units),
                             plate_text(p, units, pb, sizeof pb));
    if (!it->fixed) return LAM_OK;
    if (!isfinite(it->at[0]) || !isfinite(it->at[1]))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "fixed part %s has a place that is not finite", nm);
    pbox f = { it->at[0] - w / 2, it->at[1] - h / 2, it->at[0] + w / 2, it->at[1] + h / 2, i };
    if (!inside(a, &f))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "fixed part %s at (%s, %s) is off the plate (%s)", nm,
                             LAM_NUM(it->at[0]), LAM_NUM(it->at[1]), plate_text(p, units, pb, sizeof pb));
    return LAM_OK;
}

/* Every pair of fixed parts (in index order) keeps the spacing. */
static int check_fixed_pairs(const pbox *f, size_t nf, const lam_arrange_item *items, double s, double tol,
                             const char *units, lam_error *err)
{
    for (size_t i = 0; i < nf; i++)
        for (size_t j = i + 1; j < nf; j++) {
            double gx = gap_x(&f[i], &f[j]), gy = gap_y(&f[i], &f[j]);
            if (fmax(gx, gy) >= s - tol) continue;
            char na[32], nb[32];
            const char *a = name_of(&items[f[i].i], f[i].i, na), *b = name_of(&items[f[j].i], f[j].i, nb);
            if (gx < 0 && gy < 0)
                return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "fixed parts %s and %s overlap", a, b);
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                                 "fixed parts %s and %s are closer than the spacing (%s%s%s)",
                                 a, b, LAM_NUM(s), unit_sp(units), unit_of(units));
        }
    return LAM_OK;
}

static int cmp_pbox_x0(const void *pa, const void *pb)
{
    const pbox *a = pa, *b = pb;
    if (a->x0 != b->x0) return a->x0 < b->x0 ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* The automatic items' packing order: deepest first, ties by index. */
typedef struct okey {
    double h;
    size_t i;
} okey;

static int cmp_okey(const void *pa, const void *pb)
{
    const okey *a = pa, *b = pb;
    if (a->h != b->h) return a->h > b->h ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

/* Working memory of one call (calloc: a count times a size cannot wrap). */
typedef struct work {
    pbox *fixed;
    okey *order;
    double *w, *h, *x, *y, *bx, *by, *tops;
    row *rows;
    unsigned char *placed, *bp;
} work;

static void work_free(work *m)
{
    free(m->fixed);
    free(m->order);
    free(m->w);
    free(m->h);
    free(m->x);
    free(m->y);
    free(m->bx);
    free(m->by);
    free(m->tops);
    free(m->rows);
    free(m->placed);
    free(m->bp);
}

static int work_alloc(work *m, size_t n)
{
    size_t k = n ? n : 1;
    memset(m, 0, sizeof *m);
    m->fixed = calloc(k, sizeof *m->fixed);
    m->order = calloc(k, sizeof *m->order);
    m->w = calloc(k, sizeof(double));
    m->h = calloc(k, sizeof(double));
    m->x = calloc(k, sizeof(double));
    m->y = calloc(k, sizeof(double));
    m->bx = calloc(k, sizeof(double));
    m->by = calloc(k, sizeof(double));
    m->tops = calloc(k, sizeof(double));
    m->rows = calloc(k, sizeof *m->rows);
    m->placed = calloc(k, 1);
    m->bp = calloc(k, 1);
    if (m->fixed && m->order && m->w && m->h && m->x && m->y && m->bx && m->by && m->tops && m->rows && m->placed &&
        m->bp)
        return 1;
    work_free(m);
    return 0;
}

/* "only K of N parts fit ...; not placed: NAME and M more". */
static int not_all_fit(const lam_plate *p, double s, const lam_arrange_item *items, size_t n, const work *m,
                       size_t nauto, size_t fitted, const char *units, lam_error *err)
{
    size_t first = n;
    for (size_t k = 0; k < nauto; k++)
        if (!m->placed[k] && m->order[k].i < first) first = m->order[k].i;
    char nb[32], pb[160], more[48] = "";
    size_t left = nauto - (fitted - (n - nauto));
    if (left > 1) snprintf(more, sizeof more, " and %zu more", left - 1);
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                         "only %zu of %zu parts fit on the plate (%s, spacing %s); not placed: %s%s",
                         fitted, n, plate_text(p, units, pb, sizeof pb), LAM_NUM(s), name_of(&items[first], first, nb),
                         more);
}

/* Split the items into the fixed boxes (sorted by x0) and the automatic
 * ones' packing order and sizes. Returns how many are automatic. */
static size_t sort_items(const lam_arrange_item *items, size_t n, work *m, size_t *nfixed)
{
    size_t nf = 0, na = 0;
    for (size_t i = 0; i < n; i++) {
        const double *b = items[i].box;
        double w = b[2] - b[0], h = b[3] - b[1];
        if (items[i].fixed)
            m->fixed[nf++] = (pbox){ items[i].at[0] - w / 2, items[i].at[1] - h / 2, items[i].at[0] + w / 2,
                                     items[i].at[1] + h / 2, i };
        else
            m->order[na++] = (okey){ h, i };
    }
    qsort(m->order, na, sizeof *m->order, cmp_okey);
    for (size_t k = 0; k < na; k++) {
        const double *b = items[m->order[k].i].box;
        m->w[k] = b[2] - b[0];
        m->h[k] = b[3] - b[1];
    }
    *nfixed = nf;
    return na;
}

/* Sort the fixed parts by x0 and their tops (y1 + spacing); returns the
 * widest one's width. */
static double sort_fixed(work *m, size_t nf, double s)
{
    double wmax = 0;
    qsort(m->fixed, nf, sizeof *m->fixed, cmp_pbox_x0);
    for (size_t k = 0; k < nf; k++) {
        wmax = fmax(wmax, m->fixed[k].x1 - m->fixed[k].x0);
        m->tops[k] = m->fixed[k].y1 + s;
    }
    qsort(m->tops, nf, sizeof *m->tops, cmp_double);
    return wmax;
}

/* Write the placement into the items: at and shift (fixed ones keep at). */
static void write_out(lam_arrange_item *items, size_t n, const work *m, size_t nauto)
{
    for (size_t i = 0; i < n; i++) {
        if (!items[i].fixed) continue;
        const double *b = items[i].box;
        items[i].shift[0] = items[i].at[0] - (b[0] + b[2]) / 2;
        items[i].shift[1] = items[i].at[1] - (b[1] + b[3]) / 2;
    }
    for (size_t k = 0; k < nauto; k++) {
        lam_arrange_item *it = &items[m->order[k].i];
        it->shift[0] = m->x[k] - it->box[0];
        it->shift[1] = m->y[k] - it->box[1];
        it->at[0] = (it->box[0] + it->box[2]) / 2 + it->shift[0];
        it->at[1] = (it->box[1] + it->box[3]) / 2 + it->shift[1];
    }
}

int lam_arrange(const lam_plate *p, double spacing, lam_arrange_item *items, size_t n, const char *units,
                lam_error *err)
{
    area a;
    int rc = make_area(p, spacing, &a, err);
    if (rc) return rc;
    if (n && !items) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "no parts to arrange");
    for (size_t i = 0; i < n; i++)
        if ((rc = check_item(p, &a, &items[i], i, units, err))) return rc;
    work m;
    if (!work_alloc(&m, n)) return lam_error_nomem(err, "while arranging the parts");
    size_t nf, na = sort_items(items, n, &m, &nf);
    rc = check_fixed_pairs(m.fixed, nf, items, spacing, a.tol, units, err);
    if (!rc) {
        packer pk = { .a = &a, .s = spacing, .fixed = m.fixed, .nfixed = nf, .wmax = sort_fixed(&m, nf, spacing),
                      .tops = m.tops, .w = m.w, .h = m.h, .nauto = na, .rows = m.rows, .x = m.x, .y = m.y,
                      .placed = m.placed };
        size_t fitted = nf + pack_best(&pk, m.bx, m.by, m.bp);
        if (fitted < n)
            rc = not_all_fit(p, spacing, items, n, &m, na, fitted, units, err);
        else
            write_out(items, n, &m, na);
    }
    work_free(&m);
    return rc;
}

static int cmp_xy(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

/* (b - a) x (c - a): > 0 when a, b, c turn left. */
static double cross(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int check_verts(const double *xyz, size_t nverts, lam_error *err)
{
    if (!nverts || !xyz) return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "a footprint needs at least one vertex");
    for (size_t i = 0; i < nverts; i++)
        if (!isfinite(xyz[3 * i]) || !isfinite(xyz[3 * i + 1]))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "vertex %zu of the footprint is not finite", i + 1);
    return LAM_OK;
}

int lam_footprint_hull(const double *xyz, size_t nverts, double **out_xy, size_t *out_n, lam_error *err)
{
    *out_xy = NULL;
    *out_n = 0;
    int rc = check_verts(xyz, nverts, err);
    if (rc) return rc;
    /* the chain holds at most 2 * nverts points on the way */
    double *pt = nverts <= SIZE_MAX / (8 * sizeof(double)) ? malloc(2 * nverts * sizeof *pt) : NULL;
    double *h = pt ? malloc(4 * nverts * sizeof *h) : NULL;
    if (!h) {
        free(pt);
        return lam_error_nomem(err, "while taking a footprint's hull");
    }
    /* + 0.0 makes -0 into 0: points equal as numbers are then equal in
     * every bit, and which of them qsort puts first cannot show */
    for (size_t i = 0; i < nverts; i++) {
        pt[2 * i] = xyz[3 * i] + 0.0;
        pt[2 * i + 1] = xyz[3 * i + 1] + 0.0;
    }
    qsort(pt, nverts, 2 * sizeof *pt, cmp_xy);
    /* Andrew's monotone chain: the lower hull left to right, then the
     * upper one back; a point that does not turn left is dropped, so
     * collinear and repeated points go. */
    size_t k = 0;
    for (size_t i = 0; i < nverts; i++) {
        while (k >= 2 && cross(&h[2 * (k - 2)], &h[2 * (k - 1)], &pt[2 * i]) <= 0) k--;
        memcpy(&h[2 * k++], &pt[2 * i], 2 * sizeof *h);
    }
    for (size_t i = nverts - 1, lo = k + 1; i-- > 0;) {
        while (k >= lo && cross(&h[2 * (k - 2)], &h[2 * (k - 1)], &pt[2 * i]) <= 0) k--;
        memcpy(&h[2 * k++], &pt[2 * i], 2 * sizeof *h);
    }
    if (k > 1) k--; /* the last point is the first again */
    if (k == 2 && h[0] == h[2] && h[1] == h[3]) k = 1;
    free(pt);
    double *shrunk = realloc(h, 2 * k * sizeof *h);
    *out_xy = shrunk ? shrunk : h;
    *out_n = k;
    return LAM_OK;
}

int lam_footprint_box(const double *xyz, size_t nverts, double box[4], lam_error *err)
{
    int rc = check_verts(xyz, nverts, err);
    if (rc) return rc;
    double b[4] = { xyz[0], xyz[1], xyz[0], xyz[1] };
    for (size_t i = 1; i < nverts; i++) {
        b[0] = fmin(b[0], xyz[3 * i]);
        b[1] = fmin(b[1], xyz[3 * i + 1]);
        b[2] = fmax(b[2], xyz[3 * i]);
        b[3] = fmax(b[3], xyz[3 * i + 1]);
    }
    memcpy(box, b, sizeof b);
    return LAM_OK;
}
