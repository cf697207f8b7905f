/* The sink that writes a plan through a dialect's templates, and the
 * layer text worker threads format with it. See dialect.h; the template
 * language itself is dialect_template.c. */
#include "dialect.h"

#include <stdlib.h>
#include <string.h>

/* ---- the sink ----------------------------------------------------------- */

typedef struct dsink {
    const lam_dialect *d;
    lam_writer *w;
    lam_error *err;
    lam_job_info job;
    char *name, *process, *units, *label;   /* copies of the job's strings */
    char **labels;                  /* copies of the job's labels (one: label) */
    size_t nlabels;
    double pos[3];                  /* the stage position as the machine knows it */
    size_t blocks;                  /* contour blocks written */
    size_t layer_index, in_layer;   /* contours seen in the current layer */
    lam_tbuf b;
    /* a worker's layer text (d_fork, the sink's fork member): w is NULL, the strings are
     * the main sink's, and the layer's first separator is noted */
    int worker, borrowed, complete, has_sep;
    size_t sep_at, sep_len, layer_blocks;
} dsink;

/* Commands collect in s->b and go to the writer at the end of a layer once
 * they pass this size (one writer call per line was a fifth of the run
 * time): the same places whether the text was formatted here or by worker
 * threads, so a write error (a full disk, --max-output) stops the run at
 * the same layer for every -j. A layer whose text passes FLUSH_BIG is
 * written as it goes, to bound memory (layers that big are planned on one
 * thread: LAM_THREAD_LAYER_MAX). */
#define FLUSH_AT 65536
#define FLUSH_BIG (16u << 20)

static int flush(dsink *s)
{
    if (s->b.len == 0) return LAM_OK;
    int rc = lam_writer_write(s->w, s->b.s, s->b.len);
    s->b.len = 0;
    return rc ? lam_writer_error(s->w, s->err) : LAM_OK;
}

static int emit(dsink *s, lam_cmd c, const lam_tvals *v, double rel[3], int has_rel[3])
{
    const lam_template *t = &s->d->cmd[c];
    if (!t->present) return LAM_OK;
    lam_template_render(t, v, &s->b, rel, has_rel);
    lam_tbuf_put(&s->b, "\n", 1);
    if (s->b.oom) return lam_error_set(s->err, LAM_ENOMEM, NULL, 0, 0, "out of memory writing the %s command",
                                       lam_cmd_name(c));
    return s->w && s->b.len >= FLUSH_BIG ? flush(s) : LAM_OK;
}

static void job_vals(const dsink *s, lam_tvals *v)
{
    memset(v, 0, sizeof *v);
    v->text[LAM_TF_NAME] = s->name;
    v->text[LAM_TF_PROCESS] = s->process;
    v->text[LAM_TF_UNITS] = s->units;
    v->text[LAM_TF_LABEL] = s->label;
    v->labels = (const char *const *)s->labels;
    v->nlabels = s->nlabels;
    v->num[LAM_TF_LAYERS] = (double)s->job.layers;
    v->num[LAM_TF_DIMENSION] = 3;
    v->num[LAM_TF_BEAD] = s->job.bead;
    v->num[LAM_TF_RATE] = s->job.rate;
    v->num[LAM_TF_TRAVEL_RATE] = s->job.travel_rate;
    for (int j = 0; j < 6; j++) v->num[LAM_TF_XMIN + j] = s->job.bbox[j];
}

static char *dup_or_empty(const char *s)
{
    return strdup(s ? s : "");
}

static void free_labels(dsink *s)
{
    for (size_t k = 0; k < s->nlabels; k++) free(s->labels[k]);
    free(s->labels);
    s->labels = NULL;
    s->nlabels = 0;
}

/* Copy the job's label table (a label NULL: "part"), or make the one
 * label `label` (id 1) of a job without one. 0 when out of memory. */
static int copy_labels(dsink *s, const lam_job_info *job)
{
    free_labels(s);
    int table = job->labels && job->nlabels;
    size_t n = table ? job->nlabels : 1;
    if (!(s->labels = calloc(n, sizeof *s->labels))) return 0;
    for (size_t k = 0; k < n; k++) {
        const char *text = !table ? s->label : job->labels[k] ? job->labels[k] : "part";
        if (!(s->labels[k] = strdup(text))) return 0;
        s->nlabels = k + 1;
    }
    return 1;
}

