/* Plugins, host side: load shared objects that speak the lamina plugin ABI
 * (lamina_plugin.h), keep a registry of what they provide, and adapt a
 * plugin writer to the lam_sink interface planners emit to.
 *
 * The registry is process-wide and thread-safe (one lock): any thread may
 * load plugins, list writers and create sinks; a sink itself is used by one
 * thread at a time (the sinks of its fork member run on worker threads).
 * Everything a plugin registered (writer names, the sinks built on them)
 * stays valid until lam_plugins_unload. */
#ifndef LAM_PLUGIN_HOST_H
#define LAM_PLUGIN_HOST_H

#include <stddef.h>

#include "error.h"
#include "plan.h"
#include "writer.h"

/* Load the plugin at `path` (dlopen RTLD_NOW | RTLD_LOCAL; a path without
 * '/' is taken relative to the working directory, never looked up in the
 * library path), check its ABI and run its lamina_plugin_init, which
 * registers its writers. Loading a file that is already loaded (the same
 * file, by device and inode, under any path) does nothing and succeeds.
 * The file is opened first and what was opened is checked, before any of
 * its code runs: a regular file owned by root or the user and not writable
 * by group or others, and so is every directory from where it really is
 * (realpath) and from the directory it was named in, up to / (OpenSSH's
 * StrictModes; except that a sticky directory owned by root or the user
 * passes: in it only an entry's owner may replace the entry). Then that
 * descriptor is loaded (dlopen of /proc/self/fd/N: Linux, /proc mounted),
 * so no other file can be put in its place between the check and the load;
 * it stays open while the plugin is loaded. A file read this way counts as
 * read for the outputs' check (file.h, writer.h).
 * A plugin that fails is unloaded again and leaves nothing registered.
 * Errors: LAM_EIO (no such file / unreadable, or refused by the rule above,
 * naming the file, or directory, and why),
 * LAM_EFORMAT (not a loadable shared object, no lamina_plugin_abi or
 * lamina_plugin_init symbol, built for another ABI: refused before init
 * runs), LAM_EINVAL (init failed, with the plugin's set_error message, or
 * it registered a malformed writer or one whose name is already taken),
 * LAM_ENOMEM. */
int lam_plugin_load(const char *path, lam_error *err);

/* A sink (plan.h) that writes through the plugin writer called `name`
 * (a profile's `writer:`) into w. If no writer of that name is registered,
 * the file NAME.so is loaded from the first plugin directory that has one
 * (so a sanitizer build's <exe dir>/plugins wins over an installed copy),
 * and no other file: a plugin's code runs only when a profile names it.
 * That file must provide the writer NAME. Plugin directories, in order:
 * $LAMINA_PLUGINS (colon-separated), then <exe dir>/plugins,
 * <exe dir>/../plugins, <exe dir>/../lib/lamina/plugins; from the C module
 * lamina.so (paths.h): <dir>/plugins, <dir>/../plugins, <dir>/../../lamina/plugins
 * (lib/lua/5.4/lamina.so installed), <dir>/lamina/plugins (a LuaRocks tree). A name that is not
 * a file name (letters, digits, '-', '_', '.'; not starting with '.') is
 * refused.
 *
 * The sink does not own w (the caller commits or aborts it afterwards) and
 * keeps `err` to report errors of later sink calls, so both must outlive the
 * sink; the caller calls out->destroy exactly once. The writer handles
 * contour programs only: begin, layer, contour, end; layer_end is a no-op;
 * feed, laser and move fail with LAM_EUSAGE.
 * Errors: LAM_EINVAL (unknown writer: the message lists the directories
 * searched), what lam_plugin_load returns for NAME.so, LAM_ENOMEM. Sink calls return LAM_EUSAGE (misuse), LAM_EIO (the
 * output could not be written) or LAM_EINVAL (the writer refused, with its
 * message). */
int lam_plugin_writer_sink(const char *name, lam_writer *w, lam_sink *out, lam_error *err);

struct lam_dialect;

/* Layers formatted by worker threads through a plugin writer that allows
 * it (lamina_writer.layer_written): the plugin sink's fork member (plan.h)
 * makes a worker's sink after its begin, or fails (LAM_EUSAGE, making
 * nothing) when its writer does not allow it or refuses a second state;
 * the fork's put writes a layer's bytes through the main sink in layer
 * order and tells the writer. */

/* The sink a machine profile writes its programs through: the dialect's
 * templates (lam_dialect_sink) when writer is NULL or "text", else the
 * plugin writer of that name (above). Ownership and errors as theirs. */
int lam_program_sink(const char *writer, const struct lam_dialect *d, lam_writer *w, lam_sink *out, lam_error *err);

/* 1 when a profile's `writer` means its dialect's templates (NULL or
 * "text": lam_program_sink writes text), 0 for a plugin writer. */
int lam_program_text(const char *writer);

/* Unload every plugin (dlclose) and empty the registry. Any sink or writer
 * name obtained before becomes invalid. For tests and leak checks. */
void lam_plugins_unload(void);

/* The names of the registered writers, sorted: stores up to max of them
 * into names (valid until lam_plugins_unload) and returns how many there
 * are in all (which may exceed max). names may be NULL when max is 0. */
size_t lam_plugin_writers(const char **names, size_t max);

#endif
