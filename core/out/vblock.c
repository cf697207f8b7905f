/* The viewer's layer blocks; see vblock.h and docs/viewer.md. */
#include "vblock.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "grow.h"
#include "profile_keys.h"

void lam_vblock_init(lam_vblock *b, double quantum)
{
    memset(b, 0, sizeof *b);
    b->quantum = quantum > 0 ? quantum : 1e-4;
    b->run_kind = -1;
}

double lam_vblock_quantum(const char *units, const double box[4])
{
    double mm = lam_key_unit_mm(units), q = mm > 0 ? 1e-4 / mm : 1e-4, most = 0;
    for (int k = 0; k < 4; k++)
        if (isfinite(box[k]) && fabs(box[k]) > most) most = fabs(box[k]);
    /* room for four times the extent: vectors a little outside the box
     * (a jump, a LADRP move from the origin) keep their place */
    double fit = 4 * most / (double)(LAM_VBLOCK_MAX_Q / 4);
    return fit > q ? fit : q;
}

/* A varint at q, which has room for 10 bytes; returns the byte after it. */
static unsigned char *varint(unsigned char *q, unsigned long long x)
{
    while (x >= 0x80) {
        *q++ = (unsigned char)(x | 0x80);
        x >>= 7;
    }
    *q++ = (unsigned char)x;
    return q;
}

/* Room for n more bytes at the end of to, or NULL (b failed). */
static unsigned char *room(lam_vblock *b, lam_buf *to, size_t n)
{
    if (lam_buf_reserve(to, n)) {
        b->failed = 1;
        return NULL;
    }
    return (unsigned char *)to->data + to->len;
}

static void put_u(lam_vblock *b, lam_buf *to, unsigned long long x)
{
    unsigned char *q = room(b, to, 10);
    if (q) to->len = (size_t)(varint(q, x) - (unsigned char *)to->data);
}

static unsigned long long zigzag(long long s)
{
    return ((unsigned long long)s << 1) ^ (unsigned long long)(s >> 63);
}

static long long quant(const lam_vblock *b, double x)
{
    double q = x / b->quantum;
    if (!(q > -(double)LAM_VBLOCK_MAX_Q)) return isnan(q) ? 0 : -LAM_VBLOCK_MAX_Q;
    if (q > (double)LAM_VBLOCK_MAX_Q) return LAM_VBLOCK_MAX_Q;
    /* llround's rounding (half away from zero), without its call: q - r is
     * exact below 2^52 */
    long long r = (long long)q;
    double f = q - (double)r;
    return r + (f >= 0.5) - (f <= -0.5);
}

/* The point (u, v) at q as its difference from the cursor, which moves
 * there; the first number's low bit may carry a flag (shift 1) or not (0). */
static unsigned char *point(lam_vblock *b, unsigned char *q, double u, double v, int shift, int flag)
{
    long long qu = quant(b, u), qv = quant(b, v);
    q = varint(q, zigzag(qu - b->cu) << shift | (unsigned long long)flag);
    q = varint(q, zigzag(qv - b->cv));
    b->cu = qu;
    b->cv = qv;
    return q;
}

static void put_point(lam_vblock *b, lam_buf *to, double u, double v, int shift, int flag)
{
    unsigned char *q = room(b, to, 20);
    if (q) to->len = (size_t)(point(b, q, u, v, shift, flag) - (unsigned char *)to->data);
}

void lam_vblock_mark(lam_vblock *b, int region, const double *uv, size_t n, int solid, int depth)
{
    /* the marks' own cursor: they are encoded as they come (with the layer)
     * and written after the vectors */
    long long cu = b->cu, cv = b->cv;
    b->cu = b->mu;
    b->cv = b->mv;
    put_u(b, &b->marks, (unsigned long long)region);
    put_u(b, &b->marks, n);
    put_u(b, &b->marks, (unsigned long long)(depth > 0 ? depth : 0) << 1 | (solid ? 1u : 0u));
    for (size_t i = 0; i < n; i++) put_point(b, &b->marks, uv[2 * i], uv[2 * i + 1], 0, 0);
    b->mu = b->cu;
    b->mv = b->cv;
    b->cu = cu;
    b->cv = cv;
    b->nmarks++;
}