static int d_begin(void *ctx, const lam_job_info *job)
{
    dsink *s = ctx;
    s->job = *job;
    free(s->name);
    free(s->process);
    free(s->units);
    free(s->label);
    s->name = dup_or_empty(job->name);
    s->process = dup_or_empty(job->process);
    s->units = dup_or_empty(job->units);
    s->label = dup_or_empty(job->label ? job->label : "part");
    if (!s->name || !s->process || !s->units || !s->label || !copy_labels(s, job))
        return lam_error_set(s->err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    memcpy(s->pos, job->origin, sizeof s->pos);
    s->blocks = 0;
    lam_tvals v;
    job_vals(s, &v);
    return emit(s, LAM_CMD_PREAMBLE, &v, NULL, NULL);
}

static int layer_cmd(dsink *s, lam_cmd c, const lam_layer_info *L)
{
    lam_tvals v;
    memset(&v, 0, sizeof v);
    v.num[LAM_TF_INDEX] = (double)L->index;
    v.num[LAM_TF_NUMBER] = (double)L->index + 1;
    v.num[LAM_TF_Z] = L->z;
    v.num[LAM_TF_WIDTH] = L->width;
    v.num[LAM_TF_FLOOR] = L->floor;
    v.num[LAM_TF_CEILING] = L->ceiling;
    return emit(s, c, &v, NULL, NULL);
}

static int d_layer(void *ctx, const lam_layer_info *L)
{
    dsink *s = ctx;
    s->layer_index = L->index;
    s->in_layer = 0;
    return layer_cmd(s, LAM_CMD_LAYER, L);
}

static int d_layer_end(void *ctx, const lam_layer_info *L)
{
    dsink *s = ctx;
    int rc = layer_cmd(s, LAM_CMD_LAYER_END, L);
    if (rc) return rc;
    s->complete = 1;
    return s->w && s->b.len >= FLUSH_AT ? flush(s) : LAM_OK;
}

static int d_feed(void *ctx, double rate)
{
    lam_tvals v;
    memset(&v, 0, sizeof v);
    v.num[LAM_TF_RATE] = rate;
    return emit(ctx, LAM_CMD_FEED, &v, NULL, NULL);
}

static int d_laser(void *ctx, int on)
{
    dsink *s = ctx;
    lam_tvals v;
    memset(&v, 0, sizeof v);
    v.num[LAM_TF_RATE] = s->job.rate;
    return emit(s, on ? LAM_CMD_LASER_ON : LAM_CMD_LASER_OFF, &v, NULL, NULL);
}

static int d_move(void *ctx, const lam_move_info *m)
{
    dsink *s = ctx;
    int deposit = m->deposit;
    const double *xyz = m->xyz;
    lam_cmd c = deposit ? LAM_CMD_DEPOSIT : LAM_CMD_TRAVEL;
    if (!s->d->cmd[c].present) return LAM_OK; /* the machine was not told to move */
    lam_tvals v;
    memset(&v, 0, sizeof v);
    v.num[LAM_TF_DX] = xyz[0] - s->pos[0];
    v.num[LAM_TF_DY] = xyz[1] - s->pos[1];
    v.num[LAM_TF_DZ] = xyz[2] - s->pos[2];
    v.num[LAM_TF_X] = xyz[0];
    v.num[LAM_TF_Y] = xyz[1];
    v.num[LAM_TF_Z] = xyz[2];
    v.num[LAM_TF_RATE] = deposit ? s->job.rate : s->job.travel_rate;
    double rel[3];
    int has_rel[3] = { 0, 0, 0 };
    int rc = emit(s, c, &v, rel, has_rel);
    /* The stage now is where the written command takes it: relative moves
     * are accumulated as the machine reads them (the rounded numbers), so
     * rounding never drifts; an axis without a relative field is absolute. */
    for (int j = 0; j < 3; j++) s->pos[j] = has_rel[j] ? s->pos[j] + rel[j] : xyz[j];
    return rc;
}

/* A contour or hatch block starts: the separator between blocks, and the
 * fields every block has (its index in the layer, its part id, its
 * exposure). Fills v. */
static int block_start(dsink *s, lam_tvals *v, double id, double power, double speed, double point_distance,
                       double exposure_time)
{
    size_t index = s->in_layer++;
    memset(v, 0, sizeof *v);
    size_t at = s->b.len;
    int rc = s->blocks++ > 0 ? emit(s, LAM_CMD_SEPARATOR, v, NULL, NULL) : LAM_OK;
    if (s->worker && !s->layer_blocks++) {
        /* a worker takes it that blocks came before; the writer drops this
         * separator if none did */
        s->has_sep = 1;
        s->sep_at = at;
        s->sep_len = s->b.len - at;
    }
    v->num[LAM_TF_INDEX] = (double)index;
    v->num[LAM_TF_ID] = id;
    v->num[LAM_TF_POWER] = power;
    v->num[LAM_TF_SPEED] = speed;
    v->num[LAM_TF_POINT_DISTANCE] = point_distance;
    v->num[LAM_TF_EXPOSURE_TIME] = exposure_time;
    return rc;
}

static int d_contour(void *ctx, const lam_contour_info *ci)
{
    dsink *s = ctx;
    const lam_dialect *d = s->d;
    lam_tvals v;
    int rc = block_start(s, &v, (double)lam_attrs_id(&ci->attrs), ci->power, ci->speed, ci->point_distance, ci->exposure_time);
    if (rc) return rc;
    int close = d->close_polylines && ci->n > 0;
    size_t written = ci->n + (close ? 1 : 0);
    v.num[LAM_TF_DIR] = ci->solid ? 1 : 0;
    v.text[LAM_TF_KIND] = ci->solid ? "solid" : "hole";
    v.num[LAM_TF_DEPTH] = ci->depth;
    v.num[LAM_TF_N] = (double)written;
    v.num[LAM_TF_Z] = ci->z;
    if (ci->uv) {
        v.uv = ci->uv;
        v.uv_stride = 2;
    } else {
        v.uv = ci->xyz;
        v.uv_stride = 3;
    }
    v.npts = ci->n;
    v.close = close;
    if ((rc = emit(s, LAM_CMD_CONTOUR_BEGIN, &v, NULL, NULL))) return rc;
    if ((rc = emit(s, LAM_CMD_LOOP_BEGIN, &v, NULL, NULL))) return rc;
    if (d->cmd[LAM_CMD_VERTEX].present) {
        lam_tvals pv;
        memset(&pv, 0, sizeof pv);
        for (size_t k = 0; k < written && !rc; k++) {
            const double *p = ci->xyz + 3 * (k % ci->n);
            pv.num[LAM_TF_X] = p[0];
            pv.num[LAM_TF_Y] = p[1];
            pv.num[LAM_TF_Z] = p[2];
            pv.num[LAM_TF_I] = (double)k;
            rc = emit(s, LAM_CMD_VERTEX, &pv, NULL, NULL);
        }
        if (rc) return rc;
    }
    if ((rc = emit(s, LAM_CMD_LOOP_END, &v, NULL, NULL))) return rc;
    if ((rc = emit(s, LAM_CMD_CONTOUR_END, &v, NULL, NULL))) return rc;
    return emit(s, LAM_CMD_POLYLINE, &v, NULL, NULL);
}

static int d_hatches(void *ctx, const lam_hatch_info *h)
{
    dsink *s = ctx;
    const lam_dialect *d = s->d;
    lam_tvals v;
    int rc = block_start(s, &v, (double)lam_attrs_id(&h->attrs), h->power, h->speed, h->point_distance, h->exposure_time);
    if (rc) return rc;
    v.text[LAM_TF_KIND] = lam_kind_name(h->kind);
    v.num[LAM_TF_N] = (double)h->n;
    v.num[LAM_TF_Z] = h->z;
    v.num[LAM_TF_ANGLE] = h->angle;
    if (h->uv) {
        v.uv = h->uv;
        v.uv_stride = 2;
    } else {
        v.uv = h->xyz;
        v.uv_stride = 3;
    }
    v.npts = 2 * h->n;
    if ((rc = emit(s, LAM_CMD_HATCHES_BEGIN, &v, NULL, NULL))) return rc;
    if (d->cmd[LAM_CMD_HATCH].present) {
        lam_tvals pv;
        memset(&pv, 0, sizeof pv);
        pv.num[LAM_TF_POWER] = h->power;
        pv.num[LAM_TF_SPEED] = h->speed;
        for (size_t k = 0; k < h->n && !rc; k++) {
            const double *p = h->xyz + 6 * k;
            for (int j = 0; j < 3; j++) pv.num[LAM_TF_X0 + j] = p[j], pv.num[LAM_TF_X1 + j] = p[3 + j];
            pv.num[LAM_TF_I] = (double)k;
            rc = emit(s, LAM_CMD_HATCH, &pv, NULL, NULL);
        }
        if (rc) return rc;
    }
    if ((rc = emit(s, LAM_CMD_HATCHES_END, &v, NULL, NULL))) return rc;
    return emit(s, LAM_CMD_HATCHES, &v, NULL, NULL);
}

static int d_end(void *ctx)
{
    dsink *s = ctx;
    lam_tvals v;
    job_vals(s, &v);
    int rc = emit(s, LAM_CMD_POSTAMBLE, &v, NULL, NULL);
    return rc ? rc : flush(s);
}

static void d_destroy(void *ctx)
{
    dsink *s = ctx;
    if (!s) return;
    if (!s->borrowed) {
        free(s->name);
        free(s->process);
        free(s->units);
        free(s->label);
        free_labels(s);
    }
    free(s->b.s);
    free(s);
}

static int d_fork(void *ctx, int moves, lam_sink_fork *out, lam_error *err);

/* The callbacks a dialect's sink and its workers' share: the layers and
 * their operations. */
static void d_ops(dsink *s, lam_sink *out)
{
    *out = (lam_sink){ .ctx = s, .layer = d_layer, .layer_end = d_layer_end, .feed = d_feed, .laser = d_laser,
                       .move = d_move, .contour = d_contour, .hatches = d_hatches, .destroy = d_destroy };
}

int lam_dialect_sink(const lam_dialect *d, lam_writer *w, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    dsink *s = calloc(1, sizeof *s);
    if (!s) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    s->d = d;
    s->w = w;
    s->err = err;
    d_ops(s, out);
    out->begin = d_begin;
    out->end = d_end;
    out->fork = d_fork;
    return LAM_OK;
}

/* ---- layer text formatted by worker threads (issue 15) ------------------ */

/* Whether the dialect's text for a layer depends on the layers before it
 * beyond what the fork's put makes right: relative moves (dx dy dz) are
 * measured from where the text before left the stage, rounding included. */
static int relative_moves(const lam_dialect *d)
{
    const lam_cmd moves[2] = { LAM_CMD_TRAVEL, LAM_CMD_DEPOSIT };
    for (int m = 0; m < 2; m++) {
        const lam_template *t = &d->cmd[moves[m]];
        for (size_t i = 0; t->present && i < t->nsegs; i++) {
            int f = t->segs[i].field;
            if (f == LAM_TF_DX || f == LAM_TF_DY || f == LAM_TF_DZ) return 1;
        }
    }
    return 0;
}

/* A worker's sink formatting layers like m's (d_fork, the sink's fork member). */
static int fork_of(const dsink *m, int moves, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    if (moves && relative_moves(m->d)) return LAM_EUSAGE;
    dsink *s = calloc(1, sizeof *s);
    if (!s) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
    s->d = m->d;
    s->err = err;
    s->job = m->job;
    s->name = m->name;
    s->process = m->process;
    s->units = m->units;
    s->label = m->label;
    s->labels = m->labels;
    s->nlabels = m->nlabels;
    s->borrowed = 1;
    s->worker = 1;
    memcpy(s->pos, m->job.origin, sizeof s->pos);
    d_ops(s, out);
    return LAM_OK;
}

static void fork_start(void *ctx, lam_error *err)
{
    dsink *s = ctx;
    s->err = err;
    s->b.len = 0;
    s->b.oom = 0;
    s->blocks = 1;
    s->complete = s->has_sep = 0;
    s->sep_at = s->sep_len = s->layer_blocks = 0;
}

static void fork_take(void *ctx, lam_layer_text *t)
{
    dsink *s = ctx;
    char *keep = t->s;
    size_t keep_cap = t->cap;
    t->s = s->b.s;
    t->len = s->b.len;
    t->cap = s->b.cap;
    t->complete = s->complete;
    t->has_sep = s->has_sep;
    t->sep_at = s->sep_at;
    t->sep_len = s->sep_len;
    t->blocks = s->layer_blocks;
    s->b.s = keep; /* the buffer the writer is done with, for the next layer */
    s->b.cap = keep_cap;
    s->b.len = 0;
}

static int fork_put(void *ctx, const lam_layer_text *t)
{
    dsink *s = ctx;
    if (t->has_sep && s->blocks == 0) {
        /* the first block of the program: no separator before it */
        lam_tbuf_put(&s->b, t->s, t->sep_at);
        lam_tbuf_put(&s->b, t->s + t->sep_at + t->sep_len, t->len - t->sep_at - t->sep_len);
    } else {
        lam_tbuf_put(&s->b, t->s, t->len);
    }
    s->blocks += t->blocks;
    if (s->b.oom) return lam_error_set(s->err, LAM_ENOMEM, NULL, 0, 0, "out of memory writing a layer");
    return t->complete && s->b.len >= FLUSH_AT ? flush(s) : LAM_OK;
}

/* The sink's fork member (plan.h). */
static int d_fork(void *ctx, int moves, lam_sink_fork *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    int rc = fork_of(ctx, moves, &out->sink, err);
    if (rc) return rc;
    out->start = fork_start;
    out->take = fork_take;
    out->put = fork_put;
    out->main = ctx;
    return LAM_OK;
}

void lam_dialect_text_free(lam_dialect_text *t)
{
    free(t->s);
    memset(t, 0, sizeof *t);
}
