/* lamina's version, in one place for the executable, the Lua module and
 * the plugin host. */
#ifndef LAM_VERSION_H
#define LAM_VERSION_H

#define LAMINA_VERSION "0.1.0"

#endif
