/* The viewer page; see html.h and docs/viewer.md. */
#include "html.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "buf.h"
#include "escape.h"
#include "fmt.h"
#include "frame.h"
#include "json_sink.h"
#include "layer.h"
#include "vblock.h"
#include "viewer_html.h"

typedef struct page {
    lam_writer *w;
    lam_error *err;
    lam_vec_consumer json;   /* the run's summary JSON, to meta */
    lam_writer *meta;        /* that JSON until the end */
    lam_vblock vb;
    lam_buf bytes, text;     /* the layer's block, and as base64 */
    size_t layer;            /* layers written */
} page;

static void text(page *p, const char *t) { lam_writer_write(p->w, t, strlen(t)); }

/* The template's text from `from` (NULL: its start) to the marker `to`
 * (NULL: its end), the markers' own text left out. */
static void part(page *p, const char *from, const char *to)
{
    const char *a = lam_viewer_html, *end = lam_viewer_html + lam_viewer_html_len;
    if (from) a = strstr(lam_viewer_html, from) + strlen(from);
    const char *b = to ? strstr(lam_viewer_html, to) : end;
    lam_writer_write(p->w, a, (size_t)(b - a));
}

/* The run's extent in the layer plane: the job's box, projected. */
static void uv_box(const lam_job_info *job, double box[4])
{
    lam_frame f;
    if (job->frame && !job->frame_machine) f = *job->frame;
    else lam_frame_axis('z', &f, NULL);
    box[0] = box[1] = HUGE_VAL;
    box[2] = box[3] = -HUGE_VAL;
    for (int i = 0; i < 8; i++) {
        const double *b = job->bbox;
        double q[3] = { b[(i & 1) ? 3 : 0], b[(i & 2) ? 4 : 1], b[(i & 4) ? 5 : 2] };
        double u = q[0] * f.u[0] + q[1] * f.u[1] + q[2] * f.u[2];
        double v = q[0] * f.v[0] + q[1] * f.v[1] + q[2] * f.v[2];
        box[0] = fmin(box[0], u), box[1] = fmin(box[1], v);
        box[2] = fmax(box[2], u), box[3] = fmax(box[3], v);
    }
    if (!(box[2] >= box[0] && box[3] >= box[1] && isfinite(box[0]) && isfinite(box[3])))
        box[0] = box[1] = 0, box[2] = box[3] = 1;
}

static void names(page *p, const char *key, size_t n, const char *(*name)(size_t))
{
    lam_writer_printf(p->w, ", \"%s\": [", key);
    for (size_t i = 0; i < n; i++) lam_writer_printf(p->w, "%s\"%s\"", i ? ", " : "", name(i));
    text(p, "]");
}

static const char *kind_name(size_t i) { return lam_kind_name((int)i); }

static void head(page *p, const lam_job_info *job, const double box[4])
{
    char t[LAM_FMT_NUM];
    lam_writer_printf(p->w, "<script type=\"application/json\" id=\"lamina-head\">{\"format\": \"lamina-viewer\", "
                            "\"version\": 1, \"quantum\": %s, \"box\": [",
                      lam_fmt_num(t, p->vb.quantum, 17));
    for (int k = 0; k < 4; k++) lam_writer_printf(p->w, "%s%s", k ? ", " : "", lam_fmt_num(t, box[k], 17));
    text(p, "], \"units\": \"");
    lam_esc_write(p->w, job->units ? job->units : "", LAM_ESC_JSON_SCRIPT);
    lam_writer_printf(p->w, "\", \"layers\": %zu", job->layers);
    names(p, "kinds", LAM_KINDS, kind_name);
    names(p, "attrs", LAM_NATTRS, lam_attr_key);
    text(p, "}</script>\n");
}

static int p_begin(void *ctx, const lam_job_info *job)
{
    page *p = ctx;
    double box[4];
    uv_box(job, box);
    lam_vblock_init(&p->vb, lam_vblock_quantum(job->units, box));
    part(p, NULL, LAM_VIEWER_HEAD);
    head(p, job, box);
    part(p, LAM_VIEWER_HEAD, LAM_VIEWER_DATA);
    int rc = lam_writer_error(p->w, p->err);
    return rc ? rc : p->json.begin(p->json.ctx, job);
}

