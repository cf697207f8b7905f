/* A build plate's CLI labels (issue 25): a job with a label table gets one
 * $$LABEL per label in the header, through the shipped cli-ascii profile's
 * text dialect and through the cli-binary plugin, and every block carries
 * its operation's label id. Also the preamble's per-label lines on their
 * own, and the plugin's size rule: a job description from a host older
 * than the table (a smaller size) gives the one label.
 *
 * Paths: $TESTS (default "tests") is the tests directory, its ../machines
 * the shipped profiles; the cli plugin is $BUILD/plugins/cli-binary.so when
 * that exists (SAN=1 builds), else $TESTS/../plugins/cli-binary.so. The
 * readers of the outputs are the test's own. */
#include <dlfcn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "dialect.h"
#include "lamina_plugin.h"
#include "plugin.h"
#include "profile.h"
#include "profile_keys.h"
#include "tap.h"
#include "writer.h"

static const char *const three[3] = { "bracket", "gear_2", "housing.v3" };

/* The job: one layer, labels `labels` (NULL: none, the job's label). */
static lam_job_info job(const char *const *labels, size_t n)
{
    lam_job_info j;
    memset(&j, 0, sizeof j);
    j.name = "plate";
    j.process = "sls";
    j.units = "mm";
    j.layers = 1;
    double box[6] = { 0, 0, 0, 10, 10, 0.1 };
    memcpy(j.bbox, box, sizeof box);
    j.bead = 0.1;
    j.label = "the_plate";
    j.labels = labels;
    j.nlabels = n;
    return j;
}

/* Drive s: begin, one layer with a contour of label 2, a hatch block of
 * label 3 and a contour of a plain part (no label: its part, 1), end. */
static int drive(const lam_sink *s, const lam_job_info *j)
{
    static const double sq_xyz[12] = { 0, 0, 0.05, 4, 0, 0.05, 4, 4, 0.05, 0, 4, 0.05 };
    static const double sq_uv[8] = { 0, 0, 4, 0, 4, 4, 0, 4 };
    static const double h_xyz[12] = { 1, 1, 0.05, 3, 1, 0.05, 1, 2, 0.05, 3, 2, 0.05 };
    static const double h_uv[8] = { 1, 1, 3, 1, 1, 2, 3, 2 };
    int rc = s->begin(s->ctx, j);
    lam_layer_info L = { .index = 0, .z = 0.1, .width = 0.1, .floor = 0, .ceiling = 0.1 };
    if (!rc) rc = s->layer(s->ctx, &L);
    lam_contour_info c = { .attrs = lam_attrs_default(), .solid = 1, .z = 0.05, .xyz = sq_xyz, .uv = sq_uv, .n = 4 };
    c.attrs.label = 2;
    if (!rc) rc = s->contour(s->ctx, &c);
    lam_hatch_info h = { .attrs = lam_attrs_default(), .kind = LAM_KIND_CORE, .z = 0.05, .xyz = h_xyz, .uv = h_uv,
                         .n = 2 };
    h.attrs.label = 3;
    if (!rc) rc = s->hatches(s->ctx, &h);
    c.attrs = lam_attrs_default(); /* part 1, label 0: id 1 */
    if (!rc) rc = s->contour(s->ctx, &c);
    if (!rc) rc = s->layer_end(s->ctx, &L);
    if (!rc) rc = s->end(s->ctx);
    return rc;
}

/* Run the job through profile `name`'s program sink; the bytes in *out
 * (caller frees), or NULL after a diagnostic. */
static char *run(const char *name, const lam_job_info *j, size_t *len)
{
    lam_profile *p = NULL;
    lam_error err;
    lam_error_clear(&err);
    lam_writer *w = NULL;
    lam_sink s;
    char *out = NULL;
    int rc = lam_profile_find(name, &p, &err);
    if (!rc) rc = lam_writer_memory(&w, &err);
    if (!rc) rc = lam_program_sink(p->writer, &p->dialect, w, &s, &err);
    if (!rc) {
        rc = drive(&s, j);
        s.destroy(s.ctx);
    }
    if (!rc) rc = lam_writer_take(w, &out, len, &err);
    else if (w) lam_writer_abort(w);
    if (rc) diag("%s: %s", name, err.msg);
    lam_profile_free(p);
    return rc ? NULL : out;
}

