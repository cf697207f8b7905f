/* Writer callbacks that do nothing and succeed, for the test plugins that
 * are about loading and registration rather than output. */
#ifndef NOOP_WRITER_H
#define NOOP_WRITER_H

#include <stddef.h>

#include "lamina_plugin.h"

static void *noop_begin(struct lamina_out *out, const struct lamina_job *job)
{
    (void)out;
    (void)job;
    return NULL;
}
static int noop_layer(void *state, size_t index, double z)
{
    (void)state, (void)index, (void)z;
    return 1;
}
static int noop_polyline(void *state, size_t id, int solid, const double *xy, size_t n)
{
    (void)state, (void)id, (void)solid, (void)xy, (void)n;
    return 1;
}
static int noop_end(void *state)
{
    (void)state;
    return 1;
}

#define NOOP_WRITER(var, wname)                                                                              \
    static const struct lamina_writer var = {                                                                \
        .size = sizeof var, .name = wname, .begin = noop_begin, .layer = noop_layer,                         \
        .polyline = noop_polyline, .end = noop_end,                                                          \
    }

#endif
