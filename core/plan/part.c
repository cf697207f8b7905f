/* Part files (part.h): a recording sink, and the reader that replays parts. */
#include "part.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "file.h"
#include "grow.h"

static const char MAGIC[8] = { 'L', 'A', 'M', 'P', 'A', 'R', 'T', 0 };

#define FNV_BASIS 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * FNV_PRIME;
    return h;
}

uint64_t lam_part_hash(uint64_t h, const void *data, size_t n) { return fnv(h ? h : FNV_BASIS, data, n); }

/* ---- identity ------------------------------------------------------------ */

int lam_part_identity(const char *model_path, const char *profile, size_t profile_len, const lam_slicer *s,
                      uint64_t *out, lam_error *err)
{
    uint64_t h = fnv(FNV_BASIS, profile, profile_len);
    FILE *f = fopen(model_path, "rb");
    if (!f) return lam_error_set(err, LAM_EIO, model_path, 0, 0, "cannot open: %s", strerror(errno));
    enum { CHUNK = 1 << 20 };
    unsigned char *buf = malloc(CHUNK);
    if (!buf) {
        fclose(f);
        return lam_error_nomem(err, "hashing the model");
    }
    /* the file as 64-bit words (a byte at a time is a quarter of a second
     * on a 250 MB model): a check that parts belong together, not security */
    size_t got;
    while ((got = fread(buf, 1, CHUNK, f)) > 0) {
        size_t w = got / 8;
        for (size_t i = 0; i < w; i++) {
            uint64_t x;
            memcpy(&x, buf + 8 * i, 8);
            h = (h ^ x) * FNV_PRIME;
        }
        h = fnv(h, buf + 8 * w, got - 8 * w);
    }
    int bad = ferror(f);
    free(buf);
    fclose(f);
    if (bad) return lam_error_set(err, LAM_EIO, model_path, 0, 0, "cannot read");
    size_t n = lam_slicer_count(s);
    h = fnv(h, &n, sizeof n);
    h = fnv(h, lam_slicer_planes(s), (n + 1) * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        double c = lam_slicer_cut(s, i);
        h = fnv(h, &c, sizeof c);
    }
    h = fnv(h, lam_slicer_frame(s), sizeof(lam_frame));
    double gap = lam_slicer_gap(s);
    *out = fnv(h, &gap, sizeof gap);
    return LAM_OK;
}

/* ---- the recording sink ---------------------------------------------------- */

/* The header in the plan's encoding's buffer, then each operation encoded
 * by plan_record.c and written out every FLUSH_AT bytes. */
typedef struct rec {
    lam_writer *w;
    lam_error *err;
    lam_part_meta meta;       /* strings owned */
    lam_scan_time *time;
    uint64_t hash;
    lam_record b;             /* pending bytes */
    lam_sink enc;             /* the encoder, into b */
} rec;

#define FLUSH_AT 65536

static void put(rec *r, const void *p, size_t n) { lam_record_bytes(&r->b, p, n); }

static void put_u64(rec *r, uint64_t v)
{
    unsigned char b[8];
    for (int i = 0; i < 8; i++) b[i] = (unsigned char)(v >> (8 * i));
    put(r, b, 8);
}

static void put_f64s(rec *r, const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        uint64_t v;
        memcpy(&v, &x[i], 8);
        put_u64(r, v);
    }
}

static void put_str(rec *r, const char *s, size_t n)
{
    put_u64(r, n);
    put(r, s, n);
}

static void put_cstr(rec *r, const char *s)
{
    put_str(r, s ? s : "", s ? strlen(s) : 0);
}

static int flush(rec *r, int force)
{
    if (r->b.failed) return lam_error_nomem(r->err, "writing a part file");
    if (r->b.len < FLUSH_AT && !force) return LAM_OK;
    r->hash = fnv(r->hash, r->b.buf, r->b.len);
    int rc = lam_writer_write(r->w, r->b.buf, r->b.len);
    lam_record_clear(&r->b);
    return rc ? lam_writer_error(r->w, r->err) : LAM_OK;
}

/* The attribute table the records were written with (vocab.h): a part of
 * a lamina with other attributes is refused, not misread. */
static void put_attr_keys(rec *r)
{
    put_u64(r, LAM_NATTRS);
    for (size_t i = 0; i < LAM_NATTRS; i++) put_cstr(r, lam_attr_key(i));
}

/* A build's CLI labels (plan.h's lam_job_info.labels; none: 0). */
static void put_labels(rec *r, const lam_job_info *j)
{
    put_u64(r, j->labels ? j->nlabels : 0);
    for (size_t i = 0; j->labels && i < j->nlabels; i++) put_cstr(r, j->labels[i] ? j->labels[i] : "");
}

