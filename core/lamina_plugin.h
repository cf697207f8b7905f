/* lamina plugin ABI. A plugin is a shared object exporting
 *
 *     int lamina_plugin_init(const struct lamina_host *host);
 *
 * which registers what it provides through the host's function pointers and
 * returns 0 (non-zero refuses to load, with host->set_error's message).
 *
 * Compatibility rules (as SQLite's sqlite3ext.h): every struct starts with
 * its own size and only ever grows at its end; LAMINA_PLUGIN_ABI changes
 * only when an existing member changes meaning. The host refuses a plugin
 * built for another ABI (it checks lamina_plugin_abi, which
 * LAMINA_PLUGIN_DECLARE defines), and reads a plugin's struct members only
 * up to the size the plugin declared. This header is all a plugin needs. */
#ifndef LAMINA_PLUGIN_H
#define LAMINA_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#define LAMINA_PLUGIN_ABI 1

/* Every plugin says which ABI it was built for; put this line once in it. */
#define LAMINA_PLUGIN_DECLARE \
    const uint32_t lamina_plugin_abi = LAMINA_PLUGIN_ABI

struct lamina_job {
    size_t size;               /* sizeof(struct lamina_job) of the host */
    const char *machine;       /* profile name */
    const char *process;       /* "ladrp" or "sls" */
    const char *units;
    size_t layers;
    double bbox[6];            /* min xyz, max xyz (output frame) */
    double bead;               /* bead or spot width */
    const char *label;         /* the part's name (CLI $$LABEL text) */
    /* The job's labels, one per id the polyline and hatches calls give:
     * labels[k] (never NULL) is the text of id k + 1, nlabels >= 1 (a job
     * of one part: its label, id 1). A host older than these members
     * passes a smaller size: read them only when size holds them, else
     * the one label `label`. */
    const char *const *labels;
    size_t nlabels;
    /* New members go here, at the end, only. */
};

/* Output bytes go through the host: the host owns the file (atomic: it
 * appears only if the whole job succeeds). */
struct lamina_out;

/* A writer for contour-based programs (one polyline per contour). */
struct lamina_writer {
    size_t size;               /* sizeof(struct lamina_writer) of the plugin */
    const char *name;          /* what a profile names in `writer:` */
    const char *description;
    /* Start a job; return a state pointer, or NULL after host->set_error. */
    void *(*begin)(struct lamina_out *out, const struct lamina_job *job);
    int (*layer)(void *state, size_t index, double z);
    /* One closed contour: n points (x, y pairs in the layer plane), solid 1
     * for counter-clockwise solids, 0 for clockwise holes; id counts from 1. */
    int (*polyline)(void *state, size_t id, int solid, const double *xy, size_t n);
    /* Finish (write trailers) and free state; non-zero on failure. */
    int (*end)(void *state);
    /* Free state after a failure elsewhere; nothing more is written. */
    void (*abort)(void *state);
    /* One block of n hatch vectors, 4 doubles each (x0 y0 x1 y1, layer
     * plane) of part `id` (optional: a writer without it refuses jobs
     * with hatches). */
    int (*hatches)(void *state, size_t id, const double *xy, size_t n);
    /* Optional: layers formatted apart, on several threads. Set it only
     * when the bytes of a layer (its layer, polyline and hatches calls)
     * depend on nothing but the job and those calls, and states from
     * different begin calls share nothing writable (the host calls them
     * from different threads at the same time; host->set_error is per
     * thread). The host then formats a layer through a state of its own,
     * begun with the same job (what that begin writes is dropped; the
     * state is freed with abort, never ended), writes the bytes itself and
     * calls this on the state that writes the file, in layer order, as if
     * that state had written layer `index`: count it, check it. Non-zero
     * fails the job (after host->set_error). */
    int (*layer_written)(void *state, size_t index);
};

struct lamina_host {
    size_t size;               /* sizeof(struct lamina_host) of the host */
    uint32_t abi;              /* LAMINA_PLUGIN_ABI of the host */
    const char *version;       /* lamina's version text */
    /* Register a writer; the struct must stay valid while the plugin is loaded. */
    int (*register_writer)(const struct lamina_host *host, const struct lamina_writer *w);
    /* Append bytes to the output; non-zero when writing failed. */
    int (*write)(struct lamina_out *out, const void *data, size_t len);
    /* Record why the plugin failed (printf-style). */
    void (*set_error)(const struct lamina_host *host, const char *fmt, ...);
    /* New members go here, at the end, only. */
};

#endif
