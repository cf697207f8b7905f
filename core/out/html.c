#include "html.h"

#include <stdlib.h>
#include <string.h>

#include "viewer_html.h"

/* The page around the JSON: a consumer that writes what comes before the
 * data when the job begins, and one that writes the rest when it ends,
 * with the JSON consumer between them in the run's vector stream. */
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

int lam_html_page(lam_writer *w, lam_vec_consumer *head, lam_vec_consumer *tail, lam_error *err)
{
    page *p = malloc(sizeof *p);
    if (!p) return lam_error_nomem(err, "making the viewer");
    p->w = w;
    p->err = err;
    *head = (lam_vec_consumer){ .ctx = p, .begin = page_head, .destroy = free };
    *tail = (lam_vec_consumer){ .ctx = p, .end = page_tail };
    return LAM_OK;
}