static int r_begin(void *ctx, const lam_job_info *j)
{
    rec *r = ctx;
    put(r, MAGIC, 8);
    unsigned char v[8] = { LAM_PART_VERSION, 0, 0, 0, 0, 0, 0, 0 };
    put(r, v, 8);
    put_u64(r, r->meta.identity);
    put_u64(r, r->meta.first);
    put_u64(r, r->meta.last);
    put_u64(r, r->meta.layers);
    put_cstr(r, j->name);
    put_cstr(r, j->process);
    put_cstr(r, j->units);
    put_cstr(r, j->label);
    put_f64s(r, j->bbox, 6);
    put_f64s(r, &j->bead, 1);
    put_f64s(r, &j->rate, 1);
    put_f64s(r, &j->travel_rate, 1);
    put_f64s(r, j->origin, 3);
    put_str(r, r->meta.profile, r->meta.profile_len);
    put_cstr(r, r->meta.model);
    put_attr_keys(r);
    put_labels(r, j);
    put_u64(r, fnv(FNV_BASIS, r->b.buf, r->b.len)); /* the header's own check */
    if (j->layers != r->meta.layers)
        return lam_error_set(r->err, LAM_EUSAGE, NULL, 0, 0, "part: the run has %zu layers, not %zu", j->layers,
                             r->meta.layers);
    return flush(r, 0);
}

static int r_layer(void *ctx, const lam_layer_info *L)
{
    rec *r = ctx;
    lam_record_layer(&r->b, L);
    return flush(r, 0);
}

static int r_layer_end(void *ctx, const lam_layer_info *L)
{
    rec *r = ctx;
    lam_scan_time t;
    memset(&t, 0, sizeof t);
    if (r->time) {
        /* the planner added this layer's estimate to a zero total */
        t = *r->time;
        memset(r->time, 0, sizeof *r->time);
    } else if (L->time) { /* a build's layer carries its own (build_plan.h) */
        t = *L->time;
    }
    lam_record_layer_end(&r->b, L, &t);
    return flush(r, 0);
}

static int r_feed(void *ctx, double rate)
{
    rec *r = ctx;
    r->enc.feed(r->enc.ctx, rate);
    return flush(r, 0);
}

static int r_laser(void *ctx, int on)
{
    rec *r = ctx;
    r->enc.laser(r->enc.ctx, on);
    return flush(r, 0);
}

static int r_move(void *ctx, const lam_move_info *m)
{
    rec *r = ctx;
    r->enc.move(r->enc.ctx, m);
    return flush(r, 0);
}

static int r_contour(void *ctx, const lam_contour_info *c)
{
    rec *r = ctx;
    r->enc.contour(r->enc.ctx, c);
    return flush(r, 0);
}

static int r_hatches(void *ctx, const lam_hatch_info *h)
{
    rec *r = ctx;
    r->enc.hatches(r->enc.ctx, h);
    return flush(r, 0);
}

static int r_end(void *ctx)
{
    rec *r = ctx;
    int rc = flush(r, 1);
    if (rc) return rc;
    put(r, "Z", 1);
    r->hash = fnv(r->hash, r->b.buf, r->b.len);
    put_u64(r, r->hash);
    if (r->b.failed) return lam_error_nomem(r->err, "writing a part file");
    rc = lam_writer_write(r->w, r->b.buf, r->b.len);
    lam_record_clear(&r->b);
    return rc ? lam_writer_error(r->w, r->err) : LAM_OK;
}

static void r_destroy(void *ctx)
{
    rec *r = ctx;
    if (!r) return;
    free((char *)r->meta.profile);
    free((char *)r->meta.model);
    lam_record_free(&r->b);
    free(r);
}

int lam_part_sink(const lam_part_meta *meta, lam_scan_time *time, lam_writer *w, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    rec *r = calloc(1, sizeof *r);
    if (!r) return lam_error_nomem(err, NULL);
    r->w = w;
    r->err = err;
    r->time = time;
    r->hash = FNV_BASIS;
    r->meta = *meta;
    char *prof = malloc(meta->profile_len + 1), *model = strdup(meta->model ? meta->model : "");
    if (prof) {
        memcpy(prof, meta->profile, meta->profile_len);
        prof[meta->profile_len] = '\0';
    }
    r->meta.profile = prof;
    r->meta.model = model;
    lam_sink all = { .feed = r_feed, .laser = r_laser, .move = r_move, .contour = r_contour, .hatches = r_hatches };
    r->enc = lam_record_sink(&r->b, &all);
    if (!prof || !model) {
        r_destroy(r);
        return lam_error_nomem(err, NULL);
    }
    *out = all;
    out->ctx = r;
    out->begin = r_begin;
    out->layer = r_layer;
    out->layer_end = r_layer_end;
    out->end = r_end;
    out->destroy = r_destroy;
    return LAM_OK;
}

/* ---- reading ----------------------------------------------------------------- */

