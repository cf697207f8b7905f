/* The run as JSON, streamed layer by layer; see json_sink.h. */
#include "json_sink.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "dialect.h"
#include "escape.h"
#include "fmt.h"
#include "grow.h"
#include "hatch.h"
#include "repair.h"
#include "slice.h"
#include "vstream.h"

/* Text waits in buf until a line ends or it passes FLUSH_AT bytes, so a
 * contour of a million points never needs its whole line in memory. */
#define FLUSH_AT 65536

#define LAM_JSON_LASERS 16

typedef struct js {
    lam_writer *w;           /* the JSON, or NULL */
    lam_writer *script;      /* the same for a <script> element, or NULL */
    lam_error *err;
    lam_buf b;               /* text not written yet */
    int rc;                  /* sticky: the first error */
    lam_frame frame;
    int frame_machine;
    double cut;              /* the layer's build height */
    size_t layers, contours, vectors;
    double deposit_total, travel_total;
    lam_scan_time time;      /* the layers' estimates, summed */
    size_t timed;            /* layers that had one */
    /* a build's totals: each laser's (busiest-laser) time, each part's */
    double laser_time[LAM_JSON_LASERS];
    size_t nlasers;
    double *part_time;
    size_t nparts_time;
    /* the last points written: a vector starts where the one before ended,
     * so each point is formatted once (formatting is most of the time) */
    struct {
        double p[3];
        char text[3 * LAM_FMT_MAX + 8];
        size_t len;
    } seen[4];
    unsigned nseen, next_seen;
    double axis_val[3];      /* each coordinate's last value and text (coord) */
    char axis_text[3][40];
    unsigned char axis_len[3];
    lam_json_opts o;         /* what is written (first, last: 1..layers, last 0: to the end) */
    int skip;                /* the layer being planned is not written (outside first..last) */
    size_t written;          /* layers written */
    /* SUMMARY: the layer's groups of vectors, in order of first appearance */
    struct group {
        int kind;
        lam_attrs attrs;
        size_t count;
        double length;
    } *groups;
    size_t ngroups, cap_groups, last_group, prev_group;
} js;

static int nomem(js *s) { return s->rc = lam_error_nomem(s->err, "writing the JSON"); }

static void putn(js *s, const char *t, size_t n)
{
    if (!s->rc && lam_buf_append(&s->b, t, n)) nomem(s);
}

static void put(js *s, const char *t) { putn(s, t, strlen(t)); }

/* The text with every '<' as \u003c: in JSON text '<' is only ever a
 * string's character, so this is the text of LAM_ESC_JSON_SCRIPT strings. */
static int write_script(lam_writer *w, const char *t, size_t n)
{
    int rc = LAM_OK;
    for (const char *lt; !rc && n && (lt = memchr(t, '<', n));) {
        rc = lam_writer_write(w, t, (size_t)(lt - t));
        if (!rc) rc = lam_writer_write(w, "\\u003c", 6);
        n -= (size_t)(lt - t) + 1;
        t = lt + 1;
    }
    return rc || !n ? rc : lam_writer_write(w, t, n);
}

static void flush(js *s)
{
    if (s->rc || !s->b.len) return;
    if (s->w && lam_writer_write(s->w, s->b.data, s->b.len)) s->rc = lam_writer_error(s->w, s->err);
    if (!s->rc && s->script && write_script(s->script, s->b.data, s->b.len)) s->rc = lam_writer_error(s->script, s->err);
    lam_buf_clear(&s->b);
}

/* A line ends: the text goes out when enough has gathered. */
static void line(js *s)
{
    put(s, "\n");
    if (s->b.len >= FLUSH_AT) flush(s);
}

static void num(js *s, double x)
{
    if (s->rc) return;
    if (!isfinite(x)) {
        s->rc = lam_error_set(s->err, LAM_EINVAL, NULL, 0, 0,
                              "a number that is not finite in layer %zu: JSON cannot hold it", s->layers + 1);
        return;
    }
    char b[LAM_FMT_MAX];
    putn(s, b, lam_dialect_number(b, x));
}

/* A whole number's digits (no printf: one for each vector's order) */
static void unum(js *s, unsigned long long n)
{
    char b[24], *e = b + sizeof b, *p = e;
    do *--p = (char)('0' + (int)(n % 10)); while (n /= 10);
    putn(s, p, (size_t)(e - p));
}