static int p_layer(void *ctx, const lam_layer_info *li)
{
    page *p = ctx;
    lam_vblock_reset(&p->vb);
    const lam_layer *L = li->section;
    for (size_t k = 0; L && k < L->ncontours; k++) {
        const lam_contour *c = &L->contours[k];
        lam_vblock_contour(&p->vb, L->uv + 2 * c->first, c->n, c->kind == LAM_SOLID, c->depth);
    }
    const lam_layer *marks[2] = { li->support, li->overhang };
    for (int m = 0; m < 2; m++)
        for (size_t k = 0; marks[m] && k < marks[m]->ncontours; k++) {
            const lam_contour *c = &marks[m]->contours[k];
            lam_vblock_mark(&p->vb, m ? LAM_VBLOCK_OVERHANG : LAM_VBLOCK_SUPPORT, marks[m]->uv + 2 * c->first, c->n,
                            c->kind == LAM_SOLID, c->depth);
        }
    return p->json.layer(p->json.ctx, li);
}

static int p_vector(void *ctx, const lam_vec *v)
{
    page *p = ctx;
    lam_vblock_vector(&p->vb, v);
    return p->json.vector(p->json.ctx, v);
}

static int p_path(void *ctx, const lam_contour_info *c, size_t order)
{
    page *p = ctx;
    return p->json.path ? p->json.path(p->json.ctx, c, order) : LAM_OK;
}

static int p_layer_end(void *ctx, const lam_layer_info *li, const lam_vec_stats *st)
{
    page *p = ctx;
    int rc = p->json.layer_end(p->json.ctx, li, st);
    if (rc) return rc;
    lam_buf_clear(&p->bytes);
    lam_buf_clear(&p->text);
    if (lam_vblock_finish(&p->vb, &p->bytes) || lam_buf_base64(&p->text, p->bytes.data, p->bytes.len))
        return lam_error_nomem(p->err, "writing the viewer");
    p->layer++;
    lam_writer_printf(p->w, "<script type=\"application/octet-stream\" id=\"lamina-layer-%zu\">", p->layer);
    lam_writer_write(p->w, p->text.data, p->text.len);
    lam_writer_printf(p->w, "</script><script>lamina.arrived(%zu)</script>\n", p->layer);
    return lam_writer_error(p->w, p->err);
}

static int p_end(void *ctx)
{
    page *p = ctx;
    int rc = p->json.end(p->json.ctx);
    char *json = NULL;
    size_t len = 0;
    lam_writer *m = p->meta;
    p->meta = NULL;
    if (!rc) rc = lam_writer_take(m, &json, &len, p->err);
    else lam_writer_abort(m);
    if (rc) return rc;
    text(p, "<script type=\"application/json\" id=\"lamina-run\">");
    lam_writer_write(p->w, json, len);
    text(p, "</script>\n<script>lamina.loaded()</script>");
    free(json);
    part(p, LAM_VIEWER_DATA, NULL);
    return lam_writer_error(p->w, p->err);
}

static void p_destroy(void *ctx)
{
    page *p = ctx;
    if (p->json.destroy) p->json.destroy(p->json.ctx);
    lam_writer_abort(p->meta);
    lam_vblock_free(&p->vb);
    lam_buf_free(&p->bytes);
    lam_buf_free(&p->text);
    free(p);
}

int lam_html_consumer(lam_writer *w, lam_vec_consumer *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    page *p = calloc(1, sizeof *p);
    if (!p) return lam_error_nomem(err, "making the viewer");
    p->w = w;
    p->err = err;
    static const lam_json_opts summary = { .vectors = LAM_JSON_VECTORS_SUMMARY, .no_contours = 1 };
    int rc = lam_writer_memory(&p->meta, err);
    if (!rc) rc = lam_json_consumer_opts(NULL, p->meta, &summary, &p->json, err);
    if (rc) {
        lam_writer_abort(p->meta);
        free(p);
        return rc;
    }
    *out = (lam_vec_consumer){ .ctx = p, .begin = p_begin, .layer = p_layer, .vector = p_vector, .path = p_path,
                               .layer_end = p_layer_end, .end = p_end, .destroy = p_destroy };
    return LAM_OK;
}