struct lam_part {
    char *path;
    FILE *f;
    long long size, off;      /* the file's size; bytes read */
    uint64_t hash;
    lam_part_meta meta;       /* strings owned */
    lam_job_info job;         /* strings owned */
    long long body;           /* where the records start */
    uint64_t body_hash;       /* the hash of the bytes before them */
    double *d;                /* a record's reals */
    size_t dcap;
    /* what the records' values may be (check_job): points in lo..hi,
     * layer-frame points and heights within reach of the origin */
    double lo[3], hi[3], tol, reach;
    lam_layer_info layer;     /* the layer being replayed */
    char **labels;            /* the job's labels (job.labels), owned */
};

/* LAM_EFORMAT at the current offset */
static int corrupt(lam_part *p, lam_error *err, const char *what)
{
    return lam_error_at_offset(err, LAM_EFORMAT, p->path, p->off, "corrupt part file: %s", what);
}

static int get(lam_part *p, void *dst, size_t n, lam_error *err)
{
    if ((long long)n > p->size - p->off)
        return lam_error_at_offset(err, LAM_EFORMAT, p->path, p->off,
                                   "truncated part file (the file ends in the middle of a record)");
    if (n && fread(dst, 1, n, p->f) != n)
        return lam_error_at_offset(err, LAM_EIO, p->path, p->off, "cannot read: %s",
                                   ferror(p->f) ? strerror(errno) : "unexpected end of file");
    p->hash = fnv(p->hash, dst, n);
    p->off += (long long)n;
    return LAM_OK;
}

static int get_u64(lam_part *p, uint64_t *v, lam_error *err)
{
    unsigned char b[8];
    *v = 0;
    int rc = get(p, b, 8, err);
    if (rc) return rc;
    for (int i = 7; i >= 0; i--) *v = (*v << 8) | b[i];
    return LAM_OK;
}

static int get_size(lam_part *p, size_t *v, lam_error *err)
{
    uint64_t x;
    int rc = get_u64(p, &x, err);
    if (rc) return rc;
    if (x > (uint64_t)p->size) return corrupt(p, err, "a count larger than the file");
    *v = (size_t)x;
    return LAM_OK;
}

static int get_f64s(lam_part *p, double *x, size_t n, lam_error *err)
{
    for (size_t i = 0; i < n; i++) {
        uint64_t v;
        int rc = get_u64(p, &v, err);
        if (rc) return rc;
        memcpy(&x[i], &v, 8);
    }
    return LAM_OK;
}

/* a string of at most the rest of the file, NUL-terminated, owned */
static int get_str(lam_part *p, char **s, size_t *len, lam_error *err)
{
    size_t n = 0;
    int rc = get_size(p, &n, err);
    if (rc) return rc;
    if (!(*s = malloc(n + 1))) return lam_error_nomem(err, "reading a part file");
    if ((rc = get(p, *s, n, err))) return rc;
    (*s)[n] = '\0';
    if (len) *len = n;
    return LAM_OK;
}

void lam_part_close(lam_part *p)
{
    if (!p) return;
    if (p->f) fclose(p->f);
    free(p->path);
    free((char *)p->meta.profile);
    free((char *)p->meta.model);
    free((char *)p->job.name);
    free((char *)p->job.process);
    free((char *)p->job.units);
    free((char *)p->job.label);
    for (size_t i = 0; p->labels && i < p->job.nlabels; i++) free(p->labels[i]);
    free(p->labels);
    free(p->d);
    free(p);
}

/* ---- what the values may be ----------------------------------------------------
 * A part whose hashes match may still hold numbers no slicing run gives
 * (a hand-made or buggy part: the hashes only say the bytes are the ones
 * written): every value is checked as the model and program readers check
 * theirs before a sink sees it, so a join writes no `nan` and no point
 * outside the job. What the planners give: points on the layers' sections
 * (inside the job's box), LADRP's approach one bead beside them, heights
 * within the layers' planes; the tolerance is two beads and the rounding
 * of a point's frame change. */

/* the smallest layer: its 'L' and 'E' records */
#define LAYER_BYTES (2 * (1 + 5 * 8) + 10 * 8)

static int finite_all(const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i])) return 0;
    return 1;
}

/* LAM_EFORMAT at byte `at`: "corrupt part file: layer N: ..." (no layer
 * when none is being read) */
