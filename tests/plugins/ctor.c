/* Test plugin: a library constructor that leaves a mark (LAMINA_CTOR_RAN in
 * the environment) when the file is opened at all, to show the host opens
 * no plugin file but the one a profile names. */
#include <stdlib.h>

#include "lamina_plugin.h"

LAMINA_PLUGIN_DECLARE;

__attribute__((constructor)) static void mark(void)
{
    setenv("LAMINA_CTOR_RAN", "1", 1);
}

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    (void)host;
    return 0;
}
