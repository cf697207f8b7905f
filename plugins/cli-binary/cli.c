/* cli-binary: Common Layer Interface (CLI 2.0) writer, binary form.
 *
 * The file is an ASCII header
 *
 *     $$HEADERSTART
 *     $$BINARY
 *     $$UNITS/00000001.000000      millimetres per coordinate unit
 *     $$VERSION/200
 *     $$DIMENSION/x1,y1,z1,x2,y2,z2   the job's bounding box (%.5f)
 *     $$LAYERS/<n>
 *     $$LABEL/<id>,<label>         one per label of the job, ids 1, 2, ...
 *     $$HEADEREND
 *
 * (lines end with "\n"; binary data follows "$$HEADEREND" immediately),
 * then little-endian commands, each a uint16 command id and its parameters:
 *
 *     127  start layer long   float32 z
 *     130  polyline long      int32 id, int32 dir, int32 n, n x (float32 x, float32 y)
 *     132  hatches long       int32 id, int32 n, n x (float32 x0, y0, x1, y1)
 *
 * id is the block's label id, as $$LABEL says (1: the job's one model; a
 * build plate's ids 1..n name its labels); dir is 1 for counter-clockwise
 * (solid) and 0 for clockwise (hole) contours; every polyline is closed by
 * repeating its first point, which n counts (as the ASCII profile's
 * $$POLYLINE/id,dir,n,... with close_polylines). Nothing follows the last
 * polyline: CLI binary has no end-of-file command. Bytes are written one by
 * one, so the output does not depend on the host's byte order; float32 is
 * IEEE 754 binary32 (C's float on every platform lamina supports). */
#include <float.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lamina_plugin.h"

LAMINA_PLUGIN_DECLARE;

_Static_assert(sizeof(float) == 4 && FLT_MANT_DIG == 24 && FLT_MAX_EXP == 128,
               "CLI binary needs IEEE 754 binary32 floats");

#define CMD_LAYER_LONG 127
#define CMD_POLYLINE_LONG 130
#define CMD_HATCHES_LONG 132

static const struct lamina_host *host;

typedef struct cli {
    struct lamina_out *out;
    size_t layers;           /* promised in the header */
    size_t layers_written;
    unsigned char *buf;      /* one command, assembled before writing */
    size_t len, cap;
    int failed;
} cli;

/* ---- little-endian encoding ---- */

static int reserve(cli *c, size_t more)
{
    if (c->len + more <= c->cap) return 0;
    size_t cap = c->cap ? c->cap : 256;
    while (cap < c->len + more) {
        if (cap > SIZE_MAX / 2) return -1;
        cap *= 2;
    }
    unsigned char *nb = realloc(c->buf, cap);
    if (!nb) return -1;
    c->buf = nb;
    c->cap = cap;
    return 0;
}

/* (callers reserve first) */
static void put_u16(cli *c, uint16_t v)
{
    c->buf[c->len++] = (unsigned char)(v & 0xff);
    c->buf[c->len++] = (unsigned char)(v >> 8);
}

static void put_u32(cli *c, uint32_t v)
{
    for (int i = 0; i < 4; i++) c->buf[c->len++] = (unsigned char)((v >> (8 * i)) & 0xff);
}

static void put_i32(cli *c, int32_t v)
{
    put_u32(c, (uint32_t)v);   /* two's complement bits, well defined */
}

static void put_f32(cli *c, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    put_u32(c, bits);
}

/* v converted to float32, refusing what float32 cannot hold (out-of-range
 * conversion is undefined behaviour in C, and NaN is never a coordinate). */
static int to_f32(double v, float *out)
{
    if (!(v >= -FLT_MAX && v <= FLT_MAX)) return -1;
    *out = (float)v;
    return 0;
}

static int flush(cli *c)
{
    int rc = host->write(c->out, c->buf, c->len);
    c->len = 0;
    if (rc != 0) {
        host->set_error(host, "cli-binary: cannot write output");
        c->failed = 1;
        return 1;
    }
    return 0;
}

/* ---- the writer ---- */

/* Millimetres per model unit, 0 when the unit is not one CLI can state. */
static double unit_mm(const char *units)
{
    static const struct { const char *name; double mm; } table[] = {
        {"mm", 1}, {"cm", 10}, {"m", 1000}, {"um", 0.001}, {"in", 25.4}, {"inch", 25.4},
    };
    if (!units || !*units) return 1;   /* lamina's default unit */
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcmp(units, table[i].name) == 0) return table[i].mm;
    return 0;
}