static int bad_value(lam_part *p, long long at, lam_error *err, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int bad_value(lam_part *p, long long at, lam_error *err, const char *fmt, ...)
{
    char what[512], where[64] = "";
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (p->layer.index != (size_t)-1) snprintf(where, sizeof where, "layer %zu: ", p->layer.index + 1);
    return lam_error_at_offset(err, LAM_EFORMAT, p->path, at, "corrupt part file: %s%s", where, what);
}

/* n points of 3 reals each (stride apart): finite and inside the job's box */
static int check_points(lam_part *p, long long at, const char *what, const double *x, size_t n, size_t stride,
                        lam_error *err)
{
    for (size_t i = 0; i < n; i++) {
        const double *q = x + stride * i;
        char which[80];
        if (n > 1) snprintf(which, sizeof which, "%s %zu", what, i + 1);
        else snprintf(which, sizeof which, "%s", what);
        if (!finite_all(q, 3))
            return bad_value(p, at, err, "%s is not finite (%g, %g, %g)", which, q[0], q[1], q[2]);
        for (int k = 0; k < 3; k++)
            if (q[k] < p->lo[k] || q[k] > p->hi[k])
                return bad_value(p, at, err, "%s (%g, %g, %g) is outside the job's box [%g, %g] x [%g, %g] x [%g, %g]",
                                 which, q[0], q[1], q[2], p->lo[0], p->hi[0], p->lo[1], p->hi[1], p->lo[2], p->hi[2]);
    }
    return LAM_OK;
}

/* n layer-frame points (u, v): finite and no farther from the frame's
 * origin than the job's box */
static int check_uv(lam_part *p, long long at, const char *what, const double *uv, size_t n, lam_error *err)
{
    for (size_t i = 0; i < n; i++) {
        const double *q = uv + 2 * i;
        if (!finite_all(q, 2) || hypot(q[0], q[1]) > p->reach)
            return bad_value(p, at, err, "%s %zu in the layer frame (%g, %g) is outside the job's box", what, i + 1,
                             q[0], q[1]);
    }
    return LAM_OK;
}

/* a contour's or hatch block's height: in its layer */
static int check_height(lam_part *p, long long at, const char *what, double z, lam_error *err)
{
    const lam_layer_info *L = &p->layer;
    double lo = fmin(L->floor, L->z) - p->tol, hi = fmax(L->ceiling, L->z) + p->tol;
    if (!(z >= lo && z <= hi))
        return bad_value(p, at, err, "%s at height %g, outside its layer (%g..%g)", what, z, L->floor, L->ceiling);
    return LAM_OK;
}

/* power, speed, point distance, exposure time: what a profile may set */
static int check_exposure(lam_part *p, long long at, const char *what, const double e[4], lam_error *err)
{
    for (int i = 0; i < 4; i++)
        if (!(isfinite(e[i]) && e[i] >= 0))
            return bad_value(p, at, err, "%s with a %s of %g", what,
                             (const char *[]){ "power", "speed", "point distance", "exposure time" }[i], e[i]);
    return LAM_OK;
}

/* a flag byte (lamina writes 0 or 1) */
static int check_flag(lam_part *p, long long at, const char *what, int v, lam_error *err)
{
    return v == 0 || v == 1 ? LAM_OK : bad_value(p, at, err, "%s flag %d (not 0 or 1)", what, v);
}

/* a layer record's fields: finite, a positive width, heights within
 * reach of the box (the last plane may lie a layer above it) */
static int check_layer(lam_part *p, long long at, const lam_layer_info *L, lam_error *err)
{
    double h[4] = { L->z, L->width, L->floor, L->ceiling };
    if (!finite_all(h, 4) || !(L->width > 0) || !(L->floor <= L->ceiling))
        return bad_value(p, at, err, "height %g, width %g, from %g to %g: not a layer", L->z, L->width, L->floor,
                         L->ceiling);
    double r = p->reach + L->width;
    if (fabs(L->z) > r || fabs(L->floor) > r || fabs(L->ceiling) > r)
        return bad_value(p, at, err, "height %g (from %g to %g) is outside the job's box", L->z, L->floor, L->ceiling);
    /* the stage starts at the run's first cut along the slicing axis: no
     * farther out than the box or this layer's cut, which lies above it */
    const double *o = p->job.origin;
    if (hypot(hypot(o[0], o[1]), o[2]) > fmax(p->reach, fabs(L->z)) + p->tol)
        return bad_value(p, at, err, "the stage's start (%g, %g, %g) is outside the job's box", o[0], o[1], o[2]);
    return LAM_OK;
}

static int plain_text(const char *s, int label)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        int word = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                   c == '-' || c == '.'; /* lam_job_label's characters */
        if (label ? !word : c < 0x20 || c == 0x7f) return 0;
    }
    return 1;
}

/* The header's job (the box every record is checked against) and counts,
 * once its hash matched. */
