#include "html.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dialect.h"
#include "fmt.h"
#include "grow.h"
#include "viewer_html.h"
#include "vstream.h"

/* A layer read but not yet planned: its sections. */
typedef struct section {
    size_t index;
    double cut;
    double *uv;
    lam_contour *contours;
    size_t ncontours;
} section;

struct lam_html {
    lam_writer *w;
    char *model;
    lam_frame f;
    int machine;
    const double *layer_time;
    const lam_scan_time *total;
    lam_error *err;
    section *q;                 /* FIFO of sections: q[head .. head+nq) */
    size_t head, nq, cap;
    size_t nvec, ncontours, layers;
    double dep, trav;
    double area;                /* the current layer's net area */
    int have_time;
};

static void num(lam_writer *w, double x)
{
    char buf[LAM_FMT_MAX];
    if (!isfinite(x)) {
        lam_writer_write(w, "null", 4);
        return;
    }
    lam_writer_write(w, buf, lam_dialect_number(buf, x));
}

static void vec3(lam_writer *w, const double p[3])
{
    lam_writer_write(w, "[", 1);
    num(w, p[0]);
    lam_writer_write(w, ",", 1);
    num(w, p[1]);
    lam_writer_write(w, ",", 1);
    num(w, p[2]);
    lam_writer_write(w, "]", 1);
}

/* A JSON string that can sit inside an HTML <script> element. */
static void str(lam_writer *w, const char *s)
{
    lam_writer_write(w, "\"", 1);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        if (*p == '"' || *p == '\\') lam_writer_printf(w, "\\%c", *p);
        else if (*p < 0x20 || *p == '<' || *p == '>' || *p == '&') lam_writer_printf(w, "\\u%04x", *p);
        else lam_writer_write(w, p, 1);
    }
    lam_writer_write(w, "\"", 1);
}

static void section_free(section *s)
{
    free(s->uv);
    free(s->contours);
}

int lam_html_new(lam_writer *w, const char *model, const lam_frame *f, int frame_machine, lam_html **out,
                 lam_error *err)
{
    *out = NULL;
    lam_html *h = calloc(1, sizeof *h);
    if (h) h->model = strdup(model ? model : "");
    if (!h || !h->model) {
        lam_html_free(h);
        return lam_error_nomem(err, "making the viewer");
    }
    h->w = w;
    h->f = *f;
    h->machine = frame_machine;
    *out = h;
    return LAM_OK;
}

void lam_html_times(lam_html *h, const double *layer_time, const lam_scan_time *total)
{
    h->layer_time = layer_time;
    h->total = total;
}

int lam_html_section(lam_html *h, const lam_layer *L, lam_error *err)
{
    if (h->head + h->nq == h->cap) {
        if (h->head) { /* slide to the front before growing */
            memmove(h->q, h->q + h->head, h->nq * sizeof *h->q);
            h->head = 0;
        }
        if (h->nq == h->cap) {
            section *n = lam_grow(h->q, &h->cap, h->nq + 1, sizeof *n, 4);
            if (!n) return lam_error_nomem(err, "making the viewer");
            h->q = n;
        }
    }
    section s = { L->index, L->cut, malloc((2 * L->npoints + 1) * sizeof *s.uv),
                  malloc((L->ncontours + 1) * sizeof *s.contours), L->ncontours };
    if (!s.uv || !s.contours) {
        section_free(&s);
        return lam_error_nomem(err, "making the viewer");
    }
    memcpy(s.uv, L->uv, 2 * L->npoints * sizeof *s.uv);
    memcpy(s.contours, L->contours, L->ncontours * sizeof *s.contours);
    h->q[h->head + h->nq++] = s;
    return LAM_OK;
}

void lam_html_free(lam_html *h)
{
    if (!h) return;
    for (size_t k = 0; k < h->nq; k++) section_free(&h->q[h->head + k]);
    free(h->q);
    free(h->model);
    free(h);
}

/* ---- the sink ------------------------------------------------------------- */

static const char *mark(void)
{
    return strstr(lam_viewer_html, LAM_VIEWER_MARK);
}

static int ht_begin(void *ctx, const lam_job_info *job)
{
    lam_html *h = ctx;
    lam_writer *w = h->w;
    const char *m = mark();
    lam_writer_write(w, lam_viewer_html, (size_t)(m - lam_viewer_html));
    lam_writer_printf(w, "{\"format\":\"lamina-run\",\"version\":1,\n\"job\":{\"model\":");
    str(w, h->model);
    lam_writer_printf(w, ",\"machine\":");
    str(w, job->name ? job->name : "sls-contours");
    lam_writer_printf(w, ",\"process\":");
    str(w, job->process);
    lam_writer_printf(w, ",\"units\":");
    if (job->units) str(w, job->units);
    else lam_writer_write(w, "null", 4);
    lam_writer_printf(w, ",\"frame\":\"%s\",\"axis\":", h->machine ? "machine" : "model");
    static const lam_frame ident = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    const lam_frame *pf = h->machine ? &ident : &h->f;
    vec3(w, h->f.w);
    lam_writer_printf(w, ",\"plane\":{\"origin\":[0,0,0],\"u\":");
    vec3(w, pf->u);
    lam_writer_printf(w, ",\"v\":");
    vec3(w, pf->v);
    lam_writer_printf(w, ",\"w\":");
    vec3(w, pf->w);
    lam_writer_printf(w, "},\"bbox\":[");
    for (int k = 0; k < 6; k++) {
        if (k) lam_writer_write(w, ",", 1);
        num(w, job->bbox[k]);
    }
    lam_writer_printf(w, "],\"layers\":%zu,\"bead\":", job->layers);
    num(w, job->bead);
    lam_writer_printf(w, "},\n\"layers\":[");
    return lam_writer_error(w, h->err);
}

