#include "html.h"

#include <stdlib.h>
#include <string.h>

#include "json_sink.h"
#include "tee.h"
#include "viewer_html.h"

/* The page around the JSON: a sink that writes what comes before the data
 * when the job begins, and one that writes the rest when it ends, with the
 * JSON sink between them in a tee. */
typedef struct page {
    lam_writer *w;
    lam_error *err;
} page;

static const char *mark(void)
{
    return strstr(lam_viewer_html, LAM_VIEWER_MARK);
}

static int page_head(void *ctx, const lam_job_info *job)
{
    (void)job;
    page *p = ctx;
    lam_writer_write(p->w, lam_viewer_html, (size_t)(mark() - lam_viewer_html));
    return lam_writer_error(p->w, p->err);
}

static int page_tail(void *ctx)
{
    page *p = ctx;
    const char *rest = mark() + strlen(LAM_VIEWER_MARK);
    lam_writer_write(p->w, rest, lam_viewer_html_len - (size_t)(rest - lam_viewer_html));
    return lam_writer_error(p->w, p->err);
}

int lam_html_sink(lam_writer *w, lam_sink *out, lam_error *err)
{
    memset(out, 0, sizeof *out);
    page *p = malloc(sizeof *p);
    if (!p) return lam_error_nomem(err, "making the viewer");
    p->w = w;
    p->err = err;
    lam_sink parts[3] = { { .ctx = p, .begin = page_head, .destroy = free }, { 0 }, { .ctx = p, .end = page_tail } };
    int rc = lam_json_sink(w, LAM_JSON_SCRIPT, &parts[1], err);
    if (!rc && (rc = lam_tee_sink(parts, 3, out, err))) parts[1].destroy(parts[1].ctx);
    if (rc) free(p);
    return rc;
}