static int check_job(lam_part *p, long long at_reals, lam_error *err)
{
    lam_job_info *j = &p->job;
    if (strcmp(j->process, "ladrp") != 0 && strcmp(j->process, "sls") != 0)
        return bad_value(p, 0, err, "process '%.32s' (not ladrp or sls)", j->process);
    if (!plain_text(j->name, 0) || !plain_text(j->units, 0) || !j->label[0] || strlen(j->label) > 127 ||
        !plain_text(j->label, 1))
        return bad_value(p, 0, err, "the job's name, units or label holds characters lamina does not write");
    if (!finite_all(j->bbox, 6) || !(j->bbox[0] <= j->bbox[3] && j->bbox[1] <= j->bbox[4] && j->bbox[2] <= j->bbox[5]))
        return bad_value(p, at_reals, err, "the job's box [%g, %g] x [%g, %g] x [%g, %g] is not finite or empty",
                         j->bbox[0], j->bbox[3], j->bbox[1], j->bbox[4], j->bbox[2], j->bbox[5]);
    double e[3] = { j->bead, j->rate, j->travel_rate };
    if (!finite_all(e, 3) || !(j->bead >= 0 && j->rate >= 0 && j->travel_rate >= 0))
        return bad_value(p, at_reals + 48, err, "bead %g, feed rate %g, travel rate %g", j->bead, j->rate,
                         j->travel_rate);
    double r2 = 0, big = 0;
    for (int k = 0; k < 3; k++) {
        double m = fmax(fabs(j->bbox[k]), fabs(j->bbox[k + 3]));
        r2 += m * m;
        big = fmax(big, m);
    }
    p->tol = 2 * j->bead + 1e-9 * big;
    p->reach = sqrt(r2) * (1 + 1e-12) + p->tol;
    for (int k = 0; k < 3; k++) {
        p->lo[k] = j->bbox[k] - p->tol;
        p->hi[k] = j->bbox[k + 3] + p->tol;
    }
    /* (how far it may be is known at the first layer: check_layer) */
    if (!finite_all(j->origin, 3))
        return bad_value(p, at_reals + 72, err, "the stage's start (%g, %g, %g) is not finite", j->origin[0],
                         j->origin[1], j->origin[2]);
    /* every layer takes two records: the count is bounded by the bytes */
    size_t n = p->meta.last - p->meta.first + 1;
    if (n > (size_t)(p->size - p->off) / LAYER_BYTES)
        return bad_value(p, 24, err, "%zu layers in %lld bytes", n, p->size);
    return LAM_OK;
}

/* The header's CLI labels (a build's), each text lamina writes: no
 * control characters, no comma (a CLI $$LABEL's separator). */
static int read_labels(lam_part *p, lam_error *err)
{
    size_t n = 0;
    int rc = get_size(p, &n, err);
    if (rc || !n) return rc;
    if (!(p->labels = calloc(n, sizeof *p->labels))) return lam_error_nomem(err, "reading a part file");
    p->job.nlabels = n;
    p->job.labels = (const char *const *)p->labels;
    for (size_t i = 0; i < n && !rc; i++) {
        rc = get_str(p, &p->labels[i], NULL, err);
        if (!rc && (!plain_text(p->labels[i], 0) || strchr(p->labels[i], ',')))
            rc = corrupt(p, err, "a label holds characters lamina does not write");
    }
    return rc;
}

/* The header's attribute keys: the same as this lamina's (vocab.h). */
static int read_attr_keys(lam_part *p, lam_error *err)
{
    size_t n = 0;
    int rc = get_size(p, &n, err);
    if (!rc && n != LAM_NATTRS)
        return corrupt(p, err, "operations with another set of attributes (a part of another lamina)");
    for (size_t i = 0; i < n && !rc; i++) {
        char *key = NULL;
        rc = get_str(p, &key, NULL, err);
        if (!rc && strcmp(key, lam_attr_key(i)))
            rc = corrupt(p, err, "operations with another set of attributes (a part of another lamina)");
        free(key);
    }
    return rc;
}

static int read_header(lam_part *p, lam_error *err)
{
    unsigned char head[16];
    if (p->size < 16 || fread(head, 1, 16, p->f) != 16 || memcmp(head, MAGIC, 8) != 0)
        return lam_error_set(err, LAM_EFORMAT, p->path, 0, 0,
                             "not a lamina part file (written by `lamina slice --layers A:B`)");
    p->hash = fnv(p->hash, head, 16);
    p->off = 16;
    uint32_t version = head[8] | (uint32_t)head[9] << 8 | (uint32_t)head[10] << 16 | (uint32_t)head[11] << 24;
    if (version != LAM_PART_VERSION)
        return lam_error_set(err, LAM_EFORMAT, p->path, 0, 0,
                             "part file version %u: this lamina reads version %d", (unsigned)version,
                             LAM_PART_VERSION);
    uint64_t id = 0, first = 0, last = 0, layers = 0;
    char *s[4] = { 0 };
    char *prof = NULL, *model = NULL;
    int rc = get_u64(p, &id, err);
    if (!rc) rc = get_u64(p, &first, err);
    if (!rc) rc = get_u64(p, &last, err);
    if (!rc) rc = get_u64(p, &layers, err);
    if (!rc && (first < 1 || first > last || last > layers || layers > SIZE_MAX))
        return lam_error_at_offset(err, LAM_EFORMAT, p->path, 24, "corrupt part file: layers %llu..%llu of %llu",
                                   (unsigned long long)first, (unsigned long long)last, (unsigned long long)layers);
    p->meta.identity = id;
    p->meta.first = (size_t)first;
    p->meta.last = (size_t)last;
    p->meta.layers = p->job.layers = (size_t)layers;
    for (int i = 0; !rc && i < 4; i++) rc = get_str(p, &s[i], NULL, err);
    p->job.name = s[0];
    p->job.process = s[1];
    p->job.units = s[2];
    p->job.label = s[3];
    long long at_reals = p->off;
    if (!rc) rc = get_f64s(p, p->job.bbox, 6, err);
    if (!rc) rc = get_f64s(p, &p->job.bead, 1, err);
    if (!rc) rc = get_f64s(p, &p->job.rate, 1, err);
    if (!rc) rc = get_f64s(p, &p->job.travel_rate, 1, err);
    if (!rc) rc = get_f64s(p, p->job.origin, 3, err);
    if (!rc) rc = get_str(p, &prof, &p->meta.profile_len, err);
    p->meta.profile = prof;
    if (!rc) rc = get_str(p, &model, NULL, err);
    p->meta.model = model;
    if (!rc) rc = read_attr_keys(p, err);
    if (!rc) rc = read_labels(p, err);
    uint64_t want = p->hash, got = 0;
    if (!rc) rc = get_u64(p, &got, err);
    if (!rc && got != want)
        return lam_error_set(err, LAM_EFORMAT, p->path, 0, 0, "corrupt part file: its header does not match its checksum");
    return rc ? rc : check_job(p, at_reals, err);
}