static void size(js *s, size_t n) { unum(s, n); }

/* A point's coordinate: the axis's last one again (a layer's height, a
 * hatch line's across its direction) is not formatted again. */
static void coord(js *s, int axis, double x)
{
    if (s->axis_len[axis] && !memcmp(&s->axis_val[axis], &x, sizeof x)) {
        putn(s, s->axis_text[axis], s->axis_len[axis]);
        return;
    }
    size_t at = s->b.len;
    num(s, x);
    size_t n = s->b.len - at;
    if (s->rc || n > sizeof s->axis_text[axis]) return;
    s->axis_val[axis] = x;
    s->axis_len[axis] = (unsigned char)n;
    memcpy(s->axis_text[axis], s->b.data + at, n);
}

static void pt(js *s, const double p[3])
{
    for (unsigned i = 0; i < s->nseen; i++)
        if (!memcmp(s->seen[i].p, p, sizeof s->seen[i].p)) {
            putn(s, s->seen[i].text, s->seen[i].len);
            return;
        }
    size_t at = s->b.len;
    put(s, "[");
    coord(s, 0, p[0]);
    put(s, ", ");
    coord(s, 1, p[1]);
    put(s, ", ");
    coord(s, 2, p[2]);
    put(s, "]");
    if (s->rc) return;
    unsigned k = s->next_seen;
    s->next_seen = (k + 1) % 4;
    if (s->nseen < 4) s->nseen++;
    memcpy(s->seen[k].p, p, sizeof s->seen[k].p);
    s->seen[k].len = s->b.len - at;
    memcpy(s->seen[k].text, s->b.data + at, s->b.len - at);
}

/* A JSON string, escaped by escape.h (bytes that are not UTF-8, which a
 * path may hold, become U+FFFD, so the document stays valid). */
static void str(js *s, const char *t)
{
    lam_esc_mode mode = LAM_ESC_JSON;
    size_t n = t ? strlen(t) : 0;
    put(s, "\"");
    while (n) {
        char e[LAM_ESC_MAX];
        size_t k = lam_esc_plain(t, n, mode);
        if (k) putn(s, t, k);
        else put(s, (k = lam_esc_one(t, n, mode, e), e));
        t += k, n -= k;
    }
    put(s, "\"");
}

static void key(js *s, const char *k)
{
    str(s, k);
    put(s, ": ");
}

/* `, "k": x` for each of n keys and numbers (the first without its comma
 * when `first`). */
/* What repair on load did (repair.h's rows), when it did anything. */
static void repair_obj(js *s, const lam_repair_report *r)
{
    put(s, ",");
    line(s);
    put(s, "  ");
    key(s, "repair");
    put(s, "{");
    const char *sep = "";
#define COUNT(f) put(s, sep), key(s, #f), size(s, r->f), sep = ", ";
    LAM_REPAIR_COUNTS(COUNT)
#undef COUNT
#define MEASURE(f) put(s, ", "), key(s, #f), num(s, r->f);
    LAM_REPAIR_MEASURES(MEASURE)
#undef MEASURE
    put(s, "}");
}

static void nums(js *s, int first, const char *const *k, const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        put(s, first && i == 0 ? "" : ", ");
        key(s, k[i]);
        num(s, x[i]);
    }
}

static void integer(js *s, long long x)
{
    if (x < 0) put(s, "-");
    unum(s, x < 0 ? -(unsigned long long)x : (unsigned long long)x);
}

/* An SLS run's exposures (job.exposure): each region's power, speed and
 * distance, per build style in a build; point exposure's keys when it is on. */
static void exposure_list(js *s, const lam_job_info *job)
{
    const lam_job_exposure *e = job->exposure ? job->exposure : job->own_exposure;
    put(s, ",");
    line(s);
    put(s, "  ");
    key(s, "exposure");
    put(s, "[");
    for (size_t i = 0; i < job->nexposure; i++) {
        put(s, i ? ", {\"style\": " : "{\"style\": ");
        integer(s, e[i].style);
        put(s, ", \"region\": \"");
        put(s, lam_kind_name(e[i].region));
        put(s, "\"");
        static const char *const keys[] = { "power", "speed", "distance", "point_distance", "exposure_time" };
        nums(s, 0, keys, (const double[]){ e[i].power, e[i].speed, e[i].distance, e[i].point_distance,
                                           e[i].exposure_time }, e[i].point_distance > 0 ? 5 : 3);
        put(s, "}");
    }
    put(s, "]");
}

