/* The build in the run's JSON (docs/json.md): the job object's "build"
 * member, made once when the plate is set up and written by the JSON sink
 * (lam_job_info.json_extra). */
#include "build_run.h"

#include <stdio.h>
#include <string.h>

#include "buf.h"
#include "escape.h"
#include "fmt.h"

static void str(lam_buf *b, const char *s)
{
    lam_buf_append(b, "\"", 1);
    size_t n = strlen(s);
    while (n) {
        size_t k = lam_esc_plain(s, n, LAM_ESC_JSON);
        lam_buf_append(b, s, k);
        s += k, n -= k;
        if (!n) break;
        char out[LAM_ESC_MAX];
        size_t used = lam_esc_one(s, n, LAM_ESC_JSON, out);
        lam_buf_append(b, out, strlen(out));
        s += used, n -= used;
    }
    lam_buf_append(b, "\"", 1);
}

static void nums(lam_buf *b, const double *x, size_t n)
{
    char t[LAM_FMT_NUM];
    lam_buf_append(b, "[", 1);
    for (size_t i = 0; i < n; i++) lam_buf_printf(b, "%s%s", i ? ", " : "", lam_fmt_num(t, x[i], 17));
    lam_buf_append(b, "]", 1);
}

static void plate(lam_buf *b, const lam_build_run *r)
{
    char t[LAM_FMT_NUM];
    const lam_plate *p = &r->plate;
    lam_buf_printf(b, "\"plate\": {");
    if (p->round) lam_buf_printf(b, "\"diameter\": %s", lam_fmt_num(t, p->diameter, 17));
    else lam_buf_printf(b, "\"width\": %s, ", lam_fmt_num(t, p->width, 17)), lam_buf_printf(b, "\"depth\": %s", lam_fmt_num(t, p->depth, 17));
    lam_buf_printf(b, ", \"margin\": %s}, ", lam_fmt_num(t, p->margin, 17));
    lam_buf_printf(b, "\"spacing\": %s, \"gas_flow\": ", lam_fmt_num(t, r->spacing, 17));
    nums(b, r->lasers.gas_flow, 2);
    lam_buf_printf(b, ",\n   \"lasers\": [");
    for (size_t l = 0; l < r->lasers.n; l++) {
        lam_buf_printf(b, "%s{\"laser\": %zu, \"field\": ", l ? ", " : "", l + 1);
        nums(b, r->lasers.field[l], 4);
        lam_buf_append(b, "}", 1);
    }
    lam_buf_printf(b, "],\n   \"styles\": [");
    for (size_t s = 0; s < r->nstyles; s++) {
        lam_buf_printf(b, "%s{\"style\": %zu, \"name\": ", s ? ", " : "", s + 1);
        str(b, r->styles[s]);
        lam_buf_append(b, "}", 1);
    }
    lam_buf_printf(b, "],\n   \"labels\": [");
    for (size_t l = 0; l < r->nlabels; l++) {
        lam_buf_printf(b, "%s{\"label\": %zu, \"name\": ", l ? ", " : "", l + 1);
        str(b, r->labels[l]);
        lam_buf_append(b, "}", 1);
    }
    lam_buf_append(b, "]", 1);
}

static void part(lam_buf *b, const lam_build_run *r, size_t i)
{
    const lam_run_part *p = &r->parts[i];
    lam_buf_printf(b, "%s\n    {\"part\": %zu, \"name\": ", i ? "," : "", i + 1);
    str(b, p->name);
    lam_buf_printf(b, ", \"model\": ");
    str(b, r->b->parts[p->spec].model);
    lam_buf_printf(b, ", \"at\": ");
    nums(b, p->at, 2);
    lam_buf_printf(b, ", \"box\": ");
    nums(b, p->box, 4);
    lam_buf_printf(b, ", \"layers\": [%zu, %zu], \"styles\": {", p->first + 1, p->first + p->count);
    for (int k = 0; k < LAM_REGIONS; k++) /* a region without a style (support, none made): left out */
        if (p->style_id[k]) lam_buf_printf(b, "%s\"%s\": %d", k ? ", " : "", lam_kind_name(k), p->style_id[k]);
    lam_buf_printf(b, "}}");
}

int lam_build_run_json(lam_build_run *r, lam_error *err)
{
    lam_buf b;
    lam_buf_init(&b);
    lam_buf_printf(&b, "\"build\": {");
    plate(&b, r);
    lam_buf_printf(&b, ",\n   \"parts\": [");
    for (size_t i = 0; i < r->nparts; i++) part(&b, r, i);
    lam_buf_printf(&b, "]}");
    if (lam_buf_append(&b, "", 1)) {
        lam_buf_free(&b);
        return lam_error_nomem(err, "describing the build");
    }
    r->json = lam_buf_take(&b, NULL);
    r->job.json_extra = r->json;
    return LAM_OK;
}