/* The header's $$LABEL lines of text[0..len) (up to "$$HEADEREND") joined
 * by ";" into buf, and its other lines' count into *others. */
static void header_labels(const char *text, size_t len, char *buf, size_t size, int *others)
{
    buf[0] = '\0';
    *others = 0;
    size_t k = 0;
    for (size_t at = 0; at < len;) {
        const char *nl = memchr(text + at, '\n', len - at);
        size_t n = nl ? (size_t)(nl - (text + at)) : len - at;
        if (n >= 11 && !memcmp(text + at, "$$HEADEREND", 11)) break;
        if (n > 8 && !memcmp(text + at, "$$LABEL/", 8)) {
            k += (size_t)snprintf(buf + k, size - k, "%s%.*s", k ? ";" : "", (int)(n - 8), text + at + 8);
            if (k >= size) k = size - 1;
        } else {
            (*others)++;
        }
        at += n + 1;
    }
}

static void test_ascii(void)
{
    lam_job_info j = job(three, 3);
    size_t len;
    char *out = run("cli-ascii", &j, &len);
    ok(out != NULL, "cli-ascii: the job with three labels runs");
    if (!out) return;
    char labels[256];
    int others;
    header_labels(out, len, labels, sizeof labels, &others);
    is_str(labels, "1,bracket;2,gear_2;3,housing.v3", "cli-ascii: one $$LABEL per label, ids 1..3, in order");
    /* $$HEADERSTART $$ASCII $$UNITS $$VERSION $$DIMENSION $$LAYERS */
    is_int(others, 6, "cli-ascii: the header's other lines once each");
    /* the blocks, in the order given: label 2's contour, label 3's hatches, part 1's contour */
    const char *p2 = strstr(out, "\n$$POLYLINE/2,1,5,");
    const char *h3 = strstr(out, "\n$$HATCHES/3,2,");
    const char *p1 = strstr(out, "\n$$POLYLINE/1,1,5,");
    ok(p2 && h3 && p1 && p2 < h3 && h3 < p1, "cli-ascii: blocks carry their label ids 2, 3, 1");
    free(out);

    j = job(NULL, 0);
    out = run("cli-ascii", &j, &len);
    ok(out != NULL, "cli-ascii: a job without a label table runs");
    if (!out) return;
    header_labels(out, len, labels, sizeof labels, &others);
    is_str(labels, "1,the_plate", "cli-ascii: no table: the one label, id 1, the job's label");
    free(out);
}

/* ---- binary CLI, read back here ---- */

static uint32_t rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The ids of the polyline (130) and hatch (132) commands after the header
 * of data[0..len), joined by "," into buf ("?" and stop on anything else). */
static void binary_ids(const unsigned char *data, size_t len, char *buf, size_t size)
{
    buf[0] = '\0';
    const unsigned char *end = data + len, *p = NULL;
    for (size_t i = 0; i + 11 <= len && !p; i++)
        if (!memcmp(data + i, "$$HEADEREND", 11)) p = data + i + 11;
    size_t k = 0;
    while (p && end - p >= 2 && k + 16 < size) {
        unsigned cmd = (unsigned)p[0] | (unsigned)p[1] << 8;
        p += 2;
        if (cmd == 127 && end - p >= 4) {
            p += 4;
        } else if (cmd == 130 && end - p >= 12 && (size_t)(end - p - 12) / 8 >= rd_u32(p + 8)) {
            k += (size_t)snprintf(buf + k, size - k, "%sP%u", k ? "," : "", (unsigned)rd_u32(p));
            p += 12 + 8 * (size_t)rd_u32(p + 8);
        } else if (cmd == 132 && end - p >= 8 && (size_t)(end - p - 8) / 16 >= rd_u32(p + 4)) {
            k += (size_t)snprintf(buf + k, size - k, "%sH%u", k ? "," : "", (unsigned)rd_u32(p));
            p += 8 + 16 * (size_t)rd_u32(p + 4);
        } else {
            snprintf(buf + k, size - k, "%s?", k ? "," : "");
            return;
        }
    }
}