static void to_out(const js *s, double u, double v, double xyz[3])
{
    if (s->frame_machine) {
        xyz[0] = u;
        xyz[1] = v;
        xyz[2] = s->cut;
    } else {
        lam_frame_to_model(&s->frame, u, v, s->cut, xyz);
    }
}

static int j_begin(void *ctx, const lam_job_info *job)
{
    js *s = ctx;
    if (job->frame) s->frame = *job->frame;
    else lam_frame_axis('z', &s->frame, NULL);
    s->frame_machine = job->frame_machine;
    put(s, "{\"format\": \"lamina-run\", \"version\": ");
    size(s, LAM_JSON_VERSION);
    put(s, ",");
    line(s);
    put(s, " \"job\": {");
    key(s, "model");
    str(s, job->model ? job->model : job->label);
    put(s, ", ");
    key(s, "machine");
    str(s, job->name);
    put(s, ", ");
    key(s, "process");
    str(s, job->process);
    put(s, ", ");
    key(s, "units");
    str(s, job->units);
    put(s, ", ");
    key(s, "frame");
    str(s, s->frame_machine ? "machine" : "model");
    put(s, ",");
    line(s);
    put(s, "  ");
    key(s, "axis");
    pt(s, s->frame.w);
    put(s, ", ");
    key(s, "plane");
    /* the output frame's points project onto the layer plane: in the model
     * frame with the layer frame's axes, in the machine frame as they are */
    static const double zero[3] = { 0, 0, 0 }, ex[3] = { 1, 0, 0 }, ey[3] = { 0, 1, 0 }, ez[3] = { 0, 0, 1 };
    put(s, "{\"origin\": ");
    pt(s, zero);
    put(s, ", \"u\": ");
    pt(s, s->frame_machine ? ex : s->frame.u);
    put(s, ", \"v\": ");
    pt(s, s->frame_machine ? ey : s->frame.v);
    put(s, ", \"w\": ");
    pt(s, s->frame_machine ? ez : s->frame.w);
    put(s, "},");
    line(s);
    /* the layer frame in the model, also when the points are in it: what
     * a reader needs to put a machine-frame run back on the model */
    put(s, "  ");
    key(s, "layer_frame");
    put(s, "{\"u\": ");
    pt(s, s->frame.u);
    put(s, ", \"v\": ");
    pt(s, s->frame.v);
    put(s, ", \"w\": ");
    pt(s, s->frame.w);
    put(s, "},");
    line(s);
    put(s, "  ");
    key(s, "bbox");
    put(s, "[");
    for (int i = 0; i < 6; i++) {
        if (i) put(s, ", ");
        num(s, job->bbox[i]);
    }
    put(s, "], ");
    key(s, "layers");
    size(s, job->layers);
    put(s, ", ");
    key(s, "bead");
    num(s, job->bead);
    if (job->process && !strcmp(job->process, "sls")) exposure_list(s, job);
    if (job->repair) repair_obj(s, job->repair);
    if (job->json_extra) {
        put(s, ",");
        line(s);
        put(s, "  ");
        put(s, job->json_extra);
    }
    put(s, "},");
    line(s);
    put(s, " \"layers\": [");
    return s->rc;
}

/* Contours of L as lines, numbered from id0 + 1; region: a "region" key
 * (the support's), part: each contour's part (a build), or NULL. */
static void contour_lines(js *s, const lam_layer *L, size_t id0, const char *region, const long long *part)
{
    for (size_t k = 0; L && k < L->ncontours; k++) {
        const lam_contour *c = &L->contours[k];
        put(s, k || id0 ? "," : "");
        line(s);
        put(s, "    {\"id\": ");
        size(s, id0 + k + 1);
        if (region) put(s, ", \"region\": \""), put(s, region), put(s, "\"");
        put(s, c->kind == LAM_SOLID ? ", \"solid\": true, \"depth\": " : ", \"solid\": false, \"depth\": ");
        size(s, c->depth > 0 ? (size_t)c->depth : 0);
        put(s, ", \"parent\": ");
        if (c->parent >= 0) size(s, id0 + (size_t)c->parent + 1);
        else put(s, "null");
        put(s, ", \"area\": ");
        num(s, c->area);
        if (part) put(s, ", \"part\": "), integer(s, part[k]);
        put(s, ", \"points\": [");
        for (size_t i = 0; i < c->n; i++) {
            const double *uv = L->uv + 2 * (c->first + i);
            double p[3];
            to_out(s, uv[0], uv[1], p);
            if (i) put(s, ", ");
            pt(s, p);
            if (s->b.len >= FLUSH_AT) flush(s);
        }
        put(s, "]}");
    }
}