static void cli_free(cli *c)
{
    if (!c) return;
    free(c->buf);
    free(c);
}

/* Append printf-style text to c's buffer (at most 1023 bytes); non-zero
 * when it cannot. */
static int append(cli *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int append(cli *c, const char *fmt, ...)
{
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= sizeof text || reserve(c, (size_t)n) != 0) return -1;
    memcpy(c->buf + c->len, text, (size_t)n);
    c->len += (size_t)n;
    return 0;
}

/* Label k + 1 of the job: its table's when the host passes one (a host
 * older than the table passes a size without it), else the one label;
 * "part" for a missing or empty one. */
static const char *job_label(const struct lamina_job *job, size_t k)
{
    const char *label = NULL;
    if (job->size >= offsetof(struct lamina_job, nlabels) + sizeof job->nlabels && job->labels && job->nlabels)
        label = k < job->nlabels ? job->labels[k] : NULL;
    else if (job->size >= offsetof(struct lamina_job, label) + sizeof job->label && k == 0)
        label = job->label;
    return label && *label ? label : "part";
}

static size_t job_nlabels(const struct lamina_job *job)
{
    if (job->size >= offsetof(struct lamina_job, nlabels) + sizeof job->nlabels && job->labels && job->nlabels)
        return job->nlabels;
    return 1;
}

/* The ASCII header into c's buffer: one $$LABEL per label, each text cut
 * at 200 bytes (as the header always had it). Non-zero when it cannot. */
static int header(cli *c, const struct lamina_job *job, double mm)
{
    const double *b = job->bbox;
    int rc = append(c,
                    "$$HEADERSTART\n$$BINARY\n$$UNITS/%015.6f\n$$VERSION/200\n"
                    "$$DIMENSION/%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n$$LAYERS/%zu\n",
                    mm, b[0], b[1], b[2], b[3], b[4], b[5], job->layers);
    size_t n = job_nlabels(job);
    for (size_t k = 0; k < n && !rc; k++) rc = append(c, "$$LABEL/%zu,%.200s\n", k + 1, job_label(job, k));
    return rc ? rc : append(c, "$$HEADEREND");
}

static void *cli_begin(struct lamina_out *out, const struct lamina_job *job)
{
    if (!job || job->size < offsetof(struct lamina_job, layers) + sizeof job->layers) {
        host->set_error(host, "cli-binary: the host passed no job description");
        return NULL;
    }
    const char *units = job->units;
    double mm = unit_mm(units);
    if (mm == 0) {
        host->set_error(host, "cli-binary: CLI cannot express units '%s' (use mm, cm, m, um, in or inch)",
                        units);
        return NULL;
    }
    cli *c = calloc(1, sizeof *c);
    if (!c) {
        host->set_error(host, "cli-binary: out of memory");
        return NULL;
    }
    c->out = out;
    c->layers = job->layers;
    if (header(c, job, mm) != 0) {
        host->set_error(host, "cli-binary: cannot format the header");
        cli_free(c);
        return NULL;
    }
    if (flush(c) != 0) {
        cli_free(c);
        return NULL;
    }
    return c;
}

/* Count a layer written, refusing one more than the header announced. */
static int count_layer(cli *c, size_t index)
{
    if (c->layers_written >= c->layers) {
        host->set_error(host, "cli-binary: layer %zu is one more than the %zu the header announced", index,
                        c->layers);
        return 1;
    }
    c->layers_written++;
    return 0;
}

static int cli_layer(void *state, size_t index, double z)
{
    cli *c = state;
    if (c->failed) return 1;
    if (c->layers_written >= c->layers) return count_layer(c, index);
    float zf;
    if (to_f32(z, &zf) != 0) {
        host->set_error(host, "cli-binary: layer %zu: height %g does not fit a float32", index, z);
        return 1;
    }
    if (reserve(c, 2 + 4) != 0) {
        host->set_error(host, "cli-binary: out of memory");
        return 1;
    }
    put_u16(c, CMD_LAYER_LONG);
    put_f32(c, zf);
    count_layer(c, index);
    return flush(c);
}

