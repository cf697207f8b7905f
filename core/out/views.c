/* The run's views on one vector stream; see views.h. */
#include "views.h"

#include "html.h"
#include "json_sink.h"
#include "vstream.h"

int lam_views_sink(const lam_views *v, lam_sink *out, lam_error *err)
{
    lam_vec_consumer c[4];
    size_t n = 0;
    int rc = LAM_OK;
    if (v->html && !(rc = lam_html_consumer(v->html, &c[n], err))) n++;
    if (!rc && v->json && !(rc = lam_json_consumer_opts(v->json, NULL, v->json_opts, &c[n], err))) n++;
    if (!rc && v->svg && !(rc = lam_svg_consumer(v->svg, v->frame, v->frame_machine, &c[n], err))) n++;
    if (!rc && v->data) lam_plan_data_consumer(v->data, err, &c[n++]);
    if (rc) {
        for (size_t k = 0; k < n; k++)
            if (c[k].destroy) c[k].destroy(c[k].ctx);
        return rc;
    }
    return lam_vstream_sink(c, n, out, err);
}
