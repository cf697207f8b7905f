/* Test plugin: registers "dup-ok", then "cli-binary" again (taken when the
 * cli plugin is loaded). It ignores register_writer's result and returns 0:
 * the host must still refuse the load and drop "dup-ok". */
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

static const struct lamina_writer ok_w = {
    .size = sizeof ok_w, .name = "dup-ok", .begin = begin, .layer = layer, .polyline = polyline, .end = end,
};
static const struct lamina_writer dup_w = {
    .size = sizeof dup_w, .name = "cli-binary", .begin = begin, .layer = layer, .polyline = polyline, .end = end,
};

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    host->register_writer(host, &ok_w);
    host->register_writer(host, &dup_w);
    return 0;
}
