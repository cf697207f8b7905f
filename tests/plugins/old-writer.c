/* Test plugin: a writer built against an older, smaller struct
 * lamina_writer, one that ended before `abort`. The struct here does hold an
 * abort pointer, but its declared size excludes it, so the host must never
 * call it: if it did, "ABORT" would appear in the output.
 *
 * The writer writes text: "begin <machine> <layers>\n", "layer <i> <z>\n",
 * "poly <id> <solid> <n> x,y ...\n", "end\n". begin fails (with a message)
 * when the job's machine is "fail-begin"; polyline fails when solid is 0
 * and the job's machine is "fail-hole". */
#include <stdio.h>
#include <string.h>

#include "lamina_plugin.h"

LAMINA_PLUGIN_DECLARE;

static const struct lamina_host *host;

typedef struct state {
    struct lamina_out *out;
    int fail_hole;
} state;

static int say(state *s, const char *text)
{
    return host->write(s->out, text, strlen(text));
}

static void *begin(struct lamina_out *out, const struct lamina_job *job)
{
    if (job->machine && strcmp(job->machine, "fail-begin") == 0) {
        host->set_error(host, "old-writer: refusing machine '%s'", job->machine);
        return NULL;
    }
    /* static, not malloc'd: without abort, a malloc'd state would leak */
    static state one;
    state *s = &one;
    s->out = out;
    s->fail_hole = job->machine && strcmp(job->machine, "fail-hole") == 0;
    char line[128];
    snprintf(line, sizeof line, "begin %s %zu\n", job->machine ? job->machine : "-", job->layers);
    say(s, line);
    return s;
}

static int layer(void *st, size_t index, double z)
{
    char line[128];
    snprintf(line, sizeof line, "layer %zu %g\n", index, z);
    return say(st, line);
}

static int polyline(void *st, size_t id, int solid, const double *xy, size_t n)
{
    state *s = st;
    if (!solid && s->fail_hole) {
        host->set_error(host, "old-writer: contour %zu is a hole", id);
        return 1;
    }
    char line[128];
    snprintf(line, sizeof line, "poly %zu %d %zu", id, solid, n);
    int rc = say(s, line);
    for (size_t i = 0; i < n; i++) {
        snprintf(line, sizeof line, " %g,%g", xy[2 * i], xy[2 * i + 1]);
        rc |= say(s, line);
    }
    return rc | say(s, "\n");
}

static int end(void *st)
{
    return say(st, "end\n");
}

static void abort_(void *st)
{
    say(st, "ABORT\n");
}

static const struct lamina_writer w = {
    .size = offsetof(struct lamina_writer, abort),   /* the "old" size */
    .name = "old-writer",
    .description = "text writer of an older ABI revision (tests only)",
    .begin = begin,
    .layer = layer,
    .polyline = polyline,
    .end = end,
    .abort = abort_,
};

int lamina_plugin_init(const struct lamina_host *h);

int lamina_plugin_init(const struct lamina_host *h)
{
    host = h;
    return h->register_writer(h, &w);
}
