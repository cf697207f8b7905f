/* lam_plan_layers: the planning driver (plan_drive.h) over a list of
 * layers made already; they outlive the run, so workers borrow them. */
#include "plan_layers.h"

#include <string.h>

#include "plan_drive.h"

static int list_get(void *ctx, unsigned worker, size_t j, size_t keep, const lam_layer **out, lam_error *err)
{
    (void)worker, (void)keep, (void)err;
    *out = ((const lam_plan_layers_job *)ctx)->layers[j];
    return LAM_OK;
}

int lam_plan_layers(const lam_plan_layers_job *j, const lam_sink *sink, lam_error *err)
{
    lam_plan_source src;
    memset(&src, 0, sizeof src);
    src.n = src.end = j->n;
    src.f = j->frame;
    src.o = j->o;
    memcpy(src.origin, j->origin, sizeof src.origin);
    src.get = list_get;
    src.stable = 1;
    src.ctx = (void *)j;
    src.layer_opts = j->layer_opts;
    src.given = j->given;
    src.stop = j->stop;
    src.planned = j->planned;
    src.user = j->ctx;
    return lam_plan_drive(&src, sink, err);
}