/* A layer's section, then its support region (region "support") and its
 * overhang (region "overhang"): each contour a line. */
static void contours(js *s, const lam_layer_info *li)
{
    put(s, ",");
    line(s);
    put(s, "   \"contours\": [");
    size_t n = li->section ? li->section->ncontours : 0, ns = li->support ? li->support->ncontours : 0;
    contour_lines(s, li->section, 0, NULL, li->section_part);
    contour_lines(s, li->support, n, lam_kind_name(LAM_KIND_SUPPORT), li->support_part);
    contour_lines(s, li->overhang, n + ns, "overhang", li->overhang_part);
    put(s, "]");
}

static int j_layer(void *ctx, const lam_layer_info *li)
{
    js *s = ctx;
    s->cut = li->z;
    size_t index = li->index + 1;
    s->contours += li->section ? li->section->ncontours : 0; /* the run's, written or not */
    s->contours += li->support ? li->support->ncontours : 0;
    s->contours += li->overhang ? li->overhang->ncontours : 0;
    s->skip = index < s->o.first || (s->o.last && index > s->o.last);
    s->ngroups = s->last_group = s->prev_group = 0;
    if (s->skip) return s->rc;
    put(s, s->written++ ? "," : "");
    line(s);
    put(s, "  {\"index\": ");
    size(s, index);
    static const char *const keys[] = { "z", "floor", "ceiling", "width" };
    nums(s, 0, keys, (const double[]){ li->z, li->floor, li->ceiling, li->width }, 4);
    if (li->has_cut) put(s, ", \"cut\": "), num(s, li->cut);
    if (!s->o.no_contours) contours(s, li);
    if (s->o.vectors == LAM_JSON_VECTORS_ALL) {
        put(s, ",");
        line(s);
        put(s, "   \"vectors\": [");
    }
    return s->rc;
}

/* A vector's (or a summary group's) attributes: an attribute at its
 * default is left out (vocab.h), but in a build (a style set): there every
 * vector says its part, region, style and laser (docs/builds.md). */
static void attrs_text(js *s, int kind, const lam_attrs *a)
{
    int build = a->style != 0;
    if (build && kind < LAM_REGIONS) {
        put(s, ", \"region\": \"");
        put(s, lam_kind_name(kind));
        put(s, "\"");
    }
    for (size_t i = 0; i < LAM_NATTRS; i++)
        if (build || lam_attr_get(a, i) != lam_attr_default(i)) {
            put(s, ", ");
            key(s, lam_attr_key(i));
            integer(s, lam_attr_get(a, i));
        }
}

static int in_group(const struct group *g, const lam_vec *v)
{
    return g->kind == v->kind && !memcmp(&g->attrs, &v->attrs, sizeof v->attrs);
}

/* SUMMARY: the vector counted in its (kind, attributes) group; most
 * vectors are in the group of the one before or the one before that (a
 * hatching alternates jump, hatch, jump), so those two are tried first. */
static void summarise(js *s, const lam_vec *v)
{
    struct group *g = s->ngroups ? &s->groups[s->last_group] : NULL;
    if (!g || !in_group(g, v)) {
        size_t before = s->last_group;
        g = s->ngroups && in_group(&s->groups[s->prev_group], v) ? &s->groups[s->prev_group] : NULL;
        for (size_t i = 0; i < s->ngroups && !g; i++)
            if (in_group(&s->groups[i], v)) g = &s->groups[i];
        if (!g) {
            if (s->ngroups == s->cap_groups) {
                struct group *ng = lam_grow(s->groups, &s->cap_groups, s->ngroups + 1, sizeof *ng, 16);
                if (!ng) {
                    nomem(s);
                    return;
                }
                s->groups = ng;
            }
            g = &s->groups[s->ngroups++];
            *g = (struct group){ .kind = v->kind, .attrs = v->attrs };
        }
        s->last_group = (size_t)(g - s->groups);
        s->prev_group = before;
    }
    g->count++;
    g->length += v->length; /* as vstream.c measures it for the layer's stats */
}

