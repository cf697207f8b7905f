/* Test plugin: registers "dup-ok", then "cli-binary" again (taken when the
 * cli plugin is loaded). It ignores register_writer's result and returns 0:
 * the host must still refuse the load and drop "dup-ok". */
#include "noop_writer.h"

LAMINA_PLUGIN_DECLARE;

NOOP_WRITER(ok_w, "dup-ok");
NOOP_WRITER(dup_w, "cli-binary");

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    host->register_writer(host, &ok_w);
    host->register_writer(host, &dup_w);
    return 0;
}