/* A part named path, nothing read yet. */
static lam_part *part_new(const char *path, lam_error *err)
{
    lam_part *p = calloc(1, sizeof *p);
    if (!p || !(p->path = strdup(path))) {
        free(p);
        lam_error_nomem(err, NULL);
        return NULL;
    }
    p->hash = FNV_BASIS;
    p->layer.index = (size_t)-1;
    return p;
}

/* Read p's header (p->f and p->size set); *out is p, or NULL and p closed. */
static int part_start(lam_part *p, lam_part **out, lam_error *err)
{
    int rc = read_header(p, err);
    p->body = p->off;
    p->body_hash = p->hash;
    if (rc) {
        lam_part_close(p);
        return rc;
    }
    *out = p;
    return LAM_OK;
}

int lam_part_open(const char *path, lam_part **out, lam_error *err)
{
    *out = NULL;
    lam_part *p = part_new(path, err);
    if (!p) return LAM_ENOMEM;
    /* the one opening of a file to read (file.h): a FIFO or device is
     * refused at once, not waited on, and the file is recorded as an input */
    struct stat st;
    int fd = -1, orc = lam_file_open(path, &fd, &st, err);
    if (!orc && !(p->f = fdopen(fd, "rb"))) {
        close(fd);
        orc = lam_error_set(err, LAM_EIO, path, 0, 0, "cannot open: %s", strerror(errno));
    }
    if (orc) {
        lam_part_close(p);
        return orc;
    }
    p->size = (long long)st.st_size;
    return part_start(p, out, err);
}

int lam_part_open_buf(const char *name, const void *data, size_t len, lam_part **out, lam_error *err)
{
    *out = NULL;
    lam_part *p = part_new(name, err);
    if (!p) return LAM_ENOMEM;
    /* read-only: fmemopen does not write to a buffer opened "rb" (and
     * needs a non-empty one; fewer than 16 bytes are refused unread) */
    if (len >= 16 && !(p->f = fmemopen((void *)data, len, "rb"))) {
        int e = errno;
        lam_part_close(p);
        return lam_error_set(err, LAM_ENOMEM, name, 0, 0, "cannot read from memory: %s", strerror(e));
    }
    p->size = (long long)len;
    return part_start(p, out, err);
}

const lam_part_meta *lam_part_get_meta(const lam_part *p) { return &p->meta; }

const lam_job_info *lam_part_job(const lam_part *p) { return &p->job; }

/* ---- joining ----------------------------------------------------------------- */

static int by_first(const void *a, const void *b)
{
    const lam_part *x = *(lam_part *const *)a, *y = *(lam_part *const *)b;
    if (x->meta.first != y->meta.first) return x->meta.first < y->meta.first ? -1 : 1;
    return (x->meta.last > y->meta.last) - (x->meta.last < y->meta.last);
}

int lam_part_order(lam_part **parts, size_t n, lam_error *err)
{
    if (!n) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no part files to join");
    for (size_t i = 1; i < n; i++)
        if (parts[i]->meta.identity != parts[0]->meta.identity || parts[i]->meta.layers != parts[0]->meta.layers)
            return lam_error_set(err, LAM_EINVAL, parts[i]->path, 0, 0,
                                 "part of a different run than %s (another model, machine profile or slicing "
                                 "option)", parts[0]->path);
    qsort(parts, n, sizeof *parts, by_first);
    size_t next = 1;   /* the first layer no part has held so far */
    for (size_t i = 0; i < n; i++) {
        const lam_part *p = parts[i];
        if (p->meta.first > next)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "layers %zu..%zu are missing: no part holds them", next,
                                 p->meta.first - 1);
        if (p->meta.first < next)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s (layers %zu..%zu) and %s (layers %zu..%zu) overlap",
                                 parts[i - 1]->path, parts[i - 1]->meta.first, parts[i - 1]->meta.last, p->path,
                                 p->meta.first, p->meta.last);
        next = p->meta.last + 1;
    }
    if (next <= parts[0]->meta.layers)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "layers %zu..%zu are missing: no part holds them", next,
                             parts[0]->meta.layers);
    return LAM_OK;
}