void lam_vblock_contour(lam_vblock *b, const double *uv, size_t n, int solid, int depth)
{
    put_u(b, &b->contours, n);
    put_u(b, &b->contours, (unsigned long long)(depth > 0 ? depth : 0) << 1 | (solid ? 1u : 0u));
    for (size_t i = 0; i < n; i++) put_point(b, &b->contours, uv[2 * i], uv[2 * i + 1], 0, 0);
    b->ncontours++;
}

/* The row of attributes a, added when new (the last one found first:
 * consecutive vectors mostly share it). */
static size_t row_of(lam_vblock *b, const lam_attrs *a)
{
    if (b->nrows && !memcmp(&b->rows[b->last_row], a, sizeof *a)) return b->last_row;
    for (size_t k = 0; k < b->nrows; k++)
        if (!memcmp(&b->rows[k], a, sizeof *a)) return b->last_row = k;
    if (b->nrows == b->cap_rows) {
        lam_attrs *r = lam_grow(b->rows, &b->cap_rows, b->nrows + 1, sizeof *b->rows, 8);
        if (!r) {
            b->failed = 1;
            return 0;
        }
        b->rows = r;
    }
    b->rows[b->nrows] = *a;
    return b->last_row = b->nrows++;
}

static void close_run(lam_vblock *b)
{
    if (!b->run_n) return;
    put_u(b, &b->runs, b->run_n);
    put_u(b, &b->runs, (unsigned long long)b->run_kind);
    put_u(b, &b->runs, b->run_row);
    if (lam_buf_append(&b->runs, b->run.data, b->run.len)) b->failed = 1;
    lam_buf_clear(&b->run);
    b->nruns++;
    b->run_n = 0;
}

void lam_vblock_vector(lam_vblock *b, const lam_vec *v)
{
    if (v->kind == LAM_KIND_JUMP) {
        b->jump = 1;
        return;
    }
    size_t row = row_of(b, &v->attrs);
    if (b->run_n && (v->kind != b->run_kind || row != b->run_row)) close_run(b);
    b->run_kind = v->kind;
    b->run_row = row;
    /* both points in one reservation: this runs once a vector */
    unsigned char *q = room(b, &b->run, 40);
    if (q) {
        q = point(b, q, v->fuv[0], v->fuv[1], 1, b->jump);
        b->run.len = (size_t)(point(b, q, v->tuv[0], v->tuv[1], 0, 0) - (unsigned char *)b->run.data);
    }
    b->jump = 0;
    b->run_n++;
}

int lam_vblock_finish(lam_vblock *b, lam_buf *out)
{
    close_run(b);
    put_u(b, out, b->nrows);
    for (size_t k = 0; k < b->nrows; k++)
        for (size_t i = 0; i < LAM_NATTRS; i++) put_u(b, out, zigzag(lam_attr_get(&b->rows[k], i)));
    put_u(b, out, b->ncontours);
    if (lam_buf_append(out, b->contours.data, b->contours.len)) b->failed = 1;
    put_u(b, out, b->nruns);
    if (lam_buf_append(out, b->runs.data, b->runs.len)) b->failed = 1;
    if (b->nmarks) {
        put_u(b, out, b->nmarks);
        if (lam_buf_append(out, b->marks.data, b->marks.len)) b->failed = 1;
    }
    return b->failed ? LAM_ENOMEM : LAM_OK;
}

void lam_vblock_reset(lam_vblock *b)
{
    b->cu = b->cv = 0;
    b->nrows = b->last_row = 0;
    lam_buf_clear(&b->contours);
    lam_buf_clear(&b->runs);
    lam_buf_clear(&b->run);
    lam_buf_clear(&b->marks);
    b->nmarks = 0;
    b->mu = b->mv = 0;
    b->ncontours = b->nruns = b->run_n = 0;
    b->run_kind = -1;
    b->jump = 0;
    b->failed = 0;
}

void lam_vblock_free(lam_vblock *b)
{
    if (!b) return;
    free(b->rows);
    lam_buf_free(&b->contours);
    lam_buf_free(&b->runs);
    lam_buf_free(&b->run);
    lam_buf_free(&b->marks);
    memset(b, 0, sizeof *b);
}
