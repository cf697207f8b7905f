/* Test plugin: declares the ABI but exports no lamina_plugin_init. */
#include "lamina_plugin.h"

LAMINA_PLUGIN_DECLARE;

int lamina_plugin_nit(void);

int lamina_plugin_nit(void) { return 0; }