/* The part as the decoder's source (plan_record.h): its bytes read and
 * hashed in order. */
static int src_get(void *ctx, void *dst, size_t n, lam_error *err) { return get(ctx, dst, n, err); }

static unsigned long long src_left(void *ctx)
{
    const lam_part *p = ctx;
    return (unsigned long long)(p->size - p->off);
}

static int src_corrupt(void *ctx, const char *what, lam_error *err) { return corrupt(ctx, err, what); }

/* 'L', 'E': the layer expected next, with values that could be a layer of
 * the job; an end the same as its start, and an estimate of what the
 * records hold. */
static int check_layer_rec(lam_part *p, long long at, const lam_rec_op *op, size_t want, lam_error *err)
{
    if (op->index != want) {
        p->off = at + 9;
        return corrupt(p, err, "a layer out of order");
    }
    p->layer.index = op->layer.index;
    int rc = check_layer(p, at, &op->layer, err);
    if (rc || op->tag == 'L') return rc;
    const lam_layer_info *L = &op->layer;
    if (L->z != p->layer.z || L->width != p->layer.width || L->floor != p->layer.floor ||
        L->ceiling != p->layer.ceiling)
        return bad_value(p, at, err, "its end does not match its start");
    for (int i = 0; i < 4; i++)
        if (op->counts[i] > (uint64_t)p->size)
            return bad_value(p, at, err, "an estimate counting %llu", (unsigned long long)op->counts[i]);
    const lam_scan_time *t = &op->time;
    double r[6] = { t->exposure_length, t->jump_length, t->hatch_length, t->exposure, t->jump, t->recoat };
    for (int i = 0; i < 6; i++)
        if (!(isfinite(r[i]) && r[i] >= 0)) return bad_value(p, at, err, "an estimate of %g", r[i]);
    return LAM_OK;
}

/* An operation's attributes: whole numbers of no more than the file's
 * size (a part id, a style or laser number), never negative. */
static int check_attrs(lam_part *p, long long at, const char *what, const lam_attrs *a, lam_error *err)
{
    for (size_t i = 0; i < LAM_NATTRS; i++) {
        long long v = lam_attr_get(a, i);
        if (v < 0 || v > p->size)
            return bad_value(p, at, err, "%s with %s %lld", what, lam_attr_key(i), v);
    }
    return LAM_OK;
}

static int check_contour(lam_part *p, long long at, const lam_rec_op *op, lam_error *err)
{
    const lam_contour_info *c = &op->contour;
    double e[4] = { c->power, c->speed, c->point_distance, c->exposure_time };
    int rc = check_attrs(p, at, "a contour", &c->attrs, err);
    if (!rc) rc = check_flag(p, at, "a contour's solid", c->solid, err);
    if (!rc && op->flag != 1) rc = bad_value(p, at, err, "a contour without its layer-frame points");
    if (!rc) rc = check_exposure(p, at, "a contour", e, err);
    if (!rc) rc = check_height(p, at, "a contour", c->z, err);
    if (!rc) rc = check_points(p, at, "contour point", c->xyz, c->n, 3, err);
    if (!rc) rc = check_uv(p, at, "contour point", c->uv, c->n, err);
    return rc;
}

static int check_hatches(lam_part *p, long long at, const lam_rec_op *op, lam_error *err)
{
    const lam_hatch_info *h = &op->hatches;
    double e[4] = { h->power, h->speed, h->point_distance, h->exposure_time };
    int rc = check_attrs(p, at, "hatches", &h->attrs, err);
    /* the kind is written into programs: only the planner's regions (a
     * build's contour pass cut at a laser field's edge is contour vectors) */
    if (!rc && !(h->kind >= LAM_KIND_CONTOUR && h->kind < LAM_REGIONS))
        rc = bad_value(p, at, err, "hatches of kind %lld (not a hatch region)", (long long)op->kind);
    if (!rc && op->flag != 1) rc = bad_value(p, at, err, "hatches without their layer-frame points");
    if (!rc) rc = check_exposure(p, at, "hatches", e, err);
    if (!rc) rc = check_height(p, at, "hatches", h->z, err);
    if (!rc && !isfinite(h->angle)) rc = bad_value(p, at, err, "hatches at an angle of %g", h->angle);
    if (!rc) rc = check_points(p, at, "hatch end", h->xyz, 2 * h->n, 3, err);
    if (!rc) rc = check_uv(p, at, "hatch end", h->uv, 2 * h->n, err);
    return rc;
}

