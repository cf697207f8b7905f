/* Test plugin: exports lamina_plugin_init but not lamina_plugin_abi (no
 * LAMINA_PLUGIN_DECLARE): not a lamina plugin as far as the host knows. */
#include "lamina_plugin.h"

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    host->set_error(host, "no_abi: init must not run");
    return 1;
}