/* The plan's vectors come decoded by vstream.h, by the rules the SVG
 * preview draws them with. */
static int j_vector(void *ctx, const lam_vec *v)
{
    js *s = ctx;
    s->vectors++;
    if (s->skip || s->o.vectors == LAM_JSON_VECTORS_NONE) return s->rc;
    if (s->o.vectors == LAM_JSON_VECTORS_SUMMARY) {
        summarise(s, v);
        return s->rc;
    }
    put(s, v->order > 1 ? "," : "");
    line(s);
    put(s, "    {\"kind\": \"");
    put(s, lam_kind_name(v->kind));
    put(s, "\", \"from\": ");
    pt(s, v->from);
    put(s, ", \"to\": ");
    pt(s, v->to);
    put(s, ", \"order\": ");
    size(s, v->order);
    attrs_text(s, v->kind, &v->attrs);
    put(s, "}");
    if (s->b.len >= FLUSH_AT) flush(s);
    return s->rc;
}

/* SUMMARY: the layer's groups, each a line. */
static void summary(js *s)
{
    put(s, ",");
    line(s);
    put(s, "   \"summary\": [");
    for (size_t i = 0; i < s->ngroups; i++) {
        const struct group *g = &s->groups[i];
        put(s, i ? "," : "");
        line(s);
        put(s, "    {\"kind\": \"");
        put(s, lam_kind_name(g->kind));
        put(s, "\"");
        attrs_text(s, g->kind, &g->attrs);
        put(s, ", \"count\": ");
        size(s, g->count);
        put(s, ", \"length\": ");
        num(s, g->length);
        put(s, "}");
    }
    put(s, "]");
}

static void time_object(js *s, const lam_scan_time *t)
{
    put(s, "{\"total\": ");
    num(s, lam_scan_time_total(t));
    put(s, ", \"exposure\": ");
    num(s, t->exposure);
    put(s, ", \"jumps\": ");
    num(s, t->jump);
    put(s, ", \"recoat\": ");
    num(s, t->recoat);
    put(s, "}");
}

/* A build layer's lasers: each one's time, exposure and jumps, and the
 * balance (the busiest over the ideal, lasers.h). */
static void lasers_obj(js *s, const lam_layer_info *li)
{
    put(s, ", \"lasers\": [");
    for (size_t l = 0; l < li->nlasers; l++) {
        const lam_scan_time *t = &li->lasers[l];
        put(s, l ? ", {\"laser\": " : "{\"laser\": ");
        size(s, l + 1);
        static const char *const keys[] = { "time", "exposure", "jumps", "exposed" };
        nums(s, 0, keys, (const double[]){ t->exposure + t->jump, t->exposure, t->jump, t->exposure_length }, 4);
        put(s, "}");
    }
    put(s, "], \"balance\": ");
    num(s, li->balance);
}

/* A build layer's parts: each one's own time. */
static void parts_obj(js *s, const lam_layer_info *li)
{
    put(s, ", \"parts\": [");
    for (size_t i = 0; i < li->nparts; i++) {
        const lam_part_time *p = &li->parts[i];
        put(s, i ? ", {\"part\": " : "{\"part\": ");
        integer(s, p->part);
        put(s, ", \"time\": ");
        num(s, p->time);
        put(s, "}");
    }
    put(s, "]");
}

/* The layer in the run's totals, whether it is written or not: lengths,
 * time, and a build's lasers' and parts' times. */
static void add_totals(js *s, const lam_layer_info *li, const lam_vec_stats *st)
{
    s->layers++;
    s->deposit_total += st->deposit_length;
    s->travel_total += st->travel_length;
    if (li->time) {
        lam_scan_time_add(&s->time, li->time);
        s->timed++;
    }
    for (size_t l = 0; l < li->nlasers && l < LAM_JSON_LASERS; l++)
        s->laser_time[l] += li->lasers[l].exposure + li->lasers[l].jump;
    if (li->nlasers > s->nlasers) s->nlasers = li->nlasers < LAM_JSON_LASERS ? li->nlasers : LAM_JSON_LASERS;
    for (size_t i = 0; i < li->nparts; i++) {
        const lam_part_time *p = &li->parts[i];
        if (p->part >= 1 && (size_t)p->part > s->nparts_time) {
            size_t n = (size_t)p->part;
            double *t = realloc(s->part_time, n * sizeof *t);
            if (!t) {
                nomem(s);
                return;
            }
            memset(t + s->nparts_time, 0, (n - s->nparts_time) * sizeof *t);
            s->part_time = t;
            s->nparts_time = n;
        }
        if (p->part >= 1) s->part_time[p->part - 1] += p->time;
    }
}