/* 'F', 'A', 'M': the LADRP stage's records */
static int check_stage(lam_part *p, long long at, const lam_rec_op *op, lam_error *err)
{
    if (op->tag == 'F')
        return isfinite(op->rate) && op->rate >= 0 ? LAM_OK : bad_value(p, at, err, "a feed rate of %g", op->rate);
    int rc = check_flag(p, at, op->tag == 'A' ? "a laser" : "a move's deposit", op->flag, err);
    if (rc || op->tag == 'A') return rc;
    if ((rc = check_attrs(p, at, "a move", &op->move.attrs, err))) return rc;
    if ((rc = check_points(p, at, "a move to", op->move.xyz, 1, 3, err))) return rc;
    return check_uv(p, at, "a move to", op->move.uv, 1, err);
}

/* Every value of a decoded operation, as a slicing run writes it. */
static int check_op(lam_part *p, long long at, const lam_rec_op *op, lam_error *err)
{
    switch (op->tag) {
    case 'C': return check_contour(p, at, op, err);
    case 'H': return check_hatches(p, at, op, err);
    default: return check_stage(p, at, op, err);
    }
}

/* The part's end: its hash, its last layer, nothing after it. */
static int read_end(lam_part *p, long long at, int in_layer, size_t next, lam_error *err)
{
    uint64_t want = p->hash, got;
    int rc = get_u64(p, &got, err);
    if (rc) return rc;
    p->off = at;
    if (got != want) return corrupt(p, err, "its contents do not match its checksum");
    if (in_layer || next != p->meta.last) return corrupt(p, err, "it ends before its last layer");
    if (p->size != at + 9) {
        p->off = at + 9;
        return corrupt(p, err, "bytes after its end");
    }
    return LAM_OK;
}

/* One record in its place: layers in order within the part's range,
 * operations inside a layer. */
static int place(lam_part *p, long long at, const lam_rec_op *op, int *in_layer, size_t *next, lam_error *err)
{
    int tag = op->tag;
    if (!*in_layer && strchr("FAMCH", tag)) {
        p->off = at;
        return corrupt(p, err, "an operation outside a layer");
    }
    if (tag == 'L' && (*in_layer || *next >= p->meta.last)) {
        p->off = at;
        return corrupt(p, err, "a layer outside its range");
    }
    if (tag == 'E' && !*in_layer) {
        p->off = at;
        return corrupt(p, err, "a layer's end without its start");
    }
    if (tag == 'L' || tag == 'E') return check_layer_rec(p, at, op, *next, err);
    return check_op(p, at, op, err);
}

/* Replay one part's records into sink. */
static int replay(lam_part *p, const lam_sink *sink, lam_scan_time *time, double *layer_time, lam_error *err)
{
    size_t next = p->meta.first - 1;  /* 0-based index of the next layer */
    int in_layer = 0, rc = LAM_OK;
    /* from the first record, each time (join may check the parts first) */
    if (fseek(p->f, (long)p->body, SEEK_SET) != 0)
        return lam_error_set(err, LAM_EIO, p->path, 0, 0, "cannot read: %s", strerror(errno));
    p->off = p->body;
    p->hash = p->body_hash;
    p->layer.index = (size_t)-1;
    lam_rec_source src = { p, src_get, src_left, src_corrupt };
    lam_rec_scratch sc = { 0 };
    lam_rec_op op;
    for (;;) {
        long long at = p->off;
        if ((rc = lam_rec_read(&src, &sc, &op, err))) break;
        if (op.tag == 'Z') {
            rc = read_end(p, at, in_layer, next, err);
            break;
        }
        if ((rc = place(p, at, &op, &in_layer, &next, err))) break;
        if (op.tag == 'L') {
            p->layer = op.layer;
            in_layer = 1;
        } else if (op.tag == 'E') {
            if (time) lam_scan_time_add(time, &op.time);
            if (layer_time) layer_time[next] = lam_scan_time_total(&op.time);
            in_layer = 0;
            next++;
        }
        if ((rc = lam_rec_send(&op, sink))) break;
    }
    lam_rec_scratch_free(&sc);
    return rc;
}

int lam_part_join(lam_part *const *parts, size_t n, const lam_sink *sink, lam_scan_time *time, double *layer_time,
                  lam_error *err)
{
    if (!n) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "no part files to join");
    int rc = sink->begin ? sink->begin(sink->ctx, &parts[0]->job) : LAM_OK;
    for (size_t i = 0; i < n && !rc; i++) rc = replay(parts[i], sink, time, layer_time, err);
    if (!rc && sink->end) rc = sink->end(sink->ctx);
    if (rc && err && err->code == LAM_OK) lam_error_set(err, rc, NULL, 0, 0, "joining failed");
    return rc;
}