static void to_out(const lam_html *h, double u, double v, double cut, double xyz[3])
{
    if (h->machine) {
        xyz[0] = u, xyz[1] = v, xyz[2] = cut;
        return;
    }
    lam_frame_to_model(&h->f, u, v, cut, xyz);
}

static int ht_layer(void *ctx, const lam_layer_info *li)
{
    lam_html *h = ctx;
    lam_writer *w = h->w;
    /* the section of this layer: the oldest kept */
    while (h->nq && h->q[h->head].index < li->index) {
        section_free(&h->q[h->head++]);
        h->nq--;
    }
    const section *s = h->nq && h->q[h->head].index == li->index ? &h->q[h->head] : NULL;
    lam_writer_printf(w, "%s\n{\"index\":%zu,\"z\":", h->layers ? "," : "", li->index + 1);
    num(w, li->z);
    lam_writer_printf(w, ",\"floor\":");
    num(w, li->floor);
    lam_writer_printf(w, ",\"ceiling\":");
    num(w, li->ceiling);
    lam_writer_printf(w, ",\"width\":");
    num(w, li->width);
    lam_writer_printf(w, ",\"contours\":[");
    h->area = 0;
    for (size_t k = 0; s && k < s->ncontours; k++) {
        const lam_contour *c = &s->contours[k];
        lam_writer_printf(w, "%s\n {\"id\":%zu,\"solid\":%s,\"depth\":%d,\"parent\":", k ? "," : "", k + 1,
                          c->kind == LAM_SOLID ? "true" : "false", c->depth);
        if (c->parent >= 0) lam_writer_printf(w, "%ld", c->parent + 1);
        else lam_writer_write(w, "null", 4);
        lam_writer_printf(w, ",\"area\":");
        num(w, c->area);
        lam_writer_printf(w, ",\"points\":[");
        for (size_t j = 0; j < c->n; j++) {
            double xyz[3];
            to_out(h, s->uv[2 * (c->first + j)], s->uv[2 * (c->first + j) + 1], s->cut, xyz);
            if (j) lam_writer_write(w, ",", 1);
            vec3(w, xyz);
        }
        lam_writer_write(w, "]}", 2);
        h->area += c->area;
    }
    h->ncontours += s ? s->ncontours : 0;
    if (s) {
        section_free(&h->q[h->head++]);
        h->nq--;
    }
    lam_writer_printf(w, "],\"vectors\":[");
    return lam_writer_error(w, h->err);
}

static int ht_vector(void *ctx, const lam_vec *v)
{
    lam_html *h = ctx;
    lam_writer *w = h->w;
    lam_writer_printf(w, "%s\n {\"kind\":\"%s\",\"from\":", v->order > 1 ? "," : "", v->kind);
    vec3(w, v->from);
    lam_writer_printf(w, ",\"to\":");
    vec3(w, v->to);
    lam_writer_printf(w, ",\"order\":%zu}", v->order);
    return lam_writer_error(w, h->err);
}

static int ht_layer_end(void *ctx, const lam_layer_info *li, const lam_vec_stats *st)
{
    lam_html *h = ctx;
    lam_writer *w = h->w;
    lam_writer_printf(w, "],\"stats\":{\"area\":");
    num(w, h->area);
    lam_writer_printf(w, ",\"vectors\":%zu,\"deposit_length\":", st->vectors);
    num(w, st->deposit_length);
    lam_writer_printf(w, ",\"travel_length\":");
    num(w, st->travel_length);
    lam_writer_printf(w, ",\"time\":");
    if (h->layer_time) num(w, h->layer_time[li->index]);
    else lam_writer_write(w, "null", 4);
    lam_writer_write(w, "}}", 2);
    h->layers++;
    h->nvec += st->vectors;
    h->dep += st->deposit_length;
    h->trav += st->travel_length;
    return lam_writer_error(w, h->err);
}

static int ht_end(void *ctx)
{
    lam_html *h = ctx;
    lam_writer *w = h->w;
    lam_writer_printf(w, "],\n\"totals\":{\"layers\":%zu,\"contours\":%zu,\"vectors\":%zu,\"deposit_length\":",
                      h->layers, h->ncontours, h->nvec);
    num(w, h->dep);
    lam_writer_printf(w, ",\"travel_length\":");
    num(w, h->trav);
    lam_writer_printf(w, ",\"time\":");
    if (h->total) {
        lam_writer_printf(w, "{\"total\":");
        num(w, lam_scan_time_total(h->total));
        lam_writer_printf(w, ",\"exposure\":");
        num(w, h->total->exposure);
        lam_writer_printf(w, ",\"jumps\":");
        num(w, h->total->jump);
        lam_writer_printf(w, ",\"recoat\":");
        num(w, h->total->recoat);
        lam_writer_write(w, "}", 1);
    } else {
        lam_writer_write(w, "null", 4);
    }
    lam_writer_printf(w, "}}\n");
    const char *m = mark() + strlen(LAM_VIEWER_MARK);
    lam_writer_write(w, m, lam_viewer_html_len - (size_t)(m - lam_viewer_html));
    return lam_writer_error(w, h->err);
}

int lam_html_sink(lam_html *h, lam_sink *out, lam_error *err)
{
    h->err = err;
    lam_vec_consumer c = { h, ht_begin, ht_layer, ht_vector, ht_layer_end, ht_end, NULL };
    return lam_vstream_sink(&h->f, h->machine, &c, out, err);
}