static void test_binary(void)
{
    lam_job_info j = job(three, 3);
    size_t len;
    char *out = run("cli-binary", &j, &len);
    ok(out != NULL, "cli-binary: the job with three labels runs");
    if (!out) return;
    char labels[256], ids[256];
    int others;
    header_labels(out, len, labels, sizeof labels, &others);
    is_str(labels, "1,bracket;2,gear_2;3,housing.v3", "cli-binary: one $$LABEL per label, ids 1..3, in order");
    is_int(others, 6, "cli-binary: the header's other lines once each");
    binary_ids((const unsigned char *)out, len, ids, sizeof ids);
    is_str(ids, "P2,H3,P1", "cli-binary: polyline 2, hatches 3, polyline 1: the label ids");
    free(out);

    j = job(NULL, 0);
    out = run("cli-binary", &j, &len);
    ok(out != NULL, "cli-binary: a job without a label table runs");
    if (!out) return;
    header_labels(out, len, labels, sizeof labels, &others);
    is_str(labels, "1,the_plate", "cli-binary: no table: the one label, id 1, the job's label");
    free(out);
}

/* ---- the preamble's per-label lines ---- */

static char *preamble(const char *tpl, const char *const *labels, size_t n)
{
    lam_dialect d;
    memset(&d, 0, sizeof d);
    lam_error err;
    lam_error_clear(&err);
    size_t off;
    lam_writer *w = NULL;
    lam_sink s;
    char *out = NULL;
    size_t len;
    int rc = lam_template_parse(LAM_CMD_PREAMBLE, tpl, &d.cmd[LAM_CMD_PREAMBLE], &off, &err);
    if (!rc) rc = lam_writer_memory(&w, &err);
    if (!rc) rc = lam_dialect_sink(&d, w, &s, &err);
    if (!rc) {
        lam_job_info j = job(labels, n);
        rc = s.begin(s.ctx, &j);
        if (!rc) rc = s.end(s.ctx);
        s.destroy(s.ctx);
    }
    if (!rc) rc = lam_writer_take(w, &out, &len, &err);
    else if (w) lam_writer_abort(w);
    if (rc) diag("'%s': %s", tpl, err.msg);
    lam_dialect_free(&d);
    return out;
}

static void check_preamble(const char *tpl, const char *const *labels, size_t n, const char *want, const char *what)
{
    char *got = preamble(tpl, labels, n);
    is_str(got ? got : "(failed)", want, "%s", what);
    free(got);
}

static void test_lines(void)
{
    const char *const two[2] = { "a", NULL };
    check_preamble("H {label}\nL{id}={label}\nE {label}", three, 3,
                   "H the_plate\nL1=bracket\nL2=gear_2\nL3=housing.v3\nE the_plate\n",
                   "a line with {id} once per label; {label} elsewhere is the job's");
    check_preamble("H\nL{id:%03d} {label:%-8s}|", three, 2, "H\nL001 bracket |\nL002 gear_2  |\n",
                   "the last line repeated one a line, formats kept");
    check_preamble("{{{id}}}{label}\n{{x}}", two, 2, "{1}a\n{2}part\n{x}\n",
                   "literal braces around {id}; a NULL label is \"part\"");
    check_preamble("$$LABEL/1,{label}", three, 3, "$$LABEL/1,the_plate\n",
                   "a profile's old fixed line names the job's label only");
    check_preamble("L{id},{label}", NULL, 0, "L1,the_plate\n", "no table: one line, id 1, the job's label");
    lam_template t;
    lam_error err;
    size_t off = 0;
    int rc = lam_template_parse(LAM_CMD_LAYER, "$$LAYER/{id}", &t, &off, &err);
    ok(rc == LAM_EINVAL && off == 9 && strstr(err.msg, "unknown field 'id' for the layer command"),
       "{id} is a preamble and postamble field, not a layer's (%s at %zu)", err.msg, off);
    lam_template_free(&t);
    rc = lam_template_parse(LAM_CMD_POSTAMBLE, "E{id}", &t, &off, &err);
    ok(rc == LAM_OK, "the postamble takes {id}");
    lam_template_free(&t);
}