static int j_layer_end(void *ctx, const lam_layer_info *li, const lam_vec_stats *st)
{
    js *s = ctx;
    if (!s->skip) {
        double area = 0;
        for (size_t k = 0; li->section && k < li->section->ncontours; k++) area += li->section->contours[k].area;
        if (s->o.vectors == LAM_JSON_VECTORS_ALL) put(s, "]");
        else if (s->o.vectors == LAM_JSON_VECTORS_SUMMARY) summary(s);
        put(s, ",");
        line(s);
        put(s, "   \"stats\": {\"area\": ");
        num(s, area);
        put(s, ", \"vectors\": ");
        size(s, st->vectors);
        put(s, ", \"deposit_length\": ");
        num(s, st->deposit_length);
        put(s, ", \"travel_length\": ");
        num(s, st->travel_length);
        put(s, ", \"time\": ");
        if (li->time) num(s, lam_scan_time_total(li->time));
        else put(s, "null");
        if (li->nlasers) lasers_obj(s, li);
        if (li->nparts) parts_obj(s, li);
        put(s, "}}");
    }
    add_totals(s, li, st);
    flush(s); /* the layer is whole: out it goes */
    return s->rc;
}

/* A list of numbered times: [{"KEY": 1, "time": t[0]}, ...]. */
static void numbered_times(js *s, const char *list, const char *key, const double *t, size_t n)
{
    put(s, ", \"");
    put(s, list);
    put(s, "\": [");
    for (size_t i = 0; i < n; i++) {
        put(s, i ? ", {\"" : "{\"");
        put(s, key);
        put(s, "\": ");
        size(s, i + 1);
        put(s, ", \"time\": ");
        num(s, t[i]);
        put(s, "}");
    }
    put(s, "]");
}

/* A build's totals: each laser's time and each part's. */
static void build_totals(js *s)
{
    if (s->nlasers) numbered_times(s, "lasers", "laser", s->laser_time, s->nlasers);
    if (s->nparts_time) numbered_times(s, "parts", "part", s->part_time, s->nparts_time);
}

static int j_end(void *ctx)
{
    js *s = ctx;
    put(s, "],");
    line(s);
    put(s, " \"totals\": {\"layers\": ");
    size(s, s->layers);
    put(s, ", \"contours\": ");
    size(s, s->contours);
    put(s, ", \"vectors\": ");
    size(s, s->vectors);
    static const char *const keys[] = { "deposit_length", "travel_length" };
    nums(s, 0, keys, (const double[]){ s->deposit_total, s->travel_total }, 2);
    put(s, ", \"time\": ");
    /* a total only when every layer had its estimate */
    if (s->timed && s->timed == s->layers) time_object(s, &s->time);
    else put(s, "null");
    build_totals(s);
    put(s, "}}");
    line(s);
    flush(s);
    return s->rc;
}

static void j_destroy(void *ctx)
{
    js *s = ctx;
    lam_buf_free(&s->b);
    free(s->part_time);
    free(s->groups);
    free(s);
}

int lam_json_consumer(lam_writer *w, lam_writer *script, lam_vec_consumer *out, lam_error *err)
{
    return lam_json_consumer_opts(w, script, NULL, out, err);
}

int lam_json_consumer_opts(lam_writer *w, lam_writer *script, const lam_json_opts *o, lam_vec_consumer *out,
                           lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (o && ((o->vectors != LAM_JSON_VECTORS_ALL && o->vectors != LAM_JSON_VECTORS_SUMMARY &&
               o->vectors != LAM_JSON_VECTORS_NONE) ||
              (o->last && o->first > o->last)))
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "JSON options: vectors %d, layers %zu to %zu", o->vectors,
                             o->first, o->last);
    js *s = calloc(1, sizeof *s);
    if (!s) return lam_error_nomem(err, "writing the JSON");
    s->w = w;
    s->script = script;
    s->err = err;
    if (o) s->o = *o;
    *out = (lam_vec_consumer){ .ctx = s, .begin = j_begin, .layer = j_layer, .vector = j_vector,
                               .layer_end = j_layer_end, .end = j_end, .destroy = j_destroy };
    return LAM_OK;
}