static int cli_polyline(void *state, size_t id, int solid, const double *xy, size_t n)
{
    cli *c = state;
    if (c->failed) return 1;
    if (c->layers_written == 0) {
        host->set_error(host, "cli-binary: contour %zu before the first layer", id);
        return 1;
    }
    if (n == 0 || !xy) {
        host->set_error(host, "cli-binary: contour %zu has no points", id);
        return 1;
    }
    if (id > INT32_MAX || n >= (size_t)INT32_MAX || n > (SIZE_MAX - 14) / 8 - 1) {
        host->set_error(host, "cli-binary: contour %zu (%zu points) exceeds the format's int32 fields", id, n);
        return 1;
    }
    if (reserve(c, 2 + 12 + 8 * (n + 1)) != 0) {
        host->set_error(host, "cli-binary: out of memory");
        return 1;
    }
    put_u16(c, CMD_POLYLINE_LONG);
    put_i32(c, (int32_t)id);
    put_i32(c, solid ? 1 : 0);
    put_i32(c, (int32_t)(n + 1));
    for (size_t i = 0; i <= n; i++) {
        size_t k = i < n ? i : 0;   /* close: repeat the first point */
        float x, y;
        if (to_f32(xy[2 * k], &x) != 0 || to_f32(xy[2 * k + 1], &y) != 0) {
            c->len = 0;
            host->set_error(host, "cli-binary: contour %zu point %zu (%g, %g) does not fit float32", id, k + 1,
                            xy[2 * k], xy[2 * k + 1]);
            return 1;
        }
        put_f32(c, x);
        put_f32(c, y);
    }
    return flush(c);
}

static int cli_hatches(void *state, size_t id, const double *xy, size_t n)
{
    cli *c = state;
    if (c->failed) return 1;
    if (c->layers_written == 0) {
        host->set_error(host, "cli-binary: hatches before the first layer");
        return 1;
    }
    if (n == 0) return 0;
    if (!xy || id > INT32_MAX || n >= (size_t)INT32_MAX || n > (SIZE_MAX - 10) / 16) {
        host->set_error(host, "cli-binary: a block of %zu hatches exceeds the format's int32 fields", n);
        return 1;
    }
    if (reserve(c, 2 + 8 + 16 * n) != 0) {
        host->set_error(host, "cli-binary: out of memory");
        return 1;
    }
    put_u16(c, CMD_HATCHES_LONG);
    put_i32(c, (int32_t)id);
    put_i32(c, (int32_t)n);
    for (size_t i = 0; i < 4 * n; i++) {
        float f;
        if (to_f32(xy[i], &f) != 0) {
            c->len = 0;
            host->set_error(host, "cli-binary: hatch coordinate %g does not fit float32", xy[i]);
            return 1;
        }
        put_f32(c, f);
    }
    return flush(c);
}

static int cli_end(void *state)
{
    cli *c = state;
    int rc = c->failed;
    if (!rc && c->layers_written != c->layers) {
        host->set_error(host, "cli-binary: the header announced %zu layers, %zu were written", c->layers,
                        c->layers_written);
        rc = 1;
    }
    cli_free(c);
    return rc;
}

static void cli_abort(void *state)
{
    cli_free(state);
}

/* A layer's bytes hang only on the job and its own calls (the header is
 * begin's), and a state is all a call touches: layers may be formatted
 * apart. The state writing the file counts them. */
static int cli_layer_written(void *state, size_t index)
{
    cli *c = state;
    return c->failed ? 1 : count_layer(c, index);
}

static const struct lamina_writer cli_writer = {
    .size = sizeof(struct lamina_writer),
    .name = "cli-binary",
    .description = "Common Layer Interface 2.0, binary (long commands: layer 127, polyline 130)",
    .begin = cli_begin,
    .layer = cli_layer,
    .polyline = cli_polyline,
    .end = cli_end,
    .abort = cli_abort,
    .hatches = cli_hatches,
    .layer_written = cli_layer_written,
};

int lamina_plugin_init(const struct lamina_host *h);

int lamina_plugin_init(const struct lamina_host *h)
{
    /* everything this plugin calls must be within the host's struct */
    if (!h || h->size < offsetof(struct lamina_host, set_error) + sizeof h->set_error) return 1;
    host = h;
    return h->register_writer(h, &cli_writer);
}