/* ---- the size rule: a host older than the table ---- */

static const struct lamina_writer *old_writer;
static char old_dest; /* the writer's lamina_out: old_write needs none */
static char old_out[1024];
static size_t old_len;

static int old_register(const struct lamina_host *h, const struct lamina_writer *w)
{
    (void)h;
    old_writer = w;
    return 0;
}

static int old_write(struct lamina_out *out, const void *data, size_t len)
{
    (void)out;
    if (old_len + len >= sizeof old_out) return 1;
    memcpy(old_out + old_len, data, len);
    old_len += len;
    return 0;
}

static void old_error(const struct lamina_host *h, const char *fmt, ...)
{
    (void)h;
    diag("plugin error: %s", fmt);
}

/* Load the plugin with a host of our own (after the runs above: its init
 * takes this host from now on) and begin a job whose size ends before
 * the table: the header names the one label, whatever the members past
 * the size hold. */
static void test_old_host(const char *path)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    ok(h != NULL, "dlopen %s", path);
    if (!h) return;
    int (*init)(const struct lamina_host *) = (int (*)(const struct lamina_host *))dlsym(h, "lamina_plugin_init");
    struct lamina_host host = { .size = sizeof host, .abi = LAMINA_PLUGIN_ABI, .version = "test",
                                .register_writer = old_register, .write = old_write, .set_error = old_error };
    ok(init && init(&host) == 0 && old_writer, "the plugin registers with the test's host");
    if (!old_writer) return;
    struct lamina_job j;
    memset(&j, 0, sizeof j);
    j.size = offsetof(struct lamina_job, labels); /* the ABI 1 struct before the table */
    j.machine = "plate";
    j.process = "sls";
    j.units = "mm";
    j.layers = 0;
    j.label = "old_part";
    j.labels = three; /* past the size: must not be read */
    j.nlabels = 3;
    void *state = old_writer->begin((struct lamina_out *)(void *)&old_dest, &j);
    ok(state != NULL, "begin with the old size");
    if (state) old_writer->end(state);
    char labels[256];
    int others;
    header_labels(old_out, old_len, labels, sizeof labels, &others);
    is_str(labels, "1,old_part", "an old host's job: the one label, from `label`");
    old_len = 0;
    j.size = sizeof j;
    state = old_writer->begin((struct lamina_out *)(void *)&old_dest, &j);
    if (state) old_writer->end(state);
    header_labels(old_out, old_len, labels, sizeof labels, &others);
    is_str(labels, "1,bracket;2,gear_2;3,housing.v3", "the same job at today's size: the table");
}

int main(void)
{
    const char *tests = getenv("TESTS"), *build = getenv("BUILD");
    if (!tests || !*tests) tests = "tests";
    if (!build || !*build) build = "build";
    char machines[1100], plugins[1100], so[1200];
    snprintf(machines, sizeof machines, "%s/../machines", tests);
    setenv("LAMINA_MACHINES", machines, 1);
    struct stat st;
    snprintf(plugins, sizeof plugins, "%s/plugins", build);
    snprintf(so, sizeof so, "%s/cli-binary.so", plugins);
    if (stat(so, &st) != 0) {
        snprintf(plugins, sizeof plugins, "%s/../plugins", tests);
        snprintf(so, sizeof so, "%s/cli-binary.so", plugins);
    }
    setenv("LAMINA_PLUGINS", plugins, 1);
    diag("machines %s, cli plugin %s", machines, so);

    test_lines();
    test_ascii();
    test_binary();
    lam_plugins_unload();
    test_old_host(so);
    return done_testing();
}
