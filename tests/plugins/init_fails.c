/* Test plugin: registers a writer, then refuses to load with a message; the
 * host must report the message and drop the writer. */
#include <stddef.h>

#include "lamina_plugin.h"

LAMINA_PLUGIN_DECLARE;

static void *begin(struct lamina_out *out, const struct lamina_job *job)
{
    (void)out;
    (void)job;
    return NULL;
}
static int layer(void *state, size_t index, double z)
{
    (void)state, (void)index, (void)z;
    return 1;
}
static int polyline(void *state, size_t id, int solid, const double *xy, size_t n)
{
    (void)state, (void)id, (void)solid, (void)xy, (void)n;
    return 1;
}
static int end(void *state)
{
    (void)state;
    return 1;
}

static const struct lamina_writer w = {
    .size = sizeof w, .name = "init-fails", .begin = begin, .layer = layer, .polyline = polyline, .end = end,
};

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    if (host->register_writer(host, &w) != 0) return 1;
    host->set_error(host, "the frobnicator is not calibrated (code %d)", 42);
    return 1;
}
