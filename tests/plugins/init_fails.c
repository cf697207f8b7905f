/* Test plugin: registers a writer, then refuses to load with a message; the
 * host must report the message and drop the writer. */
#include "noop_writer.h"

LAMINA_PLUGIN_DECLARE;

NOOP_WRITER(w, "init-fails");

int lamina_plugin_init(const struct lamina_host *host);

int lamina_plugin_init(const struct lamina_host *host)
{
    if (host->register_writer(host, &w) != 0) return 1;
    host->set_error(host, "the frobnicator is not calibrated (code %d)", 42);
    return 1;
}
