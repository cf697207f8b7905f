/* Test plugin: built for an ABI lamina does not speak. Its init must never
 * run (it would register "bad-abi"). */
#include "lamina_plugin.h"

const uint32_t lamina_plugin_abi = 999;

static const struct lamina_writer w = {
    .size = sizeof w, .name = "bad-abi",
};

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    return host->register_writer(host, &w);
}
